"""The Python API as a research user scripts it: a shipped case by name, a changed value, a run at two torques, TE
plotted into a given Axes, a figure read from the summary, in a process with a non-Agg backend that the library
must leave alone and without a line printed. One result vocabulary across the gear kinds."""
from __future__ import annotations

import math

import matplotlib
import numpy as np
import pytest
from matplotlib.figure import Figure

import ltca
from fixtures.paths import ROOT
from ltca.errors import CaseError


@pytest.fixture
def svg_backend():
    """A non-Agg backend for the test; the library must not change it."""
    old = matplotlib.get_backend()
    matplotlib.use("svg")
    yield "svg"
    matplotlib.use(old)


def _check_result(res, ax, capfd, backend):
    assert matplotlib.get_backend() == backend
    out = capfd.readouterr()
    assert out.out == "" and out.err == ""
    assert len(ax.lines) >= 2
    ds = res.dataset
    assert {"torque", "position", "cycle"} <= set(ds.coords)
    for f, t in zip(res.figures, ds.torque.values):
        assert f.torque_nm == pytest.approx(float(t))
        assert f.te_loaded_ptp_arcsec == pytest.approx(float(np.ptp(ds.te_loaded.sel(torque=t).values)), rel=1e-6)
        assert f.converged and f.max_torque_residual < 1e-6
    assert res.summary["te_loaded_ptp_arcsec"] == pytest.approx(res.figures[0].te_loaded_ptp_arcsec)
    # more torque, more elastic lag of the driven member: the TE mean grows with the torque (positive = lag)
    assert res.figures[1].te_loaded_mean_arcsec > res.figures[0].te_loaded_mean_arcsec > 0


def test_five_lines_cylindrical(svg_backend, capfd):
    ax = Figure().add_subplot()
    case = ltca.load_case("fzg_c14").with_values({"assembly.lead_misalignment_um": 10.0, "analysis.positions": 4,
                                                   "analysis.fidelity": "coarse"})
    res = ltca.run(case, torques_nm=[100.0, 200.0])
    res.dataset.ltca.plot_te(ax=ax)
    assert res.figures[1].mesh_stiffness_mean_n_per_mm_um > 10
    _check_result(res, ax, capfd, svg_backend)
    assert case.record.lead_misalignment == pytest.approx(0.010)
    # both stiffness figures: per face width times the face width is the total
    f = res.figures[0]
    assert f.mesh_stiffness_mean_n_per_um == pytest.approx(f.mesh_stiffness_mean_n_per_mm_um * 14.0, rel=1e-5)


@pytest.mark.heavy
def test_five_lines_bevel(svg_backend, capfd, tmp_path):
    ax = Figure().add_subplot()
    case = ltca.load_case("spiral_bevel_cao2008").with_values({"assembly.E_mm": 0.05})
    res = ltca.run(case, torques_nm=[100.0, 175.0], positions=4, fidelity="coarse")
    res.dataset.ltca.plot_te(ax=ax)
    _check_result(res, ax, capfd, svg_backend)
    f = res.figures[1]
    assert f.max_contact_pressure_mpa >= f.max_flank_pressure_mpa > 0
    assert f.mesh_stiffness_mean_n_per_mm_um == pytest.approx(f.mesh_stiffness_mean_n_per_um / case.record.basic.face_width, rel=1e-9)
    # saved and read back: the same numbers
    res.save(tmp_path / "run", report=False)
    ds, head = ltca.open_result(tmp_path / "run")
    assert head["te_loaded_ptp_arcsec"] == pytest.approx(res.figures[0].te_loaded_ptp_arcsec)
    np.testing.assert_allclose(ds.te_loaded.values, res.dataset.te_loaded.values, rtol=1e-12)
    assert ds.ltca.plot_te(ax=Figure().add_subplot()).lines


@pytest.mark.slow
def test_five_lines_planetary(svg_backend, capfd):
    ax = Figure().add_subplot()
    case = ltca.load_case("eccentric_planetary_satellite").with_values({"analysis.positions": 3})
    res = ltca.run(case, torques_nm=[1000.0, 2000.0])
    res.dataset.ltca.plot_te(ax=ax)
    _check_result(res, ax, capfd, svg_backend)


def test_with_values_validates_and_copies():
    case = ltca.load_case("fzg_c14")
    new = case.with_values({"load.torque_nm": [50.0, 150.0]})
    assert new.record.torques == (50e3, 150e3) and case.record.torques != new.record.torques
    assert new.name == case.name and new.kind == "cylindrical"
    with pytest.raises(CaseError, match="lead_misalignmen_um"):
        case.with_values({"assembly.lead_misalignmen_um": 1.0})
    with pytest.raises(CaseError, match=r"\[15, 45\]"):
        ltca.load_case("spiral_bevel_cao2008").with_values({"bevel.spiral_angle_deg": 80.0})
    with pytest.raises(CaseError, match="shipped"):
        ltca.load_case("no_such_case")


def test_every_kind_loads_by_name():
    kinds = {n: ltca.load_case(n).kind for n in ("fzg_c14", "helical_c14", "internal_spur", "spiral_bevel_cao2008",
                                                 "eccentric_planetary_satellite", "budget_wang", "chain_zftkk250")}
    assert kinds == {"fzg_c14": "cylindrical", "helical_c14": "cylindrical", "internal_spur": "cylindrical",
                     "spiral_bevel_cao2008": "bevel", "eccentric_planetary_satellite": "planetary",
                     "budget_wang": "budget", "chain_zftkk250": "chain"}
    with pytest.raises(CaseError, match="ltca budget"):
        ltca.run(ltca.load_case("budget_wang"))


def test_bad_run_settings_are_refused_before_work():
    case = ltca.load_case("fzg_c14")
    for kw, field in (({"positions": 0}, "positions"), ({"fidelity": "medium"}, "--fidelity"),
                      ({"torques_nm": [math.nan]}, "--torque")):
        with pytest.raises(CaseError, match=field):
            ltca.run(case, **kw)
    with pytest.raises(CaseError, match="--torque"):
        ltca.run(ltca.load_case("spiral_bevel_cao2008"), torques_nm=[0.0])


@pytest.mark.heavy
def test_readme_python_example_runs_as_written(svg_backend, capfd):
    """The README's five lines, executed as they stand (the plot goes to a new Figure, not a window)."""
    import re
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    code = re.search(r"## Five lines of Python\n\n```python\n(.*?)```", text, re.S).group(1)
    assert len(code.strip().splitlines()) == 5
    scope: dict = {}
    exec(compile(code, "README.md", "exec"), scope)
    out = capfd.readouterr().out.split()
    assert len(out) == 2 and float(out[0]) > 0 and float(out[1]) > 500     # TE ptp (arcsec), flank peak (MPa)
    assert scope["ax"].lines and matplotlib.get_backend() == svg_backend


def test_tca_of_every_gear_kind_prints_nothing(capfd):
    """``ltca.tca``: the unloaded analysis as a record; a conjugate spur pair has zero unloaded TE (an identity)."""
    r = ltca.tca("fzg_c14", positions=8)
    assert r.summary["te_unloaded_ptp_arcsec"] < 0.01 and 1.2 < r.summary["contact_ratio_transverse"] < 2.0
    b = ltca.tca(ltca.load_case("spiral_bevel_cao2008"))
    # the synthesis meets its target: the parabolic TE of the working flank (Cao et al. 2008: 8.25 arcsec)
    assert b.summary["flanks"]["working"]["te_amplitude_arcsec"] == pytest.approx(8.25, rel=0.02)
    out = capfd.readouterr()
    assert out.out == "" and out.err == ""
