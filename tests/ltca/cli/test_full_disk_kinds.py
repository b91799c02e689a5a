"""A full disk under ``ltca run`` of a spiral bevel and a planetary case (a small tmpfs; root only): exit status 2
with one line naming the cause, ``run.json`` says ``failed``, nothing half-written under a final name, no torn line
in ``positions.jsonl``; at each size the disk fills at another stage (the stored positions, or the result files)."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

pytestmark = pytest.mark.heavy

ENV = {**os.environ, "OMP_NUM_THREADS": "1", "MPLBACKEND": "Agg"}
#: case, its run options, tmpfs sizes: one filled by the stored positions, one by the result files
RUNS = [("spiral_bevel_cao2008", ["--fidelity", "coarse", "--positions", "4", "--torque", "350"], ["40k", "500k"]),
        ("eccentric_planetary_satellite", ["--fidelity", "coarse", "--positions", "3", "--torque", "100"],
         ["20k", "120k"])]
FINAL = ("summary.json", "results.nc", "report.html", "paraview.pvd", "te.png", "load_sharing.png",
         "load_sharing.csv", "bearing_pattern.png")


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    return tmp_path_factory.mktemp("mesh_cache")


@pytest.mark.parametrize("case, options, size", [(c, o, s) for c, o, sizes in RUNS for s in sizes],
                         ids=lambda v: v if isinstance(v, str) else "")
def test_a_full_disk_ends_in_exit_2_and_a_failed_run(tmp_path, cache, case, options, size):
    if os.geteuid() != 0:
        pytest.skip("mounting a tmpfs needs root")
    full = tmp_path / "full"
    full.mkdir()
    if subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(full)],
                      capture_output=True).returncode != 0:
        pytest.skip("cannot mount a tmpfs here")
    try:
        out = full / "out"
        proc = subprocess.run([sys.executable, "-m", "ltca.cli", "run", case, "--out", str(out), "--quiet",
                               "--cache", str(cache), *options], capture_output=True, text=True, env=ENV, timeout=900)
        assert proc.returncode == 2, proc.stderr
        assert "No space left" in proc.stderr and "Traceback" not in proc.stderr
        assert len(proc.stderr.strip().splitlines()) == 1, proc.stderr
        assert json.loads((out / "run.json").read_text())["status"] == "failed"
        for name in FINAL:
            assert not (out / name).exists(), name
        assert not list(out.glob(".staging-*"))
        log = out / "positions.jsonl"
        for line in (log.read_text().splitlines() if log.exists() else []):
            json.loads(line)
    finally:
        subprocess.run(["umount", str(full)])

