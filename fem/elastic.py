"""Linear elasticity on quadratic (10-node) tetrahedra: the stiffness (loads in :mod:`ltca.fem.loads`, point
read-out in :mod:`ltca.fem.readout`).

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

from ltca.fem.solver import Factorization, factorize

__all__ = ["assemble_stiffness", "factorize", "Factorization", "rigid_body_modes", "p2_shape", "lame", "node_pattern",
           "blocks_to_csr"]

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
    eye = np.eye(3)
    # elements sorted by lowest node: each chunk then scatters into a narrow band of blocks
    tets = tets[np.argsort(tets[:, :4].min(axis=1), kind="stable")]
    pattern, where = node_pattern(tets, len(nodes), _CHUNK)
    blocks = np.zeros((len(pattern), 9))
    pos = 0
    for s in range(0, len(tets), _CHUNK):
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
    return blocks_to_csr(pattern, blocks, len(nodes))


def node_pattern(cells: np.ndarray, N: int, chunk: int) -> tuple[np.ndarray, np.ndarray]:
    """The node-level sparsity of a stiffness: one 3x3 block per coupled node pair.

    Parameters
    ----------
    cells : ndarray of int, (M, c)
        Element nodes.
    N : int
        Nodes.
    chunk : int
        Elements per chunk of the assembly loop.

    Returns
    -------
    pattern : ndarray of int64, (P,)
        Sorted keys ``row_node * N + col_node`` of the blocks.
    where : ndarray of int, (M c^2,)
        The block of each element entry, chunk by chunk in the layout [i, j, m] (node i, node j, element m).
    """
    t64 = cells.astype(np.int64)
    keys = np.concatenate([(t64[s:s + chunk].T[:, None, :] * N + t64[s:s + chunk].T[None, :, :]).ravel()
                           for s in range(0, len(cells), chunk)])
    return np.unique(keys, return_inverse=True)


def blocks_to_csr(pattern: np.ndarray, blocks: np.ndarray, N: int) -> sp.csr_matrix:
    """The (3N, 3N) CSR matrix of 3x3 node-pair ``blocks`` (P, 9), row-major, at the keys ``pattern``
    (:func:`node_pattern`); dofs ``3 * node + component``."""
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
