"""ISO 10300 Method B1 nominal stresses of the shipped spiral bevel pair (cases/spiral_bevel_cao2008.toml: 12/36
teeth, outer module 5.08 mm, face 25.4 mm, 35 deg spiral, 22.5 deg pressure angle, 90 deg shafts) against a hand
calculation written out step by step from the clauses (ISO 10300-1 Annex A, ISO 10300-2 6.4 and 8.1, ISO
10300-3 6.4; the Gleason blank of Gleason 1971 / ANSI/AGMA 2005-D03 Annex A), and textbook anchors (Z_E of steel
189.8 sqrt(MPa); sigma_H0 grows as sqrt(T), sigma_F0 as T)."""
from __future__ import annotations

import math
from math import atan, cos, pi, radians, sin, sqrt, tan

import pytest

from ltca.bevel.iso10300 import iso10300_b1, virtual_gears
from ltca.geometry.bevel.blank import BevelBasicData, design_blank

Z1, Z2, M, B = 12, 36, 5.08, 25.4
BETA, ALPHA = radians(35.0), radians(22.5)
T1 = 175.0                      # N m
E, NU = 206000.0, 0.3
RHO_A0 = 0.2 * M                # blade edge radius, both members (mm)


@pytest.fixture(scope="module")
def blank():
    return design_blank(BevelBasicData(z1=Z1, z2=Z2, module=M, face_width=B, spiral_angle=BETA, pressure_angle=ALPHA,
                                       shaft_angle=radians(90.0), hand="right", cutter_radius=88.9))


