"""Read the blank, machine and cutter blocks of a HypoidFaceMilled / Transmission3D input script into a bevel case.

The script (conventions: :mod:`ltca.bevel.hfm_format`) holds, per member, a ``TYPE FACEMILLED_PINION`` or
``FACEMILLED_GEAR`` section with its blank (``COMMON``) and, concave flank first, a ``MACHINE`` and a ``CUTTER`` block
per flank (a ``CONCAVE`` or ``CONVEX`` line before them names the flank explicitly); ``PAIRS`` gives
``HAND_PINION``, the gear section ``GEAR_TYPE GENERATED`` or ``FORMATE``. Every keyword inside these blocks and
sections must be known: an unknown or unsupported one, a malformed number, a missing block is a
:class:`ltca.errors.CaseError` naming the line. The program's other menus (shafts, FE mesh, solver, post-processing,
session commands) are skipped with a logged message.

The bevel case of a script: :func:`ltca.bevel.hfm_case.case_data`; the script of a case:
:mod:`ltca.bevel.hfm_export`.
"""
from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from pathlib import Path

from ..errors import CaseError
from . import hfm_format as F

__all__ = ["HfmScript", "parse_hfm", "read_hfm"]

log = logging.getLogger(__name__)

_BLOCKS = {"COMMON": set(F.COMMON) | {"NTEETH", "HAND", "USE_SPRD_BLD_THICKNESS", "TYPE_THICKNESS",
                                      "NORMAL_THICKNESS"},
           "MACHINE": set(F.MACHINE0) | set(F.ROLL) | {"RATIOROLL", "MODROLL_5040H", "HORIZONTAL", "VERTICAL"}
           | {f"{s}{k}" for s in F.MOTIONS for k in range(1, 7)},
           "CUTTER": set(F.CUTTER) | {"USENEWCUTTER", "TYPE", "RHO", "POINTWIDTH"}
           | {f"{r}_{x}" for r in ("TOPREM", "FLANKREM") for x in ("OPTION", "DEPTH", "BLEND_RADIUS", "ANGLE")},
           "PAIRS": {"HAND_PINION"}}
_SECTION = ("GEAR_TYPE", "COMMON", "MACHINE", "CUTTER", "CONCAVE", "CONVEX", "EXIT")
_TOP = ("EDIT", "PAIRS", "ROTOR", "HYPOID", "NHYPOIDS", "TYPE", "EXIT", "SAVESESSION", "SESFILENAME")


@dataclass(frozen=True)
class HfmScript:
    """A script read: ``pinion_hand`` ("left" or "right"), ``common`` ({member: {KEYWORD: value}}, the script's
    units), ``sheets`` ({member: {"concave": sheet, "convex": sheet}}, :mod:`ltca.geometry.bevel.sheet`'s keys),
    ``skipped`` (the menus and lines not read, for the log), ``file``, ``lines`` ({member: {KEYWORD: line}} of
    the COMMON blocks, for messages) and ``remarks`` (values read otherwise than written, one line each)."""
    pinion_hand: str
    common: dict
    sheets: dict
    skipped: tuple[str, ...] = ()
    file: str | None = None
    lines: dict | None = None
    remarks: tuple[str, ...] = ()


def read_hfm(path: str | Path) -> HfmScript:
    """:func:`parse_hfm` of a file (UTF-8 or Latin-1 text)."""
    p = Path(path)
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise CaseError("file", str(p), f"a readable script file ({exc.strerror or exc})") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    return parse_hfm(text, str(p))


def _lines(text: str):
    for n, line in enumerate(text.splitlines(), start=1):
        words = line.split("//", 1)[0].split()
        if words:
            yield n, words[0].upper(), words[1:]


