"""The cylindrical commands ``ltca run`` and ``ltca tca``: a case file in, a run folder and the console tables out.

The analysis itself is :func:`ltca.core.run` (:mod:`ltca.cylindrical.analysis`); this layer locks the folder,
prints and saves.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from ..case import load_case
from ..errors import CaseError
from .loop import analyse, cycle_rolls
from .model import build_model
from .tca import unloaded_tca

__all__ = ["run_case", "run_tca", "cycle_rolls", "analyse", "print_run"]


def _say(enabled: bool):
    def say(msg: str) -> None:
        print(f"  {msg}", file=sys.stderr, flush=True)
    return say if enabled else None


def print_run(head: dict, dataset, name: str, n_pos: int, cycles: int, say=None) -> None:
    """The console output of ``ltca run`` of a cylindrical case: edge contacts (``say``), the headline JSON and the
    tables per torque and of the TE harmonics."""
    from .sweep import harmonics_table, torque_table
    if say is not None:
        for rec in head["torques"]:
            for e in rec.get("edge_contact", []):
                say(f"  edge contact at {rec['torque_nm']:g} N m, {e['edge']} ({e['modelled_as']}): up to "
                    f"{e['max_load_n']:.0f} N at {e['positions']} position(s), roll {min(e['roll_deg']):+.2f} .. "
                    f"{max(e['roll_deg']):+.2f} deg, pinion diameter {e['pinion_diameter_mm'][0]:.2f} .. "
                    f"{e['pinion_diameter_mm'][1]:.2f} mm, peak {e['max_pressure_mpa']:.0f} MPa"
                    + (f" - MESH-DEPENDENT (not a flank pressure): {e['why']}" if e["mesh_dependent"] else ""))
    print(json.dumps({k: head[k] for k in ("torque_nm", "te_loaded_ptp_arcsec", "te_unloaded_ptp_arcsec",
                                           "max_flank_pressure_mpa", "max_flank_pressure_at", "edge_note",
                                           "max_contact_pressure_mpa", "max_root_stress_mpa",
                                           "mesh_stiffness_mean_n_per_mm_um", "max_pairs_in_contact",
                                           "converged", "timings_s") if k in head}, indent=1))
    print(f"{name}: {n_pos} positions per mesh cycle x {cycles} cycle(s), every torque:")
    print(torque_table(head["torques"]))
    print(harmonics_table(dataset))


def run_case(case_path: str, out: str = "out", fidelity: str | None = None, positions: int | None = None,
             progress: bool = True, cache: str | None = None, write: bool = True, resume: bool = False,
             max_output_gb: float = 2.0, torques: list[float] | None = None, paraview_steps: int = 10) -> dict:
    """``ltca run`` of a cylindrical case: the analysis (:func:`ltca.core.run`) into the run folder ``out``
    (checked and locked before any FE work, status in run.json, files atomic, ``resume`` takes over the positions
    an interrupted run finished), then the console tables. Returns the summary as written."""
    from ..driver import run_to_dir
    return run_to_dir(case_path, out, fidelity=fidelity, positions=positions, progress=progress, cache=cache,
                      write=write, resume=resume, max_output_gb=max_output_gb, torques=torques,
                      paraview_steps=paraview_steps)


def run_tca(case_path: str, out: str | None = None, positions: int | None = None) -> dict:
    """Unloaded TCA of a case: TE and contact path over one mesh cycle, contact ratio."""
    from .warnings import check_contact, contact_ratio_transverse, design_warnings
    from ..sizing import MAX_POSITIONS
    case = load_case(case_path)
    model = build_model(case)
    check_contact(model, str(case_path))
    warnings = design_warnings(model)
    for w in warnings:
        print(f"ltca tca: warning: {w}", file=sys.stderr)
    n = positions or case.positions
    if n > MAX_POSITIONS:
        raise CaseError("--positions", n, f"an integer in [1, {MAX_POSITIONS}] (as analysis.positions)")
    rolls = cycle_rolls(n, case.pinion.teeth)
    r = unloaded_tca(model, rolls)
    head = {"case": case.name, "positions": n, "te_unloaded_ptp_arcsec": float(np.ptp(r.te_arcsec)),
            "contact_ratio_transverse": r.eps_alpha, "contact_ratio_overlap": r.eps_beta,
            "working_pressure_angle_deg": float(np.degrees(model.pair.alpha_w)),
            "centre_distance_mm": model.pair.a, "path": {"roll_deg": np.degrees(rolls).tolist(),
                                                         "tooth": r.contact_tooth.tolist(),
                                                         "radius_mm": r.contact_r.tolist(),
                                                         "z_mm": r.contact_z.tolist(),
                                                         "te_arcsec": r.te_arcsec.tolist()},
            "contact_ratio_tip_circles": contact_ratio_transverse(model), "warnings": warnings}
    print(f"{case.name}: eps_alpha = {r.eps_alpha:.4f}, eps_beta = {r.eps_beta:.4f}, "
          f"alpha_wt = {head['working_pressure_angle_deg']:.4f} deg, unloaded TE ptp = "
          f"{head['te_unloaded_ptp_arcsec']:.4f} arcsec")
    print(f"{'roll [deg]':>11} {'tooth':>5} {'r [mm]':>9} {'z [mm]':>8} {'TE [arcsec]':>12}")
    for i in range(n):
        print(f"{np.degrees(rolls[i]):11.3f} {r.contact_tooth[i]:5d} {r.contact_r[i]:9.4f} {r.contact_z[i]:8.3f} "
              f"{r.te_arcsec[i]:12.4f}")
    if out:
        from ..outputs import check_out_dir, write_json_atomic
        check_out_dir(out)
        write_json_atomic(Path(out) / "summary.json", head)
        from matplotlib.figure import Figure
        fig = Figure(figsize=(7, 4))
        ax = fig.add_subplot()
        ax.plot(np.degrees(rolls), r.te_arcsec, "o-")
        ax.set(xlabel="pinion roll from the pitch point [deg]", ylabel="unloaded TE [arcsec]", title=case.name)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        from ..outputs import atomic_path
        with atomic_path(Path(out) / "te_unloaded.png") as tmp:
            fig.savefig(tmp, dpi=110, format="png")
    return head
