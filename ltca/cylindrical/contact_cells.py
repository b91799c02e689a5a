"""Contact cells of one mesh position and their contact problem (gaps, levers, areas, compliance).

The cells are narrow strips on the pinion's driving flank, one per face slice and tooth, centred on the
unloaded contact line and a few Hertz half-widths wide, on a lattice of the flank that follows that line
(:func:`contact_strips`). :func:`contact_system` gives their gaps from the separation field (both members'
micro-geometry and errors included) and their compliance from the two bodies' FE grids (bilinear
interpolation) plus the half-space near field (:func:`near_field_block`); :func:`ltca.cylindrical.loaded.solve_position`
solves the complementarity problem on it.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from geometry.cylindrical import arc_length, flank_point_normal

from .loaded_model import LoadedModel
from .tca import flank_gaps

__all__ = ["ContactSystem", "contact_strips", "contact_system", "flank_tangents", "near_field_block"]


def flank_tangents(p1, s: np.ndarray, z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Flank tangents dP/ds, dP/dz (n, 3) of the pinion drive flank, by differences (the flank is exact)."""
    eps = 1e-4
    s, z = np.broadcast_arrays(np.atleast_1d(np.asarray(s, float)), np.atleast_1d(np.asarray(z, float)))
    ra = np.sqrt(p1.r_base ** 2 + 2 * p1.r_base * (s + eps))
    Pa, _ = flank_point_normal(p1, +1, ra, z, tooth=0)
    Pb, _ = flank_point_normal(p1, +1, np.sqrt(p1.r_base ** 2 + 2 * p1.r_base * (s - eps)), z, tooth=0)
    Pz1, _ = flank_point_normal(p1, +1, ra, z + eps, tooth=0)
    return (Pa - Pb) / (2 * eps), (Pz1 - Pa) / eps


def contact_strips(lm: LoadedModel, phi1: float, theta_guess: float, widen: dict, torque: float, cycle: int = 0):
    """Contact strips of all teeth at a position, on a lattice of the pinion flank that follows the line.

    Per tooth the unloaded contact line s = q + t z is fitted (t = 0 on a spur flank, the slope of the
    inclined line on a helical one). The lattice has rectangular cells aligned with that line: step
    ``dz`` along it (one slice per face step) and step ``ds`` across it, so the near-field term depends on
    integer offsets only (tabulated), and a helical contact band is covered by cells along it instead of
    a staircase of face-long rectangles.

    Returns strips [(tooth, slice, lattice indices, s, z, open below, open above)], dz, ds and the lattice
    of each tooth {tooth: (t, step_s, step_z)}: one step across the line in (s, z)."""
    model, fid = lm.model, lm.fid
    p1 = model.pinion
    rb = p1.r_base
    s_lo, s_hi = (arc_length(r, rb) for r in model.pinion_range())
    b = model.face_width
    dz = b / fid.slices
    zc = -0.5 * b + dz * (np.arange(fid.slices) + 0.5)
    s_scan = np.linspace(s_lo, s_hi, 400)
    S, Z = np.meshgrid(s_scan, zc, indexing="ij")
    ds = lm.half_width(torque) / fid.cells_per_b
    out, lattice = [], {}
    for k in lm.teeth1:
        fg = flank_gaps(model, phi1, k, S, Z, cycle=cycle)
        g = np.where(np.isfinite(fg.gap) & (fg.lever1 > 0), fg.gap - fg.lever1 * theta_guess, np.inf)
        if not np.isfinite(g).any() or g.min() > 0.02 + 0.5 * abs(theta_guess) * rb:
            continue
        has = np.isfinite(g).any(axis=0)
        s_min = s_scan[np.argmin(g, axis=0)]
        inner = has & (s_min > s_scan[0]) & (s_min < s_scan[-1])   # the line itself, not a flank border
        t = float(np.polyfit(zc[inner], s_min[inner], 1)[0]) if inner.sum() >= 3 else 0.0
        t = 0.0 if abs(t) * b < 1e-9 else t
        # one step across the line, perpendicular to it on the flank, of 3D length ds
        Ps, Pz = flank_tangents(p1, np.median(s_min[has]), 0.0)
        L = Pz[0] + t * Ps[0]
        mu = float(Ps[0] @ L / (L @ L))
        A = (1 - mu * t) * Ps[0] - mu * Pz[0]
        step_s, step_z = ds * (1 - mu * t) / np.linalg.norm(A), -ds * mu / np.linalg.norm(A)
        dq = step_s - t * step_z                      # the across coordinate q = s - t z per step
        lattice[int(k)] = (t, step_s, step_z)
        for j in range(fid.slices):
            if not has[j]:
                continue
            s0 = s_lo + t * zc[j]                     # cell i of slice j: (s0, zc) + (i + 1/2) step
            lo_i = int(np.ceil((s_lo - s0) / step_s - 0.5 - 1e-9))
            hi_i = int(np.floor((s_hi - s0) / step_s - 0.5 + 1e-9)) + 1
            ic = int(round((s_min[j] - t * zc[j] - s_lo) / dq - 0.5))
            nw = int(np.ceil(fid.window * fid.cells_per_b * widen.get((k, j), 1.0)))
            i0, i1 = max(lo_i, ic - nw), min(hi_i, ic + nw + 1)
            if i1 <= i0:
                continue
            idx = np.arange(i0, i1)
            zz = np.clip(zc[j] + (idx + 0.5) * step_z, -0.5 * b, 0.5 * b)
            out.append((k, j, idx, s0 + (idx + 0.5) * step_s, zz, i0 > lo_i, i1 < hi_i))
    return out, dz, ds, lattice


