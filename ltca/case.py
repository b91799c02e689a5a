"""Case files (TOML) for cylindrical gear pairs: schema, validation and unit conversion.

Engineer's units in the file (mm, deg, um, N m, MPa); converted once here to the SI-consistent
mm-N-MPa-rad used inside. Every field is checked: a bad file raises :class:`ltca.errors.CaseError`
naming the field, its value and what is allowed; the command line turns that into exit status 2.
"""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .errors import CaseError

__all__ = ["Modifications", "Member", "CylindricalCase", "load_case", "parse_case", "read_toml", "FIDELITIES"]

DEG = math.pi / 180.0

#: Fidelity presets: flank element size (x module), body element size (x module), compliance grid
#: (profile x face per flank), contact cells across the Hertz width, face slices, near-field on/off, and the
#: longest contact cell along a helical face (x module; more slices on a wide helical face).
FIDELITIES: dict[str, dict[str, Any]] = {
    "coarse": dict(h_flank=0.45, h_body=1.6, grid=(7, 6), cells_per_b=3, slices=8, near_field=True, window=1.8,
                   slice_length=0.5),
    "default": dict(h_flank=0.3, h_body=1.3, grid=(9, 8), cells_per_b=5, slices=14, near_field=True, window=2.0,
                    slice_length=0.25),
    "fine": dict(h_flank=0.2, h_body=1.0, grid=(12, 10), cells_per_b=8, slices=20, near_field=True, window=2.5,
                 slice_length=0.17),
}


@dataclass(frozen=True)
class Modifications:
    """Flank modifications of one member, as material removed normal to the flank (mm)."""
    tip_relief: float = 0.0            # C_a at the tip, mm
    tip_relief_start_diameter: float | None = None  # mm; None: the diameter of the single-pair zone end
    tip_relief_exponent: float = 1.0   # 1 linear, 2 parabolic
    profile_crowning: float = 0.0      # C_alpha, mm, parabola over the active profile
    lead_crowning: float = 0.0         # C_beta, mm, parabola over the face width
    lead_slope: float = 0.0            # f_Hbeta, mm, linear over the face (+ at z = +b/2)
    pitch_errors: tuple[tuple[int, float], ...] = ()  # (tooth, position error in mm): + drive flank moved back
    profile_slope: float = 0.0         # f_Halpha, mm (+ = tip relieved)
    roll_ratio_error: float = 0.0      # generating-chain ratio error e (-), turned into a profile slope
    tip_edge_radius: float = 0.0       # mm, rounding of the tip edges (tangent to flank and tip circle); 0: sharp
    tip_chamfer: float = 0.0           # mm, leg of a chamfer of the tip edges (along flank and tip circle); 0: none


@dataclass(frozen=True)
class Member:
    """One gear of the pair."""
    teeth: int
    profile_shift: float
    face_width: float
    tip_diameter: float | None
    bore_diameter: float | None
    internal: bool
    modifications: Modifications
    thickness_allowance: float = 0.0   # mm, normal, total tooth thinning (backlash)
    rim_thickness: float | None = None # mm, radial rim below the root (ring gear: above it); None: solid disc
    web_thickness: float | None = None # mm, axial width of the web that joins rim and hub
    web_offset: float = 0.0            # mm, axial position of the web's mid-plane from mid-face
    hub_diameter: float | None = None  # mm, where the web meets the hub (ring gear: the outer ring)


@dataclass(frozen=True)
class CylindricalCase:
    """A validated cylindrical gear-pair case, SI-consistent (mm, N, MPa, rad)."""
    name: str
    module: float
    pressure_angle: float
    helix_angle: float
    rack_addendum: float        # cutter addendum (cuts the dedendum), mm
    rack_dedendum: float        # mm
    rack_tip_radius: float      # mm
    shaper_teeth: int
    shaper_profile_shift: float
    pinion: Member
    gear: Member
    centre_distance: float | None
    lead_misalignment: float    # mm over the face width, in the plane of action
    lead_deviation: float       # mm over the face width, normal to the plane of action
    young: float
    poisson: float
    torques: tuple[float, ...]  # N mm on the pinion (driver)
    positions: int
    cycles: int
    fidelity: str
    fidelity_params: dict = field(default_factory=dict)
    source: str | None = None


