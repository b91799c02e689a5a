"""Ours against frozen whole-gear CalculiX references (issue 18), without ccx at test time.

The references ``tests/reference/*_calculix_whole.json`` were computed by ``ltca validate --reference
calculix-whole ... --freeze FILE`` (the command is stored in each file, with the CalculiX version, the
deck hashes, the mesh sizes, nodes, elements, wall times and the refinement ladder that checks their
convergence): whole gears with every tooth built apart from our body (``fem.solids.full_gear``), the
gear's bore fixed, the pinion's bore on a rigid body turning under the torque, penalty contact.

Bounds (issue 18): loaded TE and mesh stiffness 2 %, load share 0.03, the flank peak pressure away from
the face ends and edge contact 5 % (like with like: ours is ``max_flank_pressure_mpa``'s per-position
value, CalculiX's the elliptic-fit peak over the face slices but the end ones), the root stress of each
member 5 % (both: largest principal stress on the loaded teeth's tension-side fillets, ``|z| <= 0.45 b``).
The reference figure is CalculiX's converged estimate: where a position's last three rungs refine the contact
band by the same ratio (1.5) and converge in the asymptotic range (monotone, shrinking steps, observed order in
[0.5, 4]), the Richardson extrapolation with the observed order, its uncertainty Roache's grid convergence index
(GCI, safety 1.25); elsewhere the finest rung (:func:`converged_estimate`).
A file that does not record a quantity (the bore-20 variant was frozen before the root stress and the
flank peak were read) is not compared in it. Where the figures we had when a reference was frozen
(``ours_at_freeze``) are outside a bound, that check is a strict xfail naming the numbers, not a looser
bound. Our compliance of each file's case (default fidelity) is computed once per file.

``fzg_c14_calculix_whole.json``: FZG C14 with its own bores (pinion 40, gear 60 mm) at 200 N m, at pinion roll
0 deg (the pitch point, single contact), -9 deg (double contact) and -4.5 deg (single contact just after the
loaded transition near the inner point of single contact B: rigid B at -6.25 deg, loaded single contact from
about -4.9 deg; the gear's highest point of single contact, where its root stress peaks). Contact band 150 um
(0.75 of the nominal Hertz half-width), the tension-side fillets of the loaded teeth 0.675 mm (0.15 module);
at 0 deg the ladder 225 / 150 / 100 um band with 1.0 / 0.675 / 0.45 mm fillets, 0 deg frozen at its finest;
-9 and -4.5 deg refined to 100 um / 0.45 mm by ``--merge`` (``ltca.verify.whole_merge``; their ladders under
``ladders``). The flank peak is like with like at these positions: neither solver has edge contact there
(CalculiX's ``max_pressure`` over all slices equals its inner-slice ``flank_pressure``, its third pair carries
nothing; ours has no tip edge or form circle loaded), both peaks are the Hertzian contact of the same flank point
(``flank_at``). At 0 deg CalculiX 1722 / 1506 / 1434 MPa over the ladder, Richardson 1398 (order 2.7), ours 1387;
local Hertz with our largest slice line load 1370. At -4.5 deg CalculiX 1612 / 1507 MPa at 150 / 100 um (122 k /
166 k nodes, ccx 648 / 1837 s; TE 117.68 / 117.47 arcsec, -0.18 %), at pinion tooth 0, r 35.68 mm, z +5.5 mm (ours
r 35.67 mm, z +2.5 mm), ours 1442 MPa (-4.3 %): within 5 %, though the last step still moves -6.5 % (with the 0 deg
order about 1455 converged); local Hertz 1430 MPa (our largest slice line load 434 N/mm, R 7.65 mm, b 193 um),
GEARpie's rigid sharing (single contact there) 1410 MPa. The flank peak at -9 deg (double contact), where CalculiX's
finest rung is not converged: 1465 / 1266 / 1207 MPa at 150 / 100 / 67 um (-13.6 / -4.7 %; 126 k / 176 k / 271 k
nodes, ccx 1158 / 1114 / 2883 s), observed order 2.97 (2.69 at 0 deg), Richardson 1181 MPa, GCI 2.6 %: ours 1128
MPa is -4.5 % from the estimate (-6.5 % from the 67 um rung; a strict xfail against the finest rung until the
estimate replaced it); at 0 deg -0.7 % (-3.3 % from the 100 um rung). Its other figures:
TE 76.48 / 76.23 arcsec, -0.33 %; shares 0.526 / 0.474 at 100 um), at pinion tooth 0, r 34.93 mm, z +3.5 mm near
the pinion's root (ours r 34.91 mm, z +4.5 mm), fitted half-width 168 um against a Hertz half-width of 130 um (0.78
band element); ours 1128 MPa (-10.9 %). Local Hertz there 1126 MPa (our share 0.527, largest slice line load 229
N/mm, R 6.52 mm); GEARpie's rigid sharing (0.5 each, not the elastic 0.527: a rigid pair shares by contact length)
1081 MPa.
The pinion's root stress was a strict xfail at every position when frozen (ours then 253.1 / 168.9 / 244.5 MPa at 0
/ -9 / -4.5 deg, +9.4 / +5.4 / +7.8 %): not converged (ours at 0 deg coarse / default / fine 219.9 / 253.1 / 242.0
MPa) because 1.35 mm elements on a 2 mm fillet were read 0.05 mm inside (chord sagitta 0.11 mm) with the stress of
the one element there, at points 0.42 mm apart along the fillet. Since issue 18 (``ROOT_REMEASURED``) the read
fillets are meshed at 0.4 of their smallest radius of curvature, the stress is averaged at the nodes as CalculiX's
and read 0.1 mm apart along the fillet (:mod:`fem.fillet`): ours at the default fidelity 234.2 / 159.5 / 224.1 MPa
(pinion, +1.2 / +0.9 / +1.2 % against CalculiX at 100 um), 219.6 / 151.0 / 242.3 MPa (gear, -0.0 / -0.5 / -0.1 %),
converged over coarse / default / fine within 2 % at each position (tests/test_commands.py); the root stresses'
xfails at freeze no longer apply and are checked at 5 % like the rest. CalculiX's root stress moves -1.3 / -2.4 %
(pinion) and -2.3 / -0.6 % (gear) at -9 / -4.5 deg over 150 -> 100 um, its TE -0.33 / -0.18 %; ours then TE -0.67 /
-0.33 %, shares within 0.002.

``helical_c14_calculix_whole.json``: helical C14 (``cases/helical_c14.toml``: C14's transverse geometry, beta 20 deg,
b 40 mm, bores 40/60 mm) at 200 N m, at pinion roll 0 deg (mid-cycle: three pairs, our shares 0.16/0.67/0.17, our TE
minimum) and +6 deg (where the load passes from three pairs to two: tooth 1 leaves, ours 0.001; our TE maximum,
stiffness minimum and pinion root stress maximum over the cycle; ours has three pairs from -5.25 to +5.25 deg).
``--coarse-body`` (flanks with a contact line 0.45, other teeth 0.75, body 1.6, fillets 0.225 module = 0.95 mm, band
growth x 1.5; the default body was 300 k nodes at a 150 um band; on FZG C14 at 224 um the coarse body moved TE
+0.09 % and stiffness -0.1 %). 0 deg frozen at a 100 um band (0.85 of the Hertz half-width 118 um), 0.63 mm
fillets, 219 k nodes, ccx 1331 s; +6 deg at 150 um, 0.95 mm, 148 k nodes, 678 s. Ladder at 0 deg 225 / 150 / 100
um, continued to 67 um by ``--merge`` (0.42 mm fillets, 332 k nodes, ccx 1728 s on 2 threads): TE 35.807 / 35.293 /
35.079 / 34.987 arcsec (-1.44 / -0.60 / -0.26 %: converged to 0.5 % over the last step; until the 67 um rung a
strict xfail of ``test_reference_te_is_converged``), Richardson over the last three 34.917 arcsec (order 2.1, GCI
0.25 %), the figure ours is compared with; stiffness 16.78 / 17.02 / 17.13 / 17.17 (estimate 17.21), root stress
pinion 69.4 / 71.3 / 74.7 / 73.5 MPa, gear 72.3 / 69.2 / 70.4 / 70.3 MPa (not monotone: the finest rung; within 2 %
over the last step). +6 deg refined to 100 um by ``--merge`` (0.63 mm fillets, 206 k nodes, ccx 493 s on 2 threads):
TE 35.760 / 35.589 arcsec (-0.48 %), stiffness 16.80 / 16.88, root stress pinion 74.4 / 75.2, gear 68.0 / 68.2 MPa;
ours TE +0.18 %, stiffness -0.18 %, root stress pinion +1.5 %, gear -2.8 %. The flank peak is not compared
(``unconverged``: 6174 / 4964 / 41934 MPa over the ladder, 14865 MPa at +6
deg): CalculiX's inner face slices hold the tip-edge contact at the ends of the helical contact lines inside the
face (at 150 um nodal 7 GPa at pinion r 34.2 mm under the gear's tip edge, 5.4 GPa at the pinion tip r 41.2 mm),
which ours leaves out as edge contact (ours 934 / 933 MPa). Ours when frozen: TE -1.06 / -0.29 %, stiffness +1.08 /
+0.29 %, shares within 0.016 / 0.003, root stress pinion -4.3 / +2.6 %, gear -2.6 / -2.4 % at 0 / +6 deg; at the
67 um merge (today's bodies) against the converged estimate at 0 deg: TE 34.707 arcsec -0.60 %, stiffness +0.60 %,
root stress pinion 71.5 MPa -2.6 %, gear 68.5 MPa -2.5 %, shares within 0.016. Our compliance of this case takes
21-88 s (52 s at freeze), shared with the session's ``helical_lm``; its comparisons are in the fast suite
(``SLOW_COMPLIANCE_S``).
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from conftest import ROOT
from ltca.verify.whole_merge import ladder_key

REFERENCES = sorted((Path(__file__).resolve().parent / "reference").glob("*_calculix_whole.json"))
BOUNDS = {"te": 0.02, "stiffness": 0.02, "share": 0.03, "flank_pressure": 0.05, "root_pinion": 0.05,
          "root_gear": 0.05}
QUANTITIES = tuple(BOUNDS)
#: quantities whose read-out changed after the references were frozen (issue 18: the root stress); their
#: ``ours_at_freeze`` no longer marks an xfail
ROOT_REMEASURED = ("root_pinion", "root_gear")
#: a file whose case costs more than this (s) for our compliance at the default fidelity (``ours_compliance_wall_s``,
#: measured when it was frozen) has its comparisons marked slow, for the fast suite's budget: FZG C14 (15 s) and
#: helical C14 (52 s when frozen, 21 s on a quiet machine; shared with the session's ``helical_lm``) are fast. The
#: helical comparisons were slow while the session's models kept their factors (the suite passed 24 GiB with them;
#: :meth:`ltca.cylindrical.loaded_model.LoadedModel.without_solver` frees them now)
SLOW_COMPLIANCE_S = 120.0
#: the CalculiX TE of a frozen reference changes by less than this over its ladder's last refinement
TE_CONVERGED = 0.005
_LM: dict = {}
_OURS: dict = {}


@pytest.fixture(scope="module", autouse=True)
def _release_models():
    """Our models of the references' cases live as long as this module's tests, not the whole session."""
    yield
    _LM.clear()
    _OURS.clear()


def _rec(path: Path) -> dict:
    return json.loads(path.read_text())


#: the session fixtures (tests/conftest.py) that hold our model of a reference's case, built the same way as
#: :func:`_lm` (default fidelity, the case's 30 positions per cycle, its first torque): shared, not built twice
SESSION_MODELS = {"cases/fzg_c14.toml": "fzg_lm", "cases/helical_c14.toml": "helical_lm"}


def _lm(path: Path, request=None):
    """Our loaded model of the reference's case (default fidelity), built once per file (or the session's)."""
    if path not in _LM:
        from ltca.case import FIDELITIES, load_case
        from ltca.cylindrical.loaded_model import Fidelity, prepare
        from ltca.cylindrical.model import build_model
        from ltca.cylindrical.run import cycle_rolls
        name = _rec(path)["case"]
        case = load_case(ROOT / name)
        if request is not None and name in SESSION_MODELS:
            _LM[path] = request.getfixturevalue(SESSION_MODELS[name]), case
        else:
            _LM[path] = prepare(build_model(case), Fidelity.from_preset(FIDELITIES["default"], case.module),
                                cycle_rolls(case.positions, case.pinion.teeth), case.torques[0]), case
    return _LM[path]


def _ours(path: Path, roll_deg: float, request=None) -> dict:
    """Our figures at a reference position (:func:`ltca.verify.whole_check.ours_figures`), solved once."""
    if (path, roll_deg) not in _OURS:
        from ltca.cylindrical.loaded import solve_position
        from ltca.verify.whole_check import ours_figures
        lm, case = _lm(path, request)
        r = solve_position(lm, np.radians(roll_deg), case.torques[0])
        _OURS[path, roll_deg] = ours_figures(lm, r, case.torques[0])
    return _OURS[path, roll_deg]


def _rung_value(ref: dict, quantity: str):
    """A quantity as one CalculiX run gave it."""
    if quantity.startswith("root_"):
        return ref.get("root_stress", {}).get(quantity[5:], {}).get("max")
    return ref.get(quantity)


def _first_key(rec: dict) -> str:
    """The ladder key (:func:`ltca.verify.whole_merge.ladder_key`) of the file's first position, the one
    ``convergence`` refines."""
    return ladder_key(rec["convergence"][-1]["roll_deg"])


def _joined_ladder(rec: dict, key: str) -> list[dict] | None:
    """The refinement ladder of the position ``key`` (:func:`ltca.verify.whole_merge.ladder_key`), coarsest first,
    or None without one: the first position's is ``convergence``, continued by its rungs refined by ``--merge``
    (``ladders``, whose first entry is the frozen finest rung of ``convergence``); another position refined by
    ``--merge`` has its own."""
    first, merged = rec["convergence"], rec.get("ladders", {}).get(key)
    if _first_key(rec) != key:
        return merged
    if merged:
        assert merged[0]["h_contact_um"] == first[-1]["h_contact_um"], "a merged ladder starts at the frozen rung"
        return first + merged[1:]
    return first


def _position_ladder(rec: dict, ref: dict) -> list[dict]:
    """A position's refinement ladder, coarsest first (:func:`_joined_ladder`; a position never refined: its
    record alone); its last rung is the position's record."""
    return _joined_ladder(rec, ladder_key(ref["roll_deg"])) or [ref]


