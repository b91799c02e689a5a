"""Sphinx extension of the ltca documentation: the pages generated from the repository's files at build time.

- ``_generated/validation_tables.md``: the reference figures and the CalculiX comparisons, read from the files of
  ``tests/reference/`` (never copied by hand), included by ``validation.md``;
- the check that ``case_keys.md`` is the output of ``ltca keys --markdown`` (a warning otherwise: with ``-W`` the
  build fails, as ``tests/ltca/test_keys.py`` does).
"""
from __future__ import annotations

import ast
import csv
import json
from pathlib import Path

from sphinx.util import logging

logger = logging.getLogger(__name__)

DOCS = Path(__file__).resolve().parents[1]
ROOT = DOCS.parent
REFERENCE = ROOT / "tests" / "reference"
GENERATED = DOCS / "_generated"


def _fmt(x, digits: int = 4) -> str:
    if x is None:
        return "-"
    if isinstance(x, str):
        return x
    return f"{x:.{digits}g}"


def _table(head: list[str], rows: list[list]) -> str:
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(str(c).replace("|", "\\|") for c in r) + " |" for r in rows]
    return "\n".join(lines) + "\n"


def _diff(ours, ref, relative: bool = True) -> str:
    if ours is None or ref is None or ref == 0:
        return "-"
    return f"{100 * (ours - ref) / abs(ref):+.1f} %" if relative else f"{ours - ref:+.3f}"


def _test_bounds(test_file: Path, name: str) -> dict:
    """A module-level dict literal (the bounds) of a test file, read without importing the test."""
    for node in ast.parse(test_file.read_text()).body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == name for t in node.targets):
            return ast.literal_eval(node.value)
    raise KeyError(f"{name} in {test_file}")


def _share_of(share: dict) -> str:
    """A per-pair share dict as '0.53 / 0.47' over the pairs that carry load."""
    keys = sorted((k for k, v in share.items() if v > 1e-3), key=int)
    return " / ".join(f"{share[k]:.3f}" for k in keys) or "-"


def fzg_reference() -> str:
    """The FZG C14 reference figures (GEARpie, Hertz) of fzg_c14.csv beside our closed forms of the same."""
    with open(REFERENCE / "fzg_c14.csv") as fh:
        rows = [r for r in csv.DictReader(line for line in fh if not line.startswith("#"))]
    out = ["### FZG C14 reference figures (`tests/reference/fzg_c14.csv`)\n",
           "Source: GEARpie (cfernandesFEUP/GEARpie, `REPORT/C14.txt`, MIT licence); p0 and b at the pitch point "
           "re-derived with the Hertz line-contact formulas of `hertz.md`.\n",
           _table(["quantity", "value", "unit"], [[r["quantity"], r["value"], r["unit"]] for r in rows])]
    return "\n".join(out)


def iso6336_table() -> str:
    """ISO 6336-1 Method B stiffness of the shipped cylindrical pairs, evaluated by ltca's implementation of
    ``iso6336_stiffness.md``, beside CalculiX's whole-gear single-pair stiffness where a frozen file has it."""
    from ltca.cases import load_case
    from ltca.cylindrical.iso6336 import iso6336_stiffness
    from ltca.cylindrical.model import build_model
    rows = []
    for name, ref in (("fzg_c14", "fzg_c14_calculix_whole.json"), ("helical_c14", "helical_c14_calculix_whole.json")):
        case = load_case(name)
        cp, cth = iso6336_stiffness(build_model(case.record))
        rec = json.loads((REFERENCE / ref).read_text())
        single = [p for p in rec["positions"] if p.get("contact") == "single"]
        ccx = single[0]["stiffness"] if single else None
        ours = single[0].get("ours_at_freeze", {}).get("stiffness") if single else None
        rows.append([case.name, _fmt(cp), _fmt(cth), _fmt(ccx), _fmt(ours)])
    return "\n".join([
        "### ISO 6336-1 tooth stiffness (`tests/reference/iso6336_stiffness.md`)\n",
        "c' and c'_th by Method B for the shipped pairs, beside the single-pair mesh stiffness of the whole-gear "
        "CalculiX model and ours at the single-contact pitch position (N/(mm um); '-' where the pair has no "
        "single-contact position). ISO's figures are empirical fits: an FE stiffness of a solid steel pair is "
        "expected between about c' and c'_th.\n",
        _table(["pair", "ISO c'", "ISO c'_th", "CalculiX (whole gears)", "ltca"], rows)])


