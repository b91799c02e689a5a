"""Litvin cradle model of a face-milling generator, and standard settings from the blank.

Frames (4x4 homogeneous transforms, xyz on the last axis; Litvin & Fuentes, *Gear Geometry and Applied
Theory*, 2nd ed. 2004, ch. 20-21, and Litvin NASA CR-4342, 1990, with our own sign choices):

* S_m, machine (fixed): z_m along the cradle axis, origin at the machine centre in the cutter tip plane.
* S_p, cradle: rotated by the cradle angle psi about z_m.
* S_c, cutter: origin at the cutter centre, at ``Sr (cos q, sin q, 0)`` in S_p; axes parallel to S_p
  (no tilt/swivel).  See :mod:`ltca.geometry.bevel.cutter` for the blade surface.
* S_w, work body frame (gear frame of :mod:`ltca.geometry.flank`: origin at the pitch apex, z along the axis
  towards the back): at roll phi = 0 its axes are z_w = k = (cos gm, 0, sin gm), y_w = y_m,
  x_w = y_w x z_w, with gm the machine root angle; its origin is
  ``O_w = Em y_m + XB z_m + XG k`` (blank offset, sliding base, machine centre to back).  The work body lies on
  the +z_m side of the tip plane (the blade tips generate its root).
* Roll: the work turns by ``phi(psi) = m_a (psi - C psi**2 - D psi**3)`` about +k when the cradle turns
  by psi about +z_m (Cao et al. 2008, Eq. 8).  Pure rolling of the pitch cone (angle g) on the generating crown
  gear needs ``m_a = cos(g - gm) / sin(g)`` (the relative angular velocity m_a k - z_m lies along the
  pitch generatrix), the Gleason ratio of roll cos(dedendum angle)/sin(pitch angle).

The universal machine (the settings sheet of a face-milling generator; Litvin & Fuentes 2004, sec. 20.3-20.5
and ch. 21 for the tilted head-cutter; Fan, *J. Mech. Des.* 129 (2007) 31-37 for the motions as polynomials of
the cradle roll) adds, each optional:

* Modified roll to 6th order: ``phi = m_a (psi - C psi^2 - D psi^3 - E psi^4 - F psi^5 - G psi^6)`` (a sheet
  gives 2C, 6D, 24E, 120F, 720G).
* Radial, vertical and helical motions and modified tilt and swivel: the radial setting ``Sr``, the blank
  offset ``Em``, the sliding base ``XB``, the tilt ``i`` and the swivel ``j`` are each
  ``x(psi) = x0 + sum_k a_k psi^k / k!`` (``a_k`` the k-th derivative at psi = 0, Gleason's factorial scaling),
  k = 1..6.
* Tilt ``i`` and swivel ``j``: the cutter axis is turned by ``i`` about an axis in the cradle plane that makes
  the angle ``q - j`` with x_p (the swivel measured from the radial direction of the cutter centre, back
  towards x_p): cutter frame -> cradle ``R_t = Rz(q - j) Rx(i) Rz(j - q)`` about the cutter centre.  The
  cutter is a surface of revolution, so the outer ``Rz(j - q)`` only shifts its angle theta.
* Formate (non-generated) member: the cutter is plunged without roll; the flank is the cutter surface
  itself in the work placed at psi = 0 (:attr:`MachineSettings.formate`).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .blank import BevelBlank
from .cutter import HeadCutter
from .surface_state import cross3

MOTIONS = ("radial_motion", "vertical_motion", "helical_motion", "tilt_motion", "swivel_motion")
"""Fields of :class:`MachineSettings` that hold the derivatives (orders 1..6) of a setting by the cradle roll."""
MAX_ORDER = 6

__all__ = ["MachineSettings", "MOTIONS", "FlankCut", "MemberCut", "rot_z", "translation", "cradle_to_machine",
           "cutter_to_cradle", "work_to_machine", "roll", "tilt_rotation", "gear_settings", "pinion_settings",
           "conjugate_pinion_settings", "mean_pitch_point"]


@dataclass(frozen=True)
class MachineSettings:
    """Basic machine settings of one flank cut.

    Parameters
    ----------
    radial_setting : float
        Sr, mm, > 0.
    cradle_angle : float
        q, rad.
    root_angle : float
        Machine root angle gamma_m, rad, in (0, pi/2].
    center_to_back : float
        XG, mm (shift of the work along its own axis).
    blank_offset : float
        Em, mm (shift along y_m).
    sliding_base : float
        XB, mm (shift along the cradle axis).
    ratio_of_roll : float
        m_a = d(phi)/d(psi) at psi = 0, > 0.
    modified_roll_c, modified_roll_d, modified_roll_e, modified_roll_f, modified_roll_g : float
        C, D, E, F, G (1/rad, 1/rad^2, ... 1/rad^5) of the modified roll (module docstring).
    tilt, swivel : float
        Cutter tilt i and swivel j, rad (module docstring); |i| <= pi/4.
    radial_motion, vertical_motion, helical_motion, tilt_motion, swivel_motion : tuple of float
        Derivatives d^k/dpsi^k (k = 1, 2, ...; at most 6) at psi = 0 of the radial setting (mm), the blank
        offset (mm), the sliding base (mm), the tilt and the swivel (rad): each setting is
        ``x0 + sum_k a_k psi^k / k!``.  Empty: the setting is constant.
    formate : bool
        True: the member is not generated (no roll; the cutter is plunged); ``ratio_of_roll`` and the roll and
        motion terms must then be zero.
    """

    radial_setting: float
    cradle_angle: float
    root_angle: float
    center_to_back: float = 0.0
    blank_offset: float = 0.0
    sliding_base: float = 0.0
    ratio_of_roll: float = 1.0
    modified_roll_c: float = 0.0
    modified_roll_d: float = 0.0
    modified_roll_e: float = 0.0
    modified_roll_f: float = 0.0
    modified_roll_g: float = 0.0
    tilt: float = 0.0
    swivel: float = 0.0
    radial_motion: tuple[float, ...] = ()
    vertical_motion: tuple[float, ...] = ()
    helical_motion: tuple[float, ...] = ()
    tilt_motion: tuple[float, ...] = ()
    swivel_motion: tuple[float, ...] = ()
    formate: bool = False

    def __post_init__(self) -> None:
        if not (np.isfinite(self.radial_setting) and self.radial_setting > 0):
            raise ValueError(f"radial_setting = {self.radial_setting!r} is outside the allowed range (0, inf) mm")
        if not (0.0 < self.root_angle <= 0.5 * np.pi + 1e-12):
            raise ValueError(f"root_angle = {self.root_angle!r} is outside the allowed range (0, pi/2] rad")
        if not self.formate and not (np.isfinite(self.ratio_of_roll) and self.ratio_of_roll > 0):
            raise ValueError(f"ratio_of_roll = {self.ratio_of_roll!r} is outside the allowed range (0, inf)")
        if not (abs(self.tilt) <= 0.25 * np.pi) or not np.isfinite(self.swivel):
            raise ValueError(f"tilt = {self.tilt!r} is outside the allowed range [-0.785, 0.785] rad (swivel = "
                             f"{self.swivel!r} rad must be finite)")
        for name in MOTIONS:
            a = getattr(self, name)
            if not isinstance(a, tuple):
                object.__setattr__(self, name, tuple(float(x) for x in a))
                a = getattr(self, name)
            if len(a) > MAX_ORDER or not all(np.isfinite(a)):
                raise ValueError(f"{name} = {a!r} is outside the allowed range: at most {MAX_ORDER} finite "
                                 "derivatives")
        rolls = (self.modified_roll_c, self.modified_roll_d, self.modified_roll_e, self.modified_roll_f,
                 self.modified_roll_g)
        if self.formate and (any(rolls) or self.ratio_of_roll or any(any(getattr(self, n)) for n in MOTIONS)):
            raise ValueError("formate = True with a modified roll or a motion: a formate member has no roll; "
                             "allowed: all roll and motion terms 0")
        object.__setattr__(self, "_basic", not (
            self.tilt or self.swivel or self.formate or self.modified_roll_e or self.modified_roll_f
            or self.modified_roll_g or any(getattr(self, n) for n in MOTIONS)))

    @property
    def roll_coefficients(self) -> np.ndarray:
        """Coefficients c_1..c_6 of ``phi = sum_k c_k psi^k`` (c_1 = m_a, c_2 = -m_a C, ...), shape (6,)."""
        m = 0.0 if self.formate else self.ratio_of_roll
        return m * np.array([1.0, -self.modified_roll_c, -self.modified_roll_d, -self.modified_roll_e,
                             -self.modified_roll_f, -self.modified_roll_g])

    @property
    def is_basic(self) -> bool:
        """True for the basic cradle machine: no tilt, swivel, motions, roll terms above D, not formate."""
        return self._basic

    def motion(self, name: str, psi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """A setting at the cradle roll ``psi`` and its derivative by psi.

        Parameters
        ----------
        name : str
            ``"radial_setting"``, ``"blank_offset"``, ``"sliding_base"``, ``"tilt"`` or ``"swivel"``.
        psi : ndarray
            Cradle roll, rad.

        Returns
        -------
        x, dx : ndarray shaped like ``psi`` (mm or rad, per rad).
        """
        motion = {"radial_setting": "radial_motion", "blank_offset": "vertical_motion",
                  "sliding_base": "helical_motion", "tilt": "tilt_motion", "swivel": "swivel_motion"}[name]
        return _taylor(getattr(self, name), getattr(self, motion), psi)

    def _frame(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Cutter centre, work axis, work origin and work basis (the properties below), built on first use and
        kept: the generators read them at every evaluation.  Read-only arrays, as the settings are frozen."""
        f = self.__dict__.get("_frame_arrays")
        if f is None:
            centre = np.array([self.radial_setting * np.cos(self.cradle_angle),
                               self.radial_setting * np.sin(self.cradle_angle), 0.0])
            k = np.array([np.cos(self.root_angle), 0.0, np.sin(self.root_angle)])
            origin = np.array([0.0, self.blank_offset, self.sliding_base]) + self.center_to_back * k
            y = np.array([0.0, 1.0, 0.0])
            f = (centre, k, origin, np.stack([cross3(y, k), y, k], axis=1))
            for a in f:
                a.flags.writeable = False
            object.__setattr__(self, "_frame_arrays", f)
        return f

    @property
    def cutter_center(self) -> np.ndarray:
        """Cutter centre in the cradle frame, shape (3,), mm (read-only)."""
        return self._frame()[0]

    @property
    def work_axis(self) -> np.ndarray:
        """Unit work axis k in S_m, shape (3,) (read-only)."""
        return self._frame()[1]

    @property
    def work_origin(self) -> np.ndarray:
        """Work body origin (pitch apex) O_w in S_m, shape (3,), mm (read-only)."""
        return self._frame()[2]

    @property
    def work_basis(self) -> np.ndarray:
        """Columns x_w = y_w x z_w, y_w, z_w of the work body frame at phi = 0, in S_m; shape (3, 3) (read-only)."""
        return self._frame()[3]


