"""The 20-node serendipity hexahedra under a Kuhn split: the stiffness against scikit-fem's own 20-node brick
(an independent implementation), rigid-body modes, the interpolation to the tetrahedra, and a cantilever against
beam theory, hexahedra against the split tetrahedra on the same nodes."""
import numpy as np
import pytest
import scipy.sparse as sp

from ltca.fem.elastic import assemble_stiffness, rigid_body_modes
from ltca.fem.serendipity import assemble_hex20, hex20_shape, tet_interpolation
from ltca.fem.solids.bevel_body import _hexes, _kuhn, _quadratic

E, NU = 210e3, 0.3


def _box(nx, ny, nz, size=(1.0, 1.0, 1.0), warp=0.0):
    """A structured box of hexahedra split into tetrahedra as the bevel bodies are: (mesh, hexes (M, 20))."""
    g = np.stack(np.meshgrid(*[np.linspace(0, s, n + 1) for s, n in zip(size, (nx, ny, nz))], indexing="ij"), -1)
    g = g + warp * np.stack([np.sin(3 * g[..., 1] + 2 * g[..., 2]), np.cos(2 * g[..., 0] + g[..., 2]),
                             np.sin(g[..., 0] * g[..., 1] * 4)], -1)
    ids = np.arange(g[..., 0].size).reshape(g.shape[:3])
    corners = _hexes(ids, False)
    tets, parity = _kuhn(corners)
    X = g.reshape(-1, 3)
    v = np.einsum("ij,ij->i", np.cross(X[tets[:, 1]] - X[tets[:, 0]], X[tets[:, 2]] - X[tets[:, 0]]),
                  X[tets[:, 3]] - X[tets[:, 0]])
    tets[v < 0] = tets[v < 0][:, [0, 2, 1, 3]]
    mesh = _quadratic(X, tets, {}, "box", 0.0, corners.reshape(-1, 8))
    return mesh, mesh.hexes


def test_shape_functions_are_a_partition_of_unity_and_nodal():
    xi = np.concatenate([2.0 * np.array([[(a >> 2) & 1, (a >> 1) & 1, a & 1] for a in range(8)]) - 1,
                         np.zeros((1, 3))])
    N, dN = hex20_shape(np.random.default_rng(0).uniform(-1, 1, (50, 3)))
    assert np.allclose(N.sum(1), 1.0) and np.allclose(dN.sum(1), 0.0, atol=1e-12)
    Nc, _ = hex20_shape(xi)
    assert np.allclose(Nc[:8, :8], np.eye(8)) and np.allclose(Nc[:8, 8:], 0.0)
    assert np.allclose(Nc[8, :8], -0.25) and np.allclose(Nc[8, 8:], 0.25)   # the body-centre weights


def test_element_stiffness_equals_scikit_fem_hex_s2():
    skfem = pytest.importorskip("skfem")
    from skfem.models.elasticity import lame_parameters, linear_elasticity
    mesh, hexes = _box(1, 1, 1, size=(2.0, 1.5, 1.0), warp=0.12)
    K = assemble_hex20(mesh.nodes, hexes, E, NU)
    h = hexes[0]
    Kh = K[np.repeat(3 * h, 3) + np.tile(np.arange(3), 20)][:, np.repeat(3 * h, 3) + np.tile(np.arange(3), 20)]
    # scikit-fem: the same brick, its own node order; dofs matched by location
    order = [0, 1, 2, 4, 3, 5, 6, 7]          # our corner a = 4i+2j+k in skfem's MeshHex order
    sk = skfem.MeshHex(mesh.nodes[h[:8][order]].T.copy(), np.arange(8)[:, None])
    vb = skfem.Basis(sk, skfem.ElementVector(skfem.ElementHexS2()), intorder=5)
    Ks = skfem.asm(linear_elasticity(*lame_parameters(E, NU)), vb).toarray()
    loc = vb.doflocs.T
    ours = np.repeat(mesh.nodes[h], 3, axis=0)
    match = [int(np.argmin(np.linalg.norm(ours - p, axis=1) + 1e3 * (np.arange(60) % 3 != i % 3)))
             for i, p in enumerate(loc)]
    assert sorted(match) == list(range(60))
    assert np.abs(Kh.toarray()[np.ix_(match, match)] - Ks).max() < 2e-3 * np.abs(Ks).max()


