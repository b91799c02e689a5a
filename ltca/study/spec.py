"""Study files: a base case and its variations, validated, expanded into variants.

A study TOML (paths relative to the study file)::

    [study]
    name = "FZG C14 torque x misalignment"
    case = "../cases/fzg_c14.toml"       # the base case
    torque_nm = [50, 100, 200]            # the torque dimension (or "load.torque_nm" in [grid]; else the case's)

    [set]                                 # fixed overrides of the base case, dotted case keys
    "analysis.positions" = 16

    [grid]                                # full factorial over any case keys
    "assembly.lead_misalignment_um" = [0, 10, 20]

    [[variants]]                          # named variants (times the grid)
    name = "crowned"
    "pinion.modifications.lead_crowning_um" = 5.0

    [monte_carlo]                         # ISO 1328-1 tooth errors (times the variants and the grid)
    grade = 6
    samples = 200
    seed = 1
    members = ["pinion", "gear"]
    [monte_carlo.uniform]                 # and / or any case keys drawn: uniform in [low, high] ...
    "assembly.lead_misalignment_um" = [-5.0, 5.0]
    [monte_carlo.normal]                  # ... or normal (mean, standard deviation)
    "assembly.lead_deviation_um" = [0.0, 3.0]

The base case is a cylindrical or a bevel pair (``[bevel]``; then ``grade`` and ``members`` do not apply and
the torques may be negative: the coast flank). Variants are the product of the named variants, the grid points
and the Monte Carlo samples; each runs at every torque. A variant's id hashes everything that defines its
results except the torque list (its resolved case and the largest torque, which sets the teeth in mesh), so a
rerun finds what is done.
A bad study file raises :class:`ltca.errors.CaseError` naming the field (exit status 2).

The file is declared as :mod:`ltca.validation` tables (:data:`CASE`); the dotted keys it varies are checked against
the case keys after the table check. Imports ltca.case, ltca.bevel.case, ltca.errors, ltca.validation and
ltca.study.montecarlo.
"""
from __future__ import annotations

import copy
import hashlib
import itertools
import json
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..case import case_keys, parse_case, read_toml, to_toml
from ..errors import CaseError
from ..validation import Int, List, Num, OneOrList, Str, Table, TableList, check_table, kind_of
from .montecarlo import MEMBERS, check_members, draw_keys, draw_sample

__all__ = ["Study", "Variant", "MonteCarlo", "set_key", "to_toml", "CASE", "study_keys", "validate_case"]

#: the gear kinds a study runs
STUDY_KINDS = ("cylindrical", "bevel")

_ANY_KEY = lambda k: True       # noqa: E731  dotted case keys, checked against the case's keys after the table
_TORQUE = Num(0, 1e6, "N m", lo_open=True)

#: the study kind
CASE = Table({
    "study": Table({
        "name": Str(non_empty=True, max_len=200, meaning="the study's name (default: the file's stem)"),
        "case": Str(non_empty=True, max_len=1000, required=True,
                    meaning="the base case file (.toml), relative to the study file"),
        "torque_nm": OneOrList(Num(-1e6, 1e6, "N m"), 1, 100,
                               meaning="the torque dimension (default: the base case's torques); a bevel study: "
                                       "the sign picks the flank"),
        "description": Str(max_len=2000, default="", meaning="free text"),
    }, required=True),
    "set": Table({}, extra=_ANY_KEY, meaning="fixed overrides of the base case: \"dotted.case.key\" = value"),
    "grid": Table({}, extra=_ANY_KEY, meaning="full factorial: \"dotted.case.key\" = [values]"),
    "variants": TableList(Table({"name": Str(non_empty=True, max_len=200, meaning="the variant's name, unique "
                                                                                  "(default: variant<i>)")},
                                extra=_ANY_KEY, meaning="\"dotted.case.key\" = value of this variant"), 1, 10_000,
                          meaning="named variants: name and \"dotted.case.key\" = value (times the grid)"),
    "monte_carlo": Table({
        "grade": Int(1, 11, note="an ISO 1328-1:2013 flank tolerance class",
                      meaning="ISO 1328-1:2013 flank tolerance class of every member (cylindrical pairs)"),
        "samples": Int(1, 100_000, required=True, note="the sample size", meaning="the sample size"),
        "seed": Int(0, 2 ** 32 - 1, default=0, meaning="random seed; sample i does not depend on samples"),
        "members": List(Str(MEMBERS), 1, len(MEMBERS), default=list(MEMBERS),
                        meaning="the members whose tooth errors are drawn"),
        "uniform": Table({}, extra=_ANY_KEY, default={},
                         meaning="\"dotted.case.key\" = [low, high]: drawn uniform"),
        "normal": Table({}, extra=_ANY_KEY, default={},
                        meaning="\"dotted.case.key\" = [mean, standard deviation]: drawn normal"),
    }, meaning="a sample per draw (times the variants and the grid): ISO 1328-1 tooth errors and / or case keys"),
})


