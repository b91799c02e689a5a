"""Measure the hand-written pieces of ltca.fem against what scikit-fem offers for them, on the FZG C14 pinion body at
the default fidelity: time and agreement. The numbers go to docs/design.md (section "Libraries the design names").

    PYTHONPATH=. python3 tools/measure_fem_libraries.py [--cache DIR]

Pieces: the point read-out (locate the compliance read points in the P2 mesh and interpolate; scikit-fem:
``Mesh.element_finder`` and ``Basis.probes``), the P2 stiffness (scikit-fem: ``asm`` of ``linear_elasticity`` on
an ``ElementVector(ElementTetP2())`` basis), the facet quadrature (scikit-fem's degree-5 triangle rule as the
base of the subdivided rule) and the mesh record (scikit-fem's ``MeshTet2`` with named boundaries).
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp


def _best(f, repeat: int = 3):
    """((smallest wall time, smallest CPU time of this process) of ``repeat`` calls, s; the last result). On a
    shared machine the CPU time is the steadier figure (the pieces run on one thread, BLAS aside)."""
    wall, cpu, out = np.inf, np.inf, None
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = f()
        wall, cpu = min(wall, time.perf_counter() - t0), min(cpu, time.process_time() - c0)
    return (round(wall, 3), round(cpu, 3)), out


def fzg_pinion(cache):
    """The FZG C14 pinion body (default fidelity), its compliance read points (d and 2d under the loaded flank grid)
    and its loaded flank facets."""
    from ltca.case import FIDELITIES, load_case
    from ltca.cylindrical.loaded_model import Fidelity, plan_bodies
    from ltca.cylindrical.loop import cycle_rolls
    from ltca.cylindrical.model import build_model
    from ltca.fem.compliance import body_spec
    from ltca.fem.solids.gear_body import build_gear_body
    from ltca.geometry.cylindrical import helical_flank
    case = load_case(Path(__file__).resolve().parent.parent / "cases" / "fzg_c14.toml")
    model = build_model(case)
    fid = Fidelity.from_preset(FIDELITIES["default"], case.module)
    plan = plan_bodies(model, fid, cycle_rolls(30, case.pinion.teeth), case.torques[0])
    spec, p = plan.spec1, model.pinion
    mesh = build_gear_body(body_spec(p, spec), cache_dir=cache)
    ns, nz = spec.grid
    flanks = [helical_flank(p, spec.side, spec.face_width, ns, nz, r_range=tuple(spec.r_range), tooth=k)
              for k in spec.loaded]
    half = np.abs(p.flank_angle(flanks[0].u, spec.side))
    depth = np.minimum(spec.depth, 0.15 * 2 * flanks[0].u * np.sin(np.clip(half, 0, np.pi / 2)))
    X = np.concatenate([f.points.reshape(-1, 3) for f in flanks])
    N = np.concatenate([f.normals.reshape(-1, 3) for f in flanks])
    d = np.tile(np.repeat(depth, nz), len(spec.loaded))[:, None]
    Y = np.concatenate([X - d * N, X - 2 * d * N])
    side = "right" if spec.side > 0 else "left"
    tri = np.concatenate([mesh.facets[f"flank_{k}_{side}"] for k in spec.loaded])
    return mesh, Y, X, N, tri, spec


def _skfem_mesh(mesh):
    """A scikit-fem MeshTet of the vertices, its P2 vector basis and the map ``perm`` from its dofs to ours
    (node-major, 3 a + k)."""
    from scipy.spatial import cKDTree
    from skfem import Basis, ElementTetP2, ElementVector, MeshTet
    vert = np.unique(mesh.tets[:, :4])
    m = MeshTet(mesh.nodes[vert].T.copy(), np.searchsorted(vert, mesh.tets[:, :4]).T.copy())
    basis = Basis(m, ElementVector(ElementTetP2()), intorder=2)
    tree = cKDTree(mesh.nodes)
    perm = np.empty(basis.N, int)
    for c in range(3):
        dofs = np.concatenate([basis.nodal_dofs[c], basis.edge_dofs[c]])
        dist, node = tree.query(basis.doflocs[:, dofs].T)
        assert dist.max() < 1e-9 * np.abs(mesh.nodes).max()
        perm[dofs] = 3 * node + c
    return m, basis, perm


def readout(mesh, Y):
    from ltca.fem.readout import interpolation_matrix, locate_points
    t_ours, P = _best(lambda: interpolation_matrix(mesh.nodes, mesh.tets, Y))
    elem, bary = locate_points(mesh.nodes, mesh.tets, Y)
    t_basis, (m, basis, perm) = _best(lambda: _skfem_mesh(mesh), repeat=1)
    find = m.element_finder()
    inside = np.ones(len(Y), bool)
    try:
        t_find, found = _best(lambda: find(*Y.T))
    except ValueError:
        found = None
        t_find = None
        inside = np.array([_finds(find, y) for y in Y])
    t_probe, Q = _best(lambda: basis.probes(Y[inside].T))
    Q = Q.tocoo()
    Qn = sp.csr_matrix((Q.data, (Q.row, perm[Q.col])), shape=(Q.shape[0], 3 * len(mesh.nodes)))
    rng = np.random.default_rng(0)
    u = rng.standard_normal(3 * len(mesh.nodes))
    a = (P @ u).reshape(-1, 3)[inside]
    b = Qn @ u
    # a vector basis probes component-major (all x, then y, z) or point-major: take the one it is
    b = min((b.reshape(3, -1).T, b.reshape(-1, 3)), key=lambda v: np.abs(v - a).max())
    agree = float(np.abs(b - a).max() / np.abs(a).max())
    same_elem = None if found is None else float(np.mean(found == elem))
    return dict(points=len(Y), outside=int((~inside).sum()), t_ours=t_ours, t_skfem_basis=t_basis, t_find=t_find,
                t_probe=t_probe, probe_rows=Q.shape[0], agreement=agree, same_element=same_elem)


def _finds(find, y) -> bool:
    try:
        find(*y[:, None])
        return True
    except ValueError:
        return False


def stiffness(mesh, E: float, nu: float):
    from skfem import asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    from ltca.fem.elastic import assemble_stiffness
    t_ours, K = _best(lambda: assemble_stiffness(mesh.nodes, mesh.tets, E, nu), repeat=2)
    m, basis, perm = _skfem_mesh(mesh)
    t_sk, Ks = _best(lambda: asm(linear_elasticity(*lame_parameters(E, nu)), basis), repeat=2)
    P = sp.csr_matrix((np.ones(len(perm)), (perm, np.arange(len(perm)))), shape=(len(perm), len(perm)))
    Kp = (P @ Ks @ P.T).tocsr()
    diff = abs(Kp - K).max() / abs(K).max()
    return dict(dofs=K.shape[0], t_ours=t_ours, t_skfem=t_sk, agreement=float(diff))


#: the 7-point degree-5 triangle rule as tabulated by Strang & Fix 1973 (table 4.1), barycentric (a, b, b) orbits
STRANG_FIX_7 = (np.array([[1 / 3, 1 / 3, 1 / 3],
                          [0.0597158717897698, 0.4701420641051151, 0.4701420641051151],
                          [0.4701420641051151, 0.0597158717897698, 0.4701420641051151],
                          [0.4701420641051151, 0.4701420641051151, 0.0597158717897698],
                          [0.7974269853530873, 0.1012865073234563, 0.1012865073234563],
                          [0.1012865073234563, 0.7974269853530873, 0.1012865073234563],
                          [0.1012865073234563, 0.1012865073234563, 0.7974269853530873]]),
                np.array([0.225] + [0.1323941527885062] * 3 + [0.1259391805448271] * 3))


def quadrature(mesh, X, N, tri):
    """The patch loads of the compliance (0.75 of a 2 mm grid spacing, 28 points per facet) with the base rule
    typed from the table against scikit-fem's."""
    import ltca.fem.loads as loads
    t_sk, G = _best(lambda: loads.patch_loads(mesh.nodes, tri, X, -N, 0.75 * 2.0))
    skfem_rule = loads._base_rule
    loads._base_rule = lambda: STRANG_FIX_7
    try:
        t_table, F = _best(lambda: loads.patch_loads(mesh.nodes, tri, X, -N, 0.75 * 2.0))
    finally:
        loads._base_rule = skfem_rule
    diff = abs(G - F).max() / abs(F).max()
    pts, wts = skfem_rule()
    return dict(patches=F.shape[1], t_table=t_table, t_skfem_rule=t_sk, agreement=float(diff),
                rule_points_differ=float(np.abs(np.sort(pts, 0) - np.sort(STRANG_FIX_7[0], 0)).max()))


