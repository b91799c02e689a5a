"""Whole-gear bodies: the full 360 deg rim, web and hub of a cylindrical gear, meshed by extrusion.

The body is the gear, not a sector: the teeth that can touch (and a neighbour each side) are meshed
finely, the rest of the ring coarsely, and the support is the real one (the bore on the shaft, or the
rim of an internal gear in its housing). A body cut out of a gear (a segment with free radial cut
faces) bends like a curved cantilever about its fixed bore, so its stiffness depends on where it is
cut and falls as the rim gets deeper, the wrong way round.

Meshing by a twisted sweep
--------------------------
The transverse section (built-in gmsh kernel: the fine teeth as splines through their generated
outline, the far teeth as their outline or left out and replaced by the root circle, the support
circle, and the rim and hub circles of a webbed body) is swept along the axis by ``geo.twist``: the
swept surfaces are exact helicoids (the kernel evaluates them through the sweep), so a wide, strongly
twisted helical gear needs no lofting of transverse sections and meshes in seconds. A web narrower
than the face splits the sweep into axial stacks; the web's volumes outside its width are dropped.
The 3D mesh is graded from ``h_flank`` at the fine teeth (slope 0.6) up to half the body depth far
away, so the whole 360 deg ring costs about what a segment did. The fillets whose root stress is read
(``fillets``) are meshed at ``h_fillet``, graded at slope 1 into the body (:mod:`ltca.fem.fillet`).

Conventions as in :mod:`ltca.fem.solids.mesh_record`: points (n, 3) in mm, tooth ``k`` is the outline rotated by
``-k 2 pi / z``, 10-node tetrahedra in the meshio order, straight edges (mid-edge nodes at the edge
midpoints), facets oriented outward and named ``flank_{k}_{left|right}``, ``fillet_{k}_...``,
``tip_{k}``, ``root``, ``far_teeth``, ``bore`` (internal: ``rim``), ``ends`` and ``body_faces``
(web and hub side faces, rim inner face).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from .cache import load_cached, store_cached
from .planar import rot2
from .gmsh_mesh import background_size, fresh_model, mesh_labelled
from .planar import Polylines
from .session import gmsh_session
from .mesh_record import BodyMesh, outline_hash

__all__ = ["GearBodySpec", "build_gear_body"]

_VERSION = "body-2"
_KIND_NAMES = {0: "root", 1: "fillet", 2: "flank", 3: "tip"}
_SIDE_NAMES = {-1: "left", 1: "right"}


@dataclass(frozen=True)
class GearBodySpec:
    """What to mesh: a whole cylindrical gear body.

    Parameters
    ----------
    outline, kind, side, z, internal, face_width, lead_twist
        One tooth's transverse outline (mm, dense, from the mid-gap at +pi/z clockwise over the tooth centred on +y
        to the mid-gap at -pi/z), its codes (kind: 0 root, 1 fillet, 2 flank, 3 tip; side: -1 left, +1 right, 0
        centre), teeth of the whole gear, internal gear, face width (mm) and lead twist (rad/mm, 0 for spur).
    fine_teeth : tuple of int
        Consecutive teeth meshed at ``h_flank`` (the loaded ones and a neighbour each side).
    r_support : float
        External gear: bore radius (held by the shaft). Internal gear: outer rim radius (held by the
        housing). mm.
    rim : tuple (r_rim, r_hub, web_width, web_offset) or None
        A webbed body: the toothed rim ends at radius ``r_rim`` (external: its inner radius; internal: its
        outer radius), a web of axial width ``web_width`` centred at axial position ``web_offset`` joins it
        to the hub ring between ``r_hub`` and the support radius; rim and hub span the face width.
        None: a solid disc (rim and web are one, as wide as the face).
    far_teeth : {"full", "none"}
        Teeth outside ``fine_teeth``: meshed with their real outline at ``h_body`` ("full"), or left out
        and replaced by the root circle ("none"). Measured in the tests against each other.
    h_flank, h_body : float
        Element size at the fine teeth and far from them (mm).
    h_fillet : float or None
        Element size on the ``fillets`` surfaces (mm), graded like ``h_flank`` into the body: the fillets whose
        root stress is read (:func:`ltca.fem.fillet.fillet_size`). None: ``h_flank``.
    fillets : tuple of str
        Facet groups meshed at ``h_fillet``, e.g. ``("fillet_0_right",)``.
    order : int
        1 or 2.
    size_fields : tuple of str
        Extra gmsh ``MathEval`` size expressions in x, y, z (mm), combined by their minimum with the graded
        sizes: local refinement (:func:`ltca.fem.solids.refinement.build_refined_body`).
    """

    outline: np.ndarray
    kind: np.ndarray
    side: np.ndarray
    z: int
    fine_teeth: tuple[int, ...]
    r_support: float
    face_width: float
    lead_twist: float = 0.0
    internal: bool = False
    rim: tuple[float, float, float] | None = None
    far_teeth: str = "none"
    h_flank: float = 1.0
    h_body: float = 4.0
    order: int = 2
    size_fields: tuple[str, ...] = ()
    h_fillet: float | None = None
    fillets: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        xy = np.asarray(self.outline, dtype=float)
        if self.h_fillet is not None and not 0 < self.h_fillet <= self.h_flank:
            raise ValueError(f"h_fillet = {self.h_fillet} must be in (0, h_flank = {self.h_flank}]")
        if xy.ndim != 2 or xy.shape[1] != 2 or len(xy) < 8 or not np.all(np.isfinite(xy)):
            raise ValueError(f"outline must be finite with shape (n >= 8, 2), got {xy.shape}")
        if int(self.z) < 3:
            raise ValueError(f"z = {self.z} must be >= 3")
        t = tuple(int(k) for k in self.fine_teeth)
        if len(t) < 1 or len(t) > int(self.z) or np.any(np.diff(t) != 1):
            raise ValueError(f"fine_teeth = {self.fine_teeth} must be 1..z consecutive increasing indices")
        r = np.hypot(xy[:, 0], xy[:, 1])
        if self.internal and not self.r_support > r.max():
            raise ValueError(f"r_support = {self.r_support} must exceed the root radius {r.max():.4f} "
                             "(internal gear: outer rim radius)")
        if not self.internal and not 0.0 < self.r_support < r.min():
            raise ValueError(f"r_support = {self.r_support} must be in (0, {r.min():.4f}) (below the root)")
        if self.rim is not None:
            r_rim, r_hub, bw, off = (float(v) for v in self.rim)
            lo, hi = (r.max(), self.r_support) if self.internal else (self.r_support, r.min())
            if not (lo < r_rim < hi and lo < r_hub < hi and (r_hub > r_rim) == self.internal):
                raise ValueError(f"rim radius {r_rim} and hub radius {r_hub} must lie between {lo:.4f} and "
                                 f"{hi:.4f} mm, the hub nearer the support")
            if not 0 < bw <= self.face_width or abs(off) + bw / 2 > self.face_width / 2 + 1e-9:
                raise ValueError(f"web width {bw} at offset {off} must lie inside the face width "
                                 f"{self.face_width}")
        if self.far_teeth not in ("full", "none"):
            raise ValueError(f"far_teeth = {self.far_teeth!r} must be 'full' or 'none'")
        if not self.face_width > 0 or not np.isfinite(self.lead_twist):
            raise ValueError("face_width must be > 0 and lead_twist finite")
        if not 0 < self.h_flank <= self.h_body:
            raise ValueError(f"h_flank = {self.h_flank} must be in (0, h_body = {self.h_body}]")
        if self.order not in (1, 2):
            raise ValueError(f"order = {self.order} must be 1 or 2")

    @property
    def spec_hash(self) -> str:
        """SHA-256 (hex, 20 chars) of everything that determines the mesh."""
        h = outline_hash(_VERSION, self.outline, self.kind, self.side)
        h.update(repr((int(self.z), tuple(int(k) for k in self.fine_teeth), float(self.r_support),
                       float(self.face_width), float(self.lead_twist), bool(self.internal), self.rim,
                       self.far_teeth, float(self.h_flank), float(self.h_body),
                       int(self.order))).encode())
        for expr in self.size_fields:
            h.update(expr.encode())
        if self.h_fillet is not None and self.fillets:
            h.update(repr(("h_fillet", float(self.h_fillet), tuple(self.fillets))).encode())
        return h.hexdigest()[:20]


def _chain(spec: GearBodySpec):
    """The toothed boundary as (label, dense points, fine) pieces in clockwise order, over the whole gear.

    Far teeth are left out when ``far_teeth == "none"``: the caller closes the chain by the root circle."""
    xy = np.asarray(spec.outline, dtype=float)
    kind, side = np.asarray(spec.kind, int), np.asarray(spec.side, int)
    z = int(spec.z)
    pitch = 2 * np.pi / z
    gap = np.linalg.norm(rot2(xy[:1], -pitch) - xy[-1:])
    if gap > 1e-3:
        raise ValueError(f"outline end points are {gap:.3g} mm apart from their neighbours' after a rotation "
                         "by 2 pi / z: outline must run from mid-gap +pi/z to -pi/z")
    brk = np.flatnonzero((np.diff(kind) != 0) | (np.diff(side) != 0)) + 1
    runs = [(a, b) for a, b in zip(np.r_[0, brk], np.r_[brk, len(xy) - 1]) if b > a]
    fine = tuple(int(k) for k in spec.fine_teeth)
    pieces = []
    for k in range(fine[0], fine[0] + z):
        is_fine = k in fine
        if not is_fine and spec.far_teeth == "none":
            continue
        for a, b in runs:
            kd, sd = int(kind[a]), int(side[a])
            if kd == 0:
                label = "root"
            elif not is_fine:
                label = "far_teeth"
            elif kd == 3 or sd == 0:
                label = f"{_KIND_NAMES[kd]}_{k}"
            else:
                label = f"{_KIND_NAMES[kd]}_{k}_{_SIDE_NAMES[sd]}"
            pieces.append((label, rot2(xy[a:b + 1], -k * pitch), is_fine))
    return pieces


def _subsample(pts: np.ndarray, ds: float) -> np.ndarray:
    s = np.r_[0.0, np.cumsum(np.hypot(*np.diff(pts, axis=0).T))]
    n = int(np.clip(np.ceil(s[-1] / ds) + 1, 3, 400))
    idx = np.unique(np.searchsorted(s, np.linspace(0.0, s[-1], n)).clip(0, len(pts) - 1))
    idx[0], idx[-1] = 0, len(pts) - 1
    return pts[np.unique(idx)]


def _arc_ref(r: float, a0: float, a1: float) -> np.ndarray:
    t = np.linspace(a0, a1, max(20, int(abs(a1 - a0) / 0.01)))
    return r * np.c_[np.cos(t), np.sin(t)]


def _section(spec: GearBodySpec, z0: float):
    """Plane surfaces of the transverse section at axial position ``z0`` (rotated by the lead twist there).

    Returns the surfaces with their region (0 toothed rim, 1 web, 2 hub), the labelled reference
    polylines of every curve (for naming the swept surfaces) and the curves of the fine teeth."""
    import gmsh
    geo = gmsh.model.geo
    phi0 = spec.lead_twist * z0

    def point(p2) -> int:
        q = rot2(np.asarray(p2, float)[None, :], phi0)[0]
        return geo.addPoint(float(q[0]), float(q[1]), z0)

    centre = geo.addPoint(0.0, 0.0, z0)
    refs: list[tuple[str, np.ndarray]] = []

    def circle(r: float, label: str) -> int:
        pts = [point((r * np.cos(a), r * np.sin(a))) for a in np.arange(4) * np.pi / 2]
        cs = [geo.addCircleArc(pts[i], centre, pts[(i + 1) % 4]) for i in range(4)]
        refs.append((label, _arc_ref(r, 0.0, 2 * np.pi)))
        return geo.addCurveLoop(cs)

    pieces = _chain(spec)
    closes = spec.far_teeth == "full" or len(spec.fine_teeth) == spec.z
    first = prev = point(pieces[0][1][0])
    curves, fine = [], []
    for i, (label, dense, is_fine) in enumerate(pieces):
        pts = _subsample(dense, 0.1 if is_fine else max(0.25, spec.h_body / 6))
        end = first if closes and i == len(pieces) - 1 else point(pts[-1])
        c = geo.addSpline([prev] + [point(p) for p in pts[1:-1]] + [end])
        curves.append(c)
        refs.append((label, dense))
        if is_fine and label != "root":
            fine.append(c)
        prev = end
    if not closes:                       # far teeth left out: the root circle, clockwise the long way round
        p_end, p_first = pieces[-1][1][-1], pieces[0][1][0]
        r0 = float(np.linalg.norm(p_end))
        a0, a1 = np.arctan2(p_end[1], p_end[0]), np.arctan2(p_first[1], p_first[0])
        span = (a0 - a1) % (2 * np.pi)
        n_arc = int(np.ceil(span / (np.pi / 2)))
        angs = a0 - np.linspace(0, span, n_arc + 1)
        for j in range(n_arc):
            nxt = first if j == n_arc - 1 else point((r0 * np.cos(angs[j + 1]), r0 * np.sin(angs[j + 1])))
            curves.append(geo.addCircleArc(prev, centre, nxt))
            prev = nxt
        refs.append(("root", _arc_ref(r0, a0 - span, a0)))
    teeth = geo.addCurveLoop(curves)
    support = "rim" if spec.internal else "bore"
    if spec.rim is None:
        sup = circle(spec.r_support, support)
        return [(geo.addPlaneSurface([sup, teeth] if spec.internal else [teeth, sup]), 0)], refs, fine
    l_rim, l_hub = circle(spec.rim[0], "body_faces"), circle(spec.rim[1], "body_faces")
    sup = circle(spec.r_support, support)
    if spec.internal:
        loops = [[l_rim, teeth], [l_hub, l_rim], [sup, l_hub]]
    else:
        loops = [[teeth, l_rim], [l_rim, l_hub], [l_hub, sup]]
    return [(geo.addPlaneSurface(lp), r) for r, lp in enumerate(loops)], refs, fine


def _stacks(spec: GearBodySpec) -> list[tuple[float, float, bool]]:
    """Axial stacks (z0, z1, web present) of the extrusion: the web faces split the face width."""
    b = float(spec.face_width)
    if spec.rim is None:
        return [(-b / 2, b / 2, True)]
    w, off = float(spec.rim[2]), float(spec.rim[3])
    cuts = np.unique(np.clip([-b / 2, off - w / 2, off + w / 2, b / 2], -b / 2, b / 2))
    return [(float(z0), float(z1), bool(abs(0.5 * (z0 + z1) - off) < w / 2))
            for z0, z1 in zip(cuts[:-1], cuts[1:]) if z1 - z0 > 1e-9]


def _build(spec: GearBodySpec):
    """The gmsh model of the body: section at -b/2 swept (and twisted) through the axial stacks."""
    import gmsh
    geo = gmsh.model.geo
    stacks = _stacks(spec)
    surfaces, refs, fine_curves = _section(spec, stacks[0][0])
    current = surfaces
    volumes, dropped = [], []
    for z0, z1, web in stacks:
        dz = z1 - z0
        out = geo.twist([(2, s) for s, _ in current], 0, 0, 0, 0, 0, dz, 0, 0, 1, spec.lead_twist * dz)
        # per source surface: its top surface, its volume, then its swept sides
        tops = [out[i][1] for i, (d, _) in enumerate(out) if d == 2 and i + 1 < len(out) and out[i + 1][0] == 3]
        vols = [t for d, t in out if d == 3]
        nxt = []
        for (s, reg), top, vol in zip(current, tops, vols):
            nxt.append((top, reg))
            (dropped if reg == 1 and not web else volumes).append(vol)
        current = nxt
    geo.synchronize()
    return volumes, dropped, refs, fine_curves


def _label(spec: GearBodySpec, volumes: list[int], refs) -> dict[int, str]:
    """Name each boundary surface of the kept volumes: end planes, web/hub faces, or the section curve it
    was swept from (its parametric mid-point un-twisted and matched to the nearest reference polyline)."""
    import gmsh
    count: dict[int, int] = {}
    for v in volumes:
        for _, s in gmsh.model.getBoundary([(3, v)], oriented=False):
            count[abs(s)] = count.get(abs(s), 0) + 1
    half = 0.5 * spec.face_width
    names = {}
    curves = Polylines([ref for _, ref in refs])
    for s, n in count.items():
        if n != 1:
            continue
        lo, hi = gmsh.model.getParametrizationBounds(2, s)
        uv = 0.5 * (np.asarray(lo) + np.asarray(hi))
        x, y, zc = gmsh.model.getValue(2, s, uv)
        normal = gmsh.model.getNormal(s, uv)
        if abs(normal[2]) > 0.999:
            names[s] = "ends" if abs(abs(zc) - half) < 1e-6 * max(1.0, half) else "body_faces"
            continue
        p = rot2(np.array([[x, y]]), -spec.lead_twist * zc)[0]
        dist = curves.distance(p)
        i = int(np.argmin(dist))
        # the swept surfaces follow the section polylines within their chord error, which grows with the radius
        if dist[i] > max(2e-2, 2e-5 * float(np.hypot(x, y))):
            raise RuntimeError(f"surface {s} matches no transverse curve (distance {dist[i]:.3g} mm)")
        names[s] = refs[i][0]
    return names


def build_gear_body(spec: GearBodySpec, cache_dir=None, progress: bool = False) -> BodyMesh:
    """Mesh a whole gear body (module docstring); returns the mesh record the compliance path consumes.

    Parameters
    ----------
    spec : GearBodySpec
    cache_dir : path, optional
        Meshes are stored there as ``body_<spec_hash>.npz`` and reloaded on a hit.
    progress : bool
        Let gmsh print to the terminal.
    """
    t0 = time.perf_counter()
    cached = load_cached(cache_dir, "body", spec.spec_hash)
    if cached is not None:
        return cached
    twist = abs(spec.lead_twist) * spec.face_width
    # the twisted sweep's edge curves are splines through this many points: one per 5 mrad of twist keeps the
    # tip and root edges of a helical tooth on the helix to well under a micrometre
    options = _OPTIONS | {"Mesh.MeshSizeMax": 1e22,
                          "Geometry.ExtrudeSplinePoints": int(np.clip(np.ceil(twist / 0.005), 5, 400))}
    with gmsh_session(progress), fresh_model(f"body_{spec.spec_hash}", options):
        import gmsh
        volumes, dropped, refs, _ = _build(spec)
        if dropped:
            gmsh.model.removeEntities([(3, v) for v in dropped])
        labels = _label(spec, volumes, refs)
        nodes, tets, facets = mesh_labelled(labels, volumes, spec.order, lambda fine: _size_field(spec, fine, labels))
    mesh = BodyMesh(nodes, tets, facets, spec.spec_hash, time.perf_counter() - t0)
    store_cached(cache_dir, "body", mesh)
    return mesh


def _size_field(spec: GearBodySpec, fine: list[int], labels: dict[int, str]) -> None:
    """``h_flank`` on the fine surfaces (``h_fillet`` on the named fillets), growing with slope 0.6 to ``h_body``
    and on, far from the teeth, to half the body's radial depth or face width (whichever is smaller): a large
    gear's far ring stays cheap."""
    r = np.hypot(*np.asarray(spec.outline, float).T)
    depth = (spec.r_support - r.max()) if spec.internal else (r.min() - spec.r_support)
    h_far = max(spec.h_body, 0.5 * min(depth, spec.face_width))
    fields = [_graded(fine, spec.h_flank, h_far, spec.face_width, _SLOPE)]
    fillets = [t for t, s in labels.items() if s in spec.fillets]
    if spec.h_fillet is not None and fillets:
        fields.append(_graded(fillets, spec.h_fillet, h_far, spec.face_width, _FILLET_SLOPE))
    background_size(fields, spec.size_fields)


