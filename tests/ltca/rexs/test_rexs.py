"""REXS in and out (ltca.rexs): the published sample models import in every form, their stages become the cases
the file describes, run, and take our results back as REXS 2.0.0 attributes the schema accepts.

The samples (tests/reference/rexs/, see SOURCE.md there) carry the centre distance of each stage; the working
centre distance our model derives from the profile shifts (the zero-backlash mesh, ISO 21771:2007 eq. (57)) must
reproduce it to the digits the file gives.
"""
from __future__ import annotations

import dataclasses
import json
import math
import zipfile
from pathlib import Path

import numpy as np
import pytest

import ltca.rexs as rexs
from fixtures.paths import REFERENCE
from ltca.errors import CaseError
from ltca.rexs.errors import RexsError
from ltca.rexs.io import read_model, write_model
from ltca.rexs.schema import check_model, load_schema

HERE = REFERENCE / "rexs"
FVA2 = HERE / "FVA-Industriegetriebe_2stufig_1-4.rexs"
PLANET = HERE / "FVA_Planetary_stage_-_Minus_gearing_1.1.rexs"
SEW = HERE / "SEW_3-stage_cylindrical_gearbox_1.0.rexs"
SAMPLES = [FVA2, FVA2.with_suffix(".rexsj"), PLANET, PLANET.with_suffix(".rexsj"), SEW]
#: the stages of each sample: gear teeth and normal module the README of the samples states
STAGES = {FVA2.stem: {19: (27, 51, 4.5), 20: (23, 34, 6.5)},
          PLANET.stem: {211: (17, 22, 4.0), 212: (17, 22, 4.0), 213: (17, 22, 4.0),
                        220: (22, 61, 4.0), 221: (22, 61, 4.0), 222: (22, 61, 4.0)},
          SEW.stem: {6: (23, 67, 1.0), 37: (13, 76, 1.25), 55: (14, 87, 1.5)}}


def _same_case(a, b):
    return dataclasses.replace(a, source=None) == dataclasses.replace(b, source=None)


@pytest.mark.parametrize("path", SAMPLES, ids=lambda p: p.name)
def test_sample_imports_every_stage_and_lists_every_attribute(path):
    rx = rexs.read(path)
    assert {s.id: None for s in rx.stages}.keys() == STAGES[path.stem].keys()
    for s in rx.stages:
        z1, z2, m = STAGES[path.stem][s.id]
        case = rx.stage_record(s.id)
        assert (case.pinion.teeth, case.gear.teeth, case.module) == (z1, z2, m)
        assert case.gear.internal == (s.id >= 220 and path.stem == PLANET.stem)
        assert case.torques and all(t > 0 for t in case.torques)
    # nothing silently dropped: every attribute is mapped or listed with a reason
    everything = {(c.id, a) for c in rx.model.components.values() for a in c.attributes}
    listed = {(u.component, u.attribute) for u in rx.unmapped
              if not u.reason.startswith(("load case", "not given"))}      # 'not given': a default the case takes
    assert everything == listed | rx.mapped and not listed & rx.mapped
    assert all(u.reason for u in rx.unmapped)


@pytest.mark.parametrize("stem", [FVA2.stem, PLANET.stem])
def test_xml_and_json_forms_give_identical_cases(stem):
    x, j = rexs.read(HERE / f"{stem}.rexs"), rexs.read(HERE / f"{stem}.rexsj")
    assert [s.id for s in x.stages] == [s.id for s in j.stages]
    for s in x.stages:
        assert _same_case(x.stage_record(s.id), j.stage_record(s.id))


def test_zipped_form_reads_and_writes(tmp_path):
    z = tmp_path / "gearbox.rexsz"
    with zipfile.ZipFile(z, "w") as zf:
        zf.write(FVA2, "model.rexs")
        zf.writestr("notes.txt", "kept")
    rx = rexs.read(z)
    assert rx.model.form == "zip" and _same_case(rx.stage_record(20), rexs.read(FVA2).stage_record(20))
    out = write_model(rx.model, tmp_path / "again.rexsz")
    with zipfile.ZipFile(out) as zf:
        assert sorted(zf.namelist()) == ["model.rexs", "notes.txt"]
    assert _same_case(rexs.read(out).stage_record(19), rx.stage_record(19))


