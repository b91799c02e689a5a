"""The whole-gear body (fem.solids.gear_body): geometry identities, supports, what may be left out, physics.

Identities: the mesh volume equals the section area times the face width (webbed: each region times its
own width); corner nodes of a helical flank lie on the generated helicoid. What may be left out: the far
teeth change the flank compliance by well under 1 % (measured here; the design rule of docs/design.md).
Physics (slow): a rigid shaft seat nearer the root stiffens the mesh (less disc torsion, a stiffer
foundation); a web narrower than the face softens it by about ISO 6336-1's rim factor C_R.
"""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fixtures.paths import CASES


def _polygon_area(xy: np.ndarray) -> float:
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def _volume(mesh) -> float:
    v = mesh.nodes[mesh.tets[:, :4]]
    return float(np.sum(np.abs(np.einsum("ij,ij->i", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]),
                                         v[:, 3] - v[:, 0]))) / 6)


def _spec(profile, r_support, b, **kw):
    from ltca.fem.solids import GearBodySpec
    return GearBodySpec(np.asarray(profile.xy), np.asarray(profile.kind, np.int8), np.asarray(profile.side, np.int8),
                        profile.z, (-1, 0, 1), r_support, b, float(np.tan(profile.beta) / profile.r_ref),
                        profile.internal, **kw)


def _section_area(profile, far_teeth: str) -> float:
    """Area inside the toothed boundary: every tooth's outline, or three teeth closed by the root circle."""
    from ltca.fem.solids.planar import rot2
    xy = np.asarray(profile.xy)
    pitch = 2 * np.pi / profile.z
    if far_teeth == "full":
        return _polygon_area(np.concatenate([rot2(xy[:-1], -k * pitch) for k in range(profile.z)]))
    chain = np.concatenate([rot2(xy[:-1], -k * pitch) for k in (-1, 0, 1)] + [rot2(xy[-1:], -pitch)])
    r0 = np.linalg.norm(chain[-1])
    a0, a1 = np.arctan2(*chain[-1][::-1]), np.arctan2(*chain[0][::-1])
    t = a0 - np.linspace(0, (a0 - a1) % (2 * np.pi), 2000)
    return _polygon_area(np.concatenate([chain, r0 * np.c_[np.cos(t), np.sin(t)]]))


@pytest.mark.parametrize("far_teeth", ["none", "full"])
def test_volume_is_section_area_times_face_width(fzg_model, far_teeth):
    from ltca.fem.solids import build_gear_body
    p = fzg_model.pinion
    r_bore, b = 15.0, 14.0
    mesh = build_gear_body(_spec(p, r_bore, b, far_teeth=far_teeth, h_flank=2.0, h_body=6.0))
    exact = (_section_area(p, far_teeth) - np.pi * r_bore ** 2) * b
    assert _volume(mesh) == pytest.approx(exact, rel=2e-3)      # straight edges on curved outlines: O(h^2)
    assert "bore" in mesh.facets and "cut" not in mesh.facets
    assert all(f"flank_{k}_{s}" in mesh.facets for k in (-1, 0, 1) for s in ("left", "right"))
    assert ("far_teeth" in mesh.facets) == (far_teeth == "full")


def test_webbed_body_volume_counts_each_region_at_its_width(fzg_model):
    from ltca.fem.solids import build_gear_body
    p = fzg_model.pinion
    b, r_bore, r_rim, r_hub, bs, off = 14.0, 10.0, p.r_root - 9.0, 15.0, 4.0, 2.0
    mesh = build_gear_body(_spec(p, r_bore, b, rim=(r_rim, r_hub, bs, off), h_flank=2.0, h_body=6.0))
    exact = ((_section_area(p, "none") - np.pi * r_rim ** 2) * b + np.pi * (r_rim ** 2 - r_hub ** 2) * bs
             + np.pi * (r_hub ** 2 - r_bore ** 2) * b)
    assert _volume(mesh) == pytest.approx(exact, rel=2e-3)
    z = mesh.nodes[np.unique(mesh.facets["body_faces"]), 2]
    assert {-b / 2 + 0.0, off - bs / 2, off + bs / 2} <= set(np.round(z, 9)) | {-b / 2}
    assert np.isclose(z, off - bs / 2).any() and np.isclose(z, off + bs / 2).any()


