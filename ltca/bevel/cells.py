"""Contact cells of a bevel tooth pair, sized to its local contact ellipse.

For each tooth pair that can touch at a pinion angle, the first-contact point (smallest closing gear rotation g)
is found on the pinion flank (coarse scan, then Newton on a 9-point stencil, box-constrained to the flank), and
the normal gap's Hessian there, in an orthonormal frame of the tangent plane, gives the principal relative
curvatures and directions (the quadratic term of the separation: lambda_1 <= lambda_2, 1/mm).  The cells are a
rectangular lattice in that frame, centred on the first-contact point (so that the unloaded TE is met exactly
as the load vanishes), covering the ellipse where the separation stays below a window approach: a multiple of
the elliptic-Hertz approach (:func:`ltca.fem.hertz.elliptic_hertz`) of the whole load carried by this one pair.  The
cells thus shrink and grow with the load.  Lattice points are carried onto the flank by two Newton steps of
the tangent-plane map; those off the pinion flank or not over the gear flank are dropped, and the loaded
cells next to a dropped one tell edge contact and where.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ltca.fem.hertz import elliptic_hertz

from .model import BevelLoadedModel


__all__ = ["PairMinimum", "PairCells", "pair_minimum", "pair_minima", "pair_cells", "cells_of", "window",
           "pair_hertz"]

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
    flank coordinates (t, L), the gaps (:class:`ltca.geometry.bevel.gaps.PointGaps`), cell sizes (dxi, deta, mm) and
    the dropped lattice points' edge labels (``edge``: per cell, the edge it borders or ''), and ``rim``: the cell
    borders
    the window on the flank (a loaded rim cell means the window was too small)."""
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
    rim: np.ndarray = None
    edge_dist: np.ndarray = None


def _evaluate(lm: BevelLoadedModel, phi: float, t: np.ndarray, L: np.ndarray, extend: bool = False):
    return lm.gaps.gaps(phi, t, L, extend)


def pair_minimum(lm: BevelLoadedModel, phi1: float, j: int, scan: tuple[int, int] = (13, 19)) -> PairMinimum | None:
    """First contact of pair ``j`` (pinion tooth +j) at pinion angle ``phi1``; None if it is not over the gear."""
    return pair_minima(lm, phi1, (j,), scan)[0]


