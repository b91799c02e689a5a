"""The planetary case reader on the one validation layer: finite, bounded numbers, unknown keys refused at every
depth, the stated ranges enforced; satellite profile shifts over their whole allowed range [-2, 2] either compute
or end in exit 2 naming the fields (never a traceback)."""
from __future__ import annotations

import pytest
import tomllib

from fixtures.paths import CASES
from fixtures.toml_text import dumps
from ltca.cli import main
from ltca.errors import CaseError
from ltca.planetary.case import parse_planetary_case

CASE = CASES / "eccentric_planetary_satellite.toml"


def _doc() -> dict:
    return tomllib.loads(CASE.read_text())


def _set(doc: dict, dotted: str, value) -> dict:
    *head, last = dotted.split(".")
    t = doc
    for k in head:
        t = t.setdefault(k, {})
    t[last] = value
    return doc


BAD = [   # (dotted key, value, the field the message must name)
    ("case.fuzz", 1, "case.fuzz"),
    ("case.name", "", "case.name"),
    ("satellite.fuzz", 1.0, "satellite.fuzz"),
    ("satellite.disk_cutter.fuzz", 1.0, "satellite.disk_cutter.fuzz"),
    ("satellite.hob_three_pass.shift_mm", float("inf"), "satellite.hob_three_pass.shift_mm"),
    ("satellite.hob_three_pass.lead_angle_deg", 45.0, "satellite.hob_three_pass.lead_angle_deg"),
    ("satellite.disk_cutter.x_plunge", float("nan"), "satellite.disk_cutter.x_plunge"),
    ("satellite.disk_cutter.teeth", 0, "satellite.disk_cutter.teeth"),
    ("satellite.special_hob.thickening", 1.0, "satellite.special_hob.thickening"),
    ("satellite.tip_diameter_mm", float("inf"), "satellite.tip_diameter_mm"),
    ("satellite.bore_diameter_mm", 1e9, "satellite.bore_diameter_mm"),
    ("satellite.teeth", 50.0, "satellite.teeth"),
    ("cutter.addendum", 0.5, "cutter.addendum"),
    ("cutter.tip_radius", -0.1, "cutter.tip_radius"),
    ("wheel.eccentricity_mm", 1e9, "wheel.eccentricity_mm"),
    ("wheel.profile_shift", 3.0, "wheel.profile_shift"),
    ("wheel.shaper_teeth", 60, "wheel.shaper_teeth"),
    ("wheel.far_tip_clearance_mm", float("-inf"), "wheel.far_tip_clearance_mm"),
    ("wheel.outer_diameter_mm", float("inf"), "wheel.outer_diameter_mm"),
    ("wheel.fuzz", {"a": 1}, "wheel.fuzz"),
    ("material.youngs_modulus_mpa", 1e9, "material.youngs_modulus_mpa"),
    ("material.fuzz", 1, "material.fuzz"),
    ("load.torques_percent_of_rated", [5, float("inf")], "load.torques_percent_of_rated[1]"),
    ("load.fuzz", 1, "load.fuzz"),
    ("analysis.positions", 0, "analysis.positions"),
    ("analysis.fuzz", 1, "analysis.fuzz"),
    ("fuzz_table.a", 1, "fuzz_table"),
]


@pytest.mark.parametrize("key,value,field", BAD, ids=[b[0] for b in BAD])
def test_bad_field_named(key, value, field):
    with pytest.raises(CaseError) as exc:
        parse_planetary_case(_set(_doc(), key, value), "case.toml")
    assert f"'{field}'" in str(exc.value), str(exc.value)


def test_torque_nm_bounded():
    doc = _doc()
    del doc["load"]["torques_percent_of_rated"]
    for v in (float("inf"), 1e9, 0, [100, 100]):
        doc["load"]["torque_nm"] = v
        with pytest.raises(CaseError, match="'load.torque_nm"):
            parse_planetary_case(doc, "case.toml")
    doc["load"]["torque_nm"] = [50, 100]
    assert parse_planetary_case(doc, "case.toml").torques == (5e4, 1e5)


def test_shipped_case_reads():
    c = parse_planetary_case(_doc(), str(CASE))
    assert c.design.z == 50 and c.design.x == -0.5 and c.torque_fractions == (0.05, 0.5, 1.0, 1.5)
    assert c.tools["disk_cutter"].x_plunge == -1.3 and c.tools["hob_three_pass"].shift is None


@pytest.mark.parametrize("x", [-2.0, -1.5, 1.0, 2.0])
@pytest.mark.parametrize("method", ["special_hob", "disk_cutter"])
def test_profile_shift_in_range_never_a_traceback(tmp_path, capsys, x, method):
    doc = _set(_set(_doc(), "satellite.profile_shift", x), "satellite.method", method)
    path = tmp_path / "case.toml"
    path.write_text(dumps(doc))
    for cmd in (["forming", str(path)], ["tca", str(path), "--positions", "3"]):
        status = main(cmd)
        err = capsys.readouterr().err
        assert status in (0, 2) and "Traceback" not in err, (cmd, err)
        if status == 2:
            line = err.strip().splitlines()
            assert len(line) == 1 and ("field '" in line[0] or "set by '" in line[0]), err
