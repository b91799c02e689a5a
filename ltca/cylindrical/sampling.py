"""Positions per mesh cycle that resolve the cycle's load transitions.

A mesh cycle of a pair with overlap ratio below 1 alternates between zones with k and k + 1 pairs in contact
(k = floor(eps_alpha)); tip relief spreads the hand-over over the relieved roll range. A zone sampled by fewer
than :data:`MIN_PER_ZONE` positions leaves the TE steps and the load hand-over unresolved: the default number of
positions is raised to cover every zone, and a number given in the case or by ``--positions`` that does not
gets a warning.
"""
from __future__ import annotations

import math

import numpy as np

from .warnings import contact_ratio_transverse

__all__ = ["transition_zones", "positions_needed", "default_positions", "sampling_warnings", "MIN_PER_ZONE",
           "DEFAULT_POSITIONS", "MAX_DEFAULT_POSITIONS"]

MIN_PER_ZONE = 4            # positions at least in every transition zone
DEFAULT_POSITIONS = 30      # the default when the zones need no more
MAX_DEFAULT_POSITIONS = 120  # the automatic default never exceeds this (a warning says what would be needed)


def _relief_fraction(profile, mod, pitch_rotation: float, rotation_per_roll: float) -> float | None:
    """Share of a mesh cycle over which ``mod``'s tip relief is in mesh (None: no relief or default start)."""
    if mod.tip_relief <= 0 or mod.tip_relief_start_radius is None or profile.internal:
        return None
    rb = profile.r_base
    u = [math.sqrt(max((r / rb) ** 2 - 1.0, 0.0)) for r in (mod.tip_relief_start_radius, profile.r_tip)]
    return (u[1] - u[0]) * rotation_per_roll / pitch_rotation


def transition_zones(model) -> dict[str, float]:
    """Zones of a mesh cycle whose sampling matters, as shares of the cycle: the k- and (k+1)-pair zones (overlap
    ratio below 1 only: with full overlap the hand-over is gradual) and each member's tip-relief range (its
    default start is the end of the single-pair zone, which the pair zones cover already)."""
    c = model.case
    eps_a = contact_ratio_transverse(model)
    eps_b = abs(model.face_width * np.sin(c.helix_angle) / (np.pi * c.module))
    zones: dict[str, float] = {}
    if eps_b < 1.0 and np.isfinite(eps_a):
        k = int(math.floor(eps_a))
        f = eps_a - k
        if 0.02 < f < 0.98:
            zones[f"{k + 1}-pair contact zone"] = f
            zones[f"{k}-pair contact zone"] = 1.0 - f
    pitch = 2 * math.pi / model.pinion.z
    ratio = model.gear.z / model.pinion.z
    for name, prof, mod, per_roll in (("pinion", model.pinion, model.mod1, 1.0),
                                      ("gear", model.gear, model.mod2, ratio)):
        f = _relief_fraction(prof, mod, pitch, per_roll)
        if f is not None and f > 0:
            zones[f"{name} tip-relief range"] = f
    return zones


def positions_needed(model) -> int:
    """Positions per mesh cycle that put :data:`MIN_PER_ZONE` in every transition zone."""
    zones = transition_zones(model)
    return max([math.ceil(MIN_PER_ZONE / f - 1e-9) for f in zones.values()] or [1])


def default_positions(model) -> int:
    """The default positions per mesh cycle: :data:`DEFAULT_POSITIONS`, raised (up to
    :data:`MAX_DEFAULT_POSITIONS`) until every transition zone holds :data:`MIN_PER_ZONE`."""
    return int(min(MAX_DEFAULT_POSITIONS, max(DEFAULT_POSITIONS, positions_needed(model))))


def sampling_warnings(model, n: int) -> list[str]:
    """One line per transition zone that ``n`` positions per mesh cycle sample fewer than MIN_PER_ZONE times."""
    out = []
    zones = transition_zones(model)
    need = positions_needed(model)
    for name, f in zones.items():
        if n * f < MIN_PER_ZONE - 1e-9:
            out.append(f"{n} positions per mesh cycle put {n * f:.1f} positions in the {name} ({100 * f:.0f} % of "
                       f"the cycle; at least {MIN_PER_ZONE} resolve its transitions): use at least {need} "
                       "(analysis.positions or --positions)")
    return out
