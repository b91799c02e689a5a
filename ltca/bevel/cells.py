"""Contact cells of a bevel tooth pair, sized to its local contact ellipse.

For each tooth pair that can touch at a pinion angle, the first-contact point (smallest closing gear rotation g)
is found on the pinion flank (coarse scan, then Newton on a 9-point stencil, box-constrained to the flank), and
the normal gap's Hessian there, in an orthonormal frame of the tangent plane, gives the principal relative
curvatures and directions (the quadratic term of the separation: lambda_1 <= lambda_2, 1/mm).  The cells are a
rectangular lattice in that frame, centred on the first-contact point (so that the unloaded TE is met exactly
as the load vanishes), covering the ellipse where the separation stays below a window approach: a multiple of
the elliptic-Hertz approach (:func:`fem.hertz.elliptic_hertz`) of the whole load carried by this one pair.  The
cells thus shrink and grow with the load.  Lattice points are carried onto the flank by two Newton steps of
the tangent-plane map; those off the pinion flank or not over the gear flank are dropped, and the loaded
cells next to a dropped one tell edge contact and where.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem.hertz import elliptic_hertz

from .loaded_model import BevelLoadedModel

__all__ = ["PairMinimum", "PairCells", "pair_minimum", "pair_cells"]

_STENCIL = np.array([[0, 0], [1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [1, -1], [-1, 1], [-1, -1]], float)


@dataclass(frozen=True)
class PairMinimum:
    """First contact of tooth pair ``j`` at pinion angle phi1: flank point (t, L), closing rotation g (rad),
    gear lever v2 (mm/rad), tangent frame E (2, 3), map B (2, 2) from (dt, dL) to tangent coordinates (mm),
    principal relative curvatures lam (2,) ascending (1/mm) and directions D (2, 2) (columns, tangent frame),
    ``at_edge``: the point lies on the flank's boundary."""
    j: int
    t: float
    L: float
    g: float
    v2: float
    r: np.ndarray
    E: np.ndarray
    B: np.ndarray
    lam: np.ndarray
    D: np.ndarray
    at_edge: bool


@dataclass(frozen=True)
class PairCells:
    """Cells of one pair: lattice indices (ia along the major, ib across), tangent coordinates (xi, eta, mm),
    flank coordinates (t, L), the gaps (:class:`geometry.bevel.gaps.PointGaps`), cell sizes (dxi, deta, mm) and
    the dropped lattice points' edge labels (``edge``: per cell, the edge it borders or '')."""
    j: int
    ia: np.ndarray
    ib: np.ndarray
    xi: np.ndarray
    eta: np.ndarray
    t: np.ndarray
    L: np.ndarray
    gaps: object
    dxi: float
    deta: float
    edge: np.ndarray


def _evaluate(lm: BevelLoadedModel, phi: float, t: np.ndarray, L: np.ndarray, extend: bool = False):
    return lm.gaps.gaps(phi, t, L, extend)


