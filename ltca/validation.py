"""One validation layer for every case kind (cylindrical, bevel, budget, chain, and new kinds).

A case kind declares its tables with the small field types below; :func:`check_table` walks the file
against them and raises :class:`ltca.errors.CaseError` with one short line: the dotted field, its value
(shortened) and what is allowed. Every number is finite and bounded; strings, booleans, lists and tables are
type-checked; unknown keys are refused at every depth; tooth-index tables are checked against the tooth count.
:func:`read_case_file` reads a file safely (UTF-8 only, bounded nesting and size) for every kind.

Hand-written rather than pydantic (measured on the bevel kind): its schema here is 22 lines of declarations
(ltca/bevel/case.py) against 60 for pydantic v2 (41 lines of models and a validator, a 15-line one-line error
formatter, the loader); pydantic's messages give one side of a range ("less than or equal to 45"), need a
formatter to reach one line, and the tooth-count check needs custom validators anyway. No new dependency.
Imports nothing of ours but :mod:`ltca.errors`.
"""
from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

from .errors import CaseError

__all__ = ["Num", "Int", "Str", "Bool", "List", "Table", "ToothMap", "check_table", "check_value",
           "read_case_file", "MAX_FILE_BYTES", "MAX_DEPTH", "words", "DesignError"]

MAX_FILE_BYTES = 4_000_000     # a case file is a few KB; a MB of TOML is a mistake
MAX_DEPTH = 8                  # tables/arrays nested deeper than any case kind needs


class DesignError(CaseError):
    """A derived check that failed (pointed tooth, undercut, no contact, interference, ...): one line with the
    quantity that failed and the input fields that drive it, plus advice."""

    def __init__(self, failed: str, fields, advice: str = "", file: str | None = None):
        self.failed, self.fields, self.advice = failed, tuple(fields), advice
        CaseError.__init__(self, self.fields[0], None, failed, file)
        where = f"{file}: " if file else ""
        self.args = (f"{where}{failed}; set by " + ", ".join(f"'{f}'" for f in self.fields)
                     + (f": {advice}" if advice else ""),)

    def __str__(self) -> str:
        return self.args[0]


def _fmt(x: float) -> str:
    return f"{x:g}"


# ------------------------------------------------------------------------------------------ field types #
@dataclass(frozen=True)
class Num:
    """A finite real number in [lo, hi] (open ends with lo_open / hi_open); ints are accepted."""
    lo: float
    hi: float
    unit: str = ""
    default: Any = None
    required: bool = False
    lo_open: bool = False
    hi_open: bool = False
    note: str = ""

    def words(self) -> str:
        u = f" {self.unit}" if self.unit else ""
        rng = f"{'(' if self.lo_open else '['}{_fmt(self.lo)}, {_fmt(self.hi)}{')' if self.hi_open else ']'}"
        return f"a number in {rng}{u}" + (f" ({self.note})" if self.note else "")

    def check(self, v: Any, path: str, file: str | None) -> float:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise CaseError(path, v, f"wrong type {type(v).__name__}; {self.words()}", file)
        v = float(v)
        ok = math.isfinite(v) and (v > self.lo if self.lo_open else v >= self.lo) and \
            (v < self.hi if self.hi_open else v <= self.hi)
        if not ok:
            raise CaseError(path, v, self.words(), file)
        return v


@dataclass(frozen=True)
class Int:
    """An integer in [lo, hi] (a float such as 16.0 is refused: tooth counts are written as integers)."""
    lo: int
    hi: int
    default: Any = None
    required: bool = False
    note: str = ""

    def words(self) -> str:
        return f"an integer in [{self.lo}, {self.hi}]" + (f" ({self.note})" if self.note else "")

    def check(self, v: Any, path: str, file: str | None) -> int:
        if isinstance(v, float) and math.isfinite(v) and v.is_integer():
            raise CaseError(path, v, f"{self.words()} (write it without a decimal point)", file)
        if isinstance(v, bool) or not isinstance(v, int):
            raise CaseError(path, v, f"wrong type {type(v).__name__}; {self.words()}", file)
        if not self.lo <= v <= self.hi:
            raise CaseError(path, v, self.words(), file)
        return v


@dataclass(frozen=True)
class Str:
    """A string: one of ``choices``, or free text up to ``max_len`` characters."""
    choices: tuple[str, ...] | None = None
    default: Any = None
    required: bool = False
    max_len: int = 500
    non_empty: bool = False

    def words(self) -> str:
        if self.choices:
            return "one of " + ", ".join(repr(c) for c in self.choices)
        return f"a {'non-empty ' if self.non_empty else ''}string of at most {self.max_len} characters"

    def check(self, v: Any, path: str, file: str | None) -> str:
        if not isinstance(v, str):
            raise CaseError(path, v, f"wrong type {type(v).__name__}; {self.words()}", file)
        if (self.choices and v not in self.choices) or len(v) > self.max_len or (self.non_empty and not v.strip()):
            raise CaseError(path, v, self.words(), file)
        return v


@dataclass(frozen=True)
class Bool:
    default: Any = None
    required: bool = False

    def words(self) -> str:
        return "true or false"

    def check(self, v: Any, path: str, file: str | None) -> bool:
        if not isinstance(v, bool):
            raise CaseError(path, v, f"wrong type {type(v).__name__}; true or false", file)
        return v


