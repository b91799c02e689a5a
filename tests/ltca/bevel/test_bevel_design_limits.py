"""A bevel pair the synthesis cannot make exits 2 naming the limiting field and a value of it that works, and that
value runs.

The pair: 17/29 teeth, module 5 mm, a 20 deg spiral on a 90 deg shaft angle, built as tools/bevel_sweep.py builds its
pairs (face 0.3 of the outer cone distance, cutter radius 0.6 of the mean cone distance, ellipse 0.2 face widths),
with the working path angle 0 deg: a path along the face, which over one mesh cycle would run about one axial pitch,
p_t / tan(beta) = 37 mm (p_t = pi m A_m / A_0 = 13.4 mm at the mean point), on a 25 mm face, and leaves the flank
before the transfer points."""
from __future__ import annotations

import math
import re

import numpy as np
import pytest

from ltca.cli import main
from tools.bevel_sweep import CASE, suggestions, with_values


def _pair_text() -> str:
    z1, z2, m, sigma, beta = 17, 29, 5.0, 90.0, 20.0
    S = math.radians(sigma)
    g2 = math.atan2(math.sin(S), z1 / z2 + math.cos(S))
    A0 = m * z2 / (2 * math.sin(g2))
    b = min(0.3 * A0, 10 * m)
    g = dict(i=0, z1=z1, z2=z2, m=m, b=b, beta=beta, sigma=sigma, rc=0.6 * (A0 - b / 2), ell=0.2 * b,
             torque=350.0 * (b / 25.4) * (z1 * m / (12 * 5.08)) ** 2)
    text = CASE.format(**g)
    return with_values(text, {"bevel.working.path_angle_deg": 0.0})


@pytest.mark.heavy
def test_path_angle_out_of_reach_names_a_value_that_runs(tmp_path, capsys):
    case = tmp_path / "pair_17_29.toml"
    case.write_text(_pair_text())
    assert main(["tca", str(case)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "Traceback" not in err[0] and "Warning" not in err[0], err
    assert "'bevel.working.path_angle_deg' = 0 deg is out of reach" in err[0], err
    values = suggestions(err[0])
    assert "bevel.working.path_angle_deg" in values and values["bevel.working.path_angle_deg"] != 0.0
    assert re.search(r": -?\d+(\.\d+)? deg works \(checked", err[0])
    # the case with the values named runs `ltca tca` (synthesis, TCA and separation field of both flanks; no plots)
    from ltca.bevel.case import load_bevel_case
    from ltca.bevel.run import bevel_tca_summary
    fixed = tmp_path / "pair_17_29_suggested.toml"
    fixed.write_text(with_values(case.read_text(), values))
    s, _, _ = bevel_tca_summary(load_bevel_case(fixed))
    # the TCA's path (least-squares line of the contact points in the gear axial section) runs at the suggested angle
    eta = values["bevel.working.path_angle_deg"]
    assert s["flanks"]["working"]["targets"]["path_angle_deg"] == eta
    assert s["flanks"]["working"]["path_angle_deg"] == pytest.approx(eta, abs=0.5)


def test_working_values_bisects_towards_the_user(monkeypatch):
    """The search keeps the value nearest the user's among those it found to work: on a made-up feasibility (values
    above 13.2 work), from 0 and the first anchor 22 (works), two bisections try 11 (fails) and 16.5 rounded to 16
    (works); the value returned is one that was tried and worked."""
    from ltca.bevel import limits
    tried = []

    def works(v):
        tried.append(v)
        return v > 13.2
    got = limits._search(works, 0.0, [22.0, 10.0], 0, False, steps=2)
    assert tried == [22.0, 11.0, 16.0] and got == 16.0
    assert limits._search(lambda v: False, 0.0, [22.0, 10.0], 0, False) is None
    # on a log scale (ellipse axis, TE magnitude): the geometric mean
    tried.clear()
    got = limits._search(works, 4.0, [64.0], 1, True, steps=2)
    assert tried == [64.0, 16.0, 8.0] and got == 16.0
    assert np.all(np.asarray(tried) > 0)
