"""Tooth-segment solids meshed by gmsh with graded quadratic tetrahedra.

A segment is a few consecutive teeth of a cylindrical gear (spur or helical, external or internal)
on a slice of the rim, closed by two radial cut faces and the bore (external) or the rim's outer
cylinder (internal). The transverse section is built from one tooth's dense outline (as produced by
generation), rotated into place for each included tooth; every run of equal (kind, side) codes becomes
its own spline curve, so each flank, fillet and tip surface gets its own named facet group.

Conventions
-----------
* Points are (n, 3) with xyz on the last axis (see ``geometry.flank``); units mm, rad.
* Tooth ``k`` is the outline rotated by ``-k * 2 pi / z`` about +z (clockwise for ``k > 0``).
* Helical teeth: ``point(z) = Rot(lead_twist * z) point(0)``.
* ``tets`` use the meshio / scikit-fem / CalculiX order of the 10-node tetrahedron
  (mid-edge nodes 01, 12, 20, 03, 13, 23). gmsh's own order swaps the last two; it is converted here.
* Elements are second order with straight edges (``Mesh.SecondOrderLinear = 1``): the mid-edge nodes
  are the edge midpoints, so every element map is affine. Corner nodes lie on the CAD surfaces.
"""
from __future__ import annotations

import contextlib
import hashlib
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterator

import numpy as np

__all__ = ["SegmentSpec", "SegmentMesh", "build_segment", "gmsh_session"]

_VERSION = "mesh-1"                    # bump when the meshing recipe changes (invalidates caches)
_KIND_NAMES = {0: "root", 1: "fillet", 2: "flank", 3: "tip"}
_SIDE_NAMES = {-1: "left", 1: "right"}
_GMSH_TO_MESHIO_TET10 = np.array([0, 1, 2, 3, 4, 5, 6, 7, 9, 8])
_FLIP_TRI6 = np.array([0, 2, 1, 5, 4, 3])


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
        minimum: local refinement, e.g. a band around contact lines (:func:`fem.export.build_refined_segment`).
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
        h = hashlib.sha256(_VERSION.encode())
        for a in (self.outline, self.kind, self.side):
            arr = np.ascontiguousarray(a, dtype=float)
            h.update(str(arr.shape).encode())
            h.update(arr.tobytes())
        h.update(repr((int(self.z), tuple(int(k) for k in self.teeth), float(self.r_bore),
                       float(self.face_width), float(self.lead_twist), bool(self.internal),
                       float(self.h_flank), float(self.h_body), int(self.order))).encode())
        for expr in self.size_fields:
            h.update(expr.encode())
        return h.hexdigest()[:20]


@dataclass(frozen=True)
class SegmentMesh:
    """A meshed tooth segment.

    Attributes
    ----------
    nodes : ndarray, shape (N, 3)
        Node coordinates, mm.
    tets : ndarray, shape (M, 10) (order 2) or (M, 4) (order 1)
        Node indices, meshio order, positive orientation.
    facets : dict of str to ndarray, shape (k, 6) (order 2) or (k, 3)
        Boundary triangles (3 vertices, then mid-edge 01, 12, 20), oriented outward. Names:
        ``"bore"`` (internal: ``"rim"``), ``"cut"``, ``"ends"``, ``"root"``,
        ``"flank_{k}_{left|right}"``, ``"fillet_{k}_{left|right}"``, ``"tip_{k}"``.
    spec_hash : str
        ``SegmentSpec.spec_hash`` of the spec that made it.
    seconds : float
        Wall time spent building (or loading) the mesh, s.
    """

    nodes: np.ndarray
    tets: np.ndarray
    facets: dict[str, np.ndarray]
    spec_hash: str
    seconds: float = field(default=0.0, compare=False)

    @property
    def n_dofs(self) -> int:
        """Displacement degrees of freedom, 3 per node."""
        return 3 * len(self.nodes)