def near_field_block(I, J, Vs, Vz, E, nu):
    """Half-space surface compliance of both bodies between one tooth's cells on the lattice, (n, n), mm/N.

    Cells (I, J) are lattice indices; one lattice step is the 3D vector Vs (profile) or Vz (face). The
    bodies' FE parts have their own half-space response removed (:mod:`fem.compliance`), so this is
    the whole local term; it is tabulated over integer lattice offsets."""
    from fem.halfspace import surface_influence
    e1 = Vs / np.linalg.norm(Vs)
    nrm = np.cross(Vs, Vz)
    area = np.linalg.norm(nrm)
    e2 = np.cross(nrm / area, e1)
    a = 0.5 * np.linalg.norm(Vs)
    bh = area / (4 * a)
    di = np.arange(I.min() - I.max(), I.max() - I.min() + 1)
    dj = np.arange(J.min() - J.max(), J.max() - J.min() + 1)
    DI, DJ = np.meshgrid(di, dj, indexing="ij")
    X = DI * (Vs @ e1) + DJ * (Vz @ e1)
    Y = DI * (Vs @ e2) + DJ * (Vz @ e2)
    table = 2.0 * surface_influence(X, Y, a, bh, E, nu)
    return table[I[:, None] - I[None, :] - di[0], J[:, None] - J[None, :] - dj[0]]


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


def contact_system(lm: LoadedModel, phi1: float, strips, dz: float, ds: float, cycle: int,
                   lattice: dict) -> ContactSystem:
    """Gaps (separation field + micro-geometry), compliance (FE far field of both bodies, bilinearly
    interpolated, plus the half-space near field) and cell areas of the strips of one position."""
    model, fid = lm.model, lm.fid
    p1 = model.pinion
    tooth = np.concatenate([np.full(len(x), k) for k, _, x, *_ in strips])
    sl = np.concatenate([np.full(len(x), j) for _, j, x, *_ in strips])
    lat = np.concatenate([x[2] for x in strips])
    s = np.concatenate([x[3] for x in strips])
    z = np.concatenate([x[4] for x in strips])
    n = len(s)
    g0, h1, h2 = np.empty(n), np.empty(n), np.empty(n)
    gt, gs, gz = np.empty(n, int), np.empty(n), np.empty(n)
    P = np.empty((n, 3))
    for k in np.unique(tooth):
        m = tooth == k
        fg = flank_gaps(model, phi1, int(k), s[m], z[m], cycle=cycle)
        g0[m], h1[m], h2[m] = fg.gap, fg.lever1, fg.lever2
        gt[m], gs[m], gz[m], P[m] = fg.gear_tooth, fg.gear_s, fg.gear_z, fg.points
    # cell geometry: lattice steps across (Vs) and along (Vz) the line from the local flank tangents
    Ps, Pz = flank_tangents(p1, s, z)
    keys = np.array(sorted(lattice))
    t, st_s, st_z = np.array([lattice[k] for k in keys])[np.searchsorted(keys, tooth)].T
    Vs = st_s[:, None] * Ps + st_z[:, None] * Pz
    Vz = (Pz + t[:, None] * Ps) * dz
    area = np.linalg.norm(np.cross(Vs, Vz), axis=1)
    W1 = lm.body1.weights(tooth, s, z)
    W2 = lm.body2.weights(gt, gs, gz)
    C = np.asarray(W1 @ (W1 @ lm.body1.C).T) + np.asarray(W2 @ (W2 @ lm.body2.C).T)
    if fid.near_field:
        E, nu = model.case.young, model.case.poisson
        for k in np.unique(tooth):
            m = np.flatnonzero(tooth == k)
            c = m[len(m) // 2]
            C[np.ix_(m, m)] += near_field_block(lat[m], sl[m], Vs[c], Vz[c], E, nu)
    else:   # the coarse FE alone is (nearly) singular at sub-element spacing: a trace of regularisation
        C[np.diag_indices(n)] += 1e-6 * np.mean(np.diag(C))
    return ContactSystem(tooth, sl, lat, s, z, g0, h1, h2, gt, gs, gz, area, 0.5 * (C + C.T), W1, W2)
