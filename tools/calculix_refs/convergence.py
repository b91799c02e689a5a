"""Convergence of a CalculiX refinement ladder: Richardson extrapolation with the observed order, Roache's grid
convergence index, and the converged estimate a frozen reference is compared with.

Read by the ladder and freeze scripts of :mod:`tools.calculix_refs` and by the tests that compare our figures with
the frozen references (``tests/test_reference_calculix*.py``).
"""
from __future__ import annotations

import numpy as np

__all__ = ["richardson", "grid_convergence_index", "converged_estimate"]


def richardson(values: list[float], ratio: float) -> tuple[float, float] | None:
    """Extrapolated limit and observed order of three values on meshes refined by ``ratio`` each time.

    p = ln((f0 - f1) / (f1 - f2)) / ln(ratio), f = f2 + (f2 - f1) / (ratio^p - 1) (Richardson extrapolation with
    the observed order; Roache, *Verification and Validation in Computational Science and Engineering*, 1998,
    ch. 5). None outside the asymptotic range: when the differences change sign or vanish, when the last one is
    not the smaller (no convergence), or when the order lies outside [0.5, 4] (the formal orders of quadratic
    elements are 2 for stress and 3 for displacement; an order far beyond them is a near-coincidence of two
    rungs, not a rate)."""
    f0, f1, f2 = values
    d1, d2 = f0 - f1, f1 - f2
    if d1 == 0 or d2 == 0 or d1 * d2 < 0 or abs(d2) >= abs(d1):
        return None
    p = np.log(d1 / d2) / np.log(ratio)
    if not 0.5 <= p <= 4.0:
        return None
    return float(f2 - d2 / (ratio ** p - 1)), float(p)


def grid_convergence_index(values: list[float], ratio: float, safety: float = 1.25) -> float | None:
    """Roache's grid convergence index of the finest of three rungs: safety |f2 - f1| / |f2| / (ratio^p - 1), the
    relative band that holds the converged value with the observed order p of :func:`richardson` (safety 1.25 for
    a three-rung study; Roache 1998; Celik et al., J. Fluids Eng. 130 (2008) 078001). None outside the asymptotic
    range."""
    est = richardson(values, ratio)
    if est is None:
        return None
    f1, f2 = values[1:]
    return float(safety * abs(f2 - f1) / abs(f2) / (ratio ** est[1] - 1))


def converged_estimate(values: list[float], sizes: list[float]) -> tuple[float, float | None]:
    """The converged estimate of a quantity over a refinement ladder (``values`` on element sizes ``sizes``,
    coarsest first) and its grid convergence index: where the last three rungs are refined by one ratio (within
    1 %) and converge in the asymptotic range, :func:`richardson` and :func:`grid_convergence_index`; otherwise
    the finest value and None."""
    if len(values) < 3 or None in values[-3:]:
        return values[-1], None
    h = sizes[-3:]
    ratio = h[0] / h[1]
    if abs(h[1] / h[2] / ratio - 1) > 0.01:
        return values[-1], None
    est = richardson(list(values[-3:]), ratio)
    return (values[-1], None) if est is None else (est[0], grid_convergence_index(list(values[-3:]), ratio))
