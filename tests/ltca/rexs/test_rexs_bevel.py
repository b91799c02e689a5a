"""A REXS bevel stage read as a bevel case: the blank of the shipped 12/36 spiral bevel pair written as a REXS 2.0
model by hand (attribute ids and units of the REXS 2.0.0 schema), read back as the same blank, checked against the
pitch angles and cone distance of ISO 23509, refused where the case cannot hold it, and run through ``ltca.tca``."""
from __future__ import annotations

import math
from pathlib import Path

import pytest
import tomllib

import ltca
from ltca import rexs
from ltca.rexs.errors import RexsError
from ltca.shipped import case_path

SHIPPED = tomllib.loads(case_path("spiral_bevel_cao2008").read_text())

#: 12/36 teeth, outer transverse module 5.08 mm, 90 deg: pitch angles atan(12/36) and its complement,
#: outer cone distance 5.08 * 36 / (2 sin 71.565 deg) (ISO 23509 table 2), written to the digits a file would carry
STAGE = {"shaft_angle": ("deg", "90"), "outer_transverse_module": ("mm", "5.08"), "cutter_radius": ("mm", "88.9"),
         "hypoid_offset": ("mm", "0"), "nominal_design_pressure_angle_on_drive_side": ("deg", "22.5"),
         "nominal_design_pressure_angle_on_coast_side": ("deg", "22.5")}
PINION = {"number_of_teeth": ("none", "12"), "face_width": ("mm", "25.4"), "mean_spiral_angle": ("deg", "35"),
          "spiral_angle_pitch_direction": ("none", "left"), "pitch_angle": ("deg", "18.435")}
GEAR = {"number_of_teeth": ("none", "36"), "face_width": ("mm", "25.4"), "mean_spiral_angle": ("deg", "35"),
        "spiral_angle_pitch_direction": ("none", "right"), "pitch_angle": ("deg", "71.565"),
        "outer_cone_distance": ("mm", "96.386"), "outer_pitch_diameter": ("mm", "182.88")}


def _component(cid: int, kind: str, attrs: dict) -> str:
    rows = "".join(f'      <attribute id="{k}" unit="{u}">{v}</attribute>\n' for k, (u, v) in attrs.items())
    return f'    <component id="{cid}" name="{kind} {cid}" type="{kind}">\n{rows}    </component>\n'


def _write(path: Path, stage=STAGE, pinion=PINION, gear=GEAR) -> Path:
    path.write_text(
        '<?xml version="1.0" encoding="UTF-8"?>\n<model applicationId="hand" applicationVersion="1" '
        'date="2026-01-01T00:00:00+00:00" version="2.0">\n  <relations>\n'
        '    <relation id="1" type="stage">\n      <ref hint="bevel_stage" id="2" role="stage"/>\n'
        '      <ref hint="bevel_gear" id="11" role="gear_1"/>\n      <ref hint="bevel_gear" id="10" role="gear_2"/>\n'
        '    </relation>\n  </relations>\n  <components>\n'
        + _component(2, "bevel_stage", stage) + _component(10, "bevel_gear", pinion)
        + _component(11, "bevel_gear", gear) + "  </components>\n</model>\n", encoding="utf-8")
    return path


def test_the_pitch_angles_and_cone_distance_written_are_iso_23509s():
    d1 = math.degrees(math.atan2(1.0, 3.0))
    assert float(PINION["pitch_angle"][1]) == pytest.approx(d1, abs=5e-4)
    assert float(GEAR["outer_cone_distance"][1]) == pytest.approx(5.08 * 36 / (2 * math.sin(math.radians(90 - d1))),
                                                                  abs=5e-4)


