"""Errors of the REXS reader and writer: a bad or partial file names the component, the attribute and what is
missing or wrong; a :class:`ltca.errors.CaseError`, so the command line exits with status 2."""
from __future__ import annotations

from ..errors import CaseError

__all__ = ["RexsError"]


class RexsError(CaseError):
    """A REXS model we cannot read or map.

    Parameters
    ----------
    component : str
        The component as ``"cylindrical_gear 15 'Cylindrical gear [27]'"`` (or the part of the file).
    attribute : str
        The attribute id (or ``"-"`` when the component itself is missing or wrong).
    problem : str
        What is missing or wrong, and what is allowed.
    value : object
        The value found (``None`` when missing).
    file : str, optional
        The file read.
    """

    def __init__(self, component: str, attribute: str, problem: str, value: object = None,
                 file: str | None = None):
        self.component, self.attribute, self.problem = component, attribute, problem
        super().__init__(f"{component}: {attribute}", value, problem, file)
