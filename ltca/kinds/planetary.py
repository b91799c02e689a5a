"""The planetary kind in the one core (:mod:`ltca.core`): the satellite in its internal central wheel.

TE of this pair (the wheel held): the satellite's rotation beyond its rigid-body position under its torque, in
arcsec of the satellite (positive) and in um along the line of action; ``torque`` is the satellite's torque.
Root stresses: ``pinion`` is the satellite, ``gear`` the wheel.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import xarray as xr

from ..cases import Case
from ..cylindrical.tca import ARCSEC_PER_RAD
from ..planetary import analysis as prun
from ..results import LoadedResult
from . import Analysis, figures_from

__all__ = ["ANALYSIS", "planetary_dataset", "CONVENTIONS"]

#: the sign and meaning of the planetary dataset's figures (its ``conventions`` attribute)
CONVENTIONS = ("TE: the satellite's rotation beyond its rigid-body position under its torque (the wheel held), "
               "positive, arcsec of the satellite and um along the line of action; torque: the satellite's; root "
               "stress pinion: the satellite, gear: the wheel")


def _plan(case: Case, fidelity, positions, torques_nm, max_output_gb):
    return prun.plan(case.record, fidelity, positions, torques_nm, max_output_gb, file=case.file)


def planetary_dataset(run: prun.PlanetaryRun) -> xr.Dataset:
    """The drive-direction results of every torque as one dataset (torque x position [x pair])."""
    rb1 = run.sm.pair.pinion.r_base
    pairs = sorted({k for res in run.results for r in res for k in r.pair_load})
    dth = np.array([[r.theta - r.theta0 for r in res] for res in run.results])
    TP = ("torque", "position")

    def per(f):
        return np.array([[f(r) for r in res] for res in run.results])
    ds = xr.Dataset(
        {"te_loaded": (TP, ARCSEC_PER_RAD * dth, {"units": "arcsec", "long_name": "satellite rotation beyond its "
                                                  "rigid position under load (arcsec of the satellite)"}),
         "te_loaded_um": (TP, 1e3 * rb1 * dth, {"units": "um", "long_name": "the same along the line of action"}),
         "pair_load": (TP + ("pair",), per(lambda r: [r.pair_load.get(k, 0.0) for k in pairs]),
                       {"units": "N", "long_name": "normal load of each tooth pair"}),
         "max_pressure": (TP, per(lambda r: r.max_pressure), {"units": "MPa", "long_name": "largest cell pressure"}),
         "root_stress_pinion": (TP, per(lambda r: max(r.root1.values(), default=np.nan)),
                                {"units": "MPa", "long_name": "max principal fillet stress, satellite"}),
         "root_stress_gear": (TP, per(lambda r: max(r.root2.values(), default=np.nan)),
                              {"units": "MPa", "long_name": "max principal fillet stress, wheel"}),
         "torque_residual": (TP, per(lambda r: r.torque_residual),
                             {"units": "1", "long_name": "relative torque balance residual"})},
        coords={"torque": ("torque", np.array(run.torques) * 1e-3, {"units": "N m", "long_name": "satellite torque"}),
                "position": ("position", np.degrees(run.phis), {"units": "deg", "long_name": "satellite angle"}),
                "cycle": ("position", run.phis * run.sm.mesh.z1 / (2 * np.pi),
                          {"units": "1", "long_name": "position in mesh cycles"}),
                "pair": ("pair", np.array(pairs), {"units": "1", "long_name": "tooth pair"})},
        attrs={"case": run.plan.case.name, "conventions": CONVENTIONS})
    return ds


def _record(ds: xr.Dataset, k: int, res: list) -> dict:
    d = ds.isel(torque=k)
    return dict(torque_nm=float(d.torque), te_loaded_ptp_arcsec=float(np.ptp(d.te_loaded.values)),
                te_loaded_mean_arcsec=float(d.te_loaded.mean()), te_loaded_ptp_um=float(np.ptp(d.te_loaded_um.values)),
                max_contact_pressure_mpa=float(d.max_pressure.max()),
                max_root_stress_mpa={"pinion": float(np.nanmax(d.root_stress_pinion.values)),
                                     "gear": float(np.nanmax(d.root_stress_gear.values))},
                converged=bool(all(r.residual < 1e-6 for r in res)),
                max_torque_residual=float(d.torque_residual.max()))


def _result(case: Case, run: prun.PlanetaryRun) -> LoadedResult:
    ds = planetary_dataset(run)
    records = [_record(ds, k, res) for k, res in enumerate(run.results)]
    c, lm = run.plan.case, run.lm
    head = dict(case=c.name, kind="planetary", method=c.method, rated_torque_nm=run.rating.torque_Nm,
                fidelity=run.plan.fidelity_name, positions=len(run.phis), **records[0],
                teeth_satellite=list(lm.teeth1), teeth_wheel=list(lm.teeth2),
                max_pairs_loaded=max(r["pairs_max"] for r in run.rows), torques=records,
                results=[dict(r) for r in run.rows], timings_s=run.timings,
                reverse_direction="mirror image of the drive direction (symmetric teeth, axisymmetric supports)")
    if run.computed or run.taken_over:
        head.update(positions_computed=run.computed, positions_taken_over=run.taken_over)
    head["converged"] = all(r["converged"] for r in records)
    head["max_torque_residual"] = max(r["max_torque_residual"] for r in records)
    return LoadedResult(case=case, dataset=ds, summary=head, figures=tuple(figures_from(r) for r in records),
                        timings=dict(run.timings), _state=run, _writer=_write)


def _write(result: LoadedResult, head: dict, stage: Path, case_file: str, report: bool, paraview_steps: int):
    run = result._state
    prun.write_files(run, stage, result.dataset)
    if paraview_steps:
        from ..cylindrical.paraview import write_series
        t0 = time.perf_counter()
        T = run.torques[0]
        pv = write_series(stage, run.lm, run.results[0], T, steps=paraview_steps,
                          comment=f"{run.plan.case.name}, satellite torque {T * 1e-3:g} N m, drive direction; "
                                  "timestep = satellite angle, deg")
        head["timings_s"]["paraview"] = round(time.perf_counter() - t0, 3)
        head["paraview"] = {"pvd": "paraview.pvd", "torque_nm": T * 1e-3, "position_deg": pv["roll_deg"],
                            "flank_peak_mpa": pv["flank_peak_mpa"]}


ANALYSIS = Analysis(plan=_plan, execute=prun.execute, result=_result, write=_write, resumable=True,
                    bodies=lambda run: (run.lm.body1, run.lm.body2))
