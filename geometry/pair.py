"""Assembly of a cylindrical gear pair and its separation field.

World frame: pinion axis = world z axis through the origin; the pinion's tooth 0 points to +y at
pinion rotation 0. The gear centre is at (0, a) for an external pair and at (0, -a) for an internal
one (the ring surrounds the pinion), so that the mesh is near (0, r_w1) in both cases.
The pinion drives **clockwise** seen from +z with its right flank (side +1); the gear turns the other
way (external) or the same way (internal). Rotation angles are measured positive counter-clockwise.

The separation of a pinion flank point from the gear is the signed distance of that point to the
gear's transverse tooth outline (after undoing the gear's rotation, helix and tooth index), times
cos(beta_b) to turn the transverse distance into the distance along the 3D normal of the involute
helicoid. Because the outline includes fillet, tip arc and the tip corner, edge contact of the gear
tip on the pinion flank comes out of the same distance (to the corner vertex).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

__all__ = ["CylindricalPair", "Separation", "rotation_z", "axis_rotation"]


def rotation_z(angle: float) -> np.ndarray:
    """4x4 homogeneous rotation about +z by ``angle`` (rad, counter-clockwise)."""
    c, s = np.cos(angle), np.sin(angle)
    T = np.eye(4)
    T[:2, :2] = [[c, -s], [s, c]]
    return T


def axis_rotation(axis: np.ndarray, angle: float, pivot: np.ndarray) -> np.ndarray:
    """4x4 rotation by ``angle`` about the unit ``axis`` through ``pivot`` (Rodrigues' formula)."""
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    R = np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K
    T = np.eye(4)
    T[:3, :3] = R
    T[:3, 3] = pivot - R @ pivot
    return T


@dataclass(frozen=True)
class Separation:
    """Gaps of pinion flank points against the gear at one mesh position (all arrays broadcast alike).

    gap : mm along the normal, > 0 open; +inf where the point faces no gear flank.
    lever1 : mm, approach per rad of pinion rotation in the driving direction (> 0 on the driving flank).
    lever2 : mm, gear torque per unit normal force, about the gear axis.
    gear_tooth : int, gear tooth index; gear_r, gear_z : where on the gear (radius, axial position);
    gear_side : int8 side label (-1/+1) of the nearest gear outline point; gear_kind : its kind code.
    points, normals : (..., 3) the pinion flank points and outward normals in the world frame.
    """
    gap: np.ndarray
    lever1: np.ndarray
    lever2: np.ndarray
    gear_tooth: np.ndarray
    gear_r: np.ndarray
    gear_z: np.ndarray
    gear_side: np.ndarray
    gear_kind: np.ndarray
    points: np.ndarray
    normals: np.ndarray


class CylindricalPair:
    """A pinion and a gear (external or internal) placed at a centre distance, with misalignments.

    Parameters
    ----------
    pinion, gear : geometry.involute.ToothProfile
        Transverse profiles. ``gear.internal`` selects an internal pair. Their helix signs must be
        consistent (opposite hands for external pairs, the same hand for internal ones).
    centre_distance : float
        mm.
    face_width : float
        Common (contact) face width, mm, centred on z = 0 for both members.
    misalignment : float
        Lead misalignment in the plane of action, mm over ``face_width`` (rotation of the gear axis
        about the normal of the plane of action through the pitch point).
    deviation : float
        Axis deviation normal to the plane of action, mm over ``face_width``.
    """

    def __init__(self, pinion, gear, centre_distance: float, face_width: float,
                 misalignment: float = 0.0, deviation: float = 0.0):
        self.pinion, self.gear = pinion, gear
        self.gear_face_width = float(face_width)
        self.a, self.b = float(centre_distance), float(face_width)
        self.internal = bool(gear.internal)
        self.ratio = gear.z / pinion.z
        self.centre2 = np.array([0.0, -self.a if self.internal else self.a, 0.0])
        self.twist1 = np.tan(pinion.beta) / pinion.r_ref
        self.twist2 = np.tan(gear.beta) / gear.r_ref
        self.cos_bb = np.cos(pinion.beta_b)
        # working pressure angle and pitch radius (transverse)
        rb1, rb2 = pinion.r_base, gear.r_base
        self.alpha_w = np.arccos((rb2 - rb1) / self.a) if self.internal else np.arccos((rb1 + rb2) / self.a)
        self.r_w1 = rb1 / np.cos(self.alpha_w)
        # line-of-action direction at the pitch point for the right pinion flank driving clockwise: the
        # outward normal of that flank at the pitch point (0, r_w1), tangent to the base circle
        self.n_loa = np.array([np.cos(self.alpha_w), np.sin(self.alpha_w), 0.0])
        pivot = np.array([0.0, self.r_w1, 0.0])
        u = np.cross(self.n_loa, [0.0, 0.0, 1.0])
        self.T_mis = (axis_rotation(u, -misalignment / self.b, pivot)
                      @ axis_rotation(self.n_loa, deviation / self.b, pivot))
        xy = np.asarray(gear.xy, float)
        self._seg = np.diff(xy, axis=0)
        self._seglen2 = np.einsum("ij,ij->i", self._seg, self._seg)
        self._xy = xy
        self._tree = cKDTree(xy)
        self._out_sign = -1.0 if self.internal else 1.0
        self.phi2_0 = 0.0
        self.phi2_0 = self._calibrate()

    # ------------------------------------------------------------------ placement
    def gear_frame(self, phi1: float) -> np.ndarray:
        """4x4 transform gear body frame -> world at pinion rotation ``phi1`` (rigid, kinematic)."""
        sign = 1.0 if self.internal else -1.0
        base = 0.0 if self.internal else np.pi
        phi2 = base + np.pi / self.gear.z + self.phi2_0 + sign * phi1 / self.ratio
        T = np.eye(4)
        T[:3, 3] = self.centre2
        return self.T_mis @ T @ rotation_z(phi2)

    # ------------------------------------------------------------------ distance to outline
    def _signed_distance(self, q: np.ndarray):
        """Signed transverse distance of 2D points q (n, 2) to the gear's tooth outline (tooth 0)."""
        _, idx = self._tree.query(q)
        nseg = len(self._seg)
        best = np.full(len(q), np.inf)
        foot = np.zeros((len(q), 2))
        segi = np.zeros(len(q), int)
        for off in (-1, 0):
            s = np.clip(idx + off, 0, nseg - 1)
            d = self._seg[s]
            t = np.clip(np.einsum("ij,ij->i", q - self._xy[s], d) / self._seglen2[s], 0.0, 1.0)
            c = self._xy[s] + t[:, None] * d
            dist = np.linalg.norm(q - c, axis=1)
            better = dist < best
            best = np.where(better, dist, best)
            foot[better] = c[better]
            segi = np.where(better, s, segi)
        # sign from the pseudo-normal at the foot (average of adjacent segment normals at vertices)
        d = self._seg[segi]
        nrm = np.stack([-d[:, 1], d[:, 0]], 1) * self._out_sign
        nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
        nxt = np.clip(segi + 1, 0, nseg - 1)
        d2 = self._seg[nxt]
        n2 = np.stack([-d2[:, 1], d2[:, 0]], 1) * self._out_sign
        n2 /= np.linalg.norm(n2, axis=1, keepdims=True)
        at_end = np.linalg.norm(foot - self._xy[segi + 1], axis=1) < 1e-12
        nrm = np.where(at_end[:, None], nrm + n2, nrm)
        sgn = np.sign(np.einsum("ij,ij->i", q - foot, nrm))
        sgn[sgn == 0] = 1.0
        nrm /= np.linalg.norm(nrm, axis=1, keepdims=True)
        return best * sgn, foot, segi, nrm

    def _signed_distance_rows(self, q: np.ndarray, shape: tuple[int, ...]):
        """:meth:`_signed_distance` of the points q (n, 2) of a grid ``shape`` (n = prod(shape)), once per row of
        the grid's last axis when q does not change along it: a spur pair's flank grid (profile x face) meets the
        gear in the same transverse points at every axial position. The results are the same, row by row."""
        if len(shape) < 2 or shape[-1] < 2:
            return self._signed_distance(q)
        grid = q.reshape(-1, shape[-1], 2)
        if not (grid == grid[:, :1]).all():
            return self._signed_distance(q)
        return tuple(np.repeat(a, shape[-1], axis=0) for a in self._signed_distance(grid[:, 0]))

    def separation(self, phi1: float, points: np.ndarray, normals: np.ndarray, side: int = 1) -> Separation:
        """Separation of pinion flank points (pinion frame, (..., 3)) at pinion rotation ``phi1``.

        ``side`` +1: the right (drive) flank, closed by a clockwise pinion rotation; -1: the left
        (coast) flank, closed by a counter-clockwise one. ``lever1`` is per rad in that sense."""
        shape = points.shape[:-1]
        R1 = rotation_z(phi1)
        P = points.reshape(-1, 3) @ R1[:3, :3].T
        N = normals.reshape(-1, 3) @ R1[:3, :3].T
        Tg = self.gear_frame(phi1)
        Tinv = np.linalg.inv(Tg)
        Q = P @ Tinv[:3, :3].T + Tinv[:3, 3]
        # undo the helix, then the tooth index (tooth k sits at clockwise angle k * 2 pi / z)
        ang = -self.twist2 * Q[:, 2]
        c, s = np.cos(ang), np.sin(ang)
        x = c * Q[:, 0] - s * Q[:, 1]
        y = s * Q[:, 0] + c * Q[:, 1]
        pitch = 2 * np.pi / self.gear.z
        k = np.round(np.arctan2(x, y) / pitch).astype(int)
        c, s = np.cos(k * pitch), np.sin(k * pitch)
        q = np.stack([c * x - s * y, s * x + c * y], 1)
        dist, foot, segi, nrm2 = self._signed_distance_rows(q, shape)
        gap = dist * self.cos_bb
        face = np.abs(Q[:, 2]) <= 0.5 * self.gear_face_width + 1e-9
        gap = np.where(face, gap, np.inf)
        # the drive flank closes under a clockwise rotation (velocity -ez x P per rad), the coast flank
        # under a counter-clockwise one
        v = -side * np.cross([0.0, 0.0, 1.0], P)
        lever1 = np.einsum("ij,ij->i", v, N)
        side = np.asarray(self.gear.side)[np.clip(segi, 0, len(self._xy) - 1)]
        kind = np.asarray(self.gear.kind)[np.clip(segi, 0, len(self._xy) - 1)]
        # the gear's lever arm from its own normal at the foot point: exactly r_b2 cos(beta_b) on the
        # involute (the normal is tangent to the base circle), the outline normal elsewhere (edges)
        lever2 = np.abs(foot[:, 0] * nrm2[:, 1] - foot[:, 1] * nrm2[:, 0]) * self.cos_bb
        lever2 = np.where(kind == 2, self.gear.r_base * self.cos_bb, lever2)
        r2 = np.linalg.norm(foot, axis=1)
        rs = lambda a: a.reshape(shape)
        return Separation(rs(gap), rs(lever1), rs(np.abs(lever2)), rs(k), rs(r2), rs(Q[:, 2]), rs(side),
                          rs(kind), P.reshape(shape + (3,)), N.reshape(shape + (3,)))

    # ------------------------------------------------------------------ calibration
    def _calibrate(self) -> float:
        """Gear angle offset that makes the unmodified drive flanks touch at phi1 = 0."""
        from .cylindrical import flank_point_normal
        r1 = np.linspace(self.r_w1 - 0.3 * (self.r_w1 - self.pinion.r_base), self.r_w1 +
                         0.5 * (self.pinion.r_tip - self.r_w1), 400)
        offset = 0.0
        for _ in range(6):
            P, N = flank_point_normal(self.pinion, +1, r1, np.zeros_like(r1), 0)
            self.phi2_0 = offset
            s = self.separation(0.0, P, N)
            g = np.where(np.isfinite(s.gap), s.gap, np.inf)
            i = np.argmin(g)
            # a gear rotation d(phi2) towards the pinion flank closes the gap by lever2 * d(phi2)
            step = g[i] / s.lever2[i]
            offset += step if self.internal else -step
            if abs(g[i]) < 1e-12:
                break
        return offset
