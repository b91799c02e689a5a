"""The sparse direct back-end for machines without MKL (``ltca.fem.solver``, ``"cvxopt"``: CHOLMOD from cvxopt's wheels).

Checked against scipy's SuperLU on the compliance pattern of the solver tests (the ``beam`` fixture, tests/fixtures/meshes.py) (a P2 beam, 100 sparse patch loads,
200 observed rows, and the transposed path with fewer rows than loads), and the automatic choice without pypardiso.
"""
from __future__ import annotations

import logging
import sys

import numpy as np
import pytest

from ltca.fem.solver import available_methods, factorize

pytest.importorskip("cvxopt")


def _rel(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.abs(a - b).max() / np.abs(b).max())


@pytest.mark.heavy
def test_cvxopt_matches_superlu_on_loads_rows_and_vectors(beam):
    K, fixed, F, O = beam
    ref = factorize(K, fixed, "splu")
    fac = factorize(K, fixed, "cvxopt")
    assert fac.method == "cvxopt"
    U = ref.solve(F)
    assert _rel(fac.solve(F), U) < 1e-10                                   # sparse loads, full displacements
    assert _rel(fac.solve(F.toarray()), U) < 1e-10                         # dense loads take the sparse path too
    assert _rel(fac.solve(F, observe=O), O @ U) < 1e-10                    # 200 rows >= 100 loads: the loads
    assert _rel(fac.solve(F, observe=O[:30], block=7), O[:30] @ U) < 1e-10  # 30 rows < 100 loads: the rows
    f = F[:, 5].toarray().ravel()
    assert _rel(fac.solve(f), U[:, 5]) < 1e-10                             # one vector, the dense solve
    res = (K @ fac.solve(F) - F.toarray())[fac.free]
    assert np.abs(res).max() < 1e-9 * np.abs(F).max()


def test_auto_without_pypardiso_takes_cvxopt_and_says_so(beam, monkeypatch, caplog):
    monkeypatch.setitem(sys.modules, "pypardiso", None)                  # pypardiso unimportable, as on arm64
    methods = available_methods()
    assert "pardiso" not in methods and "cvxopt" in methods and methods[-1] == "splu"
    K, fixed, F, O = beam
    with caplog.at_level(logging.INFO, logger="ltca.fem.solver"):
        fac = factorize(K, fixed)
    assert fac.method == methods[0]
    assert any(methods[0] in r.getMessage() for r in caplog.records)


def _cholesky_entries(A, perm) -> int:
    """Entries of the Cholesky factor of ``A[perm][:, perm]`` (SuperLU without pivoting: L is the Cholesky pattern)."""
    import scipy.sparse as sp
    from scipy.sparse.linalg import splu
    P = sp.csc_matrix(A[perm][:, perm])
    return splu(P, permc_spec="NATURAL", diag_pivot_thresh=0.0, options={"SymmetricMode": True}).L.nnz


def _grid_stiffness(n: int, seed: int = 0):
    """A 3-dof-per-node SPD matrix on an n x n x n grid (27-point stencil, as hexahedral elements couple nodes), the
    nodes numbered at random."""
    import scipy.sparse as sp
    band = sp.diags([1.0, 1.0, 1.0], [-1, 0, 1], shape=(n, n))
    graph = sp.kron(sp.kron(band, band), band)
    lap = sp.diags(np.asarray(graph.sum(1)).ravel() + 1.0) - 0.5 * graph
    shuffle = np.random.default_rng(seed).permutation(n ** 3)
    lap = sp.csr_matrix(lap)[shuffle][:, shuffle]
    return sp.csr_matrix(sp.kron(lap, np.eye(3) + 0.1))


def test_nested_dissection_orders_nodes_and_cuts_the_fill(monkeypatch):
    """METIS's ordering (pymetis) keeps a node's 3 dofs together and leaves a far smaller factor than a random
    numbering and a smaller one than SuperLU's minimum degree on A + A' (12^3 grid: 1.25 M entries against 9.95 M
    and 1.84 M; the inverse permutation taken for the ordering: 9.7 M); without pymetis it says None (cvxopt then
    orders with AMD)."""
    pytest.importorskip("pymetis")
    from scipy.sparse.linalg import splu

    from ltca.fem.solver import nested_dissection
    A = _grid_stiffness(12)
    perm = nested_dissection(A, 3)
    assert np.array_equal(np.sort(perm), np.arange(A.shape[0]))
    assert (perm.reshape(-1, 3) == perm[::3, None] + np.arange(3)).all() and not (perm[::3] % 3).any()
    random, metis = _cholesky_entries(A, np.arange(A.shape[0])), _cholesky_entries(A, perm)
    mmd = splu(A.tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True}).L.nnz
    print(f"\nCholesky entries: random numbering {random}, minimum degree {mmd}, METIS {metis}")
    assert metis < 0.3 * random and metis < mmd
    with pytest.raises(ValueError, match="block"):
        nested_dissection(A, 7)
    monkeypatch.setitem(sys.modules, "pymetis", None)
    assert nested_dissection(A, 3) is None