@contextlib.contextmanager
def gmsh_session(progress: bool = False) -> Iterator[None]:
    """Initialise gmsh for the duration of a ``with`` block; re-entrant safe.

    If gmsh is already initialised, it is left running on exit (only the models added inside are
    the caller's to remove). Output goes to the terminal only if ``progress``.
    """
    import gmsh

    owner = not gmsh.isInitialized()
    if owner:
        gmsh.initialize(readConfigFiles=False, interruptible=False)
    old_terminal = gmsh.option.getNumber("General.Terminal")
    gmsh.option.setNumber("General.Terminal", 1 if progress else 0)
    try:
        yield
    finally:
        if owner:
            gmsh.finalize()
        else:
            gmsh.option.setNumber("General.Terminal", old_terminal)


def build_segment(spec: SegmentSpec, cache_dir: str | os.PathLike | None = None,
                  progress: bool = False) -> SegmentMesh:
    """Mesh a tooth segment with graded (quadratic) tetrahedra.

    Parameters
    ----------
    spec : SegmentSpec
        Geometry and mesh sizes.
    cache_dir : path, optional
        If given, meshes are stored there as ``segment_<spec_hash>.npz`` and reloaded on a hit.
    progress : bool
        Let gmsh print to the terminal.

    Returns
    -------
    SegmentMesh
    """
    t0 = time.perf_counter()
    key = spec.spec_hash
    path = None
    if cache_dir is not None:
        path = Path(cache_dir) / f"segment_{key}.npz"
        if path.exists():
            with np.load(path) as d:
                facets = {k[len("facet__"):]: d[k] for k in d.files if k.startswith("facet__")}
                return SegmentMesh(d["nodes"], d["tets"], facets, key, time.perf_counter() - t0)
    with gmsh_session(progress):
        nodes, tets, facets = _mesh_with_gmsh(spec)
    mesh = SegmentMesh(nodes, tets, facets, key, time.perf_counter() - t0)
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".tmp{os.getpid()}.npz")
        np.savez(tmp, nodes=nodes, tets=tets, **{f"facet__{k}": v for k, v in facets.items()})
        os.replace(tmp, path)
    return mesh


# ----------------------------------------------------------------------------------------------
# transverse section: pieces of the closed outline
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class _Piece:
    label: str                 # facet group name
    kind: str                  # "spline", "line" or "arc" (arc centred on the axis)
    pts: np.ndarray            # (m, 2) points through which the curve passes (arc: start, end)
    ref: np.ndarray            # (p, 2) dense polyline of the curve, for labelling surfaces


def _rot2(xy: np.ndarray, phi: float) -> np.ndarray:
    c, s = np.cos(phi), np.sin(phi)
    return xy @ np.array([[c, s], [-s, c]])


def _subsample(pts: np.ndarray, ds: float, n_min: int = 4, n_max: int = 400) -> np.ndarray:
    """Points of a dense polyline at about ``ds`` arc-length spacing, end points kept exactly."""
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    n = int(np.clip(np.ceil(s[-1] / ds) + 1, n_min, n_max))
    idx = np.unique(np.searchsorted(s, np.linspace(0.0, s[-1], n)).clip(0, len(pts) - 1))
    idx[0], idx[-1] = 0, len(pts) - 1
    return pts[np.unique(idx)]


