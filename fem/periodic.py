"""Tooth-periodic compliance: the unit loads of one tooth stand for those of every loaded tooth.

Where the fine teeth of a body are turned copies of each other (tooth k is tooth 0 turned by ``k * pitch`` about
+z) and the body under them is axisymmetric (a sector-periodic fine region on a turned support), the response at
tooth a to a load on tooth b is the response at tooth ``c + a - b`` to the same load turned onto a centre tooth c:
displacements normal to the flank unchanged, stresses turned back by ``(b - c) * pitch``. Loading the centre tooth
alone and reading it and its neighbours up to ``n - 1`` teeth away (n loaded teeth) gives every block of the
n x n compliance and of the root-stress influence with a third of the back-substitutions for three loaded teeth.
The blocks at tooth distance 0 are the centre tooth's for every loaded tooth, which is the more complete
neighbourhood: the centre tooth has the most fine neighbours. A freely meshed body (the cylindrical ones, gmsh) has
teeth of the same shape but not the same mesh: the blocks then carry the centre tooth's mesh, a difference of the
size of the discretisation error (docs/design.md, "Compliance computed once").
"""
from __future__ import annotations

import numpy as np

__all__ = ["periodic_offsets", "turn_z", "voigt_turn"]

#: Voigt order of the stresses (xx, yy, zz, yz, xz, xy)
_VOIGT = ((0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1))


def periodic_offsets(loaded, teeth) -> tuple[int, np.ndarray] | None:
    """The centre tooth and the tooth distances ``-(n - 1) .. n - 1`` of n consecutive loaded teeth, or None where
    the loaded teeth are not consecutive or a tooth that far from the centre is not meshed (``teeth``)."""
    loaded = [int(k) for k in loaded]
    n = len(loaded)
    if n < 2 or loaded != list(range(loaded[0], loaded[0] + n)):
        return None
    centre = loaded[n // 2]
    offsets = np.arange(-(n - 1), n)
    if not set((centre + offsets).tolist()) <= {int(k) for k in teeth}:
        return None
    return centre, offsets


def turn_z(points: np.ndarray, angle: float) -> np.ndarray:
    """Points or vectors (..., 3) turned by ``angle`` (rad) about +z."""
    c, s = np.cos(angle), np.sin(angle)
    p = np.asarray(points, dtype=float)
    return np.stack([c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1], p[..., 2]], -1)


def voigt_turn(angle: float) -> np.ndarray:
    """The (6, 6) matrix T with ``sigma' = T sigma`` (Voigt xx, yy, zz, yz, xz, xy) for the stress tensor turned by
    ``angle`` (rad) about +z: ``Q sigma Q^T``, Q the rotation."""
    Q = turn_z(np.eye(3), angle).T          # columns: the turned unit vectors
    T = np.zeros((6, 6))
    for col, (k, m) in enumerate(_VOIGT):
        E = np.zeros((3, 3))
        E[k, m] = E[m, k] = 1.0
        S = Q @ E @ Q.T
        T[:, col] = [S[i, j] for i, j in _VOIGT]
    return T
