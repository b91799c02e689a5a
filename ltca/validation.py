"""One validation layer for every case kind (cylindrical, bevel, planetary, budget, chain, study, design).

A case kind declares its tables with the small field types below (:class:`Table` of :class:`Num`, :class:`Int`,
:class:`Str`, :class:`Bool`, :class:`List`, :class:`ToothMap`, :class:`OneOrList` for a torque or a list of them,
:class:`TableList` for ``[[name]]``, :class:`Tagged` for a table whose ``kind`` picks its keys), each field with its
unit and meaning; :func:`check_table` walks the file against them and raises :class:`ltca.errors.CaseError` with
one short line: the dotted field, its value (shortened) and what is allowed. Every number is finite and bounded;
strings, booleans, lists and tables are type-checked; unknown keys are refused at every depth; tooth-index tables
are checked against the tooth count. The same declarations give the key reference (:func:`table_reference`,
``ltca keys``, docs/case_keys.md) and a JSON Schema for editors (:func:`json_schema`). :func:`read_case_file` reads
a file safely (UTF-8 only, bounded nesting and size) for every kind.

Hand-written rather than pydantic v2 (2.13), measured on the budget kind: the Table declarations are 55 lines with a
meaning per key, the pydantic models with a one-line error formatter 61 lines without meanings; importing them takes
33 ms against 564 ms (``python3 -X importtime``, best of 9); a range violation reads ``a number in [0.1, 100]
N/(um mm)`` against pydantic's ``Input should be less than or equal to 100`` (one side of the range, the tag
``mesh`` inside the field path), an unknown key ``unknown key; allowed: base_radius_mm, ...`` against ``Extra inputs
are not permitted``; cross-field checks (exactly one stiffness, teeth against the tooth count) are hand code in
both, and both give a JSON Schema (5.4 kB here, 5.1 kB from pydantic). No new dependency.
Imports nothing of ours but :mod:`ltca.errors`.
"""
from __future__ import annotations

import difflib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import tomllib

from .errors import CaseError

__all__ = ["Num", "Int", "Str", "Bool", "List", "Table", "ToothMap", "OneOrList", "TableList", "Tagged",
           "check_table", "check_value", "table_reference", "table_keys", "json_schema", "read_case_file",
           "MAX_FILE_BYTES", "MAX_DEPTH", "words", "DesignError", "CASE_KINDS", "KINDS", "kind_of"]

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
    """A bound as an engineer writes it: 0.5, 200, 5000, 1e5, 5e5, 2e8, 1e-3 (a power of ten outside [0.01, 1e4)
    as 1eN, one significant digit from 1e5 up as 5e5)."""
    if x and (abs(x) >= 1e4 or abs(x) < 1e-2):
        e = round(math.log10(abs(x)))
        if abs(x) == 10.0 ** e:
            return f"{'-' if x < 0 else ''}1e{e}"
    if abs(x) >= 1e5 and float(f"{x:.0e}") == x:
        return re.sub(r"e\+0*", "e", f"{x:.0e}")
    return re.sub(r"e([+-])0*(\d)", lambda m: "e" + m.group(1).replace("+", "") + m.group(2), f"{x:g}")


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
    meaning: str = ""

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
    meaning: str = ""
    unit: str = ""

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
    meaning: str = ""

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
    """true or false."""
    default: Any = None
    required: bool = False
    meaning: str = ""

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
    meaning: str = ""

    def words(self) -> str:
        n = f"{self.min_len}" if self.min_len == self.max_len else f"{self.min_len} to {self.max_len}"
        return f"a list of {n} entries, each {self.item.words()}"

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
    meaning: str = ""

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
    """A table of known ``fields`` (name -> field type or nested Table); any other key is refused unless ``extra``
    admits it (then it is passed through as written, for its reader to check)."""
    fields: dict
    default: Any = None
    required: bool = False
    extra: Callable[[str], bool] | None = None   # keys checked elsewhere (e.g. a sub-table of its own)
    meaning: str = ""

    def words(self) -> str:
        return "a table"

    def check(self, v: Any, path: str, file: str | None) -> dict:
        return check_table(v, self, path, file)


