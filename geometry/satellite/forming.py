"""Cutting the satellite by the three methods of Kapitonov et al. (2014); each gives a
:class:`~ltca.geometry.profile.ToothProfile`.

* (c) ``special_hob``: one rack envelope (:func:`ltca.geometry.involute.generate_by_rack`) with the thickened
  rack, i.e. the ISO 21771 thickness allowance ``A = k m`` (:class:`SpecialHob`).
* (a) ``hob_three_pass``: three rack envelopes with the standard rack at the design shift, the second and
  third with the rack moved by ``+t`` and ``-t`` along its pitch line. A rack moved by t generates the same
  tooth turned by ``t / r`` (the rolling of the rack's pitch line on the reference circle r; Litvin &
  Fuentes 2004, sec. 10.3), so the passes are rotated copies of one envelope; the metal left is their
  intersection, taken in polar form: at each radius the boundary angle is the minimum over the passes.
* (b) ``disk_cutter``: form copying: the cutter profile (:class:`DiskCutter`), translated along the space
  centre line to the plunge, is removed at every tooth space of the blank (tip circle of the design).
* ``hob``: one pass of the standard hob, no thinning (the reference of the interference study).

Frame and units as in :mod:`ltca.geometry.profile` (tooth on +y, mm, rad).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from ..gear_blank import GearBlank, RackCutter
from ..involute import generate_by_rack
from ..outline import GearOutline
from ..profile import ToothProfile, _assemble
from ..transverse import _arc, _cw, _pol, _rot_cw, inverse_involute, involute
from .tools import DiskCutter, HobThreePass, SatelliteDesign, SpecialHob

__all__ = ["FormedTooth", "METHODS", "form_satellite", "form_special_hob", "form_hob_three_pass",
           "form_disk_cutter", "NEARLY_POINTED"]

METHODS = ("hob", "hob_three_pass", "disk_cutter", "special_hob")
NEARLY_POINTED = 0.2   # tip land below 0.2 m: common minimum for through-hardened gears (Niemann & Winter I)


@dataclass(frozen=True)
class FormedTooth:
    """A satellite tooth as cut by one method.

    profile : ToothProfile (for ``disk_cutter`` the flanks are translated involutes: use ``profile.xy``;
        the analytic involute methods of the record are exact only when ``involute_exact``).
    method : str.   tool : the tool record.   passes : int, cutting passes (cycles on the machine).
    s_ref : tooth thickness on the reference circle measured on the outline, mm.   s_eq3 : Kapitonov et al. Eq. 3, mm.
    tip_land : arc thickness on the tip circle, mm (0 when pointed).   r_tip : outermost radius, mm.
    pointed : the flanks meet below the blank's tip circle.   nearly_pointed : tip land < 0.2 m.
    r_root : innermost radius, mm.   dedendum : r_ref - r_root, mm.
    root_fillet_radius : smallest curvature radius of the fillet, mm.
    """

    profile: ToothProfile
    method: str
    tool: object
    passes: int
    s_ref: float
    s_eq3: float
    tip_land: float
    r_tip: float
    pointed: bool
    nearly_pointed: bool
    r_root: float
    dedendum: float
    root_fillet_radius: float
    involute_exact: bool


def _fillet_radius(profile: ToothProfile) -> float:
    """Smallest circumradius of three consecutive right-flank fillet points, mm."""
    p = profile.xy[(profile.kind == 1) & (profile.side == 1)]
    if len(p) < 3:
        return float("nan")
    a, b, c = p[:-2] - p[1:-1], p[2:] - p[1:-1], p[2:] - p[:-2]
    cross = np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    with np.errstate(divide="ignore"):
        R = np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1) * np.linalg.norm(c, axis=1) / (2 * cross)
    return float(np.min(R))


def _record(profile, method, tool, passes, design, pointed, exact) -> FormedTooth:
    ol = GearOutline(profile)
    r = profile.r_ref
    s_ref = float(2 * r * ol.half_angle(r))
    R = np.hypot(*profile.xy.T)
    tip = profile.xy[profile.kind == 3]
    land = 0.0 if pointed else float(2 * profile.r_tip * np.max(np.abs(_cw(tip))))
    r_root = float(R.min())
    return FormedTooth(profile=profile, method=method, tool=tool, passes=passes, s_ref=s_ref,
                       s_eq3=float(design.eq3_thickness), tip_land=land, r_tip=float(R.max()), pointed=pointed,
                       nearly_pointed=bool(pointed or land < NEARLY_POINTED * design.m), r_root=r_root,
                       dedendum=float(r - r_root), root_fillet_radius=_fillet_radius(profile),
                       involute_exact=exact)


def _right_half(profile: ToothProfile):
    """Right half (tooth centre -> right mid-gap) points and kinds."""
    sel = profile.xy[:, 0] >= 0
    return profile.xy[sel], profile.kind[sel]


def form_special_hob(design: SatelliteDesign, tool: SpecialHob = SpecialHob()) -> FormedTooth:
    """Method (c): one pass of the hob with the thickened rack (Eq. 3 thickness, ISO 21771 eq. 52)."""
    k = design.thinning if tool.thickening is None else tool.thickening
    prof = generate_by_rack(design.blank(thinning=k), design.rack())
    return _record(prof, "special_hob", tool, 1, design, False, True)


def form_hob(design: SatelliteDesign) -> FormedTooth:
    """One pass of the standard hob at the design shift, no thinning."""
    return _record(generate_by_rack(design.blank(), design.rack()), "hob", None, 1, design, False, True)


def form_hob_three_pass(design: SatelliteDesign, tool: HobThreePass = HobThreePass()) -> FormedTooth:
    """Method (a): three passes of the standard hob, offsets 0, +t, -t along the rack pitch line.

    Each pass is :func:`generate_by_rack` of the unthinned blank; pass i turned clockwise by ``t_i / r``.
    Right boundary (clockwise angle) of the intersection ``min_i (h(rho) + t_i / r)``, left boundary
    ``min_i (h(rho) - t_i / r)``: for +-t both are ``h(rho) - t / r``, a tooth thinner by 2 t on every
    circle, i.e. Eq. 3 for ``t = k m / 2``. Tip arc and root arc are re-cut to the new corners.
    """
    t = tool.tangential_shift(design)
    blank0, rack = design.blank(), design.rack()
    r = blank0.r_ref
    offsets = np.array([0.0, t, -t])
    passes = [generate_by_rack(blank0, rack) for _ in offsets]        # one envelope per pass
    halves = [_right_half(p) for p in passes]
    # tip corner (last tip-arc point) + involute + fillet; tip and root arcs are re-cut below
    flank = [(h[0][np.argmin(h[1] == 3) - 1:], np.where(h[1] == 3, 2, h[1])[np.argmin(h[1] == 3) - 1:])
             for h in halves]
    R = np.hypot(*flank[0][0].T)
    ang = np.stack([_cw(f[0]) for f in flank])
    right = np.min(ang + offsets[:, None] / r, axis=0)
    left = np.min(ang - offsets[:, None] / r, axis=0)
    if not np.allclose(right, left, atol=1e-15):
        raise ValueError("HobThreePass: asymmetric offsets are not supported")
    keep = (flank[0][1] == 1) | (flank[0][1] == 2)
    pts, kinds = _pol(R[keep], right[keep]), flank[0][1][keep]
    if _cw(pts[0]) <= 0:
        raise ValueError(f"HobThreePass.shift = {t!r} mm: the tooth tip vanishes (allowed [0, "
                         f"{r * ang[0, 0]:.4f}) mm for this satellite)")
    r_root = passes[0].r_root
    tip = _arc(design.r_tip, 0.0, _cw(pts[0]))
    root = _arc(r_root, _cw(pts[-1]), np.pi / design.z)
    inv = kinds == 2
    prof = _assemble([tip, pts[inv], pts[~inv], root], [3, 2, 1, 0], design.blank(thinning=2 * t / design.m),
                     r_tip=design.r_tip, r_root=r_root, r_form_left=passes[0].r_form_left,
                     r_form_right=passes[0].r_form_right, undercut=passes[0].undercut)
    return _record(prof, "hob_three_pass", tool, 3, design, False, True)


def _cutter_space(design: SatelliteDesign, tool: DiskCutter):
    """Left half of the disk cutter's axial profile in the frame of its own x = 0 gear, space on +y.

    Returns points (n, 2) from the top of the involute (where the x = 0 tooth would be pointed) down to
    the space centre on the root circle, their kinds (2 involute, 1 fillet, 0 root) and that gear's
    reference radius.
    """
    zp = tool.z_profile or design.z
    m, a = design.m, design.alpha
    r0 = 0.5 * zp * m
    r_pt = r0 * np.cos(a) / np.cos(inverse_involute(np.pi / (2 * zp) + involute(a)))
    std = design.rack()
    rack = RackCutter(a, std.ha, r_pt - r0 + m, std.rho)           # dedendum above the pointed radius
    p = generate_by_rack(GearBlank(zp, m, a, 0.0, 0.0, d_tip=2 * (r_pt - 1e-6)), rack)
    xy, kind = _right_half(p)
    flank = kind != 3
    return _rot_cw(xy[flank], -np.pi / zp), kind[flank], r0


def form_disk_cutter(design: SatelliteDesign, tool: DiskCutter = DiskCutter()) -> FormedTooth:
    """Method (b): form copying with a disk module cutter plunged to ``tool.x_plunge`` (see DiskCutter).

    The space boundary is the cutter profile translated by ``(r - r0) + x_plunge m`` along the space centre
    line, placed at the clockwise angle pi/z of the tooth's right gap; walking up from the space centre
    the tooth flank ends at the blank's tip circle (tip land) or where it crosses the tooth centre line
    (pointed: the two copied spaces meet below the tip circle, the tooth tip is the crossing radius).
    """
    P, kind, r0 = _cutter_space(design, tool)
    r = 0.5 * design.d
    q = _rot_cw(P + np.array([0.0, (r - r0) + tool.x_plunge * design.m]), np.pi / design.z)[::-1]
    kind = kind[::-1]                                             # space centre (root) -> top
    R, A = np.hypot(*q.T), _cw(q)
    out = (R >= design.r_tip) | (A <= 0)
    if not out.any():
        raise ValueError(f"DiskCutter.z_profile = {tool.z_profile!r}: the cutter profile is too short for the "
                         f"blank (tip circle {2 * design.r_tip} mm)")
    i = int(np.argmax(out))
    pointed = bool(A[i] <= 0 and (R[i] < design.r_tip or A[i - 1] / (A[i - 1] - A[i]) <=
                                  (design.r_tip - R[i - 1]) / (R[i] - R[i - 1])))
    # crossing parameter on segment i-1 -> i: angle 0 (pointed) or radius r_tip (tip land)
    s = A[i - 1] / (A[i - 1] - A[i]) if pointed else (design.r_tip - R[i - 1]) / (R[i] - R[i - 1])
    end = q[i - 1] + s * (q[i] - q[i - 1])
    if pointed:
        end = np.array([0.0, np.hypot(*end)])
    curve, ck = np.vstack([q[:i], end])[::-1], np.concatenate([kind[:i], [kind[i - 1]]])[::-1]
    parts = [curve[ck == k] for k in (2, 1, 0)]
    r_tip = float(np.hypot(*end))
    right = parts if pointed else [_arc(r_tip, 0.0, _cw(end))] + parts
    kinds = [2, 1, 0] if pointed else [3, 2, 1, 0]
    r_form = float(np.hypot(*parts[1][0])) if len(parts[1]) else float(np.hypot(*parts[0][-1]))
    prof = _assemble(right, kinds, design.blank(x=tool.x_plunge), r_tip=r_tip, r_root=float(R.min()),
                     r_form_left=r_form, r_form_right=r_form, undercut=False)
    rec = _record(prof, "disk_cutter", tool, 1, design, pointed, False)
    return dataclasses.replace(rec, profile=dataclasses.replace(prof, s_ref=rec.s_ref))


def form_satellite(design: SatelliteDesign, method: str, tool=None) -> FormedTooth:
    """Cut the satellite by ``method`` (one of :data:`METHODS`) with ``tool`` (None: the paper's tool)."""
    if method not in METHODS:
        raise ValueError(f"method = {method!r}: allowed one of {METHODS}")
    if method == "hob":
        return form_hob(design)
    fun, cls = {"hob_three_pass": (form_hob_three_pass, HobThreePass),
                "disk_cutter": (form_disk_cutter, DiskCutter),
                "special_hob": (form_special_hob, SpecialHob)}[method]
    tool = cls() if tool is None else tool
    if not isinstance(tool, cls):
        raise ValueError(f"tool = {tool!r}: method {method!r} takes a {cls.__name__}")
    return fun(design, tool)