def whole_gear_tables() -> str:
    """Every ``*_calculix_whole.json``: per position CalculiX's figures beside ours stored with it."""
    test = ROOT / "tests" / "ltca" / "verify" / "test_reference_calculix.py"
    bounds = _test_bounds(test, "BOUNDS")
    remeasured = _test_bounds(test, "ROOT_REMEASURED")
    out = ["### Cylindrical pairs against whole-gear CalculiX models\n",
           "Bounds of `tests/ltca/verify/test_reference_calculix.py` (relative; share absolute): "
           + ", ".join(f"{k} {v:g}" for k, v in bounds.items()) + ". The test compares ltca's live figures with "
           "CalculiX's converged estimate; the tables show the finest CalculiX model of each file beside ltca's "
           "figures stored with it (`ours_at_freeze`); a difference outside its bound is a strict expected failure "
           "of that test, naming the numbers. The root stresses are compared live only (their stored figures "
           "predate the fillet read-out).\n"]
    quantities = (("te", "loaded TE [arcsec]"), ("stiffness", "mesh stiffness [N/(mm um)]"),
                  ("flank_pressure", "flank peak pressure [MPa]"))

    def within(q, ours, ref):
        return "yes" if abs(ours - ref) <= bounds[q] * abs(ref) else "no"

    for path in sorted(REFERENCE.glob("*_calculix_whole.json")):
        rec = json.loads(path.read_text())
        unconverged = rec.get("unconverged") or {}
        rows = []
        for p in rec["positions"]:
            ours = p.get("ours_at_freeze") or {}
            where = [_fmt(p["roll_deg"], 3), p.get("contact", "-")]
            for q, label in quantities:
                if q not in p:
                    continue
                if q in unconverged:
                    rows.append(where + [label, _fmt(p[q]), "-", "-", "CalculiX not converged: not compared"])
                elif q in ours:
                    rows.append(where + [label, _fmt(p[q]), _fmt(ours[q]), _diff(ours[q], p[q]),
                                         within(q, ours[q], p[q])])
                else:
                    rows.append(where + [label, _fmt(p[q]), "-", "-", "-"])
            if "share" in p and ours.get("share"):
                worst = max(abs(ours["share"].get(k, 0.0) - v) for k, v in p["share"].items())
                rows.append(where + ["load share per pair", _share_of(p["share"]), _share_of(ours["share"]),
                                     f"{worst:+.3f}", "yes" if worst <= bounds["share"] else "no"])
            for member in ("pinion", "gear"):
                if "root_stress" in p:
                    live = f"root_{member}" in remeasured
                    rows.append(where + [f"root stress {member} [MPa]", _fmt(p["root_stress"][member]["max"]),
                                         "live" if live else "-", "-", "-"])
        out += [f"#### `{path.name}`: `{rec['case']}` at {rec['torque_nm']:g} N m\n",
                f"CalculiX: {rec.get('calculix_version', '-')}, {rec.get('date', 'date not recorded')}; "
                f"model: {rec.get('model', 'whole gears, every tooth')}; made by `{rec['command']}`.\n",
                _table(["roll [deg]", "contact", "quantity", "CalculiX", "ltca", "difference", "within bound"],
                       rows)]
    return "\n".join(out)


def bevel_table() -> str:
    rec = json.loads((REFERENCE / "spiral_bevel_calculix.json").read_text())
    b = rec["bounds"]
    rows = []
    for r in rec["rows"]:
        o, c = r["ours"], r["ccx"]
        rows += [[_fmt(r["fraction"], 3), "loaded TE [arcsec]", _fmt(c["theta"]), _fmt(o["theta"]),
                  _diff(o["theta"], c["theta"])],
                 [_fmt(r["fraction"], 3), "torque share per pair", _share_of(c["share"]), _share_of(o["share"]),
                  f"{r['share_err']:+.3f}"],
                 [_fmt(r["fraction"], 3), "interior peak pressure [MPa]", _fmt(c["p_interior"]),
                  _fmt(o["p_interior"]), _diff(o["p_interior"], c["p_interior"])]]
    return "\n".join([
        "### Spiral bevel pair against CalculiX (`spiral_bevel_calculix.json`)\n",
        f"`{rec['case']}` at {rec['torque_nm']:g} N m; CalculiX: {rec['calculix_version']}, {rec['date']}; model: "
        f"{rec['model']}; made by `{rec['command']}`. Bounds: TE {b['te_rel']:g} relative, share {b['share_abs']:g}, "
        f"pressure {b['pressure_rel']:g} relative. Position in mesh cycles from the mean point.\n",
        _table(["position [cycles]", "quantity", "CalculiX", "ltca", "difference"], rows)])


def planetary_table() -> str:
    rec = json.loads((REFERENCE / "eccentric_planetary_calculix.json").read_text())
    b = rec["bounds"]
    rows = []
    for r in rec["rows"]:
        o, c = r["ours"], r["ccx"]
        rows += [[_fmt(r["phi_deg"], 3), "loaded TE [um on the line of action]", _fmt(c["te_um"]), _fmt(o["te_um"]),
                  _diff(o["te_um"], c["te_um"])],
                 [_fmt(r["phi_deg"], 3), "pairs carrying load", c["loaded_pairs"], o["loaded_pairs"], "-"],
                 [_fmt(r["phi_deg"], 3), "load share per pair", _share_of(c["share"]), _share_of(o["share"]),
                  f"{r['share_diff']:+.3f}"]]
    return "\n".join([
        "### Eccentric planetary satellite against CalculiX (`eccentric_planetary_calculix.json`)\n",
        f"`{rec['case']}` at {rec['torque_nm']:g} N m on the satellite; CalculiX: {rec['calculix_version']}, "
        f"{rec['date']}; model: {rec['model']}; made by `{rec['command']}`. Bounds: TE {b['te_rel']:g} relative, "
        f"share {b['share_abs']:g}.\n",
        _table(["satellite position [deg]", "quantity", "CalculiX", "ltca", "difference"], rows)])


def write_validation() -> Path:
    GENERATED.mkdir(exist_ok=True)
    text = "\n".join([fzg_reference(), iso6336_table(), whole_gear_tables(), bevel_table(), planetary_table()])
    path = GENERATED / "validation_tables.md"
    if not path.is_file() or path.read_text() != text:
        path.write_text(text)
    return path


def check_case_keys() -> None:
    from ltca.keys import keys_markdown
    if (DOCS / "case_keys.md").read_text() != keys_markdown():
        logger.warning("docs/case_keys.md is not the output of `ltca keys --markdown`: regenerate it with "
                       "`ltca keys --markdown > docs/case_keys.md`")


def _builder_inited(app) -> None:
    write_validation()
    check_case_keys()


def setup(app):
    app.connect("builder-inited", _builder_inited)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
