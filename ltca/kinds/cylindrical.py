"""The cylindrical kind in the one core (:mod:`ltca.core`): its plan, execute, result and write functions."""
from __future__ import annotations

from pathlib import Path

from ..cases import Case
from ..cylindrical import analysis
from ..results import LoadedResult
from . import Analysis, figures_from

__all__ = ["ANALYSIS"]


def _plan(case: Case, fidelity, positions, torques_nm, max_output_gb):
    return analysis.plan(case.record, fidelity, positions, torques_nm, max_output_gb, file=case.file)


def _result(case: Case, run: analysis.CylindricalRun) -> LoadedResult:
    head = run.head
    if run.computed or run.taken_over:
        head = {**head, "positions_computed": run.computed, "positions_taken_over": run.taken_over}
    return LoadedResult(case=case, dataset=run.dataset, summary=head,
                        figures=tuple(figures_from(r) for r in head["torques"]), timings=dict(head["timings_s"]),
                        _state=run, _writer=_write)


def _write(result: LoadedResult, head: dict, stage: Path, case_file: str, report: bool, paraview_steps: int):
    from ..cylindrical.save import write_outputs
    write_outputs(result._state, head, stage, case_file, report=report, paraview_steps=paraview_steps)


ANALYSIS = Analysis(plan=_plan, execute=analysis.execute, result=_result, write=_write, resumable=True,
                    bodies=lambda run: (run.lm.body1, run.lm.body2))
