"""Unloaded tooth contact analysis of cylindrical pairs: separation field, contact path, unloaded TE.

The separation field is evaluated on a grid of the pinion's driving flank (arc length from the base
circle x axial position) against the gear's whole tooth outline, so edge (corner) contact shows up
as well as flank contact. The unloaded transmission error at a position is the smallest pinion
rotation that closes a gap: theta_0 = min_k g_k / h_k (h_k the lever arm of cell k).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ltca.geometry.cylindrical import arc_length, radius_of_arc
from ltca.geometry.cylindrical import flank_point_normal
from ltca.geometry.modification import modification_depth
from ltca.geometry.tip_edge import tip_edge_depth

from .model import PairModel

__all__ = ["FlankGaps", "flank_gaps", "TCAResult", "unloaded_tca", "first_contact", "contact_ratio", "ARCSEC_PER_RAD",
           "split_roll", "double_flank_tca"]

ARCSEC_PER_RAD = 180 * 3600 / np.pi   # arcsec per rad


@dataclass(frozen=True)
class FlankGaps:
    """Unloaded gaps of pinion flank points of one tooth at one position (arrays of one shape)."""
    tooth: int | np.ndarray  # an array when flank_gaps was given a tooth per point
    r: np.ndarray
    s: np.ndarray
    z: np.ndarray
    gap: np.ndarray          # mm, rigid gap incl. modifications of both members (+inf: no gear flank)
    lever1: np.ndarray       # mm
    lever2: np.ndarray       # mm
    gear_tooth: np.ndarray
    gear_r: np.ndarray
    gear_s: np.ndarray
    gear_z: np.ndarray
    points: np.ndarray       # pinion frame
    normals: np.ndarray      # pinion frame
    world: np.ndarray        # world frame points


def flank_gaps(model: PairModel, phi1: float, tooth, s: np.ndarray, z: np.ndarray, side: int = 1,
               cycle: int = 0) -> FlankGaps:
    """Gaps at pinion flank arc lengths ``s`` and axial positions ``z`` (broadcast) of ``tooth`` (an int, or an
    int array of their broadcast shape: a tooth per point).

    ``side`` +1 is the drive (right) flank, -1 the coast (left) flank. ``cycle`` counts the mesh
    cycles travelled: the model's teeth then stand for the physical teeth ``tooth - cycle`` of the
    pinion and ``gear_tooth + model.gear_shift * cycle`` of the gear, whose errors apply."""
    p1, p2 = model.pinion, model.gear
    s, z = np.broadcast_arrays(np.asarray(s, float), np.asarray(z, float))
    r = radius_of_arc(s, p1.r_base)
    P, N = flank_point_normal(p1, side, r, z, tooth=tooth)
    sep = model.pair.separation(phi1, P, N, side)
    b = model.face_width
    g = sep.gap + modification_depth(model.mod1, r, z, tooth - cycle, p1.r_base, p1.r_form_right, p1.r_tip, b,
                                     p1.z, side)
    if p1.tip_edge is not None:   # the pinion's rounded or chamfered tip edge (the gear's is in its outline)
        g = g + tip_edge_depth(p1, r) * np.cos(p1.beta_b)
    r2 = np.clip(sep.gear_r, p2.r_base, None)
    rf2 = p2.r_form_right if model.gear_side > 0 else p2.r_form_left
    g = g + modification_depth(model.mod2, r2, sep.gear_z, sep.gear_tooth + model.gear_shift * cycle, p2.r_base,
                               rf2, p2.r_tip, b, p2.z, side)
    return FlankGaps(tooth, r, s, z, g, sep.lever1, sep.lever2, sep.gear_tooth, sep.gear_r,
                     arc_length(r2, p2.r_base), sep.gear_z, P, N, sep.points)


def contact_ratio(model: PairModel) -> tuple[float, float]:
    """Transverse and overlap contact ratio from the generated tip and base radii (ISO 21771 sec. 5.4)."""
    p1, p2, pair = model.pinion, model.gear, model.pair
    pbt = 2 * np.pi * p1.r_base / p1.z
    g1 = np.sqrt(p1.r_tip ** 2 - p1.r_base ** 2)
    g2 = np.sqrt(p2.r_tip ** 2 - p2.r_base ** 2)
    if p2.internal:
        eps_a = (g1 - g2 + pair.a * np.sin(pair.alpha_w)) / pbt
    else:
        eps_a = (g1 + g2 - pair.a * np.sin(pair.alpha_w)) / pbt
    mn = p1.m_n
    eps_b = model.face_width * abs(np.sin(p1.beta)) / (np.pi * mn)
    return float(eps_a), float(eps_b)


@dataclass(frozen=True)
class TCAResult:
    """Unloaded TCA over a set of positions.

    roll : (n,) pinion roll angle from the pitch-point position of tooth 0, rad (positive along the motion)
    theta0 : (n,) pinion rotation to first contact, rad (unloaded TE = theta0 z1/z2 on the gear)
    te_arcsec : (n,) unloaded TE of the gear, arcsec (positive = gear lags)
    contact_tooth, contact_r, contact_z : (n,) where first contact happens
    min_gap : (n, nt) smallest gap per pinion tooth in ``teeth``, mm (after removing theta0)
    teeth : (nt,) pinion teeth scanned
    """
    roll: np.ndarray
    theta0: np.ndarray
    te_arcsec: np.ndarray
    contact_tooth: np.ndarray
    contact_r: np.ndarray
    contact_z: np.ndarray
    min_gap: np.ndarray
    teeth: np.ndarray
    eps_alpha: float
    eps_beta: float


def scan_grid(model: PairModel, ns: int = 240, nz: int = 9) -> tuple[np.ndarray, np.ndarray]:
    """Arc lengths and axial positions of the scan grid on the pinion's active flank."""
    rb = model.pinion.r_base
    lo, hi = model.pinion_range()
    s = np.linspace(arc_length(lo, rb), arc_length(hi, rb), ns)
    b = model.face_width
    return s, np.linspace(-0.5 * b, 0.5 * b, nz)


