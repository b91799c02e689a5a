"""Spiral bevel ``ltca run``: pinion synthesis, both bodies' compliance, the loaded contact over a mesh cycle at
every torque of the case (working flank for positive, coast flank for negative pinion torques), and the outputs
(:mod:`ltca.bevel.results`): summary.json, results.nc, bearing_pattern_*.vtu and the plots.
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from geometry.bevel.blank import design_blank
from geometry.bevel.design import synthesize_pinion
from geometry.bevel.generation import standard_gear_cut
from geometry.bevel.tca import Assembly, BevelPair

from ..validation import DesignError
from .case import load_bevel_case
from .loaded import BevelPosition, solve_position
from .loaded_model import BevelBodies, BevelFidelity, loaded_model, prepare_bodies

__all__ = ["build_pair", "cycle_positions", "analyse_torque", "run_bevel_ltca"]

FLANK = {"concave": "working", "convex": "coast"}


def build_pair(case: dict) -> BevelPair:
    """The gear (standard cut) and the pinion synthesised for the case's targets, or the pair cut as the case's
    settings sheets give it."""
    bl = design_blank(case["basic"])
    if case.get("cuts"):
        return BevelPair(bl, case["cuts"]["gear"], case["cuts"]["pinion"])
    gear = standard_gear_cut(bl)
    pin, _ = synthesize_pinion(bl, gear, case["targets"], blank_offset=case["blank_offset"])
    return BevelPair(bl, gear, pin)


def cycle_positions(n: int, z1: int) -> np.ndarray:
    """``n`` pinion angles over one mesh cycle 2 pi / z1, centred on the mean point (rad)."""
    return (np.arange(n) / n - 0.5) * 2 * np.pi / z1


def analyse_torque(lm, phi: np.ndarray, torque_nm: float, progress: bool = False) -> list[BevelPosition]:
    """The loaded contact at the pinion angles ``phi`` under |torque_nm| (N m) on the model's flank."""
    out = []
    t0 = time.perf_counter()
    for k, p in enumerate(phi):
        out.append(solve_position(lm, float(p), abs(torque_nm) * 1e3))
        if progress:
            r = out[-1]
            print(f"  {FLANK[lm.side]} {torque_nm:g} N m: position {k + 1}/{len(phi)}  TE {r.te / 4.8481368e-6:8.2f} "
                  f"arcsec  p_max {r.max_pressure:7.0f} MPa  ({time.perf_counter() - t0:.1f} s)", file=sys.stderr)
    return out


def run_bevel_ltca(case_path: str, out: str = "out", positions: int | None = None, fidelity: str | None = None,
                   torques: list[float] | None = None, progress: bool = True, cache: str | None = None,
                   assembly: Assembly | None = None) -> dict:
    """Synthesise, mesh, load and solve a bevel case over one mesh cycle per torque; write the outputs.

    Parameters
    ----------
    case_path : str
        TOML case with [bevel] and [load] (pinion torque_nm, a number or a list; the sign picks the flank).
    out : str
        Output directory.
    positions, fidelity, torques : optional
        Override [analysis] positions / fidelity and [load] torque_nm.
    cache : str, optional
        Mesh cache directory.
    assembly : Assembly, optional
        Overrides the case's [assembly].

    Returns
    -------
    dict
        The summary (also written to ``summary.json``).
    """
    case = load_bevel_case(case_path)
    tq = tuple(torques) if torques else case["torques"]
    if not tq:
        raise DesignError("no torque to analyse", ("load.torque_nm",), "add [load] torque_nm = [..] (N m, pinion)",
                          file=str(case_path))
    n = positions or case["positions"]
    fid = BevelFidelity.named(fidelity or case["fidelity"])
    asm = assembly or Assembly(**case["assembly"])
    d = Path(out)
    d.mkdir(parents=True, exist_ok=True)
    timings = {}
    t0 = time.perf_counter()
    pair = build_pair(case)
    timings["synthesis"] = time.perf_counter() - t0
    say = (lambda m: print(m, file=sys.stderr)) if progress else None
    bodies: dict[str, BevelBodies] = {}
    runs = {}
    for T in tq:
        side = "concave" if T > 0 else "convex"
        if side not in bodies:
            t1 = time.perf_counter()
            bodies[side] = prepare_bodies(pair, side, fid, case["young"], case["poisson"], cache, say,
                                          mounting=case["mounting"])
            timings[f"compliance_{FLANK[side]}"] = time.perf_counter() - t1
            t1 = time.perf_counter()
            runs[side] = {"lm": loaded_model(pair, bodies[side], asm)}
            timings[f"reference_{FLANK[side]}"] = time.perf_counter() - t1
        t1 = time.perf_counter()
        phi = cycle_positions(n, pair.blank.pinion.z)
        runs[side][T] = analyse_torque(runs[side]["lm"], phi, T, progress)
        timings[f"torque_{T:g}"] = time.perf_counter() - t1
    from .results import write_outputs
    summary = write_outputs(d, case, pair, asm, fid, runs, tq, timings)
    print(f"Spiral bevel LTCA: {case['name']} ({fid.name}, {n} positions per cycle, assembly E {asm.E:g} P {asm.P:g} "
          f"G {asm.G:g} mm)")
    print(f"{'torque N m':>10s} {'flank':8s} {'TE p-p loaded':>13s} {'unloaded':>9s} {'p int MPa':>10s} "
          f"{'p edge MPa':>10s} {'max share':>9s} {'root MPa':>9s} {'k N/um':>7s}  edges")
    for T, t in summary["torques"].items():
        print(f"{float(T):10g} {t['flank']:8s} {t['te_pp_loaded_arcsec']:13.2f} {t['te_pp_unloaded_arcsec']:9.2f} "
              f"{t['peak_pressure_interior_mpa']:10.0f} {t['peak_pressure_mpa']:10.0f} {t['max_pair_share']:9.3f} "
              f"{t['root_stress_pinion_mpa']:9.0f} {t['mesh_stiffness_mean_n_per_um']:7.0f}  "
              f"{', '.join(t['edge_locations']) or '-'}")
    print("TE in arcsec; p int: peak pressure away from the flank edges (its convergence: ltca convergence); "
          "p edge: with the edge cells (singular at a sharp edge, grows as the cells shrink)")
    return summary