def hand():
    """The hand calculation, step by step (mm, N, MPa, rad)."""
    h = {}
    # --- the Gleason blank (Gleason 1971): pitch angles, cone distances, depths at the mean point
    d1 = atan(Z1 / Z2)                                   # tan(delta1) = sin(S) / (z2/z1 + cos(S)), S = 90 deg
    d2 = pi / 2 - d1
    A0 = Z2 * M / (2 * sin(d2))                          # 96.3874 mm
    Am = A0 - B / 2                                      # 83.6874 mm
    m90 = sqrt(Z2 / Z1 * cos(d1) / cos(d2))              # 3
    hk, ht = 1.700 * M, 1.888 * M
    a2 = 0.460 * M + 0.390 * M / m90 ** 2
    a1 = hk - a2
    b1, b2 = ht - a1, ht - a2
    dd1, dd2 = atan(b1 / A0), atan(b2 / A0)
    ham1, ham2 = a1 - B / 2 * tan(dd2), a2 - B / 2 * tan(dd1)       # face angle = pitch + other's dedendum angle
    hfm1, hfm2 = b1 - B / 2 * tan(dd1), b2 - B / 2 * tan(dd2)
    mmn = M * Am / A0 * cos(BETA)                        # mean normal module
    smn2 = pi * mmn / 2 - (ham1 - ham2) * tan(ALPHA)     # mean normal thickness, thickness factor 0
    smn1 = pi * mmn - smn2
    assert m90 == pytest.approx(3.0, rel=1e-12)
    assert ham1 == pytest.approx(5.15224, abs=2e-5) and mmn == pytest.approx(3.61299, abs=2e-5)
    # --- ISO 10300-1 Annex A: virtual cylindrical gears (no offset, 90 deg)
    dm1 = 2 * Am * sin(d1)
    u = Z2 / Z1
    dv1 = dm1 * sqrt(u * u + 1) / u                      # (A.3)
    dv2 = u * u * dv1                                    # (A.4)
    zv1, zv2 = Z1 * sqrt(u * u + 1) / u, Z2 * sqrt(u * u + 1)      # (A.14), (A.15)
    avt = atan(tan(ALPHA) / cos(BETA))                   # (A.10), beta_v = beta_m (A.8)
    bvb = math.asin(sin(BETA) * cos(ALPHA))              # (A.16)
    dva1, dva2 = dv1 + 2 * ham1, dv2 + 2 * ham2          # (A.6)
    dvb1, dvb2 = dv1 * cos(avt), dv2 * cos(avt)          # (A.9)
    pvet = pi * mmn * cos(avt) / cos(BETA)               # (A.17)
    gva = 0.5 * (sqrt(dva1 ** 2 - dvb1 ** 2) - dv1 * sin(avt) + sqrt(dva2 ** 2 - dvb2 ** 2) - dv2 * sin(avt))  # (A.18)
    eva = gva / pvet                                     # (A.23)
    beff = 0.85 * B                                      # assumed effective face width
    evb = beff * sin(BETA) / (pi * mmn)                  # (A.24)
    fmax = (gva / 2 * cos(bvb) + beff / 2 * sin(bvb))    # (A.33): the farthest corner of the zone of action
    # middle contact line through the zone's centre at beta_vb: inside the b_eff x g_va rectangle it is cut by the
    # shorter of the two limits, then reduced for the elliptic pattern by sqrt(b_eff / b) (A.26 at f = 0)
    lb0_m = min(beff / cos(bvb), gva / sin(bvb))
    lbm = lb0_m * sqrt(beff / B)
    Rm1, Rm2 = Am, Am
    rho_t = sin(ALPHA) / (cos(BETA) ** 2 * (1 / (Rm1 * tan(d1)) + 1 / (Rm2 * tan(d2))))      # (A.39), alpha_lim 0
    bB = atan(tan(BETA) * sin(ALPHA))                    # (A.38)
    rho_rel = rho_t * cos(bB) ** 2                       # (A.37)
    h.update(dm1=dm1, dv1=dv1, dv2=dv2, zv1=zv1, zv2=zv2, avt=avt, bvb=bvb, gva=gva, eva=eva, evb=evb, fmax=fmax,
             lbm=lbm, rho_rel=rho_rel)
    # --- ISO 10300-2 Method B1
    Fmt1 = 2 * T1 * 1e3 / dm1                            # ISO 10300-1 (1)
    Fn = Fmt1 / (cos(ALPHA) * cos(BETA))                 # ISO 10300-1 (3)
    F = eva                                              # Table 4, eps_vbeta >= 1: F1 = F2 = eps_va
    ZMB = tan(avt) / sqrt((sqrt((dva1 / dvb1) ** 2 - 1) - F * pi / zv1) * (sqrt((dva2 / dvb2) ** 2 - 1) - F * pi / zv2))
    # Z_LS (7)-(10): neighbours of the middle line at f = +-p_vet cos(beta_vb); their lines in the rectangle,
    # by slab clipping in the frame centred on the zone (x along the face, y along the path)
    def line(f):
        c = (f * sin(bvb), f * cos(bvb))
        t = (cos(bvb), -sin(bvb))
        lo, hi = -math.inf, math.inf
        for k, half in ((0, beff / 2), (1, gva / 2)):
            s1, s2 = (-half - c[k]) / t[k], (half - c[k]) / t[k]
            lo, hi = max(lo, min(s1, s2)), min(hi, max(s1, s2))
        r2 = (f / fmax) ** 2
        kk = 1 - sqrt(beff / B)
        return max(hi - lo, 0.0) * (1 - sqrt(r2 + kk * kk * (1 - r2)))
    ft = pvet * cos(bvb)
    A = [pi / 4 * (1 - abs(f / fmax) ** 1.5) * line(f) for f in (ft, 0.0, -ft)]
    ZLS = sqrt(A[1] / sum(A))
    ZE = sqrt(1 / (pi * 2 * (1 - NU ** 2) / E))          # 8.1 (51)
    sH0 = sqrt(Fn / (lbm * rho_rel)) * ZMB * ZLS * ZE    # (2)
    h.update(Fmt1=Fmt1, ZMB=ZMB, ZLS=ZLS, ZE=ZE, sH0=sH0)
    # --- ISO 10300-3 Method B1: virtual gears in the normal section, tooth form (ISO 6336-3 Method B)
    zvn1 = zv1 / (cos(bvb) ** 2 * cos(BETA))             # (A.41)
    zvn2 = u * u * zvn1                                  # (A.42), u_v = u^2 at 90 deg
    xhm1 = (ham1 - ham2) / (2 * mmn)
    ha0 = (hfm1 + hfm2) / 2
    forms = []
    for xhm, zvn, ham, smn in ((xhm1, zvn1, ham1, smn1), (-xhm1, zvn2, ham2, smn2)):
        xsm = (smn / mmn - pi / 2) / 2 - xhm * tan(ALPHA)
        Ee = (pi / 4 - xsm) * mmn - ha0 * tan(ALPHA) - RHO_A0 * (1 - sin(ALPHA)) / cos(ALPHA)   # (7)
        G = RHO_A0 / mmn - ha0 / mmn + xhm                                                     # (8)
        H = 2 / zvn * (pi / 2 - Ee / mmn) - pi / 3                                             # (9)
        th = pi / 6
        for _ in range(100):                                                                   # (10)
            th = 2 * G / zvn * tan(th) - H
        sFn = mmn * (zvn * sin(pi / 3 - th) + sqrt(3) * (G / cos(th) - RHO_A0 / mmn))         # (11)
        rhoF = RHO_A0 + 2 * G * G * mmn / (cos(th) * (zvn * cos(th) ** 2 - 2 * G))            # (13)
        dvn = zvn * mmn
        dvan, dvbn = dvn + 2 * ham, dvn * cos(ALPHA)                                           # (A.43)-(A.45)
        aan = math.acos(dvbn / dvan)                                                           # (16)
        inv = lambda a: tan(a) - a                                                             # noqa: E731
        ga = (pi / 2 + 2 * (xhm * tan(ALPHA) + xsm)) / zvn + inv(ALPHA) - inv(aan)             # (17)
        aFan = aan - ga                                                                        # (15)
        hFa = mmn / 2 * ((cos(ga) - sin(ga) * tan(aFan)) * dvan / mmn - zvn * cos(pi / 3 - th) - G / cos(th)
                         + RHO_A0 / mmn)                                                       # (14)
        YFa = 6 * hFa / mmn * cos(aFan) / ((sFn / mmn) ** 2 * cos(ALPHA))                     # (6)
        La, qs = sFn / hFa, sFn / (2 * rhoF)
        YSa = (1.2 + 0.13 * La) * qs ** (1 / (1.21 + 2.3 / La))                                # (24)-(26)
        forms.append((YFa, YSa))
    Yeps = 0.625                                         # (29): eps_vbeta >= 1
    ba = B / cos(BETA)                                   # (34)
    lbb = lbm * cos(bvb) / cos(BETA)                     # (35)
    x = 2 * ba / (ham1 + hfm1 + ham2 + hfm2)
    aBS, bBS, cBS = -0.0182 * x * x + 0.4736 * x - 0.32, -0.0032 * x * x + 0.0526 * x + 0.712, \
        -0.0050 * x * x + 0.0850 * x + 0.54
    YBS = aBS / cBS * (lbb / ba - 1.05 * bBS) ** 2 + 1   # (30)
    YLS = ZLS ** 2                                       # (36)
    sF0 = [Fmt1 / (B * mmn) * YFa * YSa * Yeps * YBS * YLS for YFa, YSa in forms]   # (2), F_vmt = F_mt1
    h.update(zvn1=zvn1, zvn2=zvn2, forms=forms, YBS=YBS, sF0=sF0)
    return h


