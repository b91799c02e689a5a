"""Whole bevel member bodies by mapped (structured) meshing of the generated flanks and the blank.

A bevel tooth has a natural hexahedral parameterisation in the member's axial section: depth fraction t
(root cone -> face cone), cone distance L (toe -> heel) and, across the tooth, the polar angle between its
two generated flanks, which share the same axial-section point (Z, rho)(t, L) (:mod:`ltca.geometry.bevel.sampling`).
The member is meshed on that map, which needs no boolean operations on spline surfaces and cannot fail on a
spiral twist:

* **Teeth** (``spec.teeth``, the loaded ones plus a neighbour each side): rows of t from the root cone to the
  face cone (top land), columns of L from the front cone (toe) to the back cone (heel), and across the tooth
  from one flank to the other, clustered at both flanks.  The flank nodes lie on the *exact* generated
  surfaces (:func:`ltca.geometry.bevel.sampling.flank_at`); below the flank grid's lowest row (a small root offset
  above the root cone, where the fillet still makes a fair angle with the root cone) the fillet is continued
  along its tangent down to the root cone (a sliver of height ``root_offset``; stated, not hidden).
* **Blank** (the whole 360 deg): the root cone down to the member's mounting (``support``: the pinion's
  shaft seat, a cylinder; the gear's back face, a plane normal to its axis), bounded by the front and back
  cones continued straight down; or, without a support, a bottom parallel to the root cone ``rim_depth`` below.  Under
  the meshed teeth the blank's polar nodes follow the teeth (and their spiral twist); the other teeth are left
  out (their root cone runs on), as ``far_teeth = "none"`` of the cylindrical body.  The bottom surface is
  the support (facet group ``"bore"``), held as on a rigid shaft or a rigid mounting face.

Each hexahedron is split into six tetrahedra along its main diagonal (Kuhn), which is conforming across
neighbours; quadratic (10-node) tetrahedra get straight mid-edge nodes (the elements are subparametric,
:mod:`ltca.fem.elastic`). The hexahedra are kept too (``BodyMesh.hexes``): the body is solved on them as 20-node
serendipity bricks, the tetrahedra carrying loads and read-outs (:mod:`ltca.fem.serendipity`).
Facets (tri6, outward): ``flank_{k}_{concave|convex}``, ``top_{k}``, ``root``, ``toe``,
``heel``, ``bore``.  Frame: the member's body frame of :mod:`ltca.geometry.bevel` (z along the axis, origin at the
pitch apex), mm.  Meshing in a structured map instead of gmsh's unstructured mesher is deliberate: the bevel
tooth is a topological cube, the map keeps element shape and grading under the spiral twist, and it runs in a
fraction of a second.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ltca.geometry.bevel.sampling import axial_target, flank_at
from ltca.geometry.flank import Flank

from .mesh_record import BodyMesh, outline_hash

__all__ = ["BevelBodySpec", "build_bevel_body", "convex_shift", "blank_outline"]

_VERSION = "bevel-mapped-4"        # the mesh recipe (the cache key): tooth rows graded by DEPTH_GRADING, hexahedra kept


@dataclass(frozen=True)
class BevelBodySpec:
    """A bevel member to mesh (module docstring); lengths mm, angles rad.

    Parameters
    ----------
    concave, convex : Flank
        The member's generated flanks on the same axial grid (:func:`ltca.geometry.bevel.generation.generate_flank`),
        body frame, the grid's lowest row ``root_offset`` above the root cone.
    z : int
        Teeth of the member.
    root_offset : float
        Height of the grid's lowest row over the root cone, mm (> 0).
    convex_shift : float
        Rotation (rad) applied to the convex flank so that it bounds the same tooth as the concave one with the
        design thickness (:func:`convex_shift` finds it).
    teeth : tuple of int
        Teeth meshed; tooth k is tooth 0 turned by ``k 2 pi / z`` about +z.
    rim_depth : float
        Blank depth under the root cone, mm (used where ``support`` is None).
    support : (kind, value) or None
        The member's mounting in service, the blank's bottom: ``("seat", rho)`` the pinion's shaft seat, a
        cylinder of radius rho (mm); ``("face", Z)`` the gear's back (mounting) face, the plane at axial
        position Z (mm, body frame).  The blank then runs from the root cone down to it between the front
        and back cones (continued straight below the toe and heel).  None: a bottom parallel to the root cone
        ``rim_depth`` below it.
    divisions : (n_L, n_t, n_s, n_g, n_rim, n_far)
        Cells along the face, up the tooth, across a tooth, across a space, down the blank, and over the rest of
        the circle.
    """
    concave: Flank = field(repr=False)
    convex: Flank = field(repr=False)
    z: int
    root_offset: float
    convex_shift: float
    teeth: tuple[int, ...] = (-2, -1, 0, 1, 2)
    rim_depth: float = 10.0
    divisions: tuple[int, int, int, int, int, int] = (16, 8, 6, 4, 4, 24)
    support: tuple[str, float] | None = None

    def __post_init__(self) -> None:
        if self.support is not None and (len(self.support) != 2 or self.support[0] not in ("seat", "face")
                                         or not np.isfinite(self.support[1])):
            raise ValueError(f"support = {self.support!r}: ('seat', radius mm) or ('face', Z mm)")
        if self.z < 3:
            raise ValueError(f"z = {self.z}: at least 3 teeth")
        if not self.root_offset > 0:
            raise ValueError(f"root_offset = {self.root_offset}: must be > 0 mm")
        if not self.rim_depth > 0:
            raise ValueError(f"rim_depth = {self.rim_depth}: must be > 0 mm")
        if len(self.teeth) >= self.z or list(self.teeth) != sorted(set(self.teeth)) or \
                list(self.teeth) != list(range(self.teeth[0], self.teeth[-1] + 1)):
            raise ValueError(f"teeth = {self.teeth}: consecutive indices, fewer than z = {self.z}")
        if len(self.divisions) != 6 or min(self.divisions) < 1:
            raise ValueError(f"divisions = {self.divisions}: six counts >= 1")

    def spec_hash(self) -> str:
        h = outline_hash(_VERSION, self.concave.points, self.convex.points, np.asarray(self.concave.v),
                         np.asarray(self.concave.meta["Z"]), np.asarray(self.concave.meta["rho"]))
        h.update(repr((self.z, self.root_offset, self.convex_shift, self.teeth, self.rim_depth,
                       self.divisions) + ((self.support,) if self.support else ())).encode())
        return h.hexdigest()[:20]


def _polar(p: np.ndarray) -> np.ndarray:
    return np.arctan2(p[..., 1], p[..., 0])


def convex_shift(concave: Flank, convex: Flank, z: int, t0: float, L0: float,
                 thickness_angle: float | None = None) -> float:
    """Rotation (rad) of the convex flank that makes it bound tooth 0 together with the concave flank.

    The material lies opposite the outward normals: with the concave normal along +theta the tooth lies at
    lower polar angles.  At the axial-section point (t0, L0) the tooth's angular thickness becomes
    ``thickness_angle`` (rad; the design value, e.g. the normal thickness / (cos beta_m rho_m) on the pitch
    cone), or stays the generated one modulo the pitch (None).  Synthesised pinions need the design value:
    their two flanks are set independently and their relative angle is arbitrary."""
    pitch = 2 * np.pi / z
    pc, nc, _ = flank_at(concave, np.array([t0]), np.array([L0]))
    pv = flank_at(convex, np.array([t0]), np.array([L0]))[0]
    a_c, a_v = float(_polar(pc)[0]), float(_polar(pv)[0])
    up = float(np.sign(pc[0, 0] * nc[0, 1] - pc[0, 1] * nc[0, 0]))
    thick = (up * (a_c - a_v)) % pitch if thickness_angle is None else float(thickness_angle)
    if not 0 < thick < pitch:
        raise ValueError(f"thickness_angle = {thick!r} rad is outside the allowed range (0, {pitch:.4f})")
    return float((a_c - up * thick - a_v + np.pi) % (2 * np.pi) - np.pi)


#: the tooth's node rows crowd towards the root as (k / n) ** DEPTH_GRADING, so that the fillet (the lowest tenth or
#: so of the depth) has several element rows (uniform rows put it inside one and the root stress does not
#: converge); a stronger grading starves the flank above. Graded at 1.5 with 10 rows, the mean point's interior
#: peak pressure and loaded TE (Cao et al.'s pair, 175 N m) are within 1 % of a 20-row body.
DEPTH_GRADING = 1.5


def _depth_rows(spec: BevelBodySpec) -> np.ndarray:
    fl = spec.concave
    rn = np.asarray(fl.meta["Rn"])
    span = float(np.mean(rn[-1] - rn[0]))
    t_root = -spec.root_offset / span
    return np.concatenate([[t_root], np.linspace(0.0, 1.0, spec.divisions[1]) ** DEPTH_GRADING])


def _flank_theta(fl: Flank, t: np.ndarray, L: np.ndarray, shift: float) -> np.ndarray:
    """Polar angle of the flank at rows t (>= t_root) and columns L, (nt, nL); tangent continuation below t = 0."""
    T, LL = np.meshgrid(np.maximum(t, 0.0), L, indexing="ij")
    th = _polar(flank_at(fl, T, LL)[0]) + shift
    th = np.unwrap(np.unwrap(th, axis=0), axis=1)
    below = t < 0
    if below.any():
        dt = 0.02
        th1 = _polar(flank_at(fl, np.full(len(L), dt), L)[0]) + shift
        slope = ((th1 - th[~below][0] + np.pi) % (2 * np.pi) - np.pi) / dt
        th[below] = th[~below][0] + t[below, None] * slope
    return th


def _grid_nodes(spec: BevelBodySpec):
    """Node positions of the structured map: rim (I, n_rim + 1, K) and teeth (n_teeth, n_s + 1, J_t, K)."""
    nL, _, ns, ng, nrim, nfar = spec.divisions
    fl = spec.concave
    L = np.linspace(float(fl.v[0]), float(fl.v[-1]), nL + 1)
    t = _depth_rows(spec)
    pitch = 2 * np.pi / spec.z
    cc = _flank_theta(spec.concave, t, L, 0.0)
    cv = _flank_theta(spec.convex, t, L, spec.convex_shift)
    cv = cc + (cv - cc + np.pi) % (2 * np.pi) - np.pi
    lo, hi = (cv, cc) if np.mean(cv) < np.mean(cc) else (cc, cv)
    s = 0.5 - 0.5 * np.cos(np.pi * np.arange(ns + 1) / ns)
    teeth = np.array(spec.teeth)
    # tooth nodes: polar angle (n_teeth, ns+1, nt, nL)
    th_t = (lo[None, None] + s[None, :, None, None] * (hi - lo)[None, None] + teeth[:, None, None, None] * pitch)
    # the blank's top row (root cone): tooth bases, spaces between fine teeth, the far sector
    base = th_t[:, :, 0, :]                                 # (n_teeth, ns+1, nL)
    rows = []
    for k in range(len(teeth)):
        rows.append(base[k])
        if k < len(teeth) - 1:
            a, b = base[k, -1], base[k + 1, 0]
            f = np.arange(1, ng)[:, None] / ng
            rows.append(a[None] + f * (b - a)[None])
    a, b = base[-1, -1], base[0, 0] + 2 * np.pi
    f = np.arange(1, nfar)[:, None] / nfar
    rows.append(a[None] + f * (b - a)[None])
    th_rim = np.concatenate(rows, 0)                        # (I, nL)
    # axial section: tooth rows at (t, L); blank rows from the root cone down to the support
    Tg, Lg = np.meshgrid(t, L, indexing="ij")
    Zt, Rt = axial_target(fl, Tg, Lg)                       # (nt, nL)
    Zb, Rb = _bottom(spec, Zt, Rt)                          # (nL,) the blank's bottom under each column
    if spec.support is not None:                            # n_rim rows per 1.2 tooth heights of blank
        height = np.hypot(Zt[-1] - Zt[0], Rt[-1] - Rt[0]).max()
        nrim = max(nrim, int(np.ceil(nrim * np.hypot(Zb - Zt[0], Rb - Rt[0]).max() / (1.2 * height))))
    frac = (np.arange(nrim + 1)[::-1] / nrim) ** 1.5        # 1 at the bottom .. 0 at the root cone, graded
    Zr = Zt[0][None, :] + frac[:, None] * (Zb - Zt[0])[None, :]
    Rr = Rt[0][None, :] + frac[:, None] * (Rb - Rt[0])[None, :]
    rim = np.stack([Rr[None] * np.cos(th_rim[:, None]), Rr[None] * np.sin(th_rim[:, None]),
                    np.broadcast_to(Zr[None], (len(th_rim),) + Zr.shape)], -1)      # (I, nrim+1, nL, 3)
    tooth = np.stack([Rt[None, None] * np.cos(th_t), Rt[None, None] * np.sin(th_t),
                      np.broadcast_to(Zt[None, None], th_t.shape)], -1)            # (nT, ns+1, nt, nL, 3)
    return rim, tooth


def _bottom(spec: BevelBodySpec, Zt: np.ndarray, Rt: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The blank's bottom (Z, rho) under each column of the axial-section grid (Zt, Rt) (nt, nL), mm."""
    if spec.support is None:
        g_root = np.arctan2(np.diff(Rt[0])[0], np.diff(Zt[0])[0])   # direction of the root-cone generatrix
        down = np.array([np.sin(g_root), -np.cos(g_root)])      # towards the axis, normal to the root cone
        if down[1] > 0:
            down = -down
        Zb, Rb = Zt[0] + spec.rim_depth * down[0], Rt[0] + spec.rim_depth * down[1]
        if np.any(Rb <= 0):
            raise ValueError(f"rim_depth = {spec.rim_depth} mm reaches the axis: at most "
                             f"{float(np.min(Rt[0] / -down[1])):.2f} mm")
        return Zb, Rb
    kind, value = spec.support
    corners = []
    for j in (0, -1):                                       # toe and heel: the front / back cone continued down
        d = np.array([Zt[0, j] - Zt[-1, j], Rt[0, j] - Rt[-1, j]])
        d /= np.hypot(*d)
        k = 1 if kind == "seat" else 0                      # the coordinate the support fixes
        if d[k] * (value - (Zt[0, j], Rt[0, j])[k]) <= 0:
            raise ValueError(f"support = {spec.support!r}: the {('toe', 'heel')[j]}'s front/back cone does not "
                             f"reach it below the root cone (root at Z {Zt[0, j]:.2f}, rho {Rt[0, j]:.2f} mm)")
        s = (value - (Zt[0, j], Rt[0, j])[k]) / d[k]
        corners.append((Zt[0, j] + s * d[0], Rt[0, j] + s * d[1]))
    w = np.linspace(0.0, 1.0, Zt.shape[1])
    Zb = (1 - w) * corners[0][0] + w * corners[1][0]
    Rb = (1 - w) * corners[0][1] + w * corners[1][1]
    if np.any(Rb <= 0) or np.any((Rt[0] - Rb) * np.sign(Rt[0, 0] - Rb[0]) < 0):
        raise ValueError(f"support = {spec.support!r}: the blank's bottom crosses the axis or the root cone")
    return Zb, Rb


