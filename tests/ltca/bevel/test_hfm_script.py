"""Exchange with the HypoidFaceMilled / Transmission3D input script: SpyGO's script of its 19/62 pair read against
the settings tools/compare_spygo.py derives from SpyGO independently, a written sheet read back unchanged, the
shipped pair through the script to the same flanks and TE, and bad scripts named by their line."""
from __future__ import annotations

import dataclasses
import json
import logging
import math
import re

import numpy as np
import pytest
import tomllib

from fixtures.paths import REFERENCE
from ltca.bevel.analysis import build_pair
from ltca.bevel.case import bevel_case_from_data, case_blank
from ltca.bevel.hfm_case import case_data
from ltca.bevel.hfm_export import hfm_text
from ltca.bevel.hfm_script import parse_hfm, read_hfm
from ltca.cli import main
from ltca.errors import CaseError
from ltca.geometry.bevel.blank import BevelBasicData, cone_apexes, design_blank, with_cones
from ltca.geometry.bevel.cutter import HeadCutter
from ltca.geometry.bevel.generation import generate_member, solve_axial_points, surface_state
from ltca.geometry.bevel.machine import MOTIONS, FlankCut, MachineSettings, MemberCut, gear_settings, pinion_settings
from ltca.geometry.bevel.sheet import flank_sheet, member_sheet
from ltca.geometry.bevel.tca import BevelPair, tca
from ltca.geometry.bevel.universal import blade_coordinates

SCRIPT = REFERENCE / "spygo_19x62_hfm.txt"
SPYGO = json.loads((REFERENCE / "spygo_19x62.json").read_text())
BASE = {(v["member"], v["flank"]): v for v in SPYGO["variants"] if v["variant"].startswith("base ")}


def _same_sheet(a: dict, b: dict, rel: float = 1e-12) -> None:
    assert a.keys() == b.keys(), set(a) ^ set(b)
    for k, v in a.items():
        if isinstance(v, str):
            assert b[k] == v, k
        else:
            assert np.allclose(b[k], v, rtol=rel, atol=rel), (k, v, b[k])


def _spygo_cut(d: dict) -> FlankCut:
    c = {k: (float(v) if v == "inf" else v) for k, v in d["cutter"].items()}
    return FlankCut(MachineSettings(**d["machine"]), HeadCutter(**c))


@pytest.fixture(scope="module")
def spygo_case():
    script = read_hfm(SCRIPT)
    data, notes = case_data(script)
    return script, data, notes, bevel_case_from_data(data, str(SCRIPT))


def test_spygo_script_gives_the_settings_compare_spygo_derives(spygo_case):
    """Each flank's sheet equals the one of the settings tools/compare_spygo.py derives from SpyGO's design data
    through SpyGO's own scaling and sign tables (stored in spygo_19x62.json), and the blank's basic data are the
    notebook's (19/62, module 4.169 mm, face 36.83 mm, spiral 35 deg, shaft angle 95 deg, cutter radius 95.25 mm,
    20 deg blades, left-hand pinion)."""
    script, data, notes, case = spygo_case
    for (m, s), v in BASE.items():
        _same_sheet(flank_sheet(_spygo_cut(v["settings"])), script.sheets[m][s])
    b = data["bevel"]
    assert (b["pinion_teeth"], b["gear_teeth"], b["gear_hand"], b["taper"]) == (19, 62, "right", "standard")
    for k, want in (("module_mm", 4.169), ("face_width_mm", 36.83), ("spiral_angle_deg", 35.0),
                    ("shaft_angle_deg", 95.0), ("cutter_radius_mm", 95.25), ("pressure_angle_deg", 20.0)):
        assert b[k] == pytest.approx(want, rel=1e-12), k
    # SpyGO's blank (ISO 23509 depths) is not the Gleason blank the case designs: the case gives its cones
    assert notes == ["gear HAND LEFT (line 144) taken as RIGHT: the pair's hand is the pinion's, LEFT"]
    bl = case_blank(case)
    for m, face, root, t_f, t_r in (("pinion", 19.336171904255103, 15.64096727073747, -2.2196693296425956,
                                     -0.001306176586991889),
                                    ("gear", 79.35903272926254, 75.6638280957449, -0.7474565076452753, 0.0)):
        mb = bl.member(m)
        assert math.degrees(mb.face_angle) == pytest.approx(face, rel=1e-14)
        assert math.degrees(mb.root_angle) == pytest.approx(root, rel=1e-14)
        assert cone_apexes(bl, m) == pytest.approx((t_f, t_r), abs=1e-12)