def converged_estimate(rec: dict, ref: dict, quantity: str) -> tuple[float | None, float | None]:
    """CalculiX's converged estimate of a quantity at a position and its grid convergence index.

    Where the position's last three rungs are refined by the same ratio and converge in the asymptotic range
    (:func:`ltca.verify.calculix.converged_estimate`), the Richardson extrapolation with the observed order and Roache's
    GCI of the finest rung; otherwise the finest rung and None."""
    from ltca.verify.calculix import converged_estimate as estimate
    ladder = _position_ladder(rec, ref)
    if _rung_value(ref, quantity) is None:
        return None, None
    return estimate([_rung_value(e, quantity) for e in ladder], [e["h_contact_um"] for e in ladder])


def _reference_value(ref: dict, quantity: str, rec: dict | None = None):
    """The reference figure ours is compared with: CalculiX's converged estimate (:func:`converged_estimate`) when
    the file's record ``rec`` is given, else the finest rung's."""
    if rec is None or quantity == "share":
        return _rung_value(ref, quantity)
    return converged_estimate(rec, ref, quantity)[0]


def deviation(quantity: str, ours: dict, ref: dict, rec: dict | None = None) -> float:
    """How far ours is from the reference (:func:`_reference_value`): relative (TE, stiffness, pressure, root
    stress) or the largest absolute share difference."""
    if quantity == "share":
        teeth = set(ref["share"]) | set(ours["share"])
        return max(abs(ours["share"].get(k, 0.0) - ref["share"].get(k, 0.0)) for k in teeth)
    return abs(ours[quantity] / _reference_value(ref, quantity, rec) - 1)


