"""Kapitonov et al.: the satellite cut by (a) a hob in three passes, (b) a disk cutter, (c) a special hob; its rating.

Every test guards a number against an independent hand computation (formula written out) or a stated value;
a 5 % move of that number fails it.
"""
import time

import numpy as np
import pytest
from scipy.optimize import brentq

from ltca.geometry.satellite.compare import compare_forming, plot_forming
from ltca.geometry.satellite.forming import form_disk_cutter, form_hob_three_pass, form_satellite, form_special_hob
from ltca.geometry.satellite.rating import RatingInputs, rated_torque
from ltca.geometry.satellite.tools import DiskCutter, HobThreePass, SatelliteDesign, SpecialHob, eq4_rack_thickness
from ltca.geometry.transverse import involute

DEG = np.pi / 180
SEED = SatelliteDesign()                     # z 50, m 3, alpha 20 deg, x -0.5, k 0.6
M, Z, X, K, A20 = 3.0, 50, -0.5, 0.6, 20 * DEG
EQ3 = np.pi * M / 2 + 2 * X * M * np.tan(A20) - K * M          # 1.820478 mm


@pytest.fixture(scope="module")
def cmp():
    t = time.perf_counter()
    c = compare_forming(SEED)
    return c, time.perf_counter() - t


def test_special_hob_thickness_is_eq3(cmp):
    cmp = cmp[0]
    c = cmp.teeth["special_hob"]
    assert abs(EQ3 - 1.820478) < 1e-6
    assert abs(c.s_ref - EQ3) < 1e-3                        # within 1 um, measured on the outline
    assert c.passes == 1 and not c.pointed
    # tip land of the thinned tooth: 2 r_a (s/(2r) + inv(alpha) - inv(alpha_a)), r_a = 76.5 mm
    ra = 76.5
    aa = np.arccos(75 * np.cos(A20) / ra)
    land = 2 * ra * (EQ3 / 150 + involute(A20) - involute(aa))
    assert abs(c.tip_land - land) < 1e-4 and abs(land - 0.6644) < 1e-3


def test_three_pass_hob_equals_special_hob(cmp):
    cmp = cmp[0]
    a, c = cmp.teeth["hob_three_pass"], cmp.teeth["special_hob"]
    assert a.passes == 3
    assert abs(a.s_ref - c.s_ref) < 5e-3                    # within 5 um
    assert abs(a.s_ref - EQ3) < 1e-3
    dev = cmp.deviations["hob_three_pass"]
    assert len(dev.radius) > 300 and np.all(np.isfinite(dev.deviation_um))
    # the thickened rack is the union of the two side-shifted standard racks, so the envelopes coincide
    # (fillet included): the deviation is the bisection resolution, not geometry
    assert dev.max_abs_um < 1e-3
    # the side passes move the standard rack by k m / 2 = 0.9 mm along the pitch line; a 5 % smaller shift
    # leaves the tooth 2 * 0.045 mm thicker
    thicker = form_hob_three_pass(SEED, HobThreePass(shift=0.95 * 0.9))
    assert abs((thicker.s_ref - a.s_ref) - 2 * 0.05 * 0.9) < 1e-6


def test_disk_cutter_pointed_and_deeper(cmp):
    cmp = cmp[0]
    b, c = cmp.teeth["disk_cutter"], cmp.teeth["special_hob"]
    assert b.pointed and b.nearly_pointed and b.tip_land == 0.0
    # dedendum: the rack root line r + x m - ha and the copied root r + x_b m - ha (same ha = 1.25 m):
    # deeper by (x_c - x_b) m = (-0.5 + 1.3) 3 = 2.4 mm
    hand = (X - (-1.3)) * M
    assert abs((b.dedendum - c.dedendum) - hand) < 1e-9
    assert abs(b.r_root - (75 - 1.3 * M - 1.25 * M)) < 1e-9
    # pointed: the x = 0 tooth of z 50 (half angle h0(R) = pi/(2 z) + inv(a) - inv(acos(r_b / R))) copied
    # 1.3 m = 3.9 mm down along the space centre line (at pi/z): its flank point R meets the tooth centre line
    # where R sin(h0(R)) = 3.9 sin(pi/z), at radius R cos(h0(R)) - 3.9 cos(pi/z)
    rb, D = 75 * np.cos(A20), 1.3 * M

    def h0(R):
        return np.pi / 100 + involute(A20) - involute(np.arccos(rb / R))
    R = brentq(lambda R: R * np.sin(h0(R)) - D * np.sin(np.pi / Z), 76.0, 80.3)
    r_point = R * np.cos(h0(R)) - D * np.cos(np.pi / Z)
    assert abs(b.r_tip - r_point) < 1e-4 and abs(r_point - 75.963) < 1e-3
    assert r_point < SEED.r_tip                                   # below the 153 mm tip circle: pointed
    # thinner than Eq. 3 at the reference circle: 0.984 mm (Eq. 3 would need the plunge -1.042)
    assert abs(b.s_ref - 0.98416) < 0.02
    assert abs(cmp.plunge_for_eq3 - (-1.0421)) < 0.01
    assert abs(form_disk_cutter(SEED, DiskCutter(cmp.plunge_for_eq3)).s_ref - EQ3) < 1e-5
    dev = cmp.deviations["disk_cutter"]
    assert abs(dev.max_abs_involute_um - 502.2) < 20            # thinner by 0.5 mm near the tip
    i = np.nanargmin(np.abs(dev.radius - 75.0))
    assert abs(dev.deviation_um[i] - (-376.4)) < 15


