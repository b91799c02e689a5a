"""What to mesh for a tooth segment: a few consecutive teeth of a cylindrical gear on a slice of the rim.

The segment is closed by two radial cut faces and the bore (external) or the rim's outer cylinder (internal).
The transverse section is built from one tooth's dense outline (as produced by generation), rotated into place
for each included tooth; every run of equal (kind, side) codes becomes its own spline curve, so each flank,
fillet and tip surface gets its own named facet group. The section is built in
:mod:`tools.segment_mesh.section`, the solid and its mesh in :mod:`tools.segment_mesh.mesher`; the mesh is a
:class:`ltca.fem.solids.mesh_record.BodyMesh` (conventions there).

Conventions
-----------
* Tooth ``k`` is the outline rotated by ``-k * 2 pi / z`` about +z (clockwise for ``k > 0``).
* Helical teeth: ``point(z) = Rot(lead_twist * z) point(0)``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ltca.fem.solids.mesh_record import outline_hash

__all__ = ["SegmentSpec"]

_VERSION = "mesh-1"                    # bump when the meshing recipe changes (invalidates caches)


@dataclass(frozen=True)
class SegmentSpec:
    """What to mesh: a few consecutive teeth of a cylindrical gear.

    Parameters
    ----------
    outline : ndarray, shape (n, 2)
        One tooth's transverse outline, mm, dense (5-50 um spacing): from the mid-gap at polar
        angle +pi/z from +y (x < 0) clockwise over the tooth (centred on +y) to the mid-gap at -pi/z.
    kind : ndarray, shape (n,)
        0 root arc, 1 fillet, 2 involute flank, 3 tip arc.
    side : ndarray, shape (n,)
        -1 left, +1 right, 0 centre.
    z : int
        Number of teeth of the whole gear, >= 3.
    teeth : tuple of int
        Consecutive tooth indices to include, fewer than ``z``.
    r_bore : float
        External gear: bore radius (fixed face), 0 < r_bore < r_root. Internal gear: rim outer
        radius, > r_root. mm.
    face_width : float
        Axial width b, mm; the solid spans z in [-b/2, b/2].
    lead_twist : float
        Rotation about +z per mm of axial position, rad/mm (0 for spur).
    internal : bool
        Internal gear (tooth points inwards, material outside).
    h_flank, h_body : float
        Element size on the flank / fillet / tip surfaces of the included teeth and far from them, mm.
    order : int
        Element order, 1 or 2.
    size_fields : tuple of str
        Extra gmsh ``MathEval`` size expressions in x, y, z (mm) combined with the graded sizes by their
        minimum: local refinement, e.g. a band around contact lines (:func:`ltca.fem.solids.refinement.line_size_expression`).
    """

    outline: np.ndarray
    kind: np.ndarray
    side: np.ndarray
    z: int
    teeth: tuple[int, ...]
    r_bore: float
    face_width: float
    lead_twist: float = 0.0
    internal: bool = False
    h_flank: float = 1.0
    h_body: float = 4.0
    order: int = 2
    size_fields: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        xy = np.asarray(self.outline, dtype=float)
        if xy.ndim != 2 or xy.shape[1] != 2 or len(xy) < 8:
            raise ValueError(f"outline must have shape (n >= 8, 2), got {xy.shape}")
        if not np.all(np.isfinite(xy)):
            raise ValueError("outline contains non-finite values")
        for name in ("kind", "side"):
            a = np.asarray(getattr(self, name))
            if a.shape != (len(xy),):
                raise ValueError(f"{name} must have shape ({len(xy)},), got {a.shape}")
        if not set(np.unique(self.kind)).issubset({0, 1, 2, 3}):
            raise ValueError(f"kind values must be in {{0, 1, 2, 3}}, got {np.unique(self.kind)}")
        if not set(np.unique(self.side)).issubset({-1, 0, 1}):
            raise ValueError(f"side values must be in {{-1, 0, 1}}, got {np.unique(self.side)}")
        if int(self.z) < 3:
            raise ValueError(f"z = {self.z} must be >= 3")
        t = tuple(int(k) for k in self.teeth)
        if len(t) < 1 or len(t) >= int(self.z) or np.any(np.diff(t) != 1):
            raise ValueError(f"teeth = {self.teeth} must be 1..z-1 = {int(self.z) - 1} consecutive "
                             "increasing indices")
        r = np.hypot(xy[:, 0], xy[:, 1])
        r_lo, r_hi = float(r.min()), float(r.max())
        if self.internal and not self.r_bore > r_hi:
            raise ValueError(f"r_bore = {self.r_bore} must exceed the root radius {r_hi:.4f} "
                             "(internal gear: rim outer radius)")
        if not self.internal and not 0.0 < self.r_bore < r_lo:
            raise ValueError(f"r_bore = {self.r_bore} must be in (0, {r_lo:.4f}) (below the root)")
        if not self.face_width > 0:
            raise ValueError(f"face_width = {self.face_width} must be > 0")
        if not np.isfinite(self.lead_twist) or abs(self.lead_twist) * self.face_width > np.pi / 2:
            raise ValueError(f"lead_twist = {self.lead_twist} must be finite with "
                             f"|lead_twist| * face_width <= pi/2")
        if not 0 < self.h_flank <= self.h_body:
            raise ValueError(f"h_flank = {self.h_flank} must be in (0, h_body = {self.h_body}]")
        if self.order not in (1, 2):
            raise ValueError(f"order = {self.order} must be 1 or 2")

    @property
    def spec_hash(self) -> str:
        """SHA-256 (hex, 20 chars) of everything that determines the mesh."""
        h = outline_hash(_VERSION, self.outline, self.kind, self.side)
        h.update(repr((int(self.z), tuple(int(k) for k in self.teeth), float(self.r_bore),
                       float(self.face_width), float(self.lead_twist), bool(self.internal),
                       float(self.h_flank), float(self.h_body), int(self.order))).encode())
        for expr in self.size_fields:
            h.update(expr.encode())
        return h.hexdigest()[:20]
