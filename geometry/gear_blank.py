"""Inputs of generation by rack or shaper: the basic rack (hob) and the gear blank.

Dimensions in mm, angles in rad. Both records validate their fields on construction and raise
``ValueError`` naming the field and its allowed range (:func:`_check`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["RackCutter", "GearBlank"]


def _check(name, value, ok, allowed):
    """Raise ``ValueError`` naming the field ``name``, its ``value`` and the ``allowed`` range unless ``ok``."""
    if not ok:
        raise ValueError(f"{name} = {value!r} is invalid: allowed {allowed}")


@dataclass(frozen=True)
class RackCutter:
    """Basic rack (hob) in the normal section, dimensions in mm (not per module).

    Parameters
    ----------
    alpha_n : float   normal pressure angle, rad, in (0, pi/4]; must equal the blank's.
    ha : float        cutter addendum (cuts the gear dedendum), mm, > 0 (e.g. 1.25 m).
    hf : float        cutter dedendum, mm, > 0 (e.g. 1.0 m); the gear tip must stay below it.
    rho : float       tip edge radius, mm, 0 <= rho, fitting in the tip (e.g. 0.38 m).
    protuberance : float   not supported: must be 0.
    """

    alpha_n: float
    ha: float
    hf: float
    rho: float
    protuberance: float = 0.0

    def __post_init__(self):
        _check("RackCutter.alpha_n", self.alpha_n, 0 < self.alpha_n <= np.pi / 4, "(0, pi/4] rad")
        _check("RackCutter.ha", self.ha, np.isfinite(self.ha) and self.ha > 0, "> 0 mm")
        _check("RackCutter.hf", self.hf, np.isfinite(self.hf) and self.hf > 0, "> 0 mm")
        _check("RackCutter.rho", self.rho, np.isfinite(self.rho) and 0 <= self.rho < self.ha,
               "0 <= rho < ha mm")
        _check("RackCutter.protuberance", self.protuberance, self.protuberance == 0.0,
               "0 only (protuberance racks are not supported)")


@dataclass(frozen=True)
class GearBlank:
    """Gear data. Internal gear: ``internal=True`` (ring with internal teeth, tip circle inside).

    Parameters
    ----------
    z : int
        Teeth, an integer in [3, 10000].
    m_n : float
        Normal module, mm, > 0.
    alpha_n : float
        Normal pressure angle, rad, in (0, pi/4].
    beta : float
        Helix angle at the reference circle, rad, ``|beta| < 1.2`` (sign = hand, + right).
    x : float
        Profile shift coefficient, [-3, 3]; positive thickens the tooth (internal: thickens the internal tooth,
        narrows the space).
    d_tip : float or None
        Tip diameter, mm; None -> external d + 2 m_n (1 + x), internal d - 2 m_n (1 + x).
    thickness_allowance : float
        Normal tooth thickness reduction (total, mm), ``|A| < m_n``; > 0 thins.
    internal : bool
        A ring with internal teeth.
    """

    z: int
    m_n: float
    alpha_n: float
    beta: float = 0.0
    x: float = 0.0
    d_tip: float | None = None
    thickness_allowance: float = 0.0
    internal: bool = False

    def __post_init__(self):
        _check("GearBlank.z", self.z, isinstance(self.z, (int, np.integer)) and 3 <= self.z <= 10000,
               "an integer in [3, 10000]")
        _check("GearBlank.m_n", self.m_n, np.isfinite(self.m_n) and self.m_n > 0, "> 0 mm")
        _check("GearBlank.alpha_n", self.alpha_n, 0 < self.alpha_n <= np.pi / 4, "(0, pi/4] rad")
        _check("GearBlank.beta", self.beta, np.isfinite(self.beta) and abs(self.beta) < 1.2,
               "|beta| < 1.2 rad")
        _check("GearBlank.x", self.x, np.isfinite(self.x) and abs(self.x) <= 3, "[-3, 3]")
        _check("GearBlank.d_tip", self.d_tip,
               self.d_tip is None or (np.isfinite(self.d_tip) and self.d_tip > 0), "None or > 0 mm")
        _check("GearBlank.thickness_allowance", self.thickness_allowance,
               np.isfinite(self.thickness_allowance) and abs(self.thickness_allowance) < self.m_n,
               "|A| < m_n mm")

    @property
    def alpha_t(self) -> float:
        return float(np.arctan(np.tan(self.alpha_n) / np.cos(self.beta)))

    @property
    def m_t(self) -> float:
        return self.m_n / np.cos(self.beta)

    @property
    def r_ref(self) -> float:
        return 0.5 * self.z * self.m_t

    @property
    def s_ref(self) -> float:
        """Transverse tooth thickness (internal: of the internal tooth) on the reference circle, mm.

        ISO 21771:2007 eq. (52): s_t = m_t (pi/2 + 2 x tan alpha_n) = m_t pi/2 + 2 x m_n tan alpha_t,
        less the allowance A_n / cos(beta).
        """
        return (self.m_t * np.pi / 2 + 2 * self.x * self.m_n * np.tan(self.alpha_t)
                - self.thickness_allowance / np.cos(self.beta))
