"""``ltca run`` for every gear kind: plan (validate and size, no FE work), check and lock the run folder, run
the analysis (:mod:`ltca.core`), save, print. One run folder discipline for every kind: lock, ``run.json``,
atomic files, ``--resume`` where the kind stores its positions (refused with a message where it does not).
"""
from __future__ import annotations

import sys
import time

from .console import print_result
from .core import _analysis, execute, plan
from .errors import CaseError
from .results import write_into

__all__ = ["run_to_dir"]


def run_to_dir(case_path: str, out: str = "out", *, fidelity: str | None = None, positions: int | None = None,
               progress: bool = True, cache: str | None = None, write: bool = True, resume: bool = False,
               max_output_gb: float = 2.0, torques: list[float] | None = None, paraview_steps: int | None = None
               ) -> dict:
    """Run a case file into the folder ``out`` and print its tables; returns the summary as written.

    ``write=False`` runs and prints without touching a folder."""
    from .cases import load_case
    from .outputs import PositionStore, RunDir
    t0 = time.perf_counter()
    say = (lambda msg: print(f"  {msg}", file=sys.stderr, flush=True)) if progress else None
    case, p = plan(load_case(case_path), fidelity=fidelity, positions=positions, torques_nm=torques,
                   max_output_gb=max_output_gb)
    analysis = _analysis(case.kind)
    if resume and not analysis.resumable:
        raise CaseError("--resume", True, f"not available for a {case.kind} case (its positions are not stored); "
                        "run afresh")
    for w in getattr(p, "warnings", ()):
        print(f"ltca run: warning: {w}", file=sys.stderr)
    if not write:
        result = execute(case, p, progress=say, cache=cache)
        head = dict(result.summary)
        print_result(result, head, say)
        return head
    from .outputs import signature_of
    sig = signature_of(case_path, fidelity=p.fidelity_name, positions=p.positions, torques_nm=list(p.torques_nm))
    with RunDir(out, f"ltca run {case_path}", sig, resume=resume) as rd:
        store = PositionStore(rd.out) if analysis.resumable else None
        result = execute(case, p, progress=say, cache=cache, store=store)
        head = write_into(result, rd.out, paraview_steps=10 if paraview_steps is None else paraview_steps)
        if say:
            say(f"wrote {rd.out}: summary.json, results.nc, the plots, VTU and report ({time.perf_counter() - t0:.1f} s)")
    for w in head.get("warnings", [])[len(getattr(p, "warnings", ())):]:
        print(f"ltca run: warning: {w}", file=sys.stderr)
    print_result(result, head, say)
    return head
