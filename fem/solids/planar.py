"""Plane geometry of transverse sections: rotation about the axis and distances to polylines (mm, rad).

The solid builders name each CAD surface by the transverse curve it was swept from: a surface's mid-point,
rotated back into the section, is matched to the nearest curve (:mod:`ltca.fem.solids.gear_body`,
:mod:`ltca.fem.solids.full_gear`).
"""
from __future__ import annotations

import numpy as np

__all__ = ["rot2", "polyline_distance", "Polylines"]


def rot2(xy: np.ndarray, phi: float) -> np.ndarray:
    """Points ``xy`` (n, 2) rotated counter-clockwise by ``phi`` (rad) about the origin."""
    c, s = np.cos(phi), np.sin(phi)
    return xy @ np.array([[c, s], [-s, c]])


def polyline_distance(p: np.ndarray, poly: np.ndarray) -> float:
    """Distance from point ``p`` (2,) to the polyline ``poly`` (m, 2)."""
    a, d = poly[:-1], np.diff(poly, axis=0)
    t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.maximum(np.einsum("ij,ij->i", d, d), 1e-300), 0, 1)
    return float(np.min(np.hypot(*(a + t[:, None] * d - p).T)))


class Polylines:
    """Distances from points to each of several polylines at once (:func:`polyline_distance` of each, the same
    arithmetic segment by segment): a body's labelling matches a hundred surfaces against tens of curves."""

    def __init__(self, polys: list[np.ndarray]):
        polys = [np.asarray(p, float) for p in polys]
        self.a = np.concatenate([p[:-1] for p in polys])
        self.d = np.concatenate([np.diff(p, axis=0) for p in polys])
        self.dd = np.maximum(np.einsum("ij,ij->i", self.d, self.d), 1e-300)
        self.start = np.cumsum([0] + [len(p) - 1 for p in polys[:-1]])

    def distance(self, p: np.ndarray) -> np.ndarray:
        """Distance from point ``p`` (2,) to every polyline, (n_polylines,)."""
        t = np.clip(np.einsum("ij,ij->i", p - self.a, self.d) / self.dd, 0, 1)
        return np.minimum.reduceat(np.hypot(*(self.a + t[:, None] * self.d - p).T), self.start)
