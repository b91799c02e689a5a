"""Extreme but legal cylindrical inputs: each computes or exits 2 (one line) naming the limiting quantity and a
value that would work, before any FE work where it can be known then.

- a torque of 1e6 N m on FZG C14, module 100 on a 0.5 mm face: the Hertz half-width reaches across the face;
- a face width of 2000 mm: the estimated body size (degrees of freedom) is refused;
- a lead misalignment of 500 um: the load sits on the face end only (no flank cell), said after the analysis;
- a gear of 1000 teeth: computes (the meshing's surface labels tolerate the chord error of a large radius).
The Hertz half-width is checked against an independent evaluation of Johnson (1985) eq. 4.43."""
from __future__ import annotations

import json
import math
import os
import subprocess
import sys
import time

import pytest
import tomllib

from fixtures.paths import CASES, ROOT
from fixtures.toml_text import dumps
from ltca.case import FIDELITIES, parse_case
from ltca.cli import main
from ltca.cylindrical.limits import MAX_BODY_DOFS, body_dofs, check_limits, hertz_half_width
from ltca.cylindrical.model import build_model
from ltca.validation import DesignError

ENV = {**os.environ, "PYTHONPATH": str(ROOT), "OMP_NUM_THREADS": "1"}
FZG = (CASES / "fzg_c14.toml").read_text()


def _variant(tmp_path, edit) -> str:
    doc = tomllib.loads(FZG)
    edit(doc)
    p = tmp_path / "case.toml"
    p.write_text(dumps(doc))
    return str(p)


def _model(path):
    from ltca.case import load_case
    return build_model(load_case(path))


def test_hertz_half_width_independent():
    """b = sqrt(4 w R / (pi E*)) with 1/E* = 2 (1 - nu^2) / E for two steel bodies (Johnson 1985 eq. 4.43)."""
    m = _model(CASES / "fzg_c14.toml")
    p1, p2, a = m.pinion, m.gear, m.pair.alpha_w
    R = 1 / (1 / (p1.r_base * math.tan(a)) + 1 / (p2.r_base * math.tan(a)))
    w = 200e3 / (p1.r_base * m.face_width)
    E_star = 206000 / (2 * (1 - 0.3 ** 2))
    b = math.sqrt(4 * w * R / (math.pi * E_star))
    assert hertz_half_width(m, 200e3)[0] == pytest.approx(b, rel=1e-6)
    assert hertz_half_width(m, 800e3)[0] == pytest.approx(2 * b, rel=1e-6)        # b ~ sqrt(T)


@pytest.mark.parametrize("name,edit,field,fix", [
    ("torque 1e6 N m", lambda d: d["load"].update(torque_nm=1e6), "load.torque_nm", "a torque of at most"),
    ("module 100, face 0.5 mm", lambda d: (d["gear_pair"].update(module_mm=100.0),
                                           [d[k].pop(x, None) for k in ("pinion", "gear")
                                            for x in ("tip_diameter_mm", "bore_diameter_mm")],
                                           d["pinion"].update(face_width_mm=0.5, profile_shift=0.0),
                                           d["gear"].update(face_width_mm=0.5, profile_shift=0.0),
                                           d["assembly"].pop("centre_distance_mm")),
     "pinion.face_width_mm", "a face width of at least"),
    ("face 2000 mm", lambda d: (d["pinion"].update(face_width_mm=2000.0), d["gear"].update(face_width_mm=2000.0)),
     "face_width_mm", "a face width of at most"),
])
def test_refused_before_any_fe_work_with_a_value_that_works(tmp_path, capsys, name, edit, field, fix):
    path = _variant(tmp_path, edit)
    t0 = time.perf_counter()
    assert main(["run", path, "--out", str(tmp_path / "out"), "--fidelity", "coarse", "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert time.perf_counter() - t0 < 20 and len(err) == 1, err
    assert field in err[0] and fix in err[0], err[0]
    assert not (tmp_path / "out" / "run.json").exists()          # refused before the output folder is touched


def test_the_suggested_values_pass():
    """The torque and face width the messages suggest pass the same checks."""
    doc = tomllib.loads(FZG)
    doc["load"]["torque_nm"] = 1e6
    m = build_model(parse_case(doc))
    with pytest.raises(DesignError) as exc:
        check_limits(m, FIDELITIES["coarse"], "coarse")
    t_ok = float(str(exc.value).split("a torque of at most ")[1].split(" N m")[0])
    doc["load"]["torque_nm"] = t_ok
    check_limits(build_model(parse_case(doc)), FIDELITIES["coarse"], "coarse")
    doc = tomllib.loads(FZG)
    for k in ("pinion", "gear"):
        doc[k]["face_width_mm"] = 2000.0
    with pytest.raises(DesignError) as exc:
        check_limits(build_model(parse_case(doc)), FIDELITIES["coarse"], "coarse")
    f_ok = float(str(exc.value).split("a face width of at most ")[1].split(" mm")[0])
    for k in ("pinion", "gear"):
        doc[k]["face_width_mm"] = f_ok
    m = build_model(parse_case(doc))
    check_limits(m, FIDELITIES["coarse"], "coarse")
    h = 4.5 * FIDELITIES["coarse"]["h_flank"], 4.5 * FIDELITIES["coarse"]["h_body"]
    assert max(body_dofs(m, *h)) <= 0.55 * MAX_BODY_DOFS


def test_lead_misalignment_500um_no_traceback(tmp_path):
    """The documented bound: either a result without NaN, or exit 2 naming the misalignment (the load on the face
    end only); never a traceback or a numpy warning on the console."""
    path = _variant(tmp_path, lambda d: d["assembly"].update(lead_misalignment_um=500.0))
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "ltca.cli", "run", path, "--out", str(out), "--fidelity", "coarse",
                           "--positions", "3", "--paraview-steps", "0", "--quiet", "--cache", str(tmp_path / "c")],
                          capture_output=True, text=True, env=ENV, timeout=600)
    assert "Traceback" not in proc.stderr and "RuntimeWarning" not in proc.stderr, proc.stderr[-2000:]
    assert proc.returncode in (0, 2), proc.stderr[-2000:]
    if proc.returncode == 2:
        last = proc.stderr.strip().splitlines()[-1]
        assert "assembly.lead_misalignment_um" in last and "a lead misalignment of at most" in last, last
        assert json.loads((out / "run.json").read_text())["status"] == "failed"
    else:
        head = json.loads((out / "summary.json").read_text())
        assert head["max_flank_pressure_mpa"] > 0
        assert all(r["ours"] is not None and r["reference"] is not None for r in head["iso6336"])


@pytest.mark.slow
def test_gear_of_1000_teeth_computes(tmp_path):
    """Coarse, three positions: about 90 s (the gear body about 0.4 million dofs)."""
    path = _variant(tmp_path, lambda d: (d["gear"].update(teeth=1000, profile_shift=0.0),
                                         [d["gear"].pop(x) for x in ("tip_diameter_mm", "bore_diameter_mm")],
                                         d["assembly"].pop("centre_distance_mm")))
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "ltca.cli", "run", path, "--out", str(out), "--fidelity", "coarse",
                           "--positions", "3", "--paraview-steps", "0", "--quiet"],
                          capture_output=True, text=True, env=ENV, timeout=900)
    assert proc.returncode == 0, proc.stderr[-2000:]
    head = json.loads((out / "summary.json").read_text())
    hertz = [r for r in head["iso6336"] if r["quantity"].startswith("pitch-point peak")][0]
    assert hertz["ours"] == pytest.approx(hertz["reference"], rel=0.1)
