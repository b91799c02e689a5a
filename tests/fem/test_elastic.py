"""Validation of fem.elastic / fem.solver: FE identities, analytic solutions, skfem equality."""
from __future__ import annotations

import time

import gmsh
import numpy as np
import pytest
import scipy.sparse as sp

import ltca.fem.elastic as el
import ltca.fem.loads as loads
import ltca.fem.readout as readout
from fixtures.meshes import boundary_tri6 as _boundary_tri6
from fixtures.meshes import gmsh_tets as _gmsh_tets
from ltca.fem.solver import available_methods

E, NU = 210e3, 0.3


# --- helpers ------------------------------------------------------------------------------

def _skfem_mesh(refine=2, jitter=0.02, seed=0):
    """P2 nodes/tets of a jittered unit cube, built from skfem's own dof numbering."""
    from skfem import Basis, ElementTetP2, ElementVector, MeshTet

    m = MeshTet().refined(refine)
    p = m.p + jitter * np.random.default_rng(seed).standard_normal(m.p.shape) * (m.p > 0) * (m.p < 1)
    b = Basis(MeshTet(p, m.t), ElementVector(ElementTetP2()))
    ed = b.element_dofs
    assert np.all(ed[1::3] == ed[0::3] + 1) and np.all(ed[2::3] == ed[0::3] + 2)  # interleaved
    return b.doflocs[:, ::3].T.copy(), (ed[0::3].T // 3).astype(np.int64), b


def _dofs(mask, comp):
    return 3 * np.flatnonzero(mask) + comp


# --- FE identities ------------------------------------------------------------------------

def test_stiffness_equals_skfem_symmetric_rigid_modes_in_nullspace():
    from skfem import asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    nodes, tets, basis = _skfem_mesh()
    K = el.assemble_stiffness(nodes, tets, E, NU)
    Ks = asm(linear_elasticity(*lame_parameters(E, NU)), basis)
    scale = abs(Ks).max()
    assert abs(K - Ks).max() / scale < 1e-10
    assert abs(K - K.T).max() / scale < 1e-12
    R = el.rigid_body_modes(nodes)
    assert np.abs(K @ R).max() / (scale * np.abs(R).max()) < 1e-10
    # a non-rigid field is not in the null space (the test above can fail)
    assert np.abs(K @ (nodes[:, [0]] ** 2 * [1, 0, 0]).ravel()).max() / scale > 1e-3


def test_patch_test_linear_field_reproduced_inside():
    nodes, tets, _ = _skfem_mesh()
    K = el.assemble_stiffness(nodes, tets, E, NU)
    A = np.random.default_rng(1).standard_normal((3, 3))
    u_exact = (nodes @ A.T + [0.1, -0.2, 0.3]).ravel()
    bnd = np.any((nodes < 1e-12) | (nodes > 1 - 1e-12), axis=1)
    fixed = (3 * np.flatnonzero(bnd)[:, None] + np.arange(3)).ravel()
    assert (~bnd).sum() > 100
    for method in available_methods():
        fac = el.factorize(K, fixed, method)
        ub = np.zeros(K.shape[0])
        ub[fixed] = u_exact[fixed]
        u = ub + fac.solve(-(K @ ub))
        assert np.abs(u - u_exact).max() / np.abs(u_exact).max() < 1e-10, method


def test_solvers_agree_multiple_rhs_blocks_and_observe():
    nodes, tets, _ = _skfem_mesh()
    K = el.assemble_stiffness(nodes, tets, E, NU)
    fixed = _dofs(nodes[:, 0] < 1e-12, 0).tolist() + _dofs(nodes[:, 0] < 1e-12, 1).tolist() \
        + _dofs(nodes[:, 0] < 1e-12, 2).tolist()
    F = sp.random(K.shape[0], 7, density=0.01, random_state=2, format="csc")
    pts = np.random.default_rng(3).random((20, 3))
    P = readout.interpolation_matrix(nodes, tets, pts)
    ref = None
    for method in available_methods():
        fac = el.factorize(K, np.array(fixed), method)
        U = fac.solve(F, block=3)
        assert U.shape == (K.shape[0], 7) and np.all(U[fixed] == 0)
        res = (K @ U - F.toarray())[fac.free]
        assert np.abs(res).max() < 1e-9 * np.abs(F).max()
        assert np.allclose(fac.solve(F, observe=P), P @ U, rtol=1e-12, atol=1e-15)
        assert np.allclose(fac.solve(F[:, 2].toarray().ravel()), U[:, 2], rtol=1e-12, atol=1e-15)
        ref = U if ref is None else ref
        assert np.allclose(U, ref, rtol=1e-8, atol=1e-12 * np.abs(ref).max())
    if "pardiso" in available_methods():
        assert el.factorize(K, np.array(fixed)).method == "pardiso"


def test_bad_input_raises_value_error_naming_parameter():
    nodes, tets, _ = _skfem_mesh(refine=1)
    with pytest.raises(ValueError, match="nu"):
        el.assemble_stiffness(nodes, tets, E, 0.5)
    with pytest.raises(ValueError, match="E ="):
        el.assemble_stiffness(nodes, tets, -1.0, 0.3)
    with pytest.raises(ValueError, match="tets"):
        el.assemble_stiffness(nodes, tets[:, :4], E, NU)
    K = el.assemble_stiffness(nodes, tets, E, NU)
    with pytest.raises(ValueError, match="method"):
        el.factorize(K, np.array([0]), "magic")
    with pytest.raises(ValueError, match="fixed_dofs"):
        el.factorize(K, np.array([K.shape[0]]))
    tri = _boundary_tri6(tets)
    with pytest.raises(ValueError, match="radius"):
        loads.patch_loads(nodes, tri, [[0.5, 0.5, 0.0]], [[0, 0, 1]], radius=0.0)


# --- read-out -----------------------------------------------------------------------------

def test_interpolation_exact_for_quadratic_and_stress_exact_for_linear_field():
    nodes, tets, _ = _skfem_mesh()
    rng = np.random.default_rng(4)
    pts = rng.random((400, 3))

    def quad(x):  # any quadratic field lies in the P2 space
        return np.stack([x[:, 0] ** 2 + x[:, 1] * x[:, 2], x[:, 1] ** 2 - 2 * x[:, 0] * x[:, 2] + 1,
                         x[:, 2] * x[:, 0] + 3 * x[:, 1]], axis=1)

    P = readout.interpolation_matrix(nodes, tets, pts)
    assert P.shape == (1200, 3 * len(nodes))
    assert np.abs(P @ quad(nodes).ravel() - quad(pts).ravel()).max() < 1e-12
    elem, bary = readout.locate_points(nodes, tets, pts)
    x = np.einsum("na,nak->nk", bary, nodes[tets[elem, :4]])
    assert np.abs(x - pts).max() < 1e-12

    A = rng.standard_normal((3, 3)) * 1e-3
    eps = (A + A.T) / 2  # Hooke's law, isotropic: sigma = lam tr(eps) I + 2 mu eps
    lam, mu = el.lame(E, NU)
    sig = lam * np.trace(eps) * np.eye(3) + 2 * mu * eps
    voigt = sig[[0, 1, 2, 1, 0, 0], [0, 1, 2, 2, 2, 1]]
    S = readout.stress_matrix(nodes, tets, E, NU, pts)
    out = (S @ (nodes @ A.T).ravel()).reshape(-1, 6)
    assert np.abs(out - voigt).max() < 1e-10 * np.abs(voigt).max()


def test_points_outside_are_clamped_into_nearest_element():
    nodes, tets, _ = _skfem_mesh()
    pts = np.array([[0.5, 0.5, 1.0 + 1e-4], [-1e-4, 0.3, 0.3]])
    elem, bary = readout.locate_points(nodes, tets, pts)
    assert np.all(bary >= 0) and np.allclose(bary.sum(axis=1), 1.0)
    x = np.einsum("na,nak->nk", bary, nodes[tets[elem, :4]])
    assert np.abs(x - pts).max() < 2e-4


# --- loads --------------------------------------------------------------------------------

def test_patch_loads_resultant_is_exactly_one_newton_and_local():
    nodes, tets = _gmsh_tets(lambda: gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, 10, 5), size=1.5)
    tri = _boundary_tri6(tets)
    r = np.hypot(*nodes[tri[:, :3]][..., :2].transpose(2, 0, 1))
    tri = tri[np.all(np.abs(r - 5) < 1e-6, axis=1)]                     # curved mantle only
    ang = np.linspace(0.2, 5.5, 6)
    centres = np.stack([5 * np.cos(ang), 5 * np.sin(ang), np.linspace(3, 7, 6)], axis=1)
    normals = -centres * [1, 1, 0]                                      # inward, not unit
    radius = 1.2
    F = loads.patch_loads(nodes, tri, centres, normals, radius)
    assert F.shape == (3 * len(nodes), 6)
    Fr = F.toarray().reshape(len(nodes), 3, 6)
    unit = normals / np.linalg.norm(normals, axis=1)[:, None]
    assert np.abs(Fr.sum(axis=0).T - unit).max() < 1e-13
    loaded = np.abs(Fr).sum(axis=1) > 0                                 # (N, 6)
    for j in range(6):   # nodes of facets touched by the patch: within radius + one facet
        d = np.linalg.norm(nodes[loaded[:, j]] - centres[j], axis=1)
        assert d.max() < radius + 1.5 * 1.2