def _section_pieces(spec: SegmentSpec) -> list[_Piece]:
    """The closed transverse boundary as an ordered chain of pieces (clockwise over the teeth)."""
    xy = np.asarray(spec.outline, dtype=float)
    kind = np.asarray(spec.kind, dtype=int)
    side = np.asarray(spec.side, dtype=int)
    pitch = 2.0 * np.pi / spec.z
    brk = np.flatnonzero((np.diff(kind) != 0) | (np.diff(side) != 0)) + 1
    starts, ends = np.r_[0, brk], np.r_[brk, len(xy) - 1]      # run i covers starts[i]..ends[i]
    ds = 0.1
    gap = np.linalg.norm(_rot2(xy[:1], -pitch) - xy[-1:])
    if gap > 1e-3:
        raise ValueError(f"outline end points are {gap:.3g} mm apart from their neighbours' after a "
                         f"rotation by 2 pi / z: outline must run from mid-gap +pi/z to -pi/z")
    pieces: list[_Piece] = []
    for k in spec.teeth:
        for a, b in zip(starts, ends):
            if b <= a:
                continue
            dense = _rot2(xy[a:b + 1], -k * pitch)
            kd, sd = int(kind[a]), int(side[a])
            if kd == 0:
                label = "root"
            elif kd == 3 or sd == 0:
                label = f"{_KIND_NAMES[kd]}_{k}"
            else:
                label = f"{_KIND_NAMES[kd]}_{k}_{_SIDE_NAMES[sd]}"
            pieces.append(_Piece(label, "spline", _subsample(dense, ds), dense))
    p_end, p_start = pieces[-1].pts[-1], pieces[0].pts[0]
    b_end = p_end * spec.r_bore / np.linalg.norm(p_end)
    b_start = p_start * spec.r_bore / np.linalg.norm(p_start)
    cut = "cut"
    closing = "rim" if spec.internal else "bore"
    pieces.append(_Piece(cut, "line", np.array([p_end, b_end]), np.linspace(p_end, b_end, 50)))
    a0 = np.arctan2(b_end[1], b_end[0])
    span = len(spec.teeth) * pitch                               # counter-clockwise back to b_start
    n_arc = int(np.ceil(span / (np.pi / 2)))
    ang = a0 + np.linspace(0.0, span, n_arc + 1)
    for i in range(n_arc):
        t = np.linspace(ang[i], ang[i + 1], 200)
        ref = spec.r_bore * np.c_[np.cos(t), np.sin(t)]
        pieces.append(_Piece(closing, "arc", ref[[0, -1]], ref))
    pieces.append(_Piece(cut, "line", np.array([b_start, p_start]), np.linspace(b_start, p_start, 50)))
    return pieces


def _add_wire(pieces: list[_Piece], phi: float, zc: float) -> list[int]:
    """gmsh OCC curves of the chain rotated by ``phi`` about +z and placed at axial position ``zc``."""
    import gmsh

    occ = gmsh.model.occ

    def point(p2: np.ndarray) -> int:
        q = _rot2(p2[None, :], phi)[0]                           # rotation by +phi (counter-clockwise)
        return occ.addPoint(float(q[0]), float(q[1]), zc)

    first = point(pieces[0].pts[0])
    prev = first
    centre = occ.addPoint(0.0, 0.0, zc)
    curves = []
    for i, pc in enumerate(pieces):
        last = first if i == len(pieces) - 1 else point(pc.pts[-1])
        if pc.kind == "spline":
            tags = [prev] + [point(p) for p in pc.pts[1:-1]] + [last]
            curves.append(occ.addSpline(tags))
        elif pc.kind == "line":
            curves.append(occ.addLine(prev, last))
        else:
            curves.append(occ.addCircleArc(prev, centre, last))
        prev = last
    return curves


# ----------------------------------------------------------------------------------------------
# solid, surface labels, size field, mesh extraction
# ----------------------------------------------------------------------------------------------
def _build_solid(spec: SegmentSpec, pieces: list[_Piece]) -> int:
    """The OCC volume: extrusion (spur) or thru-sections of twisted copies (helical)."""
    import gmsh

    occ = gmsh.model.occ
    b = float(spec.face_width)
    if spec.lead_twist == 0.0:
        loop = occ.addCurveLoop(_add_wire(pieces, 0.0, -b / 2))
        face = occ.addPlaneSurface([loop])
        out = occ.extrude([(2, face)], 0.0, 0.0, b)
        return next(t for d, t in out if d == 3)
    n_sec = max(4, int(np.ceil(abs(spec.lead_twist) * b / 0.02)) + 1)
    wires = [occ.addWire(_add_wire(pieces, spec.lead_twist * zc, zc))
             for zc in np.linspace(-b / 2, b / 2, n_sec)]
    out = occ.addThruSections(wires, makeSolid=True, makeRuled=False)
    return next(t for d, t in out if d == 3)


def _polyline_distance(p: np.ndarray, poly: np.ndarray) -> float:
    """Distance from point ``p`` (2,) to the polyline ``poly`` (m, 2)."""
    a, d = poly[:-1], np.diff(poly, axis=0)
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0, 1)
    return float(np.min(np.hypot(*(a + t[:, None] * d - p).T)))


