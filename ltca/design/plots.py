"""Figures of ``ltca optimise``: the Harris map, the objective map over two variables, the search history.

Each function returns a matplotlib Figure (Agg backend) or None when there is nothing to draw; the caller writes it
atomically (:mod:`ltca.design.report`).
"""
from __future__ import annotations

import numpy as np

from .history import History
from .problem import Evaluation
from .schema import DesignSpec

__all__ = ["plot_harris", "plot_map", "plot_history"]


def _plt():
    from .. import figures as plt
    return plt


def plot_harris(torques, curves: dict, title: str = ""):
    """Loaded TE peak-to-peak (arcsec) against torque (N m), one line per design (baseline, optimum)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for (name, te), style in zip(curves.items(), ("o--", "s-")):
        ax.plot(torques, te, style, label=name)
    ax.set(xlabel="pinion torque [N m]", ylabel="loaded TE peak-to-peak [arcsec]",
           title=f"{title}: Harris map", ylim=(0, None))
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return fig


def plot_map(grid: dict | None, spec: DesignSpec, base: Evaluation, start: Evaluation, best: Evaluation, found,
             torques, title: str = ""):
    """The objective and the TE peak-to-peak at each torque over the two map variables, with the baseline, the
    start, the search's candidates and the optimum marked; infeasible points hatched."""
    if grid is None:
        return None
    plt = _plt()
    a, b = grid["variables"]
    x, y = np.array(grid["x"]), np.array(grid["y"])
    te = np.array(grid["te_ptp_arcsec"])            # (x, y, torque)
    panels = [("objective", np.array(grid["objective"]))]
    if len(torques) > 1:
        panels += [(f"TE ptp at {t:g} N m", te[..., k]) for k, t in enumerate(torques)]
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.4), squeeze=False)
    infeasible = ~np.array(grid["feasible"], bool)
    for ax, (label, z) in zip(axes[0], panels):
        cs = ax.contourf(x, y, z.T, levels=16, cmap="viridis")
        fig.colorbar(cs, ax=ax, label=f"{label} [arcsec]")
        if infeasible.any():
            ax.contourf(x, y, infeasible.T.astype(float), levels=[0.5, 1.5], colors="none", hatches=["//"])
        pts = np.array([[e.values[a], e.values[b]] for e in found.evaluations])
        ax.plot(pts[:, 0], pts[:, 1], ".-", color="w", lw=0.6, ms=4, alpha=0.8, label="search")
        base_name = "baseline (case's design)" if spec.kind != "bevel" else \
            "baseline: case's design ({:g} / {:g})".format(*(base.values[n] for n in (a, b)))
        for ev, mk, name in ((base, "X", base_name), (start, "^", "start"), (best, "*", "optimum")):
            ax.plot(ev.values[a], ev.values[b], mk, ms=12 if mk == "*" else 9, mec="k", label=name)
        ax.set(xlabel=a, ylabel=b, title=label, xlim=(x[0], x[-1]), ylim=(y[0], y[-1]))
    axes[0][0].legend(fontsize=8, loc="best")
    fig.suptitle(f"{title}: {spec.objective} over {a} x {b} (others at the optimum)")
    fig.tight_layout()
    return fig


def plot_history(hist: History, title: str = ""):
    """Objective of every candidate in the order evaluated, and the best feasible so far."""
    recs = [r for r in hist.candidates() if r["role"] != "map"]
    if not recs:
        return None
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 4))
    obj = np.array([r["objective"] for r in recs])
    ok = np.array([r["feasible"] for r in recs])
    n = np.arange(1, len(recs) + 1)
    ax.plot(n[ok], obj[ok], "o", label="feasible")
    ax.plot(n[~ok], obj[~ok], "x", color="C3", label="infeasible")
    best = np.minimum.accumulate(np.where(ok, obj, np.inf))
    ax.step(n, best, where="post", color="k", label="best feasible so far")
    ax.set(xlabel="candidate", ylabel="objective [arcsec]", title=f"{title}: search history", ylim=(0, None))
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return fig
