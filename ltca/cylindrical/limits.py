"""Extreme but legal cylindrical inputs refused before any FE work, each naming the limiting quantity and a value
that would work:

- :func:`body_dofs`, :func:`check_body_size`: the degrees of freedom of each gear body, estimated from its
  volumes and the fidelity's element sizes (a face of 2000 mm, a gear of 1000 teeth: meshing alone would take
  many minutes and the factorisation more memory than the machine has);
- :func:`check_edge_zones`: a Hertz contact half-width that reaches across the face or the active profile (a
  torque of 1e6 N m on a 14 mm face, a module of 100 on a 0.5 mm face): every contact cell would lie in an edge
  zone (:mod:`ltca.cylindrical.edges`) and no flank pressure could be read.
"""
from __future__ import annotations

import math

import numpy as np

from ltca.geometry.cylindrical import arc_length

from ..validation import DesignError
from .loaded_model import hertz_line

__all__ = ["MAX_BODY_DOFS", "body_dofs", "check_body_size", "hertz_half_width", "check_edge_zones", "check_limits"]

#: degrees of freedom of one gear body at most: its sparse factorisation needs a few GB beyond that
MAX_BODY_DOFS = 1_500_000
#: dofs per h_flank^2 of loaded-tooth flank surface and per h_body^2 of body surface (root circle, support and
#: end faces), quadratic tetrahedra graded from the flanks into the body. Fitted to the FZG C14 gear at the coarse
#: fidelity (37 818 dofs) and a gear of 1000 teeth of module 4.5 (393 687); it then gives the FZG pinion (34 062:
#: estimate 34 500) and the helical_m8_wide pinion (142 755: 137 000), and over-estimates the default fidelity's
#: FZG bodies (55 518: 72 000) and the helical_m8_wide gear's webbed body (111 528: 284 000)
_DOFS_PER_FLANK_H2 = 114.0
_DOFS_PER_BODY_H2 = 21.0


def _parts(model, member, r_support: float, h_flank: float, h_body: float, fine_teeth: int) -> tuple[float, float]:
    """(flank part, body part) of one body's estimated dofs."""
    b = model.face_width
    flanks = fine_teeth * 2 * abs(member.r_tip - member.r_root) * b          # both flanks of the fine teeth, mm^2
    r1, r2 = member.r_root, r_support
    body = 2 * math.pi * (r1 + r2) * b + 2 * math.pi * abs(r1 ** 2 - r2 ** 2)  # the ring's surface, mm^2
    return _DOFS_PER_FLANK_H2 * flanks / h_flank ** 2, _DOFS_PER_BODY_H2 * body / h_body ** 2


def body_dofs(model, h_flank: float, h_body: float, fine_teeth: int = 4) -> tuple[int, int]:
    """Estimated dofs of (pinion, gear): both flanks of the ``fine_teeth`` teeth at ``h_flank`` and the surface of
    the ring from the root circle to the support (bore, or an internal gear's outer rim) at ``h_body`` (mm)."""
    return tuple(int(sum(_parts(model, mem, rs, h_flank, h_body, fine_teeth)))
                 for mem, rs in ((model.pinion, model.r_bore1), (model.gear, model.r_bore2)))


