"""Several torques first-class (results.nc, summary.json, console, every plot), torque_nm spelling and
--torque, TE in um and harmonics, the transition-zone sampling, and the case-key reference."""
from __future__ import annotations

import contextlib
import io
import json
import re
import warnings

import numpy as np
import pytest

from fixtures.paths import CASES

TORQUES = [100.0, 200.0, 300.0]


@pytest.fixture(scope="module")
def three(tmp_path_factory):
    """The flagship case at three torques in one run (--torque), coarse, 10 positions (4 in every transition zone).
    Every Python warning is recorded (none may be raised) and the console captured."""
    from ltca.cli import main
    out = tmp_path_factory.mktemp("three")
    so, se = io.StringIO(), io.StringIO()
    with warnings.catch_warnings(record=True) as caught, contextlib.redirect_stdout(so), \
            contextlib.redirect_stderr(se):
        warnings.simplefilter("always")
        status = main(["run", str(CASES / "fzg_c14.toml"), "--out", str(out / "run"), "--fidelity", "coarse",
                       "--positions", "10", "--torque", *map(str, TORQUES), "--quiet",
                       "--cache", str(out / "cache")])
    assert status == 0, se.getvalue()
    return out / "run", so.getvalue(), se.getvalue(), [str(w.message) for w in caught]


def _open(run):
    import xarray as xr
    with xr.open_dataset(run / "results.nc", engine="h5netcdf") as ds:
        return ds.load()


@pytest.mark.heavy
def test_no_warnings_printed(three):
    _, _, err, caught = three
    assert caught == [], caught
    assert "Warning" not in err and "warning" not in err, err


def test_results_nc_coordinates_units_no_padding(three):
    run = three[0]
    ds = _open(run)
    assert list(ds.torque.values) == TORQUES and ds.torque.attrs["units"] == "N m"
    assert ds.sizes["position"] == 10 and ds.position.attrs["units"] == "deg"
    np.testing.assert_allclose(np.diff(ds.position.values), 360 / 16 / 10)
    for name in list(ds.data_vars) + list(ds.coords):
        assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
    # one shared flank lattice: no NaN anywhere in the pressure field, no bin empty at every torque and position
    assert np.isfinite(ds.pressure.values).all()
    assert ds.sizes["flank_roll"] <= 240
    for t in TORQUES:
        assert (ds.pressure.sel(torque=t).max(("position", "pinion_tooth")) > 0).any()
    # pressure per position: each position has its own contact
    assert (ds.pressure.max(("pinion_tooth", "flank_roll", "face")) > 0).all()
    # TE in um along the line of action = pinion rotation x base radius; arcsec is the gear's rotation
    from ltca.case import load_case
    from ltca.cylindrical.model import build_model
    m = build_model(load_case(CASES / "fzg_c14.toml"))
    rad = ds.te_loaded.values / 206264.80624709636 * m.pair.ratio
    np.testing.assert_allclose(ds.te_loaded_um.values, rad * m.pinion.r_base * 1e3, rtol=1e-9)
    assert ds.te_mesh_harmonic.dims == ("torque", "mesh_order") and list(ds.mesh_order.values) == [1, 2, 3, 4, 5]
    assert np.isfinite(ds.te_mesh_harmonic.values[:, :4]).all() and np.isnan(ds.te_mesh_harmonic.values[:, 4]).all()
    assert (run / "results.nc").stat().st_size < 1e6


def test_summary_per_torque_equals_netcdf(three):
    run, out, _, _ = three
    ds = _open(run)
    s = json.loads((run / "summary.json").read_text())
    assert [r["torque_nm"] for r in s["torques"]] == TORQUES
    assert s["torque_nm"] == TORQUES[0] and s["te_loaded_ptp_arcsec"] == s["torques"][0]["te_loaded_ptp_arcsec"]
    for r in s["torques"]:
        d = ds.sel(torque=r["torque_nm"])
        assert r["te_loaded_ptp_arcsec"] == pytest.approx(np.ptp(d.te_loaded.values), abs=1e-6)
        assert r["te_loaded_ptp_um"] == pytest.approx(float(d.te_loaded_ptp_um), abs=1e-6)
        assert r["max_contact_pressure_mpa"] == pytest.approx(float(d.max_pressure.max()), abs=1e-6)
        assert r["max_root_stress_mpa"]["pinion"] == pytest.approx(float(d.root_stress_pinion.max()), abs=1e-6)
        assert r["mesh_stiffness_mean_n_per_mm_um"] == pytest.approx(float(d.mesh_stiffness.mean()), abs=1e-6)
        assert r["te_mesh_harmonics_arcsec"][0] == pytest.approx(float(d.te_mesh_harmonic[0]), abs=1e-6)
        assert r["te_mesh_harmonics_arcsec"][4] is None        # not resolved by 10 positions
    ptp = [r["te_loaded_ptp_arcsec"] for r in s["torques"]]
    assert ptp == sorted(ptp)
    # the console prints every torque (table and harmonics)
    for t in TORQUES:
        assert re.search(rf"^\s+{t:g}\s+{s['torques'][TORQUES.index(t)]['te_loaded_ptp_arcsec']:.3f}", out, re.M), out
    assert "loaded TE amplitude per mesh order" in out


