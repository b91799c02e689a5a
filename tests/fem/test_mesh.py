"""Tests of the tooth-segment mesher (tools.segment_mesh) and the shared gmsh meshing (fem.solids.gmsh_mesh):
graded quadratic tetrahedra."""
from __future__ import annotations

import time

import numpy as np
import pytest

from ltca.fem.solids import BodyMesh, gmsh_session
from tools.segment_mesh import SegmentSpec, build_segment


# ----------------------------------------------------------------------------------------------
# a self-made tooth outline: involute + straight/circular fillet + root and tip arcs
# ----------------------------------------------------------------------------------------------
def _inv(a):
    return np.tan(a) - a


def _polar(r, th):
    """Points at radius r and angle th measured clockwise from +y."""
    return np.c_[r * np.sin(th), r * np.cos(th)]


def _arc(r, th0, th1, step):
    n = max(3, int(np.ceil(abs(th1 - th0) * r / step)) + 1)
    return _polar(r, np.linspace(th0, th1, n))


def _line(p, q, step):
    n = max(2, int(np.ceil(np.linalg.norm(q - p) / step)) + 1)
    return p + np.linspace(0, 1, n)[:, None] * (q - p)


def tooth_outline(m=4.5, z=16, alpha=np.deg2rad(20.0), internal=False, rho=0.3, step=0.01):
    """One tooth, dense, in the fem.solids convention. Returns xy, kind, side, r_root, r_tip."""
    rp = m * z / 2
    rb = rp * np.cos(alpha)
    if not internal:
        r_tip, r_root, r_form = rp + m, rp - 1.25 * m, rb
        half = lambda r: np.pi / (2 * z) + _inv(alpha) - _inv(np.arccos(np.minimum(rb / r, 1)))
    else:
        r_tip, r_root, r_form = rp - m, rp + 1.25 * m, rp + 0.95 * m
        half = lambda r: np.pi / (2 * z) - _inv(alpha) + _inv(np.arccos(rb / r))
    # right flank from tip to form radius (arc-length spacing ~ step)
    r = np.linspace(r_tip, r_form, 4000)
    fl = _polar(r, half(r))
    s = np.r_[0, np.cumsum(np.hypot(*np.diff(fl, axis=0).T))]
    fl = np.c_[np.interp(np.linspace(0, s[-1], int(s[-1] / step) + 2), s, fl[:, 0]),
               np.interp(np.linspace(0, s[-1], int(s[-1] / step) + 2), s, fl[:, 1])]
    # fillet: straight extension of the flank's last tangent, then an arc of radius rho tangent to
    # that line and to the root circle
    P = fl[-1]
    d = (fl[-1] - fl[-2]) / np.linalg.norm(fl[-1] - fl[-2])
    nrm = np.array([d[1], -d[0]])                                  # towards the gap (x increasing)
    if nrm[0] < 0:
        nrm = -nrm
    rc = r_root - rho if internal else r_root + rho
    # |P + s d + rho nrm| = rc
    q = P + rho * nrm
    bq, cq = q @ d, q @ q - rc ** 2
    roots = -bq + np.array([-1, 1]) * np.sqrt(bq ** 2 - cq)
    s1 = roots[roots > 0].min()
    T1 = P + s1 * d
    C = q + s1 * d
    T2 = C / np.linalg.norm(C) * r_root
    a1, a2 = np.arctan2(*(T1 - C)[::-1]), np.arctan2(*(T2 - C)[::-1])
    da = (a2 - a1 + np.pi) % (2 * np.pi) - np.pi
    t = np.linspace(a1, a1 + da, max(3, int(abs(da) * rho / step) + 1))
    fil = np.vstack([_line(P, T1, step)[1:], (C + rho * np.c_[np.cos(t), np.sin(t)])[1:]])
    th2 = np.arctan2(T2[0], T2[1])
    root = _arc(r_root, th2, np.pi / z, step)[1:]
    th_tip = half(r_tip)
    tip = _arc(r_tip, -th_tip, th_tip, step)[1:-1]
    right = [fl, fil, root]
    left = [np.c_[-a[::-1, 0], a[::-1, 1]] for a in right[::-1]]
    parts = left + [tip] + right
    kinds = [0, 1, 2, 3, 2, 1, 0]
    sides = [-1, -1, -1, 0, 1, 1, 1]
    xy = np.vstack(parts)
    kind = np.concatenate([np.full(len(p), k, np.int8) for p, k in zip(parts, kinds)])
    side = np.concatenate([np.full(len(p), sd, np.int8) for p, sd in zip(parts, sides)])
    return xy, kind, side, r_root, r_tip


