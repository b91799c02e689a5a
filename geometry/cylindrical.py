"""3D involute-helicoid flanks of cylindrical gears from the transverse tooth profile.

The flank is the screw motion of the transverse involute (Litvin & Fuentes 2004, sec. 14.3):

    p(r, zeta) = Rot_z(A) [-r sin a, r cos a, 0] + [0, 0, zeta],   A = zeta tan(beta) / r_ref - tooth 2 pi / z

with ``a = profile.flank_angle(r, side)`` (polar angle from +y, counter-clockwise positive). Positive
``beta`` (right hand) turns the transverse section counter-clockwise (seen from +z) as zeta grows, like a
right-hand screw. Tooth ``k`` is tooth 0 rotated by ``-k 2 pi / z`` about z, i.e. clockwise seen from +z
for positive ``k``. ``zeta`` is the axial coordinate (mm), 0 at mid-face.

Curvatures (analytic): the involute helicoid is developable; its generators (tangent to the base helix)
have zero normal curvature and the other principal direction is the transverse profile tangent, with
normal curvature ``cos(beta_b) / sqrt(r^2 - r_b^2)`` (Meusnier's theorem applied to the transverse involute,
whose curvature radius is ``sqrt(r^2 - r_b^2)`` and whose principal normal makes the angle beta_b with the
surface normal). Sign: + for external (convex), - for internal (concave) flanks.
"""
from __future__ import annotations

import numpy as np

from .flank import Flank
from .involute import ToothProfile

__all__ = ["helical_flank", "flank_point_normal", "flank_curvatures", "arc_length", "radius_of_arc"]


def _check_side(side):
    if side not in (-1, 1):
        raise ValueError(f"side = {side!r}: allowed -1 (left, x < 0) or +1 (right, x > 0)")


def _frame(profile: ToothProfile, side: int, r, zeta, tooth: int):
    r, zeta = np.broadcast_arrays(np.asarray(r, dtype=float), np.asarray(zeta, dtype=float))
    a = profile.flank_angle(r, side)
    A = a + zeta * np.tan(profile.beta) / profile.r_ref - tooth * 2 * np.pi / profile.z
    sA, cA = np.sin(A), np.cos(A)
    p = np.stack([-r * sA, r * cA, zeta], axis=-1)
    # da/dr = -side * d(half)/dr;  d inv(alpha_r)/dr = tan(alpha_r) / r
    sig = -1.0 if profile.internal else 1.0
    dadr = side * sig * profile.involute_roll(r) / r
    e_A = np.stack([-r * cA, -r * sA, np.zeros_like(r)], axis=-1)          # dp/dA
    p_r = np.stack([-sA, cA, np.zeros_like(r)], axis=-1) + e_A * dadr[..., None]
    k = np.tan(profile.beta) / profile.r_ref
    p_z = e_A * k + np.array([0.0, 0.0, 1.0])
    return p, p_r, p_z, e_A


def flank_point_normal(profile: ToothProfile, side: int, r, zeta, tooth: int = 0):
    """Exact points and unit normals of the involute helicoid flank.

    Parameters
    ----------
    profile : ToothProfile
    side : int         +1 right flank (x > 0 on tooth 0), -1 left flank.
    r : array_like     transverse radius, mm (>= r_base), any shape, broadcast with ``zeta``.
    zeta : array_like  axial position, mm (0 at mid-face).
    tooth : int        tooth index (rotation -tooth 2 pi / z about z).

    Returns
    -------
    points : ndarray (..., 3) mm
    normals : ndarray (..., 3) unit, out of the material (towards the space beside the flank).
    """
    _check_side(side)
    p, p_r, p_z, e_A = _frame(profile, side, r, zeta, tooth)
    n = np.cross(p_r, p_z)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    # out of the material = towards the gap: decreasing polar angle for the right flank (side +1)
    flip = np.einsum("...i,...i", n, -side * e_A) < 0
    n = np.where(flip[..., None], -n, n)
    return p, n


