"""Unloaded tooth contact analysis of face-milled spiral bevel gears (pure kinematics).

Mesh frame S_h: origin at the common pitch apex; the mean pitch points of both members lie on +x_h at
the reference position.  Gear body frame: z2 = (cos g2, 0, sin g2), y2 = y_h; pinion body frame:
z1 = (cos g1', 0, -sin g1'), y1 = -y_h, with g1' = Sigma + dSigma - g2 (this is the gear machine frame
turned so that both generating crown gears coincide; see :func:`ltca.geometry.bevel.machine.conjugate_pinion_settings`).
Assembly errors: gear axial G along z2, pinion axial P along z1, offset E along y_h, shaft angle dSigma.
Members turn by phi1 about z1 and phi2 about z2; in mesh phi2 ~ -(z1/z2) phi1.

Continuous-tangency TCA (Litvin & Fuentes 2004, sec. 9.4 and 20.7): for each pinion angle phi1 solve
r1_h = r2_h, n1_h = -n2_h, f1 = 0, f2 = 0 for the seven unknowns (u1, theta1, psi1, u2, theta2, psi2, phi2)
(eight equations of rank seven; Gauss-Newton with a least-squares step, which also copes with the
rank-deficient line contact of conjugate surfaces).  Transmission error, in the driven sense (negative = gear lagging),
TE = s (-(phi2 - phi2_0) - (z1/z2)(phi1 - phi1_0))  (Cao et al. 2008, Eq. 1), s = :func:`drive_sign`: the pinion
drives the gear away from the pinion flank, so the driving rotation of the pinion is -s phi1.
Contact ellipse: gap = x^T (K1 + K2) x / 2 with K_i the curvature tensors (dn = K dr, convex > 0),
semi-axes sqrt(2 delta / lambda) for the elastic approach delta (Litvin & Fuentes 2004, sec. 9.3).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .blank import BevelBlank
from .generation import _guess, solve_axial_points, surface_state
from .machine import FlankCut, MemberCut
from .surface_state import _rotz, _rotz_cs, norm1d

__all__ = ["ContactError", "Assembly", "BevelPair", "TCAResult", "mesh_frames", "to_pitch_coords", "curvature_tensor",
           "drive_sign", "contact_path", "tca", "RAD_PER_ARCSEC"]

RAD_PER_ARCSEC = np.pi / (180.0 * 3600.0)


class ContactError(RuntimeError):
    """The continuous-tangency TCA found no interior contact point (edge contact or no contact)."""


@dataclass(frozen=True)
class Assembly:
    """Assembly errors: offset E, pinion axial P, gear axial G (mm), shaft angle error d_sigma (rad)."""

    E: float = 0.0
    P: float = 0.0
    G: float = 0.0
    d_sigma: float = 0.0

    def __post_init__(self) -> None:
        for name in ("E", "P", "G"):
            v = getattr(self, name)
            if not (np.isfinite(v) and abs(v) <= 10.0):
                raise ValueError(f"{name} = {v!r} is outside the allowed range [-10, 10] mm")
        if not abs(self.d_sigma) <= np.deg2rad(2.0):
            raise ValueError(f"d_sigma = {self.d_sigma!r} is outside the allowed range [-0.0349, 0.0349] rad")


@dataclass(frozen=True)
class BevelPair:
    """A generated pair: blank and the cuts of both members."""

    blank: BevelBlank
    gear: MemberCut
    pinion: MemberCut


@dataclass(frozen=True)
class TCAResult:
    """Result of :func:`tca` for one flank pair, positions ordered by phi1.

    phi1, phi2 : (n,) rad;  te : (n,) rad (driven sense, zero at the reference position);
    r_h : (n, 3) contact point in the mesh frame;  r2 : (n, 3) on the gear body frame;
    gear_L, gear_Rn : (n,) contact point in the gear axial section (cone distance, height over pitch cone);
    r1 : (n, 3) in the pinion body frame;  major, minor : (n,) ellipse axis lengths (2a, 2b), mm;
    major_dir : (n, 3) unit direction of the major axis in the gear body frame;
    cycle : pinion angle of one mesh cycle 2 pi / z1;  stops : why the path ended at each end;
    phi1_3, te_3 : TE over three cycles (envelope of the neighbouring pairs, driven sense), rad.
    """

    pinion_side: str
    gear_side: str
    phi1: np.ndarray
    phi2: np.ndarray
    te: np.ndarray
    r_h: np.ndarray
    r1: np.ndarray
    r2: np.ndarray
    gear_L: np.ndarray
    gear_Rn: np.ndarray
    major: np.ndarray
    minor: np.ndarray
    major_dir: np.ndarray
    cycle: float
    stops: tuple
    phi1_3: np.ndarray
    te_3: np.ndarray
    params: np.ndarray = field(repr=False, default=None)

    @property
    def te_arcsec(self) -> np.ndarray:
        return self.te / RAD_PER_ARCSEC

    @property
    def contact_ratio(self) -> float:
        """Pinion angle range of the path on both flanks divided by the mesh cycle."""
        return float((self.phi1.max() - self.phi1.min()) / self.cycle)


def _rz_mats(a: np.ndarray) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    m = np.zeros(np.shape(a) + (3, 3))
    m[..., 0, 0], m[..., 0, 1], m[..., 1, 0], m[..., 1, 1], m[..., 2, 2] = c, -s, s, c, 1.0
    return m


def mesh_frames(blank: BevelBlank, asm: Assembly = Assembly()) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                                          np.ndarray]:
    """Body bases (columns x, y, z in S_h) and origins of pinion and gear: (B1, O1, B2, O2)."""
    g2 = blank.gear.pitch_angle
    g1 = blank.data.shaft_angle + asm.d_sigma - g2
    z2 = np.array([np.cos(g2), 0.0, np.sin(g2)])
    y2 = np.array([0.0, 1.0, 0.0])
    z1 = np.array([np.cos(g1), 0.0, -np.sin(g1)])
    y1 = -y2
    B2 = np.stack([np.cross(y2, z2), y2, z2], 1)
    B1 = np.stack([np.cross(y1, z1), y1, z1], 1)
    return B1, asm.P * z1 + asm.E * y2, B2, asm.G * z2


def to_pitch_coords(r_body: np.ndarray, pitch_angle: float) -> tuple[np.ndarray, np.ndarray]:
    """Cone distance L and height over the pitch cone Rn of body-frame points (..., 3), mm."""
    Z = r_body[..., 2]
    rho = np.hypot(r_body[..., 0], r_body[..., 1])
    return Z * np.cos(pitch_angle) + rho * np.sin(pitch_angle), -Z * np.sin(pitch_angle) + rho * np.cos(pitch_angle)


def _inside(blank: BevelBlank, member: str, r: np.ndarray) -> bool:
    mb = blank.member(member)
    L, Rn = to_pitch_coords(r, mb.pitch_angle)
    A0 = blank.outer_cone_distance
    root, face = blank.cones(member, L)
    return bool(blank.inner_cone_distance - 1e-9 <= L <= A0 + 1e-9 and root <= Rn <= face + 1e-9)


def _solve_psi(fc: FlankCut, u, th, psi, iters: int = 30):
    """psi with f(u, theta, psi) = 0 near the given psi (vectorised secant-Newton)."""
    for _ in range(iters):
        f = surface_state(fc, u, th, psi, with_work=False).f
        df = (surface_state(fc, u, th, psi + 1e-7, with_work=False).f - f) / 1e-7
        dpsi = -f / df
        psi = psi + np.clip(dpsi, -0.05, 0.05)
        if np.all(np.abs(f) < 1e-12):
            break
    return psi


def drive_sign(r2: np.ndarray, n2: np.ndarray) -> float:
    """+1 or -1: the sense of gear rotation (about +z2) that moves the gear flank at the body-frame point
    ``r2`` (normal ``n2``, out of the material) towards the pinion, sign(n2 . e_theta).

    The pinion drives the gear the other way, so the TE in the driven sense (negative = gear lagging) is
    ``drive_sign * (-(phi2 - phi2_0) - (z1/z2) phi1)``: on the flank pair whose pinion turns by -phi1 when
    it drives, the sign flips (here the working flank, pinion concave, right-hand gear convex).
    """
    return float(np.sign(n2[..., 1] * r2[..., 0] - n2[..., 0] * r2[..., 1]))


def curvature_tensor(fc: FlankCut, q: np.ndarray) -> np.ndarray:
    """Curvature tensors (3x3, in the work body frame, tangent-plane part) at parameters q (n, 3).

    Central differences of points and normals over (u, theta) on the generated surface, with psi
    re-solved from the equation of meshing; K with dn = K dr (convex positive)."""
    q = np.atleast_2d(q)
    hu, ht = 2e-3, 2e-5
    offs = np.array([[hu, 0], [-hu, 0], [0, ht], [0, -ht]])
    u = q[:, None, 0] + offs[None, :, 0]
    th = q[:, None, 1] + offs[None, :, 1]
    psi = _solve_psi(fc, u, th, np.repeat(q[:, None, 2], 4, 1))
    st = surface_state(fc, u, th, psi)
    r, n = st.r_w, st.n_w
    ru, rt = (r[:, 0] - r[:, 1]) / (2 * hu), (r[:, 2] - r[:, 3]) / (2 * ht)
    nu_, nt = (n[:, 0] - n[:, 1]) / (2 * hu), (n[:, 2] - n[:, 3]) / (2 * ht)
    n0 = surface_state(fc, q[:, 0], q[:, 1], q[:, 2]).n_w
    e1 = ru - np.einsum("ni,ni->n", ru, n0)[:, None] * n0
    e1 /= np.linalg.norm(e1, axis=1, keepdims=True)
    e2 = np.cross(n0, e1)
    E = np.stack([e1, e2], 1)                                     # (n, 2, 3)
    Jr = np.einsum("nai,nbi->nab", E, np.stack([ru, rt], 1))      # [e_a . r_b]
    Jn = np.einsum("nai,nbi->nab", E, np.stack([nu_, nt], 1))
    K2 = Jn @ np.linalg.inv(Jr)
    K2 = 0.5 * (K2 + np.swapaxes(K2, 1, 2))
    return np.einsum("nai,nab,nbj->nij", E, K2, E)


def contact_path(pair: BevelPair, pinion_side: str = "concave", asm: Assembly = Assembly(),
                 steps_per_cycle: int = 16, max_cycles: float = 3.0
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple[str, ...]]:
    """The path of contact of :func:`tca` without the contact ellipses: the kinematics alone.

    Parameters as :func:`tca`.

    Returns
    -------
    phi1 : ndarray (n,)
        Pinion angles, rad, ascending.
    X : ndarray (n, 7)
        (u1, theta1, psi1, u2, theta2, psi2, phi2) at each angle (module docstring).
    te : ndarray (n,)
        Transmission error, rad (driven sense, zero at phi1 = 0).
    stops : tuple of str
        Why the path ended at each end.
    """
    if pinion_side not in ("concave", "convex"):
        raise ValueError(f"pinion_side = {pinion_side!r}: allowed 'concave' or 'convex'")
    if steps_per_cycle < 4:
        raise ValueError(f"steps_per_cycle = {steps_per_cycle!r} is outside the allowed range [4, inf)")
    gear_side = "convex" if pinion_side == "concave" else "concave"
    bl = pair.blank
    fc1, fc2 = pair.pinion.flank(pinion_side), pair.gear.flank(gear_side)
    B1, O1, B2, O2 = mesh_frames(bl, asm)
    Am = bl.mean_cone_distance
    W = 0.1 * Am                                                   # weight of the normal equations, mm

    B1T, B2T = B1.T, B2.T

    def residual(X, phi1):
        s1 = surface_state(fc1, X[..., 0], X[..., 1], X[..., 2])
        s2 = surface_state(fc2, X[..., 3], X[..., 4], X[..., 5])
        c1, z1 = np.cos(phi1), np.sin(phi1)
        c2, z2 = np.cos(X[..., 6]), np.sin(X[..., 6])
        r1 = _rotz_cs(s1.r_w, c1, z1) @ B1T + O1
        n1 = _rotz_cs(s1.n_w, c1, z1) @ B1T
        r2 = _rotz_cs(s2.r_w, c2, z2) @ B2T + O2
        n2 = _rotz_cs(s2.n_w, c2, z2) @ B2T
        out = np.empty(np.shape(X)[:-1] + (8,))
        out[..., :3], out[..., 3:6], out[..., 6], out[..., 7] = r1 - r2, W * (n1 + n2), s1.f, s2.f
        return out

    h = np.array([1e-6, 1e-8, 1e-8, 1e-6, 1e-8, 1e-8, 1e-8])
    steps = np.diag(h)
    angles = np.array([1, 2, 4, 5, 6])                             # the unknowns in rad: their steps are capped

    def newton(X, phi1):
        # Levenberg-Marquardt: damping keeps steps small along the (near) null direction of line contact
        F = residual(X, phi1)
        nF = norm1d(F)
        mu = 1e-4
        for _ in range(60):
            if np.abs(F).max() < 1e-10:
                return X, True
            Xp = X[None, :] + steps
            J = (residual(Xp, phi1) - F).T / h
            A = J.T @ J
            g = J.T @ F
            while True:
                dx = -np.linalg.solve(A + mu * np.diag(np.diag(A) + 1e-12), g)
                dx *= min(1.0, 0.1 / max(np.abs(dx[angles]).max(), 1e-300))
                Fn = residual(X + dx, phi1)
                if norm1d(Fn) < nF or mu > 1e8:
                    break
                mu *= 10.0
            X, F, nF = X + dx, Fn, norm1d(Fn)
            mu = max(mu * 0.1, 1e-12)
        return X, bool(np.abs(F).max() < 1e-8)

    # reference position: gear mean point, phi1 = 0
    mb2, mb1 = bl.gear, bl.pinion
    X0 = np.zeros(7)
    for k, (fc, mb) in enumerate(((fc1, mb1), (fc2, mb2))):
        Z, rho = Am * np.cos(mb.pitch_angle), Am * np.sin(mb.pitch_angle)
        x, ok = solve_axial_points(fc, np.array([Z]), np.array([rho]), _guess(fc, Z, rho)[None])
        X0[3 * k:3 * k + 3] = x[0]
    # the gear angle that brings the two mean points together to first order
    s1 = surface_state(fc1, *X0[:3]); s2 = surface_state(fc2, *X0[3:6])
    r1 = s1.r_w @ B1.T + O1
    a1 = np.arctan2(*(np.linalg.solve(B2, r1 - O2)[[1, 0]]))
    X0[6] = a1 - np.arctan2(s2.r_w[1], s2.r_w[0])
    X, ok = newton(X0, 0.0)
    if not ok:
        raise ContactError(f"TCA ({pinion_side} pinion flank): no interior point of tangency near the mean "
                           f"point at phi1 = 0 (residual {np.max(np.abs(residual(X, 0.0))):.2e}); contact is "
                           f"at an edge or absent: use the separation-field analysis, or check the settings "
                           f"and the assembly errors {asm}")
    s1 = surface_state(fc1, *X[:3]); s2 = surface_state(fc2, *X[3:6])
    for member, r in (("gear", s2.r_w), ("pinion", s1.r_w)):
        if not _inside(bl, member, r):
            L, Rn = to_pitch_coords(r, bl.member(member).pitch_angle)
            raise ContactError(f"TCA ({pinion_side} pinion flank): the point of tangency at phi1 = 0 lies off the "
                               f"{member} flank (L = {L:.3f} mm, Rn = {Rn:.3f} mm, outside the blank): contact "
                               f"is at an edge; use the separation-field analysis "
                               f"(geometry.bevel.separation.separation_tca), or check the assembly errors {asm}")
    cycle = 2 * np.pi / bl.pinion.z
    dphi = cycle / steps_per_cycle
    nmax = int(np.ceil(max_cycles * steps_per_cycle))
    rows, stops = {0: (0.0, X)}, []
    for sgn in (1, -1):
        Xp, Xpp = X, X
        reason = f"reached {max_cycles} cycles"
        for i in range(1, nmax + 1):
            phi1 = sgn * i * dphi
            Xn, ok = newton(2 * Xp - Xpp if i > 1 else Xp, phi1)
            if not ok:
                reason = f"Newton did not converge at phi1 = {phi1:.5f} rad (contact left the surfaces?)"
                break
            s1 = surface_state(fc1, *Xn[:3]); s2 = surface_state(fc2, *Xn[3:6])
            if not (_inside(bl, "gear", s2.r_w) and _inside(bl, "pinion", s1.r_w)):
                reason = f"contact reached the flank edge at phi1 = {phi1:.5f} rad"
                break
            rows[sgn * i] = (phi1, Xn)
            Xpp, Xp = Xp, Xn
        stops.append(reason)
    keys = sorted(rows)
    phi1 = np.array([rows[k][0] for k in keys])
    Xs = np.array([rows[k][1] for k in keys])
    ratio = bl.pinion.z / bl.gear.z
    ref = surface_state(fc2, *X[3:6])
    te = drive_sign(ref.r_w, ref.n_w) * (-(Xs[:, 6] - X[6]) - ratio * phi1)
    return phi1, Xs, te, tuple(stops)


def tca(pair: BevelPair, pinion_side: str = "concave", asm: Assembly = Assembly(), steps_per_cycle: int = 16,
        delta: float = 0.00632, max_cycles: float = 3.0) -> TCAResult:
    """Continuous-tangency TCA of one flank pair, from the mean point both ways to the flank edges.

    Parameters
    ----------
    pair : BevelPair
    pinion_side : ``"concave"`` (drives the gear convex) or ``"convex"`` (meets the gear concave)
    asm : Assembly
    steps_per_cycle : int, >= 4
    delta : float
        Elastic approach of the contact ellipse, mm.
    max_cycles : float
        Largest pinion rotation followed each way, in mesh cycles.
    """
    phi1, Xs, te, stops = contact_path(pair, pinion_side, asm, steps_per_cycle, max_cycles)
    gear_side = "convex" if pinion_side == "concave" else "concave"
    bl = pair.blank
    fc1, fc2 = pair.pinion.flank(pinion_side), pair.gear.flank(gear_side)
    B1, O1, B2, O2 = mesh_frames(bl, asm)
    cycle = 2 * np.pi / bl.pinion.z
    phi2 = Xs[:, 6]
    s1 = surface_state(fc1, Xs[:, 0], Xs[:, 1], Xs[:, 2]); s2 = surface_state(fc2, Xs[:, 3], Xs[:, 4], Xs[:, 5])
    r_h = _rotz(s2.r_w, phi2) @ B2.T + O2
    L2, Rn2 = to_pitch_coords(s2.r_w, bl.gear.pitch_angle)
    # contact ellipses, in the gear body frame
    K2 = curvature_tensor(fc2, Xs[:, 3:6])
    K1 = curvature_tensor(fc1, Xs[:, 0:3])
    R1 = B1 @ _rz_mats(phi1)                                       # pinion body -> mesh
    R2 = B2 @ _rz_mats(phi2)
    M = np.einsum("nji,njk->nik", R2, R1)                          # pinion body -> gear body
    K = K2 + M @ K1 @ np.swapaxes(M, 1, 2)
    w, v = np.linalg.eigh(K)                                       # the normal direction gives ~0
    n2 = s2.n_w
    tang = np.abs(np.einsum("nik,ni->nk", v, n2)) < 0.5
    wt = np.where(tang, w, np.inf)
    order = np.argsort(wt, axis=1)
    lam = np.take_along_axis(wt, order, 1)[:, :2]
    with np.errstate(divide="ignore", invalid="ignore"):
        axes = np.where(lam > 0, 2 * np.sqrt(2 * delta / lam), np.inf)
    major_dir = np.take_along_axis(v, order[:, None, :1], 2)[..., 0]
    # three cycles: envelope of neighbouring pairs (driven sense: the leading pair carries the gear)
    p3 = np.linspace(-1.5 * cycle, 1.5 * cycle, 3 * steps_per_cycle * 4 + 1)
    curves = []
    for k in range(-4, 5):
        x = p3 - k * cycle
        curves.append(np.where((x >= phi1[0]) & (x <= phi1[-1]), np.interp(x, phi1, te), -np.inf))
    te3 = np.max(curves, axis=0)
    return TCAResult(pinion_side, gear_side, phi1, phi2, te, r_h, s1.r_w, s2.r_w, L2, Rn2, axes[:, 0], axes[:, 1],
                     major_dir, cycle, tuple(stops), p3, te3, Xs)
