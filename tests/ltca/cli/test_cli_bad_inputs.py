"""Bad inputs to every command: the expected exit status and the field named (one line, no
traceback). Cheap: validation, geometry and unloaded TCA only; the bevel TCA is not run (15 s)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import pytest

from fixtures.paths import CASES
from ltca.cli import main

C14 = (CASES / "fzg_c14.toml").read_text()
BEVEL = (CASES / "spiral_bevel_cao2008.toml").read_text()
BUDGET = (CASES / "budget_wang.toml").read_text()
CHAIN = (CASES / "chain_zftkk250.toml").read_text()


def _sub(text: str, old: str, new: str) -> str:
    assert old in text, old
    return text.replace(old, new, 1)


def _run(tmp_path, argv, text: str | bytes, capsys):
    path = tmp_path / "case.toml"
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    argv = [a.replace("CASE", str(path)) for a in argv]
    status = main(argv)
    cap = capsys.readouterr()
    return status, cap.out, cap.err


TCA = ["tca", "CASE", "--positions", "3"]
BEV = ["tca", "CASE"]

BAD_INPUTS = {
    # tracebacks
    "non-UTF-8 (tca)": (TCA, C14.encode().replace(b"FZG C14", b"FZG \xff C14", 1), 2, "'file'"),
    "non-UTF-8 (budget)": (["budget", "CASE"], BUDGET.encode() + b"\n# \xc3\x28\n", 2, "'file'"),
    "non-UTF-8 (chain)": (["chain", "CASE"], b"\xe2\x82" + CHAIN.encode(), 2, "'file'"),
    "deeply nested array": (TCA, C14 + "\n[x]\nv = " + "[" * 3000 + "1" + "]" * 3000 + "\n", 2, "'file'"),
    "bevel te_magnitude 1000": (BEV, _sub(BEVEL, "te_magnitude_arcsec = 8.25", "te_magnitude_arcsec = 1000"), 2,
                                "'bevel.working.te_magnitude_arcsec'"),
    "bevel ellipse inf": (BEV, _sub(BEVEL, "ellipse_major_mm = 6.0", "ellipse_major_mm = inf"), 2,
                          "'bevel.working.ellipse_major_mm'"),
    "bevel spiral 0": (BEV, _sub(BEVEL, "spiral_angle_deg = 35.0", "spiral_angle_deg = 0"), 2,
                       "'bevel.spiral_angle_deg'"),
    "bevel spiral 60": (BEV, _sub(BEVEL, "spiral_angle_deg = 35.0", "spiral_angle_deg = 60"), 2,
                        "'bevel.spiral_angle_deg'"),
    "bevel path 79": (BEV, _sub(BEVEL, "path_angle_deg = 22.0", "path_angle_deg = 79"), 2,
                      "'bevel.working.path_angle_deg'"),
    "bevel blank offset 100": (BEV, _sub(BEVEL, "blank_offset_mm = 0.0", "blank_offset_mm = 100"), 2,
                               "'bevel.blank_offset_mm'"),
    "bevel 5 pinion teeth": (BEV, _sub(BEVEL, "pinion_teeth = 12", "pinion_teeth = 5"), 2, "'bevel.pinion_teeth'"),
    "budget torque inf": (["budget", "CASE"], _sub(BUDGET, "[2.5, 5.0, 7.5, 10.0]", "[2.5, inf]"), 2,
                          "'budget.torque_nm[1]'"),
    "tca centre distance 105": (TCA, _sub(C14, "centre_distance_mm = 91.5", "centre_distance_mm = 105.0"), 2,
                                "'assembly.centre_distance_mm'"),
    "run centre distance 105": (["run", "CASE", "--out", "OUT", "--quiet"],
                                _sub(C14, "centre_distance_mm = 91.5", "centre_distance_mm = 105.0"), 2,
                                "'assembly.centre_distance_mm'"),
    # hangs
    "tca --positions 100000": (["tca", "CASE", "--positions", "100000"], C14, 2, "2000"),
    "backlash positions 100000": (["budget", "CASE"], _sub(BUDGET, "positions_per_cycle = 6",
                                                           "positions_per_cycle = 100000"), 2,
                                  "'backlash.positions_per_cycle'"),
    "backlash cycles 100000": (["budget", "CASE"], _sub(BUDGET, "cycles = 0", "cycles = 100000"), 2,
                               "'backlash.cycles'"),
    # exit 0 with absurd output
    "tca centre distance 1e4": (TCA, _sub(C14, "centre_distance_mm = 91.5", "centre_distance_mm = 1e4"), 2,
                                "'assembly.centre_distance_mm'"),
    "tca centre distance 1e9": (TCA, _sub(C14, "centre_distance_mm = 91.5", "centre_distance_mm = 1e9"), 2,
                                "'assembly.centre_distance_mm'"),
    "bevel case.name nan": (BEV, _sub(BEVEL, 'name = "Spiral bevel, Cao et al. 2008 targets"', "name = nan"), 2,
                            "'case.name'"),
    "budget stiffness 1e-300": (["budget", "CASE"], _sub(BUDGET, "stiffness_Nm_per_deg = 289.44",
                                                         "stiffness_Nm_per_deg = 1e-300"), 2,
                                "'member[1].stiffness_Nm_per_deg'"),
    "budget stiffness 1e300": (["budget", "CASE"], _sub(BUDGET, "stiffness_Nm_per_rad = 1.87e4",
                                                        "stiffness_Nm_per_rad = 1e300"), 2,
                               "'member[3].stiffness_Nm_per_rad'"),
    "budget torque 1e300": (["budget", "CASE"], _sub(BUDGET, "[2.5, 5.0, 7.5, 10.0]", "[1e300]"), 2,
                            "'budget.torque_nm[0]'"),
    "budget base radius 1e-300": (["budget", "CASE"], _sub(BUDGET, "base_radius_mm = 80.0",
                                                           "base_radius_mm = 1e-300"), 2,
                                  "'member[0].base_radius_mm'"),
    "chain diameter 1e300": (["chain", "CASE"], _sub(CHAIN, "pitch_diameter_mm = 96.0", "pitch_diameter_mm = 1e300"),
                             2, "pitch_diameter_mm'"),
    "chain teeth huge": (["chain", "CASE"], _sub(CHAIN, "workpiece_teeth = 15", "workpiece_teeth = 1000000000"), 2,
                         "'chain[0].workpiece_teeth'"),
    "pinion bore 0.001": (TCA, _sub(C14, "bore_diameter_mm = 40.0", "bore_diameter_mm = 0.001"), 2,
                          "'pinion.bore_diameter_mm'"),
    # accepted silently
    "torque_nm and torques_nm": (TCA, _sub(C14, "torque_nm = 200.0", "torque_nm = 200.0\ntorques_nm = [100.0]"), 2,
                                 "'load.torques_nm'"),
    "pitch keys 1 and 01": (TCA, _sub(C14, "[gear]", "[pinion.modifications]\npitch_errors_um = {1 = 5.0, 01 = 5.0}"
                                                        "\n\n[gear]"), 2, "'pinion.modifications.pitch_errors_um.01'"),
    "pitch tooth 99 of 16": (TCA, _sub(C14, "[gear]", "[pinion.modifications]\npitch_errors_um = {99 = 5.0}\n\n[gear]"),
                             2, "'pinion.modifications.pitch_errors_um.99'"),
    "tip relief start inside the root": (TCA, _sub(C14, "[gear]", "[pinion.modifications]\ntip_relief_um = 10.0\n"
                                                   "tip_relief_start_diameter_mm = 60.0\n\n[gear]"), 2,
                                         "'pinion.modifications.tip_relief_start_diameter_mm'"),
    "unknown [bevel.*] table": (BEV, BEVEL + "\n[bevel.extra]\nfoo = 1\n", 2, "'bevel.extra'"),
    "bevel [case] name of wrong type": (BEV, _sub(BEVEL, 'name = "Spiral bevel, Cao et al. 2008 targets"', "name = 3"),
                                        2, "'case.name'"),
    "bevel [case] unknown key": (BEV, _sub(BEVEL, "[case]", "[case]\nauthor = 1"), 2, "'case.author'"),
    "budget title a table": (["budget", "CASE"], _sub(BUDGET, 'title = "Wang et al. test rig, Table 2 '
                                                      'stiffnesses"', "title = {a = 1}"), 2, "'budget.title'"),
    # unclear errors
    "cutter tip radius at 30 deg": (TCA, _sub(_sub(C14, "pressure_angle_deg = 20.0", "pressure_angle_deg = 30.0"),
                                              "tip_radius = 0.38", "tip_radius = 0.6"), 2, "'cutter.tip_radius'"),
    "wrong kind (budget to tca)": (TCA, BUDGET, 2, "a budget case"),
    "wrong kind (cylindrical to chain)": (["chain", "CASE"], C14, 2, "a cylindrical case"),
    "wrong kind (chain to budget)": (["budget", "CASE"], CHAIN, 2, "ltca chain"),
}


@pytest.mark.parametrize("name", sorted(BAD_INPUTS))
def test_bad_input_exit_status_and_field(name, tmp_path, capsys):
    argv, text, status, field = BAD_INPUTS[name]
    argv = [a.replace("OUT", str(tmp_path / "out")) for a in argv]
    if "100000" in argv:                 # argparse: exit 2 through SystemExit
        with pytest.raises(SystemExit) as exc:
            _run(tmp_path, argv, text, capsys)
        assert exc.value.code == 2
        assert field in capsys.readouterr().err
        return
    t0 = time.perf_counter()
    got, out, err = _run(tmp_path, argv, text, capsys)
    assert got == status, err
    assert field in err, err
    assert "Traceback" not in err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and len(lines[0]) < 600, err
    assert time.perf_counter() - t0 < 20
    if argv[0] == "run":
        assert not (tmp_path / "out" / "positions").exists()      # refused before any FE work


def test_undercut_pinion_warns(tmp_path, capsys):
    """x = -0.8 at z = 16: heavily undercut; the contact ratio of the tip formula is flagged, in the summary too."""
    text = _sub(_sub(C14, "profile_shift = 0.1817", "profile_shift = -0.8"), "tip_diameter_mm = 82.456\n", "")
    text = _sub(text, "centre_distance_mm = 91.5\n", "")
    status, out, err = _run(tmp_path, ["tca", "CASE", "--positions", "3", "--out", str(tmp_path / "o")], text, capsys)
    assert status == 0, err
    head = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert any("undercut" in w for w in head["warnings"]), head["warnings"]
    assert "warning" in err and "undercut" in err


def test_contact_pressure_warning():
    from types import SimpleNamespace

    from ltca.cylindrical.warnings import pressure_warnings
    case = SimpleNamespace(young=206000.0)
    w = pressure_warnings(case, {"max_contact_pressure_mpa": 15000.0, "torque_nm": 200.0,
                                 "max_root_stress_mpa": {"pinion": 300.0, "gear": 250.0},
                                 "mesh_stiffness_mean_n_per_mm_um": 0.01})
    assert any("contact pressure 15000" in x for x in w) and any("mesh stiffness" in x for x in w)


def test_exception_exit_statuses(monkeypatch, capsys):
    """MeshingError/ContactError: 2 with fields and advice; non-converged contact: 3 with its residual; a bug: 1,
    with the traceback and a line asking for a report."""
    import ltca.cli as cli
    from ltca.fem.contact import ContactNotConverged
    from ltca.geometry.bevel.generation import MeshingError
    from ltca.geometry.bevel.tca import ContactError
    for exc, status, text in ((MeshingError("Newton lost the flank"), 2, "'bevel.spiral_angle_deg'"),
                              (ContactError("path leaves the flank"), 2, "'bevel.working.path_angle_deg'"),
                              (ContactNotConverged(3.2e-4, 80), 3, "3.200e-04"),
                              (OSError(28, "No space left on device", "results.nc"), 2, "No space left"),
                              (ZeroDivisionError("oops"), 1, "please report")):
        def boom(a, exc=exc):
            raise exc
        monkeypatch.setattr(cli, "_cmd_chain", boom)
        p = cli.build_parser()
        p._subparsers._group_actions[0].choices["chain"].set_defaults(func=boom)
        monkeypatch.setattr(cli, "build_parser", lambda p=p: p)
        assert cli.main(["chain", "x.toml"]) == status
        err = capsys.readouterr().err
        assert text in err, err
        assert ("Traceback" in err) == (status == 1)


def test_torque_1e3_lattice_bounded():
    """A torque of 1e-3 N m: the Hertz width is tiny, the pressure lattice is not (924 MB before)."""
    from ltca.cylindrical.results import MAX_LATTICE
    from ltca.sizing import estimate_run_bytes
    assert MAX_LATTICE <= 300
    assert estimate_run_bytes(30, 1, 1, 14) < 100e6


def test_size_guard(tmp_path, capsys):
    text = _sub(_sub(C14, "positions = 30", "positions = 2000"), "[analysis]", "[analysis]\ncycles = 1000")
    status, out, err = _run(tmp_path, ["run", "CASE", "--out", str(tmp_path / "o"), "--quiet"], text, capsys)
    assert status == 2 and "'analysis." in err
    text = _sub(C14, "positions = 30", "positions = 600")
    status, out, err = _run(tmp_path, ["run", "CASE", "--out", str(tmp_path / "o"), "--quiet",
                                       "--max-output-gb", "0.01"], text, capsys)
    assert status == 2 and "--max-output-gb" in err, err


def test_cli_process_non_utf8(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_bytes(b"\xff\xfe" + C14.encode())
    proc = subprocess.run([sys.executable, "-m", "ltca.cli", "tca", str(path)], capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(CASES.parent)})
    assert proc.returncode == 2 and "UTF-8" in proc.stderr and "Traceback" not in proc.stderr
