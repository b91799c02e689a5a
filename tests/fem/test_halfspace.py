"""Half-space influence coefficients against closed-form elasticity, and Hertz contact through the solver.

Sources: Boussinesq point load, Johnson, *Contact Mechanics* (1985) eq. 3.21c; Timoshenko & Goodier,
*Theory of Elasticity* (3rd ed., 1970) sec. 138 (uniformly loaded rectangle / square); Hertz formulas
in tests/reference/hertz.md (Johnson 1985 eqs. 4.23, 4.45, 4.51).
"""
import numpy as np
import pytest
from scipy.integrate import dblquad

from ltca.fem.contact import solve_contact
from ltca.fem.halfspace import near_field_correction, subsurface_influence, surface_influence, surface_influence_matrix

E, NU = 206000.0, 0.3
ES = E / (2.0 * (1.0 - NU**2))          # E* of two equal steel bodies


def boussinesq_uz(r, z):
    """Point load 1 N: u_z = (1+nu)/(2 pi E) [2(1-nu)/R + z^2/R^3] (Johnson 1985 eq. 3.21c)."""
    R = np.sqrt(r**2 + z**2)
    return (1 + NU) / (2 * np.pi * E) * (2 * (1 - NU) / R + z**2 / R**3)


def test_surface_far_field_is_point_load():
    a, b = 0.01, 0.03
    ang = np.linspace(0, 2 * np.pi, 13)
    r = 10.0
    u = surface_influence(r * np.cos(ang), r * np.sin(ang), a, b, E, NU)
    ref = (1 - NU**2) / (np.pi * E * r)              # Boussinesq at z = 0
    assert np.max(np.abs(u / ref - 1)) < 1e-4


def test_square_centre_and_corner_deflection():
    # Timoshenko & Goodier sec. 138: square of side 2a under pressure p deflects at the centre by
    # w = 8 ln(1 + sqrt 2) (1 - nu^2) p a / (pi E) (= 2.24 (1-nu^2) p a / E), at a corner by half that.
    a = 0.05
    p = 1.0 / (4 * a * a)
    w_c = 8 * np.log(1 + np.sqrt(2)) * (1 - NU**2) * p * a / (np.pi * E)
    assert surface_influence(0.0, 0.0, a, a, E, NU) == pytest.approx(w_c, rel=1e-12)
    assert surface_influence(a, -a, a, a, E, NU) == pytest.approx(w_c / 2, rel=1e-12)


def test_surface_against_numerical_integration_outside_cell():
    a, b, dx, dy = 0.02, 0.01, 0.05, -0.013
    f = lambda y, x: (1 - NU**2) / (np.pi * E) / np.hypot(dx - x, dy - y) / (4 * a * b)
    ref = dblquad(f, -a, a, -b, b, epsabs=0, epsrel=1e-11)[0]
    assert surface_influence(dx, dy, a, b, E, NU) == pytest.approx(ref, rel=1e-9)


@pytest.mark.parametrize("dx,dy,z", [(0.02, 0.005, 0.007), (0.0, 0.0, 0.02), (0.003, -0.01, 0.004)])
def test_subsurface_against_numerical_integration(dx, dy, z):
    a, b = 0.01, 0.03
    f = lambda y, x: boussinesq_uz(np.hypot(dx - x, dy - y), z) / (4 * a * b)
    ref = dblquad(f, -a, a, -b, b, epsabs=0, epsrel=1e-11)[0]
    assert subsurface_influence(dx, dy, z, a, b, E, NU) == pytest.approx(ref, rel=1e-8)


def test_subsurface_tends_to_surface():
    a, b = 0.01, 0.02
    dx = np.array([0.0, 0.004, 0.01, 0.03, -0.2])
    dy = np.array([0.0, -0.015, 0.02, 0.0, 0.1])
    surf = surface_influence(dx, dy, a, b, E, NU)
    assert np.allclose(subsurface_influence(dx, dy, 0.0, a, b, E, NU), surf, rtol=1e-14, atol=0)
    errs = [np.max(np.abs(subsurface_influence(dx, dy, d, a, b, E, NU) / surf - 1)) for d in (1e-4, 1e-6)]
    assert errs[1] < 1e-4 and errs[1] < errs[0]


def test_subsurface_far_field_is_point_load():
    a, b = 0.01, 0.02
    for r, z in [(5.0, 0.0), (3.0, 4.0), (0.0, 5.0), (1.0, 8.0)]:
        u = subsurface_influence(r, 0.0, z, a, b, E, NU)
        assert u == pytest.approx(boussinesq_uz(r, z), rel=1e-4)


def test_near_field_correction_shape_and_value():
    xs = np.array([[0.0, 0.0], [0.1, 0.2], [1.0, -3.0]])
    centres = np.array([[0.0, 0.0], [0.05, 0.2]])
    half = np.array([[0.01, 0.02], [0.02, 0.01]])
    K = near_field_correction(xs, centres, half, 0.3, E, NU)
    assert K.shape == (3, 2)
    d = xs[:, None, :] - centres[None]
    ref = (surface_influence(d[..., 0], d[..., 1], half[:, 0], half[:, 1], E, NU)
           - subsurface_influence(d[..., 0], d[..., 1], 0.3, half[:, 0], half[:, 1], E, NU))
    assert np.allclose(K, ref, rtol=1e-13, atol=0)
    assert np.all(K[:2] > 0)        # near the load the surface moves more than the point below it
    # far away (r >> d) the difference is O(d^2 / r^3): u(r, d) - u(r, 0) ~ (1+nu) nu d^2 / (2 pi E r^3)
    # (expansion of the Boussinesq formula), i.e. the correction is small and negative
    r = np.hypot(*(xs[2] - centres).T)
    assert np.allclose(K[2], -(1 + NU) * NU * 0.3**2 / (2 * np.pi * E * r**3), rtol=0.05)