def _label_surfaces(spec: SegmentSpec, pieces: list[_Piece], vol: int) -> dict[int, str]:
    """Name each boundary surface of the volume by the transverse curve it was swept from.

    A surface's parametric mid-point is rotated back by ``-lead_twist * z`` and matched to the
    nearest piece of the transverse section; surfaces at z = +-b/2 are the ends.
    """
    import gmsh

    half = 0.5 * spec.face_width
    names: dict[int, str] = {}
    for _, tag in gmsh.model.getBoundary([(3, vol)], oriented=False):
        lo, hi = gmsh.model.getParametrizationBounds(2, tag)
        x, y, zc = gmsh.model.getValue(2, tag, 0.5 * (np.asarray(lo) + np.asarray(hi)))
        if abs(abs(zc) - half) < 1e-6 * max(1.0, half):
            normal = gmsh.model.getNormal(tag, 0.5 * (np.asarray(lo) + np.asarray(hi)))
            if abs(normal[2]) > 0.999:
                names[tag] = "ends"
                continue
        p = _rot2(np.array([[x, y]]), -spec.lead_twist * zc)[0]
        dist = [_polyline_distance(p, pc.ref) for pc in pieces]
        i = int(np.argmin(dist))
        if dist[i] > 1e-2:
            raise RuntimeError(f"surface {tag} matches no transverse curve (distance {dist[i]:.3g} mm)")
        names[tag] = pieces[i].label
    return names


def _set_size_field(spec: SegmentSpec, fine: list[int]) -> None:
    """h_flank on the ``fine`` surfaces, growing linearly (slope 0.3) to h_body with distance; the minimum
    with the spec's extra ``size_fields``."""
    import gmsh

    fld = gmsh.model.mesh.field
    extent = max(spec.face_width, 10.0)
    sampling = int(np.clip(np.ceil(2.0 * extent / spec.h_flank), 20, 300))
    dist = fld.add("Distance")
    fld.setNumbers(dist, "SurfacesList", fine)
    fld.setNumber(dist, "Sampling", sampling)
    d_min = max(0.5 * spec.h_flank, extent / sampling)
    thr = fld.add("Threshold")
    fld.setNumber(thr, "InField", dist)
    fld.setNumber(thr, "SizeMin", spec.h_flank)
    fld.setNumber(thr, "SizeMax", spec.h_body)
    fld.setNumber(thr, "DistMin", d_min)
    fld.setNumber(thr, "DistMax", d_min + (spec.h_body - spec.h_flank) / 0.3)
    if not spec.size_fields:
        fld.setAsBackgroundMesh(thr)
        return
    tags = [thr]
    for expr in spec.size_fields:
        f = fld.add("MathEval")
        fld.setString(f, "F", expr)
        tags.append(f)
    m = fld.add("Min")
    fld.setNumbers(m, "FieldsList", tags)
    fld.setAsBackgroundMesh(m)


class _FaceIndex:
    """Sorted keys of all tetrahedron faces, to find the tetrahedron behind a boundary triangle."""

    def __init__(self, tets: np.ndarray, n_nodes: int) -> None:
        self.n = np.int64(n_nodes)
        faces = tets[:, [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]]]      # face i opposite vertex i
        self.keys = self._key(faces.reshape(-1, 3))
        self.order = np.argsort(self.keys)
        self.opp = tets[:, :4].reshape(-1)

    def _key(self, tri: np.ndarray) -> np.ndarray:
        s = np.sort(tri.astype(np.int64), axis=1)
        return (s[:, 0] * self.n + s[:, 1]) * self.n + s[:, 2]

    def opposite(self, tri: np.ndarray) -> np.ndarray:
        """The fourth vertex of the tetrahedron owning each triangle (k, >=3) -> (k,)."""
        tk = self._key(tri[:, :3])
        hit = self.order[np.clip(np.searchsorted(self.keys, tk, sorter=self.order), 0,
                                 len(self.order) - 1)]
        if not np.all(self.keys[hit] == tk):
            raise RuntimeError("boundary triangle that is not a tetrahedron face")
        return self.opp[hit]


