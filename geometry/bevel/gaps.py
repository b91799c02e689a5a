"""Gaps between a bevel pinion flank and the gear at any pinion points and angles: the input of the LTCA.

The separation field (:mod:`ltca.geometry.bevel.separation`) evaluates the gap of the pinion *grid* to the gear;
the loaded analysis needs it at its own contact cells, anywhere on the pinion flank, for any tooth pair.  A
pinion point (depth fraction t, cone distance L) of tooth 0 at pinion angle phi1 is carried into the gear
body frame with the gear at its kinematic angle phi2_0 - (z1/z2) phi1; the gear rotation g (rad, positive
apart) that brings the gear's generated surface onto it is solved exactly at the same axial-section point
(Newton on the equation of meshing), with the gear's normal speed v = rho |n . e_theta| (mm/rad), so the
normal gap is g v to first order.  Tooth pair j is tooth 0 at phi1 + j 2 pi / z1 (the pinion tooth turned by
+j pitches and the gear tooth by -j gear pitches in their body frames).

Assembly errors E, P, G and the shaft angle error enter through the mesh frames
(:func:`ltca.geometry.bevel.tca.mesh_frames`), as in the TCA.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .separation import _gap, _Member, _speed, reference_gear_angle
from .tca import Assembly, BevelPair, mesh_frames, to_pitch_coords

__all__ = ["PointGaps", "MeshGaps", "depth_fraction"]


def depth_fraction(blank, member: str, off: float, L: np.ndarray, Rn: np.ndarray) -> np.ndarray:
    """Depth fraction of axial-section points (L, Rn) (mm) on ``member``'s flank grid whose lowest row lies ``off``
    (mm) above the root cone and whose top row is the face cone (:func:`ltca.geometry.bevel.generation.axial_grid`);
    ``blank`` is the pair's :class:`ltca.geometry.bevel.blank.BevelBlank`."""
    root, face = blank.cones(member, L)
    root = root + off
    return (Rn - root) / (face - root)


@dataclass(frozen=True)
class PointGaps:
    """Gaps of pinion points to the gear, all arrays of the points' shape.

    g : gear rotation closing the gap, rad (inf where the point is not over the gear flank);
    v2 : gear normal speed at the gear point, mm/rad (lever of the gear torque);
    v1 : pinion normal speed at the pinion point, mm/rad (lever of the pinion torque);
    r1, n1 : pinion point and outward normal, pinion body frame (tooth 0), mm;
    L1, Rn1 : pinion point in the pinion axial section, mm;  L2, Rn2 : the point in the gear axial section (also
    where it is off the gear flank);
    ok : the point lies on the pinion flank and over the gear flank, and Newton converged.
    """
    g: np.ndarray
    v2: np.ndarray
    v1: np.ndarray
    r1: np.ndarray
    n1: np.ndarray
    L1: np.ndarray
    Rn1: np.ndarray
    L2: np.ndarray
    Rn2: np.ndarray
    ok: np.ndarray


