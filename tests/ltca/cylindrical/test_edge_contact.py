"""Flank pressure and edge contact kept apart: the flank peak of FZG C14 against local Hertz, the
tip-edge contacts flagged where they happen, and a rounded tip edge whose pressure converges with the cells
(against the Hertz pressure of the rounding), where a sharp edge's does not."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fixtures.cylindrical import with_case
from ltca.cylindrical.edges import EDGES, classify, edge_summary, position_edges
from ltca.cylindrical.loaded import solve_position
from ltca.cylindrical.loaded_model import hertz_line
from ltca.cylindrical.run import analyse, cycle_rolls
from ltca.geometry.cylindrical import radius_of_arc


@pytest.fixture(scope="module")
def fzg_cycle(fzg_lm, fzg_case):
    """FZG C14 (unmodified, sharp tips) at 30 positions, and its flank / edge summary."""
    T = fzg_case.torques[0]
    results = analyse(fzg_lm, cycle_rolls(30, 16), T)
    return results, edge_summary(fzg_lm, results, T)


def _local_hertz(lm, res, cells, rho2_of):
    """Hertz peak for the line load of ``cells`` (one tooth, one slice) and the curvature at their pressure
    centre: rho1 of the pinion flank (rounding ``rho2_of`` returns the counter radius)."""
    dz = lm.model.face_width / lm.fid.slices
    w = res.force[cells].sum() / dz
    s0 = np.sum(res.s[cells] * res.pressure[cells]) / res.pressure[cells].sum()
    r1, r2 = rho2_of(s0)
    _, p0 = hertz_line(w, 1.0 / (1.0 / r1 + 1.0 / r2), lm.model.case.young, lm.model.case.poisson)
    return p0


def test_flank_peak_is_local_hertz_in_the_single_contact_zone(fzg_lm, fzg_cycle):
    results, head = fzg_cycle
    at = head["max_flank_pressure_at"]
    assert at["pairs_in_contact"] == 1                              # the single-contact zone
    res = next(r for r in results if np.isclose(np.degrees(r.roll), at["roll_deg"]))
    e = position_edges(fzg_lm, res, fzg_lm.model.case.torques[0])
    i = e["flank_index"]
    cells = (res.tooth == res.tooth[i]) & (res.slice == res.slice[i])
    pair = fzg_lm.model.pair
    T_len = pair.a * np.sin(pair.alpha_w)
    rho1 = lambda s0: (np.sqrt(2 * fzg_lm.model.pinion.r_base * s0), T_len - np.sqrt(2 * fzg_lm.model.pinion.r_base * s0))
    p_hertz = _local_hertz(fzg_lm, res, cells, rho1)
    print(f"flank peak {head['max_flank_pressure_mpa']:.1f} MPa at roll {at['roll_deg']:+.2f} deg, d1 "
          f"{at['pinion_diameter_mm']:.2f} mm, z {at['z_mm']:+.2f} mm; local Hertz {p_hertz:.1f} MPa; largest cell "
          f"{max(r.max_pressure for r in results):.0f} MPa")
    # within 3 % (it is within 1 %), so a 5 % move of the reported peak fails
    assert head["max_flank_pressure_mpa"] == pytest.approx(p_hertz, rel=0.03)
    assert abs(head["max_flank_pressure_mpa"] / p_hertz - 1) < 0.015
    # the place: on the pinion's flank below the pitch circle, inside the face, where that cell is
    assert at["pinion_diameter_mm"] == pytest.approx(2 * radius_of_arc(res.s[i], fzg_lm.model.pinion.r_base), abs=1e-3)
    assert 2 * fzg_lm.model.pinion.r_form_right < at["pinion_diameter_mm"] < 2 * fzg_lm.model.pair.r_w1
    assert abs(at["z_mm"]) < 0.5 * fzg_lm.model.face_width
    # the corner spike of the unmodified tips is not the flank pressure
    assert max(r.max_pressure for r in results) > 2 * head["max_flank_pressure_mpa"]


def test_tip_edge_contacts_are_flagged_with_place_and_load(fzg_lm, fzg_cycle):
    _, head = fzg_cycle
    edges = {e["edge"]: e for e in head["edge_contact"]}
    p1, p2, pair = fzg_lm.model.pinion, fzg_lm.model.gear, fzg_lm.model.pair
    # the pinion's tip edge, at the end of its mesh (negative roll), on its tip diameter
    tip = edges["pinion tip edge"]
    assert tip["mesh_dependent"] and tip["modelled_as"] == "sharp"
    assert all(-7.0 < r < -4.5 for r in tip["roll_deg"]) and tip["positions"] >= 1
    assert tip["pinion_diameter_mm"][1] == pytest.approx(2 * p1.r_tip, abs=0.05)
    assert tip["max_load_n"] > 1000.0
    # the gear's tip edge, at the start of the pinion's mesh, near the pinion's start of active profile
    L1 = pair.a * np.sin(pair.alpha_w) - np.sqrt(p2.r_tip ** 2 - p2.r_base ** 2)
    d_sap = 2 * np.hypot(p1.r_base, L1)
    gear = edges["gear tip edge"]
    assert gear["mesh_dependent"]
    assert all(4.5 < r < 7.0 for r in gear["roll_deg"])
    assert gear["pinion_diameter_mm"][0] - 0.5 < d_sap < gear["pinion_diameter_mm"][1] + 0.5
    assert gear["gear_diameter_mm"][1] == pytest.approx(2 * p2.r_tip, abs=0.05)
    assert gear["max_load_n"] > 1000.0
    # their spikes are the max cell pressure, stated as mesh-dependent
    assert max(tip["max_pressure_mpa"], gear["max_pressure_mpa"]) > 2 * head["max_flank_pressure_mpa"]
    assert "mesh-dependent" in head["edge_note"] and "pinion tip edge" in head["edge_note"]


def _edge_peak(lm, roll_deg, kind):
    """Largest cell pressure of an edge zone in contact, mid-face slice (N, MPa), and the result."""
    T = lm.model.case.torques[0]
    res = solve_position(lm, np.radians(roll_deg), T)
    zone, _ = classify(lm, res, T)
    assert position_edges(lm, res, T)["loaded"][kind]
    mid = (zone == kind) & (res.slice == lm.fid.slices // 2)
    return float(res.pressure[mid].max()), res, mid


@pytest.mark.parametrize("roll_deg, kind", [(-6.0, 0), (6.75, 1)])
def test_rounded_tip_edge_pressure_converges_to_hertz_of_the_rounding(fzg_lm, roll_deg, kind):
    """0.5 mm rounding on both members (gaps only: same bodies). The spur edge is uniform along the face, so
    four slices serve; the cells across refine twice (cells_per_b 20 -> 40, 10 and 5 um)."""
    rounded = with_case(fzg_lm, pinion=_rounded(fzg_lm.model.case.pinion), gear=_rounded(fzg_lm.model.case.gear))
    peaks = []
    for cpb in (20.0, 40.0):
        lm = dataclasses.replace(rounded, fid=dataclasses.replace(rounded.fid, cells_per_b=cpb, slices=4))
        p, res, mid = _edge_peak(lm, roll_deg, kind)
        peaks.append(p)
    # Hertz of a 0.5 mm cylinder against the counter flank, for the line load of the edge zone at mid-face
    model = rounded.model
    p1, pair = model.pinion, model.pair
    T_len = pair.a * np.sin(pair.alpha_w)
    if kind == 0:     # pinion rounding on the gear flank, where it meets the pinion's tip circle
        counter = lambda s0: (0.5, T_len - np.sqrt(p1.r_tip ** 2 - p1.r_base ** 2))
    else:             # gear rounding on the pinion flank near its start of active profile
        counter = lambda s0: (0.5, np.sqrt(2 * p1.r_base * s0))
    p_hertz = _local_hertz(lm, res, mid, counter)
    print(f"roll {roll_deg:+.2f}: {EDGES[kind]} rounded 0.5 mm: {peaks[0]:.0f} / {peaks[1]:.0f} MPa at 20 / 40 cells "
          f"per b, Hertz of the rounding {p_hertz:.0f} MPa")
    assert abs(peaks[1] / peaks[0] - 1) < 0.02      # converged with the cells (0.2 %)
    assert peaks[1] == pytest.approx(p_hertz, rel=0.03)              # and it is the rounding's Hertz pressure


def _rounded(member, radius=0.5):
    return dataclasses.replace(member, modifications=dataclasses.replace(member.modifications, tip_edge_radius=radius))


def test_sharp_tip_edge_pressure_grows_with_the_cells(fzg_lm):
    """The same edge modelled sharp: its peak grows like 1/sqrt(cell size), so it is reported as mesh-dependent."""
    peaks = []
    for cpb in (10.0, 20.0):
        lm = dataclasses.replace(fzg_lm, fid=dataclasses.replace(fzg_lm.fid, cells_per_b=cpb, slices=4))
        peaks.append(_edge_peak(lm, -6.0, 0)[0])
    print(f"sharp pinion tip edge: {peaks[0]:.0f} / {peaks[1]:.0f} MPa at 10 / 20 cells per b")
    assert peaks[1] > 1.25 * peaks[0]
