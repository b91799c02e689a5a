"""The gear kinds as the core (:mod:`ltca.core`) sees them: each module here adapts one kind's analysis
(:mod:`ltca.cylindrical`, :mod:`ltca.bevel`, :mod:`ltca.planetary`) to an :class:`Analysis`, and its results to
the one :class:`ltca.results.LoadedResult`. A new gear kind adds a module here, its schema and its analysis."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from ..results import TorqueFigures

__all__ = ["Analysis", "figures_from"]


@dataclass(frozen=True)
class Analysis:
    """What a gear kind supplies: ``plan(case, fidelity, positions, torques_nm, max_output_gb)`` (validate and
    size, no FE work), ``execute(plan, progress, cache, store)`` (the analysis; returns the kind's run record),
    ``result(case, run)`` (its LoadedResult), ``write(result, head, stage, case_file, report, paraview_steps)``
    (its files, summary.json excepted) and ``bodies(run)`` (the FE bodies' compliance records, for the run's log)."""
    plan: Callable
    execute: Callable
    result: Callable
    write: Callable
    resumable: bool
    bodies: Callable = lambda run: ()


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
