"""Drive-train budget against Wang et al. (Chinese Journal of Engineering p. 1061).

Table 2 gives the stiffnesses, Table 3 the member deformations in 1e-3 deg at 2.5/5/7.5/10 N m.
The gear face width x base radius^2 and the ball-spline pitch radius are not on the paper's page; the
case file uses the values these tables imply (b = 20 mm, r_b = 80 mm; r = 16 mm), derived below.
"""
from __future__ import annotations

import numpy as np
import pytest

from fixtures.paths import CASES
from ltca.drivetrain.backlash import backlash_curves, plot_backlash, unloaded_from_loaded
from ltca.drivetrain.budget import (
    DEG,
    BallSplineMember,
    DriveTrain,
    MeshMember,
    TorsionMember,
    compute_budget,
    load_budget_case,
    run_budget,
)
from ltca.errors import CaseError

CASE = str(CASES / "budget_wang.toml")
TORQUES = np.array([2.5, 5.0, 7.5, 10.0])
# Wang et al., Table 3 (p. 1061), theoretical deformation / (1e-3 deg)
TABLE3 = {"gear": [0.06, 0.11, 0.17, 0.22], "shaft": [8.64, 17.27, 25.91, 34.55],
          "spline": [1.06, 1.69, 2.21, 2.68], "coupling": [7.66, 15.32, 22.98, 30.64]}
TABLE3_TOTAL = [17.42, 34.39, 51.27, 68.09]


@pytest.fixture(scope="module")
def result():
    train, torques = load_budget_case(CASE)
    np.testing.assert_array_equal(torques, TORQUES)
    return compute_budget(train, torques)


@pytest.mark.parametrize("name", list(TABLE3))
def test_members_match_table3(result, name):
    """Shaft and coupling: Table 2 against Table 3 (independent). Gear and spline: a consistency check only (their
    b r_b^2 and ball radius were read back from this table, test_implied_radii); the hand calculation from Eq. 19
    is in test_drivetrain_hand.py."""
    mine = result.deflection[result.names.index(name)] / DEG * 1e3
    table = np.array(TABLE3[name])
    tol = np.maximum(0.01 * table, 0.005)          # 1 % or half the last printed digit
    assert np.all(np.abs(mine - table) <= tol), (name, mine, table)


def test_total_matches_table3(result):
    mine = result.total / DEG * 1e3
    assert np.allclose(mine, TABLE3_TOTAL, rtol=0.01), mine
    # Table 3's total is the sum of its rounded rows: check the paper's own arithmetic too
    assert np.allclose(np.sum(list(TABLE3.values()), axis=0), TABLE3_TOTAL, atol=1e-9)


def test_implied_radii():
    """Derivation of the radii from the printed digits of Table 3."""
    c_gear = 20e3                                                  # N/(mm mm), Table 2
    lo = np.max((np.array(TABLE3["gear"]) - 0.005) / TORQUES)      # 1e-3 deg/(N m)
    hi = np.min((np.array(TABLE3["gear"]) + 0.005) / TORQUES)
    assert 0.0219 < lo < hi < 0.0226                                # slope interval is not empty
    b_rb2 = [1.0 / (c_gear * s * 1e-3 * DEG * 1e-3) for s in (hi, lo)]   # mm^3
    assert b_rb2[0] < 20.0 * 80.0**2 < b_rb2[1]                   # 128e3 in [127.3e3, 130.2e3]
    # spline: theta = T^(2/3) / (c_s r^(5/3)) -> r from the coefficient A = theta / T^(2/3)
    sp = np.array(TABLE3["spline"])
    a_lo = np.max((sp - 0.005) / TORQUES ** (2 / 3)) * 1e-3 * DEG  # rad/(N m)^(2/3)
    a_hi = np.min((sp + 0.005) / TORQUES ** (2 / 3)) * 1e-3 * DEG
    r_m = [(1.0 / (9.768e7 * a)) ** 0.6 for a in (a_hi, a_lo)]
    assert r_m[0] < 0.016 < r_m[1] and r_m[1] - r_m[0] < 5e-5     # 15.99 .. 16.02 mm
    # the integrated tangent-stiffness form (3/2 P^(2/3)/c_s) would need r 1.5^(3/5) larger
    assert 0.016 * 1.5**0.6 > r_m[1] + 4e-3


def test_b0_linear_in_torque(result):
    """Eq. (19): B0 = sum(1/k_i) T + j_phi0 is linear when the k_i are constant; the ball spline
    (k ~ P^(1/3)) adds a T^(2/3) term of 4 % of the total, so B0 is linear to 0.5 % of its range."""
    lin = result.hysteresis - result.deflection[result.names.index("spline")]
    slope = np.polyfit(result.torque, lin, 1)
    assert np.allclose(np.polyval(slope, result.torque), lin, rtol=1e-12, atol=0)
    assert abs(np.polyval(slope, 0.0)) < 1e-15                    # j_phi0 = 0 in the case
    fit = np.polyval(np.polyfit(result.torque, result.hysteresis, 1), result.torque)
    dev = np.max(np.abs(fit - result.hysteresis)) / np.ptp(result.hysteresis)
    assert 1e-4 < dev < 5e-3, dev


