"""Tip-edge rounding and chamfer of a generated tooth: the outline and the material removed from the flank.

A generated tooth has a sharp edge where its involute meets the tip circle. A rounding of radius ``rho``
replaces the corner by a circular arc tangent to the involute and to the tip circle (inside the tooth); a
chamfer of leg ``c`` by a straight cut from the involute point ``c`` from the corner (along the involute) to the
tip-circle point ``c`` from the corner (along the tip circle). Both are built on the right flank of tooth 0 and
mirrored, so the transverse outline of :class:`ltca.geometry.profile.ToothProfile` (and every body meshed from it)
carries them; the involute then ends at ``TipEdge.r_start`` instead of at the tip circle.

Contact analysis evaluates the flank on the analytic involute up to the tip circle: :func:`tip_edge_depth`
gives the transverse material removed there (distance from the involute point to the rounded or chamfered
outline), which enters the gaps like a flank modification. Internal gears (tip circle inside the form circle)
are handled the same way with the rounding tangent to the tip circle from outside.

Frame and conventions as in :mod:`ltca.geometry.profile` (tooth centred on +y; right flank x > 0).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from .profile import ToothProfile
from .transverse import _CHORD_TOL, _H_MAX

__all__ = ["TipEdge", "with_tip_edge", "tip_edge_depth", "largest_tip_edge"]


@dataclass(frozen=True)
class TipEdge:
    """The tip edge of a tooth: ``kind`` "radius" (rounding of radius ``size``) or "chamfer" (leg ``size``), mm.

    ``r_start``: radius where the involute ends (the rounding's point of tangency, the chamfer's first corner);
    ``start``, ``end``: that point and the one on the tip circle, right flank of tooth 0 (mm);
    ``centre``: the rounding's centre (for a chamfer, the midpoint of the cut)."""
    kind: str
    size: float
    r_start: float
    start: tuple[float, float]
    end: tuple[float, float]
    centre: tuple[float, float]

    def describe(self) -> str:
        """Plain words, e.g. ``rounded r = 0.5 mm``."""
        return f"rounded r = {self.size:g} mm" if self.kind == "radius" else f"chamfered {self.size:g} mm"


def _inward(profile: ToothProfile, r: float) -> tuple[np.ndarray, np.ndarray]:
    """Point and unit normal into the material of the right involute at radius r (transverse)."""
    eps = 1e-6
    p = profile.flank_xy(r, +1)
    t = profile.flank_xy(r + eps, +1) - profile.flank_xy(r - eps, +1)
    n = np.array([-t[1], t[0]]) / np.hypot(*t)
    ccw = np.array([-p[1], p[0]])                  # towards larger polar angle: into the tooth for the right flank
    return p, (n if n @ ccw > 0 else -n)


def _span(profile: ToothProfile) -> tuple[float, float]:
    rf = profile.r_form_right
    return (min(rf, profile.r_tip), max(rf, profile.r_tip))


def _rounding(profile: ToothProfile, rho: float) -> TipEdge:
    sig = 1.0 if profile.internal else -1.0       # centre on the circle r_tip -+ rho

    def f(r):
        p, n = _inward(profile, r)
        return np.hypot(*(p + rho * n)) - (profile.r_tip + sig * rho)

    lo, hi = _span(profile)
    r_far = lo if not profile.internal else hi    # the involute's end away from the tip
    a, b = sorted((r_far, profile.r_tip - sig * 1e-9))
    if not (np.isfinite(f(a)) and f(a) * f(b) < 0):
        raise ValueError("the rounding does not fit on the involute")
    r0 = brentq(f, a, b, xtol=1e-12)
    p, n = _inward(profile, r0)
    c = p + rho * n
    end = c * profile.r_tip / np.hypot(*c)
    if end[0] <= 0:
        raise ValueError("the rounding is wider than half the tip land")
    return TipEdge("radius", rho, float(r0), tuple(map(float, p)), tuple(map(float, end)), tuple(map(float, c)))


def _chamfer(profile: ToothProfile, leg: float) -> TipEdge:
    rb, rt = profile.r_base, profile.r_tip
    s_tip = (rt * rt - rb * rb) / (2 * rb)
    s0 = s_tip + (leg if profile.internal else -leg)
    lo, hi = _span(profile)
    r0 = np.sqrt(rb * rb + 2 * rb * s0) if s0 > 0 else 0.0
    if not lo < r0 < hi:
        raise ValueError("the chamfer does not fit on the involute")
    corner = profile.flank_xy(rt, +1)
    a = np.arctan2(corner[0], corner[1]) - leg / rt         # clockwise angle from +y, towards the centre line
    if a <= 0:
        raise ValueError("the chamfer is wider than half the tip land")
    p = profile.flank_xy(r0, +1)
    end = np.array([rt * np.sin(a), rt * np.cos(a)])
    return TipEdge("chamfer", leg, float(r0), tuple(map(float, p)), tuple(map(float, end)),
                   tuple(map(float, 0.5 * (p + end))))