def pair_minimum(lm: BevelLoadedModel, phi1: float, j: int, scan: tuple[int, int] = (13, 19)) -> PairMinimum | None:
    """First contact of pair ``j`` (pinion tooth +j) at pinion angle ``phi1``; None if it is not over the gear."""
    G = lm.gaps
    phi = phi1 + j * G.c1
    t0, t1 = G.t_range
    L0, L1 = G.L_range
    T, L = np.meshgrid(np.linspace(t0, t1, scan[0]), np.linspace(L0, L1, scan[1]), indexing="ij")
    g = _evaluate(lm, phi, T, L).g
    if not np.isfinite(g).any():
        return None
    i = np.unravel_index(np.argmin(g), g.shape)
    x = np.array([T[i], L[i]])
    lo, hi = np.array([t0, L0]), np.array([t1, L1])
    h = np.array([(t1 - t0) / (scan[0] - 1), (L1 - L0) / (scan[1] - 1)])
    best_x, best_g = x.copy(), float(g[i])
    for _ in range(12):
        xc = np.clip(x, lo + h, hi - h)
        P = xc + _STENCIL * h
        F = _evaluate(lm, phi, P[:, 0], P[:, 1]).g
        fin = np.isfinite(F)
        if fin.any() and F[fin].min() < best_g:           # the best valid point seen (the minimum may sit on
            k = int(np.argmin(np.where(fin, F, np.inf)))   # the border of the region over the gear flank)
            best_x, best_g = P[k].copy(), float(F[k])
        if not fin.all():
            x, h = best_x.copy(), 0.5 * h
            continue
        gr = np.array([(F[1] - F[2]) / (2 * h[0]), (F[3] - F[4]) / (2 * h[1])])
        H = np.array([[(F[1] - 2 * F[0] + F[2]) / h[0] ** 2, (F[5] - F[6] - F[7] + F[8]) / (4 * h[0] * h[1])],
                      [0.0, (F[3] - 2 * F[0] + F[4]) / h[1] ** 2]])
        H[1, 0] = H[0, 1]
        gr = gr + H @ (x - xc)
        w, V = np.linalg.eigh(H)
        step = -V @ ((V.T @ gr) / np.maximum(w, 1e-3 * max(w.max(), 1e-30)))
        step = np.clip(step, -2 * h, 2 * h)
        x_new = np.clip(x + step, lo, hi)
        g_new = float(_evaluate(lm, phi, x_new[:1], x_new[1:]).g[0])
        if not np.isfinite(g_new) or g_new > best_g:       # backtrack to the best point, smaller stencil
            x, h = best_x.copy(), 0.5 * h
            continue
        moved = np.abs(x_new - x)
        x, best_x, best_g = x_new, x_new.copy(), g_new
        h = np.maximum(0.5 * h, np.array([1e-3, 1e-2]))
        if np.all(moved < 1e-6 * np.array([1.0, 10.0])):
            break
    x = best_x
    # curvature of the normal gap in the tangent plane, from a small stencil around the (clipped) point
    hs = np.array([0.01, 0.15])
    xc = np.clip(x, lo + hs, hi - hs)
    P = xc + _STENCIL * hs
    res = _evaluate(lm, phi, np.append(P[:, 0], x[0]), np.append(P[:, 1], x[1]), extend=True)
    F, r = res.g[:9], res.r1[:9]
    if not (np.all(np.isfinite(F)) and np.isfinite(res.g[9]) and res.ok[9]):
        return None
    v2 = float(res.v2[9])
    Huu = np.array([[(F[1] - 2 * F[0] + F[2]) / hs[0] ** 2, (F[5] - F[6] - F[7] + F[8]) / (4 * hs[0] * hs[1])],
                    [0.0, (F[3] - 2 * F[0] + F[4]) / hs[1] ** 2]]) * v2
    Huu[1, 0] = Huu[0, 1]
    ru = np.stack([(r[1] - r[2]) / (2 * hs[0]), (r[3] - r[4]) / (2 * hs[1])], 1)       # (3, 2)
    e1 = ru[:, 1] / np.linalg.norm(ru[:, 1])                                          # along L (toe -> heel)
    n = np.cross(ru[:, 0], ru[:, 1])
    n /= np.linalg.norm(n)
    e2 = np.cross(n, e1)
    E = np.stack([e1, e2])
    B = E @ ru
    Bi = np.linalg.inv(B)
    Hy = Bi.T @ Huu @ Bi
    lam, D = np.linalg.eigh(0.5 * (Hy + Hy.T))
    edge = bool(np.any(np.abs(x - lo) < 1e-9) or np.any(np.abs(x - hi) < 1e-9))
    return PairMinimum(j, float(x[0]), float(x[1]), float(res.g[9]), v2, res.r1[9], E, B, lam, D, edge)


def window(lm: BevelLoadedModel, pm: PairMinimum, load2: float) -> tuple[float, float]:
    """Window semi-axes (along the major, across the minor axis), mm, for the gear torque ``load2`` (N mm)."""
    bl = lm.pair.blank
    F = load2 / pm.v2
    cap = 0.75 * bl.face_width
    lam = np.maximum(pm.lam, [2 * 1e-3 / cap ** 2, 1e-3])
    hz = elliptic_hertz(F, 0.5 * lam[0], 0.5 * lam[1], lm.bodies.young, lm.bodies.poisson)
    ka, kb = lm.fid.window
    a = min(np.sqrt(2 * ka * hz.delta / lam[0]), cap)
    b = min(np.sqrt(2 * kb * hz.delta / lam[1]), 0.5 * bl.whole_depth)
    return float(a), float(b)