@dataclass(frozen=True)
class OneOrList:
    """One ``item`` or a list of ``min_len`` to ``max_len`` of them (``distinct``: no repeats), read as a tuple:
    the torques of every case kind (one analysis per torque)."""
    item: Num
    min_len: int = 1
    max_len: int = 100
    distinct: bool = False
    default: Any = None
    required: bool = False
    meaning: str = ""

    def words(self) -> str:
        return (f"{self.item.words()}, or a list of {self.min_len} to {self.max_len} "
                + ("distinct such numbers (one analysis each)" if self.distinct else "such numbers"))

    def check(self, v: Any, path: str, file: str | None) -> tuple:
        if not isinstance(v, list):
            return (self.item.check(v, path, file),)
        out = List(self.item, self.min_len, self.max_len).check(v, path, file)
        if self.distinct and len(set(out)) != len(out):
            raise CaseError(path, v, "distinct values (each is one analysis)", file)
        return tuple(out)


def _header(path: str) -> str:
    """``chain[0].element`` -> ``chain.element``: the TOML header of a list of tables."""
    return re.sub(r"\[\d+\]", "", path)


@dataclass(frozen=True)
class TableList:
    """A list of ``min_len`` to ``max_len`` tables of one spec (TOML ``[[name]]``); entry i is ``name[i]``."""
    item: Any                      # Table or Tagged
    min_len: int = 1
    max_len: int = 1000
    default: Any = None
    required: bool = False
    meaning: str = ""

    def words(self) -> str:
        return f"{self.min_len} to {self.max_len} tables"

    def check(self, v: Any, path: str, file: str | None) -> list:
        what = f"{self.min_len} to {self.max_len} [[{_header(path)}]] tables"
        if not isinstance(v, list):
            raise CaseError(path, v, f"wrong type {type(v).__name__}; {what}", file)
        if not self.min_len <= len(v) <= self.max_len:
            raise CaseError(path, f"{len(v)} tables", what, file)
        return [self.item.check(x, f"{path}[{i}]", file) for i, x in enumerate(v)]


@dataclass(frozen=True)
class Tagged:
    """A table whose string key ``tag`` picks its spec among ``tables`` (tag value -> Table, each declaring the
    tag itself), e.g. a drive-train member of kind torsion, shaft, mesh or ball_spline."""
    tag: str
    tables: dict
    default: Any = None
    required: bool = False
    meaning: str = ""

    def words(self) -> str:
        return f"a table with {self.tag} = one of " + ", ".join(repr(k) for k in self.tables)

    def check(self, v: Any, path: str, file: str | None) -> dict:
        if not isinstance(v, dict):
            raise CaseError(path, v, f"wrong type {type(v).__name__}; {self.words()}", file)
        t = v.get(self.tag)
        if not isinstance(t, str) or t not in self.tables:
            raise CaseError(f"{path}.{self.tag}", t, "one of " + ", ".join(repr(k) for k in self.tables), file)
        return check_table(v, self.tables[t], path, file)


def check_value(spec, v: Any, path: str, file: str | None) -> Any:
    return spec.check(v, path, file)


#: a table with more keys than this names the closest ones and points to ``ltca keys`` instead of listing them all
LISTED_KEYS = 12


def _unknown_key(key: str, spec: Table, path: str) -> str:
    """The message for an unknown key: every allowed key of a small table; else the closest and where all are."""
    names = sorted(spec.fields)
    if len(names) <= LISTED_KEYS:
        return f"unknown key; allowed: {', '.join(names)}"
    close = difflib.get_close_matches(key, names, n=3, cutoff=0.5)
    hint = f"did you mean {' or '.join(close)}? " if close else ""
    where = f"in [{path}]" if path else "at the top level"
    return f"unknown key; {hint}{len(names)} keys are allowed {where} (`ltca keys` lists them)"


def check_table(raw: Any, spec: Table, path: str, file: str | None) -> dict:
    """Validate ``raw`` against ``spec``; returns a dict with every field (defaults filled in) and the keys its
    ``extra`` admits (as written, checked by their reader)."""
    label = path or "case file"
    if not isinstance(raw, dict):
        raise CaseError(label, raw, f"wrong type {type(raw).__name__}; a table", file)
    for k in raw:
        if k not in spec.fields and not (spec.extra and spec.extra(k)):
            raise CaseError(f"{path}.{k}" if path else k, raw[k], _unknown_key(str(k), spec, path), file)
    out = {}
    for k, f in spec.fields.items():
        p = f"{path}.{k}" if path else k
        if k not in raw:
            if f.required:
                what = (f"a [{p}] table" if isinstance(f, (Table, Tagged)) else f.words() if not
                        isinstance(f, TableList) else f"{f.min_len} to {f.max_len} [[{_header(p)}]] tables")
                raise CaseError(p, None, f"required; {what}", file)
            # an absent table is its defaults, or None when it has required keys (an optional table of its own)
            fill = isinstance(f, Table) and f.default is None and not any(v.required for v in f.fields.values())
            out[k] = check_table({}, f, p, file) if fill else f.default
            continue
        out[k] = f.check(raw[k], p, file)
    out.update((k, v) for k, v in raw.items() if k not in spec.fields)     # the extra keys, as written
    return out


