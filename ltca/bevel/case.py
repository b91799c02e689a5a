"""Spiral bevel case: read and validate a TOML case with a [bevel] table (basic data, flank targets, blank offset).

Instead of the targets a case may give each member's settings sheet per flank, ``[bevel.settings.gear.concave]``
and so on (keys of :mod:`ltca.geometry.bevel.sheet`): the pair is then cut as given, with no synthesis. A member's
face and root cones may be given (``[bevel.blank.pinion]``, ``[bevel.blank.gear]``) instead of designed, e.g. for a
pair from another program (:func:`case_blank`).

Case units: mm, deg, arcsec; converted once here to mm and rad.  Mistakes raise
:class:`ltca.errors.CaseError` naming the field.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ltca.geometry.bevel.blank import BevelBasicData, BevelBlank, design_blank, with_cones
from ltca.geometry.bevel.sheet import member_from_sheet
from ltca.geometry.bevel.synthesis import FlankTarget
from ltca.geometry.bevel.tca import RAD_PER_ARCSEC

from ..errors import CaseError
from ..validation import DesignError, Int, List, Num, OneOrList, Str, Table, check_kind, check_table
from .model import BevelMounting, face_limit

__all__ = ["BevelCase", "load_bevel_case", "bevel_case_from_data", "check_bevel_torques", "case_blank"]

# the bevel kind in the one validation layer (ltca.validation); ranges are those the cradle model and the
# Cao et al. (2008) synthesis are known to handle (outside them the Newton solves of generation and TCA lose the flank)
_FLANK = Table({
    "path_angle_deg": Num(-60, 60, "deg", required=True, meaning="contact-path angle eta2 on the gear flank"),
    "te_magnitude_arcsec": Num(1, 200, "arcsec", required=True, meaning="parabolic TE amplitude over a cycle"),
    "ellipse_major_mm": Num(0.5, 50, "mm", required=True, meaning="contact-ellipse major axis at the mean point"),
}, required=True, meaning="synthesis target of the flank")
_DERIVS = List(Num(-1e6, 1e6), 1, 6)


def _flank_sheet(blade: str) -> Table:
    """One flank's settings sheet (geometry.bevel.sheet); ranges are those the generator is built for."""
    return Table({
        "generation": Str(("generated", "formate"), default="generated"),
        "blade": Str((blade,), default=blade),
        "radial_setting_mm": Num(0, 1e4, "mm", required=True, lo_open=True),
        "cradle_angle_deg": Num(-360, 360, "deg", required=True),
        "machine_root_angle_deg": Num(0, 90, "deg", required=True, lo_open=True),
        "machine_center_to_back_mm": Num(-1e3, 1e3, "mm", default=0.0),
        "blank_offset_mm": Num(-1e3, 1e3, "mm", default=0.0),
        "sliding_base_mm": Num(-1e3, 1e3, "mm", default=0.0),
        "tilt_deg": Num(-45, 45, "deg", default=0.0),
        "swivel_deg": Num(-360, 360, "deg", default=0.0),
        "ratio_of_roll": Num(0, 100, "", default=None, lo_open=True, note="required for a generated flank"),
        "modified_roll_2C": Num(-1e3, 1e3, "", default=0.0),
        "modified_roll_6D": Num(-1e4, 1e4, "", default=0.0),
        "modified_roll_24E": Num(-1e5, 1e5, "", default=0.0),
        "modified_roll_120F": Num(-1e6, 1e6, "", default=0.0),
        "modified_roll_720G": Num(-1e7, 1e7, "", default=0.0),
        "radial_motion_mm": _DERIVS, "vertical_motion_mm": _DERIVS, "helical_motion_mm": _DERIVS,
        "tilt_motion_deg": _DERIVS, "swivel_motion_deg": _DERIVS,
        "point_radius_mm": Num(0, 1e4, "mm", required=True, lo_open=True),
        "blade_angle_deg": Num(0, 45, "deg", required=True),
        "edge_radius_mm": Num(0, 100, "mm", default=0.0),
        "profile_radius_mm": Num(0, 1e7, "mm", default=None, lo_open=True, note="curved blade; absent: straight"),
        "toprem_depth_mm": Num(0, 1e3, "mm", default=None, lo_open=True, note="blended toprem from this depth"),
        "toprem_radius_mm": Num(0, 1e7, "mm", default=None, lo_open=True),
        "flankrem_depth_mm": Num(0, 1e3, "mm", default=None, lo_open=True, note="blended flankrem from this depth"),
        "flankrem_radius_mm": Num(0, 1e7, "mm", default=None, lo_open=True),
    }, required=True)


