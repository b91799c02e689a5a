"""The gmsh session: gmsh initialised for the duration of a ``with`` block (every solid builder meshes in one).

gmsh's initialisation installs its own handler for SIGTERM at the C level and sets SIGPIPE back to the default
action, and both stay after ``gmsh.finalize``. A process that has meshed once would then die on SIGTERM without
running the Python handler a caller had set (``ltca run`` turns SIGTERM into an ``interrupted`` run status), and
die on a write to a closed pipe or socket instead of raising ``BrokenPipeError`` (Python ignores SIGPIPE). A
session opened in the main thread puts the Python dispositions back after initialising gmsh. A session opened in
another thread cannot (signal handlers are the main thread's to set): open an enclosing session in the main thread
first, so that the thread's session finds gmsh initialised.
"""
from __future__ import annotations

import contextlib
import signal
import threading
from typing import Iterator

__all__ = ["gmsh_session"]

#: the signals whose Python handlers a session keeps
_KEPT = (signal.SIGTERM, signal.SIGINT) + ((signal.SIGPIPE,) if hasattr(signal, "SIGPIPE") else ())


@contextlib.contextmanager
def gmsh_session(progress: bool = False) -> Iterator[None]:
    """Initialise gmsh for the duration of a ``with`` block; re-entrant safe.

    If gmsh is already initialised, it is left running on exit (only the models added inside are
    the caller's to remove). Output goes to the terminal only if ``progress``. In the main thread, the Python
    signal handlers of SIGTERM, SIGINT and SIGPIPE are the same after the session starts as before (module docstring).
    """
    import gmsh

    owner = not gmsh.isInitialized()
    if owner:
        main = threading.current_thread() is threading.main_thread()
        kept = {s: signal.getsignal(s) for s in _KEPT} if main else {}
        gmsh.initialize(readConfigFiles=False, interruptible=False)
        for s, handler in kept.items():
            if handler is not None:          # None: a handler not set from Python, nothing to put back
                signal.signal(s, handler)
    old_terminal = gmsh.option.getNumber("General.Terminal")
    gmsh.option.setNumber("General.Terminal", 1 if progress else 0)
    try:
        yield
    finally:
        if owner:
            gmsh.finalize()
        else:
            gmsh.option.setNumber("General.Terminal", old_terminal)