def _graded(surfaces: list[int], h: float, h_far: float, face_width: float, slope: float = 0.6) -> int:
    """A gmsh size field: ``h`` within ``h / 2`` of ``surfaces``, growing with ``slope`` to ``h_far``."""
    import gmsh
    fld = gmsh.model.mesh.field
    dist = fld.add("Distance")
    fld.setNumbers(dist, "SurfacesList", surfaces)
    fld.setNumber(dist, "Sampling", int(np.clip(np.ceil(2.0 * max(face_width, 10.0) / h), 20, 300)))
    thr = fld.add("Threshold")
    fld.setNumber(thr, "InField", dist)
    fld.setNumber(thr, "SizeMin", h)
    fld.setNumber(thr, "SizeMax", h_far)
    fld.setNumber(thr, "DistMin", 0.5 * h)
    fld.setNumber(thr, "DistMax", 0.5 * h + (h_far - h) / slope)
    return thr


_SLOPE = 0.6
#: the read fillets' sizes grow faster into the body: the root stress needs small elements within about a fillet
#: element of the surface, and the slope 0.6 of the flanks would fill the tooth root with them
_FILLET_SLOPE = 1.0
_OPTIONS = {"Geometry.ExtrudeSplinePoints": 5, "General.NumThreads": 1, "Mesh.MeshSizeFromPoints": 0,
            "Mesh.MeshSizeExtendFromBoundary": 0,
            "Mesh.MeshSizeFromCurvature": 0, "Mesh.SecondOrderLinear": 1, "Mesh.Algorithm": 6,
            "Mesh.Algorithm3D": 1, "Mesh.Optimize": 1, "Mesh.ElementOrder": 1}