def test_helical_flank_nodes_lie_on_the_generated_helicoid():
    """Corner nodes of a flank facet, turned back by the lead twist, land on the transverse outline (< 1 um)."""
    from ltca.case import load_case
    from ltca.cylindrical.model import build_model
    from ltca.fem.solids import build_gear_body
    from ltca.fem.solids.planar import rot2
    p = build_model(load_case(CASES / "helical_c14.toml")).pinion
    spec = _spec(p, 20.0, 40.0, h_flank=2.0, h_body=6.0)
    mesh = build_gear_body(spec)
    v = mesh.nodes[np.unique(mesh.facets["flank_0_right"][:, :3])]
    back = np.stack([rot2(q[None, :2], -spec.lead_twist * q[2])[0] for q in v])
    from ltca.fem.solids.planar import polyline_distance
    dense = np.asarray(p.xy)
    d = np.array([polyline_distance(q, dense) for q in back])
    print(f"helical flank vertices off the generated outline by at most {1e3 * d.max():.3f} um")
    assert np.max(d) < 1e-3
    assert abs(spec.lead_twist) * 40.0 > 0.2                       # the twist is substantial


def test_internal_gear_is_held_at_its_outer_rim():
    from ltca.case import load_case
    from ltca.cylindrical.model import build_model
    from ltca.fem.solids import build_gear_body
    model = build_model(load_case(CASES / "internal_spur.toml"))
    p = model.gear
    mesh = build_gear_body(_spec(p, model.r_bore2, model.face_width, h_flank=2.0, h_body=8.0))
    r = np.hypot(*mesh.nodes[np.unique(mesh.facets["rim"][:, :3])][:, :2].T)     # vertices lie on the circle
    assert np.allclose(r, model.r_bore2, rtol=1e-9)
    assert "bore" not in mesh.facets


def test_read_fillets_are_meshed_at_h_fillet_and_nothing_else_changes(fzg_model):
    """The named fillets get edges of about h_fillet, the other fillets keep h_flank; without h_fillet the
    spec (its hash: the mesh caches) does not change."""
    from ltca.fem.solids import build_gear_body
    p = fzg_model.pinion
    plain = _spec(p, 20.0, 14.0, h_flank=2.0, h_body=6.0)
    assert plain.spec_hash == _spec(p, 20.0, 14.0, h_flank=2.0, h_body=6.0, h_fillet=None, fillets=()).spec_hash
    spec = dataclasses.replace(plain, h_fillet=0.8, fillets=("fillet_0_right",))
    assert spec.spec_hash != plain.spec_hash
    mesh = build_gear_body(spec)

    def edge(group):
        tri = mesh.nodes[mesh.facets[group][:, :3]]
        return float(np.mean(np.linalg.norm(tri - np.roll(tri, 1, axis=1), axis=2)))
    print(f"mean fillet edge: refined {edge('fillet_0_right'):.3f} mm, other {edge('fillet_0_left'):.3f} mm")
    assert 0.6 < edge("fillet_0_right") < 1.0 and edge("fillet_0_left") > 1.4
    with pytest.raises(ValueError, match="h_fillet"):
        dataclasses.replace(plain, h_fillet=3.0)


def test_far_teeth_change_the_flank_compliance_by_under_one_percent(fzg_model, tmp_path):
    """The design choice 'far teeth left out' measured against the body with every tooth (docs/design.md)."""
    from ltca.fem.compliance import ComplianceSpec, body_compliance
    p = fzg_model.pinion
    base = ComplianceSpec(teeth=(-2, -1, 0, 1, 2), loaded=(-1, 0, 1), side=+1, r_range=fzg_model.pinion_range(),
                          grid=(5, 4), face_width=14.0, r_bore=fzg_model.r_bore1, h_flank=2.0, h_body=7.2, depth=1.5,
                          young=206000.0, poisson=0.3, root_points=(2, 2))
    # the mean compliance of the middle tooth's flank (what the mesh stiffness integrates); single entries also
    # carry the difference of two unstructured meshes (about 1 % at this coarse size)
    C = {far: np.diag(body_compliance(p, dataclasses.replace(base, far_teeth=far)).C).reshape(3, 5, 4)[1].mean()
         for far in ("none", "full")}
    rel = abs(C["none"] / C["full"] - 1)
    print(f"far teeth left out: mean flank compliance changes by {100 * rel:.2f} %")
    assert rel < 0.01


