"""Kapitonov et al.: the central wheel at e = m, interference of the internal pair, minimum thinning, unloaded gaps.

Hand numbers used below (z1 50, z2 51, m 3, alpha 20 deg, x1 -0.5, wheel x2 0, e = m):
  cos(alpha_w) = m (z2 - z1) cos(alpha) / (2 e) = cos(20 deg) / 2  ->  alpha_w = 61.976 deg
  zero backlash: x2 + k / (2 tan(alpha)) = x1 + (inv(alpha_w) - inv(alpha)) (z2 - z1) / (2 tan(alpha)) = 0.5746
  so with x2 = 0 the satellite fits for k_fit = 2 tan(alpha) 0.5746 = 0.4182, and a satellite thinned by k
  has the circumferential backlash (k - k_fit) m r_w1 / r1 on the working circle, i.e. (k - k_fit) m cos(alpha)
  along the line of action: -1179.1 um unthinned (the flanks overlap), +512.4 um at the paper's k = 0.6.
"""
import numpy as np
import pytest

from ltca.geometry.satellite.forming import form_special_hob
from ltca.geometry.satellite.interference import analyse_interference, margin, minimum_thinning
from ltca.geometry.satellite.mesh import EccentricMesh
from ltca.geometry.satellite.separation import unloaded_gaps
from ltca.geometry.satellite.tools import SatelliteDesign
from ltca.geometry.satellite.wheel import CentralWheelDesign, generate_central_wheel, wheel_shift
from ltca.geometry.transverse import inverse_involute, involute

DEG = np.pi / 180
A20, M = 20 * DEG, 3.0
SEED = SatelliteDesign()
AW = np.arccos(np.cos(A20) / 2)
X2_ZB = -0.5 + (involute(AW) - involute(A20)) / (2 * np.tan(A20))
K_FIT = 2 * np.tan(A20) * X2_ZB


def sat(k):
    return form_special_hob(SatelliteDesign(thinning=k)).profile


@pytest.fixture(scope="module")
def wheel():
    return generate_central_wheel(SEED)


def test_central_wheel_centre_distance_is_m(wheel):
    prof, ch = wheel
    assert ch.z2 == 51 and ch.x2 == 0.0 and abs(np.degrees(ch.alpha_w) - 61.9757) < 1e-3
    assert abs(ch.x2_zero_backlash - X2_ZB) < 1e-12 and abs(X2_ZB - 0.57456) < 1e-4
    assert abs(ch.thinning_fit - K_FIT) < 1e-12 and abs(K_FIT - 0.41825) < 1e-4
    # centre distance from the involute-function equation for the chosen wheel and the fitting thinning
    aw = inverse_involute(involute(A20) + 2 * np.tan(A20) * (ch.x2 + K_FIT / (2 * np.tan(A20)) + 0.5) / 1)
    a = M * (51 - 50) / 2 * np.cos(A20) / np.cos(aw)
    assert abs(a - M) < 1e-9
    # ... and on the generated profiles: base radii give alpha_w at e = m, zero backlash at k_fit
    mesh = EccentricMesh(sat(K_FIT), prof, M)
    assert abs((prof.r_base - mesh.sat.r_base) / np.cos(mesh.alpha_w) - M) < 1e-9
    assert abs(mesh.backlash) < 1e-6
    # the wheel: standard root r2 + 1.25 m, tip bored to leave 0.5 mm to the satellite tips opposite the mesh
    assert abs(prof.r_root - 80.25) < 1e-6 and abs(prof.r_tip - 74.0) < 1e-12
    # tooth difference 2 at e = m: alpha_w = alpha and x2 = x1
    c2 = wheel_shift(SEED, 2)
    assert abs(c2.alpha_w - A20) < 1e-12 and abs(c2.x2_zero_backlash + 0.5) < 1e-12


@pytest.fixture(scope="module")
def unthinned(wheel):
    return analyse_interference(EccentricMesh(sat(0.0), wheel[0], M), n_positions=12)


def test_no_thinning_interferes(unthinned):
    r = unthinned
    assert r.interferes
    hand = K_FIT * M * np.cos(A20) * 1e3                       # 1179.1 um flank overlap along the LOA
    assert abs(r.margin_um + hand) < 0.5 and abs(hand - 1179.1) < 0.1
    inv = r.kinds["involute"]
    assert abs(inv.depth_um - hand) < 1.0
    assert 30 < abs(inv.psi_deg) < 55                          # the mesh zone at alpha_w = 62 deg: +-40 deg
    assert r.kinds["tip"].depth_um > 0.9 * hand                # tip corners into the flanks, same depth
    assert "fillet" in r.kinds and r.kinds["fillet"].r_satellite < 71.6     # below the form circle 71.58
    for kd, p in r.kinds.items():
        print(f"unthinned: {kd:9s} {p.depth_um:8.1f} um pair {p.pair:+d} psi {p.psi_deg:+7.1f} deg "
              f"r_sat {p.r_satellite:.3f} r_wheel {p.r_wheel:.3f} phi {p.phi:.4f} dir {p.direction:+d}")
    # both directions (mirror images): the same kinds and the same deepest penetration (the split between
    # kinds at a deep overlap follows the nearest boundary, which the mirrored sampling may tip either way)
    assert set(r.by_direction[1]) == set(r.by_direction[-1])
    deepest = [max(p.depth_um for p in r.by_direction[d].values()) for d in (1, -1)]
    assert abs(deepest[0] - deepest[1]) < 0.01 * deepest[0]
    tro = r.kinds["trochoid"]                                  # tip against tip, away from the mesh
    assert 120 < abs(tro.psi_deg) < 150 and abs(tro.r_wheel - 74.0) < 0.01 and tro.depth_um > 250


