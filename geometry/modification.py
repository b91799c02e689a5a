"""Flank modifications (micro-geometry) as material removed along the flank normal.

Profile modifications are functions of the roll length L = sqrt(r^2 - r_b^2) (distance along the
line of action in the transverse plane, ISO 21771 sec. 4.3), lead modifications of the axial
position z (0 at mid-face; the datum face I at z = -b/2, the non-datum face II at z = +b/2).
Positive values remove material (open the gap). The terms (ISO 21771:2007 sec. 4.6, flank modifications):
tip and root relief (C_a, C_f), profile and lead crowning (C_alpha, C_beta), end relief at each face
(C_I, C_II over the lengths L_I, L_II) and triangular tip relief (C_Ea at a corner of tip and face end,
zero on the line from the tip edge at L_Ea from that face to the face end at d_Ea), plus the deviations
of ISO 1328-1 (slopes and parabolic forms) and tooth position errors.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["FlankModification", "modification_depth", "profile_slope_from_roll_ratio"]


@dataclass(frozen=True)
class FlankModification:
    """Micro-geometry of one member (all lengths in mm).

    Attributes
    ----------
    tip_relief : float
        C_a, depth at the tip; starts at ``tip_relief_start_radius`` and grows as
        ``((L - L_start) / (L_tip - L_start)) ** tip_relief_exponent``.
    profile_crowning : float
        C_alpha, parabola over the active profile [r_form, r_tip], zero at its middle.
    lead_crowning : float
        C_beta, parabola over the face width, zero at mid-face, C_beta at both ends.
    lead_slope : float
        f_Hbeta, linear over the face, zero at mid-face, +f/2 at z = +b/2.
    pitch_errors : tuple of (int, float)
        Per tooth index (taken modulo the number of teeth), the tooth's position error along the base tangent
        (+ = the drive flank moved back, so the coast flank moved forward).
    profile_slope : float
        f_Halpha, linear in the roll length over the active profile, zero at its middle, +f/2 (material
        removed) at the tip (ISO 1328-1 profile slope deviation, sign: tip relieved).
    profile_form : float
        f_falpha, the parabolic (second-order) part of a profile form deviation over the active profile, zero at
        its middle and f at both ends: + convex (material removed at the ends), - hollow. Its range about the
        least-squares mean line is ``|f|`` (the ISO 1328-1 form deviation of a parabola); higher-order waviness
        is not modelled.
    lead_form : float
        f_fbeta, the same over the face width (zero at mid-face, f at both ends).
    root_relief : float
        C_f, depth at ``root_relief_end_radius`` (the start of the active profile); starts at
        ``root_relief_start_radius`` and grows as ``((L - L_start) / (L_end - L_start)) ** root_relief_exponent``.
    end_relief : tuple of two (float, float)
        ((C_I, L_I), (C_II, L_II)): depth at the datum face (z = -b/2) and the non-datum face (z = +b/2) and the
        axial length over which it falls to zero, as ``(1 - d / L) ** end_relief_exponent`` with d the distance
        from that face.
    triangular_tip_relief : float
        C_Ea, depth at the corner of the tip edge and the face end(s) of ``triangular_tip_relief_faces`` (-1 datum,
        +1 non-datum, 0 both). Zero on the line from the tip edge at ``triangular_tip_relief_length`` (L_Ea) from
        the face to the face end at ``triangular_tip_relief_start_radius`` (d_Ea / 2); linear in the distance
        beyond that line, C_Ea at the corner.
    """
    tip_relief: float = 0.0
    tip_relief_start_radius: float | None = None
    tip_relief_exponent: float = 1.0
    profile_crowning: float = 0.0
    lead_crowning: float = 0.0
    lead_slope: float = 0.0
    pitch_errors: tuple[tuple[int, float], ...] = ()
    profile_slope: float = 0.0
    profile_form: float = 0.0
    lead_form: float = 0.0
    root_relief: float = 0.0
    root_relief_start_radius: float | None = None
    root_relief_end_radius: float | None = None
    root_relief_exponent: float = 1.0
    end_relief: tuple[tuple[float, float], tuple[float, float]] = ((0.0, 0.0), (0.0, 0.0))
    end_relief_exponent: float = 1.0
    triangular_tip_relief: float = 0.0
    triangular_tip_relief_start_radius: float | None = None
    triangular_tip_relief_length: float = 0.0
    triangular_tip_relief_faces: int = 0


def _roll(r: float, r_base: float) -> float:
    """Roll length of radius ``r`` on the base circle ``r_base`` (0 inside it), mm."""
    return float(np.sqrt(max(r * r - r_base * r_base, 0.0)))


def modification_depth(mod: FlankModification, r: np.ndarray, z: np.ndarray, tooth: np.ndarray,
                       r_base: float, r_form: float, r_tip: float, face_width: float, teeth: int = 0,
                       side: int = 1) -> np.ndarray:
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
    teeth : int
        Number of teeth of the member (pitch-error indices are taken modulo it; 0: as given).
    side : int
        +1 drive flank, -1 coast flank (a tooth position error opens one and closes the other).

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
    if mod.profile_slope != 0:
        mid, span = 0.5 * (L_tip + L_form), (L_tip - L_form)
        out = out + mod.profile_slope * (L - mid) / span
    if mod.profile_form != 0:
        mid, half = 0.5 * (L_tip + L_form), 0.5 * (L_tip - L_form)
        out = out + mod.profile_form * ((L - mid) / half) ** 2
    if mod.lead_form != 0:
        out = out + mod.lead_form * (2.0 * z / face_width) ** 2
    if mod.root_relief > 0:
        Ls = _roll(mod.root_relief_start_radius if mod.root_relief_start_radius else r_form + 0.4 * (r_tip - r_form),
                   r_base)
        Le = _roll(mod.root_relief_end_radius if mod.root_relief_end_radius else r_form, r_base)
        xi = np.clip((L - Ls) / (Le - Ls if abs(Le - Ls) > 1e-12 else -1e-12), 0.0, None)
        out = out + mod.root_relief * xi ** mod.root_relief_exponent
    half = 0.5 * face_width
    for (depth, length), d in zip(mod.end_relief, (z + half, half - z)):
        if depth > 0 and length > 0:
            out = out + depth * np.clip(1.0 - d / length, 0.0, None) ** mod.end_relief_exponent
    if mod.triangular_tip_relief > 0 and mod.triangular_tip_relief_length > 0:
        rs = mod.triangular_tip_relief_start_radius or r_tip - 0.4 * (r_tip - r_form)
        Ls = _roll(rs, r_base)
        u = (L - L_tip) / (L_tip - Ls if abs(L_tip - Ls) > 1e-12 else 1e-12)     # 0 at the tip, -1 at d_Ea
        faces = (z + half, half - z) if mod.triangular_tip_relief_faces == 0 else \
            (z + half,) if mod.triangular_tip_relief_faces < 0 else (half - z,)
        for d in faces:
            out = out + mod.triangular_tip_relief * np.clip(1.0 + u - d / mod.triangular_tip_relief_length, 0.0, None)
    if mod.pitch_errors:
        tooth = np.asarray(tooth)
        if teeth:
            tooth = np.mod(tooth, teeth)
        for k, e in mod.pitch_errors:
            out = out + side * np.where(tooth == (k % teeth if teeth else k), e, 0.0)
    return out


def profile_slope_from_roll_ratio(ratio_error: float, r_base: float, r_form: float, r_tip: float) -> float:
    """Profile slope deviation (mm) generated by a roll (generating) ratio error ``ratio_error``.

    A generating chain whose ratio is (1 + e) times the nominal one rolls the blank against the cutter
    as if its base radius were r_b (1 + e); over the evaluated roll length L_alpha the generated
    involute then deviates by f_Halpha = L_alpha * dr_b / r_b = e * L_alpha (ISO 21771 and ISO 1328-1:
    base-circle error and profile slope deviation). A larger base circle gives a flank with less
    material towards the tip, i.e. a positive f_Halpha in the convention of :class:`FlankModification`."""
    L_tip = np.sqrt(r_tip ** 2 - r_base ** 2)
    L_form = np.sqrt(max(r_form ** 2 - r_base ** 2, 0.0))
    return float(ratio_error * (L_tip - L_form))
