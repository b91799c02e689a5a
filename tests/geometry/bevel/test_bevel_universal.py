"""The universal face-milling generator: identity with the basic cradle, the equation of meshing with every
motion, curved blades, and flanks against SpyGO (independent open code, stored reference)."""
import dataclasses
import json

import numpy as np
import pytest

from fixtures.paths import REFERENCE
from ltca.geometry.bevel.blank import BevelBasicData, design_blank
from ltca.geometry.bevel.cutter import HeadCutter
from ltca.geometry.bevel.generation import generate_member, solve_axial_points, standard_gear_cut, surface_state
from ltca.geometry.bevel.machine import FlankCut, MachineSettings
from ltca.geometry.bevel.universal import blade_coordinates, universal_state

REF = REFERENCE


@pytest.fixture(scope="module")
def gear_fc():
    bl = design_blank(BevelBasicData())
    return standard_gear_cut(bl).concave


def test_basic_settings_reproduce_the_basic_cradle_flanks_bit_for_bit(bevel_pair):
    """The shipped pair (gear standard cut, pinion synthesised) through the whole chain: synthesis and flanks.

    The reference arrays are our own output of the basic cradle model (no tilt, swivel, motions; straight
    blades) on the same grid, kept for this identity check only, never as evidence of correctness."""
    ref = np.load(REF / "bevel_flanks_cao2008_basic.npz")
    pair = bevel_pair
    for m, cut in (("gear", pair.gear), ("pinion", pair.pinion)):
        assert cut.concave.machine.is_basic and cut.convex.machine.is_basic
        for s, f in generate_member(cut, pair.blank, nu=9, nv=11).items():
            assert np.array_equal(f.points, ref[f"{m}_{s}_points"]), (m, s)
            assert np.array_equal(f.normals, ref[f"{m}_{s}_normals"]), (m, s)
            assert np.array_equal(f.meta["params"], ref[f"{m}_{s}_params"]), (m, s)


def test_universal_path_equals_basic_path_on_basic_settings(gear_fc):
    rng = np.random.default_rng(1)
    u, th, psi = rng.uniform(-1, 8, 200), rng.uniform(-0.3, 0.3, 200), rng.uniform(-0.3, 0.3, 200)
    a, b = surface_state(gear_fc, u, th, psi), universal_state(gear_fc, u, th, psi)
    for k in ("r_w", "n_w", "f", "Z", "rho", "phi"):
        assert np.allclose(getattr(a, k), getattr(b, k), rtol=0, atol=1e-12), k


FULL = dict(tilt=0.2, swivel=0.7, modified_roll_c=0.05, modified_roll_d=-0.1, modified_roll_e=0.3,
            modified_roll_f=-0.5, modified_roll_g=-2.0, radial_motion=(3.0, 1.0, -2.0, 4.0, 5.0, 6.0),
            vertical_motion=(1.0, 2.0, 3.0), helical_motion=(2.0, -1.0, 0.0, 0.0, 0.0, 3.0),
            tilt_motion=(0.1, 0.2, 0.3), swivel_motion=(0.3, -0.2, 0.1, 0.5))


@pytest.mark.parametrize("curved", [False, True])
def test_equation_of_meshing_is_normal_times_work_relative_velocity(gear_fc, curved):
    """f = n . d r_w / d psi at fixed blade point (Litvin & Fuentes 2004, sec. 6.1), d/dpsi by central
    differences of the work point: checks every derivative term of the relative velocity."""
    cu = dataclasses.replace(gear_fc.cutter, profile_radius=250.0) if curved else gear_fc.cutter
    fc = FlankCut(dataclasses.replace(gear_fc.machine, **FULL), cu)
    rng = np.random.default_rng(2)
    u, th, psi = rng.uniform(-1, 8, 100), rng.uniform(-0.3, 0.3, 100), rng.uniform(-0.3, 0.3, 100)
    h = 1e-5
    st = surface_state(fc, u, th, psi)
    drw = (surface_state(fc, u, th, psi + h).r_w - surface_state(fc, u, th, psi - h).r_w) / (2 * h)
    assert np.max(np.abs(np.einsum("...i,...i", st.n_w, drw) - st.f)) < 1e-6 * np.max(np.abs(st.f))
    # each term matters: without the radial motion the same check fails
    fc0 = FlankCut(dataclasses.replace(fc.machine, radial_motion=()), cu)
    assert np.max(np.abs(surface_state(fc0, u, th, psi).f - st.f)) > 1e-2


