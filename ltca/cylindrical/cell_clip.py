"""Contact cells clipped to the flanks that can touch: the pinion's active flank and the gear's flank up to its tip.

A contact cell of :func:`ltca.cylindrical.contact_cells.contact_strips` is long along the contact line (one face
slice) and narrow across it. On a helical flank the edges of the contact region cross the cells obliquely: the
pinion's tip and form circles (``s = s_hi``, ``s = s_lo``), the face ends (``z = +-b/2``) and the locus of the
gear's tip edge on the pinion flank. A cell judged by its centre alone is either wholly in or wholly out, so the
length of contact line jumps by up to a cell (a slice, 3 mm on helical C14) as the line moves over the lattice
from one position to the next: the per-position TE, root stress and peak pressure zig-zag.

Here each cell is the segment ``(s, z) = (s_m + v ds, z_m + v dz)``, ``v`` in ``[-1/2, 1/2]``, between the ends of
its centre line (straight on the developed flank; ``s`` departs from linear by a few um over a cell), clipped to
the part that lies on the pinion's flank and faces the gear's flank (not the gear's tip land, not beyond its
face). The clipped cell keeps its width, the fraction ``v1 - v0`` of its length and the centre
``(v0 + v1) / 2``, so the length of contact changes continuously with the position. The pinion's edges clip
analytically; the gear's tip edge is located on each cell that straddles it by samples of the gear's foot point
along the cell, then by extrapolating the foot radius from the flank side (it is smooth there, and constant,
the tip radius, beyond the edge).
"""
from __future__ import annotations

import numpy as np

from .model import PairModel
from .tca import flank_gaps

__all__ = ["clip_to_pinion_flank", "clip_to_gear_flank", "gear_tip_on_pinion", "bounding_edges", "MIN_FRACTION",
           "PINION_TIP", "GEAR_TIP", "PINION_FORM", "FACE_END"]

#: cells keeping less than this fraction of their length are dropped (they carry next to nothing)
MIN_FRACTION = 1e-3

_TIP_TOL = 1e-5        # mm: a gear foot point this close to the tip circle faces the tip edge or tip land

#: bits of :func:`bounding_edges` (the order of :data:`ltca.cylindrical.edges.EDGES`)
PINION_TIP, GEAR_TIP, PINION_FORM, FACE_END = 1, 2, 4, 8


def _interval(v0, v1, m, d, lo, hi):
    """Narrow [v0, v1] to where lo <= m + v d <= hi."""
    tilted = np.abs(d) > 1e-12
    dd = np.where(tilted, d, 1.0)
    va, vb = (lo - m) / dd, (hi - m) / dd
    v0 = np.where(tilted, np.maximum(v0, np.minimum(va, vb)), v0)
    v1 = np.where(tilted, np.minimum(v1, np.maximum(va, vb)), v1)
    return v0, np.where(~tilted & ((m < lo - 1e-12) | (m > hi + 1e-12)), v0, v1)


def clip_to_pinion_flank(s_m: np.ndarray, z_m: np.ndarray, d_s: np.ndarray, d_z: np.ndarray, s_lo: float,
                         s_hi: float, b: float) -> tuple[np.ndarray, np.ndarray]:
    """Part of each cell's segment on the pinion's active flank, ``s_lo <= s <= s_hi`` and ``|z| <= b/2``.

    Parameters
    ----------
    s_m, z_m : ndarray (n,)
        Middle of the cells' centre lines (flank arc length, axial position), mm.
    d_s, d_z : ndarray (n,)
        Change of s and z from one end of the centre line to the other, mm.
    s_lo, s_hi, b : float
        Arc lengths of the pinion's form and tip circles, face width, mm.

    Returns
    -------
    v0, v1 : ndarray (n,)
        The kept interval of ``v`` in [-1/2, 1/2] (empty where ``v1 <= v0``).
    """
    v0, v1 = np.full(len(s_m), -0.5), np.full(len(s_m), 0.5)
    v0, v1 = _interval(v0, v1, s_m, d_s, s_lo, s_hi)
    return _interval(v0, v1, z_m, d_z, -0.5 * b, 0.5 * b)


def bounding_edges(s_m, z_m, d_s, d_z, v0, v1, s_lo, s_hi, b, gear_cut) -> np.ndarray:
    """Which edges end each cell's kept part ``[v0, v1]`` (bits PINION_TIP, GEAR_TIP, PINION_FORM, FACE_END, uint8);
    ``gear_cut``: the cells that :func:`clip_to_gear_flank` cut."""
    tol = 1e-7
    s = np.stack([s_m + v0 * d_s, s_m + v1 * d_s])
    z = np.abs(np.stack([z_m + v0 * d_z, z_m + v1 * d_z]))
    out = np.where((s >= s_hi - tol).any(axis=0), PINION_TIP, 0) | np.where(gear_cut, GEAR_TIP, 0)
    out |= np.where((s <= s_lo + tol).any(axis=0), PINION_FORM, 0) | np.where((z >= 0.5 * b - tol).any(axis=0),
                                                                               FACE_END, 0)
    return out.astype(np.uint8)