def _cases():
    out = []
    for path in REFERENCES:
        rec = _rec(path)
        slow = [pytest.mark.slow] if rec.get("ours_compliance_wall_s", 0.0) > SLOW_COMPLIANCE_S else []
        for i, ref in enumerate(rec["positions"]):
            for q in QUANTITIES:
                if _reference_value(ref, q) is None:
                    continue
                marks = list(slow)
                then = ref.get("ours_at_freeze")
                if q in rec.get("unconverged", {}):      # CalculiX's own ladder moved it beyond the bound
                    marks.append(pytest.mark.skip(reason=f"not applicable: {rec['unconverged'][q]}"))
                elif then is not None and q not in ROOT_REMEASURED and deviation(q, then, ref, rec) > BOUNDS[q]:
                    shown = (f"{then[q]} vs {ref[q]}" if q == "share" else
                             f"{then[q]:.4g} vs {_reference_value(ref, q, rec):.4g} "
                             f"({100 * (then[q] / _reference_value(ref, q, rec) - 1):+.1f} %)")
                    marks.append(pytest.mark.xfail(strict=True, reason=f"{q} at roll {ref['roll_deg']:g} deg: ours "
                                                                       f"{shown}, outside {BOUNDS[q]} (when frozen)"
                                                                       f"{_ladder_note(rec, ref, q)}"))
                out.append(pytest.param(path, i, q, marks=marks, id=f"{path.stem}-{ref['roll_deg']:g}-{q}"))
    return out


