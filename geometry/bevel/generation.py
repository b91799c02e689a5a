"""Generated tooth surfaces of face-milled spiral bevel gears (cradle model, equation of meshing).

A work point is the image of a blade point (u, theta) at cradle angle psi (frames in
:mod:`ltca.geometry.bevel.machine`).  The generated surface is the envelope of the blade surfaces, selected by
the equation of meshing (Litvin & Fuentes 2004, sec. 6.1, 20.5):

    f(u, theta, psi) = n_m . v_m = 0,    v_m = z_m x r_m - phi'(psi) k x (r_m - O_w),

the normal times the velocity of the blade point relative to the work, per unit cradle rotation (mm).
On the universal machine (:mod:`ltca.geometry.bevel.machine`) the cutter centre, its tilt and the work origin move
with psi too, and their derivatives enter the relative velocity (Litvin & Fuentes 2004, sec. 6.1; Fan, J. Mech.
Des. 129 (2007) 31-37):

    v_m = z_m x r_m + Rz(psi) (Sr'(psi) e_q + R_t'(psi) r_c) - O_w'(psi) - phi'(psi) k x (r_m - O_w(psi)),

with e_q = (cos q, sin q, 0).  A formate member has no envelope: its flank is the cutter surface at psi = 0,
which the same solver finds with the equation of meshing replaced by f = Sr psi = 0.
Grid points are fixed in the axial section of the work: for each node the two axial-section coordinates
(axial position Z and radius rho) are prescribed and (u, theta, psi) solved with Newton on the three
equations, vectorised over the nodes and continued from node to node (centre column first, then column by
column towards toe and heel).  Nodes are placed in pitch-cone coordinates: ``L`` along the pitch
generatrix (toe L = A_i to heel L = A_0, i.e. trimmed by the back cones), ``Rn`` normal to it in the axial
plane, from just above the root cone (into the fillet) up to the face cone.
"""
from __future__ import annotations

import numpy as np

from ..flank import Flank, surface_curvatures
from .blank import BevelBlank
from .machine import FlankCut, MemberCut, cutter_to_cradle, gear_settings, roll
from .surface_state import SurfaceState, _vectors, work_state

__all__ = ["MeshingError", "SurfaceState", "surface_state", "solve_axial_points", "generate_flank",
           "generate_member", "normal_thickness", "standard_gear_cut", "axial_grid"]


class MeshingError(RuntimeError):
    """The equation of meshing has no (converged) solution for some grid region."""


def surface_state(fc: FlankCut, u: np.ndarray, theta: np.ndarray, psi: np.ndarray,
                  with_work: bool = True) -> SurfaceState:
    """Evaluate the generating blade, the equation of meshing and the work point (vectorised)."""
    ms = fc.machine
    if not ms.is_basic:
        from .universal import universal_state
        return universal_state(fc, u, theta, psi, with_work)
    # the blade point and normal (cutter frame, centre moved to Sr (cos q, sin q, 0)) turned by psi about z_m,
    # component by component: the arithmetic of HeadCutter.surface and _rotz without building the (..., 3) arrays
    p = fc.cutter.profile(u)
    psi = np.asarray(psi, dtype=float)
    c, s = np.cos(theta), np.sin(theta)
    cp, sp = np.cos(psi), np.sin(psi)
    C, k, O = ms.cutter_center, ms.work_axis, ms.work_origin
    x, y = p.rho * c + C[0], p.rho * s + C[1]
    nx, ny = p.n_rho * c, p.n_rho * s
    rx, ry = cp * x - sp * y, sp * x + cp * y
    r_m = _vectors(rx, ry, p.z + C[2])
    n_m = _vectors(cp * nx - sp * ny, sp * nx + cp * ny, p.n_z)
    d = r_m - O
    phi, dphi = roll(ms, psi)
    # v = e_z x r_m - phi' k x d, with k = (k_x, 0, k_z) (the products of _cross with the zero terms left out)
    dx, dy, dz = d[..., 0], d[..., 1], d[..., 2]
    v = _vectors(-ry - dphi * -(k[2] * dy), rx - dphi * (k[2] * dx - k[0] * dz), -(dphi * (k[0] * dy)))
    f = np.einsum("...i,...i", n_m, v)
    return work_state(ms, d, r_m, n_m, f, phi, with_work)


