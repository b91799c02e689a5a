"""Rigid kinematics of the satellite inside the central wheel, and the distances between their outlines.

Frame (transverse, spur): satellite centre O1 at the origin, wheel centre O2 at (0, -e), so the mesh is on
+y (as :mod:`ltca.geometry.pair` places an internal pair). Angles counter-clockwise positive. At position
``phi`` (rad of satellite rotation, clockwise) the satellite is turned by ``-phi + delta`` and the wheel by
``-phi z1/z2 + pi/z2`` (a wheel SPACE on +y at phi = 0; both turn the same way, as an internal pair does).
``delta = 0`` is the symmetric placement (satellite tooth 0 centred in the wheel space on the line of
centres); ``delta = -beta``, ``beta = j_t / (2 r_w1)``, closes half the circumferential backlash
``j_t = e2(r_w2) - s1(r_w1)`` (arcs on the working pitch circles, analytic involutes; ISO 21771 sec. 5)
and puts the right flanks (the satellite's clockwise-leading side) of the mesh pair in involute contact
along the line of action, ``+beta`` the left flanks.

The configuration repeats after one satellite pitch 2 pi / z1 with every tooth label advanced by one,
and all z1 satellite teeth are evaluated at every position, so one pitch of ``phi`` covers every tooth pair
of the whole revolution.

Both outlines are sampled (:func:`ltca.geometry.outline.resample_outline`, corners kept) and each point is
measured against the other gear's whole outline (:class:`ltca.geometry.outline.GearOutline`). ``rate`` is how
fast (mm per rad of satellite rotation in the closing sense ``d``, the wheel held) the distance would
shrink, so ``distance / rate`` is the rotation that closes it (first order).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..outline import GearOutline, resample_outline, rotate
from ..profile import ToothProfile

__all__ = ["EccentricMesh", "MeshSample", "Window"]


@dataclass(frozen=True)
class MeshSample:
    """Distances at one position, for satellite points against the wheel (``src`` 0) and wheel points
    against the satellite (``src`` 1); only points within ``cap`` mm of the other gear's tooth band.

    distance (mm, < 0 penetration), rate (mm/rad), pair (satellite tooth, signed label in [-z1/2, z1/2),
    0 at the mesh at phi = 0), wheel_tooth, kind1 / side1 (satellite outline kind and flank side),
    kind2 / side2 (wheel), r1 (radius on the satellite, mm), r2 (radius on the wheel, mm).
    """

    src: np.ndarray
    distance: np.ndarray
    rate: np.ndarray
    pair: np.ndarray
    wheel_tooth: np.ndarray
    kind1: np.ndarray
    side1: np.ndarray
    kind2: np.ndarray
    side2: np.ndarray
    r1: np.ndarray
    r2: np.ndarray


@dataclass(frozen=True)
class Window:
    """The satellite rotations (rad, from the symmetric placement, counter-clockwise +) free of overlap
    at one position, and what limits them.

    drive : the clockwise limit (right flanks touch), <= 0 when free;  coast : the counter-clockwise limit.
    free_play : coast - drive (< 0: no placement is free, the teeth jam).
    drive_gap, coast_gap : (z1,) rad, further rotation past each limit until satellite tooth (pair label
    index + z1/2) touches in that direction (0 for the limiting pair; inf where nothing is met).
    drive_at, coast_at : dict of the limiting contact: pair, wheel_tooth, r1 (on the satellite), r2 (on the
    wheel), kind2 / side2 (wheel outline kind and side at the wheel point).
    """

    drive: float
    coast: float
    free_play: float
    drive_gap: np.ndarray
    coast_gap: np.ndarray
    drive_at: dict
    coast_at: dict


class EccentricMesh:
    """Satellite (external :class:`ToothProfile`) inside the wheel (internal) at centre distance ``e``.

    Parameters
    ----------
    satellite, wheel : ToothProfile   generated outlines (any method; analytic involutes for the backlash).
    e : float                         centre distance (eccentricity), mm.
    spacing : float                   sampling of the outlines for the distance queries, mm.
    """

    def __init__(self, satellite: ToothProfile, wheel: ToothProfile, e: float, spacing: float = 0.02):
        if satellite.internal or not wheel.internal:
            raise ValueError("EccentricMesh: satellite must be external and wheel internal")
        if wheel.z - satellite.z < 1:
            raise ValueError(f"wheel.z - satellite.z = {wheel.z - satellite.z}: allowed >= 1 (the satellite "
                             f"cannot be assembled inside the wheel)")
        self.sat, self.wheel, self.e = satellite, wheel, float(e)
        self.z1, self.z2 = int(satellite.z), int(wheel.z)
        c = (wheel.r_base - satellite.r_base) / self.e
        if not 0 < c < 1:
            raise ValueError(f"e = {e!r} mm: no involute mesh (cos alpha_w = {c:.6f} must be in (0, 1))")
        self.alpha_w = float(np.arccos(c))
        self.r_w1, self.r_w2 = satellite.r_base / c, wheel.r_base / c
        s1 = float(satellite.thickness_at(self.r_w1))
        e2 = 2 * np.pi * self.r_w2 / self.z2 - float(wheel.thickness_at(self.r_w2))
        self.backlash = e2 - s1                                   # circumferential, on the working circles
        self.beta = 0.5 * self.backlash / self.r_w1
        self.ol1, self.ol2 = GearOutline(satellite), GearOutline(wheel)
        self.p1, self.kind_p1, self.side_p1, self.tooth_p1 = self._all_teeth(satellite, spacing)
        self.p2, self.kind_p2, self.side_p2, self.tooth_p2 = self._all_teeth(wheel, spacing)

    @staticmethod
    def _all_teeth(profile, spacing):
        xy, kind, side = resample_outline(profile, spacing)
        z = int(profile.z)
        k = np.repeat(np.arange(z), len(xy))
        pts = rotate(np.tile(xy, (z, 1)), -k * 2 * np.pi / z)     # tooth k turned clockwise
        return pts, np.tile(kind, z), np.tile(side, z), k

    def angles(self, phi: float, delta: float = 0.0):
        """Body rotations (theta1, theta2), rad counter-clockwise, at position phi, satellite turned by delta
        more (0: the symmetric placement; ``-beta`` / ``+beta``: right / left flanks in involute contact)."""
        return -phi + delta, -phi * self.z1 / self.z2 + np.pi / self.z2

    def _label(self, k):
        return (np.asarray(k) + self.z1 // 2) % self.z1 - self.z1 // 2

    def sample(self, phi: float, delta: float = 0.0, direction: int = 1, cap: float = 1.0,
               only_inside: bool = False) -> MeshSample:
        """Distances and closing rates of both outlines at position ``phi``, satellite turned by ``delta``.

        ``direction`` +1: rates for a clockwise satellite rotation (closes the right flanks), -1 the other
        way. ``cap`` (mm): points farther than this outside the other gear's tip circle are skipped;
        ``only_inside``: only points inside the other gear's material (penetrations), the cheap test first.
        """
        if direction not in (-1, 1):
            raise ValueError(f"direction = {direction!r}: allowed +1 (clockwise, right flanks) or -1")
        t1, t2 = self.angles(phi, delta)
        O2 = np.array([0.0, -self.e])
        # satellite points -> wheel (wheel body frame)
        w1 = rotate(self.p1, t1)
        b1 = rotate(w1 - O2, -t2)
        keep1 = np.hypot(b1[:, 0], b1[:, 1]) >= self.wheel.r_tip - cap
        if only_inside:
            keep1[keep1] = self.ol2.contains(b1[keep1])
        q1 = self.ol2.query(b1[keep1])
        u1 = rotate(q1.direction, t2)
        v1 = direction * np.stack([w1[keep1, 1], -w1[keep1, 0]], axis=1)
        rate1 = -np.einsum("ij,ij->i", u1, v1)
        # wheel points -> satellite (satellite body frame)
        b2 = rotate(rotate(self.p2, t2) + O2, -t1)
        keep2 = np.hypot(b2[:, 0], b2[:, 1]) <= self.sat.r_tip + cap
        if only_inside:
            keep2[keep2] = self.ol1.contains(b2[keep2])
        q2 = self.ol1.query(b2[keep2])
        F = rotate(q2.foot, t1)
        u2 = rotate(q2.direction, t1)
        rate2 = direction * np.einsum("ij,ij->i", u2, np.stack([F[:, 1], -F[:, 0]], axis=1))
        n1, n2 = int(keep1.sum()), int(keep2.sum())
        cat = np.concatenate
        return MeshSample(
            src=cat([np.zeros(n1, np.int8), np.ones(n2, np.int8)]),
            distance=cat([q1.distance, q2.distance]), rate=cat([rate1, rate2]),
            pair=self._label(cat([self.tooth_p1[keep1], q2.tooth])),
            wheel_tooth=cat([q1.tooth, self.tooth_p2[keep2]]),
            kind1=cat([self.kind_p1[keep1], q2.kind]), side1=cat([self.side_p1[keep1], q2.side]),
            kind2=cat([q1.kind, self.kind_p2[keep2]]), side2=cat([q1.side, self.side_p2[keep2]]),
            r1=cat([np.hypot(*self.p1[keep1].T), q2.foot_radius]),
            r2=cat([q1.foot_radius, np.hypot(*self.p2[keep2].T)]))

    def window(self, phi: float) -> Window:
        """Exact overlap-free rotation window of the satellite at position ``phi`` (:class:`Window`).

        A wheel outline point at polar radius rho and clockwise angle ``a`` from the nearest satellite tooth
        centre (satellite frame, symmetric placement) lies in that tooth for satellite rotations
        ``delta in [-a - h(rho), -a + h(rho)]`` (h: :meth:`GearOutline.material_half_angle`): turning the
        satellite about its own axis is a shift of its polar angle, so this is exact. Intervals centred
        below 0 (points on the clockwise side of their tooth) stop a clockwise turn, the others a
        counter-clockwise one; the neighbouring teeth's copies (centre +- pitch) are included. If two gears
        overlap, the wheel's outline enters the satellite, so testing the wheel's points suffices (to the
        sampling: a satellite corner can hide between two wheel points by < spacing / 2).
        """
        t1, t2 = self.angles(phi, 0.0)
        b = rotate(rotate(self.p2, t2) + np.array([0.0, -self.e]), -t1)
        rho = np.hypot(b[:, 0], b[:, 1])
        h = self.ol1.material_half_angle(rho)
        sel = h > 0
        b, rho, h = b[sel], rho[sel], h[sel]
        p1 = 2 * np.pi / self.z1
        cw = np.arctan2(b[:, 0], b[:, 1])
        k0 = np.round(cw / p1).astype(int)
        c = -(cw - k0 * p1)
        j = np.array([-1, 0, 1])
        cs = c[:, None] + j * p1                                  # (n, 3) centres of tooth k0 + j
        tooth = self._label(k0[:, None] + j)
        hi = np.where(cs < 0, cs + h[:, None], -np.inf)
        lo = np.where(cs >= 0, cs - h[:, None], np.inf)
        i_d, i_c = np.unravel_index(np.argmax(hi), hi.shape), np.unravel_index(np.argmin(lo), lo.shape)
        drive, coast = float(hi[i_d]), float(lo[i_c])
        dgap, cgap = np.full(self.z1, np.inf), np.full(self.z1, np.inf)
        np.minimum.at(dgap, (tooth + self.z1 // 2).ravel(), (drive - hi).ravel())
        np.minimum.at(cgap, (tooth + self.z1 // 2).ravel(), (lo - coast).ravel())
        w_idx = np.nonzero(sel)[0]

        def at(ij):
            i = w_idx[ij[0]]
            return dict(pair=int(tooth[ij]), wheel_tooth=int(self.tooth_p2[i]), r1=float(rho[ij[0]]),
                        r2=float(np.hypot(*self.p2[i])), kind2=int(self.kind_p2[i]), side2=int(self.side_p2[i]))
        return Window(drive=drive, coast=coast, free_play=coast - drive, drive_gap=dgap, coast_gap=cgap,
                      drive_at=at(i_d), coast_at=at(i_c))