# --------------------------------------------------------------------------------------------- #
_SCHEMA: dict[str, dict[str, tuple]] = {
    # section: key -> (type, required, default, check, allowed text)
    "case": {"name": (str, False, "case", None, "a string"),
             "description": (str, False, "", None, "a string"),
             "source": (str, False, "", None, "a string")},
    "gear_pair": {
        "module_mm": (float, True, None, lambda v: 0.1 <= v <= 100, "a number in [0.1, 100] mm"),
        "pressure_angle_deg": (float, False, 20.0, lambda v: 10 <= v <= 35, "a number in [10, 35] deg"),
        "helix_angle_deg": (float, False, 0.0, lambda v: -45 <= v <= 45, "a number in [-45, 45] deg"),
    },
    "cutter": {
        "addendum": (float, False, 1.25, lambda v: 0.8 <= v <= 2.0, "a number in [0.8, 2.0] x module"),
        "dedendum": (float, False, 1.0, lambda v: 0.5 <= v <= 2.0, "a number in [0.5, 2.0] x module"),
        "tip_radius": (float, False, 0.38, lambda v: 0.0 <= v <= 0.6, "a number in [0, 0.6] x module"),
        "shaper_teeth": (int, False, 20, lambda v: 8 <= v <= 200, "an integer in [8, 200]"),
        "shaper_profile_shift": (float, False, 0.0, lambda v: -1 <= v <= 1, "a number in [-1, 1]"),
    },
    "member": {
        "teeth": (int, True, None, lambda v: 5 <= v <= 1000, "an integer in [5, 1000]"),
        "profile_shift": (float, False, 0.0, lambda v: -1.5 <= v <= 2.0, "a number in [-1.5, 2.0]"),
        "face_width_mm": (float, True, None, lambda v: 0.5 <= v <= 2000, "a number in [0.5, 2000] mm"),
        "tip_diameter_mm": (float, False, None, lambda v: v > 0, "a positive number (mm)"),
        "bore_diameter_mm": (float, False, None, lambda v: v > 0, "a positive number (mm)"),
        "internal": (bool, False, False, None, "true or false"),
        "thickness_allowance_um": (float, False, 0.0, lambda v: 0 <= v <= 2000, "a number in [0, 2000] um"),
        "rim_thickness_mm": (float, False, None, lambda v: 0 < v <= 1e4,
                             "a number in (0, 1e4] mm: radial rim thickness below the root circle (a ring gear: "
                             "above it), given with web_thickness_mm"),
        "web_thickness_mm": (float, False, None, lambda v: 0 < v <= 2000,
                             "a number in (0, 2000] mm, at most the face width: the web joining rim and hub"),
        "web_offset_mm": (float, False, 0.0, lambda v: -1000 <= v <= 1000,
                          "a number in [-1000, 1000] mm: the web's mid-plane from mid-face"),
        "hub_diameter_mm": (float, False, None, lambda v: 0 < v <= 1e5,
                            "a positive number (mm): where the web meets the hub (a ring gear: the outer ring)"),
    },
    "modifications": {
        "tip_relief_um": (float, False, 0.0, lambda v: 0 <= v <= 500, "a number in [0, 500] um"),
        "tip_relief_start_diameter_mm": (float, False, None, lambda v: v > 0, "a positive number (mm)"),
        "tip_relief_exponent": (float, False, 1.0, lambda v: 1 <= v <= 3, "a number in [1, 3]"),
        "profile_crowning_um": (float, False, 0.0, lambda v: 0 <= v <= 200, "a number in [0, 200] um"),
        "lead_crowning_um": (float, False, 0.0, lambda v: 0 <= v <= 200, "a number in [0, 200] um"),
        "lead_slope_um": (float, False, 0.0, lambda v: -200 <= v <= 200, "a number in [-200, 200] um"),
        "pitch_errors_um": (dict, False, {}, None, "a table {tooth index = error in um}"),
        "profile_slope_um": (float, False, 0.0, lambda v: -200 <= v <= 200, "a number in [-200, 200] um"),
        "roll_ratio_error": (float, False, 0.0, lambda v: -0.01 <= v <= 0.01, "a number in [-0.01, 0.01]"),
        "tip_edge_radius_mm": (float, False, 0.0, lambda v: 0 <= v <= 50, "a number in [0, 50] mm (0: a sharp "
                               "tip edge): the radius of the rounding tangent to the flank and the tip circle"),
        "tip_chamfer_mm": (float, False, 0.0, lambda v: 0 <= v <= 50, "a number in [0, 50] mm (0: none): the leg "
                           "of a chamfer of the tip edge, along the flank and along the tip circle"),
    },
    "assembly": {
        "centre_distance_mm": (float, False, None, lambda v: v > 0, "a positive number (mm)"),
        "lead_misalignment_um": (float, False, 0.0, lambda v: -500 <= v <= 500, "a number in [-500, 500] um"),
        "lead_deviation_um": (float, False, 0.0, lambda v: -500 <= v <= 500, "a number in [-500, 500] um"),
    },
    "material": {
        "youngs_modulus_mpa": (float, False, 206000.0, lambda v: 1e3 <= v <= 1e6, "a number in [1e3, 1e6] MPa"),
        "poisson_ratio": (float, False, 0.3, lambda v: 0.0 <= v < 0.5, "a number in [0, 0.5)"),
    },
    "load": {
        "torque_nm": (float, False, None, lambda v: 0 < v <= 1e6, "a number in (0, 1e6] N m"),
        "torques_nm": (list, False, None, None, "a list of numbers in (0, 1e6] N m"),
        "driver": (str, False, "pinion", lambda v: v == "pinion", "'pinion' (the pinion drives)"),
    },
    "analysis": {
        "positions": (int, False, 30, lambda v: 1 <= v <= 2000, "an integer in [1, 2000] (per mesh cycle)"),
        "cycles": (int, False, 1, lambda v: 1 <= v <= 1000, "an integer in [1, 1000] (mesh cycles analysed; the "
                   "pinion teeth for a full pinion revolution)"),
        "fidelity": (str, False, "default", lambda v: v in FIDELITIES, f"one of {sorted(FIDELITIES)}"),
    },
}
_TOP = {"case", "gear_pair", "cutter", "pinion", "gear", "assembly", "material", "load", "analysis"}


