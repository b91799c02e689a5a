"""gmsh construction of a tooth segment: OCC solid, surface labels, size field, then the shared meshing.

The internals behind :func:`tools.segment_mesh.build_segment`; the transverse section comes from
:mod:`tools.segment_mesh.section`, the record of what to mesh from :mod:`tools.segment_mesh.spec`, the
meshing and read-back from :mod:`ltca.fem.solids.gmsh_mesh`.
"""
from __future__ import annotations

import numpy as np

from ltca.fem.solids.gmsh_mesh import background_size, fresh_model, mesh_labelled
from ltca.fem.solids.planar import polyline_distance, rot2

from .section import SectionPiece, section_pieces
from .spec import SegmentSpec

__all__ = ["mesh_with_gmsh"]


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
        Geometry and mesh sizes. gmsh must be initialised (:func:`ltca.fem.solids.session.gmsh_session`); the
        model is removed and the previous model and options are restored on exit.

    Returns
    -------
    nodes, tets, facets
        As the fields of :class:`ltca.fem.solids.mesh_record.BodyMesh`.
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
