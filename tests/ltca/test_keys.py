"""``ltca keys`` and docs/case_keys.md cover every case kind: each kind with a declared Table has a section, and every
key its Table accepts (walked independently with ``table_keys``) has a row there; the JSON Schema of each kind
accepts the shipped cases of that kind (checked by the ``jsonschema`` package) and refuses a value out of range and
an unknown key, as the Table does."""
from __future__ import annotations

import copy
import json

import pytest
import tomllib

from fixtures.paths import CASES, ROOT
from ltca.cli import main
from ltca.errors import CaseError
from ltca.keys import KINDS, keys_markdown, kind_json_schema, kind_schema, kinds
from ltca.validation import Int, Num, OneOrList, Str, Table, TableList, Tagged, check_table, table_keys, table_reference


def _sections(markdown: str) -> dict[str, set[str]]:
    """kind -> the dotted keys its section documents (``table.key``; lists of tables without brackets)."""
    out: dict[str, set[str]] = {}
    kind = table = None
    for line in markdown.splitlines():
        if line.startswith("## "):
            kind = line[3:].strip()
            out[kind] = set()
        elif line.startswith("### "):
            table = line[4:].strip().strip("[]")
        elif line.startswith("| `") and kind is not None:
            out[kind].add(f"{table}.{line.split('`')[1]}")
    return out


def _missing(accepted: set[str], documented: set[str]) -> set[str]:
    """Accepted keys without a row; ``T.*`` (a free-form table) is covered by any row of table T."""
    return {k for k in accepted if k not in documented and not (
        k.endswith(".*") and any(d.rpartition(".")[0] == k[:-2] for d in documented))}


def test_every_kind_and_every_accepted_key_is_documented():
    docs = (ROOT / "docs" / "case_keys.md").read_text()
    assert docs == keys_markdown(), "docs/case_keys.md is stale: regenerate with `ltca keys --markdown`"
    sections = _sections(docs)
    declared = kinds()
    assert set(declared) >= set(KINDS) - {"planetary"}          # planetary: once its reader declares a Table
    assert list(sections) == declared
    for kind in declared:
        accepted = table_keys(kind_schema(kind))
        assert accepted and not _missing(accepted, sections[kind]), (kind, _missing(accepted, sections[kind]))
    # the check is not vacuous: a key added to a schema without its row is caught
    cyl = kind_schema("cylindrical")
    grown = Table({**cyl.fields, "lubricant": Table({"viscosity_cst": Num(1, 1e4, "cSt")})})
    assert _missing(table_keys(grown), sections["cylindrical"]) == {"lubricant.viscosity_cst"}