def _ladder(path: Path, key: str | None) -> list[dict]:
    """A file's refinement ladder, coarsest first: the first position's (``key`` None, with its rungs merged
    later) or another merged position's (:func:`_joined_ladder`)."""
    rec = _rec(path)
    return _joined_ladder(rec, _first_key(rec) if key is None else key)


def _ladder_note(rec: dict, ref: dict, quantity: str) -> str:
    """The CalculiX ladder of a quantity at a position refined by ``--merge`` (``ladders``), for an xfail reason."""
    ladder = rec.get("ladders", {}).get(ladder_key(ref["roll_deg"]))
    if not ladder or quantity != "flank_pressure":
        return ""
    values = " / ".join(f"{e['flank_pressure']:.0f}" for e in ladder)
    bands = " / ".join(f"{e['h_contact_um']:.0f}" for e in ladder)
    return (f"; CalculiX over the band {bands} um: {values} MPa "
            f"({100 * (ladder[-1]['flank_pressure'] / ladder[-2]['flank_pressure'] - 1):+.1f} % over the last step)")


def _te_refinement(path: Path, key: str | None = None) -> float:
    """The CalculiX TE's relative change over the last refinement of a file's ladder (:func:`_ladder`)."""
    a, b = _ladder(path, key)[-2:]
    return b["te"] / a["te"] - 1


