"""Unloaded separations of every satellite/wheel tooth pair over the mesh cycle, both directions.

For each position of one mesh cycle (which covers all pairs of the revolution, :mod:`ltca.geometry.satellite.mesh`)
the satellite is turned, the wheel held, until its first contact in the direction (clockwise: right flanks,
``+1``; counter-clockwise: left flanks, ``-1``); the separation of pair j is the further rotation until
satellite tooth j touches too, given as its arc on the satellite's base circle (um), i.e. the gap along the
line of action: for two involute flanks exactly the gap along their common normal, and the same measure
as the loaded TE (rad times r_b1). It is exact (:meth:`EccentricMesh.window`, the polar-shift argument),
not a linearisation. This is the input the LTCA needs to pick the pairs in near contact.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .mesh import EccentricMesh

__all__ = ["UnloadedGaps", "unloaded_gaps"]


@dataclass(frozen=True)
class UnloadedGaps:
    """Gaps of all pairs over one mesh cycle.

    phi : (n,) rad, positions (satellite rotation).   pairs : (z1,) satellite tooth labels, 0 at the mesh at
    phi = 0, clockwise +.   gap_um : {+1: (n, z1), -1: (n, z1)} um along the line of action from the first
    contact in that direction (0 for the touching pair; inf where the tooth meets nothing).
    first_contact_um : {+1: (n,), -1: (n,)} how far (um along the line of action) the first contact comes
    before the nominal involute contact of the mesh pair (0: the involutes touch first; > 0: interference).
    free_play_um : (n,) the whole rotational play, um along the line of action.
    """

    phi: np.ndarray
    pairs: np.ndarray
    gap_um: dict
    first_contact_um: dict
    free_play_um: np.ndarray

    def pairs_within(self, threshold_um: float, direction: int = 1) -> np.ndarray:
        """Number of pairs with a gap below ``threshold_um`` at each position, (n,) int."""
        return np.sum(self.gap_um[direction] <= threshold_um, axis=1)


def unloaded_gaps(mesh: EccentricMesh, n_positions: int = 24) -> UnloadedGaps:
    """Gaps (um) of every tooth pair at ``n_positions`` positions of one mesh cycle, both directions."""
    if not (isinstance(n_positions, (int, np.integer)) and n_positions >= 1):
        raise ValueError(f"n_positions = {n_positions!r}: allowed an integer >= 1")
    rb = mesh.sat.r_base * 1e3
    phi = np.arange(n_positions) * (2 * np.pi / mesh.z1) / n_positions
    win = [mesh.window(p) for p in phi]
    b = mesh.beta
    return UnloadedGaps(
        phi=phi, pairs=np.arange(mesh.z1) - mesh.z1 // 2,
        gap_um={1: rb * np.stack([w.drive_gap for w in win]), -1: rb * np.stack([w.coast_gap for w in win])},
        first_contact_um={1: rb * np.array([w.drive + b for w in win]), -1: rb * np.array([b - w.coast for w in win])},
        free_play_um=rb * np.array([w.free_play for w in win]))
