"""Tests of geometry.cylindrical: involute-helicoid flanks (normals, curvatures, screw motion)."""
import numpy as np
import pytest

from ltca.geometry.cylindrical import flank_point_normal, helical_flank
from ltca.geometry.flank import Flank, surface_curvatures
from ltca.geometry.involute import GearBlank, RackCutter, generate_by_rack

DEG = np.pi / 180
A20 = 20 * DEG


def _profile(beta, z=23, m=3.0, x=0.2):
    return generate_by_rack(GearBlank(z, m, A20, beta=beta, x=x), RackCutter(A20, 1.25 * m, m, 0.38 * m))


@pytest.mark.parametrize("beta", [0.0, 25 * DEG, -15 * DEG])
@pytest.mark.parametrize("side", [1, -1])
def test_normals_orthogonal_to_tangents(beta, side):
    p = _profile(beta)
    r = np.linspace(p.r_form_right + 0.01, p.r_tip, 9)[:, None]
    zeta = np.linspace(-12, 12, 7)[None, :]
    h = 1e-5
    P, N = flank_point_normal(p, side, r, zeta, tooth=2)
    assert P.shape == (9, 7, 3) and N.shape == (9, 7, 3)
    assert np.allclose(np.linalg.norm(N, axis=-1), 1, atol=1e-14)
    tr = (flank_point_normal(p, side, r + h, zeta, tooth=2)[0] - flank_point_normal(p, side, r - h, zeta, tooth=2)[0])
    tz = (flank_point_normal(p, side, r, zeta + h, tooth=2)[0] - flank_point_normal(p, side, r, zeta - h, tooth=2)[0])
    for t in (tr, tz):
        cosang = np.einsum("...i,...i", t, N) / np.linalg.norm(t, axis=-1)
        assert np.max(np.abs(cosang)) < 1e-9


@pytest.mark.parametrize("beta", [0.0, 25 * DEG, -15 * DEG])
def test_screw_motion_and_normal_direction(beta):
    p = _profile(beta)
    z = p.z
    r = p.r_ref
    for side in (1, -1):
        P0, N0 = flank_point_normal(p, side, r, 0.0)
        # transverse section at mid-face = the generated profile (exact involute)
        assert np.allclose(P0[:2], p.flank_xy(r, side), atol=1e-12)
        # normal out of the material: towards the gap, i.e. +x on the right flank, -x on the left
        assert np.sign(N0[0]) == side
        # helix: at axial position zeta the point turned by zeta tan(beta) / r_ref (right hand: ccw)
        zeta = 7.0
        P1, _ = flank_point_normal(p, side, r, zeta)
        turn = np.arctan2(-P1[0], P1[1]) - np.arctan2(-P0[0], P0[1])
        assert abs(turn - zeta * np.tan(beta) / r) < 1e-12 and P1[2] == zeta
        # tooth k: rotated by -k 2 pi / z (clockwise)
        P2, _ = flank_point_normal(p, side, r, 0.0, tooth=3)
        turn = np.arctan2(-P2[0], P2[1]) - np.arctan2(-P0[0], P0[1])
        assert abs(turn + 3 * 2 * np.pi / z) < 1e-12
        # the normal is inclined to the transverse plane by the base helix angle beta_b
        # (tan beta_b = tan beta cos alpha_t; Litvin & Fuentes 2004 eq. 14.3.12)
        assert abs(abs(np.arcsin(N0[2])) - abs(p.beta_b)) < 1e-12
        assert abs(np.tan(p.beta_b) - np.tan(beta) * np.cos(p.alpha_t)) < 1e-14


@pytest.mark.parametrize("beta", [0.0, 25 * DEG, -15 * DEG])
def test_analytic_curvatures_match_finite_differences(beta):
    p = _profile(beta)
    for side in (1, -1):
        # start where the transverse curvature radius is 8 mm: closer to the base circle the curvature
        # varies so fast that the FD reference itself is off by more than 1 % on this grid
        f = helical_flank(p, side, 20.0, 81, 21, r_range=(np.hypot(p.r_base, 8.0), p.r_tip))
        assert isinstance(f, Flank) and f.points.shape == (81, 21, 3)
        k_fd, d_fd = surface_curvatures(f.points, f.normals, f.u, f.v)
        sl = (slice(2, -2), slice(2, -2))      # FD rows next to the edges use one-sided differences
        rel = np.abs(k_fd[sl][..., 0] - f.curvatures[sl][..., 0]) / f.curvatures[sl][..., 0]
        assert rel.max() < 0.01
        assert np.max(np.abs(k_fd[sl][..., 1])) < 0.01 * f.curvatures[sl][..., 0].min()
        # directions agree (up to sign) and are tangent to the surface
        assert np.min(np.abs(np.einsum("...i,...i", d_fd[sl][..., 0, :], f.directions[sl][..., 0, :]))) > 0.999
        assert np.max(np.abs(np.einsum("...ki,...i", f.directions, f.normals))) < 1e-12
        # external flank: convex, k1 = cos(beta_b) / rho_transverse (Meusnier)
        rho_t = np.sqrt(f.u ** 2 - p.r_base ** 2)
        assert np.allclose(f.curvatures[:, 0, 0], np.cos(p.beta_b) / rho_t, rtol=1e-12)


def test_helical_flank_defaults_and_bad_input():
    p = _profile(10 * DEG)
    f = helical_flank(p, -1, 14.0, 5, 3)
    assert f.u[0] == p.r_form_left and f.u[-1] == p.r_tip and f.side == "left"
    assert np.allclose(f.v, [-7, 0, 7])
    with pytest.raises(ValueError, match="side"):
        helical_flank(p, 0, 14.0, 5, 3)
    with pytest.raises(ValueError, match="face_width"):
        helical_flank(p, 1, -1.0, 5, 3)
    with pytest.raises(ValueError, match="nu"):
        helical_flank(p, 1, 14.0, 1, 3)
    with pytest.raises(ValueError, match="r_range"):
        helical_flank(p, 1, 14.0, 5, 3, r_range=(p.r_base - 1, p.r_tip))
    with pytest.raises(ValueError, match="r ="):
        flank_point_normal(p, 1, p.r_base - 1.0, 0.0)


def test_internal_flank_is_concave():
    from ltca.geometry.shaper import ShaperCutter, generate_by_shaper
    m = 3.0
    for beta in (0.0, 20 * DEG):
        p = generate_by_shaper(GearBlank(60, m, A20, beta=beta, d_tip=2 * 88.0 / np.cos(beta) if beta else 175.0,
                                         internal=True), ShaperCutter(20, 0.0, 1.25 * m, 0.3 * m))
        for side in (1, -1):
            f = helical_flank(p, side, 20.0, 81, 21)
            assert f.u[0] > f.u[-1]              # u from root (outer) to tip (inner)
            assert np.all(f.curvatures[..., 1] < 0) and np.all(f.curvatures[..., 0] == 0)
            k_fd, _ = surface_curvatures(f.points, f.normals, f.u, f.v)
            sl = (slice(2, -2), slice(2, -2))
            rel = np.abs(k_fd[sl][..., 1] - f.curvatures[sl][..., 1]) / np.abs(f.curvatures[sl][..., 1])
            assert rel.max() < 0.01
            # normal out of the internal tooth points towards the space (right flank: +x)
            assert np.all(np.sign(f.normals[..., 0]) == side)
