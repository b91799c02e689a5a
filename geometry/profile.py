"""The generated transverse tooth profile (:class:`ToothProfile`) and its assembly from a half tooth.

Frame: gear axis = z, tooth centred on +y. Polar angles ("flank angles") are measured from +y,
positive counter-clockwise (towards -x), so the left flank (x < 0) has positive angles. The generators
(:func:`ltca.geometry.involute.generate_by_rack`, :func:`ltca.geometry.shaper.generate_by_shaper`) build the right
half, from the tooth centre to the right mid-gap, and :func:`_assemble` mirrors it into the record.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .transverse import _pol, involute

__all__ = ["ToothProfile"]


@dataclass(frozen=True)
class ToothProfile:
    """Transverse section (plane z = 0) of ONE tooth and the two half gaps beside it, gear frame.

    The tooth is centred on +y. Points run from the mid-gap at polar angle +pi/z (x < 0) over the tooth to
    the mid-gap at -pi/z (x > 0), i.e. clockwise seen from +z. Chord error < 1e-6 mm on involute and
    fillet (spacing <= 5 um there), <= 50 um spacing on root and tip arcs.

    Attributes
    ----------
    xy : (n, 2) mm.   kind : (n,) int8, 0 root arc, 1 fillet, 2 involute, 3 tip arc.
    side : (n,) int8, -1 left (x < 0), +1 right (x > 0), 0 on the centre line.
    r_base, r_ref, r_tip, r_root, r_form_left, r_form_right : transverse radii, mm (r_form: involute
    start at the fillet; internal gears: r_tip < r_form < r_root).
    s_ref : transverse tooth thickness (arc) on the reference circle, mm (internal: of the internal tooth).
    alpha_t, beta_b : rad.   undercut : the fillet cut into the involute.
    tip_edge : :class:`ltca.geometry.tip_edge.TipEdge` or None, a rounding or chamfer of the tip edges (the outline
    carries it; the involute ends at ``r_flank_end``).
    """

    xy: np.ndarray
    kind: np.ndarray
    side: np.ndarray
    z: int
    internal: bool
    m_n: float
    alpha_n: float
    beta: float
    x: float
    r_base: float
    r_ref: float
    r_tip: float
    r_root: float
    r_form_left: float
    r_form_right: float
    s_ref: float
    alpha_t: float
    beta_b: float
    undercut: bool
    tip_edge: object = None

    @property
    def r_flank_end(self) -> float:
        """Radius where the involute ends at the tip: the tip circle, or where a tip-edge rounding or chamfer starts."""
        return self.tip_edge.r_start if self.tip_edge is not None else self.r_tip

    def _radius(self, r):
        r = np.asarray(r, dtype=float)
        if np.any(r < self.r_base * (1 - 1e-12)):
            raise ValueError(f"r = {r.min()!r} is below the base radius {self.r_base} mm")
        return np.maximum(r, self.r_base)

    def involute_roll(self, r):
        """Roll angle ``tan(alpha_r) = sqrt(r^2 - r_b^2) / r_b`` (rad) of the involute at radius r (mm)."""
        r = self._radius(r)
        return np.sqrt(r * r - self.r_base ** 2) / self.r_base

    def half_angle(self, r):
        """Half angular tooth thickness (rad) at radius r (mm) on the involute part.

        External: ``s/(2 r_ref) + inv(alpha_t) - inv(alpha_r)``; internal: the internal tooth,
        ``s/(2 r_ref) - inv(alpha_t) + inv(alpha_r)`` (the space has the shape of an external tooth).
        """
        u = self.involute_roll(r)
        inv_r = u - np.arctan(u)
        sig = -1.0 if self.internal else 1.0
        return self.s_ref / (2 * self.r_ref) + sig * (involute(self.alpha_t) - inv_r)

    def flank_angle(self, r, side):
        """Polar angle (rad, from +y, counter-clockwise positive) of the ``side`` involute at radius r.

        ``side`` = +1 right flank (x > 0, negative angle), -1 left flank. Exact (analytic involute).
        """
        if side not in (-1, 1):
            raise ValueError(f"side = {side!r}: allowed -1 (left) or +1 (right)")
        return -side * self.half_angle(r)

    def flank_xy(self, r, side):
        """Exact transverse points (..., 2) of the ``side`` involute at radius r (mm)."""
        return _pol(np.asarray(r, dtype=float), -self.flank_angle(r, side))

    def thickness_at(self, r):
        """Transverse arc tooth thickness ``2 r half_angle(r)`` (mm) at radius r on the involute."""
        return 2 * np.asarray(r, dtype=float) * self.half_angle(r)


def _assemble(right, kinds, blank, **radii) -> ToothProfile:
    """Mirror the right half (list of (m, 2) arrays ordered from the tooth centre to the right mid-gap)."""
    pts, knd = [], []
    for p, k in zip(right, kinds):
        if pts and np.linalg.norm(p[0] - pts[-1][-1]) < 1e-9:
            p = p[1:]
        pts.append(p)
        knd.append(np.full(len(p), k, np.int8))
    r_xy, r_k = np.concatenate(pts), np.concatenate(knd)
    l_xy = r_xy[::-1] * np.array([-1.0, 1.0])
    l_k = r_k[::-1]
    if abs(r_xy[0, 0]) < 1e-12:            # centre point shared
        l_xy, l_k = l_xy[:-1], l_k[:-1]
    xy = np.concatenate([l_xy, r_xy])
    kind = np.concatenate([l_k, r_k])
    side = np.where(np.abs(xy[:, 0]) < 1e-12, 0, np.sign(xy[:, 0])).astype(np.int8)
    alpha_t = blank.alpha_t
    beta_b = float(np.arctan(np.tan(blank.beta) * np.cos(alpha_t)))
    return ToothProfile(xy=xy, kind=kind, side=side, z=int(blank.z), internal=bool(blank.internal),
                        m_n=blank.m_n, alpha_n=blank.alpha_n, beta=blank.beta, x=blank.x,
                        r_ref=blank.r_ref, r_base=blank.r_ref * np.cos(alpha_t), s_ref=blank.s_ref,
                        alpha_t=alpha_t, beta_b=beta_b, **radii)
