"""Spiral bevel case file: run_bevel_tca writes summary.json; case mistakes raise CaseError."""
import json

import pytest

from fixtures.paths import BEVEL_CASE
from ltca.bevel.run import bevel_benchmark, run_bevel_tca
from ltca.errors import CaseError

CASE = BEVEL_CASE


@pytest.fixture(scope="module")
def summary(tmp_path_factory):
    out = tmp_path_factory.mktemp("bevel")
    s = run_bevel_tca(str(CASE), str(out))
    return s, json.loads((out / "summary.json").read_text()), out


def test_summary_meets_seed_targets(summary):
    s, disk, _ = summary
    assert disk == json.loads(json.dumps(s))
    for label, (eta, te) in {"working": (22.0, 8.25), "coast": (-14.0, 11.25)}.items():
        f = disk["flanks"][label]
        for key in ("path_angle_deg", "te_amplitude_arcsec", "contact_ratio", "path_straightness_mm"):
            assert key in f
        assert abs(f["path_angle_deg"] - eta) < 1.0                    # Cao et al. 2008 sec. 4 targets
        assert f["te_amplitude_arcsec"] == pytest.approx(te, rel=0.05)
        # measured apart from the continuous TCA the synthesis drives: the separation-field TCA's TE range
        assert f["separation_te_range_arcsec"] == pytest.approx(te, rel=0.02)
        assert f["te_r2"] > 0.99 and f["contact_ratio"] > 1.0
    for member in ("gear", "pinion"):
        for side in ("concave", "convex"):
            assert "radial_setting_mm" in disk["machine_settings"][member][side]
    assert disk["machine_settings"]["pinion"]["concave"]["blank_offset_mm"] == 0.0   # redesigned Em1
    assert abs(disk["design"]["coast"]["blank_offset_mm"]) > 1.0                       # first design had one


def test_te_parabola_curvature_by_hand():
    """Cao et al. 2008 Eq. 2-3: TE = (m21 / 2) phi1^2 reaches the magnitude at the transfer points phi1 = +-pi / z1, so
    m21 = -2 TE / (pi / z1)^2; z1 = 12, TE = 8.25 arcsec = 3.99970e-5 rad: m21 = -1.16713e-3 rad/rad^2."""
    from ltca.geometry.bevel.synthesis import te_curvature
    te = 8.25 / 206264.806
    assert te == pytest.approx(3.99970e-5, rel=1e-5)
    assert te_curvature(te, 12) == pytest.approx(-1.16713e-3, rel=1e-5)


def test_plots_and_separation_figures(summary):
    """run_bevel_tca with ``out`` writes the three standard plots and the separation-field figures."""
    import matplotlib.image as mpimg
    s, disk, out = summary
    assert disk["plots"] == ["bearing_pattern.png", "transmission_error.png", "ease_off.png"]
    for name in disk["plots"]:
        img = mpimg.imread(out / name)
        assert img.ndim == 3 and img.shape[0] > 400 and img.shape[1] > 800
        assert img[..., :3].std() > 0.05                                  # not a blank canvas
    for label in ("working", "coast"):
        f = disk["flanks"][label]
        assert f["separation_vs_continuous_te_arcsec"] < 0.5
        assert f["separation_te_range_arcsec"] == pytest.approx(f["te_amplitude_arcsec"], rel=0.05)
        assert 1.0 < f["ease_off_max_um"] < 1000.0
    assert all(not v.startswith("undercut") for m in disk["undercut"].values() for v in m.values())


def test_benchmark_reports_medians(monkeypatch):
    """The benchmark times each stage and reports the median of the repeats: every stage replaced by a stand-in
    that advances a fake clock by a known time per repeat (synthesis 3, 1, 2 s -> median 2 s; generation 0.5 s
    per member call + 0.25 s per pinion flank; tca 5, 7, 6 s; separation 9, 8, 10 s). Speed itself is measured
    and printed, not asserted."""
    import time as _time

    import ltca.bevel.run as run
    import ltca.geometry.bevel.generation as gen
    clock = [1000.0]
    steps = {"synthesis": iter([3.0, 1.0, 2.0]), "tca": iter([5.0, 7.0, 6.0]), "separation": iter([9.0, 8.0, 10.0])}

    def advance(dt):
        clock[0] += dt

    monkeypatch.setattr(_time, "perf_counter", lambda: clock[0])
    monkeypatch.setattr(run, "BevelPair", lambda *a, **k: None)
    monkeypatch.setattr(run, "generate_member", lambda *a, **k: advance(0.5))
    monkeypatch.setattr(gen, "generate_flank", lambda *a, **k: advance(0.25))
    monkeypatch.setattr(run, "tca", lambda *a, **k: advance(next(steps["tca"])))
    monkeypatch.setattr(run, "separation_tca", lambda *a, **k: advance(next(steps["separation"])))

    class _Pin:                                        # the stand-in pinion's flanks for generate_flank
        def flank(self, side):
            return side
    monkeypatch.setattr(run, "synthesize_pinion",
                        lambda *a, **k: (advance(next(steps["synthesis"])), (_Pin(), None))[1])
    med = bevel_benchmark(repeat=3)
    assert med == {"synthesis": 2.0, "generation": 1.0, "tca": 6.0, "separation": 9.0}


@pytest.mark.parametrize("old,new,field", [("pinion_teeth = 12", "pinion_teeth = 12.5", "bevel.pinion_teeth"),
                                           ('gear_hand = "right"', 'gear_hand = "up"', "bevel.gear_hand"),
                                           ("te_magnitude_arcsec = 8.25", "te_magnitude_arcsec = -1",
                                            "bevel.working.te_magnitude_arcsec"),
                                           ("path_angle_deg = 22.0", "path_angel_deg = 22.0",
                                            "bevel.working.path_angel_deg")])
def test_case_mistakes_raise_case_error(tmp_path, old, new, field):
    text = CASE.read_text()
    assert old in text
    p = tmp_path / "bad.toml"
    p.write_text(text.replace(old, new, 1))
    with pytest.raises(CaseError) as exc:
        run_bevel_tca(str(p), None)
    assert exc.value.field == field