def test_curved_blade_profile():
    for blade in ("outside", "inside"):
        cu = HeadCutter(60.0, np.deg2rad(20.0), blade, 1.5, profile_radius=300.0)
        u = np.linspace(cu.u_min, 8.0, 2001)
        p = cu.profile(u)
        assert np.allclose(np.hypot(p.d_rho, p.d_z), 1.0) and np.allclose(p.n_rho * p.d_rho + p.n_z * p.d_z, 0.0)
        assert p.z[0] == pytest.approx(0.0, abs=1e-12) and np.all(p.z <= 1e-12)
        assert np.allclose(cu.u_at_depth(-p.z), u, atol=1e-9)
        # circle of radius 300 through (R_p, 0) with its centre on the work side (against the normal)
        c = np.array([60.0 + cu.sigma * 300.0 * np.cos(cu.blade_angle), 300.0 * np.sin(cu.blade_angle)])
        on = u >= 0
        assert np.allclose(np.hypot(p.rho[on] - c[0], p.z[on] - c[1]), 300.0, atol=1e-9)
        assert np.allclose(c[0] - p.rho[on], 300.0 * -p.n_rho[on], atol=1e-9)
        # toprem and flankrem: arcs of their radii from their depths, tangent (G1) to the blade
        cr = HeadCutter(60.0, np.deg2rad(20.0), blade, 1.0, profile_radius=400.0, toprem_depth=1.2,
                        toprem_radius=15.0, flankrem_depth=6.0, flankrem_radius=30.0)
        u0, ph0, r0, z0, kp = cr.chain
        assert np.allclose(z0[1:], [-1.2, -6.0]) and np.allclose(kp, [1 / 15.0, 1 / 400.0, 1 / 30.0])
        q = cr.profile(np.r_[u0[1:] - 1e-9, u0[1:] + 1e-9])
        assert np.allclose(q.n_rho[:2], q.n_rho[2:], atol=1e-9) and np.allclose(q.rho[:2], q.rho[2:], atol=1e-8)
        u = np.linspace(cr.u_min, 8.0, 4001)
        assert np.allclose(cr.u_at_depth(-cr.profile(u).z), u, atol=1e-9)
        # a very large radius is the straight blade
        s, b = HeadCutter(60.0, 0.35, blade, 1.5).profile(u), HeadCutter(60.0, 0.35, blade, 1.5,
                                                                          profile_radius=1e9).profile(u)
        assert np.allclose(s.rho, b.rho, atol=1e-6) and np.allclose(s.z, b.z, atol=1e-6)


def test_bad_settings_name_the_field():
    with pytest.raises(ValueError, match="tilt"):
        MachineSettings(50.0, 0.1, 0.5, tilt=1.0)
    with pytest.raises(ValueError, match="radial_motion"):
        MachineSettings(50.0, 0.1, 0.5, radial_motion=(1.0,) * 7)
    with pytest.raises(ValueError, match="formate"):
        MachineSettings(50.0, 0.1, 0.5, formate=True, ratio_of_roll=0.0, modified_roll_c=0.1)
    with pytest.raises(ValueError, match="profile_radius"):
        HeadCutter(50.0, 0.3, profile_radius=-1.0)


def _flank_cut(d: dict) -> FlankCut:
    c = {k: (float(v) if v == "inf" else v) for k, v in d["cutter"].items()}
    return FlankCut(MachineSettings(**d["machine"]), HeadCutter(**c))


SPYGO = json.loads((REF / "spygo_19x62.json").read_text())


@pytest.mark.parametrize("v", SPYGO["variants"], ids=[f"{v['variant']}-{v['member']}-{v['flank']}"
                                                       for v in SPYGO["variants"]])
def test_flanks_match_spygo(v):
    """SpyGO's points and normals (tools/compare_spygo.py; provenance in the file) of its 19/62, 95 deg pair,
    each variant a changed settings sheet: ours at the same axial-section (z, R) within 0.1 um and 1e-5.
    SpyGO's straight blade is an arc of 2e6 mm: 0.03 um and 4e-6 rad of the difference on the straight-bladed
    pinion come from that (the comparison tool shows 1e-9 um with the same arc)."""
    fc = _flank_cut(v["settings"])
    z, R = np.array(v["z"]), np.array(v["R"])
    P, N = np.array(v["spygo_points"]), np.array(v["spygo_normals"])
    assert len(z) >= 3
    x, ok = solve_axial_points(fc, z, R, blade_coordinates(fc, P, np.array(v["spygo_psi"])), tol=1e-11,
                               max_iter=60)
    st = surface_state(fc, x[:, 0], x[:, 1], x[:, 2])
    # (at the root nodes next to the blade's edge-radius junction u = 0 Newton stops at |f| ~ 1e-4 mm, the
    # point still within 1e-5 um: the claims are the points and normals)
    assert np.max(np.abs(st.f)) < 1e-3 and np.all(x[:, 0] >= fc.cutter.u_min - 1e-9)
    assert np.max(np.linalg.norm(st.r_w - P, axis=1)) < 1e-4          # 0.1 um
    assert np.max(np.linalg.norm(st.n_w + N, axis=1)) < 1e-5          # SpyGO's normal points out of the blade