def test_surface_traction_load_resultant_on_flat_and_curved_faces():
    nodes, tets = _gmsh_tets(lambda: gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, 10, 5), size=1.5)
    tri = _boundary_tri6(tets)
    top = tri[np.all(np.abs(nodes[tri][..., 2] - 10) < 1e-9, axis=1)]
    t = np.array([1.0, -2.0, 3.0])
    f = loads.surface_traction_load(nodes, top, t).reshape(-1, 3)
    area = f.sum(axis=0) / t
    # quadratic facets with mid-nodes on the circle: area of the disc to O(h^4)
    assert np.allclose(area, np.pi * 25, rtol=2e-4)
    # moment of a linear traction t_z = x on the disc: int x^2 dA = pi R^4 / 4
    tz = np.zeros((len(nodes), 3))
    tz[:, 2] = nodes[:, 0]
    fz = loads.surface_traction_load(nodes, top, tz).reshape(-1, 3)
    assert abs((fz[:, 2] * nodes[:, 0]).sum() / (np.pi * 5 ** 4 / 4) - 1) < 1e-3


# --- analytic solutions ------------------------------------------------------------------

def test_cantilever_tip_load_vs_timoshenko_beam():
    L, B, H, P = 100.0, 10.0, 10.0, 100.0
    nodes, tets = _gmsh_tets(lambda: gmsh.model.occ.addBox(0, 0, 0, L, B, H), size=2.5)
    K = el.assemble_stiffness(nodes, tets, E, NU)
    clamp = nodes[:, 0] < 1e-9
    fixed = np.concatenate([_dofs(clamp, k) for k in range(3)])
    tri = _boundary_tri6(tets)
    end = tri[np.all(nodes[tri][..., 0] > L - 1e-9, axis=1)]
    f = loads.surface_traction_load(nodes, end, [0.0, 0.0, -P / (B * H)])
    assert abs(f.sum() + P) < 1e-9
    u = el.factorize(K, fixed).solve(f)
    tip = (readout.interpolation_matrix(nodes, tets, [[L, B / 2, H / 2]]) @ u)[2]
    # Timoshenko beam (Timoshenko & Gere): P L^3 / (3 E I) + P L / (kappa G A),
    # kappa of a rectangle = 10 (1 + nu) / (12 + 11 nu) (Cowper 1966)
    I, A, G = B * H ** 3 / 12, B * H, E / (2 * (1 + NU))
    kappa = 10 * (1 + NU) / (12 + 11 * NU)
    w = P * L ** 3 / (3 * E * I) + P * L / (kappa * G * A)
    print(f"cantilever: tip {-tip:.6f} mm, Timoshenko {w:.6f} mm, ratio {-tip / w:.4f}")
    assert abs(-tip / w - 1) < 0.02
    # bending stress at mid-span, top fibre: sigma_xx = M (H/2) / I, M = P (L - x)
    s = (readout.stress_matrix(nodes, tets, E, NU, [[L / 2, B / 2, H - 1e-9]]) @ u)[0]
    s_ref = P * (L / 2) * (H / 2) / I
    print(f"cantilever: sigma_xx {s:.3f} MPa, beam {s_ref:.3f} MPa")
    assert abs(s / s_ref - 1) < 0.03


