"""A checker of REXS models against the published REXS schema (attribute database) of version 2.0.0: every
component type is known, every attribute belongs to its component type, carries the schema's unit, and holds a value
of the schema's value type (a ``custom_`` attribute may be anything, with a unit the schema knows).

The schema file is ``data/rexs_schema_2.0.0.xml.gz`` (FVA, Apache License 2.0; see ``data/SOURCE.md``).
"""
from __future__ import annotations

import gzip
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path
from typing import Any, Iterable

from .model import Attribute, Component, RexsModel
from .units import normalise_unit

__all__ = ["Schema", "SchemaAttribute", "Issue", "load_schema", "check_model", "check_component", "SCHEMA_2_0"]

SCHEMA_2_0 = Path(__file__).with_name("data") / "rexs_schema_2.0.0.xml.gz"


@dataclass(frozen=True)
class SchemaAttribute:
    """One attribute of the schema: its id, value type, unit and (enums) allowed values."""
    id: str
    value_type: str
    unit: str
    enum_values: tuple[str, ...] = ()


@dataclass(frozen=True)
class Schema:
    """The schema: version, unit names, attributes by id, and the attribute ids of each component type."""
    version: str
    units: frozenset[str]
    attributes: dict[str, SchemaAttribute]
    components: dict[str, frozenset[str]]


@dataclass(frozen=True)
class Issue:
    """A schema violation: component id and type, attribute id ('-' for the component) and the problem."""
    component: int
    component_type: str
    attribute: str
    problem: str


@lru_cache(maxsize=4)
def load_schema(path: str | Path = SCHEMA_2_0) -> Schema:
    """Read a REXS schema file (XML, or gzip-compressed XML)."""
    p = Path(path)
    raw = p.read_bytes()
    if raw[:2] == b"\x1f\x8b":
        raw = gzip.decompress(raw)
    root = ET.fromstring(raw)
    units = {u.get("id"): u.get("name") for u in root.find("units")}
    vts = {v.get("id"): v.get("name") for v in root.find("valueTypes")}
    attrs = {}
    for a in root.find("attributes"):
        enums = tuple(e.get("value") for e in a.iter("enumValue"))
        attrs[a.get("attributeId")] = SchemaAttribute(a.get("attributeId"), vts[a.get("valueType")],
                                                      units[a.get("unit")], enums)
    comps: dict[str, set[str]] = {c.get("componentId"): set() for c in root.find("components")}
    for m in root.find("componentAttributeMappings"):
        comps.setdefault(m.get("componentId"), set()).add(m.get("attributeId"))
    return Schema(root.get("version"), frozenset(units.values()), attrs,
                  {k: frozenset(v) for k, v in comps.items()})


def _is_float(x: Any) -> bool:
    if isinstance(x, bool):
        return False
    try:
        float(x)
        return True
    except (TypeError, ValueError):
        return False


def _is_int(x: Any) -> bool:
    if isinstance(x, bool):
        return False
    if isinstance(x, int):
        return True
    if isinstance(x, float):
        return False
    try:
        int(str(x).strip())
        return True
    except ValueError:
        return False


def _is_bool(x: Any) -> bool:
    return isinstance(x, bool) or str(x).strip() in ("true", "false")


_SCALAR = {"floating_point": _is_float, "integer": _is_int, "boolean": _is_bool,
           "reference_component": _is_int,
           "string": lambda x: isinstance(x, str), "enum": lambda x: isinstance(x, str),
           "file_reference": lambda x: isinstance(x, str), "date_time": lambda x: isinstance(x, str)}


def _value_ok(vt: str, a: Attribute) -> str | None:
    """None when the value fits value type ``vt``, else what is wrong."""
    v = a.value
    if a.value_type is not None and a.value_type != vt and a.value_type != f"{vt}_coded":
        return f"value type {a.value_type!r}, the schema says {vt!r}"
    if hasattr(v, "tag"):                                         # a coded XML array or matrix
        return None if ("array" in vt or "matrix" in vt) else f"an array, the schema says {vt!r}"
    if isinstance(v, dict):                                        # a coded JSON array
        return None if ("array" in vt or "matrix" in vt) else f"a coded array, the schema says {vt!r}"
    base = vt.replace("_array", "").replace("_matrix", "")
    if vt == "array_of_integer_arrays":
        ok = isinstance(v, list) and all(isinstance(r, list) and all(_is_int(x) for x in r) for r in v)
        return None if ok else "not an array of integer arrays"
    if vt.endswith("_matrix"):
        ok = isinstance(v, list) and all(isinstance(r, list) and all(_SCALAR[base](x) for x in r) for r in v)
        return None if ok else f"not a matrix of {base}"
    if vt.endswith("_array"):
        ok = isinstance(v, list) and all(not isinstance(x, list) and _SCALAR[base](x) for x in v)
        return None if ok else f"not an array of {base}"
    if isinstance(v, list):
        return f"an array, the schema says {vt!r}"
    return None if _SCALAR[vt](v) else f"value {v!r} is not of type {vt!r}"


def check_component(c: Component, schema: Schema, attributes: Iterable[str] | None = None) -> list[Issue]:
    """Issues of one component (only the given ``attributes`` when named)."""
    out = []
    if c.type not in schema.components:
        return [Issue(c.id, c.type, "-", f"unknown component type {c.type!r}")]
    allowed = schema.components[c.type]
    for a in c.attributes.values():
        if attributes is not None and a.id not in attributes:
            continue
        unit = normalise_unit(a.unit)
        if a.id.startswith("custom_"):
            if unit not in schema.units:
                out.append(Issue(c.id, c.type, a.id, f"unit {a.unit!r} is not a unit of the schema"))
            continue
        if a.id not in allowed:
            out.append(Issue(c.id, c.type, a.id, f"not an attribute of {c.type} in REXS {schema.version}"))
            continue
        sa = schema.attributes[a.id]
        if (a.unit or "none") != sa.unit and not (a.unit is None and sa.unit == "none"):
            out.append(Issue(c.id, c.type, a.id, f"unit {a.unit!r}, the schema says {sa.unit!r}"))
        bad = _value_ok(sa.value_type, a)
        if bad:
            out.append(Issue(c.id, c.type, a.id, bad))
        elif sa.value_type == "enum" and sa.enum_values and str(a.value) not in sa.enum_values:
            out.append(Issue(c.id, c.type, a.id, f"enum value {a.value!r} is not one of {list(sa.enum_values)[:8]}"))
    return out


def check_model(model: RexsModel, schema: Schema | None = None,
                only: dict[int, Iterable[str] | None] | None = None) -> list[Issue]:
    """Issues of the whole model (its components and its load cases' components) against ``schema`` (default:
    REXS 2.0.0); with ``only`` ({component id: attribute ids or None for all}), just those."""
    schema = schema or load_schema()
    comps = list(model.components.values()) + [c for lc in model.load_cases for c in lc.components.values()]
    out = []
    for c in comps:
        if only is not None and c.id not in only:
            continue
        out += check_component(c, schema, None if only is None else only[c.id])
    return out
