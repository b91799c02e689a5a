"""Surface loads on quadratic (6-node) facets of a P2 tetrahedral mesh: tractions and unit patch loads.

Conventions of :mod:`ltca.fem.elastic` (``tri6`` facets: vertices 0-2, then mid-edge nodes of 01, 12, 20; dofs
node-major). Loads integrate over the quadratic facets (curved surfaces exactly as meshed).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree

from .elastic import TRI_EDGES, _check_mesh, p2_shape

__all__ = ["surface_traction_load", "patch_loads", "patch_quadrature"]


def _triangle_rule(refine: int) -> tuple[np.ndarray, np.ndarray]:
    """Barycentric points (q, 3) and weights (q,) summing to 1 on a triangle.

    The 7-point degree-5 rule (Strang & Fix 1973, table 4.1; Dunavant 1985) applied on
    each of the ``4**refine`` congruent sub-triangles of a uniform subdivision.
    """
    a1, b1, w1 = 0.0597158717897698, 0.4701420641051151, 0.1323941527885062
    a2, b2, w2 = 0.7974269853530873, 0.1012865073234563, 0.1259391805448271
    pts = np.array([[1 / 3, 1 / 3, 1 / 3],
                    [a1, b1, b1], [b1, a1, b1], [b1, b1, a1],
                    [a2, b2, b2], [b2, a2, b2], [b2, b2, a2]])
    wts = np.array([0.225, w1, w1, w1, w2, w2, w2])
    tris = np.eye(3)[None]  # sub-triangles as (s, 3 vertices, 3 bary)
    for _ in range(refine):
        v0, v1, v2 = tris[:, 0], tris[:, 1], tris[:, 2]
        m01, m12, m20 = (v0 + v1) / 2, (v1 + v2) / 2, (v2 + v0) / 2
        tris = np.concatenate([np.stack(s, axis=1) for s in
                               ((v0, m01, m20), (m01, v1, m12), (m20, m12, v2), (m12, m20, m01))])
    q = np.einsum("pa,sab->spb", pts, tris).reshape(-1, 3)
    return q, np.tile(wts, len(tris)) / len(tris)


def _facet_quadrature(nodes: np.ndarray, tri6: np.ndarray, refine: int):
    """Quadrature on the quadratic facets: points (F, q, 3), dA weights (F, q) [mm^2], shape values (q, 6)."""
    bary, wts = _triangle_rule(refine)
    N = p2_shape(bary, TRI_EDGES)                        # (q, 6)
    dL = 4.0 * bary[:, :, None] * np.eye(3)[None] - np.eye(3)[None] * 1.0  # d(vertex N_a)/dL_c
    dN = np.zeros((len(bary), 6, 3))                     # dN_i / dL_c, (q, 6, 3)
    dN[:, :3, :] = dL
    for i, (a, b) in enumerate(TRI_EDGES):
        dN[:, 3 + i, a] = 4.0 * bary[:, b]
        dN[:, 3 + i, b] = 4.0 * bary[:, a]
    X = nodes[tri6]                                      # (F, 6, 3)
    d1 = np.einsum("qi,fik->fqk", dN[:, :, 1] - dN[:, :, 0], X)  # dx/dL1 with L0 = 1 - L1 - L2
    d2 = np.einsum("qi,fik->fqk", dN[:, :, 2] - dN[:, :, 0], X)
    dA = 0.5 * np.linalg.norm(np.cross(d1, d2), axis=-1) * wts  # reference triangle area 1/2
    return np.einsum("qi,fik->fqk", N, X), dA, N


def surface_traction_load(nodes: np.ndarray, tri6: np.ndarray, traction: np.ndarray,
                          refine: int = 0) -> np.ndarray:
    """Consistent nodal loads of a traction field on quadratic surface facets.

    Parameters
    ----------
    nodes : ndarray, (N, 3)
        Node coordinates [mm].
    tri6 : ndarray of int, (F, 6)
        Loaded facets (vertices, then mid-edge nodes 01, 12, 20).
    traction : ndarray, (3,), (N, 3) or (F, 6, 3)
        Traction [MPa] (force per area of the deformed-free surface): constant, at every
        node, or at the nodes of every facet; interpolated with the P2 facet basis.
    refine : int
        Levels of subdivision of the 7-point quadrature (0: degree 5 per facet).

    Returns
    -------
    ndarray, (3N,)
        ``f[3a+k] = sum_facets int N_a t_k dA`` [N].
    """
    nodes, tri6 = _check_mesh(nodes, tri6, 6, "tri6")
    t = np.asarray(traction, dtype=float)
    if t.shape == (3,):
        t = np.broadcast_to(t, (len(tri6), 6, 3))
    elif t.shape == (len(nodes), 3):
        t = t[tri6]
    elif t.shape != (len(tri6), 6, 3):
        raise ValueError(f"traction: shape {t.shape}, must be (3,), ({len(nodes)}, 3) or ({len(tri6)}, 6, 3)")
    _, dA, N = _facet_quadrature(nodes, tri6, refine)
    tq = np.einsum("qi,fik->fqk", N, t) * dA[:, :, None]     # (F, q, 3)
    fa = np.einsum("qa,fqk->fak", N, tq)                       # (F, 6, 3)
    dof = 3 * tri6[:, :, None] + np.arange(3)
    return np.bincount(dof.ravel(), weights=fa.ravel(), minlength=3 * len(nodes))


def patch_quadrature(nodes: np.ndarray, tri6: np.ndarray, centres: np.ndarray, radius: float,
                     refine: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The traction distribution of :func:`patch_loads` as weighted facet quadrature points.

    Returns
    -------
    patch : ndarray of int, (k,)
        Patch (centre) of each hit.
    q : ndarray of int, (k,)
        Flat quadrature point index, ``facet * points_per_facet + point``.
    points : ndarray, (k, 3)
        The quadrature points, mm.
    weights : ndarray, (k,)
        Cosine-bell weight times area, normalised to sum to 1 per patch (a unit force).
    """
    nodes, tri6 = _check_mesh(nodes, tri6, 6, "tri6")
    c = np.atleast_2d(np.asarray(centres, dtype=float))
    if c.ndim != 2 or c.shape[1] != 3:
        raise ValueError(f"centres: shape {c.shape}, must be (m, 3)")
    if not np.isfinite(radius) or radius <= 0:
        raise ValueError(f"radius = {radius}: must be > 0 (mm)")
    X, dA, _ = _facet_quadrature(nodes, tri6, refine)
    Xf = X.reshape(-1, 3)
    hits = cKDTree(Xf).query_ball_point(c, radius)
    counts = np.array([len(h) for h in hits])
    if np.any(counts == 0):
        j = int(np.flatnonzero(counts == 0)[0])
        raise ValueError(f"radius = {radius}: patch {j} at {c[j]} reaches no facet quadrature point; "
                         "increase radius (> facet size / 2) or refine, or move the centre onto tri6")
    patch = np.repeat(np.arange(len(c)), counts)
    q = np.concatenate([np.asarray(h, dtype=np.int64) for h in hits])
    d = np.linalg.norm(Xf[q] - c[patch], axis=1)
    w = 0.5 * (1.0 + np.cos(np.pi * np.minimum(d / radius, 1.0))) * dA.ravel()[q]
    w /= np.bincount(patch, weights=w, minlength=len(c))[patch]
    return patch, q, Xf[q], w


