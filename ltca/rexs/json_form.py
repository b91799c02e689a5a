"""The JSON form of a REXS model (``.rexsj``): ``{"model": {...}}`` with ``relations`` (``refs``), ``components``
(each attribute's value under its value-type key) and ``load_spectrum`` of ``load_cases`` (spec.rexs.info, JSON
syntax).
"""
from __future__ import annotations

import json
from typing import Any

from .errors import RexsError
from .model import Attribute, Component, LoadCase, Ref, Relation, RexsModel
from .xml_form import as_int

__all__ = ["parse_json", "to_json"]

_META = ("id", "unit")


def _json_component(c: dict, file: str) -> Component:
    if not isinstance(c, dict) or "id" not in c:
        raise RexsError(file, "components", "a component without an id", None)
    cid = as_int(c.get("id"), f"component {c.get('name')!r}", "id", file)
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
        refs = tuple(Ref(as_int(x.get("id"), f"relation {r.get('id')}", "ref id", file), x.get("role") or "",
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
            case = LoadCase(as_int(lc.get("id"), "load_case", "id", file))
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