def mesh_record(mesh):
    t0, c0 = time.perf_counter(), time.process_time()
    vert = np.unique(mesh.tets[:, :4])
    m, _, _ = _skfem_mesh(mesh)
    # named boundaries: the facets of each of our groups found among scikit-fem's facets by their vertex sets
    keys = {tuple(sorted(f)): i for i, f in enumerate(m.facets.T)}
    inv = -np.ones(len(mesh.nodes), int)
    inv[vert] = np.arange(len(vert))
    groups = {name: np.array([keys[tuple(sorted(inv[f[:3]]))] for f in tri]) for name, tri in mesh.facets.items()}
    m2 = m.with_boundaries(groups)
    t = (round(time.perf_counter() - t0, 3), round(time.process_time() - c0, 3))
    return dict(nodes=len(mesh.nodes), tets=len(mesh.tets), t_skfem_record=t, groups=len(m2.boundaries))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cache", default=None, help="mesh cache folder")
    a = ap.parse_args(argv)
    t0 = time.perf_counter()
    mesh, Y, X, N, tri, spec = fzg_pinion(a.cache)
    print(f"FZG C14 pinion: {len(mesh.nodes)} nodes, {len(mesh.tets)} tets, {3 * len(mesh.nodes)} dofs "
          f"({time.perf_counter() - t0:.1f} s)")
    print("read-out:", readout(mesh, Y))
    print("quadrature:", quadrature(mesh, X, N, tri))
    print("mesh record:", mesh_record(mesh))
    print("stiffness:", stiffness(mesh, spec.young, spec.poisson))


if __name__ == "__main__":
    main()
