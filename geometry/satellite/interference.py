"""Interference of the satellite and the central wheel over the whole revolution, and the thinning that ends it.

Kinematic reference (:mod:`ltca.geometry.satellite.mesh`): for each direction d the satellite sits where the
mesh pair's involutes touch on that side (``delta = -d beta``). The pair is interference-free when, at every
position of one mesh cycle (which covers every tooth pair of the revolution), both these placements are
free of overlap, i.e. lie in the exact free window ``[drive, coast]`` of :meth:`EccentricMesh.window`:

    margin = min(-beta - drive, coast + beta, beta - drive, coast - beta) >= 0        (rad)

(negative backlash makes ``coast + beta < 0``; a first contact anywhere but on the mesh pair's involutes
makes one of the terms negative). Reported in um along the line of action (times r_b1).

Where and how deep, at the two nominal placements, by the partners of each penetrating point (outline
kinds, :class:`ltca.geometry.outline.OutlineQuery`), true normal depth in um:

* ``involute``: flank into flank: the tooth does not fit the space at this centre distance (backlash < 0);
* ``tip``: a tip corner or tip land of one member into the other's involute flank;
* ``trochoid``: tip into tip: the satellite tip's path relative to the wheel crosses the wheel tooth's tip
  region outside the mesh (secondary interference, e.g. opposite the mesh with a tooth difference of one);
* ``fillet``: anything into a fillet or root (contact below the form diameter).

Both directions are checked: the profiles are symmetric, so direction -1 at phi mirrors direction +1 at
-phi and gives the same maxima over a full cycle; computing both is cheap and confirms it.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..profile import ToothProfile
from .forming import form_satellite
from .mesh import EccentricMesh
from .tools import SatelliteDesign

__all__ = ["Penetration", "InterferenceReport", "ThinningResult", "analyse_interference", "margin",
           "minimum_thinning", "KINDS"]

KINDS = ("involute", "tip", "trochoid", "fillet")


@dataclass(frozen=True)
class Penetration:
    """Deepest penetration of one kind: depth (um), satellite tooth ``pair`` (label, 0 at the mesh at
    phi = 0), ``psi_deg`` its angle from the line of centres (clockwise +, at that position), wheel tooth,
    radii on satellite and wheel (mm), position ``phi`` (rad) and ``direction`` (+1 right flanks working)."""

    kind: str
    depth_um: float
    pair: int
    psi_deg: float
    wheel_tooth: int
    r_satellite: float
    r_wheel: float
    phi: float
    direction: int


@dataclass(frozen=True)
class InterferenceReport:
    """Result of :func:`analyse_interference`.

    interferes : margin < -tol.   margin_um : worst margin over the cycle (um along the line of action).
    free_play_um : smallest free play (coast - drive) over the cycle, um.   backlash : circumferential,
    on the working circles, mm.   kinds : dict kind -> :class:`Penetration` (deepest over both
    directions; absent kinds did not occur).   by_direction : {+1: {...}, -1: {...}}.
    """

    interferes: bool
    margin_um: float
    free_play_um: float
    backlash: float
    kinds: dict
    by_direction: dict
    n_positions: int


def _kind(k1, k2):
    out = np.full(len(k1), "tip", dtype=object)
    out[(k1 == 2) & (k2 == 2)] = "involute"
    out[(k1 == 3) & (k2 == 3)] = "trochoid"
    out[(k1 <= 1) | (k2 <= 1)] = "fillet"
    return out


def margin(mesh: EccentricMesh, n_positions: int = 48) -> tuple[float, float]:
    """Worst interference margin and smallest free play over one mesh cycle, both in rad (module doc)."""
    b = mesh.beta
    worst, play = np.inf, np.inf
    for phi in np.arange(n_positions) * (2 * np.pi / mesh.z1) / n_positions:
        w = mesh.window(phi)
        worst = min(worst, -b - w.drive, w.coast + b, b - w.drive, w.coast - b)
        play = min(play, w.free_play)
    return float(worst), float(play)


def analyse_interference(mesh: EccentricMesh, n_positions: int = 48, tol_um: float = 0.1) -> InterferenceReport:
    """Tip, trochoid, fillet (and flank) interference over one mesh cycle, both directions (module doc)."""
    if not (isinstance(n_positions, (int, np.integer)) and n_positions >= 1):
        raise ValueError(f"n_positions = {n_positions!r}: allowed an integer >= 1")
    rb = mesh.sat.r_base * 1e3
    p1 = 2 * np.pi / mesh.z1
    by_dir = {}
    for d in (1, -1):
        best = {}
        for phi in np.arange(n_positions) * p1 / n_positions:
            delta = -d * mesh.beta
            s = mesh.sample(phi, delta, d, cap=0.0, only_inside=True)
            if not len(s.distance):
                continue
            kinds = _kind(s.kind1, s.kind2)
            for kd in np.unique(kinds):
                sel = np.nonzero(kinds == kd)[0]
                i = sel[np.argmin(s.distance[sel])]
                depth = -1e3 * s.distance[i]
                if depth > tol_um and depth > best.get(kd, Penetration(kd, -1, 0, 0, 0, 0, 0, 0, d)).depth_um:
                    psi = np.degrees((s.pair[i] * p1 + phi - delta + np.pi) % (2 * np.pi) - np.pi)
                    best[kd] = Penetration(str(kd), float(depth), int(s.pair[i]), float(psi), int(s.wheel_tooth[i]),
                                           float(s.r1[i]), float(s.r2[i]), float(phi), d)
        by_dir[d] = best
    kinds = {}
    for d in (1, -1):
        for kd, pen in by_dir[d].items():
            if kd not in kinds or pen.depth_um > kinds[kd].depth_um:
                kinds[kd] = pen
    mg, play = margin(mesh, n_positions)
    return InterferenceReport(interferes=bool(mg * rb < -tol_um or kinds), margin_um=mg * rb,
                              free_play_um=play * rb, backlash=float(mesh.backlash), kinds=kinds,
                              by_direction=by_dir, n_positions=int(n_positions))


@dataclass(frozen=True)
class ThinningResult:
    """Smallest Eq. 3 thinning coefficient k that removes all interference (NaN: none below ``k_max``),
    the paper's k and the margins (um along the line of action) at both; ``evaluations`` of the margin."""

    k_min: float
    k_seed: float
    margin_at_k_min_um: float
    margin_at_seed_um: float
    k_max: float
    evaluations: int


