"""Spiral bevel case: read and validate a TOML case with a [bevel] table (basic data, flank targets, blank offset).

Case units: mm, deg, arcsec; converted once here to mm and rad.  Mistakes raise
:class:`ltca.errors.CaseError` naming the field.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from geometry.bevel.blank import BevelBasicData, design_blank
from geometry.bevel.synthesis import FlankTarget
from geometry.bevel.tca import RAD_PER_ARCSEC

from ..errors import CaseError

__all__ = ["load_bevel_case"]

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
    from ..case import read_toml
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
        targets[side] = FlankTarget(np.deg2rad(t["path_angle_deg"]), t["te_magnitude_arcsec"] * RAD_PER_ARCSEC,
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
