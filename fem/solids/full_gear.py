"""A full gear with every tooth, built independently of :mod:`ltca.fem.solids.gear_body` (the whole-gear check).

The reference solid of the whole-gear CalculiX check: the transverse outline of all ``z`` teeth (the
generated tooth outline rotated into place for each tooth) is one closed curve, the bore is a circular
hole, and the face is extruded over the face width with gmsh's OpenCASCADE kernel. A webbed (thin-rim)
gear is a toothed rim ring, a narrower web and a hub, each extruded over its own width and made
conforming by ``occ.fragment``. A helical gear (``twist`` = tan(beta) / r, rad/mm: the transverse section at
z is the one at z = 0 turned by ``twist`` z, counter-clockwise) is lofted (``occ.addThruSections``, cubic
B-spline surfaces) through the whole outline at sections at most ``max_turn`` apart in that turn, and its bore
cut out; no web. An internal gear (``internal``) is the ring between its toothed inner outline and the outer
circle ``r_bore`` where the housing holds it (the eccentric planetary's central wheel); spur only.

Nothing here is shared with the compliance body of our solver: its own construction (OCC extrusion and
fragments, not the built-in kernel's sweep), every tooth meshed (none left out), its own size field
(the teeth in contact at ``h_flank``, every other tooth at ``h_tooth``, the rest graded up to
``h_body``) and the caller's contact-band size expressions (:func:`ltca.fem.solids.refinement.line_size_expression`).

Surfaces are labelled by where they are: ``flank_{k}_{left|right}``, ``fillet_{k}_{left|right}``,
``tip_{k}``, ``root``, ``bore`` (internal: ``rim``, the outer cylinder), ``ends`` (z = +-b/2) and ``body_faces``
(the groove faces of a web).
Tooth ``k`` (``-z//2 <= k < z - z//2``) is the outline rotated by ``-k 2 pi / z``, as in
:mod:`ltca.fem.solids.mesh_record`. Units mm; points (n, 3); 10-node tetrahedra in the meshio order.
"""
from __future__ import annotations

import hashlib
import time
from dataclasses import dataclass

import numpy as np

from .gmsh_mesh import background_size, extract_mesh
from .mesh_record import BodyMesh
from .planar import polyline_distance, rot2
from .session import gmsh_session

__all__ = ["FullGearSpec", "build_full_gear", "gear_solid"]

_KIND = {0: "root", 1: "fillet", 2: "flank", 3: "tip"}
_SIDE = {-1: "left", 0: "", 1: "right"}


