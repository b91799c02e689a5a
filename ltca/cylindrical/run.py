"""The analyses behind ``ltca run`` and ``ltca tca``: case file in, result files out."""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from ..case import FIDELITIES, load_case
from ..errors import CaseError
from geometry.pair import rotation_z

from .edges import edge_summary, position_edges
from .loaded import PositionResult, solve_position, weights_of
from .loaded_model import Fidelity, LoadedModel, prepare
from .model import build_model
from .results import position_dataset, summary
from .tca import ARCSEC_PER_RAD, unloaded_tca
from .warnings import pressure_warnings

__all__ = ["run_case", "run_tca", "cycle_rolls", "analyse"]


def cycle_rolls(n: int, z1: int, cycles: int = 1) -> np.ndarray:
    """``n`` pinion roll angles (rad) per mesh cycle over ``cycles`` cycles, starting half a cycle before
    the pitch point of tooth 0."""
    return (np.arange(n * cycles) / n - 0.5) * 2 * np.pi / z1


def _progress(enabled: bool):
    def say(msg: str) -> None:
        if enabled:
            print(f"  {msg}", file=sys.stderr, flush=True)
    return say


def _log_line(lm: LoadedModel, torque: float, warm: PositionResult) -> dict:
    return {"torque_nm": torque * 1e-3, "roll_deg": float(np.degrees(warm.roll)),
            "te_loaded_arcsec": warm.theta / lm.model.pair.ratio * ARCSEC_PER_RAD,
            "max_pressure_mpa": warm.max_pressure,
            "max_flank_pressure_mpa": position_edges(lm, warm, torque)["flank_peak"],
            "pair_load_n": {str(k): v for k, v in warm.pair_load.items()},
            "root_stress_mpa": {"pinion": warm.root1, "gear": warm.root2}}


def analyse(lm: LoadedModel, rolls: np.ndarray, torque: float, progress: bool = False,
            log: Path | None = None, store=None, it: int = 0, lines: list | None = None) -> list[PositionResult]:
    """Loaded contact at every roll angle, warm-started from the previous position.

    With ``log``, each finished position is appended to that JSON-lines file at once, so a crash
    loses nothing already finished. With ``store`` (:class:`ltca.outputs.PositionStore`), each finished position is
    also kept whole, and positions already in the store (``--resume``) are taken over instead of computed."""
    from threadpoolctl import threadpool_limits

    from .tca import split_roll
    out: list[PositionResult] = []
    steps = list(zip(*split_roll(lm.model, np.asarray(rolls))))
    if progress:
        from tqdm import tqdm
        steps = tqdm(steps, desc=f"positions at {torque * 1e-3:g} N m", unit="pos", file=sys.stderr)
    warm = None
    # small dense factorisations: one BLAS thread is faster than two fighting for the cores (the limit is set once
    # for the loop: setting it inspects the loaded libraries, ~3 ms a position)
    with threadpool_limits(limits=1, user_api="blas"):
        for k, (r, n) in enumerate(steps):
            old = store.load(it, k) if store is not None else None
            if old is not None:
                warm = old
                store.taken_over += 1
                store.dirty = True
                lines.append(_log_line(lm, torque, warm))
                out.append(warm)
                continue
            warm = solve_position(lm, float(r), torque, warm=warm, cycle=int(n))
            out.append(warm)
            if store is not None:
                if store.dirty:       # the log of the positions taken over, rewritten once before the first new one
                    store.rewrite_log(lines)
                    store.dirty = False
                lines.append(_log_line(lm, torque, warm))
                store.save(it, k, warm, lines[-1])
                store.computed += 1
            elif log is not None:
                with open(log, "a") as fh:
                    fh.write(json.dumps(_log_line(lm, torque, warm)) + "\n")
    return out


def run_case(case_path: str, out: str = "out", fidelity: str | None = None, positions: int | None = None,
             progress: bool = True, cache: str | None = None, write: bool = True, resume: bool = False,
             max_output_gb: float = 2.0, torques: list[float] | None = None, paraview_steps: int = 10) -> dict:
    """Loaded analysis of a case over one mesh cycle; writes summary.json, results.nc, plots, VTU, report.html and
    the ParaView series (``paraview_steps`` positions of the first torque, 0: none; :mod:`.paraview`).

    The output folder is checked and locked before any work, its status kept in run.json, every file written
    atomically; ``resume`` takes over the positions an interrupted run finished (:mod:`ltca.outputs`).
    ``torques`` (N m) replace the case's ``[load] torque_nm`` (``--torque``)."""
    import contextlib
    with contextlib.ExitStack() as stack:
        return _run_case(stack, case_path, out, fidelity, positions, progress, cache, write, resume, max_output_gb,
                         torques, paraview_steps)


