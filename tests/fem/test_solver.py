"""fem.solver on the compliance pattern: many sparse patch loads, a sparse observation matrix.

The fast path (``Factorization.solve(F, observe=O)`` without PARDISO's per-solve iterative
refinement, or solved for the observed rows when they are fewer than the loads) must equal the
plain full solve to 1e-10, and the full solve must still work afterwards.
"""
from __future__ import annotations

import time

import numpy as np
import pytest
import scipy.sparse as sp

from fixtures.meshes import BEAM_SIZE
from ltca.fem.solver import available_methods, factorize

L, B, H = BEAM_SIZE


def _median_time(fun, repeats: int = 3):
    """Median wall time of `repeats` calls of ``fun()`` and the last result."""
    times, out = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fun()
        times.append(time.perf_counter() - t0)
    return float(np.median(times)), out


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a - b).max() / np.abs(b).max())


def _plain_pardiso(K, fixed):
    """The pre-change PARDISO path: pypardiso's MKL defaults (iterative refinement in every solve)."""
    import pypardiso

    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    A = sp.triu(sp.csr_matrix(K)[free][:, free], format="csr")
    A.sort_indices()
    solver = pypardiso.PyPardisoSolver(mtype=2, size_limit_storage=0)
    solver.factorize(A)

    def solve(F):
        solver.set_phase(33)
        U = np.zeros(F.shape)
        U[free] = solver._call_pardiso(A, sp.csc_matrix(F)[free].toarray(order="F"))
        return U

    return solve, solver


@pytest.mark.heavy
def test_observe_fast_path_equals_plain_full_solve_and_full_solve_still_works(beam):
    pytest.importorskip("pypardiso")
    K, fixed, F, O = beam
    assert 30_000 <= K.shape[0] <= 60_000 and F.shape[1] == 100 and O.shape[0] == 600

    plain, plain_solver = _plain_pardiso(K, fixed)
    fac = factorize(K, fixed, "pardiso")
    U_old = plain(F)
    ref = O @ U_old
    t_old, _ = _median_time(lambda: O @ plain(F))
    t_new, Y = _median_time(lambda: fac.solve(F, observe=O))
    assert Y.shape == (600, 100)
    assert _rel(Y, ref) < 1e-10

    # the full solve after the observed one: same displacements, zero on the fixed dofs
    U = fac.solve(F)
    assert np.all(U[fixed] == 0)
    assert _rel(U, U_old) < 1e-10
    assert _rel(O @ U, ref) < 1e-10
    res = (K @ U - F.toarray())[fac.free]
    assert np.abs(res).max() < 1e-9 * np.abs(F).max()
    # ... and a single load vector, and the observed path again
    assert _rel(fac.solve(F[:, 7].toarray().ravel()), U_old[:, 7]) < 1e-10
    assert _rel(fac.solve(F, observe=O), ref) < 1e-10

    print(f"\n{K.shape[0]} dofs, 100 patch loads, {O.shape[0]} observed rows (median of 3): "
          f"MKL's default refinement {t_old:.2f} s, solve(F, observe) {t_new:.2f} s "
          f"({t_old / t_new:.1f}x)")
    plain_solver.free_memory(everything=False)
    fac.release()


@pytest.mark.parametrize("method", [m for m in available_methods() if m != "splu"])
def test_observe_with_fewer_rows_than_loads_solves_for_the_rows(beam, method):
    K, fixed, F, O = beam
    O_few = O[:30]                                # 30 rows < 100 loads: the transposed path
    fac = factorize(K, fixed, method)
    U = fac.solve(F)
    ref = O_few @ U
    assert _rel(fac.solve(F, observe=O_few), ref) < 1e-10
    assert _rel(fac.solve(F, observe=O_few.toarray(), block=7), ref) < 1e-10
    assert _rel(fac.solve(F.toarray(), observe=O_few, block=11), ref) < 1e-10
    f = F[:, 3].toarray().ravel()                 # one load, 30 rows: the direct path, vector out
    assert _rel(fac.solve(f, observe=O_few), ref[:, 3]) < 1e-10
    fac.release()


def test_body_without_solver_frees_the_factor_and_keeps_the_compliance(beam):
    """``BodyCompliance.without_solver``: the back-end factor is released at once (not when the collector gets to
    it), the copy has no mesh, factor or patch, and every figure the contact reads (C, root stress) is the same object."""
    from ltca.fem.compliance import BodyCompliance
    if "pardiso" not in available_methods():
        pytest.skip("PARDISO (pypardiso) missing: the other back-ends hold their factor in Python")
    K, fixed, F, O = beam
    fact = factorize(K, fixed, method="pardiso")
    assert fact._release is not None
    body = BodyCompliance(spec=None, s_grid=np.zeros(2), z_grid=np.zeros(2), C=np.eye(4), depth=np.zeros(2),
                          root_points=np.zeros((0, 3)), root_tooth=np.zeros(0, int),
                          root_stress=np.zeros((0, 6, 4)), n_dofs=K.shape[0], mesh=object(), factorization=fact,
                          patch=F)
    lean = body.without_solver()
    assert lean.factorization is None and lean.mesh is None and lean.patch is None
    assert lean.C is body.C and lean.root_stress is body.root_stress and lean.n_dofs == body.n_dofs
    assert fact._release is None                     # freed now, not when the garbage collector gets to it