def first_contact(model: PairModel, phi1: float, teeth, ns: int = 240, nz: int = 9, detail: bool = False,
                  side: int = 1, cycle: int = 0):
    """Smallest pinion rotation (rad, driving direction) that closes a gap at pinion angle ``phi1``.

    The separation field is scanned on an (ns, nz) flank grid per tooth, then the minimum of g/h is
    refined along the profile by two rounds of parabolic interpolation through three points, which
    is exact for the locally quadratic gap of smooth flanks. With ``detail`` also returns the tooth,
    radius and axial position of the contact and the per-tooth minima.

    Every tooth is scanned and refined in the same array (one :func:`flank_gaps` per step for all teeth: the
    per-call cost dominated the 3-point refinements)."""
    s, z = scan_grid(model, ns, nz)
    teeth = np.asarray(list(teeth), int)
    nt = len(teeth)
    shape = (nt, ns, nz)
    S, Z = np.meshgrid(s, z, indexing="ij")
    fg = flank_gaps(model, phi1, np.broadcast_to(teeth[:, None, None], shape), np.broadcast_to(S, shape),
                    np.broadcast_to(Z, shape), side, cycle)
    ok = np.isfinite(fg.gap) & (fg.lever1 > 0)
    q = np.where(ok, fg.gap / np.where(ok, fg.lever1, 1.0), np.inf).reshape(nt, -1)
    flat = np.argmin(q, axis=1)
    i, j = np.unravel_index(flat, (ns, nz))
    qk, sk, zk = q[np.arange(nt), flat], s[i], z[j]
    h = np.full(nt, s[1] - s[0]) if ns > 1 else np.zeros(nt)
    live = ok.reshape(nt, -1).any(axis=1)      # teeth without a gap to close stay at +inf
    for _ in range(2):
        trial = np.clip(sk[:, None] + h[:, None] * np.array([-1.0, 0.0, 1.0]), s[0], s[-1])
        live &= (trial[:, 0] != trial[:, 1]) & (trial[:, 1] != trial[:, 2])
        idx = np.flatnonzero(live)
        if not idx.size:
            break
        f = flank_gaps(model, phi1, np.broadcast_to(teeth[idx, None], (idx.size, 3)), trial[idx],
                       np.broadcast_to(zk[idx, None], (idx.size, 3)), side, cycle)
        qq = f.gap / f.lever1
        den = qq[:, 0] - 2 * qq[:, 1] + qq[:, 2]
        good = np.isfinite(qq).all(axis=1) & (den > 0)
        live[idx[~good]] = False
        idx, qq, den = idx[good], qq[good], den[good]
        if idx.size:
            sv = np.clip(sk[idx] + 0.5 * h[idx] * (qq[:, 0] - qq[:, 2]) / den, s[0], s[-1])
            fv = flank_gaps(model, phi1, teeth[idx], sv, zk[idx], side, cycle)
            qv = fv.gap / fv.lever1
            better = np.isfinite(qv) & (qv < qk[idx])
            qk[idx[better]], sk[idx[better]] = qv[better], sv[better]
        h *= 0.25
    best, where = np.inf, (0, 0.0, 0.0)
    if nt and np.min(qk) < np.inf:
        k = int(np.argmin(qk))                  # the first of equal minima, as a scan tooth by tooth
        best = qk[k]
        where = (int(teeth[k]), float(np.sqrt(model.pinion.r_base ** 2 + 2 * model.pinion.r_base * sk[k])),
                 float(zk[k]))
    if detail:
        return best, where, qk
    return best


