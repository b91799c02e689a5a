"""From a validated case to the geometric model of the pair: profiles, assembly, modifications.

This is the geometry stage of the chain: it generates both transverse tooth profiles by the cutter
(rack for external teeth, pinion-type shaper for internal teeth), places them at the centre distance
with the misalignments and turns the case's micro-geometry into flank modifications.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ltca.geometry.cylindrical import flank_point_normal
from ltca.geometry.involute import GearBlank, RackCutter, ToothProfile, generate_by_rack, involute, inverse_involute
from ltca.geometry.shaper import ShaperCutter, generate_by_shaper
from ltca.geometry.tip_edge import largest_tip_edge, with_tip_edge
from ltca.geometry.modification import FlankModification, profile_slope_from_roll_ratio
from ltca.geometry.pair import CylindricalPair

from ..case import CylindricalCase, Member
from ..errors import CaseError
from ..validation import DesignError

__all__ = ["PairModel", "build_model", "working_centre_distance"]


@dataclass(frozen=True)
class PairModel:
    """Everything geometric about a case (mm, rad)."""
    case: CylindricalCase
    pinion: ToothProfile
    gear: ToothProfile
    pair: CylindricalPair
    mod1: FlankModification
    mod2: FlankModification
    face_width: float
    r_bore1: float
    r_bore2: float
    gear_side: int          # which side label of the gear outline carries the load
    phi_pitch: float        # pinion rotation where tooth 0 touches at the pitch point (rad)
    gear_shift: int = 0     # gear tooth index change per pinion mesh cycle (physical tooth bookkeeping)
    web1: tuple | None = None   # (r_rim, r_hub, web width, web offset) of a webbed pinion, mm; None: solid disc
    web2: tuple | None = None
    contact_search: str = "line"  # "line": a band around each tooth's nominal contact line; "flank": the whole active
                                  # flank (pairs whose contact lies off the nominal line, e.g. the eccentric internal pair)

    @property
    def pitch_angle(self) -> float:
        """Angular pitch of the pinion, rad."""
        return 2 * np.pi / self.pinion.z

    def pinion_range(self) -> tuple[float, float]:
        """Radii of the pinion's loaded flank from the form circle to the tip, mm."""
        return self.pinion.r_form_right, self.pinion.r_tip

    def gear_range(self) -> tuple[float, float]:
        """Radii of the gear's loaded flank (form circle .. tip, ordered low to high), mm."""
        rf = self.gear.r_form_right if self.gear_side > 0 else self.gear.r_form_left
        return (min(rf, self.gear.r_tip), max(rf, self.gear.r_tip))


def working_centre_distance(case: CylindricalCase) -> float:
    """Centre distance for zero backlash from the profile shifts (ISO 21771 eq. for inv alpha_wt)."""
    z1, z2 = case.pinion.teeth, case.gear.teeth
    at = np.arctan(np.tan(case.pressure_angle) / np.cos(case.helix_angle))
    mt = case.module / np.cos(case.helix_angle)
    if case.gear.internal:
        inv_w = involute(at) + 2 * np.tan(case.pressure_angle) * (case.gear.profile_shift - case.pinion.profile_shift) / (z2 - z1)
        aw = inverse_involute(inv_w)
        return 0.5 * mt * (z2 - z1) * np.cos(at) / np.cos(aw)
    inv_w = involute(at) + 2 * np.tan(case.pressure_angle) * (case.pinion.profile_shift + case.gear.profile_shift) / (z1 + z2)
    aw = inverse_involute(inv_w)
    return 0.5 * mt * (z1 + z2) * np.cos(at) / np.cos(aw)


def _modification(m, profile: ToothProfile, name: str) -> FlankModification:
    r_tip = profile.r_tip
    start = None
    if m.tip_relief_start_diameter is not None:
        start = 0.5 * m.tip_relief_start_diameter
        if start >= r_tip:
            raise CaseError(f"{name}.modifications.tip_relief_start_diameter_mm", m.tip_relief_start_diameter,
                            f"smaller than the tip diameter {2 * r_tip:.3f} mm")
        r_form = max(profile.r_form_left, profile.r_form_right)
        if not profile.internal and start <= r_form:
            raise CaseError(f"{name}.modifications.tip_relief_start_diameter_mm", m.tip_relief_start_diameter,
                            f"a diameter on the active involute, between the form diameter {2 * r_form:.3f} mm and "
                            f"the tip diameter {2 * r_tip:.3f} mm (not in the root)")
    slope = m.profile_slope
    if m.roll_ratio_error:
        rf = profile.r_form_right
        lo, hi = (r_tip, rf) if profile.internal else (rf, r_tip)
        slope += profile_slope_from_roll_ratio(m.roll_ratio_error, profile.r_base, lo, hi)
    return FlankModification(m.tip_relief, start, m.tip_relief_exponent, m.profile_crowning, m.lead_crowning,
                             m.lead_slope, m.pitch_errors, slope, profile_form=m.profile_form,
                             lead_form=m.lead_form)


