"""Elastic half-space influence coefficients of uniformly loaded rectangular cells.

The near field of the gear-flank compliance is taken from the Boussinesq / Love solution of a linear
elastic half-space (Vijayakar 1991 idea, see docs/design.md): a contact cell is a rectangle of half sizes
``a`` (profile direction, local x) and ``b`` (face direction, local y) carrying a total force of 1 N
as the uniform pressure ``1 / (4 a b)``.

Sign convention: a positive displacement moves the surface **into** the body (the direction of a
compressive load).  Each function gives the influence of **one** body; the caller adds both bodies.

Formulas (closed forms, no quadrature)
--------------------------------------
Boussinesq point load F at the origin, displacement along the load at (X, Y, z), R^2 = X^2+Y^2+z^2
(Johnson, *Contact Mechanics*, 1985, eq. 3.21c; Timoshenko & Goodier, *Theory of Elasticity*, sec. 138)::

    u_z = F (1 + nu) / (2 pi E) [2 (1 - nu) / R + z^2 / R^3]

Integrated over a rectangle with the mixed primitives (d^2/dX dY of each gives the integrand)::

    1/R    : X asinh(Y / sqrt(X^2+z^2)) + Y asinh(X / sqrt(Y^2+z^2)) - z atan(X Y / (z R))
    z/R^3  : atan(X Y / (z R))                          (solid angle of the rectangle)

so that, with p = 1/(4ab) and the corner sum  S[f] = f(x+a, y+b) - f(x-a, y+b) - f(x+a, y-b) + f(x-a, y-b),

    u_z(x, y, z) = p (1 + nu) / (2 pi E) S[ 2 (1 - nu) (X asinh(..) + Y asinh(..)) - (1 - 2 nu) z atan(..) ].

At z = 0 this is Love's (1929) surface solution for a uniformly loaded rectangle
(Johnson 1985, sec. 3.3 eq. 3.25): ``u_z = p (1 - nu^2) / (pi E) S[X asinh(Y/|X|) + Y asinh(X/|Y|)]``.
The primitives are written odd in X and in Y so that the corner sum is valid on every side of the cell.
"""
from __future__ import annotations

import numpy as np

__all__ = [
    "point_influence_sq",
    "surface_influence",
    "subsurface_influence",
    "near_field_correction",
    "surface_influence_matrix",
]

_CHUNK = 1 << 20  # target number of (target, cell) pairs per block in the matrix builders


def _check_material(E, nu) -> None:
    if not (np.isfinite(E) and E > 0):
        raise ValueError(f"E = {E!r}: Young's modulus must be a finite number > 0 (MPa)")
    if not (np.isfinite(nu) and -1.0 < nu < 0.5):
        raise ValueError(f"nu = {nu!r}: Poisson's ratio must lie in (-1, 0.5)")


def _check_positive(name: str, value) -> np.ndarray:
    arr = np.asarray(value, dtype=float)
    if not np.all(np.isfinite(arr)) or np.any(arr <= 0):
        bad = arr[~(np.isfinite(arr) & (arr > 0))].ravel()[:1]
        raise ValueError(f"{name} = {bad[0] if bad.size else value!r}: must be finite and > 0 (mm)")
    return arr