def _lame_error(size, a=10.0, b=20.0, T=2.0, p=100.0):
    def build():
        occ = gmsh.model.occ
        ring = occ.cut([(3, occ.addCylinder(0, 0, 0, 0, 0, T, b))], [(3, occ.addCylinder(0, 0, 0, 0, 0, T, a))])[0]
        occ.intersect(ring, [(3, occ.addBox(0, 0, 0, b, b, T))])

    nodes, tets = _gmsh_tets(build, size)
    K = el.assemble_stiffness(nodes, tets, E, NU)
    x, y, z = nodes.T
    fixed = np.concatenate([_dofs(np.abs(x) < 1e-9, 0), _dofs(np.abs(y) < 1e-9, 1),
                            _dofs((np.abs(z) < 1e-9) | (np.abs(z - T) < 1e-9), 2)])
    tri = _boundary_tri6(tets)
    rt = np.hypot(nodes[tri][..., 0], nodes[tri][..., 1])
    inner = tri[np.all(np.abs(rt - a) < 1e-6 * a, axis=1)]
    r = np.hypot(x, y)
    t = p * np.stack([x / r, y / r, 0 * r], axis=1)      # pressure on r = a pushes outward
    u = el.factorize(K, fixed).solve(loads.surface_traction_load(nodes, inner, t)).reshape(-1, 3)
    # Lame, plane strain (Timoshenko & Goodier, Theory of Elasticity, sec. 30):
    # u_r = (1 + nu) p a^2 / (E (b^2 - a^2)) ((1 - 2 nu) r + b^2 / r)
    ur = (1 + NU) * p * a ** 2 / (E * (b ** 2 - a ** 2)) * ((1 - 2 * NU) * r + b ** 2 / r)
    ue = np.stack([ur * x / r, ur * y / r, 0 * r], axis=1)
    err = np.sqrt(((u - ue) ** 2).sum() / (ue ** 2).sum())
    return err, 3 * len(nodes)


def test_lame_cylinder_converges_at_second_order_or_better():
    sizes = np.array([4.0, 2.0, 1.0])
    out = [_lame_error(h) for h in sizes]
    err = np.array([e for e, _ in out])
    order = np.log(err[:-1] / err[1:]) / np.log(sizes[:-1] / sizes[1:])
    for h, (e, n) in zip(sizes, out):
        print(f"Lame: h {h:.2f} mm, {n} dofs, relative nodal displacement error {e:.3e}")
    print("Lame: observed orders", order)
    assert err[-1] < 1e-3
    assert order[-1] > 1.8


@pytest.mark.slow
def test_lame_cylinder_fine_ladder():
    sizes = np.array([2.0, 1.0, 0.5])
    t0 = time.perf_counter()
    err = np.array([_lame_error(h)[0] for h in sizes])
    order = np.log(err[:-1] / err[1:]) / np.log(sizes[:-1] / sizes[1:])
    print(f"Lame fine ladder: errors {err}, orders {order}, {time.perf_counter() - t0:.1f} s")
    assert order[-1] > 1.8
