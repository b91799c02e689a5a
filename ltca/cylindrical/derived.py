"""Derived geometry of a cylindrical pair for the report and the bearing-pattern axes: diameters, contact ratios,
base pitch, and the form and active diameters (SAP, EAP) of both members.

The path of contact on the transverse line of action runs, in the pinion's roll distance rho1 (from its
tangent point T1), from ``start1`` (where the gear tip meets the pinion: the pinion's start of active profile,
SAP) to the pinion tip rho_tip1 (its end of active profile, EAP). The gear's roll distance is rho2 = T1T2 - rho1
(external) or T1T2 + rho1 (internal), so the gear's SAP lies where the pinion tip meets it and its EAP at its
tip. Diameters d = 2 sqrt(r_b^2 + rho^2).
"""
from __future__ import annotations

import numpy as np

from .model import PairModel

__all__ = ["active_profile", "derived_geometry", "roll_to_diameter"]


def _rho_tip(p) -> float:
    return float(np.sqrt(max(p.r_tip ** 2 - p.r_base ** 2, 0.0)))


def active_profile(model: PairModel) -> dict:
    """Start and end of the active profile (SAP, EAP) and the form diameter of each member, mm.

    Returns ``{"pinion": {"sap", "eap", "form", "tip_form", "tip", "root", "base"}, "gear": {...}}`` (diameters,
    mm). A gear tip that reaches below the pinion base circle (interference) puts the pinion SAP at its base circle."""
    p1, p2, pair = model.pinion, model.gear, model.pair
    loa = float(pair.a * np.sin(pair.alpha_w))           # T1 T2
    rho_tip1, rho_tip2 = _rho_tip(p1), _rho_tip(p2)
    start1 = rho_tip2 - loa if p2.internal else loa - rho_tip2
    start1 = max(start1, 0.0)
    rho2_at_tip1 = rho_tip1 + loa if p2.internal else loa - rho_tip1

    def d(rb: float, rho: float) -> float:
        return float(2 * np.hypot(rb, rho))
    form2 = model.gear.r_form_right if model.gear_side > 0 else model.gear.r_form_left
    return {
        "pinion": {"sap": d(p1.r_base, start1), "eap": d(p1.r_base, rho_tip1), "form": 2 * float(p1.r_form_right),
                   "tip_form": 2 * float(p1.r_flank_end), "tip": 2 * float(p1.r_tip), "root": 2 * float(p1.r_root),
                   "base": 2 * float(p1.r_base)},
        "gear": {"sap": d(p2.r_base, max(rho2_at_tip1, 0.0)), "eap": d(p2.r_base, rho_tip2), "form": 2 * float(form2),
                 "tip_form": 2 * float(p2.r_flank_end),
                 "tip": 2 * float(p2.r_tip), "root": 2 * float(p2.r_root), "base": 2 * float(p2.r_base)},
    }


def roll_to_diameter(roll_deg: np.ndarray, r_base: float) -> np.ndarray:
    """Pinion involute roll angle (deg) -> diameter, mm: d = 2 r_b sqrt(1 + u^2)."""
    u = np.radians(np.asarray(roll_deg, dtype=float))
    return 2 * r_base * np.sqrt(1 + u ** 2)


def derived_geometry(model: PairModel) -> dict:
    """The pair's derived geometry as rows for the report: ``{"pair": [(name, value, unit)], "members":
    [(name, pinion value, gear value, unit)], "active": active_profile(model)}``."""
    case, p1, p2, pair = model.case, model.pinion, model.gear, model.pair
    loa = float(pair.a * np.sin(pair.alpha_w))
    rho_tip1, rho_tip2 = _rho_tip(p1), _rho_tip(p2)
    g_alpha = rho_tip1 - (rho_tip2 - loa) if p2.internal else rho_tip1 + rho_tip2 - loa
    p_bt = 2 * np.pi * p1.r_base / p1.z
    eps_a = g_alpha / p_bt
    eps_b = abs(model.face_width * np.sin(case.helix_angle) / (np.pi * case.module))
    act = active_profile(model)
    pair_rows = [
        ("centre distance a", float(pair.a), "mm"),
        ("working transverse pressure angle alpha_wt", float(np.degrees(pair.alpha_w)), "deg"),
        ("gear ratio u = z2 / z1", float(pair.ratio), "-"),
        ("transverse base pitch p_bt", float(p_bt), "mm"),
        ("normal base pitch p_bn", float(p_bt * np.cos(p1.beta_b)), "mm"),
        ("length of path of contact g_alpha", float(g_alpha), "mm"),
        ("transverse contact ratio eps_alpha", float(eps_a), "-"),
        ("overlap ratio eps_beta", float(eps_b), "-"),
        ("total contact ratio eps_gamma", float(eps_a + eps_b), "-"),
        ("face width b", float(model.face_width), "mm"),
    ]
    members = [
        ("teeth z", p1.z, p2.z, "-"),
        ("internal", "no", "yes" if p2.internal else "no", ""),
        ("profile shift x", float(p1.x), float(p2.x), "-"),
        ("reference diameter d", 2 * float(p1.r_ref), 2 * float(p2.r_ref), "mm"),
        ("working pitch diameter d_w", 2 * float(pair.r_w1), 2 * float(pair.r_w1 * pair.ratio), "mm"),
        ("base diameter d_b", act["pinion"]["base"], act["gear"]["base"], "mm"),
        ("tip diameter d_a", act["pinion"]["tip"], act["gear"]["tip"], "mm"),
        ("root diameter d_f", act["pinion"]["root"], act["gear"]["root"], "mm"),
        ("root form diameter d_Ff (involute start)", act["pinion"]["form"], act["gear"]["form"], "mm"),
        ("tip form diameter d_Fa (involute end)", act["pinion"]["tip_form"], act["gear"]["tip_form"], "mm"),
        ("start of active profile SAP", act["pinion"]["sap"], act["gear"]["sap"], "mm"),
        ("end of active profile EAP", act["pinion"]["eap"], act["gear"]["eap"], "mm"),
        ("undercut", "yes" if p1.undercut else "no", "yes" if p2.undercut else "no", ""),
    ]
    return {"pair": pair_rows, "members": members, "active": act, "eps_alpha": float(eps_a),
            "eps_beta": float(eps_b)}
