"""Blank design of spiral bevel gears: cone identities and Gleason depth relations."""
import numpy as np
import pytest

from ltca.geometry.bevel.blank import BevelBasicData, design_blank


@pytest.mark.parametrize("z1,z2,sigma", [(10, 41, 90.0), (15, 30, 90.0), (17, 23, 75.0), (12, 40, 110.0)])
def test_pitch_cone_identities(z1, z2, sigma):
    S = np.deg2rad(sigma)
    bl = design_blank(BevelBasicData(z1=z1, z2=z2, module=5.0, face_width=25.0, shaft_angle=S))
    g1, g2 = bl.pinion.pitch_angle, bl.gear.pitch_angle
    assert g1 + g2 == pytest.approx(S, abs=1e-14)
    assert np.tan(g1) == pytest.approx(np.sin(S) / (z2 / z1 + np.cos(S)), rel=1e-13)
    # both pitch cones have the same outer cone distance (common apex, rolling cones)
    assert bl.pinion.pitch_diameter / (2 * np.sin(g1)) == pytest.approx(bl.outer_cone_distance, rel=1e-13)
    assert bl.gear.pitch_diameter / (2 * np.sin(g2)) == pytest.approx(bl.outer_cone_distance, rel=1e-13)
    assert np.sin(g1) / np.sin(g2) == pytest.approx(z1 / z2, rel=1e-13)


def test_depths_and_diameters():
    bl = design_blank(BevelBasicData(z1=10, z2=41, module=6.0, face_width=40.0))
    m = 6.0
    p, g = bl.pinion, bl.gear
    assert p.addendum + g.addendum == pytest.approx(1.700 * m)       # working depth
    assert p.addendum + p.dedendum == pytest.approx(1.888 * m)       # whole depth
    assert g.addendum + g.dedendum == pytest.approx(1.888 * m)
    assert bl.clearance == pytest.approx(0.188 * m)
    m90 = np.sqrt(41 / 10 * np.cos(p.pitch_angle) / np.cos(g.pitch_angle))
    assert m90 == pytest.approx(41 / 10, rel=1e-12)                  # 90-degree pair: m90 = ratio
    assert g.addendum == pytest.approx(0.46 * m + 0.39 * m / m90 ** 2)
    for mb in (p, g):
        # outside diameter: heel point of the face cone, d + 2 a cos(gamma)
        assert mb.outside_diameter == pytest.approx(mb.pitch_diameter + 2 * mb.addendum * np.cos(mb.pitch_angle))
        # crown point lies on the face cone at (x0, do/2) seen from the apex of the pitch cone
        x0, r0 = mb.crown_to_apex, mb.outside_diameter / 2
        assert np.hypot(x0, r0) ** 2 == pytest.approx(bl.outer_cone_distance ** 2 + mb.addendum ** 2)
        assert mb.root_angle == pytest.approx(mb.pitch_angle - np.arctan(mb.dedendum / bl.outer_cone_distance))
    # constant clearance: each face angle follows the mate's root angle
    assert p.face_angle - p.pitch_angle == pytest.approx(g.dedendum_angle)
    assert g.face_angle - g.pitch_angle == pytest.approx(p.dedendum_angle)
    # mean thickness: pinion + gear = mean normal circular pitch (no backlash)
    assert p.mean_normal_thickness + g.mean_normal_thickness == pytest.approx(bl.mean_normal_pitch)
    assert p.mean_normal_thickness > g.mean_normal_thickness          # long-addendum pinion is thicker
    assert bl.mean_cone_distance == pytest.approx(bl.outer_cone_distance - 20.0)


def test_uniform_depth():
    bl = design_blank(BevelBasicData(taper="uniform"))
    for mb in (bl.pinion, bl.gear):
        assert mb.root_angle == mb.pitch_angle == mb.face_angle
        assert mb.mean_addendum == pytest.approx(mb.addendum)


@pytest.mark.parametrize("kw,name", [({"z1": 3}, "z1"), ({"module": -1.0}, "module"),
                                      ({"hand": "up"}, "hand"), ({"face_width": 500.0}, "face_width"),
                                      ({"pressure_angle": 0.7}, "pressure_angle"),
                                      ({"cutter_radius": 1.0}, "cutter_radius")])
def test_bad_input_names_parameter(kw, name):
    with pytest.raises(ValueError, match=name):
        design_blank(BevelBasicData(**kw))
