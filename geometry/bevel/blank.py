"""Blank design of a face-milled spiral bevel gear pair from its basic data.

Formulas follow the Gleason spiral bevel gear system (Gleason Works, *Spiral Bevel Gear System*, 1971;
reproduced in Dudley, *Handbook of Practical Gear Design*, 1984, sec. 3.3, and in ANSI/AGMA 2005-D03,
Annex A): outer transverse module ``m``, working depth ``1.700 m``, whole depth ``1.888 m``, gear addendum
``0.460 m + 0.390 m / m90**2``, equivalent 90-degree ratio ``m90 = sqrt(z2/z1 cos(g1)/cos(g2))``, dedendum
angles either of the standard (apex-converging) taper or zero (uniform depth), face angles for constant
clearance (pinion face angle = pinion pitch angle + gear dedendum angle, and vice versa).

Subscript 1 is the pinion, 2 the gear.  Units: mm, rad.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

__all__ = ["BevelBasicData", "MemberBlank", "BevelBlank", "design_blank", "cone_apexes", "with_cones"]


def _check(name: str, value: float, lo: float, hi: float, lo_open: bool = False) -> None:
    ok = (value > lo if lo_open else value >= lo) and value <= hi
    if not (np.isfinite(value) and ok):
        br = "(" if lo_open else "["
        raise ValueError(f"{name} = {value!r} is outside the allowed range {br}{lo}, {hi}]")


@dataclass(frozen=True)
class BevelBasicData:
    """Basic data of a spiral bevel pair (the designer's input).

    Parameters
    ----------
    z1, z2 : int
        Tooth numbers of pinion and gear, 5 <= z1 <= z2.
    module : float
        Outer transverse module m = d2/z2, mm.
    face_width : float
        Face width along the pitch-cone generatrix, mm; 0 < b < outer cone distance.
    spiral_angle : float
        Mean spiral angle beta_m, rad, in [0, 60 deg].
    pressure_angle : float
        Normal pressure angle alpha_n, rad, in [10, 30 deg] (blade angle of the gear cutter).
    shaft_angle : float
        Shaft angle Sigma, rad, in (0, 180 deg).
    hand : str
        Hand of spiral of the **gear**, ``"left"`` or ``"right"`` (the pinion has the other hand).
    cutter_radius : float
        Nominal (mean) head-cutter radius r_c, mm; must exceed A_m sin(beta_m) / 2.
    taper : str
        ``"standard"`` (root and face cones converge at the pitch apex up to the constant-clearance face
        angle) or ``"uniform"`` (uniform depth: root and face cones parallel to the pitch cone).
    thickness_factor : float
        Gleason thickness factor K moving tooth thickness from gear to pinion (dimensionless, |K| <= 0.2).
    backlash : float
        Normal backlash at the mean point, taken from the gear thickness, mm.
    """

    z1: int = 10
    z2: int = 41
    module: float = 6.0
    face_width: float = 40.0
    spiral_angle: float = np.deg2rad(35.0)
    pressure_angle: float = np.deg2rad(20.0)
    shaft_angle: float = np.deg2rad(90.0)
    hand: str = "right"
    cutter_radius: float = 76.2
    taper: str = "standard"
    thickness_factor: float = 0.0
    backlash: float = 0.0

    def __post_init__(self) -> None:
        _check("z1", self.z1, 5, 200)
        _check("z2", self.z2, self.z1, 500)
        if int(self.z1) != self.z1 or int(self.z2) != self.z2:
            raise ValueError(f"tooth numbers must be integers, got z1={self.z1!r}, z2={self.z2!r}")
        _check("module", self.module, 0.0, 100.0, lo_open=True)
        _check("spiral_angle", self.spiral_angle, 0.0, np.deg2rad(60.0))
        _check("pressure_angle", self.pressure_angle, np.deg2rad(10.0), np.deg2rad(30.0))
        _check("shaft_angle", self.shaft_angle, 1e-3, np.pi - 1e-3)
        _check("thickness_factor", self.thickness_factor, -0.2, 0.2)
        _check("backlash", self.backlash, 0.0, 0.2 * self.module)
        if self.hand not in ("left", "right"):
            raise ValueError(f"hand = {self.hand!r}: allowed 'left' or 'right'")
        if self.taper not in ("standard", "uniform"):
            raise ValueError(f"taper = {self.taper!r}: allowed 'standard' or 'uniform'")


@dataclass(frozen=True)
class MemberBlank:
    """Blank of one member. Lengths in mm, angles in rad.

    Attributes
    ----------
    z : teeth;  pitch_angle, face_angle, root_angle : cone angles from the axis;
    dedendum_angle, addendum_angle : root/face cone against the pitch cone;
    pitch_diameter, outside_diameter : outer (heel) diameters;
    addendum, dedendum : outer (heel) values;  mean_addendum, mean_dedendum : at the mean cone distance;
    crown_to_apex : axial distance from the pitch apex to the crown (heel edge of the face cone);
    mean_pitch_radius : pitch-cone radius at the mean cone distance;
    mean_normal_thickness : design normal circular thickness on the pitch cone at the mean point;
    hand : hand of spiral.
    """

    z: int
    pitch_angle: float
    face_angle: float
    root_angle: float
    dedendum_angle: float
    addendum_angle: float
    pitch_diameter: float
    outside_diameter: float
    addendum: float
    dedendum: float
    mean_addendum: float
    mean_dedendum: float
    crown_to_apex: float
    mean_pitch_radius: float
    mean_normal_thickness: float
    hand: str


@dataclass(frozen=True)
class BevelBlank:
    """Blank design of the pair (result of :func:`design_blank`)."""

    data: BevelBasicData
    pinion: MemberBlank
    gear: MemberBlank
    outer_cone_distance: float
    mean_cone_distance: float
    inner_cone_distance: float
    face_width: float
    working_depth: float
    whole_depth: float
    clearance: float
    mean_normal_module: float
    mean_normal_pitch: float
    m90: float

    def member(self, which: str) -> MemberBlank:
        """``"pinion"`` or ``"gear"``."""
        if which not in ("pinion", "gear"):
            raise ValueError(f"which = {which!r}: allowed 'pinion' or 'gear'")
        return self.pinion if which == "pinion" else self.gear

    def root_point(self, which: str, end: str) -> np.ndarray:
        """(Z, rho) of ``which``'s root cone at its ``"toe"`` or ``"heel"``, member body frame (pitch apex at the
        origin, z along the axis), mm."""
        if end not in ("toe", "heel"):
            raise ValueError(f"end = {end!r}: allowed 'toe' or 'heel'")
        mb, A0 = self.member(which), self.outer_cone_distance
        L = self.inner_cone_distance if end == "toe" else A0
        g = mb.pitch_angle
        Rn = self.cones(which, L)[0]
        return np.array([L * np.cos(g) - Rn * np.sin(g), L * np.sin(g) + Rn * np.cos(g)])

    def cones(self, which: str, L):
        """Root and face cones of ``which`` at cone distance ``L`` (mm, scalar or array): their offsets normal to
        the pitch generatrix in the axial section, mm (root < 0 < face), with the heel (``L`` = A0) at the
        dedendum and addendum and the cones' angles against the pitch cone (Gleason duplex taper)."""
        mb, A0 = self.member(which), self.outer_cone_distance
        root = -(mb.dedendum - (A0 - L) * np.tan(mb.dedendum_angle))
        return root, mb.addendum - (A0 - L) * np.tan(mb.addendum_angle)


