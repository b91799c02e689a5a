"""``ltca tca`` on a bevel case honours ``[assembly]``; ``ltca optimise`` whose constraints no design meets ends
with its own status (4) and says so, never exit 0 with an "optimum".

The shipped case is synthesised for its targets on the ideal mounting (path angles 22 / -14 deg, TE 8.25 /
11.25 arcsec); an offset E of 0.05 mm moves the path and the TE away from them (the sensitivity of spiral bevel
gears to misalignment: Litvin and Fuentes 2004, Gear Geometry and Applied Theory), and one of 5 mm leaves no point of tangency."""
from __future__ import annotations

import re

from fixtures.paths import CASES
from ltca.cli import NO_FEASIBLE_DESIGN, main

BEVEL = (CASES / "spiral_bevel_cao2008.toml").read_text()


def _with_E(tmp_path, E: float):
    text, n = re.subn(r"(\[assembly\][^\[]*?)E_mm = [-0-9.]+", lambda m: f"{m.group(1)}E_mm = {E}", BEVEL,
                      flags=re.S)
    assert n == 1
    p = tmp_path / f"bevel_E{E}.toml"
    p.write_text(text)
    return p


def test_bevel_tca_honours_the_assembly(tmp_path):
    from ltca.bevel.run import run_bevel_tca
    s = run_bevel_tca(str(_with_E(tmp_path, 0.05)))
    assert s["assembly"]["E_mm"] == 0.05
    coast = s["flanks"]["coast"]
    # the synthesis meets the targets on the ideal mounting within 0.2 deg and 2 % (test_bevel_synthesis); the
    # offset moves them by more than that
    assert abs(coast["path_angle_deg"] - coast["targets"]["path_angle_deg"]) > 0.5
    assert abs(coast["te_amplitude_arcsec"] - coast["targets"]["te_magnitude_arcsec"]) > 0.5


def test_bevel_tca_impossible_assembly_exit_2(tmp_path, capsys):
    assert main(["tca", str(_with_E(tmp_path, 5.0))]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "'assembly.E_mm'" in err[0], err


def test_optimise_without_a_feasible_design_exits_4(tmp_path, capsys, monkeypatch):
    """The command's outcome for a search whose best candidate is infeasible (the search itself is covered in
    test_design_bevel.py): status 4, the JSON says least_infeasible, one line on stderr."""
    import ltca.design as design

    class Res:
        out = tmp_path
        summary = {"optimum": {"values": {"eta2": 20.0}, "objective_arcsec": 5.0, "feasible": False},
                   "baseline": {"objective_arcsec": 6.0}, "start": {"objective_arcsec": 6.0},
                   "evaluations": {"search": 12}, "timings_s": {"total": 1.0},
                   "constraints": {"max_flank_pressure_mpa": 900.0, "misalignment_um": 0.0}}
    monkeypatch.setattr(design, "optimise", lambda *a, **k: Res())
    case = CASES / "spiral_bevel_optimise.toml"
    assert main(["optimise", str(case), "--out", str(tmp_path / "o")]) == NO_FEASIBLE_DESIGN == 4
    cap = capsys.readouterr()
    assert '"least_infeasible"' in cap.out and '"optimum"' not in cap.out.split('"objective_arcsec"')[0]
    err = cap.err.strip().splitlines()
    assert len(err) == 1 and "no feasible design" in err[0] and "12 candidates" in err[0] and "max_flank_pressure_mpa 900" in err[0], err
    Res.summary["optimum"]["feasible"] = True
    assert main(["optimise", str(case), "--out", str(tmp_path / "o")]) == 0
