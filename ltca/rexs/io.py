"""Reading and writing REXS files in their three forms: XML (``.rexs``), JSON (``.rexsj``, often with a UTF-8
byte-order mark) and zipped (``.rexsz``: a zip archive holding one ``.rexs`` or ``.rexsj`` model and perhaps
external files), REXS 1.x and 2.0, into the one in-memory :class:`ltca.rexs.model.RexsModel`.

The structure follows the REXS specification (spec.rexs.info: model, relations with refs, components with
attributes, load spectrum with load cases; the JSON form names each value by its value type). Values are kept as
read so a model written again keeps every attribute it had.
"""
from __future__ import annotations

import copy
import io
import json
import zipfile
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any

from .errors import RexsError
from .model import Attribute, Component, LoadCase, Ref, Relation, RexsModel

__all__ = ["read_model", "write_model", "parse_xml", "parse_json", "to_xml", "to_json"]

_ARRAY_TYPES = ("floating_point_array", "integer_array", "boolean_array", "string_array", "enum_array",
                "reference_component_array")
_MATRIX_TYPES = ("floating_point_matrix", "integer_matrix", "boolean_matrix", "string_matrix",
                 "array_of_integer_arrays")


def read_model(path: str | Path) -> RexsModel:
    """Read a ``.rexs`` (XML), ``.rexsj`` (JSON) or ``.rexsz`` (zip) file; the form is told by the content, not
    the name. A missing, unreadable or malformed file is a :class:`RexsError`."""
    p = Path(path)
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise RexsError(str(p), "-", f"cannot read the file ({exc.strerror or exc})", None) from None
    if data[:2] == b"PK":
        return _read_zip(data, str(p))
    return _parse_bytes(data, str(p))


def _parse_bytes(data: bytes, file: str) -> RexsModel:
    text = data.decode("utf-8-sig", errors="strict") if _utf8(data, file) else ""
    head = text.lstrip()[:1]
    if head == "<":
        return parse_xml(text, file)
    if head == "{":
        return parse_json(text, file)
    raise RexsError(file, "-", "not a REXS model: XML (<model ...>) or JSON ({\"model\": ...}) expected",
                    text[:40])


def _utf8(data: bytes, file: str) -> bool:
    try:
        data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise RexsError(file, "-", f"not UTF-8 text (byte {exc.start})", None) from None
    return True


def _read_zip(data: bytes, file: str) -> RexsModel:
    try:
        zf = zipfile.ZipFile(io.BytesIO(data))
    except zipfile.BadZipFile:
        raise RexsError(file, "-", "a broken zip archive (.rexsz)", None) from None
    names = [n for n in zf.namelist() if n.lower().endswith((".rexs", ".rexsj"))]
    if len(names) != 1:
        raise RexsError(file, "-", f"a .rexsz archive holds exactly one .rexs or .rexsj model; found {names}", None)
    model = _parse_bytes(zf.read(names[0]), f"{file}:{names[0]}")
    model.inner, model.form, model.file = model.form, "zip", file
    model.extra["zip_member"] = names[0]
    model.extra["zip_others"] = {n: zf.read(n) for n in zf.namelist() if n != names[0]}
    return model


