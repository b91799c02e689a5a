"""Separation-field TCA of face-milled spiral bevel gears: gap fields on the flank grids (ease-off style).

At each pinion angle phi1 the gear is first held at its kinematic position phi2_n = phi2_0 - (z1/z2) phi1.
For every point p of one member's flank grid (trimmed by its own blank) the gap is the rotation of the
OTHER member about its own axis that brings its generated surface onto p: in the other member's body frame,
p has axial-section coordinates (Z, rho) and polar angle a_p; the other surface is solved exactly at the same
(Z, rho) (Newton on the equation of meshing, :func:`ltca.geometry.bevel.generation.solve_axial_points`), polar angle
a_s, and the rotation is a_p - a_s, wrapped to the tooth pitch and signed so that it is positive when the
flanks are apart (the surface normal, out of the material, tells which way the member must turn to close).
Points whose (Z, rho) fall outside the other member's flank (face and root cones, toe and heel) do not count.
Gaps are converted to gear rotation (first order: normal gap = rotation x rho |n . e_theta|).

Both directions are evaluated, pinion grid onto the gear surface and gear grid onto the pinion surface, so
that an edge of either member (tip, root, toe, heel) meets the other's interior: the contact is where the
rotation is smallest, i.e. the smallest gear rotation closing a gap; it is refined off the grid by a
box-constrained Newton on the continuous gap function (source grid parameters t, L).  The mesh cycle repeats
with period 2 pi / z1: the gap fields of one tooth pair over several cycles give those of the neighbours,
and the transmission error over three cycles is the envelope (smallest gap over the pairs).

Litvin & Fuentes, *Gear Geometry and Applied Theory*, 2nd ed. 2004, sec. 9.4 (TCA) and 20.7; the ease-off
(difference surface) as used e.g. by Kolivand & Kahraman, MMT 44 (2009) 1848-1865 (their separation approach).
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from scipy.interpolate import RegularGridInterpolator

from .blank import BevelBlank
from .generation import generate_flank, solve_axial_points, surface_state
from .machine import FlankCut
from .surface_table import SurfaceTable
from .tca import RAD_PER_ARCSEC, Assembly, BevelPair, mesh_frames, to_pitch_coords

__all__ = ["SeparationResult", "separation_tca", "EDGES"]

#: contact location labels: (member, edge) for the box bounds (t = 0, t = 1, L = A_i, L = A_0)
EDGES = ("root", "tip", "toe", "heel")


def _rotz(v, a):
    c, s = np.cos(a), np.sin(a)
    x, y, z = np.broadcast_arrays(v[..., 0], v[..., 1], v[..., 2], c)[:3]
    return np.stack([c * x - s * y, s * x + c * y, z], -1)


#: flanks generated lately, by the identity of their cut and blank (kept alive here, so an id is not reused)
_FLANKS: dict = {}


def _generated(fc: FlankCut, blank: BevelBlank, member: str, nu: int, nv: int, root_offset: float):
    """:func:`generate_flank`, remembered for the last 16 cuts: a flank does not depend on the assembly, and the
    LTCA builds the same flanks for every torque, mounting and (the gear) every design of a search."""
    key = (id(fc), id(blank), member, nu, nv, float(root_offset))
    hit = _FLANKS.get(key)
    if hit is None:
        if len(_FLANKS) >= 16:
            _FLANKS.pop(next(iter(_FLANKS)))
        hit = _FLANKS[key] = (fc, blank, generate_flank(fc, blank, member, nu, nv, root_offset))
    return hit[2]


class _Member:
    """One flank of one member in the mesh: grid, blank region, frames, exact surface at (t, L)."""

    def __init__(self, fc: FlankCut, blank: BevelBlank, member: str, B: np.ndarray, O: np.ndarray,
                 nu: int, nv: int, root_offset: float):
        self.fc, self.B, self.O, self.name = fc, B, O, member
        self.mb = mb = blank.member(member)
        self.blank = blank
        self.A0, self.Ai, self.off = blank.outer_cone_distance, blank.inner_cone_distance, root_offset
        self.flank = _generated(fc, blank, member, nu, nv, root_offset)
        self.t, self.L = self.flank.u, self.flank.v
        self._guess = RegularGridInterpolator((self.t, self.L), self.flank.meta["params"], bounds_error=False,
                                              fill_value=None)
        self.pitch = 2 * np.pi / mb.z
        self.lo = np.array([0.0, self.Ai])
        self.hi = np.array([1.0, self.A0])
        self.tol = 1e-11                       # Newton tolerance of surface points, mm
        self.table = None                      # a SurfaceTable serving surface() (use_table), else exact

    def _cones(self, L):
        root, face = self.blank.cones(self.name, L)
        return root + self.off, face

    def axial(self, t, L):
        """(Z, rho) of grid coordinates (t, L), mm."""
        root, face = self._cones(L)
        Rn = root + t * (face - root)
        g = self.mb.pitch_angle
        return L * np.cos(g) - Rn * np.sin(g), L * np.sin(g) + Rn * np.cos(g)

    def coords(self, r_body):
        """Grid coordinates (t, L) of body-frame points (..., 3)."""
        L, Rn = to_pitch_coords(r_body, self.mb.pitch_angle)
        root, face = self._cones(L)
        return (Rn - root) / (face - root), L

    def inside(self, t, L, tol=1e-9):
        return (t >= -tol) & (t <= 1 + tol) & (L >= self.Ai - tol) & (L <= self.A0 + tol)

    def use_table(self, tol: float = 1e-7) -> None:
        """Serve :meth:`surface` from a :class:`~ltca.geometry.bevel.surface_table.SurfaceTable` of this flank (built
        once per flank, remembered with it): within ``tol`` mm of the exact surface, exact where it is not."""
        key = ("table", id(self.fc), self.name, self.A0, self.Ai, float(self.off), self.tol, float(tol))
        hit = _FLANKS.get(key)
        if hit is None:
            if len(_FLANKS) >= 16:
                _FLANKS.pop(next(iter(_FLANKS)))
            dL = 0.05 * (self.A0 - self.Ai)
            hit = _FLANKS[key] = (self.fc, SurfaceTable(self.exact_surface, self.axial, (-0.25, 1.25),
                                                        (self.Ai - dL, self.A0 + dL), tol=tol,
                                                        branches=self._branches()))
        self.table = hit[1]

    def _branches(self):
        """The flank's smooth branches (:class:`~ltca.geometry.bevel.surface_table.SurfaceTable`): the surfaces the
        blade's straight part and its edge circle generate, each continued past their tangency; their validity
        fields w (mm) are the blade parameter u's distance inside the part (straight: u >= 0; arc:
        ``u_min`` <= u < 0)."""
        cut = self.fc.cutter
        parts = [("straight", lambda u: u)]
        if cut.edge_radius > 0:
            parts.append(("arc", lambda u: np.minimum(-u, u - cut.u_min)))

        def branch(part, w):
            fc = replace(self.fc, cutter=replace(cut, part=part))

            def smooth(t, L):
                Z, rho = self.axial(t, L)
                x, ok = solve_axial_points(fc, Z, rho, self._guess(np.stack([np.clip(t, -0.2, 1.2), L], -1)),
                                           tol=self.tol)
                st = surface_state(fc, x[:, 0], x[:, 1], x[:, 2])
                return st.r_w, st.n_w, ok, w(x[:, 0])
            return smooth
        return [branch(*p) for p in parts]

    def surface(self, t, L):
        """Surface point, normal (body frame) and convergence flag at (t, L), any shape: exact, or from the
        flank's table after :meth:`use_table`."""
        if self.table is None:
            return self.exact_surface(t, L)
        t, L = np.broadcast_arrays(np.asarray(t, float), np.asarray(L, float))
        r, n, ok = self.table.surface(t.ravel(), L.ravel())
        return r.reshape(t.shape + (3,)), n.reshape(t.shape + (3,)), ok.reshape(t.shape)

    def exact_surface(self, t, L):
        """Exact surface point, normal (body frame) and convergence flag at (t, L), any shape."""
        t, L = np.broadcast_arrays(np.asarray(t, float), np.asarray(L, float))
        shp = t.shape
        t, L = t.ravel(), L.ravel()
        Z, rho = self.axial(t, L)
        x, ok = solve_axial_points(self.fc, Z, rho, self._guess(np.stack([np.clip(t, -0.2, 1.2), L], -1)),
                                   tol=self.tol)
        st = surface_state(self.fc, x[:, 0], x[:, 1], x[:, 2])
        return st.r_w.reshape(shp + (3,)), st.n_w.reshape(shp + (3,)), ok.reshape(shp)

    def to_mesh(self, r, ang):
        return _rotz(r, ang) @ self.B.T + self.O

    def from_mesh(self, r_h, ang):
        return _rotz((r_h - self.O) @ self.B, -ang)


