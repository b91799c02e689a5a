"""Loaded tooth contact analysis of cylindrical pairs: compliance once, contact per mesh position.

At each position the contact cells are narrow strips on the pinion's driving flank, one per face
slice and tooth, centred on the unloaded contact line and a few Hertz half-widths wide. Their gaps
come from the separation field (both members' micro-geometry and errors included), their compliance
from the two bodies' FE grids (bilinear interpolation) plus the half-space near field, and the
complementarity problem with torque balance gives the cell forces and the loaded rotation. The cells
and their contact problem are built in :mod:`ltca.contact_cells`.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from fem.compliance import BodyCompliance, ComplianceSpec, body_compliance
from fem.contact import ContactNotConverged, solve_contact
from geometry.cylindrical import arc_length

from .contact_cells import contact_strips, contact_system
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
        strips, dz, ds, lattice = contact_strips(lm, phi1, theta_guess, widen, torque, cycle)
        if not strips:
            raise ConvergenceError("contact search", float("inf"), 0,
                                   "no tooth pair comes near contact: check the centre distance and the positions")
        sy = contact_system(lm, phi1, strips, dz, ds, cycle, lattice)
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
