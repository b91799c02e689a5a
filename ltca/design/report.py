"""The files of ``ltca optimise``: the optimum's settings beside the baseline's, both designs as case files and
their full LTCA outputs, the check of the compliance reuse, the design rule, the plots and ``design.json``.

``DIR/``
    ``design.json`` (this module's summary), ``history.jsonl`` (:mod:`ltca.design.history`), ``settings.csv``
    (case key, baseline, optimum), bevel: ``seed_vs_optimum.csv`` (:mod:`ltca.design.compare`), ``baseline.toml``
    and ``optimum.toml`` (the case with each design, without its [design] table), ``baseline/`` and ``optimum/``
    (``ltca run`` of those files: summary.json, results.nc, plots), ``harris_map.png``, ``objective_map.png``,
    ``history.png``.

The full runs compute the compliance afresh: their loaded TE against the candidate's (computed on the reused
compliance) is the measured error of the reuse (``full_analysis`` in design.json).
"""
from __future__ import annotations

import contextlib
import io
from pathlib import Path

import numpy as np

from ..outputs import atomic_path, write_bytes_atomic
from .history import History
from .problem import Evaluation
from .schema import VARIABLES, DesignSpec

__all__ = ["write_results", "evaluation_record", "timing_record"]


def evaluation_record(ev: Evaluation, torques_nm) -> dict:
    """One candidate for design.json: values, objective, feasibility and the per-torque measures."""
    m = ev.measures
    return {"values": ev.values, "objective_arcsec": round(ev.objective, 6), "feasible": ev.feasible,
            "pressure_violation": ev.pressure_violation, "edge_violation": ev.edge_violation,
            "te_ptp_arcsec": dict(zip([f"{t:g}" for t in torques_nm], m.te_ptp_arcsec)),
            "max_flank_pressure_mpa": dict(zip([f"{t:g}" for t in torques_nm], m.flank_pressure_mpa)),
            "edge_share_under_misalignment": m.edge_share}


def timing_record(hist: History) -> dict:
    """Wall time per candidate per torque (one contact cycle), s: the median and largest over the search's
    candidates (one at a time) and the median over the map's (computed side by side by the workers)."""
    out = {}
    for role in ("search", "map"):
        per = [r["seconds"] / max(r["cycles"], 1) for r in hist.candidates(role)]
        if per:
            out[f"{role}_per_candidate_per_torque_median"] = round(float(np.median(per)), 4)
            out[f"{role}_per_candidate_per_torque_max"] = round(float(np.max(per)), 4)
    return out


def _toml(path: Path, data: dict) -> None:
    from ..case import to_toml
    write_bytes_atomic(path, (to_toml(data) + "\n").encode())


def _full_run(path: Path, out: Path, backend) -> dict:
    """``ltca run`` of a design's case file (compliance computed afresh), its console output kept out."""
    if hasattr(backend, "full_run"):
        return backend.full_run(path, out)
    from ..driver import run_to_dir as run_case
    with contextlib.redirect_stdout(io.StringIO()):
        head = run_case(str(path), out=str(out), fidelity=backend.fidelity, positions=backend.positions,
                        progress=False)
    return {f"{r['torque_nm']:g}": r["te_loaded_ptp_arcsec"] for r in head["torques"]}


