"""The process pool of ``ltca optimise``: the objective map, the Harris curves and a bevel candidate's cycles side
by side in worker processes that share the prepared backend (its bodies' compliance, computed once).

The workers are started with the 'spawn' method: a fresh interpreter each, so none inherits the thread pools
(MKL, OpenMP, OpenBLAS) or the locks of the process that computed the compliance. A forked child of a process
whose threads hold such a lock at the fork deadlocks on it; spawn has no such state to copy.

The backend goes to each worker once, at its start, pickled with its large arrays (the compliance ``C``, the
root-stress influence) written once to ``.npy`` files in a temporary folder and memory-mapped read-only by every
worker: the operating system's page cache holds one copy for all of them. The back-end's factorisation of a body
(PARDISO memory outside Python) is not sent: a worker solves contact problems on the compliance only.
"""
from __future__ import annotations

import contextlib
import copy
import io
import os
import pickle
import sys
import tempfile
import types

import numpy as np

__all__ = ["backend_pool", "backend", "dumps_shared", "MMAP_BYTES"]

#: arrays of at least this many bytes go to the workers as memory-mapped files (smaller ones are pickled)
MMAP_BYTES = 1 << 20

#: seconds the pool's workers may take to start (import the library, load the backend) before it is given up
START_SECONDS = 600.0

#: the backend of this process, for the pool's workers (set by the worker initialiser, or for one worker)
_BACKEND = None


def backend():
    """The backend this worker process was started with."""
    return _BACKEND


def _load_array(path: str) -> np.ndarray:
    return np.load(path, mmap_mode="r")


def _none():
    return None


class _SharedPickler(pickle.Pickler):
    """Pickles large plain arrays as a reference to a ``.npy`` file in ``folder`` and a solver factorisation as
    None."""

    def __init__(self, fh, folder: str):
        super().__init__(fh, protocol=pickle.HIGHEST_PROTOCOL)
        self.folder = folder
        self.saved = 0

    def reducer_override(self, obj):
        if type(obj) is np.ndarray and obj.nbytes >= MMAP_BYTES and not obj.dtype.hasobject:
            path = os.path.join(self.folder, f"a{self.saved}.npy")
            np.save(path, obj, allow_pickle=False)
            self.saved += 1
            return _load_array, (path,)
        from ltca.fem.solver import Factorization
        if isinstance(obj, Factorization):
            return _none, ()
        return NotImplemented


def dumps_shared(obj, folder: str) -> bytes:
    """``obj`` pickled with every plain array of at least :data:`MMAP_BYTES` saved to ``folder`` (loaded back
    memory-mapped, read-only) and every :class:`ltca.fem.solver.Factorization` replaced by None.

    Parameters
    ----------
    obj : object
        What to send (a prepared backend).
    folder : str
        An existing folder that outlives every process that unpickles the result.

    Returns
    -------
    bytes
        The pickle; ``pickle.loads`` gives the object back with the large arrays as ``numpy.memmap``.
    """
    fh = io.BytesIO()
    _SharedPickler(fh, folder).dump(obj)
    return fh.getvalue()


def _start_worker(payload: bytes) -> None:
    global _BACKEND
    _BACKEND = pickle.loads(payload)


def _ready(_=None) -> int:
    return os.getpid()


@contextlib.contextmanager
def _main_not_imported():
    """The workers run library functions only: while they are started, ``__main__`` is a bare module, so a spawned
    worker does not import the caller's script (a script without the ``if __name__ == "__main__":`` guard would
    otherwise run again in every worker)."""
    main = sys.modules.get("__main__")
    sys.modules["__main__"] = types.ModuleType("__main__")
    try:
        yield
    finally:
        if main is not None:
            sys.modules["__main__"] = main


def _for_worker(be):
    """A shallow copy of the backend without what stays in this process (its progress callback, its pool)."""
    w = copy.copy(be)
    for name in ("progress", "pool"):
        if hasattr(w, name):
            setattr(w, name, None)
    return w


@contextlib.contextmanager
def backend_pool(be, workers: int):
    """A pool of ``workers`` spawned processes, each holding ``be`` (see the module docstring); None for one
    worker (the caller then computes in this process).

    Parameters
    ----------
    be : backend
        The prepared backend (:class:`ltca.design.cylindrical.CylindricalBackend` or
        :class:`ltca.design.bevel.BevelBackend`).
    workers : int
        Processes of the pool.

    Yields
    ------
    multiprocessing.pool.Pool or None
    """
    if workers < 2:
        yield None
        return
    import multiprocessing as mp
    with tempfile.TemporaryDirectory(prefix="ltca-pool-") as folder:
        payload = dumps_shared(_for_worker(be), folder)
        with _main_not_imported():
            pool = mp.get_context("spawn").Pool(workers, initializer=_start_worker, initargs=(payload,))
        with pool:
            try:
                pool.map_async(_ready, range(workers), chunksize=1).get(START_SECONDS)
            except mp.TimeoutError:
                raise RuntimeError(f"the optimiser's {workers} worker processes did not start within "
                                   f"{START_SECONDS:.0f} s; run with workers=1") from None
            yield pool