def pair_minima(lm: BevelLoadedModel, phi1: float, js, scan: tuple[int, int] = (13, 19)) -> list[PairMinimum | None]:
    """First contacts of the pairs ``js`` at ``phi1``, all pairs in each gap evaluation (module docstring)."""
    G = lm.gaps
    js = np.asarray(js, int)
    k = len(js)
    phi = phi1 + js * G.c1                                          # (k,)
    t0, t1 = G.t_range
    L0, L1 = G.L_range
    lo, hi = np.array([t0, L0]), np.array([t1, L1])
    T, L = np.meshgrid(np.linspace(t0, t1, scan[0]), np.linspace(L0, L1, scan[1]), indexing="ij")
    # the scan grid's pinion points are the same at every position and pair: solved once per gap evaluator
    surf = tuple(a[None] for a in G.pinion_surface(T, L))
    g = G.gaps(phi[:, None, None], T[None], L[None], surface=surf).g.reshape(k, -1)
    live = np.isfinite(g).any(1)
    i = np.argmin(np.where(np.isfinite(g), g, np.inf), 1)
    x = np.stack([T.ravel()[i], L.ravel()[i]], 1)                    # (k, 2)
    best_x, best_g = x.copy(), g[np.arange(k), i]
    h = np.tile([(t1 - t0) / (scan[0] - 1), (L1 - L0) / (scan[1] - 1)], (k, 1))
    done = ~live
    err = np.seterr(invalid="ignore", divide="ignore")      # stencils reaching off the region over the gear: inf
    for _ in range(10):
        if done.all():
            break
        xc = np.clip(x, lo + h, hi - h)
        P = xc[:, None, :] + _STENCIL[None] * h[:, None, :]          # (k, 9, 2)
        F = _evaluate(lm, phi[:, None], P[..., 0], P[..., 1]).g      # (k, 9)
        fin = np.isfinite(F)
        Fm = np.where(fin, F, np.inf)
        kb = np.argmin(Fm, 1)
        better = Fm[np.arange(k), kb] < best_g
        best_x[better], best_g[better] = P[np.arange(k), kb][better], Fm[np.arange(k), kb][better]
        gr = np.stack([(F[:, 1] - F[:, 2]) / (2 * h[:, 0]), (F[:, 3] - F[:, 4]) / (2 * h[:, 1])], 1)
        H = np.empty((k, 2, 2))
        H[:, 0, 0] = (F[:, 1] - 2 * F[:, 0] + F[:, 2]) / h[:, 0] ** 2
        H[:, 1, 1] = (F[:, 3] - 2 * F[:, 0] + F[:, 4]) / h[:, 1] ** 2
        H[:, 0, 1] = H[:, 1, 0] = (F[:, 5] - F[:, 6] - F[:, 7] + F[:, 8]) / (4 * h[:, 0] * h[:, 1])
        ok = fin.all(1) & ~done
        H = np.where(ok[:, None, None], H, np.eye(2))
        gr = np.where(ok[:, None], gr + np.einsum("kab,kb->ka", H, x - xc), 0.0)
        w, V = np.linalg.eigh(H)
        w = np.maximum(w, 1e-3 * np.maximum(w.max(1, keepdims=True), 1e-30))
        step = -np.einsum("kab,kb->ka", V, np.einsum("kba,kb->ka", V, gr) / w)
        step = np.clip(step, -2 * h, 2 * h)
        x_new = np.clip(x + step, lo, hi)
        g_new = _evaluate(lm, phi, x_new[:, 0], x_new[:, 1]).g
        accept = ok & np.isfinite(g_new) & (g_new <= best_g)
        moved = np.abs(x_new - x)
        # accepted: move on; refused (or a stencil off the region over the gear): back to the best, smaller stencil
        x = np.where(accept[:, None], x_new, best_x)
        best_x = np.where(accept[:, None], x_new, best_x)
        best_g = np.where(accept, g_new, best_g)
        h = np.where(accept[:, None], np.maximum(0.5 * h, [1e-3, 1e-2]), 0.5 * h)
        done |= accept & np.all(moved < np.array([2e-5, 2e-4]), 1)      # 0.2 um on the flank
        done |= np.all(h < np.array([1e-6, 1e-5]), 1)
    np.seterr(**err)
    x = best_x
    # curvature of the normal gap in the tangent plane, from a small stencil around the (clipped) point
    hs = np.array([0.01, 0.15])
    xc = np.clip(x, lo + hs, hi - hs)
    P = np.concatenate([xc[:, None, :] + _STENCIL[None] * hs, x[:, None, :]], 1)     # (k, 10, 2)
    res = _evaluate(lm, phi[:, None], P[..., 0], P[..., 1], extend=True)
    out: list[PairMinimum | None] = []
    for q in range(k):
        F, r = res.g[q, :9], res.r1[q, :9]
        if not (live[q] and np.all(np.isfinite(F)) and np.isfinite(res.g[q, 9]) and res.ok[q, 9]):
            out.append(None)
            continue
        v2 = float(res.v2[q, 9])
        Huu = np.array([[(F[1] - 2 * F[0] + F[2]) / hs[0] ** 2, (F[5] - F[6] - F[7] + F[8]) / (4 * hs[0] * hs[1])],
                        [0.0, (F[3] - 2 * F[0] + F[4]) / hs[1] ** 2]]) * v2
        Huu[1, 0] = Huu[0, 1]
        ru = np.stack([(r[1] - r[2]) / (2 * hs[0]), (r[3] - r[4]) / (2 * hs[1])], 1)       # (3, 2)
        e1 = ru[:, 1] / np.linalg.norm(ru[:, 1])                                          # along L (toe -> heel)
        n = np.cross(ru[:, 0], ru[:, 1])
        n /= np.linalg.norm(n)
        E = np.stack([e1, np.cross(n, e1)])
        B = E @ ru
        Bi = np.linalg.inv(B)
        Hy = Bi.T @ Huu @ Bi
        lam, D = np.linalg.eigh(0.5 * (Hy + Hy.T))
        edge = bool(np.any(np.abs(x[q] - lo) < 1e-9) or np.any(np.abs(x[q] - hi) < 1e-9))
        out.append(PairMinimum(int(js[q]), float(x[q, 0]), float(x[q, 1]), float(res.g[q, 9]), v2, res.r1[q, 9], E,
                               B, lam, D, edge))
    return out


