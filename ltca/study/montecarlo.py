"""Monte Carlo tooth errors of an ISO 1328-1 flank tolerance class, mapped onto the case keys.

Sampling model: every drawn gear conforms to the class and uses the whole tolerance band, each deviation
uniform within its tolerance (:mod:`ltca.study.iso1328`), independently per member and per sample (sample i
of seed s is the same whatever the sample size: numpy ``SeedSequence(s, spawn_key=(i,))``). Per member:

- runout F_r ~ U[0, F_rT], modelled as an eccentricity e = F_r / 2 (a ball probe in the tooth spaces of a gear
  whose axis is off by e reads a runout of 2 e) at a uniform phase; it moves tooth k along its base tangent by
  e sin(2 pi k / z + phase). Its centre-distance part e cos(...) is not modelled: an involute pair's
  transmission is insensitive to the centre distance (second order through the contact ratio).
- single pitch deviations: each pitch uniform within +/- (f_pT - 2 e sin(pi / z)), closing over the revolution
  (:func:`ltca.geometry.errors.random_pitch_deviations`), so that with the eccentricity every measured single pitch
  deviation stays within f_pT. Their sum is each tooth's position error: case key
  ``<member>.modifications.pitch_errors_um`` (added to any the base case has). The total cumulative pitch
  deviation F_p follows from these; a draw whose F_p exceeds F_pT is drawn again (rejection: the gear
  conforms to the class in F_p as well).
- profile slope f_Halpha ~ U[-f_HalphaT, f_HalphaT] -> ``profile_slope_um``; helix slope f_Hbeta ->
  ``lead_slope_um`` (over the face width: the model's evaluation range is the whole flank, ISO's slightly less).
- profile form f_falpha and helix form f_fbeta ~ U[-T, T] (sign: convex or hollow) -> ``profile_form_um`` and
  ``lead_form_um``, the parabolic part of a form deviation (:class:`ltca.geometry.modification.FlankModification`);
  waviness is not modelled.
- slope and form are the same on every tooth of a member (the case keys are per member): their tooth-to-tooth
  scatter is not modelled.

Drawn case keys (``[monte_carlo.uniform]``, ``[monte_carlo.normal]``, any gear kind, e.g. a bevel pair's
assembly errors E, P, G and the shaft angle error): each key independently, uniform in [low, high] or normal
(mean, standard deviation), per sample from numpy ``SeedSequence(seed, spawn_key=(i, 1))`` (sample i is the same
whatever the sample size, and the ISO 1328 draws of a cylindrical sample are not moved by them).

Imports geometry.errors, ltca.case, ltca.errors and ltca.study.iso1328.
"""
from __future__ import annotations

import numpy as np
from scipy import stats

from ltca.geometry.errors import random_pitch_deviations, tooth_positions

from ..case import CylindricalCase
from ..errors import CaseError
from .iso1328 import TOLERANCE_KINDS, Iso1328Tolerances, iso1328_tolerances

__all__ = ["MEMBERS", "member_tolerances", "draw_sample", "draw_keys", "check_key_draws", "check_draws",
           "check_members"]

MEMBERS = ("pinion", "gear")
_KEYS = {"f_Halpha": "profile_slope_um", "f_falpha": "profile_form_um", "f_Hbeta": "lead_slope_um",
         "f_fbeta": "lead_form_um"}


def member_tolerances(case: CylindricalCase, member: str, grade: int) -> Iso1328Tolerances:
    """ISO 1328-1:2013 tolerances of the case's ``member`` ("pinion" or "gear") in class ``grade``."""
    m = getattr(case, member)
    return iso1328_tolerances(grade, m.teeth, case.module, m.face_width, float(np.degrees(case.helix_angle)))


def _draw_member(tol: Iso1328Tolerances, teeth: int, rng: np.random.Generator) -> tuple[np.ndarray, dict]:
    """Tooth position errors (um, per tooth) and the drawn / measured deviations (um) of one gear."""
    e = 0.5 * rng.uniform(0.0, tol.F_rT)
    phase = rng.uniform(0.0, 2 * np.pi)
    k = np.arange(teeth)
    ecc = e * np.sin(2 * np.pi * k / teeth + phase)
    room = max(tol.f_pT - 2 * e * np.sin(np.pi / teeth), 0.0)
    for _ in range(1000):                                 # a conforming gear: F_p within F_pT too
        dev = random_pitch_deviations(teeth, room, seed=int(rng.integers(2 ** 63)))[0]
        pos = tooth_positions(dev) + ecc - ecc.mean()
        if np.ptp(pos) <= tol.F_pT:
            break
    single = np.roll(pos, -1) - pos                       # f_pt,k: pitch from tooth k to k + 1
    drawn = {"f_pt": float(np.abs(single).max()), "F_p": float(np.ptp(pos)), "F_r": 2 * e}
    for kind in _KEYS:
        bound = getattr(tol, TOLERANCE_KINDS[kind])
        drawn[kind] = float(rng.uniform(-bound, bound))
    return pos, drawn