def test_torques_follow_the_gear_train():
    """Torques carried from the input load by the tooth ratios (no losses): the FVA gearbox's second stage
    pinion sits on the intermediate shaft (567 N m x 51/27 in load case 1); the planetary sun torque splits over
    three planets, the planet passes the tooth force to the ring (x 22/17)."""
    fva = {s.id: s.torques_nm for s in rexs.read(FVA2).stages}
    assert fva[19] == (567.0, 345.0, 456.0, 789.0)
    assert np.allclose(fva[20], np.array(fva[19]) * 51 / 27, rtol=1e-12)
    pl = {s.id: s.torques_nm[0] for s in rexs.read(PLANET).stages}
    t_sun = 1591.5494309189535                                 # Belastung [38], the sun shaft's torque
    assert pl[211] == pytest.approx(t_sun / 3, rel=1e-12) and pl[213] == pytest.approx(t_sun / 3, rel=1e-12)
    assert pl[220] == pytest.approx(t_sun / 3 * 22 / 17, rel=1e-12) == pl[222]
    sew = {s.id: s.torques_nm[0] for s in rexs.read(SEW).stages}
    assert sew[37] == pytest.approx(sew[6] * 67 / 23, rel=1e-12)
    assert sew[55] == pytest.approx(sew[37] * 76 / 13, rel=1e-12)


def _digits(text: str) -> int:
    return len(text.split(".")[1]) if "." in text else 0


@pytest.mark.parametrize("path", [FVA2, PLANET, SEW], ids=lambda p: p.name)
def test_derived_geometry_agrees_with_the_file(path):
    from ltca.case import parse_case
    from ltca.cylindrical.model import build_model
    rx = rexs.read(path)
    for s in rx.stages:
        data = rx.stage_dict(s.id)
        text = str(rx.model.components[s.id].attributes["center_distance"].value)
        a_file = float(text)
        data.pop("assembly")                                   # our zero-backlash working centre distance
        model = build_model(parse_case(data))
        assert round(model.pair.a, _digits(text)) == pytest.approx(a_file, abs=1e-9), (s.id, model.pair.a)
        case = rx.stage_record(s.id)
        st = rx.model.components[s.id]
        if st.has("common_face_width"):
            assert st.number("common_face_width", "length") == min(case.pinion.face_width, case.gear.face_width)


def test_implausible_tip_diameter_is_listed_not_used():
    rx = rexs.read(FVA2)
    assert rx.stage_record(20).pinion.tip_diameter is None           # 'tip_diameter' = 1 mm on a 151.8 mm gear
    bad = [u for u in rx.stage_unmapped(20) if u.attribute == "tip_diameter"]
    assert len(bad) == 1 and bad[0].component == 16 and "implausible" in bad[0].reason


@pytest.mark.parametrize("path", [FVA2, SEW, PLANET], ids=lambda p: p.name)
def test_every_stage_builds_a_model_and_meshes(path):
    """Every stage builds our model (tooth generation, bodies' geometry) and meshes without load: the unloaded
    TCA's transverse contact ratio is the tip circles' (ISO 21771 eq. (73)) and the overlap ratio b sin(beta)/(pi m)."""
    from ltca.cylindrical.model import build_model
    from ltca.cylindrical.run import cycle_rolls
    from ltca.cylindrical.tca import unloaded_tca
    from ltca.cylindrical.warnings import check_contact
    rx = rexs.read(path)
    for s in rx.stages:
        case = rx.stage_record(s.id)
        model = build_model(case)
        check_contact(model, path.name)
        r = unloaded_tca(model, cycle_rolls(6, case.pinion.teeth))
        p1, p2, pair = model.pinion, model.gear, model.pair
        ra = [math.sqrt(p.r_tip ** 2 - p.r_base ** 2) for p in (p1, p2)]
        g = ra[0] - ra[1] + pair.a * math.sin(pair.alpha_w) if p2.internal else \
            ra[0] + ra[1] - pair.a * math.sin(pair.alpha_w)
        assert r.eps_alpha == pytest.approx(g / (2 * math.pi * p1.r_base / p1.z), rel=2e-3), s.id
        b = min(case.pinion.face_width, case.gear.face_width)
        assert r.eps_beta == pytest.approx(b * abs(math.sin(case.helix_angle)) / (math.pi * case.module), rel=2e-3)
        assert np.ptp(r.te_arcsec) < 0.05                     # conjugate involutes, no modifications


# ------------------------------------------------------------------------------- loaded run and write-back
#: the sun-planet pair (stage 211) at coarse fidelity, 3 positions: `ltca import` then `ltca run` (the commands in
#: tests/reference/rexs/SOURCE.md); the fast test takes its results.nc and summary.json as input, the slow test runs
#: them anew
SUN_PLANET_RUN = HERE / "sun_planet_211_coarse"


