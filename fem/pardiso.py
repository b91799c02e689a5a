"""MKL PARDISO for :mod:`ltca.fem.solver`: where MKL's runtime is, and the factorisation with its back-substitution.

pypardiso (:class:`pypardiso.PyPardisoSolver`) holds PARDISO's handle and parameters; the two phases are called
through its ``_mkl_pardiso`` with the arguments of its ``_call_pardiso`` (see :func:`pardiso_factor` for what is
done differently and why). These are pypardiso's internals, so pyproject.toml holds it below 0.5.
"""
from __future__ import annotations

import numpy as np
import scipy.sparse as sp

__all__ = ["mkl_rt_path", "pardiso_factor"]


def mkl_rt_path() -> None:
    """Tell pypardiso where MKL's runtime is, once per process: without it every solver instance (and the one
    pypardiso builds when imported) searches the Python prefix with a recursive glob (about 1 s each).
    The library's usual places (``lib`` of the prefix, ``Library/bin`` on Windows) are looked at first."""
    import ctypes.util
    import glob
    import os
    import sys

    if os.environ.get("PYPARDISO_MKL_RT") or ctypes.util.find_library("mkl_rt"):
        return
    for pattern in (f"{sys.prefix}/[Ll]ib*/*mkl_rt*", f"{sys.prefix}/Library/bin/*mkl_rt*",
                    f"{sys.prefix}/[Ll]ib*/**/*mkl_rt*"):
        for path in sorted(glob.glob(pattern, recursive=True), key=len):
            try:
                ctypes.CDLL(path)
            except OSError:
                continue
            os.environ["PYPARDISO_MKL_RT"] = path
            return


def pardiso_factor(Kff: sp.csr_matrix, symmetric: bool):
    """Factorise the free block of a stiffness matrix with PARDISO.

    Parameters
    ----------
    Kff : scipy.sparse.csr_matrix, (m, m)
        With ``symmetric`` (``mtype=2``, Cholesky) its upper triangle (:func:`ltca.fem.solver._free_block` with
        ``upper``), else the whole block (``mtype=11``).
    symmetric : bool

    Returns
    -------
    solve : callable
        ``solve(b)`` for b (m,) or (m, k): the solution, Fortran-ordered.
    release : callable
        Frees PARDISO's factor.
    """
    import ctypes

    import pypardiso
    from pypardiso.pardiso_wrapper import PyPardisoError

    mkl_rt_path()
    A = Kff
    if symmetric:
        solver = pypardiso.PyPardisoSolver(mtype=2, size_limit_storage=0)
    else:
        solver = pypardiso.PyPardisoSolver(mtype=11, size_limit_storage=0)
    A.sort_indices()
    if not np.diff(A.indptr).all():     # PARDISO crashes on an empty row (pypardiso's own check)
        raise ValueError("K: the free block has an empty row: it is singular")
    # MKL is called with the arguments of ``PyPardisoSolver._call_pardiso`` (pypardiso's ``factorize`` is phase 12,
    # a direct phase-33 call the documented reuse of its factor), but with the 1-based index arrays made once,
    # without pypardiso's SHA-1 of A (it keeps it to recognise A in its own ``solve``) and with the solution left
    # in Fortran order: pypardiso zeroes x first and copies it to C order after, which cost as much as a third
    # of the back-substitution of the 216 unit loads of a gear body (68k dofs).
    ia, ja = A.indptr.astype(np.int32) + 1, A.indices.astype(np.int32) + 1
    i32 = ctypes.POINTER(ctypes.c_int32)
    f64 = ctypes.POINTER(ctypes.c_double)

    def call(phase: int, b: np.ndarray) -> np.ndarray:
        b = np.asfortranarray(b, dtype=np.float64)
        x = np.empty_like(b, order="F")
        nrhs = 1 if b.ndim == 1 else b.shape[1]
        error = ctypes.c_int32(0)
        one = ctypes.c_int32(1)
        solver._mkl_pardiso(solver.pt.ctypes.data_as(ctypes.POINTER(solver._pt_type[0])), ctypes.byref(one),
                            ctypes.byref(one), ctypes.byref(ctypes.c_int32(solver.mtype)),
                            ctypes.byref(ctypes.c_int32(phase)), ctypes.byref(ctypes.c_int32(A.shape[0])),
                            A.data.ctypes.data_as(f64), ia.ctypes.data_as(i32), ja.ctypes.data_as(i32),
                            solver.perm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(nrhs)),
                            solver.iparm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(0)),
                            b.ctypes.data_as(f64), x.ctypes.data_as(f64), ctypes.byref(error))
        if error.value != 0:
            raise PyPardisoError(error.value)
        return x

    solver.set_iparm(12, 0)             # CSR (pypardiso's setting for a CSR A)
    call(12, np.zeros((A.shape[0], 1)))  # analysis and numerical factorisation
    # After the first call MKL has filled ``iparm`` with its defaults (``iparm(1) = 1``), among
    # them ``iparm(8) = 2``: two steps of iterative refinement in every solve, which triples the
    # back-substitution cost. They only pay off against perturbed pivots (``iparm(14)``), which a
    # Cholesky factor of an SPD matrix never has; the factorisation itself is unchanged.
    if solver.get_iparm(14) == 0:
        solver.set_iparm(8, 0)
    # one matrix per solver handle: phase -1 frees all of its memory (phase 0 frees the factor only and leaves
    # about 1.3 kB per dof resident)
    return (lambda b: call(33, b)), lambda: solver.free_memory(everything=True)
