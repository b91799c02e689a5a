"""Flank compliance of one gear body: FE far field on a coarse flank grid plus the half-space near field.

The body is the whole gear (:mod:`ltca.fem.solids.gear_body`: the 360 deg rim, web and hub, the teeth that
can touch and one neighbour each side meshed finely, held at the bore as on a rigid shaft, or at the rim
of an internal gear as in a rigid housing); it is meshed once, factorised once, and loaded by a unit normal force spread over a small patch around
each node of a coarse grid on the loaded flanks. The coarse FE cannot resolve the contact's local
deformation, so the compliance is split (docs/design.md, "Near field", after Vijayakar, IJNME 31 (1991)):

    C_ij = R_ij + C_HS(cell j -> x_i),
    R = 2 R(d) - R(2d),   R(d)_ij = C_FE(patch j -> x_i - d n_i) - C_HS(patch j -> x_i - d n_i).

The regular part R(d) is the FE response minus the half-space (Boussinesq) response of the *same*
patch load at the *same* read point, so whatever the FE sees of the patch's spreading and of the
bilinear grid interpolation cancels; it is read at two depths where the coarse mesh is accurate and
extrapolated linearly to the flank (it varies linearly with depth there: flank curvature, finite tooth).
The contact cells add their own half-space response at the flank (:mod:`ltca.cylindrical.contact_cells`). Against
CalculiX, a single read depth without the matched subtraction makes the FZG pitch-point TE
3 % too stiff; this split converges to CalculiX's with the flank element size.

R is stored on the grid and interpolated bilinearly (in flank arc length and axial position) to any
contact cell, for the source and the receiver alike, so one factorisation serves every mesh position
and every micro-geometry change. Root stress responses at fillet points are stored from the same
solves, for superposition.
"""
from __future__ import annotations

import threading
import time
from dataclasses import dataclass, field, replace

import numpy as np
import scipy.sparse as sp

from ltca.geometry.cylindrical import arc_length, helical_flank

from .background import Background
from .elastic import assemble_stiffness
from .fillet import fillet_points, fillet_size
from .loads import patch_loads, patch_quadrature
from .periodic import periodic_offsets, turn_z, voigt_turn
from .readout import interpolation_matrix, nodal_stress, stress_matrix
from .serendipity import assemble_hex20, tet_interpolation
from .solids import BodyMesh, GearBodySpec, build_gear_body
from .solids.mesh_job import BodyMeshJob
from .solver import SubspaceFactorization, factorize

__all__ = ["ComplianceSpec", "BodyCompliance", "body_compliance", "pair_compliance", "flank_compliance", "principal_max",
           "body_spec"]


@dataclass(frozen=True)
class ComplianceSpec:
    """What to model for one body and at which fidelity (mm, MPa)."""
    teeth: tuple[int, ...]        # teeth meshed finely in the FE body (loaded ones plus a neighbour each side)
    loaded: tuple[int, ...]       # teeth whose `side` flank carries load
    side: int                     # +1 right flank, -1 left flank
    r_range: tuple[float, float]  # radii of the loaded flank grid (form radius .. tip), mm
    grid: tuple[int, int]         # (profile, face) grid nodes per loaded flank
    face_width: float
    r_bore: float                 # bore radius (internal gear: outer rim radius)
    h_flank: float
    h_body: float
    depth: float                  # shallower read depth d of the regular part (also 2d), mm; 0: no near field
    young: float
    poisson: float
    root_points: tuple[int, int] | None = None  # fillet read-out points (along fillet, along face) per loaded tooth;
                                                # None: fem.fillet.ROOT_STEP apart
    web: tuple[float, float, float, float] | None = None  # (r_rim, r_hub, web width, web offset), mm; None: solid
    far_teeth: str = "none"       # teeth away from the load: "none" (root circle) or "full" (see fem.solids.gear_body)
    fillet: float = 0.0           # element size on the loaded teeth's read fillets / their smallest radius of curvature
                                  # (fem.fillet.fillet_size); 0: h_flank
    periodic: bool = True         # load the centre loaded tooth only and read its neighbours (fem.periodic): the
                                  # fine teeth are turned copies on a body of revolution; else load every loaded tooth


