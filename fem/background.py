"""A call run in a daemon thread, its value or exception handed back when joined.

The thread is a daemon: an interrupted program does not wait for it. Used where a second core takes half of a
two-part job (:func:`ltca.fem.compliance.pair_compliance`, :func:`ltca.position_runs.solve_positions`).
"""
from __future__ import annotations

import threading
from typing import Any, Callable

__all__ = ["Background"]


class Background:
    """``call()`` in a daemon thread named ``name``, started at once.

    Parameters
    ----------
    call : callable() -> value
    name : str
        The thread's name (shown by profilers and in tracebacks).
    """

    def __init__(self, call: Callable[[], Any], name: str = "ltca-background") -> None:
        self._call, self._value, self._error = call, None, None
        self._thread = threading.Thread(target=self._run, name=name, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        try:
            self._value = self._call()
        except BaseException as exc:       # handed to the caller by result()
            self._error = exc

    def join(self) -> None:
        """Wait for the call to end, whatever its outcome."""
        self._thread.join()

    def result(self) -> Any:
        """Wait for the call; its value, or its exception raised here."""
        self._thread.join()
        if self._error is not None:
            raise self._error
        return self._value