def test_spygo_gear_cutter_centre_is_the_standard_one_of_the_read_blank(spygo_case):
    """An independent check of the radial setting and cradle angle as read (sign included): the gear cutter centre
    that our own standard settings put at the mean pitch point for the read blank's spiral angle and cutter radius
    (ltca.geometry.bevel.machine.gear_settings) is SpyGO's."""
    script, _, _, case = spygo_case
    std = gear_settings(case_blank(case))
    for s in ("concave", "convex"):
        sheet = script.sheets["gear"][s]
        assert sheet["radial_setting_mm"] == pytest.approx(std.flank(s).machine.radial_setting, rel=1e-12)
        assert sheet["cradle_angle_deg"] == pytest.approx(math.degrees(std.flank(s).machine.cradle_angle), rel=1e-12)


def test_given_cones_are_the_designed_blank_when_they_are_its_own():
    """with_cones of the designed blank's own cones (cone_apexes) is the designed blank (Gleason's formulas)."""
    for taper in ("standard", "uniform"):
        bl = design_blank(BevelBasicData(shaft_angle=math.radians(95.0), taper=taper))
        for m in ("pinion", "gear"):
            mb = bl.member(m)
            again = with_cones(bl, m, mb.face_angle, mb.root_angle, *cone_apexes(bl, m))
            for f in dataclasses.fields(mb):
                x, y = getattr(mb, f.name), getattr(again.member(m), f.name)
                assert x == y if isinstance(x, str) else x == pytest.approx(y, rel=1e-12, abs=1e-12), (m, f.name)
            for k in ("working_depth", "whole_depth", "clearance"):
                assert getattr(again, k) == pytest.approx(getattr(bl, k), rel=1e-12, abs=1e-12), k


def test_spygo_pair_read_from_the_script_cuts_spygo_flanks(spygo_case):
    """The case's pair, at the axial-section points where SpyGO sampled its own flanks: within 0.1 um and 1e-5
    of SpyGO's points and normals (SpyGO's straight pinion blade is an arc of 2e6 mm, 0.03 um of the difference)."""
    pair = build_pair(spygo_case[3])
    for (m, s), v in BASE.items():
        fc = getattr(pair, m).flank(s)
        z, R = np.array(v["z"]), np.array(v["R"])
        P, N = np.array(v["spygo_points"]), np.array(v["spygo_normals"])
        x, ok = solve_axial_points(fc, z, R, blade_coordinates(fc, P, np.array(v["spygo_psi"])), tol=1e-11,
                                   max_iter=60)
        st = surface_state(fc, x[:, 0], x[:, 1], x[:, 2])
        assert len(z) >= 3 and np.max(np.abs(st.f)) < 1e-3
        assert np.max(np.linalg.norm(st.r_w - P, axis=1)) < 1e-4, (m, s)
        assert np.max(np.linalg.norm(st.n_w + N, axis=1)) < 1e-5, (m, s)


def _full_pair(pinion_hand: str, formate_gear: bool) -> BevelPair:
    """A pair whose sheets use every keyword: tilt, swivel, each motion to the 6th order, the modified roll to G,
    curved blades, toprem and flankrem (the gear formate when asked)."""
    bl = design_blank(BevelBasicData(hand="left" if pinion_hand == "right" else "right"))
    gear, pin = gear_settings(bl), pinion_settings(bl)
    full = dict(tilt=0.02, swivel=-0.4, modified_roll_c=0.01, modified_roll_d=-0.02, modified_roll_e=0.3,
                modified_roll_f=-0.5, modified_roll_g=-3.0, radial_motion=(0.5, 0.0, 2.0, -1.0, 3.0, 0.25),
                vertical_motion=(0.1, 0.3, 0.0, 0.0, 0.0, -2.0), helical_motion=(1.0, 0.2, -0.3, 0.4, 5.0, -7.0),
                tilt_motion=(1e-3, 2e-3, 0.0, 0.1), swivel_motion=(0.1, -0.05, 0.0, 0.0, 0.3, 0.7))
    rems = dict(profile_radius=450.0, toprem_depth=1.5, toprem_radius=20.0, flankrem_depth=7.0, flankrem_radius=35.0)

    def cut(mc: MemberCut, formate: bool) -> MemberCut:
        out = {}
        for s in ("concave", "convex"):
            fc = mc.flank(s)
            ms = dataclasses.replace(fc.machine, formate=True, ratio_of_roll=0.0, tilt=0.01, blank_offset=0.3) \
                if formate else dataclasses.replace(fc.machine, blank_offset=-1.5, sliding_base=0.7, **full)
            out[s] = FlankCut(ms, dataclasses.replace(fc.cutter, **rems))
        return MemberCut(mc.member, mc.z, **out)
    return BevelPair(bl, cut(gear, formate_gear), cut(pin, False))


