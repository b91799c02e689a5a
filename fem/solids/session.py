"""The gmsh session: gmsh initialised for the duration of a ``with`` block (every solid builder meshes in one)."""
from __future__ import annotations

import contextlib
from typing import Iterator

__all__ = ["gmsh_session"]


@contextlib.contextmanager
def gmsh_session(progress: bool = False) -> Iterator[None]:
    """Initialise gmsh for the duration of a ``with`` block; re-entrant safe.

    If gmsh is already initialised, it is left running on exit (only the models added inside are
    the caller's to remove). Output goes to the terminal only if ``progress``.
    """
    import gmsh

    owner = not gmsh.isInitialized()
    if owner:
        gmsh.initialize(readConfigFiles=False, interruptible=False)
    old_terminal = gmsh.option.getNumber("General.Terminal")
    gmsh.option.setNumber("General.Terminal", 1 if progress else 0)
    try:
        yield
    finally:
        if owner:
            gmsh.finalize()
        else:
            gmsh.option.setNumber("General.Terminal", old_terminal)
