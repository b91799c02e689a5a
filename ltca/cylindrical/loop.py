"""The position loop of a cylindrical run: the loaded contact at every roll angle of one torque, warm-started,
each finished position logged or stored as it finishes."""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from .edges import position_edges
from .loaded import PositionResult, solve_position
from .loaded_model import LoadedModel
from .tca import ARCSEC_PER_RAD

__all__ = ["cycle_rolls", "analyse", "log_line"]


def cycle_rolls(n: int, z1: int, cycles: int = 1) -> np.ndarray:
    """``n`` pinion roll angles (rad) per mesh cycle over ``cycles`` cycles, starting half a cycle before
    the pitch point of tooth 0."""
    return (np.arange(n * cycles) / n - 0.5) * 2 * np.pi / z1


def log_line(lm: LoadedModel, torque: float, warm: PositionResult) -> dict:
    """The JSON line of one finished position (engineer's units) in ``positions.jsonl``."""
    return {"torque_nm": torque * 1e-3, "roll_deg": float(np.degrees(warm.roll)),
            "te_loaded_arcsec": warm.theta / lm.model.pair.ratio * ARCSEC_PER_RAD,
            "max_pressure_mpa": warm.max_pressure,
            "max_flank_pressure_mpa": position_edges(lm, warm, torque)["flank_peak"],
            "pair_load_n": {str(k): v for k, v in warm.pair_load.items()},
            "root_stress_mpa": {"pinion": warm.root1, "gear": warm.root2}}


def analyse(lm: LoadedModel, rolls: np.ndarray, torque: float, progress: bool = False,
            log: Path | None = None, store=None, it: int = 0, lines: list | None = None,
            threads: int = 1) -> list[PositionResult]:
    """Loaded contact at every roll angle, warm-started from the previous position.

    With ``log``, each finished position is appended to that JSON-lines file at once, so a crash
    loses nothing already finished. With ``store`` (:class:`ltca.outputs.PositionStore`), each finished position is
    also kept whole, and positions already in the store (``--resume``) are taken over instead of computed.
    ``threads`` runs of consecutive positions are solved side by side (:func:`ltca.position_runs.solve_positions`)."""
    from threadpoolctl import threadpool_limits

    from ..position_runs import solve_positions
    from .tca import split_roll
    steps = list(zip(*split_roll(lm.model, np.asarray(rolls))))
    bar = None
    if progress:
        from tqdm import tqdm
        bar = tqdm(total=len(steps), desc=f"positions at {torque * 1e-3:g} N m", unit="pos", file=sys.stderr)

    def done(k: int, res: PositionResult) -> None:
        if log is not None and store is None:
            with open(log, "a") as fh:
                fh.write(json.dumps(log_line(lm, torque, res)) + "\n")
        if bar is not None:
            bar.update(1)

    def solve(k: int, warm: PositionResult | None) -> PositionResult:
        r, n = steps[k]
        return solve_position(lm, float(r), torque, warm=warm, cycle=int(n))

    # small dense factorisations: one BLAS thread is faster than two fighting for the cores (the limit is set once
    # for the loop: setting it inspects the loaded libraries, ~3 ms a position)
    try:
        with threadpool_limits(limits=1, user_api="blas"):
            return solve_positions(len(steps), solve, lambda k, res: log_line(lm, torque, res), store=store, it=it,
                                   lines=lines, threads=threads, done=done)
    finally:
        if bar is not None:
            bar.close()
