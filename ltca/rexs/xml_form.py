"""The XML form of a REXS model (``.rexs``): ``<model>`` with ``<relations>``, ``<components>`` (attributes with
text, ``<array>`` of ``<c>`` or ``<matrix>`` of ``<r>`` rows) and ``<load_spectrum>`` of ``<load_case>``
(spec.rexs.info, XML syntax). Coded arrays and anything else are kept as written.
"""
from __future__ import annotations

import copy
import xml.etree.ElementTree as ET
from typing import Any

from .errors import RexsError
from .model import Attribute, Component, LoadCase, Ref, Relation, RexsModel

__all__ = ["parse_xml", "to_xml", "as_int"]


def as_int(v: str | None, where: str, what: str, file: str) -> int:
    try:
        return int(str(v).strip())
    except (TypeError, ValueError):
        raise RexsError(where, what, "an integer id expected", v, file) from None


def _xml_value(el: ET.Element) -> Any:
    kids = list(el)
    if not kids:
        return (el.text or "").strip()
    if len(kids) == 1 and kids[0].tag == "array" and not kids[0].get("code"):
        return [(c.text or "").strip() for c in kids[0]]
    if len(kids) == 1 and kids[0].tag == "matrix" and not kids[0].get("code"):
        return [[(c.text or "").strip() for c in r] for r in kids[0]]
    return copy.deepcopy(kids[0])          # coded arrays, arrays of arrays: kept as written


def _xml_component(el: ET.Element, file: str) -> Component:
    cid = as_int(el.get("id"), f"component {el.get('name')!r}", "id", file)
    comp = Component(cid, el.get("type") or "", el.get("name"), {}, file)
    if not comp.type:
        raise RexsError(f"component {cid}", "type", "missing: every component has a type", None, file)
    for a in el.findall("attribute"):
        aid = a.get("id")
        if not aid:
            raise RexsError(comp.label, "-", "an attribute without an id", None, file)
        comp.attributes[aid] = Attribute(aid, a.get("unit"), _xml_value(a))
    return comp


def parse_xml(text: str, file: str = "<xml>") -> RexsModel:
    """A REXS model from its XML text."""
    try:
        root = ET.fromstring(text.encode("utf-8"))
    except ET.ParseError as exc:
        raise RexsError(file, "-", f"malformed XML ({exc})", None) from None
    if root.tag != "model":
        raise RexsError(file, "-", f"the root element is <{root.tag}>, <model> expected", None)
    if not root.get("version"):
        raise RexsError(file, "model", "missing the attribute 'version'", None)
    relations = []
    for r in root.findall("./relations/relation"):
        refs = tuple(Ref(as_int(x.get("id"), f"relation {r.get('id')}", "ref id", file), x.get("role") or "",
                         x.get("hint")) for x in r.findall("ref"))
        relations.append(Relation(as_int(r.get("id"), "relation", "id", file) if r.get("id") else None,
                                  r.get("type") or "", refs, int(r.get("order")) if r.get("order") else None))
    comps: dict[int, Component] = {}
    for c in root.findall("./components/component"):
        comp = _xml_component(c, file)
        if comp.id in comps:
            raise RexsError(comp.label, "id", f"the id {comp.id} is used by two components", comp.id, file)
        comps[comp.id] = comp
    load_cases, extra, spectrum_id = [], {}, None
    spec = root.find("load_spectrum")
    if spec is not None:
        spectrum_id = as_int(spec.get("id"), "load_spectrum", "id", file) if spec.get("id") else None
        for lc in spec.findall("load_case"):
            case = LoadCase(as_int(lc.get("id"), "load_case", "id", file))
            for c in lc.findall("component"):
                comp = _xml_component(c, file)
                case.components[comp.id] = comp
            load_cases.append(case)
        extra["xml_spectrum_other"] = [copy.deepcopy(e) for e in spec if e.tag != "load_case"]
    extra["xml_other"] = [copy.deepcopy(e) for e in root if e.tag not in ("relations", "components", "load_spectrum")]
    return RexsModel(root.get("version"), root.get("applicationId"), root.get("applicationVersion"),
                     root.get("date"), relations, comps, load_cases, spectrum_id, "xml", "xml", file, extra)


def _xml_put(parent: ET.Element, a: Attribute) -> None:
    el = ET.SubElement(parent, "attribute", {"id": a.id, "unit": a.unit if a.unit is not None else "none"})
    v = a.value
    if isinstance(v, ET.Element):
        el.append(copy.deepcopy(v))
    elif isinstance(v, list) and v and isinstance(v[0], list):
        m = ET.SubElement(el, "matrix")
        for row in v:
            r = ET.SubElement(m, "r")
            for x in row:
                ET.SubElement(r, "c").text = _text(x)
    elif isinstance(v, list):
        arr = ET.SubElement(el, "array")
        for x in v:
            ET.SubElement(arr, "c").text = _text(x)
    else:
        el.text = _text(v)


def _text(x: Any) -> str:
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, float):
        return repr(x)
    return str(x)


def _xml_comp(parent: ET.Element, c: Component) -> None:
    attrs = {"id": str(c.id)}
    if c.name is not None:
        attrs["name"] = c.name
    attrs["type"] = c.type
    el = ET.SubElement(parent, "component", attrs)
    for a in c.attributes.values():
        _xml_put(el, a)


def to_xml(model: RexsModel) -> str:
    """The model as REXS XML text."""
    head = {"applicationId": model.application_id, "applicationVersion": model.application_version,
            "date": model.date, "version": model.version}
    root = ET.Element("model", {k: v for k, v in head.items() if v is not None})
    rels = ET.SubElement(root, "relations")
    for r in model.relations:
        attrs = {"id": str(r.id)} if r.id is not None else {}
        if r.order is not None:
            attrs["order"] = str(r.order)
        attrs["type"] = r.type
        rel = ET.SubElement(rels, "relation", attrs)
        for x in r.refs:
            ET.SubElement(rel, "ref", {**({"hint": x.hint} if x.hint else {}), "id": str(x.id), "role": x.role})
    comps = ET.SubElement(root, "components")
    for c in model.components.values():
        _xml_comp(comps, c)
    if model.load_cases or model.extra.get("xml_spectrum_other"):
        spec = ET.SubElement(root, "load_spectrum", {"id": str(model.spectrum_id or 1)})
        for lc in model.load_cases:
            el = ET.SubElement(spec, "load_case", {"id": str(lc.id)})
            for c in lc.components.values():
                _xml_comp(el, c)
        for e in model.extra.get("xml_spectrum_other", []):
            spec.append(copy.deepcopy(e))
    for e in model.extra.get("xml_other", []):
        root.append(copy.deepcopy(e))
    ET.indent(root, "  ")
    return '<?xml version="1.0" encoding="UTF-8" standalone="no"?>\n' + ET.tostring(root, encoding="unicode") + "\n"
