"""``ltca bench``: cold wall time of the flagship analysis, medians of several runs, beside its error.

The machines are shared and noisy: each run is a complete cold analysis in a fresh process state
(no mesh cache), and the median and spread are reported. The error column is the pitch-point check
against Hertz for the local line load (the accuracy the speed is bought with)."""
from __future__ import annotations

import time

import numpy as np

from ..case import FIDELITIES, load_case
from ..cylindrical.loaded_model import Fidelity, prepare
from ..cylindrical.model import build_model
from ..cylindrical.run import analyse, cycle_rolls
from .validate import pitch_point_hertz

__all__ = ["run_bench"]


def run_bench(case_path: str, repeat: int = 3, positions: int | None = None, fidelity: str | None = None) -> dict:
    case = load_case(case_path)
    n = positions or case.positions
    name = fidelity or case.fidelity
    stages: dict[str, list[float]] = {k: [] for k in ("geometry", "mesh", "compliance", "contact", "per_position",
                                                     "total")}
    err_p, err_b = [], []
    for i in range(repeat):
        t0 = time.perf_counter()
        model = build_model(case)
        t_geo = time.perf_counter() - t0
        fid = Fidelity.from_preset(FIDELITIES[name], case.module)
        rolls = cycle_rolls(n, case.pinion.teeth)
        lm = prepare(model, fid, rolls, max(case.torques))
        t1 = time.perf_counter()
        analyse(lm, rolls, case.torques[0])
        t_con = time.perf_counter() - t1
        total = time.perf_counter() - t0
        stages["geometry"].append(t_geo + lm.timings["tca"])
        stages["mesh"].append(lm.timings["mesh"])
        stages["compliance"].append(sum(lm.timings[k] for k in ("assembly", "factorisation", "setup", "solves")))
        stages["contact"].append(t_con)
        stages["per_position"].append(t_con / n)
        stages["total"].append(total)
        hc = pitch_point_hertz(lm, case.torques[0])
        err_p.append(hc.p0_error)
        err_b.append(hc.b_error)
        print(f"  run {i + 1}/{repeat}: total {total:.1f} s, per position {t_con / n:.3f} s", flush=True)
    med = {k: float(np.median(v)) for k, v in stages.items()}
    print(f"{case.name}, fidelity '{name}', {n} positions, {repeat} cold runs (median [min, max]):")
    for k, v in stages.items():
        print(f"  {k:14} {np.median(v):8.3f} s  [{min(v):.3f}, {max(v):.3f}]")
    print(f"  pitch-point error vs Hertz: p0 {100 * np.median(err_p):+.2f} %, half-width {100 * np.median(err_b):+.2f} %"
          f"  (dofs {lm.body1.n_dofs} + {lm.body2.n_dofs})")
    return {"median_s": med, "p0_error": float(np.median(err_p)), "b_error": float(np.median(err_b))}