def words(spec) -> str:
    return spec.words()


# ------------------------------------------------------------------------------- reference and JSON Schema #
_TYPE_NAMES = {"Num": "number", "Int": "integer", "Str": "string", "Bool": "boolean", "List": "list",
               "ToothMap": "table", "Table": "table", "OneOrList": "number or list", "TableList": "list of tables",
               "Tagged": "table"}


def _unit(f) -> str:
    inner = getattr(f, "item", None) or getattr(f, "value", None)
    return getattr(f, "unit", "") or (getattr(inner, "unit", "") if inner is not None else "") or "-"


def _default_text(f) -> str:
    if f.required:
        return "required"
    if f.default is None:
        return "derived"
    return str(f.default).lower() if isinstance(f.default, bool) else repr(f.default)


def _row(table: str, key: str, f, array: bool, allowed_prefix: str = "") -> dict:
    return dict(table=table, key=key, type=_TYPE_NAMES[type(f).__name__], unit=_unit(f), default=_default_text(f),
                allowed=allowed_prefix + f.words(), meaning=f.meaning or "-", array=array)


def _is_section(f) -> bool:
    """A nested table documented as a section of its own (a free-form table: one row ``*``)."""
    return isinstance(f, (TableList, Tagged, Table))


def table_reference(spec: Table, prefix: str = "", array: bool = False) -> list[dict]:
    """Every key a Table accepts, walked depth first: one dict per key with ``table`` (dotted, e.g.
    ``pinion.modifications``; ``chain.element`` for a list of tables, ``array`` True), ``key``, ``type``, ``unit``,
    ``default`` ("required", "derived" or the value), ``allowed`` (the field's words) and ``meaning``.

    The rows of a table come before those of its sub-tables; a table picked by a tag (:class:`Tagged`) lists the
    union of its variants' keys, each key's ``allowed`` naming the variants it belongs to when not all."""
    rows: list[dict] = []
    subs: list[tuple[str, Any]] = []
    if spec.extra is not None and prefix:          # a (partly) free-form table: its other keys are its reader's
        rows.append(dict(table=prefix, key="*", type="any", unit="-", default="none", allowed="keys and values "
                         "its reader checks (see the meaning)", meaning=spec.meaning or "-", array=array))
    for k, f in spec.fields.items():
        p = f"{prefix}.{k}" if prefix else k
        if _is_section(f):
            subs.append((p, f))
        else:
            rows.append(_row(prefix, k, f, array))
    for p, f in subs:
        if isinstance(f, TableList):
            rows += _section_rows(f.item, p, True)
        else:
            rows += _section_rows(f, p, False)
    return rows


def _section_rows(f, path: str, array: bool) -> list[dict]:
    if isinstance(f, Table):
        return table_reference(f, path, array)
    # Tagged: the union of the variants' keys
    merged: dict[str, tuple[Any, list[str]]] = {}
    for tag, t in f.tables.items():
        for k, sub in t.fields.items():
            if k == f.tag:
                continue
            merged.setdefault(k, (sub, []))[1].append(tag)
    tags = list(f.tables)
    rows = [dict(table=path, key=f.tag, type="string", unit="-", default="required", allowed=f.words()
                 .replace(f"a table with {f.tag} = ", ""), meaning=f.meaning or "the kind of table, which sets its "
                 "other keys", array=array)]
    for k, (sub, where) in merged.items():
        pre = "" if where == tags else f"({f.tag} " + " or ".join(repr(w) for w in where) + ") "
        rows.append(_row(path, k, sub, array, pre))
    return rows


def table_keys(spec: Any, prefix: str = "") -> set[str]:
    """Every dotted key a spec accepts (lists of tables without indices: ``chain.element.teeth``)."""
    if isinstance(spec, TableList):
        return table_keys(spec.item, prefix)
    if isinstance(spec, Tagged):
        return {f"{prefix}.{spec.tag}" if prefix else spec.tag} | set().union(
            *(table_keys(t, prefix) for t in spec.tables.values()))
    out: set[str] = {f"{prefix}.*"} if spec.extra is not None and prefix else set()
    for k, f in spec.fields.items():
        p = f"{prefix}.{k}" if prefix else k
        out |= table_keys(f, p) if _is_section(f) else {p}
    return out