def test_seed_thinning_removes_interference(wheel):
    mesh = EccentricMesh(sat(0.6), wheel[0], M)
    r = analyse_interference(mesh, n_positions=12)
    assert not r.interferes and not r.kinds
    hand = (0.6 - K_FIT) * M * np.cos(A20) * 1e3               # 512.4 um free play along the LOA
    assert abs(r.free_play_um - hand) < 0.5 and abs(hand - 512.4) < 0.1
    assert abs(r.backlash - (0.6 - K_FIT) * M * 2) < 1e-6       # circumferential on r_w1 = 2 r1


def test_minimum_thinning(wheel):
    t = minimum_thinning(SEED, wheel[0], M, n_positions=16)
    print(f"minimum thinning k = {t.k_min:.4f} (hand {K_FIT:.4f}), seed 0.6, "
          f"margin at seed {t.margin_at_seed_um:.3f} um")
    assert 0 < t.k_min < 0.6
    assert abs(t.k_min - K_FIT) < 2e-3
    assert t.margin_at_seed_um > -0.1


def test_standard_wheel_tip_keeps_tip_to_tip_interference():
    # standard tip d_a2 = d2 - 2 m = 147 mm: the tip circles touch opposite the mesh, where a tooth difference
    # of one sets tooth against tooth; thinning cannot cure that (no k below the pointed limit does)
    prof, ch = generate_central_wheel(SEED, CentralWheelDesign(far_tip_clearance=0.0))
    assert abs(prof.r_tip - 73.5) < 1e-12
    r = analyse_interference(EccentricMesh(sat(0.6), prof, M), n_positions=12)
    assert r.interferes
    tro = r.kinds["trochoid"]
    assert abs(abs(tro.psi_deg) - 156) < 5 and abs(tro.r_wheel - 73.5) < 0.01
    assert abs(tro.depth_um - 262) < 13
    assert np.isnan(minimum_thinning(SEED, prof, M, n_positions=8).k_min)


def test_tooth_difference_two_jams():
    # z2 = 52, x2 = -0.5 (zero backlash at alpha_w = 20 deg), shaper z0 42 x0 -0.5 (the smallest that cuts it)
    prof, ch = generate_central_wheel(SEED, CentralWheelDesign(2, x2=-0.5, shaper_teeth=42, shaper_shift=-0.5))
    mg, play = margin(EccentricMesh(sat(0.6), prof, M), n_positions=16)
    play_um = play * 75 * np.cos(A20) * 1e3
    assert abs(play_um - (-1672)) < 80                          # jammed by 1.7 mm even at k = 0.6


def test_unloaded_gaps_both_directions(wheel):
    g = unloaded_gaps(EccentricMesh(sat(0.6), wheel[0], M), n_positions=12)
    for d in (1, -1):
        assert g.gap_um[d].shape == (12, 50)
        assert np.allclose(g.first_contact_um[d], 0.0, atol=0.05)    # the mesh pair's involutes touch first
        row = np.sort(g.gap_um[d][0])
        assert row[0] < 1e-6 and row[1] < 0.1                   # two pairs in involute contact at phi = 0
        assert abs(row[2] - 4.7) < 0.24 and abs(row[3] - 16.8) < 0.84
        assert np.all(g.pairs_within(100.0, d) >= 6)
    # right-flank pairs lead on the -psi side, left-flank pairs mirror them
    i = np.argsort(g.gap_um[1][0])[:3]
    assert np.all(g.pairs[i] < 0)
    assert np.allclose(np.sort(g.gap_um[1][0])[:8], np.sort(g.gap_um[-1][0])[:8], atol=0.5)
    print("pairs within 10/50/100 um:", [int(g.pairs_within(t, 1).max()) for t in (10, 50, 100)])


@pytest.mark.parametrize("make, field", [
    (lambda: CentralWheelDesign(tooth_difference=0), "CentralWheelDesign.tooth_difference"),
    (lambda: wheel_shift(SEED, 0), "CentralWheelDesign.tooth_difference"),
    (lambda: wheel_shift(SEED, 4), "CentralWheelDesign.eccentricity"),
    (lambda: CentralWheelDesign(x2=2.0), "CentralWheelDesign.x2"),
    (lambda: generate_central_wheel(SEED, CentralWheelDesign(shaper_teeth=48)), "CentralWheelDesign.shaper_teeth"),
    (lambda: CentralWheelDesign(far_tip_clearance=-1.0), "CentralWheelDesign.far_tip_clearance"),
])
def test_bad_input_names_the_field(make, field):
    with pytest.raises(ValueError, match=field.replace(".", r"\.")):
        make()


def test_mesh_rejects_swapped_members(wheel):
    with pytest.raises(ValueError, match="satellite must be external"):
        EccentricMesh(wheel[0], sat(0.6), M)
    with pytest.raises(ValueError, match="direction"):
        EccentricMesh(sat(0.6), wheel[0], M).sample(0.0, 0.0, 0)
