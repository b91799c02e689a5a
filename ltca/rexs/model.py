"""The in-memory REXS model: components with attributes (value, unit, value type), relations with their roles, and
the load cases of a load spectrum; one form for the XML, JSON and zipped files (:mod:`ltca.rexs.io`).

A value is kept as the file gives it (XML: text, lists of text for arrays and matrices; JSON: the typed value under
its value-type key), so a model read and written again keeps every attribute; typed access converts and checks
(:meth:`Component.number`, ...), raising :class:`ltca.rexs.errors.RexsError` that names the component and the
attribute.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from .errors import RexsError
from .units import DIMENSIONS, factor, normalise_unit

__all__ = ["Attribute", "Component", "Ref", "Relation", "LoadCase", "RexsModel"]

_TRUE, _FALSE = ("true", "1"), ("false", "0")


@dataclass
class Attribute:
    """One attribute: ``id``, declared ``unit``, ``value`` as read, and the ``value_type`` the file states (JSON) or
    None (XML, where the schema alone says the type)."""
    id: str
    unit: str | None
    value: Any
    value_type: str | None = None


@dataclass
class Component:
    """A component: integer ``id``, REXS ``type``, ``name`` and its attributes by id (file order kept)."""
    id: int
    type: str
    name: str | None
    attributes: dict[str, Attribute] = field(default_factory=dict)
    file: str | None = None

    @property
    def label(self) -> str:
        """How messages name the component: ``cylindrical_gear 15 'Cylindrical gear [27]'``."""
        return f"{self.type} {self.id}" + (f" {self.name!r}" if self.name else "")

    def has(self, attr: str) -> bool:
        return attr in self.attributes

    def _attr(self, attr: str) -> Attribute:
        if attr not in self.attributes:
            raise RexsError(self.label, attr, "missing: this attribute is needed here", None, self.file)
        return self.attributes[attr]

    def _scalar(self, attr: str, kinds: tuple[str, ...], what: str) -> Any:
        a = self._attr(attr)
        if a.value_type is not None and a.value_type not in kinds:
            raise RexsError(self.label, attr, f"wrong value type {a.value_type!r}: {what} expected", a.value, self.file)
        if isinstance(a.value, (list, dict)):
            raise RexsError(self.label, attr, f"wrong value type (an array): {what} expected", a.value, self.file)
        return a.value

    def number(self, attr: str, dimension: str = "none") -> float:
        """A floating-point value in the base unit of ``dimension`` (:data:`ltca.rexs.units.DIMENSIONS`)."""
        a = self._attr(attr)
        raw = self._scalar(attr, ("floating_point", "integer"), "a number")
        if isinstance(raw, bool):
            raise RexsError(self.label, attr, "wrong value type (a boolean): a number expected", raw, self.file)
        try:
            v = float(raw)
        except (TypeError, ValueError):
            raise RexsError(self.label, attr, "wrong value type: a number expected", raw, self.file) from None
        if not math.isfinite(v):
            raise RexsError(self.label, attr, "a finite number expected", raw, self.file)
        f = factor(a.unit, dimension)
        if f is None:
            raise RexsError(self.label, attr, f"unknown unit {a.unit!r}: one of {sorted(DIMENSIONS[dimension])} "
                            "expected", raw, self.file)
        return v * f

    def integer(self, attr: str) -> int:
        """An integer value (an integral floating-point value, as some writers give counts, is accepted)."""
        a = self._attr(attr)
        raw = self._scalar(attr, ("integer", "floating_point"), "an integer")
        if factor(a.unit, "none") is None:
            raise RexsError(self.label, attr, f"unknown unit {a.unit!r}: a count has unit 'none'", raw, self.file)
        if isinstance(raw, bool):
            raise RexsError(self.label, attr, "wrong value type (a boolean): an integer expected", raw, self.file)
        try:
            v = float(raw)
        except (TypeError, ValueError):
            raise RexsError(self.label, attr, "wrong value type: an integer expected", raw, self.file) from None
        if not v.is_integer():
            raise RexsError(self.label, attr, "wrong value type: an integer expected", raw, self.file)
        return int(v)

    def boolean(self, attr: str) -> bool:
        raw = self._scalar(attr, ("boolean",), "true or false")
        if isinstance(raw, bool):
            return raw
        if str(raw).strip().lower() in _TRUE:
            return True
        if str(raw).strip().lower() in _FALSE:
            return False
        raise RexsError(self.label, attr, "wrong value type: true or false expected", raw, self.file)

    def text(self, attr: str) -> str:
        raw = self._scalar(attr, ("string", "enum", "file_reference", "date_time"), "a text")
        if isinstance(raw, bool):
            raise RexsError(self.label, attr, "wrong value type (a boolean): a text expected", raw, self.file)
        return str(raw)

    def reference(self, attr: str) -> int:
        raw = self._scalar(attr, ("reference_component", "integer", "floating_point"), "a component id")
        try:
            return int(float(raw))
        except (TypeError, ValueError):
            raise RexsError(self.label, attr, "wrong value type: a component id expected", raw, self.file) from None


@dataclass(frozen=True)
class Ref:
    """One end of a relation: the component ``id``, its ``role`` and the type ``hint``."""
    id: int
    role: str
    hint: str | None = None


@dataclass
class Relation:
    """A relation of a ``type`` (stage, flank, assembly, reference, ...) between components by role."""
    id: int | None
    type: str
    refs: tuple[Ref, ...]
    order: int | None = None

    def role(self, role: str) -> int | None:
        """The id of the component in ``role`` (None when the relation has no such role)."""
        for r in self.refs:
            if r.role == role:
                return r.id
        return None


@dataclass
class LoadCase:
    """One load case of the load spectrum: the components' load-dependent attributes by component id."""
    id: int
    components: dict[int, Component] = field(default_factory=dict)


@dataclass
class RexsModel:
    """A whole REXS model as read (``form``: ``"xml"``, ``"json"`` or ``"zip"``, the inner form in ``inner``)."""
    version: str
    application_id: str | None
    application_version: str | None
    date: str | None
    relations: list[Relation]
    components: dict[int, Component]
    load_cases: list[LoadCase]
    spectrum_id: int | None = 1
    form: str = "xml"
    inner: str = "xml"
    file: str | None = None
    extra: dict = field(default_factory=dict)       # anything else the file holds at model level (kept on write)

    @property
    def major(self) -> int:
        """The REXS major version (1 or 2)."""
        try:
            return int(str(self.version).split(".")[0])
        except ValueError:
            return 0

    def component(self, cid: int, context: str = "model") -> Component:
        if cid not in self.components:
            raise RexsError(context, "-", f"refers to component {cid}, which the model does not contain",
                            cid, self.file)
        return self.components[cid]

    def of_type(self, *types: str) -> list[Component]:
        return [c for c in self.components.values() if c.type in types]

    def relations_of(self, rtype: str, cid: int, role: str | None = None) -> list[Relation]:
        """Relations of ``rtype`` in which component ``cid`` takes part (in ``role`` when given)."""
        return [r for r in self.relations if r.type == rtype
                and any(x.id == cid and (role is None or x.role == role) for x in r.refs)]

    def next_id(self) -> int:
        """A component id not used yet."""
        ids = list(self.components) + [c for lc in self.load_cases for c in lc.components]
        return max(ids, default=0) + 1

    def next_relation_id(self) -> int:
        return max((r.id or 0 for r in self.relations), default=0) + 1

    def unit_of(self, cid: int, attr: str) -> str:
        return normalise_unit(self.components[cid].attributes[attr].unit)
