"""The one entry of every loaded analysis.

:func:`run` a :class:`ltca.cases.Case` of any gear kind and get a :class:`ltca.results.LoadedResult`;
:func:`ltca.results.save_result` writes it into a run folder. The command line, studies
and scripts all come through here; a gear kind supplies its plan / execute / write functions
(:mod:`ltca.kinds`), nothing else. Nothing here prints or picks a plotting backend.
"""
from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from .cases import PAIR_KINDS, Case, load_case
from .errors import CaseError
from .kinds import Analysis
from .results import LoadedResult

__all__ = ["run", "tca", "TcaResult", "plan", "execute", "ANALYSES"]

Progress = Callable[[str], None]

log = logging.getLogger(__name__)


def _analysis(kind: str) -> Analysis:
    if kind == "cylindrical":
        from .kinds import cylindrical
        return cylindrical.ANALYSIS
    if kind == "bevel":
        from .kinds import bevel
        return bevel.ANALYSIS
    if kind == "planetary":
        from .kinds import planetary
        return planetary.ANALYSIS
    raise CaseError("case", f"a {kind} case", f"a gear-pair case ({', '.join(PAIR_KINDS)}); a {kind} case runs "
                    f"with `ltca {kind}`")


ANALYSES = PAIR_KINDS


def _as_case(case: Case | str | Path) -> Case:
    return case if isinstance(case, Case) else load_case(case)


def plan(case: Case | str | Path, *, fidelity: str | None = None, positions: int | None = None,
         torques_nm: list[float] | None = None, max_output_gb: float = 2.0) -> tuple[Case, Any]:
    """Validate a run's settings and size it before any FE work: (the case, the kind's plan)."""
    case = _as_case(case)
    if positions is not None and (isinstance(positions, bool) or not isinstance(positions, int) or positions < 1):
        raise CaseError("positions", positions, "a whole number of positions per mesh cycle, at least 1")
    if isinstance(max_output_gb, bool) or not isinstance(max_output_gb, (int, float)) \
            or not math.isfinite(max_output_gb) or max_output_gb <= 0:
        raise CaseError("max_output_gb", max_output_gb, "a finite size in GB above 0")
    return case, _analysis(case.kind).plan(case, fidelity, positions, torques_nm, max_output_gb)


def execute(case: Case, p: Any, *, progress: Progress | None = None, cache: str | None = None,
            store=None) -> LoadedResult:
    """Run a planned analysis (:func:`plan`); ``store`` keeps finished positions (resumable kinds)."""
    a = _analysis(case.kind)
    t0 = time.perf_counter()
    run = a.execute(p, progress, cache, store)
    result = a.result(case, run)
    _log_run(case, p, result, a.bodies(run), time.perf_counter() - t0)
    return result


def _log_run(case: Case, p: Any, result: LoadedResult, bodies, seconds: float) -> None:
    """The run's summary on the ``ltca.core`` logger: model, solver, convergence, reuse."""
    if not log.isEnabledFor(logging.INFO):
        return
    solvers = []
    for b in bodies:
        method = getattr(getattr(b, "factorization", None), "method", None) or "factor freed"
        t = getattr(b, "timings", {})
        solvers.append(f"{b.n_dofs} dofs, {method} ({t.get('factorisation', float('nan')):.1f} s factorisation, "
                       f"{t.get('solves', float('nan')):.1f} s unit-load solves)")
    s = result.summary
    log.info("%s (%s), fidelity %s: %s positions at %s N m in %.1f s; bodies: %s", case.name, case.kind,
             getattr(p, "fidelity_name", "?"), s.get("positions", "?"),
             ", ".join(f"{f.torque_nm:g}" for f in result.figures), seconds, "; ".join(solvers) or "none")
    log.info("%s: converged %s, largest torque residual %.2g", case.name, result.converged,
             result.max_torque_residual)
    if s.get("positions_taken_over"):
        log.info("%s: %d positions taken over from the interrupted run, %d computed", case.name,
                 s["positions_taken_over"], s.get("positions_computed", 0))
    for f in result.figures:
        if not f.converged:
            log.warning("%s: not every position converged at %g N m (largest torque residual %.2g)", case.name,
                        f.torque_nm, f.max_torque_residual)


def run(case: Case | str | Path, *, fidelity: str | None = None, positions: int | None = None,
        torques_nm: list[float] | None = None, progress: Progress | None = None,
        cache: str | None = None) -> LoadedResult:
    """The loaded analysis of a gear-pair case over one mesh cycle at each torque.

    Parameters
    ----------
    case : Case or str or Path
        A case (:func:`ltca.load_case`), a case file or a shipped case's name.
    fidelity : {"coarse", "default", "fine"}, optional
        The fidelity preset; default the case's.
    positions : int, optional
        Positions per mesh cycle; default the case's.
    torques_nm : list of float, optional
        Torques (N m, pinion; satellite for a planetary pair) replacing the case's.
    progress : callable, optional
        Receives a line of text per stage (and turns on the per-position bar on stderr).
    cache : str, optional
        A folder for the mesh cache.

    Returns
    -------
    LoadedResult
        Writes nothing, prints nothing.
    """
    case, p = plan(case, fidelity=fidelity, positions=positions, torques_nm=torques_nm)
    return execute(case, p, progress=progress, cache=cache)


@dataclass(frozen=True)
class TcaResult:
    """The unloaded analysis of a gear-pair case: the case and its summary.

    The summary is in engineer's units (contact path, unloaded TE in arcsec, contact ratios; bevel: machine settings and the TCA of both flanks; planetary: the
    unloaded gaps of every pair).
    """

    case: Case
    summary: dict


def tca(case: Case | str | Path, *, positions: int | None = None) -> TcaResult:
    """The unloaded TCA of a gear-pair case (a Case, a case file or a shipped name). Writes and prints nothing."""
    case = _as_case(case)
    if case.kind == "cylindrical":
        from .cylindrical.run import tca_summary
        return TcaResult(case, tca_summary(case.record, positions, case.file)[0])
    if case.kind == "bevel":
        from .bevel.run import bevel_tca_summary
        return TcaResult(case, bevel_tca_summary(case.record, case.file)[0])
    if case.kind == "planetary":
        from .planetary.analysis import planetary_tca_summary
        return TcaResult(case, planetary_tca_summary(case.record, positions)[0])
    _analysis(case.kind)          # names the command of a case that is not a gear pair
    raise AssertionError(case.kind)
