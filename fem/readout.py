"""Point read-out on a P2 tetrahedral mesh: locating points, displacement interpolation, stress.

Conventions of :mod:`fem.elastic` (straight-edged, subparametric tets; dofs node-major).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree

from .elastic import _T, _affine, _check_mesh, lame, p2_shape

__all__ = ["locate_points", "interpolation_matrix", "stress_matrix"]


def locate_points(nodes: np.ndarray, tets: np.ndarray, points: np.ndarray,
                  k: int = 16, tol: float = 1e-9) -> tuple[np.ndarray, np.ndarray]:
    """Element and barycentric coordinates of points (straight-edged tets).

    Candidates are the ``k`` elements with the nearest centroids (cKDTree); points not
    inside any of them are retried with ``8 k`` candidates. A point outside the mesh (or
    in none of the candidates) gets the candidate it is least outside of (largest minimum
    barycentric coordinate), with its coordinates clamped to >= 0 and renormalised: the
    point is projected into that element, which is what a point a little off a curved
    flank (straight tets under a curved surface) needs.

    Parameters
    ----------
    nodes : ndarray, (N, 3)
    tets : ndarray of int, (M, 10) or (M, 4)
    points : ndarray, (n, 3)
        Points [mm].
    k : int
        Candidate elements per point, >= 1.
    tol : float
        A point is inside when every barycentric coordinate is >= -tol.

    Returns
    -------
    elem : ndarray of int, (n,)
    bary : ndarray, (n, 4)
        Barycentric coordinates w.r.t. vertices 0..3, non-negative, summing to 1.
    """
    nodes = np.asarray(nodes, dtype=float)
    tets = np.asarray(tets)
    if tets.ndim != 2 or tets.shape[1] not in (4, 10):
        raise ValueError(f"tets: shape {tets.shape}, must be (M, 10) or (M, 4)")
    nodes, _ = _check_mesh(nodes, tets[:, :4], 4, "tets")
    p = np.atleast_2d(np.asarray(points, dtype=float))
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"points: shape {p.shape}, must be (n, 3)")
    if k < 1:
        raise ValueError(f"k = {k}: must be >= 1")
    x0, Jinv, _, _ = _affine(nodes, tets)
    tree = cKDTree(nodes[tets[:, :4]].mean(axis=1))

    def search(pts: np.ndarray, kk: int):
        kk = min(kk, len(tets))
        _, cand = tree.query(pts, k=kk)
        cand = cand.reshape(len(pts), kk)
        l123 = np.einsum("nkij,nkj->nki", Jinv[cand], pts[:, None, :] - x0[cand])
        bary = np.concatenate([1.0 - l123.sum(axis=2, keepdims=True), l123], axis=2)
        best = np.argmax(bary.min(axis=2), axis=1)  # inside if any; else least outside
        r = np.arange(len(pts))
        return cand[r, best], bary[r, best]

    elem, bary = search(p, k)
    out = bary.min(axis=1) < -tol
    if out.any() and k < len(tets):
        e2, b2 = search(p[out], 8 * k)
        better = b2.min(axis=1) > bary[out].min(axis=1)
        idx = np.flatnonzero(out)[better]
        elem[idx], bary[idx] = e2[better], b2[better]
    bary = np.clip(bary, 0.0, None)
    bary /= bary.sum(axis=1, keepdims=True)
    return elem, bary


def _point_dofs(tets: np.ndarray, elem: np.ndarray) -> np.ndarray:
    return 3 * tets[elem][:, :, None] + np.arange(3)  # (n, 10, 3)


def interpolation_matrix(nodes: np.ndarray, tets: np.ndarray, points: np.ndarray) -> sp.csr_matrix:
    """Matrix mapping nodal displacements to displacements at points.

    Parameters
    ----------
    nodes : ndarray, (N, 3)
    tets : ndarray of int, (M, 10)
    points : ndarray, (n, 3)
        Points [mm]; see `locate_points` for points slightly outside the mesh.

    Returns
    -------
    scipy.sparse.csr_matrix, (3n, 3N)
        ``(P @ u)[3i + k]`` is displacement component k at point i (P2 shape functions).
    """
    nodes, tets = _check_mesh(nodes, tets, 10, "tets")
    elem, bary = locate_points(nodes, tets, points)
    n = len(elem)
    Nv = p2_shape(bary)                                                 # (n, 10)
    val = np.broadcast_to(Nv[:, :, None], (n, 10, 3))
    row = np.broadcast_to(3 * np.arange(n)[:, None, None] + np.arange(3), (n, 10, 3))
    return sp.csr_matrix((val.ravel(), (row.ravel(), _point_dofs(tets, elem).ravel())),
                         shape=(3 * n, 3 * len(nodes)))


def stress_matrix(nodes: np.ndarray, tets: np.ndarray, E: float, nu: float,
                  points: np.ndarray) -> sp.csr_matrix:
    """Matrix mapping nodal displacements to Cauchy stress at points.

    Parameters
    ----------
    nodes : ndarray, (N, 3)
    tets : ndarray of int, (M, 10)
    E, nu : float
        Young's modulus [MPa], Poisson ratio.
    points : ndarray, (n, 3)
        Points [mm] (the element containing each point is used; on a shared face the
        choice is arbitrary, stresses being discontinuous there).

    Returns
    -------
    scipy.sparse.csr_matrix, (6n, 3N)
        Rows ``6i + v`` with Voigt order v = xx, yy, zz, yz, xz, xy [MPa per mm].
    """
    nodes, tets = _check_mesh(nodes, tets, 10, "tets")
    lam, mu = lame(E, nu)
    elem, bary = locate_points(nodes, tets, points)
    n = len(elem)
    _, _, g, _ = _affine(nodes, tets[elem])                             # (n, 4, 3)
    G = np.einsum("icd,nd,nck->nik", _T, bary, g)                       # grad N_i, (n, 10, 3)
    S = np.zeros((n, 6, 10, 3))                                          # d sigma_v / d u_ik
    for k in range(3):
        S[:, k, :, k] += 2 * mu * G[:, :, k]
        S[:, :3, :, k] += lam * G[:, None, :, k]
    for v, (a, b) in zip((3, 4, 5), ((1, 2), (0, 2), (0, 1))):
        S[:, v, :, a] = mu * G[:, :, b]
        S[:, v, :, b] = mu * G[:, :, a]
    row = np.broadcast_to(6 * np.arange(n)[:, None, None, None] + np.arange(6)[:, None, None], S.shape)
    col = np.broadcast_to(_point_dofs(tets, elem)[:, None], S.shape)
    return sp.csr_matrix((S.ravel(), (row.ravel(), col.ravel())), shape=(6 * n, 3 * len(nodes)))
