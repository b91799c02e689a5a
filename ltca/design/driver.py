"""``ltca optimise CASE --out DIR``: the search over the ``[design]`` variables.

A derivative-free optimiser of scipy drives it on the variables scaled to [0, 1], each candidate a full analysis by the case's backend.

Order of work: the ``[design]`` table validated (exit 2 naming the field), the folder locked
(:class:`ltca.outputs.RunDir`), a pressure limit below what any design can reach refused, the bodies' compliance
computed once, the case's own design (baseline) and the start evaluated, an edge constraint that no variable of the
table can act on refused, then the search, the objective map over two variables, the Harris map of the baseline
and the optimum, and the files (:mod:`ltca.design.report`). Every candidate goes to ``history.jsonl`` as it
finishes; ``resume`` replays the finished ones (:mod:`ltca.design.history`).
"""
from __future__ import annotations

import itertools
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import CaseError
from .history import History
from .pool import backend, backend_pool
from .problem import Evaluation
from .schema import DesignSpec, parse_design

__all__ = ["optimise", "Search", "search", "OptimiseResult", "make_backend"]

#: COBYQA's first trust-region radius and its last, on the variables scaled to [0, 1]
TR_START, TR_END = 0.25, 1e-3


class _Budget(Exception):
    """The search used its ``max_evaluations``."""


@dataclass
class Search:
    """The outcome of :func:`search`: the best candidate, every candidate the search asked for, and scipy's word."""

    best: Evaluation
    evaluations: list[Evaluation]
    message: str
    calls: int = 0
    seconds: float = 0.0
    extra: dict = field(default_factory=dict)


def _values(spec: DesignSpec, u: np.ndarray) -> dict:
    u = np.clip(np.asarray(u, float), 0.0, 1.0)
    return {v.name: float(v.lower + ui * (v.upper - v.lower)) for v, ui in zip(spec.variables, u)}


def _unit(spec: DesignSpec, values: dict) -> np.ndarray:
    return np.array([(values[v.name] - v.lower) / (v.upper - v.lower) for v in spec.variables])


def best_of(evaluations: list[Evaluation]) -> Evaluation:
    """The best feasible candidate (smallest objective), or the least infeasible when none is feasible."""
    feasible = [e for e in evaluations if e.feasible]
    if feasible:
        return min(feasible, key=lambda e: e.objective)
    return min(evaluations, key=lambda e: (e.violation, e.objective))


