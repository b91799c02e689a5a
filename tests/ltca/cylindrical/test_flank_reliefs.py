"""Root relief, end relief and triangular tip relief (ISO 21771:2007 sec. 4.6), and where the default reliefs start.

- the default tip and root reliefs start at the ends of the single-pair zone: on FZG C14 the points B and D of the
  path of contact as GEARpie gives them (AB 5.81 mm, AD 13.28 mm from A; tests/reference/fzg_c14.csv);
- the depths at the corners, faces and boundary lines of each relief as the definitions give them;
- an end relief of C over half the face at both faces, parabolic, is a lead crowning C_beta (the same gaps and the
  same loaded contact, to round-off);
- a triangular tip relief over a very long L_Ea is the linear tip relief from the same start;
- under a lead misalignment an end relief at the loaded face moves the load inwards and lowers the flank peak;
- a relief without its length, or starting off the active involute, is refused naming the key.
"""
from __future__ import annotations

import csv
import dataclasses

import numpy as np
import pytest

from fixtures.paths import REFERENCE
from ltca.case import Modifications, load_case
from ltca.cylindrical.loaded import solve_position
from ltca.cylindrical.model import build_model, relief_zone_radii
from ltca.cylindrical.tca import unloaded_tca
from ltca.errors import CaseError
from ltca.geometry.modification import FlankModification, modification_depth
from ltca.shipped import case_path

GEARPIE = REFERENCE / "fzg_c14.csv"


def _gearpie() -> dict[str, float]:
    rows = [r for r in csv.reader(line for line in GEARPIE.read_text().splitlines() if not line.startswith("#"))]
    return {r[1]: r[2] for r in rows[1:]}


def _with_mods(case, **members):
    """The case with other modifications of the named members (keyword dicts for Modifications)."""
    changes = {name: dataclasses.replace(getattr(case, name), modifications=Modifications(**kw))
               for name, kw in members.items()}
    return dataclasses.replace(case, **changes)


def _with_case(lm, case):
    """The same bodies (compliance) with another case: new gaps, same FE."""
    return dataclasses.replace(lm, model=build_model(case))


def test_default_reliefs_start_at_the_single_pair_zone_ends_of_gearpie():
    """Along the path of contact A..E (A: the gear tip meets the pinion), the pinion's tip relief starts at D and
    its root relief at B, the gear's tip relief at B and its root relief at D; C_f is given at A (pinion) and E
    (gear). Roll lengths from the base tangency points: pinion T1A + AX, gear T1T2 - T1A - AX."""
    ref = _gearpie()
    r_b1, r_b2 = (float(v) * np.cos(np.radians(20.0)) for v in ref["reference radius 1/2"].split("/"))
    r_a2 = float(ref["tip radius 1/2"].split("/")[1])
    t1t2 = float(ref["T1T2 (line of action between base tangency points)"])
    ab, ad, ae = (float(ref[k]) for k in ("AB", "AD", "AE (path of contact length)"))
    t1a = t1t2 - np.sqrt(r_a2 ** 2 - r_b2 ** 2)
    m = build_model(load_case(case_path("fzg_c14")))
    z1, z2 = relief_zone_radii(m.pinion, m.gear, m.pair.a, float(m.pair.alpha_w))

    def roll(r, rb):
        return np.sqrt(r ** 2 - rb ** 2)
    tol = 0.02                        # mm of roll length: GEARpie prints 0.01 mm
    assert abs(roll(z1["tip_start"], r_b1) - (t1a + ad)) < tol
    assert abs(roll(z1["root_start"], r_b1) - (t1a + ab)) < tol
    assert abs(roll(z1["root_end"], r_b1) - t1a) < tol
    assert abs(roll(z2["tip_start"], r_b2) - (t1t2 - t1a - ab)) < tol
    assert abs(roll(z2["root_start"], r_b2) - (t1t2 - t1a - ad)) < tol
    assert abs(roll(z2["root_end"], r_b2) - (t1t2 - t1a - ae)) < tol
    # a case's default tip relief starts there
    case = _with_mods(load_case(case_path("fzg_c14")), pinion=dict(tip_relief=0.01))
    assert build_model(case).mod1.tip_relief_start_radius == pytest.approx(z1["tip_start"], abs=1e-12)