def _profile(case: CylindricalCase, member: Member, beta: float, name: str) -> ToothProfile:
    try:
        blank = GearBlank(z=member.teeth, m_n=case.module, alpha_n=case.pressure_angle, beta=beta,
                          x=member.profile_shift, d_tip=member.tip_diameter, internal=member.internal,
                          thickness_allowance=member.thickness_allowance)
        if member.internal:
            cutter = ShaperCutter(z0=case.shaper_teeth, x0=case.shaper_profile_shift, ha0=case.rack_addendum,
                                  rho0=case.rack_tip_radius)
            profile = generate_by_shaper(blank, cutter)
        else:
            rack = RackCutter(alpha_n=case.pressure_angle, ha=case.rack_addendum, hf=case.rack_dedendum,
                              rho=case.rack_tip_radius)
            profile = generate_by_rack(blank, rack)
    except ValueError as exc:
        raise _generation_error(str(exc), name, member.internal) from None
    return _tip_edge(profile, member.modifications, name)


def _tip_edge(profile: ToothProfile, mods, name: str) -> ToothProfile:
    """The generated profile with its tip edges rounded or chamfered as the case asks (geometry.tip_edge)."""
    for key, kind, size in (("tip_edge_radius_mm", "radius", mods.tip_edge_radius),
                            ("tip_chamfer_mm", "chamfer", mods.tip_chamfer)):
        if size > 0:
            try:
                return with_tip_edge(profile, **{kind: size})
            except ValueError:
                raise CaseError(f"{name}.modifications.{key}", size, f"a {kind} that fits on the tooth: "
                                f"(0, {largest_tip_edge(profile, kind):.3f}] mm (the {kind} starts on the involute "
                                "above the form circle and leaves tip land)") from None
    return profile



#: what failed in the generation (a phrase of geometry.involute's message) -> the quantity and the input fields
_GENERATION = (
    ("pointed tooth", "tooth thickness at the tip <= 0 (pointed tooth)", ("tip_diameter_mm", "profile_shift")),
    ("fillets meet", "undercut so deep that the two fillets meet", ("profile_shift", "teeth", "cutter.tip_radius")),
    ("no active involute", "no active involute (form diameter above the tip)",
     ("profile_shift", "teeth", "tip_diameter_mm", "cutter.tip_radius")),
    ("too large: the two tip edges", "rack tip land < 0 (the tip radius does not fit on the rack tooth)",
     ("cutter.tip_radius", "gear_pair.pressure_angle_deg", "cutter.addendum")),
    ("root radius", "root diameter <= 0", ("profile_shift", "teeth", "cutter.addendum")),
    ("above the rack root line", "tip diameter above what the rack can cut",
     ("tip_diameter_mm", "profile_shift", "cutter.dedendum")),
    ("must exceed the root and base", "tip diameter not above the root and base diameters",
     ("tip_diameter_mm", "profile_shift")),
)


def _generation_error(msg: str, name: str, internal: bool) -> DesignError:
    """A tooth that cannot be generated: the quantity that failed and the input fields that drive it."""
    for phrase, quantity, keys in _GENERATION:
        if phrase in msg:
            break
    else:
        quantity, keys = "the tooth cannot be generated", ("teeth", "profile_shift", "tip_diameter_mm",
                                                           "cutter.shaper_teeth" if internal else "cutter.tip_radius")
    fields = tuple(k if "." in k else f"{name}.{k}" for k in keys)
    detail = msg.replace("GearBlank.", "").replace("RackCutter.", "cutter ")[:140]
    return DesignError(f"{name}: {quantity} ({detail})", fields, "")


