"""A bevel case from a HypoidFaceMilled / Transmission3D script read by :func:`ltca.bevel.hfm_script.parse_hfm`.

The case takes the settings sheets as they stand and the basic data of its blank from the ``COMMON`` blocks: teeth,
spiral angle, face width, shaft angle = sum of the pitch angles, module = 2 A_0 sin(delta_2) / z_2, taper uniform
when the face angles equal the pitch angles; the pressure angle and the cutter radius from the gear's blades (their
mean blade angle and mean point radius: the gear's standard cut centres its blades on the cutter radius). Where a
member's face and root cones differ from those the case designs (Gleason's formulas,
:mod:`ltca.geometry.bevel.blank`), the case gives them (``[bevel.blank.<member>]``): FACEANGLE, FACEAPEX, ROOTAPEX
and the root angle, BASECONEANGLE (SpyGO writes the root angle there: the rim's base cone parallel to the root cone)
or else the concave flank's machine ROOTANGLE. What the case cannot hold (back and front cones other than normal to
the pitch cone, the FE rim) is logged and listed (``notes``).
"""
from __future__ import annotations

import logging
import math
from pathlib import Path

from ltca.geometry.bevel.blank import BevelBasicData, cone_apexes, design_blank

from ..errors import CaseError
from .hfm_script import HfmScript

__all__ = ["case_data", "case_toml"]

log = logging.getLogger(__name__)


def case_data(script: HfmScript, name: str | None = None, torques: list[float] | None = None
              ) -> tuple[dict, list[str]]:
    """The bevel case dict of a script (module docstring) and the notes on what the case does not carry.

    Returns ``(data, notes)``: ``data`` as read from a case file (``[case]``, ``[bevel]`` with
    ``[bevel.settings.*]``, ``[bevel.blank.*]`` where the script's cones are not the designed ones, ``[load]`` when
    ``torques`` (N m on the pinion) are given), ``notes`` the script's remarks
    (:class:`ltca.bevel.hfm_script.HfmScript`) and one line per blank value the case does not hold."""
    f = script.file
    p, g = script.common["pinion"], script.common["gear"]

    def at(m: str, k: str) -> str:
        n = (script.lines or {}).get(m, {}).get(k)
        return f"line {n}: {m}.COMMON.{k}" if n else f"{m}.COMMON.{k}"

    for k, tol in (("SPIRALANGLE", 1e-6), ("OUTERCONEDIST", 1e-6), ("FACEWIDTH", 1e-6)):
        if abs(p[k] - g[k]) > tol:
            raise CaseError(at("pinion", k), p[k], f"the gear's {g[k]!r}: a spiral bevel pair without offset "
                            "(a hypoid pair is not modelled)", f)
    for m in ("pinion", "gear"):
        if abs(script.common[m]["PITCHAPEX"]) > 1e-6:
            raise CaseError(at(m, "PITCHAPEX"), script.common[m]["PITCHAPEX"], "0: the pitch apex at the "
                            "crossing point (a hypoid pair is not modelled)", f)
    z1, z2 = int(p["NTEETH"]), int(g["NTEETH"])
    g1, g2 = math.radians(p["PITCHANGLE"]), math.radians(g["PITCHANGLE"])
    if abs(math.atan2(math.sin(g1 + g2), z2 / z1 + math.cos(g1 + g2)) - g1) > math.radians(1e-6):
        raise CaseError(at("pinion", "PITCHANGLE"), p["PITCHANGLE"], f"the pitch angle of {z1}/{z2} teeth at the "
                        f"shaft angle {p['PITCHANGLE'] + g['PITCHANGLE']!r} deg (rolling pitch cones)", f)
    gs = script.sheets["gear"]
    uniform = all(c["FACEANGLE"] is not None and abs(c["FACEANGLE"] - c["PITCHANGLE"]) < 1e-9 for c in (p, g))
    bevel = {"pinion_teeth": z1, "gear_teeth": z2, "module_mm": 2 * g["OUTERCONEDIST"] * math.sin(g2) / z2,
             "face_width_mm": g["FACEWIDTH"], "spiral_angle_deg": g["SPIRALANGLE"],
             "pressure_angle_deg": 0.5 * (gs["concave"]["blade_angle_deg"] + gs["convex"]["blade_angle_deg"]),
             "shaft_angle_deg": p["PITCHANGLE"] + g["PITCHANGLE"], "gear_hand": g["HAND"],
             "cutter_radius_mm": 0.5 * (gs["concave"]["point_radius_mm"] + gs["convex"]["point_radius_mm"]),
             "taper": "uniform" if uniform else "standard", "settings": script.sheets}
    stem = Path(f).stem if f else "hfm"
    data = {"case": {"name": name or stem, "description": f"{z1}/{z2} spiral bevel pair of a HypoidFaceMilled "
                     "script, cut as its settings give it",
                     "source": f"HypoidFaceMilled / Transmission3D script {Path(f).name if f else ''}".strip()},
            "bevel": bevel}
    if torques:
        data["load"] = {"torque_nm": [float(t) for t in torques]}
    return data, list(script.remarks) + _blank(script, bevel)