@dataclass(frozen=True)
class FullGearSpec:
    """What to mesh: every tooth of a spur gear, its bore (internal: outer rim) and optionally a web.

    Parameters
    ----------
    outline, kind, side : ndarray
        One tooth's transverse outline (n, 2) and its codes, as ``ltca.geometry.profile.ToothProfile``.
    z : int
        Number of teeth.
    r_bore : float
        Radius of the support cylinder, mm: the bore (external gear, below the root) or the outer rim held in
        the housing (internal gear, beyond the root).
    face_width : float
        Axial width, mm; the solid spans z in [-b/2, b/2].
    web : tuple (r_rim, r_hub, web_width, web_offset) or None
        Rim inner radius, hub outer radius, web axial width and mid-plane position (mm); None: solid disc.
    loaded_teeth : tuple of int
        Teeth whose flank, fillet and tip surfaces get ``h_flank``.
    h_flank, h_tooth, h_body : float
        Element sizes at the loaded teeth, at every other tooth and far from the teeth (mm).
    size_fields : tuple of str
        Extra gmsh ``MathEval`` sizes in x, y, z (mm), combined by their minimum (contact bands).
    ds : float
        Spacing of the spline through-points of the outline, mm.
    h_fillet : float or None
        Element size on the loaded teeth's fillets, mm, for their root stress; None: ``h_flank``.
    fillet_side : {"left", "right"} or None
        The side of the fillets refined to ``h_fillet`` (the loaded flank's: the tension side); None: both.
    twist : float
        tan(beta) / r of a helical gear, rad/mm (the sign of beta: the hand); 0 for spur.
    max_turn : float
        Largest turn between the loft's sections, rad (a helical gear).
    internal : bool
        Internal teeth (the outline's teeth point to the axis): the solid is the ring out to ``r_bore``.
    """

    outline: np.ndarray
    kind: np.ndarray
    side: np.ndarray
    z: int
    r_bore: float
    face_width: float
    web: tuple[float, float, float, float] | None = None
    loaded_teeth: tuple[int, ...] = ()
    h_flank: float = 1.0
    h_tooth: float = 2.0
    h_body: float = 5.0
    size_fields: tuple[str, ...] = ()
    ds: float = 0.4
    h_fillet: float | None = None
    fillet_side: str | None = None
    twist: float = 0.0
    max_turn: float = 0.02
    internal: bool = False

    def __post_init__(self) -> None:
        r = np.hypot(*np.asarray(self.outline, float).T)
        if self.internal:
            if not self.r_bore > r.max() or self.web is not None:
                raise ValueError(f"r_bore = {self.r_bore} must exceed {r.max():.4f} (the internal gear's root) and "
                                 "an internal gear has no web here")
        elif not 0 < self.r_bore < r.min():
            raise ValueError(f"r_bore = {self.r_bore} must be in (0, {r.min():.4f}) (below the root)")
        if self.web is not None:
            r_rim, r_hub, width, off = self.web
            if not (self.r_bore < r_hub < r_rim < r.min() and 0 < width
                    and abs(off) + width / 2 <= self.face_width / 2):
                raise ValueError(f"web = {self.web}: need r_bore < r_hub < r_rim < r_root and a web inside the face")
        if not 0 < self.h_flank <= self.h_tooth <= self.h_body:
            raise ValueError("element sizes must satisfy 0 < h_flank <= h_tooth <= h_body")
        if self.h_fillet is not None and not 0 < self.h_fillet <= self.h_body:
            raise ValueError(f"h_fillet = {self.h_fillet} must be in (0, h_body]")
        if self.twist and (self.web is not None or not 0 < self.max_turn <= 0.2):
            raise ValueError("a helical full gear has no web and needs 0 < max_turn <= 0.2 rad")
        if self.twist and self.internal:
            raise ValueError("an internal full gear is spur only here (twist = 0)")

    @property
    def spec_hash(self) -> str:
        """SHA-256 (hex, 20 chars) of everything that determines the mesh."""
        h = hashlib.sha256(b"full-gear-1")
        for a in (self.outline, self.kind, self.side):
            h.update(np.ascontiguousarray(a, dtype=float).tobytes())
        h.update(repr((self.z, self.r_bore, self.face_width, self.web, self.loaded_teeth, self.h_flank,
                       self.h_tooth, self.h_body, self.size_fields, self.ds)).encode())
        if self.h_fillet is not None:
            h.update(repr(("h_fillet", self.h_fillet, self.fillet_side)).encode())
        if self.twist:
            h.update(repr(("twist", self.twist, self.max_turn)).encode())
        if self.internal:
            h.update(b"internal")
        return h.hexdigest()[:20]

    @property
    def support(self) -> str:
        """Name of the support surface: ``bore`` (external) or ``rim`` (internal)."""
        return "rim" if self.internal else "bore"


def _runs(spec: FullGearSpec) -> list[tuple[str, np.ndarray]]:
    """One tooth's outline split into runs of equal (kind, side): (label stem, points (m, 2)), end points shared."""
    xy = np.asarray(spec.outline, float)
    code = np.asarray(spec.kind, int) * 3 + np.asarray(spec.side, int)
    cut = np.flatnonzero(np.diff(code)) + 1
    bounds = np.concatenate([[0], cut, [len(xy)]])
    out = []
    for a, b in zip(bounds[:-1], bounds[1:]):
        pts = xy[max(a - 1, 0):b]                     # include the previous run's last point: runs join
        k, s = int(spec.kind[a]), int(spec.side[a])
        stem = _KIND[k] if k == 0 else f"{_KIND[k]}_{{k}}" + (f"_{_SIDE[s]}" if s else "")
        if len(pts) >= 2:
            out.append((stem, pts))
    return out


