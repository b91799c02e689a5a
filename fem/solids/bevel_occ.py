"""A whole bevel member as an OpenCASCADE solid (gmsh OCC), meshed with contact-refined quadratic tetrahedra.

The independent body of the bevel CalculiX check, built apart from our mapped compliance body
(:mod:`ltca.fem.solids.bevel_body`): a different geometry kernel, topology, mesher and support.

* **Teeth.** One tooth is lofted (``addThruSections``) through sections of constant cone distance L (each
  section lies on a cone normal to the pitch cone, so the first and last are the front and back cones): in each,
  interpolating splines through exact points of both generated flanks (depth fraction t = 0..1 of the flank
  record), the top land as a spline arc at the face cone, and below t = 0 straight legs (constant polar angle)
  down to ``leg_depth`` under the root cone joined by an arc, so that the tooth's foot lies inside the blank.
  The toe and heel caps are filling surfaces; the shell is sewn into a solid.  Every tooth of the member is a
  rotated copy.
* **Blank.** The axial-section polygon ``outline`` (Z, rho), whose first edge is the root cone from toe to heel,
  revolved through 360 deg and fused with all teeth: the root land between the teeth is the root cone.
* **Mesh.** gmsh Frontal-Delaunay surfaces and Delaunay volumes, second order (C3D10, straight edges: curved
  ones gave a nonpositive Jacobian in a coarse fillet), sized by the distance to the contact zone points ``zone``
  (``h_zone + grow * d``, at most ``h_body``).  The nodes of the anchor-side flanks of ``snap_teeth`` above depth
  fraction ``snap_from`` (the fillet below it is left on its chords) are then moved in polar angle onto the exact
  generated surface (:func:`ltca.geometry.bevel.sampling.flank_at`): the contact surfaces carry no spline or chord
  error.

Facet groups: ``flank_{k}_{concave|convex}`` for k in ``name_teeth`` (k = tooth index, counter-clockwise about
+z), and one group per named outline edge (``supports``: name -> edge index).  Frame: the member's body frame
(z along the axis, origin at the pitch apex), mm.  CAD approach after the loft/sew/boolean recipes of the gmsh
OCC API (C. Geuzaine, J.-F. Remacle, gmsh reference manual, sec. 6, ``occ.addThruSections``, ``occ.fuse``).
"""
from __future__ import annotations

import hashlib
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ltca.geometry.bevel.sampling import flank_at
from ltca.geometry.flank import Flank

from .gmsh_mesh import extract_mesh, fresh_model
from .mesh_record import BodyMesh
from .session import gmsh_session

__all__ = ["BevelSolidSpec", "build_bevel_solid", "member_solid", "polar", "flank_t"]

_VERSION = "bevel-occ-4"


@dataclass(frozen=True)
class BevelSolidSpec:
    """A bevel member to build (module docstring); mm, rad.

    concave, convex : generated flanks on one axial grid (body frame, lowest row ``root_offset`` above the root
    cone);  z : teeth;  pitch_angle : pitch cone angle;  anchor : the flank kept where it was generated (the
    loaded one); the other is turned about z so that the tooth's angular thickness at (``t_ref``, ``L_ref``) is
    ``thickness``;  outline : (k, 2) blank polygon (Z, rho), edge 0 the root cone toe -> heel;  supports : facet
    group name -> outline edge index;  zone : (m, 3) contact-zone points;  h_zone, grow, h_body : sizes.
    """
    concave: Flank
    convex: Flank
    z: int
    pitch_angle: float
    root_offset: float
    anchor: str
    thickness: float
    t_ref: float
    L_ref: float
    outline: np.ndarray
    supports: dict
    zone: np.ndarray
    h_zone: float
    h_body: float
    grow: float = 0.35
    h_tooth: float = 2.0
    leg_depth: float = 1.0
    sections: int = 15
    rows: int = 21
    name_teeth: tuple = (-2, -1, 0, 1, 2)
    snap_teeth: tuple = ()
    snap_from: float = 0.15
    cad_cache: str | None = None
    extra: dict = field(default_factory=dict)