def _check_write_back(run_dir: Path, tmp_path: Path) -> None:
    import xarray as xr

    from ltca.rexs.results import read_results, results_from_dataset, write_results
    for src in (PLANET, PLANET.with_suffix(".rexsj")):
        rx = rexs.read(src)
        case = rx.stage_record(211)
        with xr.open_dataset(run_dir / "results.nc") as ds:
            res = results_from_dataset(ds.load(), case)
        summary = json.loads((run_dir / "summary.json").read_text())
        # the tooth loads add up to the normal force of the torque, T / (r_b1 cos beta_b), at every position
        rb1 = 0.5 * 17 * 4.0 * math.cos(math.radians(20))
        dz = res["face_mm"][1] - res["face_mm"][0]
        assert res["load_distribution_n_per_mm"].sum() * dz == pytest.approx(summary["torque_nm"] * 1e3 / rb1,
                                                                             rel=1e-3)
        # a spur pair without misalignment carries its load nearly uniformly over the face (K_Hbeta = 1 ideally)
        assert 1.0 <= res["face_load_factor"] < 1.1
        assert np.nanmax(res["root_stress_mpa"]["pinion"]) == pytest.approx(summary["max_root_stress_mpa"]["pinion"],
                                                                            rel=1e-6)
        written = write_results(rx.model, 211, 53, 247, res, 22 / 17)
        assert check_model(rx.model, only=written) == []
        out = write_model(rx.model, tmp_path / f"with_results{src.suffix}")
        if src.suffix == ".rexsj":
            assert out.read_bytes()[:3] == b"\xef\xbb\xbf"
        # the written file: every attribute we wrote passes the 2.0.0 schema, and no issue is new
        again = rexs.read(out)
        assert check_model(again.model, only=written) == []
        before = {(i.component, i.attribute, i.problem) for i in check_model(read_model(src))}
        after = {(i.component, i.attribute, i.problem) for i in check_model(again.model)}
        assert after <= before                     # (the 1.x stage_gear_data written is now the 2.0 type)
        # the same case and the same result values
        for s in rx.stages:
            assert _same_case(again.stage_record(s.id), rexs.read(src).stage_record(s.id))
        back = read_results(again.model, 211, 53, 247)
        for key, v in res.items():
            if isinstance(v, dict):
                for k2 in v:
                    np.testing.assert_allclose(back[key][k2], v[k2], rtol=1e-12, err_msg=f"{key}.{k2}")
            else:
                np.testing.assert_allclose(back[key], v, rtol=1e-12, err_msg=key)
        # written twice: replaced, not doubled
        n = len(again.model.components)
        write_results(again.model, 211, 53, 247, res, 22 / 17)
        assert len(again.model.components) == n


def test_results_written_read_back_and_schema_valid(tmp_path):
    _check_write_back(SUN_PLANET_RUN, tmp_path)


@pytest.mark.slow
def test_sun_planet_runs_and_writes_back(tmp_path):
    from ltca.cli import main
    assert main(["import", str(PLANET), "--stage", "211", "--out", str(tmp_path / "s211.toml")]) == 0
    assert main(["run", str(tmp_path / "s211.toml"), "--out", str(tmp_path / "out"), "--fidelity", "coarse",
                 "--positions", "3", "--quiet", "--paraview-steps", "0"]) == 0
    _check_write_back(tmp_path / "out", tmp_path)


# ------------------------------------------------------------------------------- units, modifications
def _edit(path: Path, tmp: Path, old: str, new: str, name: str = "edited.rexs") -> Path:
    text = path.read_text(encoding="utf-8-sig")
    assert old in text, old
    out = tmp / name
    out.write_text(text.replace(old, new, 1), encoding="utf-8")
    return out


def test_declared_units_are_converted(tmp_path):
    f = _edit(FVA2, tmp_path, '<attribute id="normal_module" unit="mm">4.5</attribute>',
              '<attribute id="normal_module" unit="m">0.0045</attribute>')
    f = _edit(f, tmp_path, '<attribute id="helix_angle_reference_diameter" unit="deg">21</attribute>',
              f'<attribute id="helix_angle_reference_diameter" unit="rad">{math.radians(21)!r}</attribute>', "e2.rexs")
    f = _edit(f, tmp_path, '<attribute id="torque_around_u_axis" unit="N m">567</attribute>',
              '<attribute id="torque_around_u_axis" unit="N mm">567000</attribute>', "e3.rexs")
    a, b = rexs.read(f).stage_record(19), rexs.read(FVA2).stage_record(19)
    assert a.module == pytest.approx(b.module, rel=1e-15) and a.helix_angle == pytest.approx(b.helix_angle, rel=1e-15)
    assert a.torques == pytest.approx(b.torques, rel=1e-15)