def test_virtual_cylindrical_gears_by_hand(blank):
    h = hand()
    v = virtual_gears(blank)
    for key, attr in (("dv1", "d_v1"), ("dv2", "d_v2"), ("zv1", "z_v1"), ("zv2", "z_v2"), ("avt", "alpha_vet"),
                      ("bvb", "beta_vb"), ("gva", "g_va"), ("eva", "eps_va"), ("evb", "eps_vb"), ("fmax", "f_max"),
                      ("lbm", "l_bm"), ("rho_rel", "rho_rel"), ("zvn1", "z_vn1"), ("zvn2", "z_vn2")):
        assert getattr(v, attr) == pytest.approx(h[key], rel=1e-9), attr
    # the numbers of the shipped pair, guarded (rounded hand results)
    assert (v.d_v1, v.d_v2, v.z_v1, v.z_vn1) == pytest.approx((55.7908, 502.1173, 12.6491, 21.4710), abs=1e-4)
    assert (v.eps_va, v.eps_vb, v.l_bm, v.rho_rel) == pytest.approx((1.10923, 1.09101, 23.4715, 13.3589), abs=1e-4)


def test_nominal_stresses_by_hand(blank):
    h = hand()
    r = iso10300_b1(blank, T1, E, NU, (RHO_A0, RHO_A0))
    assert r.F_mt1 == pytest.approx(h["Fmt1"], rel=1e-12)
    assert r.Z_E == pytest.approx(189.81, abs=0.01)                 # steel on steel: the textbook 189.8
    assert (r.Z_MB, r.Z_LS, r.Y_BS) == pytest.approx((h["ZMB"], h["ZLS"], h["YBS"]), rel=1e-9)
    assert r.pinion.Y_Fa == pytest.approx(h["forms"][0][0], rel=1e-9)
    assert r.gear.Y_Sa == pytest.approx(h["forms"][1][1], rel=1e-9)
    assert r.sigma_H0 == pytest.approx(h["sH0"], rel=1e-9)
    assert (r.sigma_F0_pinion, r.sigma_F0_gear) == pytest.approx(tuple(h["sF0"]), rel=1e-9)
    # the figures of the shipped pair at 175 N m (rounded hand results)
    assert r.sigma_H0 == pytest.approx(930.0, abs=0.5)
    assert (r.sigma_F0_pinion, r.sigma_F0_gear) == pytest.approx((183.6, 179.5), abs=0.1)
    # sigma_H0 ~ sqrt(T), sigma_F0 ~ T
    r4 = iso10300_b1(blank, 4 * T1, E, NU, (RHO_A0, RHO_A0))
    assert r4.sigma_H0 == pytest.approx(2 * r.sigma_H0, rel=1e-12)
    assert r4.sigma_F0_pinion == pytest.approx(4 * r.sigma_F0_pinion, rel=1e-12)


