"""The loaded analysis of a spiral bevel pair: :func:`plan` (validate), :func:`execute` (pinion synthesis, each
loaded flank's compliance once, the loaded contact over a mesh cycle at every torque: working flank for positive,
coast flank for negative pinion torques); the results and files are :mod:`ltca.bevel.results`.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from ltca.geometry.bevel.design import synthesize_pinion
from ltca.geometry.bevel.generation import MeshingError, standard_gear_cut
from ltca.geometry.bevel.tca import RAD_PER_ARCSEC as ARCSEC
from ltca.geometry.bevel.tca import Assembly, BevelPair, ContactError

from ..errors import CaseError
from ..position_runs import solve_positions
from ..validation import DesignError
from .case import BevelCase, case_blank, check_bevel_torques
from .limits import BevelDesignLimit, working_values
from .loaded import BevelPosition, solve_position
from .loaded_model import BevelBodies, BevelFidelity, loaded_model, prepare_bodies

__all__ = ["build_pair", "synthesis_error", "cycle_positions", "analyse_torque", "BevelPlan", "BevelRun", "plan", "execute"]

FLANK = {"concave": "working", "convex": "coast"}


def build_pair(case: BevelCase) -> BevelPair:
    """The gear (standard cut) and the pinion synthesised for the case's targets, or the pair cut as the case's
    settings sheets give it."""
    bl = case_blank(case)
    if case.cuts:
        return BevelPair(bl, case.cuts["gear"], case.cuts["pinion"])
    gear = standard_gear_cut(bl)
    pin, _ = synthesize_pinion(bl, gear, case.targets, blank_offset=case.blank_offset)
    return BevelPair(bl, gear, pin)


def synthesis_error(case: BevelCase, exc: Exception, file: str | None = None) -> DesignError:
    """The user's design (targets, blank, cutter) has no solution in the cradle model: the error (exit 2) that
    names the inputs, the same for ``ltca tca`` and ``ltca run``.

    For a case with synthesis targets, :func:`ltca.bevel.limits.working_values` searches the limiting field and a
    value of it that works (a :class:`ltca.bevel.limits.BevelDesignLimit` naming both); where the pair is made on
    the ideal mounting, or the search finds no value within its budget, the error names the inputs that drive it."""
    searched = None
    if not case.cuts and case.targets:
        searched = working_values(case)
        if searched.found:
            return BevelDesignLimit(searched.failure, searched.found, file)
    side = "working" if "concave" in str(exc) else "coast" if "convex" in str(exc) else "working/coast"
    asm = case.assembly or {}
    mounted = [f"assembly.{key}" for name, key in (("E", "E_mm"), ("P", "P_mm"), ("G", "G_mm"),
                                                   ("d_sigma", "sigma_deg")) if asm.get(name, 0.0) != 0.0]
    if case.cuts:                           # the pair as its settings sheets cut it: no synthesis to blame
        flank = {"working": "concave", "coast": "convex"}.get(side, "concave")
        return DesignError(f"spiral bevel TCA failed ({type(exc).__name__}: {str(exc)[:160]})",
                           (*mounted, f"bevel.settings.pinion.{flank}", "bevel.settings.gear"),
                           ("smaller assembly errors, or " if mounted else "") + "settings of a finished design "
                           "(the flanks must touch at an interior point near the mean point)", file=file)
    return DesignError(f"spiral bevel synthesis/TCA failed ({type(exc).__name__}: {str(exc)[:160]})",
                       (*mounted, f"bevel.{side}.path_angle_deg", f"bevel.{side}.te_magnitude_arcsec",
                        f"bevel.{side}.ellipse_major_mm", "bevel.spiral_angle_deg", "bevel.cutter_radius_mm"),
                       ("smaller assembly errors, or " if mounted else "") +
                       ("move the targets towards the shipped case's values" if searched is None or
                        searched.failure is None else
                        f"no single change of the failing flank's path angle, ellipse axis or TE magnitude, nor a "
                        f"cutter radius of 0.6 to 1.2 mean cone distances, made the pinion in {searched.trials} "
                        "trials: change several targets at once, towards the shipped case's values"), file=file)


def cycle_positions(n: int, z1: int) -> np.ndarray:
    """``n`` pinion angles over one mesh cycle 2 pi / z1, centred on the mean point (rad)."""
    return (np.arange(n) / n - 0.5) * 2 * np.pi / z1


def analyse_torque(lm, phi: np.ndarray, torque_nm: float, progress=None, store=None, it: int = 0,
                   lines: list | None = None) -> list[BevelPosition]:
    """The loaded contact at the pinion angles ``phi`` under |torque_nm| (N m) on the model's flank.

    ``progress`` (a callable) receives a line per position; ``store`` (:class:`ltca.outputs.PositionStore`) keeps
    each finished position and takes over those an interrupted run finished (torque index ``it``). The positions run
    in order (:func:`ltca.position_runs.solve_positions` in one run: two gained nothing, the gap evaluation holds the
    GIL)."""
    t0 = time.perf_counter()
    count = [0]

    def done(k: int, r: BevelPosition) -> None:
        count[0] += 1
        if progress:
            progress(f"{FLANK[lm.side]} {torque_nm:g} N m: position {count[0]}/{len(phi)}  TE {-r.te / ARCSEC:8.2f} "
                     f"arcsec  p_max {r.max_pressure:7.0f} MPa  ({time.perf_counter() - t0:.1f} s)")

    def line(k: int, res: BevelPosition) -> dict:
        return {"torque_nm": torque_nm, "phi1_deg": float(np.degrees(res.phi1)), "te_loaded_arcsec": -res.te / ARCSEC,
                "max_pressure_mpa": float(res.max_pressure), "torque_residual": float(res.torque_residual)}

    return solve_positions(len(phi), lambda k, warm: solve_position(lm, float(phi[k]), abs(torque_nm) * 1e3), line,
                           store=store, it=it, lines=lines, done=done)


@dataclass(frozen=True)
class BevelPlan:
    """A validated bevel run: the case, its torques (N m), positions per cycle, fidelity and assembly errors."""
    case: object
    torques_nm: tuple[float, ...]
    positions: int
    fid: BevelFidelity
    asm: Assembly
    warnings: tuple[str, ...] = ()

    @property
    def fidelity_name(self) -> str:
        return self.fid.name


@dataclass
class BevelRun:
    """What :func:`execute` found: the pair, the loaded models and results per flank and torque, timings."""
    plan: BevelPlan
    pair: BevelPair
    runs: dict
    timings: dict
    computed: int = 0
    taken_over: int = 0


def plan(case, fidelity: str | None = None, positions: int | None = None, torques_nm=None,
         max_output_gb: float = 2.0, file: str | None = None) -> BevelPlan:
    """Validate a bevel run's settings (no synthesis, no FE work)."""
    tq = case.torques if torques_nm is None else check_bevel_torques(list(torques_nm), "--torque", file)
    if not tq:
        raise DesignError("no torque to analyse", ("load.torque_nm",), "add [load] torque_nm = [..] (N m, pinion)",
                          file=file)
    n = positions or case.positions
    if not 4 <= n <= 400:
        raise CaseError("--positions", n, "an integer in [4, 400] (as analysis.positions)", file)
    fid_name = fidelity or case.fidelity
    if fid_name not in ("coarse", "default", "fine"):
        raise CaseError("--fidelity", fid_name, "one of ['coarse', 'default', 'fine']", file)
    return BevelPlan(case, tq, n, BevelFidelity.named(fid_name), Assembly(**case.assembly))


