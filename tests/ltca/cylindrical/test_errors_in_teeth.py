"""Machine errors turned into tooth errors and run through TCA/LTCA.

Backlash of thinned teeth against the closed-form value; Nguyen et al. (2020) pitch errors over a pinion
revolution (once-per-revolution and tooth-mesh content, load moving to the pair with the smaller gap);
a generating-ratio error as a profile slope deviation shifting the bearing pattern."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import tomllib

from fixtures.cylindrical import with_case
from fixtures.paths import CASES
from ltca.case import Modifications, load_case
from ltca.cylindrical.model import build_model, working_centre_distance
from ltca.cylindrical.run import analyse, cycle_rolls
from ltca.cylindrical.tca import ARCSEC_PER_RAD, double_flank_tca


def test_backlash_of_thinned_teeth_matches_closed_form():
    case = load_case(CASES / "fzg_c14.toml")
    A1, A2 = 0.030, 0.050
    case = dataclasses.replace(case, pinion=dataclasses.replace(case.pinion, thickness_allowance=A1),
                               gear=dataclasses.replace(case.gear, thickness_allowance=A2))
    model = build_model(case)
    drive, coast = double_flank_tca(model, cycle_rolls(5, 16, 2))
    backlash = coast - drive
    # thinning by A (transverse arc on the reference circle) frees a rotation A / r of that member; the
    # centre distance a below the zero-backlash a0 takes back 2 (a0 - a) tan(alpha_wt) along the pitch circle
    a0 = working_centre_distance(case)
    pair = model.pair
    r_w2 = pair.a - pair.r_w1
    expected = (A1 / 36.0 * 16 / 24 + A2 / 54.0 - 2 * (a0 - pair.a) * np.tan(pair.alpha_w) / r_w2) * ARCSEC_PER_RAD
    assert np.ptp(backlash) < 0.01
    assert backlash.mean() == pytest.approx(expected, abs=0.05)
    assert np.all(drive <= 1e-3) and np.all(coast > 0)


def test_budget_case_writes_backlash_curves(tmp_path):
    from ltca.drivetrain.budget import run_budget
    result = run_budget(str(CASES / "budget_wang.toml"), str(tmp_path))
    data = np.genfromtxt(tmp_path / "backlash.csv", delimiter=",", names=True)
    # 30 + 30 um thinning of FZG C14: (0.03/36 * 16/24 + 0.03/54) rad = 229.19 arcsec less 0.25 arcsec for
    # the 0.08 um tight centre distance
    assert data["backlash_arcsec"] == pytest.approx(228.94, abs=0.05)
    last = f"{result.torque[-1]:g}Nm"
    shift = data[f"loaded_coast_{last}"] - data[f"loaded_drive_{last}"] - data["backlash_arcsec"]
    assert shift == pytest.approx(2 * result.total[-1] * ARCSEC_PER_RAD, rel=1e-6)      # Eq. 20-21


def _pitch_error_mods():
    text = tomllib.loads((CASES / "fzg_c14_pitch_errors.toml").read_text())
    errs = text["pinion"]["modifications"]["pitch_errors_um"]
    return Modifications(pitch_errors=tuple(sorted((int(k), v * 1e-3) for k, v in errs.items())))


def test_pitch_error_case_follows_from_the_seed_002_indexing_chain():
    from ltca.drivetrain.chain import evaluate_chain, load_chain_case, pitch_deviation_bound
    from ltca.geometry.errors import tooth_positions, worst_case_pitch_deviations
    indexing_z1 = next(c for c in load_chain_case(str(CASES / "chain_zftkk250.toml")) if "index" in c.name.lower()
                       and c.name.lower().rstrip().endswith("z1"))
    bound = pitch_deviation_bound(evaluate_chain(indexing_z1))
    assert bound == pytest.approx(0.01032, abs=5e-6)          # Nguyen et al. 2020: 20.64 um band -> +-10.32 um
    expected = tooth_positions(worst_case_pitch_deviations(16, bound, "half"))
    case = dict(_pitch_error_mods().pitch_errors)
    assert np.allclose([case[k] for k in range(16)], expected, atol=6e-6)   # file rounds to 0.01 um


def test_pitch_errors_over_a_revolution(fzg_lm, fzg_case):
    T = fzg_case.torques[0]
    lm = with_case(fzg_lm, pinion=dataclasses.replace(fzg_case.pinion, modifications=_pitch_error_mods()))
    n, z1 = 4, 16
    rolls = cycle_rolls(n, z1, z1)
    res = analyse(lm, rolls, T)
    ref = analyse(fzg_lm, rolls, T)
    for r in res:
        assert np.isfinite(r.theta) and r.torque_residual < 1e-6 and np.all(np.isfinite(r.pressure))
    te = np.array([r.theta for r in res]) / lm.model.pair.ratio * ARCSEC_PER_RAD
    te0 = np.array([r.theta for r in ref]) / lm.model.pair.ratio * ARCSEC_PER_RAD
    amp = np.abs(np.fft.rfft(te)) * 2 / len(te)
    amp0 = np.abs(np.fft.rfft(te0)) * 2 / len(te0)
    # once per revolution: the cumulative pitch error is a triangle of +-41.28 um on the pinion base
    # circle (r_b1 = 33.83 mm) -> +-167.6 arcsec of the gear; its first harmonic is 8/pi^2 of that
    assert amp[1] == pytest.approx(8 / np.pi ** 2 * 41.28e-3 / 33.8289 * 16 / 24 * ARCSEC_PER_RAD, rel=0.15)
    assert amp0[1] < 0.01 * amp[1]
    assert amp[z1] > 1.0 and amp0[z1] > 1.0          # tooth-mesh content in both


def test_load_moves_to_the_pair_with_the_smaller_gap(fzg_lm, fzg_case):
    T = fzg_case.torques[0]
    mods = _pitch_error_mods()
    lm = with_case(fzg_lm, pinion=dataclasses.replace(fzg_case.pinion, modifications=mods))
    pos = dict(mods.pitch_errors)
    roll = np.radians(-9.0)                             # double contact of model teeth 0 and 1
    from ltca.cylindrical.loaded import solve_position
    nominal = solve_position(fzg_lm, roll, T)
    for cycle in (2, 11):                               # errors rising / falling between the two teeth
        r = solve_position(lm, roll, T, cycle=cycle)
        e0, e1 = pos[(0 - cycle) % 16], pos[(1 - cycle) % 16]
        smaller = 0 if e0 < e1 else 1                  # drive flank moved back less: smaller gap
        share = r.pair_load[smaller] / sum(r.pair_load.values())
        share_nom = nominal.pair_load[smaller] / sum(nominal.pair_load.values())
        assert share > share_nom + 0.1


def test_roll_ratio_error_shifts_the_bearing_pattern(fzg_lm, fzg_case):
    from ltca.geometry.modification import profile_slope_from_roll_ratio
    T = fzg_case.torques[0]
    eps = 8.0e-4          # envelope chain extreme of Nguyen et al. (ltca.drivetrain.chain.roll_ratio_error: 0.99920)
    p1 = fzg_lm.model.pinion
    fH = profile_slope_from_roll_ratio(eps, p1.r_base, p1.r_form_right, p1.r_tip)
    assert fH == pytest.approx(eps * (np.sqrt(p1.r_tip ** 2 - p1.r_base ** 2) -
                                      np.sqrt(p1.r_form_right ** 2 - p1.r_base ** 2)))
    lm = with_case(fzg_lm, pinion=dataclasses.replace(fzg_case.pinion,
                                                        modifications=Modifications(roll_ratio_error=eps)))
    rolls = cycle_rolls(10, 16)

    def centroid(results):
        s = np.concatenate([r.s for r in results])
        f = np.concatenate([r.force * 0 + r.pressure for r in results])
        return float(np.sum(s * f) / np.sum(f))
    c_err, c_nom = centroid(analyse(lm, rolls, T)), centroid(analyse(fzg_lm, rolls, T))
    # material removed towards the pinion tip: the pattern moves towards the pinion root
    assert c_err < c_nom - 0.05