# ----------------------------------------------------------------------------------------------- XML
def _int(v: str | None, where: str, what: str, file: str) -> int:
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
    cid = _int(el.get("id"), f"component {el.get('name')!r}", "id", file)
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
        refs = tuple(Ref(_int(x.get("id"), f"relation {r.get('id')}", "ref id", file), x.get("role") or "",
                         x.get("hint")) for x in r.findall("ref"))
        relations.append(Relation(_int(r.get("id"), "relation", "id", file) if r.get("id") else None,
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
        spectrum_id = _int(spec.get("id"), "load_spectrum", "id", file) if spec.get("id") else None
        for lc in spec.findall("load_case"):
            case = LoadCase(_int(lc.get("id"), "load_case", "id", file))
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


# ----------------------------------------------------------------------------------------------- JSON
_META = ("id", "unit")


def _json_component(c: dict, file: str) -> Component:
    if not isinstance(c, dict) or "id" not in c:
        raise RexsError(file, "components", "a component without an id", None)
    cid = _int(c.get("id"), f"component {c.get('name')!r}", "id", file)
    comp = Component(cid, c.get("type") or "", c.get("name"), {}, file)
    if not comp.type:
        raise RexsError(f"component {cid}", "type", "missing: every component has a type", None, file)
    for a in c.get("attributes", []) or []:
        aid = a.get("id") if isinstance(a, dict) else None
        if not aid:
            raise RexsError(comp.label, "-", "an attribute without an id", a, file)
        keys = [k for k in a if k not in _META]
        if len(keys) != 1:
            raise RexsError(comp.label, aid, f"one value keyed by its value type expected, found keys {keys}",
                            None, file)
        comp.attributes[aid] = Attribute(aid, a.get("unit"), a[keys[0]], keys[0])
    return comp


def parse_json(text: str, file: str = "<json>") -> RexsModel:
    """A REXS model from its JSON text (the byte-order mark already removed)."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise RexsError(file, "-", f"malformed JSON ({exc.msg}, line {exc.lineno})", None) from None
    m = data.get("model") if isinstance(data, dict) else None
    if not isinstance(m, dict):
        raise RexsError(file, "-", "the top-level object 'model' is missing", None)
    if not m.get("version"):
        raise RexsError(file, "model", "missing the attribute 'version'", None)
    relations = []
    for r in m.get("relations", []) or []:
        refs = tuple(Ref(_int(x.get("id"), f"relation {r.get('id')}", "ref id", file), x.get("role") or "",
                         x.get("hint")) for x in r.get("refs", []))
        relations.append(Relation(r.get("id"), r.get("type") or "", refs, r.get("order")))
    comps: dict[int, Component] = {}
    for c in m.get("components", []) or []:
        comp = _json_component(c, file)
        if comp.id in comps:
            raise RexsError(comp.label, "id", f"the id {comp.id} is used by two components", comp.id, file)
        comps[comp.id] = comp
    load_cases, spectrum_id, extra = [], None, {}
    spec = m.get("load_spectrum")
    if isinstance(spec, dict):
        spectrum_id = spec.get("id")
        for lc in spec.get("load_cases", []) or []:
            case = LoadCase(_int(lc.get("id"), "load_case", "id", file))
            for c in lc.get("components", []) or []:
                comp = _json_component(c, file)
                case.components[comp.id] = comp
            load_cases.append(case)
        extra["json_spectrum_other"] = {k: v for k, v in spec.items() if k not in ("id", "load_cases")}
    known = ("version", "applicationId", "applicationVersion", "date", "relations", "components", "load_spectrum")
    extra["json_other"] = {k: v for k, v in m.items() if k not in known}
    extra["json_had_spectrum"] = isinstance(spec, dict)
    return RexsModel(str(m.get("version")), m.get("applicationId"), m.get("applicationVersion"), m.get("date"),
                     relations, comps, load_cases, spectrum_id, "json", "json", file, extra)


def _json_type(a: Attribute) -> str:
    if a.value_type:
        return a.value_type
    v = a.value
    if isinstance(v, bool):
        return "boolean"
    if isinstance(v, int):
        return "integer"
    if isinstance(v, float):
        return "floating_point"
    if isinstance(v, list) and v and isinstance(v[0], list):
        return "floating_point_matrix"
    if isinstance(v, list):
        return "floating_point_array"
    return "string"


def _json_comp(c: Component) -> dict:
    out: dict[str, Any] = {"id": c.id, "type": c.type}
    if c.name is not None:
        out["name"] = c.name
    atts = []
    for a in c.attributes.values():
        d: dict[str, Any] = {"id": a.id}
        if a.unit is not None:
            d["unit"] = a.unit
        d[_json_type(a)] = a.value
        atts.append(d)
    out["attributes"] = atts
    return out


def to_json(model: RexsModel) -> str:
    """The model as REXS JSON text (without a byte-order mark)."""
    m: dict[str, Any] = {"version": model.version}
    for k, v in (("applicationId", model.application_id), ("applicationVersion", model.application_version),
                 ("date", model.date)):
        if v is not None:
            m[k] = v
    m["relations"] = [{**({"id": r.id} if r.id is not None else {}), "type": r.type,
                       **({"order": r.order} if r.order is not None else {}),
                       "refs": [{"id": x.id, "role": x.role, **({"hint": x.hint} if x.hint else {})} for x in r.refs]}
                      for r in model.relations]
    m["components"] = [_json_comp(c) for c in model.components.values()]
    if model.load_cases or model.extra.get("json_had_spectrum"):
        m["load_spectrum"] = {"id": model.spectrum_id if model.spectrum_id is not None else 1,
                              "load_cases": [{"id": lc.id,
                                              "components": [_json_comp(c) for c in lc.components.values()]}
                                             for lc in model.load_cases],
                              **model.extra.get("json_spectrum_other", {})}
    m.update(model.extra.get("json_other", {}))
    return json.dumps({"model": m}, indent=2, ensure_ascii=False) + "\n"


def write_model(model: RexsModel, path: str | Path, bom: bool = True) -> Path:
    """Write the model in the form it was read (XML, JSON with a byte-order mark when ``bom``, or zipped with the
    archive's other members kept). Returns the path written."""
    p = Path(path)
    inner = model.inner if model.form == "zip" else model.form
    body = (to_json(model).encode("utf-8") if inner == "json" else to_xml(model).encode("utf-8"))
    if inner == "json" and bom:
        body = b"\xef\xbb\xbf" + body
    if model.form == "zip":
        buf = io.BytesIO()
        with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as zf:
            zf.writestr(model.extra.get("zip_member", "model.rexs" if inner == "xml" else "model.rexsj"), body)
            for n, b in model.extra.get("zip_others", {}).items():
                zf.writestr(n, b)
        body = buf.getvalue()
    tmp = p.with_name(p.name + ".tmp")
    tmp.write_bytes(body)
    tmp.replace(p)
    return p