@dataclass(frozen=True)
class FlankCut:
    """Machine settings and blade family that generate one flank."""

    machine: MachineSettings
    cutter: HeadCutter

    @property
    def side(self) -> str:
        return self.cutter.side


@dataclass(frozen=True)
class MemberCut:
    """Both flank cuts of one member (``member`` = ``"gear"`` or ``"pinion"``; ``z`` teeth)."""

    member: str
    z: int
    concave: FlankCut
    convex: FlankCut

    def flank(self, side: str) -> FlankCut:
        if side not in ("concave", "convex"):
            raise ValueError(f"side = {side!r}: allowed 'concave' or 'convex'")
        return self.concave if side == "concave" else self.convex


def rot_z(angle: float) -> np.ndarray:
    """4x4 rotation by ``angle`` (rad) about z."""
    c, s = np.cos(angle), np.sin(angle)
    m = np.eye(4)
    m[:2, :2] = [[c, -s], [s, c]]
    return m


def translation(t: np.ndarray) -> np.ndarray:
    """4x4 translation by the vector ``t`` (mm)."""
    m = np.eye(4)
    m[:3, 3] = t
    return m


def cradle_to_machine(psi: float) -> np.ndarray:
    """M_mp(psi): cradle frame -> machine frame."""
    return rot_z(psi)


