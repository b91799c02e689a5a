"""CalculiX cross-check: deck writer and readers without ccx; one position against ccx (slow)."""
from __future__ import annotations

import dataclasses
import shutil

import numpy as np
import pytest

from ltca.fem.calculix.deck import CcxDeck, ContactPairSpec, DeckBody, _face_numbers, write_deck
from ltca.fem.calculix.run import CCX_INSTALL, CcxNotFound, ccx_path
from ltca.fem.solids import BodyMesh, ContactLine, facets_near_lines

needs_ccx = pytest.mark.skipif(shutil.which("ccx") is None, reason=f"CalculiX missing: {CCX_INSTALL}")


def _two_tets():
    """Two tetrahedra sharing face (1, 2, 3); P2 mid-edge nodes appended in meshio order."""
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1.0]])
    tets4 = np.array([[0, 1, 2, 3], [1, 4, 2, 3]])
    edges = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
    nodes, mid, tets = list(v), {}, []
    for t in tets4:
        row = list(t)
        for a, b in edges:
            key = tuple(sorted((t[a], t[b])))
            if key not in mid:
                mid[key] = len(nodes)
                nodes.append(0.5 * (v[t[a]] + v[t[b]]))
            row.append(mid[key])
        tets.append(row)
    return np.array(nodes), np.array(tets)


def test_face_numbers_follow_calculix_c3d10():
    nodes, tets = _two_tets()
    # S1 = 1-2-3, S2 = 1-4-2, S3 = 2-4-3, S4 = 3-4-1 (1-based vertices of element 0)
    tri = np.array([[0, 1, 2], [0, 3, 1], [1, 3, 2], [2, 3, 0]])
    el, face = _face_numbers(tets, tri, len(nodes))
    assert el.tolist() == [0, 0, 0, 0]
    assert face.tolist() == [1, 2, 3, 4]
    with pytest.raises(ValueError):
        _face_numbers(tets, np.array([[0, 1, 4]]), len(nodes))


def test_facets_near_lines_selects_the_band():
    nodes, tets = _two_tets()
    mesh = BodyMesh(nodes, tets, {"f": np.array([[0, 1, 2, 5, 6, 7], [1, 4, 3, 0, 0, 0]])}, "x")
    line = ContactLine(np.array([0.0, 0.0, 0.0]), np.array([0.5, 0.0, 0.0]), np.array([0.0, 0.0, 1.0]))
    near = facets_near_lines(mesh, ("f",), [line], 0.5)
    assert len(near) == 1 and near[0, 0] == 0


def test_deck_has_rigid_body_contact_and_moment(tmp_path):
    nodes, tets = _two_tets()
    tri = np.array([[0, 1, 2, 4, 5, 6]])
    mesh = BodyMesh(nodes, tets, {"bore": tri, "flank": tri}, "x")
    frame = np.eye(4)
    frame[:3, 3] = [0, 10, 0]
    deck = CcxDeck(young=206000.0, poisson=0.3, fixed=("gear", "bore"), driven=("pinion", "bore"), moment=-2e5,
                   pairs=(ContactPairSpec("P0", ("pinion", ("flank",)), ("gear", ("flank",))),), penalty=1e7)
    ids = write_deck(tmp_path / "job.inp", [DeckBody("pinion", mesh, np.eye(4)), DeckBody("gear", mesh, frame)], deck)
    text = (tmp_path / "job.inp").read_text()
    n = len(nodes)
    assert ids["ref"] == 2 * n + 1 and ids["rot"] == 2 * n + 2
    assert f"*RIGID BODY, NSET=NRIGID, REF NODE={2 * n + 1}, ROT NODE={2 * n + 2}" in text
    assert f"{2 * n + 2}, 3, -200000" in text and f"{2 * n + 2}, 1, 2" in text
    assert "TYPE=SURFACE TO SURFACE" in text and "SP0, MP0" in text
    assert f"{n + 1}, 0, 10, 0" in text           # gear node 1 placed by its frame
    assert "3, S1" in text                          # gear element 3 (= its first), face 1-2-3


def test_missing_ccx_names_the_install_command(monkeypatch):
    monkeypatch.setattr(shutil, "which", lambda name: None)
    with pytest.raises(CcxNotFound, match="apt-get install -y calculix-ccx"):
        ccx_path()


def test_bad_positions_are_case_errors(tmp_path):
    if shutil.which("ccx") is None:
        pytest.skip(f"CalculiX missing: {CCX_INSTALL}")
    from fixtures.paths import CASES
    from ltca.errors import CaseError
    from ltca.verify.crosscheck import run_calculix_validation
    with pytest.raises(CaseError, match="positions"):
        run_calculix_validation(str(CASES / "fzg_c14.toml"), [40.0], str(tmp_path), progress=False)


