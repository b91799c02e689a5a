"""Conventions of the HypoidFaceMilled / Transmission3D input script: keywords, units and signs of its machine and
cutter blocks against the settings sheet of :mod:`ltca.geometry.bevel.sheet`.

The script is text, one ``KEYWORD value`` a line, menus opened by a keyword alone and closed by ``EXIT``, ``//``
starting a comment; lengths in mm, angles in deg. No public manual of the format was found: the keywords, their
scaling and their signs are those of SpyGO (public Python, github haomjc/SpyGO, which writes this script for
Transmission3D: ``MultyxInterface.settings_script_T3D``, and reads the same settings in its cradle kinematics:
``DesignData.manage_machine_settings``), composed with the frame identity between SpyGO's machine and ours that
``tools/compare_spygo.py`` checks point by point on SpyGO's 19/62 pair (a left-hand pinion).

Per flank, the script's value x gives our sheet's value ``sign * factor * x``:

* order 0 (RADIALSETTING, TILTANGLE, SWIVELANGLE, BLANKOFFSET, SLIDINGBASE, CRADLEANGLE, MACHCTRBACK, ROOTANGLE,
  RATIOROLL): factor 1, both in mm and deg; a formate flank may give the cutter centre as HORIZONTAL, VERTICAL
  (mm) instead of RADIALSETTING, CRADLEANGLE.
* the motions R1..R6 (radial), V1..V6 (vertical: blank offset), H1..H6 (helical: sliding base), TLT1..TLT6 and
  SW1..SW6 (modified tilt and swivel) are the k-th derivatives by the cradle roll, as our sheet's; H5 and H6 are
  in thousandths, TLT and SW in rad (ours deg).
* MODROLL_2C, _6D, _24E, _120F, _720G are our 2C .. 720G, 720G in thousandths; MODROLL_5040H (7th order) must be 0.
* signs, left-hand pinion (:data:`LEFT_SIGNS`): the pinion's cradle angle, tilt and swivel and the gear's tilt
  change sign; the blank offset changes sign on the pinion, and its derivatives (V1..V6) on both members.
* a right-hand pinion: the pair is read as the mirror image of its left-hand twin, whose sheet has the same numbers
  (:func:`sign`: cradle angle, tilt, swivel and blank offset change sign, and each derivative of order k by
  (-1)^k as the cradle rolls the other way). SpyGO's own right-hand tables agree for the pinion's basic settings,
  modified roll and helical motion and differ in some motion orders and the gear's swivel; no public source settles
  those, so a right-hand pair's motions are the least certain part of this exchange.

The cutter block is ours as it stands: POINTRADIUS, BLADEANGLE, EDGERADIUS, TYPE STRAIGHT or CURVED with RHO
(profile radius), TOPREM_OPTION and FLANKREM_OPTION NONE or BLENDED with _DEPTH and _BLEND_RADIUS; the concave
flank is cut by the outside blade.
"""
from __future__ import annotations

import math

__all__ = ["MACHINE0", "MOTIONS", "ROLL", "CUTTER", "COMMON", "LEFT_SIGNS", "factor", "sign", "motion_keyword"]

#: order-0 machine keyword -> (sheet key, row of the sign table)
MACHINE0 = {
    "RADIALSETTING": ("radial_setting_mm", "S"),
    "TILTANGLE": ("tilt_deg", "tilt"),
    "SWIVELANGLE": ("swivel_deg", "swivel"),
    "BLANKOFFSET": ("blank_offset_mm", "E"),
    "ROOTANGLE": ("machine_root_angle_deg", "root"),
    "MACHCTRBACK": ("machine_center_to_back_mm", "XG"),
    "SLIDINGBASE": ("sliding_base_mm", "B"),
    "CRADLEANGLE": ("cradle_angle_deg", "q"),
}
#: motion keyword stem (``R`` -> R1..R6) -> (sheet key, row)
MOTIONS = {"H": ("helical_motion_mm", "B"), "V": ("vertical_motion_mm", "E"), "R": ("radial_motion_mm", "S"),
           "TLT": ("tilt_motion_deg", "tilt"), "SW": ("swivel_motion_deg", "swivel")}
#: modified-roll keyword -> (sheet key, order)
ROLL = {"MODROLL_2C": ("modified_roll_2C", 2), "MODROLL_6D": ("modified_roll_6D", 3),
        "MODROLL_24E": ("modified_roll_24E", 4), "MODROLL_120F": ("modified_roll_120F", 5),
        "MODROLL_720G": ("modified_roll_720G", 6)}
#: numeric cutter keyword -> sheet key
CUTTER = {"POINTRADIUS": "point_radius_mm", "BLADEANGLE": "blade_angle_deg", "EDGERADIUS": "edge_radius_mm"}
#: blank (COMMON) keywords read as numbers, in the order written
COMMON = ("SPIRALANGLE", "OUTERCONEDIST", "FACEWIDTH", "FACEANGLE", "BACKANGLE", "FRONTANGLE", "PITCHANGLE",
          "PITCHAPEX", "FACEAPEX", "ROOTAPEX", "BASECONEANGLE", "BASECONEAPEX")

#: left-hand pinion: member -> row -> (sign of order 0, sign of the orders >= 1)
LEFT_SIGNS = {
    "pinion": {"S": (1, 1), "tilt": (-1, 1), "swivel": (-1, 1), "E": (-1, -1), "B": (1, 1), "q": (-1, 1),
               "XG": (1, 1), "root": (1, 1), "roll": (1, 1)},
    "gear": {"S": (1, 1), "tilt": (-1, 1), "swivel": (1, 1), "E": (1, -1), "B": (1, 1), "q": (1, 1),
             "XG": (1, 1), "root": (1, 1), "roll": (1, 1)},
}
#: the mirror image (y_m -> -y_m, the cradle and the work rolling the other way): row -> sign of order k
_MIRROR = {"S": lambda k: (-1) ** k, "B": lambda k: (-1) ** k, "E": lambda k: -(-1) ** k,
           "tilt": lambda k: -(-1) ** k, "swivel": lambda k: -(-1) ** k, "q": lambda k: -1,
           "XG": lambda k: 1, "root": lambda k: 1, "roll": lambda k: -(-1) ** k}


def sign(member: str, pinion_hand: str, row: str, order: int) -> int:
    """The sign from the script's value to ours (module docstring) of ``row`` at ``order`` (0: the setting, k: its
    k-th derivative; ``row`` ``"roll"``: the modified roll of order k, 2..6)."""
    s0, sk = LEFT_SIGNS[member][row]
    s = s0 if order == 0 else sk
    return s * (_MIRROR[row](order) if pinion_hand == "right" else 1)


def factor(keyword: str) -> float:
    """The script's unit of ``keyword`` in ours (module docstring): 1e-3 for H5, H6, MODROLL_720G; deg per rad
    for TLTk, SWk; else 1."""
    if keyword in ("H5", "H6", "MODROLL_720G"):
        return 1e-3
    if keyword.startswith(("TLT", "SW")) and keyword[-1].isdigit():
        return 180.0 / math.pi
    return 1.0


def motion_keyword(keyword: str) -> tuple[str, int] | None:
    """``("R", 3)`` for ``"R3"`` and the like (orders 1..6); None for any other keyword."""
    for stem in MOTIONS:
        rest = keyword[len(stem):]
        if keyword.startswith(stem) and len(rest) == 1 and rest in "123456":
            return stem, int(rest)
    return None