def cutter_to_cradle(ms: MachineSettings) -> np.ndarray:
    """M_pc at psi = 0: cutter frame -> cradle frame (cutter centre at Sr(cos q, sin q, 0), tilted by R_t)."""
    m = translation(ms.cutter_center)
    if ms.tilt:
        b, i = ms.cradle_angle - ms.swivel, ms.tilt
        m[:3, :3] = rot_z(b)[:3, :3] @ np.array([[1.0, 0.0, 0.0], [0.0, np.cos(i), -np.sin(i)],
                                                  [0.0, np.sin(i), np.cos(i)]]) @ rot_z(-b)[:3, :3]
    return m


def work_to_machine(ms: MachineSettings, phi: float) -> np.ndarray:
    """M_mw(phi): work body frame -> machine frame when the work has rolled by phi about +k."""
    m = np.eye(4)
    m[:3, :3] = ms.work_basis
    m[:3, 3] = ms.work_origin
    return m @ rot_z(phi)


def _taylor(x0: float, derivs: tuple[float, ...], psi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``x0 + sum_k a_k psi^k / k!`` and its derivative by psi, arrays shaped like ``psi``."""
    psi = np.asarray(psi, dtype=float)
    x, dx = np.full_like(psi, x0), np.zeros_like(psi)
    for k, a in enumerate(derivs, start=1):
        x = x + a * psi ** k / _FACT[k]
        dx = dx + a * psi ** (k - 1) / _FACT[k - 1]
    return x, dx


_FACT = [1.0, 1.0, 2.0, 6.0, 24.0, 120.0, 720.0]


def roll(ms: MachineSettings, psi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Work roll angle phi(psi) and its derivative d(phi)/d(psi) (modified roll, Cao et al. 2008 Eq. 8, to
    6th order; zero for a formate member)."""
    c, d, m = ms.modified_roll_c, ms.modified_roll_d, ms.ratio_of_roll
    if not (ms.formate or ms.modified_roll_e or ms.modified_roll_f or ms.modified_roll_g):
        return m * (psi - c * psi ** 2 - d * psi ** 3), m * (1.0 - 2 * c * psi - 3 * d * psi ** 2)
    psi = np.asarray(psi, dtype=float)
    cf = ms.roll_coefficients
    phi, dphi = np.zeros_like(psi), np.zeros_like(psi)
    for k in range(6, 0, -1):
        phi = (phi + cf[k - 1]) * psi
        dphi = dphi * psi + k * cf[k - 1]
    return phi, dphi


def tilt_rotation(ms: MachineSettings, tilt: np.ndarray, swivel: np.ndarray) -> tuple[np.ndarray, np.ndarray,
                                                                                       np.ndarray]:
    """Tilt axis and its in-plane normal at the given tilt and swivel (module docstring), for Rodrigues' formula.

    Returns
    -------
    a, a_perp : ndarray, shape tilt.shape + (3,)
        Unit tilt axis (cos(q - j), sin(q - j), 0) in the cradle frame and d a / d(q - j).
    i : ndarray
        The tilt, broadcast.
    """
    b = ms.cradle_angle - np.asarray(swivel, dtype=float)
    cb, sb = np.cos(b), np.sin(b)
    zero = np.zeros_like(cb)
    return (np.stack([cb, sb, zero], axis=-1), np.stack([-sb, cb, zero], axis=-1),
            np.broadcast_to(np.asarray(tilt, dtype=float), cb.shape))


def mean_pitch_point(blank: BevelBlank, member: str, root_angle: float, sliding_base: float = 0.0
                     ) -> np.ndarray:
    """Mean point of the pitch cone (cone distance A_m) in S_m for a work at O_w = XB z_m, shape (3,)."""
    g = blank.member(member).pitch_angle
    k = np.array([np.cos(root_angle), 0.0, np.sin(root_angle)])
    xw = np.cross([0.0, 1.0, 0.0], k)
    return np.array([0.0, 0.0, sliding_base]) + blank.mean_cone_distance * (np.cos(g) * k + np.sin(g) * xw)


def _hand_sign(hand: str) -> float:
    return 1.0 if hand == "right" else -1.0


def _flank_cut(P: np.ndarray, beta: float, h: float, offset: float, rho: float, depth: float,
               blade: str, alpha: float, rf: float, ms_kw: dict) -> FlankCut:
    """Blade through the flank point Q = P + offset n_P at radius ``rho`` (at ``depth`` below the tip)."""
    nP = np.array([-np.sin(beta), h * np.cos(beta)])       # unit normal to the tooth trace, to the centre
    C = P[:2] + (offset + rho) * nP
    sg = 1.0 if blade == "outside" else -1.0
    Rp = rho - sg * depth * np.tan(alpha)
    ms = MachineSettings(radial_setting=float(np.hypot(*C)), cradle_angle=float(np.arctan2(C[1], C[0])),
                         **ms_kw)
    return FlankCut(ms, HeadCutter(float(Rp), float(alpha), blade, float(rf)))


def gear_settings(blank: BevelBlank, point_width: float | None = None, edge_radius: float | None = None
                  ) -> MemberCut:
    """Standard settings of the generated gear (spread-blade cutter, both flanks in one cut).

    Machine root angle = root angle (uniform depth: pitch angle, apex lowered by the dedendum with the
    sliding base), no offsets, ratio of roll cos(g - gm)/sin(g), cutter of mean radius r_c centred so that the
    tooth trace through the mean pitch point has the spiral angle beta_m.  Point width (tip-plane slot
    width) W = p_mn - s_2 - 2 b_m2 tan(alpha_n) gives the design thickness to first order (crown-gear
    normal section); :func:`ltca.geometry.bevel.generation.standard_gear_cut` refines it on the generated surface.
    """
    d, g = blank.data, blank.gear
    alpha = d.pressure_angle
    gm = g.root_angle
    xb = -g.dedendum if d.taper == "uniform" else 0.0
    P = mean_pitch_point(blank, "gear", gm, xb)
    depth = -P[2]
    slot = blank.mean_normal_pitch - g.mean_normal_thickness
    W = slot - 2 * depth * np.tan(alpha) if point_width is None else point_width
    if W <= 0:
        raise ValueError(f"point_width = {W!r} is outside the allowed range (0, {slot}) mm")
    rf = min(0.2 * d.module, 0.45 * W * np.cos(alpha) / (1 - np.sin(alpha))) if edge_radius is None \
        else edge_radius
    half = 0.5 * (W + 2 * depth * np.tan(alpha))            # half slot width at the pitch point
    kw = dict(root_angle=gm, sliding_base=xb, ratio_of_roll=float(np.cos(g.pitch_angle - gm) / np.sin(g.pitch_angle)))
    h = _hand_sign(g.hand)
    b = d.spiral_angle
    rc = d.cutter_radius
    return MemberCut("gear", g.z,
                     concave=_flank_cut(P, b, h, -half, rc + half, depth, "outside", alpha, rf, kw),
                     convex=_flank_cut(P, b, h, +half, rc - half, depth, "inside", alpha, rf, kw))


def pinion_settings(blank: BevelBlank, mismatch: float = 2.0, edge_radius: float | None = None) -> MemberCut:
    """Basic (unsynthesised) pinion settings: each flank cut separately at the root angle.

    The pinion tooth (not its slot) is centred on the mean pitch point, as it fills the gear slot there in
    mesh.  The blade radius at the mean pitch point is the mating gear blade's radius there plus (concave)
    or minus (convex) ``mismatch`` (mm), which localises the bearing lengthwise; otherwise as
    :func:`gear_settings`.  Local synthesis (Cao et al. 2008) replaces these settings.
    """
    d, p = blank.data, blank.pinion
    if not (0.0 <= mismatch < 0.5 * d.cutter_radius):
        raise ValueError(f"mismatch = {mismatch!r} is outside the allowed range [0, {0.5 * d.cutter_radius}) mm")
    alpha = d.pressure_angle
    gm = p.root_angle
    xb = -p.dedendum if d.taper == "uniform" else 0.0
    P = mean_pitch_point(blank, "pinion", gm, xb)
    depth = -P[2]
    half1 = 0.5 * p.mean_normal_thickness                   # the pinion TOOTH is centred at P (it fills the gear slot)
    half2 = 0.5 * (blank.mean_normal_pitch - blank.gear.mean_normal_thickness)
    rc = d.cutter_radius
    rf = 0.2 * d.module if edge_radius is None else edge_radius
    kw = dict(root_angle=gm, sliding_base=xb, ratio_of_roll=float(np.cos(p.pitch_angle - gm) / np.sin(p.pitch_angle)))
    h = -_hand_sign(blank.gear.hand)
    b = d.spiral_angle
    return MemberCut("pinion", p.z,
                     concave=_flank_cut(P, b, h, +half1, rc - half2 + mismatch, depth, "outside", alpha, rf, kw),
                     convex=_flank_cut(P, b, h, -half1, rc + half2 - mismatch, depth, "inside", alpha, rf, kw))


def conjugate_pinion_settings(gear: MemberCut, blank: BevelBlank, edge_radius: float = 0.0) -> MemberCut:
    """Pinion generated by the gear's own imaginary crown gear (kinematic oracle).

    Requires a gear cut with machine root angle = pitch angle (uniform depth).  The pinion sits on the
    other side of the same crown gear: the generating cone of the gear's concave (convex) flank, seen from
    the pinion's tip plane a depth H = b1 + b2 further on, is an inside (outside) blade of point radius
    R_p +- H tan(alpha); the cutter centre is mirrored (y -> -y, opposite hand), root angle = pinion pitch
    angle, XB = -b1, ratio of roll 1/sin(g1).  Derivation: rotate the gear's machine by pi about x_m.
    """
    g, p = blank.gear, blank.pinion
    H = p.dedendum + g.dedendum
    out = {}
    for gside, pside, blade in (("concave", "convex", "inside"), ("convex", "concave", "outside")):
        fc = gear.flank(gside)
        ms, cu = fc.machine, fc.cutter
        if abs(ms.root_angle - g.pitch_angle) > 1e-12 or ms.modified_roll_c or ms.modified_roll_d:
            raise ValueError(f"root_angle = {ms.root_angle!r}: the oracle needs the gear pitch angle "
                             f"{g.pitch_angle!r} and no modified roll")
        Rp = cu.point_radius + cu.sigma * H * np.tan(cu.blade_angle)
        m = MachineSettings(radial_setting=ms.radial_setting, cradle_angle=-ms.cradle_angle,
                            root_angle=p.pitch_angle, sliding_base=-p.dedendum,
                            ratio_of_roll=float(1.0 / np.sin(p.pitch_angle)))
        out[pside] = FlankCut(m, HeadCutter(float(Rp), cu.blade_angle, blade, edge_radius))
    return MemberCut("pinion", p.z, concave=out["concave"], convex=out["convex"])
