"""Linear elasticity on quadratic (10-node) tetrahedra: stiffness, loads, point read-out.

Conventions used across ``fem``:

- ``nodes`` (N, 3) float [mm]; ``tets`` (M, 10) int, node order of scikit-fem / meshio /
  CalculiX: vertices 0-3, then mid-edge nodes of edges 01, 12, 02, 03, 13, 23.
- ``tri6`` (F, 6) int surface facets: vertices 0-2, then mid-edge nodes of 01, 12, 20.
- dofs are node-major interleaved: ``dof = 3 * node + component``.

Elements are *subparametric*: the geometry map is affine (straight edges, vertices only);
mid-edge nodes carry displacement but their position is not used by the stiffness or by
point location. On curved boundaries this costs a geometric error O(h^2) (the domain is
the inscribed polyhedron). Surface loads, in contrast, integrate over the quadratic facets.

The element stiffness is integrated in closed form. With barycentric coordinates L_a and
the P2 basis ``N_a = L_a (2 L_a - 1)``, ``N_ab = 4 L_a L_b``, every gradient is
``grad N_i = sum_cd T[i,c,d] L_d grad L_c`` (linear in L), so with the exact moments
``int L_d L_f dV = V (1 + delta_df) / 20`` (from ``int L1^a L2^b L3^c L4^d dV =
6 V a! b! c! d! / (a + b + c + d + 3)!``, Zienkiewicz, Taylor & Zhu, *The Finite Element
Method: Its Basis and Fundamentals*, 6th ed., sec. 6.3)::

    K_e[ik, jl] = V sum_ce Q[i,c,j,e] H[c,k,e,l],
    H[c,k,e,l]  = lam g_ck g_el + mu (g_cl g_ek + delta_kl g_c . g_e),  g_c = grad L_c,

with the element-independent tensor ``Q = T T M``: per chunk of elements, nine BLAS
products (100, 16) x (16, m), summed into 3x3 node-pair blocks by ``bincount`` on a
node-level sparsity pattern (9x fewer keys to sort than a dof-level COO -> CSR).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree

from fem.solver import Factorization, factorize

__all__ = [
    "assemble_stiffness", "factorize", "Factorization", "rigid_body_modes",
    "surface_traction_load", "patch_loads", "patch_quadrature", "locate_points", "interpolation_matrix",
    "stress_matrix", "p2_shape", "lame",
]

EDGES = np.array([[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]])
TRI_EDGES = np.array([[0, 1], [1, 2], [2, 0]])
_CHUNK = 50000  # elements per assembly chunk: ~60 MB of work arrays


def lame(E: float, nu: float) -> tuple[float, float]:
    """Lame constants (lambda, mu) [MPa] of Young's modulus E [MPa] and Poisson ratio nu."""
    if not np.isfinite(E) or E <= 0:
        raise ValueError(f"E = {E}: Young's modulus must be > 0 (MPa)")
    if not (-1.0 < nu < 0.5):
        raise ValueError(f"nu = {nu}: Poisson ratio must be in (-1, 0.5)")
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


def _grad_tensor(n_vertices: int, edges: np.ndarray) -> np.ndarray:
    """T[i, c, d] with grad N_i = sum_cd T[i,c,d] L_d grad L_c for the P2 simplex basis."""
    n = n_vertices + len(edges)
    T = np.zeros((n, n_vertices, n_vertices))
    for a in range(n_vertices):  # (4 L_a - sum_d L_d) grad L_a
        T[a, a, :] = -1.0
        T[a, a, a] = 3.0
    for i, (a, b) in enumerate(edges):
        T[n_vertices + i, b, a] = 4.0
        T[n_vertices + i, a, b] = 4.0
    return T


_T = _grad_tensor(4, EDGES)
_M = (np.ones((4, 4)) + np.eye(4)) / 20.0
_Q = np.einsum("icd,jef,df->ijce", _T, _T, _M).reshape(100, 16)


def p2_shape(bary: np.ndarray, edges: np.ndarray = EDGES) -> np.ndarray:
    """P2 shape-function values at barycentric coordinates.

    Parameters
    ----------
    bary : ndarray, (..., nv)
        Barycentric coordinates (nv = 4 for tets, 3 for triangles).
    edges : ndarray, (ne, 2)
        Local vertex pairs of the mid-edge nodes.

    Returns
    -------
    ndarray, (..., nv + ne)
    """
    vert = bary * (2.0 * bary - 1.0)
    mid = 4.0 * bary[..., edges[:, 0]] * bary[..., edges[:, 1]]
    return np.concatenate([vert, mid], axis=-1)


def _check_mesh(nodes: np.ndarray, cells: np.ndarray, width: int, name: str):
    nodes = np.asarray(nodes, dtype=float)
    cells = np.asarray(cells)
    if nodes.ndim != 2 or nodes.shape[1] != 3:
        raise ValueError(f"nodes: shape {nodes.shape}, must be (N, 3)")
    if cells.ndim != 2 or cells.shape[1] != width or not np.issubdtype(cells.dtype, np.integer):
        raise ValueError(f"{name}: shape {cells.shape} dtype {cells.dtype}, must be integer (M, {width})")
    if cells.size and (cells.min() < 0 or cells.max() >= len(nodes)):
        raise ValueError(f"{name}: node indices in [{cells.min()}, {cells.max()}], "
                         f"allowed [0, {len(nodes) - 1}]")
    return nodes, cells


