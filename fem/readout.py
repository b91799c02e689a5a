"""Point read-out on a P2 tetrahedral mesh: locating points, displacement interpolation, stress.

Conventions of :mod:`ltca.fem.elastic` (straight-edged, subparametric tets; dofs node-major).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree

from .elastic import EDGES, _T, _affine, _check_mesh, lame, p2_shape

__all__ = ["locate_points", "interpolation_matrix", "stress_matrix", "element_stress_matrix", "nodal_stress"]


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


def _stress_coefficients(g: np.ndarray, bary: np.ndarray, lam: float, mu: float) -> np.ndarray:
    """d sigma_v / d u_ik at barycentric points ``bary`` (n, 4) of elements with barycentric gradients ``g``
    (n, 4, 3), (n, 6, 10, 3), Voigt xx, yy, zz, yz, xz, xy."""
    G = np.matmul(np.einsum("icd,nd->nic", _T, bary), g)               # grad N_i, (n, 10, 3)
    S = np.zeros((len(g), 6, 10, 3))
    for k in range(3):
        S[:, k, :, k] += 2 * mu * G[:, :, k]
        S[:, :3, :, k] += lam * G[:, None, :, k]
    for v, (a, b) in zip((3, 4, 5), ((1, 2), (0, 2), (0, 1))):
        S[:, v, :, a] = mu * G[:, :, b]
        S[:, v, :, b] = mu * G[:, :, a]
    return S


def _rows(S: np.ndarray, tets: np.ndarray, n_dofs: int) -> sp.csr_matrix:
    """Sparse (6 k, n_dofs) matrix of the coefficients S (k, 6, 10, 3) of elements ``tets`` (k, 10), one row block
    each."""
    k = len(S)
    r = np.broadcast_to(6 * np.arange(k)[:, None, None, None] + np.arange(6)[:, None, None], S.shape)
    c = np.broadcast_to(_point_dofs(tets, np.arange(k))[:, None], S.shape)
    return sp.csr_matrix((S.ravel(), (r.ravel(), c.ravel())), shape=(6 * k, n_dofs))


def stress_matrix(nodes: np.ndarray, tets: np.ndarray, E: float, nu: float,
                  points: np.ndarray, recovery: str = "element") -> sp.csr_matrix:
    """Matrix mapping nodal displacements to Cauchy stress at points.

    Parameters
    ----------
    nodes : ndarray, (N, 3)
    tets : ndarray of int, (M, 10)
    E, nu : float
        Young's modulus [MPa], Poisson ratio.
    points : ndarray, (n, 3)
        Points [mm].
    recovery : {"element", "nodal"}
        "element": the stress of the element containing each point (discontinuous between elements; on a shared
        face the choice is arbitrary). "nodal": the stress of every element at each of its 10 nodes, averaged at
        the node over the elements sharing it, interpolated to the point with the P2 shape functions of the
        element containing it: the nodal stresses of CalculiX's ``*EL FILE S`` (its C3D10 stress, linear in the
        element, extrapolated from the integration points to the nodes and averaged there; CalculiX manual,
        ``*EL FILE``), continuous, and less sensitive to where the nodes of a faceted curved surface fall.

    Returns
    -------
    scipy.sparse.csr_matrix, (6n, 3N)
        Rows ``6i + v`` with Voigt order v = xx, yy, zz, yz, xz, xy [MPa per mm].
    """
    nodes, tets = _check_mesh(nodes, tets, 10, "tets")
    if recovery not in ("element", "nodal"):
        raise ValueError(f"recovery = {recovery!r} must be 'element' or 'nodal'")
    if recovery == "element":
        return element_stress_matrix(nodes, tets, E, nu, *locate_points(nodes, tets, points))
    P, A = nodal_stress(nodes, tets, E, nu, points)
    return (P @ A).tocsr()


def element_stress_matrix(nodes: np.ndarray, tets: np.ndarray, E: float, nu: float, elem: np.ndarray,
                          bary: np.ndarray) -> sp.csr_matrix:
    """:func:`stress_matrix` (element recovery) at points given by their elements and barycentric coordinates.

    For points whose element is known (the centroids of chosen elements: ``bary`` = 1/4 each), without
    :func:`locate_points`' search of the whole mesh.

    Parameters
    ----------
    nodes : ndarray, (N, 3)
    tets : ndarray of int, (M, 10)
    E, nu : float
        Young's modulus [MPa], Poisson ratio.
    elem : ndarray of int, (n,)
        Element of each point.
    bary : ndarray, (4,) or (n, 4)
        Barycentric coordinates w.r.t. the vertices 0..3.

    Returns
    -------
    scipy.sparse.csr_matrix, (6n, 3N)
        Rows ``6i + v`` with Voigt order v = xx, yy, zz, yz, xz, xy [MPa per mm].
    """
    nodes, tets = _check_mesh(nodes, tets, 10, "tets")
    elem = np.asarray(elem, dtype=np.int64)
    lam, mu = lame(E, nu)
    _, _, g, _ = _affine(nodes, tets[elem])
    bary = np.broadcast_to(np.asarray(bary, dtype=float), (len(elem), 4))
    return _rows(_stress_coefficients(g, bary, lam, mu), tets[elem], 3 * len(nodes))


def nodal_stress(nodes: np.ndarray, tets: np.ndarray, E: float, nu: float,
                 points: np.ndarray) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """The nodal-averaged stress at points (``stress_matrix(..., recovery="nodal")``) as two factors ``P @ A``.

    ``A`` (6u, 3N) maps the displacements to the averaged stress at the u nodes of the elements containing the
    points, ``P`` (6n, 6u) interpolates those with the P2 shape functions. Observing ``A`` in a solve and applying
    ``P`` after keeps many points in few elements cheap (the product has far more non-zeros than its factors).

    Parameters
    ----------
    nodes : ndarray, (N, 3)
    tets : ndarray of int, (M, 10)
    E, nu : float
        Young's modulus [MPa], Poisson ratio.
    points : ndarray, (n, 3)
        Points [mm].

    Returns
    -------
    P : scipy.sparse.csr_matrix, (6n, 6u)
    A : scipy.sparse.csr_matrix, (6u, 3N)
        Rows in Voigt order xx, yy, zz, yz, xz, xy per point / node [MPa per mm].
    """
    nodes, tets = _check_mesh(nodes, tets, 10, "tets")
    lam, mu = lame(E, nu)
    elem, bary = locate_points(nodes, tets, points)
    n = len(elem)
    # the nodes of the containing elements, and every (element, local node) incidence of those nodes
    used, inv = np.unique(tets[elem], return_inverse=True)
    inv = inv.reshape(n, 10)
    pos = np.searchsorted(used, tets).clip(0, len(used) - 1)
    e_idx, a_idx = np.nonzero(used[pos] == tets)
    node_of = pos[e_idx, a_idx]                                         # index into `used`
    count = np.bincount(node_of, minlength=len(used)).astype(float)
    near, e_of = np.unique(e_idx, return_inverse=True)
    _, _, g, _ = _affine(nodes, tets[near])
    S = _stress_coefficients(g[e_of], _NODE_BARY[a_idx], lam, mu) / count[node_of, None, None, None]
    # sum the 6 x 3 blocks of each (averaged node, displacement node) pair: a block sparse row matrix
    key = (node_of[:, None].astype(np.int64) * len(nodes) + tets[e_idx]).ravel()
    order = np.argsort(key, kind="stable")
    ks = key[order]
    start = np.flatnonzero(np.r_[True, ks[1:] != ks[:-1]])
    blocks = np.add.reduceat(S.transpose(0, 2, 1, 3).reshape(-1, 6, 3)[order], start, axis=0)
    row, col = np.divmod(ks[start], len(nodes))
    A = sp.bsr_matrix((blocks, col, np.searchsorted(row, np.arange(len(used) + 1))),
                      shape=(6 * len(used), 3 * len(nodes))).tocsr()
    v = np.tile(np.arange(6), 10 * n)
    P = sp.csr_matrix((np.repeat(p2_shape(bary).ravel(), 6),
                       (np.repeat(6 * np.arange(n), 60) + v, 6 * np.repeat(inv.ravel(), 6) + v)),
                      shape=(6 * n, 6 * len(used)))
    return P, A


#: barycentric coordinates of the 10 nodes of the tetrahedron (vertices, then the mid-edges of ``EDGES``)
_NODE_BARY = np.concatenate([np.eye(4), 0.5 * (np.eye(4)[EDGES[:, 0]] + np.eye(4)[EDGES[:, 1]])])
