"""Checks of one bevel candidate for ``ltca optimise``: the machine settings inside a generator's ranges, the
bearing pattern's distance to the flank boundary (edge margin) and its edge load, the peak interior pressure.

Edge margin (mm): the smallest distance of a loaded contact cell (force > 0) to the toe (L = A_i) or the heel
(L = A_0), the cone distance L taken in the gear's and in the pinion's axial section; a cell at an end has a margin
of about half its size. The top and root edges are not in the margin: under load the incoming pair of every design
first touches at the pinion top / gear root (the mesh entry through the edge, seen by the LTCA as edge cells), so a
margin there would exclude every design; their load is measured as the edge load share (cells at any edge, share
of the position's normal load) and bounded by ``max_edge_share``.

Machine ranges (:data:`MACHINE_RANGES`) are those of a generic cradle-type generator relative to the blank's mean
cone distance A_m (our assumption, not a named machine): radial setting 0.2-2 A_m, |blank offset| and
|sliding base| and |centre-to-back| at most 0.5 A_m, ratio of roll 0.1-10, |C| <= 2 /rad, |D| <= 20 /rad^2.
"""
from __future__ import annotations

import math

import numpy as np

from geometry.bevel.machine import FlankCut

__all__ = ["MACHINE_RANGES", "machine_violations", "edge_margin", "cycle_measures"]

#: setting -> (lower, upper, relative to A_m?)
MACHINE_RANGES = {"radial_setting": (0.2, 2.0, True), "blank_offset": (-0.5, 0.5, True),
                  "sliding_base": (-0.5, 0.5, True), "center_to_back": (-0.5, 0.5, True),
                  "ratio_of_roll": (0.1, 10.0, False), "modified_roll_c": (-2.0, 2.0, False),
                  "modified_roll_d": (-20.0, 20.0, False)}


def machine_violations(fc: FlankCut, mean_cone_distance: float) -> list[str]:
    """The settings of a flank cut outside :data:`MACHINE_RANGES` (one phrase each; empty: all in range)."""
    out = []
    for key, (lo, hi, rel) in MACHINE_RANGES.items():
        x = float(getattr(fc.machine, key))
        s = mean_cone_distance if rel else 1.0
        if not (math.isfinite(x) and lo * s <= x <= hi * s):
            out.append(f"{key} = {x:.4g} outside [{lo * s:.4g}, {hi * s:.4g}]")
    return out


def edge_margin(lm, res) -> float:
    """The edge margin (module docstring) of the loaded cells of positions ``res`` on model ``lm``, mm."""
    d = math.inf
    for r in res:
        m = r.force > 0
        if m.any():
            for member, L in ((lm.gaps.G, r.L2[m]), (lm.gaps.P, r.L1[m])):
                d = min(d, float(np.minimum(L - member.Ai, member.A0 - L).min()))
    return d


def cycle_measures(lm, res) -> dict:
    """Figures of one loaded cycle: TE peak-to-peak (arcsec), peak interior pressure (MPa, cells at no edge),
    largest edge load share of a position, edge margin (mm), the edges loaded."""
    from geometry.bevel.tca import RAD_PER_ARCSEC
    te = np.array([r.te for r in res]) / RAD_PER_ARCSEC
    inner = max((float(r.pressure[r.edge == ""].max()) for r in res if np.any(r.edge == "")), default=0.0)
    share = max(float(r.force[r.edge != ""].sum() / max(r.force.sum(), 1e-300)) for r in res)
    edges = sorted({e for r in res for e in r.edge_load()})
    return dict(te_ptp=float(np.ptp(te)), pressure=inner, edge_share=share, margin=edge_margin(lm, res),
                edges=edges)