def json_schema(spec: Any, title: str | None = None) -> dict:
    """A JSON Schema (draft 4, the draft the Taplo TOML toolkit reads) of a spec, for editors that complete and check
    TOML against one (Taplo, the Even Better TOML extension: a first line ``#:schema FILE.json`` in the case):
    types, ranges, choices, required keys, no unknown keys."""
    out = _schema(spec)
    if title is not None:
        out = {"$schema": "http://json-schema.org/draft-04/schema#", "title": title, **out}
    return out


def _schema(f: Any) -> dict:
    d: dict[str, Any] = {}
    if getattr(f, "meaning", ""):
        d["description"] = f.meaning
    if isinstance(f, Num):
        d |= {"type": "number", "minimum": f.lo, "maximum": f.hi}
        d |= ({"exclusiveMinimum": True} if f.lo_open else {}) | ({"exclusiveMaximum": True} if f.hi_open else {})
    elif isinstance(f, Int):
        d |= {"type": "integer", "minimum": f.lo, "maximum": f.hi}
    elif isinstance(f, Str):
        d |= {"type": "string"} | ({"enum": list(f.choices)} if f.choices else {"maxLength": f.max_len}) | (
            {"minLength": 1} if f.non_empty else {})
    elif isinstance(f, Bool):
        d["type"] = "boolean"
    elif isinstance(f, List):
        d |= {"type": "array", "items": _schema(f.item), "minItems": f.min_len, "maxItems": f.max_len}
    elif isinstance(f, OneOrList):
        d["anyOf"] = [_schema(f.item), {"type": "array", "items": _schema(f.item), "minItems": f.min_len,
                                        "maxItems": f.max_len}]
    elif isinstance(f, ToothMap):
        d |= {"type": "object", "patternProperties": {"^(0|[1-9][0-9]{0,5})$": _schema(f.value)},
              "additionalProperties": False}
    elif isinstance(f, TableList):
        d |= {"type": "array", "items": _schema(f.item), "minItems": f.min_len, "maxItems": f.max_len}
    elif isinstance(f, Tagged):
        d |= {"type": "object", "required": [f.tag], "properties": {f.tag: {"enum": list(f.tables)}},
              "oneOf": [_schema(t) | {"properties": {**_schema(t)["properties"], f.tag: {"enum": [k]}}}
                        for k, t in f.tables.items()]}
    elif isinstance(f, Table):
        d |= {"type": "object", "properties": {k: _schema(v) for k, v in f.fields.items()},
              "additionalProperties": f.extra is not None}
        req = [k for k, v in f.fields.items() if v.required]
        if req:
            d["required"] = req
    else:
        raise TypeError(f"no JSON Schema for {type(f).__name__}")
    return d


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


#: the case kinds, each recognised by one of its top-level tables (in this order)
CASE_KINDS: dict[str, frozenset[str]] = {
    "bevel": frozenset({"bevel"}),
    "planetary": frozenset({"satellite"}),
    "study": frozenset({"study"}),
    "budget": frozenset({"budget", "member"}),
    "chain": frozenset({"chain", "workpiece"}),
    "cylindrical": frozenset({"gear_pair", "pinion", "gear"}),
}

#: the kinds a reader names when it is given a case of another kind, with the command that reads that kind
KINDS = {kind: (CASE_KINDS[kind], command) for kind, command in (
    ("cylindrical", "ltca run / ltca tca"), ("bevel", "ltca tca"), ("budget", "ltca budget"), ("chain", "ltca chain"))}


def kind_of(data, file: str | None = None) -> str:
    """The kind of a case given as TOML tables (the first kind in :data:`CASE_KINDS` whose table it has)."""
    for kind, tables in CASE_KINDS.items():
        if tables & set(data):
            return kind
    raise CaseError("file", "no case tables", "a case of one kind: " + "; ".join(
        f"{k} ([{'], ['.join(sorted(t))}])" for k, t in CASE_KINDS.items()), file)


def check_kind(data: dict, expected: str, file: str | None = None) -> None:
    """A case of another kind is named in one line (its tables are not dumped)."""
    found = [k for k, (keys, _) in KINDS.items() if keys & set(data)]
    if found and expected not in found:
        raise CaseError("file", f"a {found[0]} case", f"a {expected} case here; read it with "
                        f"`{KINDS[found[0]][1]}`", file)
