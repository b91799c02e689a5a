"""The process pool of ``ltca optimise``: workers forked once the backend is prepared (they share its bodies and
compliance), for the objective map, the Harris curves and a bevel candidate's cycles side by side."""
from __future__ import annotations

import contextlib

__all__ = ["forked_pool", "backend"]

#: the backend of this process, for the pool's workers (forked after the compliance is computed: they share it)
_BACKEND = None


def backend():
    """The backend the pool's workers were forked with."""
    return _BACKEND


@contextlib.contextmanager
def forked_pool(be, workers: int):
    """``workers`` forked processes sharing ``be`` (None for one worker)."""
    global _BACKEND
    if workers < 2:
        yield None
        return
    import multiprocessing as mp
    _BACKEND = be
    try:
        with mp.get_context("fork").Pool(workers) as pool:
            yield pool
    finally:
        _BACKEND = None