def _speed(r, n):
    """|n . (e_z x r)| = rho |n . e_theta|: normal speed per unit rotation about the body axis, mm/rad."""
    return np.abs(r[..., 0] * n[..., 1] - r[..., 1] * n[..., 0])


def _gap(dst: _Member, r_h: np.ndarray, ang: np.ndarray, sign: float | None = None, mask: bool = True):
    """Rotation of ``dst`` (about its axis, rad, > 0 apart) closing the gap to mesh-frame points ``r_h``.

    Only tooth 0 of dst counts (the points' gap within [-1/4, 3/4) of a pitch; the single tooth pair).
    ``ang`` (dst rotation) broadcasts with ``r_h[..., 0]``.  Returns the gap (rad; inf where not solved or
    Newton failed), the normal speed of dst there (mm/rad), the dst surface point (body frame), the closing
    sign and a flag: the point lies on the dst flank (inside its blank) and was solved.  With ``mask`` only
    points on the dst flank are solved, otherwise all (for finite-difference stencils near an edge).
    """
    r = dst.from_mesh(r_h, ang)
    t, L = dst.coords(r)
    ins = dst.inside(t, L)
    sel = ins if mask else np.ones(t.shape, bool)
    g = np.full(t.shape, np.inf)
    q = np.full(r.shape, np.nan)
    v = np.full(t.shape, np.nan)
    ok_all = np.zeros(t.shape, bool)
    if sel.any():
        qs, ns, ok = dst.surface(t[sel], L[sel])
        a = np.arctan2(r[sel][:, 1], r[sel][:, 0]) - np.arctan2(qs[:, 1], qs[:, 0])
        if sign is None:
            sign = float(np.sign(np.median(ns[:, 1] * qs[:, 0] - ns[:, 0] * qs[:, 1])))
        # tooth 0 of dst only: principal angle, then a window of one pitch around the flank
        gi = sign * ((a + np.pi) % (2 * np.pi) - np.pi)
        ok = ok & (gi >= -0.25 * dst.pitch) & (gi < 0.75 * dst.pitch)
        g[sel] = np.where(ok, gi, np.inf)
        q[sel], v[sel] = qs, _speed(qs, ns)
        ok_all[sel] = ok
    return g, v, q, sign, ins & ok_all


