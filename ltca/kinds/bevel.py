"""The bevel kind in the one core (:mod:`ltca.core`): its plan, execute, result and write functions."""
from __future__ import annotations

import time
from pathlib import Path

from ..bevel import analysis
from ..cases import Case
from ..results import LoadedResult
from . import Analysis, figures_from

__all__ = ["ANALYSIS"]


def _plan(case: Case, fidelity, positions, torques_nm, max_output_gb):
    return analysis.plan(case.record, fidelity, positions, torques_nm, max_output_gb, file=case.file)


def _result(case: Case, run: analysis.BevelRun) -> LoadedResult:
    from ..bevel.results import bevel_dataset
    p = run.plan
    ds, head, plotdata = bevel_dataset(p.case, run.pair, p.asm, p.fid, run.runs, p.torques_nm, run.timings)
    if run.computed or run.taken_over:
        head.update(positions_computed=run.computed, positions_taken_over=run.taken_over)
    run.plotdata = plotdata
    return LoadedResult(case=case, dataset=ds, summary=head, figures=tuple(figures_from(r) for r in head["torques"]),
                        timings=dict(run.timings), _state=run, _writer=_write)


def _write(result: LoadedResult, head: dict, stage: Path, case_file: str, report: bool, paraview_steps: int):
    from ..bevel.results import write_files
    run = result._state
    head["plots"] = write_files(stage, run.plan.case, run.pair, result.dataset, run.plotdata, run.runs,
                                run.plan.torques_nm)
    if paraview_steps:
        from ..bevel.paraview import write_series
        t0 = time.perf_counter()
        T = run.plan.torques_nm[0]
        rr = run.runs["concave" if T > 0 else "convex"]
        pv = write_series(stage, rr["lm"], rr[T], result.dataset.cycle.values, T, steps=paraview_steps,
                          name=run.plan.case.name)
        head["timings_s"]["paraview"] = round(time.perf_counter() - t0, 3)
        head["paraview"] = {"pvd": "paraview.pvd", "torque_nm": T, "cycle": pv["cycle"],
                            "flank_peak_mpa": pv["flank_peak_mpa"]}
    if report:
        from ..bevel.html_report import write_bevel_report
        write_bevel_report(stage, run.plan.case, run.pair, head, case_file)


def _bodies(run: analysis.BevelRun) -> tuple:
    return tuple(b for rr in run.runs.values() for b in (rr["lm"].bodies.body1, rr["lm"].bodies.body2))


ANALYSIS = Analysis(plan=_plan, execute=analysis.execute, result=_result, write=_write, resumable=True,
                    bodies=_bodies)