def build_model(case: CylindricalCase) -> PairModel:
    """Generate both profiles, assemble the pair, check it and find the pitch-point position."""
    p1 = _profile(case, case.pinion, case.helix_angle, "pinion")
    p2 = _profile(case, case.gear, case.helix_angle if case.gear.internal else -case.helix_angle, "gear")
    a = case.centre_distance or working_centre_distance(case)
    b = min(case.pinion.face_width, case.gear.face_width)
    if case.gear.internal:
        if a <= 0 or p2.r_tip <= p1.r_tip + 1e-6 or a > p2.r_tip - p1.r_root:
            raise CaseError("assembly.centre_distance_mm", a, "an internal pair whose pinion fits inside the ring "
                            f"(0 < a <= {p2.r_tip - p1.r_root:.3f} mm)")
        if p2.r_base - p1.r_base >= a:
            raise CaseError("assembly.centre_distance_mm", a, f"more than r_b2 - r_b1 = {p2.r_base - p1.r_base:.3f} mm")
    else:
        if a < p1.r_base + p2.r_base:
            raise CaseError("assembly.centre_distance_mm", a, f"at least r_b1 + r_b2 = {p1.r_base + p2.r_base:.3f} mm")
        if a < p1.r_tip + p2.r_root or a < p2.r_tip + p1.r_root:
            raise CaseError("assembly.centre_distance_mm", a, "large enough that each tip clears the other's root "
                            f"(>= {max(p1.r_tip + p2.r_root, p2.r_tip + p1.r_root):.3f} mm)")
    pair = CylindricalPair(p1, p2, a, b, case.lead_misalignment, case.lead_deviation)
    # interference check of the internal pair: the ring's tip must stay outside the pinion's base circle path
    if case.gear.internal:
        L2 = np.sqrt(p2.r_tip ** 2 - p2.r_base ** 2)
        T1T2 = np.sqrt(a ** 2 - (p2.r_base - p1.r_base) ** 2)
        if L2 < T1T2:
            raise CaseError("gear.tip_diameter_mm", 2 * p2.r_tip, "a ring tip outside the interference point "
                            f"(tip diameter > {2 * np.hypot(p2.r_base, T1T2):.3f} mm): the ring tip cuts the pinion "
                            "below its base circle")
    r_b = (0.5 * case.pinion.bore_diameter) if case.pinion.bore_diameter else max(p1.r_root - 4 * case.module,
                                                                                   0.35 * p1.r_root)
    if r_b >= p1.r_root - 0.5 * case.module:
        raise CaseError("pinion.bore_diameter_mm", 2 * r_b, f"below the root diameter minus one module "
                        f"({2 * (p1.r_root - 0.5 * case.module):.3f} mm)")
    if case.gear.internal:
        r_b2 = (0.5 * case.gear.bore_diameter) if case.gear.bore_diameter else p2.r_root + 4 * case.module
        if r_b2 <= p2.r_root + 0.5 * case.module:
            raise CaseError("gear.bore_diameter_mm", 2 * r_b2, "for a ring gear: its outer rim diameter, larger than "
                            f"the root diameter plus one module ({2 * (p2.r_root + 0.5 * case.module):.3f} mm)")
    else:
        r_b2 = (0.5 * case.gear.bore_diameter) if case.gear.bore_diameter else max(p2.r_root - 4 * case.module,
                                                                                    0.35 * p2.r_root)
        if r_b2 >= p2.r_root - 0.5 * case.module:
            raise CaseError("gear.bore_diameter_mm", 2 * r_b2, f"below the root diameter minus one module "
                            f"({2 * (p2.r_root - 0.5 * case.module):.3f} mm)")
    # which gear flank carries the load, and where the pitch point is
    P, N = flank_point_normal(p1, +1, np.array([pair.r_w1]), np.zeros(1), 0)
    s = pair.separation(0.0, P, N)
    x, y = P[0, 0], P[0, 1]
    phi_pitch = float(np.arctan2(x, y))
    # the gear tooth that meets the same world point one mesh cycle later (pinion tooth -1 then stands
    # where tooth 0 was): the index step per cycle, for the physical bookkeeping of tooth errors
    P1, N1 = flank_point_normal(p1, +1, np.array([pair.r_w1]), np.zeros(1), -1)
    s1 = pair.separation(-2 * np.pi / p1.z, P1, N1)
    shift = int(s1.gear_tooth[0] - s.gear_tooth[0])
    web1 = _web(case.pinion, p1, r_b, "pinion", case.module)
    web2 = _web(case.gear, p2, r_b2, "gear", case.module)
    return PairModel(case, p1, p2, pair, _modification(case.pinion.modifications, p1, "pinion"),
                     _modification(case.gear.modifications, p2, "gear"), b, r_b, r_b2,
                     int(s.gear_side[0]) or 1, phi_pitch, shift, web1, web2)


def _web(member, profile: ToothProfile, r_support: float, name: str, module: float):
    """(r_rim, r_hub, web width, web offset) of a webbed member, mm, or None for a solid disc.

    The rim ends ``rim_thickness`` below the root circle (a ring gear: above it); the hub ring reaches from the
    support to ``hub_diameter / 2``, by default a third of the way from the support to the rim."""
    if member.rim_thickness is None:
        return None
    sgn = 1.0 if member.internal else -1.0
    r_rim = profile.r_root + sgn * member.rim_thickness
    if (r_rim - r_support) * sgn >= -0.5 * module:
        raise CaseError(f"{name}.rim_thickness_mm", member.rim_thickness,
                        f"a rim that ends at least half a module short of the {'outer ring' if member.internal else 'bore'}"
                        f" (at most {abs(profile.r_root - r_support) - 0.5 * module:.3f} mm)")
    r_hub = 0.5 * member.hub_diameter if member.hub_diameter else r_support + (r_rim - r_support) / 3
    if not (min(r_support, r_rim) < r_hub < max(r_support, r_rim)):
        raise CaseError(f"{name}.hub_diameter_mm", 2 * r_hub,
                        f"between the support ({2 * r_support:.3f} mm) and the rim ({2 * r_rim:.3f} mm) diameters")
    return (float(r_rim), float(r_hub), float(member.web_thickness), float(member.web_offset))
