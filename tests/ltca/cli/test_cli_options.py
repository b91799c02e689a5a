"""Command-line options validated like case fields: one line naming the option, its value and what is allowed,
exit status 2, before any work (no traceback, no option silently switching a guard off)."""
from __future__ import annotations

import time

import pytest

from fixtures.paths import CASES, ROOT
from ltca.cli import main

BEVEL = str(CASES / "spiral_bevel_cao2008.toml")
FZG = str(CASES / "fzg_c14.toml")
STUDY = str(ROOT / "studies" / "fzg_torque_misalignment.toml")


def _cases(tmp):
    afile = tmp / "afile"
    afile.write_text("x")
    notjson = tmp / "bad.json"
    notjson.write_text("{not json")
    binary = tmp / "bin.json"
    binary.write_bytes(b"\xff\xfe\x00")
    return [   # (argv, the option the message must name)
        (["run", BEVEL, "--torque", "0"], "--torque"),
        (["run", BEVEL, "--torque", "nan"], "--torque[0]"),
        (["run", BEVEL, "--torque", "100", "100"], "--torque"),
        (["run", FZG, "--torque", "inf"], "--torque[0]"),
        (["run", FZG, "--torque", "-5"], "--torque[0]"),
        (["run", FZG, "--cache", str(afile)], "--cache"),
        (["run", FZG, "--max-output-gb", "nan"], "--max-output-gb"),
        (["run", FZG, "--max-output-gb", "-1"], "--max-output-gb"),
        (["run", FZG, "--max-output-gb", "inf"], "--max-output-gb"),
        (["study", STUDY, "--scheduler", "tcp://bad host:::"], "--scheduler"),
        (["study", STUDY, "--scheduler", "tcp://127.0.0.1"], "--scheduler"),
        (["study", STUDY, "--scheduler", "tcp://127.0.0.1:99999"], "--scheduler"),
        (["validate", "--reference", "calculix", "--band", "nan"], "--band"),
        (["validate", "--reference", "calculix", "--threads", "0"], "--threads"),
        (["validate", "--reference", "calculix", "--positions", "inf"], "--positions[0]"),
    ]


def test_bad_options_one_line_exit_2(tmp_path, capsys):
    for argv, option in _cases(tmp_path):
        t0 = time.perf_counter()
        status = main([*argv, "--out", str(tmp_path / "out")])
        err = capsys.readouterr().err
        lines = err.strip().splitlines()
        assert status == 2, (argv, err)
        assert len(lines) == 1 and f"'{option}'" in lines[0] and "Traceback" not in err, (argv, err)
        assert time.perf_counter() - t0 < 15, argv          # before any FE work


def test_argparse_errors_are_one_line(capsys):
    with pytest.raises(SystemExit) as exc:
        main(["run", FZG, "--positions", "abc"])
    err = capsys.readouterr().err.strip().splitlines()
    assert exc.value.code == 2 and len(err) == 1 and "--positions" in err[0], err


@pytest.mark.parametrize("text,field", [
    ('[study]\ncase = "{case}"\ntorque_nm = 100\n[[variants]]\n"pinion.modifications.lead_crowning_um" = 5.0\n',
     "variants[0].name"),
    ('[study]\ncase = "{long}.toml"\ntorque_nm = 100\n', "study.case"),
    ('[study]\ncase = "{case}"\nname = ""\ntorque_nm = 100\n', "study.name"),
])
def test_study_file_fields(tmp_path, capsys, text, field):
    p = tmp_path / "s.toml"
    p.write_text(text.format(case=FZG, long="a" * 5000))
    assert main(["study", str(p), "--out", str(tmp_path / "o"), "--workers", "1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"'{field}'" in err[0], err


@pytest.mark.heavy
def test_impossible_study_variant_one_line_no_dask_noise(tmp_path):
    """A variant the geometry cannot make (a pinion profile shift whose tips reach the gear root at the case's
    centre distance): exit 2 and only the one line, no Dask worker traceback or dashboard warning."""
    import os
    import subprocess
    import sys
    p = tmp_path / "impossible.toml"
    p.write_text(f'[study]\ncase = "{FZG}"\ntorque_nm = 100\n[set]\n"analysis.positions" = 2\n'
                 '"analysis.fidelity" = "coarse"\n[[variants]]\nname = "pointed"\n"pinion.profile_shift" = 1.5\n')
    proc = subprocess.run([sys.executable, "-m", "ltca.cli", "study", str(p), "--out", str(tmp_path / "o"),
                           "--workers", "1", "--no-plots", "--quiet"], capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(ROOT)}, timeout=300)
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 2 and len(lines) == 1, proc.stderr
    assert "'assembly.centre_distance_mm'" in lines[0], lines