def _thin(pts: np.ndarray, ds: float) -> np.ndarray:
    """Through-points about ``ds`` apart along the polyline, both ends kept."""
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    n = max(2, int(np.ceil(s[-1] / ds)) + 1)
    idx = np.unique(np.searchsorted(s, np.linspace(0, s[-1], n)).clip(0, len(pts) - 1))
    return pts[np.unique(np.concatenate([[0], idx, [len(pts) - 1]]))]


def tooth_label(k: int, z: int) -> int:
    """Tooth index ``k`` mapped to -z//2 .. z - z//2 - 1."""
    return (k + z // 2) % z - z // 2


def _outline_loop(spec: FullGearSpec, runs, z0: float | None = None, wire: bool = False) -> int:
    """The closed OCC curve loop (or wire) of all z teeth at z0 (default -b/2), turned by ``twist`` z0."""
    import gmsh
    occ = gmsh.model.occ
    z0 = -0.5 * spec.face_width if z0 is None else z0
    first = prev = None
    curves = []
    for i in range(spec.z):
        phi = -2 * np.pi * i / spec.z + spec.twist * z0
        for j, (_, pts) in enumerate(runs):
            q = rot2(_thin(pts, spec.ds), phi)
            start = prev if prev is not None else occ.addPoint(q[0, 0], q[0, 1], z0)
            first = first if first is not None else start
            last_run = i == spec.z - 1 and j == len(runs) - 1
            end = first if last_run else occ.addPoint(q[-1, 0], q[-1, 1], z0)
            mid = [occ.addPoint(x, y, z0) for x, y in q[1:-1]]
            curves.append(occ.addSpline([start, *mid, end]) if mid else occ.addLine(start, end))
            prev = end
    return occ.addWire(curves) if wire else occ.addCurveLoop(curves)


def _helical(spec: FullGearSpec, runs) -> list[tuple[int, int]]:
    """The helical gear's volume: the outline lofted through sections along the face, the bore cut out."""
    import gmsh
    occ = gmsh.model.occ
    b = spec.face_width
    n = max(3, int(np.ceil(abs(spec.twist) * b / spec.max_turn)) + 1)
    wires = [_outline_loop(spec, runs, z0, wire=True) for z0 in np.linspace(-0.5 * b, 0.5 * b, n)]
    loft = [e for e in occ.addThruSections(wires, makeSolid=True, makeRuled=False) if e[0] == 3]
    bore = occ.addCylinder(0, 0, -0.5 * b - 1.0, 0, 0, b + 2.0, spec.r_bore)
    out = [e for e in occ.cut(loft, [(3, bore)])[0] if e[0] == 3]
    occ.synchronize()
    return out


def _solid(spec: FullGearSpec, runs) -> list[tuple[int, int]]:
    """The OCC volume(s): the toothed disc with its bore; a webbed gear as conforming axial slabs.

    Webbed: the section is split (2D fragments) into the toothed ring, the annulus between rim and hub and
    the hub ring, and extruded slab by slab (below, across and above the web); the annulus volumes
    outside the web are then removed (not recursively: their faces bound the rim and hub)."""
    import gmsh
    occ = gmsh.model.occ
    b = spec.face_width
    z0 = -0.5 * b
    if spec.twist:
        return _helical(spec, runs)
    outer = _outline_loop(spec, runs)
    if spec.web is None:
        circle = occ.addCurveLoop([occ.addCircle(0, 0, z0, spec.r_bore)])
        loops = [circle, outer] if spec.internal else [outer, circle]      # first loop: the outer boundary
        out = [(d, t) for d, t in occ.extrude([(2, occ.addPlaneSurface(loops))], 0, 0, b) if d == 3]
        occ.synchronize()
        return out
    r_rim, r_hub, width, off = spec.web
    disc = occ.addPlaneSurface([outer])
    cuts = [(2, occ.addDisk(0, 0, z0, r, r)) for r in (r_rim, r_hub, spec.r_bore)]
    faces = [e for e in occ.fragment([(2, disc)], cuts)[0] if e[0] == 2]
    occ.synchronize()

    def mid_radius(tag: int) -> float:       # ring: > r_rim, annulus: r_hub..r_rim, hub: r_bore..r_hub, bore disc
        lo = gmsh.model.getBoundingBox(2, tag)
        return lo[3]
    faces = [f for f in faces if mid_radius(f[1]) > spec.r_bore + 1e-6]
    occ.remove([e for e in gmsh.model.getEntities(2) if e not in faces], recursive=True)
    heights = [h for h in (off - 0.5 * width - z0, width, 0.5 * b - off - 0.5 * width) if h > 1e-9]
    keep, level = [], faces
    for i, h in enumerate(heights):
        ext = occ.extrude(level, 0, 0, h)
        tops = [ext[j] for j in range(len(ext)) if j + 1 < len(ext) and ext[j + 1][0] == 3]
        vols = [e for e in ext if e[0] == 3]
        occ.synchronize()
        for v in vols:
            x_hi = gmsh.model.getBoundingBox(3, v[1])[3]
            across = abs(z0 + sum(heights[:i]) + 0.5 * h - off) < 0.5 * width
            if x_hi > r_rim + 1e-6 or x_hi < r_hub + 1e-6 or across:
                keep.append(v)
        level = tops
    occ.remove([v for v in gmsh.model.getEntities(3) if v not in keep])
    occ.synchronize()
    closure, level = set(keep), keep
    for _ in range(3):
        level = gmsh.model.getBoundary(level, combined=False, oriented=False)
        closure.update((d, abs(t)) for d, t in level)
    occ.remove([e for d in (2, 1, 0) for e in gmsh.model.getEntities(d) if e not in closure])
    occ.synchronize()
    return keep


def gear_solid(spec: FullGearSpec) -> list[tuple[int, int]]:
    """The gear's OCC volume(s) in the current gmsh model, (dim, tag) pairs; gmsh must be initialised with a model
    current. The solid that :func:`build_full_gear` meshes (its size and label fields do not enter)."""
    return _solid(spec, _runs(spec))


def _labels(spec: FullGearSpec, runs, vol) -> dict[int, str]:
    """Name every boundary surface by where its parametric mid-point lies (see the module docstring)."""
    import gmsh
    half, pitch = 0.5 * spec.face_width, 2 * np.pi / spec.z
    refs = [(stem, _thin(pts, 0.05)) for stem, pts in runs]
    names = {}
    for _, tag in gmsh.model.getBoundary(vol, combined=True, oriented=False):
        lo, hi = gmsh.model.getParametrizationBounds(2, tag)
        uv = 0.5 * (np.asarray(lo) + np.asarray(hi))
        x, y, zc = gmsh.model.getValue(2, tag, uv)
        nz = gmsh.model.getNormal(tag, uv)[2]
        r = np.hypot(x, y)
        if abs(nz) > 0.999:
            names[tag] = "ends" if abs(abs(zc) - half) < 1e-6 else "body_faces"
            continue
        if abs(r - spec.r_bore) < 1e-6:
            names[tag] = spec.support
            continue
        x, y = rot2(np.array([[x, y]]), -spec.twist * zc)[0]            # back to the section at z = 0
        k = int(np.round(np.arctan2(-x, y) / -pitch))       # polar angle from +y, tooth k at -k pitch
        p = rot2(np.array([[x, y]]), k * pitch)[0]
        dist = [polyline_distance(p, ref) for _, ref in refs]
        i = int(np.argmin(dist))
        if dist[i] > 1e-2:
            names[tag] = "body_faces"                        # rim, web or hub cylinder of the grooves
            continue
        names[tag] = refs[i][0].format(k=tooth_label(k, spec.z))
    return names


def _size_field(spec: FullGearSpec, labels: dict[int, str]) -> None:
    """h_flank at the loaded teeth (h_fillet on their fillets), h_tooth at the others, graded (slope 0.5) to
    h_body; min with the extras."""
    import gmsh
    fld = gmsh.model.mesh.field
    tags = []
    loaded = {str(k) for k in spec.loaded_teeth}
    on_loaded = [t for t, s in labels.items() if s.count("_") and s.split("_")[1] in loaded]
    groups = [(on_loaded, spec.h_flank), ([t for t, s in labels.items() if s not in ("bore", "rim", "ends")],
                                          spec.h_tooth)]
    if spec.h_fillet is not None:
        groups.append(([t for t in on_loaded if labels[t].startswith("fillet_")
                        and labels[t].endswith(spec.fillet_side or "")], spec.h_fillet))
    for surfaces, h in groups:
        if not surfaces:
            continue
        d = fld.add("Distance")
        fld.setNumbers(d, "SurfacesList", surfaces)
        fld.setNumber(d, "Sampling", 60)
        t = fld.add("Threshold")
        fld.setNumber(t, "InField", d)
        fld.setNumber(t, "SizeMin", h)
        fld.setNumber(t, "SizeMax", spec.h_body)
        fld.setNumber(t, "DistMin", 0.5 * h)
        fld.setNumber(t, "DistMax", 0.5 * h + (spec.h_body - h) / 0.5)
        tags.append(t)
    background_size(tags, spec.size_fields)


_OPTIONS = {"General.NumThreads": 1, "Mesh.MeshSizeFromPoints": 0, "Mesh.MeshSizeExtendFromBoundary": 0,
            "Mesh.MeshSizeFromCurvature": 0, "Mesh.SecondOrderLinear": 1, "Mesh.Algorithm": 6,
            "Mesh.Algorithm3D": 1, "Mesh.Optimize": 1, "Mesh.ElementOrder": 1}


def _remove_flat_tets(rounds: int = 3) -> None:
    """Optimise the linear tetrahedra (Netgen) while any is flat (quality SICN <= 1e-9).

    The Delaunay mesher can leave a tetrahedron of four coplanar vertices where the points of a regular
    size field line up (seen in the 51-tooth internal ring); CalculiX stops on its zero Jacobian. Meshes
    without one are left exactly as they are."""
    import gmsh
    for _ in range(rounds):
        tags = gmsh.model.mesh.getElementsByType(4)[0]
        if not len(tags) or np.min(gmsh.model.mesh.getElementQualities(tags, "minSICN")) > 1e-9:
            return
        gmsh.model.mesh.optimize("Netgen")
    raise RuntimeError("full gear: flat tetrahedra remain after Netgen optimisation")


def build_full_gear(spec: FullGearSpec, progress: bool = False) -> BodyMesh:
    """Build and mesh the full gear ``spec`` with quadratic tetrahedra; returns the mesh record.

    Facet groups: see the module docstring. The mesh is deterministic (one gmsh thread)."""
    import gmsh
    t0 = time.perf_counter()
    runs = _runs(spec)
    with gmsh_session(progress):
        gmsh.model.add(f"full_{spec.spec_hash}")
        old = {k: gmsh.option.getNumber(k) for k in _OPTIONS}
        try:
            for k, v in _OPTIONS.items():
                gmsh.option.setNumber(k, v)
            gmsh.option.setNumber("Mesh.MeshSizeMax", spec.h_body)
            vol = _solid(spec, runs)
            labels = _labels(spec, runs, vol)
            _size_field(spec, labels)
            gmsh.model.mesh.generate(3)
            _remove_flat_tets()
            gmsh.model.mesh.setOrder(2)
            nodes, tets, facets = extract_mesh(labels, 2)
        finally:
            gmsh.model.remove()
            for k, v in old.items():
                gmsh.option.setNumber(k, v)
    return BodyMesh(nodes, tets, facets, spec.spec_hash, time.perf_counter() - t0)