def polar(p: np.ndarray) -> np.ndarray:
    return np.arctan2(p[..., 1], p[..., 0])


def flank_t(fl: Flank, pitch_angle: float, P: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Depth fraction t and cone distance L of body-frame points on the flank record's axial grid."""
    Z, rho = P[..., 2], np.hypot(P[..., 0], P[..., 1])
    L = Z * np.cos(pitch_angle) + rho * np.sin(pitch_angle)
    Rn = -Z * np.sin(pitch_angle) + rho * np.cos(pitch_angle)
    Rg = np.asarray(fl.meta["Rn"])
    lo, hi = np.interp(L, fl.v, Rg[0]), np.interp(L, fl.v, Rg[-1])
    return (Rn - lo) / (hi - lo), L


def _shift(spec: BevelSolidSpec) -> float:
    """Rotation of the non-anchor flank (rad) that sets the tooth thickness."""
    fa = spec.concave if spec.anchor == "concave" else spec.convex
    fo = spec.convex if spec.anchor == "concave" else spec.concave
    pa, na, _ = flank_at(fa, np.array([spec.t_ref]), np.array([spec.L_ref]))
    po, no, _ = flank_at(fo, np.array([spec.t_ref]), np.array([spec.L_ref]))
    side = np.sign(pa[0, 0] * na[0, 1] - pa[0, 1] * na[0, 0])          # + : normal along e_theta
    if side == np.sign(po[0, 0] * no[0, 1] - po[0, 1] * no[0, 0]):
        raise ValueError("both flanks face the same way; not the two sides of a tooth")
    target = polar(pa[0]) - side * spec.thickness           # the material lies against the normal
    return float((target - polar(po[0]) + np.pi) % (2 * np.pi) - np.pi)   # not modulo a pitch: that is the slot


def _rz(p: np.ndarray, a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.stack([c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1], p[..., 2]], -1)


def _arc(p: np.ndarray, q: np.ndarray, n: int = 5) -> np.ndarray:
    """Points from p to q at p's (Z, rho) turning in polar angle (p, q at the same Z, rho)."""
    a0, a1 = polar(p), polar(q)
    a1 = a0 + (a1 - a0 + np.pi) % (2 * np.pi) - np.pi
    r = np.hypot(p[0], p[1])
    a = np.linspace(a0, a1, n)
    return np.column_stack([r * np.cos(a), r * np.sin(a), np.full(n, p[2])])


def _tooth(spec: BevelSolidSpec, shift: float) -> int:
    """OCC volume of tooth 0 (module docstring)."""
    import gmsh
    occ = gmsh.model.occ
    g = spec.pitch_angle
    fl = {s: getattr(spec, s) for s in ("concave", "convex")}
    t = 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, spec.rows)))     # rows clustered at the fillet and tip
    L = np.linspace(fl["concave"].v[0], fl["concave"].v[-1], spec.sections)
    T, LL = np.meshgrid(t, L, indexing="ij")
    P = {s: flank_at(fl[s], T, LL)[0] for s in fl}
    other = "convex" if spec.anchor == "concave" else "concave"
    P[other] = _rz(P[other], shift)
    root = np.interp(L, fl["concave"].v, np.asarray(fl["concave"].meta["Rn"])[0]) - spec.root_offset
    wires = []
    for j in range(len(L)):
        a, b = P["concave"][:, j], P["convex"][:, j]
        Rn_leg = root[j] - spec.leg_depth
        feet = []
        for p in (a[0], b[0]):
            r, ang = L[j] * np.sin(g) + Rn_leg * np.cos(g), polar(p)
            feet.append(np.array([r * np.cos(ang), r * np.sin(ang), L[j] * np.cos(g) - Rn_leg * np.sin(g)]))

        def pts(X):
            return [occ.addPoint(*x) for x in X]
        ca, cb = pts(a), pts(b)
        fa, fb = pts(feet)
        top = pts(_arc(a[-1], b[-1])[1:-1])
        bot = pts(_arc(feet[1], feet[0])[1:-1])
        curves = [occ.addSpline(ca), occ.addSpline([ca[-1], *top, cb[-1]]), occ.addSpline(cb[::-1]),
                  occ.addLine(cb[0], fb), occ.addSpline([fb, *bot, fa]), occ.addLine(fa, ca[0])]
        wires.append(occ.addWire(curves, checkClosed=True))
    shell = occ.addThruSections(wires, makeSolid=False, makeRuled=False)
    caps = [occ.addSurfaceFilling(wires[0]), occ.addSurfaceFilling(wires[-1])]
    loop = occ.addSurfaceLoop([s for d, s in shell if d == 2] + caps, sewing=True)
    return occ.addVolume([loop])