def _run_case(stack, case_path, out, fidelity, positions, progress, cache, write, resume, max_output_gb,
              torques=None, paraview_steps=10) -> dict:
    from ..outputs import PositionStore, RunDir, signature_of
    from ..sizing import check_run_size
    from .limits import check_limits
    from .warnings import check_contact, convergence_warnings, design_warnings
    t_start = time.perf_counter()
    case = load_case(case_path)
    if torques is not None:
        import dataclasses

        from ..case import check_torques
        case = dataclasses.replace(case, torques=tuple(1e3 * t for t in check_torques(list(torques), "--torque")))
    say = _progress(progress)
    fid_name = fidelity or case.fidelity
    if fid_name not in FIDELITIES:
        raise CaseError("--fidelity", fid_name, f"one of {sorted(FIDELITIES)}")
    t0 = time.perf_counter()
    model = build_model(case)
    check_contact(model, str(case_path))
    t_geom = time.perf_counter() - t0
    from .sampling import default_positions, sampling_warnings
    n_pos = positions or (default_positions(model) if case.positions_auto else case.positions)
    check_run_size(case, n_pos, FIDELITIES[fid_name], max_output_gb)
    check_limits(model, FIDELITIES[fid_name], fid_name, str(case_path))   # body size, edge zones: before any FE
    store = None
    if write:           # the output folder: checked, locked and cleaned before any FE work
        rd = stack.enter_context(RunDir(out, f"ltca run {case_path}", signature_of(
            case_path, fidelity=fid_name, positions=n_pos, torques_nm=[t * 1e-3 for t in case.torques]),
            resume=resume))
        store = PositionStore(rd.out)
    warnings = design_warnings(model) + sampling_warnings(model, n_pos)
    for w in warnings:
        print(f"ltca run: warning: {w}", file=sys.stderr)
    fid = Fidelity.from_preset(FIDELITIES[fid_name], case.module)
    rolls = cycle_rolls(n_pos, case.pinion.teeth, case.cycles)
    say(f"{case.name}: {n_pos} positions per cycle x {case.cycles} cycle(s), fidelity '{fid_name}' "
        f"(flank elements {fid.h_flank:.2f} mm)")
    lm = prepare(model, fid, cycle_rolls(n_pos, case.pinion.teeth), max(case.torques), cache_dir=cache,
                 progress=say)
    outdir = Path(out)
    summaries, datasets, first, lines, unconverged = [], [], None, [], []
    for it, torque in enumerate(case.torques):
        t0 = time.perf_counter()
        results = analyse(lm, rolls, torque, progress, None, store=store, it=it, lines=lines)
        first = first or results
        t_contact = time.perf_counter() - t0
        ds = position_dataset(lm, results, torque)
        timings = {"geometry": t_geom + lm.timings["tca"], "mesh": lm.timings["mesh"],
                   "compliance": sum(lm.timings[k] for k in ("assembly", "factorisation", "setup", "solves")),
                   "contact": t_contact, "contact_per_position": t_contact / len(rolls),
                   "total": time.perf_counter() - t_start}
        converged = all(r.residual < 1e-6 for r in results)
        summaries.append(summary(lm, ds, timings, converged, edge_summary(lm, results, torque)))
        unconverged += convergence_warnings(results, torque * 1e-3)
        warnings_t = warnings + pressure_warnings(case, summaries[-1]) + convergence_warnings(results, torque * 1e-3)
        summaries[-1]["warnings"] = warnings_t
        datasets.append(ds)
        head = summaries[-1]
        at = head.get("max_flank_pressure_at", {})
        say(f"T = {torque * 1e-3:g} N m: loaded TE ptp {head['te_loaded_ptp_arcsec']:.2f} arcsec, "
            f"max flank pressure {head['max_flank_pressure_mpa']:.0f} MPa at roll {at.get('roll_deg', 0):+.2f} deg, "
            f"pinion diameter {at.get('pinion_diameter_mm', 0):.2f} mm, z {at.get('z_mm', 0):+.2f} mm "
            f"({t_contact:.1f} s)")
        for e in head["edge_contact"]:
            say(f"  edge contact, {e['edge']} ({e['modelled_as']}): up to {e['max_load_n']:.0f} N at "
                f"{e['positions']} position(s), roll {min(e['roll_deg']):+.2f} .. {max(e['roll_deg']):+.2f} deg, "
                f"pinion diameter {e['pinion_diameter_mm'][0]:.2f} .. {e['pinion_diameter_mm'][1]:.2f} mm, "
                f"peak {e['max_pressure_mpa']:.0f} MPa" + (" - MESH-DEPENDENT (not a flank pressure): "
                                                           f"{e['why']}" if e["mesh_dependent"] else ""))
    from .sweep import harmonics_table, run_dataset, torque_record, torque_table
    all_ds = run_dataset(datasets, n_pos, case.cycles, case.pinion.teeth)
    records = [torque_record(all_ds, h) for h in summaries]
    # the top-level single-torque keys are the first torque's; "torques" holds every torque's figures
    head = dict(summaries[0])
    head["torques"] = records
    head["warnings"] = list(dict.fromkeys(w for h in summaries for w in h["warnings"]))
    head["timings_s"]["total"] = round(time.perf_counter() - t_start, 3)
    for w in head["warnings"][len(warnings):]:
        print(f"ltca run: warning: {w}", file=sys.stderr)
    if write:
        from ..outputs import staging, write_json_atomic, write_netcdf_atomic
        from .report import plot_all, write_vtu
        from .sweep import NC_ENCODING
        if store.dirty:                    # every position was taken over: the log in order
            store.rewrite_log(lines)
        head["positions_computed"], head["positions_taken_over"] = store.computed, store.taken_over
        say(f"positions computed {store.computed}, taken over from the interrupted run {store.taken_over}")
        # every file is written into a staging folder and renamed into place; summary.json last
        with staging(outdir) as stage:
            write_netcdf_atomic(stage / "results.nc", all_ds, NC_ENCODING)  # in memory first: HDF5 aborts on ENOSPC
            plot_all(all_ds, stage, case.name)
            k = int(np.argmax(datasets[0].max_pressure.values))
            r = first[k]
            W1, W2 = weights_of(lm, r)
            write_vtu(stage / "pinion_loaded.vtu", lm.body1, W1.T @ r.force, rotation_z(model.phi_pitch - r.roll))
            write_vtu(stage / "gear_loaded.vtu", lm.body2, W2.T @ r.force,
                      model.pair.gear_frame(model.phi_pitch - r.roll))
            pv = None
            if paraview_steps:
                from .paraview import write_series
                t0 = time.perf_counter()
                pv = write_series(stage, lm, first, case.torques[0], steps=paraview_steps)
                head["timings_s"]["paraview"] = round(time.perf_counter() - t0, 3)
                head["paraview"] = {"pvd": "paraview.pvd", "torque_nm": case.torques[0] * 1e-3,
                                    "roll_deg": pv["roll_deg"], "flank_peak_mpa": pv["flank_peak_mpa"]}
            from .html_report import write_run_report
            t0 = time.perf_counter()
            extra = write_run_report(stage, lm, case_path, head, all_ds, n_pos, fid_name, unconverged,
                                     head["timings_s"], "paraview.pvd" if pv else None)
            head["timings_s"]["report"] = round(time.perf_counter() - t0, 3)
            head["iso6336"] = extra["comparisons"]
            head["striping_index"] = {f"{t:g}": round(v, 4) for t, v in extra["striping"].items()}
        write_json_atomic(outdir / "summary.json", head)
        say(f"wrote {outdir}/summary.json, report.html, results.nc, te.png, te_ptp.png, te_harmonics.png, "
            "load_sharing.png, bearing_pattern.png, bearing_pattern_diameter.png, root_stress.png, pinion_loaded.vtu, "
            "gear_loaded.vtu" + (", paraview.pvd" if pv else ""))
    print(json.dumps({k: head[k] for k in ("torque_nm", "te_loaded_ptp_arcsec", "te_unloaded_ptp_arcsec",
                                           "max_flank_pressure_mpa", "max_flank_pressure_at", "edge_note",
                                           "max_contact_pressure_mpa", "max_root_stress_mpa",
                                           "mesh_stiffness_mean_n_per_mm_um", "max_pairs_in_contact",
                                           "converged", "timings_s")}, indent=1))
    print(f"{case.name}: {n_pos} positions per mesh cycle x {case.cycles} cycle(s), every torque:")
    print(torque_table(records))
    print(harmonics_table(all_ds))
    return head


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
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4))
        ax.plot(np.degrees(rolls), r.te_arcsec, "o-")
        ax.set(xlabel="pinion roll from the pitch point [deg]", ylabel="unloaded TE [arcsec]", title=case.name)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        from ..outputs import atomic_path
        with atomic_path(Path(out) / "te_unloaded.png") as tmp:
            fig.savefig(tmp, dpi=110, format="png")
        plt.close(fig)
    return head