def _edge_points(edge: TipEdge) -> np.ndarray:
    """Points (m, 2) of the rounding arc or chamfer from the tip circle to the involute."""
    p, e = np.asarray(edge.start), np.asarray(edge.end)
    if edge.kind == "chamfer":
        n = max(int(np.ceil(np.hypot(*(p - e)) / _H_MAX)) + 1, 2)
        return e + np.linspace(0.0, 1.0, n)[:, None] * (p - e)
    c = np.asarray(edge.centre)
    a0, a1 = np.arctan2(*(e - c)[::-1]), np.arctan2(*(p - c)[::-1])
    a1 = a0 + (a1 - a0 + np.pi) % (2 * np.pi) - np.pi              # the short way round
    h = min(_H_MAX, np.sqrt(8 * _CHORD_TOL * edge.size))
    n = max(int(np.ceil(abs(a1 - a0) * edge.size / h)) + 1, 3)
    t = np.linspace(a0, a1, n)
    return c + edge.size * np.stack([np.cos(t), np.sin(t)], 1)


def with_tip_edge(profile: ToothProfile, radius: float = 0.0, chamfer: float = 0.0) -> ToothProfile:
    """The profile with its tip edges rounded (``radius``, mm) or chamfered (``chamfer``, leg in mm), both sides.

    Raises ValueError when both are given, or when the edge does not fit (it must start on the involute above
    the form circle, and a chamfer must leave some tip land)."""
    if radius > 0 and chamfer > 0:
        raise ValueError("give a tip-edge rounding or a chamfer, not both")
    if radius <= 0 and chamfer <= 0:
        return profile
    edge = _rounding(profile, radius) if radius > 0 else _chamfer(profile, chamfer)
    xy, kind, side = np.asarray(profile.xy), np.asarray(profile.kind), np.asarray(profile.side)
    ic = int(np.flatnonzero(side == 0)[0])
    rx, rk = xy[ic:], kind[ic:]
    r = np.hypot(rx[:, 0], rx[:, 1])
    cw_end = np.arctan2(edge.end[0], edge.end[1])
    past = (r > edge.r_start) if not profile.internal else (r < edge.r_start)
    cut = ((rk == 3) & (np.arctan2(rx[:, 0], rx[:, 1]) >= cw_end)) | ((rk == 2) & past)
    first = int(np.argmax(cut))
    keep_head, keep_tail = rx[:first], rx[first:][~cut[first:]]
    arc = _edge_points(edge)[1:-1]
    rxy = np.concatenate([keep_head, [edge.end], arc, [edge.start], keep_tail])
    rkd = np.concatenate([rk[:first], np.full(len(arc) + 2, 3, np.int8), rk[first:][~cut[first:]]])
    rkd[len(keep_head) + len(arc) + 1] = 2                            # the involute starts at the tangent point
    lxy, lkd = rxy[::-1][:-1] * np.array([-1.0, 1.0]), rkd[::-1][:-1]
    new_xy = np.concatenate([lxy, rxy])
    new_kind = np.concatenate([lkd, rkd]).astype(np.int8)
    new_side = np.where(np.abs(new_xy[:, 0]) < 1e-12, 0, np.sign(new_xy[:, 0])).astype(np.int8)
    return dataclasses.replace(profile, xy=new_xy, kind=new_kind, side=new_side, tip_edge=edge)


def tip_edge_depth(profile: ToothProfile, r: np.ndarray) -> np.ndarray:
    """Transverse material removed (mm) at radius ``r`` of the (analytic) involute by the tip-edge rounding or
    chamfer: 0 below ``r_start``, the distance from the involute point to the arc or cut beyond it."""
    r = np.asarray(r, float)
    edge = profile.tip_edge
    if edge is None:
        return np.zeros_like(r)
    beyond = (r > edge.r_start) if not profile.internal else (r < edge.r_start)
    if not beyond.any():
        return np.zeros_like(r)
    p = profile.flank_xy(np.where(beyond, r, edge.r_start), +1)
    if edge.kind == "radius":
        q = p - np.asarray(edge.centre)
        d = np.hypot(q[..., 0], q[..., 1]) - edge.size
    else:
        a, e = np.asarray(edge.start), np.asarray(edge.end)
        t = (e - a) / np.hypot(*(e - a))
        out = np.array([t[1], -t[0]])                      # normal of the cut, towards the removed corner
        out = out if out @ (profile.flank_xy(profile.r_tip, +1) - a) > 0 else -out
        d = (p - a) @ out
    return np.where(beyond, np.maximum(d, 0.0), 0.0)


def largest_tip_edge(profile: ToothProfile, kind: str) -> float:
    """The largest rounding radius (``kind`` "radius") or chamfer leg ("chamfer") that fits on the tooth, mm."""
    make = _rounding if kind == "radius" else _chamfer
    lo, hi = 0.0, 2.0 * abs(profile.r_tip - profile.r_form_right) + 2.0 * profile.m_n
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        try:
            make(profile, mid)
            lo = mid
        except ValueError:
            hi = mid
    return lo
