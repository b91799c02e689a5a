"""Errors the command line turns into one clear message and exit status 2 (no traceback)."""
from __future__ import annotations

__all__ = ["CaseError", "ConvergenceError"]


class CaseError(ValueError):
    """A user mistake in a case file or on the command line.

    Parameters
    ----------
    field : str
        Dotted path of the offending field, e.g. ``"pinion.teeth"``.
    value : object
        The value found (``None`` when missing).
    allowed : str
        What is allowed, in words, e.g. ``"an integer >= 3"``.
    """

    def __init__(self, field: str, value: object, allowed: str, file: str | None = None):
        self.field, self.value, self.allowed, self.file = field, value, allowed, file
        where = f"{file}: " if file else ""
        super().__init__(f"{where}field '{field}' = {_short(value)}: {allowed}")


def _short(value: object, n: int = 60) -> str:
    """The value as shown in a message: a table is not dumped, long values are cut to one short line."""
    if isinstance(value, dict):
        return "{table}"
    text = repr(value)
    return text if len(text) <= n else text[: n - 3] + "..."


class ConvergenceError(RuntimeError):
    """A solver that did not converge: says its residual and what to try."""

    def __init__(self, what: str, residual: float, iterations: int, advice: str):
        self.residual, self.iterations = residual, iterations
        super().__init__(f"{what} did not converge after {iterations} iterations "
                         f"(residual {residual:.3e}); try: {advice}")
