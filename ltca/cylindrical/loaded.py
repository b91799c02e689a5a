"""Loaded tooth contact analysis of cylindrical pairs: compliance once, contact per mesh position.

At each position the contact cells are narrow strips on the pinion's driving flank, one per face
slice and tooth, centred on the unloaded contact line and a few Hertz half-widths wide. Their gaps
come from the separation field (both members' micro-geometry and errors included), their compliance
from the two bodies' FE grids (bilinear interpolation) plus the half-space near field, and the
complementarity problem with torque balance gives the cell forces and the loaded rotation. The cells
and their contact problem are built in :mod:`ltca.cylindrical.contact_cells`; the model with both bodies'
compliance in :mod:`ltca.cylindrical.loaded_model`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ltca.fem.compliance import BodyCompliance

from ..errors import ConvergenceError
from ..position import root_stresses, solve_rounds
from .contact_cells import contact_strips, contact_system
from .loaded_model import LoadedModel
from .tca import ARCSEC_PER_RAD, first_contact

__all__ = ["PositionResult", "solve_position", "weights_of", "te_arcsec"]


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
    bound: np.ndarray | None = None   # (n,) edges that end each cell's part (ltca.cylindrical.cell_clip bits)
    span: np.ndarray | None = None    # (n,) half the change of s over each cell's part, mm

    @property
    def max_pressure(self) -> float:
        return float(self.pressure.max()) if self.pressure.size else 0.0


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
    state = {"theta": theta_guess}

    def assemble():
        strips, dz, ds, lattice = contact_strips(lm, phi1, state["theta"], widen, torque, cycle)
        if not strips:
            raise ConvergenceError("contact search", float("inf"), 0,
                                   "no tooth pair comes near contact: check the centre distance, the positions "
                                   "(more of them: analysis.positions) and large form deviations or misalignment "
                                   "(profile_form_um, lead_form_um, lead_misalignment_um)")
        return strips, ds, contact_system(lm, phi1, strips, dz, ds, cycle, lattice)

    def solve_args(x):
        sy = x[2]
        ok = np.isfinite(sy.gap0) & (sy.lever1 > 0)
        active0 = ok & _carried_over(warm, sy, roll, model.pitch_angle)
        if not active0.any():
            active0 = ok & (sy.gap0 - sy.lever1 * state["theta"] < 0)
        return (sy.C, np.where(ok, sy.gap0, np.inf), np.where(ok, sy.lever1, 1.0), torque,
                active0 if active0.any() else None)

    def grow(x, sol) -> bool:
        strips = x[0]
        state["theta"] = sol.approach
        more, i0 = False, 0
        for st in strips:
            f = sol.force[i0:i0 + len(st.s)]
            if (st.open_lo and f[0] > 1e-9 * torque / rb1) or (st.open_hi and f[-1] > 1e-9 * torque / rb1):
                widen[(st.tooth, st.slice)] = widen.get((st.tooth, st.slice), 1.0) * 1.7
                more = True
            i0 += len(st.s)
        return more

    (strips, ds, sy), sol = solve_rounds(assemble, solve_args, grow, max_widen + 1,
                                         f"contact at roll {np.degrees(roll):.3f} deg")
    F = sol.force
    T1, T2 = float(F @ sy.lever1), float(F @ sy.lever2)
    theta0 = float(first_contact(model, phi1, lm.teeth1, cycle=cycle))
    return PositionResult(
        float(roll + cycle * model.pitch_angle), float(sol.approach), theta0, sy.tooth, sy.lattice, sy.slice, sy.s,
        sy.z, sy.area, F, F / sy.area, sy.gap0, sy.gear_tooth, sy.gear_s, sy.gear_z,
        {int(k): float(F[sy.tooth == k].sum()) for k in lm.teeth1},
        *root_stresses(lm.body1, sy.W1, lm.body2, sy.W2, F), abs(T1 - torque) / torque,
        T2 / T1 if T1 else np.nan, sol.iterations, sol.residual, sol.active, ds, sy.bound, sy.span)


def _cell_keys(tooth, lattice, slice_) -> np.ndarray:
    return (np.asarray(tooth, np.int64) * 1_000_003 + lattice) * 65_536 + slice_


def _carried_over(warm: PositionResult | None, sy, roll: float, pitch: float) -> np.ndarray:
    """The cells that carried load at the previous position (same tooth, same place on the lattice along its line):
    the active set to start from. A cycle boundary renumbers the teeth by one. A warm start that is only a starting
    rotation (an object with ``theta``, no cells) carries no cells over."""
    if not isinstance(warm, PositionResult) or not warm.active.any():
        return np.zeros(len(sy.s), bool)
    r_prev = warm.roll - np.round(warm.roll / pitch) * pitch
    shift = int(np.round((r_prev - roll) / pitch))
    keys = _cell_keys(warm.tooth[warm.active] + shift, warm.lattice[warm.active], warm.slice[warm.active])
    return np.isin(_cell_keys(sy.tooth, sy.lattice, sy.slice), keys)


def weights_of(lm: LoadedModel, res: PositionResult):
    """Interpolation weights of a position's cells on the pinion and gear compliance grids."""
    return lm.body1.weights(res.tooth, res.s, res.z), lm.body2.weights(res.gear_tooth, res.gear_s, res.gear_z)


def te_arcsec(lm: LoadedModel, theta: np.ndarray) -> np.ndarray:
    """Pinion rotation (rad) -> transmission error of the gear (arcsec, positive = lag)."""
    return np.asarray(theta) / lm.model.pair.ratio * ARCSEC_PER_RAD