def design_blank(data: BevelBasicData) -> BevelBlank:
    """Pitch, face and root cones, depths and diameters of a Gleason spiral bevel pair.

    Parameters
    ----------
    data : BevelBasicData

    Returns
    -------
    BevelBlank

    Notes
    -----
    * Pitch angles: tan(g1) = sin(S) / (z2/z1 + cos(S)), g2 = S - g1 (rolling pitch cones).
    * Outer cone distance A0 = d2 / (2 sin g2), mean Am = A0 - b/2.
    * Depths (Gleason 1971): hk = 1.700 m, ht = 1.888 m, c = ht - hk,
      a2 = 0.460 m + 0.390 m / m90**2 with m90 = sqrt(z2/z1 cos g1 / cos g2), a1 = hk - a2, b_i = ht - a_i.
    * Standard taper: dedendum angle d_i = atan(b_i / A0), root angle g_i - d_i, face angle g1 + d2 and
      g2 + d1 (constant clearance); uniform depth: all zero.
    * Outside diameter do = d + 2 a cos g; crown to apex x0 = A0 cos g - a sin g.
    * Mean normal circular thickness on the pitch cone (balanced by the mean addendum difference as a
      profile shift, ANSI/AGMA 2005-D03 style): s2 = p_mn/2 - (am1 - am2) tan(alpha_n) - K m_mn - j_n,
      s1 = p_mn - s2 - j_n with p_mn = pi m_mn and m_mn = m (Am/A0) cos(beta_m).
    """
    z1, z2, m, b = data.z1, data.z2, data.module, data.face_width
    S = data.shaft_angle
    g1 = np.arctan2(np.sin(S), z2 / z1 + np.cos(S))
    g2 = S - g1
    d1, d2 = z1 * m, z2 * m
    A0 = d2 / (2.0 * np.sin(g2))
    _check("face_width", b, 0.0, 0.5 * A0, lo_open=True)
    Am = A0 - 0.5 * b
    Ai = A0 - b
    if data.cutter_radius <= 0.5 * Am * np.sin(data.spiral_angle) or data.cutter_radius > 4.0 * A0:
        raise ValueError(f"cutter_radius = {data.cutter_radius!r} is outside the allowed range "
                         f"({0.5 * Am * np.sin(data.spiral_angle):.3f}, {4.0 * A0:.3f}] mm")
    hk, ht = 1.700 * m, 1.888 * m
    c = ht - hk
    m90 = np.sqrt(z2 / z1 * np.cos(g1) / np.cos(g2)) if g2 < 0.5 * np.pi else np.inf
    a2 = 0.460 * m + 0.390 * m / m90 ** 2
    a1 = hk - a2
    b1, b2 = ht - a1, ht - a2
    if data.taper == "standard":
        dd1, dd2 = np.arctan(b1 / A0), np.arctan(b2 / A0)
    else:
        dd1 = dd2 = 0.0
    da1, da2 = dd2, dd1                                   # constant clearance
    # mean addenda/dedenda: face and root cones measured back from the heel
    am1, am2 = a1 - 0.5 * b * np.tan(da1), a2 - 0.5 * b * np.tan(da2)
    bm1, bm2 = b1 - 0.5 * b * np.tan(dd1), b2 - 0.5 * b * np.tan(dd2)
    m_mn = m * Am / A0 * np.cos(data.spiral_angle)
    p_mn = np.pi * m_mn
    s2 = 0.5 * p_mn - (am1 - am2) * np.tan(data.pressure_angle) - data.thickness_factor * m_mn \
        - data.backlash
    s1 = p_mn - s2 - data.backlash
    other = "left" if data.hand == "right" else "right"

    def member(z, g, a, bd, am, bm, dd, da, d, s, hand):
        return MemberBlank(z=int(z), pitch_angle=float(g), face_angle=float(g + da),
                           root_angle=float(g - dd), dedendum_angle=float(dd), addendum_angle=float(da),
                           pitch_diameter=float(d), outside_diameter=float(d + 2 * a * np.cos(g)),
                           addendum=float(a), dedendum=float(bd), mean_addendum=float(am),
                           mean_dedendum=float(bm), crown_to_apex=float(A0 * np.cos(g) - a * np.sin(g)),
                           mean_pitch_radius=float(Am * np.sin(g)), mean_normal_thickness=float(s),
                           hand=hand)

    return BevelBlank(data=data,
                      pinion=member(z1, g1, a1, b1, am1, bm1, dd1, da1, d1, s1, other),
                      gear=member(z2, g2, a2, b2, am2, bm2, dd2, da2, d2, s2, data.hand),
                      outer_cone_distance=float(A0), mean_cone_distance=float(Am),
                      inner_cone_distance=float(Ai), face_width=float(b), working_depth=float(hk),
                      whole_depth=float(ht), clearance=float(c), mean_normal_module=float(m_mn),
                      mean_normal_pitch=float(p_mn), m90=float(m90))


