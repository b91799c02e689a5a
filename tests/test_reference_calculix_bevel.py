"""Our bevel LTCA against the frozen CalculiX reference of the spiral bevel pair (issue 13), without ccx at test time.

``tests/reference/spiral_bevel_calculix*.json`` are computed by ``ltca validate --reference calculix
--case cases/spiral_bevel_cao2008.toml [--torque NM] --threads 1 --freeze FILE`` at the middle torque, 175 N m
(command, CalculiX version, date, mesh sizes, deck hashes and the contact-zone refinement stored in each): whole
members built apart from our body (gmsh OCC solids, every tooth), pinion bore on a rigid body under the torque,
gear back face fixed, penalty contact, both members held at the case's [mounting].  Bounds (issue 13): loaded TE
(loaded minus unloaded, arcsec of the gear) 3 %, torque share per pair 0.03, interior peak flank pressure 5 %.

phi1 = 0, before the deck fix (pinion band slave everywhere): nodal max 297 GPa at 200 um, TE 98.0/108.6/86.7 arcsec
at 450/300/200 um, shares 0.12/0.88 (ours 111.3, 0.26/0.74). After (gear tip-corner pair, edge lines refined,
:mod:`ltca.verify.bevel_ccx`): TE 112.03/112.62/112.86 (ours 111.46, -1.25 %), shares 0.258/0.742 (ours
0.259/0.741), nodal max 2.7/3.2/3.4 GPa at the pinion's top edge, torque balance 0.998-1.000. phi1 = 0.4 (300 um):
TE 99.19 (ours -1.53 %), shares 0.492/0.508. Interior peak pressure: ours +8.2 % (phi1 0) and +11.2 % (0.4) of
CalculiX (1519, 1464 MPa; CalculiX's own not converged: 1361/1550/1519 MPa over the ladder): strict xfails. Extended
ladder at phi1 = 0 (not frozen: one freeze reruns every rung, ~25 min each on the shared machine; run by
:func:`ltca.verify.bevel_ccx.solve_bevel_ccx`, read by :mod:`ltca.verify.bevel_ccx_read`): 133 / 89 um, 104057 /
122536 nodes, 1427 / 1828 s, TE 112.99 / 113.06. The interior peak's read-out had passed a single nodal spike as a
peak (133 um, pair -1: 1924 MPa, neighbours 1309/1095/968, ours 983 there): now passed over. Read like-with-like
(same interior mask both sides), pair 0's Hertz ellipse, where ours' peak lies (L1 83.2 mm, Rn1 -0.1 mm), reads 1528
/ 1552 MPa fitted (nodal max 1578 / 1579): converged within 1.6 %; ours 1644 is +5.9 %. The flank's interior maximum
at 89 um is 1568 (fitted, pair -1, L1 73.3 Rn1 2.2, 2.3 mm from the toe, where ours has no contact: 1 mm from the
133 um spike, not a like-with-like peak): +4.8 %.  Along pair 0's major axis ours and CalculiX agree within 3 % beyond
2 mm of the centre and ours is 5-7 % higher over the central +-1.6 mm; line Hertz from ours' line load (800 N/mm, R'
11.3 mm) gives 1595 MPa, between the two. No single-pair position at 175 N m: ours' largest pair share over a cycle
is 0.752 (phi1 -0.05 pitch); at 35 N m pair 0 carries all at -0.15..-0.05 (a light reference there is not frozen
yet).
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from conftest import ROOT

REFERENCES = sorted((Path(__file__).resolve().parent / "reference").glob("spiral_bevel_calculix*.json"))
BOUNDS = {"te_rel": 0.03, "share_abs": 0.03, "pressure_rel": 0.05}
_LM: dict = {}


def _rec(name: str) -> dict:
    return json.loads(next(p for p in REFERENCES if p.stem == name).read_text())


def _ours(name: str, fraction: float) -> dict:
    from ltca.verify.bevel_calculix import bevel_model, ours_at
    rec = _rec(name)
    if rec["case"] not in _LM:
        _LM[rec["case"]] = bevel_model(str(ROOT / rec["case"]))[1]
    lm = _LM[rec["case"]]
    import numpy as np
    return ours_at(lm, fraction * 2 * np.pi / lm.pair.blank.pinion.z, rec["torque_nm"])


@pytest.mark.parametrize("name", [p.stem for p in REFERENCES])
def test_reference_records_its_provenance(name):
    rec = _rec(name)
    assert "Version" in rec["calculix_version"] and rec["date"]
    assert rec["command"].startswith("ltca validate --reference calculix")
    assert rec["bounds"] == BOUNDS
    assert len(rec["refinement"]) >= 3, "a frozen reference needs its two-level contact refinement"
    for r in rec["rows"]:
        c = r["ccx"]
        assert len(c["deck_sha256"]) == 64 and c["nodes"] > 0 and c["elements"] > 0 and c["h_zone_um"] > 0
        # pair torques from each pair's total force at its pressure centroid (nodal pressures, not area-weighted):
        # within 10 % of the pinion torque; the shares are normalised by their sum
        assert abs(c["torque_balance"] - 1) < 0.1, "CalculiX pair torques do not add up to the pinion torque"


def converged_pressure(name: str, index: int) -> float:
    """CalculiX's interior peak at a row: at the ladder's position, where its last three rungs (refined by 1.5)
    converge in the asymptotic range, the Richardson extrapolation with the observed order
    (:func:`ltca.verify.calculix.richardson`, as the cylindrical references); otherwise the row's own rung."""
    from ltca.verify.calculix import richardson
    rec = _rec(name)
    row, ladder = rec["rows"][index], rec["refinement"]
    if index != 0 or len(ladder) < 3:
        return row["ccx"]["p_interior"]
    est = richardson([e["p_interior"] for e in ladder[-3:]], 1.5)
    return row["ccx"]["p_interior"] if est is None else est[0]


