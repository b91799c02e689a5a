"""Helical pair (physics: smoother than the spur pair of the same transverse geometry) and the
internal pair (concave ring flank: negative relative curvature, Hertz with 1/R = 1/rho1 - 1/rho2)."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fixtures.paths import CASES
from ltca.case import FIDELITIES, load_case
from ltca.cylindrical.loaded_model import Fidelity, prepare
from ltca.cylindrical.model import build_model
from ltca.cylindrical.run import analyse, cycle_rolls
from ltca.verify.validate import pitch_point_hertz


def _te_ptp(case, tmp_path, n=12, fidelity="default"):
    model = build_model(case)
    fid = Fidelity.from_preset(FIDELITIES[fidelity], case.module)
    rolls = cycle_rolls(n, case.pinion.teeth)
    lm = prepare(model, fid, rolls, case.torques[0], cache_dir=tmp_path)
    res = analyse(lm, rolls, case.torques[0])
    te = np.array([r.theta for r in res])
    assert all(r.torque_residual < 1e-6 for r in res)
    return np.ptp(te) / model.pair.ratio * 206264.8, res


@pytest.mark.heavy
@pytest.mark.parametrize("fidelity", ["coarse", pytest.param("default", marks=pytest.mark.heavy)])
def test_helical_te_smaller_than_spur_of_same_transverse_geometry(tmp_path, fidelity):
    """The helical pair's loaded TE peak-to-peak is under 0.8 of the spur pair's of the same transverse geometry, at
    the coarse fidelity (default tier) and the default one (heavy tier)."""
    helical = load_case(CASES / "helical_c14.toml")
    mt = helical.module / np.cos(helical.helix_angle)
    at = np.arctan(np.tan(helical.pressure_angle) / np.cos(helical.helix_angle))
    xt = lambda x: x * helical.module / mt
    spur = dataclasses.replace(
        helical, helix_angle=0.0, module=mt, pressure_angle=at,
        rack_addendum=helical.rack_addendum, rack_dedendum=helical.rack_dedendum,
        pinion=dataclasses.replace(helical.pinion, profile_shift=xt(helical.pinion.profile_shift)),
        gear=dataclasses.replace(helical.gear, profile_shift=xt(helical.gear.profile_shift)))
    ptp_h, _ = _te_ptp(helical, tmp_path, fidelity=fidelity)
    ptp_s, _ = _te_ptp(spur, tmp_path, fidelity=fidelity)
    print(f"loaded TE ptp: helical {ptp_h:.2f} arcsec, spur {ptp_s:.2f} arcsec")
    assert ptp_h < 0.8 * ptp_s


@pytest.mark.parametrize("fidelity", ["coarse", pytest.param("default", marks=pytest.mark.heavy)])
def test_internal_pair_converges_with_concave_contact(tmp_path, fidelity):
    """The internal pair at the pitch point against concave-convex Hertz, at the coarse fidelity (default tier) and
    the default one (heavy tier), with the same bounds."""
    case = load_case(CASES / "internal_spur.toml")
    model = build_model(case)
    assert model.gear.internal
    fid = Fidelity.from_preset(FIDELITIES[fidelity], case.module)
    rolls = cycle_rolls(10, case.pinion.teeth)
    lm = prepare(model, fid, rolls, case.torques[0], cache_dir=tmp_path)
    res = analyse(lm, rolls, case.torques[0])
    for r in res:
        assert r.torque_residual < 1e-6
        assert r.torque_ratio == pytest.approx(case.gear.teeth / case.pinion.teeth, rel=1e-4)
    hc = pitch_point_hertz(lm, case.torques[0])
    # concave-convex Hertz: the relative radius is larger than either flank's, the pressure low
    print(f"internal pitch point: p0 {hc.p0:.1f} vs Hertz {hc.p0_hertz:.1f} MPa, b {1e3 * hc.b:.1f} vs "
          f"{1e3 * hc.b_hertz:.1f} um")
    assert abs(hc.p0_error) < 0.05 and abs(hc.b_error) < 0.08