def _affine(nodes: np.ndarray, tets: np.ndarray):
    """Per element: x0 (M,3), inverse Jacobian (M,3,3), barycentric gradients (M,4,3), volume (M,)."""
    x0 = nodes[tets[:, 0]]
    J = np.stack([nodes[tets[:, 1]] - x0, nodes[tets[:, 2]] - x0, nodes[tets[:, 3]] - x0], axis=2)
    det = np.linalg.det(J)
    scale = np.max(np.abs(J), axis=(1, 2)) ** 3
    bad = np.abs(det) <= 1e-12 * scale
    if bad.any():
        raise ValueError(f"tets: {bad.sum()} degenerate element(s), e.g. element {np.flatnonzero(bad)[0]}: "
                         "volume must be > 0")
    Jinv = np.linalg.inv(J)  # rows: grad L_1..L_3
    g = np.concatenate([-Jinv.sum(axis=1, keepdims=True), Jinv], axis=1)
    return x0, Jinv, g, np.abs(det) / 6.0


def assemble_stiffness(nodes: np.ndarray, tets: np.ndarray, E: float, nu: float) -> sp.csr_matrix:
    """Global stiffness of isotropic linear elasticity on straight-edged P2 tetrahedra.

    Parameters
    ----------
    nodes : ndarray, (N, 3)
        Node coordinates [mm].
    tets : ndarray of int, (M, 10)
        Element nodes, meshio order.
    E, nu : float
        Young's modulus [MPa] and Poisson ratio [-].

    Returns
    -------
    scipy.sparse.csr_matrix, (3N, 3N)
        Symmetric stiffness [N/mm], dofs ``3 * node + component``. Exact integration
        (closed form, see the module docstring).
    """
    nodes, tets = _check_mesh(nodes, tets, 10, "tets")
    lam, mu = lame(E, nu)
    N = len(nodes)
    eye = np.eye(3)
    # node-level pattern: one 3x3 block per coupled node pair; entries in layout [i, j, m]
    # elements sorted by lowest node: each chunk then scatters into a narrow band of blocks
    tets = tets[np.argsort(tets[:, :4].min(axis=1), kind="stable")]
    t64 = tets.astype(np.int64)
    chunks = range(0, len(tets), _CHUNK)
    keys = np.concatenate([(t64[s:s + _CHUNK].T[:, None, :] * N + t64[s:s + _CHUNK].T[None, :, :]).ravel()
                           for s in chunks])
    pattern, where = np.unique(keys, return_inverse=True)
    del keys
    blocks = np.zeros((len(pattern), 9))
    pos = 0
    for s in chunks:
        t = tets[s:s + _CHUNK]
        _, _, g, vol = _affine(nodes, t)
        dots = np.einsum("mck,mek->cem", g, g)
        H = lam * np.einsum("mck,mel->ceklm", g, g)        # H[c, e, k, l, m]
        H += mu * np.einsum("mcl,mek->ceklm", g, g)
        H += mu * np.einsum("cem,kl->ceklm", dots, eye)
        H *= vol
        H = H.reshape(16, 9, len(t))
        w = where[pos:pos + 100 * len(t)]
        pos += 100 * len(t)
        lo, hi = int(w.min()), int(w.max()) + 1
        w = w - lo
        for kl in range(9):  # (100, m) contiguous, entries [i, j, m]
            data = _Q @ H[:, kl, :]
            blocks[lo:hi, kl] += np.bincount(w, weights=data.ravel(), minlength=hi - lo)
        del H, data
    rows, cols = np.divmod(pattern, N)
    indptr = np.searchsorted(rows, np.arange(N + 1)).astype(np.int64)
    idx_t = np.int32 if len(pattern) < 2**31 - 1 else np.int64
    K = sp.bsr_matrix((blocks.reshape(-1, 3, 3), cols.astype(idx_t), indptr.astype(idx_t)),
                      shape=(3 * N, 3 * N))
    return K.tocsr()


def rigid_body_modes(nodes: np.ndarray) -> np.ndarray:
    """The six rigid-body displacement fields.

    Parameters
    ----------
    nodes : ndarray, (N, 3)
        Node coordinates [mm].

    Returns
    -------
    ndarray, (3N, 6)
        Columns: unit translations x, y, z [mm], then unit rotations [rad] about x, y, z
        through the centroid of the nodes (``theta x (x - x_mean)``), dofs ``3 * node + k``.
    """
    nodes = np.asarray(nodes, dtype=float)
    if nodes.ndim != 2 or nodes.shape[1] != 3:
        raise ValueError(f"nodes: shape {nodes.shape}, must be (N, 3)")
    r = nodes - nodes.mean(axis=0)
    R = np.zeros((len(nodes), 3, 6))
    R[:, :, :3] = np.eye(3)
    for a in range(3):
        R[:, :, 3 + a] = np.cross(np.eye(3)[a], r)
    return R.reshape(-1, 6)


# --- surface loads ------------------------------------------------------------------------

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
                radius: float, refine: int = 1) -> sp.csc_matrix:
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
    patch, q, _, w = patch_quadrature(nodes, tri6, c, radius, refine)
    _, _, N = _facet_quadrature(nodes, tri6[:1], refine)
    nq = N.shape[0]
    f, iq = np.divmod(q, nq)
    # entries (hit, facet node a, component k)
    val = (w[:, None] * N[iq])[:, :, None] * nv[patch][:, None, :]
    row = 3 * tri6[f][:, :, None] + np.arange(3)
    col = np.broadcast_to(patch[:, None, None], val.shape)
    return sp.csc_matrix((val.ravel(), (row.ravel(), col.ravel())), shape=(3 * len(nodes), len(c)))


# --- point read-out -----------------------------------------------------------------------

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