@dataclass
class BodyCompliance:
    """FE compliance of one body on its flank grid, and root-stress influence.

    Attributes
    ----------
    spec : ComplianceSpec
    s_grid, z_grid : ndarray (ns,), (nz,)
        Grid arc lengths (mm, from the base circle) and axial positions (mm).
    C : ndarray (n, n)
        Regular part R of the compliance (module docstring) between grid nodes, mm/N: normal
        displacement into the body at grid node i per newton of normal force at grid node j, with the
        half-space part of same-flank pairs removed; n = len(loaded) * ns * nz, ordered (tooth, s, z).
        Without the near field (depth 0) the FE response read at the flank itself.
    depth : ndarray (ns,)
        Shallower read depth d per profile row (at most 15 % of the local tooth thickness), mm.
    root_points : ndarray (m, 3); root_tooth : ndarray (m,)
    root_stress : ndarray (m, 6, n)
        Voigt stress (xx, yy, zz, yz, xz, xy) at the root points per newton at grid node j, MPa/N.
    mesh, factorization, patch : kept for the VTU of a loaded position.
    timings : dict, seconds of mesh, assembly, factorisation, solves.
    """
    spec: ComplianceSpec
    s_grid: np.ndarray
    z_grid: np.ndarray
    C: np.ndarray
    depth: np.ndarray
    root_points: np.ndarray
    root_tooth: np.ndarray
    root_stress: np.ndarray
    n_dofs: int
    mesh: object = field(repr=False, default=None)
    factorization: object = field(repr=False, default=None)
    patch: object = field(repr=False, default=None)
    timings: dict = field(default_factory=dict)

    def without_solver(self) -> BodyCompliance:
        """This compliance without what only a loaded position's VTU needs (``mesh``, ``factorization``,
        ``patch``), the back-end's factor freed now: PARDISO holds it outside Python, 0.3-3.5 GB on the shipped
        bodies (1.3 GB both helical C14 bodies, about 7 GB both of the eccentric planetary pair's). Every
        figure of the contact (``C``, ``root_stress``, ``weights``) is unchanged; ``self`` can no longer solve."""
        if self.factorization is not None:
            self.factorization.release()
        return replace(self, mesh=None, factorization=None, patch=None)

    def root_max(self, f: np.ndarray) -> dict[int, float]:
        """Largest principal fillet stress (MPa) per loaded tooth under the grid forces ``f`` (n,), N."""
        if self.root_stress.shape[0] == 0:
            return {}
        smax = principal_max(np.einsum("mkn,n->mk", self.root_stress, f))
        return {int(k): float(smax[self.root_tooth == k].max()) for k in np.unique(self.root_tooth)}

    def weights(self, tooth: np.ndarray, s: np.ndarray, z: np.ndarray) -> sp.csr_matrix:
        """Bilinear interpolation weights (n_cells, n_grid) of cells at (tooth, s, z) on the grid.

        Cells outside the grid are clamped to its border; cells on a tooth that is not loaded get
        zero weight (the caller must not put contact there)."""
        ns, nz = len(self.s_grid), len(self.z_grid)
        loaded = np.asarray(self.spec.loaded)
        tooth = np.asarray(tooth)
        t_idx = np.searchsorted(loaded, tooth)
        ok = (t_idx < len(loaded)) & (loaded[np.clip(t_idx, 0, len(loaded) - 1)] == tooth)
        fs = np.clip(np.interp(s, self.s_grid, np.arange(ns)), 0, ns - 1 - 1e-12)
        fz = np.clip(np.interp(z, self.z_grid, np.arange(nz)), 0, nz - 1 - 1e-12)
        i0, j0 = np.floor(fs).astype(int), np.floor(fz).astype(int)
        ws, wz = fs - i0, fz - j0
        rows, cols, vals = [], [], []
        n = len(s)
        base = np.clip(t_idx, 0, len(loaded) - 1) * ns * nz
        for di, wi in ((0, 1 - ws), (1, ws)):
            for dj, wj in ((0, 1 - wz), (1, wz)):
                rows.append(np.arange(n))
                cols.append(base + (i0 + di) * nz + (j0 + dj))
                vals.append(np.where(ok, wi * wj, 0.0))
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                             shape=(n, len(loaded) * ns * nz))


