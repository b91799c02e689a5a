"""Hard cases of spiral bevel generation: undercut of a 9-tooth pinion, and settings for which the equation
of meshing has no solution over part of the flank (the error names the grid region)."""
import re

import numpy as np
import pytest

from geometry.bevel.blank import BevelBasicData, design_blank
from geometry.bevel.generation import MeshingError, generate_flank
from geometry.bevel.machine import gear_settings, pinion_settings
from geometry.bevel.undercut import undercut_check


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


def test_no_solution_of_meshing_names_the_grid_region():
    """9 teeth, 16 deg: the convex pinion flank has no generated point in its lower part; the MeshingError
    says which flank and gives the region in the axial section (cone distance L and height Rn)."""
    bl = _blank(9, 16.0, 35.0)
    with pytest.raises(MeshingError) as exc:
        generate_flank(pinion_settings(bl).convex, bl, "pinion", nu=20, nv=30)
    msg = str(exc.value)
    m = re.search(r"convex flank for (\d+) grid node\(s\) in the axial-section region L = \[([\d.]+), ([\d.]+)\] mm, "
                  r"Rn = \[([-\d.]+), ([-\d.]+)\] mm", msg)
    assert m, msg
    n, Rn0, Rn1 = int(m.group(1)), float(m.group(4)), float(m.group(5))
    assert 0 < n < 600                                   # a region, not the whole flank
    mb = bl.pinion
    assert -mb.dedendum <= Rn0 < Rn1 <= mb.addendum


def test_bad_sampling():
    bl = _blank(9, 20.0, 35.0)
    with pytest.raises(ValueError, match="n = 5"):
        undercut_check(pinion_settings(bl).convex, bl, "pinion", n=5)