def test_a_bevel_stage_reads_as_the_blank_it_was_written_from(tmp_path):
    rx = rexs.read(_write(tmp_path / "bevel.rexs"))
    (info,) = rx.stages
    assert info.kind == "bevel" and (info.pinion, info.gear) == (10, 11)       # the pinion has fewer teeth
    data = rx.stage_dict(2, 350.0)
    for key in ("pinion_teeth", "gear_teeth", "module_mm", "face_width_mm", "spiral_angle_deg", "pressure_angle_deg",
                "shaft_angle_deg", "gear_hand", "cutter_radius_mm"):
        assert data["bevel"][key] == pytest.approx(SHIPPED["bevel"][key]) if not isinstance(
            SHIPPED["bevel"][key], str) else data["bevel"][key] == SHIPPED["bevel"][key], key
    um = rx.stage_unmapped(2)
    attrs = {(u.component, u.attribute) for u in um}
    for c, a in [(10, "pitch_angle"), (11, "pitch_angle"), (11, "outer_cone_distance"), (2, "hypoid_offset")]:
        assert (c, a) not in attrs, (c, a)                                   # read (and agreeing with the blank)
    assumed = {u.attribute for u in um if u.reason.startswith("not in REXS")}
    assert {"bevel.working.path_angle_deg", "bevel.coast.te_magnitude_arcsec"} <= assumed
    case = rx.stage(2, 350.0)
    assert case.kind == "bevel"


def test_a_pitch_angle_that_disagrees_is_listed_with_the_derived_value(tmp_path):
    rx = rexs.read(_write(tmp_path / "bevel.rexs", pinion={**PINION, "pitch_angle": ("deg", "20.0")}))
    (row,) = [u for u in rx.stage_unmapped(2) if (u.component, u.attribute) == (10, "pitch_angle")]
    assert "disagrees" in row.reason and "18.43" in row.reason


@pytest.mark.parametrize("where, attr, value, words", [
    ("stage", "hypoid_offset", ("mm", "5"), "hypoid"),
    ("stage", "nominal_design_pressure_angle_on_coast_side", ("deg", "20"), "one blade pressure angle"),
    ("pinion", "spiral_angle_pitch_direction", ("none", "right"), "opposite hand"),
])
def test_what_the_bevel_case_cannot_hold_is_refused_by_name(tmp_path, where, attr, value, words):
    parts = {"stage": dict(STAGE), "pinion": dict(PINION), "gear": dict(GEAR)}
    parts[where][attr] = value
    rx = rexs.read(_write(tmp_path / "bevel.rexs", **parts))
    with pytest.raises(RexsError) as err:
        rx.stage_dict(2, 350.0)
    assert attr in str(err.value) and words in str(err.value)


def test_a_missing_blank_value_is_named(tmp_path):
    rx = rexs.read(_write(tmp_path / "bevel.rexs", stage={k: v for k, v in STAGE.items() if k != "cutter_radius"}))
    with pytest.raises(RexsError, match="cutter_radius"):
        rx.stage_dict(2, 350.0)


@pytest.mark.heavy
def test_the_imported_stage_gives_the_shipped_pairs_tca(tmp_path):
    """Same blank, same targets (the assumed ones are the shipped pair's): the synthesis and the unloaded TE agree."""
    rx = rexs.read(_write(tmp_path / "bevel.rexs"))
    imported = ltca.tca(rx.stage(2, 350.0))
    shipped = ltca.tca(ltca.load_case("spiral_bevel_cao2008"))
    assert _numbers(imported.summary) == pytest.approx(_numbers(shipped.summary), rel=1e-9, abs=1e-12)


def _numbers(tree, prefix="") -> dict:
    """Every number of a nested summary by its dotted path (the case name and file left out)."""
    out = {}
    items = tree.items() if isinstance(tree, dict) else enumerate(tree) if isinstance(tree, list) else ()
    for k, v in items:
        if isinstance(v, bool) or k in ("name", "file", "case"):
            continue
        if isinstance(v, (int, float)):
            out[f"{prefix}{k}"] = float(v)
        elif isinstance(v, (dict, list)):
            out.update(_numbers(v, f"{prefix}{k}."))
    return out