#: one factorisation at a time in a process: the back-end runs it on every core, and two side by side would fight for
#: the cores and hold both working sets at once (:func:`pair_compliance` runs the other body's single-threaded steps
#: beside it)
_FACTOR_LOCK = threading.Lock()

#: facet quadrature levels of the cylindrical bodies' patch loads (:func:`flank_compliance`): a patch reaches 0.75 of
#: the grid spacing, several flank elements, so the 7-point rule per facet already puts hundreds of points on it
PATCH_REFINE = 0


def principal_max(sig: np.ndarray) -> np.ndarray:
    """Largest principal stress of Voigt stresses (..., 6) ordered xx, yy, zz, yz, xz, xy."""
    T = np.stack([np.stack([sig[..., 0], sig[..., 5], sig[..., 4]], -1),
                  np.stack([sig[..., 5], sig[..., 1], sig[..., 3]], -1),
                  np.stack([sig[..., 4], sig[..., 3], sig[..., 2]], -1)], -2)
    return np.linalg.eigvalsh(T)[..., -1]


def _rotate_tooth(points: np.ndarray, tooth: int, z: int) -> np.ndarray:
    a = -tooth * 2 * np.pi / z
    R = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1.0]])
    return points @ R.T


def _patch_halfspace(quadrature, Y, Nn, n_teeth, E, nu) -> np.ndarray:
    """Half-space (Boussinesq) normal displacement at depth point Y_i under the patch load of grid node j.

    Only pairs on the same flank: (n, n) block diagonal, mm/N. The half-space is the one tangent at the
    receiver: depth and lateral distance are measured along and across its normal, the patch traction is
    the cosine bell of :func:`ltca.fem.loads.patch_loads` on the facet quadrature points (``quadrature``, from
    :func:`ltca.fem.loads.patch_quadrature`)."""
    from .halfspace import point_influence_sq
    patch, _, pts, w = quadrature
    n = len(Y)
    m = n // n_teeth
    H = np.zeros((n, n))
    for t in range(n_teeth):
        rows = np.arange(t * m, (t + 1) * m)
        hit = (patch >= t * m) & (patch < (t + 1) * m)
        P, Yr, Nr = pts[hit], Y[rows], Nn[rows]
        # distance and depth of every (receiver, source) pair by matrix products, without (m, k, 3) temporaries:
        # |p - y|^2 = |p|^2 + |y|^2 - 2 y.p and depth = (p - y).n
        dist2 = np.einsum("kc,kc->k", P, P)[None, :] + np.einsum("ac,ac->a", Yr, Yr)[:, None] - 2.0 * (Yr @ P.T)
        depth = Nr @ P.T - np.einsum("ac,ac->a", Yr, Nr)[:, None]
        depth *= depth
        G = point_influence_sq(np.maximum(dist2, depth), depth, E, nu)
        S = sp.csr_matrix((w[hit], (np.arange(hit.sum()), patch[hit] - t * m)), shape=(int(hit.sum()), m))
        H[np.ix_(rows, rows)] = np.asarray((S.T @ G.T).T)
    return H