def write_results(out: Path, case_path, spec: DesignSpec, backend, hist: History, found, ev_base: Evaluation,
                  ev_start: Evaluation, grid: dict | None, harris, curves: dict, full_runs: bool, say) -> dict:
    """Write every file of the optimisation folder (the module docstring) and return the summary."""
    import time
    t0 = time.perf_counter()
    best = found.best
    torques = backend.torques_nm
    offered = VARIABLES[spec.kind]
    variables = [{"name": v.name, "unit": offered[v.name].unit, "member": v.member, "lower": v.lower,
                  "upper": v.upper, "baseline": ev_base.values[v.name], "start": ev_start.values[v.name],
                  "optimum": best.values[v.name]} for v in spec.variables]
    s_base, s_opt = backend.settings(ev_base.values), backend.settings(best.values)
    settings = [{"key": k, "baseline": s_base[k], "optimum": s_opt[k]} for k in s_opt]
    text = "key,baseline,optimum\n" + "".join(f"{r['key']},{r['baseline']:.6g},{r['optimum']:.6g}\n"
                                             for r in settings)
    write_bytes_atomic(out / "settings.csv", text.encode())
    full = {}
    for name, ev in (("baseline", ev_base), ("optimum", best)):
        _toml(out / f"{name}.toml", backend.case_dict(ev.values))
        if full_runs and name == "optimum":
            say(f"full LTCA of the {name} (compliance afresh) -> {out / name}")
            reused = dict(zip([f"{t:g}" for t in torques], ev.measures.te_ptp_arcsec))
            try:
                fresh = _full_run(out / f"{name}.toml", out / name, backend)
            except (ValueError, ArithmeticError, RuntimeError) as exc:
                # a fresh body the mesher cannot build (measured: a synthesised bevel pinion whose flank grid does
                # not converge near the root) must not lose the search: the failure is the result
                say(f"full LTCA of the {name} failed: {type(exc).__name__}: {exc}")
                full[name] = {"failure": f"{type(exc).__name__}: {exc}"[:400],
                              "te_ptp_arcsec_reused_compliance": reused}
                continue
            full[name] = {"te_ptp_arcsec": fresh, "te_ptp_arcsec_reused_compliance": reused,
                          "reuse_error_relative": {k: abs(reused[k] - fresh[k]) / max(abs(fresh[k]), 1e-12)
                                                   for k in fresh}}
    summary = {
        "case": str(case_path), "kind": spec.kind, "objective": spec.objective, "weights": list(spec.weights),
        "torques_nm": list(torques), "positions": backend.positions, "fidelity": backend.fidelity,
        "variables": variables,
        "constraints": {"max_flank_pressure_mpa": spec.constraints.max_flank_pressure_mpa,
                        "misalignment_um": spec.constraints.misalignment_um, "edges": list(spec.constraints.edges),
                        "edge_margin_mm": spec.constraints.edge_margin_mm,
                        "max_edge_share": spec.constraints.max_edge_share,
                        "tolerance_box_mm": list(spec.constraints.tolerance_box)},
        "optimiser": spec.optimiser, "message": found.message,
        "evaluations": {"search": found.calls, "max_evaluations": spec.max_evaluations,
                        "candidates": len(hist.candidates()), "map": len(hist.candidates("map")),
                        "taken_over_from_history": hist.taken_over},
        "baseline": evaluation_record(ev_base, torques), "start": evaluation_record(ev_start, torques),
        "optimum": evaluation_record(best, torques), "settings": settings,
        "harris": {"torque_nm": list(harris), **curves}, "map": grid, "full_analysis": full,
        "timings_s": {"compliance_once": round(backend.prepare_seconds, 3), **timing_record(hist),
                      "search": round(found.seconds, 3)},
    }
    if hasattr(backend, "box_report"):
        say("the baseline and the optimum over the tolerance box at the top torque ...")
        summary["tolerance_box"] = {name: backend.box_report(ev.values) for name, ev in (("baseline", ev_base),
                                                                                        ("optimum", best))}
        from .compare import seed_table, table_csv
        evs = {"baseline": ev_base, "optimum": best}
        summary["seed_vs_optimum"] = seed_table(
            torques, {"baseline": s_base, "optimum": s_opt},
            {n: list(e.measures.te_ptp_arcsec) for n, e in evs.items()}, summary["tolerance_box"],
            {n: e.feasible for n, e in evs.items()}, spec.constraints.tolerance_box)
        write_bytes_atomic(out / "seed_vs_optimum.csv", table_csv(summary["seed_vs_optimum"]).encode())
    if hasattr(backend, "pair_deflection_um"):
        summary["design_rule"] = _design_rule(backend, best, max(torques))
    from .plots import plot_harris, plot_history, plot_map
    for name, fn, args in (("harris_map.png", plot_harris, (harris, curves)),
                           ("objective_map.png", plot_map, (grid, spec, ev_base, ev_start, best, found, torques)),
                           ("history.png", plot_history, (hist,))):
        fig = fn(*args, title=Path(str(case_path)).stem)
        if fig is None:
            continue
        with atomic_path(out / name) as tmp:
            fig.savefig(tmp, dpi=110, format="png")
        import matplotlib.pyplot as plt
        plt.close(fig)
    summary["timings_s"]["results"] = round(time.perf_counter() - t0, 3)
    return summary


def _design_rule(backend, best: Evaluation, torque_nm: float) -> dict:
    """The classic rule beside the optimum: linear tip relief = the tooth-pair deflection at the design load,
    from our own LTCA's single-pair mesh stiffness (:meth:`CylindricalBackend.pair_deflection_um`)."""
    rule = backend.pair_deflection_um(torque_nm)
    rec = {"torque_nm": torque_nm, **rule}
    if "tip_relief_um" in best.values:
        rec["optimal_tip_relief_um"] = best.values["tip_relief_um"]
        rec["relief_over_deflection"] = best.values["tip_relief_um"] / rule["deflection_um"]
    return rec
