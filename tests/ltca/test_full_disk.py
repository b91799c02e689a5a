"""A full disk never crashes the process: the netCDF writer (:func:`ltca.outputs.write_netcdf_atomic`) at twenty
fill levels of a small tmpfs, with the free-space check and without it (the disk filling during the write), each
ending in the file complete or in ``OSError(ENOSPC)`` with nothing under the final name; never a signal.

The HDF5 library, handed a file on a full disk, aborts the process (a segmentation fault) instead of raising; the
writer serialises in memory and writes the bytes from Python. Skipped where a tmpfs cannot be mounted (not root)."""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from fixtures.paths import CASES, ROOT

ENV = {**os.environ, "PYTHONPATH": str(ROOT), "OMP_NUM_THREADS": "1"}
SIZE_K = 160          # the tmpfs; the results.nc of the run below is about 44 kB
TRIES = 20

# one process, twenty fill levels: a segfault anywhere ends it with a negative status
SCRIPT = r"""
import errno, json, os, sys
from pathlib import Path
import xarray as xr
import ltca.outputs as outputs
src, disk, check = sys.argv[1], Path(sys.argv[2]), sys.argv[3] == "check"
if not check:                      # the disk fills during the write: only the write itself can notice
    outputs.check_free_space = lambda path, n: None
ds = xr.load_dataset(src, engine="h5netcdf")
size = len(outputs.netcdf_bytes(ds))
total = os.statvfs(disk).f_blocks * os.statvfs(disk).f_frsize
out = []
for k in range(int(sys.argv[4])):
    fill = int(total * k / (int(sys.argv[4]) - 1))
    filler = disk / "filler"
    try:
        with open(filler, "wb") as fh:
            fh.write(b"\0" * fill)
    except OSError:
        pass                          # the disk is full: that is the point
    target = disk / "results.nc"
    try:
        outputs.write_netcdf_atomic(target, ds)
        ok = xr.load_dataset(target, engine="h5netcdf").identical(ds)
        out.append({"fill": fill, "outcome": "written", "identical": bool(ok)})
    except OSError as exc:
        out.append({"fill": fill, "outcome": "enospc" if exc.errno == errno.ENOSPC else repr(exc),
                    "left": sorted(p.name for p in disk.iterdir() if p.name != "filler")})
    for p in disk.iterdir():
        p.unlink()
print(json.dumps({"size": size, "tries": out}))
"""


def _mount(path: Path, opts: str) -> bool:
    path.mkdir(exist_ok=True)
    return subprocess.run(["mount", "-t", "tmpfs", "-o", opts, "tmpfs", str(path)], capture_output=True).returncode == 0


@pytest.fixture(scope="module")
def results_nc(tmp_path_factory):
    """The results.nc of a real run (FZG C14, coarse, three positions)."""
    out = tmp_path_factory.mktemp("run")
    proc = subprocess.run([sys.executable, "-m", "ltca.cli", "run", str(CASES / "fzg_c14.toml"), "--out", str(out),
                           "--fidelity", "coarse", "--positions", "3", "--paraview-steps", "0", "--quiet",
                           "--cache", str(out / "cache")], capture_output=True, text=True, env=ENV, timeout=600)
    assert proc.returncode == 0, proc.stderr
    return out / "results.nc"


@pytest.mark.heavy
@pytest.mark.parametrize("check", ["check", "no-check"])
def test_netcdf_writer_on_a_filling_disk(tmp_path, results_nc, check):
    if os.geteuid() != 0:
        pytest.skip("mounting a tmpfs needs root")
    disk = tmp_path / "disk"
    if not _mount(disk, f"size={SIZE_K}k"):
        pytest.skip("cannot mount a tmpfs here")
    try:
        proc = subprocess.run([sys.executable, "-c", SCRIPT, str(results_nc), str(disk), check, str(TRIES)],
                              capture_output=True, text=True, env=ENV, timeout=300)
    finally:
        subprocess.run(["umount", str(disk)])
    assert proc.returncode == 0, f"status {proc.returncode} (a negative status is a signal): {proc.stderr[-2000:]}"
    res = json.loads(proc.stdout)
    tries = res["tries"]
    assert len(tries) == TRIES
    outcomes = [t["outcome"] for t in tries]
    assert set(outcomes) <= {"written", "enospc"}, outcomes
    # an empty disk takes the file, a full one refuses it: both outcomes occur
    assert outcomes[0] == "written" and outcomes[-1] == "enospc", outcomes
    for t in tries:
        if t["outcome"] == "written":
            assert t["identical"], t
        else:
            assert t["left"] == [], t          # nothing half-written, not even under a temporary name
    if check == "check":                       # with the check: refused exactly when the room is short
        room = SIZE_K * 1024
        for t in tries:
            fits = room - t["fill"] >= res["size"] + 2 * 4096
            assert (t["outcome"] == "written") == fits or abs(room - t["fill"] - res["size"]) < 3 * 4096, t