def unloaded_tca(model: PairModel, roll: np.ndarray, teeth=range(-3, 4), ns: int = 240, nz: int = 9) -> TCAResult:
    """Separation-field TCA at pinion roll angles ``roll`` (rad) for the pinion ``teeth``."""
    roll = np.atleast_1d(np.asarray(roll, float))
    teeth = np.asarray(list(teeth))
    n = len(roll)
    theta0 = np.empty(n)
    ct, cr, cz = np.zeros(n, int), np.zeros(n), np.zeros(n)
    ratio = np.empty((n, len(teeth)))
    for i, ps in enumerate(roll):
        theta0[i], (ct[i], cr[i], cz[i]), ratio[i] = first_contact(model, model.phi_pitch - ps, teeth, ns, nz, True)
    min_gap = (ratio - theta0[:, None]) * model.pinion.r_base
    te = theta0 / model.pair.ratio * ARCSEC_PER_RAD
    ea, eb = contact_ratio(model)
    return TCAResult(roll, theta0, te, ct, cr, cz, min_gap, teeth, ea, eb)


def split_roll(model: PairModel, roll: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Roll angles over several mesh cycles -> (roll within the cycle around tooth 0, cycle index)."""
    pitch = model.pitch_angle
    cycle = np.round(np.asarray(roll, float) / pitch).astype(int)
    return np.asarray(roll, float) - cycle * pitch, cycle


def double_flank_tca(model: PairModel, roll: np.ndarray, teeth=range(-2, 3)) -> tuple[np.ndarray, np.ndarray]:
    """Unloaded drive- and coast-side TE (arcsec of the gear) at pinion roll angles ``roll`` (rad, any range).

    Sign as in Wang et al.: TE = gear position minus its kinematic position (positive = ahead). The drive
    flanks touch with the gear behind (TE <= 0), the coast flanks with the gear ahead, so the backlash
    curve is coast TE minus drive TE (>= 0 when the pair has play)."""
    r_c, cyc = split_roll(model, roll)
    drive, coast = np.empty(len(r_c)), np.empty(len(r_c))
    for i, (rc, n) in enumerate(zip(r_c, cyc)):
        phi1 = model.phi_pitch - rc
        drive[i] = -first_contact(model, phi1, teeth, ns=160, nz=5, side=+1, cycle=int(n))
        coast[i] = first_contact(model, phi1, teeth, ns=160, nz=5, side=-1, cycle=int(n))
    scale = ARCSEC_PER_RAD / model.pair.ratio
    return drive * scale, coast * scale
