"""The convergence and validate commands run and report what they promise."""
from __future__ import annotations

import json

import pytest

from conftest import CASES


def test_convergence_ladder_reports_time_and_error(tmp_path, capsys):
    from ltca.verify.convergence import run_convergence
    ladder = [("coarse", "coarse", {}), ("coarse, contact cells x 2", "coarse", {"cells_per_b": 6, "slices": 12}),
              ("coarse (reference)", "coarse", {"cells_per_b": 8, "slices": 14})]
    rows = run_convergence(str(CASES / "fzg_c14.toml"), out=str(tmp_path), positions=4, progress=False,
                           ladder=ladder)
    out = capsys.readouterr().out
    assert "wall [s]" in out and "TE err" in out
    assert rows[-1]["err_te"] == 0.0 and all(r["wall_s"] > 0 for r in rows)
    # on the same compliance the contact grid moves the loaded TE by well under 1 % (measured 0.4 / 0.6 %:
    # not monotone at these sizes, the cell lattice's phase against the contact line changes with ds)
    assert rows[0]["err_te"] < 0.015 and rows[1]["err_te"] < 0.015
    assert json.loads((tmp_path / "convergence.json").read_text())["rungs"][0]["label"] == "coarse"
    assert (tmp_path / "convergence.png").stat().st_size > 0


@pytest.mark.slow
def test_validate_command_passes(tmp_path, capsys):
    from ltca.verify.validate import run_validate
    assert run_validate(out=str(tmp_path)) == 0
    out = capsys.readouterr().out
    assert "pitch point p0 with near field" in out
    assert (tmp_path / "validation.csv").exists()
