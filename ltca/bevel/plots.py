"""Plots of a bevel LTCA run: TE against position for every torque, the bearing pattern on the gear flank per
torque (axial section, toe to heel and root to top, tooth outline, unloaded path and loaded ellipses, one colour
scale), and the load sharing of a tooth over its engagement."""
from __future__ import annotations

from pathlib import Path

import numpy as np

from .loaded_model import LOADED

__all__ = ["plot_all"]


def _outline(pair) -> np.ndarray:
    bl = pair.blank
    A0, Ai = bl.outer_cone_distance, bl.inner_cone_distance
    Lb = np.array([Ai, A0])
    root, face = bl.cones("gear", Lb)
    return np.array([[Ai, root[0]], [A0, root[1]], [A0, face[1]], [Ai, face[0]], [Ai, root[0]]])


def plot_all(d: Path, title: str, pair, ds, per: dict, patterns: dict, outlines: dict, paths: dict, runs: dict
             ) -> list[str]:
    """Write te.png, bearing_pattern.png and load_sharing.png; returns the file names."""
    from matplotlib import colormaps
    from matplotlib.figure import Figure
    files = []
    tq = [float(t) for t in ds.torque.values]
    x = ds.cycle.values
    cmap = colormaps["viridis"]
    colours = {T: cmap(k / max(len(tq) - 1, 1)) for k, T in enumerate(tq)}
    fig = Figure(figsize=(8, 4.2))
    ax = fig.add_subplot()
    drawn = set()
    for T in tq:
        ax.plot(x, per[T]["te"], "-o", ms=3, color=colours[T], label=f"loaded, {T:g} N m")
        flank = "working" if T > 0 else "coast"
        if flank not in drawn:
            ax.plot(x, per[T]["te0"], "--", color="k" if T > 0 else "0.5", lw=1, label=f"unloaded ({flank})")
            drawn.add(flank)
    ax.set_xlabel("pinion angle [mesh cycles]")
    ax.set_ylabel("transmission error [arcsec] (positive: gear lags)")
    ax.set_title(f"{title}: loaded TE", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(d / "te.png", dpi=120)
    files.append("te.png")

    box = _outline(pair)
    # colour scale: the largest interior peak (edge peaks are singular and mesh-dependent: they saturate)
    vmax = 1.1 * max(float(np.max(per[T]["pmax_interior"])) for T in tq)
    fig = Figure(figsize=(8, 2.6 * len(tq) + 0.6))
    axes = fig.subplots(len(tq), 1, squeeze=False)
    for ax, T in zip(axes[:, 0], tq):
        Lb, Rb, P = patterns[T]
        im = ax.pcolormesh(Lb, Rb, np.where(P > 0, P, np.nan), cmap="inferno", vmin=0, vmax=vmax, shading="nearest")
        ax.plot(box[:, 0], box[:, 1], "k-", lw=1.2)
        side = "concave" if T > 0 else "convex"
        ax.plot(*paths[side], "c-", lw=1.2, label="unloaded path of contact")
        for e in outlines[T]:
            ax.plot(e[:, 0], e[:, 1], "-", color="0.85", lw=0.8, alpha=0.8)
        ax.text(box[0, 0] + 0.3, box[3, 1] + 0.2, "toe", fontsize=8)
        ax.text(box[1, 0] - 2.0, box[2, 1] + 0.2, "heel", fontsize=8)
        ax.set_title(f"{T:g} N m ({'working' if T > 0 else 'coast'} flank): pressure envelope over the cycle, "
                     "loaded ellipses (grey, every few positions)", fontsize=9)
        ax.set_ylabel("Rn [mm] (root to top)")
        ax.set_aspect("equal")
        ax.legend(loc="lower right", fontsize=7)
    axes[-1, 0].set_xlabel("gear cone distance L [mm] (toe to heel)")
    fig.colorbar(im, ax=axes[:, 0], label="contact pressure [MPa] (edge peaks saturate)", shrink=0.8, extend="max")
    fig.suptitle(f"{title}: bearing pattern on the gear flank, axial section", fontsize=10)
    fig.savefig(d / "bearing_pattern.png", dpi=120)
    files.append("bearing_pattern.png")

    fig = Figure(figsize=(8, 3.6))
    ax = fig.add_subplot()
    for T in tq:
        s = per[T]["share"]
        xx = np.concatenate([x + j for j in LOADED])
        yy = np.concatenate([s[:, k] for k in range(len(LOADED))])
        o = np.argsort(xx)
        ax.plot(xx[o], yy[o], "-", color=colours[T], label=f"{T:g} N m")
    ax.set_xlabel("angle of the reference pinion tooth [mesh cycles]")
    ax.set_ylabel("share of the torque")
    ax.set_title(f"{title}: load sharing of one tooth pair over its engagement", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(d / "load_sharing.png", dpi=120)
    files.append("load_sharing.png")
    return files
