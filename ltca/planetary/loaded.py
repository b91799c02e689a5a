"""Loaded contact of the satellite in the central wheel: every pair that can close takes load.

Route (the smallest that is honest): the pair is a :class:`ltca.cylindrical.model.PairModel`
(:mod:`.model`), so the cylindrical chain's separation field, contact strips (a transverse profile
lattice times face slices per pair, :mod:`ltca.cylindrical.contact_cells`), half-space near field and
complementarity solve with torque balance (:func:`ltca.cylindrical.loaded.solve_position`,
:func:`ltca.fem.contact.solve_contact`) run unchanged. What is specific to this pair is done here:

* the teeth in mesh: every satellite tooth whose exact unloaded gap (:func:`ltca.geometry.satellite.unloaded_gaps`)
  at any analysed position is below ``3 w / c' + 10 um`` (w the line load of the largest torque on one
  pair, c' = 14 N/(mm um), the cylindrical chain's rule), instead of +-3 teeth around a pitch point that
  lies outside both gears; the wheel teeth they face;
* both bodies whole (:func:`ltca.fem.compliance.body_compliance`, :mod:`ltca.fem.solids.gear_body`): the satellite held
  at its bore (the eccentric bearing's seat), the wheel at its outer rim (the housing), the loaded teeth and
  a neighbour each side fine;
* the nominal Hertz radius at the actual contact (radius ``r1`` of the first contact, relative curvature of
  the nearly conformal internal involutes ``rho1 rho2 / (rho2 - rho1)``), not at the working pitch circle.

The reverse direction (negative torque, left satellite flanks) is the mirror image of the drive direction
about the line of centres: both tooth outlines are symmetric and both supports axisymmetric, so the
reverse contact at position phi is the drive contact at -phi with tooth labels negated. It is taken so,
not solved again; the exact unloaded gaps of both directions (computed independently by
:meth:`ltca.geometry.satellite.EccentricMesh.window`) confirm the symmetry (tests).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ltca.fem.compliance import ComplianceSpec, body_compliance
from ltca.geometry.cylindrical import arc_length

from ..cylindrical.loaded import solve_position
from ..cylindrical.loaded_model import Fidelity, LoadedModel, hertz_line
from ..cylindrical.tca import flank_gaps
from ..position_runs import solve_positions
from .model import SatelliteModel

__all__ = ["C_PRIME", "positions", "teeth_in_mesh", "prepare_satellite", "solve_cycle"]

C_PRIME = 14.0e3     # N/(mm mm): ISO 6336-1 single-pair stiffness order, only to bound the closable gap


def positions(sm: SatelliteModel, n: int) -> np.ndarray:
    """``n`` mesh positions phi (rad) over one satellite pitch, symmetric about 0 (so the mirror of the set
    is the set)."""
    p = 2 * np.pi / sm.mesh.z1
    return p * (np.arange(n) + 0.5) / n - 0.5 * p


def teeth_in_mesh(sm: SatelliteModel, phis: np.ndarray, cap_um: float):
    """Satellite teeth (labels) with an exact unloaded drive gap below ``cap_um`` at any position, and the
    wheel teeth their flanks face; also the gaps (UnloadedGaps over ``phis``)."""
    rb = sm.mesh.sat.r_base * 1e3
    g = np.stack([sm.mesh.window(float(p)).drive_gap for p in phis]) * rb
    near = (g <= cap_um).any(axis=0)
    labels = np.arange(sm.mesh.z1) - sm.mesh.z1 // 2
    t1 = labels[near]
    teeth1 = tuple(range(int(t1.min()), int(t1.max()) + 1))
    pm = sm.pair
    s_lo, s_hi = (arc_length(r, pm.pinion.r_base) for r in pm.pinion_range())
    t2 = set()
    for p in phis:
        theta0 = -sm.mesh.window(float(p)).drive          # rigid drive rotation to first contact
        for k in teeth1:
            fg = flank_gaps(pm, -float(p), k, np.linspace(s_lo, s_hi, 60), 0.0)
            g_k = fg.gap - fg.lever1 * theta0
            t2.update(int(t) for t in np.unique(fg.gear_tooth[np.isfinite(g_k) & (g_k < 2 * cap_um * 1e-3)]))
    return teeth1, tuple(range(min(t2), max(t2) + 1)), g


def prepare_satellite(sm: SatelliteModel, fid: Fidelity, phis: np.ndarray, torque_max: float,
                      far_teeth: str = "none", cache_dir=None, progress=None, keep_solver: bool = True) -> LoadedModel:
    """Teeth in mesh over ``phis`` for torques up to ``torque_max`` (N mm) and both bodies' compliance.

    Without ``keep_solver`` each body's factor is freed as soon as its compliance is known
    (:meth:`ltca.fem.compliance.BodyCompliance.without_solver`: no VTU can be written), so that the two factors
    never coexist: on the shipped pair the peak falls by the first body's factor (about 3.5 GB)."""
    say = progress or (lambda m: None)
    pm, case = sm.pair, sm.pair.case
    t0 = time.perf_counter()
    rb1, b = pm.pinion.r_base, pm.face_width
    w_max = torque_max / (rb1 * b)
    cap_um = 1e3 * (3.0 * w_max / C_PRIME + 0.01)
    teeth1, teeth2, _ = teeth_in_mesh(sm, phis, cap_um)
    say(f"teeth in mesh (gap < {cap_um:.0f} um): satellite {list(teeth1)}, wheel {list(teeth2)}")
    # nominal Hertz radius at the first contact of the middle position
    r1 = sm.mesh.window(0.0).drive_at["r1"]
    rho1 = np.sqrt(max(r1 ** 2 - rb1 ** 2, 1e-6))
    rho2 = rho1 + sm.mesh.e * np.sin(sm.mesh.alpha_w)
    R_nom = rho1 * rho2 / (rho2 - rho1)
    b_nom, _ = hertz_line(w_max, R_nom, case.young, case.poisson)
    timings = {"tca": time.perf_counter() - t0}

    def spec(teeth, side, r_range, r_support):
        return ComplianceSpec(teeth=tuple(range(min(teeth) - 1, max(teeth) + 2)), loaded=teeth, side=side,
                              r_range=r_range, grid=fid.grid, face_width=b, r_bore=r_support, h_flank=fid.h_flank,
                              h_body=fid.h_body, depth=fid.depth, young=case.young, poisson=case.poisson,
                              far_teeth=far_teeth, fillet=fid.fillet)
    lean = (lambda body: body) if keep_solver else (lambda body: body.without_solver())
    body1 = lean(body_compliance(pm.pinion, spec(teeth1, +1, pm.pinion_range(), pm.r_bore1), cache_dir, say))
    body2 = lean(body_compliance(pm.gear, spec(teeth2, pm.gear_side, pm.gear_range(), pm.r_bore2), cache_dir, say))
    for name in ("mesh", "assembly", "factorisation", "setup", "solves"):
        timings[name] = body1.timings.get(name, 0) + body2.timings.get(name, 0)
    return LoadedModel(pm, fid, teeth1, teeth2, body1, body2, b_nom, R_nom, torque_max, timings)