@pytest.mark.parametrize("pinion_hand,formate_gear", [("left", False), ("right", False), ("left", True)])
def test_sheet_written_and_read_back_is_unchanged(pinion_hand, formate_gear):
    pair = _full_pair(pinion_hand, formate_gear)
    script = parse_hfm(hfm_text(pair, "round trip"))
    assert script.pinion_hand == pinion_hand
    for m in ("pinion", "gear"):
        want = member_sheet(getattr(pair, m))
        for s in ("concave", "convex"):
            _same_sheet(want[s], script.sheets[m][s])
    data, notes = case_data(script)
    assert not notes                                # the blank is the one the case designs
    d, b = pair.blank.data, data["bevel"]
    assert b["module_mm"] == pytest.approx(d.module, rel=1e-14)
    assert b["shaft_angle_deg"] == pytest.approx(math.degrees(d.shaft_angle), rel=1e-14)
    assert b["gear_hand"] == d.hand


def _value(text: str, key: str) -> float:
    return float(re.search(rf"^\s*{key} (\S+)$", text, re.M).group(1))


def test_script_numbers_of_a_left_hand_pinion():
    """The written numbers themselves, SpyGO's scaling and signs (DesignData.manage_machine_settings) with the frame
    identity of tools/compare_spygo.py: the pinion's cradle angle, tilt, swivel and blank offset and the gear's tilt
    change sign, the vertical motion on both members; H5, H6 and MODROLL_720G in thousandths; TLTk and SWk in rad."""
    pair = _full_pair("left", False)
    pin, gear = hfm_text(pair).split("TYPE FACEMILLED_GEAR")
    pin = pin.split("CONVEX")[0]
    gear = gear.split("CONVEX")[0]
    pm, gm = pair.pinion.concave.machine, pair.gear.concave.machine
    deg = math.degrees
    for text, ms, s in ((pin, pm, dict(q=-1, i=-1, j=-1, E=-1)), (gear, gm, dict(q=1, i=-1, j=1, E=1))):
        assert _value(text, "CRADLEANGLE") == pytest.approx(s["q"] * deg(ms.cradle_angle), rel=1e-14)
        assert _value(text, "TILTANGLE") == pytest.approx(s["i"] * deg(ms.tilt), rel=1e-14)
        assert _value(text, "SWIVELANGLE") == pytest.approx(s["j"] * deg(ms.swivel), rel=1e-14)
        assert _value(text, "BLANKOFFSET") == pytest.approx(s["E"] * ms.blank_offset, rel=1e-14)
        assert _value(text, "V1") == pytest.approx(-ms.vertical_motion[0], rel=1e-14)
        assert _value(text, "R3") == pytest.approx(ms.radial_motion[2], rel=1e-14)
        assert _value(text, "H5") == pytest.approx(1e3 * ms.helical_motion[4], rel=1e-14)
        assert _value(text, "MODROLL_2C") == pytest.approx(2 * ms.modified_roll_c, rel=1e-14)
        assert _value(text, "MODROLL_720G") == pytest.approx(720e3 * ms.modified_roll_g, rel=1e-14)
        assert _value(text, "TLT2") == pytest.approx(ms.tilt_motion[1], rel=1e-14)
        assert _value(text, "SW5") == pytest.approx(ms.swivel_motion[4], rel=1e-14)