def _fused(spec: BevelSolidSpec, shift: float) -> list:
    """Every tooth (copies of tooth 0) fused with the revolved blank."""
    import gmsh
    occ = gmsh.model.occ
    tooth = _tooth(spec, shift)
    # copies alternately on both sides, the last one opposite tooth 0 (OCC dropped the flanks of the last copy
    # of the fuse once: it must be far from the mesh)
    order = sorted(range(1, spec.z), key=lambda k: (min(k, spec.z - k), k > spec.z - k))
    teeth = [(3, tooth)] + [occ.copy([(3, tooth)])[0] for _ in order]
    for k, dt in zip(order, teeth[1:]):
        occ.rotate([dt], 0, 0, 0, 0, 0, 1, k * 2 * np.pi / spec.z)
    fused, _ = occ.fuse(_blank(spec), teeth)
    return fused


def _blank(spec: BevelSolidSpec) -> list:
    """The blank: the axial-section polygon ``outline`` revolved through 360 deg, its seam opposite tooth 0."""
    import gmsh
    occ = gmsh.model.occ
    O = np.asarray(spec.outline, float)
    pts = [occ.addPoint(-r, 0.0, zz) for zz, r in O]
    loop = occ.addCurveLoop([occ.addLine(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))])
    blank = occ.revolve([(2, occ.addPlaneSurface([loop]))], 0, 0, 0, 0, 0, 1, 2 * np.pi)
    return [d for d in blank if d[0] == 3]


def member_solid(spec: BevelSolidSpec, progress=None) -> list:
    """The whole member as one OCC volume in the current gmsh model, (dim, tag) pairs; gmsh must be initialised
    with a model current.

    The teeth of :func:`build_bevel_solid`'s solid, fused with the blank one at a time: one fuse of all the teeth
    at once (the meshed solid, whose far teeth carry no load) can lose a whole tooth; one at a time keeps every
    tooth (tests/fem/solids/test_step_export.py compares the volume with the FE body's), at about the same cost."""
    import gmsh
    occ = gmsh.model.occ
    say = progress or (lambda m: None)
    tooth = (3, _tooth(spec, _shift(spec)))
    teeth = [tooth] + [occ.copy([tooth])[0] for _ in range(1, spec.z)]
    for k, t in enumerate(teeth[1:], 1):
        occ.rotate([t], 0, 0, 0, 0, 0, 1, k * 2 * np.pi / spec.z)
    solid = _blank(spec)
    for k, t in enumerate(teeth):
        solid = [d for d in occ.fuse(solid, [t])[0] if d[0] == 3]
        say(f"  tooth {k + 1}/{spec.z} fused")
    return solid


