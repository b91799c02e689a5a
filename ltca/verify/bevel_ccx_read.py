"""Read-out of a bevel CalculiX run (:mod:`ltca.verify.bevel_ccx`): pair torque shares and the interior peak pressure.

The interior peak is read like ours (:func:`ltca.verify.bevel_calculix.ours_at`, the largest cell pressure of the
cells farther than ``edge`` from every edge): on the pinion's slave nodes farther than ``edge`` from both members'
tops, toes and heels (:func:`interior`), the peak of a quadratic fit of p^2 (elliptic Hertz: p^2 is quadratic)
around the highest node whose neighbourhood resolves a pressure field (:func:`fit_peak`).  A node that stands
alone above its neighbours is a spike of the penalty contact, not a peak of the field, and is passed over: at
phi1 = 0, 133 um zone, one pinion node of pair -1 read 1924 MPa with its neighbours at 1309/1095/968 MPa (three
of them above 30 % of it within 2.5 h), where ours reads 983 and CalculiX's own interpolated field 925 MPa; the
Hertz ellipse of pair 0 read 1528 MPa (fit) next to it.
"""
from __future__ import annotations

import numpy as np

from ltca.geometry.bevel.tca import to_pitch_coords

__all__ = ["interior", "world_interior", "fit_peak", "read_pairs"]

SUPPORT = 8          # least nodes above 30 % of a candidate peak within the fit radius


def interior(lm, L1, Rn1, L2, Rn2, edge: float) -> np.ndarray:
    """Points (pinion and gear axial sections, mm) farther than ``edge`` mm from both members' tops, toes and heels
    (a member's root is the other's top)."""
    out = np.ones(np.shape(L1), bool)
    for M, L, Rn in ((lm.gaps.P, L1, Rn1), (lm.gaps.G, L2, Rn2)):
        out &= (M._cones(L)[1] - Rn > edge) & (L > M.Ai + edge) & (L < M.A0 - edge)
    return out


def world_interior(lm, X: np.ndarray, T2: np.ndarray, edge: float) -> np.ndarray:
    """:func:`interior` of world points X on the pinion (world = pinion frame at its deck angle ``T1 = rz``), the
    gear placed by the 4x4 frame ``T2``."""
    bl = lm.pair.blank
    L1, Rn1 = to_pitch_coords(X, bl.pinion.pitch_angle)
    Xg = (X - T2[:3, 3]) @ T2[:3, :3]
    L2, Rn2 = to_pitch_coords(Xg, bl.gear.pitch_angle)
    return interior(lm, L1, Rn1, L2, Rn2, edge)


def _fit_at(X: np.ndarray, p: np.ndarray, i: int, radius: float) -> float | None:
    """Fitted peak around node i, None when fewer than :data:`SUPPORT` nodes above 0.3 p[i] lie within
    ``radius``."""
    m = (np.linalg.norm(X - X[i], axis=1) < radius) & (p > 0.3 * p[i])
    if m.sum() < SUPPORT:
        return None
    Y = X[m] - X[i]
    vt = np.linalg.svd(Y - Y.mean(0), full_matrices=False)[2]
    a, b = Y @ vt[0], Y @ vt[1]
    A = np.column_stack([np.ones_like(a), a, b, a * a, a * b, b * b])
    c = np.linalg.lstsq(A, p[m] ** 2, rcond=None)[0]
    H = np.array([[2 * c[3], c[4]], [c[4], 2 * c[5]]])
    if np.all(np.linalg.eigvalsh(H) < 0):
        x = np.linalg.solve(H, -c[1:3])
        if np.hypot(*x) < radius:
            return float(np.sqrt(max(c[0] + 0.5 * c[1:3] @ x, 0.0)))
    return float(np.sqrt(max(np.max(A @ c), 0.0)))


def fit_peak(X: np.ndarray, p: np.ndarray, radius: float) -> float:
    """Peak of the nodal pressures p at points X: the fit (:func:`_fit_at`) around the highest node with at least
    :data:`SUPPORT` nodes above 30 % of it within ``radius`` (isolated spikes passed over); the nodal maximum when
    no node has that support (a field narrower than the mesh)."""
    if not len(p):
        return 0.0
    for i in np.argsort(-p):
        v = _fit_at(X, p, int(i), radius)
        if v is not None:
            return v
    return float(p.max())


def read_pairs(lm, res, X: np.ndarray, nodes1: np.ndarray, T2: np.ndarray, groups: dict, pairs, owner, pairs_j,
               edge: float, radius: float) -> tuple[dict, dict, float, float]:
    """Pair torques about the pinion axis (N mm, each pair's force at its pressure centroid; a gear-slave pair's
    force acts on the gear: its reaction on the pinion), pair forces (N), interior peak pressure on the pinion's
    flank and the nodal maximum (MPa) of the CalculiX results ``res``.

    X : world points of all nodes (pinion first);  nodes1 : pinion nodes, body frame;  groups : {member: facet
    groups};  pairs, owner : contact pairs and their tooth pair j."""
    n1 = len(nodes1)
    idx = res.contact_nodes - 1
    ok = (idx >= 0) & (idx < len(X)) & (res.contact_pressure > 0)
    idx, p = idx[ok], res.contact_pressure[ok]
    torques, forces, peaks = {j: 0.0 for j in pairs_j}, {j: 0.0 for j in pairs_j}, []
    for j, pr in zip(owner, pairs):
        gear_slave = pr.slave[0] == "gear"
        on = np.isin(idx, np.unique(groups[pr.slave[0]][pr.slave[1][0]]) + (n1 if gear_slave else 0))
        F = np.asarray(res.pair_force.get(pr.name, np.zeros(3))) * (-1.0 if gear_slave else 1.0)
        forces[j] += float(np.linalg.norm(F))
        if on.any() and np.linalg.norm(F) > 0.0:
            c = (p[on, None] * X[idx[on]]).sum(0) / p[on].sum()
            torques[j] += float(np.cross(c, F)[2])
        keep = on & (idx < n1)
        keep[keep] = world_interior(lm, X[idx[keep]], T2, edge)
        if keep.any():
            peaks.append(fit_peak(nodes1[idx[keep]], p[keep], radius))
    return ({j: abs(v) for j, v in torques.items()}, forces, max(peaks, default=0.0),
            float(p.max()) if p.size else 0.0)
