"""Head cutter of face milling: straight or curved (circular-arc) blades with a circular edge radius.

Cutter frame S_c: z along the cutter axis, origin at the cutter centre in the **tip plane** (the plane of
the blade tips, z = 0); the blades occupy z <= 0 (head body further down).  A blade point at depth
``s`` from the tip along the straight profile lies at

    rho(s) = R_p + sigma s sin(alpha),   z(s) = -s cos(alpha),

with R_p the point radius (radius of the straight profile extended to the tip plane), alpha the blade
angle and sigma = +1 for an **outside** blade (cuts the concave side of the work) or -1 for an
**inside** blade (cuts the convex side).  The unit normal out of the *work* material (into the blade) is

    n = -sigma cos(phi) e_rho - sin(phi) e_z,

phi = alpha on the straight part; on the edge radius r_f (the fillet generator) phi runs from alpha to
pi/2 (tip plane).  The edge arc is tangent to the straight profile and to the tip plane; its centre is at
z = -r_f, rho = R_p - sigma r_f (1 - sin alpha) / cos alpha (elementary plane geometry).

Profile parameter ``u`` (mm, arc length, unit speed, C1): u < 0 on the edge radius
(u = -r_f (phi - alpha)), u >= 0 on the straight part (s = s0 + u with s0 the depth of the tangency
point).  A surface point is (rho(u) cos(theta), rho(u) sin(theta), z(u)).  Litvin & Fuentes, *Gear Geometry
and Applied Theory*, 2nd ed. (2004), sec. 20.3 (blade cone surfaces), with our own parametrisation.

**Curved blade** (profile radius rho_b, the circular-arc blade of profile crowning; Litvin & Fuentes 2004,
sec. 20.3, blade surface of a torus): the profile is the circle through (R_p, 0) tangent there to the straight
profile, its centre a distance rho_b on the work side.  With s the arc length from (R_p, 0) and
phi = alpha + s / rho_b,

    rho(s) = R_p + sigma rho_b (cos(alpha) - cos(phi)),   z(s) = rho_b (sin(alpha) - sin(phi)),

normal n = -sigma cos(phi) e_rho - sin(phi) e_z as above.  The edge radius touches it (externally) and the tip
plane at phi_t with sin(phi_t) = (rho_b sin(alpha) + r_f) / (rho_b + r_f) (the two circles' centres lie
rho_b + r_f apart, the edge centre at z = -r_f); u = s - rho_b (phi_t - alpha) on the blade, u < 0 on the edge.
rho_b -> inf is the straight blade.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["HeadCutter", "CutterProfile"]

_INF = float("inf")


@dataclass(frozen=True)
class CutterProfile:
    """Axial profile of a blade at the parameters ``u``: all arrays broadcast with ``u``.

    rho, z : position in the cutter axial plane, mm;  n_rho, n_z : unit normal out of the work;
    d_rho, d_z : derivatives d(rho)/du, dz/du (unit tangent).
    """

    rho: np.ndarray
    z: np.ndarray
    n_rho: np.ndarray
    n_z: np.ndarray
    d_rho: np.ndarray
    d_z: np.ndarray


@dataclass(frozen=True)
class HeadCutter:
    """One blade family of a head cutter (a surface of revolution about the cutter axis).

    Parameters
    ----------
    point_radius : float
        R_p, mm, > 0.
    blade_angle : float
        alpha, rad, in [0, 45 deg].
    blade : str
        ``"outside"`` (generates the concave flank) or ``"inside"`` (convex flank).
    edge_radius : float
        r_f, mm, >= 0; generates the fillet.
    part : str
        ``"whole"`` (the blade), or ``"straight"``: its straight profile continued past the tangency with the
        edge radius, for every u (the whole blade is that line for u >= 0). The straight part generates a smooth
        branch of the flank, which :class:`geometry.bevel.surface_table.SurfaceTable` tabulates. For a curved
        blade ``"straight"`` is its circular arc continued likewise.
    profile_radius : float
        rho_b, mm, > 0: radius of a curved blade (centre on the work side); ``inf`` (default) a straight blade.
    """

    point_radius: float
    blade_angle: float
    blade: str = "outside"
    edge_radius: float = 0.0
    part: str = "whole"
    profile_radius: float = float("inf")

    def __post_init__(self) -> None:
        if not (self.profile_radius > 0 and not np.isnan(self.profile_radius)):
            raise ValueError(f"profile_radius = {self.profile_radius!r} is outside the allowed range (0, inf] mm")
        if self.blade not in ("outside", "inside"):
            raise ValueError(f"blade = {self.blade!r}: allowed 'outside' or 'inside'")
        if not (np.isfinite(self.point_radius) and self.point_radius > 0):
            raise ValueError(f"point_radius = {self.point_radius!r} is outside the allowed range (0, inf) mm")
        if not (0.0 <= self.blade_angle <= np.deg2rad(45.0)):
            raise ValueError(f"blade_angle = {self.blade_angle!r} is outside the allowed range [0, 0.785] rad")
        if self.part not in ("whole", "straight", "arc"):
            raise ValueError(f"part = {self.part!r}: allowed 'whole' or 'straight'")
        if not (0.0 <= self.edge_radius < 0.5 * self.point_radius):
            raise ValueError(f"edge_radius = {self.edge_radius!r} is outside the allowed range "
                             f"[0, {0.5 * self.point_radius}) mm")

    @property
    def sigma(self) -> float:
        """+1 for an outside blade, -1 for an inside blade."""
        return 1.0 if self.blade == "outside" else -1.0

    @property
    def side(self) -> str:
        """Work flank generated by this blade: ``"concave"`` (outside) or ``"convex"`` (inside)."""
        return "concave" if self.blade == "outside" else "convex"

    @property
    def curved(self) -> bool:
        """True for a curved (circular-arc) blade."""
        return self.profile_radius != _INF

    @property
    def phi_t(self) -> float:
        """Normal angle of the edge-radius tangency point, rad (alpha for a straight blade)."""
        a = self.blade_angle
        if not self.curved:
            return a
        rb, rf = self.profile_radius, self.edge_radius
        return float(np.arcsin((rb * np.sin(a) + rf) / (rb + rf)))

    @property
    def s0(self) -> float:
        """Arc length along the blade profile from (R_p, 0) to the edge-radius tangency point, mm."""
        a = self.blade_angle
        if self.curved:
            return self.profile_radius * (self.phi_t - a)
        return self.edge_radius * (1.0 - np.sin(a)) / np.cos(a)

    @property
    def u_min(self) -> float:
        """Smallest profile parameter (the edge radius meets the tip plane), mm."""
        return -self.edge_radius * (0.5 * np.pi - self.phi_t)

    def profile(self, u: np.ndarray) -> CutterProfile:
        """Blade axial profile at parameters ``u`` (mm), shape preserved; u below ``u_min`` continues
        the tip plane, so Newton iterates stay defined."""
        u = np.asarray(u, dtype=float)
        if self.curved:
            return self._curved_profile(u)
        a, sg, rf = self.blade_angle, self.sigma, self.edge_radius
        sa, ca = np.sin(a), np.cos(a)
        # straight part
        s = self.s0 + u
        rho_s, z_s = self.point_radius + sg * s * sa, -s * ca
        if rf == 0.0 or self.part == "straight":
            one = np.ones_like(u)
            return CutterProfile(rho_s, z_s, -sg * ca * one, -sa * one, sg * sa * one, -ca * one)
        # edge arc: phi = alpha - u / r_f, point = centre - r_f n (n = work normal)
        rho_c = self.point_radius - sg * rf * (1.0 - sa) / ca
        phi = a - u / rf if self.part == "arc" else np.clip(a - u / rf, a, 0.5 * np.pi)
        n_rho_a, n_z_a = -sg * np.cos(phi), -np.sin(phi)
        rho_a, z_a = rho_c - rf * n_rho_a, -rf - rf * n_z_a
        # tangent d/du of the arc = -(1/rf) d/dphi (centre - rf n) = -(dn/dphi) = (-sg sin phi, cos phi)*(-1)
        d_rho_a, d_z_a = sg * np.sin(phi), -np.cos(phi)
        if self.part == "arc":
            return CutterProfile(rho_a, z_a, n_rho_a, n_z_a, d_rho_a, d_z_a)
        # beyond the tip: continue along the tip plane (normal -e_z)
        beyond = u < self.u_min
        rho_a = np.where(beyond, rho_c + sg * (u - self.u_min), rho_a)
        on_arc = u < 0.0
        return CutterProfile(np.where(on_arc, rho_a, rho_s), np.where(on_arc, z_a, z_s),
                             np.where(on_arc, n_rho_a, -sg * ca), np.where(on_arc, n_z_a, -sa),
                             np.where(on_arc, d_rho_a, sg * sa), np.where(on_arc, d_z_a, -ca))

    def _curved_profile(self, u: np.ndarray) -> CutterProfile:
        """:meth:`profile` of a curved blade (module docstring)."""
        a, sg, rf, rb = self.blade_angle, self.sigma, self.edge_radius, self.profile_radius
        pt = self.phi_t
        ph = a + (self.s0 + u) / rb
        rho_s = self.point_radius + sg * rb * (np.cos(a) - np.cos(ph))
        z_s = rb * (np.sin(a) - np.sin(ph))
        blade = CutterProfile(rho_s, z_s, -sg * np.cos(ph), -np.sin(ph), sg * np.sin(ph), -np.cos(ph))
        if rf == 0.0 or self.part == "straight":
            return blade
        # edge centre: tangency point + r_f n(phi_t) (inside the blade), at z = -r_f
        rho_c = self.point_radius + sg * rb * (np.cos(a) - np.cos(pt)) - sg * rf * np.cos(pt)
        phi = pt - u / rf if self.part == "arc" else np.clip(pt - u / rf, pt, 0.5 * np.pi)
        n_rho_a, n_z_a = -sg * np.cos(phi), -np.sin(phi)
        rho_a, z_a = rho_c - rf * n_rho_a, -rf - rf * n_z_a
        d_rho_a, d_z_a = sg * np.sin(phi), -np.cos(phi)
        if self.part == "arc":
            return CutterProfile(rho_a, z_a, n_rho_a, n_z_a, d_rho_a, d_z_a)
        beyond = u < self.u_min
        rho_a = np.where(beyond, rho_c + sg * (u - self.u_min), rho_a)
        on_arc = u < 0.0
        return CutterProfile(*(np.where(on_arc, e, b) for e, b in zip(
            (rho_a, z_a, n_rho_a, n_z_a, d_rho_a, d_z_a),
            (blade.rho, blade.z, blade.n_rho, blade.n_z, blade.d_rho, blade.d_z))))

    def surface(self, u: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Points and unit work-outward normals of the cutter surface in S_c.

        Parameters
        ----------
        u, theta : ndarray, broadcastable
            Profile parameter (mm) and angle about the cutter axis (rad).

        Returns
        -------
        r, n : ndarray, shape broadcast(u, theta) + (3,)
        """
        p = self.profile(u)
        c, s = np.cos(theta), np.sin(theta)
        r = np.stack(np.broadcast_arrays(p.rho * c, p.rho * s, p.z), axis=-1)
        n = np.stack(np.broadcast_arrays(p.n_rho * c, p.n_rho * s, p.n_z), axis=-1)
        return r, n

    def u_at_depth(self, depth: np.ndarray) -> np.ndarray:
        """Profile parameter of the blade point at ``depth`` (mm, >= 0) below the tip plane."""
        depth = np.asarray(depth, dtype=float)
        rf, a = self.edge_radius, self.blade_angle
        if self.curved:
            rb, pt = self.profile_radius, self.phi_t
            zt = rf * (1.0 - np.sin(pt))
            u_arc = rb * (np.arcsin(np.clip(np.sin(a) + depth / rb, -1.0, 1.0)) - a) - self.s0
            if rf == 0.0:
                return u_arc
            ph = np.arcsin(np.clip(1.0 - depth / rf, np.sin(pt), 1.0))
            return np.where(depth >= zt, u_arc, -rf * (ph - pt))
        zt = rf * (1.0 - np.sin(a))                       # depth of the tangency point
        u_line = depth / np.cos(a) - self.s0
        if rf == 0.0:
            return u_line
        # on the arc: depth = rf (1 - sin(phi))  ->  phi = asin(1 - depth/rf)
        ph = np.arcsin(np.clip(1.0 - depth / rf, np.sin(a), 1.0))
        return np.where(depth >= zt, u_line, -rf * (ph - a))