def _blank(script: HfmScript, bevel: dict) -> list[str]:
    """The script's cones against the blank the case designs from ``bevel``: ``bevel["blank"]`` where they differ
    (1e-6 deg or mm); returns the notes on what the case does not carry (logged)."""
    try:
        bl = design_blank(BevelBasicData(
            z1=bevel["pinion_teeth"], z2=bevel["gear_teeth"], module=bevel["module_mm"],
            face_width=bevel["face_width_mm"], spiral_angle=math.radians(bevel["spiral_angle_deg"]),
            pressure_angle=math.radians(bevel["pressure_angle_deg"]),
            shaft_angle=math.radians(bevel["shaft_angle_deg"]), hand=bevel["gear_hand"],
            cutter_radius=bevel["cutter_radius_mm"], taper=bevel["taper"]))
    except ValueError:
        return []                           # the case's own check names the field
    notes, cones = [], {}
    for m in ("pinion", "gear"):
        c, mb = script.common[m], bl.member(m)
        root = c["BASECONEANGLE"] if c["BASECONEANGLE"] is not None else \
            script.sheets[m]["concave"]["machine_root_angle_deg"]
        given = {"face_angle_deg": c["FACEANGLE"], "root_angle_deg": root, "face_apex_mm": c["FACEAPEX"],
                 "root_apex_mm": c["ROOTAPEX"]}
        ours = dict(zip(given, (math.degrees(mb.face_angle), math.degrees(mb.root_angle), *cone_apexes(bl, m))))
        if None in given.values():
            notes.append(f"{m} cones: the blank designed here (the script gives no "
                         f"{', '.join(k for k in ('FACEANGLE', 'FACEAPEX', 'ROOTAPEX') if c[k] is None)})")
        elif any(abs(given[k] - ours[k]) > 1e-6 for k in given):
            cones[m] = given
            log.info("%s: %s cones as the script gives them (face angle %.6g, root angle %.6g deg, apexes %.6g, "
                     "%.6g mm; designed here: %.6g, %.6g deg, %.6g, %.6g mm)", script.file or "script", m,
                     *given.values(), *ours.values())
        for k in ("BACKANGLE", "FRONTANGLE"):
            if c[k] is not None and abs(c[k] - math.degrees(mb.pitch_angle)) > 1e-6:
                notes.append(f"{m} {k} {c[k]:.6g} deg in the script: the heel and toe here are normal to the "
                             f"pitch cone ({math.degrees(mb.pitch_angle):.6g} deg)")
    if cones:
        bevel["blank"] = cones
    for line in notes:
        log.warning("%s: %s", script.file or "script", line)
    return notes


def case_toml(data: dict, notes: list[str], source: str = "") -> str:
    """The TOML text of :func:`case_data`'s result: a header naming ``source`` and the notes as comments, then the
    case (floats written exactly)."""
    from ltca.geometry.bevel.sheet import sheet_toml

    from ..case import to_toml
    head = [f"# converted by `ltca convert` from {source}" if source else "# converted by `ltca convert`"]
    head += [f"# not carried: {n}" for n in notes]
    if "load" not in data:
        head.append("# no torque: add [load] torque_nm = [..] (N m on the pinion) before `ltca run`")
    rest = dict(data, bevel={k: v for k, v in data["bevel"].items() if k != "settings"})
    return ("\n".join(head) + "\n\n" + to_toml(rest).lstrip("\n") + "\n\n# each member's settings sheet per flank (mm, deg), "
            "as the script gives it\n" + sheet_toml(data["bevel"]["settings"]))