def patch_loads(nodes: np.ndarray, tri6: np.ndarray, centres: np.ndarray, normals: np.ndarray,
                radius: float, refine: int = 1, quadrature: tuple | None = None) -> sp.csc_matrix:
    """Unit loads spread over small surface patches: one column per patch.

    Patch j carries the traction ``w_j(x) n_j / int w_j dA`` with the cosine bell
    ``w_j(x) = (1 + cos(pi d / radius)) / 2`` for ``d = |x - centres[j]| < radius`` and 0
    beyond (3-D distance), integrated on the quadratic facets. Because the P2 facet basis
    sums to 1, the nodal loads of column j add up to exactly ``n_j`` (1 N).

    Parameters
    ----------
    nodes : ndarray, (N, 3)
        Node coordinates [mm].
    tri6 : ndarray of int, (F, 6)
        Candidate facets (pass only the loaded surface, e.g. one flank: the distance is 3-D).
    centres : ndarray, (m, 3)
        Patch centres [mm], on or near the surface.
    normals : ndarray, (m, 3)
        Load directions; normalised here.
    radius : float
        Patch radius [mm], > 0; should span a few quadrature points (facet size / 2 or more).
    refine : int
        Quadrature subdivision levels (1: 28 points per facet).
    quadrature : tuple, optional
        The result of :func:`patch_quadrature` for these arguments, when the caller already has it.

    Returns
    -------
    scipy.sparse.csc_matrix, (3N, m)
        Nodal forces [N].
    """
    nodes, tri6 = _check_mesh(nodes, tri6, 6, "tri6")
    c = np.atleast_2d(np.asarray(centres, dtype=float))
    nv = np.atleast_2d(np.asarray(normals, dtype=float))
    if nv.shape != c.shape:
        raise ValueError(f"normals: shape {nv.shape}, must equal centres' {c.shape}")
    length = np.linalg.norm(nv, axis=1)
    if np.any(length < 1e-12):
        raise ValueError(f"normals: row {int(np.argmin(length))} has zero length, must be non-zero")
    nv = nv / length[:, None]
    patch, q, _, w = quadrature if quadrature is not None else patch_quadrature(nodes, tri6, c, radius, refine)
    _, _, N = _facet_quadrature(nodes, tri6[:1], refine)
    nq = N.shape[0]
    f, iq = np.divmod(q, nq)
    # entries (hit, facet node a, component k)
    val = (w[:, None] * N[iq])[:, :, None] * nv[patch][:, None, :]
    row = 3 * tri6[f][:, :, None] + np.arange(3)
    col = np.broadcast_to(patch[:, None, None], val.shape)
    return sp.csc_matrix((val.ravel(), (row.ravel(), col.ravel())), shape=(3 * len(nodes), len(c)))