@dataclass(frozen=True)
class SeparationResult:
    """Result of :func:`separation_tca` for one flank pair.

    phi1 : (m,) pinion angles over ``cycles`` mesh cycles, rad;  te : (m,) TE of the driven gear, rad
    (same definition as :func:`ltca.geometry.bevel.tca.tca`, zero at phi1 = 0);  pairs : (k,) tooth-pair offsets j
    (pinion tooth j is at phi1 + j 2 pi / z1);  pinion_gap : (m, k, nu, nv) normal gap of the pinion grid
    points to the gear after the gear has closed the smallest gap, mm (inf off the gear flank);
    gear_gap : (m, k, nu2, nv2) the same for the gear grid points against the pinion;  gear_L, gear_Rn :
    (m,) contact point in the gear axial section, mm;  where : (m,) location of the contact
    (``"interior"`` or ``"<member> <edge>"``, edges :data:`EDGES`);  pinion, gear : the two grid flanks
    (:class:`ltca.geometry.flank.Flank`, body frames);  pinion_to_gear_L/Rn : (m, k, nu, nv) the pinion grid
    points in the gear axial section;  delta : elastic approach of the contact zone, mm;  ease_off :
    (nu, nv) pinion ease-off, mm (:func:`_ease_off`; NaN where the point never passes over the gear flank).
    """

    pinion_side: str
    gear_side: str
    phi1: np.ndarray
    te: np.ndarray
    pairs: np.ndarray
    pinion_gap: np.ndarray
    gear_gap: np.ndarray
    gear_L: np.ndarray
    gear_Rn: np.ndarray
    where: tuple
    pinion: object = field(repr=False)
    gear: object = field(repr=False)
    pinion_to_gear_L: np.ndarray = field(repr=False)
    pinion_to_gear_Rn: np.ndarray = field(repr=False)
    cycle: float = 0.0
    delta: float = 0.00632

    @property
    def te_arcsec(self) -> np.ndarray:
        return self.te / RAD_PER_ARCSEC

    def gear_zone(self) -> np.ndarray:
        """(m, nu2, nv2) gear grid points inside the contact zone (gap below ``delta``) at each position."""
        return np.any(self.gear_gap < self.delta, axis=1)

    def gear_gap_at(self, L: np.ndarray, Rn: np.ndarray) -> np.ndarray:
        """Normal gap (mm) at gear axial-section points (L, Rn), one per position (shape (m,)): the smallest
        over the tooth pairs, bilinear on the gear grid (linear in the depth fraction between the grid's
        root and face rows)."""
        fl = self.gear
        Rn_lo = np.interp(L, fl.v, fl.meta["Rn"][0])
        Rn_hi = np.interp(L, fl.v, fl.meta["Rn"][-1])
        t = (np.asarray(Rn) - Rn_lo) / (Rn_hi - Rn_lo)
        out = np.empty(len(self.phi1))
        for k in range(len(self.phi1)):
            f = RegularGridInterpolator((fl.u, fl.v), np.moveaxis(self.gear_gap[k], 0, -1), bounds_error=False,
                                        fill_value=np.inf)
            out[k] = np.min(f([[t[k], L[k]]])[0])
        return out

    def pinion_zone(self) -> np.ndarray:
        """(m, nu, nv) pinion grid points of the reference tooth inside the contact zone (pair j = 0)."""
        return self.pinion_gap[:, list(self.pairs).index(0)] < self.delta
    ease_off: np.ndarray = field(repr=False, default=None)


