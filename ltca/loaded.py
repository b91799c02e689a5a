"""Loaded tooth contact analysis of cylindrical pairs: compliance once, contact per mesh position.

At each position the contact cells are narrow strips on the pinion's driving flank, one per face
slice and tooth, centred on the unloaded contact line and a few Hertz half-widths wide. Their gaps
come from the separation field (both members' micro-geometry and errors included), their compliance
from the two bodies' FE grids (bilinear interpolation) plus the half-space near field, and the
complementarity problem with torque balance gives the cell forces and the loaded rotation.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from fem.compliance import BodyCompliance, ComplianceSpec, body_compliance
from fem.contact import ContactNotConverged, solve_contact
from geometry.cylindrical import arc_length, flank_point_normal

from .errors import ConvergenceError
from .model import PairModel
from .tca import ARCSEC_PER_RAD, first_contact, flank_gaps, unloaded_tca

__all__ = ["Fidelity", "LoadedModel", "PositionResult", "prepare", "solve_position", "hertz_line", "weights_of",
           "te_arcsec"]


@dataclass(frozen=True)
class Fidelity:
    """The knobs of one analysis (lengths in mm)."""
    h_flank: float          # FE element size at the flanks
    h_body: float           # FE element size far from the teeth
    grid: tuple[int, int]   # compliance grid per loaded flank (profile, face)
    cells_per_b: float      # contact cells per nominal Hertz half-width (profile direction)
    slices: int             # contact cells along the face
    near_field: bool        # half-space near-field correction on/off
    depth: float            # read depth d of the FE regular part (and 2d), mm; default 0.75 h_flank
    window: float = 3.0     # strip half-width in nominal Hertz half-widths

    @staticmethod
    def from_preset(params: dict, module: float, **override) -> "Fidelity":
        p = dict(params)
        p.update({k: v for k, v in override.items() if v is not None})
        h = p["h_flank"] * module
        return Fidelity(h_flank=h, h_body=p["h_body"] * module, grid=tuple(p["grid"]),
                        cells_per_b=p["cells_per_b"], slices=p["slices"], near_field=p["near_field"],
                        depth=p.get("depth", 0.75 * h) if p["near_field"] else 0.0, window=p.get("window", 2.0))


def hertz_line(w: float, R: float, E: float, nu: float) -> tuple[float, float]:
    """Hertz line contact of two equal materials: half-width b (mm) and peak p0 (MPa) for load w (N/mm).

    b = sqrt(4 w R / (pi E*)), p0 = 2 w / (pi b), 1/E* = 2 (1 - nu^2)/E (Johnson, Contact Mechanics, 4.2).
    """
    Es = E / (2 * (1 - nu ** 2))
    b = np.sqrt(4 * w * R / (np.pi * Es))
    return float(b), float(2 * w / (np.pi * b))


@dataclass
class LoadedModel:
    """The pair with both bodies' compliance, ready for any number of positions and torques."""
    model: PairModel
    fid: Fidelity
    teeth1: tuple[int, ...]
    teeth2: tuple[int, ...]
    body1: BodyCompliance
    body2: BodyCompliance
    b_nom: float              # Hertz half-width of the nominal line load at torque_nom, mm
    R_nom: float
    torque_nom: float         # N mm
    timings: dict = field(default_factory=dict)

    def half_width(self, torque: float) -> float:
        """Nominal Hertz half-width at another torque: b grows as sqrt(load) (Johnson 4.2)."""
        return self.b_nom * np.sqrt(torque / self.torque_nom)