def _cad_key(spec: BevelSolidSpec) -> str:
    """Hash of what the solid's geometry depends on (not the mesh sizes or the zone)."""
    h = hashlib.sha256(_VERSION.encode())
    for a in (spec.concave.points, spec.convex.points, spec.outline,
              [spec.z, spec.pitch_angle, spec.root_offset, spec.thickness, spec.t_ref, spec.L_ref, spec.leg_depth,
               spec.sections, spec.rows]):
        h.update(np.ascontiguousarray(np.asarray(a, float)).tobytes())
    h.update(spec.anchor.encode())
    return h.hexdigest()[:16]


def _sizes(spec: BevelSolidSpec):
    from scipy.spatial import cKDTree
    tree = cKDTree(np.asarray(spec.zone, float))
    pitch = 2 * np.pi / spec.z
    za = polar(np.asarray(spec.zone, float))
    mid = float(np.angle(np.exp(1j * za).mean()))
    half = float(np.max(np.abs((za - mid + np.pi) % (2 * np.pi) - np.pi))) + 1.5 * pitch

    def size(dim, tag, x, y, z, lc):
        d = tree.query([x, y, z])[0]
        h = spec.h_zone + spec.grow * d
        if abs((np.arctan2(y, x) - mid + np.pi) % (2 * np.pi) - np.pi) < half:
            h = min(h, spec.h_tooth)
        return float(min(h, spec.h_body))
    return size