@pytest.mark.parametrize("motions", [False, True])
def test_a_right_hand_pair_is_the_mirror_image_of_the_left_hand_one(motions):
    """The same script read with the other hand cuts the mirror image (y -> -y in the member frame) of each flank:
    basic settings, and tilt, swivel, modified roll and every motion to the 6th order (curved blades, rems)."""
    full = _full_pair("left", False)
    bl = full.blank
    gear = gear_settings(bl)
    if motions:                 # the pinion's sheet uses every keyword; the gear's every roll and motion term
        terms = {k: getattr(full.gear.concave.machine, k) for k in ("modified_roll_c", "modified_roll_d",
                 "modified_roll_e", "modified_roll_f", "modified_roll_g", *MOTIONS)}
        gear = MemberCut("gear", gear.z, **{s: FlankCut(dataclasses.replace(gear.flank(s).machine, swivel=-0.4,
                                                                            **terms), gear.flank(s).cutter)
                                            for s in ("concave", "convex")})
    pair = BevelPair(bl, gear, full.pinion if motions else pinion_settings(bl))
    text = hfm_text(pair)
    assert "HAND_PINION LEFT" in text
    other = parse_hfm(text.replace("HAND_PINION LEFT", "HAND_PINION RIGHT").replace("HAND LEFT", "HAND X")
                      .replace("HAND RIGHT", "HAND LEFT").replace("HAND X", "HAND RIGHT"))
    data, _ = case_data(other)
    mirror = build_pair(bevel_case_from_data(data, "mirror"))
    for m in ("gear", "pinion"):
        a, b = generate_member(getattr(pair, m), bl, 5, 5), generate_member(getattr(mirror, m), mirror.blank, 5, 5)
        for s in ("concave", "convex"):
            assert np.max(np.abs(a[s].points * [1, -1, 1] - b[s].points)) < 1e-9, (m, s)


def test_shipped_pair_through_the_script_cuts_the_same_flanks_and_te(bevel_pair):
    """cases/spiral_bevel_cao2008.toml synthesised, written, read back as a given-settings case: the same flank
    points (1e-9 mm) and unloaded TE."""
    script = parse_hfm(hfm_text(bevel_pair, "spiral_bevel_cao2008"))
    data, notes = case_data(script)
    assert not notes and "blank" not in data["bevel"]            # the cones are the ones the case designs
    pair2 = build_pair(bevel_case_from_data(data, "through the script"))
    for m in ("gear", "pinion"):
        f1, f2 = generate_member(getattr(bevel_pair, m), bevel_pair.blank, 9, 11), \
            generate_member(getattr(pair2, m), pair2.blank, 9, 11)
        for s in ("concave", "convex"):
            assert np.max(np.abs(f1[s].points - f2[s].points)) < 1e-9, (m, s)
    r1 = tca(bevel_pair, "concave", steps_per_cycle=16, max_cycles=3.0)
    r2 = tca(pair2, "concave", steps_per_cycle=16, max_cycles=3.0)
    assert np.max(np.abs(r1.te_3 - r2.te_3)) < 1e-10       # rad


def _edit(old: str, new: str, count: int = 1) -> str:
    text = SCRIPT.read_text()
    assert old in text
    return text.replace(old, new, count)


@pytest.mark.parametrize("text,match", [
    (_edit("RATIOROLL 3.339685914944047", "RATIOROLL 3.33x"),
     r"line 4\d: pinion\.concave\.MACHINE\.RATIOROLL' = '3\.33x': a finite number"),
    (_edit("SWIVELANGLE 0.0", "SPHERICALRADIUS 500.0"),
     r"pinion\.concave\.MACHINE\.SPHERICALRADIUS' = '500\.0': a keyword of the MACHINE block: .*RADIALSETTING"),
    (_edit("TYPE STRAIGHT", "TYPE CURVED"), r"pinion\.concave\.CUTTER\.RHO' = None: required"),
    (_edit("TOPREM_OPTION NONE", "TOPREM_OPTION STRAIGHT"), r"line \d+: .*TOPREM_OPTION' = 'STRAIGHT': one of NONE"),
    (_edit("MODROLL_5040H 0.0", "MODROLL_5040H 1e-3"), r"MODROLL_5040H' = '1e-3': 0: the modified roll is modelled"),
    (_edit("TYPE FACEMILLED_GEAR", "TYPE FACEHOBBED_GEAR"), r"line \d+: .*TYPE' = 'FACEHOBBED_GEAR'"),
    (_edit("\t\t\tGEAR_TYPE generated\n", "\t\t\tGEAR_TYPE generated\n\t\t\tTOOTHTHICKNESS 3\n"),
     r"line \d+: gear\.TOOTHTHICKNESS' = '3': in the gear's section one of GEAR_TYPE"),
    (_edit("USE_SPRD_BLD_THICKNESS TRUE", "USE_SPRD_BLD_THICKNESS FALSE"), r"USE_SPRD_BLD_THICKNESS' = 'FALSE'"),
    (SCRIPT.read_text().rsplit("\t\t\t\tCUTTER", 1)[0],
     r"line \d+: gear\.convex\.CUTTER' = None: a block the script must give"),
])
def test_bad_scripts_name_the_line_and_what_is_allowed(text, match):
    with pytest.raises(CaseError, match=match):
        parse_hfm(text, "bad.txt")