def test_initial_backlash_and_ratio():
    k = 1.87e7                                                      # N mm/rad
    train = DriveTrain((TorsionMember("c", k, ratio=2.0),), initial_backlash=1e-3)
    res = compute_budget(train, [4.0])
    # member on a shaft twice as fast carries T/2, twists T/(2k), seen as T/(4k) at the reference
    assert res.total[0] == pytest.approx(4e3 / (4 * k))
    assert res.hysteresis[0] == pytest.approx(4e3 / (4 * k) + 1e-3)
    mesh = MeshMember("g", 2e4, 20.0, 80.0)
    assert mesh.stiffness == pytest.approx(2e4 * 20 * 6400)
    spline = BallSplineMember("s", 9.768e4, 16.0)
    t = np.array([1e3, 8e3])
    assert spline.angle(t)[1] / spline.angle(t)[0] == pytest.approx(4.0)   # 8^(2/3)


def test_run_budget_writes_outputs(tmp_path, capsys):
    res = run_budget(CASE, str(tmp_path))
    out = capsys.readouterr().out
    assert "68.09" in out and "spline" in out
    data = np.loadtxt(tmp_path / "budget.csv", delimiter=",", skiprows=1)
    assert data.shape == (4, 7) and data[-1, -1] == pytest.approx(res.hysteresis[-1] / DEG * 1e3)
    assert (tmp_path / "budget.png").stat().st_size > 1000


@pytest.mark.parametrize("text,field", [
    ('kind = "torsion"\nstiffness_Nm_per_rad = -1.0', "member[0].stiffness_Nm_per_rad"),
    ('kind = "torsion"\nstiffness_Nm_per_deg = 0', "member[0].stiffness_Nm_per_deg"),
    ('kind = "torsion"\nstiffnes_Nm_per_rad = 5.0', "member[0].stiffnes_Nm_per_rad"),
    ('kind = "spring"', "member[0].kind"),
    ('kind = "mesh"\nstiffness_N_per_um_mm = 20\nface_width_mm = "20"\nbase_radius_mm = 80',
     "member[0].face_width_mm"),
    ('kind = "shaft"\nshear_modulus_MPa = 8e4\ndiameter_mm = 20\nlength_mm = 100\nbore_mm = 25',
     "member[0].bore_mm"),
])
def test_bad_member_names_field(tmp_path, text, field):
    p = tmp_path / "bad.toml"
    p.write_text(f'[budget]\ntorque_nm = [1.0]\n[[member]]\nname = "x"\n{text}\n')
    with pytest.raises(CaseError) as exc:
        load_budget_case(str(p))
    assert exc.value.field == field


def test_bad_torques(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text('[budget]\ntorque_nm = [1.0, -2.0]\n[[member]]\nname = "x"\n'
                 'kind = "torsion"\nstiffness_Nm_per_rad = 1.0\n')
    with pytest.raises(CaseError, match="budget.torque_nm"):
        load_budget_case(str(p))


def test_backlash_curves_eq20_21(tmp_path):
    """Eq. (20)-(21): loaded curves = unloaded shifted by -/+ delta_k; backlash = coast - drive."""
    phi = np.linspace(0, 2 * np.pi, 361)
    drive = 1e-5 * np.sin(20 * phi)
    coast = 3e-4 + 1e-5 * np.sin(20 * phi + 0.3) + 2e-5 * np.cos(phi)
    train, torques = load_budget_case(CASE)
    dk = compute_budget(train, torques).total[0]                   # 17.42e-3 deg at 2.5 N m
    c = backlash_curves(phi, drive, coast, dk)
    np.testing.assert_allclose(c.backlash, coast - drive)
    np.testing.assert_allclose(c.loaded_drive, drive - dk)
    np.testing.assert_allclose(c.loaded_coast, coast + dk)
    np.testing.assert_allclose(c.loaded_hysteresis, c.backlash + 2 * dk)
    back = unloaded_from_loaded(phi, c.loaded_drive, c.loaded_coast, dk)
    np.testing.assert_allclose(back.backlash, c.backlash, atol=1e-18)
    assert c.min_backlash == pytest.approx(np.min(coast - drive))
    plot_backlash(c, str(tmp_path / "b.png"), "test")
    assert (tmp_path / "b.png").stat().st_size > 1000
    with pytest.raises(ValueError):
        backlash_curves(phi, drive, coast[:-1], dk)
    with pytest.raises(ValueError):
        backlash_curves(phi, drive, coast, -1e-4)