def test_rigid_body_modes_cost_no_energy_and_a_stretch_its_closed_form():
    mesh, hexes = _box(2, 2, 3, size=(1.0, 1.0, 2.0), warp=0.05)
    K = assemble_hex20(mesh.nodes, hexes, E, NU)
    R = rigid_body_modes(mesh.nodes)
    assert np.abs(K @ R).max() < 1e-8 * abs(K).max()
    # uniform uniaxial stress: u = (-nu x, -nu y, z) eps: strain energy E eps^2 V / 2
    _, hexes0 = _box(2, 2, 3, size=(1.0, 1.0, 2.0))
    m0, _ = _box(2, 2, 3, size=(1.0, 1.0, 2.0))
    K0 = assemble_hex20(m0.nodes, hexes0, E, NU)
    eps = 1e-3
    u = (m0.nodes * [-NU * eps, -NU * eps, eps]).ravel()
    assert u @ (K0 @ u) / 2 == pytest.approx(E * eps ** 2 * 2.0 / 2, rel=1e-10)


def test_interpolation_reproduces_quadratic_fields_on_the_tetrahedra():
    mesh, hexes = _box(2, 3, 2, size=(1.0, 1.3, 0.7))
    T, hex_nodes = tet_interpolation(len(mesh.nodes), hexes, mesh.tets)
    assert T.shape == (3 * len(mesh.nodes), 3 * len(hex_nodes))
    x, y, z = mesh.nodes.T
    f = np.stack([x * y - 0.3 * z * z, y * z + x, x * x - 2 * x * z], 1)   # quadratic, every component
    assert np.abs(T @ f[hex_nodes].ravel() - f.ravel()).max() < 1e-12
    f = np.stack([x * y * z, x * x * y, y * z * z], 1)          # cubic terms of the serendipity space: exact too
    assert np.abs(T @ f[hex_nodes].ravel() - f.ravel()).max() < 1e-12
    f = (x * x * y * y)[:, None] * np.ones(3)                  # beyond it (a 27-node brick's): not exact
    assert np.abs(T @ f[hex_nodes].ravel() - f.ravel()).max() > 1e-3


def test_cantilever_tip_deflection_against_beam_theory():
    """A square cantilever (L = 10, a = 1 mm, 10 x 1 x 1 hexahedra) under a tip shear: Timoshenko's deflection; the hexahedra on half
    the split tetrahedra's unknowns are closer to it than the tetrahedra."""
    L, a, P = 10.0, 1.0, 1.0
    mesh, hexes = _box(10, 1, 1, size=(L, a, a))
    X = mesh.nodes
    fixed_nodes = np.flatnonzero(X[:, 0] < 1e-9)
    tip = np.flatnonzero(X[:, 0] > L - 1e-9)
    G, I, A = E / (2 * (1 + NU)), a ** 4 / 12, a * a
    exact = P * L ** 3 / (3 * E * I) + P * L / ((10 * (1 + NU) / (12 + 11 * NU)) * G * A)

    def tip_deflection(K, T=None):
        n = K.shape[0]
        F = np.zeros(3 * len(X))
        F[3 * tip + 2] = P / len(tip)         # a consistent-enough load: the deflection is read as a mean
        free = np.ones(3 * len(X), bool)
        free[(3 * fixed_nodes[:, None] + np.arange(3)).ravel()] = False
        if T is not None:
            F_r, free_r = T.T @ F, np.asarray(abs(T[free]).sum(0) > 0).ravel()
            free_r &= ~np.asarray(abs(T[~free]).sum(0) > 0).ravel()
            u_r = np.zeros(n)
            u_r[free_r] = sp.linalg.spsolve(K[free_r][:, free_r].tocsc(), F_r[free_r])
            u = T @ u_r
        else:
            u = np.zeros(n)
            u[free] = sp.linalg.spsolve(K[free][:, free].tocsc(), F[free])
        return u[3 * tip + 2].mean()

    import scipy.sparse.linalg  # noqa: F401
    K_tet = assemble_stiffness(X, mesh.tets, E, NU)
    T, hex_nodes = tet_interpolation(len(X), hexes, mesh.tets)
    col = np.full(len(X), -1)
    col[hex_nodes] = np.arange(len(hex_nodes))
    K_hex = assemble_hex20(X[hex_nodes], col[hexes], E, NU)
    w_tet, w_hex = tip_deflection(K_tet), tip_deflection(K_hex, T)
    assert abs(w_hex / exact - 1) < 0.025          # -2.0 %; 40 x 4 x 4 hexahedra: -0.79 % (3D end effects)
    assert abs(w_hex / exact - 1) < abs(w_tet / exact - 1)


def test_the_mesh_cache_keeps_the_hexahedra(tmp_path):
    """A cached mapped body comes back with its hexahedra (without them it would be solved on the tetrahedra)."""
    from ltca.fem.solids.cache import load_cached, store_cached
    mesh, hexes = _box(2, 1, 1)
    store_cached(tmp_path, "box", mesh)
    back = load_cached(tmp_path, "box", mesh.spec_hash)
    assert back is not None and back.hexes is not None and np.array_equal(back.hexes, hexes)