_MEMBER_SHEET = Table({"concave": _flank_sheet("outside"), "convex": _flank_sheet("inside")}, required=True)
_CONES = Table({
    "face_angle_deg": Num(0, 90, "deg", required=True, lo_open=True, note="at least the pitch angle",
                          meaning="face angle (face cone from the axis)"),
    "root_angle_deg": Num(0, 90, "deg", required=True, lo_open=True, note="at most the pitch angle",
                          meaning="root angle (root cone from the axis)"),
    "face_apex_mm": Num(-1e4, 1e4, "mm", required=True,
                        meaning="face-cone apex beyond the crossing point along the member's axis (ISO 23509 t_zF)"),
    "root_apex_mm": Num(-1e4, 1e4, "mm", required=True,
                        meaning="root-cone apex beyond the crossing point along the member's axis (ISO 23509 t_zR)"),
}, required=False, meaning="the member's face and root cones as given (default: designed from the basic data)")
_CONE_TABLE = Table({"pinion": _CONES, "gear": _CONES}, default={}, required=False,
                    meaning="given face and root cones of the members (default: Gleason's design)")
_SETTINGS = Table({"gear": _MEMBER_SHEET, "pinion": _MEMBER_SHEET}, default={}, required=False)
_BEVEL = Table({
    "pinion_teeth": Int(6, 100, required=True, meaning="pinion teeth z1"),
    "gear_teeth": Int(6, 300, required=True, note=">= pinion_teeth", meaning="gear teeth z2"),
    "module_mm": Num(0.5, 50, "mm", required=True, meaning="outer transverse module"),
    "face_width_mm": Num(1, 500, "mm", required=True, note="at most 0.4 of the outer cone distance",
                         meaning="face width"),
    "spiral_angle_deg": Num(15, 45, "deg", required=True, meaning="mean spiral angle"),
    "pressure_angle_deg": Num(14, 25, "deg", required=True, meaning="pressure angle of the cutter blades"),
    "shaft_angle_deg": Num(45, 135, "deg", default=90.0, meaning="shaft angle"),
    "gear_hand": Str(("left", "right"), required=True, meaning="hand of spiral of the gear"),
    "cutter_radius_mm": Num(5, 1000, "mm", required=True, meaning="mean cutter radius of the face-milling head"),
    "taper": Str(("standard", "uniform"), default="standard", meaning="tooth depth taper"),
    "blank_offset_mm": Num(-10, 10, "mm", default=None, meaning="pinion blank offset of the redesign (default: none)"),
    "working": Table(_FLANK.fields, default={}, required=False,
                     meaning="synthesis target of the working flank (or give [bevel.settings])"),
    "coast": Table(_FLANK.fields, default={}, required=False,
                   meaning="synthesis target of the coast flank (or give [bevel.settings])"),
    "settings": _SETTINGS,
    "blank": _CONE_TABLE,
}, required=True)
_TORQUE = Num(-1e5, 1e5, "N m", note="not 0")
_ASSEMBLY = Table({
    "E_mm": Num(-5, 5, "mm", default=0.0, meaning="pinion offset error (hypoid offset direction)"),
    "P_mm": Num(-5, 5, "mm", default=0.0, meaning="pinion axial error (+ away from the crossing point)"),
    "G_mm": Num(-5, 5, "mm", default=0.0, meaning="gear axial error (+ away from the crossing point)"),
    "sigma_deg": Num(-2, 2, "deg", default=0.0, meaning="shaft angle error"),
}, required=False)
_MATERIAL = Table({"youngs_modulus_mpa": Num(1e3, 1e6, "MPa", default=206000.0,
                                          meaning="Young's modulus of both members"),
                   "poisson_ratio": Num(0.0, 0.499, "", default=0.3, meaning="Poisson's ratio of both members")},
                  required=False)