def test_flank_modifications_are_mapped():
    """A REXS 2.0 helix crowning, tip and root relief, end reliefs and a triangular tip relief referenced by both
    flanks of the pinion become its case keys (shape linear / parabolic: exponent 1 / 2); what the case cannot
    hold is listed as unmapped."""
    from ltca.rexs.model import Attribute, Component, Ref, Relation
    rx = rexs.read(FVA2)
    m = rx.model

    def component(cid, kind, **attrs):
        return Component(cid, kind, kind, {k: Attribute(k, "none" if isinstance(v, str) else "mm", str(v))
                                           for k, v in attrs.items()})
    comps = [
        component(900, "helix_crowning", helix_crowning_amount_datum_face=0.008,
                  helix_crowning_amount_non_datum_face=0.008),
        component(901, "tip_relief", tip_relief_depth=0.012, tip_relief_datum_diameter=136.5, shape_of_relief="linear"),
        component(902, "root_relief", root_relief_depth=0.005, root_relief_datum_diameter=121.0,
                  shape_of_relief="parabolic"),
        component(903, "end_relief_datum_face", end_relief_depth_datum_face=0.010, end_relief_length_datum_face=6.0,
                  shape_of_relief="parabolic"),
        component(904, "end_relief_non_datum_face", end_relief_depth_non_datum_face=0.007,
                  end_relief_length_non_datum_face=5.0),
        component(905, "triangular_tip_relief", triangular_tip_relief_depth=0.009,
                  triangular_tip_relief_datum_diameter=135.0, triangular_tip_relief_datum_length=12.0,
                  triangular_tip_relief_evaluation_reference=136.0),
    ]
    m.components.update({c.id: c for c in comps})
    for flank in (48, 49):
        for c in comps:
            m.relations.append(Relation(None, "reference", (Ref(flank, "origin"), Ref(c.id, "referenced"))))
    from ltca.rexs.stages import stage_case_dict
    data, unmapped, _ = stage_case_dict(m, 19)
    assert data["pinion"]["modifications"] == {
        "lead_crowning_um": pytest.approx(8.0), "tip_relief_um": pytest.approx(12.0),
        "tip_relief_start_diameter_mm": 136.5, "tip_relief_exponent": 1.0,
        "root_relief_um": pytest.approx(5.0), "root_relief_start_diameter_mm": 121.0, "root_relief_exponent": 2.0,
        "end_relief_datum_um": pytest.approx(10.0), "end_relief_datum_length_mm": 6.0, "end_relief_exponent": 2.0,
        "end_relief_non_datum_um": pytest.approx(7.0), "end_relief_non_datum_length_mm": 5.0,
        "triangular_tip_relief_um": pytest.approx(9.0), "triangular_tip_relief_start_diameter_mm": 135.0,
        "triangular_tip_relief_length_mm": 12.0}
    assert {(u.component, u.attribute) for u in unmapped if u.component >= 900} == \
        {(905, "triangular_tip_relief_evaluation_reference")}


def test_a_relief_shape_the_case_cannot_hold_is_named():
    from ltca.rexs.errors import RexsError
    from ltca.rexs.model import Attribute, Component, Ref, Relation
    from ltca.rexs.stages import stage_case_dict
    m = rexs.read(FVA2).model
    m.components[906] = Component(906, "tip_relief", "relief", {
        "tip_relief_depth": Attribute("tip_relief_depth", "mm", "0.012"),
        "shape_of_relief": Attribute("shape_of_relief", "none", "logarithmic")})
    m.relations.append(Relation(None, "reference", (Ref(48, "origin"), Ref(906, "referenced"))))
    with pytest.raises(RexsError, match="shape_of_relief"):
        stage_case_dict(m, 19)


# ------------------------------------------------------------------------------- broken files
def test_missing_gear_is_named(tmp_path):
    f = _edit(FVA2, tmp_path, '<ref hint="cylindrical_gear" id="17" role="gear_2"/>', "")
    with pytest.raises(RexsError, match=r"cylindrical_stage 19 .*gear_2.*missing gear"):
        rexs.read(f)
    text = FVA2.read_text()
    start = text.index('<component id="17"')
    f2 = tmp_path / "no_gear.rexs"
    f2.write_text(text[:start] + text[text.index("</component>", start) + len("</component>"):])
    with pytest.raises(RexsError, match=r"gear_2.*missing gear.*component 17"):
        rexs.read(f2)


