"""Flank tolerances of cylindrical gears from an ISO 1328-1:2013 flank tolerance class (our own code from the
formulae of the standard).

ISO 1328-1:2013, clause 5 ("tolerance values"): the tolerance of flank tolerance class A is the class-5 value
times the step factor sqrt(2)^(A - 5) (5.2.2), computed from the actual reference diameter d, normal module m_n
and face width b in mm (not the geometric means of ranges of the 1995 edition) and rounded by the rules of
5.2.3: above 10 um to the nearest 1 um, from 5 to 10 um to the nearest 0.5 um, below 5 um to the nearest 0.1 um.
Formulae, in um:

    (5)  f_pT      = (0.001 d + 0.4 m_n + 5) sqrt(2)^(A-5)                 single pitch
    (6)  F_pT      = (0.002 d + 0.55 sqrt(d) + 0.7 m_n + 12) sqrt(2)^(A-5) total cumulative pitch
    (7)  f_HalphaT = (0.4 m_n + 0.001 d + 4) sqrt(2)^(A-5)                 profile slope
    (8)  f_falphaT = (0.55 m_n + 5) sqrt(2)^(A-5)                          profile form
    (9)  F_alphaT  = sqrt(f_HalphaT^2 + f_falphaT^2)                       total profile (unrounded terms)
    (10) f_HbetaT  = (0.05 sqrt(d) + 0.35 sqrt(b) + 4) sqrt(2)^(A-5)       helix slope
    (11) f_fbetaT  = (0.07 sqrt(d) + 0.45 sqrt(b) + 4) sqrt(2)^(A-5)       helix form
    (12) F_betaT   = sqrt(f_HbetaT^2 + f_fbetaT^2)                         total helix (unrounded terms)
         F_rT      = 0.9 F_pT                                              runout (unrounded F_pT)

Scope (clause 1): classes 1 to 11, 5 <= z <= 1000, 5 <= d <= 15000 mm, 0.5 <= m_n <= 70 mm, 4 <= b <= 1200 mm,
|beta| <= 45 deg; the standard forbids extrapolation, so values outside are refused.
Clause and formula numbers as in the 2013 edition (cross-read against published implementations; the text
of the standard is not reproduced here).

Imports nothing of ours but ltca.errors.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from ..errors import CaseError

__all__ = ["Iso1328Tolerances", "iso1328_round", "iso1328_tolerances", "TOLERANCE_KINDS"]

#: the deviations a Monte Carlo study draws, and the tolerance that bounds each (attribute names)
TOLERANCE_KINDS = {"f_pt": "f_pT", "f_Halpha": "f_HalphaT", "f_falpha": "f_falphaT",
                   "f_Hbeta": "f_HbetaT", "f_fbeta": "f_fbetaT", "F_r": "F_rT"}


def iso1328_round(value_um: float) -> float:
    """Round a tolerance (um) by ISO 1328-1:2013, 5.2.3: > 10 um to 1 um, 5..10 um to 0.5 um, < 5 um to 0.1 um.

    Halves round away from zero (the usual engineering rule; the standard gives no other).

    Parameters
    ----------
    value_um : float
        Unrounded tolerance, um (>= 0).

    Returns
    -------
    float
        The rounded tolerance, um.
    """
    def half_up(x: float) -> float:
        return math.floor(x + 0.5)
    v = float(value_um)
    if v > 10.0:
        return float(half_up(v))
    if v >= 5.0:
        return half_up(2.0 * v) / 2.0
    return half_up(10.0 * v) / 10.0


@dataclass(frozen=True)
class Iso1328Tolerances:
    """The flank tolerances of one gear (um, rounded by 5.2.3) and the data they were computed from."""
    grade: int
    d: float          # reference diameter, mm
    m_n: float        # normal module, mm
    b: float          # face width, mm
    f_pT: float
    F_pT: float
    f_HalphaT: float
    f_falphaT: float
    F_alphaT: float
    f_HbetaT: float
    f_fbetaT: float
    F_betaT: float
    F_rT: float

    def as_dict(self) -> dict:
        """All fields as a plain dict (for JSON and netCDF attributes)."""
        return asdict(self)


def iso1328_tolerances(grade: int, teeth: int, m_n: float, b: float, helix_deg: float = 0.0,
                       field: str = "monte_carlo.grade") -> Iso1328Tolerances:
    """Flank tolerances of ISO 1328-1:2013 flank tolerance class ``grade`` for one gear.

    Parameters
    ----------
    grade : int
        Flank tolerance class A, 1 (finest) to 11.
    teeth : int
        Number of teeth z.
    m_n : float
        Normal module, mm.
    b : float
        Face width, mm.
    helix_deg : float
        Helix angle, deg (d = z m_n / cos beta).
    field : str
        The study field named in a :class:`~ltca.errors.CaseError` when the gear is outside the scope.

    Returns
    -------
    Iso1328Tolerances
        Formulae (5)-(12) and F_rT = 0.9 F_pT, each rounded by 5.2.3 (the totals from unrounded terms).

    Raises
    ------
    CaseError
        Class or gear outside the scope of clause 1 (the formulae must not be extrapolated).
    """
    if isinstance(grade, bool) or not isinstance(grade, int) or not 1 <= grade <= 11:
        raise CaseError(field, grade, "an ISO 1328-1:2013 flank tolerance class, an integer in [1, 11]")
    d = teeth * m_n / math.cos(math.radians(helix_deg))
    for name, v, lo, hi in (("teeth", teeth, 5, 1000), ("reference diameter d [mm]", d, 5, 15000),
                            ("normal module [mm]", m_n, 0.5, 70), ("face width [mm]", b, 4, 1200),
                            ("|helix angle| [deg]", abs(helix_deg), 0, 45)):
        if not lo <= v <= hi:
            raise CaseError(field, grade, f"a gear inside the scope of ISO 1328-1:2013 ({name} = {v:g} is outside "
                                          f"[{lo}, {hi}]; the standard's formulae must not be extrapolated)")
    step = math.sqrt(2.0) ** (grade - 5)
    fpt = (0.001 * d + 0.4 * m_n + 5.0) * step
    Fp = (0.002 * d + 0.55 * math.sqrt(d) + 0.7 * m_n + 12.0) * step
    fHa = (0.4 * m_n + 0.001 * d + 4.0) * step
    ffa = (0.55 * m_n + 5.0) * step
    fHb = (0.05 * math.sqrt(d) + 0.35 * math.sqrt(b) + 4.0) * step
    ffb = (0.07 * math.sqrt(d) + 0.45 * math.sqrt(b) + 4.0) * step
    r = iso1328_round
    return Iso1328Tolerances(grade, d, m_n, b, r(fpt), r(Fp), r(fHa), r(ffa), r(math.hypot(fHa, ffa)),
                             r(fHb), r(ffb), r(math.hypot(fHb, ffb)), r(0.9 * Fp))
