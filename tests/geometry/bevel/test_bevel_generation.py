"""Generated spiral bevel tooth surfaces: equation of meshing, normals, blank, thickness, speed."""
import time

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from ltca.geometry.bevel.blank import BevelBasicData, design_blank
from ltca.geometry.bevel.cutter import HeadCutter
from ltca.geometry.bevel.generation import (
    MeshingError,
    generate_flank,
    generate_member,
    normal_thickness,
    solve_axial_points,
    standard_gear_cut,
    surface_state,
)
from ltca.geometry.bevel.machine import (
    FlankCut,
    MachineSettings,
    cradle_to_machine,
    cutter_to_cradle,
    gear_settings,
    pinion_settings,
    work_to_machine,
)
from ltca.geometry.bevel.tca import _solve_psi


@pytest.fixture(scope="module")
def blank():
    return design_blank(BevelBasicData())


@pytest.fixture(scope="module")
def gear_cut(blank):
    return standard_gear_cut(blank)


@pytest.fixture(scope="module")
def flanks(blank, gear_cut):
    t0 = time.perf_counter()
    out = {"gear": generate_member(gear_cut, blank, nu=20, nv=31),
           "pinion": generate_member(pinion_settings(blank), blank, nu=20, nv=31)}
    out["seconds"] = time.perf_counter() - t0
    return out


def test_cutter_profile_is_unit_speed_and_normal():
    cu = HeadCutter(60.0, np.deg2rad(20.0), "inside", 1.5)
    u = np.linspace(cu.u_min, 8.0, 401)
    p = cu.profile(u)
    assert np.allclose(np.hypot(p.d_rho, p.d_z), 1.0)
    assert np.allclose(p.n_rho * p.d_rho + p.n_z * p.d_z, 0.0, atol=1e-15)
    drho, dz = np.gradient(p.rho, u), np.gradient(p.z, u)
    assert np.allclose(drho[1:-1], p.d_rho[1:-1], atol=2e-3) and np.allclose(dz[1:-1], p.d_z[1:-1], atol=2e-3)
    assert p.z[0] == pytest.approx(0.0, abs=1e-12) and np.all(p.z <= 1e-12)      # tip plane, blade below
    assert np.allclose(cu.u_at_depth(-p.z), u, atol=1e-9)


def test_meshing_residual_normals_and_speed(flanks):
    for member in ("gear", "pinion"):
        for side, fl in flanks[member].items():
            assert fl.meta["meshing_residual"] < 1e-9, (member, side)
            assert np.allclose(np.linalg.norm(fl.normals, axis=-1), 1.0, atol=1e-12)
            assert not fl.meta["undercut"].any()
    print(f"both members, both flanks: {flanks['seconds']:.2f} s (target 2 s; measured, not asserted)")


def test_normals_orthogonal_to_surface_tangents(blank, gear_cut, flanks):
    """Tangents from re-solved neighbouring points (central differences, h = 1e-4 mm in Z and rho).

    Truncation error is O(h^2) on the straight-blade part (< 1e-9 measured 2e-10); the edge-radius
    fillet (radius 1.2 mm, curvature jump at its tangency point) gets a looser bound."""
    for fl, fc in ((flanks["gear"]["convex"], gear_cut.convex), (flanks["gear"]["concave"], gear_cut.concave)):
        X = fl.meta["params"].reshape(-1, 3)
        Z, rho = fl.meta["Z"].ravel(), fl.meta["rho"].ravel()
        n = fl.normals.reshape(-1, 3)
        straight = X[:, 0] > 0.05
        h = 1e-4
        for dZ, dR in ((h, 0.0), (0.0, h)):
            pts = []
            for s in (1, -1):
                x, ok = solve_axial_points(fc, Z + s * dZ, rho + s * dR, X)
                assert ok.all()
                pts.append(surface_state(fc, x[:, 0], x[:, 1], x[:, 2]).r_w)
            t = (pts[0] - pts[1]) / np.linalg.norm(pts[0] - pts[1], axis=-1, keepdims=True)
            dot = np.abs(np.einsum("ni,ni->n", t, n))
            assert dot[straight].max() < 1e-9
            assert dot.max() < 1e-7
        assert straight.sum() > 0.8 * len(X)


def test_points_match_transform_chain(gear_cut):
    """Vectorised kinematics agree with the explicit 4x4 chain M_wm(phi) M_mp(psi) M_pc r_c."""
    fc = gear_cut.concave
    u, th, psi = 3.0, -0.9, 0.07
    st = surface_state(fc, np.array([u]), np.array([th]), np.array([psi]))
    r_c, _ = fc.cutter.surface(u, th)
    M = np.linalg.inv(work_to_machine(fc.machine, st.phi[0])) @ cradle_to_machine(psi) @ cutter_to_cradle(fc.machine)
    assert np.allclose((M @ np.append(r_c, 1.0))[:3], st.r_w[0], atol=1e-12)