def pair_hertz(lm: BevelLoadedModel, pm: PairMinimum, load2: float):
    """Elliptic Hertz of the whole gear torque ``load2`` (N mm) on one pair at its first contact, and the relative
    curvatures used (lambda floored: a flat direction is capped at 0.75 face width, the other at 1e-3 1/mm)."""
    cap = 0.75 * lm.pair.blank.face_width
    lam = np.maximum(pm.lam, [2 * 1e-3 / cap ** 2, 1e-3])
    return elliptic_hertz(load2 / pm.v2, 0.5 * lam[0], 0.5 * lam[1], lm.bodies.young, lm.bodies.poisson), lam


def window(lm: BevelLoadedModel, pm: PairMinimum, load2: float, widen: float = 1.0) -> tuple[float, float]:
    """Window semi-axes (along the major, across the minor axis), mm, for the gear torque ``load2`` (N mm); ``widen``
    multiplies the window approach (a pair whose loaded cells reached the window's rim)."""
    bl = lm.pair.blank
    cap = 0.75 * bl.face_width
    hz, lam = pair_hertz(lm, pm, load2)
    ka, kb = lm.fid.window
    a = min(np.sqrt(2 * ka * widen * hz.delta / lam[0]), cap)
    b = min(np.sqrt(2 * kb * widen * hz.delta / lam[1]), 0.5 * bl.whole_depth)
    return float(a), float(b)


def pair_cells(lm: BevelLoadedModel, phi1: float, pm: PairMinimum, load2: float) -> PairCells:
    """The cells of pair ``pm.j`` at ``phi1`` for the gear torque ``load2`` (module docstring)."""
    return cells_of(lm, phi1, [pm], load2)[0]