def draw_sample(base: dict, case: CylindricalCase, grade: int, seed: int, index: int,
                members: tuple[str, ...] = MEMBERS) -> tuple[dict, dict]:
    """The case-key overrides and the drawn deviations of Monte Carlo sample ``index``.

    Parameters
    ----------
    base : dict
        The base case as read from TOML (its modifications are added to, not replaced).
    case : CylindricalCase
        The same case, parsed (teeth, module, face width, helix angle).
    grade : int
        ISO 1328-1:2013 flank tolerance class.
    seed, index : int
        Study seed and sample number.
    members : tuple of str
        Which gears get errors.

    Returns
    -------
    overrides : dict
        Dotted case key -> value, e.g. ``"pinion.modifications.profile_slope_um" -> 3.2``.
    drawn : dict
        ``"<member>.<kind>_um"`` -> the drawn deviation in um (kinds f_pt, F_p, F_r, f_Halpha, f_falpha,
        f_Hbeta, f_fbeta; f_pt and F_p as measured on the drawn tooth positions).
    """
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(index,)))
    overrides, drawn = {}, {}
    for name in MEMBERS:                                  # fixed order: the draws of one member don't move
        tol = member_tolerances(case, name, grade)
        teeth = getattr(case, name).teeth
        pos, d = _draw_member(tol, teeth, rng)
        if name not in members:
            continue
        mods = base.get(name, {}).get("modifications", {})
        old = {int(k): float(v) for k, v in mods.get("pitch_errors_um", {}).items()}
        overrides[f"{name}.modifications.pitch_errors_um"] = {
            str(t): round(float(pos[t]) + old.get(t, 0.0), 9) for t in range(teeth)}
        for kind, key in _KEYS.items():
            overrides[f"{name}.modifications.{key}"] = round(float(mods.get(key, 0.0)) + d[kind], 9)
        drawn.update({f"{name}.{kind}_um": v for kind, v in d.items()})
    return overrides, drawn


def draw_keys(uniform: dict, normal: dict, seed: int, index: int) -> dict[str, float]:
    """The drawn case keys of Monte Carlo sample ``index``.

    Parameters
    ----------
    uniform : dict
        Dotted case key -> (low, high), in the case's units.
    normal : dict
        Dotted case key -> (mean, standard deviation).
    seed, index : int
        Study seed and sample number.

    Returns
    -------
    dict
        Dotted case key -> drawn value (rounded to 1e-9 of the unit, as written into the variant's case).
    """
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(index, 1)))
    out = {}
    for key, (lo, hi) in uniform.items():
        out[key] = round(float(rng.uniform(lo, hi)), 9)
    for key, (mu, sd) in normal.items():
        out[key] = round(float(rng.normal(mu, sd)), 9)
    return out


def check_key_draws(drawn: list[dict], uniform: dict, normal: dict) -> dict:
    """Statistics of the drawn case keys against their laws: per key n, mean, std, min, max, the law's mean and
    std (uniform: (a + b) / 2, (b - a) / sqrt(12)) and the Kolmogorov-Smirnov p-value against it."""
    out = {}
    for key, law in [(k, ("uniform", v)) for k, v in uniform.items()] + [(k, ("normal", v)) for k, v in normal.items()]:
        x = np.array([d[key] for d in drawn if key in d])
        if x.size == 0:
            continue
        name, (a, b) = law
        if name == "uniform":
            exp_mean, exp_std = 0.5 * (a + b), (b - a) / np.sqrt(12)
            p = stats.kstest(x, "uniform", args=(a, b - a)).pvalue
        else:
            exp_mean, exp_std = a, b
            p = stats.kstest(x, "norm", args=(a, b)).pvalue
        out[key] = {"law": name, "parameters": [a, b], "n": int(x.size), "mean": float(x.mean()),
                    "std": float(x.std(ddof=1)) if x.size > 1 else 0.0, "min": float(x.min()), "max": float(x.max()),
                    "expected_mean": float(exp_mean), "expected_std": float(exp_std), "ks_p": float(p)}
    return out


def check_draws(drawn: list[dict], tolerances: dict[str, Iso1328Tolerances]) -> dict:
    """Statistics of the drawn deviations against the class's tolerances.

    Parameters
    ----------
    drawn : list of dict
        The ``drawn`` dicts of :func:`draw_sample`, one per sample.
    tolerances : dict
        Member name -> its tolerances.

    Returns
    -------
    dict
        ``"<member>.<kind>"`` -> {tolerance, n, within (fraction with |x| <= T), mean, std, max_abs, and for the
        uniformly drawn kinds the expected mean and std and the Kolmogorov-Smirnov p-value against that
        uniform law}. f_pt and F_p are measured, not drawn uniformly: within and the moments only.
    """
    out = {}
    for name, tol in tolerances.items():
        for kind in ("f_pt", "F_p", "F_r", "f_Halpha", "f_falpha", "f_Hbeta", "f_fbeta"):
            key = f"{name}.{kind}_um"
            x = np.array([d[key] for d in drawn if key in d])
            if x.size == 0:
                continue
            T = tol.F_pT if kind == "F_p" else getattr(tol, TOLERANCE_KINDS[kind])
            rec = {"tolerance_um": T, "n": int(x.size), "within": float(np.mean(np.abs(x) <= T + 1e-9)),
                   "mean_um": float(x.mean()), "std_um": float(x.std(ddof=1)) if x.size > 1 else 0.0,
                   "max_abs_um": float(np.abs(x).max())}
            if kind == "F_r":
                rec.update(expected_mean_um=T / 2, expected_std_um=T / np.sqrt(12),
                           ks_p=float(stats.kstest(x, "uniform", args=(0.0, T)).pvalue))
            elif kind not in ("f_pt", "F_p"):
                rec.update(expected_mean_um=0.0, expected_std_um=T / np.sqrt(3),
                           ks_p=float(stats.kstest(x, "uniform", args=(-T, 2 * T)).pvalue))
            out[f"{name}.{kind}"] = rec
    return out


def check_members(members, field: str = "monte_carlo.members") -> tuple[str, ...]:
    """Validate a list of member names (a CaseError names ``field``)."""
    if not isinstance(members, list) or not members or any(m not in MEMBERS for m in members):
        raise CaseError(field, members, f"a non-empty list of {list(MEMBERS)}")
    return tuple(dict.fromkeys(members))