def test_unknown_unit_is_named(tmp_path):
    """A stage that cannot be mapped is refused, naming the component and attribute, when it is asked for (the
    file's other stages still import)."""
    f = _edit(FVA2, tmp_path, '<attribute id="normal_module" unit="mm">4.5</attribute>',
              '<attribute id="normal_module" unit="furlong">4.5</attribute>')
    with pytest.raises(RexsError, match=r"cylindrical_gear 15 'Cylindrical gear \[27\]': normal_module.*unknown "
                                        r"unit 'furlong'"):
        rexs.read(f).stage_dict(19)


def test_wrong_value_type_is_named(tmp_path):
    f = _edit(FVA2.with_suffix(".rexsj"), tmp_path, '"id": "number_of_teeth",\n                        "integer": 27',
              '"id": "number_of_teeth",\n                        "string": "twenty-seven"', "bad.rexsj")
    with pytest.raises(RexsError, match=r"cylindrical_gear 15 .*number_of_teeth.*wrong value type 'string'"):
        rexs.read(f).stage_dict(19)
    f = _edit(FVA2, tmp_path, '<attribute id="face_width" unit="mm">50</attribute>',
              '<attribute id="face_width" unit="mm">wide</attribute>')
    with pytest.raises(RexsError, match=r"cylindrical_gear 15 .*face_width.*a number expected"):
        rexs.read(f).stage_dict(19)


def test_schema_checker_finds_wrong_attributes():
    """The checker against the published 2.0.0 database: the JSON planetary sample's converter wrote arrays and
    strings as booleans; the 1.x samples use '°' for 'deg' and the 1.x type stage_gear_data."""
    schema = load_schema()
    assert schema.version == "2.0.0" and len(schema.components) == 96 and len(schema.attributes) == 1824
    issues = check_model(read_model(PLANET.with_suffix(".rexsj")), schema)
    support = [i for i in issues if i.component == 53 and i.attribute == "support_vector"]
    assert support and "boolean" in support[0].problem
    xml = check_model(read_model(PLANET), schema)
    assert any(i.component == 53 and i.attribute == "helix_angle_reference_diameter" and "'°'" in i.problem
               for i in xml)
    assert any(i.problem == "unknown component type 'stage_gear_data'" for i in xml)


def test_cli_import_lists_writes_and_fails_with_status_2(tmp_path, capsys):
    from ltca.case import load_case
    from ltca.cli import main
    assert main(["import", str(SEW), "--list"]) == 0
    assert "stage 37" in capsys.readouterr().out
    assert main(["import", str(SEW), "--stage", "55", "--out", str(tmp_path / "c.toml"), "--torque", "80"]) == 0
    assert _same_case(load_case(tmp_path / "c.toml"), rexs.read(SEW).stage_record(55, 80.0))
    assert main(["import", str(SEW), "--stage", "99"]) == 2
    assert "no stage 99" in capsys.readouterr().err
    broken = _edit(FVA2, tmp_path, '<attribute id="normal_module" unit="mm">4.5</attribute>', "")
    assert main(["import", str(broken), "--stage", "19"]) == 2
    assert "normal_module" in capsys.readouterr().err
    assert issubclass(RexsError, CaseError)


@pytest.mark.slow
@pytest.mark.parametrize("path,stage", [(FVA2, 19), (FVA2, 20), (SEW, 6), (SEW, 37), (SEW, 55), (PLANET, 211),
                                        (PLANET, 220)])
def test_every_stage_runs_loaded(path, stage, tmp_path):
    from ltca.cli import main
    assert main(["import", str(path), "--stage", str(stage), "--out", str(tmp_path / "c.toml")]) == 0
    assert main(["run", str(tmp_path / "c.toml"), "--out", str(tmp_path / "out"), "--fidelity", "coarse",
                 "--positions", "3", "--quiet", "--paraview-steps", "0"]) == 0
    assert json.loads((tmp_path / "out" / "summary.json").read_text())["converged"]


