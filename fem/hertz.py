"""Elliptic Hertz contact of two elastic bodies (same material) from their relative curvature.

The gap between the unloaded surfaces near the first contact point is ``h = A x^2 + B y^2`` (0 < A <= B, x along
the ellipse's major axis).  With the eccentricity e = sqrt(1 - b^2/a^2) and the complete elliptic integrals
K(e), E(e) (modulus e, i.e. parameter m = e^2 in scipy):

    B / A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e)),
    a^3 = 3 F (K(e) - E(e)) / (2 pi e^2 E* A),    b = a sqrt(1 - e^2),
    p0 = 3 F / (2 pi a b),    approach delta = 3 F K(e) / (2 pi a E*),

with 1/E* = 2 (1 - nu^2) / E for two bodies of the same material.  Johnson, *Contact Mechanics* (1985),
sec. 4.2, eqs. (4.39)-(4.41); the approach from Johnson eq. (4.41c) (delta = p0 b K(e) / E* ... written with
p0 = 3F/(2 pi a b)).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

__all__ = ["EllipticHertz", "elliptic_hertz"]


@dataclass(frozen=True)
class EllipticHertz:
    """Semi-axes a >= b (mm), peak pressure p0 (MPa), approach delta (mm), eccentricity e."""
    a: float
    b: float
    p0: float
    delta: float
    e: float


def elliptic_hertz(F: float, A: float, B: float, E: float, nu: float) -> EllipticHertz:
    """Hertz contact of the gap ``A x^2 + B y^2`` (1/mm, A, B > 0) under the normal force ``F`` (N).

    Parameters
    ----------
    F : float
        Normal force, N (> 0).
    A, B : float
        Half the principal relative curvatures, 1/mm (> 0); their order does not matter.
    E, nu : float
        Young's modulus (MPa) and Poisson's ratio of both bodies.
    """
    if not (np.isfinite(F) and F > 0):
        raise ValueError(f"F = {F!r} is outside the allowed range (0, inf) N")
    A, B = sorted((float(A), float(B)))
    if not A > 0:
        raise ValueError(f"curvature A = {A!r} is outside the allowed range (0, inf) 1/mm (a line contact?)")
    Es = E / (2.0 * (1.0 - nu * nu))
    ratio = B / A
    if ratio - 1.0 < 1e-6:
        m = 0.0
    else:
        def f(m):
            K, Ee = ellipk(m), ellipe(m)
            return (Ee / (1 - m) - K) / (K - Ee) - ratio
        m = brentq(f, 1e-8, 1 - 1e-13, xtol=1e-16, rtol=1e-14)
    e = np.sqrt(m)
    if e == 0.0:
        a = (3 * F / (8 * Es * A)) ** (1 / 3)     # circle: a^3 = 3 F R / (4 E*), R = 1 / (2 A)
        K = np.pi / 2
    else:
        K, Ee = ellipk(m), ellipe(m)
        a = (3 * F * (K - Ee) / (2 * np.pi * m * Es * A)) ** (1 / 3)
    b = a * np.sqrt(1 - m)
    p0 = 3 * F / (2 * np.pi * a * b)
    delta = 3 * F * K / (2 * np.pi * a * Es)
    return EllipticHertz(float(a), float(b), float(p0), float(delta), float(e))