def _labels(spec: BevelSolidSpec, shift: float, vol: list) -> dict[int, str]:
    """Facet group of each boundary surface of the fused solid, found from its mesh nodes."""
    import gmsh
    g = spec.pitch_angle
    out: dict[int, str] = {}
    O = np.asarray(spec.outline, float)
    for _, tag in gmsh.model.getBoundary(vol, oriented=False):
        X = gmsh.model.mesh.getNodes(2, tag, includeBoundary=False)[1].reshape(-1, 3)
        if len(X) == 0:
            continue
        Zr = np.column_stack([X[:, 2], np.hypot(X[:, 0], X[:, 1])])
        for name, e in spec.supports.items():
            p, q = O[e], O[(e + 1) % len(O)]
            d = np.abs(np.cross(q - p, Zr - p)) / np.linalg.norm(q - p)
            if np.all(d < 1e-3):
                out[tag] = name
        if tag in out:
            continue
        pitch = 2 * np.pi / spec.z
        S = X[np.linspace(0, len(X) - 1, min(len(X), 15)).astype(int)]
        for side in ("concave", "convex"):
            fl = getattr(spec, side)
            tt, LL = flank_t(fl, g, S)
            if not (np.all(tt > -0.02) and np.all(tt < 1.02)):
                continue
            Q = flank_at(fl, np.clip(tt, 0.0, 1.0), np.clip(LL, fl.v[0], fl.v[-1]))[0]
            da = polar(S) - polar(Q) - (shift if side != spec.anchor else 0.0)
            kk = np.round(da / pitch)
            miss = np.hypot(S[:, 0], S[:, 1]) * np.abs(da - kk * pitch)
            k = int((kk[0] + spec.z // 2) % spec.z - spec.z // 2)
            if np.all(kk == kk[0]) and miss.max() < 0.05 and k in spec.name_teeth:
                out[tag] = f"flank_{k}_{side}"
    return out


def _snap(spec: BevelSolidSpec, nodes: np.ndarray, facets: dict) -> float:
    """Move the anchor flanks' nodes of ``snap_teeth`` onto the exact surface in polar angle; largest move, mm."""
    fl = getattr(spec, spec.anchor)
    moved = 0.0
    for k in spec.snap_teeth:
        name = f"flank_{k}_{spec.anchor}"
        if name not in facets:
            raise ValueError(f"no {name} surface in the bevel solid")
        tri = facets[name][:: max(1, len(facets[name]) // 25)]
        V = nodes[tri[:, :3]]
        nf = np.cross(V[:, 1] - V[:, 0], V[:, 2] - V[:, 0])
        tc, Lc = flank_t(fl, spec.pitch_angle, _rz(V.mean(1), -k * 2 * np.pi / spec.z))
        ne = _rz(flank_at(fl, np.clip(tc, 0, 1), np.clip(Lc, fl.v[0], fl.v[-1]))[1], k * 2 * np.pi / spec.z)
        if np.median(np.einsum("ij,ij->i", nf, ne)) <= 0.0:
            raise ValueError(f"{name}: the solid's material lies on the wrong side of the generated flank")
        ids = np.unique(facets[name])
        P = _rz(nodes[ids], -k * 2 * np.pi / spec.z)
        t, L = flank_t(fl, spec.pitch_angle, P)
        ok = (t >= spec.snap_from) & (t <= 1.0) & (L >= fl.v[0]) & (L <= fl.v[-1])
        Q = flank_at(fl, t[ok], L[ok])[0]
        a = polar(Q) + k * 2 * np.pi / spec.z
        rho = np.hypot(nodes[ids[ok], 0], nodes[ids[ok], 1])
        new = np.column_stack([rho * np.cos(a), rho * np.sin(a), nodes[ids[ok], 2]])
        if ok.any():
            dist = np.linalg.norm(new - nodes[ids[ok]], axis=1)
            moved = max(moved, float(dist.max()))
            for lo in (0.0, 0.1, 0.2, 0.3, 0.5, 0.8):
                sel = t[ok] >= lo
                spec.extra.setdefault("snap_by_t", {})[f"{name} t>={lo}"] = float(dist[sel].max()) if sel.any() else 0.0
        nodes[ids[ok]] = new
    return moved


_OPTIONS = {"General.NumThreads": 2, "Mesh.MeshSizeFromPoints": 0, "Mesh.MeshSizeExtendFromBoundary": 0,
            "Mesh.MeshSizeFromCurvature": 0, "Mesh.SecondOrderLinear": 1, "Mesh.Algorithm": 6,
            "Mesh.Algorithm3D": 1, "Mesh.Optimize": 1, "Mesh.ElementOrder": 1, "Geometry.Tolerance": 1e-6,
            "Geometry.OCCParallel": 1}


def build_bevel_solid(spec: BevelSolidSpec, progress=None) -> BodyMesh:
    """Build and mesh the member ``spec``; ``extra`` of the record's spec gets the snap distance."""
    import gmsh
    say = progress or (lambda m: None)
    t0 = time.perf_counter()
    shift = _shift(spec)
    with gmsh_session(False):
        with fresh_model("bevel_occ", _OPTIONS):
            occ = gmsh.model.occ
            cad = Path(spec.cad_cache) / f"bevel_{_cad_key(spec)}.brep" if spec.cad_cache else None
            if cad is not None and cad.exists():
                fused = [d for d in occ.importShapes(str(cad)) if d[0] == 3]
            else:
                fused = _fused(spec, shift)
                if cad is not None:
                    cad.parent.mkdir(parents=True, exist_ok=True)
                    occ.synchronize()
                    gmsh.write(str(cad))
            occ.synchronize()
            say(f"  bevel solid: {spec.z} teeth lofted and fused in {time.perf_counter() - t0:.1f} s")
            gmsh.model.mesh.setSizeCallback(_sizes(spec))
            gmsh.option.setNumber("Mesh.MeshSizeMax", spec.h_body)
            gmsh.model.mesh.generate(2)
            labels = _labels(spec, shift, fused)
            gmsh.model.mesh.generate(3)
            gmsh.model.mesh.setOrder(2)
            nodes, tets, facets = extract_mesh(labels, 2)
    moved = _snap(spec, nodes, facets)
    spec.extra.update(snap_mm=moved, shift=shift)
    say(f"  bevel solid: {len(nodes)} nodes, {len(tets)} C3D10, largest snap {1e3 * moved:.2f} um "
        f"({time.perf_counter() - t0:.1f} s)")
    return BodyMesh(nodes, tets, facets, "bevel-occ", time.perf_counter() - t0)