def test_rexs_2_0_tool_and_basic_profile(tmp_path):
    """A REXS 2.0 model: the tool reached through a manufacturing_step from the flanks, its values relative to the
    module or absolute (mm); the basic profile's addendum sets the tip diameter d + 2 m_n (h_aP* + x)."""
    text = FVA2.read_text().replace('version="1.4"', 'version="2.0.0"', 1)
    tool = ('<component id="900" name="hob" type="rack_shaped_tool">'
            '<attribute id="addendum_reference_profile" unit="mm">6.075</attribute>'
            '<attribute id="dedendum_coefficient_reference_profile" unit="none">1.4</attribute>'
            '<attribute id="tip_corner_radius_factor_reference_profile" unit="none">0.3</attribute></component>'
            '<component id="901" name="settings" type="cylindrical_gear_manufacturing_settings"/>')
    steps = "".join(f'<relation id="{950 + k}" order="1" type="manufacturing_step"><ref id="{f}" role="workpiece"/>'
                    f'<ref id="900" role="tool"/><ref id="901" role="manufacturing_settings"/></relation>'
                    for k, f in enumerate((48, 49, 52, 53)))
    text = text.replace("<components>", "<components>" + tool, 1).replace("<relations>", "<relations>" + steps, 1)
    for flank in (48, 49):
        anchor = f'<component id="{flank}" name="Cylindrical gear [27] ({"left" if flank == 48 else "right"} flank)"' \
                 ' type="cylindrical_gear_flank">'
        text = text.replace(anchor, anchor + '<attribute id="addendum_coefficient_basic_profile" unit="none">0.9'
                                             '</attribute>', 1)
    f = tmp_path / "v2.rexs"
    f.write_text(text)
    rx = rexs.read(f)
    assert rx.model.major == 2
    case = rx.stage_record(19)
    assert case.rack_addendum == pytest.approx(6.075) and case.rack_dedendum == pytest.approx(1.4 * 4.5)
    assert case.rack_tip_radius == pytest.approx(0.3 * 4.5)
    d1 = 27 * 4.5 / math.cos(math.radians(21))
    assert case.pinion.tip_diameter == pytest.approx(d1 + 2 * 4.5 * (0.9 + 0.231415), rel=1e-12)
    assert case.gear.tip_diameter is None


def test_byte_order_mark_and_unreadable_files(tmp_path):
    bom = tmp_path / "bom.rexsj"
    bom.write_bytes(b"\xef\xbb\xbf" + FVA2.with_suffix(".rexsj").read_bytes())
    assert _same_case(rexs.read(bom).stage_record(19), rexs.read(FVA2).stage_record(19))
    for name, body, what in (("cut.rexs", FVA2.read_bytes()[:5000], "malformed XML"),
                             ("cut.rexsj", b'{"model": {"version": "1.4", "components": [', "malformed JSON"),
                             ("other.rexs", b"<gear/>", "<model> expected"),
                             ("latin.rexs", "<model version='1.4' date='\u00e9'/>".encode("latin-1"), "not UTF-8")):
        (tmp_path / name).write_bytes(body)
        with pytest.raises(RexsError, match=what):
            rexs.read(tmp_path / name)
    with pytest.raises(RexsError, match="cannot read"):
        rexs.read(tmp_path / "absent.rexs")


def test_torque_record_finds_an_imported_torque():
    """An imported torque has many digits (530.516476972984 N m per planet mesh); summary.json rounds it to 6
    decimals and the torques of a run are not sorted: its record is still found."""
    import xarray as xr

    from ltca.cylindrical.sweep import torque_record
    tq = [530.516476972984, 100.25]
    ds = xr.Dataset({"te_loaded_ptp_um": ("torque", [8.45, 1.74]),
                     "te_mesh_harmonic": (("torque", "mesh_order"), [[1.0, 2.0], [3.0, 4.0]]),
                     "te_mesh_harmonic_um": (("torque", "mesh_order"), [[0.1, 0.2], [0.3, 0.4]])},
                    coords={"torque": tq})
    assert torque_record(ds, {"torque_nm": round(tq[0], 6)})["te_loaded_ptp_um"] == 8.45
    assert torque_record(ds, {"torque_nm": 100.25})["te_mesh_harmonics_um"] == [0.3, 0.4]


def test_a_stage_runs_through_the_one_api():
    """``ltca.rexs.read(path).stage(id)`` is a Case: ``with_values`` edits it and ``ltca.run`` takes it."""
    case = rexs.read(FVA2).stage(19)
    assert case.kind == "cylindrical" and case.record == rexs.read(FVA2).stage_record(19)
    assert case.with_values({"analysis.fidelity": "coarse"}).record.fidelity == "coarse"
