"""ISO 10300 Method B1 nominal stresses of a spiral bevel pair without offset: the virtual cylindrical gears
(ISO 10300-1 Annex A), the nominal contact stress sigma_H0 (ISO 10300-2 Method B1) and the nominal tooth-root
stress sigma_F0 (ISO 10300-3 Method B1), every load factor K = 1: the figures the LTCA is set beside.

Source. The standard's text was not available to the project. The formulas below are those of ISO 10300-1, -2
and -3:2023 as stated, formula by formula with their clause and formula numbers, by a public C# implementation
of ISO 10300:2023 Method B1 (namespace ``ISO10300Calc``, found by the project's code search; it checks itself
against the worked example of ISO/TR 10300-30, sample 1); its tooth form is ISO 6336-3 Method B's on the
virtual gear in the normal section (checked here against the ISO 6336-3 charts of Y_Fa and Y_Sa). Clause and
formula numbers are those the implementation gives; they were not checked against the standard's text.

What is not sourced, and how it is handled:

- the effective face width b_eff (ISO 10300-1 takes it from the contact pattern under load): a parameter,
  default 0.85 b (an assumption, said so in the report);
- the exponent e_LS of the load sharing factor (ISO 10300-2 Table 5: by the amount of profile crowning): a
  parameter, default 1.5 (high crowning: the pinion is synthesised for a parabolic TE);
- the clipping of a contact line at the edges of the zone of action (ISO 10300-1 Table A.3 conditions): here the
  geometric definition, the part of the line inside the rectangle b_eff x g_va;
- the contact ratio factor Y_eps for 0 < eps_vbeta < 1 (the sources give the end points only): refused;
- Z_H, Z_beta and Z_K, named in older descriptions of ISO 10300-2, are not factors of the sigma_H0 formula
  followed here: zone and helix enter through rho_rel and l_bm, and the bevel gear factor is Z_KP of the
  permissible stress (not computed here).

Units: mm, N, MPa, rad. Subscript 1 pinion, 2 gear. Shaft angle 90 deg and no offset.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

__all__ = ["VirtualGears", "Iso10300B1", "virtual_gears", "contact_line_length", "load_sharing_factor",
           "mid_zone_factor", "elasticity_factor", "tooth_form", "contact_ratio_factor", "bevel_spiral_angle_factor",
           "iso10300_b1"]


def _inv(a: float) -> float:
    return math.tan(a) - a


@dataclass(frozen=True)
class VirtualGears:
    """The virtual cylindrical gears of a bevel pair (ISO 10300-1 Annex A), mm and rad."""
    u: float
    d_m1: float
    d_m2: float
    delta1: float
    delta2: float
    beta_m: float
    alpha_n: float
    m_mn: float
    b: float
    b_eff: float
    h_am1: float
    h_am2: float
    h_fm1: float
    h_fm2: float
    d_v1: float
    d_v2: float
    z_v1: float
    z_v2: float
    u_v: float
    beta_v: float
    alpha_vet: float
    beta_vb: float
    d_va1: float
    d_va2: float
    d_vb1: float
    d_vb2: float
    p_vet: float
    g_va: float
    eps_va: float
    eps_vb: float
    f_max: float
    l_bm: float
    rho_t: float
    beta_B: float
    rho_rel: float
    z_vn1: float
    z_vn2: float
    d_vn1: float
    d_vn2: float
    d_van1: float
    d_van2: float
    d_vbn1: float
    d_vbn2: float


def contact_line_length(f: float, beta_vb: float, g_va: float, b_eff: float, b_v: float, f_max: float) -> float:
    """Length of the contact line at the distance ``f`` (mm) from the middle of the zone of action, reduced for
    the elliptic contact pattern (ISO 10300-1 A.2.7, formulae (A.26) to (A.36)).

    The zone of action is the rectangle b_eff (along the face) x g_va (along the path); the contact lines are
    inclined at beta_vb, ``f`` is measured normal to them. l_b0 is the part of the line inside the rectangle;
    the reduction is l_b = l_b0 (1 - sqrt((f / f_max)^2 + k^2 (1 - (f / f_max)^2))) with k = 1 - sqrt(b_eff / b_v).
    """
    if beta_vb <= 1e-12:
        lb0 = b_eff if abs(f) <= 0.5 * g_va else 0.0
    else:
        # the line: points c + s t, c = (b_eff/2 + f sin, f cos) from the zone's corner-centred frame, t along it
        n = np.array([math.sin(beta_vb), math.cos(beta_vb)])
        t = np.array([math.cos(beta_vb), -math.sin(beta_vb)])
        c = f * n
        lo, hi = -math.inf, math.inf
        for k, half in ((0, 0.5 * b_eff), (1, 0.5 * g_va)):       # slab clipping of the rectangle
            if abs(t[k]) < 1e-15:
                if abs(c[k]) > half:
                    return 0.0
                continue
            s1, s2 = (-half - c[k]) / t[k], (half - c[k]) / t[k]
            lo, hi = max(lo, min(s1, s2)), min(hi, max(s1, s2))
        lb0 = max(hi - lo, 0.0)
    r2 = (f / f_max) ** 2 if f_max > 0 else 0.0
    k = 1.0 - math.sqrt(b_eff / b_v)
    return lb0 * (1.0 - math.sqrt(r2 + k * k * (1.0 - r2)))


def virtual_gears(blank, b_eff: float | None = None) -> VirtualGears:
    """The virtual cylindrical gears of a Gleason blank (:class:`ltca.geometry.bevel.blank.BevelBlank`), Method B1.

    Formulae (ISO 10300-1 Annex A): d_v = d_m / cos(delta) (A.3, A.4: d_m sqrt(u^2 + 1) / u and u^2 d_v1 at
    90 deg); beta_v = beta_m (A.8); alpha_vet = atan(tan(alpha_e) / cos(beta_v)) (A.10), alpha_e = alpha_n without
    offset; d_vb = d_v cos(alpha_vet) (A.9); d_va = d_v + 2 h_am (A.6); z_v = z / cos(delta) (A.14, A.15);
    beta_vb = asin(sin(beta_v) cos(alpha_e)) (A.16); p_vet = pi m_mn cos(alpha_vet) / cos(beta_v) (A.17);
    g_va = (sqrt(d_va1^2 - d_vb1^2) - d_v1 sin(alpha_vet) + sqrt(d_va2^2 - d_vb2^2) - d_v2 sin(alpha_vet)) / 2
    (A.18); eps_va = g_va / p_vet (A.23); b_v = b, b_v,eff = b_eff without offset (A.19, A.22);
    eps_vb = b_eff sin(beta_v) / (pi m_mn) (A.24); f_max = (g_va + b_eff tan(beta_vb)) cos(beta_vb) / 2 (A.33);
    l_bm: :func:`contact_line_length` at f = 0 (A.26); rho_t = sin(alpha_n) / (cos^2(beta_m) (1 / (R_m1
    tan(delta1)) + 1 / (R_m2 tan(delta2)))) (A.39 without offset, alpha_lim = 0); beta_B = atan(tan(beta_v)
    sin(alpha_e)) (A.38); rho_rel = rho_t cos^2(beta_B) (A.37); normal section: z_vn = z_v / (cos^2(beta_vb)
    cos(beta_v)) (A.41, A.42), d_vn = z_vn m_mn (A.43), d_van = d_vn + 2 h_am (A.44), d_vbn = d_vn cos(alpha_e)
    (A.45).

    Parameters
    ----------
    blank : BevelBlank
        Any shaft angle: the formulae are the general ones of Annex A in delta1, delta2 (A.3, A.4 are their 90 deg
        forms); both pitch angles below 90 deg (checked).
    b_eff : float, optional
        Effective face width, mm; default 0.85 b (an assumption: the standard takes it from the loaded pattern).
    """
    d = blank.data
    p, g = blank.pinion, blank.gear
    if not max(p.pitch_angle, g.pitch_angle) < 0.5 * math.pi - 1e-6:
        raise ValueError(f"pitch angles {math.degrees(p.pitch_angle):g} and {math.degrees(g.pitch_angle):g} deg: "
                         "the virtual cylindrical gears d_m / cos(delta) need both below 90 deg")
    Rm = blank.mean_cone_distance
    b = blank.face_width
    b_eff = 0.85 * b if b_eff is None else float(b_eff)
    d1, d2 = p.pitch_angle, g.pitch_angle
    dm1, dm2 = 2 * Rm * math.sin(d1), 2 * Rm * math.sin(d2)
    beta, an, m_mn = d.spiral_angle, d.pressure_angle, blank.mean_normal_module
    dv1, dv2 = dm1 / math.cos(d1), dm2 / math.cos(d2)
    zv1, zv2 = p.z / math.cos(d1), g.z / math.cos(d2)
    avt = math.atan(math.tan(an) / math.cos(beta))
    bvb = math.asin(math.sin(beta) * math.cos(an))
    dva1, dva2 = dv1 + 2 * p.mean_addendum, dv2 + 2 * g.mean_addendum
    dvb1, dvb2 = dv1 * math.cos(avt), dv2 * math.cos(avt)
    pvet = math.pi * m_mn * math.cos(avt) / math.cos(beta)
    gva = 0.5 * (math.sqrt(dva1 ** 2 - dvb1 ** 2) - dv1 * math.sin(avt)
                 + math.sqrt(dva2 ** 2 - dvb2 ** 2) - dv2 * math.sin(avt))
    eva = gva / pvet
    evb = b_eff * math.sin(beta) / (math.pi * m_mn)
    fmax = 0.5 * (gva + b_eff * math.tan(bvb)) * math.cos(bvb)
    lbm = contact_line_length(0.0, bvb, gva, b_eff, b, fmax)
    Rm1, Rm2 = dm1 / (2 * math.sin(d1)), dm2 / (2 * math.sin(d2))
    rho_t = math.sin(an) / (math.cos(beta) ** 2 * (1 / (Rm1 * math.tan(d1)) + 1 / (Rm2 * math.tan(d2))))
    bB = math.atan(math.tan(beta) * math.sin(an))
    rho_rel = rho_t * math.cos(bB) ** 2
    zvn1 = zv1 / (math.cos(bvb) ** 2 * math.cos(beta))
    zvn2 = zvn1 * zv2 / zv1
    dvn1, dvn2 = zvn1 * m_mn, zvn2 * m_mn
    return VirtualGears(
        u=g.z / p.z, d_m1=dm1, d_m2=dm2, delta1=d1, delta2=d2, beta_m=beta, alpha_n=an, m_mn=m_mn, b=b,
        b_eff=b_eff, h_am1=p.mean_addendum, h_am2=g.mean_addendum, h_fm1=p.mean_dedendum, h_fm2=g.mean_dedendum,
        d_v1=dv1, d_v2=dv2, z_v1=zv1, z_v2=zv2, u_v=zv2 / zv1, beta_v=beta, alpha_vet=avt, beta_vb=bvb,
        d_va1=dva1, d_va2=dva2, d_vb1=dvb1, d_vb2=dvb2, p_vet=pvet, g_va=gva, eps_va=eva, eps_vb=evb, f_max=fmax,
        l_bm=lbm, rho_t=rho_t, beta_B=bB, rho_rel=rho_rel, z_vn1=zvn1, z_vn2=zvn2, d_vn1=dvn1, d_vn2=dvn2,
        d_van1=dvn1 + 2 * p.mean_addendum, d_van2=dvn2 + 2 * g.mean_addendum, d_vbn1=dvn1 * math.cos(an),
        d_vbn2=dvn2 * math.cos(an))


def load_sharing_factor(v: VirtualGears, e_ls: float = 1.5) -> float:
    """Z_LS (ISO 10300-2 6.4.2, formulae (7) to (10)), for eps_vbeta >= 1: the middle contact line and its
    neighbours at f = +-p_vet cos(beta_vb) (ISO 10300-1 Table A.2) carry elliptic peak loads
    p* = 1 - |f / f_max|^e_LS (7) over areas A* = pi / 4 p* l_b (8); Z_LS = sqrt(A*_m / (A*_t + A*_m + A*_r)) (10).
    """
    if v.eps_vb < 1.0:
        raise ValueError(f"eps_vbeta = {v.eps_vb:.3f} < 1: the tip / root contact lines of Table A.2 for this "
                         "range are not implemented")
    fs = (v.p_vet * math.cos(v.beta_vb), 0.0, -v.p_vet * math.cos(v.beta_vb))
    A = [0.25 * math.pi * (1 - abs(f / v.f_max) ** e_ls) * contact_line_length(f, v.beta_vb, v.g_va, v.b_eff, v.b,
                                                                                 v.f_max) for f in fs]
    return math.sqrt(A[1] / sum(A))


def mid_zone_factor(v: VirtualGears) -> float:
    """Z_M-B (ISO 10300-2 6.4.1, formula (6), Table 4): the relative curvature at the mid-zone of the path
    against the pitch point's, Z_M-B = tan(alpha_vet) / sqrt((sqrt((d_va1/d_vb1)^2 - 1) - F1 pi / z_v1)
    (sqrt((d_va2/d_vb2)^2 - 1) - F2 pi / z_v2)); F1 = F2 = eps_va for eps_vbeta >= 1, F1 = 2, F2 = 2 (eps_va - 1)
    for eps_vbeta = 0, linear in eps_vbeta between (Table 4)."""
    ea, eb = v.eps_va, min(v.eps_vb, 1.0)
    F1 = 2.0 + (ea - 2.0) * eb
    F2 = 2.0 * (ea - 1.0) + (2.0 - ea) * eb
    a1 = math.sqrt((v.d_va1 / v.d_vb1) ** 2 - 1) - F1 * math.pi / v.z_v1
    a2 = math.sqrt((v.d_va2 / v.d_vb2) ** 2 - 1) - F2 * math.pi / v.z_v2
    return math.tan(v.alpha_vet) / math.sqrt(a1 * a2)


def elasticity_factor(young1: float, nu1: float, young2: float | None = None, nu2: float | None = None) -> float:
    """Z_E = sqrt(1 / (pi ((1 - nu1^2) / E1 + (1 - nu2^2) / E2))), sqrt(MPa) (ISO 10300-2 8.1, formula (51);
    189.8 for steel on steel)."""
    young2 = young1 if young2 is None else young2
    nu2 = nu1 if nu2 is None else nu2
    return math.sqrt(1.0 / (math.pi * ((1 - nu1 ** 2) / young1 + (1 - nu2 ** 2) / young2)))


@dataclass(frozen=True)
class ToothForm:
    """Tooth-form results of one member for load at the tip (ISO 10300-3 6.4.1.2, 6.4.2), mm and rad."""
    x_hm: float
    x_sm: float
    theta: float
    s_Fn: float
    rho_F: float
    h_Fa: float
    alpha_Fan: float
    Y_Fa: float
    Y_Sa: float


def tooth_form(m_mn: float, h_a0: float, x_hm: float, x_sm: float, rho_a0: float, alpha_n: float, z_vn: float,
               d_van: float, d_vbn: float, s_pr: float = 0.0) -> ToothForm:
    """Y_Fa and Y_Sa of a generated member (ISO 10300-3 6.4.1.2 formulae (6) to (17), 6.4.2 formulae (24) to (26);
    ISO 6336-3 Method B's tooth form on the virtual gear in the normal section).

    E = (pi/4 - x_sm) m_mn - h_a0 tan(alpha_n) - rho_a0 (1 - sin(alpha_n)) / cos(alpha_n) - s_pr (7);
    G = rho_a0 / m_mn - h_a0 / m_mn + x_hm (8); H = 2 / z_vn (pi/2 - E / m_mn) - pi/3 (9);
    theta = 2 G / z_vn tan(theta) - H (10, fixed point from pi/6);
    s_Fn = m_mn (z_vn sin(pi/3 - theta) + sqrt(3) (G / cos(theta) - rho_a0 / m_mn)) (11);
    rho_F = rho_a0 + 2 G^2 m_mn / (cos(theta) (z_vn cos^2(theta) - 2 G)) (13);
    alpha_an = acos(d_vbn / d_van) (16); gamma_a = (pi/2 + 2 (x_hm tan(alpha_n) + x_sm)) / z_vn + inv(alpha_n)
    - inv(alpha_an) (17); alpha_Fan = alpha_an - gamma_a (15);
    h_Fa = m_mn / 2 ((cos(gamma_a) - sin(gamma_a) tan(alpha_Fan)) d_van / m_mn - z_vn cos(pi/3 - theta)
    - G / cos(theta) + rho_a0 / m_mn) (14);
    Y_Fa = 6 h_Fa / m_mn cos(alpha_Fan) / ((s_Fn / m_mn)^2 cos(alpha_n)) (6);
    Y_Sa = (1.2 + 0.13 L_a) q_s^(1 / (1.21 + 2.3 / L_a)), L_a = s_Fn / h_Fa, q_s = s_Fn / (2 rho_F) (24 to 26).
    """
    E = (math.pi / 4 - x_sm) * m_mn - h_a0 * math.tan(alpha_n) - rho_a0 * (1 - math.sin(alpha_n)) / math.cos(
        alpha_n) - s_pr
    G = rho_a0 / m_mn - h_a0 / m_mn + x_hm
    H = 2 / z_vn * (math.pi / 2 - E / m_mn) - math.pi / 3
    th = math.pi / 6
    for _ in range(200):
        nxt = 2 * G / z_vn * math.tan(th) - H
        if abs(nxt - th) < 1e-14:
            th = nxt
            break
        th = nxt
    s_Fn = m_mn * (z_vn * math.sin(math.pi / 3 - th) + math.sqrt(3) * (G / math.cos(th) - rho_a0 / m_mn))
    rho_F = rho_a0 + 2 * G * G * m_mn / (math.cos(th) * (z_vn * math.cos(th) ** 2 - 2 * G))
    a_an = math.acos(d_vbn / d_van)
    g_a = (math.pi / 2 + 2 * (x_hm * math.tan(alpha_n) + x_sm)) / z_vn + _inv(alpha_n) - _inv(a_an)
    a_Fan = a_an - g_a
    h_Fa = 0.5 * m_mn * ((math.cos(g_a) - math.sin(g_a) * math.tan(a_Fan)) * d_van / m_mn
                         - z_vn * math.cos(math.pi / 3 - th) - G / math.cos(th) + rho_a0 / m_mn)
    Y_Fa = 6 * h_Fa / m_mn * math.cos(a_Fan) / ((s_Fn / m_mn) ** 2 * math.cos(alpha_n))
    La, qs = s_Fn / h_Fa, s_Fn / (2 * rho_F)
    Y_Sa = (1.2 + 0.13 * La) * qs ** (1 / (1.21 + 2.3 / La))
    return ToothForm(x_hm, x_sm, th, s_Fn, rho_F, h_Fa, a_Fan, Y_Fa, Y_Sa)


def contact_ratio_factor(v: VirtualGears) -> float:
    """Y_eps (ISO 10300-3 6.4.3, formulae (27) to (29)): 0.25 + 0.75 / eps_va for eps_vbeta = 0, 0.625 for
    eps_vbeta >= 1; between them the sources give no formula (refused)."""
    if v.eps_vb >= 1.0:
        return 0.625
    if v.eps_vb == 0.0:
        return 0.25 + 0.75 / v.eps_va
    raise ValueError(f"eps_vbeta = {v.eps_vb:.3f} in (0, 1): Y_eps not implemented there")


def bevel_spiral_angle_factor(v: VirtualGears) -> float:
    """Y_BS (ISO 10300-3 6.4.4, formulae (30) to (35)): b_a = b_v / cos(beta_v) (34), l_bb = l_bm cos(beta_vb) /
    cos(beta_v) (35), x = 2 b_a / (h_m1 + h_m2) with h_m the mean whole depths, a_BS = -0.0182 x^2 + 0.4736 x
    - 0.32, b_BS = -0.0032 x^2 + 0.0526 x + 0.712, c_BS = -0.0050 x^2 + 0.0850 x + 0.54, Y_BS = a_BS / c_BS
    (l_bb / b_a - 1.05 b_BS)^2 + 1 (30)."""
    ba = v.b / math.cos(v.beta_v)
    lbb = v.l_bm * math.cos(v.beta_vb) / math.cos(v.beta_v)
    x = 2 * ba / (v.h_am1 + v.h_fm1 + v.h_am2 + v.h_fm2)
    a = -0.0182 * x * x + 0.4736 * x - 0.32
    bb = -0.0032 * x * x + 0.0526 * x + 0.712
    c = -0.0050 * x * x + 0.0850 * x + 0.54
    return a / c * (lbb / ba - 1.05 * bb) ** 2 + 1.0


@dataclass(frozen=True)
class Iso10300B1:
    """ISO 10300 Method B1 nominal figures of a pair at one pinion torque (K factors = 1).

    sigma_H0 = sqrt(F_n / (l_bm rho_rel)) Z_M-B Z_LS Z_E (ISO 10300-2 formula (2)), F_n = F_mt1 / (cos(alpha_n)
    cos(beta_m)) (ISO 10300-1 formula (3)), F_mt1 = 2 T1 / d_m1 (formula (1));
    sigma_F0 = F_vmt / (b_v m_mn) Y_Fa Y_Sa Y_eps Y_BS Y_LS (ISO 10300-3 formula (2)), F_vmt = F_mt1 cos(beta_v)
    / cos(beta_m1) = F_mt1 without offset (ISO 10300-1 formula (2)), Y_LS = Z_LS^2 (ISO 10300-3 formula (36)).
    """
    torque_nm: float
    F_mt1: float
    F_n: float
    Z_MB: float
    Z_LS: float
    Z_E: float
    sigma_H0: float
    Y_eps: float
    Y_BS: float
    Y_LS: float
    pinion: ToothForm
    gear: ToothForm
    sigma_F0_pinion: float
    sigma_F0_gear: float
    b_eff: float
    e_ls: float

    def as_dict(self) -> dict:
        return asdict(self)


def iso10300_b1(blank, torque_nm: float, young: float = 206000.0, poisson: float = 0.3,
                rho_a0: tuple[float | None, float | None] = (None, None), b_eff: float | None = None,
                e_ls: float = 1.5) -> Iso10300B1:
    """ISO 10300 Method B1 nominal contact and root stresses of a bevel pair at the pinion torque |torque_nm|.

    Parameters
    ----------
    blank : BevelBlank
        The pair's blank (:func:`ltca.geometry.bevel.blank.design_blank`).
    torque_nm : float
        Pinion torque, N m (its magnitude; both flanks share the blank's pressure angle).
    young, poisson : float
        Material of both members, MPa and 1.
    rho_a0 : (float, float)
        Edge radius of the pinion's and the gear's cutter blades, mm (None: 0.2 outer modules, the gear
        cutter's default in :func:`ltca.geometry.bevel.machine.gear_settings`).
    b_eff : float, optional
        Effective face width, mm (default 0.85 b).
    e_ls : float
        Exponent of the load sharing factor (1.5 high, 3 low profile crowning).

    Notes
    -----
    Profile shift and thickness of the Gleason blank as ISO 23509 coefficients at the mean point: x_hm1 =
    (h_am1 - h_am2) / (2 m_mn) = -x_hm2, the tool addendum h_a0 = (h_fm1 + h_fm2) / 2, x_sm from the mean normal
    thickness s_mn = m_mn (pi/2 + 2 (x_sm + x_hm tan(alpha_n))); no protuberance.
    """
    v = virtual_gears(blank, b_eff)
    T1 = abs(float(torque_nm)) * 1e3
    F_mt1 = 2 * T1 / v.d_m1
    F_n = F_mt1 / (math.cos(v.alpha_n) * math.cos(v.beta_m))
    Z_MB, Z_LS, Z_E = mid_zone_factor(v), load_sharing_factor(v, e_ls), elasticity_factor(young, poisson)
    sigma_H0 = math.sqrt(F_n / (v.l_bm * v.rho_rel)) * Z_MB * Z_LS * Z_E
    m = v.m_mn
    x_hm1 = (v.h_am1 - v.h_am2) / (2 * m)
    h_a0 = 0.5 * (v.h_fm1 + v.h_fm2)
    r_default = 0.2 * blank.data.module
    forms = []
    for x_hm, mb, z_vn, d_van, d_vbn, r in ((x_hm1, blank.pinion, v.z_vn1, v.d_van1, v.d_vbn1, rho_a0[0]),
                                            (-x_hm1, blank.gear, v.z_vn2, v.d_van2, v.d_vbn2, rho_a0[1])):
        x_sm = 0.5 * (mb.mean_normal_thickness / m - 0.5 * math.pi) - x_hm * math.tan(v.alpha_n)
        forms.append(tooth_form(m, h_a0, x_hm, x_sm, r_default if r is None else r, v.alpha_n, z_vn, d_van, d_vbn))
    Y_eps, Y_BS, Y_LS = contact_ratio_factor(v), bevel_spiral_angle_factor(v), Z_LS ** 2
    F_vmt = F_mt1
    base = F_vmt / (v.b * m) * Y_eps * Y_BS * Y_LS
    return Iso10300B1(float(torque_nm), F_mt1, F_n, Z_MB, Z_LS, Z_E, sigma_H0, Y_eps, Y_BS, Y_LS, forms[0],
                      forms[1], base * forms[0].Y_Fa * forms[0].Y_Sa, base * forms[1].Y_Fa * forms[1].Y_Sa,
                      v.b_eff, e_ls)