def test_tooth_form_of_a_spur_gear_matches_iso6336_tables():
    """The tooth form of a standard spur gear (z = 20, x = 0, basic rack h_fP = 1.25 m, rho_fP = 0.38 m, 20 deg)
    through the Method B1 tooth form: Y_Fa = 2.80 and Y_Sa = 1.55 at z = 20, 2.19 and 1.79 at z = 100, as read from
    the Y_Fa and Y_Sa charts of ISO 6336-3 (external gears, basic rack 1.25 m / 0.38 m, x = 0) within the charts'
    reading accuracy."""
    from ltca.bevel.iso10300 import tooth_form
    m, z, a = 1.0, 20, radians(20.0)
    d = z * m
    f = tooth_form(m, 1.25 * m, 0.0, 0.0, 0.38 * m, a, z, d + 2 * m, d * cos(a))
    assert f.Y_Fa == pytest.approx(2.80, abs=0.05) and f.Y_Sa == pytest.approx(1.55, abs=0.03)
    f = tooth_form(m, 1.25 * m, 0.0, 0.0, 0.38 * m, a, 100, 102.0, 100 * cos(a))
    assert f.Y_Fa == pytest.approx(2.19, abs=0.05) and f.Y_Sa == pytest.approx(1.79, abs=0.03)