def _converged_params():
    out = []
    for path in REFERENCES:
        rec = _rec(path)
        for key in [None, *(k for k in rec.get("ladders", {}) if k != _first_key(rec))]:
            a, b = _ladder(path, key)[-2:]
            change = _te_refinement(path, key)
            marks = [] if abs(change) < TE_CONVERGED else [pytest.mark.xfail(
                strict=True, reason=f"CalculiX TE {a['te']:.3f} -> {b['te']:.3f} arcsec ({100 * change:+.2f} %) over "
                                    f"the refinement {a['h_contact_um']:.0f} -> {b['h_contact_um']:.0f} um band at "
                                    f"roll {b['roll_deg']:g} deg: not converged to {100 * TE_CONVERGED:g} %")]
            out.append(pytest.param(path, key, marks=marks, id=path.stem if key is None else f"{path.stem}-{key}"))
    return out


@pytest.mark.parametrize("path,key", _converged_params())
def test_reference_te_is_converged(path, key):
    """The CalculiX TE changes by less than 0.5 % over the last contact-band refinement of the ladder (the first
    position's, and each position's refined by ``--merge``)."""
    assert abs(_te_refinement(path, key)) < TE_CONVERGED


@pytest.mark.parametrize("path", REFERENCES, ids=lambda p: p.stem)
def test_reference_records_its_provenance(path):
    from ltca.case import load_case
    rec = _rec(path)
    case = load_case(ROOT / rec["case"])
    face_width = min(case.pinion.face_width, case.gear.face_width)     # as the model's (no compliance needed)
    assert "Version" in rec["calculix_version"]
    assert rec["command"].startswith("ltca validate --reference calculix-whole")
    assert len(rec["convergence"]) >= 2, "a frozen reference needs its contact-band refinement"
    assert set(rec.get("unconverged", {})) <= set(QUANTITIES)
    for p in rec["positions"]:
        assert len(p["deck_sha256"]) == 64 and p["nodes"] > 0 and p["elements"] > 0 and p["h_contact_um"] > 0
        if "root_stress" in p:                       # the references frozen with the root stress
            assert p["ccx_wall_s"] > 0 and p["mesh_sizes_mm"]["h_fillet"] > 0 and p["contact"]
            assert set(p["root_stress"]) == {"pinion", "gear"} and p["flank_pressure"] > 0
            for member in p["root_stress"].values():
                assert member["max"] == max(member["per_tooth"].values()) > 0
                assert abs(member["at"]["z_mm"]) <= 0.45 * face_width + 1e-9
                assert member["surface"]["max"] > 0
    for key, ladder in rec.get("ladders", {}).items():        # positions refined by --merge: coarsest first
        p = next(p for p in rec["positions"] if ladder_key(p["roll_deg"]) == key)
        assert len(ladder) >= 2 and all(e["roll_deg"] == p["roll_deg"] and len(e["deck_sha256"]) == 64 for e in ladder)
        assert all(a["h_contact_um"] > b["h_contact_um"] for a, b in zip(ladder, ladder[1:]))
        assert {k: v for k, v in p.items() if k != "ours_at_freeze"} == ladder[-1]
    for m in rec.get("merged", []):
        assert m["command"].startswith("ltca validate --reference calculix-whole") and "--merge" in m["command"]
        assert "Version" in m["calculix_version"] and set(m["positions"]) <= set(rec["ladders"])