def test_keys_command_filters_by_kind_and_table(capsys):
    assert main(["keys", "member", "--kind", "budget"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("# budget") and "[[member]]" in out and "stiffness_Nm_per_deg" in out
    assert "(kind 'shaft') a number in [100, 5e5] MPa" in out
    assert main(["keys", "load"]) == 0
    out = capsys.readouterr().out
    assert "# cylindrical" in out and "# bevel" in out and "# budget" not in out
    assert main(["keys", "--kind", "gearbox"]) == 2
    assert "'--kind'" in capsys.readouterr().err
    assert main(["keys", "pinion", "--kind", "chain"]) == 2
    assert "'TABLE'" in capsys.readouterr().err


def test_table_reference_rows():
    spec = Table({"a": Num(0, 1, "mm", required=True, meaning="first"), "b": Int(1, 9, default=3),
                  "s": Table({"c": Str(("x", "y"), default="x")}),
                  "l": TableList(Table({"d": OneOrList(Num(0, 5, "N m"), 1, 3)}), 1, 4)})
    rows = {(r["table"], r["key"]): r for r in table_reference(spec)}
    assert list(rows) == [("", "a"), ("", "b"), ("s", "c"), ("l", "d")]
    assert rows["", "a"] | {} == dict(table="", key="a", type="number", unit="mm", default="required",
                                      allowed="a number in [0, 1] mm", meaning="first", array=False)
    assert rows["", "b"]["default"] == "3" and rows["s", "c"]["allowed"] == "one of 'x', 'y'"
    assert rows["l", "d"]["array"] and rows["l", "d"]["type"] == "number or list"
    assert table_keys(spec) == {"a", "b", "s.c", "l.d"}


def test_table_list_and_tagged_name_the_entry():
    member = Tagged("kind", {"spring": Table({"kind": Str(("spring",)), "k": Num(1, 10, required=True)}),
                             "mass": Table({"kind": Str(("mass",)), "m": Num(1, 10, required=True)})})
    spec = Table({"member": TableList(member, 1, 2, required=True)})
    assert check_table({"member": [{"kind": "mass", "m": 2}]}, spec, "", None)["member"] == [{"kind": "mass",
                                                                                               "m": 2.0}]
    for raw, field, words in (({"member": []}, "member", "1 to 2 [[member]] tables"),
                              ({}, "member", "required; 1 to 2 [[member]] tables"),
                              ({"member": [{"kind": "mass", "m": 2}, {"kind": "spring"}]}, "member[1].k", "required"),
                              ({"member": [{"kind": "gas"}]}, "member[0].kind", "one of 'spring', 'mass'"),
                              ({"member": [{"kind": "mass", "m": 2, "k": 3}]}, "member[0].k", "unknown key")):
        with pytest.raises(CaseError) as exc:
            check_table(raw, spec, "", "f.toml")
        assert exc.value.field == field and words in str(exc.value), str(exc.value)


def _shipped() -> list[tuple[str, str, dict]]:
    from ltca.cases import kind_of
    out = []
    for p in sorted([*CASES.glob("*.toml"), *(ROOT / "studies").glob("*.toml")]):
        data = tomllib.loads(p.read_text())
        out.append((p.name, kind_of(data), data))
    return out


def test_json_schema_accepts_the_shipped_cases_and_refuses_what_the_table_refuses(capsys):
    jsonschema = pytest.importorskip("jsonschema")
    seen = set()
    for name, kind, data in _shipped():
        if kind_schema(kind) is None:
            continue
        schema = kind_json_schema(kind)
        jsonschema.Draft4Validator.check_schema(schema)
        validator = jsonschema.Draft4Validator(schema)
        errors = [e.message for e in validator.iter_errors(data)]
        assert not errors, (name, errors[:3])
        seen.add(kind)
    assert seen >= {"cylindrical", "bevel", "budget", "chain", "study"}
    fzg = tomllib.loads((CASES / "fzg_c14.toml").read_text())
    validator = jsonschema.Draft4Validator(kind_json_schema("cylindrical"))
    bad = copy.deepcopy(fzg)
    bad["pinion"]["teeth"] = 4                                    # the Table's range: [5, 1000]
    assert any("minimum" in e.message or "less than" in e.message for e in validator.iter_errors(bad))
    bad = copy.deepcopy(fzg)
    bad["assembly"]["backlash_um"] = 30                           # unknown key
    assert any("backlash_um" in e.message for e in validator.iter_errors(bad))
    bad = copy.deepcopy(fzg)
    bad["material"]["poisson_ratio"] = 0.5                        # [0, 0.5): the open end
    assert list(validator.iter_errors(bad))
    bad = copy.deepcopy(fzg)
    bad["pinion"]["modifications"] = {"pitch_errors_um": {"01": 5.0}}   # a tooth index with a leading zero
    assert list(validator.iter_errors(bad))
    bad["pinion"]["modifications"] = {"pitch_errors_um": {"1": 5.0}}
    assert not list(validator.iter_errors(bad))
    budget = tomllib.loads((CASES / "budget_wang.toml").read_text())
    budget["member"][1]["shear_modulus_MPa"] = 8e4                # a shaft's key on a torsion member
    assert list(jsonschema.Draft4Validator(kind_json_schema("budget")).iter_errors(budget))
    assert main(["keys", "--json-schema", "chain"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert printed["title"] == "ltca chain case" and printed["required"] == ["workpiece", "chain"]


def test_json_schema_of_each_kind_has_every_key():
    def props(s: dict, prefix: str = "") -> set[str]:
        out = set()
        s = s.get("items", s)
        for alt in s.get("oneOf", [s]):
            for k, v in alt.get("properties", {}).items():
                p = f"{prefix}.{k}" if prefix else k
                v = v.get("items", v) if v.get("type") == "array" and "properties" in v.get("items", {}) else v
                out |= props(v, p) if ("properties" in v or "oneOf" in v) else {p}
        return out
    for kind in kinds():
        if kind == "design":
            continue
        expected = {k for k in table_keys(kind_schema(kind)) if not k.endswith(".*")}
        got = props(kind_json_schema(kind))
        assert expected <= got, (kind, expected - got)


def test_planetary_kind_is_listed_from_its_schema():
    """The planetary reader's Table (``ltca.planetary.case.CASE``) is the one ``ltca keys`` walks."""
    from ltca.planetary.case import CASE
    assert "planetary" in kinds() and kind_schema("planetary") is CASE
    md = keys_markdown(only=["planetary"])
    assert "## planetary" in md and "satellite" in md


def test_one_torque_parser():
    """A torque or a list of them (OneOrList): one field type for every kind, the ranges of each kind's Table."""
    from ltca.case import check_torques
    assert check_torques(200) == (200.0,) and check_torques([100, 200.5]) == (100.0, 200.5)
    for bad, field, words in (([100, 100], "load.torque_nm", "distinct"), ([100, 2e6], "load.torque_nm[1]",
                                                                           "[1e-3, 1e6] N m"),
                              ([], "load.torque_nm", "a list of 1 to 100 entries"), ("100", "load.torque_nm",
                                                                                     "wrong type str")):
        with pytest.raises(CaseError) as exc:
            check_torques(bad)
        assert exc.value.field == field and words in str(exc.value), str(exc.value)
    spec = OneOrList(Num(0, 1e6, "N m", lo_open=True), 1, 3)
    assert spec.check([1, 1], "t", None) == (1.0, 1.0)            # repeats allowed unless distinct
