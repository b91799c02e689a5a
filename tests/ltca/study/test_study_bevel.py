"""Studies of a spiral bevel pair: the study file (bevel keys, signed torques, Monte Carlo draws of the assembly
errors by law and seed), one compliance per loaded flank shared by every assembly variant, a grid over E and P
on the local Dask cluster with its rerun computing nothing, and a point against a standalone ``ltca run``.
Coarse fidelity and 4 positions per cycle."""
from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr

from fixtures.paths import ROOT
from ltca.cli import main
from ltca.errors import CaseError

CASE = str(ROOT / "cases" / "spiral_bevel_cao2008.toml")
FAST = {"analysis.fidelity": "coarse", "analysis.positions": 4}


def bevel_study(grid=None, torques=(35.0, 175.0), **extra) -> dict:
    return {"study": {"name": "bevel test", "case": CASE, "torque_nm": list(torques)}, "set": dict(FAST),
            **({"grid": grid} if grid else {}), **extra}


def test_bevel_study_file_and_compliance_keys():
    """Every assembly variant and every torque of one sign share one compliance key; the coast flank and a change
    of the bodies (material, fidelity) get their own."""
    from ltca.study import Study
    from ltca.study.tasks import plan_variant
    st = Study.from_dict(bevel_study({"assembly.E_mm": [-0.05, 0.05], "assembly.P_mm": [-0.05, 0.05],
                                      "assembly.G_mm": [0.0, 0.02], "assembly.sigma_deg": [0.0, 0.01]},
                                     torques=(35.0, 175.0, -100.0)))
    assert st.kind == "bevel" and st.torques == (35.0, 175.0, -100.0)
    vs = st.expand()
    assert len(vs) == 16 and len({v.id for v in vs}) == 16
    assert vs[-1].case["assembly"] == {"E_mm": 0.05, "P_mm": 0.05, "G_mm": 0.02, "sigma_deg": 0.01}
    plans = [plan_variant(v.case) for v in vs]
    working = {p.compliance_key(t) for p in plans for t in (35.0, 175.0)}
    coast = {p.compliance_key(-100.0) for p in plans}
    assert len(working) == 1 and len(coast) == 1 and working != coast
    other = Study.from_dict(bevel_study({"material.youngs_modulus_mpa": [206000.0, 210000.0]})).expand()
    assert len({plan_variant(v.case).compliance_key(35.0) for v in other}) == 2
    fine = Study.from_dict(bevel_study({"analysis.fidelity": ["coarse", "default"]})).expand()
    assert len({plan_variant(v.case).compliance_key(35.0) for v in fine}) == 2


def test_bevel_monte_carlo_draws_follow_their_laws():
    """Uniform and normal draws of the assembly keys: reproducible per sample, within their ranges, moments and
    a Kolmogorov-Smirnov test against the law."""
    from ltca.study import Study
    from ltca.study.montecarlo import check_key_draws
    mc = {"samples": 400, "seed": 11, "uniform": {"assembly.E_mm": [-0.05, 0.05], "assembly.P_mm": [-0.05, 0.05]},
          "normal": {"assembly.G_mm": [0.01, 0.02], "assembly.sigma_deg": [0.0, 0.005]}}
    st = Study.from_dict(bevel_study(torques=(175.0,), monte_carlo=mc))
    vs = st.expand()
    assert len(vs) == 400 and len({v.id for v in vs}) == 400
    again = Study.from_dict(bevel_study(torques=(175.0,), monte_carlo=dict(mc, samples=3))).expand()
    assert [v.drawn for v in again] == [v.drawn for v in vs[:3]]        # sample i does not depend on n
    assert vs[7].case["assembly"]["E_mm"] == vs[7].drawn["assembly.E_mm"]
    E = np.array([v.drawn["assembly.E_mm"] for v in vs])
    assert E.min() >= -0.05 and E.max() <= 0.05
    checks = check_key_draws([v.drawn for v in vs], st.monte_carlo.uniform, st.monte_carlo.normal)
    # uniform on [-0.05, 0.05]: mean 0, std 0.1 / sqrt(12) = 0.028868; normal(0.01, 0.02)
    assert checks["assembly.E_mm"]["expected_std"] == pytest.approx(0.1 / np.sqrt(12), rel=1e-12)
    assert checks["assembly.E_mm"]["std"] == pytest.approx(0.028868, rel=0.1)
    assert checks["assembly.G_mm"]["mean"] == pytest.approx(0.01, abs=3 * 0.02 / np.sqrt(400))
    assert checks["assembly.G_mm"]["std"] == pytest.approx(0.02, rel=0.1)
    assert all(c["ks_p"] > 1e-3 for c in checks.values())