def test_converged_estimate_by_hand():
    """Richardson with the observed order on f(h) = 1 + h^2 (h = 2.25, 1.5, 1: order 2, limit 1, GCI 1.25 (f2 - f1)
    / f2 / (1.5^2 - 1)); no estimate where the ladder does not converge; the -9 deg flank peak of the FZG
    reference by hand: 1465.106 / 1266.462 / 1206.901 MPa, p = ln(198.644 / 59.561) / ln 1.5 = 2.971,
    1206.901 - 59.561 / (1.5^p - 1) = 1181.39 MPa."""
    from ltca.verify.calculix import grid_convergence_index, richardson
    f = [1 + h * h for h in (2.25, 1.5, 1.0)]
    assert richardson(f, 1.5) == pytest.approx((1.0, 2.0), rel=1e-12)
    assert grid_convergence_index(f, 1.5) == pytest.approx(1.25 * 1.25 / 2 / 1.25, rel=1e-12)
    assert richardson([1.0, 2.0, 1.5], 1.5) is None and richardson([1.0, 1.1, 1.3], 1.5) is None
    assert richardson([1.0, 1.5, 1.5001], 1.5) is None                   # order 20: two rungs coincide
    rec = _rec(next(p for p in REFERENCES if p.name == "fzg_c14_calculix_whole.json"))
    ref = next(p for p in rec["positions"] if p["roll_deg"] == -9.0)
    est, gci = converged_estimate(rec, ref, "flank_pressure")
    assert est == pytest.approx(1181.39, abs=0.05) and gci == pytest.approx(0.0264, abs=5e-4)
    assert converged_estimate(rec, ref, "root_pinion") == (ref["root_stress"]["pinion"]["max"], None)


@pytest.mark.parametrize("path,index,quantity", _cases())
def test_ours_against_frozen_calculix(path, index, quantity, request):
    """TE and mesh stiffness within 2 %, shares within 0.03, flank peak and root stresses within 5 %."""
    rec = _rec(path)
    ref = rec["positions"][index]
    ours = _ours(path, ref["roll_deg"], request)
    theirs = ref["share"] if quantity == "share" else _reference_value(ref, quantity, rec)
    assert deviation(quantity, ours, ref, rec) <= BOUNDS[quantity], \
        f"{quantity}: ours {ours[quantity]} vs CalculiX {theirs}"


@pytest.mark.slow
@pytest.mark.calculix
@pytest.mark.skipif(not REFERENCES, reason="no frozen reference")
def test_regenerated_reference_matches_stored(tmp_path):
    """Regenerate the last position of the FZG C14 reference with CalculiX: the same TE (0.5 %), shares (0.005),
    flank peak and root stresses (1 %)."""
    import shutil
    if shutil.which("ccx") is None:
        pytest.skip("CalculiX (ccx) missing")
    from ltca.verify.whole_gear import solve_whole, whole_settings
    path = next(p for p in REFERENCES if p.name == "fzg_c14_calculix_whole.json")
    ref = _rec(path)["positions"][-1]
    lm, case = _lm(path)
    st = whole_settings(lm.b_nom, case.module, ref["h_contact_um"], threads=1,
                        fillet_mm=ref["mesh_sizes_mm"]["h_fillet"])
    c = solve_whole(lm, ref["roll_deg"], case.torques[0], st, tmp_path, say=lambda m: None)
    assert c.te == pytest.approx(ref["te"], rel=0.005)
    for tooth, share in ref["share"].items():
        assert abs(c.share([int(tooth)])[int(tooth)] - share) < 0.005
    assert c.info["p_flank"] == pytest.approx(ref["flank_pressure"], rel=0.01)
    for member in ("pinion", "gear"):
        assert c.root[member]["max"] == pytest.approx(ref["root_stress"][member]["max"], rel=0.01)