def body_spec(profile, spec: ComplianceSpec) -> GearBodySpec:
    """The whole-gear body of a generated profile (geometry.involute.ToothProfile) for a compliance spec."""
    xy, kind, side_code = np.asarray(profile.xy), np.asarray(profile.kind, np.int8), np.asarray(profile.side, np.int8)
    h_fillet = fillet_size(xy, kind, side_code, spec.side, spec.fillet, spec.h_flank)
    side = "right" if spec.side > 0 else "left"
    return GearBodySpec(xy, kind, side_code, profile.z, tuple(spec.teeth), spec.r_bore, spec.face_width,
                        float(np.tan(profile.beta) / profile.r_ref), profile.internal, rim=spec.web,
                        far_teeth=spec.far_teeth, h_flank=spec.h_flank, h_body=spec.h_body, h_fillet=h_fillet,
                        fillets=tuple(f"fillet_{k}_{side}" for k in spec.loaded) if h_fillet else ())


def body_compliance(profile, spec: ComplianceSpec, cache_dir=None, progress=None,
                    mesh: BodyMesh | None = None) -> BodyCompliance:
    """Mesh, assemble, factorise and load one cylindrical gear body; see the module docstring.

    Parameters
    ----------
    profile : geometry.involute.ToothProfile
    spec : ComplianceSpec
    cache_dir : path, optional
        Mesh cache directory.
    progress : callable(str), optional
        Called with a short message at each step.
    mesh : BodyMesh, optional
        The body already meshed (``build_gear_body(body_spec(profile, spec))``); default: mesh it here.
    """
    say = progress or (lambda msg: None)
    t0 = time.perf_counter()
    if mesh is None:
        mesh = build_gear_body(body_spec(profile, spec), cache_dir=cache_dir)
        t_mesh = time.perf_counter() - t0
    else:
        t_mesh = mesh.seconds
    say(f"meshed z={profile.z}: {len(mesh.nodes)} nodes, {len(mesh.tets)} tets, {3 * len(mesh.nodes)} dofs "
        f"({t_mesh:.1f} s)")
    ns, nz = spec.grid
    b = spec.face_width
    # the loaded flanks as gridded Flank records (geometry's currency): exact points and normals
    flanks = [helical_flank(profile, spec.side, b, ns, nz, r_range=tuple(spec.r_range), tooth=k) for k in spec.loaded]
    r_grid, z_grid = flanks[0].u, flanks[0].v
    s_grid = arc_length(r_grid, profile.r_base)
    # read depths d and 2d, 2d at most 30 % of the local tooth thickness (the tooth gets thin near the tip)
    half_angle = np.abs(profile.flank_angle(r_grid, spec.side))
    thick = 2 * r_grid * np.sin(np.clip(half_angle, 0, np.pi / 2))
    depth = np.minimum(spec.depth, 0.15 * thick)
    names = [f"{kind}_{k}_{'right' if spec.side > 0 else 'left'}" for k in spec.loaded
             for kind in ("flank", "fillet")] + [f"tip_{k}" for k in spec.loaded]
    base = fillet_points(profile, spec.side, b, profile.internal, spec.root_points)
    roots = [_rotate_tooth(base, k, profile.z) for k in spec.loaded]
    R = np.concatenate(roots) if roots else np.zeros((0, 3))
    root_tooth = np.concatenate([np.full(len(base), k) for k in spec.loaded]) if roots else np.zeros(0, int)
    spacing = max(np.diff(s_grid).max(), np.diff(z_grid).max())
    return flank_compliance(spec, mesh, "rim" if profile.internal else "bore", flanks, s_grid, z_grid, depth,
                            spacing, names, R, root_tooth, {"mesh": t_mesh}, say, recovery="nodal",
                            refine=PATCH_REFINE, pitch=-2 * np.pi / profile.z if spec.periodic else None)