def test_a_hypoid_pair_is_refused_naming_the_line():
    text = _edit("SPIRALANGLE 35.0", "SPIRALANGLE 30.0")
    with pytest.raises(CaseError, match=r"line \d+: pinion\.COMMON\.SPIRALANGLE' = 30\.0: the gear's 35\.0"):
        case_data(parse_hfm(text))


def test_given_cones_that_make_no_blank_are_refused(spygo_case):
    data = spygo_case[1]
    bad = dict(data, bevel=dict(data["bevel"], blank={"pinion": dict(data["bevel"]["blank"]["pinion"],
                                                                     root_angle_deg=18.0)}))
    with pytest.raises(CaseError, match=r"bevel\.blank\.pinion.*pitch angle 17\.4147 deg.*root_angle"):
        bevel_case_from_data(bad, "x")


def test_menus_of_the_program_are_skipped_and_logged(caplog):
    shaft = "\t\tSHAFT\n\t\t\tSHAFT 1\n\t\t\tAXIALPOSNSHAFT -3.0\n\t\t\tSEGMENT\n\t\t\t\tTYPE DEFINEGEOMETRY\n" \
            "\t\t\tEXIT\n\t\tEXIT\n"
    text = _edit("\t\tROTOR 2 \n", "\t\tROTOR 2 \n" + shaft) + "POSTPROC\nCONTACT\nMEMBER 1\nSTART\nEXIT\nEXIT\n"
    with caplog.at_level(logging.INFO, logger="ltca.bevel.hfm_script"):
        script = parse_hfm(text)
    assert script.sheets == read_hfm(SCRIPT).sheets
    assert "SHAFT" in caplog.text and "POSTPROC" in caplog.text and "AXIALPOSNSHAFT" in caplog.text


def test_convert_and_export_commands(tmp_path, capsys):
    """convert writes a case that reads back; export --hfm writes the script of that case, which converts to the
    same sheets; a bad script or a folder as output exits 2 with one line."""
    case = tmp_path / "spygo.toml"
    assert main(["convert", str(SCRIPT), "--out", str(case), "--torque", "100"]) == 0
    text = case.read_text()
    assert "# not carried: gear HAND LEFT" in text and tomllib.loads(text)["load"]["torque_nm"] == [100.0]
    assert tomllib.loads(text)["bevel"]["blank"]["gear"]["face_angle_deg"] == 79.35903272926254
    out = tmp_path / "back.hfm"
    assert main(["export", str(case), "--hfm", str(out)]) == 0
    back, first = read_hfm(out), read_hfm(SCRIPT)
    assert back.sheets == first.sheets
    for m in ("pinion", "gear"):                    # the case's given cones written back
        for k in ("FACEANGLE", "FACEAPEX", "ROOTAPEX", "BASECONEANGLE"):
            assert back.common[m][k] == pytest.approx(first.common[m][k], rel=1e-12, abs=1e-12), (m, k)
    # SpyGO's unsynthesised starting pair has no interior tangency: exit 2 naming its settings, not synthesis targets
    capsys.readouterr()
    assert main(["tca", str(case), "--out", str(tmp_path / "tca")]) == 2
    assert "'bevel.settings.pinion.concave'" in capsys.readouterr().err
    bad = tmp_path / "bad.hfm"
    bad.write_text(_edit("RATIOROLL 3.339685914944047", "RATIOROLL abc"))
    capsys.readouterr()
    for args in (["convert", str(bad)], ["export", str(case), "--hfm", str(tmp_path)], ["export", str(case)],
                 ["convert", str(SCRIPT), "--out", str(tmp_path / "no" / "x.toml")],
                 ["convert", str(SCRIPT), "--out", str(tmp_path)], ["convert", str(SCRIPT), "--torque", "0"]):
        assert main(args) == 2, args
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "Traceback" not in err and err.startswith(f"ltca {args[0]}: error"), err
