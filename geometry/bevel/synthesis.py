"""Local synthesis of the pinion of a face-milled spiral bevel pair at the mean contact point M0.

Second-order relations of two surfaces in mesh (Litvin & Fuentes, *Gear Geometry and Applied Theory*,
2nd ed. 2004, ch. 8-9; Litvin, NASA CR-4342, 1990), written here in tensor form in one fixed frame.
Bodies i = 1, 2 turn with angular velocities w_i about axes through O_i; at the contact point r the
outward unit normals are n = n1 = -n2; K_i is the curvature tensor of body i (dn_i = K_i dr, convex
positive; 3x3, tangent-plane part); v12 = w1 x (r - O1) - w2 x (r - O2); x = velocity of the contact
point over surface 1 (over surface 2 it is x + v12).  Differentiating n along the motion in both bodies
and the equation of meshing n . v12 = 0 gives (derivation in the module notes of the tests)

    S x = b,    b . x = d0,    S = K1 + K2,    b = P (n x w12 - K2 v12),
    d0 = -[(w2 x n) . v12 - v12 . K2 v12 + n . (w1' x (r - O1) - w2' x (r - O2)) + n . (w12 x (w1 x (r - O1)))],

(P the tangent-plane projector, w' the angular accelerations).  Two uses:

* **Generation** (line contact, body 1 = work, body 2 = head cutter on the cradle): x is free along a
  line, so S is of rank one, S = b b^T / d0, and the generated curvature is K_w = b b^T / d0 - K_t.
* **Local synthesis** (point contact, body 1 = pinion, body 2 = gear): the path direction e on the gear
  (x + v12 = s e) and the TE curvature m21 (w2' = -m21 z2) fix s = (d0 + b . v12) / (b . e) and two
  components of S (S e = b / s); the ellipse major axis 2a for the elastic approach delta fixes the
  third: the smaller eigenvalue of S is 8 delta / (2a)^2 (gap = x^T S x / 2).  Then K1 = S - K2.

The pinion machine settings follow by solving K_w(settings) = K1 at M0 (three equations) with the blade
through M0 along its normal (blade angle, Sr, q) and the equation of meshing (ratio of roll).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .blank import BevelBlank
from .cutter import HeadCutter
from .generation import MeshingError, _guess, solve_axial_points, surface_state
from .machine import FlankCut, MachineSettings, MemberCut, roll
from .surface_state import cross3, norm1d
from .tca import RAD_PER_ARCSEC, drive_sign, mesh_frames

__all__ = ["FlankTarget", "MeanContact", "second_order", "generated_curvature", "mean_contact",
           "path_tangent", "pinion_curvature", "local_synthesis", "synthesis_at", "te_curvature"]


@dataclass(frozen=True)
class FlankTarget:
    """Design targets of one flank pair (Cao et al. 2008).

    Parameters
    ----------
    eta2 : float
        Path angle on the gear flank at M0, rad, measured in the gear axial section from the root-cone
        line (towards the heel) to the path tangent, positive towards the tooth top; |eta2| < 80 deg.
    te_magnitude : float
        Parabolic TE at the transfer points phi1 = +-pi/z1, rad of the gear, > 0.
    major_axis : float
        Contact-ellipse major axis 2a at M0, mm, > 0.
    delta : float
        Elastic approach of the ellipse, mm (Litvin: 0.00632).
    """

    eta2: float
    te_magnitude: float
    major_axis: float
    delta: float = 0.00632

    def __post_init__(self) -> None:
        if not abs(self.eta2) < np.deg2rad(80.0):
            raise ValueError(f"eta2 = {self.eta2!r} is outside the allowed range (-80, 80) deg")
        if not (np.isfinite(self.te_magnitude) and 0.0 < self.te_magnitude < 1000 * RAD_PER_ARCSEC):
            raise ValueError(f"te_magnitude = {self.te_magnitude!r} is outside the allowed range (0, 1000] arcsec")
        if not (np.isfinite(self.major_axis) and self.major_axis > 0):
            raise ValueError(f"major_axis = {self.major_axis!r} is outside the allowed range (0, inf) mm")
        if not self.delta > 0:
            raise ValueError(f"delta = {self.delta!r} is outside the allowed range (0, inf) mm")


def te_curvature(te_magnitude: float, z1: int) -> float:
    """m21 = d^2 TE / d phi1^2 (rad/rad^2, driven sense, < 0) of the parabola of magnitude
    ``te_magnitude`` (rad) at phi1 = +-pi/z1: TE = (m21 / 2) phi1^2 (Cao et al. 2008, Eq. 2)."""
    return -2.0 * te_magnitude / (np.pi / z1) ** 2


def second_order(r, n, K2, w1, O1, w2, O2, dw1=None, dw2=None) -> tuple[np.ndarray, float, np.ndarray]:
    """Coefficients (b, d0, v12) of the second-order contact relations (module docstring); all (3,)."""
    dw1 = np.zeros(3) if dw1 is None else dw1
    dw2 = np.zeros(3) if dw2 is None else dw2
    w12 = w1 - w2
    a1, a2 = r - O1, r - O2
    w1a1 = cross3(w1, a1)
    v12 = w1a1 - cross3(w2, a2)
    P = np.eye(3) - np.outer(n, n)
    b = P @ (cross3(n, w12) - K2 @ v12)
    d0 = -(cross3(w2, n) @ v12 - v12 @ K2 @ v12 + n @ (cross3(dw1, a1) - cross3(dw2, a2))
           + n @ cross3(w12, w1a1))
    return b, float(d0), v12


def _cutter_tensor(cutter: HeadCutter, u: float, ang: float) -> np.ndarray:
    """Blade curvature tensor (own outward normal) in the machine frame at angle ``ang`` about z_m."""
    p = cutter.profile(np.array(u))
    e = np.array([-np.sin(ang), np.cos(ang), 0.0])
    if u >= 0.0:                                   # straight blade: cone, zero curvature along the profile
        return float(-p.n_rho / p.rho) * np.outer(e, e)
    t = np.array([p.d_rho * np.cos(ang), p.d_rho * np.sin(ang), p.d_z])
    return float(-p.n_rho / p.rho) * np.outer(e, e) + np.outer(t, t) / cutter.edge_radius


def _generated_machine(fc: FlankCut, u: float, theta: float, psi: float) -> tuple[np.ndarray, float]:
    """Curvature tensor of the generated work surface in the machine frame, and the roll angle."""
    ms = fc.machine
    if not ms.is_basic or fc.cutter.general:
        raise ValueError("generated_curvature: the second-order relations here are those of the basic cradle "
                         "with a straight blade; allowed: no tilt, swivel, motions or roll terms above D, not "
                         "formate, a straight blade without toprem or flankrem")
    st = surface_state(fc, np.array([u]), np.array([theta]), np.array([psi]), with_work=False)
    phi, dphi = roll(ms, np.array(psi))
    ddphi = ms.ratio_of_roll * (-2.0 * ms.modified_roll_c - 6.0 * ms.modified_roll_d * psi)
    Kt = _cutter_tensor(fc.cutter, u, theta + psi)
    k = ms.work_axis
    b, d0, _ = second_order(st.r_m[0], st.n_m[0], Kt, dphi * k, ms.work_origin, np.array([0.0, 0.0, 1.0]),
                            np.zeros(3), dw1=ddphi * k)
    return np.outer(b, b) / d0 - Kt, float(phi)


def generated_curvature(fc: FlankCut, q: np.ndarray) -> np.ndarray:
    """Curvature tensors (n, 3, 3) of the generated surface in the work body frame at parameters
    q (n, 3) = (u, theta, psi), analytic (rank-one relation, module docstring)."""
    q = np.atleast_2d(q)
    B = fc.machine.work_basis
    out = np.empty((len(q), 3, 3))
    for i, (u, th, psi) in enumerate(q):
        K, phi = _generated_machine(fc, u, th, psi)
        c, s = np.cos(phi), np.sin(phi)
        R = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]) @ B.T       # machine -> work body
        out[i] = R @ K @ R.T
    return out


@dataclass(frozen=True)
class MeanContact:
    """The mean contact point M0 (gear mean pitch point on the pitch line, phi1 = 0).

    r_h, n_h : point and gear outward normal in the mesh frame;  phi2 : gear angle;  K2_h : gear curvature
    tensor in the mesh frame;  r1, n1 : point and pinion outward normal in the pinion body frame;
    r2, n2 : in the gear body frame;  w1, w2, O1, O2 : angular velocities (per unit pinion rate) and origins.
    """

    r_h: np.ndarray
    n_h: np.ndarray
    phi2: float
    K2_h: np.ndarray
    r1: np.ndarray
    n1: np.ndarray
    r2: np.ndarray
    n2: np.ndarray
    B1: np.ndarray
    B2: np.ndarray
    w1: np.ndarray
    w2: np.ndarray
    O1: np.ndarray
    O2: np.ndarray


def _rz(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def mean_contact(blank: BevelBlank, gear_fc: FlankCut) -> MeanContact:
    """M0 on the gear flank cut by ``gear_fc``, turned onto the pitch line (where v12 = 0)."""
    g = blank.gear.pitch_angle
    Am = blank.mean_cone_distance
    Z, rho = np.array([Am * np.cos(g)]), np.array([Am * np.sin(g)])
    x, ok = solve_axial_points(gear_fc, Z, rho, _guess(gear_fc, Z[0], rho[0])[None])
    if not ok[0]:
        raise MeshingError("no solution of the equation of meshing at the gear mean point")
    st = surface_state(gear_fc, x[:, 0], x[:, 1], x[:, 2])
    phi2 = -float(np.arctan2(st.r_w[0, 1], st.r_w[0, 0]))
    B1, O1, B2, O2 = mesh_frames(blank)
    R2 = B2 @ _rz(phi2)
    r_h, n_h = R2 @ st.r_w[0] + O2, R2 @ st.n_w[0]
    K2_h = R2 @ generated_curvature(gear_fc, x)[0] @ R2.T
    w1 = B1[:, 2]
    w2 = -(blank.pinion.z / blank.gear.z) * B2[:, 2]
    return MeanContact(r_h, n_h, phi2, K2_h, B1.T @ (r_h - O1), -B1.T @ n_h, st.r_w[0], st.n_w[0],
                       B1, B2, w1, w2, O1, O2)


def path_tangent(blank: BevelBlank, r2: np.ndarray, n2: np.ndarray, eta2: float) -> np.ndarray:
    """Unit tangent (gear body frame) of the surface direction whose image in the gear axial section
    makes the angle ``eta2`` with the root-cone line (module docstring of :class:`FlankTarget`)."""
    g, dd = blank.gear.pitch_angle, blank.gear.dedendum_angle
    e_rho = np.array([r2[0], r2[1], 0.0]) / np.hypot(r2[0], r2[1])
    e_z = np.array([0.0, 0.0, 1.0])
    e_th = cross3(e_z, e_rho)
    a = dd + eta2                                       # angle from the pitch generatrix (L axis)
    dL, dRn = np.cos(a), np.sin(a)
    dZ, drho = dL * np.cos(g) - dRn * np.sin(g), dL * np.sin(g) + dRn * np.cos(g)
    d = dZ * e_z + drho * e_rho
    e = d - (d @ n2) / (e_th @ n2) * e_th
    return e / norm1d(e)


def pinion_curvature(blank: BevelBlank, mc: MeanContact, target: FlankTarget) -> tuple[np.ndarray, dict]:
    """Pinion curvature tensor at M0 in the pinion body frame from (eta2, m21, 2a), and diagnostics."""
    n = -mc.n_h                                          # pinion outward normal
    e = mc.B2 @ _rz(mc.phi2) @ path_tangent(blank, mc.r2, mc.n2, target.eta2)
    m21 = te_curvature(target.te_magnitude, blank.pinion.z)
    dw2 = -drive_sign(mc.r2, mc.n2) * m21 * mc.B2[:, 2]        # m21 in the driven sense (tca.drive_sign)
    b, d0, v12 = second_order(mc.r_h, n, mc.K2_h, mc.w1, mc.O1, mc.w2, mc.O2, dw2=dw2)
    be = b @ e
    if abs(be) < 1e-12 * norm1d(b):
        raise ValueError(f"eta2 = {target.eta2!r}: this path direction is singular (b . e = 0)")
    s = (d0 + b @ v12) / be
    f = cross3(n, e)
    See, Sef = be / s, (b @ f) / s
    lam = 8.0 * target.delta / target.major_axis ** 2
    if See <= lam:
        raise ValueError(f"major_axis = {target.major_axis!r}: too short for eta2 and m21 (the relative "
                         f"curvature along the path is {See:.3e} 1/mm <= {lam:.3e}); allowed: > "
                         f"{2 * np.sqrt(2 * target.delta / max(See, 1e-300)):.3f} mm")
    Sff = lam + Sef ** 2 / (See - lam)
    S = See * np.outer(e, e) + Sef * (np.outer(e, f) + np.outer(f, e)) + Sff * np.outer(f, f)
    K1_h = S - mc.K2_h
    return mc.B1.T @ K1_h @ mc.B1, dict(m21=m21, s=s, path_speed=abs(s), S=S, e=e, lam_min=lam)


def _placement(P_w, n_w, K_w, gm, sg, rp, XG, XB, Em, C, D, edge_radius):
    """Settings putting the blade through P_w along n_w at psi = 0; returns (FlankCut, u, theta, residual).

    The residual is the generated minus the wanted curvature tensor K_w (pinion body frame): three
    tangent-plane components, 1/mm."""
    ms0 = MachineSettings(1.0, 0.0, gm, XG, Em, XB)
    B, O = ms0.work_basis, ms0.work_origin
    P, n, K_goal = O + B @ P_w, B @ n_w, B @ K_w @ B.T
    alpha = float(np.arcsin(np.clip(-n[2], -1.0, 1.0)))
    e_rho = -n[:2] / (sg * np.cos(alpha))
    e_rho /= norm1d(e_rho)
    depth = -P[2]
    rho = rp + sg * depth * np.tan(alpha)
    c = P[:2] - rho * e_rho
    k = ms0.work_axis
    ma = float(n @ cross3((0.0, 0.0, 1.0), P) / (n @ cross3(k, P - O)))
    if not (0.0 <= alpha <= np.deg2rad(45.0)) or ma <= 0 or rp <= 0:
        raise ValueError(f"no admissible blade through M0 (blade angle {np.rad2deg(alpha):.2f} deg, "
                         f"ratio of roll {ma:.4f}, point radius {rp:.3f} mm)")
    ms = MachineSettings(float(np.hypot(*c)), float(np.arctan2(c[1], c[0])), gm, XG, Em, XB, ma, C, D)
    cu = HeadCutter(float(rp), alpha, "outside" if sg > 0 else "inside", edge_radius)
    u = float(cu.u_at_depth(depth))
    pc = P[:2] - c
    th = float(np.arctan2(pc[1], pc[0]))
    fc = FlankCut(ms, cu)
    K, _ = _generated_machine(fc, u, th, 0.0)
    e1 = cross3(n, (0.0, 1.0, 0.0))
    e1 /= norm1d(e1)
    e2 = cross3(n, e1)
    dK = K - K_goal
    return fc, u, th, np.array([e1 @ dK @ e1, e1 @ dK @ e2, e2 @ dK @ e2])


def local_synthesis(blank: BevelBlank, gear: MemberCut, pinion_side: str, target: FlankTarget,
                    blank_offset: float | None = None, modified_roll: tuple[float, float] = (0.0, 0.0),
                    edge_radius: float | None = None, guess: FlankCut | None = None, tol: float = 1e-12
                    ) -> tuple[FlankCut, dict]:
    """Pinion flank settings from the local synthesis at M0 (Litvin's method, module docstring).

    Parameters
    ----------
    blank : BevelBlank
    gear : MemberCut
        The given gear settings (both flanks).
    pinion_side : ``"concave"`` (meets the gear convex) or ``"convex"``.
    target : FlankTarget
    blank_offset : float or None
        None: the unknowns are the cutter point radius, XG1 and Em1 (C as given).  A number (mm): Em1 is
        fixed (blank-offset redesign, Cao et al. 2008 sec. 3.1) and the unknowns are the point radius, XG1 and the
        modified-roll coefficient C (``modified_roll[0]`` is then only the start).  Either way the whole
        pinion curvature tensor K1 is met (eta2, m21 and the ellipse axis), and the sliding base keeps the
        blade tip plane through the pinion apex on the root line (XB1 = -XG1 sin gamma_m1): a shift along
        the cradle axis is otherwise equivalent to a change of point radius.  (Fixing Em1 and solving for
        point radius and XG1 alone leaves a nearly singular system on the test pairs: condition 1e8.)
    modified_roll : (C, D)
        Modified-roll coefficients (1/rad, 1/rad^2); C enters the second order at M0, D does not.
    edge_radius : float, optional
        Blade edge radius, mm (default 0.2 module).
    guess : FlankCut, optional
        Start of the Newton iteration (point radius, XG1, Em1), e.g. a neighbouring design.

    Returns
    -------
    FlankCut, dict
        Settings (machine root angle = pinion root angle; cutter point radius, blade angle, Sr1, q1,
        XG1, Em1, XB1 and ratio of roll from the synthesis) and diagnostics (K1, m21, residual, iterations).
    """
    if pinion_side not in ("concave", "convex"):
        raise ValueError(f"pinion_side = {pinion_side!r}: allowed 'concave' or 'convex'")
    gear_side = "convex" if pinion_side == "concave" else "concave"
    mc = mean_contact(blank, gear.flank(gear_side))
    return synthesis_at(blank, mc, pinion_side, target, blank_offset, modified_roll, edge_radius, guess, tol)


def synthesis_at(blank: BevelBlank, mc: MeanContact, pinion_side: str, target: FlankTarget,
                 blank_offset: float | None, modified_roll: tuple[float, float], edge_radius: float | None,
                 guess: FlankCut | None, tol: float) -> tuple[FlankCut, dict]:
    """:func:`local_synthesis` at a mean contact point ``mc`` of the gear flank found before
    (:func:`mean_contact`; a design loop finds it once for all its steps). ``pinion_side`` is not checked here."""
    K1, info = pinion_curvature(blank, mc, target)
    sg = 1.0 if pinion_side == "concave" else -1.0
    gm = blank.pinion.root_angle
    rf = 0.2 * blank.data.module if edge_radius is None else edge_radius
    C, D = modified_roll
    half = 0.5 * (blank.mean_normal_pitch - blank.gear.mean_normal_thickness)
    fixed = blank_offset is not None
    if guess is None:
        x = np.array([blank.data.cutter_radius - sg * half, 0.0, C if fixed else 0.0])
    else:
        x = np.array([guess.cutter.point_radius, guess.machine.center_to_back,
                      guess.machine.modified_roll_c if fixed else guess.machine.blank_offset])

    def F(x):
        Em, c = (blank_offset, x[2]) if fixed else (x[2], C)
        return _placement(mc.r1, mc.n1, K1, gm, sg, x[0], x[1], -x[1] * np.sin(gm), Em, c, D, rf)

    scale = blank.mean_cone_distance
    hx = np.array([1e-5, 1e-5, 1e-7 if fixed else 1e-5])
    it = 0
    for it in range(1, 60):
        r = F(x)[3] * scale
        if np.max(np.abs(r)) < tol * scale:
            break
        J = np.empty((len(r), len(x)))
        for j in range(len(x)):
            xp = x.copy()
            xp[j] += hx[j]
            J[:, j] = (F(xp)[3] * scale - r) / hx[j]
        dx = np.linalg.solve(J, -r)
        cap = np.array([20.0, 20.0, 0.05 if fixed else 20.0])
        x = x + dx * min(1.0, 1.0 / max(np.max(np.abs(dx) / cap), 1e-300))
    fc, u, th, res = F(x)
    if np.max(np.abs(res)) > 1e-8:
        raise MeshingError(f"local synthesis of the {pinion_side} flank did not converge (curvature "
                           f"residual {np.max(np.abs(res)):.2e} 1/mm); check eta2, te_magnitude and major_axis")
    info.update(K1=K1, mean_contact=mc, params=np.array([u, th, 0.0]), iterations=it,
                residual=float(np.max(np.abs(res))))
    return fc, info
