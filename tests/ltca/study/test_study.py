"""Studies on Dask: ISO 1328-1 tolerances by hand, Monte Carlo draws, bad study files, identity with a
standalone ``ltca run``, one compliance per geometry, a killed worker, a killed client and its rerun, the README
example. Coarse fidelity and 4 positions per cycle throughout (each test well under a minute on 2 cores)."""
from __future__ import annotations

import math
import os
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from fixtures.paths import ROOT
from ltca.cli import main
from ltca.errors import CaseError

FAST = {"analysis.fidelity": "coarse", "analysis.positions": 4}


def study_dict(grid: dict, torques=(100.0, 200.0), **extra) -> dict:
    return {"study": {"name": "test", "case": str(ROOT / "cases" / "fzg_c14.toml"), "torque_nm": list(torques)},
            "set": dict(FAST), "grid": grid, **extra}


def write_study(path: Path, text: str) -> Path:
    path.write_text(f'[study]\nname = "t"\ncase = "{ROOT / "cases" / "fzg_c14.toml"}"\n' + text)
    return path


# ------------------------------------------------------------------------------------------ ISO 1328
def test_iso1328_rounding_rules():
    from ltca.study.iso1328 import iso1328_round
    assert iso1328_round(12.49) == 12.0 and iso1328_round(10.4) == 10.0 and iso1328_round(10.6) == 11.0
    assert iso1328_round(7.3) == 7.5 and iso1328_round(7.2) == 7.0 and iso1328_round(5.0) == 5.0
    assert iso1328_round(4.25) == 4.3 and iso1328_round(4.94) == 4.9 and iso1328_round(0.04) == 0.0


def test_iso1328_tolerances_of_the_fzg_pinion_by_hand():
    """FZG C14 pinion, class 6: z = 16, m_n = 4.5 mm, b = 14 mm, d = 72 mm, step sqrt(2)."""
    from ltca.study.iso1328 import iso1328_tolerances
    t = iso1328_tolerances(6, 16, 4.5, 14.0)
    s, d, m, b = math.sqrt(2), 72.0, 4.5, 14.0
    fpt = (0.001 * d + 0.4 * m + 5) * s                              # 9.7185 -> 9.5 (5..10: nearest 0.5)
    Fp = (0.002 * d + 0.55 * math.sqrt(d) + 0.7 * m + 12) * s        # 28.229 -> 28
    fHa = (0.4 * m + 0.001 * d + 4) * s                              # 8.3043 -> 8.5
    ffa = (0.55 * m + 5) * s                                         # 10.571 -> 11
    fHb = (0.05 * math.sqrt(d) + 0.35 * math.sqrt(b) + 4) * s        # 8.1089 -> 8.0
    ffb = (0.07 * math.sqrt(d) + 0.45 * math.sqrt(b) + 4) * s        # 8.8780 -> 9.0
    assert (fpt, Fp, fHa, ffa, fHb, ffb) == pytest.approx((9.7185, 28.229, 8.3043, 10.571, 8.1089, 8.8780),
                                                          abs=1e-3)
    assert math.hypot(fHa, ffa) == pytest.approx(13.443, abs=1e-3) and 0.9 * Fp == pytest.approx(25.406, abs=1e-3)
    assert (t.f_pT, t.F_pT, t.f_HalphaT, t.f_falphaT, t.F_alphaT) == (9.5, 28.0, 8.5, 11.0, 13.0)
    assert (t.f_HbetaT, t.f_fbetaT, t.F_betaT, t.F_rT) == (8.0, 9.0, 12.0, 25.0)
    # class 5 of the gear (z = 24, d = 108 mm): f_pT = 0.108 + 1.8 + 5 = 6.908 -> 7.0
    assert iso1328_tolerances(5, 24, 4.5, 14.0).f_pT == 7.0
    with pytest.raises(CaseError, match="monte_carlo.grade"):
        iso1328_tolerances(12, 16, 4.5, 14.0)


