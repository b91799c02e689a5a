"""Bevel bodies held at their mounting in service: the pinion's shaft seat, the gear's back face.

The blank of each FE body runs from the root cone down to the case's ``[mounting]``; the support facets lie on
that cylinder and that plane (geometry, exact to rounding) and the case keys are range-checked against the blank.
What the mounting does to the answer is guarded by the frozen CalculiX reference (whole members on the same seat
and back face, ``tests/ltca/verify/test_reference_calculix_bevel.py``): loaded TE within 3 % at the two-pair position
(a blank cut 1.2 whole depths under the root cone instead reads it 9.5 % low).
"""

import numpy as np
import pytest

from fixtures.paths import BEVEL_CASE
from ltca.bevel.analysis import build_pair
from ltca.bevel.case import load_bevel_case
from ltca.bevel.loaded_model import member_flanks
from ltca.bevel.model import BevelMounting
from ltca.cli import main
from ltca.fem.solids.bevel_body import BevelBodySpec, build_bevel_body

CASE = BEVEL_CASE


@pytest.fixture(scope="module")
def pair(bevel_pair):
    """The shipped pair (the session's :func:`fixtures.bevel.bevel_pair`)."""
    return bevel_pair


def _body(pair, member: str, support):
    fl, off, shift = member_flanks(pair, member)
    spec = BevelBodySpec(fl["concave"], fl["convex"], pair.blank.member(member).z, off, shift, support=support,
                         divisions=(10, 5, 4, 3, 2, 12))
    return build_bevel_body(spec)


def _support_nodes(mesh) -> np.ndarray:
    """The support facets' corner nodes (the mid-edge nodes of the straight-sided tri6 lie on chords)."""
    return mesh.nodes[np.unique(mesh.facets["bore"][:, :3].ravel())]


def test_case_mounting_is_read_and_defaults_follow_the_blank(pair):
    case = load_bevel_case(CASE)
    sup = case.mounting.supports(pair.blank)
    assert sup == {"pinion": ("seat", 9.0), "gear": ("face", 48.07)}
    # defaults: 0.45 x the toe's root diameter (9.0 mm here), 1.2 whole depths behind the heel root along the back
    # cone (48.07 mm here): the shipped values are the defaults of this pair, to rounding
    d = BevelMounting().supports(pair.blank)
    assert d["pinion"][1] == pytest.approx(0.45 * pair.blank.root_point("pinion", "toe")[1], rel=1e-12)
    assert d["pinion"][1] == pytest.approx(9.0, abs=0.01) and d["gear"][1] == pytest.approx(48.07, abs=0.01)


@pytest.mark.parametrize("member,support", [("pinion", ("seat", 9.0)), ("pinion", ("seat", 14.0)),
                                            ("gear", ("face", 48.07)), ("gear", ("face", 60.0))])
def test_body_support_lies_on_the_mounting(pair, member, support):
    mesh = _body(pair, member, support)
    X = _support_nodes(mesh)
    kind, value = support
    coord = np.hypot(X[:, 0], X[:, 1]) if kind == "seat" else X[:, 2]
    assert np.allclose(coord, value, atol=1e-9 * max(1.0, value))
    # every other node lies on the member's side of the support (inside the seat's cylinder's outside, in front of
    # the back face), so the blank fills the space between the root cone and the mounting
    V = mesh.nodes[np.unique(mesh.tets[:, :4].ravel())]
    allc = np.hypot(V[:, 0], V[:, 1]) if kind == "seat" else V[:, 2]
    assert (allc >= value - 1e-9).all() if kind == "seat" else (allc <= value + 1e-9).all()
    # a deeper blank has more rows: the element volume stays positive and the blank reaches the support
    toe = pair.blank.root_point(member, "toe")
    assert (toe[1] - value if kind == "seat" else value - toe[0]) > 0


def test_support_beyond_the_blank_is_refused(pair):
    fl, off, shift = member_flanks(pair, "pinion")
    with pytest.raises(ValueError, match="support"):
        build_bevel_body(BevelBodySpec(fl["concave"], fl["convex"], 12, off, shift, support=("seat", 25.0)))


@pytest.mark.parametrize("text,field", [
    ("pinion_seat_diameter_mm = 39.0", "mounting.pinion_seat_diameter_mm"),
    ("gear_mounting_distance_mm = 30.0", "mounting.gear_mounting_distance_mm"),
    ("pinion_seat_diameter_mm = -3.0", "mounting.pinion_seat_diameter_mm"),
])
def test_bad_mounting_exits_2_naming_the_field(tmp_path, capsys, text, field):
    src = CASE.read_text()
    key = text.split(" =")[0]
    lines = [ln for ln in src.splitlines() if not ln.startswith(key)]
    out = "\n".join(lines).replace("[mounting]", "[mounting]\n" + text)
    p = tmp_path / "bad.toml"
    p.write_text(out)
    assert main(["tca", str(p), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert field in err


def test_body_flank_grid_of_a_synthesised_optimum_generates(tmp_path):
    """A pinion synthesised for (eta2 20.8 deg, m21 25.5 arcsec), the optimum of ``ltca optimise
    cases/spiral_bevel_optimise.toml``: the body's coarse 9 x 13 flank grid once failed to solve the equation of
    meshing on its lowest row (a row step too coarse for Newton near the fillet); the march now continues in
    sub-steps, and the flank nodes meet the equation of meshing."""
    src = CASE.read_text().replace("path_angle_deg = 22.0", "path_angle_deg = 20.8").replace(
        "te_magnitude_arcsec = 8.25", "te_magnitude_arcsec = 25.5")
    p = tmp_path / "optimum.toml"
    p.write_text(src)
    fl, off, shift = member_flanks(build_pair(load_bevel_case(p)), "pinion")
    for f in fl.values():
        assert np.isfinite(f.points).all() and f.points.shape[:2] == (9, 13)
        assert float(np.max(f.meta["meshing_residual"])) < 1e-6