@dataclass(frozen=True)
class _Start:
    """A starting rotation for :func:`solve_position` (its warm start reads only ``theta``)."""
    theta: float


def solve_cycle(lm: LoadedModel, sm: SatelliteModel, phis: np.ndarray, torque: float, store=None, it: int = 0,
                lines: list | None = None, progress=None) -> list:
    """Drive-direction contact (:class:`ltca.cylindrical.loaded.PositionResult`) at each position phi
    (roll = phi, :mod:`.model`) under ``torque`` (N mm, > 0), warm-started along the cycle.

    The rotation is counted from the symmetric placement, so the first start is the exact rigid rotation to
    first contact (half the backlash) plus a single-pair deflection. ``store`` (:class:`ltca.outputs.PositionStore`)
    keeps each finished position (torque index ``it``) and gives back those an interrupted run finished: a position
    taken over is the next one's warm start, as it was, so a resumed cycle is the uninterrupted one bit for bit.
    ``lines`` receives a record per position; ``progress`` (a callable) a line per position
    (:func:`ltca.position_runs.solve_positions` in one run: its 6 positions gained nothing from two)."""
    rb1, b = lm.model.pinion.r_base, lm.model.face_width

    def start(k: int) -> _Start:
        return _Start(-sm.mesh.window(float(phis[k])).drive + torque / (rb1 ** 2 * C_PRIME * b))

    def line(k: int, res) -> dict:
        return {"torque_nm": torque * 1e-3, "phi_deg": float(np.degrees(phis[k])),
                "te_loaded_arcsec": float((res.theta - res.theta0) * 180 / np.pi * 3600),
                "max_pressure_mpa": float(res.max_pressure), "torque_residual": float(res.torque_residual)}

    count = [0]

    def done(k: int, res) -> None:
        count[0] += 1
        if progress:
            progress(f"{torque * 1e-3:g} N m: position {count[0]}/{len(phis)}  p_max {res.max_pressure:7.0f} MPa")

    return solve_positions(len(phis), lambda k, warm: solve_position(lm, float(phis[k]), float(torque), warm=warm),
                           line, store=store, it=it, lines=lines, start=start, done=done)