def test_gear_tooth_inside_blank_and_root_cone(blank, flanks):
    """Grid nodes sit on their axial-section targets; the blade tip generates the root cone."""
    g = blank.gear
    for side, fl in flanks["gear"].items():
        rho = np.hypot(fl.points[..., 0], fl.points[..., 1])
        assert np.allclose(rho, fl.meta["rho"], atol=1e-9) and np.allclose(fl.points[..., 2], fl.meta["Z"], atol=1e-9)
        L = fl.points[..., 2] * np.cos(g.pitch_angle) + rho * np.sin(g.pitch_angle)
        Rn = -fl.points[..., 2] * np.sin(g.pitch_angle) + rho * np.cos(g.pitch_angle)
        assert L.min() >= blank.inner_cone_distance - 1e-9 and L.max() <= blank.outer_cone_distance + 1e-9
        A0 = blank.outer_cone_distance
        assert np.all(Rn <= g.addendum - (A0 - L) * np.tan(g.addendum_angle) + 1e-9)
        assert np.all(Rn >= -(g.dedendum - (A0 - L) * np.tan(g.dedendum_angle)) - 1e-9)
        # the blade tip (u = u_min) of the standard gear sweeps the root cone: the generated points of the
        # tip circle have their axial-section point on the root line (Rn = -dedendum at that L)
        X = fl.meta["params"][0]
        fc = fl.meta["flank_cut"]
        um = np.full(len(X), fc.cutter.u_min)
        st = surface_state(fc, um, X[:, 1], _solve_psi(fc, um, X[:, 1], X[:, 2]))
        assert np.max(np.abs(st.f)) < 1e-10
        Lr = st.Z * np.cos(g.pitch_angle) + st.rho * np.sin(g.pitch_angle)
        Rr = -st.Z * np.sin(g.pitch_angle) + st.rho * np.cos(g.pitch_angle)
        assert np.allclose(Rr, -(g.dedendum - (A0 - Lr) * np.tan(g.dedendum_angle)), atol=1e-9)
    # top land: the tooth (convex of one slot to concave of the next) is not pointed at the face cone
    a_cc = np.arctan2(flanks["gear"]["concave"].points[-1, :, 1], flanks["gear"]["concave"].points[-1, :, 0])
    a_cv = np.arctan2(flanks["gear"]["convex"].points[-1, :, 1], flanks["gear"]["convex"].points[-1, :, 0])
    slot = np.abs(a_cc - a_cv)
    assert np.all(2 * np.pi / g.z - slot > 0.0)


def test_mean_normal_thickness_as_designed(blank, gear_cut, flanks):
    """Thickness read off the 31-column grid (mean column, spline in Rn at the pitch cone)."""
    g = blank.gear
    j = 15
    assert flanks["gear"]["concave"].v[j] == pytest.approx(blank.mean_cone_distance)
    ang = {}
    for side, fl in flanks["gear"].items():
        Rn = fl.meta["Rn"][:, j]
        a = np.unwrap(np.arctan2(fl.points[:, j, 1], fl.points[:, j, 0]))
        ang[side] = CubicSpline(Rn, a)(0.0)
    slot = abs(ang["concave"] - ang["convex"])
    s = (2 * np.pi / g.z - slot) * g.mean_pitch_radius * np.cos(blank.data.spiral_angle)
    assert s == pytest.approx(g.mean_normal_thickness, abs=0.005)
    assert normal_thickness(gear_cut, blank) == pytest.approx(g.mean_normal_thickness, abs=1e-4)
    # the first-order point width already lands within 0.01 mm (crown-gear normal section)
    assert normal_thickness(gear_settings(blank), blank) == pytest.approx(g.mean_normal_thickness, abs=0.01)


def test_hand_of_spiral(blank, flanks):
    """Right hand (ANSI/AGMA 1012): outer half of the tooth turned clockwise seen looking at the face,
    i.e. the polar angle grows towards the heel about +z (z from the apex to the back)."""
    for member, sign in (("gear", 1.0), ("pinion", -1.0)):
        p = flanks[member]["concave"].points[10]
        assert np.all(sign * np.diff(np.unwrap(np.arctan2(p[:, 1], p[:, 0]))) > 0)


def test_no_solution_names_region(blank, gear_cut):
    """A cutter far too small for the blank: the error names the flank and the axial-section region."""
    fc = gear_cut.concave
    bad = FlankCut(MachineSettings(radial_setting=fc.machine.radial_setting, cradle_angle=fc.machine.cradle_angle,
                                   root_angle=fc.machine.root_angle, ratio_of_roll=fc.machine.ratio_of_roll),
                   HeadCutter(8.0, fc.cutter.blade_angle, "outside", 0.5))
    with pytest.raises(MeshingError, match=r"concave flank .* region L = \["):
        generate_flank(bad, blank, "gear", nu=6, nv=6)
