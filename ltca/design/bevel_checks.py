"""Checks of one bevel candidate for ``ltca optimise``: the machine settings inside a generator's ranges, the
bearing pattern's distance to the flank boundary (edge margins) and its edge load, the peak interior pressure.

Edge margins (mm), measured on the loaded contact cells (force > 0, cell centres: a cell at a boundary has a
margin of about half its size) over every position of the cycle, on both
members, in their axial sections (the plane of the bearing-pattern plot); a cell at the toe measured 0.16-0.28 mm
at the coarse fidelity:

``margin`` (toe / heel)
    the smallest distance along the cone distance L to the toe (L = A_i) or the heel (L = A_0):
    min(L - A_i, A_0 - L) over the gear's and the pinion's cells. This is ``edge_margin_mm`` of the constraints.
``top_margin`` (top / root)
    the smallest height of a cell below its member's face cone (the tooth top), over the pinion and the gear. The
    root of one member is the top of the other (the working depth), so both tops bound the pattern in depth. Not
    a constraint: for a 12/36 pair the gear's addendum is short (the mean point lies 1.3 mm below the gear top)
    and the transfer-point contact of a path inclined towards the tooth top reaches the gear top at every m21
    (measured at eta2 = 22 deg, m21 1-45 arcsec, 35 N m: 0.00-0.04 mm); load at the tops is bounded by
    ``max_edge_share`` instead (cells at any edge, share of the position's normal load).

Machine ranges (:data:`MACHINE_RANGES`) are those of a generic cradle-type generator relative to the blank's mean
cone distance A_m (our assumption, not a named machine): radial setting 0.2-2 A_m, |blank offset| and
|sliding base| and |centre-to-back| at most 0.5 A_m, ratio of roll 0.1-10, |C| <= 2 /rad, |D| <= 20 /rad^2.
"""
from __future__ import annotations

import math

import numpy as np

from ltca.geometry.bevel.machine import FlankCut

__all__ = ["MACHINE_RANGES", "machine_violations", "edge_margin", "top_margin", "cycle_measures"]

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
    """The toe / heel margin (module docstring) of the loaded cells of positions ``res`` on model ``lm``, mm."""
    d = math.inf
    for r in res:
        m = r.force > 0
        if m.any():
            for member, L in ((lm.gaps.G, r.L2[m]), (lm.gaps.P, r.L1[m])):
                d = min(d, float(np.minimum(L - member.Ai, member.A0 - L).min()))
    return d


def top_margin(lm, res) -> float:
    """The top margin (module docstring): smallest height of a loaded cell below its member's face cone, mm."""
    bl = lm.pair.blank
    d = math.inf
    for r in res:
        m = r.force > 0
        if m.any():
            for member, L, Rn in (("pinion", r.L1[m], r.Rn1[m]), ("gear", r.L2[m], r.Rn2[m])):
                d = min(d, float((bl.cones(member, L)[1] - Rn).min()))
    return d


def cycle_measures(lm, res) -> dict:
    """Figures of one loaded cycle: TE peak-to-peak (arcsec), peak interior pressure (MPa, beyond the edge band of
    :func:`ltca.bevel.results.edge_band`), largest edge load share of a position, toe / heel and top margins
    (mm, module docstring), the edges loaded."""
    from ltca.geometry.bevel.tca import RAD_PER_ARCSEC
    te = np.array([r.te for r in res]) / RAD_PER_ARCSEC
    from ltca.bevel.results import edge_band
    band = edge_band(lm.pair.blank.data.module)
    inner = max((float(r.pressure[r.edge_dist > band].max()) for r in res if np.any(r.edge_dist > band)), default=0.0)
    share = max(float(r.force[r.edge != ""].sum() / max(r.force.sum(), 1e-300)) for r in res)
    edges = sorted({e for r in res for e in r.edge_load()})
    return dict(te_ptp=float(np.ptp(te)), pressure=inner, edge_share=share, margin=edge_margin(lm, res),
                top_margin=top_margin(lm, res), edges=edges)
