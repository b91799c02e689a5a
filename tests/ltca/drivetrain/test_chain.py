"""Machine-chain ratio errors against Nguyen et al. (J. Sci. & Tech. HaUI 56(4) 2020).

Printed results (Sect. 3 and 4): indexing 0.154 % (z1 = 15, Table 4) and 0.23 % (z2 = 30, Table 6),
pitch errors 20.64 um / 30.46 um (Tables 4, 6: 20.640953, 30.45528), envelope 0.205 % (z1, Table 8:
0.204921353) and 0.154 % (z2, Table 9: 0.153606273).

Where the paper's arithmetic departs from its own rules (kept via printed values in the case file):
* Table 3: zk = 4.5 for b2, c2, d2 at n = 6.4 turns; frac(n) z gives 18, 24, 24.
* Tables 3, 5: fp printed as Fpr/(2z) for spur gears and Fpr/48 for the worm pair, not Fpr/z.
* Table 5 copies Fpr and fp of a2..d2 from Table 3 (gears 48/45/60/60 instead of 40/60/48/60).
* Table 7: dphi of a2, b2, c2, d2, worm is 2 F n / D (n = 30.75 or 32.80 turns), elsewhere 2 F / D.
* Table 6: 0.23 % is 3.78e-5 / 0.0167 (rounded ratio) = 0.226 %; with 1/60 it is 0.227 %.
* Table 1's modules for Z17/Z72/Z24 (3), z96 (3.15) and z120 (5.6) disagree with the printed dphi.
"""
from __future__ import annotations

import numpy as np
import pytest

from fixtures.paths import CASES
from ltca.drivetrain.chain import evaluate_chain, load_chain_case, pitch_deviation_bound, roll_ratio_error, run_chain
from ltca.errors import CaseError
from ltca.geometry.errors import random_pitch_deviations, worst_case_pitch_deviations

CASE = str(CASES / "chain_zftkk250.toml")


@pytest.fixture(scope="module")
def evs():
    return {c.name: evaluate_chain(c) for c in load_chain_case(CASE)}


def test_indexing_z1_table3_4(evs):
    """Consistency check: the printed zk, fp and F of Table 3 are inputs (the case file), so this reproduces the
    paper's arithmetic; the rules by hand are in test_drivetrain_hand.py."""
    ev = evs["indexing_z1"]
    # Table 3 F and dphi columns from fi, Fpr and the printed zk, fp
    np.testing.assert_allclose(ev.F, [20, 18, 20, 18, 18, 19.6, 19.6875, 19.6875, 12.525, 28.4])
    np.testing.assert_allclose(np.round(ev.dphi, 3),
                               [0.067, 0.061, 0.016, 0.043, 0.021, 0.025, 0.019, 0.019, 0.005, 0.011])
    np.testing.assert_allclose(np.round(ev.rot_max[1:], 2),
                               [720.13, 720.14, 2160.04, 2160.06, 2304.02, 2304.04, 2304.02,
                                2304.02, 24.01])
    assert ev.error == pytest.approx(5.126e-5, abs=5e-9)             # Table 4
    assert round(ev.error_percent, 3) == 0.154
    assert ev.angle_error_deg == pytest.approx(0.0369052, abs=5e-8)  # Table 4
    assert ev.pitch_error_um == pytest.approx(20.640953, abs=5e-6)   # Table 4


def test_indexing_z2_table5_6(evs):
    """Consistency check (printed zk, fp, F and the turns factor of the tables are inputs)."""
    ev = evs["indexing_z2"]
    np.testing.assert_allclose(ev.F[3:], [18, 18, 18, 18, 22.5, 12.225, 24.2])          # Table 5
    np.testing.assert_allclose(np.round(ev.dphi[3:], 4),
                               [0.0430, 0.0258, 0.0172, 0.0215, 0.0215, 0.0049, 0.0096])
    assert ev.error == pytest.approx(3.78e-5, abs=5e-8)               # Table 6
    assert round(ev.error_percent, 2) == 0.23
    assert ev.angle_error_deg == pytest.approx(0.027226, abs=5e-7)
    assert ev.pitch_error_um == pytest.approx(30.45528, abs=5e-5)     # Table 6
    assert round(ev.pitch_error_um, 2) == 30.46                        # Sect. 4


def test_envelope_z1_table7_8(evs):
    """Consistency check (printed zk, fp, F and the turns factor of the tables are inputs)."""
    ev = evs["envelope_z1"]
    np.testing.assert_allclose(np.round(ev.dphi, 2),                   # Table 7 dphi column
                               [0.01, 0.00, 0.13, 0.08, 0.03, 0.02, 0.02, 0.06, 0.08, 0.07, 0.07,
                                0.07, 0.07, 0.07, 0.07, 0.11, 0.07, 0.07, 0.06, 0.08, 0.02, 0.08,
                                0.03, 0.66, 0.79, 0.59, 0.59, 0.17, 0.03], atol=1e-9)
    assert np.round(ev.ratio_max[0], 5) == 120.02880 and np.round(ev.ratio_min[0], 5) == 119.97122
    assert ev.i_nom == pytest.approx(2.23655914, abs=5e-9)             # Table 8
    assert ev.i_max == pytest.approx(2.23885194, abs=5e-8)             # F printed to 0.01 um
    assert ev.i_min == pytest.approx(2.23426876, abs=5e-8)
    assert ev.error_percent == pytest.approx(0.204921353, abs=5e-6)
    assert round(ev.error_percent, 3) == 0.205
    rr = roll_ratio_error(ev)                                          # 0.745193 vs 0.745356
    assert rr.nominal - 1 == pytest.approx(0.745356 / 0.745193 - 1, abs=2e-6)
    assert rr.low < rr.nominal < rr.high