@pytest.mark.parametrize("kw", [dict(a=0.0), dict(E=-1.0), dict(nu=0.5), dict(depth=-0.1)])
def test_bad_input_raises(kw):
    args = dict(dx=0.0, dy=0.0, depth=0.1, a=0.01, b=0.01, E=E, nu=NU)
    args.update(kw)
    with pytest.raises(ValueError, match=list(kw)[0]):
        subsurface_influence(**args)


def _grid(x, y):
    X, Y = np.meshgrid(x, y, indexing="ij")
    return np.column_stack([X.ravel(), Y.ravel()])


def _ellipse_fit(r, p):
    """Fit p^2 = p0^2 (1 - r^2/c^2) to the loaded cells: returns p0, c."""
    on = p > 0
    slope, icpt = np.polyfit(r[on] ** 2, p[on] ** 2, 1)
    return np.sqrt(icpt), np.sqrt(-icpt / slope)


def test_hertz_line_contact_fzg_c14():
    # hertz.md worked check: FZG C14 pitch point, R1 = 13.9701, R2 = 20.9551 mm, w = 422.29 N/mm, L = 14 mm.
    R = 1 / (1 / 13.9701 + 1 / 20.9551)
    w, L = 422.29, 14.0
    nx, ny = 160, 14
    dx, dy = 0.8 / nx, L / ny
    x = (np.arange(nx) - (nx - 1) / 2) * dx
    y = (np.arange(ny) - (ny - 1) / 2) * dy
    xs = _grid(x, y)
    C = 2 * surface_influence_matrix(xs, xs, np.tile([dx / 2, dy / 2], (len(xs), 1)), E, NU)
    sol = solve_contact(C, xs[:, 0] ** 2 / (2 * R), 1.0, w * L)
    p = (sol.force / (dx * dy)).reshape(nx, ny)
    mid = ny // 2
    # The finite contact carries more at its ends (edge effect): the line load at mid-length is ~9 %
    # below w, so compare with plane-strain Hertz at the local line load (Johnson 1985 eq. 4.45).
    w_mid = p[:, mid].sum() * dx
    b = np.sqrt(4 * w_mid * R / (np.pi * ES))
    p0 = 2 * w_mid / (np.pi * b)
    p0_fit, b_fit = _ellipse_fit(x, p[:, mid])
    print(f"\nline: w_mid/w = {w_mid / w:.4f}; p_max/p0 - 1 = {p[:, mid].max() / p0 - 1:.2e}, "
          f"b_fit/b - 1 = {b_fit / b - 1:.2e}; vs FZG p0 = 1347.3: {p[:, mid].max() / 1347.3 - 1:.3f}")
    assert p[:, mid].max() == pytest.approx(p0, rel=0.01)
    assert b_fit == pytest.approx(b, rel=0.03)
    assert 0.85 < w_mid / w < 1.0                   # edge effect: the middle is unloaded a little
    # The worked example itself (hertz.md): p0 = 1347.3 MPa, b = 199.5 um from w = 422.29 N/mm.
    b_w = np.sqrt(4 * w * R / (np.pi * ES))
    assert b_w == pytest.approx(0.1995, rel=1e-3) and 2 * w / (np.pi * b_w) == pytest.approx(1347.3, rel=1e-4)


def test_hertz_point_contact_sphere_on_plane():
    Rs, P = 10.0, 1000.0
    a = (3 * P * Rs / (4 * ES)) ** (1 / 3)           # Johnson 1985 eq. 4.22-4.23
    p0 = 3 * P / (2 * np.pi * a * a)
    n, ext = 40, 0.5
    d = 2 * ext / n
    x = (np.arange(n) - (n - 1) / 2) * d
    xs = _grid(x, x)
    C = 2 * surface_influence_matrix(xs, xs, np.full(xs.shape, d / 2), E, NU)
    sol = solve_contact(C, (xs**2).sum(1) / (2 * Rs), 1.0, P)
    p = sol.force / d**2
    p0_fit, a_fit = _ellipse_fit(np.hypot(xs[:, 0], xs[:, 1]), p)
    print(f"\npoint: p_max/p0 - 1 = {p.max() / p0 - 1:.2e}, a_fit/a - 1 = {a_fit / a - 1:.2e}, "
          f"approach/(a^2/R) - 1 = {sol.approach / (a * a / Rs) - 1:.2e}")
    assert p.max() == pytest.approx(p0, rel=0.02)
    assert a_fit == pytest.approx(a, rel=0.02)
    assert sol.approach == pytest.approx(a * a / Rs, rel=0.02)   # Hertz approach delta = a^2 / R


def test_point_influence_is_the_small_cell_limit_and_the_surface_formula():
    """Boussinesq point load (Johnson eq. 3.22c) against the closed-form cell integral and Love's surface value."""
    from ltca.fem.halfspace import point_influence, subsurface_influence
    E, nu = 206000.0, 0.3
    lateral = np.array([0.0, 0.5, 1.0, 3.0])
    depth = np.array([1.0, 0.7, 2.0, 0.5])
    cell = subsurface_influence(lateral, 0.0, depth, 1e-3, 1e-3, E, nu)   # 2 um square cell carrying 1 N
    assert np.allclose(point_influence(lateral, depth, E, nu), cell, rtol=1e-5)
    r = np.array([0.3, 2.0])
    assert np.allclose(point_influence(r, 0.0, E, nu), (1 - nu ** 2) / (np.pi * E * r), rtol=1e-12)
    with pytest.raises(ValueError, match="singular"):
        point_influence(0.0, 0.0, E, nu)
