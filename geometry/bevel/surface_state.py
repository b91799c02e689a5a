"""The state of a generated flank point (position, normal, the equation of meshing and its derivatives) and the
small vector helpers that the cradle generators (:mod:`ltca.geometry.bevel.generation`, the universal machine
:mod:`ltca.geometry.bevel.universal`) share. Points and vectors are (..., 3) arrays, mm."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["SurfaceState", "work_state", "cross3", "norm1d"]


@dataclass(frozen=True)
class SurfaceState:
    """Generated-surface quantities at parameters (u, theta, psi); arrays shaped like the inputs.

    r_w, n_w : (..., 3) point and unit normal (out of the work) in the work body frame;
    f : (...) equation of meshing, mm;  Z, rho : axial-section coordinates of the point, mm;
    r_m, n_m : (..., 3) the same point and normal in the machine frame at the generating instant;
    phi : (...) work roll angle.
    """

    r_w: np.ndarray
    n_w: np.ndarray
    f: np.ndarray
    Z: np.ndarray
    rho: np.ndarray
    r_m: np.ndarray
    n_m: np.ndarray
    phi: np.ndarray


def _vectors(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """(..., 3) vectors of broadcast components (np.stack without its per-call overhead; the same values)."""
    try:                                           # arrays or numpy scalars of one shape and type: the usual case
        same = x.shape == y.shape == z.shape and x.dtype == y.dtype == z.dtype
    except AttributeError:
        same = False
    if same:
        out = np.empty(x.shape + (3,), x.dtype)
    else:
        out = np.empty(np.broadcast_shapes(np.shape(x), np.shape(y), np.shape(z)) + (3,), np.result_type(x, y, z))
    out[..., 0], out[..., 1], out[..., 2] = x, y, z
    return out


def _rotz(vec: np.ndarray, ang: np.ndarray) -> np.ndarray:
    """(..., 3) vectors turned by ``ang`` (rad, broadcast with them) about z."""
    return _rotz_cs(vec, np.cos(ang), np.sin(ang))


def _rotz_cs(vec: np.ndarray, c: np.ndarray, s: np.ndarray) -> np.ndarray:
    """:func:`_rotz` by the angle of cosine ``c`` and sine ``s``."""
    x, y = vec[..., 0], vec[..., 1]
    return _vectors(c * x - s * y, s * x + c * y, vec[..., 2])


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b of a (3,) vector and (..., 3) vectors: np.cross's arithmetic (the same products and differences,
    so the same bits) without its axis handling, which cost a third of a bevel LTCA cycle."""
    x, y, z = b[..., 0], b[..., 1], b[..., 2]
    return _vectors(a[1] * z - a[2] * y, a[2] * x - a[0] * z, a[0] * y - a[1] * x)


def cross3(a, b) -> np.ndarray:
    """a x b of two (3,) vectors, as np.cross computes it (the same products and differences) at a fraction of its
    per-call cost."""
    a0, a1, a2 = a
    b0, b1, b2 = b
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def norm1d(a: np.ndarray) -> float:
    """Euclidean length of a 1-D vector, as np.linalg.norm computes it (the square root of a . a)."""
    return math.sqrt(a.dot(a))


def _ez_cross(b: np.ndarray) -> np.ndarray:
    """e_z x b of (..., 3) vectors, as :func:`_cross` (e_z = (0, 0, 1))."""
    return _cross(np.array([0.0, 0.0, 1.0]), b)


def work_state(ms, d: np.ndarray, r_m: np.ndarray, n_m: np.ndarray, f: np.ndarray, phi: np.ndarray,
               with_work: bool) -> SurfaceState:
    """The state of generated points given their machine-frame position ``r_m``, normal ``n_m``, offset ``d`` from
    the work origin (..., 3), the meshing function ``f`` and the work roll ``phi``: axial position Z and radius rho
    about the work axis, and with ``with_work`` the point and normal in the work's own frame."""
    k, B = ms.work_axis, ms.work_basis
    Z = d @ k
    rho = np.sqrt(np.maximum(np.einsum("...i,...i", d, d) - Z ** 2, 0.0))
    if with_work:
        c, s = np.cos(-phi), np.sin(-phi)
        r_w, n_w = _rotz_cs(d @ B, c, s), _rotz_cs(n_m @ B, c, s)
    else:
        r_w = n_w = None
    return SurfaceState(r_w, n_w, f, Z, rho, r_m, n_m, phi)
