"""Settings sheet of a face-milled member: machine and cutter settings per flank in the industry's vocabulary.

A sheet is a plain dict per flank in engineer's units (mm, deg), the blocks of a summary sheet of a
face-milling generator: radial setting, cradle angle, tilt, swivel, blank offset, machine root angle, machine
centre to back, sliding base, ratio of roll and the modified roll with Gleason's factorial scaling (2C, 6D,
24E, 120F, 720G), the helical, vertical and radial motions and the modified tilt and swivel as derivatives by
the cradle roll (k = 1..6; the sheet's factorial scaling: the setting is ``x0 + sum_k a_k psi^k / k!``),
generated or formate; the cutter's blade, point radius, blade angle, edge radius and, for a curved blade, its
profile radius, and a blended toprem and flankrem (depth and radius).  :func:`flank_sheet` and :func:`flank_from_sheet` are exact inverses up to the degree <-> rad
conversion (a relative 1e-16).  Frames and signs are those of :mod:`ltca.geometry.bevel.machine`.
"""
from __future__ import annotations

import math

import numpy as np

from .cutter import HeadCutter
from .machine import FlankCut, MachineSettings, MemberCut

__all__ = ["MACHINE_KEYS", "CUTTER_KEYS", "REM_KEYS", "ROLL_KEYS", "MOTION_KEYS", "flank_sheet", "flank_from_sheet",
           "member_sheet", "member_from_sheet", "sheet_toml"]

MACHINE_KEYS = {                 # sheet key -> (MachineSettings field, factor from sheet units to ours)
    "radial_setting_mm": ("radial_setting", 1.0),
    "cradle_angle_deg": ("cradle_angle", math.pi / 180),
    "machine_root_angle_deg": ("root_angle", math.pi / 180),
    "machine_center_to_back_mm": ("center_to_back", 1.0),
    "blank_offset_mm": ("blank_offset", 1.0),
    "sliding_base_mm": ("sliding_base", 1.0),
    "tilt_deg": ("tilt", math.pi / 180),
    "swivel_deg": ("swivel", math.pi / 180),
}
ROLL_KEYS = {"ratio_of_roll": 1, "modified_roll_2C": 2, "modified_roll_6D": 3, "modified_roll_24E": 4,
             "modified_roll_120F": 5, "modified_roll_720G": 6}
"""Sheet key -> order k: the sheet gives m_a and k!-scaled roll coefficients (k = 2: 2C, ...)."""
_ROLL_FIELDS = {2: "modified_roll_c", 3: "modified_roll_d", 4: "modified_roll_e", 5: "modified_roll_f",
                6: "modified_roll_g"}
MOTION_KEYS = {                  # sheet key -> (MachineSettings field, factor)
    "radial_motion_mm": ("radial_motion", 1.0),
    "vertical_motion_mm": ("vertical_motion", 1.0),
    "helical_motion_mm": ("helical_motion", 1.0),
    "tilt_motion_deg": ("tilt_motion", math.pi / 180),
    "swivel_motion_deg": ("swivel_motion", math.pi / 180),
}
CUTTER_KEYS = {
    "point_radius_mm": ("point_radius", 1.0),
    "blade_angle_deg": ("blade_angle", math.pi / 180),
    "edge_radius_mm": ("edge_radius", 1.0),
}
REM_KEYS = {"toprem_depth_mm": "toprem_depth", "toprem_radius_mm": "toprem_radius",
            "flankrem_depth_mm": "flankrem_depth", "flankrem_radius_mm": "flankrem_radius"}


def flank_sheet(fc: FlankCut) -> dict:
    """Settings sheet of one flank cut (module docstring); motions and a curved blade only when present."""
    ms, cu = fc.machine, fc.cutter
    out: dict = {"generation": "formate" if ms.formate else "generated", "blade": cu.blade}
    for key, (name, f) in MACHINE_KEYS.items():
        out[key] = float(getattr(ms, name)) / f
    if not ms.formate:
        out["ratio_of_roll"] = float(ms.ratio_of_roll)
        for key, k in ROLL_KEYS.items():
            if k > 1:
                out[key] = float(math.factorial(k) * getattr(ms, _ROLL_FIELDS[k]))
    for key, (name, f) in MOTION_KEYS.items():
        if getattr(ms, name):
            out[key] = [float(a) / f for a in getattr(ms, name)]
    for key, (name, f) in CUTTER_KEYS.items():
        out[key] = float(getattr(cu, name)) / f
    if cu.curved:
        out["profile_radius_mm"] = float(cu.profile_radius)
    for name in ("toprem", "flankrem"):
        if getattr(cu, f"{name}_depth"):
            out[f"{name}_depth_mm"] = float(getattr(cu, f"{name}_depth"))
            out[f"{name}_radius_mm"] = float(getattr(cu, f"{name}_radius"))
    return out


def flank_from_sheet(sheet: dict) -> FlankCut:
    """The flank cut of a settings sheet (:func:`flank_sheet`'s keys; absent motions are zero, absent
    ``profile_radius_mm`` a straight blade).  Raises ValueError naming the setting for values the generator
    refuses."""
    formate = sheet.get("generation", "generated") == "formate"
    kw = {name: float(sheet.get(key, 0.0)) * f for key, (name, f) in MACHINE_KEYS.items()}
    if formate:
        kw["ratio_of_roll"] = 0.0
    else:
        m = float(sheet["ratio_of_roll"])
        kw["ratio_of_roll"] = m
        for key, k in ROLL_KEYS.items():
            if k > 1:
                kw[_ROLL_FIELDS[k]] = float(sheet.get(key, 0.0)) / math.factorial(k)
    for key, (name, f) in MOTION_KEYS.items():
        kw[name] = tuple(float(a) * f for a in sheet.get(key, ()))
    ms = MachineSettings(formate=formate, **kw)
    cu = HeadCutter(float(sheet["point_radius_mm"]), float(sheet["blade_angle_deg"]) * math.pi / 180,
                    sheet["blade"], float(sheet.get("edge_radius_mm", 0.0)),
                    profile_radius=float(sheet.get("profile_radius_mm", np.inf)),
                    **{f: float(sheet[k]) for k, f in REM_KEYS.items() if k in sheet})
    return FlankCut(ms, cu)


def member_sheet(cut: MemberCut) -> dict:
    """``{"concave": sheet, "convex": sheet}`` of a member."""
    return {s: flank_sheet(cut.flank(s)) for s in ("concave", "convex")}


def member_from_sheet(sheets: dict, member: str, z: int) -> MemberCut:
    """The member cut of ``{"concave": sheet, "convex": sheet}``."""
    return MemberCut(member, z, concave=flank_from_sheet(sheets["concave"]),
                     convex=flank_from_sheet(sheets["convex"]))


def _toml_value(v) -> str:
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return repr(float(v))


def sheet_toml(members: dict, prefix: str = "bevel.settings") -> str:
    """TOML text of ``{member: {flank: sheet}}`` as ``[prefix.member.flank]`` tables (floats written with
    Python's shortest round-trip repr, so reading back gives the same numbers)."""
    lines = []
    for member, sheets in members.items():
        for side, sheet in sheets.items():
            lines.append(f"[{prefix}.{member}.{side}]")
            lines += [f"{k} = {_toml_value(v)}" for k, v in sheet.items()]
            lines.append("")
    return "\n".join(lines)
