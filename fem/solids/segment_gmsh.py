"""gmsh construction of a tooth segment: OCC solid, surface labels, size field, mesh extraction.

The internals behind :func:`fem.solids.segment.build_segment`; the transverse section comes from
:mod:`fem.solids.section`, conventions (points, tooth rotation, helical twist, 10-node tetrahedron
order) are those of :mod:`fem.solids.spec`. The gmsh calls run in a fixed order with fixed numbers: the
mesh, and any deck written from it, is bit-identical for one spec.
"""
from __future__ import annotations

import contextlib
from typing import Callable, Iterator

import numpy as np

from .section import SectionPiece, rot2, section_pieces
from .spec import SegmentSpec

__all__ = ["mesh_with_gmsh", "extract_mesh", "polyline_distance", "background_size", "fresh_model", "mesh_labelled"]

_GMSH_TO_MESHIO_TET10 = np.array([0, 1, 2, 3, 4, 5, 6, 7, 9, 8])
_FLIP_TRI6 = np.array([0, 2, 1, 5, 4, 3])


def _add_wire(pieces: list[SectionPiece], phi: float, zc: float) -> list[int]:
    """gmsh OCC curves of the chain rotated by ``phi`` about +z and placed at axial position ``zc``."""
    import gmsh

    occ = gmsh.model.occ

    def point(p2: np.ndarray) -> int:
        q = rot2(p2[None, :], phi)[0]                           # rotation by +phi (counter-clockwise)
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
def _build_solid(spec: SegmentSpec, pieces: list[SectionPiece]) -> int:
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


def polyline_distance(p: np.ndarray, poly: np.ndarray) -> float:
    """Distance from point ``p`` (2,) to the polyline ``poly`` (m, 2)."""
    a, d = poly[:-1], np.diff(poly, axis=0)
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0, 1)
    return float(np.min(np.hypot(*(a + t[:, None] * d - p).T)))


class Polylines:
    """Distances from points to each of several polylines at once (:func:`polyline_distance` of each, the same
    arithmetic segment by segment): a body's labelling matches a hundred surfaces against tens of curves."""

    def __init__(self, polys: list[np.ndarray]):
        polys = [np.asarray(p, float) for p in polys]
        self.a = np.concatenate([p[:-1] for p in polys])
        self.d = np.concatenate([np.diff(p, axis=0) for p in polys])
        self.dd = np.maximum(np.einsum("ij,ij->i", self.d, self.d), 1e-300)
        self.start = np.cumsum([0] + [len(p) - 1 for p in polys[:-1]])

    def distance(self, p: np.ndarray) -> np.ndarray:
        """Distance from point ``p`` (2,) to every polyline, (n_polylines,)."""
        t = np.clip(np.einsum("ij,ij->i", p - self.a, self.d) / self.dd, 0, 1)
        return np.minimum.reduceat(np.hypot(*(self.a + t[:, None] * self.d - p).T), self.start)


def _label_surfaces(spec: SegmentSpec, pieces: list[SectionPiece], vol: int) -> dict[int, str]:
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
        p = rot2(np.array([[x, y]]), -spec.lead_twist * zc)[0]
        dist = [polyline_distance(p, pc.ref) for pc in pieces]
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
    background_size(thr, spec.size_fields)


def background_size(field: int | list[int], expressions: tuple[str, ...] = ()) -> None:
    """Make gmsh size field(s) ``field``, with the ``MathEval`` size ``expressions`` (in x, y, z, mm), the background
    mesh size of the current model: their minimum where there are several."""
    import gmsh

    fld = gmsh.model.mesh.field
    tags = [field] if isinstance(field, int) else list(field)
    for expr in expressions:
        f = fld.add("MathEval")
        fld.setString(f, "F", expr)
        tags.append(f)
    if len(tags) == 1:
        fld.setAsBackgroundMesh(tags[0])
        return
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


