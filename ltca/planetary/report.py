"""Tables, CSV files and plots of the planetary analyses (forming comparison, unloaded gaps, load sharing)."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

__all__ = ["write_csv", "format_table", "plot_gaps", "plot_load_sharing"]


def write_csv(path, rows: list[dict]) -> None:
    """Rows of dicts (same keys) as CSV."""
    if not rows:
        return
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def _fmt(v) -> str:
    if isinstance(v, float):
        return f"{v:.4g}"
    if isinstance(v, dict):
        return " ".join(f"{k}:{_fmt(x)}" for k, x in v.items())
    return str(v)


def format_table(rows: list[dict], keys: list[str] | None = None) -> str:
    """A fixed-width text table of ``rows`` (the columns ``keys``, default every key of the first row)."""
    keys = keys or list(rows[0])
    cells = [[_fmt(r[k]) for k in keys] for r in rows]
    width = [max(len(k), *(len(c[i]) for c in cells)) for i, k in enumerate(keys)]
    lines = ["  ".join(k.ljust(w) for k, w in zip(keys, width))]
    lines += ["  ".join(c.ljust(w) for c, w in zip(row, width)) for row in cells]
    return "\n".join(lines)


def _plt():
    from .. import figures as plt
    return plt


def plot_gaps(path, phi: np.ndarray, pairs: np.ndarray, gaps: dict, limit_um: float = 150.0) -> None:
    """Unloaded gap of every pair within ``limit_um`` over the mesh cycle, both directions."""
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    for ax, d in zip(axes, (1, -1)):
        g = gaps[d]
        for j, k in enumerate(pairs):
            if np.nanmin(g[:, j]) <= limit_um:
                ax.plot(np.degrees(phi), g[:, j], marker=".", label=f"pair {k}")
        ax.set_title("drive (+1, right flanks)" if d > 0 else "reverse (-1, left flanks)")
        ax.set_xlabel("satellite position phi, deg")
        ax.set_ylim(-2, limit_um)
        ax.legend(fontsize=7, ncol=2)
    axes[0].set_ylabel("unloaded gap along the line of action, um")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_load_sharing(path, by_torque: list[dict]) -> None:
    """Mean and max load share per pair index at each torque, both directions.

    ``by_torque``: [{"label": str, "pairs": list, "mean_share": {d: list}, "max_share": {d: list}}]."""
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5), sharey=True)
    for ax, d in zip(axes, (1, -1)):
        for i, t in enumerate(by_torque):
            p = np.asarray(t["pairs"][d])
            ax.plot(p, t["mean_share"][d], marker="o", color=f"C{i}", label=t["label"] + " mean")
            ax.plot(p, t["max_share"][d], ls=":", color=f"C{i}", label=t["label"] + " max")
        ax.set_title("drive (+1)" if d > 0 else "reverse (-1)")
        ax.set_xlabel("pair index (satellite tooth, 0 on the line of centres at phi = 0)")
        ax.axhline(0, color="k", lw=0.5)
        ax.legend(fontsize=7)
    axes[0].set_ylabel("share of the normal load over the mesh cycle")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def out_dir(out) -> Path | None:
    if out is None:
        return None
    p = Path(out)
    p.mkdir(parents=True, exist_ok=True)
    return p
