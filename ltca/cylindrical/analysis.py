"""The loaded analysis of a cylindrical pair in two steps: :func:`plan` (validate and size the run, build the
model: cheap, before any output folder is touched) and :func:`execute` (compliance once, the contact at every
position and torque, the run dataset and summary). Nothing here writes a file or prints.
"""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass, field
from typing import Callable

import xarray as xr

from ..case import FIDELITIES, CylindricalCase, check_torques
from ..errors import CaseError
from .edges import edge_summary
from .loaded import PositionResult
from .loaded_model import Fidelity, LoadedModel, prepare
from .loop import analyse, cycle_rolls
from .model import build_model
from .results import position_dataset, summary

__all__ = ["CylindricalPlan", "CylindricalRun", "plan", "execute"]


@dataclass(frozen=True)
class CylindricalPlan:
    """A validated, sized cylindrical run: the case (torques overridden), its model and its sampling."""
    case: CylindricalCase
    model: object
    fidelity_name: str
    positions: int
    warnings: tuple[str, ...]
    t_geometry: float

    @property
    def torques_nm(self) -> tuple[float, ...]:
        """The run's pinion torques, N m."""
        return tuple(t * 1e-3 for t in self.case.torques)


@dataclass
class CylindricalRun:
    """What :func:`execute` found: the loaded model, the results of every torque, the run dataset and summary."""
    plan: CylindricalPlan
    lm: LoadedModel
    results: list[list[PositionResult]]
    datasets: list[xr.Dataset]
    dataset: xr.Dataset
    head: dict
    unconverged: list[str] = field(default_factory=list)
    computed: int = 0
    taken_over: int = 0


def plan(case: CylindricalCase, fidelity: str | None = None, positions: int | None = None,
         torques_nm: list[float] | None = None, max_output_gb: float = 2.0, file: str | None = None
         ) -> CylindricalPlan:
    """Validate the run's settings, build the pair model and check the run's size (no FE work).

    Parameters
    ----------
    case : CylindricalCase
    fidelity : str, optional
        A preset of :data:`ltca.case.FIDELITIES`; default the case's.
    positions : int, optional
        Positions per mesh cycle; default the case's (or the sampling rule's when the case gives none).
    torques_nm : list of float, optional
        Pinion torques (N m) replacing the case's.
    max_output_gb : float
        The size guard of the output.
    file : str, optional
        The case file, named in messages.
    """
    from ..sizing import check_run_size
    from .limits import check_limits
    from .sampling import default_positions, sampling_warnings
    from .warnings import check_contact, design_warnings
    t0 = time.perf_counter()
    if torques_nm is not None:
        case = dataclasses.replace(case, torques=tuple(1e3 * t for t in check_torques(list(torques_nm), "--torque")))
    fid_name = fidelity or case.fidelity
    if fid_name not in FIDELITIES:
        raise CaseError("--fidelity", fid_name, f"one of {sorted(FIDELITIES)}")
    model = build_model(case)
    check_contact(model, str(file or case.name))
    n_pos = positions or (default_positions(model) if case.positions_auto else case.positions)
    check_run_size(case, n_pos, FIDELITIES[fid_name], max_output_gb)
    check_limits(model, FIDELITIES[fid_name], fid_name, str(file or case.name))   # body size, edge zones
    warnings = tuple(design_warnings(model) + sampling_warnings(model, n_pos))
    return CylindricalPlan(case, model, fid_name, n_pos, warnings, time.perf_counter() - t0)


def execute(p: CylindricalPlan, progress: Callable[[str], None] | None = None, cache: str | None = None,
            store=None) -> CylindricalRun:
    """Compliance once, then the loaded contact over the cycle at every torque (warm-started).

    ``progress`` receives one line per stage and turns on the per-position bar; ``store``
    (:class:`ltca.outputs.PositionStore`) keeps each finished position and takes over those of an interrupted run.
    """
    from ..position_runs import thread_count
    from .sweep import run_dataset, torque_record
    from .warnings import convergence_warnings, pressure_warnings
    t_start = time.perf_counter() - p.t_geometry
    case, model, n_pos = p.case, p.model, p.positions
    say = progress or (lambda msg: None)
    fid = Fidelity.from_preset(FIDELITIES[p.fidelity_name], case.module)
    rolls = cycle_rolls(n_pos, case.pinion.teeth, case.cycles)
    say(f"{case.name}: {n_pos} positions per cycle x {case.cycles} cycle(s), fidelity '{p.fidelity_name}' "
        f"(flank elements {fid.h_flank:.2f} mm)")
    lm = prepare(model, fid, cycle_rolls(n_pos, case.pinion.teeth), max(case.torques), cache_dir=cache,
                 progress=say)
    summaries, datasets, results, lines, unconverged = [], [], [], [], []
    warnings = list(p.warnings)
    for it, torque in enumerate(case.torques):
        t0 = time.perf_counter()
        res = analyse(lm, rolls, torque, progress is not None, None, store=store, it=it, lines=lines,
                      threads=thread_count())
        results.append(res)
        t_contact = time.perf_counter() - t0
        ds = position_dataset(lm, res, torque)
        timings = {"geometry": p.t_geometry + lm.timings["tca"], "mesh": lm.timings["mesh"],
                   "compliance": sum(lm.timings[k] for k in ("assembly", "factorisation", "setup", "solves")),
                   "contact": t_contact, "contact_per_position": t_contact / len(rolls),
                   "total": time.perf_counter() - t_start}
        converged = all(r.residual < 1e-6 for r in res)
        summaries.append(summary(lm, ds, timings, converged, edge_summary(lm, res, torque)))
        unconverged += convergence_warnings(res, torque * 1e-3)
        summaries[-1]["warnings"] = (warnings + pressure_warnings(case, summaries[-1])
                                     + convergence_warnings(res, torque * 1e-3))
        datasets.append(ds)
        head = summaries[-1]
        at = head.get("max_flank_pressure_at", {})
        say(f"T = {torque * 1e-3:g} N m: loaded TE ptp {head['te_loaded_ptp_arcsec']:.2f} arcsec, "
            f"max flank pressure {head['max_flank_pressure_mpa']:.0f} MPa at roll {at.get('roll_deg', 0):+.2f} deg "
            f"({t_contact:.1f} s)")
    all_ds = run_dataset(datasets, n_pos, case.cycles, case.pinion.teeth)
    records = [torque_record(all_ds, h) for h in summaries]
    head = dict(summaries[0])            # the first torque's figures at the top, every torque's in "torques"
    head["torques"] = records
    head["warnings"] = list(dict.fromkeys(w for h in summaries for w in h["warnings"]))
    head["timings_s"]["total"] = round(time.perf_counter() - t_start, 3)
    run = CylindricalRun(p, lm, results, datasets, all_ds, head, unconverged)
    if store is not None:
        if store.dirty:                  # every position was taken over: the log in order
            store.rewrite_log(lines)
        run.computed, run.taken_over = store.computed, store.taken_over
    return run
