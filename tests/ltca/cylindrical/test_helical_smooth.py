"""Helical sampling: the per-position TE, root stress and peak pressure of helical C14 change smoothly from one
position to the next. The cells are long along the contact line (one face slice) and cross the tip edges
obliquely, so they lie on the developed flank along the nominal contact line (ltca.cylindrical.flank_lattice)
and are clipped to the flanks that touch (ltca.cylindrical.cell_clip); a wide helical face gets shorter slices
(Fidelity.slice_length). Judging each cell by its centre alone makes these figures zig-zag."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fixtures.paths import CASES
from ltca.case import FIDELITIES, load_case
from ltca.cylindrical.cell_clip import gear_tip_on_pinion
from ltca.cylindrical.contact_cells import contact_strips
from ltca.cylindrical.edges import position_edges
from ltca.cylindrical.flank_lattice import line_lattice
from ltca.cylindrical.loaded import solve_position, te_arcsec
from ltca.cylindrical.loaded_model import Fidelity, LoadedModel
from ltca.cylindrical.model import build_model
from ltca.cylindrical.run import cycle_rolls
from ltca.cylindrical.tca import flank_gaps
from ltca.geometry.cylindrical import arc_length, flank_point_normal


@pytest.fixture(scope="module")
def helical_model():
    return build_model(load_case(CASES / "helical_c14.toml"))


def test_developed_lattice_is_isometric_and_follows_the_line(helical_model):
    """Cells are rectangles of the developed flank: plane distances are 3D distances on the flank, and the
    tooth's nominal contact line (y = 0) has zero unloaded gap over the whole face."""
    m = helical_model
    p1 = m.pinion
    s_lo = arc_length(m.pinion_range()[0], p1.r_base)
    roll = np.radians(-3.0)
    lat = line_lattice(p1, roll, float(np.tan(m.pair.alpha_w)), 0.04, 40 / 38, s_lo)
    x = lat.slice_x(np.linspace(-15.0, 15.0, 7))
    s, z = lat.to_flank(x, 0.0)
    g = flank_gaps(m, m.phi_pitch - roll, 0, s, z).gap
    assert np.abs(g).max() < 2e-6
    xs, ys = x[3] + np.array([0.0, 1.0, 0.0, 0.7]), np.array([0.0, 0.0, 0.5, -0.3])
    S, Z = lat.to_flank(xs, ys)
    P, _ = flank_point_normal(p1, +1, np.sqrt(p1.r_base ** 2 + 2 * p1.r_base * S), Z, 0)
    assert np.allclose(np.linalg.norm(P[1:] - P[0], axis=1), np.hypot(xs[1:] - xs[0], ys[1:] - ys[0]), atol=1e-4)
    x2, y2 = lat.to_plane(S, Z)
    assert np.allclose(x2, xs, atol=1e-9) and np.allclose(y2, ys, atol=1e-9)


def test_contact_line_length_changes_continuously_with_the_position(helical_model):
    """The cells on a tooth's line (lattice row 0) keep exactly the part of the line on both flanks (from the
    gear's tip edge to the pinion's tip circle, within the face), position by position: no cell drops in or out
    whole."""
    m = helical_model
    case = m.case
    fid = dataclasses.replace(Fidelity.from_preset(FIDELITIES["default"], case.module), slices=14)
    lm = LoadedModel(m, fid, (-1, 0, 1), (-1, 0, 1), None, None, 0.2, 8.0, case.torques[0])
    p1, b = m.pinion, m.face_width
    L_lo, L_hi = np.sqrt(2 * p1.r_base * gear_tip_on_pinion(m)), np.sqrt(p1.r_tip ** 2 - p1.r_base ** 2)
    tau = np.tan(p1.beta) / p1.r_ref * p1.r_base
    u_w = np.tan(m.pair.alpha_w)
    lengths, exact = [], []
    for roll in np.radians(np.linspace(-4.0, -2.0, 41)):
        strips, dz, ds, lattice = contact_strips(lm, m.phi_pitch - roll, 0.0, {}, case.torques[0])
        on_line = [(st.frac * lattice[st.tooth].length)[st.lattice == 0].sum() for st in strips if st.tooth == 1]
        lengths.append(sum(on_line))
        # the nominal line of tooth 1: L(z) = r_b (u_w + roll + pitch) - tau z, on the flanks for L_lo <= L <= L_hi
        z_a, z_b = sorted(((p1.r_base * (u_w + roll + m.pitch_angle) - L) / tau for L in (L_lo, L_hi)))
        exact.append(max(0.0, min(z_b, b / 2) - max(z_a, -b / 2)) / np.cos(p1.beta_b))
    lengths, exact = np.array(lengths), np.array(exact)
    assert np.abs(lengths - exact).max() < 0.01 * lattice[1].length
    assert np.abs(np.diff(lengths)).max() < 0.2 * lattice[1].length       # 0.05 deg steps: 0.1 mm of line


