"""REXS bevel stages mapped to the project's bevel case dict (the ``[bevel]`` blank of a spiral bevel pair).

A ``bevel_stage`` joins two ``bevel_gear`` components by a ``stage`` relation (``gear_1``, ``gear_2``); the pinion
is the member with fewer teeth. The mapping, REXS attribute -> case key:

=====================================================  =============================================
``bevel_gear.number_of_teeth``                         ``bevel.pinion_teeth`` / ``bevel.gear_teeth``
``bevel_stage.outer_transverse_module``                ``bevel.module_mm`` (else the gear's
                                                       ``outer_pitch_diameter`` / z2)
``bevel_gear.face_width``                              ``bevel.face_width_mm`` (the gear's)
``bevel_gear.mean_spiral_angle``                       ``bevel.spiral_angle_deg`` (magnitude)
``bevel_gear.spiral_angle_pitch_direction``            ``bevel.gear_hand`` (the gear's)
``bevel_stage.nominal_design_pressure_angle_on_*``     ``bevel.pressure_angle_deg`` (drive = coast), else
                                                       ``generated_pressure_angle_on_*``
``bevel_stage.shaft_angle``                            ``bevel.shaft_angle_deg``
``bevel_stage.cutter_radius``                          ``bevel.cutter_radius_mm``
``material.elastic_modulus / poisson_ratio``           ``material.youngs_modulus_mpa / poisson_ratio``
=====================================================  =============================================

The pitch angles and the outer cone distance a file carries are checked against those the blank derives
(tan delta_1 = sin Sigma / (z2 / z1 + cos Sigma), R_e = d_e2 / (2 sin delta_2); ISO 23509 table 2) and listed
as unmapped with the derived value when they disagree. A hypoid offset other than zero is refused (the case is a
spiral bevel pair). REXS carries no contact-pattern targets, so the synthesis targets (``[bevel.working]``,
``[bevel.coast]``, and the pinion's blank offset redesigned to zero) are those of the shipped Cao et al. (2008)
pair, the ellipse scaled to the face width, and are listed as assumed: edit them, or give the pinion's settings
sheet, for a pair of your own.
"""
from __future__ import annotations

import math

from .errors import RexsError
from .mapping import Unmapped
from .model import Component, RexsModel
from .train import material_of

__all__ = ["BEVEL_STAGE", "BEVEL_GEAR", "bevel_case_dict", "ASSUMED_TARGETS"]

BEVEL_STAGE = "bevel_stage"
BEVEL_GEAR = "bevel_gear"

#: synthesis targets REXS does not carry: those of the shipped spiral_bevel_cao2008 case (Cao et al. 2008, sec. 4);
#: the contact-ellipse major axis as that pair's share of its face width (6 mm of 25.4 mm)
ASSUMED_TARGETS = {"working": {"path_angle_deg": 22.0, "te_magnitude_arcsec": 8.25},
                   "coast": {"path_angle_deg": -14.0, "te_magnitude_arcsec": 11.25}}
ELLIPSE_SHARE = 6.0 / 25.4
ASSUMED_BLANK_OFFSET_MM = 0.0


def _close(a: float, b: float, digits_of: str) -> bool:
    """``a`` (the file's value, as written) agrees with ``b`` to the digits the file gives."""
    decimals = len(digits_of.split(".")[1]) if "." in digits_of else 0
    return abs(a - b) <= 0.51 * 10.0 ** (-decimals) + 1e-12 * abs(b)


