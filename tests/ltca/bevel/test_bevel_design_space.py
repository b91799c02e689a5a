"""Bevel pairs away from the shipped one (pairs of the design-space grid of tools/bevel_sweep.py): each runs, or
both ``ltca tca`` and ``ltca run`` exit 2 with the same message naming the limiting input."""
from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from tools.bevel_sweep import CASE, grid, suggestions

ROOT = Path(__file__).resolve().parents[3]


def _case(tmp_path: Path, i: int, **change) -> Path:
    g = dict(grid(32)[i])
    g.update(change)
    p = tmp_path / f"pair_{i}.toml"
    p.write_text(CASE.format(**g))
    return p


def test_shaft_angle_limit_names_a_working_value(tmp_path):
    """9/51 teeth at a 104 deg shaft angle: the gear's face angle passes 90 deg (an internal bevel gear); the
    error names bevel.shaft_angle_deg and the largest angle that works, and that angle is accepted with the face
    angle below 90 deg (tan(delta2) = sin(S) / (z1/z2 + cos(S)))."""
    from ltca.bevel.case import load_bevel_case
    from ltca.errors import CaseError
    with pytest.raises(CaseError) as e:
        load_bevel_case(_case(tmp_path, 0))
    msg = str(e.value)
    assert "bevel.shaft_angle_deg" in msg
    s_max = float(msg.split("at most ")[1].split(" deg")[0])
    ok = load_bevel_case(_case(tmp_path, 0, sigma=s_max))
    from ltca.geometry.bevel.blank import design_blank
    bl = design_blank(ok.basic)
    S = math.radians(s_max)
    assert bl.gear.pitch_angle == pytest.approx(math.atan2(math.sin(S), 9 / 51 + math.cos(S)), abs=1e-9)
    assert math.degrees(bl.gear.face_angle) < 90.0 < math.degrees(bl.gear.face_angle) + 0.6


def test_iso10300_virtual_gears_any_shaft_angle(tmp_path):
    """ISO 10300-1 Annex A at a 61 deg shaft angle: d_v = d_m / cos(delta), z_v = z / cos(delta) with the pitch
    angles of tan(delta1) = sin(S) / (z2/z1 + cos(S))."""
    from ltca.bevel.case import load_bevel_case
    from ltca.bevel.iso10300 import virtual_gears
    from ltca.geometry.bevel.blank import design_blank
    c = load_bevel_case(_case(tmp_path, 4))
    bl = design_blank(c.basic)
    S, z1, z2 = c.basic.shaft_angle, c.basic.z1, c.basic.z2
    d1 = math.atan2(math.sin(S), z2 / z1 + math.cos(S))
    v = virtual_gears(bl)
    assert v.delta1 == pytest.approx(d1, abs=1e-12)
    assert v.z_v1 == pytest.approx(z1 / math.cos(d1), rel=1e-12)
    assert v.z_v2 == pytest.approx(z2 / math.cos(S - d1), rel=1e-12)


def test_flank_point_at_the_blade_kink(tmp_path):
    """14/17 at 61 deg: the pinion's convex flank at (t 0.192, L 76.103 mm), where Newton from the interpolated
    start fails at the blade profile's kink, is found (from the cell's nodes) on the target axial point."""
    from ltca.bevel.analysis import build_pair
    from ltca.bevel.case import load_bevel_case
    from ltca.bevel.loaded_model import member_flanks
    from ltca.geometry.bevel.sampling import axial_target, flank_at
    pair = build_pair(load_bevel_case(_case(tmp_path, 4)))
    fl = member_flanks(pair, "pinion")[0]["convex"]
    t, L = np.array([0.192]), np.array([76.103])
    P = flank_at(fl, t, L)[0]
    Z, rho = axial_target(fl, t, L)
    assert P[0, 2] == pytest.approx(Z[0], abs=1e-8) and np.hypot(P[0, 0], P[0, 1]) == pytest.approx(rho[0], abs=1e-8)


def test_tca_and_run_same_exit_2(tmp_path):
    """35/160 with a cutter of 1.1 mean cone distances: the synthesis finds no blade for the working path angle of
    22 deg; tca and run both exit 2 with the same one-line message (no traceback), naming the path angle and a value
    of it that works."""
    case = _case(tmp_path, 3)
    out = []
    for cmd in (["tca", str(case)], ["run", str(case), "--out", str(tmp_path / "run"), "--quiet"]):
        p = subprocess.run([sys.executable, "-m", "ltca.cli", *cmd], capture_output=True, text=True, check=False,
                           env={**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"},
                           cwd=str(ROOT), timeout=600)
        assert p.returncode == 2 and "Traceback" not in p.stderr and "Warning" not in p.stderr, p.stderr
        out.append(p.stderr.split("error: ", 1)[1].split("synthesis/TCA failed", 1)[1])
    assert out[0] == out[1] and "'bevel.working.path_angle_deg' = 22 deg is out of reach" in out[0]
    assert set(suggestions(out[0])) == {"bevel.working.path_angle_deg"}
