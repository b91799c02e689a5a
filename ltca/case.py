"""Case files (TOML) for cylindrical gear pairs: schema, validation and unit conversion.

Engineer's units in the file (mm, deg, um, N m, MPa); converted once here to the SI-consistent
mm-N-MPa-rad used inside. Every field is checked: a bad file raises :class:`ltca.errors.CaseError`
naming the field, its value and what is allowed; the command line turns that into exit status 2.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .errors import CaseError
from .validation import Bool, Int, Num, OneOrList, Str, Table, ToothMap, check_table, table_reference

__all__ = ["Modifications", "Member", "CylindricalCase", "load_case", "parse_case", "read_toml", "to_toml", "case_keys",
           "check_torques", "key_reference", "FIDELITIES", "CASE", "TORQUE"]

DEG = math.pi / 180.0

#: Fidelity presets: flank element size (x module), body element size (x module), compliance grid
#: (profile x face per flank), contact cells across the Hertz width, face slices, near-field on/off, and the
#: longest contact cell along a helical face (x module; more slices on a wide helical face), the widest contact cell
#: across the line (x module; it resolves a tip edge's gap kink, :meth:`Fidelity.cell_size`), and the element size
#: on the loaded teeth's read fillets (x their smallest radius of curvature, at most h_flank; fem.fillet).
FIDELITIES: dict[str, dict[str, Any]] = {
    "coarse": dict(h_flank=0.45, h_body=1.6, grid=(7, 6), cells_per_b=3, slices=8, near_field=True, window=1.8,
                   slice_length=0.5, ds_max=0.04, fillet=0.4),
    "default": dict(h_flank=0.3, h_body=1.3, grid=(9, 8), cells_per_b=5, slices=14, near_field=True, window=2.0,
                    slice_length=0.25, ds_max=0.03, fillet=0.4),
    "fine": dict(h_flank=0.2, h_body=1.0, grid=(12, 10), cells_per_b=8, slices=20, near_field=True, window=2.5,
                 slice_length=0.17, ds_max=0.02, fillet=0.35),
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
    profile_form: float = 0.0          # f_falpha, mm, signed parabolic form deviation (+ convex, - hollow)
    lead_form: float = 0.0             # f_fbeta, mm, signed parabolic form deviation over the face
    tip_edge_radius: float = 0.0       # mm, rounding of the tip edges (tangent to flank and tip circle); 0: sharp
    tip_chamfer: float = 0.0           # mm, leg of a chamfer of the tip edges (along flank and tip circle); 0: none
    root_relief: float = 0.0           # C_f at the start of the active profile, mm
    root_relief_start_diameter: float | None = None  # mm; None: the diameter of the single-pair zone start
    root_relief_exponent: float = 1.0  # 1 linear, 2 parabolic
    end_relief_datum: float = 0.0      # C_I at the datum face (z = -b/2), mm
    end_relief_datum_length: float = 0.0      # L_I, mm
    end_relief_non_datum: float = 0.0  # C_II at the non-datum face (z = +b/2), mm
    end_relief_non_datum_length: float = 0.0  # L_II, mm
    end_relief_exponent: float = 1.0   # 1 linear, 2 parabolic
    triangular_tip_relief: float = 0.0  # C_Ea at the corner of tip and face end, mm
    triangular_tip_relief_start_diameter: float | None = None  # d_Ea at the face end, mm; None: as the tip relief's
    triangular_tip_relief_length: float = 0.0  # L_Ea along the tip edge from the face end, mm
    triangular_tip_relief_face: str = "both"   # 'datum', 'non_datum' or 'both'


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
    positions_auto: bool = False  # analysis.positions not given: ltca run picks enough for the cycle's transitions


#: one torque (N m) as the case file and ``--torque`` give it
TORQUE = Num(1e-3, 1e6, "N m")

# --------------------------------------------------------------------------------------------- #
#: the cylindrical kind's tables in the one validation layer (ltca.validation): type, range, default, unit and
#: meaning of every key; ``ltca keys`` and docs/case_keys.md are generated from them
_SCHEMA: dict[str, dict] = {
    "case": {"name": Str(non_empty=True, max_len=200, default="case",
                         meaning="name of the case, in plot titles and summary.json"),
             "description": Str(max_len=2000, default="", meaning="free text describing the case"),
             "source": Str(max_len=2000, default="", meaning="where the data come from (paper, drawing, file)")},
    "gear_pair": {
        "module_mm": Num(0.1, 100, "mm", required=True, meaning="normal module m_n"),
        "pressure_angle_deg": Num(10, 35, "deg", default=20.0,
                                  meaning="normal pressure angle alpha_n of the basic rack"),
        "helix_angle_deg": Num(-45, 45, "deg", default=0.0,
                               meaning="helix angle beta at the reference circle (0: spur; the sign is the hand)"),
    },
    "cutter": {
        "addendum": Num(0.8, 2.0, "x module", default=1.25,
                        meaning="addendum of the generating rack h_aP0 (cuts the dedendum of the gear)"),
        "dedendum": Num(0.5, 2.0, "x module", default=1.0,
                        meaning="dedendum of the generating rack (cuts the tip; above the tip circle when the tip "
                                "diameter is given)"),
        "tip_radius": Num(0.0, 0.6, "x module", default=0.38,
                          meaning="tip radius rho_aP0 of the rack (forms the root fillet)"),
        "shaper_teeth": Int(8, 200, default=20,
                            meaning="teeth of the pinion-type shaper cutter that cuts an internal gear"),
        "shaper_profile_shift": Num(-1, 1, default=0.0, meaning="profile shift coefficient of that shaper cutter"),
    },
    "member": {
        "teeth": Int(5, 1000, required=True, meaning="number of teeth z"),
        "profile_shift": Num(-1.5, 2.0, default=0.0, meaning="profile shift coefficient x"),
        "face_width_mm": Num(0.5, 2000, "mm", required=True, meaning="face width b"),
        "tip_diameter_mm": Num(1, 1e5, "mm", meaning="tip diameter d_a (default: from the module, shift and rack)"),
        "bore_diameter_mm": Num(1, 1e5, "mm", meaning="bore (seat on the shaft, held rigid); a ring gear: its outer "
                                "diameter held in the housing (default: a proportion of the root diameter)"),
        "internal": Bool(default=False, meaning="true for an internal (ring) gear; the pinion is always external"),
        "thickness_allowance_um": Num(0, 2000, "um", default=0.0, meaning="normal tooth thinning for backlash, total"),
        "rim_thickness_mm": Num(0, 1e4, "mm", lo_open=True, note="given with web_thickness_mm",
                                meaning="webbed body: radial rim thickness below the root circle (a ring gear: "
                                        "above it)"),
        "web_thickness_mm": Num(0, 2000, "mm", lo_open=True, note="at most the face width",
                                meaning="webbed body: axial width of the web between rim and hub"),
        "web_offset_mm": Num(-1000, 1000, "mm", default=0.0,
                             meaning="webbed body: axial offset of the web's mid-plane from mid-face"),
        "hub_diameter_mm": Num(0, 1e5, "mm", lo_open=True, meaning="webbed body: diameter where the web meets the "
                                                                    "hub (a ring gear: the outer ring)"),
    },
    "modifications": {
        "tip_relief_um": Num(0, 500, "um", default=0.0,
                             meaning="tip relief C_a, material removed normal to the flank at the tip"),
        "tip_relief_start_diameter_mm": Num(1, 1e5, "mm", meaning="diameter where the tip relief starts (default: "
                                            "the end of the single-pair zone when 1 < eps_alpha < 2, else 40 % of "
                                            "the active profile height below the tip)"),
        "tip_relief_exponent": Num(1, 3, default=1.0, meaning="shape of the tip relief: 1 linear, 2 parabolic"),
        "profile_crowning_um": Num(0, 200, "um", default=0.0,
                                   meaning="profile crowning C_alpha, parabola over the active profile"),
        "lead_crowning_um": Num(0, 200, "um", default=0.0, meaning="lead crowning C_beta, parabola over the face "
                                                                   "width"),
        "lead_slope_um": Num(-200, 200, "um", default=0.0,
                             meaning="lead slope f_Hbeta, linear over the face (+ at z = +b/2)"),
        "pitch_errors_um": ToothMap(Num(-500, 500, "um"), meaning="tooth position errors per tooth index (+: drive "
                                                                  "flank moved back)"),
        "profile_slope_um": Num(-200, 200, "um", default=0.0, meaning="profile slope deviation f_Halpha (+: tip "
                                                                      "relieved)"),
        "roll_ratio_error": Num(-0.01, 0.01, default=0.0,
                                meaning="generating-chain ratio error e, turned into a profile slope"),
        "profile_form_um": Num(-200, 200, "um", default=0.0,
                               meaning="parabolic profile form deviation f_falpha (+ convex, - hollow)"),
        "lead_form_um": Num(-200, 200, "um", default=0.0,
                            meaning="parabolic lead form deviation f_fbeta (+ convex, - hollow)"),
        "tip_edge_radius_mm": Num(0, 50, "mm", default=0.0, note="0: a sharp tip edge",
                                  meaning="rounding of the tip edges, tangent to the flank and the tip circle"),
        "tip_chamfer_mm": Num(0, 50, "mm", default=0.0, note="0: none",
                              meaning="leg of a chamfer of the tip edges, along the flank and the tip circle"),
        "root_relief_um": Num(0, 500, "um", default=0.0, meaning="root relief C_f, material removed normal to the "
                              "flank at the start of the active profile (where the mate's tip meets it)"),
        "root_relief_start_diameter_mm": Num(1, 1e5, "mm", meaning="diameter where the root relief starts (default: "
                                             "the start of the single-pair zone)"),
        "root_relief_exponent": Num(1, 3, default=1.0, meaning="shape of the root relief: 1 linear, 2 parabolic"),
        "end_relief_datum_um": Num(0, 500, "um", default=0.0, note="given with end_relief_datum_length_mm",
                                   meaning="end relief C_I at the datum face (z = -b/2), normal to the flank"),
        "end_relief_datum_length_mm": Num(0, 1e4, "mm", default=0.0, meaning="axial length L_I of the end relief at "
                                          "the datum face, from the face inwards"),
        "end_relief_non_datum_um": Num(0, 500, "um", default=0.0, note="given with end_relief_non_datum_length_mm",
                                       meaning="end relief C_II at the non-datum face (z = +b/2)"),
        "end_relief_non_datum_length_mm": Num(0, 1e4, "mm", default=0.0, meaning="axial length L_II of the end "
                                              "relief at the non-datum face, from the face inwards"),
        "end_relief_exponent": Num(1, 3, default=1.0, meaning="shape of the end reliefs: 1 linear, 2 parabolic"),
        "triangular_tip_relief_um": Num(0, 500, "um", default=0.0, note="given with triangular_tip_relief_length_mm",
                                        meaning="triangular tip relief C_Ea at the corner of the tip edge and the "
                                                "face end"),
        "triangular_tip_relief_start_diameter_mm": Num(1, 1e5, "mm", meaning="diameter d_Ea where the triangular "
                                                       "tip relief starts on the face end (default: as the tip "
                                                       "relief's start)"),
        "triangular_tip_relief_length_mm": Num(0, 1e4, "mm", default=0.0, meaning="length L_Ea along the tip edge "
                                               "from the face end where the triangular tip relief starts"),
        "triangular_tip_relief_face": Str(("datum", "non_datum", "both"), default="both",
                                          meaning="the face end(s) with a triangular tip relief: datum (z = -b/2), "
                                                  "non_datum (z = +b/2) or both"),
    },
    "assembly": {
        "centre_distance_mm": Num(1, 1e5, "mm", meaning="centre distance a (default: the working centre distance "
                                                        "for zero backlash)"),
        "lead_misalignment_um": Num(-500, 500, "um", default=0.0,
                                    meaning="misalignment over the face width in the plane of action (f_ma)"),
        "lead_deviation_um": Num(-500, 500, "um", default=0.0,
                                 meaning="misalignment over the face width normal to the plane of action"),
    },
    "material": {
        "youngs_modulus_mpa": Num(1e3, 1e6, "MPa", default=206000.0, meaning="Young's modulus of both members"),
        "poisson_ratio": Num(0.0, 0.5, hi_open=True, default=0.3, meaning="Poisson's ratio of both members"),
    },
    "load": {
        "torque_nm": OneOrList(TORQUE, 1, 100, distinct=True, required=True,
                               meaning="pinion torque, or a list of torques analysed one after the other; "
                                       "`ltca run --torque` replaces it"),
        "driver": Str(("pinion",), default="pinion", meaning="the driving member (the pinion)"),
    },
    "analysis": {
        "positions": Int(1, 2000, default=30, note="per mesh cycle",
                         meaning="mesh positions per mesh cycle (default: 30, or more when the transition zones of "
                                 "the cycle need them: 4 positions in each)"),
        "cycles": Int(1, 1000, default=1, note="mesh cycles analysed; the pinion teeth for a full pinion revolution",
                      meaning="mesh cycles analysed (the pinion's teeth: a full pinion revolution)"),
        "fidelity": Str(tuple(FIDELITIES), default="default",
                        meaning="element sizes and contact grid: coarse (fast), default, fine"),
    },
}
_TOP = {"case", "gear_pair", "cutter", "pinion", "gear", "assembly", "material", "load", "analysis"}
#: top-level tables read elsewhere: [design] by ltca.design.schema (``ltca optimise``)
_ELSEWHERE = {"design"}


def _member_table() -> Table:
    return Table({**_SCHEMA["member"], "modifications": Table(_SCHEMA["modifications"])}, required=True)


#: the cylindrical kind: every table of a case file
CASE = Table({
    "case": Table(_SCHEMA["case"]), "gear_pair": Table(_SCHEMA["gear_pair"], required=True),
    "cutter": Table(_SCHEMA["cutter"]), "pinion": _member_table(), "gear": _member_table(),
    "assembly": Table(_SCHEMA["assembly"]), "material": Table(_SCHEMA["material"]),
    "load": Table(_SCHEMA["load"], required=True), "analysis": Table(_SCHEMA["analysis"]),
}, extra=lambda k: k in _ELSEWHERE)


def _modifications(m: dict, name: str, file: str | None) -> Modifications:
    """The checked ``[*.modifications]`` table ``m`` in mm."""
    if m["tip_edge_radius_mm"] > 0 and m["tip_chamfer_mm"] > 0:
        raise CaseError(f"{name}.tip_chamfer_mm", m["tip_chamfer_mm"], "0 when tip_edge_radius_mm is given: a tip "
                        "edge is rounded or chamfered, not both", file)
    for depth, length in (("end_relief_datum_um", "end_relief_datum_length_mm"),
                          ("end_relief_non_datum_um", "end_relief_non_datum_length_mm"),
                          ("triangular_tip_relief_um", "triangular_tip_relief_length_mm")):
        if m[depth] > 0 and m[length] <= 0:
            raise CaseError(f"{name}.{length}", m[length], f"a length > 0 mm when {depth} is given", file)
    errors = [(tooth, v * 1e-3) for tooth, v in m["pitch_errors_um"].items()]
    return Modifications(
        tip_relief=m["tip_relief_um"] * 1e-3, tip_relief_start_diameter=m["tip_relief_start_diameter_mm"],
        tip_relief_exponent=m["tip_relief_exponent"], profile_crowning=m["profile_crowning_um"] * 1e-3,
        lead_crowning=m["lead_crowning_um"] * 1e-3, lead_slope=m["lead_slope_um"] * 1e-3,
        pitch_errors=tuple(sorted(errors)), profile_slope=m["profile_slope_um"] * 1e-3,
        roll_ratio_error=m["roll_ratio_error"], profile_form=m["profile_form_um"] * 1e-3,
        lead_form=m["lead_form_um"] * 1e-3, tip_edge_radius=m["tip_edge_radius_mm"], tip_chamfer=m["tip_chamfer_mm"],
        root_relief=m["root_relief_um"] * 1e-3, root_relief_start_diameter=m["root_relief_start_diameter_mm"],
        root_relief_exponent=m["root_relief_exponent"], end_relief_datum=m["end_relief_datum_um"] * 1e-3,
        end_relief_datum_length=m["end_relief_datum_length_mm"],
        end_relief_non_datum=m["end_relief_non_datum_um"] * 1e-3,
        end_relief_non_datum_length=m["end_relief_non_datum_length_mm"], end_relief_exponent=m["end_relief_exponent"],
        triangular_tip_relief=m["triangular_tip_relief_um"] * 1e-3,
        triangular_tip_relief_start_diameter=m["triangular_tip_relief_start_diameter_mm"],
        triangular_tip_relief_length=m["triangular_tip_relief_length_mm"],
        triangular_tip_relief_face=m["triangular_tip_relief_face"])


def _member(m: dict, name: str, file: str | None) -> Member:
    """The checked ``[pinion]`` or ``[gear]`` table ``m``, after the cross-field checks."""
    mods = _modifications(m["modifications"], f"{name}.modifications", file)
    ToothMap.check_teeth(dict(mods.pitch_errors), m["teeth"], f"{name}.modifications.pitch_errors_um", file)
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
    from .validation import check_kind
    check_kind(data, "cylindrical", file)
    if isinstance(data.get("load"), dict) and "torques_nm" in data["load"]:
        raise CaseError("load.torques_nm", data["load"]["torques_nm"], "renamed: write torque_nm = a number or a "
                        "list of numbers (N m), e.g. torque_nm = [100.0, 200.0]", file)
    d = check_table(data, CASE, "", file)
    c, gp, cu, asm, mat, load, ana = (d[k] for k in ("case", "gear_pair", "cutter", "assembly", "material", "load",
                                                     "analysis"))
    pinion, gear = _member(d["pinion"], "pinion", file), _member(d["gear"], "gear", file)
    if pinion.internal:
        raise CaseError("pinion.internal", True, "the pinion must be external (false)", file)
    torques = load["torque_nm"]
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
        fidelity_params=dict(FIDELITIES[ana["fidelity"]]), source=c["source"] or None,
        positions_auto="positions" not in (data.get("analysis") or {}))


def check_torques(v: Any, path: str = "load.torque_nm", file: str | None = None) -> tuple[float, ...]:
    """``torque_nm``: a number or a list of 1 to 100 distinct numbers in [1e-3, 1e6] N m -> tuple in N m."""
    return _SCHEMA["load"]["torque_nm"].check(v, path, file)


def case_keys() -> dict[str, str]:
    """Every settable case key as a dotted path (``"pinion.modifications.lead_crowning_um"``) -> what is allowed."""
    return {f"{r['table']}.{r['key']}": r["allowed"] for r in table_reference(CASE)}


def key_reference() -> list[dict]:
    """Every case key with its table, type, unit, default, allowed range and meaning, walked from :data:`CASE`
    (the source of ``ltca keys`` and docs/case_keys.md)."""
    return [{k: v for k, v in r.items() if k != "array"} for r in table_reference(CASE)]


def read_toml(path: str | Path) -> dict:
    """Read a case file as a dict; a missing file, non-UTF-8 bytes, broken TOML or deep nesting is a CaseError
    (exit status 2). One reader for every case kind: :func:`ltca.validation.read_case_file`."""
    from .validation import read_case_file
    return read_case_file(path)


def load_case(path: str | Path) -> CylindricalCase:
    """Read and validate a case file; raise CaseError for any user mistake."""
    return parse_case(read_toml(path), file=str(path))


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"no TOML for {type(v).__name__}")


def to_toml(data: dict, prefix: str = "") -> str:
    """A case dict (as read from TOML: tables, scalars, lists of scalars) as TOML text, e.g. a variant's case
    file for a standalone ``ltca run``. Floats are written exactly (``repr``)."""
    lines = [f"{json.dumps(k)} = {_toml_value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    out = ([f"[{prefix}]"] if prefix and lines else []) + lines
    for k, v in data.items():
        if isinstance(v, dict):
            sub = to_toml(v, f"{prefix}.{json.dumps(k)}" if prefix else json.dumps(k))
            out += [""] + [sub] if sub else []
    return "\n".join(out)