def flank_curvatures(profile: ToothProfile, side: int, r, zeta, tooth: int = 0):
    """Analytic principal curvatures (..., 2), k1 >= k2 (1/mm), and directions (..., 2, 3).

    External: k1 = cos(beta_b)/sqrt(r^2 - r_b^2) along the transverse profile tangent, k2 = 0 along the
    generator; internal: k1 = 0 (generator), k2 = -cos(beta_b)/sqrt(r^2 - r_b^2) (profile tangent).
    """
    _check_side(side)
    p, p_r, p_z, e_A = _frame(profile, side, r, zeta, tooth)
    _, n = flank_point_normal(profile, side, r, zeta, tooth)
    t = p_r / np.linalg.norm(p_r, axis=-1, keepdims=True)
    g = np.cross(n, t)
    rr = np.broadcast_to(np.asarray(r, dtype=float), p.shape[:-1])
    with np.errstate(divide="ignore"):
        kap = np.cos(profile.beta_b) / np.sqrt(np.maximum(rr ** 2 - profile.r_base ** 2, 0.0))
    zero = np.zeros_like(kap)
    if profile.internal:
        k = np.stack([zero, -kap], axis=-1)
        d = np.stack([g, t], axis=-2)
    else:
        k = np.stack([kap, zero], axis=-1)
        d = np.stack([t, g], axis=-2)
    return k, d


def helical_flank(profile: ToothProfile, side: int, face_width: float, nu: int, nv: int,
                  r_range: tuple[float, float] | None = None, tooth: int = 0) -> Flank:
    """Gridded involute-helicoid flank of one tooth.

    Parameters
    ----------
    profile : ToothProfile
    side : int           +1 right, -1 left.
    face_width : float   b, mm (> 0): zeta in [-b/2, b/2].
    nu, nv : int         grid size along the profile (radius) and the face (>= 2 each).
    r_range : (float, float) or None
        Radii (mm) of the first and last grid row, from root to tip; None -> from the form circle to the
        tip circle (internal: r_form down to r_tip, so u decreases).
    tooth : int          tooth index.

    Returns
    -------
    Flank with u = radius (mm), v = axial position (mm), analytic normals and curvatures.
    """
    _check_side(side)
    if not (np.isfinite(face_width) and face_width > 0):
        raise ValueError(f"face_width = {face_width!r}: allowed > 0 mm")
    for name, val in (("nu", nu), ("nv", nv)):
        if not (isinstance(val, (int, np.integer)) and val >= 2):
            raise ValueError(f"{name} = {val!r}: allowed an integer >= 2")
    r_form = profile.r_form_right if side == 1 else profile.r_form_left
    if r_range is None:
        r_range = (r_form, profile.r_tip)
    lo, hi = sorted(r_range)
    if lo < profile.r_base * (1 - 1e-12) or not np.all(np.isfinite(r_range)) or lo == hi:
        raise ValueError(f"r_range = {r_range!r}: allowed two distinct radii >= r_base = {profile.r_base} mm")
    u = np.linspace(r_range[0], r_range[1], nu)
    v = np.linspace(-face_width / 2, face_width / 2, nv)
    R, Z = np.meshgrid(u, v, indexing="ij")
    p, n = flank_point_normal(profile, side, R, Z, tooth)
    k, d = flank_curvatures(profile, side, R, Z, tooth)
    return Flank(points=p, normals=n, u=u, v=v, curvatures=k, directions=d,
                 side="right" if side == 1 else "left", tooth=int(tooth), u_name="r", v_name="z",
                 meta={"kind": "involute helicoid", "internal": profile.internal, "beta": profile.beta,
                       "r_base": profile.r_base, "beta_b": profile.beta_b})


def arc_length(r: np.ndarray, r_base: float) -> np.ndarray:
    """Involute arc length from the base circle, s = (r^2 - r_b^2) / (2 r_b) (mm)."""
    return (np.asarray(r, float) ** 2 - r_base ** 2) / (2.0 * r_base)


def radius_of_arc(s: np.ndarray, r_base: float) -> np.ndarray:
    """Inverse of :func:`arc_length`."""
    return np.sqrt(r_base ** 2 + 2.0 * r_base * np.asarray(s, float))
