"""One result type for every gear kind: :class:`LoadedResult`, and the one vocabulary of its figures.

Vocabulary (the same names and units in ``summary.json``, ``results.nc``, the plots and this API):

===================================  ==========  ==================================================================
``te_loaded``, ``te_unloaded``       arcsec      transmission error of the driven member: its lag behind the
                                                 rigid-body position, positive when it lags
``te_loaded_ptp_arcsec``             arcsec      peak-to-peak of the loaded TE over the cycle
``te_loaded_mean_arcsec``            arcsec      mean of the loaded TE over the cycle
``max_flank_pressure_mpa``           MPa         largest contact pressure away from edge contact (converges)
``max_contact_pressure_mpa``         MPa         largest cell pressure, edge contact included (mesh-dependent at
                                                 a sharp edge)
``max_root_stress_mpa``              MPa         largest principal fillet stress, per member
``mesh_stiffness_mean_n_per_um``     N/um        mean mesh stiffness of the whole face (normal load over the
                                                 approach)
``mesh_stiffness_mean_n_per_mm_um``  N/(mm um)   the same per face width (cylindrical and bevel pairs)
``converged``                        -           every position's torque balance met
``max_torque_residual``              -           the largest relative torque-balance residual
===================================  ==========  ==================================================================

Every dataset has the coordinates ``torque`` (N m, pinion; or satellite for a planetary pair) and ``cycle``
(position in mesh cycles, 0 at the pitch or mean point) beside its kind's own (``position``: roll in deg for
cylindrical pairs).
"""
from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import xarray as xr

from . import accessor as _accessor  # noqa: F401  (registers the ``ltca`` dataset accessor)
from .cases import Case
from .errors import CaseError

__all__ = ["LoadedResult", "TorqueFigures", "open_result", "save_result", "write_into", "TE_SIGN"]

#: the sign convention of every TE in the project
TE_SIGN = "TE is the driven member's lag behind its rigid-body position: positive when it lags"


@dataclass(frozen=True)
class TorqueFigures:
    """Headline figures of one torque, in the vocabulary of the module docstring (NaN where a kind has none)."""

    torque_nm: float
    te_loaded_ptp_arcsec: float
    te_unloaded_ptp_arcsec: float
    te_loaded_mean_arcsec: float
    max_flank_pressure_mpa: float
    max_contact_pressure_mpa: float
    max_root_stress_pinion_mpa: float
    max_root_stress_gear_mpa: float
    mesh_stiffness_mean_n_per_um: float
    mesh_stiffness_mean_n_per_mm_um: float
    converged: bool
    max_torque_residual: float


@dataclass(frozen=True)
class LoadedResult:
    """The loaded analysis of one case at its torques.

    Attributes
    ----------
    case : Case
        The case analysed (torques as run).
    dataset : xarray.Dataset
        Per torque and position (and contact grid, tooth, ...): see the module's vocabulary. Plots:
        ``result.dataset.ltca.plot_te(ax=ax)`` (:mod:`ltca.accessor`).
    summary : dict
        The figures of ``summary.json``: the first torque's at the top level, every torque's in ``"torques"``.
    figures : tuple of TorqueFigures
        The headline figures per torque, typed.
    timings : dict
        Wall time per stage (s).
    """

    case: Case
    dataset: xr.Dataset
    summary: dict
    figures: tuple[TorqueFigures, ...]
    timings: dict
    _state: Any = field(default=None, repr=False, compare=False)
    _writer: Any = field(default=None, repr=False, compare=False)

    @property
    def converged(self) -> bool:
        """Every position of every torque met its torque balance."""
        return all(f.converged for f in self.figures)

    @property
    def max_torque_residual(self) -> float:
        """The largest relative torque-balance residual over torques and positions."""
        return max(f.max_torque_residual for f in self.figures)

    @property
    def warnings(self) -> list[str]:
        """Design, sampling, pressure and convergence warnings of the run."""
        return list(self.summary.get("warnings", []))

    def at(self, torque_nm: float) -> TorqueFigures:
        """The figures of the torque closest to ``torque_nm`` (N m)."""
        return min(self.figures, key=lambda f: abs(f.torque_nm - torque_nm))

    def save(self, out: str | Path, *, report: bool = True, paraview_steps: int = 10) -> Path:
        """Write what ``ltca run`` writes into the folder ``out``; return the folder.

        The folder is created and locked while writing; every file is written atomically; ``run.json`` records
        the status.
        """
        return save_result(self, out, report=report, paraview_steps=paraview_steps)


def open_result(out: str | Path) -> tuple[xr.Dataset, dict]:
    """Read a saved run back: (the dataset of ``results.nc``, loaded into memory; the ``summary.json`` dict)."""
    import json

    out = Path(out)
    nc, js = out / "results.nc", out / "summary.json"
    for p in (nc, js):
        if not p.is_file():
            raise CaseError("out", str(out), f"a folder written by ltca run or LoadedResult.save ({p.name} missing)")
    with xr.open_dataset(nc, engine="h5netcdf") as ds:
        data = ds.load()
    return data, json.loads(js.read_text())


def signature(case: Case, **settings) -> dict:
    """What identifies a saved result: the case's TOML text and the settings."""
    return {"case_sha256": hashlib.sha256(case.to_toml().encode()).hexdigest(), **settings}


def write_into(result: LoadedResult, out: Path, *, report: bool = True, paraview_steps: int = 10) -> dict:
    """Write a result's files into the run folder ``out`` (already locked); return the summary as written.

    Every file goes through a staging folder, ``summary.json`` last.
    """
    from .outputs import staging, write_bytes_atomic, write_json_atomic
    from .validation import read_case_file
    head = dict(result.summary)
    head["timings_s"] = dict(head.get("timings_s", {}))
    case_file = result.case.file
    if case_file is None or read_case_file(case_file) != result.case.data:
        # a case edited in memory (with_values) or built without a file: the report shows the case as run
        case_file = str(Path(out) / "case.toml")
        write_bytes_atomic(case_file, result.case.to_toml().encode())
    with staging(out) as stage:
        result._writer(result, head, stage, case_file, report, paraview_steps)
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
