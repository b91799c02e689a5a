"""Transverse-section primitives of the cylindrical-gear generators: the involute function and its
inverse, polar points in the tooth frame, and sampling of curves to a chord-error tolerance.

Frame: gear axis = z, tooth centred on +y; the helpers below measure angles clockwise from +y ("cw").
Sampling: chord error < ``_CHORD_TOL`` everywhere, point spacing <= ``_H_MAX`` on flank and fillet and
<= ``_H_MAX_ARC`` on root and tip arcs (:mod:`ltca.geometry.involute`, :mod:`ltca.geometry.shaper`).
"""
from __future__ import annotations

import numpy as np

__all__ = ["involute", "inverse_involute"]

_CHORD_TOL = 1e-6      # mm, chord error of the sampled profile
_H_MAX = 5e-3          # mm, largest point spacing on flank and fillet
_H_MAX_ARC = 0.05      # mm, largest point spacing on root and tip arcs


def involute(alpha):
    """Involute function ``inv(alpha) = tan(alpha) - alpha`` (vectorised), alpha in rad."""
    alpha = np.asarray(alpha, dtype=float)
    return np.tan(alpha) - alpha


def inverse_involute(inv):
    """Inverse of :func:`involute` for ``inv >= 0`` (vectorised), accurate to ~1e-15 rad.

    Newton on the convex increasing ``f(a) = tan a - a - inv`` (derivative ``tan^2 a``) from a start above the
    root, ``min((3 inv)^(1/3), pi/2 - 1/(inv + pi/2))``, so that it converges monotonically.
    """
    inv = np.asarray(inv, dtype=float)
    if np.any(inv < 0) or not np.all(np.isfinite(inv)):
        raise ValueError(f"inverse_involute: inv = {inv!r} must be finite and >= 0")
    a = np.minimum(np.cbrt(3.0 * inv), np.pi / 2 - 1.0 / (inv + np.pi / 2))
    for _ in range(60):
        t = np.tan(a)
        t2 = np.where(a > 0, t * t, 1.0)
        step = np.where(a > 0, (t - a - inv) / t2, 0.0)
        a = a - step
        if np.all(np.abs(step) <= 1e-15 * np.maximum(a, 1e-300)):
            break
    return a


def _pol(r, cw):
    """Points (..., 2) at radius r and clockwise angle cw from +y."""
    return np.stack([r * np.sin(cw), r * np.cos(cw)], axis=-1)


def _cw(p):
    """Clockwise polar angle from +y of points (..., 2)."""
    return np.arctan2(p[..., 0], p[..., 1])


def _rot_cw(p, ang):
    """Rotate points (..., 2) clockwise by ang (broadcast)."""
    c, s = np.cos(ang), np.sin(ang)
    return np.stack([p[..., 0] * c + p[..., 1] * s, -p[..., 0] * s + p[..., 1] * c], axis=-1)


def _resample(fun, t0: float, t1: float, h_max: float = _H_MAX, n_fine: int = 1501):
    """Parameters in [t0, t1] such that the chord error of ``fun`` stays below _CHORD_TOL.

    ``fun(t) -> (n, 2)`` points. The local spacing is ``min(h_max, sqrt(8 tol / kappa))`` (chord error of an
    arc ``h^2 kappa / 8``), kappa from the turning angle of a fine polyline.
    """
    t = np.linspace(t0, t1, n_fine)
    p = fun(t)
    d = np.diff(p, axis=0)
    ds = np.linalg.norm(d, axis=1)
    ang = np.abs(np.diff(np.unwrap(np.arctan2(d[:, 1], d[:, 0]))))
    kap = np.zeros(len(ds))
    k_nodes = ang / np.maximum(0.5 * (ds[1:] + ds[:-1]), 1e-300)
    kap[1:] = np.maximum(kap[1:], k_nodes)
    kap[:-1] = np.maximum(kap[:-1], k_nodes)
    h = np.minimum(h_max, np.sqrt(8.0 * _CHORD_TOL / np.maximum(kap, 1e-300)))
    cum = np.concatenate([[0.0], np.cumsum(ds / h)])
    n = max(int(np.ceil(cum[-1] * 1.05)) + 1, 3)
    return np.interp(np.linspace(0.0, cum[-1], n), cum, t)


def _arc(r, cw0, cw1, h_max=_H_MAX_ARC):
    """Arc (m, 2) at radius r from cw angle cw0 to cw1, chord error < _CHORD_TOL, spacing <= h_max."""
    n = max(int(np.ceil(abs(cw1 - cw0) * r / min(h_max, np.sqrt(8 * _CHORD_TOL * r)))) + 1, 2)
    return _pol(r, np.linspace(cw0, cw1, n))