def test_forming_comparison_speed_and_plot(cmp, tmp_path):
    cmp, elapsed = cmp
    print(f"forming comparison (a), (b), (c) and deviations: {elapsed:.2f} s")
    assert elapsed < 10.0
    rows = {r["method"]: r for r in cmp.table()}
    assert rows["disk_cutter"]["pointed"] and rows["special_hob"]["passes"] == 1
    p = tmp_path / "forming.png"
    plot_forming(cmp, p)
    assert p.stat().st_size > 20000


def test_eq4_as_printed_does_not_cut_eq3():
    e = eq4_rack_thickness(SEED)
    t = np.tan(A20)
    assert abs(e.eq4_literal - (np.pi * M / 2 + 2 * X * M * t + K * M)) < 1e-12      # 5.4205 mm
    assert abs(e.datum - (np.pi * M / 2 + K * M)) < 1e-12                              # 6.5124 mm
    assert abs(e.rolling_line - (np.pi * M - EQ3)) < 1e-12                             # 7.6043 mm
    assert abs(e.cut_if_literal_on_datum - (np.pi * M / 2 - K * M)) < 1e-12            # 2.9124 mm
    assert abs(e.eq4_literal - 5.4205) < 1e-4 and abs(e.rolling_line - 7.6043) < 1e-4


def test_rated_torque_against_iso_closed_form():
    # ISO 6336-3:2006 Method B closed form for a rack-generated external tooth, load at the tip, the rack
    # thickened by A = k m (its half tooth on the datum pi m / 4 + A / 2):
    #   E = (pi m/2 + A)/2 - h_fP tan(a) - (1 - sin a) rho_fP / cos(a);  G = rho_fP/m - h_fP/m + x
    #   H = 2/z (pi/2 - E/m) - pi/3;  theta = 2 G / z tan(theta) - H (fixed point from pi/6)
    #   s_Fn = m (z sin(pi/3 - theta) + sqrt(3) (G / cos(theta) - rho_fP/m))
    #   rho_F = rho_fP + 2 m G^2 / (cos(theta) (z cos^2(theta) - 2 G))
    #   gamma_e = s/d + inv(a) - inv(a_en), a_en = acos(d_b / d_a), alpha_Fen = a_en - gamma_e
    #   h_Fe = m/2 ((cos(g_e) - sin(g_e) tan(a_Fen)) d_a/m - z cos(pi/3 - theta) - G / cos(theta) + rho_fP/m)
    A, hfP, rfP = K * M, 1.25 * M, 0.38 * M
    E = (np.pi * M / 2 + A) / 2 - hfP * np.tan(A20) - (1 - np.sin(A20)) * rfP / np.cos(A20)
    G = rfP / M - hfP / M + X
    H = 2 / Z * (np.pi / 2 - E / M) - np.pi / 3
    th = np.pi / 6
    for _ in range(60):
        th = 2 * G / Z * np.tan(th) - H
    sFn = M * (Z * np.sin(np.pi / 3 - th) + np.sqrt(3) * (G / np.cos(th) - rfP / M))
    rF = rfP + 2 * M * G ** 2 / (np.cos(th) * (Z * np.cos(th) ** 2 - 2 * G))
    aen = np.arccos(150 * np.cos(A20) / 153)
    ge = EQ3 / 150 + involute(A20) - involute(aen)
    aF = aen - ge
    hFe = 0.5 * M * ((np.cos(ge) - np.sin(ge) * np.tan(aF)) * 153 / M - Z * np.cos(np.pi / 3 - th)
                     - G / np.cos(th) + rfP / M)
    YF = 6 * hFe / M * np.cos(aF) / ((sFn / M) ** 2 * np.cos(A20))
    L, qs = sFn / hFe, sFn / (2 * rF)
    YS = (1.2 + 0.13 * L) * qs ** (1 / (1.21 + 2.3 / L))
    r = rated_torque(form_special_hob(SEED).profile)
    s = r.section
    assert abs(s.s_Fn - sFn) < 1e-4 and abs(s.h_Fe - hFe) < 1e-4 and abs(s.alpha_Fen - aF) < 1e-9
    assert abs(s.rho_F - rF) < 0.01
    assert abs(s.Y_F - YF) < 1e-3 and abs(s.Y_S - YS) < 2e-3
    # rated torque: sigma_FP b m / (Y_F Y_S) * d / 2 with sigma_FP = 314.5 * 2 * Y_drelT / 1.4
    sFP = 314.5 * 2.0 * r.Y_deltarelT / 1.4
    T = sFP * 20 * M / (YF * YS) * 75 / 1000
    assert abs(r.torque_Nm - T) / T < 2e-3
    assert abs(r.torque_Nm - 264.1) < 3.0
    assert abs(YF - 5.624) < 0.01 and abs(YS - 1.311) < 0.01


@pytest.mark.parametrize("make, field", [
    (lambda: DiskCutter(n_teeth=0), "DiskCutter.n_teeth"),
    (lambda: DiskCutter(x_plunge=-3.0), "DiskCutter.x_plunge"),
    (lambda: DiskCutter(z_profile=5), "DiskCutter.z_profile"),
    (lambda: HobThreePass(shift=-0.1), "HobThreePass.shift"),
    (lambda: form_hob_three_pass(SEED, HobThreePass(shift=1.9)), "HobThreePass.shift"),
    (lambda: SpecialHob(thickening=1.2), "SpecialHob.thickening"),
    (lambda: SatelliteDesign(thinning=1.5), "SatelliteDesign.thinning"),
    (lambda: SatelliteDesign(z=7), "SatelliteDesign.z"),
    (lambda: form_satellite(SEED, "broach"), "method"),
    (lambda: form_satellite(SEED, "disk_cutter", SpecialHob()), "tool"),
    (lambda: RatingInputs(b=0.0), "RatingInputs.b"),
])
def test_bad_input_names_the_field(make, field):
    with pytest.raises(ValueError, match=field.replace(".", r"\.")):
        make()