def _section(data: dict, name: str, schema: str, file: str | None, required: bool = False) -> dict:
    raw = data.get(name)
    if raw is None:
        if required:
            raise CaseError(name, None, "a required table [" + name + "] is missing", file)
        raw = {}
    if not isinstance(raw, dict):
        raise CaseError(name, raw, "a table", file)
    spec = _SCHEMA[schema]
    extra = set(raw) - set(spec) - ({"modifications"} if schema == "member" else set())
    if extra:
        key = sorted(extra)[0]
        raise CaseError(f"{name}.{key}", raw[key], f"unknown key; allowed keys are {sorted(spec)}", file)
    out = {}
    for key, (typ, req, default, check, allowed) in spec.items():
        path = f"{name}.{key}"
        if key not in raw:
            if req:
                raise CaseError(path, None, f"required; {allowed}", file)
            out[key] = default
            continue
        v = raw[key]
        if typ is float and isinstance(v, int) and not isinstance(v, bool):
            v = float(v)
        if typ is int and isinstance(v, float) and v.is_integer():
            raise CaseError(path, v, f"{allowed} (write it without a decimal point)", file)
        if not isinstance(v, typ) or (typ in (int, float) and isinstance(v, bool)):
            raise CaseError(path, v, f"wrong type {type(v).__name__}; {allowed}", file)
        if typ is float and not math.isfinite(v):
            raise CaseError(path, v, allowed, file)
        if check is not None and not check(v):
            raise CaseError(path, v, allowed, file)
        out[key] = v
    return out


def _modifications(raw: dict, name: str, file: str | None) -> Modifications:
    m = _section({name: raw}, name, "modifications", file)
    if m["tip_edge_radius_mm"] > 0 and m["tip_chamfer_mm"] > 0:
        raise CaseError(f"{name}.tip_chamfer_mm", m["tip_chamfer_mm"], "0 when tip_edge_radius_mm is given: a tip "
                        "edge is rounded or chamfered, not both", file)
    errors = []
    for k, v in m["pitch_errors_um"].items():
        try:
            tooth = int(k)
        except ValueError:
            raise CaseError(f"{name}.pitch_errors_um.{k}", v, "keys are tooth indices (integers)", file)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not -500 <= v <= 500:
            raise CaseError(f"{name}.pitch_errors_um.{k}", v, "a number in [-500, 500] um", file)
        errors.append((tooth, float(v) * 1e-3))
    return Modifications(
        tip_relief=m["tip_relief_um"] * 1e-3, tip_relief_start_diameter=m["tip_relief_start_diameter_mm"],
        tip_relief_exponent=m["tip_relief_exponent"], profile_crowning=m["profile_crowning_um"] * 1e-3,
        lead_crowning=m["lead_crowning_um"] * 1e-3, lead_slope=m["lead_slope_um"] * 1e-3,
        pitch_errors=tuple(sorted(errors)), profile_slope=m["profile_slope_um"] * 1e-3,
        roll_ratio_error=m["roll_ratio_error"], tip_edge_radius=m["tip_edge_radius_mm"],
        tip_chamfer=m["tip_chamfer_mm"])


