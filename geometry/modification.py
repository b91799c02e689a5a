"""Flank modifications (micro-geometry) as material removed along the flank normal.

Profile modifications are functions of the roll length L = sqrt(r^2 - r_b^2) (distance along the
line of action in the transverse plane, ISO 21771 sec. 4.3), lead modifications of the axial
position z. Positive values remove material (open the gap).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["FlankModification", "modification_depth"]


@dataclass(frozen=True)
class FlankModification:
    """Micro-geometry of one member (all lengths in mm).

    tip_relief : C_a, depth at the tip; starts at ``tip_relief_start_radius`` and grows as
        ((L - L_start) / (L_tip - L_start)) ** ``tip_relief_exponent``.
    profile_crowning : C_alpha, parabola over the active profile [r_form, r_tip], zero at its middle.
    lead_crowning : C_beta, parabola over the face width, zero at mid-face, C_beta at both ends.
    lead_slope : f_Hbeta, linear over the face, zero at mid-face, +f/2 at z = +b/2.
    pitch_errors : per tooth index, the flank's position error along its normal (+ = moved back).
    """
    tip_relief: float = 0.0
    tip_relief_start_radius: float | None = None
    tip_relief_exponent: float = 1.0
    profile_crowning: float = 0.0
    lead_crowning: float = 0.0
    lead_slope: float = 0.0
    pitch_errors: tuple[tuple[int, float], ...] = ()


def modification_depth(mod: FlankModification, r: np.ndarray, z: np.ndarray, tooth: np.ndarray,
                       r_base: float, r_form: float, r_tip: float, face_width: float) -> np.ndarray:
    """Material removed (mm) at flank radius ``r`` and axial position ``z`` of tooth ``tooth``.

    Parameters
    ----------
    mod : FlankModification
    r, z, tooth : ndarray, broadcastable
        Radius (mm), axial position (mm, 0 at mid-face), tooth index.
    r_base, r_form, r_tip : float
        Base, form (start of the active involute) and tip radius, mm.
    face_width : float
        mm.

    Returns
    -------
    ndarray
        Depth in mm, same broadcast shape.
    """
    r = np.asarray(r, float)
    z = np.asarray(z, float)
    L = np.sqrt(np.maximum(r * r - r_base * r_base, 0.0))
    L_tip = np.sqrt(r_tip ** 2 - r_base ** 2)
    L_form = np.sqrt(max(r_form ** 2 - r_base ** 2, 0.0))
    out = np.zeros(np.broadcast_shapes(r.shape, z.shape, np.shape(tooth)))
    if mod.tip_relief > 0:
        rs = mod.tip_relief_start_radius if mod.tip_relief_start_radius else r_tip - 0.4 * (r_tip - r_form)
        Ls = np.sqrt(max(rs ** 2 - r_base ** 2, 0.0))
        xi = np.clip((L - Ls) / max(L_tip - Ls, 1e-12), 0.0, None)
        out = out + mod.tip_relief * xi ** mod.tip_relief_exponent
    if mod.profile_crowning > 0:
        mid, half = 0.5 * (L_tip + L_form), 0.5 * (L_tip - L_form)
        out = out + mod.profile_crowning * ((L - mid) / half) ** 2
    if mod.lead_crowning > 0:
        out = out + mod.lead_crowning * (2.0 * z / face_width) ** 2
    if mod.lead_slope != 0:
        out = out + mod.lead_slope * z / face_width
    if mod.pitch_errors:
        tooth = np.asarray(tooth)
        for k, e in mod.pitch_errors:
            out = out + np.where(tooth == k, e, 0.0)
    return out
