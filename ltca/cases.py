"""The case layer: one record for a case of any kind, read from a file or a shipped name, edited by dotted keys.

A :class:`Case` keeps the case as the engineer wrote it (``data``: the TOML tables in engineer's units) beside its
validated, typed record in internal units (``record``: :class:`ltca.case.CylindricalCase`,
:class:`ltca.bevel.case.BevelCase`, :class:`ltca.planetary.case.PlanetaryCase`, the budget's drive train or the
chain's tuple of chains). Every kind is validated by its schema in the one validation layer
(:mod:`ltca.validation`): a bad value raises :class:`ltca.errors.CaseError` naming the field, its value and what
is allowed. :meth:`Case.with_values` edits dotted keys and validates the copy, so a script and a study change a
case the same way::

    case = ltca.load_case("fzg_c14").with_values({"assembly.lead_misalignment_um": 10.0})
"""
from __future__ import annotations

import copy
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Mapping

from .errors import CaseError
from .validation import CASE_KINDS, kind_of

__all__ = ["Case", "KINDS", "kind_of", "case_from_data", "load_case", "set_key", "get_key"]

#: the case kinds, each recognised by one of its top-level tables
KINDS = CASE_KINDS

#: the kinds that ``ltca.run`` analyses (gear pairs)
PAIR_KINDS = ("cylindrical", "bevel", "planetary")


def set_key(data: dict, key: str, value: Any) -> None:
    """Set dotted key ``key`` of TOML tables in place.

    E.g. ``"pinion.modifications.lead_crowning_um"``; the tables on the way are made as needed.
    """
    *path, last = key.split(".")
    for p in path:
        nxt = data.setdefault(p, {})
        if not isinstance(nxt, dict):
            raise CaseError(key, value, f"a key below a table; '{p}' is a value here")
        data = nxt
    data[last] = copy.deepcopy(value)


def get_key(data: Mapping, key: str, default: Any = None) -> Any:
    """The value of dotted key ``key`` of TOML tables, ``default`` where it is not given."""
    for p in key.split("."):
        if not isinstance(data, Mapping) or p not in data:
            return default
        data = data[p]
    return data


def _parse_cylindrical(data: dict, file: str | None, stem: str):
    from .case import parse_case
    rec = parse_case({k: v for k, v in data.items() if k != "design"}, file)
    return rec, rec.name


def _parse_bevel(data: dict, file: str | None, stem: str):
    from .bevel.case import bevel_case_from_data
    rec = bevel_case_from_data({k: v for k, v in data.items() if k != "design"}, file, stem)
    return rec, rec.name


def _parse_planetary(data: dict, file: str | None, stem: str):
    from .planetary.case import parse_planetary_case
    rec = parse_planetary_case(data, file)
    return rec, rec.name


def _parse_budget(data: dict, file: str | None, stem: str):
    from .drivetrain.budget_case import budget_from_data
    rec = budget_from_data(data, file)
    return rec, rec[0].title or stem


def _parse_chain(data: dict, file: str | None, stem: str):
    from .drivetrain.chain_case import chain_from_data
    return chain_from_data(data, file), stem


def _parse_study(data: dict, file: str | None, stem: str):
    from .study.spec import Study
    base = Path(file).parent if file else Path(".")
    rec = Study.from_dict(data, base_dir=base, file=file)
    return rec, rec.name


_PARSERS: dict[str, Callable] = {"cylindrical": _parse_cylindrical, "bevel": _parse_bevel,
                                 "planetary": _parse_planetary, "budget": _parse_budget, "chain": _parse_chain,
                                 "study": _parse_study}


@dataclass(frozen=True)
class Case:
    """A validated case of one kind.

    Attributes
    ----------
    kind : str
        One of :data:`KINDS`.
    name : str
        The case's name (``[case] name``, else the file's stem).
    record : object
        The kind's typed record in internal units (mm, N, MPa, rad; torques N mm for cylindrical and planetary
        records, N m for bevel).
    data : dict
        The TOML tables as written (engineer's units); treat as read-only, edit with :meth:`with_values`.
    file : str or None
        The file it was read from (paths inside a case, e.g. a study's base case, are relative to it).
    """

    kind: str
    name: str
    record: Any = field(repr=False)
    data: dict = field(repr=False)
    file: str | None = None

    def with_values(self, values: Mapping[str, Any]) -> "Case":
        """A validated copy with the dotted keys of ``values`` set (engineer's units, as in the file).

        Raises :class:`ltca.errors.CaseError` for an unknown key or a value out of its range.
        """
        if not isinstance(values, Mapping):
            raise CaseError("values", type(values).__name__, "a mapping of dotted case keys to values")
        data = copy.deepcopy(self.data)
        for key, value in values.items():
            if not isinstance(key, str) or not key or any(not p for p in key.split(".")):
                raise CaseError("values", key, "a dotted case key such as 'load.torque_nm'")
            set_key(data, key, value)
        return case_from_data(data, self.file, name=self.name if "name" not in get_key(data, "case", {}) else None)

    def value(self, key: str, default: Any = None) -> Any:
        """The value of a dotted key as written in the case (``default`` where the case does not give it)."""
        return get_key(self.data, key, default)

    def to_toml(self) -> str:
        """The case as TOML text (reads back to the same case)."""
        from .case import to_toml
        return to_toml(self.data)


def case_from_data(data: Mapping, file: str | None = None, name: str | None = None) -> Case:
    """Validate TOML tables as a case of their kind.

    ``name`` names the case when the tables give none (default: the file's stem).
    """
    if not isinstance(data, Mapping):
        raise CaseError("case", type(data).__name__, "TOML tables (a mapping)", file)
    data = copy.deepcopy(dict(data))
    kind = kind_of(data, file)
    stem = name or (Path(file).stem if file else kind)
    if name and kind in PAIR_KINDS and not get_key(data, "case.name"):
        set_key(data, "case.name", name)
    record, rec_name = _PARSERS[kind](copy.deepcopy(data), file, stem)
    return Case(kind=kind, name=str(rec_name or stem), record=record, data=data, file=file)


def load_case(name_or_path: str | Path) -> Case:
    """Read and validate a case file, or a shipped case by name (``"fzg_c14"``, ``"spiral_bevel_cao2008"``).

    Raises :class:`ltca.errors.CaseError` for a missing file or any bad value (field, value, what is allowed).
    """
    from .shipped import case_path
    from .validation import read_case_file
    path = case_path(str(name_or_path))
    return case_from_data(read_case_file(path), str(path))
