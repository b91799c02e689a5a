"""Quadratic serendipity (20-node) hexahedra under a Kuhn-split mesh of quadratic tetrahedra.

A mapped body (the bevel members of :mod:`ltca.fem.solids.bevel_body`) is made of hexahedra, each split into six
10-node tetrahedra along its main diagonal. The tetrahedra carry seven mid-edge nodes a hexahedron has no use for:
the midpoints of its six face diagonals and of its main diagonal. Solved on the 20-node serendipity hexahedron
instead (the 8 corners and the 12 mid-edge nodes; about half the nodes of the split mesh), the body keeps its
tetrahedra for everything but the stiffness: loads, point read-outs and stresses work on the tetrahedral field
``u = T u_h``, whose extra nodes take the serendipity field's values (:func:`tet_interpolation`), and the
stiffness is the hexahedra's own (:func:`assemble_hex20`), not ``T^T K_tet T``.

Node order of a hexahedron (``hexes`` (M, 20)): corner ``a = 4 i + 2 j + k`` at the reference point
``2 (i, j, k) - 1`` in [-1, 1]^3 (i, j, k the hexahedron's three index directions), then the mid-edge nodes of
:data:`HEX_EDGES`. The geometry map is trilinear in the corners (straight edges: the mid-edge nodes are the edge
midpoints, the elements subparametric, as the tetrahedra of :mod:`ltca.fem.elastic`).

Shape functions (Zienkiewicz, Taylor & Zhu, *The Finite Element Method: Its Basis and Fundamentals*, 7th ed.,
sec. 6.5.2, the 20-node "serendipity" brick), with the corner at (xi_a, eta_a, zeta_a) = (+-1, +-1, +-1)::

    N_a = 1/8 (1 + xi xi_a)(1 + eta eta_a)(1 + zeta zeta_a)(xi xi_a + eta eta_a + zeta zeta_a - 2)
    N_e = 1/4 (1 - xi^2)(1 + eta eta_e)(1 + zeta zeta_e)        (an edge along xi; the others alike)

Their values at a face centre are -1/4 at the face's corners and 1/2 at its mid-edge nodes (0 elsewhere), at the
body centre -1/4 at the corners and 1/4 at the mid-edge nodes: the weights of :func:`tet_interpolation`. The
stiffness is integrated by the 3 x 3 x 3 Gauss rule (exact for the serendipity products on a parallelepiped).
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .elastic import EDGES, blocks_to_csr, lame, node_pattern

__all__ = ["HEX_EDGES", "hex20_shape", "assemble_hex20", "tet_interpolation"]

_CORNER = np.array([[(a >> 2) & 1, (a >> 1) & 1, a & 1] for a in range(8)])
#: corner pairs (8 + e is the mid-edge node of edge e): along i, then j, then k
HEX_EDGES = np.array([(a, a | bit) for bit in (4, 2, 1) for a in range(8) if not a & bit])
_XI = np.concatenate([2.0 * _CORNER - 1, (2.0 * _CORNER[HEX_EDGES[:, 0]] - 1 + 2.0 * _CORNER[HEX_EDGES[:, 1]] - 1) / 2])
_CHUNK = 2000   # hexahedra per chunk of the gradient work arrays (about 100 MB); the 3 x 3 x 400 products of every
                # element are kept whole (29 kB a hexahedron) and summed into the blocks once


def hex20_shape(xi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Serendipity shape functions and their reference gradients.

    Parameters
    ----------
    xi : ndarray, (q, 3)
        Reference points in [-1, 1]^3.

    Returns
    -------
    N : ndarray, (q, 20)
    dN : ndarray, (q, 20, 3)
        d N / d xi.
    """
    xi = np.atleast_2d(np.asarray(xi, dtype=float))
    q = len(xi)
    N, dN = np.empty((q, 20)), np.empty((q, 20, 3))
    for n, c in enumerate(_XI):
        f = 1.0 + xi * c                                   # (q, 3): 1 + xi_k c_k
        if n < 8:
            s = (xi * c).sum(1) - 2.0
            N[:, n] = f.prod(1) * s / 8
            for k in range(3):
                o = [j for j in range(3) if j != k]
                dN[:, n, k] = c[k] * f[:, o].prod(1) * (s + f[:, k]) / 8
        else:
            v = int(np.flatnonzero(c == 0)[0])            # the edge's direction
            o = [j for j in range(3) if j != v]
            g = 1.0 - xi[:, v] ** 2
            N[:, n] = g * f[:, o].prod(1) / 4
            dN[:, n, v] = -2.0 * xi[:, v] * f[:, o].prod(1) / 4
            dN[:, n, o[0]] = g * c[o[0]] * f[:, o[1]] / 4
            dN[:, n, o[1]] = g * c[o[1]] * f[:, o[0]] / 4
    return N, dN