@dataclass(frozen=True)
class MonteCarlo:
    """A Monte Carlo sample: ISO 1328-1 tooth errors of class ``grade`` (cylindrical pairs; None: none) and / or
    case keys drawn uniform in [low, high] (``uniform``: key -> (low, high)) or normal (``normal``: key -> (mean,
    standard deviation)), in the case's own units."""
    grade: int | None
    samples: int
    seed: int
    members: tuple[str, ...] = MEMBERS
    uniform: dict = field(default_factory=dict)
    normal: dict = field(default_factory=dict)


@dataclass(frozen=True)
class Variant:
    """One variant: its id, its coordinates (the varied keys' values) and its resolved case (TOML dict)."""
    id: str
    index: int
    name: str
    coords: dict
    case: dict
    drawn: dict = field(default_factory=dict)


def set_key(data: dict, key: str, value) -> None:
    """Set dotted case key ``key`` of a case dict (as read from TOML) in place, making tables as needed."""
    *path, last = key.split(".")
    for p in path:
        data = data.setdefault(p, {})
    data[last] = copy.deepcopy(value)


def study_keys(kind: str) -> dict[str, str]:
    """Every settable key of a case of ``kind`` (dotted path -> what is allowed)."""
    if kind == "cylindrical":
        return case_keys()
    from ..bevel.case import _CASE

    out = {}

    def walk(table, prefix):
        for name, f in table.fields.items():
            if hasattr(f, "fields"):
                walk(f, f"{prefix}{name}.")
            else:
                out[f"{prefix}{name}"] = getattr(f, "note", "") or ""
    walk(_CASE, "")
    return {k: v for k, v in out.items() if not k.startswith("case.")}


def validate_case(kind: str, data: dict, file: str | None = None):
    """The typed record of a case of ``kind`` given as TOML tables (:class:`ltca.errors.CaseError` if bad)."""
    if kind == "cylindrical":
        return parse_case(data, file=file)
    from ..bevel.case import bevel_case_from_data
    return bevel_case_from_data(copy.deepcopy({k: v for k, v in data.items() if k != "design"}), file, "variant")


def _check_key(key: str, where: str, file: str | None = None, kind: str = "cylindrical") -> None:
    keys = study_keys(kind)
    if key not in keys:
        near = sorted(k for k in keys if k.split(".")[-1] == key.split(".")[-1])
        raise CaseError(where, key, "unknown key to vary: a dotted case key such as 'load.torque_nm' or "
                        "'pinion.modifications.lead_crowning_um'" + (f" (did you mean {near}?)" if near else ""),
                        file)
    if key == "load.driver":
        raise CaseError(where, key, "not variable; vary 'load.torque_nm' or give [study] torque_nm", file)


def _torques(values, where: str, file: str, kind: str = "cylindrical") -> tuple[float, ...]:
    words = ("a non-zero number in [-1e5, 1e5] N m (the sign picks the flank)" if kind == "bevel"
             else "a number in (0, 1e6] N m")
    if not isinstance(values, list) or not values:
        raise CaseError(where, values, f"a non-empty list of torques, each {words}", file)
    for i, t in enumerate(values):
        ok = not isinstance(t, bool) and isinstance(t, (int, float)) and (
            (t != 0 and -1e5 <= t <= 1e5) if kind == "bevel" else 0 < t <= 1e6)
        if not ok:
            raise CaseError(f"{where}[{i}]", t, words, file)
    if len(set(values)) != len(values):
        raise CaseError(where, values, "distinct torques", file)
    return tuple(float(t) for t in values)


