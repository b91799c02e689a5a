"""Loaded tooth contact of a bevel pair at one pinion angle: cells, compliance, complementarity, torque balance.

The same path as the cylindrical LTCA (:mod:`ltca.cylindrical.loaded`): the cells' compliance is the two bodies'
FE regular part on their flank grids (:meth:`ltca.fem.compliance.BodyCompliance.weights`, bilinear) plus the
half-space near field between the cells of one pair (:func:`ltca.fem.halfspace.surface_influence`, uniform pressure on
each rectangular cell of the tangent-plane lattice), and :func:`ltca.fem.contact.solve_contact` finds the forces and
the gear's extra rotation under the torque balance  sum F_i v2_i = T2,  with the unloaded gaps
g0_i = (g_i - g_min) v2_i  (g: closing gear rotation of the cell, v2: its gear lever, mm/rad).

Signs: the pinion drives; its torque T1 (N mm) loads the working flank (pinion concave) for T1 > 0 as the case
reads it, and the gear torque is T2 = T1 z2 / z1.  The loaded TE (rad, driven sense, negative = gear lags) is
-(g_min + theta - g_ref) with g_ref the first-contact rotation at phi1 = 0: it tends to the unloaded TE
-(g_min - g_ref) as the load vanishes.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ltca.fem.halfspace import surface_influence

from ..position import cell_compliance, root_stresses, solve_rounds
from .cells import PairCells, cells_of, pair_hertz, pair_minima
from .loaded_model import LOADED, BevelLoadedModel, body_t

__all__ = ["BevelPosition", "solve_position"]


@dataclass(frozen=True)
class BevelPosition:
    """Loaded contact at one pinion angle (N, mm, MPa, rad).

    phi1 : pinion angle;  te, te0 : loaded and unloaded TE (rad, driven sense);  theta : extra gear rotation
    under load;  pair : (n,) tooth pair of each cell;  t, L : pinion flank coordinates;  L2, Rn2 : gear
    axial-section coordinates of the touched point;  L1, Rn1 : pinion axial section;  xi, eta : tangent-plane
    lattice coordinates;  r1 : (n, 3) cell centres on pinion tooth 0, pinion body frame;  area, force, pressure,
    gap0 : per cell;  edge : (n,) edge the cell borders ('' inside);  edge_dist : (n,) its distance to the nearest
    point off a flank edge, mm;
    pair_share : {j: share of the gear torque};  root1, root2 : {pinion tooth / gear tooth: max principal
    fillet stress};  ellipse : {j: (lambda1, lambda2, v2)} of the first contact;  torque_residual :
    |sum F v2 - T2| / T2;  pinion_balance : sum F v1 / T1 (1 for conjugate levers);  iterations, residual.
    """
    phi1: float
    te: float
    te0: float
    theta: float
    pair: np.ndarray
    t: np.ndarray
    L: np.ndarray
    L1: np.ndarray
    Rn1: np.ndarray
    L2: np.ndarray
    Rn2: np.ndarray
    xi: np.ndarray
    eta: np.ndarray
    r1: np.ndarray
    area: np.ndarray
    force: np.ndarray
    pressure: np.ndarray
    gap0: np.ndarray
    edge: np.ndarray
    edge_dist: np.ndarray
    pair_share: dict
    root1: dict
    root2: dict
    ellipse: dict
    torque_residual: float
    pinion_balance: float
    iterations: int
    residual: float

    @property
    def max_pressure(self) -> float:
        return float(self.pressure.max()) if self.pressure.size else 0.0

    def edge_load(self) -> dict[str, float]:
        """Force (N) carried by cells at each edge."""
        out: dict[str, float] = {}
        for e in np.unique(self.edge[self.force > 0]):
            if e:
                out[str(e)] = float(self.force[(self.edge == e)].sum())
        return out


def _near_field(c: PairCells, E: float, nu: float) -> np.ndarray:
    """Half-space surface compliance of both bodies between the cells of one pair, (n, n), mm/N, from a table
    over integer lattice offsets (uniform pressure on dxi x deta rectangles)."""
    di = np.arange(c.ia.min() - c.ia.max(), c.ia.max() - c.ia.min() + 1)
    dj = np.arange(c.ib.min() - c.ib.max(), c.ib.max() - c.ib.min() + 1)
    DI, DJ = np.meshgrid(di, dj, indexing="ij")
    table = 2.0 * surface_influence(DI * c.dxi, DJ * c.deta, 0.5 * c.dxi, 0.5 * c.deta, E, nu)
    return table[c.ia[:, None] - c.ia[None, :] - di[0], c.ib[:, None] - c.ib[None, :] - dj[0]]


def solve_position(lm: BevelLoadedModel, phi1: float, torque1: float, tol: float = 1e-9) -> BevelPosition:
    """Loaded contact at pinion angle ``phi1`` (rad) under the pinion torque ``torque1`` (N mm, > 0); see
    :func:`_solve_position`.  BLAS runs on one thread here: the dense systems are small (a few hundred active
    cells), and a multi-threaded BLAS on a busy machine spins (measured: 2 s instead of 5 ms per contact solve
    at a load of 5 on 2 cores)."""
    from threadpoolctl import threadpool_limits
    with threadpool_limits(limits=1, user_api="blas"):
        return _solve_position(lm, phi1, torque1, tol)


def _solve_position(lm: BevelLoadedModel, phi1: float, torque1: float, tol: float = 1e-9) -> BevelPosition:
    """Loaded contact at pinion angle ``phi1`` (rad) under the pinion torque ``torque1`` (N mm, > 0).

    Raises
    ------
    ConvergenceError
        The contact problem did not converge (residual and advice in the message).
    ValueError
        No tooth pair is over the gear flank at this angle.
    """
    bl = lm.pair.blank
    T2 = torque1 * bl.gear.z / bl.pinion.z
    mins = [m for m in pair_minima(lm, phi1, LOADED) if m is not None]
    if not mins:
        raise ValueError(f"phi1 = {phi1:.5f} rad: no tooth pair of the {lm.side} pinion flank touches the gear")
    g_min = min(m.g for m in mins)
    # pairs that can close: first within a generous bound (5x one pair's Hertz approach plus the bodies'
    # bending under the whole load at the first contact), then every pair whose first contact the loaded
    # rotation would pass (re-solved with it: the loaded rotation decides, not the estimate)
    b1, b2 = lm.bodies.body1, lm.bodies.body2
    first = min(mins, key=lambda m: m.g)
    w1, w2 = _weights_of(lm, np.array([first.j]), lm.gaps.gaps(phi1 + first.j * lm.gaps.c1, np.array([first.t]),
                                                                np.array([first.L]), extend=True))
    bend = float(T2 / first.v2 * ((w1 @ (w1 @ b1.C).T)[0, 0] + (w2 @ (w2 @ b2.C).T)[0, 0]))
    use = [m for m in mins
           if m is first or (m.g - g_min) * m.v2 <= 5.0 * pair_hertz(lm, m, T2)[0].delta + 3.0 * abs(bend)]
    widen: dict[int, float] = {}

    def assemble():
        cells = [c for c in cells_of(lm, phi1, use, T2, widen) if len(c.t)]
        return cells, _system(lm, cells)

    def solve_args(x):
        sy = x[1]
        return sy["C"], (sy["g"] - sy["gm"]) * sy["v2"], sy["v2"], T2, None

    def grow(x, sol) -> bool:
        cells, sy = x
        more = [m for m in mins if m not in use and m.g < sy["gm"] + sol.approach]
        # a pair whose loaded cells reach its window's rim on the flank gets a wider window
        i0, grown = 0, False
        for c in cells:
            f = sol.force[i0:i0 + len(c.t)]
            i0 += len(c.t)
            if np.any(f[c.rim] > 1e-6 * max(f.max(), 1e-300)) and widen.get(c.j, 1.0) < 40:
                widen[c.j] = widen.get(c.j, 1.0) * 1.8
                grown = True
        if not more and not grown:
            return False
        use.extend(more)
        return True

    (cells, sy), sol = solve_rounds(assemble, solve_args, grow, len(mins) + 6,
                                    f"bevel contact at phi1 = {phi1:.5f} rad, pinion torque {torque1 / 1e3:.4g} N m",
                                    tol=tol)
    gm, pair, v2, v1, area = sy["gm"], sy["pair"], sy["v2"], sy["v1"], sy["area"]
    g0 = (sy["g"] - gm) * v2
    W1, W2 = sy["W1"], sy["W2"]
    F = sol.force
    shares = {int(c.j): float(F[pair == c.j] @ v2[pair == c.j] / T2) for c in cells}
    cat = lambda f: np.concatenate([getattr(c.gaps, f) for c in cells])       # noqa: E731
    edge = np.concatenate([c.edge for c in cells])
    ellipse = {int(m.j): (float(m.lam[0]), float(m.lam[1]), float(m.v2)) for m in mins}
    return BevelPosition(
        float(phi1), float(-(gm + sol.approach - lm.g_ref)), float(-(min(g_min, gm) - lm.g_ref)), float(sol.approach),
        pair, sy["t"], sy["L"], cat("L1"), cat("Rn1"), cat("L2"), cat("Rn2"), np.concatenate([c.xi for c in cells]),
        np.concatenate([c.eta for c in cells]), cat("r1"), area, F, F / area, g0, edge,
        np.concatenate([c.edge_dist for c in cells]), shares,
        *root_stresses(b1, W1, b2, W2, F), ellipse, abs(F @ v2 - T2) / T2, float(F @ v1 / torque1),
        sol.iterations, sol.residual)


def _system(lm: BevelLoadedModel, cells: list[PairCells]) -> dict:
    """Cells of the included pairs stacked: coordinates, gaps, levers, areas and the compliance (n, n)."""
    cat = lambda f: np.concatenate([getattr(c.gaps, f) for c in cells])       # noqa: E731
    out = dict(pair=np.concatenate([np.full(len(c.t), c.j) for c in cells]),
               t=np.concatenate([c.t for c in cells]), L=np.concatenate([c.L for c in cells]),
               g=cat("g"), v2=cat("v2"), v1=cat("v1"),
               area=np.concatenate([np.full(len(c.t), c.dxi * c.deta) for c in cells]))
    out["gm"] = float(out["g"].min())
    W1, W2 = _cell_weights(lm, cells)
    blocks = None
    if lm.fid.near_field:
        E, nu = lm.bodies.young, lm.bodies.poisson
        blocks, i0 = [], 0
        for c in cells:
            blocks.append((np.arange(i0, i0 + len(c.t)), _near_field(c, E, nu)))
            i0 += len(c.t)
    out.update(C=cell_compliance(lm.bodies.body1, W1, lm.bodies.body2, W2, blocks), W1=W1, W2=W2)
    return out


def _weights_of(lm: BevelLoadedModel, j: np.ndarray, res):
    bl = lm.pair.blank
    B = lm.bodies
    t1 = body_t(bl, "pinion", B.off1, res.L1, res.Rn1)
    t2 = body_t(bl, "gear", B.off2, res.L2, res.Rn2)
    return B.body1.weights(j, t1, res.L1), B.body2.weights(-j, t2, res.L2)


def _cell_weights(lm: BevelLoadedModel, cells: list[PairCells]):
    import scipy.sparse as sp
    W = [_weights_of(lm, np.full(len(c.t), c.j), c.gaps) for c in cells]
    return sp.vstack([w[0] for w in W]).tocsr(), sp.vstack([w[1] for w in W]).tocsr()
