"""The independent whole-gear CalculiX check (issue 11): full-gear solids with every tooth, their deck,
and (slow) ours against CalculiX at one position."""
from __future__ import annotations

import ast
import shutil

import numpy as np
import pytest

from conftest import CASES, ROOT

needs_ccx = pytest.mark.skipif(shutil.which("ccx") is None, reason="CalculiX (ccx) missing")


@pytest.fixture(scope="module")
def thin_rim_model():
    from ltca.case import load_case
    from ltca.cylindrical.model import build_model
    return build_model(load_case(CASES / "crosscheck" / "fzg_c14_thin_rim.toml"))


def _coarse(model, member):
    from fem.solids.full_gear import FullGearSpec, build_full_gear
    p = model.pinion if member == "pinion" else model.gear
    r_bore, web = (model.r_bore1, model.web1) if member == "pinion" else (model.r_bore2, model.web2)
    return build_full_gear(FullGearSpec(p.xy, p.kind, p.side, p.z, r_bore, model.face_width, web=web,
                                        loaded_teeth=(0,), h_flank=2.0, h_tooth=3.0, h_body=6.0, ds=0.8))


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


def test_whole_deck_writes(thin_rim_model, tmp_path):
    from fem.calculix.deck import CcxDeck, ContactPairSpec, DeckBody, write_deck
    from geometry.pair import rotation_z
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
    for path in (ROOT / "fem" / "solids" / "full_gear.py", ROOT / "ltca" / "verify" / "whole_gear.py"):
        tree = ast.parse(path.read_text())
        names = {n.module or "" for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
        names |= {a.name for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
        assert not any("gear_body" in n or "compliance" in n for n in names), (path, names)


@pytest.mark.slow
@pytest.mark.calculix
@needs_ccx
def test_whole_gear_calculix_pitch_point_bore20(tmp_path):
    """FZG C14, pinion bore 20 mm, pitch point: ours within issue 11's bounds of whole-gear CalculiX."""
    from ltca.verify.whole_check import run_whole_validation
    import json
    rc = run_whole_validation(str(CASES / "crosscheck" / "fzg_c14_bore20.toml"), [0.0], str(tmp_path), refine=0,
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