def parse_hfm(text: str, file: str | None = None) -> HfmScript:
    """The pinion's hand, each member's blank and each flank's settings sheet of a script's text (module
    docstring); raises CaseError naming the line of the first mistake."""
    blocks: dict = {}                       # (member, block, flank) -> {KEY: (words, line)}
    member = flank = None                   # the member's section and the flank a CONCAVE / CONVEX line names
    gear_type, hand, skipped, skipping = ("generated", 0), None, [], False
    it = _lines(text)
    for n, key, words in it:
        where = f"line {n}: {member or 'script'}"
        opened = member is not None and not _complete(blocks, member)
        if not words and (key == "PAIRS" and not skipping or key in ("COMMON", "MACHINE", "CUTTER") and opened):
            side = None
            if key in ("MACHINE", "CUTTER"):
                side = flank or next((s for s in ("concave", "convex") if (member, key, s) not in blocks), "convex")
            slot = (member if key != "PAIRS" else None, key, side)
            if slot in blocks:
                raise CaseError(f"{where}.{key}", key, f"one {key} block per "
                                f"{'pair' if key == 'PAIRS' else side + ' flank' if side else 'member'}", file)
            blocks[slot] = _block(it, key, f"{member}.{side}.{key}" if side else f"{slot[0] or 'pairs'}.{key}",
                                  n, file)
            if key == "PAIRS":
                hand = _hand(blocks[slot], "HAND_PINION", "pairs.PAIRS", file)
            continue
        if key in ("COMMON", "MACHINE", "CUTTER") and not words and not skipping:
            raise CaseError(f"{where}.{key}", key, "a block of a member's section (after TYPE FACEMILLED_PINION or "
                            "FACEMILLED_GEAR): one COMMON and, per flank, one MACHINE and one CUTTER block", file)
        if key == "TYPE" and words and (not skipping or words[0].upper().startswith("FACEMILLED")):
            kind = words[0].upper()
            if kind not in ("FACEMILLED_PINION", "FACEMILLED_GEAR"):
                raise CaseError(f"{where}.TYPE", words[0], "FACEMILLED_PINION or FACEMILLED_GEAR (a face-milled "
                                "spiral bevel member; face-hobbed members are not modelled)", file)
            member, flank, skipping = kind.split("_")[1].lower(), None, False
            if (member, "TYPE", None) in blocks:
                raise CaseError(f"{where}.TYPE", words[0], "one section per member", file)
            blocks[(member, "TYPE", None)] = {"": ("", n)}
            continue
        if key == "GEAR_TYPE" and not skipping:
            if member != "gear" or len(words) != 1 or words[0].lower() not in ("generated", "formate"):
                raise CaseError(f"{where}.GEAR_TYPE", " ".join(words) or None, "GENERATED or FORMATE, in the gear's "
                                "section (after TYPE FACEMILLED_GEAR)", file)
            gear_type = (words[0].lower(), n)
            continue
        if opened:
            if key in ("CONCAVE", "CONVEX") and not words:
                flank = key.lower()
            elif key not in _TOP or key == "SESFILENAME":
                raise CaseError(f"{where}.{key}", " ".join(words) or None, f"in the {member}'s section one of "
                                f"{', '.join(k for k in _SECTION if member == 'gear' or k != 'GEAR_TYPE')} (the "
                                "program's other menus are skipped outside the members' sections)", file)
            continue
        if key in ("ROTOR", "HYPOID", "EDIT"):
            skipping = False
        if key == "NHYPOIDS" and not skipping and words != ["1"]:
            raise CaseError(f"{where}.NHYPOIDS", " ".join(words) or None, "1: one face-milled member per rotor", file)
        if key == "SESFILENAME" and not words:
            next(it, None)                  # the session file's name on the next line
        if key not in _TOP:
            skipped.append(f"line {n}: {key}")
            skipping = skipping or not words
    if skipped:
        log.info("%s: not modelled here, skipped: %s", file or "script", "; ".join(skipped))
    return _assemble(blocks, hand, gear_type, tuple(skipped), file)


def _complete(blocks: dict, member: str) -> bool:
    return all((member, b, s) in blocks for b, s in (("COMMON", None), ("MACHINE", "concave"), ("CUTTER", "concave"),
                                                      ("MACHINE", "convex"), ("CUTTER", "convex")))


def _block(it, key: str, where: str, n0: int, file: str | None) -> dict:
    """The ``KEYWORD value`` lines of a block up to its EXIT, each keyword once and known."""
    out: dict = {"": ("", n0)}             # "": the line that opens the block
    for n, k, words in it:
        if k == "EXIT":
            return out
        if k not in _BLOCKS[key]:
            raise CaseError(f"line {n}: {where}.{k}", " ".join(words) or None, f"a keyword of the {key} block: "
                            f"{', '.join(sorted(_BLOCKS[key]))}", file)
        if len(words) != 1:
            raise CaseError(f"line {n}: {where}.{k}", " ".join(words) or None, "one value after the keyword", file)
        if k in out:
            raise CaseError(f"line {n}: {where}.{k}", words[0], f"given once (also on line {out[k][1]})", file)
        out[k] = (words[0], n)
    raise CaseError(f"line {n0}: {where}", key, "a block closed by EXIT (the file ends inside it)", file)


def _num(block: dict, k: str, where: str, file, default=None) -> float:
    if k not in block:
        if default is None:
            raise CaseError(f"line {block[''][1]}: {where}.{k}", None, "required in the block (a number)", file)
        return default
    text, n = block[k]
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if not math.isfinite(v):
        raise CaseError(f"line {n}: {where}.{k}", text, "a finite number", file)
    return v