def blank_outline(spec: BevelBodySpec) -> np.ndarray:
    """The body's blank in the axial section: the polygon (4, 2) of (Z, rho), mm, root cone toe -> heel, then the
    heel's and the toe's bottom corners (the support, or ``rim_depth`` under the root cone), as the mesh has it."""
    fl = spec.concave
    L = np.array([float(fl.v[0]), float(fl.v[-1])])
    Tg, Lg = np.meshgrid(_depth_rows(spec), L, indexing="ij")
    Zt, Rt = axial_target(fl, Tg, Lg)
    Zb, Rb = _bottom(spec, Zt, Rt)
    return np.array([[Zt[0, 0], Rt[0, 0]], [Zt[0, -1], Rt[0, -1]], [Zb[-1], Rb[-1]], [Zb[0], Rb[0]]])


def _kuhn(corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Six tetrahedra (m*6, 4) of hexahedra given as (m, 2, 2, 2) node indices [i, j, k], and the parity (+-1)
    of each (the orientation of the path's permutation: odd ones are mirrored)."""
    out, par = [], []
    for perm, sign in (((0, 1, 2), 1), ((0, 2, 1), -1), ((1, 0, 2), -1), ((1, 2, 0), 1), ((2, 0, 1), 1),
                       ((2, 1, 0), -1)):
        p = np.zeros(3, int)
        path = [tuple(p)]
        for ax in perm:
            p[ax] = 1
            path.append(tuple(p))
        out.append(np.stack([corners[:, a, b, c] for a, b, c in path], 1))
        par.append(np.full(len(corners), sign))
    return np.concatenate(out), np.concatenate(par)


def _quad_tris(q: np.ndarray) -> np.ndarray:
    """Two triangles (m*2, 3) per quad (m, 2, 2) [a, b], split along the (0,0)-(1,1) diagonal (Kuhn-conforming)."""
    return np.concatenate([np.stack([q[:, 0, 0], q[:, 1, 0], q[:, 1, 1]], 1),
                           np.stack([q[:, 0, 0], q[:, 0, 1], q[:, 1, 1]], 1)])


def _hexes(ids: np.ndarray, periodic: bool) -> np.ndarray:
    """(m, 2, 2, 2) corner ids of the cells of a structured node block ids (I, J, K)."""
    I, J, K = ids.shape
    ii = np.arange(I if periodic else I - 1)
    i0, i1 = ii, (ii + 1) % I
    c = np.empty((len(ii), J - 1, K - 1, 2, 2, 2), int)
    for a, ia in enumerate((i0, i1)):
        for b in (0, 1):
            for d in (0, 1):
                c[:, :, :, a, b, d] = ids[ia][:, b:J - 1 + b, d:K - 1 + d]
    return c.reshape(-1, 2, 2, 2)


def build_bevel_body(spec: BevelBodySpec, cache_dir=None) -> BodyMesh:
    """Mesh a bevel member (module docstring): quadratic tetrahedra and named outward facet groups."""
    from .cache import load_cached, store_cached
    key = spec.spec_hash()
    hit = load_cached(cache_dir, "bevel", key)
    if hit is not None:
        return hit
    t0 = time.perf_counter()
    rim, tooth = _grid_nodes(spec)
    I, R1, K = rim.shape[:3]
    nT, S1, Jt = tooth.shape[:3]
    nodes = [rim.reshape(-1, 3)]
    rim_ids = np.arange(I * R1 * K).reshape(I, R1, K)
    # tooth k's base row is the rim's top row at its polar nodes
    _, _, ns, ng, _, _ = spec.divisions
    starts = np.array([k * (ns + ng) for k in range(nT)])
    nxt = I * R1 * K
    tooth_ids = np.empty((nT, S1, Jt, K), int)
    for k in range(nT):
        tooth_ids[k, :, 0] = rim_ids[starts[k]:starts[k] + S1, -1]
        up = tooth[k, :, 1:].reshape(-1, 3)
        tooth_ids[k, :, 1:] = (nxt + np.arange(len(up))).reshape(S1, Jt - 1, K)
        nodes.append(up)
        nxt += len(up)
    X = np.concatenate(nodes)
    hexes = [_hexes(rim_ids, True)] + [_hexes(tooth_ids[k], False) for k in range(nT)]
    corners = np.concatenate(hexes)
    tets, parity = _kuhn(corners)
    v = np.einsum("ij,ij->i", np.cross(X[tets[:, 1]] - X[tets[:, 0]], X[tets[:, 2]] - X[tets[:, 0]]),
                  X[tets[:, 3]] - X[tets[:, 0]]) * parity
    ref = np.sign(np.median(v))
    bad = v * ref <= 1e-9 * np.max(np.abs(v))
    if bad.any():
        raise ValueError(f"bevel body map folds: {int(bad.sum())} of {len(v)} tetrahedra inverted or flat "
                         "(more face divisions, or a smaller rim_depth)")
    flip = parity * ref < 0
    tets[flip] = tets[flip][:, [0, 2, 1, 3]]
    groups: dict[str, np.ndarray] = {}
    side_lo, side_hi = ("convex", "concave") if _sorted_low_is_convex(spec) else ("concave", "convex")
    for k, tk in enumerate(spec.teeth):
        ids = tooth_ids[k]
        groups[f"flank_{tk}_{side_lo}"] = _quad_tris(_faces(ids[0], 0, 1))
        groups[f"flank_{tk}_{side_hi}"] = _quad_tris(_faces(ids[-1], 0, 1))
        groups[f"top_{tk}"] = _quad_tris(_faces(ids[:, -1], 0, 1))
    groups["bore"] = _quad_tris(_faces(rim_ids[:, 0], 0, 1, periodic=True))
    toe = [_quad_tris(_faces(rim_ids[:, :, 0], 0, 1, periodic=True))] + \
          [_quad_tris(_faces(tooth_ids[k, :, :, 0], 0, 1)) for k in range(nT)]
    heel = [_quad_tris(_faces(rim_ids[:, :, -1], 0, 1, periodic=True))] + \
           [_quad_tris(_faces(tooth_ids[k, :, :, -1], 0, 1)) for k in range(nT)]
    groups["toe"], groups["heel"] = np.concatenate(toe), np.concatenate(heel)
    top = _faces(rim_ids[:, -1], 0, 1, periodic=True)
    covered = np.zeros(len(top) // (K - 1), bool)
    for s0 in starts:
        covered[s0:s0 + ns] = True
    groups["root"] = _quad_tris(top.reshape(-1, K - 1, 2, 2)[~covered].reshape(-1, 2, 2))
    mesh = _quadratic(X, tets, groups, key, time.perf_counter() - t0, corners.reshape(-1, 8))
    store_cached(cache_dir, "bevel", mesh)
    return mesh


def _sorted_low_is_convex(spec: BevelBodySpec) -> bool:
    im, jm = len(spec.concave.u) // 2, len(spec.concave.v) // 2
    pc, nc = spec.concave.points[im, jm], spec.concave.normals[im, jm]
    return bool(pc[0] * nc[1] - pc[1] * nc[0] > 0)


def _faces(ids2: np.ndarray, a0: int, a1: int, periodic: bool = False) -> np.ndarray:
    """(m, 2, 2) quads of a 2-D id block (A, B); the first axis may be periodic."""
    A, B = ids2.shape
    ii = np.arange(A if periodic else A - 1)
    q = np.empty((len(ii), B - 1, 2, 2), int)
    for a, ia in enumerate((ii, (ii + 1) % A)):
        for b in (0, 1):
            q[:, :, a, b] = ids2[ia][:, b:B - 1 + b]
    return q.reshape(-1, 2, 2)


def _quadratic(X: np.ndarray, tets: np.ndarray, groups: dict, key: str, seconds: float,
               corners: np.ndarray | None = None) -> BodyMesh:
    """10-node tetrahedra and 6-node facets with straight mid-edge nodes; facets turned outward. With the
    hexahedra's ``corners`` (H, 8) (corner ``4 i + 2 j + k``) of which ``tets`` is the Kuhn split, their 20-node
    serendipity hexahedra too (:mod:`ltca.fem.serendipity`)."""
    from ltca.fem.elastic import EDGES, TRI_EDGES
    from ltca.fem.serendipity import HEX_EDGES
    e = np.sort(tets[:, EDGES].reshape(-1, 2), 1)
    uniq, inv = np.unique(e, axis=0, return_inverse=True)
    mid = len(X) + inv.reshape(-1, 6)
    nodes = np.concatenate([X, 0.5 * (X[uniq[:, 0]] + X[uniq[:, 1]])])
    tets10 = np.concatenate([tets, mid], 1)
    centre = X.mean(0)
    code = uniq[:, 0].astype(np.int64) * len(X) + uniq[:, 1]
    # outward: a facet's normal points away from the tetrahedron it bounds
    owner = _facet_owner(tets)
    facets = {}
    for name, tri in groups.items():
        key3 = np.sort(tri, 1)
        o = owner(key3)
        opp = X[o].mean(1)
        n = np.cross(X[tri[:, 1]] - X[tri[:, 0]], X[tri[:, 2]] - X[tri[:, 0]])
        flip = np.einsum("ij,ij->i", n, X[tri].mean(1) - opp) < 0
        tri = np.where(flip[:, None], tri[:, [0, 2, 1]], tri)
        ee = np.sort(tri[:, TRI_EDGES].reshape(-1, 2), 1)
        m = np.searchsorted(code, ee[:, 0].astype(np.int64) * len(X) + ee[:, 1])
        facets[name] = np.concatenate([tri, len(X) + m.reshape(-1, 3)], 1)
    del centre
    hexes = None
    if corners is not None:
        he = np.sort(corners[:, HEX_EDGES], axis=2)
        m = np.searchsorted(code, he[..., 0].astype(np.int64) * len(X) + he[..., 1])
        hexes = np.concatenate([corners, len(X) + m], 1)
    return BodyMesh(nodes, tets10, facets, key, seconds, hexes)


def _facet_owner(tets: np.ndarray):
    """A function: sorted facet triples (m, 3) -> the vertices (m, 4) of the tetrahedron they bound."""
    faces = np.sort(np.concatenate([tets[:, [0, 1, 2]], tets[:, [0, 1, 3]], tets[:, [0, 2, 3]],
                                    tets[:, [1, 2, 3]]]), 1)
    owner = np.tile(np.arange(len(tets)), 4)
    n = int(tets.max()) + 1
    code = (faces[:, 0].astype(np.int64) * n + faces[:, 1]) * n + faces[:, 2]
    order = np.argsort(code)
    code, owner = code[order], owner[order]

    def find(tri: np.ndarray) -> np.ndarray:
        c = (tri[:, 0].astype(np.int64) * n + tri[:, 1]) * n + tri[:, 2]
        i = np.searchsorted(code, c)
        if np.any(code[np.minimum(i, len(code) - 1)] != c):
            raise ValueError("a facet group names a face that no tetrahedron has")
        return tets[owner[i]]
    return find