class MeshGaps:
    """Gap evaluator of one flank pair in one assembly (pinion ``side``: "concave" drives the gear convex).

    Parameters
    ----------
    pair : BevelPair
    pinion_side : "concave" or "convex"
    asm : Assembly
        Assembly errors E, P, G (mm) and shaft angle error (rad).
    root_offset : float, optional
        Pinion flank region starts this far above its root cone (mm); default half the clearance (as the TCA).
    tol : float
        Newton tolerance of the surface points, mm (1e-9: a thousandth of a micrometre, ample for contact gaps;
        the TCA's 1e-11 costs a Newton step more).
    table : float or None
        Serve both flanks from a :class:`~ltca.geometry.bevel.surface_table.SurfaceTable` within this many mm of the
        exact surface (default 1e-7 mm; exact where the table cannot); None: every point solved exactly.
    """

    def __init__(self, pair: BevelPair, pinion_side: str = "concave", asm: Assembly = Assembly(),
                 root_offset: float | None = None, tol: float = 1e-9, table: float | None = 1e-7):
        if pinion_side not in ("concave", "convex"):
            raise ValueError(f"pinion_side = {pinion_side!r}: allowed 'concave' or 'convex'")
        bl = pair.blank
        self.pair, self.asm, self.pinion_side = pair, asm, pinion_side
        self.gear_side = "convex" if pinion_side == "concave" else "concave"
        B1, O1, B2, O2 = mesh_frames(bl, asm)
        clearance = bl.pinion.dedendum - bl.gear.addendum
        off = 0.5 * clearance if root_offset is None else root_offset
        self.P = _Member(pair.pinion.flank(pinion_side), bl, "pinion", B1, O1, 20, 30, off)
        self.G = _Member(pair.gear.flank(self.gear_side), bl, "gear", B2, O2, 20, 30, 0.03 * bl.data.module)
        self.ratio = bl.pinion.z / bl.gear.z
        self.c1 = 2 * np.pi / bl.pinion.z
        P, G = self.P, self.G
        P.tol = G.tol = tol
        if table is not None:
            P.use_table(table)
            G.use_table(table)
        self.phi2_0, rp = reference_gear_angle(P, G, bl, asm)
        # closing senses, fixed once (as the separation TCA does per call)
        g, _, _, self._s2, _ = _gap(G, P.to_mesh(rp, 0.0), np.array([self.phi2_0]))
        self.t_range = (0.0, 1.0)
        self.L_range = (P.Ai, P.A0)
        self._surface_memo = None

    def axial(self, t: np.ndarray, L: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pinion axial section (Z, rho) of its flank coordinates (t, L), mm."""
        return self.P.axial(t, L)

    def depth_fraction(self, L: np.ndarray, Rn: np.ndarray) -> np.ndarray:
        """The evaluator's pinion t of axial-section points (L, Rn)."""
        root, face = self.P._cones(L)
        return (Rn - root) / (face - root)

    def pinion_surface(self, t: np.ndarray, L: np.ndarray):
        """The pinion's points, normals and convergence flags at flank coordinates (t, L) (body frame, tooth 0),
        remembered for the last grid asked: the LTCA's first-contact scan asks the same grid at every position and
        pair, and each point's Newton solve does not depend on the others in its batch (the same bits)."""
        t, L = np.broadcast_arrays(np.asarray(t, float), np.asarray(L, float))
        key = (t.shape, t.tobytes(), L.tobytes())
        if self._surface_memo is None or self._surface_memo[0] != key:
            r1, n1, ok1 = self.P.surface(t.ravel(), L.ravel())
            self._surface_memo = (key, (r1.reshape(t.shape + (3,)), n1.reshape(t.shape + (3,)), ok1.reshape(t.shape)))
        return self._surface_memo[1]

    def gaps(self, phi1: np.ndarray, t: np.ndarray, L: np.ndarray, extend: bool = False,
             surface: tuple | None = None) -> PointGaps:
        """Gaps of pinion points (t, L) of tooth 0 at pinion angles phi1 (rad; all broadcast together).

        With ``extend`` the gear surface is continued past its blank (finite-difference stencils at an edge); ``ok``
        still says whether the point is over the gear flank. ``surface``: the pinion's (points, normals, ok) at
        (t, L) from :meth:`pinion_surface`, broadcast with them (not solved again)."""
        phi1, t, L = np.broadcast_arrays(np.asarray(phi1, float), np.asarray(t, float), np.asarray(L, float))
        shp = t.shape
        phi1, t, L = phi1.ravel(), t.ravel(), L.ravel()
        P, G = self.P, self.G
        if surface is None:
            r1, n1, ok1 = P.surface(t, L)
        else:
            r1, n1 = (np.broadcast_to(a, shp + (3,)).reshape(-1, 3) for a in surface[:2])
            ok1 = np.broadcast_to(surface[2], shp).ravel()
        ang2 = self.phi2_0 - self.ratio * phi1
        r_h = P.to_mesh(r1, phi1)
        g, v2, q, _, ok2 = _gap(G, r_h, ang2, self._s2, mask=not extend)
        ok = ok1 & ok2 & P.inside(t, L)
        g = np.where(ok | (extend & ok1 & np.isfinite(g)), g, np.inf)
        L1, Rn1 = to_pitch_coords(r1, self.pair.blank.pinion.pitch_angle)
        # the gear surface point shares the pinion point's axial-section place: take it from the pinion point, so
        # that points off the gear flank have their place too (for edge labels)
        L2, Rn2 = to_pitch_coords(G.from_mesh(r_h, ang2), self.pair.blank.gear.pitch_angle)
        out = [g, v2, _speed(r1, n1), r1, n1, L1, Rn1, L2, Rn2, ok]
        return PointGaps(*[a.reshape(shp + a.shape[1:]) for a in out])
