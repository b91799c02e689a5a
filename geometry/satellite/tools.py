"""The eccentric planetary satellite of Kapitonov et al. 2014 and the three tools that cut it (inputs only).

Kapitonov, Pashkevich, Nepsha, Khatetovsky (Vestnik of the Belarusian-Russian University 2014
No. 4(45)): satellite z = 50, m = 3 mm, alpha = 20 deg, profile shift x = -0.5 (1.5 mm radial), steel 40Kh,
teeth thinned so that (Eq. 3)

    s = pi m / 2 + 2 x m tan(alpha) - k m,     k = 0.6,

s the transverse tooth thickness on the reference circle. The tools: (a) a standard hob in three passes,
(b) a disk module cutter by form copying plunged to a shift coefficient -1.3, (c) a special hob whose rack
teeth are thickened (Eq. 4). All records are frozen and validate on construction (``ValueError`` naming the
field, its value and the allowed range, via :func:`ltca.geometry.gear_blank._check`). Units mm, rad; the
coefficients ``*_coef`` are per module.

Eq. 4 of the seed (``s_rack = pi m/2 + 2 x m tan(alpha) + k m``) is checked in :func:`eq4_rack_thickness`:
taken literally it does not cut Eq. 3; the special hob here has the rack that does (see there).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..gear_blank import GearBlank, RackCutter, _check

__all__ = ["SatelliteDesign", "HobThreePass", "DiskCutter", "SpecialHob", "Eq4Check", "eq4_rack_thickness"]

DEG = np.pi / 180.0


@dataclass(frozen=True)
class SatelliteDesign:
    """The satellite: spur, external, cut by a rack-type tool from the basic rack below.

    Parameters
    ----------
    z : int              teeth, integer in [12, 400] (seed: 50).
    m : float            module, mm, > 0 (seed: 3).
    alpha : float        pressure angle, rad, in (0, pi/4] (seed: 20 deg).
    x : float            profile shift coefficient, [-2, 2] (seed: -0.5).
    thinning : float     Eq. 3 thinning coefficient k (tooth thinner by k m), [0, 1) (seed: 0.6).
    rack_addendum_coef, rack_dedendum_coef, rack_tip_radius_coef : basic rack per module, ISO 53 profile A
                         by default (1.25, 1.0, 0.38); addendum in (0.5, 2], dedendum in [1, 2], tip radius
                         in [0, 0.5].
    d_tip : float | None tip diameter, mm; None -> d + 2 m (1 + x) (seed: 153 mm).
    """

    z: int = 50
    m: float = 3.0
    alpha: float = 20 * DEG
    x: float = -0.5
    thinning: float = 0.6
    rack_addendum_coef: float = 1.25
    rack_dedendum_coef: float = 1.0
    rack_tip_radius_coef: float = 0.38
    d_tip: float | None = None

    def __post_init__(self):
        _check("SatelliteDesign.z", self.z, isinstance(self.z, (int, np.integer)) and 12 <= self.z <= 400,
               "an integer in [12, 400]")
        _check("SatelliteDesign.m", self.m, np.isfinite(self.m) and self.m > 0, "> 0 mm")
        _check("SatelliteDesign.alpha", self.alpha, 0 < self.alpha <= np.pi / 4, "(0, pi/4] rad")
        _check("SatelliteDesign.x", self.x, np.isfinite(self.x) and abs(self.x) <= 2, "[-2, 2]")
        _check("SatelliteDesign.thinning", self.thinning, np.isfinite(self.thinning) and 0 <= self.thinning < 1,
               "[0, 1) (k in s = ... - k m)")
        _check("SatelliteDesign.rack_addendum_coef", self.rack_addendum_coef,
               0.5 < self.rack_addendum_coef <= 2, "(0.5, 2]")
        _check("SatelliteDesign.rack_dedendum_coef", self.rack_dedendum_coef,
               1 <= self.rack_dedendum_coef <= 2, "[1, 2]")
        _check("SatelliteDesign.rack_tip_radius_coef", self.rack_tip_radius_coef,
               0 <= self.rack_tip_radius_coef <= 0.5, "[0, 0.5]")
        _check("SatelliteDesign.d_tip", self.d_tip, self.d_tip is None or (np.isfinite(self.d_tip) and
               self.d - 2 * self.m < self.d_tip <= self.d + 2 * self.m * (1 + self.x) + 1e-9),
               f"None or in ({self.d - 2 * self.m}, {self.d + 2 * self.m * (1 + self.x)}] mm")

    @property
    def d(self) -> float:
        """Reference diameter z m, mm."""
        return self.z * self.m

    @property
    def r_tip(self) -> float:
        return 0.5 * (self.d_tip if self.d_tip is not None else self.d + 2 * self.m * (1 + self.x))

    @property
    def eq3_thickness(self) -> float:
        """Kapitonov et al. Eq. 3: s = pi m/2 + 2 x m tan(alpha) - k m, mm."""
        return np.pi * self.m / 2 + 2 * self.x * self.m * np.tan(self.alpha) - self.thinning * self.m

    def rack(self) -> RackCutter:
        """The standard basic rack (hob) in mm."""
        m = self.m
        return RackCutter(self.alpha, self.rack_addendum_coef * m, self.rack_dedendum_coef * m,
                          self.rack_tip_radius_coef * m)

    def blank(self, thinning: float | None = None, x: float | None = None) -> GearBlank:
        """Gear blank at shift ``x`` (default the design's) thinned by ``thinning`` m (default none), mm."""
        return GearBlank(self.z, self.m, self.alpha, 0.0, self.x if x is None else x, d_tip=2 * self.r_tip,
                         thickness_allowance=(thinning or 0.0) * self.m)


@dataclass(frozen=True)
class HobThreePass:
    """Method (a): standard hob at the design shift, then two passes shifted along the hob axis.

    Parameters
    ----------
    shift : float | None   tangential offset of passes 2 and 3 along the rack pitch line, mm (+ and -);
                           None -> k m / 2, which makes the final thickness Eq. 3. In [0, 2] mm; the
                           forming checks it against the tooth (tip must not vanish).
    lead_angle : float     hob lead angle gamma, rad, in [0, 0.2]; only to report the axial hob shift
                           ``shift / cos(gamma)`` (an axial shift of one axial pitch pi m / cos(gamma)
                           moves the generating rack by one pitch pi m).
    """

    shift: float | None = None
    lead_angle: float = 0.0

    def __post_init__(self):
        _check("HobThreePass.shift", self.shift,
               self.shift is None or (np.isfinite(self.shift) and 0 <= self.shift <= 2), "None or [0, 2] mm")
        _check("HobThreePass.lead_angle", self.lead_angle, 0 <= self.lead_angle <= 0.2, "[0, 0.2] rad")

    def tangential_shift(self, design: "SatelliteDesign") -> float:
        """Offset of passes 2 and 3 along the rack pitch line, mm (k m / 2 unless given)."""
        return 0.5 * design.thinning * design.m if self.shift is None else self.shift

    def axial_shift(self, design: "SatelliteDesign") -> float:
        """The same offset as a shift of the hob along its axis, mm: ``shift / cos(lead_angle)``."""
        return self.tangential_shift(design) / np.cos(self.lead_angle)


@dataclass(frozen=True)
class DiskCutter:
    """Method (b): disk module cutter, form copying, one tooth space per plunge.

    The cutter's axial profile is the tooth SPACE of a ``z_profile``-tooth gear with no profile shift cut
    by the design's basic rack (fillet and root circle included), its involutes carried up to where that
    gear's tooth would be pointed (the cutter is deep enough never to touch the blank with its body).
    Plunge: the profile is translated along the space's centre line so that its deepest point, which
    cuts the root of the x = 0 gear at ``r - ha``, sits at ``r + x_plunge m - ha`` from the blank axis,
    i.e. ``x_plunge`` is a profile shift coefficient of the tool as for a rack (seed: -1.3).

    Parameters
    ----------
    x_plunge : float          tool shift coefficient, [-2.5, 0.5] (seed: -1.3).
    n_teeth : int             cutting teeth on the cutter's periphery, integer in [1, 100]; no effect on the
                              copied form (a disk cutter with no teeth cuts nothing).
    z_profile : int | None    teeth of the gear the profile was made for, integer in [12, 400]; None -> the
                              satellite's z (a standard 8-cutter set would use the smallest z of its range).
    """

    x_plunge: float = -1.3
    n_teeth: int = 14
    z_profile: int | None = None

    def __post_init__(self):
        _check("DiskCutter.x_plunge", self.x_plunge, np.isfinite(self.x_plunge) and -2.5 <= self.x_plunge <= 0.5,
               "[-2.5, 0.5]")
        _check("DiskCutter.n_teeth", self.n_teeth,
               isinstance(self.n_teeth, (int, np.integer)) and 1 <= self.n_teeth <= 100, "an integer in [1, 100]")
        _check("DiskCutter.z_profile", self.z_profile, self.z_profile is None or (
            isinstance(self.z_profile, (int, np.integer)) and 12 <= self.z_profile <= 400),
            "None or an integer in [12, 400]")


@dataclass(frozen=True)
class SpecialHob:
    """Method (c): special hob with thickened rack teeth, one pass at the design shift.

    Parameters
    ----------
    thickening : float | None   k: the rack tooth on its datum line is ``pi m/2 + k m`` thick, so the cut
                                tooth is Eq. 3 (ISO 21771 eq. 52 with the allowance k m); None -> the
                                design's k. In [0, 1).
    """

    thickening: float | None = None

    def __post_init__(self):
        _check("SpecialHob.thickening", self.thickening, self.thickening is None or (
            np.isfinite(self.thickening) and 0 <= self.thickening < 1), "None or [0, 1)")


@dataclass(frozen=True)
class Eq4Check:
    """Rack tooth thickness of the special hob, mm (see :func:`eq4_rack_thickness`)."""

    eq4_literal: float
    datum: float
    rolling_line: float
    cut_if_literal_on_datum: float
    cut_if_literal_on_rolling_line: float
    eq3: float


def eq4_rack_thickness(design: SatelliteDesign) -> Eq4Check:
    """Compare Kapitonov et al. Eq. 4 with the rack that actually cuts Eq. 3.

    A rack at shift x rolls on the reference circle with its line at ``-x m`` from the datum (towards its
    own root when x < 0), where its tooth is ``s_datum - 2 x m tan(alpha)`` thick; the gear tooth is the
    rack gap there: ``s = pi m - s_datum + 2 x m tan(alpha)`` (ISO 21771 eq. 52). Eq. 3 therefore needs
    ``s_datum = pi m/2 + k m`` and ``s_rolling = pi m/2 - 2 x m tan(alpha) + k m = pi m - s_Eq3``.
    Eq. 4 as printed, ``pi m/2 + 2 x m tan(alpha) + k m``, equals neither (it is the rolling-line value
    with x = +0.5, the magnitude of the 1.5 mm feed); the gear teeth it would cut are returned too.
    """
    m, x, k, ta = design.m, design.x, design.thinning, np.tan(design.alpha)
    lit = np.pi * m / 2 + 2 * x * m * ta + k * m
    datum = np.pi * m / 2 + k * m
    return Eq4Check(eq4_literal=lit, datum=datum, rolling_line=datum - 2 * x * m * ta,
                    cut_if_literal_on_datum=np.pi * m - lit + 2 * x * m * ta,
                    cut_if_literal_on_rolling_line=np.pi * m - lit, eq3=design.eq3_thickness)