# ----------------------------------------------------------------------------------------------
# checks
# ----------------------------------------------------------------------------------------------
M, Z, B = 4.5, 16, 14.0
TEETH = (-2, -1, 0, 1, 2)
R_BORE = 18.0


def section_area(xy, z, teeth, r_bore):
    """Shoelace area of the closed transverse section: teeth outlines, radial cuts, bore arc."""
    pitch = 2 * np.pi / z
    rot = lambda p, a: p @ np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])
    outer = np.vstack([rot(xy, -k * pitch) for k in teeth])
    a_end = np.arctan2(outer[-1, 1], outer[-1, 0])
    t = a_end + np.linspace(0, len(teeth) * pitch, 20001)
    poly = np.vstack([outer, r_bore * np.c_[np.cos(t), np.sin(t)]])
    x, y = poly.T
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def corner_volumes(mesh):
    v = mesh.nodes[mesh.tets[:, :4]]
    return np.einsum("ij,ij->i", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), v[:, 3] - v[:, 0]) / 6


def polyline_distance(p, poly):
    """Distance of points p (k, 2) to the dense polyline poly (m, 2)."""
    from scipy.spatial import cKDTree

    _, i = cKDTree(poly).query(p)
    best = np.full(len(p), np.inf)
    for j0 in (i - 1, i):
        j0 = np.clip(j0, 0, len(poly) - 2)
        a, d = poly[j0], poly[j0 + 1] - poly[j0]
        t = np.clip(np.einsum("ij,ij->i", p - a, d) / np.einsum("ij,ij->i", d, d), 0, 1)
        best = np.minimum(best, np.linalg.norm(a + t[:, None] * d - p, axis=1))
    return best


def flank_deviation(mesh, xy, kind, side, z, twist):
    """Max distance of the flank facet vertices, untwisted and rotated to tooth 0, to the outline."""
    pitch = 2 * np.pi / z
    worst = 0.0
    for name, tri in mesh.facets.items():
        if not name.startswith("flank_"):
            continue
        _, k, sd = name.split("_")
        p = mesh.nodes[np.unique(tri[:, :3])]
        a = int(k) * pitch - twist * p[:, 2]
        q = np.c_[p[:, 0] * np.cos(a) - p[:, 1] * np.sin(a), p[:, 0] * np.sin(a) + p[:, 1] * np.cos(a)]
        run = np.flatnonzero((kind == 2) & (side == (-1 if sd == "left" else 1)))
        run = np.arange(run[0] - 1, run[-1] + 2)         # the curve ends on the neighbouring points
        worst = max(worst, polyline_distance(q, xy[run]).max())
    return worst


@pytest.fixture(scope="module")
def outline():
    return tooth_outline(M, Z)


@pytest.fixture(scope="module")
def spur(outline):
    xy, kind, side, *_ = outline
    spec = SegmentSpec(xy, kind, side, Z, TEETH, R_BORE, B, h_flank=1.0, h_body=4.0)
    t0 = time.perf_counter()
    mesh = build_segment(spec)
    print(f"\nspur 5 teeth m={M} z={Z} b={B} h_flank=1.0: {len(mesh.nodes)} nodes, "
          f"{len(mesh.tets)} tets, {time.perf_counter() - t0:.2f} s")
    return spec, mesh


