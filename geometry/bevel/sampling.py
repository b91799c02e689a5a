"""Exact points of a generated bevel flank anywhere in its axial section, from its Flank record.

A flank from :func:`ltca.geometry.bevel.generation.generate_flank` is gridded in the axial section of the member:
node (i, j) sits at depth fraction t_i and cone distance L_j, and its axial position Z and radius rho are
*bilinear* in (t, L) (``axial_grid``: Rn = root(L) + off + t (face(L) - root(L) - off), both cone lines
linear in L; Z = L cos g - Rn sin g, rho = L sin g + Rn cos g).  So any (t, L), also slightly outside the
grid, has a well-defined axial-section target, and the generated point there is solved with the same Newton
(:func:`ltca.geometry.bevel.generation.solve_axial_points`) from the grid's (u, theta, psi) interpolated or
extrapolated linearly.  This is how solids and checks get points of the exact surface between grid nodes:
a mesher places vertices by a spline through these points; a test measures them against it.

Also here: the depth fraction where the blade's edge radius (fillet generator, blade parameter u < 0)
meets its straight part (u = 0), per column: the fillet / flank boundary (:mod:`ltca.geometry.bevel.cutter`).
"""
from __future__ import annotations

import numpy as np

from ..flank import Flank
from .generation import MeshingError, solve_axial_points, surface_state

__all__ = ["axial_target", "flank_at", "fillet_boundary"]


def _bilinear(grid: np.ndarray, t_grid: np.ndarray, L_grid: np.ndarray, t: np.ndarray, L: np.ndarray):
    """Bilinear interpolation/extrapolation of ``grid`` (nu, nv, ...) on the grid's corner cells."""
    i = np.clip(np.searchsorted(t_grid, t) - 1, 0, len(t_grid) - 2)
    j = np.clip(np.searchsorted(L_grid, L) - 1, 0, len(L_grid) - 2)
    a = (t - t_grid[i]) / (t_grid[i + 1] - t_grid[i])
    b = (L - L_grid[j]) / (L_grid[j + 1] - L_grid[j])
    ex = (slice(None),) + (None,) * (grid.ndim - 2)
    a, b = a[ex], b[ex]
    return ((1 - a) * (1 - b) * grid[i, j] + a * (1 - b) * grid[i + 1, j] + (1 - a) * b * grid[i, j + 1]
            + a * b * grid[i + 1, j + 1])


def _retry_from_nodes(flank: Flank, fc, Z, rho, t, L, x, ok, tol):
    """Newton again from each corner node of the grid cell, for the targets whose first solve did not converge
    (near the blade profile's kink between edge radius and flank, the interpolated start can fall on the wrong
    branch and Newton steps back and forth across it)."""
    params = np.asarray(flank.meta["params"])
    tg, Lg = np.asarray(flank.u, float), np.asarray(flank.v, float)
    for di in (0, 1):
        for dj in (0, 1):
            bad = np.flatnonzero(~ok)
            if not len(bad):
                return x, ok
            i = np.clip(np.searchsorted(tg, t[bad]) - 1, 0, len(tg) - 2) + di
            j = np.clip(np.searchsorted(Lg, L[bad]) - 1, 0, len(Lg) - 2) + dj
            xb, okb = solve_axial_points(fc, Z[bad], rho[bad], params[i, j], tol=tol, max_iter=80)
            x[bad[okb]], ok[bad[okb]] = xb[okb], True
    return x, ok


