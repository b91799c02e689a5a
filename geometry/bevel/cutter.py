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

**Toprem and flankrem** (blended): below the depth h_t from the tip plane the blade continues, towards the tip,
as an arc of radius rho_t tangent to it (toprem), and below the depth h_f as an arc of radius rho_f
(flankrem), both centred on the work side; the edge radius then touches the toprem arc.  Each piece is an arc
of constant curvature kappa in the arc length u (kappa = 1/rho, 0 on a straight piece), the normal angle
phi = phi_0 + kappa (u - u_0), so the blade profile is one G1 chain: edge - toprem - blade - flankrem.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .surface_state import _vectors

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
        branch of the flank, which :class:`ltca.geometry.bevel.surface_table.SurfaceTable` tabulates. For a curved
        blade ``"straight"`` is its circular arc continued likewise.
    profile_radius : float
        rho_b, mm, > 0: radius of a curved blade (centre on the work side); ``inf`` (default) a straight blade.
    toprem_depth, toprem_radius, flankrem_depth, flankrem_radius : float
        Blended toprem and flankrem (module docstring): depth below the tip plane where the modification starts
        (mm; 0 = none) and its radius (mm, > 0).
    """

    point_radius: float
    blade_angle: float
    blade: str = "outside"
    edge_radius: float = 0.0
    part: str = "whole"
    profile_radius: float = float("inf")
    toprem_depth: float = 0.0
    toprem_radius: float = float("inf")
    flankrem_depth: float = 0.0
    flankrem_radius: float = float("inf")

    def __post_init__(self) -> None:
        for name in ("toprem", "flankrem"):
            h, r = getattr(self, f"{name}_depth"), getattr(self, f"{name}_radius")
            if not (0.0 <= h < 1e3) or (h > 0 and not (0.0 < r < 1e7)):
                raise ValueError(f"{name}_depth, {name}_radius = {h!r}, {r!r} are outside the allowed range: depth "
                                 "in [0, 1000) mm, radius in (0, 1e7) mm when the depth is > 0")
        if self.toprem_depth and self.flankrem_depth and self.flankrem_depth <= self.toprem_depth:
            raise ValueError(f"flankrem_depth = {self.flankrem_depth!r} is outside the allowed range: deeper than "
                             f"toprem_depth = {self.toprem_depth!r} mm")
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
    def general(self) -> bool:
        """True when the profile is a chain of arcs (curved blade, toprem or flankrem), not the straight blade."""
        return self.profile_radius != _INF or bool(self.toprem_depth) or bool(self.flankrem_depth)

    @property
    def chain(self) -> tuple[np.ndarray, ...]:
        """Pieces of the profile below the edge radius (module docstring): arrays (u0, phi0, rho0, z0, kappa) of
        each piece's start, in order from the tip."""
        c = self.__dict__.get("_chain")
        if c is None:
            c = self._build_chain()
            object.__setattr__(self, "_chain", c)
        return c

    def _build_chain(self) -> tuple[np.ndarray, ...]:
        a, sg, rf = self.blade_angle, self.sigma, self.edge_radius
        kb = 0.0 if not self.curved else 1.0 / self.profile_radius

        def walk(p, k, s):                       # point (phi, rho, z) after arc length s on a piece of curvature k
            phi, rho, z = p
            if k == 0.0:
                return phi, rho + sg * np.sin(phi) * s, z - np.cos(phi) * s
            ph = phi + k * s
            return ph, rho + sg * (np.cos(phi) - np.cos(ph)) / k, z - (np.sin(ph) - np.sin(phi)) / k

        def at_depth(p, k, h):                   # arc length from p to the depth h on a piece of curvature k
            phi, _, z = p
            if k == 0.0:
                return (z + h) / np.cos(phi)
            return (np.arcsin(np.clip(np.sin(phi) + k * (z + h), -1.0, 1.0)) - phi) / k

        ref = (a, self.point_radius, 0.0)        # the blade through (R_p, 0) at the blade angle
        pieces = []                              # (reference point, curvature) from the tip down
        if self.toprem_depth:
            p1 = walk(ref, kb, at_depth(ref, kb, self.toprem_depth))
            pieces.append((p1, 1.0 / self.toprem_radius))
        pieces.append((ref, kb))
        # edge tangency on the top piece: sin(phi_e) = (r_f + C_z) / (r_f + rho), C its centre
        (pr, k) = pieces[0]
        if k == 0.0:
            ph_e = pr[0]
        else:
            cz = pr[2] + np.sin(pr[0]) / k
            ph_e = float(np.arcsin((rf + cz) / (rf + 1.0 / k)))
        e = walk(pr, k, (ph_e - pr[0]) / k) if k else walk(pr, 0.0, at_depth(pr, 0.0, rf * (1 - np.sin(ph_e))))
        starts = [(0.0, e, k)]
        if self.toprem_depth:
            p1 = pieces[0][0]
            starts.append((starts[0][0] + (p1[0] - e[0]) / k, p1, kb))
        if self.flankrem_depth:
            u0, p0, k0 = starts[-1]
            s2 = at_depth(p0, k0, self.flankrem_depth)
            starts.append((u0 + s2, walk(p0, k0, s2), 1.0 / self.flankrem_radius))
        return tuple(np.array(v, dtype=float) for v in (
            [q[0] for q in starts], [q[1][0] for q in starts], [q[1][1] for q in starts],
            [q[1][2] for q in starts], [q[2] for q in starts]))

    @property
    def phi_t(self) -> float:
        """Normal angle of the edge-radius tangency point, rad (alpha for a straight blade)."""
        if not self.general:
            return self.blade_angle
        return float(self.chain[1][0])

    @property
    def s0(self) -> float:
        """Arc length along the straight blade profile from (R_p, 0) to the edge-radius tangency point, mm."""
        a = self.blade_angle
        return self.edge_radius * (1.0 - np.sin(a)) / np.cos(a)

    @property
    def u_min(self) -> float:
        """Smallest profile parameter (the edge radius meets the tip plane), mm."""
        return -self.edge_radius * (0.5 * np.pi - self.phi_t)

    def profile(self, u: np.ndarray) -> CutterProfile:
        """Blade axial profile at parameters ``u`` (mm), shape preserved; u below ``u_min`` continues
        the tip plane, so Newton iterates stay defined."""
        u = np.asarray(u, dtype=float)
        if self.general:
            return self._chain_profile(u)
        a, sg, rf, sa, ca, s0, rho_c, u_min = self._straight_constants()
        # straight part
        s = s0 + u
        rho_s, z_s = self.point_radius + sg * s * sa, -s * ca
        straight = rf == 0.0 or self.part == "straight"
        if straight or (self.part == "whole" and not (u < 0.0).any()):
            normal_tangent = np.empty((4,) + u.shape)            # n_rho, n_z, d_rho, d_z: constant
            normal_tangent.reshape(4, -1)[:] = self._straight_directions
            return CutterProfile(rho_s, z_s, *normal_tangent)
        # edge arc: phi = alpha - u / r_f, point = centre - r_f n (n = work normal)
        phi = a - u / rf if self.part == "arc" else np.minimum(np.maximum(a - u / rf, a), 0.5 * np.pi)
        cos_phi, sin_phi = np.cos(phi), np.sin(phi)
        n_rho_a, n_z_a = -sg * cos_phi, -sin_phi
        rho_a, z_a = rho_c - rf * n_rho_a, -rf - rf * n_z_a
        # tangent d/du of the arc = -(1/rf) d/dphi (centre - rf n) = -(dn/dphi) = (-sg sin phi, cos phi)*(-1)
        d_rho_a, d_z_a = sg * sin_phi, -cos_phi
        if self.part == "arc":
            return CutterProfile(rho_a, z_a, n_rho_a, n_z_a, d_rho_a, d_z_a)
        # beyond the tip: continue along the tip plane (normal -e_z)
        beyond = u < u_min
        rho_a = np.where(beyond, rho_c + sg * (u - u_min), rho_a)
        on_arc = u < 0.0
        return CutterProfile(np.where(on_arc, rho_a, rho_s), np.where(on_arc, z_a, z_s),
                             np.where(on_arc, n_rho_a, -sg * ca), np.where(on_arc, n_z_a, -sa),
                             np.where(on_arc, d_rho_a, sg * sa), np.where(on_arc, d_z_a, -ca))

    def _straight_constants(self) -> tuple[float, ...]:
        """(alpha, sigma, r_f, sin alpha, cos alpha, s0, edge-centre radius, u_min) of the straight blade, computed
        once: :meth:`profile` runs at every evaluation of a generated surface."""
        c = self.__dict__.get("_straight")
        if c is None:
            a, sg, rf = self.blade_angle, self.sigma, self.edge_radius
            sa, ca = np.sin(a), np.cos(a)
            c = (a, sg, rf, sa, ca, self.s0, self.point_radius - sg * rf * (1.0 - sa) / ca, self.u_min)
            object.__setattr__(self, "_straight", c)
            object.__setattr__(self, "_straight_directions", np.array([[-sg * ca], [-sa], [sg * sa], [-ca]]))
        return c

    def _chain_profile(self, u: np.ndarray) -> CutterProfile:
        """:meth:`profile` of a blade chain (curved blade, toprem, flankrem; module docstring)."""
        sg, rf = self.sigma, self.edge_radius
        u0, ph0, r0, z0, kp = self.chain
        i = np.clip(np.searchsorted(u0, u, side="right") - 1, 0, len(u0) - 1)
        du, k, p0 = u - u0[i], kp[i], ph0[i]
        curved = k != 0.0
        ks = np.where(curved, k, 1.0)
        ph = p0 + k * du
        rho_s = r0[i] + np.where(curved, sg * (np.cos(p0) - np.cos(ph)) / ks, sg * np.sin(p0) * du)
        z_s = z0[i] - np.where(curved, (np.sin(ph) - np.sin(p0)) / ks, np.cos(p0) * du)
        blade = CutterProfile(rho_s, z_s, -sg * np.cos(ph), -np.sin(ph), sg * np.sin(ph), -np.cos(ph))
        if rf == 0.0 or self.part == "straight":
            return blade
        pt = float(ph0[0])
        rho_c = float(r0[0]) - sg * rf * np.cos(pt)            # edge centre: tangency point + r_f n(phi_t)
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
        return _vectors(p.rho * c, p.rho * s, p.z), _vectors(p.n_rho * c, p.n_rho * s, p.n_z)

    def u_at_depth(self, depth: np.ndarray) -> np.ndarray:
        """Profile parameter of the blade point at ``depth`` (mm, >= 0) below the tip plane."""
        depth = np.asarray(depth, dtype=float)
        rf, a = self.edge_radius, self.blade_angle
        if self.general:
            u0, ph0, _, z0, kp = self.chain
            pt = float(ph0[0])
            i = np.clip(np.searchsorted(-z0, depth, side="right") - 1, 0, len(u0) - 1)
            k, p0, dz = kp[i], ph0[i], z0[i] + depth
            ks = np.where(k != 0.0, k, 1.0)
            u_b = u0[i] + np.where(k != 0.0, (np.arcsin(np.clip(np.sin(p0) + k * dz, -1.0, 1.0)) - p0) / ks,
                                   dz / np.cos(p0))
            if rf == 0.0:
                return u_b
            ph = np.arcsin(np.clip(1.0 - depth / rf, np.sin(pt), 1.0))
            return np.where(depth >= -z0[0], u_b, -rf * (ph - pt))
        zt = rf * (1.0 - np.sin(a))                       # depth of the tangency point
        u_line = depth / np.cos(a) - self.s0
        if rf == 0.0:
            return u_line
        # on the arc: depth = rf (1 - sin(phi))  ->  phi = asin(1 - depth/rf)
        ph = np.arcsin(np.clip(1.0 - depth / rf, np.sin(a), 1.0))
        return np.where(depth >= zt, u_line, -rf * (ph - a))
