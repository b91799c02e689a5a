"""Write a bevel pair as a HypoidFaceMilled / Transmission3D input script: each member's blank (``COMMON``) and, per
flank, its ``MACHINE`` and ``CUTTER`` blocks (conventions: :mod:`ltca.bevel.hfm_format`).

The layout is the one SpyGO writes for that program (the only public example of the format): ``EDIT``, ``PAIRS``
with ``HAND_PINION``, a ``ROTOR`` and a ``HYPOID`` section per member, the concave flank's blocks first, except that
each flank's blocks are opened by a ``CONCAVE`` or ``CONVEX`` line (SpyGO only closes them, with ``EXIT``; the
reader takes either form); session commands (``SESFILENAME``, ``SAVESESSION``) are left to the user. Every keyword
is written, zeros included, with Python's shortest round-trip numbers, so :func:`ltca.bevel.hfm_script.parse_hfm`
reads back the same settings sheets (up to the rad <-> deg and thousandths scaling of a few motion terms, 1e-16
relative).

The blank is the case's (designed, or its given cones): face, back and front angles, pitch, face and root apexes
(the heel and toe normal to the pitch cone: back and front angle = pitch angle). ``BASECONEANGLE`` and
``BASECONEAPEX`` give the rim of that program's FE model, as SpyGO writes it: a cone parallel to the root cone (its
angle the root angle) ``rim_thickness`` below it (default: one whole depth); the bodies here run to the case's
``[mounting]`` instead.
"""
from __future__ import annotations

import math
from pathlib import Path

from ltca.geometry.bevel.blank import cone_apexes
from ltca.geometry.bevel.sheet import member_sheet
from ltca.geometry.bevel.tca import BevelPair

from ..errors import CaseError
from . import hfm_format as F

__all__ = ["hfm_text", "export_hfm"]


def _num(x: float) -> str:
    return repr(float(x))


def _common(pair: BevelPair, member: str, rim: float) -> list[str]:
    bl = pair.blank
    mb = bl.member(member)
    face_apex, root_apex = cone_apexes(bl, member)
    deg = math.degrees
    val = {"SPIRALANGLE": deg(bl.data.spiral_angle), "OUTERCONEDIST": bl.outer_cone_distance,
           "FACEWIDTH": bl.face_width, "FACEANGLE": deg(mb.face_angle), "BACKANGLE": deg(mb.pitch_angle),
           "FRONTANGLE": deg(mb.pitch_angle), "PITCHANGLE": deg(mb.pitch_angle), "PITCHAPEX": 0.0,
           "FACEAPEX": face_apex, "ROOTAPEX": root_apex, "BASECONEANGLE": deg(mb.root_angle),
           "BASECONEAPEX": root_apex - rim / math.sin(mb.root_angle)}
    return ([f"NTEETH {mb.z}", f"HAND {mb.hand.upper()}"] + [f"{k} {_num(val[k])}" for k in F.COMMON]
            + ["USE_SPRD_BLD_THICKNESS TRUE"])


def _machine(sheet: dict, member: str, hand: str) -> list[str]:
    """The MACHINE block's lines of one flank's settings sheet (the inverse of the reader's mapping)."""
    formate = sheet.get("generation", "generated") == "formate"
    out = []
    for k, (key, row) in F.MACHINE0.items():
        v = F.sign(member, hand, row, 0) * float(sheet.get(key, 0.0))
        if formate and k == "RADIALSETTING":
            q = math.radians(F.sign(member, hand, "q", 0) * float(sheet["cradle_angle_deg"]))
            out += [f"HORIZONTAL {_num(v * math.cos(q))}", f"VERTICAL {_num(v * math.sin(q))}"]
        elif not (formate and k == "CRADLEANGLE"):
            out.append(f"{k} {_num(v)}")
    if formate:
        return out
    out.append(f"RATIOROLL {_num(sheet['ratio_of_roll'])}")
    for k, (key, order) in F.ROLL.items():
        out.append(f"{k} {_num(F.sign(member, hand, 'roll', order) * float(sheet.get(key, 0.0)) / F.factor(k))}")
    out.append("MODROLL_5040H 0.0")
    for stem, (key, row) in F.MOTIONS.items():
        a = list(sheet.get(key, ()))
        if stem in ("TLT", "SW") and not any(a):
            continue                        # not among the keywords SpyGO writes: only when given
        a += [0.0] * (6 - len(a))
        out += [f"{stem}{k} {_num(F.sign(member, hand, row, k) * float(a[k - 1]) / F.factor(f'{stem}{k}'))}"
                for k in range(1, 7)]
    return out


