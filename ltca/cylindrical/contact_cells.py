"""Contact cells of one mesh position and their contact problem (gaps, levers, areas, compliance).

The cells are narrow strips on the pinion's driving flank, one per face slice and tooth, centred on the
unloaded contact line and a few Hertz half-widths wide, on a lattice of the developed flank along that line
(:mod:`ltca.cylindrical.flank_lattice`), clipped to the flanks that can touch (:mod:`ltca.cylindrical.cell_clip`)
(:func:`contact_strips`). :func:`contact_system` gives their gaps from the separation field (both members'
micro-geometry and errors included) and their compliance from the two bodies' FE grids (bilinear
interpolation) plus the half-space near field (:func:`near_field_block`); :func:`ltca.cylindrical.loaded.solve_position`
solves the complementarity problem on it.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ltca.geometry.cylindrical import arc_length

from ..position import cell_compliance
from .cell_clip import (MIN_FRACTION, bounding_edges, clip_to_gear_flank, clip_to_pinion_flank,
                        gear_tip_on_pinion)
from .flank_lattice import line_lattice
from .loaded_model import LoadedModel
from .tca import flank_gaps

__all__ = ["ContactSystem", "Strip", "contact_strips", "contact_system", "near_field_block"]


class Strip(NamedTuple):
    """The cells of one tooth and face slice across the contact line (arrays of one length)."""
    tooth: int
    slice: int
    lattice: np.ndarray       # lattice index across the line
    s: np.ndarray             # centre of the kept part: flank arc length, mm
    z: np.ndarray             # and axial position, mm
    open_lo: bool             # the strip may be widened below its first cell
    open_hi: bool             # and above its last
    frac: np.ndarray          # fraction of the cell length kept after clipping (0, 1]
    shift: np.ndarray         # centre shift along the line, in cell lengths
    bound: np.ndarray         # edges that end the kept part (bits of ltca.cylindrical.cell_clip.bounding_edges)
    span: np.ndarray          # half the change of s over the kept part (it runs obliquely over the profile), mm


def _runs(first: np.ndarray, count: np.ndarray) -> np.ndarray:
    """Consecutive integers first[k] .. first[k] + count[k] - 1, all runs concatenated."""
    return np.repeat(first, count) + np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)


def _on_pinion(lat, I, J, zc, s_lo, s_hi, b):
    """Cells (I, J) of a lattice clipped to the pinion's flank: centre-line ends, kept interval [v0, v1]."""
    x, y = lat.slice_x(zc[J]), lat.y0 + I * lat.ds
    sa, za = lat.to_flank(x - 0.5 * lat.length, y)
    sb, zb = lat.to_flank(x + 0.5 * lat.length, y)
    sm, zm, d_s, d_z = 0.5 * (sa + sb), 0.5 * (za + zb), sb - sa, zb - za
    v0, v1 = clip_to_pinion_flank(sm, zm, d_s, d_z, s_lo, s_hi, b)
    return x, y, sm, zm, d_s, d_z, v0, v1


def _scan_cells(lat, zc, s_from, s_to, half, stride, whole: bool = False):
    """Cells to scan in each face slice: every ``stride``-th row within ``half`` rows of the contact line, the line
    held to the part of the flank where contact can happen (``s_from`` .. ``s_to``): where the line has left it,
    the flank's edge nearest to it (lattice indices I, J). ``whole``: every ``stride``-th row of that part."""
    _, y_a = lat.to_plane(s_from, zc)
    _, y_b = lat.to_plane(s_to, zc)
    yc = np.clip(lat.y_line, np.minimum(y_a, y_b), np.maximum(y_a, y_b))
    if whole:
        yc = 0.5 * (y_a + y_b)
        half = int(np.ceil(np.max(np.abs(y_b - y_a)) / (2 * lat.ds))) + 1
    first = (np.round((yc - lat.y0) / lat.ds).astype(int) - half) // stride * stride
    count = np.full(len(zc), (2 * half) // stride + 2)
    I = np.repeat(first, count) + stride * (np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count))
    return I, np.repeat(np.arange(len(zc)), count)