_MOUNTING = Table({
    "pinion_seat_diameter_mm": Num(1, 5000, "mm", default=None,
                                   note="below the toe's root diameter less two whole depths",
                                   meaning="pinion shaft seat, held as on a rigid shaft (default: 0.45 x the toe's "
                                           "root diameter)"),
    "gear_mounting_distance_mm": Num(1, 1e4, "mm", default=None,
                                     note="0.3 to 20 whole depths behind the heel root",
                                     meaning="pitch apex to the gear's back mounting face, held rigidly (default: "
                                             "1.2 whole depths behind the heel root)"),
}, required=False)
_ANALYSIS = Table({"positions": Int(4, 400, default=21, meaning="positions per mesh cycle"),
                   "fidelity": Str(("coarse", "default", "fine"), default="default",
                                   meaning="element sizes and contact grid")}, required=False)
_CASE = Table({"bevel": _BEVEL,
               "case": Table({"name": Str(non_empty=True, max_len=200, default=None,
                                          meaning="name of the case (default: the file's stem)"),
                              "description": Str(default="", meaning="free text describing the case"),
                              "source": Str(default="", meaning="where the data come from")}),
               "load": Table({"torque_nm": OneOrList(_TORQUE, 1, 20, distinct=True, meaning="pinion torque: > 0 "
                                                     "drives on the working flank (pinion concave), < 0 on the "
                                                     "coast flank (pinion convex)")}, required=False),
               "assembly": _ASSEMBLY, "material": _MATERIAL, "analysis": _ANALYSIS, "mounting": _MOUNTING})


@dataclass(frozen=True)
class BevelCase:
    """A validated spiral bevel case (mm, rad, MPa; torques in N m on the pinion, the sign picks the flank).

    ``targets`` maps the pinion side ("concave": working, "convex": coast) to its synthesis target; ``cuts``
    ({"gear", "pinion"} -> MemberCut) holds the pair as its settings sheets cut it, when the case gives them;
    ``assembly`` holds the errors E, P, G (mm) and d_sigma (rad) as keyword arguments of
    :class:`ltca.geometry.bevel.tca.Assembly`; ``cones`` ({member: (face angle, root angle (rad), face apex, root
    apex (mm))}) the cones given instead of designed (:func:`case_blank`)."""
    name: str
    basic: BevelBasicData
    targets: dict
    blank_offset: float | None
    torques: tuple[float, ...]
    assembly: dict
    young: float
    poisson: float
    positions: int
    fidelity: str
    mounting: BevelMounting
    cuts: dict | None = None
    cones: dict | None = None


def load_bevel_case(case_path: str | Path) -> BevelCase:
    """Read and validate a bevel case; returns the basic data, the targets and the blank offset."""
    from ..case import read_toml
    path = Path(case_path)
    return bevel_case_from_data(read_toml(path), str(path), path.stem)