def minimum_thinning(design: SatelliteDesign, wheel: ToothProfile, e: float, method: str = "special_hob",
                     n_positions: int = 32, tol: float = 1e-4, tol_um: float = 0.1) -> ThinningResult:
    """Bisection on k in [0, k_max] for the smallest thinning with margin >= -tol_um (module doc).

    The satellite is cut by ``method`` at each k (the design's other data kept). ``k_max`` is the largest
    k below 1 that still leaves a tip land (pointed teeth cannot be generated).
    """
    count = [0]

    def mg(k):
        count[0] += 1
        sat = form_satellite(replace(design, thinning=k), method).profile
        mesh = EccentricMesh(sat, wheel, e)
        return margin(mesh, n_positions)[0] * sat.r_base * 1e3

    k_max = 0.999
    while True:                               # the largest k that still cuts a tooth with a tip land
        try:
            seed_or_max = mg(k_max)
            break
        except ValueError:
            k_max = round(k_max - 0.01, 6)
            if k_max <= 0:
                raise
    m_seed = mg(design.thinning)
    if mg(0.0) >= -tol_um:
        return ThinningResult(0.0, design.thinning, mg(0.0), m_seed, k_max, count[0])
    if seed_or_max < -tol_um:
        return ThinningResult(float("nan"), design.thinning, float("nan"), m_seed, k_max, count[0])
    lo, hi = 0.0, k_max
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if mg(mid) >= -tol_um:
            hi = mid
        else:
            lo = mid
    return ThinningResult(float(hi), design.thinning, mg(hi), m_seed, k_max, count[0])