def _teeth_in_mesh(model: PairModel, rolls: np.ndarray, cap: float):
    tca = unloaded_tca(model, rolls, teeth=range(-3, 4), ns=120, nz=5)
    near = np.isfinite(tca.min_gap) & (tca.min_gap < cap)
    teeth1 = tuple(int(k) for k in tca.teeth[near.any(axis=0)])
    s_lo = arc_length(model.pinion_range()[0], model.pinion.r_base)
    s_hi = arc_length(model.pinion_range()[1], model.pinion.r_base)
    g2 = set()
    for roll in rolls[:: max(1, len(rolls) // 8)].tolist() + [rolls[-1]]:
        for k in teeth1:
            fg = flank_gaps(model, model.phi_pitch - roll, k, np.linspace(s_lo, s_hi, 60), 0.0)
            g2.update(int(t) for t in np.unique(fg.gear_tooth[np.isfinite(fg.gap) & (fg.gap < 2 * cap)]))
    return tca, teeth1, tuple(sorted(g2))


def prepare(model: PairModel, fid: Fidelity, rolls: np.ndarray, torque: float, cache_dir=None,
            progress=None) -> LoadedModel:
    """Choose the teeth in mesh over ``rolls`` and compute both bodies' compliance (the costly step)."""
    say = progress or (lambda m: None)
    case = model.case
    t0 = time.perf_counter()
    p1, p2 = model.pinion, model.gear
    b = model.face_width
    w_nom = torque / (p1.r_base * b)
    rho1 = p1.r_base * np.tan(model.pair.alpha_w)
    rho2 = p2.r_base * np.tan(model.pair.alpha_w)
    R_nom = 1.0 / (1 / rho1 - 1 / rho2) if p2.internal else 1.0 / (1 / rho1 + 1 / rho2)
    R_nom /= np.cos(p1.beta_b)
    b_nom, _ = hertz_line(w_nom * np.cos(p1.beta_b), R_nom, case.young, case.poisson)
    # gaps below the expected deflection (ISO c' ~ 14 N/(mm um)) with a margin can close under load
    cap = 3.0 * w_nom / 14.0e3 + 0.01
    _, teeth1, teeth2 = _teeth_in_mesh(model, rolls, cap)
    say(f"teeth in mesh: pinion {list(teeth1)}, gear {list(teeth2)}; modelled with one neighbour each side")
    timings = {"tca": time.perf_counter() - t0}

    def spec(teeth, side, r_range, r_bore):
        return ComplianceSpec(teeth=tuple(range(min(teeth) - 1, max(teeth) + 2)), loaded=teeth, side=side,
                              r_range=r_range, grid=fid.grid, face_width=b, r_bore=r_bore, h_flank=fid.h_flank,
                              h_body=fid.h_body, depth=fid.depth, young=case.young, poisson=case.poisson)
    body1 = body_compliance(p1, spec(teeth1, +1, model.pinion_range(), model.r_bore1), cache_dir, say)
    body2 = body_compliance(p2, spec(teeth2, model.gear_side, model.gear_range(), model.r_bore2), cache_dir, say)
    for name in ("mesh", "assembly", "factorisation", "setup", "solves"):
        timings[name] = body1.timings.get(name, 0) + body2.timings.get(name, 0)
    return LoadedModel(model, fid, teeth1, teeth2, body1, body2, b_nom, R_nom, torque, timings)


@dataclass(frozen=True)
class PositionResult:
    """Loaded contact at one mesh position (forces N, lengths mm, pressure MPa, angles rad)."""
    roll: float
    theta: float              # loaded pinion rotation beyond the kinematic position, rad
    theta0: float             # unloaded (rigid) part, rad
    tooth: np.ndarray         # (n,) pinion tooth of each cell
    lattice: np.ndarray       # (n,) profile lattice index of each cell (arc length step from the form circle)
    slice: np.ndarray         # (n,) face slice of each cell
    s: np.ndarray             # (n,) arc length on the pinion flank
    z: np.ndarray             # (n,) axial position
    area: np.ndarray          # (n,) mm^2
    force: np.ndarray         # (n,) N
    pressure: np.ndarray      # (n,) MPa
    gap0: np.ndarray          # (n,) unloaded gap, mm
    gear_tooth: np.ndarray    # (n,) gear tooth touched by each cell
    gear_s: np.ndarray        # (n,) arc length on the gear flank, mm
    gear_z: np.ndarray        # (n,) axial position on the gear, mm
    pair_load: dict           # pinion tooth -> normal force, N
    root1: dict               # pinion tooth -> max principal fillet stress, MPa
    root2: dict               # gear tooth -> max principal fillet stress, MPa
    torque_residual: float    # |sum F h1 - T| / T
    torque_ratio: float       # gear torque / pinion torque
    iterations: int
    residual: float
    active: np.ndarray
    ds: float                 # profile size of the contact cells (lattice step), mm

    @property
    def max_pressure(self) -> float:
        return float(self.pressure.max()) if self.pressure.size else 0.0


def _principal_max(sig: np.ndarray) -> np.ndarray:
    """Largest principal stress of Voigt stresses (..., 6) ordered xx, yy, zz, yz, xz, xy."""
    T = np.stack([np.stack([sig[..., 0], sig[..., 5], sig[..., 4]], -1),
                  np.stack([sig[..., 5], sig[..., 1], sig[..., 3]], -1),
                  np.stack([sig[..., 4], sig[..., 3], sig[..., 2]], -1)], -2)
    return np.linalg.eigvalsh(T)[..., -1]


def _tangents(p1, s: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Flank tangents dP/ds, dP/dz (n, 3) of the pinion drive flank, by differences (the flank is exact)."""
    eps = 1e-4
    s, z = np.broadcast_arrays(np.atleast_1d(np.asarray(s, float)), np.atleast_1d(np.asarray(z, float)))
    ra = np.sqrt(p1.r_base ** 2 + 2 * p1.r_base * (s + eps))
    Pa, _ = flank_point_normal(p1, +1, ra, z, tooth=0)
    Pb, _ = flank_point_normal(p1, +1, np.sqrt(p1.r_base ** 2 + 2 * p1.r_base * (s - eps)), z, tooth=0)
    Pz1, _ = flank_point_normal(p1, +1, ra, z + eps, tooth=0)
    return (Pa - Pb) / (2 * eps), (Pz1 - Pa) / eps


def _cells(lm: LoadedModel, phi1: float, theta_guess: float, widen: dict, torque: float, cycle: int = 0):
    """Contact strips of all teeth at a position, on a lattice of the pinion flank that follows the line.

    Per tooth the unloaded contact line s = q + t z is fitted (t = 0 on a spur flank, the slope of the
    inclined line on a helical one). The lattice has rectangular cells aligned with that line: step
    ``dz`` along it (one slice per face step) and step ``ds`` across it, so the near-field term depends on
    integer offsets only (tabulated), and a helical contact band is covered by cells along it instead of
    a staircase of face-long rectangles.

    Returns strips [(tooth, slice, lattice indices, s, z, open below, open above)], dz, ds and the lattice
    of each tooth {tooth: (t, step_s, step_z)}: one step across the line in (s, z)."""
    model, fid = lm.model, lm.fid
    p1 = model.pinion
    rb = p1.r_base
    s_lo, s_hi = (arc_length(r, rb) for r in model.pinion_range())
    b = model.face_width
    dz = b / fid.slices
    zc = -0.5 * b + dz * (np.arange(fid.slices) + 0.5)
    s_scan = np.linspace(s_lo, s_hi, 400)
    S, Z = np.meshgrid(s_scan, zc, indexing="ij")
    ds = lm.half_width(torque) / fid.cells_per_b
    out, lattice = [], {}
    for k in lm.teeth1:
        fg = flank_gaps(model, phi1, k, S, Z, cycle=cycle)
        g = np.where(np.isfinite(fg.gap) & (fg.lever1 > 0), fg.gap - fg.lever1 * theta_guess, np.inf)
        if not np.isfinite(g).any() or g.min() > 0.02 + 0.5 * abs(theta_guess) * rb:
            continue
        has = np.isfinite(g).any(axis=0)
        s_min = s_scan[np.argmin(g, axis=0)]
        inner = has & (s_min > s_scan[0]) & (s_min < s_scan[-1])   # the line itself, not a flank border
        t = float(np.polyfit(zc[inner], s_min[inner], 1)[0]) if inner.sum() >= 3 else 0.0
        t = 0.0 if abs(t) * b < 1e-9 else t
        # one step across the line, perpendicular to it on the flank, of 3D length ds
        Ps, Pz = _tangents(p1, np.median(s_min[has]), 0.0)
        L = Pz[0] + t * Ps[0]
        mu = float(Ps[0] @ L / (L @ L))
        A = (1 - mu * t) * Ps[0] - mu * Pz[0]
        step_s, step_z = ds * (1 - mu * t) / np.linalg.norm(A), -ds * mu / np.linalg.norm(A)
        dq = step_s - t * step_z                      # the across coordinate q = s - t z per step
        lattice[int(k)] = (t, step_s, step_z)
        for j in range(fid.slices):
            if not has[j]:
                continue
            s0 = s_lo + t * zc[j]                     # cell i of slice j: (s0, zc) + (i + 1/2) step
            lo_i = int(np.ceil((s_lo - s0) / step_s - 0.5 - 1e-9))
            hi_i = int(np.floor((s_hi - s0) / step_s - 0.5 + 1e-9)) + 1
            ic = int(round((s_min[j] - t * zc[j] - s_lo) / dq - 0.5))
            nw = int(np.ceil(fid.window * fid.cells_per_b * widen.get((k, j), 1.0)))
            i0, i1 = max(lo_i, ic - nw), min(hi_i, ic + nw + 1)
            if i1 <= i0:
                continue
            idx = np.arange(i0, i1)
            zz = np.clip(zc[j] + (idx + 0.5) * step_z, -0.5 * b, 0.5 * b)
            out.append((k, j, idx, s0 + (idx + 0.5) * step_s, zz, i0 > lo_i, i1 < hi_i))
    return out, dz, ds, lattice


def _near_field_block(I, J, Vs, Vz, E, nu):
    """Half-space surface compliance of both bodies between one tooth's cells on the lattice, (n, n), mm/N.

    Cells (I, J) are lattice indices; one lattice step is the 3D vector Vs (profile) or Vz (face). The
    bodies' FE parts have their own half-space response removed (:mod:`fem.compliance`), so this is
    the whole local term; it is tabulated over integer lattice offsets."""
    from fem.halfspace import surface_influence
    e1 = Vs / np.linalg.norm(Vs)
    nrm = np.cross(Vs, Vz)
    area = np.linalg.norm(nrm)
    e2 = np.cross(nrm / area, e1)
    a = 0.5 * np.linalg.norm(Vs)
    bh = area / (4 * a)
    di = np.arange(I.min() - I.max(), I.max() - I.min() + 1)
    dj = np.arange(J.min() - J.max(), J.max() - J.min() + 1)
    DI, DJ = np.meshgrid(di, dj, indexing="ij")
    X = DI * (Vs @ e1) + DJ * (Vz @ e1)
    Y = DI * (Vs @ e2) + DJ * (Vz @ e2)
    table = 2.0 * surface_influence(X, Y, a, bh, E, nu)
    return table[I[:, None] - I[None, :] - di[0], J[:, None] - J[None, :] - dj[0]]


@dataclass(frozen=True)
class _System:
    """The contact problem of one position: cells, their unloaded gaps, levers, areas and compliance."""
    tooth: np.ndarray
    slice: np.ndarray
    lattice: np.ndarray
    s: np.ndarray
    z: np.ndarray
    gap0: np.ndarray
    lever1: np.ndarray
    lever2: np.ndarray
    gear_tooth: np.ndarray
    gear_s: np.ndarray
    gear_z: np.ndarray
    area: np.ndarray
    C: np.ndarray
    W1: object
    W2: object


def _system(lm: LoadedModel, phi1: float, strips, dz: float, ds: float, cycle: int, lattice: dict) -> _System:
    """Gaps (separation field + micro-geometry), compliance (FE far field of both bodies, bilinearly
    interpolated, plus the half-space near field) and cell areas of the strips of one position."""
    model, fid = lm.model, lm.fid
    p1 = model.pinion
    tooth = np.concatenate([np.full(len(x), k) for k, _, x, *_ in strips])
    sl = np.concatenate([np.full(len(x), j) for _, j, x, *_ in strips])
    lat = np.concatenate([x[2] for x in strips])
    s = np.concatenate([x[3] for x in strips])
    z = np.concatenate([x[4] for x in strips])
    n = len(s)
    g0, h1, h2 = np.empty(n), np.empty(n), np.empty(n)
    gt, gs, gz = np.empty(n, int), np.empty(n), np.empty(n)
    P = np.empty((n, 3))
    for k in np.unique(tooth):
        m = tooth == k
        fg = flank_gaps(model, phi1, int(k), s[m], z[m], cycle=cycle)
        g0[m], h1[m], h2[m] = fg.gap, fg.lever1, fg.lever2
        gt[m], gs[m], gz[m], P[m] = fg.gear_tooth, fg.gear_s, fg.gear_z, fg.points
    # cell geometry: lattice steps across (Vs) and along (Vz) the line from the local flank tangents
    Ps, Pz = _tangents(p1, s, z)
    keys = np.array(sorted(lattice))
    t, st_s, st_z = np.array([lattice[k] for k in keys])[np.searchsorted(keys, tooth)].T
    Vs = st_s[:, None] * Ps + st_z[:, None] * Pz
    Vz = (Pz + t[:, None] * Ps) * dz
    area = np.linalg.norm(np.cross(Vs, Vz), axis=1)
    W1 = lm.body1.weights(tooth, s, z)
    W2 = lm.body2.weights(gt, gs, gz)
    C = np.asarray(W1 @ (W1 @ lm.body1.C).T) + np.asarray(W2 @ (W2 @ lm.body2.C).T)
    if fid.near_field:
        E, nu = model.case.young, model.case.poisson
        for k in np.unique(tooth):
            m = np.flatnonzero(tooth == k)
            c = m[len(m) // 2]
            C[np.ix_(m, m)] += _near_field_block(lat[m], sl[m], Vs[c], Vz[c], E, nu)
    else:   # the coarse FE alone is (nearly) singular at sub-element spacing: a trace of regularisation
        C[np.diag_indices(n)] += 1e-6 * np.mean(np.diag(C))
    return _System(tooth, sl, lat, s, z, g0, h1, h2, gt, gs, gz, area, 0.5 * (C + C.T), W1, W2)


def solve_position(lm: LoadedModel, roll: float, torque: float, warm: PositionResult | None = None,
                   max_widen: int = 3, cycle: int = 0) -> PositionResult:
    """Loaded contact at pinion roll angle ``roll`` (rad from the pitch point) under ``torque`` (N mm).

    ``roll`` lies within the mesh cycle around tooth 0; ``cycle`` (mesh cycles travelled) selects which
    physical teeth the modelled ones stand for, so that tooth errors follow the revolution. A strip
    whose outer cell carries load is widened and the position solved again (up to ``max_widen`` times).
    """
    model = lm.model
    phi1 = model.phi_pitch - roll
    rb1 = model.pinion.r_base
    theta_guess = warm.theta if warm is not None else torque / (rb1 ** 2 * 14.0e3 * model.face_width)
    widen: dict = {}
    for _ in range(max_widen + 1):
        strips, dz, ds, lattice = _cells(lm, phi1, theta_guess, widen, torque, cycle)
        if not strips:
            raise ConvergenceError("contact search", float("inf"), 0,
                                   "no tooth pair comes near contact: check the centre distance and the positions")
        sy = _system(lm, phi1, strips, dz, ds, cycle, lattice)
        ok = np.isfinite(sy.gap0) & (sy.lever1 > 0)
        active0 = ok & (sy.gap0 - sy.lever1 * theta_guess < 0)
        try:
            sol = solve_contact(sy.C, np.where(ok, sy.gap0, np.inf), np.where(ok, sy.lever1, 1.0), torque,
                                active0=active0 if active0.any() else None)
        except ContactNotConverged as exc:
            raise ConvergenceError(f"contact at roll {np.degrees(roll):.3f} deg", exc.residual, exc.iterations,
                                   exc.advice) from None
        F = sol.force
        theta_guess = sol.approach
        more, i0 = False, 0
        for k, j, _, sv, _, open_lo, open_hi in strips:
            f = F[i0:i0 + len(sv)]
            if (open_lo and f[0] > 1e-9 * torque / rb1) or (open_hi and f[-1] > 1e-9 * torque / rb1):
                widen[(k, j)] = widen.get((k, j), 1.0) * 1.7
                more = True
            i0 += len(sv)
        if not more:
            break
    T1, T2 = float(F @ sy.lever1), float(F @ sy.lever2)
    theta0 = float(first_contact(model, phi1, lm.teeth1, cycle=cycle))
    return PositionResult(
        float(roll + cycle * model.pitch_angle), float(sol.approach), theta0, sy.tooth, sy.lattice, sy.slice, sy.s,
        sy.z, sy.area, F, F / sy.area, sy.gap0, sy.gear_tooth, sy.gear_s, sy.gear_z,
        {int(k): float(F[sy.tooth == k].sum()) for k in lm.teeth1},
        _root(lm.body1, sy.W1.T @ F), _root(lm.body2, sy.W2.T @ F), abs(T1 - torque) / torque,
        T2 / T1 if T1 else np.nan, sol.iterations, sol.residual, sol.active, ds)


def _root(body: BodyCompliance, f: np.ndarray) -> dict:
    if body.root_stress.shape[0] == 0:
        return {}
    sig = np.einsum("mkn,n->mk", body.root_stress, f)
    smax = _principal_max(sig)
    return {int(k): float(smax[body.root_tooth == k].max()) for k in np.unique(body.root_tooth)}


def weights_of(lm: LoadedModel, res: PositionResult):
    """Interpolation weights of a position's cells on the pinion and gear compliance grids."""
    return lm.body1.weights(res.tooth, res.s, res.z), lm.body2.weights(res.gear_tooth, res.gear_s, res.gear_z)


def te_arcsec(lm: LoadedModel, theta: np.ndarray) -> np.ndarray:
    """Pinion rotation (rad) -> transmission error of the gear (arcsec, positive = lag)."""
    return np.asarray(theta) / lm.model.pair.ratio * ARCSEC_PER_RAD