def _draw_table(m: dict, name: str, file: str, kind: str) -> dict:
    """``[monte_carlo.uniform]`` (key -> [low, high]) or ``[monte_carlo.normal]`` (key -> [mean, std])."""
    raw = m.get(name, {})
    if not isinstance(raw, dict):
        raise CaseError(f"monte_carlo.{name}", raw, "a table of case keys", file)
    out = {}
    for key, pair in raw.items():
        where = f"monte_carlo.{name}.{key}"
        _check_key(key, where, file, kind)
        if key.startswith("load."):
            raise CaseError(where, pair, "not drawn: the torques are a dimension of the study", file)
        what = "[low, high] with low < high" if name == "uniform" else "[mean, standard deviation] with std > 0"
        if not (isinstance(pair, list) and len(pair) == 2 and all(
                not isinstance(x, bool) and isinstance(x, (int, float)) and np.isfinite(x) for x in pair)):
            raise CaseError(where, pair, f"two finite numbers {what}", file)
        a, b = float(pair[0]), float(pair[1])
        if (name == "uniform" and not a < b) or (name == "normal" and not b > 0):
            raise CaseError(where, pair, what, file)
        out[key] = (a, b)
    return out


@dataclass(frozen=True)
class Study:
    """A validated study: the base case (``[set]`` applied) and its variations."""
    name: str
    base: dict
    torques: tuple[float, ...]                # N m
    grid: dict                                # dotted key -> list of values (torque excluded)
    variants: tuple[dict, ...]                # named variants: {"name": ..., dotted key: value}
    monte_carlo: MonteCarlo | None = None
    file: str | None = None
    kind: str = "cylindrical"

    @classmethod
    def from_toml(cls, path: str | Path) -> "Study":
        """Read and validate a study file."""
        path = Path(path)
        data = read_toml(path)
        return cls.from_dict(data, path.parent, str(path))

    @classmethod
    def from_dict(cls, data: dict, base_dir: str | Path = ".", file: str | None = None) -> "Study":
        """Validate a study given as a dict (as read from TOML); ``base_dir`` resolves the case path."""
        st = data.get("study")
        if isinstance(st, dict) and "torques_nm" in st:
            raise CaseError("study.torques_nm", st["torques_nm"], "renamed: write torque_nm = a number or a list of "
                            "numbers (N m), the spelling of the case files", file)
        d = check_table(data, CASE, "", file)
        st = d["study"]
        if "\0" in st["case"]:
            raise CaseError("study.case", st["case"], "the base case file (.toml), relative to the study: a path "
                            "of 1 to 1000 characters without NUL", file)
        case_path = Path(base_dir) / st["case"]
        try:
            found = case_path.is_file()
        except OSError as exc:            # a path the file system refuses (a name too long)
            raise CaseError("study.case", st["case"], f"a case file path the file system accepts ({exc.strerror})",
                            file) from None
        if not found:
            raise CaseError("study.case", st["case"], f"an existing case file (looked for {case_path})", file)
        base = read_toml(case_path)
        kind = kind_of(base, str(case_path))
        if kind not in STUDY_KINDS:
            raise CaseError("study.case", st["case"], f"a gear pair case of kind {' or '.join(STUDY_KINDS)} "
                            f"(this is a {kind} case)", file)
        for key, value in d["set"].items():
            _check_key(key, f"set.{key}", file, kind)
            set_key(base, key, value)
        grid = {}
        torques = None
        for key, values in d["grid"].items():
            _check_key(key, f"grid.{key}", file, kind)
            if not isinstance(values, list) or not values:
                raise CaseError(f"grid.{key}", values, "a non-empty list of values (an empty grid has no variant)",
                                file)
            if key == "load.torque_nm":
                torques = _torques(values, f"grid.{key}", file, kind)
            else:
                grid[key] = list(values)
        if st["torque_nm"] is not None:
            if torques is not None:
                raise CaseError("study.torque_nm", data["study"]["torque_nm"], "given once: here or as grid "
                                "'load.torque_nm'", file)
            t = st["torque_nm"]
            torques = _torques(list(t), "study.torque_nm", file, kind)
        raw_variants = data.get("variants", [])
        names = set()
        for i, v in enumerate(raw_variants):
            name = v.get("name")
            if not isinstance(name, str) or name in names or not 0 < len(name.strip()) <= 200:
                raise CaseError(f"variants[{i}].name", name, "required: a non-empty string of at most 200 characters "
                                "naming the variant, unique", file)
            names.add(name)
            for key in v:
                if key != "name":
                    _check_key(key, f"variants[{i}].{key}", file, kind)
                    if key.startswith("load."):
                        raise CaseError(f"variants[{i}].{key}", v[key], "not a per-variant key: the torques are a "
                                        "dimension of the study ([study] torque_nm or grid 'load.torque_nm')", file)
        mc = None
        if d["monte_carlo"] is not None:
            m = d["monte_carlo"]
            raw_m = data["monte_carlo"]
            if kind != "cylindrical" and ({"grade", "members"} & set(raw_m)):
                key = sorted({"grade", "members"} & set(raw_m))[0]
                raise CaseError(f"monte_carlo.{key}", raw_m[key], f"not for a {kind} study (ISO 1328-1 tooth "
                                "errors are drawn for cylindrical pairs); draw case keys with [monte_carlo.uniform] "
                                "or [monte_carlo.normal]", file)
            uniform, normal = _draw_table(m, "uniform", file, kind), _draw_table(m, "normal", file, kind)
            if set(uniform) & set(normal):
                raise CaseError("monte_carlo.normal", sorted(set(uniform) & set(normal))[0],
                                "a key drawn once: uniform or normal", file)
            if m["grade"] is None and not (uniform or normal):
                raise CaseError("monte_carlo", "no draws", "what to draw: grade (ISO 1328-1 tooth errors, "
                                "cylindrical pairs) and / or [monte_carlo.uniform] or [monte_carlo.normal] case keys",
                                file)
            mc = MonteCarlo(m["grade"], m["samples"], m["seed"], check_members(m["members"]), uniform, normal)
        base_case = validate_case(kind, base, str(case_path))
        if mc is not None and mc.grade is not None:
            from .montecarlo import member_tolerances
            for member in mc.members:
                member_tolerances(base_case, member, mc.grade)
        if torques is None:
            torques = tuple(t * 1e-3 for t in base_case.torques) if kind == "cylindrical" else base_case.torques
            if not torques:
                raise CaseError("study.torque_nm", None, "the study's torques (N m): the base case gives none", file)
        base.setdefault("load", {})["torque_nm"] = list(torques)
        study = cls(st["name"] or (Path(file).stem if file else "study"), base, torques, grid,
                    tuple(raw_variants), mc, file, kind)
        for v in study.expand():                   # every variant must be a valid case
            validate_case(kind, v.case, f"{file}: variant {v.name!r} {v.coords} {v.drawn}" if file else None)
        return study

    @property
    def varied_keys(self) -> list[str]:
        """The dotted case keys varied by the named variants and the grid (not the torque)."""
        keys = dict.fromkeys(self.grid)
        for v in self.variants:
            keys.update(dict.fromkeys(k for k in v if k != "name"))
        return list(keys)

    def expand(self) -> list[Variant]:
        """All variants, in a fixed order: named variant, then grid point, then Monte Carlo sample."""
        named = list(self.variants) or [{"name": "base"}]
        points = [dict(zip(self.grid, vals)) for vals in itertools.product(*self.grid.values())]
        samples = range(self.monte_carlo.samples) if self.monte_carlo else [None]
        out = []
        for nv, point, sample in itertools.product(named, points, samples):
            case = copy.deepcopy(self.base)
            coords = {k: nv.get(k, _get(self.base, k)) for k in self.varied_keys}
            for key, value in {**{k: v for k, v in nv.items() if k != "name"}, **point}.items():
                set_key(case, key, value)
                coords[key] = value
            drawn = {}
            if sample is not None:
                mc = self.monte_carlo
                if mc.grade is not None:
                    overrides, drawn = draw_sample(case, parse_case(case), mc.grade, mc.seed, sample, mc.members)
                    for key, value in overrides.items():
                        set_key(case, key, value)
                if mc.uniform or mc.normal:
                    values = draw_keys(mc.uniform, mc.normal, mc.seed, sample)
                    for key, value in values.items():
                        set_key(case, key, value)
                    drawn.update(values)
                coords["sample"] = sample
            ident = json.dumps({"case": {k: v for k, v in case.items() if k != "load"},
                                "torque_nom": max(self.torques)}, sort_keys=True, default=str)
            vid = hashlib.sha256(ident.encode()).hexdigest()[:16]
            out.append(Variant(vid, len(out), nv["name"], coords, case, drawn))
        return out


def _get(data: dict, key: str):
    """The value of dotted key ``key`` in a case dict, or NaN when the case leaves it to its default."""
    for p in key.split("."):
        if not isinstance(data, dict) or p not in data:
            return float("nan")
        data = data[p]
    return data


