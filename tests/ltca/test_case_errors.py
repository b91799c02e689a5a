"""Bad case files: exit status 2 and one message that names the field (no traceback)."""
from __future__ import annotations

import subprocess
import sys

import pytest

from fixtures.paths import CASES
from ltca.cli import main

BASE = (CASES / "fzg_c14.toml").read_text()


def _edit(old: str, new: str) -> str:
    assert old in BASE, old
    return BASE.replace(old, new, 1)


BAD = {
    "negative teeth": (_edit("teeth = 16", "teeth = -16"), "pinion.teeth"),
    "zero teeth": (_edit("teeth = 24", "teeth = 0"), "gear.teeth"),
    "tip beyond the rack's reach": (_edit("profile_shift = 0.1817\nface_width_mm = 14.0\ntip_diameter_mm = 82.456",
                                          "profile_shift = 1.2\nface_width_mm = 14.0\ntip_diameter_mm = 95.0"),
                                    "pinion.tip_diameter_mm"),
    "undercut-impossible tooth": (_edit("teeth = 16\nprofile_shift = 0.1817", "teeth = 5\nprofile_shift = -1.0")
                                  .replace("tip_diameter_mm = 82.456\n", "").replace("bore_diameter_mm = 40.0\n", ""),
                                  "pinion.profile_shift"),
    "interfering internal pair": ((CASES / "internal_spur.toml").read_text().replace("teeth = 60", "teeth = 24")
                                  .replace("tip_diameter_mm = 175.0", "tip_diameter_mm = 66.0")
                                  .replace("bore_diameter_mm = 210.0", "bore_diameter_mm = 100.0"), "gear.teeth"),
    "missing field": (_edit("module_mm = 4.5\n", ""), "gear_pair.module_mm"),
    "missing table": (BASE.replace("[load]\ntorque_nm = 200.0\n", ""), "load"),
    "wrong type": (_edit("face_width_mm = 14.0", 'face_width_mm = "wide"'), "pinion.face_width_mm"),
    "integer as float": (_edit("teeth = 16", "teeth = 16.0"), "pinion.teeth"),
    "unknown key": (_edit("[assembly]", "[assembly]\nbacklash_um = 30"), "assembly.backlash_um"),
    "unknown table": (BASE + "\n[lubricant]\nviscosity = 3\n", "lubricant"),
    "negative torque": (_edit("torque_nm = 200.0", "torque_nm = -200.0"), "load.torque_nm"),
    "bad fidelity": (_edit('fidelity = "default"', 'fidelity = "ultra"'), "analysis.fidelity"),
    "poisson out of range": (_edit("poisson_ratio = 0.3", "poisson_ratio = 0.6"), "material.poisson_ratio"),
    "centre distance too small": (_edit("centre_distance_mm = 91.5", "centre_distance_mm = 80.0"),
                                  "assembly.centre_distance_mm"),
    "bore too large": (_edit("bore_diameter_mm = 40.0", "bore_diameter_mm = 70.0"), "pinion.bore_diameter_mm"),
    "not toml": ("this is [not toml", "file"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_case_exits_2_and_names_the_field(name, tmp_path, capsys):
    text, field = BAD[name]
    path = tmp_path / "bad.toml"
    path.write_text(text)
    status = main(["run", str(path), "--out", str(tmp_path / "out"), "--quiet"])
    err = capsys.readouterr().err
    assert status == 2
    assert f"'{field}'" in err, err          # the exact field, quoted
    assert "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_missing_file_and_cli_process(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(BAD["negative teeth"][0])
    proc = subprocess.run([sys.executable, "-m", "ltca.cli", "tca", str(path)], capture_output=True, text=True)
    assert proc.returncode == 2
    assert "pinion.teeth" in proc.stderr and "Traceback" not in proc.stderr
    assert "an integer in [5, 1000]" in proc.stderr
    proc = subprocess.run([sys.executable, "-m", "ltca.cli", "run", str(tmp_path / "nope.toml")],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and "CASE" in proc.stderr


@pytest.mark.parametrize("command", ["run", "tca", "convergence", "validate", "bench", "budget", "chain"])
def test_every_subcommand_has_help(command):
    proc = subprocess.run([sys.executable, "-m", "ltca.cli", command, "--help"], capture_output=True, text=True)
    assert proc.returncode == 0 and "usage: ltca" in proc.stdout