def search(spec: DesignSpec, start: dict, evaluate, scale: float) -> Search:
    """Minimise the penalised objective from ``start`` with the table's optimiser.

    At most ``max_evaluations`` calls of ``evaluate(values) -> Evaluation`` (the start included).

    Parameters
    ----------
    spec : DesignSpec
    start : dict
        Variable name -> start value (within the bounds).
    evaluate : callable
        One candidate's evaluation (cached by the history: a call for a finished candidate is free).
    scale : float
        The start's objective (arcsec): the size of the penalty of an infeasible candidate.
    """
    from scipy.optimize import Bounds, differential_evolution, minimize
    evals: list[Evaluation] = []
    t0 = time.perf_counter()

    def f(u):
        if len(evals) >= spec.max_evaluations:
            raise _Budget
        ev = evaluate(_values(spec, u))
        evals.append(ev)
        return ev.penalised(scale)

    u0 = _unit(spec, start)
    n = len(u0)
    box = Bounds(np.zeros(n), np.ones(n))
    try:
        if spec.optimiser == "cobyqa-corners" and n <= 3:
            # the start, the box's corners and its centre first; then a local search from the best of them
            pts = [u0] + [np.array(c, float) for c in itertools.product((0.0, 1.0), repeat=n)] + [np.full(n, 0.5)]
            vals = [f(p) for p in pts]
            u0 = pts[int(np.argmin(vals))]
        if spec.optimiser in ("cobyqa", "cobyqa-corners"):
            r = minimize(f, u0, method="COBYQA", bounds=box, options=dict(
                maxfev=spec.max_evaluations, initial_tr_radius=TR_START, final_tr_radius=TR_END))
        elif spec.optimiser == "powell":
            r = minimize(f, u0, method="Powell", bounds=box, options=dict(maxfev=spec.max_evaluations, xtol=TR_END))
        elif spec.optimiser == "nelder-mead":
            simplex = np.array([u0] + [np.clip(u0 + TR_START * np.eye(n)[i] * (1 if u0[i] <= 0.5 else -1), 0, 1)
                                       for i in range(n)])
            r = minimize(f, u0, method="Nelder-Mead", bounds=box, options=dict(
                maxfev=spec.max_evaluations, initial_simplex=simplex, xatol=TR_END, fatol=1e-3 * scale))
        else:
            popsize = max(2, spec.max_evaluations // (8 * n))
            r = differential_evolution(f, list(zip(box.lb, box.ub)), x0=u0, popsize=popsize, maxiter=10_000,
                                       seed=spec.seed, polish=False, init="sobol", tol=1e-3)
        message = str(r.message)
    except _Budget:
        message = f"stopped after max_evaluations = {spec.max_evaluations} candidates"
    return Search(best_of(evals), evals, message, len(evals), time.perf_counter() - t0)


@dataclass
class OptimiseResult:
    """What ``ltca optimise`` found and where it wrote it (the keys of ``design.json``)."""

    summary: dict
    out: Path


def _progress(enabled: bool):
    def say(msg: str) -> None:
        if enabled:
            print(f"  {msg}", file=sys.stderr, flush=True)
    return say


def _kind(data: dict) -> str:
    return "bevel" if "bevel" in data else "cylindrical"


def _n_torques(data: dict, file: str) -> int:
    from ..case import check_torques
    load = data.get("load")
    if not isinstance(load, dict) or "torque_nm" not in load:
        raise CaseError("load.torque_nm", None, "required: the torques of the objective", file)
    return len(check_torques(load["torque_nm"], "load.torque_nm", file))


def optimise(case_path: str, out: str, resume: bool = False, progress: bool = True, full_runs: bool = True,
             workers: int | None = None) -> OptimiseResult:
    """Optimise the ``[design]`` variables of a case (see the module docstring).

    Returns the summary written to ``DIR/design.json``.

    ``workers`` processes (default: the cores, at most 2 when not given) compute the objective map and the Harris
    curves in parallel; the search itself is sequential (each candidate depends on the previous ones), but a
    bevel candidate's cycles (torques, tolerance-box corners) run side by side in them.
    """
    from ..case import read_toml
    from ..outputs import RunDir, signature_of
    t_start = time.perf_counter()
    file = str(case_path)
    data = read_toml(case_path)
    kind = _kind(data)
    spec = parse_design(data, kind, _n_torques(data, file), file)
    say = _progress(progress)
    workers = workers or min(2, os.cpu_count() or 1)
    backend = make_backend(kind, data, spec, file, progress=say)
    lim = spec.constraints.max_flank_pressure_mpa
    if lim is not None:
        floor = backend.pressure_floor()
        if lim <= floor:
            raise CaseError("design.constraints.max_flank_pressure_mpa", lim, f"a limit above {floor:.0f} MPa, the "
                            "Hertz pressure of the load spread evenly over the longest contact lines at the top "
                            "torque: no design can meet a lower one", file)
    harris = spec.harris_torque_nm or tuple(float(x) for x in np.round(
        np.linspace(0.125, 1.5, 8) * max(backend.torques_nm), 3))
    with RunDir(out, f"ltca optimise {case_path}", signature_of(case_path, fidelity=backend.fidelity,
                                                                  positions=backend.positions), resume=resume) as rd:
        hist = History(rd.out, spec, resume)
        say(f"{kind} design: {', '.join(spec.names())}; {backend.positions} positions per cycle, fidelity "
            f"'{backend.fidelity}', torques {list(backend.torques_nm)} N m; compliance once ...")
        backend.prepare(max(harris))
        say(f"compliance computed once in {backend.prepare_seconds:.1f} s")
        base = backend.baseline()
        start = {v.name: (v.start if v.start is not None else float(np.clip(base[v.name], v.lower, v.upper)))
                 for v in spec.variables}

        def evaluate(role):
            def ev(values):
                e = hist.evaluation(values, role, backend.evaluate)
                say(f"{role} {len(hist.candidates())}: " + ", ".join(f"{k} {x:.4g}" for k, x in values.items())
                    + f" -> objective {e.objective:.3f} arcsec" + ("" if e.feasible else
                                                                   f" (infeasible, violation {e.violation:.3g})"))
                return e
            return ev
        with backend_pool(backend, workers) as pool:
            # the pool's workers hold the prepared backend; a backend that can runs a candidate's cycles in it
            backend.pool = pool
            try:
                ev_base = evaluate("baseline")(base)
                ev_start = evaluate("start")(start)
                _check_edges(spec, backend, ev_start, file)
                found = search(spec, start, evaluate("search"), max(ev_start.objective, 1e-6))
            finally:
                backend.pool = None
            best = found.best
            say(f"optimum after {found.calls} candidates: " + ", ".join(f"{k} {x:.4g}" for k, x in
                                                                       best.values.items())
                + f", objective {best.objective:.3f} arcsec (start {ev_start.objective:.3f}); {found.message}")
            designs = (("baseline", base), ("optimum", best.values))
            grid = _objective_map(spec, best.values, hist, evaluate("map"), pool)
            if pool is not None:
                todo = [v for _, v in designs if not hist.has(v, harris)]
                for v, te in zip(todo, pool.starmap(_curve, [(v, harris) for v in todo])):
                    hist.curve(v, harris, lambda *_, te=te: te)
        curves = {name: hist.curve(vals, harris, backend.te_ptp) for name, vals in designs}
        from .report import write_results
        summary = write_results(rd.out, case_path, spec, backend, hist, found, ev_base, ev_start, grid, harris,
                                curves, full_runs, say)
        summary["workers"] = workers
        summary["timings_s"]["total"] = round(time.perf_counter() - t_start, 3)
        from ..outputs import write_json_atomic
        write_json_atomic(rd.out / "design.json", summary)
    return OptimiseResult(summary, Path(out))


def make_backend(kind: str, data: dict, spec: DesignSpec, file: str | None = None, progress=None):
    """The backend of a case kind, checked but not yet prepared (cheap)."""
    if kind == "cylindrical":
        from .cylindrical import CylindricalBackend
        return CylindricalBackend(data, spec, file, progress)
    if kind == "bevel":
        from .bevel import BevelBackend
        return BevelBackend(data, spec, file, progress)
    raise CaseError("design", "[table]", f"a cylindrical case: the {kind} design backend (synthesis, TCA and LTCA "
                    "per candidate) is not available yet", file)


def _check_edges(spec: DesignSpec, backend, ev_start: Evaluation, file: str) -> None:
    """An edge constraint the start violates and no variable of the table can act on is impossible: exit 2."""
    tol = spec.constraints.misalignment_um
    if tol > 0 and ev_start.edge_violation > 0 and not set(backend.lead_variables) & set(spec.names()):
        raise CaseError("design.constraints.misalignment_um", tol, "a tolerance the design can meet: at +-"
                        f"{tol:g} um the start puts {100 * ev_start.edge_violation:.1f} % of the load on "
                        f"{', '.join(spec.constraints.edges)}, and no variable of [design.variables] moves the "
                        f"contact along the face ({', '.join(backend.lead_variables)})", file)


def _measure(values: dict):
    return backend().evaluate(values)


def _curve(values: dict, torques) -> list[float]:
    return backend().te_ptp(values, torques)


def _objective_map(spec: DesignSpec, at: dict, hist: History, evaluate, pool) -> dict | None:
    """The objective over the two map variables (``map_points`` each), the others at ``at``.

    The points not on file computed by ``pool`` (in parallel) and recorded as each finishes.
    """
    if spec.map_variables is None or spec.map_points < 2:
        return None
    a, b = (next(v for v in spec.variables if v.name == n) for n in spec.map_variables)
    xa = np.linspace(a.lower, a.upper, spec.map_points)
    xb = np.linspace(b.lower, b.upper, spec.map_points)
    points = [{**at, a.name: float(x), b.name: float(y)} for x in xa for y in xb]
    if pool is not None:
        todo = [p for p in points if not hist.has(p)]
        for p, m in zip(todo, pool.imap(_measure, todo)):
            hist.evaluation(p, "map", lambda v, m=m: m)
    evs = [[evaluate({**at, a.name: float(x), b.name: float(y)}) for y in xb] for x in xa]
    return {"variables": [a.name, b.name], "x": xa.tolist(), "y": xb.tolist(),
            "objective": [[e.objective for e in row] for row in evs],
            "feasible": [[e.feasible for e in row] for row in evs],
            "te_ptp_arcsec": [[list(e.measures.te_ptp_arcsec) for e in row] for row in evs]}
