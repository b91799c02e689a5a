"""The optimiser's worker pool started in a process whose PARDISO / MKL threads are at work.

A child made by ``fork`` inherits the locks of the parent's threads but not the threads: a lock held by an MKL or
OpenMP thread at the fork is never released in the child, and its first BLAS or PARDISO call waits forever. The
situation here: the FZG C14 bodies' compliance factorised by PARDISO in this process, a second thread
factorising and solving with PARDISO on two threads while the pool's workers start, then the pool's two workers
evaluate candidates of the optimiser. Every repetition must finish within a time bound and give the numbers of
this process. The 20-repetition version is in the slow tier.
"""
from __future__ import annotations

import threading
import time

import numpy as np
import pytest
import scipy.sparse as sp
import tomllib

from fixtures.paths import CASES, ROOT

#: seconds one repetition may take (two workers start in about 4 s and evaluate in about 1 s on an idle 2-core
#: machine; a deadlocked worker never returns)
BOUND_S = 60.0
VALUES = [{"tip_relief_um": x, "tip_relief_length_mm": 4.0} for x in (5.0, 30.0)]


@pytest.fixture(scope="module")
def prepared():
    """The optimiser's backend of the shipped FZG C14 case (coarse, 6 positions), compliance factorised by PARDISO
    in this process, and the candidates evaluated here."""
    from ltca.design.driver import _n_torques, make_backend
    from ltca.design.schema import parse_design
    d = tomllib.loads((CASES / "fzg_c14_optimise.toml").read_text())
    d["analysis"]["positions"] = 6
    be = make_backend("cylindrical", d, parse_design(d, "cylindrical", _n_torques(d, "case"), "case"), "case")
    be.prepare(200.0)
    return be, [be.evaluate(v) for v in VALUES]


def _pardiso_busy(stop: threading.Event) -> None:
    """Factorise and solve a 3-D Laplacian (13 824 unknowns) with PARDISO on two threads until ``stop``."""
    pypardiso = pytest.importorskip("pypardiso")
    from threadpoolctl import threadpool_limits
    n = 24
    lap = sp.diags([-1.0, 2.0, -1.0], [-1, 0, 1], shape=(n, n))
    eye = sp.identity(n)
    A = (sp.kron(sp.kron(lap, eye), eye) + sp.kron(sp.kron(eye, lap), eye) + sp.kron(sp.kron(eye, eye), lap)
         + 1e-3 * sp.identity(n ** 3)).tocsr()
    b = np.ones(n ** 3)
    with threadpool_limits(limits=2):
        while not stop.is_set():
            solver = pypardiso.PyPardisoSolver()
            solver.factorize(A)
            solver.solve(A, b)
            solver.free_memory(everything=True)


def _repeat(prepared, times: int) -> None:
    from ltca.design.driver import _measure
    from ltca.design.pool import backend_pool
    be, expected = prepared
    for i in range(times):
        stop = threading.Event()
        busy = threading.Thread(target=_pardiso_busy, args=(stop,), daemon=True)
        busy.start()
        t0 = time.perf_counter()
        try:
            with backend_pool(be, 2) as pool:
                stop.set()          # the workers are running: what they inherit is settled
                busy.join()
                got = pool.map_async(_measure, VALUES, chunksize=1).get(BOUND_S)
        finally:
            stop.set()
            busy.join()
        seconds = time.perf_counter() - t0
        assert seconds < BOUND_S, (i, seconds)
        for g, e in zip(got, expected):
            assert g.te_ptp_arcsec == e.te_ptp_arcsec and g.flank_pressure_mpa == e.flank_pressure_mpa, i


@pytest.mark.heavy
def test_pool_starts_beside_threaded_pardiso(prepared):
    _repeat(prepared, 2)


@pytest.mark.slow
def test_pool_starts_beside_threaded_pardiso_20_times(prepared):
    _repeat(prepared, 20)


def test_no_library_code_forks():
    """No module of the library starts processes with the 'fork' method."""
    import re
    root = ROOT
    hits = [f"{p.relative_to(root)}:{n}" for pkg in ("geometry", "fem", "ltca") for p in (root / pkg).rglob("*.py")
            for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
            if re.search(r"""get_context\(\s*["']fork["']|set_start_method\(\s*["']fork["']|os\.fork\(""", line)]
    assert not hits, hits