@pytest.mark.parametrize("extra, field", [
    ({"grid": {"assembly.Q_mm": [0.0]}}, "grid.assembly.Q_mm"),
    ({"grid": {"assembly.E_mm": [0.0, 9.0]}}, "assembly.E_mm"),
    ({"monte_carlo": {"samples": 4, "uniform": {"assembly.E_mm": [0.05, -0.05]}}}, "monte_carlo.uniform.assembly.E_mm"),
    ({"monte_carlo": {"samples": 4, "normal": {"assembly.P_mm": [0.0, 0.0]}}}, "monte_carlo.normal.assembly.P_mm"),
    ({"monte_carlo": {"samples": 4, "grade": 6, "uniform": {"assembly.E_mm": [0, 1]}}}, "monte_carlo.grade"),
    ({"monte_carlo": {"samples": 4}}, "monte_carlo"),
])
def test_bad_bevel_study_files_name_the_field(extra, field):
    from ltca.study import Study
    with pytest.raises(CaseError, match=field.replace(".", r"\.").replace("[", r"\[")):
        Study.from_dict(bevel_study(**extra))


def test_bad_bevel_torque_exits_2(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(f'[study]\ncase = "{CASE}"\ntorque_nm = [35.0, 0.0]\n')
    assert main(["study", str(path), "--out", str(tmp_path / "out"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert "study.torque_nm[1]" in err and "Traceback" not in err


@pytest.fixture(scope="module")
def bevel_sweep(tmp_path_factory):
    """E and P of +-0.05 mm at two torques (4 variants x 2 torques), LocalCluster of 2 workers."""
    import time

    from ltca.study import Study, run_study
    out = tmp_path_factory.mktemp("bevel_sweep")
    study = Study.from_dict(bevel_study({"assembly.E_mm": [-0.05, 0.05], "assembly.P_mm": [-0.05, 0.05]}))
    t0 = time.perf_counter()
    ds = run_study(study, out, workers=2, progress=False, plots=True)
    return study, out, ds, time.perf_counter() - t0


@pytest.mark.slow
def test_bevel_study_runs_on_dask_and_reruns_nothing(bevel_sweep):
    from ltca.study import run_study
    study, out, ds, wall = bevel_sweep
    run = json.loads(ds.attrs["run"])
    assert run["workers"] == 2 and run["points_computed"] == 8 and run["compliance_computed"] == 1
    assert ds.attrs["kind"] == "bevel" and ds.sizes["variant"] == 4 and ds.sizes["torque"] == 2
    assert ds.sizes["position"] == 4
    for var in ("te_loaded", "te_unloaded", "max_flank_pressure", "max_pressure", "root_stress_pinion",
                "mesh_stiffness", "te_loaded_ptp", "peak_flank_pressure", "max_root_stress_gear"):
        assert np.isfinite(ds[var].values).all(), var
    assert ds.converged.values.all()
    assert sorted(set(ds["assembly.E_mm"].values)) == [-0.05, 0.05]
    # the mounting errors move the loaded contact: the variants differ
    assert np.ptp(ds.te_loaded_mean.values[:, 1]) > 0.01
    # heavier load, larger flank pressure, for every variant
    assert (ds.peak_flank_pressure.values[:, 1] > ds.peak_flank_pressure.values[:, 0]).all()
    for name in ("study.nc", "summary.csv", "harris_map.png", "response_surface.png", "run.json"):
        assert (out / name).is_file(), name
    assert len(list((out / "points").glob("*.nc"))) == 8
    rows = (out / "summary.csv").read_text().splitlines()
    assert len(rows) == 9 and "assembly.E_mm" in rows[0] and "peak_flank_pressure" in rows[0]
    again = run_study(study, out, workers=2, progress=False, plots=False)
    rerun = json.loads(again.attrs["run"])
    assert rerun["points_computed"] == 0 and rerun["points_skipped"] == 8 and rerun["compliance_computed"] == 0
    xr.testing.assert_identical(again.drop_attrs(), ds.drop_attrs())


@pytest.mark.slow
def test_bevel_study_point_equals_a_standalone_run(bevel_sweep):
    """One variant at one torque through ``ltca.run`` (its own synthesis and compliance) equals the study's point
    to 1e-9."""
    import ltca
    from ltca.cases import case_from_data
    from ltca.study.store import StudyStore
    study, out, _, _ = bevel_sweep
    v = study.expand()[2]
    t = study.torques[1]
    case = case_from_data(v.case, CASE)
    alone = ltca.run(case, torques_nm=[t]).dataset.isel(torque=0)
    with xr.open_dataset(StudyStore(out).point_path(v.id, t), engine="h5netcdf") as pt:
        pt = pt.load()
    for var in ("te_loaded", "te_unloaded", "max_pressure", "max_flank_pressure", "share", "root_stress_pinion",
                "root_stress_gear", "mesh_stiffness", "pattern"):
        a, b = pt[var].values, alone[var].values
        np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9 * np.nanmax(np.abs(b)), err_msg=var)
