"""Spiral bevel case: read a TOML case with a [bevel] table, synthesise the pinion (seed 000), run the TCA,
print a Gleason-style settings summary and write summary.json.

Case units: mm, deg, arcsec; converted once here to mm and rad.  Mistakes raise
:class:`ltca.errors.CaseError` naming the field.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from geometry.bevel.blank import BevelBasicData, design_blank
from geometry.bevel.design import cycle_metrics, synthesize_pinion
from geometry.bevel.generation import standard_gear_cut
from geometry.bevel.machine import MemberCut
from geometry.bevel.synthesis import FlankTarget
from geometry.bevel.tca import ARCSEC, BevelPair, tca

from .errors import CaseError

__all__ = ["load_bevel_case", "run_bevel_tca"]

_NUM = (int, float)
# key: (type, check, words)
_BEVEL = {
    "pinion_teeth": (int, lambda v: 5 <= v <= 200, "an integer in [5, 200]"),
    "gear_teeth": (int, lambda v: 5 <= v <= 500, "an integer in [5, 500], >= pinion_teeth"),
    "module_mm": (_NUM, lambda v: 0 < v <= 100, "a number in (0, 100] mm"),
    "face_width_mm": (_NUM, lambda v: v > 0, "a positive number, mm (at most half the outer cone distance)"),
    "spiral_angle_deg": (_NUM, lambda v: 0 <= v <= 60, "a number in [0, 60] deg"),
    "pressure_angle_deg": (_NUM, lambda v: 10 <= v <= 30, "a number in [10, 30] deg"),
    "shaft_angle_deg": (_NUM, lambda v: 0 < v < 180, "a number in (0, 180) deg"),
    "gear_hand": (str, lambda v: v in ("left", "right"), "'left' or 'right'"),
    "cutter_radius_mm": (_NUM, lambda v: v > 0, "a positive number, mm"),
    "taper": (str, lambda v: v in ("standard", "uniform"), "'standard' or 'uniform'"),
    "blank_offset_mm": (_NUM, lambda v: abs(v) <= 100, "a number in [-100, 100] mm"),
}
_FLANK = {
    "path_angle_deg": (_NUM, lambda v: abs(v) < 80, "a number in (-80, 80) deg"),
    "te_magnitude_arcsec": (_NUM, lambda v: 0 < v <= 1000, "a number in (0, 1000] arcsec"),
    "ellipse_major_mm": (_NUM, lambda v: v > 0, "a positive number, mm"),
}


def _table(raw: dict, spec: dict, name: str, file: str, optional: tuple = ()) -> dict:
    out = {}
    for k in raw:
        if k not in spec and not isinstance(raw[k], dict):
            raise CaseError(f"{name}.{k}", raw[k], f"unknown key; allowed keys are {sorted(spec)}", file)
    for k, (typ, ok, words) in spec.items():
        if k not in raw:
            if k in optional:
                continue
            raise CaseError(f"{name}.{k}", None, f"required; {words}", file)
        v = raw[k]
        if isinstance(v, bool) or not isinstance(v, typ) or not ok(v):
            raise CaseError(f"{name}.{k}", v, words, file)
        out[k] = v
    return out


def load_bevel_case(case_path: str | Path) -> dict:
    """Read and validate a bevel case; returns the basic data, the targets and the blank offset."""
    from .case import read_toml
    path = Path(case_path)
    data = read_toml(path)
    f = str(path)
    raw = data.get("bevel")
    if not isinstance(raw, dict):
        raise CaseError("bevel", raw, "a required table [bevel]", f)
    b = _table(raw, _BEVEL, "bevel", f, optional=("blank_offset_mm", "taper", "shaft_angle_deg"))
    if b["gear_teeth"] < b["pinion_teeth"]:
        raise CaseError("bevel.gear_teeth", b["gear_teeth"], _BEVEL["gear_teeth"][2], f)
    targets = {}
    for name, side in (("working", "concave"), ("coast", "convex")):
        t = raw.get(name)
        if not isinstance(t, dict):
            raise CaseError(f"bevel.{name}", t, "a required table", f)
        t = _table(t, _FLANK, f"bevel.{name}", f)
        targets[side] = FlankTarget(np.deg2rad(t["path_angle_deg"]), t["te_magnitude_arcsec"] * ARCSEC,
                                    float(t["ellipse_major_mm"]))
    try:
        basic = BevelBasicData(z1=b["pinion_teeth"], z2=b["gear_teeth"], module=float(b["module_mm"]),
                               face_width=float(b["face_width_mm"]),
                               spiral_angle=np.deg2rad(b["spiral_angle_deg"]),
                               pressure_angle=np.deg2rad(b["pressure_angle_deg"]),
                               shaft_angle=np.deg2rad(b.get("shaft_angle_deg", 90.0)), hand=b["gear_hand"],
                               cutter_radius=float(b["cutter_radius_mm"]), taper=b.get("taper", "standard"))
        design_blank(basic)
    except ValueError as exc:
        raise CaseError("bevel", "(blank)", str(exc), f) from None
    name = data.get("case", {}).get("name", path.stem) if isinstance(data.get("case"), dict) else path.stem
    return dict(name=name, basic=basic, targets=targets, blank_offset=b.get("blank_offset_mm"))


def _settings(cut: MemberCut) -> dict:
    out = {}
    for side in ("concave", "convex"):
        fc = cut.flank(side)
        m, c = fc.machine, fc.cutter
        out[side] = dict(blade=c.blade, point_radius_mm=c.point_radius, blade_angle_deg=np.rad2deg(c.blade_angle),
                         edge_radius_mm=c.edge_radius, radial_setting_mm=m.radial_setting,
                         cradle_angle_deg=np.rad2deg(m.cradle_angle), machine_root_angle_deg=np.rad2deg(m.root_angle),
                         machine_center_to_back_mm=m.center_to_back, blank_offset_mm=m.blank_offset,
                         sliding_base_mm=m.sliding_base, ratio_of_roll=m.ratio_of_roll,
                         modified_roll_C=m.modified_roll_c, modified_roll_D=m.modified_roll_d)
    return {s: {k: (float(v) if not isinstance(v, str) else v) for k, v in d.items()} for s, d in out.items()}


def _print_summary(name: str, settings: dict, flanks: dict) -> None:
    keys = list(settings["gear"]["concave"])
    print(f"Spiral bevel summary: {name}")
    print(f"{'setting':28s}" + "".join(f"{m + ' ' + s:>16s}" for m in ("gear", "pinion") for s in ("concave", "convex")))
    for k in keys:
        vals = [settings[m][s][k] for m in ("gear", "pinion") for s in ("concave", "convex")]
        print(f"{k:28s}" + "".join(f"{v:>16s}" if isinstance(v, str) else f"{v:16.5f}" for v in vals))
    for fl, d in flanks.items():
        print(f"{fl:8s} flank: path {d['path_angle_deg']:7.2f} deg, TE {d['te_amplitude_arcsec']:6.2f} arcsec "
              f"(R^2 {d['te_r2']:.5f}), straightness {d['path_straightness_mm']:.3f} mm, contact ratio "
              f"{d['contact_ratio']:.2f}, ellipse {d['ellipse_major_mm']:.2f} mm")


def run_bevel_tca(case_path: str, out: str | None = None) -> dict:
    """Synthesise the pinion of a bevel case, run the TCA of both flanks, print and return the summary.

    Parameters
    ----------
    case_path : str
        TOML case with a [bevel] table (see cases/spiral_bevel_cao2008.toml).
    out : str, optional
        Directory for ``summary.json`` (created if needed).

    Returns
    -------
    dict
        ``case``, ``flanks`` ({"working", "coast"}: path_angle_deg, te_amplitude_arcsec, te_r2, contact_ratio,
        path_straightness_mm, ellipse_major_mm, targets), ``machine_settings`` ({"gear", "pinion"} x side),
        ``design`` (first design before the blank-offset redesign, per flank).
    """
    case = load_bevel_case(case_path)
    bl = design_blank(case["basic"])
    gear = standard_gear_cut(bl)
    pin, infos = synthesize_pinion(bl, gear, case["targets"], blank_offset=case["blank_offset"])
    pair = BevelPair(bl, gear, pin)
    flanks, design = {}, {}
    for label, side in (("working", "concave"), ("coast", "convex")):
        m = cycle_metrics(tca(pair, side, steps_per_cycle=16, max_cycles=3.0), bl)
        tg = case["targets"][side]
        m["targets"] = dict(path_angle_deg=float(np.rad2deg(tg.eta2)), te_magnitude_arcsec=tg.te_magnitude / ARCSEC,
                            ellipse_major_mm=tg.major_axis)
        flanks[label] = m
        d = infos[side]["design"]
        design[label] = dict(blank_offset_mm=d["blank_offset"], C=d["C"], D=d["D"], metrics=d["metrics"])
    settings = dict(gear=_settings(gear), pinion=_settings(pin))
    summary = dict(case=case["name"], flanks=flanks, machine_settings=settings, design=design)
    _print_summary(case["name"], settings, flanks)
    if out is not None:
        d = Path(out)
        d.mkdir(parents=True, exist_ok=True)
        (d / "summary.json").write_text(json.dumps(summary, indent=2))
    return summary