def _residual(fc, x, Zt, Rt):
    st = surface_state(fc, x[..., 0], x[..., 1], x[..., 2], with_work=False)
    return _vectors(st.f, st.Z - Zt, st.rho - Rt)


def solve_axial_points(fc: FlankCut, Zt: np.ndarray, Rt: np.ndarray, x0: np.ndarray, tol: float = 1e-11,
                       max_iter: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """Newton for (u, theta, psi) putting the generated point at axial-section (Zt, Rt).

    Parameters
    ----------
    Zt, Rt : ndarray, shape (n,)
        Target axial position and radius in the work frame, mm.
    x0 : ndarray, shape (n, 3)
        Initial guess of (u [mm], theta [rad], psi [rad]).

    Returns
    -------
    x : ndarray, shape (n, 3);  ok : ndarray of bool, shape (n,) (converged to ``tol`` mm).
    """
    x = np.array(x0, dtype=float)
    steps = np.array([1e-6, 1e-8, 1e-8])
    cap = np.array([2.0, 0.05, 0.1])
    ok = np.zeros(len(x), bool)
    n = len(x)
    Z4, R4 = np.tile(Zt, 4), np.tile(Rt, 4)
    for _ in range(max_iter):
        # the residual and its three forward-difference stencils in one evaluation (point by point the same
        # arithmetic as four; a small batch costs the blade and machine evaluation once, not four times)
        X = np.tile(x, (4, 1))
        for j in range(3):
            X[(j + 1) * n:(j + 2) * n, j] += steps[j]
        F4 = _residual(fc, X, Z4, R4)
        F = F4[:n]
        ok = np.all(np.abs(F) < tol, axis=-1)
        if ok.all():
            break
        J = np.empty(F.shape + (3,))
        for j in range(3):
            J[..., j] = (F4[(j + 1) * n:(j + 2) * n] - F) / steps[j]
        try:
            dx = np.linalg.solve(J, -F[..., None])[..., 0]
        except np.linalg.LinAlgError:
            dx = np.linalg.lstsq(J.reshape(-1, 3), -F.reshape(-1), rcond=None)[0].reshape(-1, 3) \
                if len(x) == 1 else np.zeros_like(x)
        dx = np.where(np.isfinite(dx), dx, 0.0)
        scale = np.max(np.abs(dx) / cap, axis=-1, keepdims=True)
        x = x + np.where(ok[:, None], 0.0, dx / np.maximum(scale, 1.0))
    F = _residual(fc, x, Zt, Rt)
    return x, np.all(np.abs(F) < 10 * tol, axis=-1)


def axial_grid(blank: BevelBlank, member: str, nu: int = 20, nv: int = 30, root_offset: float | None = None
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Grid of the flank in the axial section, trimmed by the blank.

    Returns
    -------
    t : (nu,) depth fraction; L : (nv,) cone distance, mm; Rn : (nu, nv) offset normal to the pitch
    generatrix, mm; Z, rho : (nu, nv) axial position and radius, mm.
    """
    if nu < 3 or nv < 3:
        raise ValueError(f"grid (nu, nv) = ({nu}, {nv}) is outside the allowed range: both >= 3")
    mb = blank.member(member)
    A0 = blank.outer_cone_distance
    L = np.linspace(blank.inner_cone_distance, A0, nv)
    root, face = blank.cones(member, L)
    off = 0.03 * blank.data.module if root_offset is None else root_offset
    t = np.linspace(0.0, 1.0, nu)
    Rn = (root + off)[None, :] + t[:, None] * (face - root - off)[None, :]
    g = mb.pitch_angle
    Z = L[None, :] * np.cos(g) - Rn * np.sin(g)
    rho = L[None, :] * np.sin(g) + Rn * np.cos(g)
    return t, L, Rn, Z, rho


def _guess(fc: FlankCut, Z: float, rho: float) -> np.ndarray:
    """Initial (u, theta, psi) for the node in the work's x_w-z_w half plane at psi = 0."""
    ms = fc.machine
    r_m = ms.work_origin + ms.work_basis @ np.array([rho, 0.0, Z])
    r_c = r_m - ms.cutter_center
    if ms.tilt:
        r_c = cutter_to_cradle(ms)[:3, :3].T @ r_c
    return np.array([float(fc.cutter.u_at_depth(max(-r_c[2], 0.0))), np.arctan2(r_c[1], r_c[0]), 0.0])


def _region(msg: str, L: np.ndarray, Rn: np.ndarray, bad: np.ndarray, side: str) -> MeshingError:
    return MeshingError(f"{msg} on the {side} flank for {bad.sum()} grid node(s) in the axial-section region "
                        f"L = [{L[bad].min():.3f}, {L[bad].max():.3f}] mm, Rn = [{Rn[bad].min():.3f}, "
                        f"{Rn[bad].max():.3f}] mm (L cone distance, Rn height over the pitch cone)")


def generate_flank(fc: FlankCut, blank: BevelBlank, member: str, nu: int = 20, nv: int = 30,
                   root_offset: float | None = None) -> Flank:
    """Generated flank of ``member`` cut by ``fc`` on an (nu x nv) axial-section grid.

    Returns
    -------
    Flank
        ``u`` = depth fraction t (root -> face cone), ``v`` = cone distance L (mm), side from the blade.
        ``meta`` holds ``params`` (nu, nv, 3) = (u, theta, psi), ``Rn``, ``meshing_residual`` (max |f|, mm),
        ``undercut`` (bool array: profile tangent folded back), ``flank_cut``.

    Raises
    ------
    MeshingError
        Naming the grid region where Newton found no solution or the solution lies off the blade.
    """
    t, L, Rn, Z, rho = axial_grid(blank, member, nu, nv, root_offset)
    X = np.full((nu, nv, 3), np.nan)
    ok = np.zeros((nu, nv), bool)
    jm, im = nv // 2, nu // 2
    x, okk = solve_axial_points(fc, Z[im:im + 1, jm], rho[im:im + 1, jm], _guess(fc, Z[im, jm], rho[im, jm])[None])
    if not okk[0]:
        bad = np.zeros((nu, nv), bool)
        bad[im, jm] = True
        raise _region("no solution of the equation of meshing at the mean point", np.broadcast_to(L, Z.shape),
                      Rn, bad, fc.side)
    X[im, jm], ok[im, jm] = x[0], True
    for rng in (range(im + 1, nu), range(im - 1, -1, -1)):       # centre column, node by node
        prev = im
        for i in rng:
            g = X[prev, jm] if abs(prev - im) < 1 or not ok[prev, jm] else \
                2 * X[prev, jm] - X[2 * prev - i if 0 <= 2 * prev - i < nu else prev, jm]
            x, okk = solve_axial_points(fc, Z[i:i + 1, jm], rho[i:i + 1, jm], g[None])
            if not okk[0] and ok[prev, jm]:                    # a coarse row step: continue in 8 sub-steps
                x = X[prev, jm][None]
                for w in np.linspace(0.125, 1.0, 8):
                    x, okk = solve_axial_points(fc, Z[prev:prev + 1, jm] + w * (Z[i, jm] - Z[prev, jm]),
                                                rho[prev:prev + 1, jm] + w * (rho[i, jm] - rho[prev, jm]), x)
                    if not okk[0]:
                        break
            X[i, jm], ok[i, jm] = x[0], okk[0]
            prev = i
    for rng, step in ((range(jm + 1, nv), 1), (range(jm - 1, -1, -1), -1)):   # columns
        for j in rng:
            p1 = X[:, j - step]
            p2 = X[:, j - 2 * step] if abs(j - 2 * step - jm) < abs(j - jm) else p1
            x, okk = solve_axial_points(fc, Z[:, j], rho[:, j], 2 * p1 - p2)
            X[:, j], ok[:, j] = x, okk
    Lg = np.broadcast_to(L, Z.shape)
    if not ok.all():
        raise _region("the equation of meshing did not converge", Lg, Rn, ~ok, fc.side)
    st = surface_state(fc, X[..., 0], X[..., 1], X[..., 2])
    off_blade = X[..., 0] < fc.cutter.u_min - 1e-9
    if off_blade.any():
        raise _region("the solution lies beyond the blade tip (root region not reached by the cutter)",
                      Lg, Rn, off_blade, fc.side)
    k, d = surface_curvatures(st.r_w, st.n_w, t, L)
    ru = np.gradient(st.r_w, t, axis=0)
    rv = np.gradient(st.r_w, L, axis=1)
    jac = np.einsum("...i,...i", np.cross(ru, rv), st.n_w)
    ref = np.sign(np.median(jac))
    undercut = np.sign(jac) != ref
    meta = dict(params=X, Rn=Rn, Z=Z, rho=rho, meshing_residual=float(np.max(np.abs(st.f))),
                undercut=undercut, flank_cut=fc, member=member)
    return Flank(st.r_w, st.n_w, t, L, k, d, side=fc.side, u_name="depth fraction t", v_name="L [mm]",
                 meta=meta)


def generate_member(cut: MemberCut, blank: BevelBlank, nu: int = 20, nv: int = 30) -> dict[str, Flank]:
    """Both flanks of one member: ``{"concave": Flank, "convex": Flank}``."""
    return {s: generate_flank(cut.flank(s), blank, cut.member, nu, nv) for s in ("concave", "convex")}


def _mean_points(cut: MemberCut, blank: BevelBlank, Rn: float = 0.0) -> tuple[SurfaceState, SurfaceState]:
    mb = blank.member(cut.member)
    L, g = blank.mean_cone_distance, mb.pitch_angle
    Z, rho = L * np.cos(g) - Rn * np.sin(g), L * np.sin(g) + Rn * np.cos(g)
    out = []
    for s in ("concave", "convex"):
        fc = cut.flank(s)
        x, ok = solve_axial_points(fc, np.array([Z]), np.array([rho]), _guess(fc, Z, rho)[None])
        if not ok[0]:
            raise MeshingError(f"no solution of the equation of meshing at the mean point of the {s} flank")
        out.append(surface_state(fc, x[:, 0], x[:, 1], x[:, 2]))
    return out[0], out[1]


def normal_thickness(cut: MemberCut, blank: BevelBlank) -> float:
    """Mean normal circular tooth thickness of a generated member, mm.

    Measured on the pitch cone at the mean cone distance: transverse arc (2 pi / z - slot angle) rho_m
    times cos(beta_m), the definition used by :func:`ltca.geometry.bevel.blank.design_blank`.
    """
    cc, cv = _mean_points(cut, blank)
    a_cc = np.arctan2(cc.r_w[0, 1], cc.r_w[0, 0])
    a_cv = np.arctan2(cv.r_w[0, 1], cv.r_w[0, 0])
    gap = abs((a_cc - a_cv + np.pi) % (2 * np.pi) - np.pi)
    mb = blank.member(cut.member)
    # a tooth lies between the two points when the concave normal points away from the convex point
    tooth = float(np.dot(cc.n_w[0], cc.r_w[0] - cv.r_w[0])) > 0.0
    ang = gap if tooth else 2 * np.pi / mb.z - gap
    return float(ang * mb.mean_pitch_radius * np.cos(blank.data.spiral_angle))


def standard_gear_cut(blank: BevelBlank, edge_radius: float | None = None, tol: float = 1e-5) -> MemberCut:
    """Standard gear settings (:func:`ltca.geometry.bevel.machine.gear_settings`) with the point width refined by
    secant steps until the generated mean normal thickness equals the design value within ``tol`` mm."""
    target = blank.gear.mean_normal_thickness
    cut = gear_settings(blank, edge_radius=edge_radius)
    W = 2 * (cut.concave.cutter.point_radius - blank.data.cutter_radius)
    rf = cut.concave.cutter.edge_radius
    e0 = normal_thickness(cut, blank) - target
    W1 = W + e0
    for _ in range(8):
        cut = gear_settings(blank, point_width=W1, edge_radius=rf)
        e1 = normal_thickness(cut, blank) - target
        if abs(e1) < tol:
            return cut
        W, W1, e0 = W1, W1 - e1 * (W1 - W) / (e1 - e0), e1
    raise MeshingError(f"point width iteration did not reach the design thickness (error {e1:.2e} mm)")