def test_envelope_z2_table9_reconstructed(evs):
    """Table 9 prints only totals; rows a2..Z96 are reconstructed (see the case file)."""
    ev = evs["envelope_z2"]
    assert ev.i_nom == pytest.approx(1.11827957, abs=5e-9)
    assert round(ev.error_percent, 3) == 0.154                          # Sect. 4
    assert ev.error_percent == pytest.approx(0.153606273, abs=5e-4)    # 0.15387, not all digits
    assert ev.i_max == pytest.approx(1.119138766, rel=2e-6)


def test_recomputed_by_rules_differs(evs):
    chains = {c.name: c for c in load_chain_case(CASE)}
    again = evaluate_chain(chains["indexing_z1"], honour_printed=False)
    np.testing.assert_allclose(again.zk[5:8], [18, 24, 24])            # frac(6.4) z
    assert again.error_percent == pytest.approx(0.1472, abs=1e-4)   # by hand: test_drivetrain_hand.py
    with pytest.raises(ValueError, match="fi and Fpr"):
        evaluate_chain(chains["envelope_z1"], honour_printed=False)


def test_pitch_deviations(evs):
    bound = pitch_deviation_bound(evs["indexing_z1"])
    assert bound == pytest.approx(0.5 * 20.640953e-3, rel=1e-6)        # mm
    for z in (15, 30):
        for pattern in ("alternating", "half"):
            dev = worst_case_pitch_deviations(z, bound, pattern)
            assert abs(dev.sum()) < 1e-15 and np.max(np.abs(dev)) == pytest.approx(bound)
    assert np.max(np.cumsum(worst_case_pitch_deviations(15, bound, "half"))) == pytest.approx(7 * bound)
    a = random_pitch_deviations(15, bound, seed=7, draws=200)
    b = random_pitch_deviations(15, bound, seed=7, draws=200)
    c = random_pitch_deviations(15, bound, seed=8, draws=200)
    np.testing.assert_array_equal(a, b)
    assert not np.allclose(a, c)
    assert a.shape == (200, 15)
    assert np.all(np.abs(a) <= bound * (1 + 1e-12))
    assert np.max(np.abs(np.cumsum(a, axis=1)[:, -1])) < 1e-15         # closes over a revolution
    assert np.max(np.abs(a)) > 0.9 * bound                             # uses the band


def test_run_chain(tmp_path, capsys):
    res = run_chain(CASE, str(tmp_path))
    out = capsys.readouterr().out
    assert "20.6410 um" in out and "0.2049 %" in out
    assert res["indexing_z2"].pitch_error_um == pytest.approx(30.45528, abs=5e-5)
    assert res.recomputed[2] is None
    assert (tmp_path / "chain_envelope_z1.csv").read_text().count("\n") == 30


BASE = """[workpiece]
normal_module_mm = 3.5
spiral_angle_deg = 35.0
[[chain]]
name = "t"
kind = "indexing"
workpiece_teeth = {zp}
input_turn_deg = 720.0
[[chain.element]]
name = "A"
teeth = {za}
pitch_diameter_mm = 48.0
link = "input"
fi_um = {fi}
Fpr_um = 25.0
[[chain.element]]
name = "B"
teeth = 96
pitch_diameter_mm = 192.0
link = "mesh"
fi_um = 20.0
Fpr_um = 45.0
"""


@pytest.mark.parametrize("kw,field", [
    ({"zp": 0}, "chain[0].workpiece_teeth"),
    ({"za": 0}, "chain[0].element[0].teeth"),
    ({"fi": -1.0}, "chain[0].element[0].fi_um"),
    ({"zp": 31}, "chain[0].element"),          # 2 turns x 24/96 = 1/2 turn, not 1/31: no closure
    ({"za": "\"24\""}, "chain[0].element[0].teeth"),
])
def test_bad_chain_names_field(tmp_path, kw, field):
    args = {"zp": 2, "za": 24, "fi": 18.0} | kw     # zp = 2 closes: 2 turns x 24/96 = 1/zp turn
    p = tmp_path / "c.toml"
    p.write_text(BASE.format(**args))
    with pytest.raises(CaseError) as exc:
        load_chain_case(str(p))
    assert exc.value.field == field


def test_unknown_key_and_link(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text(BASE.format(zp=2, za=24, fi=18.0).replace("Fpr_um = 45.0", "Fpr_um = 45.0\nteth = 3"))
    with pytest.raises(CaseError, match="teth"):
        load_chain_case(str(p))
    p.write_text(BASE.format(zp=2, za=24, fi=18.0).replace('link = "mesh"', 'link = "input"'))
    with pytest.raises(CaseError) as exc:
        load_chain_case(str(p))
    assert exc.value.field == "chain[0].element[1].link"


def test_good_small_chain_closes(tmp_path):
    p = tmp_path / "c.toml"
    p.write_text(BASE.format(zp=2, za=24, fi=18.0))   # 2 turns x 24/96 = 1/2 turn = 1/zp per step
    (chain,) = load_chain_case(str(p))
    assert evaluate_chain(chain).closure == pytest.approx(0.0, abs=1e-15)