def _gauss3() -> tuple[np.ndarray, np.ndarray]:
    g, w = np.polynomial.legendre.leggauss(3)
    P = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    W = np.einsum("i,j,k->ijk", w, w, w).ravel()
    return P, W


def assemble_hex20(nodes: np.ndarray, hexes: np.ndarray, E: float, nu: float) -> sp.csr_matrix:
    """Global stiffness of isotropic linear elasticity on 20-node serendipity hexahedra.

    Parameters
    ----------
    nodes : ndarray, (N, 3)
        Node coordinates [mm]; nodes that no hexahedron uses get empty rows.
    hexes : ndarray of int, (M, 20)
        Element nodes, order of the module docstring.
    E, nu : float
        Young's modulus [MPa] and Poisson ratio [-].

    Returns
    -------
    scipy.sparse.csr_matrix, (3N, 3N)
        Symmetric stiffness [N/mm], dofs ``3 * node + component``; 27-point Gauss rule on the trilinear map.

    Notes
    -----
    With the physical gradients ``G[q, n, k]`` at the Gauss points and ``c_q = w_q |det J_q|``, one contraction
    ``M[k, l, n, p] = sum_q c_q G[q,n,k] G[q,p,l]`` gives the element matrix
    ``K[nk, pl] = lam M[k, l, n, p] + mu M[l, k, n, p] + mu delta_kl sum_i M[i, i, n, p]``.
    """
    nodes = np.asarray(nodes, dtype=float)
    hexes = np.asarray(hexes)
    if hexes.ndim != 2 or hexes.shape[1] != 20 or not np.issubdtype(hexes.dtype, np.integer):
        raise ValueError(f"hexes: shape {hexes.shape} dtype {hexes.dtype}, must be integer (M, 20)")
    if hexes.size and (hexes.min() < 0 or hexes.max() >= len(nodes)):
        raise ValueError(f"hexes: node indices in [{hexes.min()}, {hexes.max()}], allowed [0, {len(nodes) - 1}]")
    lam, mu = lame(E, nu)
    P, W = _gauss3()
    _, dN = hex20_shape(P)                                 # (27, 20, 3)
    _, dL = _trilinear(P)                                  # (27, 8, 3)
    pattern, where = node_pattern(hexes, len(nodes), _CHUNK)
    data = np.empty((3, 3, len(where)))                  # M[k, l] of every element entry, in the layout of where
    pos = 0
    for s in range(0, len(hexes), _CHUNK):
        h = hexes[s:s + _CHUNK]
        m = len(h)
        J = np.einsum("mai,qak->mqik", nodes[h[:, :8]], dL, optimize=True)  # dx_i / dxi_k
        det = np.linalg.det(J)
        flat = np.abs(det) <= 1e-12 * np.abs(J).max(axis=(2, 3)) ** 3
        if flat.any():
            raise ValueError(f"hexes: element {s + int(np.flatnonzero(flat.any(1))[0])} is degenerate at a Gauss "
                             "point: volume must be > 0")
        G = np.einsum("qnk,mqki->mqni", dN, np.linalg.inv(J), optimize=True)
        G *= np.sqrt(W * np.abs(det))[:, :, None, None]
        data[:, :, pos:pos + 400 * m] = np.einsum("mqnk,mqpl->klnpm", G, G, optimize=True).reshape(3, 3, -1)
        pos += 400 * m
    Mb = np.stack([np.bincount(where, weights=d, minlength=len(pattern)) for d in data.reshape(9, -1)])
    del data
    Mb = Mb.reshape(3, 3, -1)                            # M[k, l] summed per node-pair block
    tr = mu * (Mb[0, 0] + Mb[1, 1] + Mb[2, 2])
    blocks = np.empty((len(pattern), 3, 3))
    for k in range(3):
        for j in range(3):
            blocks[:, k, j] = lam * Mb[k, j] + mu * Mb[j, k] + (tr if k == j else 0.0)
    return blocks_to_csr(pattern, blocks, len(nodes))