def test_spur_volume_jacobian_node_order(spur, outline):
    spec, mesh = spur
    assert isinstance(mesh, BodyMesh) and mesh.tets.shape[1] == 10
    vol = corner_volumes(mesh)
    assert vol.min() > 0
    exact = section_area(outline[0], Z, TEETH, R_BORE) * B
    print(f"volume {vol.sum():.2f} vs {exact:.2f} mm^3: rel {vol.sum() / exact - 1:.2e}")
    assert abs(vol.sum() / exact - 1) < 5e-3
    edges = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
    for j, (a, b) in enumerate(edges):
        mid = 0.5 * (mesh.nodes[mesh.tets[:, a]] + mesh.nodes[mesh.tets[:, b]])
        assert np.abs(mesh.nodes[mesh.tets[:, 4 + j]] - mid).max() < 1e-9
    assert len(np.unique(mesh.tets)) == len(mesh.nodes)


def test_spur_facets(spur, outline):
    spec, mesh = spur
    xy, kind, side, *_ = outline
    expected = {"bore", "cut", "ends", "root"} | {f"tip_{k}" for k in TEETH} | {
        f"{w}_{k}_{s}" for w in ("flank", "fillet") for k in TEETH for s in ("left", "right")}
    assert set(mesh.facets) == expected
    dev = flank_deviation(mesh, xy, kind, side, Z, 0.0)
    print(f"flank vertices off the outline: {dev * 1e3:.3g} um")
    assert dev < 1e-4
    # facets outward: the facet normals of the ends point along +-z, the bore's towards the axis
    for name, tri in mesh.facets.items():
        v = mesh.nodes[tri[:, :3]]
        n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
        c = v.mean(axis=1)
        if name == "ends":
            assert np.all(np.sign(n[:, 2]) == np.sign(c[:, 2]))
        if name == "bore":
            assert np.all(np.einsum("ij,ij->i", n[:, :2], c[:, :2]) < 0)
        if name.startswith("tip_"):
            assert np.all(np.einsum("ij,ij->i", n[:, :2], c[:, :2]) > 0)
    # closed surface: the divergence theorem on the facets gives the volume again
    tri = np.vstack(list(mesh.facets.values()))[:, :3]
    v = mesh.nodes[tri]
    vol_s = np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6
    assert vol_s == pytest.approx(corner_volumes(mesh).sum(), rel=1e-9)
    # element size on the flanks
    for name in ("flank_0_left", "flank_2_right"):
        t = mesh.facets[name][:, :3]
        e = np.linalg.norm(mesh.nodes[t] - mesh.nodes[np.roll(t, 1, axis=1)], axis=2)
        print(f"{name}: median edge {np.median(e):.3f} mm (h_flank {spec.h_flank})")
        assert 0.6 * spec.h_flank <= np.median(e) <= 1.4 * spec.h_flank


def test_helical_flank_is_screw_surface(outline):
    xy, kind, side, *_ = outline
    twist = np.tan(np.deg2rad(15.0)) / (M * Z / 2)              # beta = 15 deg at the pitch radius
    teeth = (-1, 0, 1)
    spec = SegmentSpec(xy, kind, side, Z, teeth, R_BORE, B, lead_twist=twist)
    mesh = build_segment(spec)
    dev = flank_deviation(mesh, xy, kind, side, Z, twist)
    vol = corner_volumes(mesh)
    exact = section_area(xy, Z, teeth, R_BORE) * B
    print(f"\nhelical: {len(mesh.nodes)} nodes, {mesh.seconds:.2f} s, untwisted flank vertices off the "
          f"outline {dev * 1e3:.3g} um, volume rel {vol.sum() / exact - 1:.2e}")
    assert dev < 1e-3
    assert vol.min() > 0 and abs(vol.sum() / exact - 1) < 5e-3
    # the flank really twists: the tip centre line turns by twist * b over the face width
    p = mesh.nodes[np.unique(mesh.facets["tip_0"][:, :3])]
    ang = np.arctan2(p[:, 0], p[:, 1])
    slope = np.polyfit(p[:, 2], ang, 1)[0]
    assert slope == pytest.approx(-twist, rel=0.05)


