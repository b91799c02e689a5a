"""Sorting of the exceptions that are not :class:`~ltca.errors.CaseError` into exit statuses (``ltca.cli``):

- 2: a user's design the geometry cannot make or mesh (bevel ``MeshingError``, ``ContactError``), a full disk or
  another OS-level refusal to write; one line with the fields that drive it and advice;
- 3: a solver that did not converge, with its residual;
- 1: anything else is a bug (the command line prints the traceback and asks for a report).
"""
from __future__ import annotations

import errno

__all__ = ["classify"]

_BEVEL_FIELDS = ("bevel.working.path_angle_deg", "bevel.working.te_magnitude_arcsec", "bevel.working.ellipse_major_mm",
                 "bevel.coast.*", "bevel.spiral_angle_deg", "bevel.cutter_radius_mm")


def classify(exc: BaseException) -> tuple[int, str]:
    """(exit status, one-line message) of an exception."""
    from ltca.fem.contact import ContactNotConverged
    from ltca.geometry.bevel.generation import MeshingError
    from ltca.geometry.bevel.tca import ContactError
    text = " ".join(str(exc).split())[:300]
    if isinstance(exc, (MeshingError, ContactError)):
        fields = ", ".join(f"'{f}'" for f in _BEVEL_FIELDS)
        return 2, (f"the design cannot be {'generated' if isinstance(exc, MeshingError) else 'brought into contact'}"
                   f" ({type(exc).__name__}: {text}); set by {fields}: move them towards a working case")
    if isinstance(exc, ContactNotConverged):
        return 3, f"contact solve did not converge (residual {exc.residual:.3e} after {exc.iterations} iterations); " \
                  f"try: {exc.advice}"
    if isinstance(exc, OSError) and exc.errno in (errno.ENOSPC, errno.EDQUOT, errno.EROFS, errno.EACCES, errno.EPERM):
        where = f" ({exc.filename})" if exc.filename else ""
        return 2, f"cannot write the results{where}: {exc.strerror}; free space or choose another --out " \
                  "(run.json says 'failed'; rerun with --resume to keep the finished positions)"
    return 1, text