def test_bad_body_specs_name_the_field(fzg_model):
    p = fzg_model.pinion
    with pytest.raises(ValueError, match="r_support"):
        _spec(p, p.r_root + 1.0, 14.0)
    with pytest.raises(ValueError, match="rim radius"):
        _spec(p, 10.0, 14.0, rim=(p.r_root + 2, 15.0, 4.0, 0.0))
    with pytest.raises(ValueError, match="web width"):
        _spec(p, 10.0, 14.0, rim=(p.r_root - 9, 15.0, 20.0, 0.0))
    with pytest.raises(ValueError, match="far_teeth"):
        _spec(p, 10.0, 14.0, far_teeth="some")


def test_web_keys_in_the_case_file(tmp_path):
    from ltca.case import load_case
    from ltca.cylindrical.model import build_model
    from ltca.errors import CaseError
    text = (CASES / "fzg_c14.toml").read_text()
    ok = tmp_path / "web.toml"
    ok.write_text(text.replace("bore_diameter_mm = 40.0", "bore_diameter_mm = 20.0\nrim_thickness_mm = 9.0\n"
                               "web_thickness_mm = 4.0"))
    model = build_model(load_case(ok))
    r_rim, r_hub, bs, off = model.web1
    assert r_rim == pytest.approx(model.pinion.r_root - 9.0) and bs == 4.0 and off == 0.0
    assert r_hub == pytest.approx(10.0 + (r_rim - 10.0) / 3)
    assert model.web2 is None
    for extra, field in (("rim_thickness_mm = 9.0", "web_thickness_mm"),
                         ("rim_thickness_mm = 9.0\nweb_thickness_mm = 20.0", "web_thickness_mm"),
                         ("rim_thickness_mm = 9.0\nweb_thickness_mm = 4.0\nweb_offset_mm = 6.0", "web_offset_mm"),
                         ("rim_thickness_mm = 30.0\nweb_thickness_mm = 4.0", "rim_thickness_mm")):
        bad = tmp_path / "bad.toml"
        bad.write_text(text.replace("bore_diameter_mm = 40.0", "bore_diameter_mm = 20.0\n" + extra))
        with pytest.raises(CaseError, match=field):
            build_model(load_case(bad))


def _mean_stiffness(case, tmp_path, positions=8, fidelity="default"):
    from ltca.case import FIDELITIES
    from ltca.cylindrical.loaded import solve_position
    from ltca.cylindrical.loaded_model import Fidelity, prepare
    from ltca.cylindrical.model import build_model
    from ltca.cylindrical.results import mesh_stiffness
    from ltca.cylindrical.run import cycle_rolls
    model = build_model(case)
    rolls = cycle_rolls(positions, case.pinion.teeth)
    T = case.torques[0]
    lm = prepare(model, Fidelity.from_preset(FIDELITIES[fidelity], case.module), rolls, T, cache_dir=tmp_path)
    res = [solve_position(lm, r, T) for r in rolls]
    return float(np.mean(mesh_stiffness(lm, np.array([r.theta for r in res]), np.array([r.theta0 for r in res]), T)))