def check_body_size(model, fid: dict, fid_name: str, file: str | None = None) -> tuple[int, int]:
    """Refuse bodies estimated above :data:`MAX_BODY_DOFS`, naming the quantity that drives the size and a value
    that fits (a face width, or a tooth count at this module); returns the estimate."""
    m = model.case.module
    h_f, h_b = fid["h_flank"] * m, fid["h_body"] * m
    est = body_dofs(model, h_f, h_b)
    worst = int(np.argmax(est))
    if est[worst] <= MAX_BODY_DOFS:
        return est
    name = ("pinion", "gear")[worst]
    member = (model.pinion, model.gear)[worst]
    face = model.face_width
    # the estimate is proportional to the face width: the widest face at half the limit (the estimate's margin)
    face_ok = face * 0.5 * MAX_BODY_DOFS / est[worst]
    teeth = member.r_ref * 2 / m
    r_support = (model.r_bore1, model.r_bore2)[worst]
    if _parts(model, member, r_support, h_f, h_b, 4)[1] > 0.5 * est[worst]:
        # the body ring dominates: its end faces grow as the square of the diameter (teeth x module)
        z_ok = max(5, int(teeth * math.sqrt(0.5 * MAX_BODY_DOFS / est[worst])))
        fields = (f"{name}.teeth", f"{name}.bore_diameter_mm", f"{name}.face_width_mm", "analysis.fidelity")
        advice = (f"at most about {z_ok} teeth at module {m:g} mm, a bore near the root circle, or a face width of "
                  f"at most {face_ok:.0f} mm")
    else:
        fields = (f"{name}.face_width_mm", "analysis.fidelity")
        advice = f"a face width of at most {face_ok:.0f} mm at module {m:g} mm"
    if fid_name != "coarse":
        advice += " (or the fidelity 'coarse')"
    raise DesignError(f"the {name} body ({round(teeth)} teeth, face {face:g} mm) would need about "
                      f"{est[worst] / 1e6:.1f} million degrees of freedom at the fidelity '{fid_name}' (at most "
                      f"{MAX_BODY_DOFS / 1e6:.1f} million: hours of meshing and more memory than a workstation has)",
                      fields, advice, file)


def hertz_half_width(model, torque: float) -> tuple[float, float]:
    """Nominal Hertz half-width (mm) and peak pressure (MPa) at the pitch point under ``torque`` (N mm): the line
    load T / (r_b1 b) on the relative radius of curvature (as :func:`ltca.cylindrical.loaded_model.plan_bodies`)."""
    p1, p2 = model.pinion, model.gear
    w = torque / (p1.r_base * model.face_width)
    rho1 = p1.r_base * np.tan(model.pair.alpha_w)
    rho2 = p2.r_base * np.tan(model.pair.alpha_w)
    R = (1.0 / (1 / rho1 - 1 / rho2) if p2.internal else 1.0 / (1 / rho1 + 1 / rho2)) / np.cos(p1.beta_b)
    b, p0 = hertz_line(w * np.cos(p1.beta_b), R, model.case.young, model.case.poisson)
    return float(b), float(p0)


def check_edge_zones(model, torques, file: str | None = None) -> None:
    """Refuse a torque whose Hertz half-width b reaches across the face (b >= b_face / 2) or the active profile
    (3 b >= its length; the tip and form-circle edge zones take 2 b + b): no flank cell would be left.

    The half-width grows as sqrt(T) and as 1 / sqrt(face) (Johnson 1985, eq. 4.43): the message gives the largest
    torque and the smallest face width at which b is a quarter of the face and a sixth of the profile."""
    T = max(torques)
    b, p0 = hertz_half_width(model, T)
    face = model.face_width
    p1 = model.pinion
    active = arc_length(p1.r_flank_end, p1.r_base) - arc_length(model.pinion_range()[0], p1.r_base)
    if b < 0.5 * face and 3 * b < active:
        return
    b_ok = min(0.25 * face, active / 6)
    t_ok = T * (b_ok / b) ** 2
    fields = ["load.torque_nm"]
    advice = f"a torque of at most {t_ok * 1e-3:.3g} N m"
    if b >= 0.5 * face and 3 * b < active:
        # b ~ face^-1/2: the face width f with b(f) = f / 4
        f_ok = (4 * b) ** (2 / 3) * face ** (1 / 3)
        fields += ["pinion.face_width_mm", "gear.face_width_mm"]
        advice += f", or a face width of at least {f_ok:.3g} mm"
    where = "the face" if b >= 0.5 * face else "the active profile"
    raise DesignError(f"the Hertz contact half-width at {T * 1e-3:g} N m ({b:.3g} mm, nominal peak {p0:.0f} MPa) "
                      f"reaches across {where} (face {face:g} mm, active profile {active:.3g} mm): every contact "
                      "cell would be edge contact and no flank pressure could be read", fields, advice, file)


def check_limits(model, fid: dict, fid_name: str, file: str | None = None) -> None:
    """Both checks, before any FE work (``ltca run``)."""
    check_edge_zones(model, model.case.torques, file)
    check_body_size(model, fid, fid_name, file)