def _word(block: dict, k: str, where: str, allowed: tuple, file, default=None) -> str:
    if k not in block:
        if default is None:
            raise CaseError(f"line {block[''][1]}: {where}.{k}", None, f"required: one of {', '.join(allowed)}", file)
        return default
    text, n = block[k]
    if text.upper() not in allowed:
        raise CaseError(f"line {n}: {where}.{k}", text, f"one of {', '.join(allowed)}", file)
    return text.upper()


def _hand(block: dict, k: str, where: str, file) -> str | None:
    return _word(block, k, where, ("LEFT", "RIGHT"), file, "").lower() or None


def _assemble(blocks: dict, hand: str | None, gear_type: tuple, skipped: tuple, file) -> HfmScript:
    common = {}
    for m in ("pinion", "gear"):
        for b, s in (("COMMON", None), ("MACHINE", "concave"), ("CUTTER", "concave"), ("MACHINE", "convex"),
                     ("CUTTER", "convex")):
            if (m, b, s) not in blocks:
                at = f"line {blocks[(m, 'TYPE', None)][''][1]}: " if (m, "TYPE", None) in blocks else "end: "
                raise CaseError(f"{at}{m}.{s + '.' if s else ''}{b}", None, "a block the script must give: per "
                                f"member a TYPE FACEMILLED_{m.upper()} section with COMMON and, per flank, MACHINE and "
                                "CUTTER", file)
        c = blocks[(m, "COMMON", None)]
        where = f"{m}.COMMON"
        common[m] = {k: _num(c, k, where, file, 0.0) if k == "PITCHAPEX" else _num(c, k, where, file) if k in
                     ("SPIRALANGLE", "OUTERCONEDIST", "FACEWIDTH", "PITCHANGLE") or k in c else None
                     for k in F.COMMON}
        common[m]["NTEETH"] = _num(c, "NTEETH", where, file)
        if common[m]["NTEETH"] != int(common[m]["NTEETH"]):
            raise CaseError(f"line {c['NTEETH'][1]}: {where}.NTEETH", c["NTEETH"][0], "a whole number", file)
        common[m]["HAND"] = _hand(c, "HAND", where, file)
        if _word(c, "USE_SPRD_BLD_THICKNESS", where, ("TRUE", "FALSE"), file, "TRUE") != "TRUE":
            raise CaseError(f"line {c['USE_SPRD_BLD_THICKNESS'][1]}: {where}.USE_SPRD_BLD_THICKNESS", "FALSE",
                            "TRUE: the tooth thickness is the one the cutters' point radii cut (a prescribed "
                            "NORMAL_THICKNESS is not modelled)", file)
        unused = sorted(k for k in ("BASECONEAPEX", "TYPE_THICKNESS", "NORMAL_THICKNESS") if k in c)
        if unused:
            log.info("%s: %s: %s not used (the rim of that program's FE model; the thickness is the one the cutters "
                     "cut)", file or "script", where, ", ".join(unused))
    hand = hand or common["pinion"]["HAND"] or {"left": "right", "right": "left"}.get(common["gear"]["HAND"])
    if hand is None:
        raise CaseError("pairs.PAIRS.HAND_PINION", None, "the pinion's hand: HAND_PINION in PAIRS or HAND in the "
                        "pinion's COMMON block (LEFT or RIGHT)", file)
    remarks = []
    for m, want in (("pinion", hand), ("gear", "left" if hand == "right" else "right")):
        if common[m]["HAND"] not in (None, want):
            remarks.append(f"{m} HAND {common[m]['HAND'].upper()} (line {blocks[(m, 'COMMON', None)]['HAND'][1]}) "
                           f"taken as {want.upper()}: the pair's hand is the pinion's, {hand.upper()}")
            log.warning("%s: %s", file or "script", remarks[-1])
        common[m]["HAND"] = want
    sheets = {m: {s: _flank(blocks[(m, "MACHINE", s)], blocks[(m, "CUTTER", s)], m, s, hand,
                            gear_type[0] if m == "gear" else "generated", file) for s in ("concave", "convex")}
              for m in ("pinion", "gear")}
    lines = {m: {k: v[1] for k, v in blocks[(m, "COMMON", None)].items() if k} for m in ("pinion", "gear")}
    return HfmScript(hand, common, sheets, skipped, file, lines, tuple(remarks))


