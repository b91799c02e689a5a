"""Fault tests of ``ltca run``: SIGKILL then --resume (identical results, only the missing positions
computed), a second run on a locked --out, a read-only or file --out refused before any FE work, a full disk
(small tmpfs; skipped where mounting is not allowed) leaving no truncated file under a final name."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from fixtures.paths import CASES, ROOT
from ltca.cli import main

CASE = str(CASES / "fzg_c14.toml")
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "OMP_NUM_THREADS": "1"}
N = 12


def _cmd(out: Path, cache: Path, *extra: str) -> list[str]:
    return [sys.executable, "-m", "ltca.cli", "run", CASE, "--out", str(out), "--fidelity", "coarse",
            "--positions", str(N), "--cache", str(cache), "--quiet", *extra]


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    return tmp_path_factory.mktemp("mesh_cache")


def _lines(p: Path) -> int:
    try:
        return p.read_bytes().count(b"\n")
    except OSError:
        return 0


@pytest.mark.heavy
def test_sigkill_then_resume_is_identical(tmp_path, cache):
    import xarray as xr
    ref, cut = tmp_path / "ref", tmp_path / "cut"
    proc = subprocess.run(_cmd(ref, cache), capture_output=True, text=True, env=ENV, timeout=300)
    assert proc.returncode == 0, proc.stderr
    # the same run, killed (SIGKILL: no chance to clean up) after a few positions
    p = subprocess.Popen(_cmd(cut, cache), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=ENV)
    t0 = time.time()
    while _lines(cut / "positions.jsonl") < 3 and p.poll() is None and time.time() - t0 < 240:
        time.sleep(0.01)
    p.send_signal(signal.SIGKILL)
    p.wait()
    done = _lines(cut / "positions.jsonl")
    assert 3 <= done < N, f"killed after {done} positions"
    from ltca.outputs import read_status
    assert read_status(cut)["status"] == "interrupted"
    assert not (cut / "summary.json").exists() and not (cut / "results.nc").exists()
    proc = subprocess.run(_cmd(cut, cache, "--resume"), capture_output=True, text=True, env=ENV, timeout=300)
    assert proc.returncode == 0, proc.stderr
    head = json.loads((cut / "summary.json").read_text())
    assert head["positions_taken_over"] >= done - 1            # the last one may have been torn by the kill
    assert head["positions_computed"] == N - head["positions_taken_over"]
    print(f"\nresume: {head['positions_taken_over']} positions taken over, {head['positions_computed']} computed")
    a, b = xr.open_dataset(ref / "results.nc"), xr.open_dataset(cut / "results.nc")
    for name in a.data_vars:
        np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)
    assert _lines(cut / "positions.jsonl") == N
    assert json.loads((cut / "run.json").read_text())["status"] == "complete"
    # a resume with other settings is refused
    proc = subprocess.run(_cmd(cut, cache, "--resume", "--fidelity", "default"), capture_output=True, text=True,
                          env=ENV, timeout=120)
    assert proc.returncode == 2 and "--resume" in proc.stderr and "fidelity" in proc.stderr


def test_second_run_on_locked_out(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    holder = subprocess.Popen(["sleep", "60"])
    try:
        (out / ".ltca.lock").write_text(json.dumps({"pid": holder.pid, "host": os.uname().nodename,
                                                    "started": "now", "command": "ltca run"}))
        t0 = time.perf_counter()
        status = main(["run", CASE, "--out", str(out), "--quiet", "--fidelity", "coarse", "--positions", "2"])
        err = capsys.readouterr().err
        assert status == 2 and ".ltca.lock" in err and str(holder.pid) in err, err
        assert time.perf_counter() - t0 < 10 and not (out / "positions").exists()
    finally:
        holder.kill()
        holder.wait()


def test_stale_lock_of_a_dead_process_is_taken_over(tmp_path):
    from ltca.outputs import RunDir
    p = subprocess.Popen(["true"])
    p.wait()
    (tmp_path / ".ltca.lock").write_text(json.dumps({"pid": p.pid, "host": os.uname().nodename}))
    with RunDir(tmp_path, "test", {"x": 1}) as rd:
        assert json.loads(rd.lock.read_text())["pid"] == os.getpid()
    assert not (tmp_path / ".ltca.lock").exists()
    assert json.loads((tmp_path / "run.json").read_text())["status"] == "complete"


def test_out_is_a_file(tmp_path, capsys):
    f = tmp_path / "file"
    f.write_text("x")
    t0 = time.perf_counter()
    assert main(["run", CASE, "--out", str(f), "--quiet"]) == 2
    assert "'--out'" in capsys.readouterr().err and time.perf_counter() - t0 < 10


def _mount_tmpfs(path: Path, opts: str) -> bool:
    path.mkdir(exist_ok=True)
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", opts, "tmpfs", str(path)], capture_output=True)
    return r.returncode == 0


def test_read_only_out_before_any_fe_work(tmp_path, capsys):
    ro = tmp_path / "ro"
    if os.geteuid() != 0:
        ro.mkdir()
        ro.chmod(0o555)
    elif not _mount_tmpfs(ro, "ro,size=64k"):
        pytest.skip("cannot mount a read-only tmpfs here")
    try:
        t0 = time.perf_counter()
        status = main(["run", CASE, "--out", str(ro / "out"), "--quiet"])
        err = capsys.readouterr().err
        assert status == 2 and "'--out'" in err, err
        assert time.perf_counter() - t0 < 10
    finally:
        if os.geteuid() == 0:
            subprocess.run(["umount", str(ro)])


# the disk fills: writing the positions, writing results.nc, writing the VTU files and the report
@pytest.mark.parametrize("size", ["100k", *(pytest.param(s, marks=pytest.mark.heavy) for s in ("120k", "600k", "2600k"))])
def test_full_disk_leaves_no_truncated_file(tmp_path, cache, size):
    if os.geteuid() != 0:
        pytest.skip("mounting a tmpfs needs root")
    full = tmp_path / "full"
    if not _mount_tmpfs(full, f"size={size}"):
        pytest.skip("cannot mount a tmpfs here")
    try:
        out = full / "out"
        cmd = _cmd(out, cache)
        cmd[cmd.index("--positions") + 1] = "3"
        proc = subprocess.run(cmd, capture_output=True, text=True, env=ENV, timeout=300)
        assert proc.returncode == 2, proc.stderr
        assert "No space left" in proc.stderr and "Traceback" not in proc.stderr
        st = json.loads((out / "run.json").read_text())
        assert st["status"] == "failed"
        for name in ("summary.json", "results.nc", "pinion_loaded.vtu", "gear_loaded.vtu", "te.png"):
            assert not (out / name).exists(), name           # nothing half-written under a final name
        assert not list(out.glob(".staging-*"))
        for line in (out / "positions.jsonl").read_text().splitlines():
            json.loads(line)                                  # no torn line
    finally:
        subprocess.run(["umount", str(full)])