@pytest.mark.slow
def test_shaft_seat_and_web_trends(fzg_case, tmp_path):
    """Bore on a rigid shaft: the nearer the seat to the root, the stiffer (disc torsion and foundation).
    A web narrower than the face under a rim of s_R: softer than the solid disc by about ISO 6336-1's rim
    factor C_R = 1 + ln(b_s / b) / (5 exp(s_R / (5 m))), and stiffer as the rim thickens from 1 m to 4 m.

    Measured (FZG C14 pinion on a 20 mm bore, 8 positions, default fidelity, solid 15.32 N/(mm um)), ratio
    webbed / solid against C_R at s_R = 1 / 1.5 / 2 / 3 / 4 m: web b/4 0.746 / 0.761 / 0.763 / 0.759 / 0.787
    against 0.773 / 0.795 / 0.814 / 0.848 / 0.875; web b/2 0.882 / 0.893 / 0.896 / 0.896 / 0.910 against
    0.886 / 0.897 / 0.907 / 0.924 / 0.938. Between 2 and 3 m the trend is flat: a thicker rim puts the web (and
    its torsion) at smaller radii, as the hub stays a third of the way from bore to rim."""
    k = {}
    for bore in (20.0, 30.0, 40.0, 50.0, 56.0):
        case = dataclasses.replace(fzg_case, pinion=dataclasses.replace(fzg_case.pinion, bore_diameter=bore))
        k[bore] = _mean_stiffness(case, tmp_path)
    print("mean mesh stiffness by pinion bore:", {b: round(v, 2) for b, v in k.items()})
    assert np.all(np.diff(list(k.values())) > 0)
    m, b = fzg_case.module, fzg_case.pinion.face_width
    for bs in (b / 4, b / 2):
        ratio = {}
        for sR in (1.0, 2.0, 4.0):
            webbed = dataclasses.replace(fzg_case.pinion, bore_diameter=20.0, rim_thickness=sR * m, web_thickness=bs)
            ratio[sR] = _mean_stiffness(dataclasses.replace(fzg_case, pinion=webbed), tmp_path) / k[20.0]
            C_R = 1 + np.log(bs / b) / (5 * np.exp(sR * m / (5 * m)))      # ISO 6336-1, rim factor
            print(f"web {bs:.1f} mm, rim {sR:g} m: webbed / solid {ratio[sR]:.3f}, ISO C_R {C_R:.3f}")
            assert ratio[sR] == pytest.approx(C_R, abs=0.1)
        assert ratio[1.0] < ratio[2.0] < ratio[4.0] < 1.0


@pytest.mark.slow
@pytest.mark.parametrize("name, bore1", [("helical_m8_wide.toml", None), ("helical_c14.toml", 30.0),
                                         ("fzg_c14.toml", 30.0), ("fzg_c14.toml", 40.0)])
def test_mean_mesh_stiffness_in_iso_band(name, bore1, tmp_path):
    """Solid-disc bodies on rigid shafts (FZG rig shafts 30-40 mm; the wide pair's bores half the reference
    diameters): mean c_gamma between 0.8 c' and 1.2 c'_th of ISO 6336-1 (tests/reference/iso6336_stiffness.md)."""
    from ltca.case import load_case
    from ltca.cylindrical.model import build_model
    from ltca.verify.validate import iso6336_stiffness
    case = load_case(CASES / name)
    if bore1 is not None:
        case = dataclasses.replace(case, pinion=dataclasses.replace(case.pinion, bore_diameter=bore1))
    k = _mean_stiffness(case, tmp_path, positions=12)
    cp, cth = iso6336_stiffness(build_model(case))
    print(f"{name} bore {bore1}: mean c_gamma {k:.2f} N/(mm um), ISO c' {cp:.2f}, c'_th {cth:.2f}")
    assert 0.8 * cp <= k <= 1.2 * cth


def test_pair_compliance_meshes_the_second_body_beside_the_first(fzg_model):
    """Both bodies of a pair, the gear meshed in a child process while the pinion is meshed, then each solved in its
    own thread: the same compliance as one body after the other (gmsh's meshes are deterministic)."""
    from ltca.fem.compliance import ComplianceSpec, body_compliance, pair_compliance
    m = fzg_model

    def spec(side, r_range, r_bore):
        return ComplianceSpec(teeth=(-2, -1, 0, 1, 2), loaded=(-1, 0, 1), side=side, r_range=r_range, grid=(4, 3),
                              face_width=14.0, r_bore=r_bore, h_flank=2.5, h_body=8.0, depth=1.5, young=206000.0,
                              poisson=0.3, root_points=(2, 2))
    specs = (spec(+1, m.pinion_range(), m.r_bore1), spec(m.gear_side, m.gear_range(), m.r_bore2))
    both = pair_compliance((m.pinion, m.gear), specs)
    for profile, s, body in zip((m.pinion, m.gear), specs, both):
        alone = body_compliance(profile, s)
        assert body.mesh.spec_hash == alone.mesh.spec_hash and len(body.mesh.nodes) == len(alone.mesh.nodes)
        np.testing.assert_allclose(body.C, alone.C, rtol=1e-9, atol=1e-12 * np.abs(alone.C).max())
