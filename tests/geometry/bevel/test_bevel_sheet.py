"""Settings sheets: a flank's settings in the industry's vocabulary, written and read back, and a bevel case
that gives the sheets instead of the synthesis targets."""
import dataclasses

import numpy as np
import pytest
import tomllib

from fixtures.paths import BEVEL_CASE
from ltca.bevel.analysis import build_pair
from ltca.bevel.case import bevel_case_from_data
from ltca.case import read_toml
from ltca.errors import CaseError
from ltca.geometry.bevel.blank import BevelBasicData, design_blank
from ltca.geometry.bevel.generation import generate_member, standard_gear_cut
from ltca.geometry.bevel.machine import FlankCut
from ltca.geometry.bevel.sheet import flank_from_sheet, flank_sheet, member_sheet, sheet_toml
from ltca.geometry.bevel.tca import tca

CASE = BEVEL_CASE


def _close(a, b):
    for f in dataclasses.fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if isinstance(x, (float, int)) and not isinstance(x, bool):
            assert x == pytest.approx(y, rel=1e-15, abs=1e-15), f.name
        else:
            assert x == pytest.approx(y, rel=1e-15, abs=1e-15) if isinstance(x, tuple) else x == y, f.name


def test_sheet_written_and_read_back_is_unchanged():
    fc0 = standard_gear_cut(design_blank(BevelBasicData())).concave
    ms = dataclasses.replace(fc0.machine, tilt=0.02, swivel=-0.4, modified_roll_c=0.01, modified_roll_g=-3.0,
                             radial_motion=(0.5, 0.0, 2.0), helical_motion=(1.0,), tilt_motion=(1e-3, 2e-3),
                             swivel_motion=(0.1,), vertical_motion=(0.0, 0.3))
    fc = FlankCut(ms, dataclasses.replace(fc0.cutter, profile_radius=450.0, toprem_depth=1.5, toprem_radius=20.0,
                                          flankrem_depth=7.0, flankrem_radius=35.0))
    sheet = flank_sheet(fc)
    assert sheet["modified_roll_2C"] == pytest.approx(0.02) and sheet["modified_roll_720G"] == pytest.approx(-2160.0)
    assert sheet["tilt_deg"] == pytest.approx(np.rad2deg(0.02)) and sheet["profile_radius_mm"] == 450.0
    back = flank_from_sheet(tomllib.loads(sheet_toml({"gear": {"concave": sheet}}))["bevel"]["settings"]["gear"]
                            ["concave"])
    _close(back.machine, fc.machine)
    _close(back.cutter, fc.cutter)
    again = flank_sheet(back)
    assert again.keys() == sheet.keys()
    assert all(again[k] == pytest.approx(v, rel=1e-15) if not isinstance(v, str) else again[k] == v
               for k, v in sheet.items())


@pytest.fixture(scope="module")
def pairs(bevel_pair):
    data = read_toml(CASE)
    pair = bevel_pair                               # gear standard cut, pinion synthesised for the targets
    text = sheet_toml({"gear": member_sheet(pair.gear), "pinion": member_sheet(pair.pinion)})
    given = dict(data)
    given["bevel"] = {k: v for k, v in data["bevel"].items() if k not in ("working", "coast")}
    given["bevel"]["settings"] = tomllib.loads(text)["bevel"]["settings"]
    case2 = bevel_case_from_data(given, "sheet case")
    return pair, build_pair(case2), given


def test_synthesis_output_read_back_as_a_case_cuts_the_same_pair(pairs):
    pair, pair2, _ = pairs
    for m in ("gear", "pinion"):
        for s in ("concave", "convex"):
            a, b = getattr(pair, m).flank(s), getattr(pair2, m).flank(s)
            _close(a.machine, b.machine)
            _close(a.cutter, b.cutter)
        f1, f2 = generate_member(getattr(pair, m), pair.blank, 9, 11), generate_member(getattr(pair2, m),
                                                                                      pair2.blank, 9, 11)
        for s in ("concave", "convex"):
            assert np.max(np.abs(f1[s].points - f2[s].points)) < 1e-9
            assert np.max(np.abs(f1[s].normals - f2[s].normals)) < 1e-12


def test_same_tca_from_the_sheet_case(pairs):
    pair, pair2, _ = pairs
    r1, r2 = tca(pair, "concave", steps_per_cycle=16, max_cycles=3.0), tca(pair2, "concave", steps_per_cycle=16,
                                                                        max_cycles=3.0)
    assert np.max(np.abs(r1.te_3 - r2.te_3)) < 1e-12       # rad
    assert np.max(np.abs(r1.phi1_3 - r2.phi1_3)) < 1e-12


def test_sheet_case_errors_name_the_field(pairs):
    _, _, given = pairs
    bad = dict(given, bevel=dict(given["bevel"], settings={**given["bevel"]["settings"]}))
    bad["bevel"]["settings"]["pinion"] = {"concave": {k: v for k, v in given["bevel"]["settings"]["pinion"]
                                                      ["concave"].items() if k != "ratio_of_roll"},
                                          "convex": given["bevel"]["settings"]["pinion"]["convex"]}
    with pytest.raises(CaseError, match="bevel.settings.pinion.concave.ratio_of_roll"):
        bevel_case_from_data(bad, "x")
    bad["bevel"]["settings"]["pinion"]["concave"] = dict(given["bevel"]["settings"]["pinion"]["concave"],
                                                         blade="inside")
    with pytest.raises(CaseError, match="bevel.settings.pinion.concave.blade"):
        bevel_case_from_data(bad, "x")
    nothing = dict(given, bevel={k: v for k, v in given["bevel"].items() if k != "settings"})
    with pytest.raises(CaseError, match="bevel.working"):
        bevel_case_from_data(nothing, "x")