def bevel_case_from_data(data: dict, f: str | None = None, stem: str = "bevel") -> BevelCase:
    """:func:`load_bevel_case` of a case already read from TOML (``data`` without tables of other commands, e.g.
    ``[design]``); ``f`` names the file in messages, ``stem`` is the name when [case] gives none."""
    check_kind(data, "bevel", f)
    c = check_table(data, _CASE, "", f)
    torques = c["load"]["torque_nm"] or ()
    if any(x == 0 for x in torques):
        raise CaseError("load.torque_nm", data["load"]["torque_nm"], "non-zero torques (the sign picks the flank)", f)
    b = c["bevel"]
    if b["gear_teeth"] < b["pinion_teeth"]:
        raise CaseError("bevel.gear_teeth", b["gear_teeth"], f"at least pinion_teeth = {b['pinion_teeth']}", f)
    raw_b = data.get("bevel") if isinstance(data.get("bevel"), dict) else {}
    given = "settings" in raw_b
    targets = {}
    for name, side in (("working", "concave"), ("coast", "convex")):
        if name not in raw_b:
            if given:
                continue
            raise CaseError(f"bevel.{name}", None, "required (or give the settings sheets [bevel.settings.gear.*] "
                            "and [bevel.settings.pinion.*]); a table", f)
        t = b[name]
        targets[side] = FlankTarget(np.deg2rad(t["path_angle_deg"]), t["te_magnitude_arcsec"] * RAD_PER_ARCSEC,
                                    float(t["ellipse_major_mm"]))
    try:
        basic = BevelBasicData(z1=b["pinion_teeth"], z2=b["gear_teeth"], module=float(b["module_mm"]),
                               face_width=float(b["face_width_mm"]),
                               spiral_angle=np.deg2rad(b["spiral_angle_deg"]),
                               pressure_angle=np.deg2rad(b["pressure_angle_deg"]),
                               shaft_angle=np.deg2rad(b.get("shaft_angle_deg", 90.0)), hand=b["gear_hand"],
                               cutter_radius=float(b["cutter_radius_mm"]), taper=b.get("taper", "standard"))
        blank = design_blank(basic)
    except ValueError as exc:
        raise DesignError(f"bevel blank: {exc}", ("bevel.face_width_mm", "bevel.module_mm", "bevel.pinion_teeth",
                                                  "bevel.gear_teeth", "bevel.cutter_radius_mm"), file=f) from None
    cones = {m: (np.deg2rad(t["face_angle_deg"]), np.deg2rad(t["root_angle_deg"]), float(t["face_apex_mm"]),
                 float(t["root_apex_mm"])) for m, t in (b.get("blank") or {}).items() if t}
    for m, cone in cones.items():
        try:
            blank = with_cones(blank, m, *cone)
        except ValueError as exc:
            raise CaseError(f"bevel.blank.{m}", "cones", f"cones of a {m} blank with its pitch angle "
                            f"{np.rad2deg(blank.member(m).pitch_angle):.4f} deg ({exc})", f) from None
    _check_pitch_angles(b, blank, f)
    mounting = _mounting(c.get("mounting") or {}, blank, f)
    cuts = _cuts(b["settings"], basic, f) if given else None
    name = c["case"]["name"] or stem
    asm = c.get("assembly") or {}
    mat = c.get("material") or {}
    an = c.get("analysis") or {}
    return BevelCase(name=name, basic=basic, targets=targets, blank_offset=b.get("blank_offset_mm"), torques=torques,
                     cuts=cuts,
                     assembly=dict(E=float(asm.get("E_mm", 0.0)), P=float(asm.get("P_mm", 0.0)),
                              G=float(asm.get("G_mm", 0.0)), d_sigma=float(np.deg2rad(asm.get("sigma_deg", 0.0)))),
                young=float(mat.get("youngs_modulus_mpa", 206000.0)), poisson=float(mat.get("poisson_ratio", 0.3)),
                positions=int(an.get("positions", 21)), fidelity=str(an.get("fidelity", "default")),
                mounting=mounting, cones=cones or None)


def case_blank(case: BevelCase) -> BevelBlank:
    """The case's blank: designed from its basic data (:func:`ltca.geometry.bevel.blank.design_blank`), with the
    members' face and root cones replaced where ``[bevel.blank]`` gives them."""
    blank = design_blank(case.basic)
    for m, c in (case.cones or {}).items():
        blank = with_cones(blank, m, *c)
    return blank


def _cuts(sheets: dict, basic: BevelBasicData, f: str | None) -> dict:
    """``[bevel.settings]``: each member's cut from its settings sheets (``{"gear": MemberCut, "pinion": ...}``)."""
    out = {}
    for member, z in (("gear", basic.z2), ("pinion", basic.z1)):
        for side in ("concave", "convex"):
            sh = sheets[member][side]
            if sh["generation"] == "generated" and sh["ratio_of_roll"] is None:
                raise CaseError(f"bevel.settings.{member}.{side}.ratio_of_roll", None,
                                "required for a generated flank; a number in (0, 100]", f)
        clean = {side: {k: v for k, v in sheets[member][side].items() if v is not None}
                 for side in ("concave", "convex")}
        try:
            out[member] = member_from_sheet(clean, member, z)
        except ValueError as exc:
            raise CaseError(f"bevel.settings.{member}", "sheet", str(exc), f) from None
    return out


