"""Budget (Wang et al.) and machine-chain (Nguyen et al. 2020) figures by hand from the papers' formulas.

The tests in test_budget.py and test_chain.py compare with the papers' tables; some of their inputs (gear
b r_b^2, ball-spline radius, the printed zk/fp/F of Nguyen et al.) were read back from those same tables, which makes
those rows consistency checks. Here the rule-based computation is checked against hand calculations written out
from the formulas, with their sources, independent of the code path:

* Wang et al. (p. 1061), Eq. 19: B0 = (1/k_g + 1/k_a + 1/k_s + 1/k_c) T + j_phi0; Table 2 stiffnesses:
  gear mesh c = 20 N/(um mm) per face width (torsional k_g = c b r_b^2), shaft 289.44 N m/deg, ball spline
  k = 9.768e7 P^(1/3) N/m with P = T / r (deflection P / k, angle P / (k r)), diaphragm coupling 1.87e4 N m/rad.
  Shaft and coupling use Table 2 alone, so they are an independent check of Table 3's rows.
* Nguyen et al. (HaUI 56(4) 2020, Sect. 2): per element n = turns in one cycle (through the tooth
  ratios), zk = frac(n) z, fp = Fpr / z, F = fi' (zk = 0) or fi' + zk fp, dphi = 2 F / D; rotations n 360 +- dphi
  (errors on one shaft add); chain ratio error = prod(max ratios) - prod(min ratios), in % of the nominal ratio.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from fixtures.paths import CASES

DEG = math.pi / 180.0


# ---------------------------------------------------------------- Wang et al. budget
def test_budget_rows_by_hand_at_10_nm():
    from ltca.drivetrain.budget import DEG as BDEG
    from ltca.drivetrain.budget import compute_budget, load_budget_case
    T = 10.0                                                     # N m, Table 3's last column
    shaft = T / 289.44                                           # deg            = 0.0345495
    coupling = T / 1.87e4 / DEG                                  # rad -> deg     = 0.0306394
    k_gear = 20.0e3 * 20.0 * 80.0 ** 2                           # N mm/rad: c (N/mm^2) b r_b^2 = 2.56e9
    gear = T * 1e3 / k_gear / DEG                                # deg            = 2.2381e-4
    P = T / 0.016                                                # N on the balls at r = 16 mm: 625
    delta = P / (9.768e7 * P ** (1 / 3))                         # m              = 7.4837e-7
    spline = delta / 0.016 / DEG                                 # deg            = 2.6799e-3
    assert shaft == pytest.approx(0.0345495, rel=1e-5) and coupling == pytest.approx(0.0306394, rel=1e-5)
    assert gear == pytest.approx(2.2381e-4, rel=1e-4) and spline == pytest.approx(2.6799e-3, rel=1e-4)
    # Table 3 (1e-3 deg): shaft 34.55 and coupling 30.64 follow from Table 2 alone
    assert round(shaft * 1e3, 2) == 34.55 and round(coupling * 1e3, 2) == 30.64
    train, torques = load_budget_case(str(CASES / "budget_wang.toml"))
    res = compute_budget(train, torques)
    i = list(torques).index(T)
    mine = dict(zip(res.names, res.deflection[:, i] / BDEG))
    assert mine["shaft"] == pytest.approx(shaft, rel=1e-9)
    assert mine["coupling"] == pytest.approx(coupling, rel=1e-9)
    assert mine["gear"] == pytest.approx(gear, rel=1e-9)
    assert mine["spline"] == pytest.approx(spline, rel=1e-9)
    B0 = shaft + coupling + gear + spline + 0.0                  # Eq. 19, j_phi0 = 0 in the case
    assert res.hysteresis[i] / BDEG == pytest.approx(B0, rel=1e-9)
    assert B0 * 1e3 == pytest.approx(68.09, abs=0.01)            # Table 3 theoretical total


# ---------------------------------------------------------------- Nguyen et al. 2020 chain
def _by_hand(z, D, link, fi, Fpr, input_turns):
    """Nguyen et al. 2020 Sect. 2 rules, written out (see the module docstring)."""
    n = [input_turns]
    for k in range(1, len(z)):
        n.append(n[-1] * (z[k - 1] / z[k] if link[k] == "mesh" else 1.0))
    zk = [round((x - math.floor(x)) * zz, 9) for x, zz in zip(n, z)]
    F = [f if q == 0 else f + q * P / zz for f, q, P, zz in zip(fi, zk, Fpr, z)]
    dphi = [2 * f * 1e-3 / d / DEG for f, d in zip(F, D)]        # deg
    acc = list(dphi)
    for k in range(1, len(z)):
        if link[k] != "mesh":
            acc[k] += acc[k - 1]
    rot = [360.0 * x for x in n]
    i_max = i_min = i_nom = 1.0
    for k in range(1, len(z)):
        if link[k] == "mesh":
            i_max *= (rot[k] + acc[k]) / (rot[k - 1] - acc[k - 1])
            i_min *= (rot[k] - acc[k]) / (rot[k - 1] + acc[k - 1])
            i_nom *= rot[k] / rot[k - 1]
    return n, zk, F, dphi, (i_max - i_min) / i_nom * 100.0, i_nom


def test_indexing_chain_by_the_rules_by_hand():
    """Indexing chain of the 15-tooth pinion (Table 3 elements: teeth, D, fi', Fpr) with every figure by the rule:
    the paper's printed zk of b2, c2, d2 (4.5) depart from frac(6.4) z = 18, 24, 24; by the rule the chain error is
    0.1472 % (the paper prints 0.154 % with its own zk)."""
    from ltca.drivetrain.chain import evaluate_chain, load_chain_case
    # L2 rack (as Z17), Z17, Z72 | Z24, a2 | b2, c2 | d2, worm k1 | Z96; input: 2 turns of L2 (720 deg)
    z = [17, 17, 72, 24, 48, 45, 60, 60, 1, 96]
    D = [34, 34, 144, 48, 96, 90, 120, 120, 288, 288]
    link = ["input", "shaft", "shaft", "mesh", "shaft", "mesh", "shaft", "mesh", "shaft", "mesh"]
    fi = [20, 18, 20, 18, 18, 18, 18, 18, 12, 20]
    Fpr = [80, 25, 45, 25, 32, 32, 45, 45, 63, 63]
    n, zk, F, dphi, err, i_nom = _by_hand(z, D, link, fi, Fpr, 2.0)
    # the hand figures: n = 2, 2, 2, 6 (= 2 x 72/24), 6, 6.4 (= 6 x 48/45), 6.4, 6.4, 6.4, 1/15 (a tooth of 15)
    assert n[3] == 6.0 and n[5] == pytest.approx(6.4) and n[-1] == pytest.approx(1 / 15)
    assert zk[5:8] == pytest.approx([18.0, 24.0, 24.0]) and zk[8] == pytest.approx(0.4) and zk[9] == pytest.approx(6.4)
    # F: 18 + 18 x 32/45 = 30.8; 18 + 24 x 45/60 = 36; 12 + 0.4 x 63 = 37.2; 20 + 6.4 x 63/96 = 24.2
    assert F == pytest.approx([20, 18, 20, 18, 18, 30.8, 36, 36, 37.2, 24.2])
    # dphi of L2: 2 x 0.020 / 34 rad = 0.06741 deg (Table 3: 0.067)
    assert dphi[0] == pytest.approx(0.067407, abs=1e-6)
    assert i_nom == pytest.approx(1 / 30) and err == pytest.approx(0.14723, abs=1e-5)
    chain = next(c for c in load_chain_case(str(CASES / "chain_zftkk250.toml")) if c.name == "indexing_z1")
    assert [e.teeth for e in chain.elements] == z and [e.pitch_diameter for e in chain.elements] == D
    ev = evaluate_chain(chain, honour_printed=False)
    np.testing.assert_allclose(ev.zk, zk, atol=1e-9)
    np.testing.assert_allclose(ev.F, F, rtol=1e-12)
    np.testing.assert_allclose(ev.dphi, dphi, rtol=1e-12)
    assert ev.error_percent == pytest.approx(err, rel=1e-9)


def test_single_mesh_chain_by_hand():
    """Two spur gears z 30 -> 60 (m 2, D 60/120), one driver turn, fi' 10/12 um, Fpr 20/30 um: the driven gear turns
    0.5 (zk = 30, fp = 0.5 um, F = 12 + 15 = 27 um); dphi = 2 F / D: 0.019099 and 0.025783 deg; ratio band
    (180 + 0.025783) / (360 - 0.019099) - (180 - 0.025783) / (360 + 0.019099) = 1.9629e-4 (0.039258 %)."""
    from ltca.drivetrain.chain_model import Chain, ChainElement, evaluate_chain
    els = (ChainElement("a", 30, 60.0, "input", fi=10.0, Fpr=20.0),
           ChainElement("b", 60, 120.0, "mesh", fi=12.0, Fpr=30.0))
    chain = Chain("t", "indexing", 360.0, 0.5, els, reference_radius=60.0)
    ev = evaluate_chain(chain, honour_printed=False)
    d1, d2 = 2 * 0.010 / 60 / DEG, 2 * 0.027 / 120 / DEG
    assert d1 == pytest.approx(0.019099, abs=1e-6) and d2 == pytest.approx(0.025783, abs=1e-6)
    band = (180 + d2) / (360 - d1) - (180 - d2) / (360 + d1)
    assert band == pytest.approx(1.9629e-4, rel=1e-4)
    assert ev.F[1] == pytest.approx(27.0) and ev.error == pytest.approx(band, rel=1e-9)
    assert ev.error_percent == pytest.approx(band / 0.5 * 100, rel=1e-9)
