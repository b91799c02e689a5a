"""The bearing pattern against the pinion diameter, with SAP/EAP and the form diameters marked, and a measure of
its striping.

The pattern is the envelope of the contact pressure over the mesh cycle on the pinion flank lattice (one
profile column per position step, :func:`ltca.cylindrical.results.flank_lattice`). When the positions are too
sparse for the lattice, columns that no contact line crossed stay low between loaded neighbours: vertical
stripes. :func:`striping_index` measures them: per profile column the face-median pressure m_i (face-end
spikes left out), and for each column of the loaded region (m_i above ``floor`` of the largest m) its dip
below the lower of its two neighbours, relative to that neighbour:

    dip_i = max(0, min(m_{i-1}, m_{i+1}) - m_i) / min(m_{i-1}, m_{i+1})

The index is the largest dip: 0 for a pattern that rises and falls smoothly, near 1 for empty columns between
loaded ones. :data:`STRIPING_LIMIT` is the limit the flagship defaults must meet.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from .. import figures as plt
from .derived import roll_to_diameter
from .report import plot_data

__all__ = ["STRIPING_LIMIT", "column_profile", "striping_index", "plot_pattern_diameter"]

#: largest dip of a profile column below its neighbours that still counts as a smooth pattern
STRIPING_LIMIT = 0.15


def column_profile(pattern: np.ndarray) -> np.ndarray:
    """Face-median pressure per profile column of a (profile, face) pattern, MPa."""
    p = np.nan_to_num(np.asarray(pattern, dtype=float))
    return np.median(p, axis=1)


def striping_index(pattern: np.ndarray, floor: float = 0.1) -> float:
    """Largest relative dip of a profile column below both its neighbours within the loaded region (module
    docstring); ``pattern`` is (profile, face) in MPa."""
    m = column_profile(pattern)
    if m.size < 3 or m.max() <= 0:
        return 0.0
    lo = np.minimum(m[:-2], m[2:])
    mid = m[1:-1]
    loaded = lo > floor * m.max()
    dip = np.where(loaded, np.maximum(lo - mid, 0.0) / np.where(loaded, lo, 1.0), 0.0)
    return float(dip.max())


def plot_pattern_diameter(ds: xr.Dataset, active: dict, r_base: float, path: Path, title: str) -> Path:
    """Bearing pattern per torque against the pinion diameter (shared colour scale), with the pinion's root form
    diameter d_Ff, SAP, EAP and tip form diameter d_Fa (the involute's end; d_a without a tip edge) marked;
    ``active`` is
    :func:`ltca.cylindrical.derived.active_profile`. Writes ``path`` and returns it."""
    data = plot_data(ds)
    torques = data["torques"]
    vmin, vmax = data["pressure_range"]
    n = len(torques)
    cols = min(n, 3)
    rows = -(-n // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(5.6 * cols, 4.0 * rows), squeeze=False)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    axes = list(axes.flat[:n])
    a = active["pinion"]
    marks = (("root form d_Ff", a["form"], "deepskyblue", ":"), ("SAP", a["sap"], "lime", "--"),
             ("EAP", a["eap"], "magenta", "--"), ("tip form d_Fa", a["tip_form"], "white", ":"))
    m = None
    for ax, t in zip(axes, torques):
        x, z, p = data["bearing_pattern"][t]
        d = roll_to_diameter(x, r_base)
        m = ax.pcolormesh(d, z, np.asarray(p).T, shading="nearest", cmap="inferno", vmin=vmin, vmax=vmax)
        for name, dia, colour, style in marks:
            ax.axvline(dia, color=colour, ls=style, lw=1.2, label=f"{name} {dia:.2f} mm")
        ax.legend(loc="lower center", ncol=2, fontsize=7, framealpha=0.85)
        ax.set(xlabel="pinion diameter [mm] (root -> tip)", ylabel="face width position [mm]",
               title=f"{title}: bearing pattern, {t:g} N m")
        ax.set_xlim(min(d.min(), a["form"]) - 0.3, max(d.max(), a["tip"]) + 0.3)
        ax.set_facecolor("black")
    fig.tight_layout()
    fig.colorbar(m, ax=axes, label="contact pressure [MPa], scale: flank peak of all torques")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)