def axial_target(flank: Flank, t: np.ndarray, L: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Axial position Z and radius rho (mm) of depth fraction ``t`` and cone distance ``L`` (mm).

    Exact (the map is bilinear, module docstring) from the four corner nodes of the grid."""
    t, L = np.broadcast_arrays(np.asarray(t, float), np.asarray(L, float))
    tg, Lg = np.asarray(flank.u, float), np.asarray(flank.v, float)
    a = (t - tg[0]) / (tg[-1] - tg[0])
    b = (L - Lg[0]) / (Lg[-1] - Lg[0])
    out = []
    for key in ("Z", "rho"):
        g = np.asarray(flank.meta[key])
        out.append((1 - a) * (1 - b) * g[0, 0] + a * (1 - b) * g[-1, 0] + (1 - a) * b * g[0, -1] + a * b * g[-1, -1])
    return out[0], out[1]


def flank_at(flank: Flank, t: np.ndarray, L: np.ndarray, tol: float = 1e-11
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Generated points, unit normals and blade parameter at depth fractions ``t`` and cone distances ``L``.

    Parameters
    ----------
    flank : Flank
        A generated bevel flank (``meta`` holds ``params``, ``Z``, ``rho`` and ``flank_cut``).
    t, L : ndarray, broadcastable
        Depth fraction (0 root offset, 1 face cone) and cone distance (mm); may lie a little outside the grid.
    tol : float
        Newton tolerance, mm.

    Returns
    -------
    points, normals : ndarray, shape broadcast + (3,)
        In the member's body frame, mm; normals out of the material.
    u : ndarray, shape broadcast
        Blade profile parameter (mm; < 0 on the edge radius, i.e. in the fillet).

    Raises
    ------
    KeyError
        ``flank`` has no generation record in ``meta``.
    MeshingError
        Newton did not converge at some of the requested points.
    """
    fc = flank.meta["flank_cut"]
    t, L = np.broadcast_arrays(np.asarray(t, float), np.asarray(L, float))
    shape = t.shape
    tf, Lf = t.ravel(), L.ravel()
    Z, rho = axial_target(flank, tf, Lf)
    x0 = _bilinear(np.asarray(flank.meta["params"]), np.asarray(flank.u), np.asarray(flank.v), tf, Lf)
    x, ok = solve_axial_points(fc, Z, rho, x0, tol=tol)
    if not ok.all():
        x, ok = _retry_from_nodes(flank, fc, Z, rho, tf, Lf, x, ok, tol)
    if not ok.all():
        raise MeshingError(f"no generated point on the {flank.side} flank at {int((~ok).sum())} of {ok.size} "
                           f"targets, t in [{tf[~ok].min():.3f}, {tf[~ok].max():.3f}], L in "
                           f"[{Lf[~ok].min():.3f}, {Lf[~ok].max():.3f}] mm")
    st = surface_state(fc, x[:, 0], x[:, 1], x[:, 2])
    return st.r_w.reshape(shape + (3,)), st.n_w.reshape(shape + (3,)), x[:, 0].reshape(shape)


def fillet_boundary(flank: Flank, iterations: int = 4) -> np.ndarray:
    """Depth fraction t of the fillet / flank boundary (blade parameter u = 0) in each grid column, (nv,).

    Linear interpolation of the grid's blade parameter, then secant steps on the exact surface (the blade
    parameter is smooth in t) until |u| < 0.1 um (Newton is slow right at the kink of the blade profile).  Columns without a fillet in the grid (u >= 0 at the lowest row) give t = 0;
    a blade without edge radius gives zeros."""
    u = np.asarray(flank.meta["params"])[..., 0]
    tg, L = np.asarray(flank.u, float), np.asarray(flank.v, float)
    if flank.meta["flank_cut"].cutter.edge_radius == 0.0:
        return np.zeros(len(L))
    has = u[0] < 0.0
    tb = np.zeros(len(L))
    for j in np.flatnonzero(has):
        tb[j] = np.interp(0.0, u[:, j], tg) if np.all(np.diff(u[:, j]) > 0) else tg[np.argmax(u[:, j] >= 0)]
    if not has.any():
        return tb
    t0 = tb[has] - 0.01
    t1 = tb[has].copy()
    Lh = L[has]
    u0 = flank_at(flank, t0, Lh)[2]
    u1 = flank_at(flank, t1, Lh)[2]
    for _ in range(iterations):
        go = (np.abs(u1) > 1e-4) & (np.abs(u1 - u0) > 1e-14)
        if not go.any():
            break
        t_new = t1[go] - u1[go] * (t1[go] - t0[go]) / (u1[go] - u0[go])
        t0[go], u0[go] = t1[go], u1[go]
        t1[go] = t_new
        u1[go] = flank_at(flank, t_new, Lh[go])[2]
    tb[has] = t1
    return tb
