"""``ltca run`` of a bevel case interrupted by SIGINT (Ctrl-C) after its first positions were stored, then
``--resume``: run.json says interrupted, the resumed run takes over what was stored and computes the rest, and
its results equal an uninterrupted run's to 1e-12. Coarse fidelity, 6 positions; the reference run goes side by
side with the interrupted one (each synthesises the pinion and computes the compliance: minutes on a busy
machine)."""
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

from fixtures.paths import ROOT

CASE = str(ROOT / "cases" / "spiral_bevel_cao2008.toml")
ENV = {**os.environ, "PYTHONPATH": str(ROOT), "OMP_NUM_THREADS": "1"}
N = 6


def _cmd(out: Path, *extra: str) -> list[str]:
    return [sys.executable, "-m", "ltca.cli", "run", CASE, "--out", str(out), "--fidelity", "coarse",
            "--positions", str(N), "--torque", "175", "--quiet", *extra]


def _stored(out: Path) -> int:
    d = out / "positions"
    return len(list(d.glob("*.pkl"))) if d.is_dir() else 0


@pytest.mark.slow
def test_bevel_sigint_then_resume_is_identical(tmp_path):
    import xarray as xr

    from ltca.outputs import read_status
    ref, cut = tmp_path / "ref", tmp_path / "cut"
    whole = subprocess.Popen(_cmd(ref), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=ENV)
    p = subprocess.Popen(_cmd(cut), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, env=ENV)
    try:
        t0 = time.time()
        while _stored(cut) < 1 and p.poll() is None and time.time() - t0 < 900:
            time.sleep(0.01)
        p.send_signal(signal.SIGINT)
        _, err = p.communicate(timeout=120)
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == 130, err
    done = _stored(cut)
    assert 1 <= done < N, f"interrupted after {done} positions"
    st = read_status(cut)
    assert st["status"] == "interrupted" and "--resume" in st["error"]
    assert not (cut / "summary.json").exists() and not (cut / "results.nc").exists()
    proc = subprocess.run(_cmd(cut, "--resume"), capture_output=True, text=True, env=ENV, timeout=900)
    assert proc.returncode == 0, proc.stderr
    _, err = whole.communicate(timeout=900)
    assert whole.returncode == 0, err
    head = json.loads((cut / "summary.json").read_text())
    assert head["positions_taken_over"] == done
    assert head["positions_computed"] + head["positions_taken_over"] == N
    assert json.loads((cut / "run.json").read_text())["status"] == "complete"
    print(f"\nbevel resume: {done} positions taken over, {head['positions_computed']} computed")
    with xr.open_dataset(ref / "results.nc", engine="h5netcdf") as a, \
            xr.open_dataset(cut / "results.nc", engine="h5netcdf") as b:
        assert set(a.data_vars) == set(b.data_vars)
        for name in a.data_vars:
            x, y = a[name].values, b[name].values
            np.testing.assert_allclose(y, x, rtol=1e-12, atol=1e-12 * max(np.nanmax(np.abs(x)), 1e-300),
                                       err_msg=name)
