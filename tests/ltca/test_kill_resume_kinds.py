"""``ltca run`` of a spiral bevel and a planetary case killed with SIGKILL (no chance to clean up) after its first
positions were stored, then run again with ``--resume``: the folder says ``interrupted``, nothing final was written,
the resumed run takes over the stored positions, computes only the rest and gives the uninterrupted run's results
(bit for bit where the compliance is computed by one thread, as here)."""
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

pytestmark = pytest.mark.heavy

ENV = {**os.environ, "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "MPLBACKEND": "Agg"}
RUNS = {"spiral_bevel_cao2008": ["--fidelity", "coarse", "--positions", "6", "--torque", "350"],
        "eccentric_planetary_satellite": ["--fidelity", "coarse", "--positions", "6", "--torque", "100"]}


def _lines(p: Path) -> int:
    try:
        return p.read_bytes().count(b"\n")
    except OSError:
        return 0


@pytest.mark.parametrize("case", sorted(RUNS))
def test_sigkill_then_resume_gives_the_uninterrupted_results(tmp_path, case):
    import xarray as xr
    cache = tmp_path / "cache"

    def cmd(out, *extra):
        return [sys.executable, "-m", "ltca.cli", "run", case, "--out", str(out), "--quiet", "--cache", str(cache),
                "--paraview-steps", "0", *RUNS[case], *extra]
    ref, cut = tmp_path / "ref", tmp_path / "cut"
    proc = subprocess.run(cmd(ref), capture_output=True, text=True, env=ENV, timeout=1200)
    assert proc.returncode == 0, proc.stderr
    n = _lines(ref / "positions.jsonl")
    p = subprocess.Popen(cmd(cut), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=ENV)
    t0 = time.time()
    while _lines(cut / "positions.jsonl") < 2 and p.poll() is None and time.time() - t0 < 1200:
        time.sleep(0.01)
    p.send_signal(signal.SIGKILL)
    p.wait()
    done = _lines(cut / "positions.jsonl")
    assert 2 <= done < n, f"killed after {done} of {n} positions"
    assert json.loads((cut / "run.json").read_text())["status"] in ("running", "interrupted")
    assert not (cut / "summary.json").exists() and not (cut / "results.nc").exists()
    proc = subprocess.run(cmd(cut, "--resume"), capture_output=True, text=True, env=ENV, timeout=1200)
    assert proc.returncode == 0, proc.stderr
    head = json.loads((cut / "summary.json").read_text())
    assert head["positions_taken_over"] >= done - 1          # the last one may have been torn by the kill
    assert head["positions_computed"] == n - head["positions_taken_over"]
    a, b = xr.open_dataset(ref / "results.nc"), xr.open_dataset(cut / "results.nc")
    for name in a.data_vars:
        np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)
    assert json.loads((cut / "run.json").read_text())["status"] == "complete"