def _member(data: dict, name: str, file: str | None) -> Member:
    m = _section(data, name, "member", file, required=True)
    mods = _modifications(data[name].get("modifications", {}), f"{name}.modifications", file)
    if (m["rim_thickness_mm"] is None) != (m["web_thickness_mm"] is None):
        key = "web_thickness_mm" if m["web_thickness_mm"] is None else "rim_thickness_mm"
        raise CaseError(f"{name}.{key}", None, "rim_thickness_mm and web_thickness_mm are given together "
                        "(a webbed body) or not at all (a solid disc)", file)
    if m["web_thickness_mm"] is not None and m["web_thickness_mm"] > m["face_width_mm"]:
        raise CaseError(f"{name}.web_thickness_mm", m["web_thickness_mm"],
                        f"at most the face width {m['face_width_mm']} mm", file)
    if m["web_thickness_mm"] is not None and abs(m["web_offset_mm"]) + m["web_thickness_mm"] / 2 > \
            m["face_width_mm"] / 2 + 1e-9:
        raise CaseError(f"{name}.web_offset_mm", m["web_offset_mm"], "a web inside the face width: "
                        f"|offset| + web_thickness/2 <= {m['face_width_mm'] / 2} mm", file)
    return Member(m["teeth"], m["profile_shift"], m["face_width_mm"], m["tip_diameter_mm"],
                  m["bore_diameter_mm"], m["internal"], mods, m["thickness_allowance_um"] * 1e-3,
                  m["rim_thickness_mm"], m["web_thickness_mm"], m["web_offset_mm"], m["hub_diameter_mm"])


def parse_case(data: dict, file: str | None = None) -> CylindricalCase:
    """Validate a case given as a dict (as read from TOML) and convert it to internal units."""
    extra = set(data) - _TOP
    if extra:
        key = sorted(extra)[0]
        raise CaseError(key, "[table]" if isinstance(data[key], dict) else data[key],
                        f"unknown key; allowed top-level tables are {sorted(_TOP)}", file)
    c = _section(data, "case", "case", file)
    gp = _section(data, "gear_pair", "gear_pair", file, required=True)
    cu = _section(data, "cutter", "cutter", file)
    pinion, gear = _member(data, "pinion", file), _member(data, "gear", file)
    asm = _section(data, "assembly", "assembly", file)
    mat = _section(data, "material", "material", file)
    load = _section(data, "load", "load", file, required=True)
    ana = _section(data, "analysis", "analysis", file)
    if pinion.internal:
        raise CaseError("pinion.internal", True, "the pinion must be external (false)", file)
    if load["torque_nm"] is None and load["torques_nm"] is None:
        raise CaseError("load.torque_nm", None, "give torque_nm (N m) or torques_nm (list of N m)", file)
    if load["torques_nm"] is not None:
        torques = load["torques_nm"]
        for i, t in enumerate(torques):
            if isinstance(t, bool) or not isinstance(t, (int, float)) or not 0 < t <= 1e6:
                raise CaseError(f"load.torques_nm[{i}]", t, "a number in (0, 1e6] N m", file)
        if not torques:
            raise CaseError("load.torques_nm", torques, "a non-empty list of torques in N m", file)
    else:
        torques = [load["torque_nm"]]
    m = gp["module_mm"]
    if gear.internal and gear.teeth - pinion.teeth < 8:
        raise CaseError("gear.teeth", gear.teeth,
                        f"an internal gear needs at least 8 more teeth than the pinion ({pinion.teeth}) "
                        "to avoid tip interference", file)
    return CylindricalCase(
        name=c["name"], module=m, pressure_angle=gp["pressure_angle_deg"] * DEG,
        helix_angle=gp["helix_angle_deg"] * DEG, rack_addendum=cu["addendum"] * m,
        rack_dedendum=cu["dedendum"] * m, rack_tip_radius=cu["tip_radius"] * m,
        shaper_teeth=cu["shaper_teeth"], shaper_profile_shift=cu["shaper_profile_shift"],
        pinion=pinion, gear=gear, centre_distance=asm["centre_distance_mm"],
        lead_misalignment=asm["lead_misalignment_um"] * 1e-3, lead_deviation=asm["lead_deviation_um"] * 1e-3,
        young=mat["youngs_modulus_mpa"], poisson=mat["poisson_ratio"],
        torques=tuple(float(t) * 1e3 for t in torques), positions=ana["positions"], cycles=ana["cycles"],
        fidelity=ana["fidelity"],
        fidelity_params=dict(FIDELITIES[ana["fidelity"]]), source=c["source"] or None)


def read_toml(path: str | Path) -> dict:
    """Read a case file as a dict; a missing file or broken TOML is a CaseError (exit status 2)."""
    path = Path(path)
    if not path.is_file():
        raise CaseError("CASE", str(path), "an existing case file (.toml)")
    try:
        return tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise CaseError("file", path.name, f"valid TOML ({exc})", str(path)) from None


def load_case(path: str | Path) -> CylindricalCase:
    """Read and validate a case file; raise CaseError for any user mistake."""
    return parse_case(read_toml(path), file=str(path))
