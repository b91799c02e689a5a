"""The independent bevel solid of the CalculiX check (fem.solids.bevel_occ): which side of a flank the tooth is on.

The generated flanks' normals point out of the material (:func:`ltca.geometry.bevel.sampling.flank_at`); the tooth
lies against the anchor flank's normal, and its other flank is turned there by the tooth's angular thickness,
not wrapped to a pitch (that would build the tooth space instead of the tooth).
"""
from __future__ import annotations

import numpy as np
import pytest

pytestmark = pytest.mark.heavy       # whole-gear solids of the CalculiX cross-check (maintainer tooling)


@pytest.mark.parametrize("member,anchor", [("pinion", "concave"), ("gear", "convex")])
def test_tooth_lies_against_the_anchor_normal(bevel_pair, member, anchor):
    from ltca.fem.solids.bevel_occ import BevelSolidSpec, _shift, polar
    from ltca.geometry.bevel.generation import generate_flank
    from ltca.geometry.bevel.sampling import flank_at
    pair = bevel_pair
    bl = pair.blank
    mb, cut = bl.member(member), (pair.pinion if member == "pinion" else pair.gear)
    fl = {s: generate_flank(cut.flank(s), bl, member, 9, 7, 0.03 * bl.data.module) for s in ("concave", "convex")}
    thick = mb.mean_normal_thickness / (np.cos(bl.data.spiral_angle) * mb.mean_pitch_radius)
    spec = BevelSolidSpec(fl["concave"], fl["convex"], mb.z, mb.pitch_angle, 0.03 * bl.data.module, anchor, thick,
                          0.5, bl.mean_cone_distance, np.zeros((3, 2)), {}, np.zeros((1, 3)), 1.0, 5.0)
    other = "convex" if anchor == "concave" else "concave"
    pa, na, _ = flank_at(fl[anchor], np.array([0.5]), np.array([bl.mean_cone_distance]))
    po, _, _ = flank_at(fl[other], np.array([0.5]), np.array([bl.mean_cone_distance]))
    e_theta = np.array([-pa[0, 1], pa[0, 0], 0.0]) / np.hypot(pa[0, 0], pa[0, 1])
    step = polar(po[0]) + _shift(spec) - polar(pa[0])
    assert step * np.sign(na[0] @ e_theta) == pytest.approx(-thick, abs=1e-9)