def cells_of(lm: BevelLoadedModel, phi1: float, pms: list[PairMinimum], load2: float,
             widen: dict | None = None) -> list[PairCells]:
    """The cells of several pairs at ``phi1``; each gap evaluation covers all pairs at once; ``widen`` {pair j:
    factor} enlarges the windows of pairs whose loaded cells reached the rim."""
    from ltca.geometry.bevel.gaps import PointGaps
    na, nb = lm.fid.cells
    lat, U, Y, phi, P0, E, Bi = [], [], [], [], [], [], []
    for pm in pms:
        a, b = window(lm, pm, load2, (widen or {}).get(pm.j, 1.0))
        dxi, deta = 2 * a / na, 2 * b / nb
        ka, kb = (na - 1) // 2 + 1, (nb - 1) // 2 + 1
        IA, IB = np.meshgrid(np.arange(-ka, ka + 1), np.arange(-kb, kb + 1), indexing="ij")
        xi, eta = IA * dxi, IB * deta
        inside = (xi / (a + 0.5 * dxi)) ** 2 + (eta / (b + 0.5 * deta)) ** 2 <= 1.0
        # the lattice points evaluated: the window and its ring of neighbours (for the edge labels)
        near = np.pad(inside, 1)
        near = (near[1:-1, 1:-1] | near[2:, 1:-1] | near[:-2, 1:-1] | near[1:-1, 2:] | near[1:-1, :-2])
        IA, IB, xi, eta, inside = IA[near], IB[near], xi[near], eta[near], inside[near]
        y = np.stack([xi, eta], 1) @ pm.D.T
        bi = np.linalg.inv(pm.B)
        lat.append((IA, IB, xi, eta, inside, dxi, deta, ka, kb))
        Y.append(y)
        U.append(np.array([pm.t, pm.L]) + y @ bi.T)
        n = len(y)
        phi.append(np.full(n, phi1 + pm.j * lm.gaps.c1))
        P0.append(np.broadcast_to(pm.r, (n, 3)))
        E.append(np.broadcast_to(pm.E, (n, 2, 3)))
        Bi.append(np.broadcast_to(bi, (n, 2, 2)))
    U, Y, phi, P0, E, Bi = (np.concatenate(v) for v in (U, Y, phi, P0, E, Bi))
    # tangent coordinates -> flank (t, L): du = B^-1 y, corrected once on the exact surface
    for _ in range(1):
        r1 = lm.gaps.P.surface(U[:, 0], U[:, 1])[0]            # the pinion surface alone
        y_now = np.einsum("nai,ni->na", E, r1 - P0)
        U = U + np.einsum("nab,nb->na", Bi, np.where(np.isfinite(y_now), Y - y_now, 0.0))
    res = _evaluate(lm, phi, U[:, 0], U[:, 1])
    ok_all = res.ok & np.isfinite(res.g)
    lab_all = _edge_labels(lm, U, res, ok_all)
    out, i0 = [], 0
    for pm, (IA, IB, xi, eta, inside, dxi, deta, ka, kb) in zip(pms, lat):
        n = IA.size
        sl = slice(i0, i0 + n)
        i0 += n
        ok, lab = ok_all[sl], lab_all[sl]
        keep = inside & ok
        # edge: a kept cell with a dropped lattice neighbour (off a flank), labelled by where the neighbour went
        sa, sb = IA - IA.min() + 1, IB - IB.min() + 1
        ok2 = np.ones((sa.max() + 2, sb.max() + 2), bool)
        lab2 = np.full(ok2.shape, "", dtype=object)
        ok2[sa, sb], lab2[sa, sb] = ok, lab
        in2 = np.zeros(ok2.shape, bool)
        in2[sa, sb] = inside
        edge = np.full(n, "", dtype=object)
        rim = np.zeros(n, bool)
        for dp, dq in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            o, lb = ok2[sa + dp, sb + dq], lab2[sa + dp, sb + dq]
            m = keep & (edge == "") & ~o & (lb != "")
            edge[m] = lb[m]
            rim |= keep & o & ~in2[sa + dp, sb + dq]          # next to a lattice point on the flank outside the window
        sel = np.flatnonzero(keep)
        # distance (mm, tangent plane) of each cell to the nearest lattice point off a flank edge that was evaluated
        off = ~ok & (lab != "")
        dist = np.full(len(sel), np.inf)
        if off.any() and len(sel):
            from scipy.spatial import cKDTree
            dist = cKDTree(np.stack([xi[off], eta[off]], 1)).query(np.stack([xi[sel], eta[sel]], 1))[0]
        g = PointGaps(*[getattr(res, f)[sl][sel] for f in PointGaps.__dataclass_fields__])
        out.append(PairCells(pm.j, IA[sel], IB[sel], xi[sel], eta[sel], U[sl][sel, 0], U[sl][sel, 1], g, dxi, deta,
                             edge[sel].astype(str), rim[sel], dist))
    return out


def _edge_labels(lm: BevelLoadedModel, U: np.ndarray, res, ok: np.ndarray) -> np.ndarray:
    """Where a dropped lattice point lies: off the pinion flank (``pinion top/root``, ``toe``, ``heel``) or off the
    gear flank (its ``toe``/``heel``, ``gear top`` beyond the face cone, ``gear root`` below the flank grid's lowest
    row near the root cone); '' where Newton failed on the flank itself."""
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
        from ltca.geometry.bevel.gaps import depth_fraction as body_t
        bl = lm.pair.blank
        L2, Rn2 = res.L2[rest], res.Rn2[rest]
        t2 = body_t(bl, "gear", lm.gaps.G.off, L2, Rn2)
        lab[np.flatnonzero(rest)] = np.select(
            [L2 < bl.inner_cone_distance, L2 > bl.outer_cone_distance, t2 > 1.0, t2 < 0.0],
            ["toe", "heel", "gear top", "gear root"], "")
    return lab
