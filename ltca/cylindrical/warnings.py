"""Derived design checks of a cylindrical pair: refusals (no continuous contact) and warnings for doubtful
designs (deep undercut, contact ratio from a tip that meets no generated involute, interference, pressures and
stresses beyond what the material takes, an implausibly soft mesh). Warnings go on the console and into
summary.json (``warnings``)."""
from __future__ import annotations

import numpy as np

from ..validation import DesignError

__all__ = ["check_contact", "design_warnings", "pressure_warnings", "convergence_warnings", "contact_ratio_transverse",
           "UNDERCUT_LIMIT", "PRESSURE_LIMIT_MPA", "ROOT_LIMIT_MPA", "RESIDUAL_LIMIT"]

UNDERCUT_LIMIT = 0.05     # undercut: involute lost above the base circle, in modules, before a warning
PRESSURE_LIMIT_MPA = 2500.0   # static contact limit of case-hardened steel (about 1.7 x sigma_Hlim 1500 MPa)
ROOT_LIMIT_MPA = 1200.0       # about the static bending strength of case-hardened steel
RESIDUAL_LIMIT = 1e-6         # contact solve residual above which a position counts as not converged


def _geometry(model):
    p1, p2, pair = model.pinion, model.gear, model.pair
    alpha_w_t = float(pair.alpha_w)
    a = float(pair.a)
    rho_tip1 = np.sqrt(max(p1.r_tip ** 2 - p1.r_base ** 2, 0.0))
    rho_tip2 = np.sqrt(max(p2.r_tip ** 2 - p2.r_base ** 2, 0.0))
    loa = a * np.sin(alpha_w_t)                    # T1 T2 along the line of action
    if p2.internal:
        start1 = rho_tip2 - loa                    # pinion roll distance where the ring tip meets it
        ga = rho_tip1 - start1
    else:
        start1 = loa - rho_tip2
        ga = rho_tip1 + rho_tip2 - loa
    pb = 2 * np.pi * p1.r_base / p1.z
    return ga, pb, start1


def contact_ratio_transverse(model) -> float:
    """eps_alpha from the tip circles (ISO 21771 form)."""
    ga, pb, _ = _geometry(model)
    return float(ga / pb)


def check_contact(model, file: str | None = None) -> None:
    """Refuse a pair that does not keep at least one pair of teeth in contact (transverse plus overlap < 1)."""
    ga, pb, _ = _geometry(model)
    eps_a = ga / pb
    c = model.case
    eps_b = abs(model.face_width * np.sin(c.helix_angle) / (np.pi * c.module))
    if not np.isfinite(eps_a) or eps_a + eps_b < 1.0:
        fields = ("assembly.centre_distance_mm", "pinion.tip_diameter_mm", "gear.tip_diameter_mm",
                  "pinion.profile_shift", "gear.profile_shift")
        what = "no contact at all: the tip circles do not reach the line of action" if eps_a <= 0 else \
            "the pair loses contact during the mesh cycle"
        raise DesignError(f"contact ratio eps_alpha + eps_beta = {eps_a + eps_b:.3f} < 1 ({what}; centre distance "
                          f"{model.pair.a:.3f} mm)", fields, "move the centre distance towards the working one "
                          "or raise the tip diameters", file)


def design_warnings(model) -> list[str]:
    """Doubtful but legal designs, one line each."""
    out = []
    m = model.case.module
    ga, pb, start1 = _geometry(model)
    for name, p in (("pinion", model.pinion), ("gear", model.gear)):
        if p.internal:
            continue
        r_form = max(p.r_form_left, p.r_form_right)
        lost = r_form - max(p.r_base, p.r_root)
        if p.undercut and lost > UNDERCUT_LIMIT * m:
            out.append(f"{name} undercut: the involute starts at d_form = {2 * r_form:.3f} mm, "
                       f"{lost / m:.2f} module above the base/root circle (limit {UNDERCUT_LIMIT}); "
                       f"raise {name}.profile_shift ({p.x:+.3f}) or {name}.teeth")
    # where the gear tip meets the pinion flank: below the pinion's form circle the involute is not generated
    p1 = model.pinion
    r_start1 = float(np.hypot(p1.r_base, start1)) if start1 >= 0 else p1.r_base
    r_form1 = max(p1.r_form_left, p1.r_form_right)
    if start1 < 0:
        out.append("interference: the gear tip reaches below the pinion base circle (line of action passes T1); "
                   "set by gear.tip_diameter_mm, assembly.centre_distance_mm, pinion.profile_shift")
    elif r_start1 < r_form1 - 1e-6:
        rho_form = np.sqrt(max(r_form1 ** 2 - p1.r_base ** 2, 0.0))
        eps_eff = (ga - (rho_form - start1)) / pb
        out.append(f"contact ratio from a tip that is not generated: the gear tip meets the pinion at d = "
                   f"{2 * r_start1:.3f} mm, below its form diameter {2 * r_form1:.3f} mm; eps_alpha "
                   f"{ga / pb:.3f} from the tip circles, {eps_eff:.3f} on the generated involute")
    return out


def pressure_warnings(case, summary: dict) -> list[str]:
    """Results beyond what the material can take, or a mesh implausibly soft for steel-like bodies."""
    out = []
    scale = case.young / 206000.0
    p = summary.get("max_contact_pressure_mpa")
    if p is not None and np.isfinite(p) and p > PRESSURE_LIMIT_MPA * np.sqrt(scale):
        out.append(f"contact pressure {p:.0f} MPa above the static limit of hardened steel "
                   f"(~{PRESSURE_LIMIT_MPA * np.sqrt(scale):.0f} MPa) at {summary.get('torque_nm')} N m")
    roots = summary.get("max_root_stress_mpa") or {}
    for name, s in roots.items():
        if s is not None and np.isfinite(s) and s > ROOT_LIMIT_MPA:
            out.append(f"{name} root stress {s:.0f} MPa above the static bending strength (~{ROOT_LIMIT_MPA:.0f} MPa)")
    c = summary.get("mesh_stiffness_mean_n_per_mm_um")
    if c is not None and np.isfinite(c) and c < 2.0 * scale:
        out.append(f"mesh stiffness {c:.2f} N/(mm um) far below ISO 6336-1 (12-20 for steel): check the bodies "
                   "(bore_diameter_mm, rim_thickness_mm)")
    return out


def convergence_warnings(results, torque_nm: float) -> list[str]:
    """One line naming the positions (pinion roll, deg) whose contact solve ended above :data:`RESIDUAL_LIMIT`,
    with the largest residual; empty when every position converged."""
    bad = [(float(np.degrees(r.roll)), float(r.residual)) for r in results if not r.residual < RESIDUAL_LIMIT]
    if not bad:
        return []
    rolls = ", ".join(f"{a:+.2f}" for a, _ in bad[:8]) + (" ..." if len(bad) > 8 else "")
    return [f"{len(bad)} of {len(results)} positions not converged at {torque_nm:g} N m (residual up to "
            f"{max(b for _, b in bad):.1e}, limit {RESIDUAL_LIMIT:g}): roll {rolls} deg; refine the fidelity or "
            "check the design"]