def _cutter(sheet: dict) -> list[str]:
    out = [f"{k} {_num(sheet.get(key, 0.0))}" for k, key in F.CUTTER.items()]
    curved = sheet.get("profile_radius_mm") is not None and math.isfinite(sheet["profile_radius_mm"])
    out += ["USENEWCUTTER TRUE", f"TYPE {'CURVED' if curved else 'STRAIGHT'}"]
    for rem in ("toprem", "flankrem"):
        if sheet.get(f"{rem}_depth_mm"):
            out += [f"{rem.upper()}_OPTION BLENDED", f"{rem.upper()}_DEPTH {_num(sheet[f'{rem}_depth_mm'])}",
                    f"{rem.upper()}_BLEND_RADIUS {_num(sheet[f'{rem}_radius_mm'])}"]
        else:
            out.append(f"{rem.upper()}_OPTION NONE")
    if curved:
        out.append(f"RHO {_num(sheet['profile_radius_mm'])}")
    return out


def hfm_text(pair: BevelPair, title: str = "", rim_thickness: float | None = None) -> str:
    """The script of a pair (:class:`ltca.geometry.bevel.tca.BevelPair`: blank, gear and pinion cuts).

    Parameters
    ----------
    pair : BevelPair
        The pair as cut (given settings or synthesised).
    title : str
        A comment line at the top (e.g. the case's name).
    rim_thickness : float, optional
        Rim under the root cone for ``BASECONEAPEX``, mm (default: the whole depth).

    Returns
    -------
    str
        The script's text (tab-indented, ``\\n`` line ends).
    """
    pinion_hand = pair.blank.pinion.hand
    rim = pair.blank.whole_depth if rim_thickness is None else float(rim_thickness)
    sheets = {"pinion": member_sheet(pair.pinion), "gear": member_sheet(pair.gear)}
    for m, sh in sheets.items():
        gen = {s: sh[s]["generation"] for s in sh}
        if len(set(gen.values())) > 1 or m == "pinion" and "formate" in gen.values():
            raise CaseError(f"bevel.settings.{m}", gen, "both flanks generated, or a formate gear (both flanks): "
                            "the script gives one generation type per member, a pinion always generated", None)
    lines = [(0, f"// {title}")] if title else []
    lines += [(0, "// HypoidFaceMilled / Transmission3D settings written by ltca (mm, deg)"), (0, "EDIT"),
              (1, "PAIRS"), (2, f"HAND_PINION {pinion_hand.upper()}"), (2, "EXIT"), (1, "ROTOR")]
    for rotor, m in ((1, "pinion"), (2, "gear")):
        lines += [(2, f"ROTOR {rotor}"), (2, "EXIT"), (2, "HYPOID"), (3, "NHYPOIDS 1"), (3, "HYPOID 1"),
                  (3, f"TYPE FACEMILLED_{m.upper()}")]
        if m == "gear":
            lines.append((3, f"GEAR_TYPE {sheets[m]['concave']['generation'].upper()}"))
        lines += [(3, "COMMON")] + [(4, x) for x in _common(pair, m, rim)] + [(3, "EXIT  // EXIT COMMON")]
        for s in ("concave", "convex"):
            sh = sheets[m][s]
            lines += [(3, s.upper()), (4, "MACHINE")] + [(5, x) for x in _machine(sh, m, pinion_hand)]
            lines += [(4, "EXIT  // EXIT MACHINE"), (4, "CUTTER")] + [(5, x) for x in _cutter(sh)]
            lines += [(4, "EXIT  // EXIT CUTTER"), (3, f"EXIT  // EXIT {s.upper()}")]
        lines += [(2, "EXIT  // EXIT HYPOID")]
    lines.append((1, "EXIT  // EXIT ROTOR"))
    return "".join("\t" * i + x + "\n" for i, x in lines)


def export_hfm(case, path: str | Path) -> Path:
    """Write a bevel case's pair (its settings sheets, or the gear's standard cut and the synthesised pinion) as a
    script at ``path``; returns the path. ``case`` is a :class:`ltca.bevel.case.BevelCase` or its file."""
    from .analysis import build_pair
    from .case import BevelCase, load_bevel_case
    if not isinstance(case, BevelCase):
        case = load_bevel_case(case)
    text = hfm_text(build_pair(case), title=f"{case.name}")
    p = Path(path)
    p.write_text(text, encoding="utf-8")
    return p