def pair_compliance(profiles, specs, cache_dir=None, progress=None) -> tuple[BodyCompliance, BodyCompliance]:
    """Both bodies of a pair, computed side by side on the two cores.

    The second body is meshed in a child process (:mod:`ltca.fem.solids.mesh_job`: gmsh is single-threaded and not
    thread-safe) while the first one is meshed here; then each body is assembled, set up, factorised and loaded in a
    thread of its own. The factorisations take turns (one at a time in a process, on every core: they scale well on
    two, and two at once would hold both working sets); assembly, set-up and read-out are single-threaded, and run
    beside the other body's factorisation instead of leaving a core idle.

    Parameters
    ----------
    profiles : (ToothProfile, ToothProfile)
    specs : (ComplianceSpec, ComplianceSpec)
    cache_dir, progress
        As for :func:`body_compliance`.

    Returns
    -------
    (BodyCompliance, BodyCompliance)
    """
    (p1, p2), (s1, s2) = profiles, specs
    job = BodyMeshJob(body_spec(p2, s2), cache_dir)
    try:
        second = Background(lambda: body_compliance(p2, s2, cache_dir, progress, mesh=job.result()), "ltca-body")
        body1 = body_compliance(p1, s1, cache_dir, progress)
        body2 = second.result()
    finally:
        job.cancel()
    return body1, body2