def mesh_with_gmsh(spec: SegmentSpec) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Build, label and mesh the segment in a fresh gmsh model; return nodes, tets, facets.

    Parameters
    ----------
    spec : SegmentSpec
        Geometry and mesh sizes. gmsh must be initialised (:func:`fem.solids.session.gmsh_session`); the
        model is removed and the previous model and options are restored on exit.

    Returns
    -------
    nodes, tets, facets
        As the fields of :class:`fem.solids.spec.SegmentMesh`.
    """
    with fresh_model(f"segment_{spec.spec_hash}", _OPTIONS):
        import gmsh
        gmsh.option.setNumber("Mesh.MeshSizeMax", spec.h_body)
        pieces = section_pieces(spec)
        vol = _build_solid(spec, pieces)
        gmsh.model.occ.synchronize()
        _remove_strays(vol)
        labels = _label_surfaces(spec, pieces, vol)
        return mesh_labelled(labels, [vol], spec.order, lambda fine: _set_size_field(spec, fine))


@contextlib.contextmanager
def fresh_model(name: str, options: dict[str, float]) -> Iterator[None]:
    """A new gmsh model with ``options`` set, for the duration of a ``with`` block; on exit the model is removed
    and the previous model and option values are restored (gmsh must be initialised)."""
    import gmsh

    old = {k: gmsh.option.getNumber(k) for k in options}
    prev_model = gmsh.model.getCurrent() if gmsh.model.list() else ""
    gmsh.model.add(name)
    try:
        for k, v in options.items():
            gmsh.option.setNumber(k, v)
        yield
    finally:
        gmsh.model.remove()
        if prev_model and prev_model in gmsh.model.list():
            gmsh.model.setCurrent(prev_model)
        for k, v in old.items():
            gmsh.option.setNumber(k, v)


def mesh_labelled(labels: dict[int, str], volumes: list[int], order: int,
                  set_sizes: Callable[[list[int]], None]) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Size (``set_sizes`` gets the flank, fillet and tip surfaces), group, mesh and read the current model."""
    import gmsh

    fine = [t for t, s in labels.items() if s.split("_")[0] in ("flank", "fillet", "tip")]
    set_sizes(fine)
    for label in sorted(set(labels.values())):
        gmsh.model.addPhysicalGroup(2, [t for t, s in labels.items() if s == label], name=label)
    gmsh.model.addPhysicalGroup(3, volumes, name="body")
    gmsh.model.mesh.generate(3)
    if order == 2:
        gmsh.model.mesh.setOrder(2)
    return extract_mesh(labels, order)


def extract_mesh(labels: dict[int, str], order: int) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Nodes, tetrahedra (meshio order) and named, outward-oriented facets of the current gmsh model.

    ``labels`` maps boundary surface tags to facet group names; nodes of no tetrahedron are dropped.
    """
    import gmsh

    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    nodes = coords.reshape(-1, 3)
    etype, npe = (11, 10) if order == 2 else (4, 4)
    _, conn = gmsh.model.mesh.getElementsByType(etype)
    tets = index[conn.astype(np.int64)].reshape(-1, npe)
    if order == 2:
        tets = tets[:, _GMSH_TO_MESHIO_TET10]
    used = np.zeros(len(nodes), dtype=bool)
    used[tets] = True
    index[tags.astype(np.int64)] = np.cumsum(used) - 1              # drop nodes of no tetrahedron
    nodes = nodes[used]
    tets = np.cumsum(used)[tets] - 1
    ttype, tpe = (9, 6) if order == 2 else (2, 3)
    parts: dict[str, list[np.ndarray]] = {}
    for tag, label in labels.items():
        _, conn = gmsh.model.mesh.getElementsByType(ttype, tag)
        parts.setdefault(label, []).append(index[conn.astype(np.int64)].reshape(-1, tpe))
    faces = _FaceIndex(tets, len(nodes))
    facets = {k: _orient_outward(np.concatenate(v), faces, nodes) for k, v in sorted(parts.items())}
    return nodes, tets, facets