def test_internal_segment_and_cache(tmp_path):
    z = 40
    xy, kind, side, r_root, r_tip = tooth_outline(M, z, internal=True)
    assert r_tip < r_root
    teeth = (-1, 0, 1)
    spec = SegmentSpec(xy, kind, side, z, teeth, 105.0, 10.0, internal=True, h_flank=1.0, h_body=4.0)
    mesh = build_segment(spec, cache_dir=tmp_path)
    vol = corner_volumes(mesh)
    exact = section_area(xy, z, teeth, 105.0) * 10.0
    print(f"\ninternal: {len(mesh.nodes)} nodes, {mesh.seconds:.2f} s, volume rel {vol.sum() / exact - 1:.2e}")
    assert vol.min() > 0 and abs(vol.sum() / exact - 1) < 5e-3
    assert "rim" in mesh.facets and "bore" not in mesh.facets
    assert flank_deviation(mesh, xy, kind, side, z, 0.0) < 1e-4
    for k in teeth:                                               # tips face the axis
        v = mesh.nodes[mesh.facets[f"tip_{k}"][:, :3]]
        n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
        assert np.all(np.einsum("ij,ij->i", n[:, :2], v.mean(axis=1)[:, :2]) < 0)
    import tools.segment_mesh as segment_module

    def no_meshing(*args, **kwargs):
        raise AssertionError("a cache hit must not mesh again")
    orig, segment_module.mesh_with_gmsh = segment_module.mesh_with_gmsh, no_meshing
    try:
        again = build_segment(spec, cache_dir=tmp_path)
    finally:
        segment_module.mesh_with_gmsh = orig
    assert again.spec_hash == mesh.spec_hash
    assert np.array_equal(again.nodes, mesh.nodes) and np.array_equal(again.tets, mesh.tets)
    assert again.facets.keys() == mesh.facets.keys()
    assert all(np.array_equal(again.facets[k], mesh.facets[k]) for k in mesh.facets)


def test_reproducible_and_reentrant(outline):
    import gmsh

    xy, kind, side, *_ = outline
    spec = SegmentSpec(xy, kind, side, Z, (0,), R_BORE, 6.0, h_flank=1.5, h_body=4.0)
    with gmsh_session():
        gmsh.model.add("mine")
        a = build_segment(spec)
        assert gmsh.isInitialized() and gmsh.model.getCurrent() == "mine"
    b = build_segment(spec)
    assert np.array_equal(a.nodes, b.nodes) and np.array_equal(a.tets, b.tets)


@pytest.mark.parametrize("field, value", [("z", 2), ("teeth", (0, 2)), ("teeth", tuple(range(16))),
                                          ("r_bore", 35.0), ("face_width", 0.0), ("h_flank", 5.0),
                                          ("order", 3), ("lead_twist", 1.0)])
def test_bad_input(outline, field, value):
    xy, kind, side, *_ = outline
    args = dict(outline=xy, kind=kind, side=side, z=Z, teeth=TEETH, r_bore=R_BORE, face_width=B)
    args[field] = value
    with pytest.raises(ValueError, match=field):
        SegmentSpec(**args)


@pytest.mark.heavy
def test_timing_h05(outline, spur):
    xy, kind, side, *_ = outline
    spec = SegmentSpec(xy, kind, side, Z, TEETH, R_BORE, B, h_flank=0.5, h_body=4.0)
    mesh = build_segment(spec)
    t = mesh.facets["flank_0_left"][:, :3]
    e = np.median(np.linalg.norm(mesh.nodes[t] - mesh.nodes[np.roll(t, 1, axis=1)], axis=2))
    print(f"\nspur 5 teeth h_flank=0.5: {len(mesh.nodes)} nodes ({mesh.n_dofs} dofs), {len(mesh.tets)} "
          f"tets, {mesh.seconds:.2f} s; h_flank=1.0: {len(spur[1].nodes)} nodes, {spur[1].seconds:.2f} s; "
          f"median flank edge {e:.3f} mm")
    assert 0.3 <= e <= 0.7
    assert corner_volumes(mesh).min() > 0