def cone_apexes(blank: BevelBlank, which: str) -> tuple[float, float]:
    """Face and root cone apexes of ``which`` beyond the crossing point along its axis (ISO 23509 t_zF, t_zR), mm:
    ``-Z`` of the apex of the cone through the heel's face (root) point, in the member frame whose origin is the
    pitch apex at the crossing point."""
    mb, A0 = blank.member(which), blank.outer_cone_distance
    g = mb.pitch_angle
    out = []
    for off, ang in ((mb.addendum, mb.face_angle), (-mb.dedendum, mb.root_angle)):
        Z, rho = A0 * np.cos(g) - off * np.sin(g), A0 * np.sin(g) + off * np.cos(g)
        out.append(float(-(Z - rho * np.cos(ang) / np.sin(ang))))
    return out[0], out[1]


def with_cones(blank: BevelBlank, which: str, face_angle: float, root_angle: float, face_apex: float,
               root_apex: float) -> BevelBlank:
    """The blank with ``which``'s face and root cones given instead of designed (pitch cone, face width, thickness
    kept), e.g. a blank read from another program.

    Parameters
    ----------
    blank : BevelBlank
    which : ``"pinion"`` or ``"gear"``
    face_angle, root_angle : float
        Cone angles from the axis, rad, ``0 < root_angle <= pitch angle <= face_angle < pi/2``.
    face_apex, root_apex : float
        Apexes beyond the crossing point along the axis, mm (:func:`cone_apexes`).

    Returns
    -------
    BevelBlank
        Heel addendum ``a = (A0 sin(gf - g) + t_zF sin gf) / cos(gf - g)`` and dedendum
        ``b = (A0 sin(g - gr) - t_zR sin gr) / cos(g - gr)`` (the heel's face and root points, normal to the pitch
        generatrix at the outer cone distance A0, on the given cones); mean values half a face width in; working
        depth a1 + a2, whole depth the larger a + b.
    """
    mb, A0, bw = blank.member(which), blank.outer_cone_distance, blank.face_width
    g = mb.pitch_angle
    _check(f"{which} root_angle", root_angle, 0.0, g, lo_open=True)
    _check(f"{which} face_angle", face_angle, g, 0.5 * np.pi - 1e-9)
    a = (A0 * np.sin(face_angle - g) + face_apex * np.sin(face_angle)) / np.cos(face_angle - g)
    b = (A0 * np.sin(g - root_angle) - root_apex * np.sin(root_angle)) / np.cos(g - root_angle)
    _check(f"{which} face_apex (heel addendum {a:.4g} mm)", a, 0.0, 0.5 * A0, lo_open=True)
    _check(f"{which} root_apex (heel dedendum {b:.4g} mm)", b, 0.0, 0.5 * A0, lo_open=True)
    da, dd = face_angle - g, g - root_angle
    new = replace(mb, face_angle=float(face_angle), root_angle=float(root_angle), addendum_angle=float(da),
                  dedendum_angle=float(dd), addendum=float(a), dedendum=float(b),
                  mean_addendum=float(a - 0.5 * bw * np.tan(da)), mean_dedendum=float(b - 0.5 * bw * np.tan(dd)),
                  outside_diameter=float(mb.pitch_diameter + 2 * a * np.cos(g)),
                  crown_to_apex=float(A0 * np.cos(g) - a * np.sin(g)))
    members = {"pinion": blank.pinion, "gear": blank.gear, which: new}
    p, q = members["pinion"], members["gear"]
    hk = p.addendum + q.addendum
    ht = max(p.addendum + p.dedendum, q.addendum + q.dedendum)
    return replace(blank, pinion=p, gear=q, working_depth=float(hk), whole_depth=float(ht), clearance=float(ht - hk))
