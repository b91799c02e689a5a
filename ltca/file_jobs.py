"""File jobs: the files of a run written in the calling process, or by a second process beside it.

Writing a run's files is Python that holds the GIL (matplotlib's drawing, meshio's base64 and zlib, the netCDF
serialisation), so a second thread cannot overlap it with the main process's own work on the other files (the
ParaView fields' back-substitutions, the report's checks). A second *process* can. A writer hands every file to a
:class:`FileJobs` as a job, a function and its arguments:

- :class:`FileJobs` runs each job at once in the caller (the library's default: :meth:`ltca.LoadedResult.save`
  starts no process);
- :class:`BackgroundFiles` runs them, in the order given, in one worker process started with ``spawn`` (the same on
  every platform, and no copy of a parent whose MKL or OpenMP threads are running). ``ltca run`` starts it with
  the run, so that it imports the writers while the main process meshes, and gives it the files when the
  analysis is done.

:meth:`FileJobs.wait` returns when every job so far is done and raises the first job's exception (after all of
them have stopped: a failed run's staging folder is not written into after it is removed). A job's arguments are
pickled: data (datasets, meshes, arrays), not solvers.
"""
from __future__ import annotations

from concurrent.futures import Future
from typing import Any, Callable, Sequence

__all__ = ["FileJobs", "BackgroundFiles", "start_background"]


class FileJobs:
    """Jobs run at once in the calling process."""

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> None:
        """Run ``fn(*args, **kwargs)``."""
        fn(*args, **kwargs)

    def wait(self) -> None:
        """Every job submitted so far is done (here: always)."""

    def close(self) -> None:
        """Release the worker, if any."""

    def __enter__(self) -> "FileJobs":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _ready(modules: Sequence[str]) -> None:
    """Worker start-up: leave Ctrl-C to the main process (which stops the worker) and import the writers."""
    import importlib
    import signal
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for name in modules:
        importlib.import_module(name)


class BackgroundFiles(FileJobs):
    """Jobs run in submission order by one worker process (module docstring).

    Parameters
    ----------
    modules : sequence of str
        Modules the worker imports as it starts (the writers the jobs will call), while the caller goes on.
    """

    def __init__(self, modules: Sequence[str] = ()):
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor
        self._pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn"), initializer=_ready,
                                         initargs=(tuple(modules),))
        self._pending: list[Future] = [self._pool.submit(int)]     # the pool starts its worker at the first job

    def submit(self, fn: Callable[..., Any], /, *args: Any, **kwargs: Any) -> None:
        """Queue ``fn(*args, **kwargs)`` for the worker."""
        self._pending.append(self._pool.submit(fn, *args, **kwargs))

    def wait(self) -> None:
        """Wait for every queued job; raise the first one's exception once all have stopped."""
        from concurrent.futures import wait
        from concurrent.futures.process import BrokenProcessPool
        pending, self._pending = self._pending, []
        wait(pending)
        for f in pending:
            exc = f.exception()
            if isinstance(exc, BrokenProcessPool):
                raise RuntimeError("the process writing the run's files stopped unexpectedly (killed, or out of "
                                   "memory); no file it had not finished was kept") from exc
            if exc is not None:
                raise exc

    def close(self) -> None:
        """Stop the worker; jobs not started are dropped (:meth:`wait` first to keep them)."""
        self._pool.shutdown(wait=True, cancel_futures=True)


def start_background(modules: Sequence[str] = ()) -> FileJobs:
    """A :class:`BackgroundFiles`, or the serial :class:`FileJobs` where no process can be started (a sandbox
    without ``fork``/``exec``, too many processes)."""
    try:
        return BackgroundFiles(modules)
    except OSError:
        return FileJobs()