def _check_pitch_angles(b: dict, blank, f: str | None) -> None:
    """The gear's face cone must open outward (face angle below 90 deg): beyond, it is an internal (or crown-like)
    bevel gear, which the blank, cradle and FE body here do not model.  tan(delta2) = sin(S) / (z1/z2 + cos(S))
    gives the largest shaft angle S for the teeth."""
    g = blank.gear
    if g.face_angle < 0.5 * np.pi - 1e-6:
        return
    z1, z2 = b["pinion_teeth"], b["gear_teeth"]
    S = float(np.radians(b.get("shaft_angle_deg", 90.0)))
    room = 0.5 * np.pi - (g.face_angle - g.pitch_angle)          # the largest pitch angle with face angle < 90
    # the shaft angle at which delta2 = room: sin(S) cos(room) - cos(S) sin(room) = (z1/z2) sin(room)
    s_max = float(np.degrees(room + np.arcsin(min(1.0, z1 / z2 * np.sin(room)))))
    raise CaseError("bevel.shaft_angle_deg", round(float(np.degrees(S)), 3),
                    f"at most {np.floor(10 * s_max - 5) / 10:.1f} deg for {z1}/{z2} teeth (there the gear's face "
                    f"angle, now {np.degrees(g.face_angle):.1f} deg, reaches 90 deg: an internal bevel gear is not "
                    "modelled); or more pinion teeth", f)


def _mounting(m: dict, blank, f: str | None) -> BevelMounting:
    """``[mounting]``: the shaft seat inside the pinion's toe, the gear's back face behind its heel."""
    out = BevelMounting(m.get("pinion_seat_diameter_mm"), m.get("gear_mounting_distance_mm"))
    d_toe = 2 * blank.root_point("pinion", "toe")[1]
    if out.pinion_seat_diameter is not None and out.pinion_seat_diameter > d_toe - 2 * blank.whole_depth:
        raise CaseError("mounting.pinion_seat_diameter_mm", out.pinion_seat_diameter,
                        f"below {d_toe - 2 * blank.whole_depth:.2f} mm (the pinion's root diameter at the toe "
                        f"{d_toe:.2f} mm less two whole depths: the blank must carry the teeth)", f)
    z_heel = blank.root_point("gear", "heel")[0]
    lo, hi = z_heel + 0.3 * blank.whole_depth, min(z_heel + 20 * blank.whole_depth, 0.8 * face_limit(blank))
    if out.gear_mounting_distance is not None and not lo <= out.gear_mounting_distance <= hi:
        raise CaseError("mounting.gear_mounting_distance_mm", out.gear_mounting_distance,
                        f"in [{lo:.2f}, {hi:.2f}] mm (0.3 to 20 whole depths behind the gear's heel root at "
                        f"{z_heel:.2f} mm from the pitch apex, and short of where the front cone meets the axis)", f)
    return out


def check_bevel_torques(v, path: str = "load.torque_nm", f: str | None = None) -> tuple[float, ...]:
    """Bevel pinion torques (N m): a number or a list of 1 to 20 distinct non-zero numbers in [-1e5, 1e5] (the
    sign picks the flank); ``path`` names the field (or the option, ``--torque``) in the message."""
    out = (List(_TORQUE, 1, 20).check(v, path, f) if isinstance(v, list) else [_TORQUE.check(v, path, f)])
    if any(x == 0 for x in out):
        raise CaseError(path, v, "non-zero torques in [-1e5, 1e5] N m (the sign picks the flank)", f)
    if len(set(out)) != len(out):
        raise CaseError(path, v, "distinct torques (each torque is one analysis)", f)
    return tuple(float(x) for x in out)
