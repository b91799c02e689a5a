"""The central wheel (internal teeth, cut by a pinion-type shaper) that the satellite runs in at e = m.

Choice of z2 and x2. An internal involute pair at centre distance ``a`` has the working pressure angle
(ISO 21771; Litvin & Fuentes 2004 ch. 13; x2 counted positive when it widens the internal SPACE, i.e. moves
the internal teeth outwards; a satellite thinned by k m acts like a wheel shift of k / (2 tan(alpha)))

    cos(alpha_w) = m (z2 - z1) cos(alpha) / (2 a),
    inv(alpha_w) = inv(alpha) + 2 tan(alpha) (x2 + k / (2 tan(alpha)) - x1) / (z2 - z1)   (zero backlash).

With ``a = e = m`` the first equation fixes alpha_w from the tooth difference alone:

* ``z2 - z1 = 2``: alpha_w = alpha = 20 deg, zero backlash for x2 = x1 - k/(2 tan alpha) (x2 = -0.5 for the
  unthinned satellite). It does not work: the satellite teeth drift against the wheel spaces by
  ``psi/pi - (e z2 / (pi z1)) sin(psi)`` pitches at the angle psi from the mesh, a quarter pitch near
  100 deg where the teeth are still 2.5 mm deep in engagement; the pair jams for every thinning that leaves
  a tooth (:mod:`ltca.geometry.satellite.interference`: free play -3.6 mm at k = 0, -1.9 mm at k = 0.6).
* ``z2 - z1 = 1`` (the eccentric reducer's case): cos(alpha_w) = cos(alpha)/2, alpha_w = 61.98 deg, and zero
  backlash for ``x2 + k/(2 tan alpha) = x1 + 1.0746 = 0.5746``: x2 = 0.5746 for the unthinned satellite,
  -0.2497 for the paper's k = 0.6. The mesh works (contact at about +-40 deg from the line of centres,
  several pairs within microns of contact: the paper's multi-pair mesh, in either direction).

Kapitonov et al. give x1 and k but not x2. Its zero-backlash value for k = 0.6 (x2 = -0.25) puts the wheel's tip
circle 0.75 mm inside the satellite's tips opposite the mesh, where a tooth difference of one sets tooth
against tooth: it jams. Chosen here: **z2 = 51, x2 = 0** (a standard wheel from a standard shaper, z0 = 25,
x0 = 0, ha0 = 1.25 m, rho0 = 0.25 m: root radius r2 + 1.25 m = 80.25 mm), its tip circle bored to leave
``far_tip_clearance`` (0.5 mm) to the satellite's tip circle opposite the mesh (d_a2 = 148 instead of the
standard 147, where the tips would touch). Then the unthinned satellite does not fit (backlash -2.51 mm on
the working circle), the thinning that fits is k = 2 tan(alpha) (0.5746 - x2) = 0.418, and the paper's
k = 0.6 leaves 1.09 mm of circumferential backlash (0.51 mm along the line of action).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..gear_blank import GearBlank, _check
from ..profile import ToothProfile
from ..shaper import ShaperCutter, generate_by_shaper
from ..transverse import involute
from .tools import SatelliteDesign

__all__ = ["CentralWheelDesign", "WheelChoice", "wheel_shift", "wheel_options", "generate_central_wheel"]


@dataclass(frozen=True)
class CentralWheelDesign:
    """Central wheel of the eccentric reducer (its module and pressure angle are the satellite's).

    Parameters
    ----------
    tooth_difference : int     z2 - z1, integer in [1, 8]; 0 or less cannot assemble (default 1, module doc).
    eccentricity : float|None  centre distance e, mm, > 0; None -> one module (seed).
    x2 : float                 wheel profile shift, positive widening the space, [-1, 1] (default 0).
    shaper_teeth : int         z0 of the shaper, integer in [8, z2 - 5] (checked on generation).
    shaper_shift : float       x0, [-1, 1].
    shaper_addendum_coef : float   ha0 / m, (0.5, 2].
    shaper_tip_radius_coef : float rho0 / m, [0, 0.5].
    far_tip_clearance : float  mm, >= 0: radial gap between the wheel's tip circle and the satellite's tip
                               circle opposite the mesh (``r_a2 >= r_a1 - e + far_tip_clearance``).
    d_tip : float | None       internal tip diameter, mm; None -> the larger of the standard
                               d2 - 2 m (1 - x2) and the far-side clearance rule.
    """

    tooth_difference: int = 1
    eccentricity: float | None = None
    x2: float = 0.0
    shaper_teeth: int = 25
    shaper_shift: float = 0.0
    shaper_addendum_coef: float = 1.25
    shaper_tip_radius_coef: float = 0.25
    far_tip_clearance: float = 0.5
    d_tip: float | None = None

    def __post_init__(self):
        _check("CentralWheelDesign.tooth_difference", self.tooth_difference,
               isinstance(self.tooth_difference, (int, np.integer)) and 1 <= self.tooth_difference <= 8,
               "an integer in [1, 8] (z2 - z1 < 1: the satellite cannot be assembled inside the wheel)")
        _check("CentralWheelDesign.eccentricity", self.eccentricity,
               self.eccentricity is None or (np.isfinite(self.eccentricity) and self.eccentricity > 0),
               "None or > 0 mm")
        _check("CentralWheelDesign.x2", self.x2, np.isfinite(self.x2) and abs(self.x2) <= 1, "[-1, 1]")
        _check("CentralWheelDesign.shaper_teeth", self.shaper_teeth,
               isinstance(self.shaper_teeth, (int, np.integer)) and self.shaper_teeth >= 8, "an integer >= 8")
        _check("CentralWheelDesign.shaper_shift", self.shaper_shift, abs(self.shaper_shift) <= 1, "[-1, 1]")
        _check("CentralWheelDesign.shaper_addendum_coef", self.shaper_addendum_coef,
               0.5 < self.shaper_addendum_coef <= 2, "(0.5, 2]")
        _check("CentralWheelDesign.shaper_tip_radius_coef", self.shaper_tip_radius_coef,
               0 <= self.shaper_tip_radius_coef <= 0.5, "[0, 0.5]")
        _check("CentralWheelDesign.far_tip_clearance", self.far_tip_clearance,
               np.isfinite(self.far_tip_clearance) and 0 <= self.far_tip_clearance <= 5, "[0, 5] mm")
        _check("CentralWheelDesign.d_tip", self.d_tip, self.d_tip is None or (
            np.isfinite(self.d_tip) and self.d_tip > 0), "None or > 0 mm")


@dataclass(frozen=True)
class WheelChoice:
    """Geometry of the internal pair for one tooth difference and wheel shift (mm, rad).

    z2; alpha_w; a; x2 (chosen, space-widening convention) and x_blank = -x2 (:class:`GearBlank`);
    x2_zero_backlash (unthinned satellite) and x2_zero_backlash_seed (satellite thinned by the design's k);
    thinning_fit: k that closes the backlash with the chosen x2 (< 0: backlash even unthinned);
    r_w1, r_w2 working pitch radii; r_tip2 (chosen), r_root2 (rack-equivalent r2 + m (ha + x2));
    far_tip_clearance: r_tip2 - (r_a1 - e); contact_ratio: involute path (satellite tip to wheel tip,
    fillets ignored) over the base pitch.
    """

    z2: int
    alpha_w: float
    a: float
    x2: float
    x_blank: float
    x2_zero_backlash: float
    x2_zero_backlash_seed: float
    thinning_fit: float
    r_w1: float
    r_w2: float
    r_tip2: float
    r_root2: float
    far_tip_clearance: float
    contact_ratio: float


def wheel_shift(sat: SatelliteDesign, tooth_difference: int, e: float | None = None, x2: float | None = None,
                far_tip_clearance: float = 0.5, d_tip: float | None = None) -> WheelChoice:
    """Pair geometry at ``a = e`` for ``z2 = z1 + tooth_difference`` (module doc); x2 None -> zero backlash."""
    _check("CentralWheelDesign.tooth_difference", tooth_difference,
           isinstance(tooth_difference, (int, np.integer)) and tooth_difference >= 1,
           "an integer >= 1 (z2 - z1 < 1: the satellite cannot be assembled inside the wheel)")
    m, al, z1 = sat.m, sat.alpha, sat.z
    e = m if e is None else e
    dz = int(tooth_difference)
    c = m * dz * np.cos(al) / (2 * e)
    if c > 1:
        raise ValueError(f"CentralWheelDesign.eccentricity = {e!r} mm: too small for tooth difference {dz} "
                         f"(allowed >= {m * dz * np.cos(al) / 2:.6f} mm, the base circles would cross)")
    aw = float(np.arccos(c))
    x2_zb = sat.x + (involute(aw) - involute(al)) * dz / (2 * np.tan(al))
    x2 = x2_zb if x2 is None else x2
    z2 = z1 + dz
    r2 = 0.5 * z2 * m
    rb1, rb2 = 0.5 * z1 * m * np.cos(al), r2 * np.cos(al)
    r_tip2 = max(r2 - m * (1 - x2), sat.r_tip - e + far_tip_clearance) if d_tip is None else 0.5 * d_tip
    L1_tip = np.sqrt(sat.r_tip ** 2 - rb1 ** 2)
    L2_tip = np.sqrt(max(r_tip2 ** 2 - rb2 ** 2, 0.0))
    path = L1_tip - (L2_tip - e * np.sin(aw))        # both measured on the satellite's roll length
    return WheelChoice(z2=z2, alpha_w=aw, a=e, x2=float(x2), x_blank=float(-x2) + 0.0, x2_zero_backlash=float(x2_zb),
                       x2_zero_backlash_seed=float(x2_zb - sat.thinning / (2 * np.tan(al))),
                       thinning_fit=float(2 * np.tan(al) * (x2_zb - x2)), r_w1=rb1 / np.cos(aw),
                       r_w2=rb2 / np.cos(aw), r_tip2=float(r_tip2),
                       r_root2=float(r2 + m * (sat.rack_addendum_coef + x2)),
                       far_tip_clearance=float(r_tip2 - (sat.r_tip - e)),
                       contact_ratio=float(path / (np.pi * m * np.cos(al))))


def wheel_options(sat: SatelliteDesign, e: float | None = None, differences=(1, 2)) -> dict:
    """Zero-backlash :func:`wheel_shift` (unthinned satellite) for each tooth difference, to compare."""
    return {dz: wheel_shift(sat, dz, e) for dz in differences}


def generate_central_wheel(sat: SatelliteDesign, wheel: CentralWheelDesign = CentralWheelDesign()):
    """Shaper-cut central wheel for ``sat``: returns ``(ToothProfile, WheelChoice)``.

    Raises ValueError when the satellite's tip circle does not clear the wheel's root circle at the
    deepest point (``r_a1 + e >= r_f2``: it cannot be assembled) or the shaper cannot cut the wheel.
    """
    ch = wheel_shift(sat, wheel.tooth_difference, wheel.eccentricity, wheel.x2, wheel.far_tip_clearance,
                     wheel.d_tip)
    m = sat.m
    d_tip = 2 * ch.r_tip2
    _check("CentralWheelDesign.shaper_teeth", wheel.shaper_teeth, wheel.shaper_teeth <= ch.z2 - 5,
           f"an integer in [8, {ch.z2 - 5}] (z2 - 5)")
    blank = GearBlank(ch.z2, m, sat.alpha, 0.0, ch.x_blank, d_tip=d_tip, internal=True)
    shaper = ShaperCutter(int(wheel.shaper_teeth), wheel.shaper_shift, wheel.shaper_addendum_coef * m,
                          wheel.shaper_tip_radius_coef * m)
    prof: ToothProfile = generate_by_shaper(blank, shaper)
    if sat.r_tip + ch.a >= prof.r_root:
        raise ValueError(f"CentralWheelDesign.tooth_difference = {wheel.tooth_difference}: the satellite tip "
                         f"circle ({sat.r_tip} mm) at e = {ch.a} mm reaches the wheel root ({prof.r_root:.4f} mm): "
                         f"it cannot be assembled")
    return prof, ch