def test_relief_depths_at_corners_faces_and_boundary_lines():
    """r_b 30 mm, form 31 mm, tip 40 mm, b 20 mm (datum face z = -10 mm, non-datum face z = +10 mm)."""
    rb, rf, ra, b = 30.0, 31.0, 40.0, 20.0

    def depth(mod, r, z):
        return modification_depth(mod, np.asarray(r, float), np.asarray(z, float), 0, rb, rf, ra, b)

    def L(r):
        return np.sqrt(r * r - rb * rb)
    end = FlankModification(end_relief=((0.020, 5.0), (0.010, 4.0)), end_relief_exponent=2.0)
    np.testing.assert_allclose(depth(end, [35] * 5, [-10, -7.5, -5, 0, 10]), [0.020, 0.005, 0, 0, 0.010], atol=1e-15)
    np.testing.assert_allclose(depth(end, 35, 8.0), 0.010 * (1 - 2 / 4) ** 2, atol=1e-15)
    tri = FlankModification(triangular_tip_relief=0.012, triangular_tip_relief_start_radius=37.0,
                            triangular_tip_relief_length=8.0, triangular_tip_relief_faces=1)
    # corner (tip, non-datum face): C_Ea; on the boundary line (tip at L_Ea from the face; face end at d_Ea): 0
    np.testing.assert_allclose(depth(tri, [40, 40, 37, 40], [10, 2, 10, -10]), [0.012, 0, 0, 0], atol=1e-15)
    # halfway along the face end between d_Ea and the tip: half, linear in the roll length
    r_mid = np.hypot(rb, 0.5 * (L(37.0) + L(40.0)))
    np.testing.assert_allclose(depth(tri, r_mid, 10.0), 0.006, atol=1e-12)
    both = dataclasses.replace(tri, triangular_tip_relief_faces=0)
    np.testing.assert_allclose(depth(both, [40, 40], [-10, 10]), [0.012, 0.012], atol=1e-15)
    root = FlankModification(root_relief=0.008, root_relief_start_radius=34.0, root_relief_end_radius=32.0)
    np.testing.assert_allclose(depth(root, [34, 32, 38], [0, 0, 0]), [0, 0.008, 0], atol=1e-15)
    r_q = np.hypot(rb, 0.75 * L(34.0) + 0.25 * L(32.0))
    np.testing.assert_allclose(depth(root, r_q, 0.0), 0.002, atol=1e-12)


def test_end_relief_over_half_the_face_at_both_faces_is_a_lead_crowning(fzg_lm, fzg_case):
    """C (1 - d / (b/2))^2 from each face, d the distance from it, is C (2 z / b)^2 over the whole face: the
    gaps and the loaded contact of lead crowning C_beta = C, to round-off."""
    C, half = 0.012, 7.0
    crowned = _with_mods(fzg_case, pinion=dict(lead_crowning=C))
    relieved = _with_mods(fzg_case, pinion=dict(end_relief_datum=C, end_relief_datum_length=half,
                                                end_relief_non_datum=C, end_relief_non_datum_length=half,
                                                end_relief_exponent=2.0))
    T = fzg_case.torques[0]
    a, b = solve_position(_with_case(fzg_lm, crowned), 0.0, T), solve_position(_with_case(fzg_lm, relieved), 0.0, T)
    np.testing.assert_allclose(b.gap0, a.gap0, rtol=0, atol=1e-12)
    np.testing.assert_allclose(b.force, a.force, rtol=1e-9, atol=1e-9)
    assert b.theta == pytest.approx(a.theta, rel=1e-9)


