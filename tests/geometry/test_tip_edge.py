"""Tip-edge rounding and chamfer (geometry.tip_edge): tangency, the outline, the material removed from the flank,
internal gears, and the case keys with their errors."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import cKDTree

from fixtures.paths import CASES
from ltca.case import parse_case, read_toml
from ltca.cylindrical.model import build_model
from ltca.errors import CaseError
from ltca.geometry.tip_edge import tip_edge_depth, with_tip_edge


@pytest.fixture(scope="module")
def profiles():
    fzg = build_model(parse_case(read_toml(CASES / "fzg_c14.toml")))
    ring = build_model(parse_case(read_toml(CASES / "internal_spur.toml")))
    return {"pinion": fzg.pinion, "gear": fzg.gear, "ring": ring.gear}


@pytest.mark.parametrize("name", ["pinion", "gear", "ring"])
def test_rounding_is_tangent_to_flank_and_tip_circle(profiles, name):
    prof = profiles[name]
    q = with_tip_edge(prof, radius=0.5)
    e = q.tip_edge
    c, start, end = map(np.asarray, (e.centre, e.start, e.end))
    assert np.hypot(*end) == pytest.approx(prof.r_tip, abs=1e-9)                 # on the tip circle ...
    assert np.hypot(*(end - c)) == pytest.approx(0.5, abs=1e-9)
    assert np.hypot(*c) == pytest.approx(prof.r_tip + (0.5 if prof.internal else -0.5), abs=1e-9)   # ... tangent
    assert np.hypot(*(start - c)) == pytest.approx(0.5, abs=1e-9)                # on the involute ...
    t = prof.flank_xy(e.r_start + 1e-6, +1) - prof.flank_xy(e.r_start - 1e-6, +1)
    assert abs((start - c) @ t) / np.hypot(*t) < 1e-6 * 0.5                      # ... tangent to it
    assert (e.r_start < prof.r_tip) != prof.internal
    # the outline is closed, symmetric and carries the arc; the flank loses depth = distance to the outline
    xy = q.xy
    assert np.abs(xy[::-1] * [-1, 1] - xy).max() < 1e-9
    r = np.linspace(e.r_start, prof.r_tip, 6)
    depth = tip_edge_depth(q, r)
    assert depth[0] == 0.0 and np.all(np.diff(depth) > 0)
    assert np.allclose(depth, cKDTree(xy).query(prof.flank_xy(r, +1))[0], atol=1e-4)
    # smooth start: the depth grows quadratically from the point of tangency (s^2 / (2 rho) to leading order)
    rb = prof.r_base
    ds = (r[1] ** 2 - e.r_start ** 2) / (2 * rb)
    assert depth[1] == pytest.approx(ds ** 2 / (2 * 0.5), rel=0.2)


def test_chamfer_cuts_the_corner_with_a_straight_leg(profiles):
    prof = profiles["pinion"]
    q = with_tip_edge(prof, chamfer=0.3)
    e = q.tip_edge
    rb = prof.r_base
    s = lambda rr: (rr ** 2 - rb ** 2) / (2 * rb)
    assert s(prof.r_tip) - s(e.r_start) == pytest.approx(0.3, abs=1e-9)         # leg along the involute
    corner = prof.flank_xy(prof.r_tip, +1)
    ang = lambda p: np.arctan2(p[0], p[1])
    assert prof.r_tip * (ang(corner) - ang(np.asarray(e.end))) == pytest.approx(0.3, abs=1e-9)   # and the tip
    r = np.linspace(e.r_start, prof.r_tip, 5)
    assert np.allclose(tip_edge_depth(q, r), cKDTree(q.xy).query(prof.flank_xy(r, +1))[0], atol=1e-4)


def _case(**mods):
    data = read_toml(CASES / "fzg_c14.toml")
    data["pinion"]["modifications"] = mods
    return parse_case(data)


def test_case_keys_build_the_edge_and_bad_values_name_the_field():
    model = build_model(_case(tip_edge_radius_mm=0.5))
    assert model.pinion.tip_edge.kind == "radius" and model.gear.tip_edge is None
    assert build_model(_case(tip_chamfer_mm=0.2)).pinion.tip_edge.kind == "chamfer"
    with pytest.raises(CaseError) as err:
        build_model(_case(tip_edge_radius_mm=5.0))
    assert err.value.field == "pinion.modifications.tip_edge_radius_mm" and "(0, 2.4" in err.value.allowed
    with pytest.raises(CaseError) as err:
        _case(tip_edge_radius_mm=0.5, tip_chamfer_mm=0.2)
    assert err.value.field == "pinion.modifications.tip_chamfer_mm"
    with pytest.raises(CaseError) as err:
        _case(tip_edge_radius_mm=-1.0)
    assert err.value.field == "pinion.modifications.tip_edge_radius_mm" and "[0, 50]" in err.value.allowed
