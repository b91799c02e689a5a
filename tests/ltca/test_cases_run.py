"""Every file in cases/ runs (examples double as tests)."""
from __future__ import annotations

import json

import pytest

from fixtures.paths import CASES

CYLINDRICAL = ["fzg_c14.toml", "helical_c14.toml", "internal_spur.toml", "fzg_c14_pitch_errors.toml",
               "helical_m8_wide.toml", "example_commented.toml", "fzg_c14_optimise.toml",
               "fzg_c14_modified.toml"]


#: the default tier runs the flagship case end to end; the heavy tier every cylindrical case
@pytest.mark.heavy
@pytest.mark.parametrize("name", [n if n == "fzg_c14.toml" else pytest.param(n, marks=pytest.mark.heavy)
                                  for n in CYLINDRICAL])
def test_cylindrical_case_runs_and_writes_results(name, tmp_path):
    from ltca.driver import run_to_dir as run_case
    out = tmp_path / "out"
    run_case(str(CASES / name), out=str(out), fidelity="coarse", positions=4, progress=False,
             cache=str(tmp_path / "cache"))
    summary = json.loads((out / "summary.json").read_text())
    for key in ("te_loaded_ptp_arcsec", "te_unloaded_ptp_arcsec", "max_contact_pressure_mpa", "max_root_stress_mpa",
                "mesh_stiffness_mean_n_per_mm_um", "max_pairs_in_contact", "positions", "converged", "timings_s",
                "max_flank_pressure_mpa", "max_flank_pressure_at", "edge_contact", "edge_note"):
        assert key in summary
    assert 0 < summary["max_flank_pressure_mpa"] <= summary["max_contact_pressure_mpa"]
    from ltca.case import load_case
    assert summary["converged"] and summary["positions"] == 4 * load_case(CASES / name).cycles
    for key in ("geometry", "mesh", "compliance", "contact", "total"):
        assert summary["timings_s"][key] >= 0
    for f in ("results.nc", "te.png", "load_sharing.png", "bearing_pattern.png", "root_stress.png",
              "pinion_loaded.vtu", "gear_loaded.vtu", "positions.jsonl"):
        assert (out / f).stat().st_size > 0, f
    import xarray as xr
    ds = xr.open_dataset(out / "results.nc")
    assert {"te_loaded", "te_unloaded", "pair_load", "max_pressure", "root_stress_pinion", "pressure",
            "max_flank_pressure", "edge_load", "edge_pattern"} <= set(ds)


def test_every_case_file_is_covered():
    # budget and chain cases run in test_budget.py / test_chain.py, the bevel case in test_bevel_case.py,
    # the planetary satellite (Kapitonov et al. 2014) through `ltca run`, `tca` and `forming` in test_planetary.py;
    # the [design] table of fzg_c14_optimise.toml through `ltca optimise` in test_design.py,
    # spiral_bevel_optimise.toml's in test_design_bevel.py
    covered = set(CYLINDRICAL) | {"budget_wang.toml", "chain_zftkk250.toml", "spiral_bevel_cao2008.toml",
                                  "eccentric_planetary_satellite.toml", "spiral_bevel_optimise.toml"}
    assert {p.name for p in CASES.glob("*.toml")} <= covered


def test_tca_command_prints_path(capsys, tmp_path):
    from ltca.cli import main
    assert main(["tca", str(CASES / "fzg_c14.toml"), "--positions", "6", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "eps_alpha = 1.43" in out
    assert json.loads((tmp_path / "summary.json").read_text())["te_unloaded_ptp_arcsec"] < 0.05