def bevel_case_dict(model: RexsModel, stage_id: int, pinion: Component, gear: Component, torques: list[float],
                    used, unmapped: list) -> dict:
    """The case dict of bevel stage ``stage_id`` (``pinion`` and ``gear`` its members, torques in N m on the
    pinion). ``used`` records the attributes read; ``unmapped`` receives :class:`ltca.rexs.Unmapped` rows for what
    the case assumes or cannot hold."""
    st = model.component(stage_id)
    z1, z2 = (abs(c.integer("number_of_teeth")) for c in (pinion, gear))
    used.take(pinion, "number_of_teeth")
    used.take(gear, "number_of_teeth")
    if st.has("hypoid_offset") and abs(st.number("hypoid_offset", "length")) > 1e-9:
        raise RexsError(st.label, "hypoid_offset", "a spiral bevel pair (offset 0): hypoid pairs are not modelled",
                        st.number("hypoid_offset", "length"), model.file)
    used.take(st, "hypoid_offset")
    if st.has("outer_transverse_module"):
        module = st.number("outer_transverse_module", "length")
        used.take(st, "outer_transverse_module")
    elif gear.has("outer_pitch_diameter"):
        module = gear.number("outer_pitch_diameter", "length") / z2
        used.take(gear, "outer_pitch_diameter")
    else:
        raise RexsError(st.label, "outer_transverse_module", f"missing (nor an outer_pitch_diameter of "
                        f"{gear.label}): the blank needs its size", None, model.file)
    sigma = st.number("shaft_angle", "angle") if st.has("shaft_angle") else 90.0
    used.take(st, "shaft_angle")
    blank: dict = {"pinion_teeth": z1, "gear_teeth": z2, "module_mm": module, "shaft_angle_deg": sigma}
    widths = [c.number("face_width", "length") for c in (gear, pinion) if c.has("face_width")]
    if not widths:
        raise RexsError(gear.label, "face_width", "missing: needed for the blank", None, model.file)
    blank["face_width_mm"] = widths[0]
    used.take(gear, "face_width")
    spirals = [(c, abs(c.number("mean_spiral_angle", "angle"))) for c in (gear, pinion) if c.has("mean_spiral_angle")]
    if not spirals:
        raise RexsError(gear.label, "mean_spiral_angle", "missing: needed for the blank", None, model.file)
    blank["spiral_angle_deg"] = spirals[0][1]
    for c, _ in spirals:
        used.take(c, "mean_spiral_angle")
    if not gear.has("spiral_angle_pitch_direction"):
        raise RexsError(gear.label, "spiral_angle_pitch_direction", "missing: the gear's hand of spiral (left or "
                        "right)", None, model.file)
    blank["gear_hand"] = gear.text("spiral_angle_pitch_direction")
    used.take(gear, "spiral_angle_pitch_direction")
    if pinion.has("spiral_angle_pitch_direction"):
        if pinion.text("spiral_angle_pitch_direction") == blank["gear_hand"]:
            raise RexsError(pinion.label, "spiral_angle_pitch_direction", "the opposite hand to the gear's "
                            f"({blank['gear_hand']})", pinion.text("spiral_angle_pitch_direction"), model.file)
        used.take(pinion, "spiral_angle_pitch_direction")
    blank["pressure_angle_deg"] = _pressure_angle(model, st, used)
    if not st.has("cutter_radius"):
        raise RexsError(st.label, "cutter_radius", "missing: the face-milling cutter's mean radius", None, model.file)
    blank["cutter_radius_mm"] = st.number("cutter_radius", "length")
    used.take(st, "cutter_radius")
    _check_derived(model, pinion, gear, z1, z2, module, sigma, used)
    data: dict = {"case": {"name": st.name or f"bevel stage {stage_id}",
                           "description": f"bevel_stage {stage_id} of {model.file}", "source": str(model.file)},
                  "bevel": dict(blank)}
    for flank, targets in ASSUMED_TARGETS.items():
        data["bevel"][flank] = {**targets, "ellipse_major_mm": round(ELLIPSE_SHARE * blank["face_width_mm"], 3)}
        for key, value in data["bevel"][flank].items():
            unmapped.append(Unmapped(stage_id, st.type, f"bevel.{flank}.{key}", value, None,
                                     "not in REXS: synthesis target assumed (those of the shipped Cao et al. 2008 "
                                     "pair); edit it or give the settings sheet"))
    data["bevel"]["blank_offset_mm"] = ASSUMED_BLANK_OFFSET_MM
    unmapped.append(Unmapped(stage_id, st.type, "bevel.blank_offset_mm", ASSUMED_BLANK_OFFSET_MM, "mm",
                             "not in REXS: the pinion's settings redesigned to a zero blank offset (as the shipped "
                             "pair's); remove the key to keep the offset the synthesis finds"))
    mat = _material(model, (pinion, gear), used)
    if mat:
        data["material"] = mat
    if not torques:
        raise RexsError(st.label, "torque", "missing: no external load defines a torque that reaches this stage "
                        "(give one with --torque)", None, model.file)
    data["load"] = {"torque_nm": torques[0] if len(torques) == 1 else torques}
    return data


def _pressure_angle(model: RexsModel, st: Component, used) -> float:
    for names in (("nominal_design_pressure_angle_on_drive_side", "nominal_design_pressure_angle_on_coast_side"),
                  ("generated_pressure_angle_on_drive_side", "generated_pressure_angle_on_coast_side")):
        given = [st.number(n, "angle") for n in names if st.has(n)]
        if not given:
            continue
        if len(given) == 2 and abs(given[0] - given[1]) > 1e-9:
            raise RexsError(st.label, names[1], f"equal to the drive side's {given[0]} deg: the case has one blade "
                            "pressure angle for both flanks", given[1], model.file)
        used.take(st, *names)
        return given[0]
    raise RexsError(st.label, "nominal_design_pressure_angle_on_drive_side", "missing (nor a generated pressure "
                    "angle): the blades' pressure angle", None, model.file)


def _check_derived(model, pinion, gear, z1, z2, module, sigma, used) -> None:
    """The file's pitch angles and outer cone distance against the blank's (ISO 23509 table 2)."""
    s = math.radians(sigma)
    d1 = math.atan2(math.sin(s), z2 / z1 + math.cos(s))
    derived = {(pinion.id, "pitch_angle"): math.degrees(d1), (gear.id, "pitch_angle"): sigma - math.degrees(d1),
               (gear.id, "outer_cone_distance"): module * z2 / (2 * math.sin(s - d1)),
               (pinion.id, "outer_cone_distance"): module * z2 / (2 * math.sin(s - d1)),
               (pinion.id, "outer_pitch_diameter"): module * z1, (gear.id, "outer_pitch_diameter"): module * z2}
    for (cid, attr), value in derived.items():
        c = model.components[cid]
        if not c.has(attr) or attr in used.ids.get(cid, set()):
            continue
        dim = "angle" if attr.endswith("angle") else "length"
        if _close(c.number(attr, dim), value, str(c.attributes[attr].value)):
            used.take(c, attr)
        else:
            used.skip(c, attr, f"disagrees with the blank: derived {value:.6g} from the teeth, module and shaft angle")


def _material(model, members, used) -> dict:
    mat = {}
    for g in members:
        mc = material_of(model, g)
        if mc is None:
            continue
        for key, attr, dim in (("youngs_modulus_mpa", "elastic_modulus", "stress"),
                               ("poisson_ratio", "poisson_ratio", "none")):
            if mc.has(attr) and key not in mat:
                mat[key] = mc.number(attr, dim)
                used.take(mc, attr)
    return mat