def _known_out(name: str) -> dict:
    """(position index, quantity) -> the measured disagreement, for the checks the frozen reference records as
    outside the issue's bounds (``rows[i]["ok"]`` false): they stay strict xfails naming the numbers, not
    loosened bounds, until the LTCA (or the reference) changes."""
    out = {}
    for i, r in enumerate(_rec(name)["rows"]):
        if abs(r["te_err_pct"]) > 100 * BOUNDS["te_rel"]:
            out[(i, "te")] = f"TE ours {r['ours']['theta']:.2f} vs CalculiX {r['ccx']['theta']:.2f} arcsec"
        if r["share_err"] > BOUNDS["share_abs"]:
            out[(i, "share")] = f"share ours {r['ours']['share']} vs CalculiX {r['ccx']['share']}"
        p_ref = converged_pressure(name, i)
        if not abs(r["ours"]["p_interior"] / p_ref - 1) <= BOUNDS["pressure_rel"]:
            out[(i, "pressure")] = f"p ours {r['ours']['p_interior']:.0f} vs CalculiX {p_ref:.0f} MPa"
    return out


def _cases():
    out = []
    for p in REFERENCES:
        known = _known_out(p.stem)
        for i, r in enumerate(_rec(p.stem)["rows"]):
            for q in ("te", "share", "pressure"):
                marks = [pytest.mark.xfail(strict=True, reason=known[(i, q)])] if (i, q) in known else []
                tag = p.stem[len("spiral_bevel_calculix_"):] or "middle"
                out.append(pytest.param(p.stem, i, q, marks=marks, id=f"{tag}{r['fraction']:+.2f}-{q}"))
    return out


@pytest.mark.parametrize("name,index,quantity", _cases())
def test_ours_against_frozen_calculix(name, index, quantity):
    """Loaded TE within 3 %, pair torque shares within 0.03, interior peak pressure within 5 % of CalculiX."""
    ref = _rec(name)["rows"][index]
    o = _ours(name, ref["fraction"])
    c = ref["ccx"]
    if quantity == "te":
        assert o["theta"] == pytest.approx(c["theta"], rel=BOUNDS["te_rel"])
    elif quantity == "share":
        for j in set(o["share"]) | {int(k) for k in c["share"]}:
            assert abs(o["share"].get(j, 0.0) - c["share"].get(str(j), 0.0)) <= BOUNDS["share_abs"]
    else:
        assert o["p_interior"] == pytest.approx(converged_pressure(name, index), rel=BOUNDS["pressure_rel"])


@pytest.mark.slow
@pytest.mark.calculix
def test_regenerated_reference_matches_stored(tmp_path):
    """Rerun CalculiX at the reference's coarsest rung at its first position: the same TE (0.5 %) and shares."""
    import shutil
    if shutil.which("ccx") is None:
        pytest.skip("CalculiX (ccx) missing")
    import numpy as np
    from ltca.verify.bevel_ccx import BevelCcxSettings, solve_bevel_ccx
    from ltca.verify.bevel_calculix import bevel_model, mounted
    rec = _rec("spiral_bevel_calculix")
    case, lm, _ = bevel_model(str(ROOT / rec["case"]))
    first = rec["refinement"][0]
    f = rec["rows"][0]["fraction"]
    c = solve_bevel_ccx(lm, f * 2 * np.pi / lm.pair.blank.pinion.z, rec["torque_nm"] * 1e3,
                        mounted(BevelCcxSettings(h_zone=1e-3 * first["h_zone_um"]), case, lm), tmp_path / "ccx",
                        cache=str(tmp_path), say=lambda m: None)
    assert c.theta_arcsec == pytest.approx(first["theta"], rel=0.005)
    for j, s in first["share"].items():
        assert abs(c.share.get(int(j), 0.0) - s) < 0.005