def flank_compliance(spec, mesh, support: str, flanks: list, s_grid: np.ndarray, z_grid: np.ndarray,
                     depth: np.ndarray, spacing: float, load_groups: list[str], root_points: np.ndarray,
                     root_tooth: np.ndarray, timings: dict | None = None, progress=None,
                     recovery: str = "element", pitch: float | None = None, refine: int = 1) -> BodyCompliance:
    """The compliance of any meshed gear body on its loaded flank grids: the one path for every gear type.

    Parameters
    ----------
    spec
        What was modelled (:class:`ComplianceSpec` or the bevel counterpart): needs ``loaded`` (teeth, in the
        order of ``flanks``), ``depth`` (read depth d, mm; 0 without the near field), ``young``, ``poisson``.
    mesh : BodyMesh
        The body (quadratic tetrahedra, named facet groups).
    support : str
        Facet group held fixed (all displacement components).
    flanks : list of Flank
        The loaded flank of each tooth of ``spec.loaded`` on the same (ns, nz) grid, body frame, normals out of
        the material.
    s_grid, z_grid : ndarray (ns,), (nz,)
        The grid's coordinates (profile and face direction) for :meth:`BodyCompliance.weights`.
    depth : ndarray (ns,)
        Read depth d per profile row, mm.
    spacing : float
        Largest grid spacing on the flank, mm: the patch loads reach 0.75 of it.
    load_groups : list of str
        Facet groups that carry the patch loads (missing names are skipped).
    root_points : ndarray (m, 3); root_tooth : ndarray (m,)
        Stress read-out points in the fillets, and their teeth.
    recovery : {"element", "nodal"}
        Stress at the read-out points: of the element containing each, or averaged at the nodes as CalculiX's
        (:func:`ltca.fem.readout.stress_matrix`). The cylindrical bodies use "nodal".
    pitch : float, optional
        Where the fine teeth are turned copies of each other on an axisymmetric body, the angle (rad, about +z) that
        turns tooth k onto tooth k + 1: then only the centre loaded tooth is loaded and its neighbours are read
        (:mod:`ltca.fem.periodic`); the flanks and root points of the loaded teeth must be turned copies too.
        None: every loaded tooth is loaded.
    refine : int
        Subdivision levels of the facet quadrature of the patch loads and of their half-space part
        (:func:`ltca.fem.loads.patch_quadrature`: 7 points a facet at 0, 28 at 1).
    """
    say = progress or (lambda msg: None)
    t = dict(timings or {})
    t0 = time.perf_counter()
    fixed_nodes = np.unique(mesh.facets[support])
    if mesh.hexes is None:
        K = assemble_stiffness(mesh.nodes, mesh.tets, spec.young, spec.poisson)
    else:                                  # solved on the serendipity hexahedra, loaded and read on the tetrahedra
        T, hex_nodes = tet_interpolation(len(mesh.nodes), mesh.hexes, mesh.tets)
        col = np.full(len(mesh.nodes), -1)
        col[hex_nodes] = np.arange(len(hex_nodes))
        K = assemble_hex20(mesh.nodes[hex_nodes], col[mesh.hexes], spec.young, spec.poisson)
        fixed_nodes = col[np.intersect1d(fixed_nodes, hex_nodes)]
    t["assembly"] = time.perf_counter() - t0
    # ---- the flank grid, its depth points and the patch loads
    t0 = time.perf_counter()
    nz = len(z_grid)
    m = len(s_grid) * nz
    X = np.concatenate([f.points.reshape(-1, 3) for f in flanks])
    Nn = np.concatenate([f.normals.reshape(-1, 3) for f in flanks])
    n = len(X)
    loaded = [int(k) for k in spec.loaded]
    per = None if pitch is None else periodic_offsets(loaded, spec.teeth)
    if per is None:                        # load every loaded tooth, read them
        Xr, Nr, R, cols = X, Nn, root_points, slice(None)
    else:                                  # load the centre tooth, read it and its neighbours
        centre, offsets = per
        ic = loaded.index(centre)
        Xc, Nc = X[ic * m:(ic + 1) * m], Nn[ic * m:(ic + 1) * m]
        base = root_points[np.asarray(root_tooth) == centre]
        Xr, Nr, R = (np.concatenate([turn_z(a, d * pitch) for d in offsets]) for a in (Xc, Nc, base))
        cols = slice(ic * m, (ic + 1) * m)
    n_read = len(Xr)
    d_pt = np.tile(np.repeat(depth, nz), n_read // m)[:, None]
    near = spec.depth > 0
    # reads at d and 2d below the flank (at the flank itself without the near field)
    Y = np.concatenate([Xr - d_pt * Nr, Xr - 2 * d_pt * Nr]) if near else Xr
    tri = np.concatenate([mesh.facets[g] for g in load_groups if g in mesh.facets])
    ds = spacing
    quad = patch_quadrature(mesh.nodes, tri, X, 0.75 * ds, refine=refine)
    F = patch_loads(mesh.nodes, tri, X, -Nn, 0.75 * ds, refine=refine, quadrature=quad)
    Pm = interpolation_matrix(mesh.nodes, mesh.tets, Y)
    NN = np.concatenate([Nr, Nr]) if near else Nr
    O = sp.csr_matrix((-NN.ravel(), (np.repeat(np.arange(len(Y)), 3), np.arange(3 * len(Y)))),
                      shape=(len(Y), 3 * len(Y))) @ Pm
    P = None
    if not len(R):
        S = sp.csr_matrix((0, mesh.n_dofs))
    elif recovery == "nodal":              # observe the nodal stresses, interpolate them to the points after
        P, S = nodal_stress(mesh.nodes, mesh.tets, spec.young, spec.poisson, R)
    else:
        S = stress_matrix(mesh.nodes, mesh.tets, spec.young, spec.poisson, R)
    t["setup"] = time.perf_counter() - t0
    fixed = (3 * fixed_nodes[:, None] + np.arange(3)).ravel()
    with _FACTOR_LOCK:
        t0 = time.perf_counter()
        fact = factorize(K, fixed)
        t["factorisation"] = time.perf_counter() - t0
    n_dofs = K.shape[0]
    del K                                  # the factor holds what the solves need
    if mesh.hexes is not None:
        fact = SubspaceFactorization(fact, T)
    say(f"assembled ({t['assembly']:.1f} s) and factorised with {fact.method} ({t['factorisation']:.1f} s)")
    t0 = time.perf_counter()
    out = fact.solve(F[:, cols], observe=sp.vstack([O, S]).tocsr())
    t["solves"] = time.perf_counter() - t0
    say(f"{out.shape[1]} unit loads solved ({t['solves']:.1f} s)")
    if near:
        # the regular part: FE minus the half-space response of the same patch loads at the same points,
        # read at d and 2d and extrapolated linearly to the flank (the regular part varies linearly with
        # depth near the surface: flank curvature and finite tooth; the FE is inaccurate at the flank
        # itself). Load spreading (patch, grid interpolation) cancels against the near field, which adds
        # the half-space response of the contact cells at the flank.
        t0 = time.perf_counter()
        regular = []
        for i in (0, 1):
            reads = out[i * n_read:(i + 1) * n_read]
            if per is None:
                H = _patch_halfspace(quad, Y[i * n:(i + 1) * n], Nn, len(loaded), spec.young, spec.poisson)
                regular.append(reads - H)
            else:                          # the same-flank pairs: the centre tooth read at offset 0
                j0 = int(np.flatnonzero(offsets == 0)[0]) * m
                H = _patch_halfspace(_tooth_quadrature(quad, ic, m), Y[i * n_read + j0:i * n_read + j0 + m], Nc, 1,
                                     spec.young, spec.poisson)
                reads = reads.copy()
                reads[j0:j0 + m] -= H
                regular.append(reads)
        C = 2.0 * regular[0] - regular[1]
        t["half-space"] = time.perf_counter() - t0
    else:
        C = out[:n_read]
    stress = out[len(Y):] if P is None else P @ out[len(Y):]
    stress = stress.reshape(len(R), 6, out.shape[1])
    if per is not None:
        C, stress = _unfold(C, stress, loaded, centre, offsets, pitch, m)
        R = root_points
    # Maxwell-Betti reciprocity holds between loads and reads at the same points; the reads sit below the
    # loads, which breaks symmetry only at the level of the discretisation error: keep the symmetric part
    # so that the contact matrix stays symmetric positive definite.
    C = 0.5 * (C + C.T)
    return BodyCompliance(spec, s_grid, z_grid, C, depth, R, np.asarray(root_tooth, int), stress,
                          n_dofs, mesh, fact, F, t)


def _tooth_quadrature(quadrature, tooth: int, m: int):
    """The patch quadrature (:func:`ltca.fem.loads.patch_quadrature`) of the patches of one tooth's m grid nodes,
    renumbered from 0."""
    patch, q, pts, w = quadrature
    hit = (patch >= tooth * m) & (patch < (tooth + 1) * m)
    return patch[hit] - tooth * m, q[hit], pts[hit], w[hit]


def _unfold(C: np.ndarray, stress: np.ndarray, loaded: list[int], centre: int, offsets: np.ndarray, pitch: float,
            m: int) -> tuple[np.ndarray, np.ndarray]:
    """Every loaded tooth's block from the centre tooth's loads (:mod:`ltca.fem.periodic`).

    ``C`` (n_off m, m) and ``stress`` (n_off r, 6, m): reads at the teeth ``centre + offsets`` under the centre
    tooth's loads. Returns the (n m, n m) compliance and the (n r, 6, n m) root stresses of the n loaded teeth:
    the response at tooth a to a load on tooth b is the centre tooth's at tooth ``centre + a - b``, its stresses
    turned by ``(b - centre) pitch``."""
    nl = len(loaded)
    at = {int(d): i for i, d in enumerate(offsets)}
    Cd = C.reshape(len(offsets), m, m)
    r = stress.shape[0] // len(offsets)
    Sd = stress.reshape(len(offsets), r, 6, m)
    C_all = np.empty((nl * m, nl * m))
    S_all = np.empty((nl * r, 6, nl * m))
    for ib, b in enumerate(loaded):
        T = voigt_turn((b - centre) * pitch)
        for ia, a in enumerate(loaded):
            k = at[a - b]
            C_all[ia * m:(ia + 1) * m, ib * m:(ib + 1) * m] = Cd[k]
            S_all[ia * r:(ia + 1) * r, :, ib * m:(ib + 1) * m] = np.einsum("uv,pvj->puj", T, Sd[k])
    return C_all, S_all