def contact_strips(lm: LoadedModel, phi1: float, theta_guess: float, widen: dict, torque: float, cycle: int = 0):
    """Contact strips of all teeth at a position, on a lattice of the developed pinion flank along the line.

    Per tooth the cells are rectangles of the developed flank aligned with the tooth's contact line
    (:mod:`ltca.cylindrical.flank_lattice`): ``ds`` across it and one face slice along it, so the near-field
    term depends on integer lattice offsets only (tabulated). Per face slice the strip is centred on the cell
    whose unloaded gap less the expected approach ``theta_guess`` is smallest, ``window`` nominal Hertz half-widths
    each side, widened by ``widen[(tooth, slice)]``; slices whose smallest gap cannot close under load get no
    strip. Contact can only happen near the tooth's contact line (where its flank meets the plane of action) or,
    where the line has left the active flank, at the flank's edge nearest to it: the scan covers a band there.
    Each cell is clipped to the pinion's flank and to the part that faces the gear's flank
    (:mod:`ltca.cylindrical.cell_clip`): it keeps a fraction of its length and its centre moves along the line,
    so the length of contact changes continuously from one position to the next.

    Returns the strips (:class:`Strip`), dz, ds and the lattice of each tooth {tooth: FlankLattice}."""
    model, fid = lm.model, lm.fid
    p1 = model.pinion
    rb = p1.r_base
    s_lo, s_hi = (arc_length(r, rb) for r in model.pinion_range())
    b = model.face_width
    dz = b / fid.slices
    zc = -0.5 * b + dz * (np.arange(fid.slices) + 0.5)
    b_h = lm.half_width(torque)
    ds = fid.cell_size(b_h)
    cpb = b_h / ds                                      # cells per half-width as used (more where capped)
    roll = model.phi_pitch - phi1
    u_w = float(np.tan(model.pair.alpha_w))
    s_edge2 = gear_tip_on_pinion(model)
    stride = max(1, int(cpb // 2))
    half = int(np.ceil((fid.window + 1.0) * cpb))
    out, lattice = [], {}
    for k in lm.teeth1:
        lat = line_lattice(p1, roll + k * model.pitch_angle, u_w, ds, dz, s_lo)
        # scan: cells of each slice on the flank (every `stride`-th row), gap at the centre of their part on the
        # pinion's flank; near the gear's tip edge, of their part that faces the gear's flank
        I, J = _scan_cells(lat, zc, max(s_lo, s_edge2 - 0.5), s_hi, half, stride,
                           whole=model.contact_search == "flank")
        x, y, sm, zm, d_s, d_z, v0, v1 = _on_pinion(lat, I, J, zc, s_lo, s_hi, b)
        on = v1 - v0 > MIN_FRACTION
        near = on & (np.abs(sm - s_edge2) < 0.5 + 0.5 * np.abs(d_s))
        if near.any():
            v0[near], v1[near] = clip_to_gear_flank(model, phi1, int(k), sm[near], zm[near], d_s[near], d_z[near],
                                                    v0[near], v1[near], cycle)
            on = v1 - v0 > MIN_FRACTION
        if not on.any():
            continue
        I, J = I[on], J[on]
        sc, zs = lat.to_flank(x[on] + 0.5 * (v0[on] + v1[on]) * lat.length, y[on])
        fg = flank_gaps(model, phi1, k, np.maximum(sc, 0.0), zs, cycle=cycle)
        g = np.where(np.isfinite(fg.gap) & (fg.lever1 > 0), fg.gap - fg.lever1 * theta_guess, np.inf)
        cap = 0.02 + 0.5 * abs(theta_guess) * rb        # gaps above this cannot close under load
        if not np.isfinite(g).any() or g.min() > cap:
            continue
        lattice[int(k)] = lat
        best = np.full(fid.slices, np.inf)
        np.minimum.at(best, J, g)
        slices = np.flatnonzero(best <= cap)            # slices that can come into contact
        ic = np.array([I[(J == j) & (g == best[j])][0] for j in slices], int)
        nw = np.ceil(fid.window * cpb * np.array([widen.get((k, j), 1.0) for j in slices])).astype(int)
        # the window and one cell beyond each end (is the strip open there?), clipped to both flanks
        count = 2 * nw + 3
        I, J = _runs(ic - nw - 1, count), np.repeat(slices, count)
        x, y, sm, zm, d_s, d_z, v0, v1 = _on_pinion(lat, I, J, zc, s_lo, s_hi, b)
        w0, w1 = clip_to_gear_flank(model, phi1, int(k), sm, zm, d_s, d_z, v0, v1, cycle)
        bound = bounding_edges(sm, zm, d_s, d_z, w0, w1, s_lo, s_hi, b, (w0 != v0) | (w1 != v1))
        v0, v1 = w0, w1
        frac = np.clip(v1 - v0, 0.0, 1.0)
        shift = 0.5 * (v0 + v1)
        span = 0.5 * np.abs(d_s) * frac
        s_c, z_c = lat.to_flank(x + shift * lat.length, y)
        keep = frac > MIN_FRACTION
        at = 0
        for j, n in zip(slices, count):
            m = slice(at + 1, at + n - 1)
            at += n
            kept = keep[m]
            if kept.any():
                out.append(Strip(int(k), int(j), I[m][kept], s_c[m][kept], z_c[m][kept], bool(keep[m.start - 1]),
                                 bool(keep[m.stop]), frac[m][kept], shift[m][kept], bound[m][kept], span[m][kept]))
    return out, dz, ds, lattice


def near_field_block(I, J, ds, length, E, nu, frac=None, shift=None):
    """Half-space surface compliance of both bodies between one tooth's cells on the lattice, (n, n), mm/N.

    Cells (I, J) are lattice indices across and along the line of the developed flank; a cell is ``ds``
    wide and ``length`` long. The bodies' FE parts have their own half-space response removed
    (:mod:`ltca.fem.compliance`), so this is the whole local term; it is tabulated over integer lattice offsets.
    Cells clipped at an edge keep the fraction ``frac`` of their length, centred ``shift`` cell lengths off
    their lattice place: their rows and columns are computed directly (receiver at each centre, symmetrised)."""
    from ltca.fem.halfspace import surface_influence
    a, bh = 0.5 * ds, 0.5 * length
    di = np.arange(I.min() - I.max(), I.max() - I.min() + 1)
    dj = np.arange(J.min() - J.max(), J.max() - J.min() + 1)
    DI, DJ = np.meshgrid(di, dj, indexing="ij")
    table = 2.0 * surface_influence(DI * ds, DJ * length, a, bh, E, nu)
    C = table[I[:, None] - I[None, :] - di[0], J[:, None] - J[None, :] - dj[0]]
    if frac is None:
        return C
    part = np.flatnonzero((frac < 1.0 - 1e-12) | (np.abs(shift) > 1e-12))
    if part.size:
        x, y = I * ds, (J + shift) * length
        # receivers: all cells, sources: the clipped ones (their own length); and the reverse
        A = 2.0 * surface_influence(x[:, None] - x[part], y[:, None] - y[part], a, bh * frac[part], E, nu)
        B = 2.0 * surface_influence(x[part, None] - x[None, :], y[part, None] - y[None, :], a,
                                    bh * frac[None, :], E, nu)
        S = 0.5 * (A + B.T)
        C[:, part] = S
        C[part, :] = S.T
    return C


@dataclass(frozen=True)
class ContactSystem:
    """The contact problem of one position: cells, their unloaded gaps, levers, areas and compliance."""
    tooth: np.ndarray
    slice: np.ndarray
    lattice: np.ndarray
    s: np.ndarray
    z: np.ndarray
    gap0: np.ndarray
    lever1: np.ndarray
    lever2: np.ndarray
    gear_tooth: np.ndarray
    gear_s: np.ndarray
    gear_z: np.ndarray
    area: np.ndarray
    C: np.ndarray
    W1: object
    W2: object
    bound: np.ndarray
    span: np.ndarray


def contact_system(lm: LoadedModel, phi1: float, strips, dz: float, ds: float, cycle: int,
                   lattice: dict) -> ContactSystem:
    """Gaps (separation field + micro-geometry), compliance (FE far field of both bodies, bilinearly
    interpolated, plus the half-space near field) and cell areas of the strips of one position."""
    model, fid = lm.model, lm.fid
    tooth = np.concatenate([np.full(len(x.lattice), x.tooth) for x in strips])
    sl = np.concatenate([np.full(len(x.lattice), x.slice) for x in strips])
    lat = np.concatenate([x.lattice for x in strips])
    s = np.concatenate([x.s for x in strips])
    z = np.concatenate([x.z for x in strips])
    frac = np.concatenate([x.frac for x in strips])
    shift = np.concatenate([x.shift for x in strips])
    n = len(s)
    g0, h1, h2 = np.empty(n), np.empty(n), np.empty(n)
    gt, gs, gz = np.empty(n, int), np.empty(n), np.empty(n)
    for k in np.unique(tooth):
        m = tooth == k
        fg = flank_gaps(model, phi1, int(k), s[m], z[m], cycle=cycle)
        g0[m], h1[m], h2[m] = fg.gap, fg.lever1, fg.lever2
        gt[m], gs[m], gz[m] = fg.gear_tooth, fg.gear_s, fg.gear_z
    length = np.array([lattice[int(k)].length for k in tooth])
    area = ds * length * frac
    W1 = lm.body1.weights(tooth, s, z)
    W2 = lm.body2.weights(gt, gs, gz)
    blocks = None
    if fid.near_field:
        E, nu = model.case.young, model.case.poisson
        blocks = []
        for k in np.unique(tooth):
            m = np.flatnonzero(tooth == k)
            blocks.append((m, near_field_block(lat[m], sl[m], ds, lattice[int(k)].length, E, nu, frac[m], shift[m])))
    C = cell_compliance(lm.body1, W1, lm.body2, W2, blocks)
    bound = np.concatenate([x.bound for x in strips])
    span = np.concatenate([x.span for x in strips])
    return ContactSystem(tooth, sl, lat, s, z, g0, h1, h2, gt, gs, gz, area, C, W1, W2, bound, span)