def _cycle(lm, n):
    T = lm.model.case.torques[0]
    out, warm = [], None
    for roll in cycle_rolls(n, lm.model.case.pinion.teeth):
        warm = solve_position(lm, roll, T, warm=warm)
        out.append(warm)
    te = np.array([float(te_arcsec(lm, r.theta)) for r in out])
    flank = np.array([position_edges(lm, r, T)["flank_peak"] for r in out])
    loads = np.array([[r.pair_load.get(k, 0.0) for k in lm.teeth1] for r in out])
    return te, flank, loads


def _away_from_engagement(loads, half):
    """Positions farther than ``half`` from one where a pair starts or stops carrying load (the TE of a pair has
    a kink there: the engaging tooth takes load at its edge); as a mask over the second differences."""
    on = loads > 1e-3 * loads.sum(axis=1, keepdims=True)
    near = np.zeros(len(loads), bool)
    for e in np.flatnonzero((on[1:] != on[:-1]).any(axis=1)) + 1:
        near[max(0, e - half):e + half] = True
    return ~near[1:-1]


@pytest.mark.slow
def test_helical_c14_te_has_no_zig_zag(helical_lm):
    """Helical C14 as shipped (sharp tips) at 60 positions, default fidelity: the second difference of the TE
    has a median below 2 % of the TE ptp, stays below 5 % away from the engagement kinks (where the engaging
    tooth's gear tip edge takes load: a kink of the pair's TE, not sampling) and is not anti-correlated from one
    position to the next (no zig-zag)."""
    assert helical_lm.fid.slices == 38
    te, _, loads = _cycle(helical_lm, 60)
    d2 = np.diff(te, 2) / np.ptp(te)
    away = _away_from_engagement(loads, 5)
    print(f"TE ptp {np.ptp(te):.3f} arcsec; |d2| / ptp: median {100 * np.median(np.abs(d2)):.2f} %, away from "
          f"engagement {100 * np.abs(d2[away]).max():.2f} %, overall {100 * np.abs(d2).max():.1f} %; lag-1 "
          f"correlation of d2 {np.corrcoef(d2[:-1], d2[1:])[0, 1]:+.2f}")
    assert np.median(np.abs(d2)) < 0.02
    assert np.abs(d2[away]).max() < 0.05
    assert np.corrcoef(d2[:-1], d2[1:])[0, 1] > 0.0


@pytest.mark.slow
def test_smooth_helical_pair_gives_smooth_te_and_flank_pressure(helical_lm):
    """Helical C14 with a parabolic tip relief (15 um) and lead crowning (10 um) on both members (gaps only:
    the same bodies): no edge contact, so its loaded TE and flank peak pressure are smooth functions of the
    position. 60 positions: |d2 TE| < 2 % of its ptp away from the two engagement kinks (5.7 % at them),
    |d2 flank peak| < 2 % of its mean everywhere."""
    case = helical_lm.model.case
    mods = dict(tip_relief=0.015, tip_relief_exponent=2.0, lead_crowning=0.010)
    case = dataclasses.replace(
        case, pinion=dataclasses.replace(case.pinion, modifications=dataclasses.replace(case.pinion.modifications, **mods)),
        gear=dataclasses.replace(case.gear, modifications=dataclasses.replace(case.gear.modifications, **mods)))
    lm = dataclasses.replace(helical_lm, model=build_model(case))
    te, flank, loads = _cycle(lm, 60)
    d2 = np.diff(te, 2) / np.ptp(te)
    away = _away_from_engagement(loads, 2)
    f2 = np.diff(flank, 2) / flank.mean()
    print(f"TE ptp {np.ptp(te):.3f} arcsec, |d2| / ptp away from engagement {100 * np.abs(d2[away]).max():.2f} %, "
          f"overall {100 * np.abs(d2).max():.2f} %; flank peak {flank.min():.0f} .. {flank.max():.0f} MPa, "
          f"|d2| / mean {100 * np.abs(f2).max():.2f} %")
    assert np.abs(d2[away]).max() < 0.02
    assert np.abs(f2).max() < 0.02
