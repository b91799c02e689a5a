"""The lattice of contact cells on the pinion flank: rectangles of the developed flank, along the contact line.

An involute helicoid is the tangent developable of its base helix, so it unrolls onto a plane without
stretching: the base helix (curvature ``sin^2(beta_b) / r_b``) becomes a circle of radius
``R0 = r_b / sin^2(beta_b)``, the flank's straight generators become its tangents, and a flank point at the
distance ``lambda`` along the generator from the helix keeps that distance (Litvin & Fuentes 2004, sec. 14.3:
the transverse roll distance is ``L = lambda sin(beta_b)``, the axial position ``z = (sigma + lambda) cos(beta_b)``
up to the hand, ``sigma`` the arc length of the helix).

The contact line of a tooth at a mesh position is one generator: the pinion flank meets the plane of action
there, whatever the gear does, at ``L(z) = r_b (u_w + roll - tau z)`` (``u_w = tan(alpha_w)``, ``roll`` the
pinion's roll from the pitch point plus the tooth's pitch angles, ``tau`` the lead twist). On the developed
plane that line is straight, so a lattice of rectangles aligned with it (``ds`` across, one face slice along)
is exact: the near field tabulates over integer lattice offsets, the line keeps its place in the lattice
from one position to the next, and a long cell follows the line over its whole length. In ``(s, z)`` the line
is curved (``s = L^2 / (2 r_b)``), so a lattice straight in ``(s, z)`` mis-aligns its cells with the line by
up to a Hertz width across a wide face, and its slope jumps when it is fitted to a partly edge-bound line.

A spur flank (``beta_b = 0``) develops onto ``(z, s)`` itself; its lattice starts at the form circle, as the
tip and form circles are then parallel to the line.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["FlankLattice", "line_lattice"]


@dataclass(frozen=True)
class FlankLattice:
    """Cells of one pinion tooth at one position on the developed flank (lengths in mm).

    Cell ``(i, j)`` is centred at ``x = x_j`` (along the line, ``x_j`` of face slice ``j``) and
    ``y = y0 + i ds`` (across it), ``ds`` wide and ``length`` long. :meth:`to_flank` and :meth:`to_plane`
    map between the developed plane and the flank coordinates ``(s, z)`` (arc length from the base
    circle, axial position)."""
    ds: float
    length: float
    y0: float
    r_base: float
    flat: bool
    sin_b: float = 0.0
    cos_b: float = 1.0
    hand: float = 1.0          # z = hand (sigma + lambda) cos(beta_b)
    radius: float = np.inf     # R0 of the developed base helix
    phi: float = 0.0           # developed angle of the line's point of tangency
    lam0: float = 0.0          # lambda of the line at z = 0
    y_line: float = 0.0        # the contact line's place across (the line of a spur flank is y = s)

    def slice_x(self, zc: np.ndarray) -> np.ndarray:
        """Place along the line of the centres of face slices at axial positions ``zc``."""
        zc = np.asarray(zc, float)
        return zc if self.flat else self.hand * zc / self.cos_b

    def _frame(self):
        c, s = np.cos(self.phi), np.sin(self.phi)
        R = self.radius
        origin = np.array([R * c - self.lam0 * s, R * s + self.lam0 * c])
        return origin, np.array([-s, c]), np.array([c, s])

    def to_flank(self, x, y) -> tuple[np.ndarray, np.ndarray]:
        """Flank coordinates (s, z) of developed points (x, y); points inside the developed base helix (no
        flank) get ``s = -1``."""
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        if self.flat:
            return y.copy(), x.copy()
        o, t, n = self._frame()
        X = o[0] + x * t[0] + y * n[0]
        Y = o[1] + x * t[1] + y * n[1]
        lam2 = X * X + Y * Y - self.radius ** 2
        lam = np.sqrt(np.maximum(lam2, 0.0))
        # every point outside the developed helix lies on exactly one forward tangent: the flank point
        sigma = self.radius * (np.arctan2(Y, X) - np.arctan2(lam, self.radius))
        L = lam * self.sin_b
        z = self.hand * (sigma + lam) * self.cos_b
        return np.where(lam2 > 0, L * L / (2 * self.r_base), -1.0), z

    def to_plane(self, s, z) -> tuple[np.ndarray, np.ndarray]:
        """Developed coordinates (x, y) of flank points (s, z), s >= 0."""
        s, z = np.broadcast_arrays(np.asarray(s, float), np.asarray(z, float))
        if self.flat:
            return z.copy(), s.copy()
        lam = np.sqrt(2 * self.r_base * np.maximum(s, 0.0)) / self.sin_b
        sigma = self.hand * z / self.cos_b - lam
        a = sigma / self.radius
        X = self.radius * np.cos(a) - lam * np.sin(a)
        Y = self.radius * np.sin(a) + lam * np.cos(a)
        o, t, n = self._frame()
        return (X - o[0]) * t[0] + (Y - o[1]) * t[1], (X - o[0]) * n[0] + (Y - o[1]) * n[1]


def line_lattice(profile, roll: float, u_w: float, ds: float, dz: float, s_lo: float) -> FlankLattice:
    """The lattice of the pinion tooth whose contact line is at ``roll`` (rad from the pitch point, the tooth's
    pitch angles included) on the right flank of ``profile``; cells ``ds`` across the line and one face slice
    ``dz`` (in z) along it. ``u_w`` is tan of the working pressure angle, ``s_lo`` the arc length of the form
    circle (where a spur lattice starts)."""
    rb = profile.r_base
    tau = np.tan(profile.beta) / profile.r_ref          # lead twist: dL/dz = -r_b tau along the line
    sb, cb = abs(np.sin(profile.beta_b)), np.cos(profile.beta_b)
    if sb < 1e-9:
        L0 = rb * (u_w + roll)
        return FlankLattice(ds, dz, s_lo + 0.5 * ds, rb, True, y_line=float(np.sign(L0) * L0 * L0 / (2 * rb)))
    hand = -np.sign(tau)
    lam0 = rb * (u_w + roll) / sb
    radius = rb / sb ** 2
    return FlankLattice(ds, dz / cb, 0.0, rb, False, sb, cb, float(hand), float(radius), float(-lam0 / radius),
                        float(lam0))