def _trilinear(xi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Trilinear corner functions (q, 8) and their reference gradients (q, 8, 3) at points xi (q, 3)."""
    c = 2.0 * _CORNER - 1
    f = 1.0 + xi[:, None, :] * c[None]                     # (q, 8, 3)
    L = f.prod(-1) / 8
    dL = np.stack([c[None, :, k] * f[:, :, [j for j in range(3) if j != k]].prod(-1) / 8 for k in range(3)], -1)
    return L, dL


def tet_interpolation(n_nodes: int, hexes: np.ndarray, tets: np.ndarray) -> tuple[sp.csr_matrix, np.ndarray]:
    """The 10-node tetrahedral field of a serendipity field on the hexahedra the tetrahedra split.

    Parameters
    ----------
    n_nodes : int
        Nodes of the tetrahedral mesh.
    hexes : ndarray of int, (M, 20)
        The hexahedra (module docstring), over the same nodes.
    tets : ndarray of int, (6 M, 10)
        Their Kuhn split, meshio order.

    Returns
    -------
    T : scipy.sparse.csr_matrix, (3 n_nodes, 3 n_h)
        ``u = T u_h``: the displacement of every node from those of the hexahedra's nodes (identity there; the
        face-diagonal and main-diagonal midpoints by the weights of the module docstring).
    hex_nodes : ndarray of int, (n_h,)
        The nodes of the hexahedra, sorted: column block j of T is node ``hex_nodes[j]``.
    """
    hexes = np.asarray(hexes)
    e = np.sort(tets[:, :4][:, EDGES].reshape(-1, 2), 1).astype(np.int64)
    code, first = np.unique(e[:, 0] * n_nodes + e[:, 1], return_index=True)
    mid_of = tets[:, 4:].reshape(-1)[first]

    def midpoint(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        c = np.minimum(a, b).astype(np.int64) * n_nodes + np.maximum(a, b)
        i = np.minimum(np.searchsorted(code, c), len(code) - 1)
        return np.where(code[i] == c, mid_of[i], -1)

    edge_at = {(int(a), int(b)): 8 + i for i, (a, b) in enumerate(HEX_EDGES)}
    rows, cols, vals = [], [], []
    for bit in (4, 2, 1):                                  # the six faces
        u, v = [b for b in (4, 2, 1) if b != bit]
        for side in (0, bit):
            q = [side, side | u, side | u | v, side | v]   # the face's corners in turn
            ring = [edge_at[tuple(sorted((q[i], q[(i + 1) % 4])))] for i in range(4)]
            diag = np.maximum(midpoint(hexes[:, q[0]], hexes[:, q[2]]), midpoint(hexes[:, q[1]], hexes[:, q[3]]))
            if np.any(diag < 0):
                raise ValueError("tets: a hexahedron face has no diagonal edge: not the Kuhn split of hexes")
            for local, w in [(a, -0.25) for a in q] + [(r, 0.5) for r in ring]:
                rows.append(diag), cols.append(hexes[:, local]), vals.append(np.full(len(hexes), w))
    centre = midpoint(hexes[:, 0], hexes[:, 7])
    if np.any(centre < 0):
        raise ValueError("tets: a hexahedron has no main-diagonal edge: not the Kuhn split of hexes")
    for local in range(20):
        rows.append(centre), cols.append(hexes[:, local]), vals.append(np.full(len(hexes), -0.25 if local < 8 else 0.25))
    r, c, w = np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)
    # a face shared by two hexahedra gives its diagonal's row twice, with the same weights: keep one
    _, once = np.unique(r.astype(np.int64) * n_nodes + c, return_index=True)
    r, c, w = r[once], c[once], w[once]
    hex_nodes = np.unique(hexes)
    col = np.full(n_nodes, -1)
    col[hex_nodes] = np.arange(len(hex_nodes))
    if np.any(col[r] >= 0):
        raise ValueError("tets: a diagonal midpoint is also a node of a hexahedron")
    uncovered = np.setdiff1d(np.arange(n_nodes), np.concatenate([hex_nodes, r]))
    if uncovered.size:
        raise ValueError(f"tets: {uncovered.size} node(s) neither of a hexahedron nor a diagonal midpoint")
    Tn = sp.csr_matrix((np.concatenate([np.ones(len(hex_nodes)), w]),
                        (np.concatenate([hex_nodes, r]), np.concatenate([col[hex_nodes], col[c]]))),
                       shape=(n_nodes, len(hex_nodes)))
    return sp.kron(Tn, sp.identity(3), format="csr"), hex_nodes
