"""The files of a cylindrical run, written into a staging folder: results.nc, the plots, the loaded bodies' VTU,
the ParaView series and report.html. Returns what the summary records of them."""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from ltca.geometry.pair import rotation_z

from .analysis import CylindricalRun
from .loaded import weights_of

__all__ = ["write_outputs"]


def write_outputs(run: CylindricalRun, head: dict, stage: Path, case_file: str, report: bool = True,
                  paraview_steps: int = 10) -> None:
    """Write every file of the run but summary.json into ``stage``; ``head`` (the summary to be written) gains
    what the writers find: ``paraview``, ``iso6336``, ``striping_index`` and their timings.

    Parameters
    ----------
    run : CylindricalRun
    stage : Path
        The staging folder (renamed into place by the caller).
    case_file : str
        The case file shown in the report (its text is embedded).
    report : bool
        Write report.html and its plot.
    paraview_steps : int
        Positions of the first torque in the ParaView series (0: none).
    """
    from ..outputs import write_netcdf_atomic
    from .report import plot_all, write_vtu
    from .sweep import NC_ENCODING
    lm, model, case = run.lm, run.lm.model, run.plan.case
    write_netcdf_atomic(stage / "results.nc", run.dataset, NC_ENCODING)   # in memory first: HDF5 aborts on ENOSPC
    plot_all(run.dataset, stage, case.name)
    first = run.results[0]
    k = int(np.argmax(run.datasets[0].max_pressure.values))
    r = first[k]
    W1, W2 = weights_of(lm, r)
    write_vtu(stage / "pinion_loaded.vtu", lm.body1, W1.T @ r.force, rotation_z(model.phi_pitch - r.roll))
    write_vtu(stage / "gear_loaded.vtu", lm.body2, W2.T @ r.force, model.pair.gear_frame(model.phi_pitch - r.roll))
    pv = None
    if paraview_steps:
        from .paraview import write_series
        t0 = time.perf_counter()
        pv = write_series(stage, lm, first, case.torques[0], steps=paraview_steps)
        head["timings_s"]["paraview"] = round(time.perf_counter() - t0, 3)
        head["paraview"] = {"pvd": "paraview.pvd", "torque_nm": case.torques[0] * 1e-3,
                           "roll_deg": pv["roll_deg"], "flank_peak_mpa": pv["flank_peak_mpa"]}
    if report:
        from .html_report import write_run_report
        t0 = time.perf_counter()
        extra = write_run_report(stage, lm, case_file, head, run.dataset, run.plan.positions,
                                 run.plan.fidelity_name, run.unconverged, head["timings_s"],
                                 "paraview.pvd" if pv else None)
        head["timings_s"]["report"] = round(time.perf_counter() - t0, 3)
        head["iso6336"] = extra["comparisons"]
        head["striping_index"] = {f"{t:g}": round(v, 4) for t, v in extra["striping"].items()}
