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