def test_monte_carlo_draws_conform_and_map_onto_case_keys():
    from ltca.study.montecarlo import check_draws, member_tolerances
    from ltca.study.spec import Study
    st = Study.from_dict(study_dict({}, torques=(200.0,), monte_carlo={"grade": 6, "samples": 60, "seed": 3}))
    vs = st.expand()
    assert len(vs) == 60 and len({v.id for v in vs}) == 60
    again = Study.from_dict(study_dict({}, torques=(200.0,), monte_carlo={"grade": 6, "samples": 5, "seed": 3}))
    assert [v.id for v in again.expand()] == [v.id for v in vs[:5]]        # sample i does not depend on n
    mods = vs[0].case["pinion"]["modifications"]
    assert len(mods["pitch_errors_um"]) == 16 and {"profile_slope_um", "profile_form_um", "lead_slope_um",
                                                   "lead_form_um"} <= set(mods)
    from ltca.case import parse_case
    case = parse_case(vs[0].case)
    tols = {m: member_tolerances(case, m, 6) for m in ("pinion", "gear")}
    checks = check_draws([v.drawn for v in vs], tols)
    assert all(c["within"] == 1.0 for c in checks.values())
    assert checks["pinion.f_Halpha"]["ks_p"] > 1e-3 and checks["gear.F_r"]["ks_p"] > 1e-3