@pytest.mark.heavy
@pytest.mark.calculix
@needs_ccx
def test_double_contact_against_calculix(fzg_lm, tmp_path):
    """FZG C14, 200 N m, -9 deg roll (two pairs in contact): ours (default fidelity) against CalculiX.

    CI-sized CalculiX model: contact band of 300 um elements and our coarse fidelity's element sizes
    elsewhere (~110k dofs, ~2 min on 2 cores). At the pitch point this model's TE is within 0.2 % of
    the 100 um / default-body one, so TE and load sharing are compared at the bounds of
    ``ltca.verify.crosscheck.BOUNDS`` (3 %, 0.03); its contact pressure is not resolved at this size and is not compared
    (`ltca validate --reference calculix` does, on the refined ladder)."""
    import dataclasses

    from ltca.verify.calculix import ccx_ladder, solve_ccx, solve_ours
    torque = fzg_lm.model.case.torques[0]
    roll = np.radians(-9.0)
    ours, _ = solve_ours(fzg_lm, roll, torque)
    st = ccx_ladder(fzg_lm.b_nom, fzg_lm.model.case.module, refine=0, h0=0.3, body=(0.45, 1.6))[0]
    ccx = solve_ccx(fzg_lm, roll, torque, dataclasses.replace(st, threads=2), tmp_path, say=print)
    print(f"TE ours {ours.te:.2f} CalculiX {ccx.te:.2f} arcsec ({100 * (ours.te / ccx.te - 1):+.2f} %); "
          f"shares ours {ours.share(fzg_lm.teeth1)} CalculiX {ccx.share(fzg_lm.teeth1)}; "
          f"wall ours {ours.wall:.2f} s, CalculiX {ccx.wall:.0f} s")
    assert abs(ours.te / ccx.te - 1) < 0.03
    so, sc = ours.share(fzg_lm.teeth1), ccx.share(fzg_lm.teeth1)
    assert sc[0] > 0.3 and sc[1] > 0.3                     # both pairs carry load in CalculiX too
    assert max(abs(so[k] - sc[k]) for k in fzg_lm.teeth1) < 0.03
    total = sum(ccx.pair_load.values())
    assert abs(total * fzg_lm.model.pinion.r_base / torque - 1) < 0.02   # CalculiX's own torque balance


def test_narrowest_half_width_is_the_hertz_width(fzg_lm):
    """The table's CalculiX resolution (elements per half-width) uses our contact width: ~Hertz b."""
    from ltca.cylindrical.loaded import solve_position
    from ltca.verify.calculix import narrowest_contact
    res = solve_position(fzg_lm, 0.0, fzg_lm.model.case.torques[0])
    b = narrowest_contact(res)[1]
    assert abs(b - 0.1995) < res.ds          # tests/reference/hertz.md: 199.5 um at the pitch point


def test_focus_refines_only_its_window_of_the_contact_line(fzg_lm):
    """The pressure ladder's focus zone: elements of the focus size in the mid-face window of the contact
    line, the band's size elsewhere along the same line."""
    from ltca.fem.compliance import body_spec
    from ltca.fem.solids import build_refined_body
    from ltca.geometry.pair import rotation_z
    from ltca.verify.calculix import Focus, _window, contact_lines
    model = fzg_lm.model
    phi1 = model.phi_pitch
    (k, P, N), = [ln for ln in contact_lines(fzg_lm, phi1, cap=0.01) if ln[0] == 0]
    R = rotation_z(phi1)[:3, :3]
    line = ContactLine(P[0] @ R, P[-1] @ R, N[len(N) // 2] @ R)       # into the pinion's own frame
    focus = Focus(tooth=0, z0=0.0, half_length=1.0, h=0.06, half_band=0.2)
    win = _window(line, focus)
    assert np.allclose(sorted([win.p0[2], win.p1[2]]), [-1.0, 1.0])
    assert np.allclose(np.cross(win.p1 - win.p0, line.p1 - line.p0), 0.0, atol=1e-9)   # a piece of the line
    p1 = model.pinion
    spec = body_spec(p1, dataclasses.replace(fzg_lm.body1.spec, h_flank=0.45 * 4.5, h_body=1.6 * 4.5, fillet=0.0))
    mesh = build_refined_body(spec, [line], 0.3, 0.4, 0.4, 0.8, focus=((win, focus.h, focus.half_band),))
    tri = mesh.facets["flank_0_right"]
    X = mesh.nodes[tri[:, :3]]
    c = X.mean(axis=1)
    edge = np.linalg.norm(X - np.roll(X, 1, axis=1), axis=2).mean(axis=1)
    p0, d = line.p0, (line.p1 - line.p0) / np.linalg.norm(line.p1 - line.p0)
    off = np.linalg.norm(np.cross(c - p0, d), axis=1)     # distance from the contact line
    in_win = (off < 0.1) & (np.abs(c[:, 2]) < 0.8)
    away = (off < 0.1) & (np.abs(c[:, 2]) > 3.0)
    print(f"edges: window {np.median(edge[in_win]):.3f} mm ({in_win.sum()} facets), "
          f"along the line away from it {np.median(edge[away]):.3f} mm")
    assert 0.04 < np.median(edge[in_win]) < 0.08
    assert 0.22 < np.median(edge[away]) < 0.36