def execute(p: BevelPlan, progress=None, cache: str | None = None, store=None) -> BevelRun:
    """Synthesise the pinion, compute each loaded flank's compliance once, solve every torque over the cycle."""
    case = p.case
    timings = {}
    t0 = time.perf_counter()
    try:
        pair = build_pair(case)
    except (ContactError, MeshingError, ValueError) as exc:
        raise synthesis_error(case, exc, getattr(case, "file", None)) from None
    timings["synthesis"] = time.perf_counter() - t0
    bodies: dict[str, BevelBodies] = {}
    runs, lines = {}, []
    for it, T in enumerate(p.torques_nm):
        side = "concave" if T > 0 else "convex"
        if side not in bodies:
            t1 = time.perf_counter()
            try:
                bodies[side] = prepare_bodies(pair, side, p.fid, case.young, case.poisson, cache, progress,
                                              mounting=case.mounting)
            except MeshingError as exc:        # a flank the body's grid cannot reach: the design limits
                raise synthesis_error(case, exc, getattr(case, "file", None)) from None
            timings[f"compliance_{FLANK[side]}"] = time.perf_counter() - t1
            t1 = time.perf_counter()
            runs[side] = {"lm": loaded_model(pair, bodies[side], p.asm)}
            timings[f"reference_{FLANK[side]}"] = time.perf_counter() - t1
        t1 = time.perf_counter()
        phi = cycle_positions(p.positions, pair.blank.pinion.z)
        runs[side][T] = analyse_torque(runs[side]["lm"], phi, T, progress, store, it, lines)
        timings[f"torque_{T:g}"] = time.perf_counter() - t1
    run = BevelRun(p, pair, runs, timings)
    if store is not None:
        store.rewrite_log(lines)
        run.computed, run.taken_over = store.computed, store.taken_over
    return run