def _x_asinh(x: np.ndarray, y: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """x * asinh(y / rho), with the limit 0 where rho = 0 (which implies x = 0)."""
    ratio = np.divide(y, rho, out=np.zeros(np.broadcast(y, rho).shape), where=rho > 0)
    return x * np.arcsinh(ratio)


def _primitive(X: np.ndarray, Y: np.ndarray, z, nu: float) -> np.ndarray:
    """Mixed primitive of 2(1-nu)/R + z^2/R^3 (module docstring); valid for z = 0 too."""
    X2, Y2 = X * X, Y * Y
    if np.all(np.asarray(z) == 0):
        f = _x_asinh(X, Y, np.abs(X)) + _x_asinh(Y, X, np.abs(Y))
        return 2.0 * (1.0 - nu) * f
    z2 = z * z
    f = _x_asinh(X, Y, np.sqrt(X2 + z2)) + _x_asinh(Y, X, np.sqrt(Y2 + z2))
    R = np.sqrt(X2 + Y2 + z2)
    # arctan2 gives the right limit (0 or +-pi/2) when z R = 0; it is then multiplied by z = 0.
    return 2.0 * (1.0 - nu) * f - (1.0 - 2.0 * nu) * z * np.arctan2(X * Y, z * R)


def _corner_sum(dx, dy, z, a, b, nu) -> np.ndarray:
    return (_primitive(dx + a, dy + b, z, nu) - _primitive(dx - a, dy + b, z, nu)
            - _primitive(dx + a, dy - b, z, nu) + _primitive(dx - a, dy - b, z, nu))


def subsurface_influence(dx, dy, depth, a, b, E: float, nu: float) -> np.ndarray:
    """Displacement along the surface normal at depth ``depth`` under the surface point (dx, dy).

    Parameters
    ----------
    dx, dy : array_like
        Offset of the surface point from the cell centre, mm (local profile / face coordinates).
    depth : array_like
        Depth below the surface, mm, >= 0. ``depth = 0`` gives :func:`surface_influence`.
    a, b : array_like
        Half sizes of the cell in x and y, mm, > 0.
    E, nu : float
        Young's modulus (MPa) and Poisson's ratio of the body.

    Returns
    -------
    ndarray, broadcast shape of the inputs
        Displacement into the body, mm per N of total cell force (closed-form integral of the
        Boussinesq point-load solution over the cell; formula in the module docstring).
    """
    _check_material(E, nu)
    a = _check_positive("a", a)
    b = _check_positive("b", b)
    z = np.asarray(depth, dtype=float)
    if not np.all(np.isfinite(z)) or np.any(z < 0):
        raise ValueError(f"depth = {depth!r}: must be finite and >= 0 (mm)")
    dx = np.asarray(dx, dtype=float)
    dy = np.asarray(dy, dtype=float)
    scale = (1.0 + nu) / (2.0 * np.pi * E) / (4.0 * a * b)
    return scale * _corner_sum(dx, dy, z, a, b, nu)


def point_influence(lateral, depth, E: float, nu: float) -> np.ndarray:
    """Displacement along the surface normal at ``depth`` and ``lateral`` distance from a 1 N normal point load.

    Boussinesq: u_z = (1 + nu) / (2 pi E) [2 (1 - nu) / rho + z^2 / rho^3], rho = sqrt(r^2 + z^2)
    (Johnson, Contact Mechanics, 1985, eq. 3.22c), mm/N; at z = 0 it is (1 - nu^2) / (pi E r).
    ``lateral`` and ``depth`` (mm, broadcast) must not both vanish."""
    r = np.asarray(lateral, dtype=float)
    z = np.asarray(depth, dtype=float)
    return point_influence_sq(r * r + z * z, z * z, E, nu)


def point_influence_sq(dist2, depth2, E: float, nu: float) -> np.ndarray:
    """:func:`point_influence` from the squared distance rho^2 and the squared depth z^2 (mm^2), in place on
    large arrays: u_z = (1 + nu) / (2 pi E rho) [2 (1 - nu) + z^2 / rho^2]."""
    _check_material(E, nu)
    rho2 = np.array(dist2, dtype=float)
    if np.any(rho2 <= 0):
        raise ValueError("point_influence: the load point itself (lateral = depth = 0) is singular")
    out = np.divide(depth2, rho2)
    out += 2.0 * (1.0 - nu)
    np.sqrt(rho2, out=rho2)
    out /= rho2
    out *= (1.0 + nu) / (2.0 * np.pi * E)
    return out


def surface_influence(dx, dy, a, b, E: float, nu: float) -> np.ndarray:
    """Normal surface displacement due to a cell carrying 1 N as a uniform pressure (Love 1929).

    Parameters
    ----------
    dx, dy : array_like
        Offset of the target point from the cell centre, mm.
    a, b : array_like
        Half sizes of the cell (profile x, face y), mm, > 0.
    E, nu : float
        Young's modulus (MPa) and Poisson's ratio.

    Returns
    -------
    ndarray, broadcast shape of the inputs
        Displacement into the body, mm/N. Far from the cell it tends to the point-load value
        (1 - nu^2) / (pi E r); at the centre of a square cell it is 8 ln(1+sqrt 2)(1-nu^2) p a/(pi E)
        (Timoshenko & Goodier sec. 138; Johnson 1985 eq. 3.25).
    """
    return subsurface_influence(dx, dy, 0.0, a, b, E, nu)


def _pairwise(xs, centres, half, depth, E, nu, what: str) -> np.ndarray:
    xs = np.asarray(xs, dtype=float)
    centres = np.asarray(centres, dtype=float)
    half = np.asarray(half, dtype=float)
    if xs.ndim != 2 or xs.shape[1] != 2:
        raise ValueError(f"xs has shape {xs.shape}: must be (n, 2) local surface coordinates (mm)")
    if centres.ndim != 2 or centres.shape[1] != 2:
        raise ValueError(f"centres has shape {centres.shape}: must be (m, 2) (mm)")
    if half.shape != centres.shape:
        raise ValueError(f"half has shape {half.shape}: must equal the shape of centres {centres.shape}")
    _check_positive("half", half)
    n, m = xs.shape[0], centres.shape[0]
    d = np.broadcast_to(np.asarray(depth, dtype=float), (n,)) if depth is not None else None
    out = np.empty((n, m))
    step = max(1, _CHUNK // max(m, 1))
    a, b = half[None, :, 0], half[None, :, 1]
    for i0 in range(0, n, step):
        sl = slice(i0, min(n, i0 + step))
        dx = xs[sl, 0, None] - centres[None, :, 0]
        dy = xs[sl, 1, None] - centres[None, :, 1]
        surf = surface_influence(dx, dy, a, b, E, nu)
        if what == "surface":
            out[sl] = surf
        else:
            out[sl] = surf - subsurface_influence(dx, dy, d[sl, None], a, b, E, nu)
    return out


def surface_influence_matrix(xs, centres, half, E: float, nu: float) -> np.ndarray:
    """Surface influence matrix of one body, (n, m) mm/N: target points ``xs`` (n, 2) and cells
    with ``centres`` (m, 2) and half sizes ``half`` (m, 2), all in local surface coordinates (mm).
    Built in row blocks to bound the memory of temporaries."""
    return _pairwise(xs, centres, half, None, E, nu, "surface")


def near_field_correction(xs, centres, half, depth, E: float, nu: float) -> np.ndarray:
    """Half-space relative displacement between the surface and a point ``depth`` below it.

    Parameters
    ----------
    xs : ndarray, shape (n, 2)
        Target points in local surface coordinates, mm.
    centres, half : ndarray, shape (m, 2)
        Cell centres and half sizes (a, b), mm.
    depth : float or ndarray, shape (n,)
        Depth d of the matching subsurface point y_i = x_i - d n_i, mm, >= 0.
    E, nu : float
        Material of the body.

    Returns
    -------
    ndarray, shape (n, m)
        ``surface_influence - subsurface_influence``, mm/N: the term C_HS(j -> x_i) - C_HS(j -> y_i)
        of the corrected compliance (docs/design.md, near field).
    """
    return _pairwise(xs, centres, half, depth, E, nu, "correction")