def _flank(mach: dict, cut: dict, member: str, side: str, hand: str, generation: str, file) -> dict:
    """One flank's settings sheet from its MACHINE and CUTTER blocks (:mod:`ltca.bevel.hfm_format`)."""
    where = f"{member}.{side}.MACHINE"
    sheet: dict = {"generation": generation, "blade": "outside" if side == "concave" else "inside"}
    formate = generation == "formate"
    hv = [k for k in ("HORIZONTAL", "VERTICAL") if k in mach]
    if hv and (not formate or "RADIALSETTING" in mach or "CRADLEANGLE" in mach):
        raise CaseError(f"line {mach[hv[0]][1]}: {where}.{hv[0]}", mach[hv[0]][0], "the cutter centre of a formate "
                        "gear (GEAR_TYPE FORMATE) as HORIZONTAL and VERTICAL instead of RADIALSETTING and CRADLEANGLE",
                        file)
    if hv:
        h, v = _num(mach, "HORIZONTAL", where, file), _num(mach, "VERTICAL", where, file, 0.0)
        mach = dict(mach, RADIALSETTING=(repr(math.hypot(h, v)), mach[hv[0]][1]),
                    CRADLEANGLE=(repr(math.degrees(math.atan2(v, h))), mach[hv[0]][1]))
    for k, (key, row) in F.MACHINE0.items():
        req = None if k in ("RADIALSETTING", "CRADLEANGLE", "ROOTANGLE") else 0.0
        sheet[key] = F.sign(member, hand, row, 0) * _num(mach, k, where, file, req)
    roll = _num(mach, "RATIOROLL", where, file, 0.0 if formate else None)
    terms = {k: _num(mach, k, where, file, 0.0) for k in mach if k in F.ROLL or k == "MODROLL_5040H"
             or F.motion_keyword(k)}
    if terms.get("MODROLL_5040H"):
        raise CaseError(f"line {mach['MODROLL_5040H'][1]}: {where}.MODROLL_5040H", mach["MODROLL_5040H"][0],
                        "0: the modified roll is modelled to the 6th order (MODROLL_720G)", file)
    if formate:
        bad = [k for k, v in terms.items() if v] + (["RATIOROLL"] if roll else [])
        if bad:
            raise CaseError(f"line {mach[bad[0]][1]}: {where}.{bad[0]}", mach[bad[0]][0], "0 on a formate flank "
                            "(no roll, no motions)", file)
    else:
        if roll <= 0:
            raise CaseError(f"line {mach['RATIOROLL'][1]}: {where}.RATIOROLL", mach["RATIOROLL"][0],
                            "a ratio of roll > 0 on a generated flank", file)
        sheet["ratio_of_roll"] = roll
        for k, (key, order) in F.ROLL.items():
            sheet[key] = F.sign(member, hand, "roll", order) * F.factor(k) * terms.get(k, 0.0)
    for stem, (key, row) in F.MOTIONS.items():
        a = [F.sign(member, hand, row, k) * F.factor(f"{stem}{k}") * terms.get(f"{stem}{k}", 0.0)
             for k in range(1, 7)]
        while a and a[-1] == 0.0:
            a.pop()
        if a:
            sheet[key] = a
    where = f"{member}.{side}.CUTTER"
    used = {"", "USENEWCUTTER", "TYPE", "TOPREM_OPTION", "FLANKREM_OPTION", *F.CUTTER}
    for k, key in F.CUTTER.items():
        sheet[key] = _num(cut, k, where, file, 0.0 if k == "EDGERADIUS" else None)
    _word(cut, "USENEWCUTTER", where, ("TRUE",), file, "TRUE")
    if _word(cut, "TYPE", where, ("STRAIGHT", "CURVED"), file, "STRAIGHT") == "CURVED":
        sheet["profile_radius_mm"] = _num(cut, "RHO", where, file)
        used.add("RHO")
    for rem in ("TOPREM", "FLANKREM"):
        opt = _word(cut, f"{rem}_OPTION", where, ("NONE", "BLENDED"), file, "NONE")
        if opt == "BLENDED":
            sheet[f"{rem.lower()}_depth_mm"] = _num(cut, f"{rem}_DEPTH", where, file)
            sheet[f"{rem.lower()}_radius_mm"] = _num(cut, f"{rem}_BLEND_RADIUS", where, file)
            used |= {f"{rem}_DEPTH", f"{rem}_BLEND_RADIUS"}
    if set(cut) - used:
        log.info("%s: %s: %s not used (the blade's TYPE and options leave them out)", file or "script", where,
                 ", ".join(f"{k} (line {cut[k][1]})" for k in sorted(set(cut) - used)))
    return sheet