# ------------------------------------------------------------------------------------------ bad files
@pytest.mark.parametrize("text, field", [
    ('[grid]\n"assembly.lead_misalignmnt_um" = [0.0]\n', "grid.assembly.lead_misalignmnt_um"),
    ('[grid]\n"assembly.lead_misalignment_um" = []\n', "grid.assembly.lead_misalignment_um"),
    ('[monte_carlo]\ngrade = 6\nsamples = 0\n', "monte_carlo.samples"),
    ('[[variants]]\nname = "x"\n"pinion.modifications.crowning_um" = 3.0\n', "variants[0].pinion.modifications."),
    ('[grid]\n"assembly.lead_misalignment_um" = [0.0, 900.0]\n', "assembly.lead_misalignment_um"),
])
def test_bad_study_files_exit_2_naming_the_field(tmp_path, capsys, text, field):
    path = write_study(tmp_path / "bad.toml", text)
    assert main(["study", str(path), "--out", str(tmp_path / "out"), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert field in err and "Traceback" not in err


# ------------------------------------------------------------------------------------------ runs
@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    """2 torques x 2 misalignments on one geometry, LocalCluster of 2 workers."""
    from ltca.study import Study, run_study
    out = tmp_path_factory.mktemp("sweep")
    study = Study.from_dict(study_dict({"assembly.lead_misalignment_um": [0.0, 10.0]}))
    return study, out, run_study(study, out, workers=2, progress=False, plots=True)


@pytest.mark.heavy
def test_one_compliance_per_geometry(sweep):
    import json
    study, out, ds = sweep
    run = json.loads(ds.attrs["run"])
    assert run["compliance_computed"] == 1 and run["points_computed"] == 4 and run["workers"] == 2
    assert ds.sizes["variant"] == 2 and ds.sizes["torque"] == 2 and np.isfinite(ds.te_loaded.values).all()
    assert list(ds["assembly.lead_misalignment_um"].values) == [0.0, 10.0]
    for name in ("study.nc", "summary.csv", "harris_map.png", "response_surface.png"):
        assert (out / name).is_file()


@pytest.mark.heavy
def test_each_variant_equals_a_standalone_run(sweep, tmp_path):
    """The misaligned variant through ``ltca run`` (its own compliance) equals the study's points to 1e-9."""
    from ltca.study.spec import to_toml
    from ltca.study.store import StudyStore
    study, out, _ = sweep
    v = study.expand()[1]
    case = tmp_path / "variant.toml"
    case.write_text(to_toml(v.case))
    assert main(["run", str(case), "--out", str(tmp_path / "run"), "--quiet"]) == 0
    alone = xr.open_dataset(tmp_path / "run" / "results.nc", engine="h5netcdf").load()
    for j, t in enumerate(study.torques):
        pt = xr.open_dataset(StudyStore(out).point_path(v.id, t), engine="h5netcdf").load()
        ref = alone.isel(torque=j)
        for var in ("te_loaded", "te_unloaded", "max_pressure", "pair_load", "root_stress_pinion",
                    "root_stress_gear", "mesh_stiffness", "pressure"):
            a, b = pt[var].values, ref[var].values
            if var == "pressure":        # run_case joins the torques' flank lattices (outer): pick this one's
                b = ref[var].sel(flank_roll=pt.flank_roll.values).values
            np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-9 * np.nanmax(np.abs(b)), err_msg=var)


def _points(out: Path) -> list[Path]:
    return sorted((out / "points").glob("*.nc")) if (out / "points").is_dir() else []


@pytest.mark.heavy
def test_a_killed_worker_loses_nothing(tmp_path):
    """Kill a worker process while it solves a point: the study completes, every point once."""
    import json

    from distributed import Client, LocalCluster

    from ltca.study import Study, run_study
    study = Study.from_dict(study_dict({"assembly.lead_misalignment_um": [0.0, 5.0, 10.0]},
                                       torques=(50.0, 100.0, 150.0, 200.0)))
    out = tmp_path / "out"
    box = {}
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        th = threading.Thread(target=lambda: box.update(ds=run_study(study, out, scheduler=cluster.scheduler_address,
                                                                     progress=False, plots=False)))
        th.start()
        killed = None
        t0 = time.time()
        while killed is None and time.time() - t0 < 120 and th.is_alive():
            busy = [w for w, keys in client.processing().items() if any("point-" in str(k) for k in keys)]
            if _points(out) and busy:
                pid = client.run(os.getpid, workers=[busy[0]])[busy[0]]
                os.kill(pid, signal.SIGKILL)
                killed = pid
            time.sleep(0.05)
        th.join(180)
    assert killed is not None, "no worker was busy with a point"
    ds = box["ds"]
    run = json.loads(ds.attrs["run"])
    names = [p.name for p in _points(out)]
    assert len(names) == len(set(names)) == 12 and run["points_computed"] == 12
    assert np.isfinite(ds.te_loaded_ptp.values).all()


@pytest.mark.heavy
def test_a_killed_client_reruns_only_what_is_missing(tmp_path):
    """``ltca study`` killed (with its LocalCluster) after some points; the rerun computes only the rest."""
    import json

    from ltca.study import run_study
    text = ('[set]\n"analysis.fidelity" = "coarse"\n"analysis.positions" = 4\n'
            '[grid]\n"load.torque_nm" = [50.0, 100.0, 150.0, 200.0]\n"assembly.lead_misalignment_um" = [0.0, 10.0]\n')
    path = write_study(tmp_path / "s.toml", text)
    out = tmp_path / "out"
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    proc = subprocess.Popen([sys.executable, "-m", "ltca.cli", "study", str(path), "--out", str(out), "--workers",
                             "1", "--quiet"], env=env, start_new_session=True, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    try:
        t0 = time.time()
        while len(_points(out)) < 2 and time.time() - t0 < 120 and proc.poll() is None:
            time.sleep(0.05)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    done = len(_points(out))
    assert 2 <= done < 8, done
    ds = run_study(path, out, workers=1, progress=False, plots=False)
    run = json.loads(ds.attrs["run"])
    assert run["points_skipped"] == done and run["points_computed"] == 8 - done
    assert run["compliance_computed"] + run["compliance_loaded"] == 1
    assert len(_points(out)) == 8 and np.isfinite(ds.te_loaded_ptp.values).all()


@pytest.mark.heavy
def test_readme_example_runs(tmp_path, monkeypatch):
    """The example of docs/guide/studies.md, run as it stands (its output directory moved to tmp_path)."""
    text = (ROOT / "docs" / "guide" / "studies.md").read_text()
    section = text
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(ROOT)
    code = code.replace('"out/study_example"', repr(str(tmp_path / "example")))
    exec(compile(code, "studies.md", "exec"), {})
    assert (tmp_path / "example" / "study.nc").is_file()