def pair_cells(lm: BevelLoadedModel, phi1: float, pm: PairMinimum, load2: float) -> PairCells:
    """The cells of pair ``pm.j`` at ``phi1`` for the gear torque ``load2`` (module docstring)."""
    na, nb = lm.fid.cells
    a, b = window(lm, pm, load2)
    dxi, deta = 2 * a / na, 2 * b / nb
    ka, kb = (na - 1) // 2 + 1, (nb - 1) // 2 + 1
    IA, IB = np.meshgrid(np.arange(-ka, ka + 1), np.arange(-kb, kb + 1), indexing="ij")
    xi, eta = IA * dxi, IB * deta
    inside = (xi / (a + 0.5 * dxi)) ** 2 + (eta / (b + 0.5 * deta)) ** 2 <= 1.0
    ring = ~inside & ((np.abs(IA) <= ka) & (np.abs(IB) <= kb))
    IA, IB, xi, eta = IA.ravel(), IB.ravel(), xi.ravel(), eta.ravel()
    # tangent coordinates -> flank (t, L): y = D (xi, eta), du = B^-1 y, two corrections on the exact surface
    Y = np.stack([xi, eta], 1) @ pm.D.T
    Bi = np.linalg.inv(pm.B)
    U = np.array([pm.t, pm.L]) + Y @ Bi.T
    phi = phi1 + pm.j * lm.gaps.c1
    for _ in range(2):
        res = _evaluate(lm, phi, U[:, 0], U[:, 1])
        y_now = (res.r1 - pm.r) @ pm.E.T
        U = U + (Y - y_now) @ Bi.T
    res = _evaluate(lm, phi, U[:, 0], U[:, 1])
    ok = res.ok & np.isfinite(res.g)
    keep = inside.ravel() & ok
    # edge: a kept cell with a dropped lattice neighbour (off a flank); label by where the neighbour went
    grid_ok = np.zeros(IA.shape, bool)
    grid_ok[ok] = True
    lab = _edge_labels(lm, U, res, ok)
    key = {(int(p), int(q)): k for k, (p, q) in enumerate(zip(IA, IB))}
    edge = np.full(len(IA), "", dtype=object)
    for k in np.flatnonzero(keep):
        for dp, dq in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            nb_ = key.get((int(IA[k]) + dp, int(IB[k]) + dq))
            if nb_ is not None and not ok[nb_] and lab[nb_]:
                edge[k] = lab[nb_]
                break
    del ring
    sel = np.flatnonzero(keep)
    from geometry.bevel.gaps import PointGaps
    g = PointGaps(*[getattr(res, f)[sel] for f in PointGaps.__dataclass_fields__])
    return PairCells(pm.j, IA[sel], IB[sel], xi[sel], eta[sel], U[sel, 0], U[sel, 1], g, dxi, deta,
                     edge[sel].astype(str))


def _edge_labels(lm: BevelLoadedModel, U: np.ndarray, res, ok: np.ndarray) -> np.ndarray:
    """Where a dropped lattice point lies: off the pinion flank (``pinion top/root``, ``toe``, ``heel``) or
    beyond the gear flank (``gear top`` / ``gear root``)."""
    t0, t1 = lm.gaps.t_range
    L0, L1 = lm.gaps.L_range
    lab = np.full(len(U), "", dtype=object)
    bad = ~ok
    lab[bad & (U[:, 0] > t1)] = "pinion top"
    lab[bad & (U[:, 0] < t0)] = "pinion root"
    lab[bad & (U[:, 1] < L0)] = "toe"
    lab[bad & (U[:, 1] > L1)] = "heel"
    rest = bad & (lab == "")
    if rest.any():
        from .loaded_model import body_t
        bl = lm.pair.blank
        t2 = body_t(bl.gear, bl, 0.0, res.L2[rest], res.Rn2[rest])
        lab[np.flatnonzero(rest)] = np.where(t2 > 0.5, "gear top", "gear root")
    return lab
