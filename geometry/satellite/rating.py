"""Rated torque of the satellite from its ISO 6336-3 tooth-root bending capacity (Method B).

    sigma_F  = F_t / (b m_n) Y_F Y_S Y_beta Y_B Y_DT K_A K_V K_Fbeta K_Falpha          (ISO 6336-3 eq. 3, 4)
    sigma_FP = sigma_Flim Y_ST Y_NT Y_deltarelT Y_RrelT Y_X / S_Fmin                    (ISO 6336-3 eq. 5)

and the rated torque ``T = F_t d / 2`` at ``sigma_F = sigma_FP``. The form and stress-correction factors are
measured on the GENERATED satellite outline (:func:`root_section`): the 30 deg tangents to the fillet give the
critical chord s_Fn and the fillet radius rho_F there; the load acts at the tip corner along the involute
normal (the whole F_t on one tooth: ISO's "load at the tip", Y_F = 6 (h_Fe/m) cos(alpha_Fen) / ((s_Fn/m)^2
cos(alpha_n)), Y_S = (1.2 + 0.13 L) q_s^(1 / (1.21 + 2.3 / L)), L = s_Fn / h_Fe, q_s = s_Fn / (2 rho_F),
ISO 6336-3:2006 eq. 7-8, 13-15 and 30-31). That is conservative here: the internal mesh shares the load among
several pairs (:mod:`ltca.geometry.satellite.separation`), which a single-pair rating ignores; the LTCA gives the
real root stress. Y_beta = 1 (spur), Y_B = 1 (rim thick: s_R / h_t > 1.2), Y_DT = 1 (it applies only to
epsilon_alpha n >= 2 with ISO accuracy grade <= 4; a cut 40Kh satellite is grade 7-8).

Material (stated choice, not from the seed): 40Kh (GOST 4543, ~ 41Cr4), quenched and tempered to
269-302 HB (about 300 HV), ISO 6336-5 quality MQ, through-hardened wrought alloy steel: sigma_Flim =
0.425 HV + 187 = 315 MPa (the MQ line of ISO 6336-5 for through-hardened alloy steel as recalled here; the
standard's figure should be read to confirm it). Y_ST = 2, Y_NT = 1 (N_L >= 3e6), Y_RrelT = 1 (Rz <= 16 um),
Y_X = 1 (m <= 5 mm), Y_deltarelT from ISO 6336-3 eq. 35 with the slip-layer thickness rho' = 0.0194 mm
(through-hardened steel, yield 800 MPa; 40Kh: >= 785 MPa); S_Fmin = 1.4; face width b = 20 mm.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..gear_blank import _check
from ..profile import ToothProfile

__all__ = ["RootSection", "root_section", "BendingRating", "rated_torque", "RatingInputs"]


@dataclass(frozen=True)
class RootSection:
    """Critical root section by the 30 deg tangents (mm, rad): chord s_Fn, fillet radius rho_F there, the
    moment arm h_Fe of the tip load, load angle alpha_Fen, and the factors Y_F, Y_S."""

    s_Fn: float
    rho_F: float
    h_Fe: float
    alpha_Fen: float
    Y_F: float
    Y_S: float


def root_section(profile: ToothProfile, tangent_angle: float = np.pi / 6,
                 load_radius: float | None = None) -> RootSection:
    """30 deg tangent root section of an external generated tooth, load at the tip corner (module doc), or with
    ``load_radius`` (mm) on the involute at that radius (ISO 6336-3 Method B: the outer point of single tooth
    contact, d_en / 2), along the involute normal there."""
    if profile.internal:
        raise ValueError("root_section: external teeth only (internal teeth use the 60 deg tangent)")
    xy, kind = profile.xy, profile.kind
    right = np.nonzero((xy[:, 0] > 0) & (kind != 3))[0]
    p = xy[right]                                             # tip corner side -> root
    t = np.gradient(p, axis=0)
    gam = np.arctan2(np.abs(t[:, 0]), np.abs(t[:, 1]))        # tangent angle to the centre line (+y)
    fil = np.nonzero((kind[right] == 1) & (np.abs(np.gradient(gam)) < 0.2))[0]
    i = fil[np.argmin(np.abs(gam[fil] - tangent_angle))]
    j0, j1 = max(i - 1, fil[0]), min(i + 1, fil[-1])
    # exact crossing of gamma = 30 deg between neighbours
    for a, b in ((j0, i), (i, j1)):
        if (gam[a] - tangent_angle) * (gam[b] - tangent_angle) <= 0 and gam[a] != gam[b]:
            f = (tangent_angle - gam[a]) / (gam[b] - gam[a])
            F = p[a] + f * (p[b] - p[a])
            break
    else:
        F = p[i]
    w = slice(max(i - 6, 0), i + 7)                           # curvature radius by a circle fit
    q = p[w]
    A = np.column_stack([2 * q, np.ones(len(q))])
    c = np.linalg.lstsq(A, (q ** 2).sum(1), rcond=None)[0]
    rho_F = float(np.sqrt(c[2] + c[0] ** 2 + c[1] ** 2))
    s_Fn = 2 * float(F[0])
    # load at the tip corner along the involute normal (tangent to the base circle)
    if load_radius is None:
        Pt = xy[(kind == 3) & (xy[:, 0] >= 0)][-1]
    else:
        Pt = np.asarray(profile.flank_xy(float(load_radius), +1), float)
    ra, rb = np.hypot(*Pt), profile.r_base
    ang_T = np.arctan2(Pt[0], Pt[1]) - np.arccos(rb / ra)     # cw angle of the base tangency point
    T = rb * np.array([np.sin(ang_T), np.cos(ang_T)])
    n = (T - Pt) / np.linalg.norm(T - Pt)                     # force direction, into the tooth
    alpha_Fen = float(np.arctan2(-n[1], -n[0]))               # below the horizontal, towards the centre line
    y_E = Pt[1] + n[1] * (-Pt[0] / n[0])                      # where the force line crosses x = 0
    h_Fe = float(y_E - F[1])
    m = profile.m_n
    Y_F = 6 * (h_Fe / m) * np.cos(alpha_Fen) / ((s_Fn / m) ** 2 * np.cos(profile.alpha_n))
    L, qs = s_Fn / h_Fe, s_Fn / (2 * rho_F)
    Y_S = (1.2 + 0.13 * L) * qs ** (1 / (1.21 + 2.3 / L))
    return RootSection(s_Fn, rho_F, h_Fe, alpha_Fen, float(Y_F), float(Y_S))


@dataclass(frozen=True)
class RatingInputs:
    """Rating data (MPa, mm): sigma_Flim, face width b, S_Fmin, slip-layer rho' (mm), K_A, K_V, K_Fbeta,
    K_Falpha, Y_NT, Y_RrelT, Y_X, Y_ST (module doc for the choices). All > 0."""

    sigma_Flim: float = 0.425 * 300 + 187
    b: float = 20.0
    S_Fmin: float = 1.4
    rho_slip: float = 0.0194
    K_A: float = 1.0
    K_V: float = 1.0
    K_Fbeta: float = 1.0
    K_Falpha: float = 1.0
    Y_NT: float = 1.0
    Y_RrelT: float = 1.0
    Y_X: float = 1.0
    Y_ST: float = 2.0

    def __post_init__(self):
        for name, v in self.__dict__.items():
            _check(f"RatingInputs.{name}", v, np.isfinite(v) and v > 0, "> 0")


@dataclass(frozen=True)
class BendingRating:
    """Rated torque (N m) and tangential force (N) of the satellite, with every factor used."""

    torque_Nm: float
    F_t: float
    sigma_FP: float
    section: RootSection
    Y_deltarelT: float
    factors: dict


def rated_torque(profile: ToothProfile, inputs: RatingInputs = RatingInputs()) -> BendingRating:
    """ISO 6336-3 Method B rated torque of the satellite (module doc), N m."""
    sec = root_section(profile)
    qs = sec.s_Fn / (2 * sec.rho_F)
    x_star = (1 + 2 * qs) / 5                                  # ISO 6336-3 eq. 36, relative stress gradient
    y_drel = (1 + np.sqrt(inputs.rho_slip * x_star)) / (1 + np.sqrt(inputs.rho_slip * 1.2))
    sigma_FP = inputs.sigma_Flim * inputs.Y_ST * inputs.Y_NT * y_drel * inputs.Y_RrelT * inputs.Y_X / inputs.S_Fmin
    K = inputs.K_A * inputs.K_V * inputs.K_Fbeta * inputs.K_Falpha
    m = profile.m_n
    F_t = sigma_FP * inputs.b * m / (sec.Y_F * sec.Y_S * 1.0 * 1.0 * 1.0 * K)
    d = 2 * profile.r_ref
    factors = dict(Y_F=sec.Y_F, Y_S=sec.Y_S, Y_beta=1.0, Y_B=1.0, Y_DT=1.0, Y_deltarelT=float(y_drel),
                   Y_ST=inputs.Y_ST, Y_NT=inputs.Y_NT, Y_RrelT=inputs.Y_RrelT, Y_X=inputs.Y_X, K_A=inputs.K_A,
                   K_V=inputs.K_V, K_Fbeta=inputs.K_Fbeta, K_Falpha=inputs.K_Falpha, S_Fmin=inputs.S_Fmin,
                   sigma_Flim=inputs.sigma_Flim, b=inputs.b)
    return BendingRating(torque_Nm=float(F_t * d / 2 / 1000), F_t=float(F_t), sigma_FP=float(sigma_FP),
                         section=sec, Y_deltarelT=float(y_drel), factors=factors)