def test_triangular_tip_relief_over_a_long_edge_is_the_tip_relief(fzg_case):
    """With L_Ea much longer than the face the triangular relief is C_Ea (1 + u - d / L_Ea): the linear tip relief
    from d_Ea to within C_Ea b / L_Ea; unloaded TE through the single-pair zone of the relieved tooth."""
    C, d_start = 0.015, 74.0                                   # just above the operating pitch diameter 73.2 mm
    tip = _with_mods(fzg_case, pinion=dict(tip_relief=C, tip_relief_start_diameter=d_start))
    tri = _with_mods(fzg_case, pinion=dict(triangular_tip_relief=C, triangular_tip_relief_start_diameter=d_start,
                                           triangular_tip_relief_length=1e4, triangular_tip_relief_face="datum"))
    psi = np.radians(np.arange(0.5, 4.6, 1.0))
    rb1 = build_model(fzg_case).pinion.r_base
    te_tip = unloaded_tca(build_model(tip), psi).theta0 * rb1
    te_tri = unloaded_tca(build_model(tri), psi).theta0 * rb1
    te0 = unloaded_tca(build_model(fzg_case), psi).theta0 * rb1
    assert (te_tip - te0).max() > 0.1 * C                      # the relief is in mesh here
    assert np.abs(te_tri - te_tip).max() < C * 14.0 / 1e4 + 1e-6


def test_end_relief_at_the_loaded_face_moves_the_load_inwards(fzg_lm, fzg_case):
    """A lead misalignment of 20 um loads one face end; an end relief of 15 um over 4 mm at that face unloads that
    end and moves the load centroid towards mid-face. (The flank peak need not fall: the contact shortens and a
    linear relief's kink concentrates the pressure where it starts.)"""
    T = fzg_case.torques[0]
    tilted = dataclasses.replace(fzg_case, lead_misalignment=0.020)
    r0 = solve_position(_with_case(fzg_lm, tilted), 0.0, T)
    z0 = float(r0.force @ r0.z / r0.force.sum())
    key = ("end_relief_non_datum", "end_relief_non_datum_length") if z0 > 0 else \
        ("end_relief_datum", "end_relief_datum_length")
    relieved = _with_mods(tilted, pinion={key[0]: 0.015, key[1]: 4.0})
    r1 = solve_position(_with_case(fzg_lm, relieved), 0.0, T)
    z1 = float(r1.force @ r1.z / r1.force.sum())
    assert abs(z0) > 1.0                                       # the misalignment does load one end
    assert abs(z1) < abs(z0) - 0.3
    end = np.sign(z0) * r0.z > 7.0 - 2.0, np.sign(z0) * r1.z > 7.0 - 2.0      # the last 2 mm of the loaded end
    assert r1.force[end[1]].sum() < 0.5 * r0.force[end[0]].sum()
    assert r1.force.sum() == pytest.approx(r0.force.sum(), rel=1e-6)


@pytest.mark.parametrize("key, value, length_key", [
    ("end_relief_datum_um", 10.0, "end_relief_datum_length_mm"),
    ("end_relief_non_datum_um", 10.0, "end_relief_non_datum_length_mm"),
    ("triangular_tip_relief_um", 10.0, "triangular_tip_relief_length_mm"),
])
def test_a_relief_without_its_length_is_refused(key, value, length_key):
    case = load_case(case_path("fzg_c14"))
    with pytest.raises(CaseError) as err:
        case_with(case, {f"pinion.modifications.{key}": value})
    assert length_key in str(err.value)


@pytest.mark.parametrize("key, value", [("root_relief_start_diameter_mm", 90.0),
                                        ("root_relief_start_diameter_mm", 60.0),
                                        ("triangular_tip_relief_start_diameter_mm", 83.0)])
def test_a_relief_start_off_the_active_involute_is_refused(key, value):
    case = load_case(case_path("fzg_c14"))
    edited = case_with(case, {"pinion.modifications.root_relief_um": 5.0,
                              "pinion.modifications.triangular_tip_relief_um": 5.0,
                              "pinion.modifications.triangular_tip_relief_length_mm": 3.0,
                              f"pinion.modifications.{key}": value})
    with pytest.raises(CaseError) as err:
        build_model(edited)
    assert key in str(err.value)


def case_with(case, values: dict):
    """The shipped FZG C14 case with dotted keys set, through the case layer (ltca.Case.with_values)."""
    import ltca
    return ltca.load_case("fzg_c14").with_values(values).record
