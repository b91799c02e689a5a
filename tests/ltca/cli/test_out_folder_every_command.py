"""The output folder of every command that writes, and of every gear kind's ``ltca run``: an ``--out`` that is a file,
a read-only folder (a read-only tmpfs when running as root, whom file modes do not stop) or a folder another run
holds is refused with exit status 2 and one line naming the option, before any computation (within seconds)."""
from __future__ import annotations

import json
import os
import subprocess
import time
from pathlib import Path

import pytest

from fixtures.paths import REFERENCE
from ltca.cli import main

#: (command words before --out): every command with a folder --out, and ltca run of each gear kind
COMMANDS = [
    ("run", "fzg_c14"), ("run", "spiral_bevel_cao2008"), ("run", "eccentric_planetary_satellite"),
    ("tca", "fzg_c14"), ("tca", "spiral_bevel_cao2008"), ("tca", "eccentric_planetary_satellite"),
    ("optimise", "fzg_c14_optimise"), ("study", "fzg_c14_tolerances"), ("budget", "budget_wang"),
    ("chain", "chain_zftkk250"), ("forming", "eccentric_planetary_satellite"), ("convergence", "fzg_c14"),
    ("validate",),
]
FAST_S = 15.0


def _refused(words, out: Path, capsys) -> str:
    t0 = time.perf_counter()
    status = main([*words, "--out", str(out)])
    err = capsys.readouterr().err
    assert status == 2, err
    assert time.perf_counter() - t0 < FAST_S, "refused only after computing"
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err, err
    return err


@pytest.mark.parametrize("words", COMMANDS, ids=lambda w: "-".join(w))
def test_an_out_that_is_a_file_is_refused(tmp_path, capsys, words):
    f = tmp_path / "file"
    f.write_text("x")
    assert "'--out'" in _refused(words, f, capsys)
    assert f.read_text() == "x"


@pytest.fixture
def read_only(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    if os.geteuid() != 0:
        ro.chmod(0o555)
        yield ro
        ro.chmod(0o755)
        return
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "ro,size=64k", "tmpfs", str(ro)],
                      capture_output=True).returncode != 0:
        pytest.skip("cannot mount a read-only tmpfs here")
    try:
        yield ro
    finally:
        subprocess.run(["umount", str(ro)])


@pytest.mark.parametrize("words", COMMANDS, ids=lambda w: "-".join(w))
def test_a_read_only_folder_is_refused_before_any_work(read_only, capsys, words):
    assert "'--out'" in _refused(words, read_only / "out", capsys)


@pytest.mark.parametrize("case", ["spiral_bevel_cao2008", "eccentric_planetary_satellite"])
def test_a_folder_another_run_holds_is_refused(tmp_path, capsys, case):
    out = tmp_path / "out"
    out.mkdir()
    holder = subprocess.Popen(["sleep", "60"])
    try:
        (out / ".ltca.lock").write_text(json.dumps({"pid": holder.pid, "host": os.uname().nodename,
                                                    "started": "now", "command": "ltca run"}))
        err = _refused(["run", case, "--quiet"], out, capsys)
        assert ".ltca.lock" in err and str(holder.pid) in err
        assert sorted(p.name for p in out.iterdir()) == [".ltca.lock"]
    finally:
        holder.kill()
        holder.wait()


def test_import_refuses_a_folder_or_a_missing_folder_for_its_case_file(tmp_path, capsys):
    rexs = REFERENCE / "rexs" / "FVA-Industriegetriebe_2stufig_1-4.rexs"
    assert "a file to write, not a folder" in _refused(["import", str(rexs), "--stage", "19"], tmp_path, capsys)
    assert "existing folder" in _refused(["import", str(rexs), "--stage", "19"], tmp_path / "no" / "c.toml", capsys)