def test_every_plot_carries_every_torque(three):
    from ltca.cylindrical.report import plot_data
    run = three[0]
    for f in ("te.png", "te_ptp.png", "te_harmonics.png", "load_sharing.png", "bearing_pattern.png",
              "root_stress.png"):
        assert (run / f).stat().st_size > 10_000, f
    data = plot_data(_open(run))
    assert data["torques"] == TORQUES
    for key in ("te", "load_sharing", "bearing_pattern", "root_stress", "harmonics"):
        assert list(data[key]) == TORQUES, key
    for t in TORQUES:
        x, arcsec, um = data["te"][t]
        assert len(x) == 10 and np.isfinite(arcsec).all() and np.isfinite(um).all()
        assert len(data["load_sharing"][t]) >= 2
        _, _, p = data["bearing_pattern"][t]
        assert p.max() > 0
    assert len(data["te_ptp"][0]) == 3
    # one colour scale for every torque: the largest flank pressure (edge contact saturates it and is marked)
    ds = _open(run)
    assert data["pressure_range"][1] == pytest.approx(float(ds.max_flank_pressure.max()))
    assert data["pressure_range"][1] <= max(data["bearing_pattern"][t][2].max() for t in TORQUES) + 1e-6


def test_torque_spellings(tmp_path):
    from ltca.case import parse_case, read_toml
    from ltca.drivetrain.budget_case import load_budget_case
    from ltca.errors import CaseError
    d = read_toml(CASES / "fzg_c14.toml")
    d["load"] = {"torque_nm": [50, 100.0]}
    assert parse_case(d).torques == (50e3, 100e3)
    for bad, field in (({"torques_nm": [100.0]}, "load.torques_nm"), ({"torque_nm": []}, "load.torque_nm"),
                       ({"torque_nm": [100.0, 100.0]}, "load.torque_nm"), ({}, "load.torque_nm"),
                       ({"torque_nm": [1.0, "2"]}, "load.torque_nm[1]")):
        d["load"] = bad
        with pytest.raises(CaseError) as exc:
            parse_case(d)
        assert exc.value.field == field
    with pytest.raises(CaseError, match="renamed"):
        d["load"] = {"torques_nm": [1.0]}
        parse_case(d)
    p = tmp_path / "b.toml"
    p.write_text((CASES / "budget_wang.toml").read_text().replace("torque_nm = [", "torques_Nm = ["))
    with pytest.raises(CaseError, match="budget.torques_Nm.*renamed"):
        load_budget_case(str(p))
    p.write_text((CASES / "budget_wang.toml").read_text().replace("torque_nm = [2.5, 5.0, 7.5, 10.0]",
                                                                     "torque_nm = 4.0"))
    assert list(load_budget_case(str(p))[1]) == [4.0]


def test_torque_option_is_checked(tmp_path, capsys):
    from ltca.cli import main
    assert main(["run", str(CASES / "fzg_c14.toml"), "--out", str(tmp_path / "o"), "--torque", "-5",
                 "--quiet"]) == 2
    assert "--torque" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_te_harmonics_of_a_known_signal():
    from ltca.cylindrical.sweep import te_harmonics
    n, cycles, z1 = 12, 16, 16
    x = np.arange(n * cycles) / n                       # mesh cycles
    te = 3.0 * np.sin(2 * np.pi * x) + 0.5 * np.cos(2 * np.pi * 3 * x) + 0.25 * np.sin(2 * np.pi * x / z1 * 2)
    mesh, rot = te_harmonics(te, n, cycles, z1)
    np.testing.assert_allclose(mesh, [3.0, 0.0, 0.5, 0.0, 0.0], atol=1e-9)
    np.testing.assert_allclose(rot, [0.0, 0.25, 0.0, 0.0, 0.0], atol=1e-9)
    mesh, rot = te_harmonics(te[:n * 2], n, 2, z1)
    assert rot is None
    mesh, _ = te_harmonics(np.sin(2 * np.pi * np.arange(4) / 4), 4, 1, z1)
    assert np.isfinite(mesh[0]) and np.isnan(mesh[1:]).all()     # order 2 = Nyquist of 4 positions


