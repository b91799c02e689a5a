"""The independent whole-gear CalculiX check: full-gear solids with every tooth, their deck,
and (slow) ours against CalculiX at one position."""
from __future__ import annotations

import ast
import shutil

import numpy as np
import pytest

from fixtures.paths import CASES, ROOT

needs_ccx = pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) missing")


@pytest.fixture(scope="module")
def thin_rim_model():
    from ltca.case import load_case
    from ltca.cylindrical.model import build_model
    return build_model(load_case(CASES / "crosscheck" / "fzg_c14_thin_rim.toml"))


def _coarse(model, member):
    from ltca.fem.solids.full_gear import FullGearSpec, build_full_gear
    p = model.pinion if member == "pinion" else model.gear
    r_bore, web = (model.r_bore1, model.web1) if member == "pinion" else (model.r_bore2, model.web2)
    return build_full_gear(FullGearSpec(p.xy, p.kind, p.side, p.z, r_bore, model.face_width, web=web,
                                        loaded_teeth=(0,), h_flank=2.0, h_tooth=3.0, h_body=6.0, ds=0.8))


@pytest.mark.heavy
def test_full_gear_has_every_tooth_bore_and_web(thin_rim_model):
    m = _coarse(thin_rim_model, "pinion")
    z = thin_rim_model.pinion.z
    teeth = {int(n.split("_")[1]) for n in m.facets if n.startswith("flank_")}
    assert teeth == set(range(-(z // 2), z - z // 2))
    assert all(f"flank_{k}_{s}" in m.facets for k in teeth for s in ("left", "right"))
    bore = m.nodes[np.unique(m.facets["bore"][:, :3])]
    assert np.allclose(np.hypot(bore[:, 0], bore[:, 1]), thin_rim_model.r_bore1, atol=1e-6)
    # the web: body nodes between hub and rim radii lie within the web's axial width only
    r_rim, r_hub, width, off = thin_rim_model.web1
    r = np.hypot(m.nodes[:, 0], m.nodes[:, 1])
    between = (r > r_hub + 0.5) & (r < r_rim - 0.5)      # chords of the rim and hub cylinders sag < 0.5 mm
    assert between.any() and np.all(np.abs(m.nodes[between, 2] - off) <= 0.5 * width + 1e-6)
    # volume of the solid against the section area: toothed rim + web + hub (rim less than a disc)
    X = m.nodes[m.tets[:, :4]]
    vol = np.abs(np.einsum("ij,ij->i", np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), X[:, 3] - X[:, 0])).sum() / 6
    b = thin_rim_model.face_width
    disc = np.pi * (r_rim ** 2 - thin_rim_model.r_bore1 ** 2) * b
    assert vol < disc + np.pi * (thin_rim_model.pinion.r_tip ** 2 - r_rim ** 2) * b


@pytest.mark.heavy
def test_whole_deck_writes(thin_rim_model, tmp_path):
    from ltca.fem.calculix.deck import CcxDeck, ContactPairSpec, DeckBody, write_deck
    from ltca.geometry.pair import rotation_z
    m1, m2 = _coarse(thin_rim_model, "pinion"), _coarse(thin_rim_model, "gear")
    m1.facets["band_0"], m2.facets["band_0"] = m1.facets["flank_0_right"], m2.facets["flank_0_left"]
    deck = CcxDeck(young=206000.0, poisson=0.3, fixed=("gear", "bore"), driven=("pinion", "bore"), moment=-2e5,
                   pairs=(ContactPairSpec("P0", ("pinion", ("band_0",)), ("gear", ("band_0",))),), penalty=1e7)
    ids = write_deck(tmp_path / "job.inp", [DeckBody("pinion", m1, rotation_z(0.1)),
                                            DeckBody("gear", m2, thin_rim_model.pair.gear_frame(0.1))], deck)
    text = (tmp_path / "job.inp").read_text()
    assert ids["rot"] == len(m1.nodes) + len(m2.nodes) + 2
    assert "*RIGID BODY, NSET=NRIGID" in text and "*CONTACT PAIR" in text and "NFIX, 1, 3" in text


def test_full_gear_is_independent_of_our_body():
    """The reference solid and its CalculiX driver import neither our body nor our compliance."""
    for path in (ROOT / "fem" / "solids" / "full_gear.py", ROOT / "ltca" / "verify" / "whole_gear.py",
                 ROOT / "ltca" / "verify" / "whole_root.py"):
        tree = ast.parse(path.read_text())
        names = {n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
        names |= {a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
        assert not any("gear_body" in n or "compliance" in n for n in names), (path, names)


@pytest.mark.heavy
def test_helical_full_gear_is_lofted_on_the_helicoid():
    """Helical C14's pinion (beta 20 deg, b 40 mm): every tooth labelled, the flank vertices of tooth 0 within
    1 um of the transverse outline turned by tan(beta) / r z (measured 0.3 um), over the whole face."""
    from ltca.case import load_case
    from ltca.cylindrical.model import build_model
    from ltca.fem.solids.full_gear import FullGearSpec, build_full_gear
    from ltca.fem.solids.planar import polyline_distance, rot2
    from ltca.verify.whole_gear import twist
    model = build_model(load_case(CASES / "helical_c14.toml"))
    p, b = model.pinion, model.face_width
    m = build_full_gear(FullGearSpec(p.xy, p.kind, p.side, p.z, model.r_bore1, b, loaded_teeth=(0,), h_flank=2.0,
                                     h_tooth=3.0, h_body=6.0, ds=0.8, twist=twist(p)))
    teeth = {int(n.split("_")[1]) for n in m.facets if n.startswith("flank_")}
    assert teeth == set(range(-(p.z // 2), p.z - p.z // 2)) and {"bore", "ends", "root"} <= set(m.facets)
    X = m.nodes[np.unique(m.facets["flank_0_right"][:, :3])]
    d = [polyline_distance(rot2(x[None, :2], -twist(p) * x[2])[0], np.asarray(p.xy)) for x in X]
    assert max(d) < 1e-3 and X[:, 2].min() == pytest.approx(-0.5 * b) and X[:, 2].max() == pytest.approx(0.5 * b)
    assert twist(p) == pytest.approx(np.tan(np.radians(20.0)) / p.r_ref)


def _frd_block(name: str, rows: dict) -> str:
    """A nodal result block of a CalculiX .frd file (I10 node ids, E12.5 values)."""
    lines = [f" -4  {name:<8}    6    1"] + [f" -5  C{i}          1    4    1    1" for i in range(6)]
    lines += [" -1" + f"{n:10d}" + "".join(f"{v:12.5E}" for v in vals) for n, vals in rows.items()]
    return "\n".join(lines + [" -3"]) + "\n"


def test_read_nodal_stress_takes_the_last_block_in_voigt_order(tmp_path):
    from ltca.fem.calculix.run import read_nodal_stress
    frd = tmp_path / "job.frd"
    frd.write_text(_frd_block("DISP", {1: [9.0] * 6}) + _frd_block("STRESS", {1: [1.0] * 6}) +
                   _frd_block("STRESS", {1: [1.0, 2.0, 3.0, 4.0, 5.0, 6.0], 12: [-1e3, 0, 0, 0, 0, 250.5]}))
    ids, sig = read_nodal_stress(frd)
    assert ids.tolist() == [1, 12]
    # CalculiX SXX SYY SZZ SXY SYZ SZX -> xx yy zz yz xz xy
    assert np.allclose(sig[0], [1, 2, 3, 5, 6, 4]) and np.allclose(sig[1], [-1e3, 0, 0, 0, 250.5, 0])


@pytest.mark.heavy
def test_fillet_stress_reads_the_tension_fillets_as_ours(tmp_path):
    """0.05 mm inside the named fillets, |z| <= 0.45 b, largest principal stress, and where; the loaded
    teeth's tension-side fillets are meshed at h_fillet, the other side left."""
    from ltca.case import load_case
    from ltca.cylindrical.model import build_model
    from ltca.fem.solids.full_gear import FullGearSpec, build_full_gear
    from ltca.verify.whole_root import Member, fillet_points, fillet_stress, largest_principal
    model = build_model(load_case(CASES / "fzg_c14.toml"))
    p, b = model.pinion, model.face_width
    spec = dict(loaded_teeth=(0,), h_flank=2.0, h_tooth=3.0, h_body=6.0, ds=0.8)
    m = build_full_gear(FullGearSpec(p.xy, p.kind, p.side, p.z, model.r_bore1, b, **spec))
    fine = build_full_gear(FullGearSpec(p.xy, p.kind, p.side, p.z, model.r_bore1, b, h_fillet=0.6,
                                        fillet_side="right", **spec))
    edge = lambda mesh, g: np.linalg.norm(np.diff(mesh.nodes[mesh.facets[g][:, :2]], axis=1), axis=2).mean()
    assert edge(fine, "fillet_0_right") < 0.6 * edge(m, "fillet_0_right")
    assert edge(fine, "fillet_0_left") > 0.8 * edge(m, "fillet_0_left")          # the other side left as it was
    # the read-out points lie 0.05 mm inside the fillet (in the mesh), over the face span
    X, angle = fillet_points((p.xy, p.kind, p.side), 1, b)
    fillet = np.asarray(p.xy)[(np.asarray(p.kind) == 1) & (np.asarray(p.side) == 1)]
    d = np.min(np.linalg.norm(X[:, None, :2] - fillet[None], axis=2), axis=1)
    assert np.all(d > 0.03) and np.all(d < 0.0501) and np.abs(X[:, 2]).max() == pytest.approx(0.45 * b)
    assert np.all(np.hypot(X[:, 0], X[:, 1]) < np.hypot(*fillet.T).max())
    # sigma_xx = 100 + z on every node (P2 interpolation is exact): the largest principal is 100 + 0.45 b
    off = 7
    frd = tmp_path / "job.frd"
    frd.write_text(_frd_block("STRESS", {off + i + 1: [100.0 + z, 0, 0, 0, 0, 0] for i, z in enumerate(m.nodes[:, 2])}))
    member = Member("pinion", m, off, (p.xy, p.kind, p.side), 1, p.z, (0, 1))
    out = fillet_stress(frd, [member], b)["pinion"]
    assert out["max"] == pytest.approx(100 + 0.45 * b, abs=1e-3)
    assert set(out["per_tooth"]) == {0, 1} and out["per_tooth"][1] == pytest.approx(out["max"], abs=1e-3)
    assert out["at"]["r_mm"] < p.r_base and out["surface"]["max"] <= 100 + 0.45 * b + 1e-9
    assert largest_principal(np.array([[0, 0, 0, 0, 0, 5.0]]))[0] == pytest.approx(5.0)   # pure shear xy


@pytest.mark.slow
@pytest.mark.calculix
@needs_ccx
def test_whole_gear_calculix_pitch_point_bore20(tmp_path):
    """FZG C14, pinion bore 20 mm, pitch point: ours within ``ltca.verify.whole_check.BOUNDS_WHOLE`` of whole-gear
    CalculiX."""
    import json

    from ltca.verify.whole_check import run_whole_validation
    rc = run_whole_validation(str(CASES / "crosscheck" / "fzg_c14_bore20.toml"), [0.0], str(tmp_path),
                              progress=False)
    row = json.loads((tmp_path / "whole_gear.json").read_text())["rows"][0]
    assert abs(row["te_diff_pct"]) < 3.0 and row["share_diff"] < 0.03 and abs(row["k_diff_pct"]) < 3.0, row
    assert rc == 0


def test_calculix_whole_argument_errors_before_ccx(tmp_path, capsys):
    """Bad positions exit 2 with the field named, whether or not ccx is installed."""
    from ltca.cli import main
    rc = main(["validate", "--reference", "calculix-whole", "--case", str(CASES / "fzg_c14.toml"),
               "--positions", "40", "--out", str(tmp_path)])
    assert rc == 2 and "--positions" in capsys.readouterr().err


def test_coarse_body_and_unconverged_readouts():
    """``--coarse-body`` coarsens only away from the contact band (same band, penalty and halo); a frozen reference
    names a read-out its ladder moves by more than 5 %, with the numbers."""
    from types import SimpleNamespace

    from ltca.verify.whole_gear import whole_settings
    from tools.calculix_refs.freeze_whole import unconverged
    d, c = whole_settings(0.118, 4.23, 150.0, threads=1), whole_settings(0.118, 4.23, 150.0, threads=1, body="coarse")
    assert (c.h_contact, c.half_band, c.penalty, c.halo) == (d.h_contact, d.half_band, d.penalty, d.halo)
    assert c.h_flank > d.h_flank and c.h_tooth > d.h_tooth and c.h_body > d.h_body and c.h_fillet > d.h_fillet
    assert c.fine_lines_only and not d.fine_lines_only

    def run(h, p, s1, s2):
        return SimpleNamespace(roll_deg=0.0, info={"h_contact_mm": h, "p_flank": p},
                               root={"pinion": {"max": s1}, "gear": {"max": s2}})
    bad = unconverged([run(0.225, 900.0, 70.0, 70.0), run(0.15, 1000.0, 72.0, 74.0)])
    assert set(bad) == {"flank_pressure", "root_gear"} and "900.0 -> 1000.0 MPa (+11.1 %)" in bad["flank_pressure"]
    assert unconverged([run(0.15, 1000.0, 72.0, 74.0)]) == {}


def test_fitted_peak_says_where():
    """The elliptic-fit flank peak is found on its line and slice, with the radius of its centre: an
    elliptic pressure of 1000 MPa over a half-width of 0.2 mm on the second of two lines, peaking at z 2.5 mm (a
    slice centre)."""
    from types import SimpleNamespace

    from ltca.fem.solids import ContactLine
    from ltca.verify.calculix import _fitted_peak
    from ltca.verify.fitted_peak import fitted_peak
    b = 14.0
    lines = [ContactLine((20.0, 0.0, -7.0), (20.0, 0.0, 7.0), (1.0, 0.0, 0.0)),
             ContactLine((0.0, 30.0, -7.0), (0.0, 30.0, 7.0), (0.0, 1.0, 0.0))]
    t, z = np.meshgrid(np.linspace(-0.3, 0.3, 31), np.linspace(-7.0, 7.0, 71))
    X = np.column_stack([t.ravel() + 0.05, np.full(t.size, 30.0), z.ravel()])     # across line 1: along -x
    p = 1000.0 * np.sqrt(np.clip(1 - (X[:, 0] - 0.05) ** 2 / 0.04, 0, None)) * (1 - 0.01 * (X[:, 2] - 2.5) ** 2)
    mesh = SimpleNamespace(nodes=X)
    ids = np.arange(1, len(X) + 1)
    at = fitted_peak(mesh, lines, ids, p, b, window=(-6.0, 6.0))
    assert at["line"] == 1 and at["p"] == pytest.approx(1000.0, rel=0.01) and at["z_mm"] == pytest.approx(2.5)
    assert at["r_mm"] == pytest.approx(np.hypot(0.05, 30.0), abs=0.01) and at["half_width_um"] == pytest.approx(200, 5)
    assert _fitted_peak(mesh, lines, ids, p, b, window=(-6.0, 6.0)) == at["p"]