_OFFS = np.array([[0, 0], [1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [1, -1], [-1, 1], [-1, -1]], float)


def _refine(src: _Member, dst: _Member, x0: np.ndarray, a_src: np.ndarray, a_dst: np.ndarray, s_dst: float,
            to_gear, iters: int = 10) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Box-constrained Newton for the smallest gap over the source flank (t, L), one start per position.

    Gradient and Hessian from a 9-point stencil (h = 0.02 in t, 0.2 mm in L), shifted inside the box near an
    edge and carried to the iterate by the Taylor expansion; coordinates at a bound with the gradient
    pointing out are held (active set).  Returns the gap (gear rotation, rad; inf if the contact point
    left the other flank), the parameters x (n, 2), the flag and the gear-body contact point (n, 3).
    """
    h = np.array([0.02, 0.2])
    cap = np.array([0.15, 3.0])
    lo, hi = src.lo, src.hi

    def evaluate(x, a1, a2):
        r, n, ok = src.surface(x[..., 0], x[..., 1])
        g, v, q, _, ins = _gap(dst, src.to_mesh(r, a1), a2, s_dst, mask=False)
        G = to_gear(g, v, r, n)
        return np.where(ok, G, np.nan), ins & ok, r, q

    x = np.clip(np.array(x0, float), lo, hi)
    err = np.seterr(invalid="ignore", divide="ignore")
    for _ in range(iters):
        xc = np.clip(x, lo + h, hi - h)
        F = evaluate(xc[:, None, :] + _OFFS * h, a_src[:, None], a_dst[:, None])[0]
        gc = np.stack([(F[:, 1] - F[:, 2]) / (2 * h[0]), (F[:, 3] - F[:, 4]) / (2 * h[1])], -1)
        Htt = (F[:, 1] - 2 * F[:, 0] + F[:, 2]) / h[0] ** 2
        HLL = (F[:, 3] - 2 * F[:, 0] + F[:, 4]) / h[1] ** 2
        HtL = (F[:, 5] - F[:, 6] - F[:, 7] + F[:, 8]) / (4 * h[0] * h[1])
        dx = x - xc
        g = gc + np.stack([Htt * dx[:, 0] + HtL * dx[:, 1], HtL * dx[:, 0] + HLL * dx[:, 1]], -1)
        held = ((x <= lo + 1e-12) & (g > 0)) | ((x >= hi - 1e-12) & (g < 0))
        det = Htt * HLL - HtL ** 2
        full = -np.stack([HLL * g[:, 0] - HtL * g[:, 1], Htt * g[:, 1] - HtL * g[:, 0]], -1) / np.where(
            det != 0, det, 1.0)[:, None]
        H11 = np.stack([Htt, HLL], -1)
        one = np.where(H11 > 0, -g / np.where(H11 > 0, H11, 1.0), -np.sign(g) * cap)
        both_free = ~held.any(1) & (Htt > 0) & (det > 0)
        step = np.where(both_free[:, None], full, np.where(held, 0.0, one))
        step = np.where(~held.any(1)[:, None] & ~both_free[:, None], -np.sign(g) * 0.5 * cap, step)
        step = np.clip(np.where(np.isfinite(step), step, 0.0), -cap, cap)
        x = np.clip(x + step, lo, hi)
        if np.all(np.abs(step) < 1e-7 * h):
            break
    np.seterr(**err)
    G, ok, r, q = evaluate(x, a_src, a_dst)
    G = np.where(ok & np.isfinite(G), G, np.inf)
    return G, x, ok, (q if dst.name == "gear" else r)


def _exact_gear_rotation(P: _Member, G: _Member, r2: np.ndarray, ang2: np.ndarray, phi1: np.ndarray, s1: float,
                         s2: float, g2: np.ndarray, iters: int = 3) -> np.ndarray:
    """Gear rotation (rad, closing sense) that puts the gear points ``r2`` (body frame, (n, 3)) onto the pinion
    surface, from the first-order estimate ``g2``: Newton on the pinion-angle gap of the turned points (exact
    also when a gear edge touches the pinion, where the two normals differ)."""
    g2 = np.array(g2, float)
    for _ in range(iters):
        r_h = G.to_mesh(r2, ang2 + s2 * g2)
        g1, _, _, _, ok = _gap(P, r_h, phi1, s1, mask=False)
        eps = 1e-7                                  # d(pinion gap)/d(gear rotation), by a forward difference
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):     # points off the flank: inf - inf
            d = (g1 - _gap(P, G.to_mesh(r2, ang2 + s2 * (g2 + eps)), phi1, s1, mask=False)[0]) / eps
            step = np.where(ok & np.isfinite(d) & (np.abs(d) > 1e-12), g1 / np.where(d != 0, d, 1.0), 0.0)
        g2 = g2 + step
    return np.where(np.isfinite(g2), g2, np.inf)


def _label(member: str, x: np.ndarray, m: _Member) -> str:
    for k, (i, b) in enumerate(((0, m.lo[0]), (0, m.hi[0]), (1, m.lo[1]), (1, m.hi[1]))):
        if abs(x[i] - b) < 1e-9 * max(1.0, abs(b)):
            return f"{member} {EDGES[k]}"
    return "interior"


def reference_gear_angle(P: _Member, G: _Member, bl: BevelBlank, asm: Assembly) -> tuple[float, np.ndarray]:
    """The gear angle (rad) whose surface passes through the pinion mean point (pitch cone, mean cone distance) at
    phi1 = 0, to first order, and that pinion point (1, 3) in its body frame."""
    root, face = P._cones(bl.mean_cone_distance)
    rp = P.surface(np.array([-root / (face - root)]), np.array([bl.mean_cone_distance]))[0]
    r0 = G.from_mesh(P.to_mesh(rp, 0.0), 0.0)
    q0, _, ok0 = G.surface(*G.coords(r0))
    if not (ok0[0] and G.inside(*G.coords(r0))[0]):
        raise ValueError(f"asm = {asm}: the pinion mean point does not lie over the gear flank at phi1 = 0")
    return float((np.arctan2(r0[0, 1], r0[0, 0]) - np.arctan2(q0[0, 1], q0[0, 0]) + np.pi) % (2 * np.pi) - np.pi), rp


def separation_tca(pair: BevelPair, pinion_side: str = "concave", asm: Assembly = Assembly(),
                   steps_per_cycle: int = 16, cycles: float = 3.0, grid: tuple[int, int] = (20, 30),
                   delta: float = 0.00632, refine: bool = True) -> SeparationResult:
    """Separation-field TCA of one flank pair over ``cycles`` mesh cycles centred on phi1 = 0.

    Parameters
    ----------
    pair : BevelPair
    pinion_side : ``"concave"`` (meets the gear convex) or ``"convex"``
    asm : Assembly
        Assembly errors E, P, G (mm) and shaft angle (rad).
    steps_per_cycle : int, >= 4
        Positions per mesh cycle 2 pi / z1.
    cycles : float, in [1, 5]
        Mesh cycles shown (the TE envelope of the tooth pairs).
    grid : (nu, nv)
        Depth x face grid of both flanks, each >= 5 (pinion from half the clearance above its root cone).
    delta : float
        Elastic approach bounding the contact zone, mm (> 0).
    refine : bool
        Refine the smallest gap off the grid (needed for sub-arcsec TE).
    """
    if pinion_side not in ("concave", "convex"):
        raise ValueError(f"pinion_side = {pinion_side!r}: allowed 'concave' or 'convex'")
    if not (isinstance(steps_per_cycle, (int, np.integer)) and steps_per_cycle >= 4):
        raise ValueError(f"steps_per_cycle = {steps_per_cycle!r} is outside the allowed range [4, inf)")
    if not 1.0 <= cycles <= 5.0:
        raise ValueError(f"cycles = {cycles!r} is outside the allowed range [1, 5]")
    if len(grid) != 2 or min(grid) < 5:
        raise ValueError(f"grid = {grid!r}: give (nu, nv), each >= 5")
    if not delta > 0:
        raise ValueError(f"delta = {delta!r} is outside the allowed range (0, inf) mm")
    gear_side = "convex" if pinion_side == "concave" else "concave"
    bl = pair.blank
    B1, O1, B2, O2 = mesh_frames(bl, asm)
    clearance = bl.pinion.dedendum - bl.gear.addendum
    P = _Member(pair.pinion.flank(pinion_side), bl, "pinion", B1, O1, *grid, 0.5 * clearance)
    G = _Member(pair.gear.flank(gear_side), bl, "gear", B2, O2, *grid, 0.03 * bl.data.module)
    ratio, c1 = bl.pinion.z / bl.gear.z, 2 * np.pi / bl.pinion.z
    phi2_0, _ = reference_gear_angle(P, G, bl, asm)
    Kd = int(round(0.5 * cycles * steps_per_cycle))
    Ks = Kd + 2 * steps_per_cycle
    phi = np.arange(-Ks, Ks + 1) * c1 / steps_per_cycle
    ang2 = phi2_0 - ratio * phi
    # pinion grid onto the gear, gear grid onto the pinion
    r1h = P.to_mesh(P.flank.points[None], phi[:, None, None])
    g_pg, v_pg, q_pg, s2, _ = _gap(G, r1h, ang2[:, None, None])
    vg = _speed(G.flank.points, G.flank.normals)
    g1, v1, _, s1, _ = _gap(P, G.to_mesh(G.flank.points[None], ang2[:, None, None]), phi[:, None, None])
    g_gp = np.where(np.isfinite(g1), g1 * v1 / vg, np.inf)
    n = len(phi)
    cand = np.stack([g_pg.reshape(n, -1).min(1), g_gp.reshape(n, -1).min(1)], 1)
    x_pg = np.stack(np.unravel_index(g_pg.reshape(n, -1).argmin(1), g_pg.shape[1:]), 1)
    x_gp = np.stack(np.unravel_index(g_gp.reshape(n, -1).argmin(1), g_gp.shape[1:]), 1)
    X = [np.stack([P.t[x_pg[:, 0]], P.L[x_pg[:, 1]]], 1), np.stack([G.t[x_gp[:, 0]], G.L[x_gp[:, 1]]], 1)]
    Q = [q_pg[np.arange(n), x_pg[:, 0], x_pg[:, 1]], G.flank.points[x_gp[:, 0], x_gp[:, 1]]]
    live = np.isfinite(cand).any(1)
    if refine and live.any():
        idx = np.nonzero(live)[0]
        for k, (src, dst, a_s, a_d, s_d, conv) in enumerate((
                (P, G, phi, ang2, s2, lambda g, v, r, nn: g),
                (G, P, ang2, phi, s1, lambda g, v, r, nn: g * v / _speed(r, nn)))):
            Gr, xr, okr, qr = _refine(src, dst, X[k][idx], a_s[idx], a_d[idx], s_d, conv)
            better = okr & (Gr < cand[idx, k])
            j = idx[better]
            cand[j, k], X[k][j], Q[k][j] = Gr[better], xr[better], qr[better]
    # gear-grid candidates: replace the first-order conversion by the exact gear rotation
    j = np.nonzero(np.isfinite(cand[:, 1]))[0]
    if len(j):
        cand[j, 1] = _exact_gear_rotation(P, G, Q[1][j], ang2[j], phi[j], s1, s2, cand[j, 1])
    best = np.argmin(cand, 1)
    gmin = cand[np.arange(n), best]
    Lc, Rnc = to_pitch_coords(np.where(best[:, None] == 0, Q[0], Q[1]), bl.gear.pitch_angle)
    where = [_label(("pinion", "gear")[b], X[b][i], (P, G)[b]) if np.isfinite(gmin[i]) else "no contact"
             for i, b in enumerate(best)]
    # envelope over the tooth pairs j (pinion tooth j at phi1 + j c1 is the reference pair at that angle)
    J = Ks // steps_per_cycle + 1
    pairs = np.arange(-J, J + 1)
    kk = np.arange(-Kd, Kd + 1)[:, None] + pairs[None, :] * steps_per_cycle + Ks       # (m, k) indices
    valid = (kk >= 0) & (kk < n)
    kk = np.clip(kk, 0, n - 1)
    gpair = np.where(valid, gmin[kk], np.inf)
    g3 = gpair.min(1)
    if not np.all(np.isfinite(g3)):
        raise ValueError(f"no contact at some positions of the {pinion_side} pinion flank "
                         f"(phi1 = {phi[kk[~np.isfinite(g3), 0]][:3]} rad): the flanks do not meet")
    jb = gpair.argmin(1)
    kb = kk[np.arange(len(kk)), jb]
    te = -(g3 - g3[Kd])                         # driven sense: the gap to close is the lag
    pin_gap = np.where(valid[..., None, None], (g_pg[kk] - g3[:, None, None, None]) * v_pg[kk], np.inf)
    gear_gap = np.where(valid[..., None, None], (g_gp[kk] - g3[:, None, None, None]) * vg, np.inf)
    pin_gap = np.where(np.isfinite(pin_gap), pin_gap, np.inf)
    gear_gap = np.where(np.isfinite(gear_gap), gear_gap, np.inf)
    L12, Rn12 = to_pitch_coords(G.from_mesh(r1h, ang2[:, None, None]), bl.gear.pitch_angle)
    return SeparationResult(pinion_side, gear_side, np.arange(-Kd, Kd + 1) * c1 / steps_per_cycle, te, pairs,
                            pin_gap, gear_gap, Lc[kb], Rnc[kb], tuple(where[i] for i in kb), P.flank, G.flank,
                            L12[kk], Rn12[kk], c1, delta, _ease_off(g_pg, v_pg))


def _ease_off(g: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Pinion ease-off (nu, nv), mm: the smallest normal gap of each pinion grid point to the gear over the
    single-pair positions at the kinematic gear angle (parabolic interpolation in phi1), zero at its minimum;
    NaN where the point does not pass over the gear flank (no minimum inside the positions where it does)."""
    n = len(g)
    i = np.clip(g.argmin(0), 1, n - 2)
    f0, fm, fp = (np.take_along_axis(g, (i + d)[None], 0)[0] for d in (0, -1, 1))
    with np.errstate(invalid="ignore", divide="ignore"):
        curv = fm - 2 * f0 + fp
        gmin = np.where(np.isfinite(curv) & (curv > 0), f0 - (fp - fm) ** 2 / (8 * curv), g.min(0))
    gmin = np.where(np.isfinite(fm) & np.isfinite(fp), gmin, np.nan)     # never met the gear flank: no value
    e = gmin * np.take_along_axis(v, i[None], 0)[0]
    return e - np.nanmin(np.where(np.isfinite(e), e, np.nan))