def _beyond(model: PairModel, phi1: float, tooth: int, s: np.ndarray, z: np.ndarray, cycle: int):
    """Where pinion points face no gear flank (the gear's tip edge or land, or beyond its face), and the foot radius."""
    fg = flank_gaps(model, phi1, tooth, np.maximum(s, 0.0), z, cycle=cycle)
    return ~np.isfinite(fg.gap) | (np.abs(fg.gear_r - model.gear.r_tip) < _TIP_TOL), fg.gear_r


def gear_tip_on_pinion(model: PairModel) -> float:
    """Arc length on the pinion flank (mm from its base circle) conjugate to the gear's tip circle: where the
    gear's tip edge meets the pinion's flank on the line of action (the pinion's start of active profile)."""
    pair, g = model.pair, model.gear
    L2 = np.sqrt(max(g.r_tip ** 2 - g.r_base ** 2, 0.0))
    T = pair.a * np.sin(pair.alpha_w)
    L1 = L2 - T if g.internal else T - L2
    return float(L1 * abs(L1) / (2 * model.pinion.r_base))


def clip_to_gear_flank(model: PairModel, phi1: float, tooth: int, s_m: np.ndarray, z_m: np.ndarray,
                       d_s: np.ndarray, d_z: np.ndarray, v0: np.ndarray, v1: np.ndarray, cycle: int = 0,
                       samples: int = 17) -> tuple[np.ndarray, np.ndarray]:
    """Narrow each cell's interval ``[v0, v1]`` (one pinion tooth) to the part that faces the gear's flank.

    A cell whose two ends both face the gear's flank, or both face its tip edge, is kept as it is (the gap at its
    centre decides). A cell with one end on each side is cut where its segment crosses the locus of the gear's
    tip edge on the pinion flank: ``samples`` points along it bracket the crossing, and the gear's foot radius,
    smooth on the flank side, is extrapolated (quadratic) from the three nearest samples there to the tip radius.

    Returns
    -------
    v0, v1 : ndarray (n,)
    """
    v0, v1 = v0.copy(), v1.copy()
    live = np.flatnonzero(v1 > v0)
    if live.size == 0:
        return v0, v1
    n = live.size

    def beyond(cells, v):
        return _beyond(model, phi1, tooth, s_m[cells] + v * d_s[cells], z_m[cells] + v * d_z[cells], cycle)

    out, _ = beyond(np.tile(live, 2), np.concatenate([v0[live], v1[live]]))
    cut = np.flatnonzero(out[:n] != out[n:])
    if cut.size == 0:
        return v0, v1
    cells, lo_side = live[cut], out[:n][cut]
    m = len(cells)
    # samples from the end on the gear flank (t = 0) to the end beyond its tip edge (t = 1)
    v_in = np.where(lo_side, v1[cells], v0[cells])
    v_out = np.where(lo_side, v0[cells], v1[cells])
    t = np.linspace(0.0, 1.0, samples)
    v = v_in[:, None] + t[None, :] * (v_out - v_in)[:, None]
    o, r = beyond(np.repeat(cells, samples), v.ravel())
    o, r = o.reshape(m, samples), r.reshape(m, samples)
    o[:, 0], o[:, -1] = False, True
    k = np.argmax(o, axis=1)                      # first sample beyond the edge (>= 1)
    rows = np.arange(m)
    # the foot radius at the last three samples on the flank side, extrapolated (quadratic) to the tip radius
    ia, ib, ic = np.maximum(k - 3, 0), np.maximum(k - 2, 0), k - 1
    ra, rb_, rc = r[rows, ia], r[rows, ib], r[rows, ic]
    h = t[1] - t[0]
    d1, d2 = rc - rb_, rc - 2 * rb_ + ra         # per sample step, at the last sample
    quad = k >= 3
    slope = np.where(quad, d1 + 0.5 * d2, d1)     # r'(t) at the last sample (steps), second-order
    curv = np.where(quad, d2, 0.0)
    target = model.gear.r_tip - rc
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.where((k >= 2) & (np.abs(slope) > 1e-15), target / slope, 0.5)
        x = x - np.where(np.abs(slope) > 1e-15, 0.5 * curv * x * x / slope, 0.0)   # one Newton-like correction
    t_star = t[ic] + np.clip(np.where(np.isfinite(x), x, 0.5), 0.0, 1.0) * h
    v_star = v_in + t_star * (v_out - v_in)
    v0[cells] = np.where(lo_side, v_star, v0[cells])
    v1[cells] = np.where(lo_side, v1[cells], v_star)
    return v0, v1