def _orient_outward(tri: np.ndarray, faces: _FaceIndex, nodes: np.ndarray) -> np.ndarray:
    """Flip boundary triangles (k, 3 or 6) whose normal points into their tetrahedron."""
    if len(tri) == 0:
        return tri
    v = nodes[tri[:, :3]]
    nrm = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    inward = np.einsum("ij,ij->i", nrm, nodes[faces.opposite(tri)] - v[:, 0]) > 0
    out = tri.copy()
    out[inward] = tri[inward][:, _FLIP_TRI6[:tri.shape[1]]]
    return out


def _remove_strays(vol: int) -> None:
    """Delete CAD entities outside the closure of the volume (spline through-points, arc centres)."""
    import gmsh

    keep = {(3, vol)}
    level = [(3, vol)]
    for _ in range(3):
        level = gmsh.model.getBoundary(level, combined=False, oriented=False)
        keep.update((d, abs(t)) for d, t in level)
    strays = [e for d in (2, 1, 0) for e in gmsh.model.getEntities(d) if e not in keep]
    if strays:
        gmsh.model.occ.remove(strays)
        gmsh.model.occ.synchronize()


_OPTIONS = {"General.NumThreads": 1, "Mesh.MeshSizeFromPoints": 0,
            "Mesh.MeshSizeExtendFromBoundary": 0, "Mesh.MeshSizeFromCurvature": 0,
            "Mesh.SecondOrderLinear": 1, "Mesh.Algorithm": 6, "Mesh.Algorithm3D": 1,
            "Mesh.Optimize": 1, "Mesh.ElementOrder": 1}


def _mesh_with_gmsh(spec: SegmentSpec) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Build, label and mesh the segment in a fresh gmsh model; return nodes, tets, facets."""
    import gmsh

    old = {k: gmsh.option.getNumber(k) for k in _OPTIONS}
    prev_model = gmsh.model.getCurrent()
    name = f"segment_{spec.spec_hash}"
    gmsh.model.add(name)
    try:
        for k, v in _OPTIONS.items():
            gmsh.option.setNumber(k, v)
        gmsh.option.setNumber("Mesh.MeshSizeMax", spec.h_body)
        pieces = _section_pieces(spec)
        vol = _build_solid(spec, pieces)
        gmsh.model.occ.synchronize()
        _remove_strays(vol)
        labels = _label_surfaces(spec, pieces, vol)
        fine = [t for t, s in labels.items() if s.split("_")[0] in ("flank", "fillet", "tip")]
        _set_size_field(spec, fine)
        for label in sorted(set(labels.values())):
            gmsh.model.addPhysicalGroup(2, [t for t, s in labels.items() if s == label], name=label)
        gmsh.model.addPhysicalGroup(3, [vol], name="body")
        gmsh.model.mesh.generate(3)
        if spec.order == 2:
            gmsh.model.mesh.setOrder(2)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
        index[tags.astype(np.int64)] = np.arange(len(tags))
        nodes = coords.reshape(-1, 3)
        etype, npe = (11, 10) if spec.order == 2 else (4, 4)
        _, conn = gmsh.model.mesh.getElementsByType(etype)
        tets = index[conn.astype(np.int64)].reshape(-1, npe)
        if spec.order == 2:
            tets = tets[:, _GMSH_TO_MESHIO_TET10]
        used = np.zeros(len(nodes), dtype=bool)
        used[tets] = True
        index[tags.astype(np.int64)] = np.cumsum(used) - 1              # drop nodes of no tetrahedron
        nodes = nodes[used]
        tets = np.cumsum(used)[tets] - 1
        ttype, tpe = (9, 6) if spec.order == 2 else (2, 3)
        parts: dict[str, list[np.ndarray]] = {}
        for tag, label in labels.items():
            _, conn = gmsh.model.mesh.getElementsByType(ttype, tag)
            parts.setdefault(label, []).append(index[conn.astype(np.int64)].reshape(-1, tpe))
        faces = _FaceIndex(tets, len(nodes))
        facets = {k: _orient_outward(np.concatenate(v), faces, nodes) for k, v in sorted(parts.items())}
    finally:
        gmsh.model.remove()
        if prev_model and prev_model in gmsh.model.list():
            gmsh.model.setCurrent(prev_model)
        for k, v in old.items():
            gmsh.option.setNumber(k, v)
    return nodes, tets, facets