@dataclass(frozen=True)
class List:
    """A list of ``item`` with ``min_len`` to ``max_len`` entries."""
    item: Any
    min_len: int = 1
    max_len: int = 1000
    default: Any = None
    required: bool = False

    def words(self) -> str:
        return f"a list of {self.min_len} to {self.max_len} entries, each {self.item.words()}"

    def check(self, v: Any, path: str, file: str | None) -> list:
        if not isinstance(v, list):
            raise CaseError(path, v, f"wrong type {type(v).__name__}; {self.words()}", file)
        if not self.min_len <= len(v) <= self.max_len:
            raise CaseError(path, f"{len(v)} entries", self.words(), file)
        return [self.item.check(x, f"{path}[{i}]", file) for i, x in enumerate(v)]


@dataclass(frozen=True)
class ToothMap:
    """A table {tooth index = number}: keys are canonical integers in [0, teeth), no duplicates such as
    "1" and "01"; the tooth count is given to :meth:`check_teeth` once it is known."""
    value: Num
    default: Any = field(default_factory=dict)
    required: bool = False

    def words(self) -> str:
        return f"a table {{tooth index = {self.value.words()}}}"

    def check(self, v: Any, path: str, file: str | None) -> dict[int, float]:
        if not isinstance(v, dict):
            raise CaseError(path, v, f"wrong type {type(v).__name__}; {self.words()}", file)
        out: dict[int, float] = {}
        for k, x in v.items():
            if not re.fullmatch(r"0|[1-9][0-9]{0,5}", k):
                raise CaseError(f"{path}.{k}", x, "keys are tooth indices written as plain integers "
                                "(0, 1, 2, ...; no sign, no leading zero)", file)
            out[int(k)] = self.value.check(x, f"{path}.{k}", file)
        return out

    @staticmethod
    def check_teeth(m: dict[int, Any], teeth: int, path: str, file: str | None) -> None:
        for k in m:
            if k >= teeth:
                raise CaseError(f"{path}.{k}", m[k], f"tooth indices in [0, {teeth - 1}] (the member has "
                                f"{teeth} teeth)", file)


@dataclass(frozen=True)
class Table:
    """A table of known ``fields`` (name -> field type or nested Table); anything else is refused."""
    fields: dict
    default: Any = None
    required: bool = False
    extra: Callable[[str], bool] | None = None   # keys checked elsewhere (e.g. a sub-table of its own)

    def words(self) -> str:
        return "a table"

    def check(self, v: Any, path: str, file: str | None) -> dict:
        return check_table(v, self, path, file)


def check_value(spec, v: Any, path: str, file: str | None) -> Any:
    return spec.check(v, path, file)


def check_table(raw: Any, spec: Table, path: str, file: str | None) -> dict:
    """Validate ``raw`` against ``spec``; returns a dict with every field (defaults filled in)."""
    label = path or "case file"
    if not isinstance(raw, dict):
        raise CaseError(label, raw, f"wrong type {type(raw).__name__}; a table", file)
    for k in raw:
        if k not in spec.fields and not (spec.extra and spec.extra(k)):
            allowed = ", ".join(sorted(spec.fields))
            raise CaseError(f"{path}.{k}" if path else k, raw[k], f"unknown key; allowed: {allowed}", file)
    out = {}
    for k, f in spec.fields.items():
        p = f"{path}.{k}" if path else k
        if k not in raw:
            if f.required:
                raise CaseError(p, None, f"required; {f.words()}", file)
            out[k] = f.default if not isinstance(f, Table) or f.default is not None else check_table({}, f, p, file)
            continue
        out[k] = f.check(raw[k], p, file)
    return out


def words(spec) -> str:
    return spec.words()


# ------------------------------------------------------------------------------------------ file reading #
def _depth(x: Any, d: int = 0) -> int:
    if d > MAX_DEPTH:
        return d
    if isinstance(x, dict):
        return max([_depth(v, d + 1) for v in x.values()] or [d + 1])
    if isinstance(x, list):
        return max([_depth(v, d + 1) for v in x] or [d + 1])
    return d


def read_case_file(path: str | Path) -> dict:
    """Read a TOML case file of any kind: a missing file, non-UTF-8 bytes, broken TOML or nesting deeper than
    :data:`MAX_DEPTH` is a CaseError (exit status 2), never a traceback."""
    path = Path(path)
    if not path.is_file():
        from .shipped import shipped_cases
        raise CaseError("CASE", str(path), "an existing case file (.toml) or the name of a shipped case: "
                        + ", ".join(shipped_cases()))
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise CaseError("file", f"{size} bytes", f"a case file of at most {MAX_FILE_BYTES} bytes", str(path))
    raw = path.read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise CaseError("file", f"byte 0x{raw[exc.start]:02x} at offset {exc.start}", "UTF-8 text", str(path)) \
            from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise CaseError("file", path.name, f"valid TOML ({exc})", str(path)) from None
    except RecursionError:
        raise CaseError("file", path.name, f"arrays or tables nested at most {MAX_DEPTH} deep", str(path)) from None
    if _depth(data) > MAX_DEPTH:
        raise CaseError("file", path.name, f"arrays or tables nested at most {MAX_DEPTH} deep", str(path))
    return data


#: case kinds by their characteristic top-level tables, and the command that reads them
KINDS = {"cylindrical": ({"gear_pair", "pinion", "gear"}, "ltca run / ltca tca"), "bevel": ({"bevel"}, "ltca tca"),
         "budget": ({"budget", "member"}, "ltca budget"), "chain": ({"chain", "workpiece"}, "ltca chain")}


def check_kind(data: dict, expected: str, file: str | None = None) -> None:
    """A case of another kind is named in one line (its tables are not dumped)."""
    found = [k for k, (keys, _) in KINDS.items() if keys & set(data)]
    if found and expected not in found:
        raise CaseError("file", f"a {found[0]} case", f"a {expected} case here; read it with "
                        f"`{KINDS[found[0]][1]}`", file)
