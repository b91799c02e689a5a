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

Variants are the product of the named variants, the grid points and the Monte Carlo samples; each runs at
every torque. A variant's id hashes everything that defines its results except the torque list (its
resolved case and the largest torque, which sets the teeth in mesh), so a rerun finds what is done.
A bad study file raises :class:`ltca.errors.CaseError` naming the field (exit status 2).

The file is declared as :mod:`ltca.validation` tables (:data:`CASE`); the dotted keys it varies are checked against
the case keys after the table check. Imports ltca.case, ltca.errors, ltca.validation and ltca.study.montecarlo.
"""
from __future__ import annotations

import copy
import hashlib
import itertools
import json
from dataclasses import dataclass, field
from pathlib import Path

from ..case import case_keys, parse_case, read_toml, to_toml
from ..errors import CaseError
from ..validation import Int, List, Num, OneOrList, Str, Table, TableList, check_table
from .montecarlo import MEMBERS, check_members, draw_sample

__all__ = ["Study", "Variant", "MonteCarlo", "set_key", "to_toml", "CASE"]

_ANY_KEY = lambda k: True       # noqa: E731  dotted case keys, checked against the case's keys after the table
_TORQUE = Num(0, 1e6, "N m", lo_open=True)

#: the study kind
CASE = Table({
    "study": Table({
        "name": Str(non_empty=True, max_len=200, meaning="the study's name (default: the file's stem)"),
        "case": Str(non_empty=True, max_len=1000, required=True,
                    meaning="the base case file (.toml), relative to the study file"),
        "torque_nm": OneOrList(_TORQUE, 1, 100, meaning="the torque dimension (default: the base case's torques)"),
        "description": Str(max_len=2000, default="", meaning="free text"),
    }, required=True),
    "set": Table({}, extra=_ANY_KEY, meaning="fixed overrides of the base case: \"dotted.case.key\" = value"),
    "grid": Table({}, extra=_ANY_KEY, meaning="full factorial: \"dotted.case.key\" = [values]"),
    "variants": TableList(Table({"name": Str(non_empty=True, max_len=200, meaning="the variant's name, unique "
                                                                                  "(default: variant<i>)")},
                                extra=_ANY_KEY, meaning="\"dotted.case.key\" = value of this variant"), 1, 10_000,
                          meaning="named variants: name and \"dotted.case.key\" = value (times the grid)"),
    "monte_carlo": Table({
        "grade": Int(1, 11, required=True, note="an ISO 1328-1:2013 flank tolerance class",
                      meaning="ISO 1328-1:2013 flank tolerance class of every member"),
        "samples": Int(1, 100_000, required=True, note="the sample size", meaning="the sample size"),
        "seed": Int(0, 2 ** 32 - 1, default=0, meaning="random seed; sample i does not depend on samples"),
        "members": List(Str(MEMBERS), 1, len(MEMBERS), default=list(MEMBERS),
                        meaning="the members whose tooth errors are drawn"),
    }, meaning="ISO 1328-1 tooth errors drawn per sample (times the variants and the grid)"),
})


@dataclass(frozen=True)
class MonteCarlo:
    """A Monte Carlo sample of ISO 1328-1 tooth errors."""
    grade: int
    samples: int
    seed: int
    members: tuple[str, ...] = MEMBERS


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


def _check_key(key: str, where: str, file: str | None = None) -> None:
    keys = case_keys()
    if key not in keys:
        near = sorted(k for k in keys if k.split(".")[-1] == key.split(".")[-1])
        raise CaseError(where, key, "unknown key to vary: a dotted case key such as 'load.torque_nm' or "
                        "'pinion.modifications.lead_crowning_um'" + (f" (did you mean {near}?)" if near else ""),
                        file)
    if key == "load.driver":
        raise CaseError(where, key, "not variable; vary 'load.torque_nm' or give [study] torque_nm", file)


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
        for key, value in d["set"].items():
            _check_key(key, f"set.{key}", file)
            set_key(base, key, value)
        grid = {}
        torques = None
        for key, values in d["grid"].items():
            _check_key(key, f"grid.{key}", file)
            if not isinstance(values, list) or not values:
                raise CaseError(f"grid.{key}", values, "a non-empty list of values (an empty grid has no variant)",
                                file)
            if key == "load.torque_nm":
                torques = tuple(List(_TORQUE, 1, 100).check(values, f"grid.{key}", file))
            else:
                grid[key] = list(values)
        if st["torque_nm"] is not None:
            if torques is not None:
                raise CaseError("study.torque_nm", data["study"]["torque_nm"], "given once: here or as grid "
                                "'load.torque_nm'", file)
            torques = st["torque_nm"]
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
                    _check_key(key, f"variants[{i}].{key}", file)
                    if key.startswith("load."):
                        raise CaseError(f"variants[{i}].{key}", v[key], "not a per-variant key: the torques are a "
                                        "dimension of the study ([study] torque_nm or grid 'load.torque_nm')", file)
        mc = None
        if d["monte_carlo"] is not None:
            m = d["monte_carlo"]
            mc = MonteCarlo(m["grade"], m["samples"], m["seed"], check_members(m["members"]))
        base_case = parse_case(base, file=str(case_path))
        if mc is not None:
            from .montecarlo import member_tolerances
            for member in mc.members:
                member_tolerances(base_case, member, mc.grade)
        if torques is None:
            torques = tuple(t * 1e-3 for t in base_case.torques)
        base.setdefault("load", {})["torque_nm"] = list(torques)
        study = cls(st["name"] or (Path(file).stem if file else "study"), base, torques, grid,
                    tuple(raw_variants), mc, file)
        for v in study.expand():                   # every variant must be a valid case
            parse_case(v.case, file=f"{file}: variant {v.name!r} {v.coords}" if file else None)
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
                overrides, drawn = draw_sample(case, parse_case(case), mc.grade, mc.seed, sample, mc.members)
                for key, value in overrides.items():
                    set_key(case, key, value)
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


