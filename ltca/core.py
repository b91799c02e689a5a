"""The one entry of every loaded analysis: :func:`run` a :class:`ltca.cases.Case` of any gear kind and get a
:class:`ltca.results.LoadedResult`; :func:`save_result` writes it into a run folder. The command line, studies
and scripts all come through here; a gear kind supplies its plan / execute / write functions
(:data:`ANALYSES`), nothing else. Nothing here prints or picks a plotting backend.
"""
from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from .cases import PAIR_KINDS, Case, load_case
from .errors import CaseError
from .results import LoadedResult, TorqueFigures

__all__ = ["run", "plan", "execute", "save_result", "write_into", "Analysis", "ANALYSES"]

Progress = Callable[[str], None]


@dataclass(frozen=True)
class Analysis:
    """What a gear kind supplies: ``plan(case, fidelity, positions, torques_nm, max_output_gb)`` (validate and
    size, no FE work), ``execute(plan, progress, cache, store)`` (the analysis; returns the kind's run record),
    ``result(case, run)`` (its LoadedResult) and ``write(result, head, stage, case_file, report, paraview_steps)``
    (its files, summary.json excepted)."""
    plan: Callable
    execute: Callable
    result: Callable
    write: Callable
    resumable: bool


def _analysis(kind: str) -> Analysis:
    if kind == "cylindrical":
        from .cylindrical import api
        return api.ANALYSIS
    if kind == "bevel":
        from .bevel import api
        return api.ANALYSIS
    if kind == "planetary":
        from .planetary import api
        return api.ANALYSIS
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
    return a.result(case, a.execute(p, progress, cache, store))


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


def figures_from(rec: dict) -> TorqueFigures:
    """The typed headline figures of one torque record of a summary in the one vocabulary."""
    nan = float("nan")
    root = rec.get("max_root_stress_mpa") or {}
    return TorqueFigures(
        torque_nm=float(rec["torque_nm"]), te_loaded_ptp_arcsec=float(rec["te_loaded_ptp_arcsec"]),
        te_unloaded_ptp_arcsec=float(rec.get("te_unloaded_ptp_arcsec", nan)),
        te_loaded_mean_arcsec=float(rec.get("te_loaded_mean_arcsec", nan)),
        max_flank_pressure_mpa=float(rec.get("max_flank_pressure_mpa", nan)),
        max_contact_pressure_mpa=float(rec.get("max_contact_pressure_mpa", nan)),
        max_root_stress_pinion_mpa=float(root.get("pinion", nan) if root.get("pinion") is not None else nan),
        max_root_stress_gear_mpa=float(root.get("gear", nan) if root.get("gear") is not None else nan),
        mesh_stiffness_mean_n_per_um=float(rec.get("mesh_stiffness_mean_n_per_um", nan)),
        mesh_stiffness_mean_n_per_mm_um=float(rec.get("mesh_stiffness_mean_n_per_mm_um", nan)),
        converged=bool(rec["converged"]), max_torque_residual=float(rec["max_torque_residual"]))


def signature(case: Case, **settings) -> dict:
    """What identifies a run's results: the case (its file's bytes, else its TOML text) and the settings."""
    if case.file and Path(case.file).is_file() and case.data == load_case(case.file).data:
        digest = hashlib.sha256(Path(case.file).read_bytes()).hexdigest()
    else:
        digest = hashlib.sha256(case.to_toml().encode()).hexdigest()
    return {"case_sha256": digest, **settings}


def write_into(result: LoadedResult, out: Path, *, report: bool = True, paraview_steps: int = 10,
               extra: dict | None = None) -> dict:
    """Write a result's files into the run folder ``out`` (already locked): every file through a staging folder,
    ``summary.json`` last. Returns the summary as written."""
    from .outputs import staging, write_json_atomic
    head = dict(result.summary)
    head["timings_s"] = dict(head.get("timings_s", {}))
    head.update(extra or {})
    a = _analysis(result.case.kind)
    with staging(out) as stage:
        a.write(result, head, stage, result.case.file or result.case.name, report, paraview_steps)
    write_json_atomic(Path(out) / "summary.json", head)
    return head


def save_result(result: LoadedResult, out: str | Path, *, report: bool = True, paraview_steps: int = 10) -> Path:
    """:meth:`LoadedResult.save`: lock ``out``, write every file atomically, record the status in run.json."""
    from .outputs import RunDir, check_out_dir
    out = check_out_dir(out)
    if isinstance(paraview_steps, bool) or not isinstance(paraview_steps, int) or paraview_steps < 0:
        raise CaseError("paraview_steps", paraview_steps, "a whole number of steps, 0 for none")
    sig = signature(result.case, torques_nm=[f.torque_nm for f in result.figures])
    with RunDir(out, f"LoadedResult.save ({result.case.name})", sig):
        write_into(result, out, report=report, paraview_steps=paraview_steps)
    return out