def test_positions_resolve_the_transition_zones():
    from ltca.case import load_case, parse_case, read_toml
    from ltca.cylindrical.model import build_model
    from ltca.cylindrical.sampling import default_positions, sampling_warnings, transition_zones
    m = build_model(load_case(CASES / "fzg_c14.toml"))
    zones = transition_zones(m)
    assert sum(zones.values()) == pytest.approx(1.0) and min(zones.values()) > 0.4
    assert default_positions(m) == 30 and sampling_warnings(m, 30) == [] and sampling_warnings(m, 10) == []
    assert len(sampling_warnings(m, 8)) == 1 and "at least 10" in sampling_warnings(m, 8)[0]
    # a short tip relief: a narrow zone raises the default and warns at 30
    d = read_toml(CASES / "fzg_c14.toml")
    d["pinion"]["modifications"] = {"tip_relief_um": 10.0, "tip_relief_start_diameter_mm": 82.0}
    d["analysis"].pop("positions")
    c = parse_case(d)
    m = build_model(c)
    assert c.positions_auto and 30 < default_positions(m) <= 120
    assert any("pinion tip-relief range" in w for w in sampling_warnings(m, 30))


def test_case_keys_reference_documents_every_accepted_key(capsys):
    """Every key ltca/case.py accepts (its schema, parsed) is in `ltca keys` and in docs/case_keys.md, which is
    the generated reference verbatim."""
    import ltca.case as case
    from ltca.cli import main
    from ltca.keys import keys_markdown
    accepted = set()
    for top in case._TOP:
        schema = "member" if top in ("pinion", "gear") else top
        accepted |= {f"{top}.{k}" for k in case._SCHEMA[schema]}
        if schema == "member":
            accepted |= {f"{top}.modifications.{k}" for k in case._SCHEMA["modifications"]}
    assert accepted == set(case.case_keys())
    from ltca.design.schema import design_keys
    accepted |= design_keys()          # the [design] table of ltca optimise
    assert main(["keys", "--kind", "cylindrical", "--kind", "design"]) == 0
    text = capsys.readouterr().out
    table = None
    listed = set()
    for line in text.splitlines():
        if line.startswith("["):
            table = line.strip("[]")
        elif line.startswith("  ") and not line.startswith("      "):
            listed.add(f"{table}.{line.split()[0]}")
    assert listed == accepted
    for row in case.key_reference():
        assert row["unit"] and row["meaning"] and row["allowed"] and row["default"], row
    docs = (CASES.parent / "docs" / "case_keys.md").read_text()
    assert docs == keys_markdown(), "docs/case_keys.md is stale: regenerate with `ltca keys --markdown`"
    assert "docs/case_keys.md" in (CASES.parent / "README.md").read_text()
    assert main(["keys", "load"]) == 0 and "torque_nm" in capsys.readouterr().out


def test_example_case_has_every_key_commented():
    import ltca.case as case
    text = (CASES / "example_commented.toml").read_text()
    for row in case.key_reference():
        assert re.search(rf"^#?\s*{row['key']}\s*=", text, re.M), row["key"]


def test_help_texts():
    """Every option has help; no 'seed 00x' jargon; lengths in mm."""
    from ltca.cli import build_parser
    p = build_parser()
    sub = p._subparsers._group_actions[0]
    for name, sp in sub.choices.items():
        assert not re.search(r"seed 00\d", sp.description or ""), name
        for act in sp._actions:
            if act.dest == "help":
                continue
            assert act.help, f"ltca {name} {act.option_strings or act.dest}: no help"
            assert not re.search(r"seed 00\d", act.help), (name, act.help)
            assert not re.search(r"\d m\b(?! N)", act.help), (name, act.help)
    for act in sub._choices_actions:
        assert not re.search(r"seed 00\d", act.help or ""), act.help


@pytest.mark.slow
def test_default_settings_three_torques_under_5_mb(tmp_path):
    """The flagship case at its defaults (default fidelity, 30 positions) and three torques: results.nc < 5 MB,
    no warnings."""
    from ltca.driver import run_to_dir as run_case
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        run_case(str(CASES / "fzg_c14.toml"), out=str(tmp_path / "o"), progress=False, torques=TORQUES)
    assert (tmp_path / "o" / "results.nc").stat().st_size < 5e6
    ds = _open(tmp_path / "o")
    assert ds.sizes["torque"] == 3 and np.isfinite(ds.pressure.values).all()
