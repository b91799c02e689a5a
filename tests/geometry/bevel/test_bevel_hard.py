"""Hard cases of spiral bevel generation: undercut of a 9-tooth pinion, and settings for which the equation
of meshing has no solution over part of the flank (the error names the grid region)."""
import re

import numpy as np
import pytest

from ltca.geometry.bevel.blank import BevelBasicData, design_blank
from ltca.geometry.bevel.generation import generate_flank
from ltca.geometry.bevel.machine import gear_settings, pinion_settings
from ltca.geometry.bevel.undercut import undercut_check


def _blank(z1, pa, sp):
    return design_blank(BevelBasicData(z1=z1, z2=40, pressure_angle=np.deg2rad(pa), spiral_angle=np.deg2rad(sp)))


@pytest.mark.parametrize("side", ["concave", "convex"])
def test_nine_tooth_pinion_undercut_is_detected_and_reported(side):
    """9 teeth, 14 deg pressure angle, 30 deg spiral: the limit line of the generated pinion surface lies inside
    the blank (measured 2.5-2.6 mm above the root cone, along the whole face); the report names the region."""
    bl = _blank(9, 14.0, 30.0)
    rep = undercut_check(pinion_settings(bl).flank(side), bl, "pinion")
    assert rep.undercut and rep.member == "pinion" and rep.side == side
    assert 1.0 < rep.height_mm < bl.pinion.addendum + bl.pinion.dedendum
    m = re.search(r"undercut on the (\w+) flank of the pinion.*L = \[([\d.]+), ([\d.]+)\] mm, Rn = \[([-\d.]+), "
                  r"([-\d.]+)\] mm", rep.message)
    assert m and m.group(1) == side
    L0, L1 = float(m.group(2)), float(m.group(3))
    assert bl.inner_cone_distance <= L0 < L1 <= bl.outer_cone_distance
    assert np.all(rep.Rn < 0.0)                         # below the pitch cone, in the dedendum
    # the same pinion with a 20 deg pressure angle, and the gear, are free of undercut
    bl20 = _blank(9, 20.0, 35.0)
    for s in ("concave", "convex"):
        assert not undercut_check(pinion_settings(bl20).flank(s), bl20, "pinion").undercut
    assert not undercut_check(gear_settings(bl).convex, bl, "gear").undercut


def test_coarse_march_steps_still_generate_the_whole_flank():
    """9 teeth, 16 deg: the node-by-node march over the convex pinion flank's lower part needs sub-steps (a
    single step there finds no solution of the equation of meshing); continued in sub-steps, every node meets
    the equation of meshing (residual < 1e-9 mm) and the flank has no undercut.  A cutter with no solution over
    part of the blank still raises the error naming the region
    (``test_bevel_generation.py::test_no_solution_names_region``)."""
    bl = _blank(9, 16.0, 35.0)
    fc = pinion_settings(bl).convex
    f = generate_flank(fc, bl, "pinion", nu=20, nv=30)
    assert np.isfinite(f.points).all()
    assert float(np.max(f.meta["meshing_residual"])) < 1e-9
    assert not f.meta["undercut"].any() and not undercut_check(fc, bl, "pinion").undercut
    # the same flank on a coarser grid (the row step the march continues in sub-steps) lies on the fine one
    g = generate_flank(fc, bl, "pinion", nu=5, nv=30)
    assert np.allclose(g.points[-1], f.points[-1], atol=1e-6) and np.allclose(g.points[0], f.points[0], atol=1e-6)


def test_bad_sampling():
    bl = _blank(9, 20.0, 35.0)
    with pytest.raises(ValueError, match="n = 5"):
        undercut_check(pinion_settings(bl).convex, bl, "pinion", n=5)
