"""Generated surface on the universal face-milling machine: motions, tilt and swivel, formate members.

:func:`universal_state` is :func:`ltca.geometry.bevel.generation.surface_state` for settings that are not the basic
cradle (:attr:`ltca.geometry.bevel.machine.MachineSettings.is_basic`); the equation of meshing with the derivative
terms of the relative velocity is given in :mod:`ltca.geometry.bevel.generation`.  The tilt rotation is Rodrigues'
formula about the tilt axis of :func:`ltca.geometry.bevel.machine.tilt_rotation`.
"""
from __future__ import annotations

import numpy as np

from .surface_state import SurfaceState, _cross, _ez_cross, _rotz, _vectors, work_state
from .machine import FlankCut, roll, tilt_rotation

__all__ = ["universal_state", "blade_coordinates"]


def _rodrigues(a: np.ndarray, ang: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rotation of the vectors ``v`` by ``ang`` about the unit axes ``a`` (all (..., 3) / (...))."""
    c, s = np.cos(ang)[..., None], np.sin(ang)[..., None]
    return v * c + np.cross(a, v) * s + a * np.einsum("...i,...i", a, v)[..., None] * (1.0 - c)


def universal_state(fc: FlankCut, u: np.ndarray, theta: np.ndarray, psi: np.ndarray,
                     with_work: bool = True) -> SurfaceState:
    """:func:`surface_state` on the universal machine (module docstring): motions, tilt, swivel, formate."""
    ms = fc.machine
    psi = np.asarray(psi, dtype=float)
    r_c, n_c = fc.cutter.surface(u, theta)
    shape = r_c.shape[:-1]
    psi_b = np.broadcast_to(psi, shape)
    S, dS = ms.motion("radial_setting", psi_b)
    eq = np.array([np.cos(ms.cradle_angle), np.sin(ms.cradle_angle), 0.0])
    if ms.tilt or ms.tilt_motion:
        i, di = ms.motion("tilt", psi_b)
        j, dj = ms.motion("swivel", psi_b)
        a, a_perp, i = tilt_rotation(ms, i, j)
        rt_c, nt_c = _rodrigues(a, i, r_c), _rodrigues(a, i, n_c)
        # d(R_t r_c)/dpsi = dR/di r_c i' + dR/db r_c b', b = q - j
        c_, s_ = np.cos(i)[..., None], np.sin(i)[..., None]
        ar = np.einsum("...i,...i", a, r_c)[..., None]
        dR_di = -r_c * s_ + np.cross(a, r_c) * c_ + a * ar * s_
        dR_db = np.cross(a_perp, r_c) * s_ + (a_perp * ar + a * np.einsum("...i,...i", a_perp, r_c)[..., None]) \
            * (1.0 - c_)
        drt = dR_di * di[..., None] - dR_db * dj[..., None]
    else:
        rt_c, nt_c, drt = r_c, n_c, 0.0
    r_p = rt_c + S[..., None] * eq
    r_m = _rotz(r_p, psi_b)
    n_m = _rotz(nt_c, psi_b)
    k = ms.work_axis
    Em, dEm = ms.motion("blank_offset", psi_b)
    XB, dXB = ms.motion("sliding_base", psi_b)
    O = _vectors(ms.center_to_back * k[0] + 0.0 * Em, Em, XB + ms.center_to_back * k[2])
    dO = _vectors(np.zeros_like(Em), dEm, dXB)
    d = r_m - O
    phi, dphi = roll(ms, psi_b)
    if ms.formate:
        f = ms.radial_setting * psi_b
    else:
        v = _ez_cross(r_m) + _rotz(dS[..., None] * eq + drt, psi_b) - dO - dphi[..., None] * _cross(k, d)
        f = np.einsum("...i,...i", n_m, v)
    return work_state(ms, d, r_m, n_m, f, phi, with_work)


def blade_coordinates(fc: FlankCut, r_w: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """Blade parameters (u, theta, psi) of work points ``r_w`` (n, 3) that the blade passes at cradle roll
    ``psi`` (n,): the work point carried to the cutter frame (the inverse of :func:`surface_state`'s chain),
    u from its depth below the tip plane.  A starting guess for :func:`solve_axial_points`, exact for a point
    on the blade surface; shape (n, 3)."""
    ms = fc.machine
    psi = np.asarray(psi, dtype=float)
    phi, _ = roll(ms, psi)
    Em, _ = ms.motion("blank_offset", psi)
    XB, _ = ms.motion("sliding_base", psi)
    S, _ = ms.motion("radial_setting", psi)
    k = ms.work_axis
    O = _vectors(ms.center_to_back * k[0] + 0.0 * Em, Em, XB + ms.center_to_back * k[2])
    r_m = O + _rotz(np.asarray(r_w, dtype=float), phi) @ ms.work_basis.T
    r_c = _rotz(r_m, -psi) - S[..., None] * np.array([np.cos(ms.cradle_angle), np.sin(ms.cradle_angle), 0.0])
    if ms.tilt or ms.tilt_motion:
        i, _ = ms.motion("tilt", psi)
        j, _ = ms.motion("swivel", psi)
        a, _, i = tilt_rotation(ms, i, j)
        r_c = _rodrigues(a, -i, r_c)
    u = fc.cutter.u_at_depth(np.maximum(-r_c[..., 2], 0.0))
    return _vectors(u, np.arctan2(r_c[..., 1], r_c[..., 0]), psi)
