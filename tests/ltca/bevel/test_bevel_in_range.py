"""Bevel inputs inside the schema's ranges that the synthesis may not meet run through the whole
``ltca tca`` (synthesis and TCA of both flanks): they exit 0 with a valid summary, or exit 2 naming the fields
that drive the failure; never a traceback.  (15-20 s each.)"""
import json
import subprocess
import sys

import pytest

from fixtures.paths import BEVEL_CASE

CASE = BEVEL_CASE


@pytest.mark.heavy
@pytest.mark.parametrize("path_angle, status", [(0.0, 0), (-1.5, 2)])
def test_in_range_path_angle(tmp_path, path_angle, status):
    text = CASE.read_text().replace("path_angle_deg = 22.0", f"path_angle_deg = {path_angle}", 1)
    case = tmp_path / "case.toml"
    case.write_text(text)
    p = subprocess.run([sys.executable, "-m", "ltca.cli", "tca", str(case), "--out", str(tmp_path / "out")],
                       capture_output=True, text=True, timeout=300)
    assert "Traceback" not in p.stderr
    assert p.returncode == status, p.stderr[-400:]
    if status == 0:
        s = json.loads((tmp_path / "out" / "summary.json").read_text())
        assert abs(s["flanks"]["working"]["path_angle_deg"] - path_angle) < 0.5
    else:
        assert "'bevel.working.path_angle_deg'" in p.stderr
