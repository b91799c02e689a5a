"""Our planetary LTCA against a frozen whole-gear CalculiX reference, no ccx at test time.

``tests/reference/eccentric_planetary_calculix.json`` was computed by ``python3 -m tools.calculix_refs.freeze_planetary
FILE --case cases/eccentric_planetary_satellite.toml --torque ... --positions ...`` (the command, CalculiX
version, date, mesh sizes, nodes and elements, deck hashes, wall times and the contact-band ladder are stored in
it): both gears whole with every tooth (:mod:`ltca.fem.solids.full_gear`, the wheel internal), the wheel held at its
outer diameter, the satellite bore on a rigid body turning about the satellite axis, penalty contact on every
tooth that could close (:mod:`ltca.verify.planetary_whole`), each wheel band split at its tip corner (the corner
zone a slave against the satellite's flank and fillet). The torque is chosen so that at least 5 pairs carry
load (at the rated 264 N m our model loads 2-3). Bounds: loaded TE 3 %, every pair's share 0.03. A
check the frozen reference records outside its bound stays a strict xfail naming the numbers, not a looser bound.
The TE bound fails when our Young's modulus is raised by 5 % (our TE then 5.2 % off CalculiX's).
"""
from __future__ import annotations

import json

import pytest

from fixtures.paths import REFERENCE as REFERENCE_DIR
from fixtures.paths import ROOT

REFERENCE = REFERENCE_DIR / "eccentric_planetary_calculix.json"
BOUNDS = {"te_rel": 0.03, "share_abs": 0.03}
_OURS: dict = {}


@pytest.fixture(scope="module", autouse=True)
def _release_model():
    """Our model (about 2 GB without its factor) lives as long as this module's tests, not the whole session."""
    yield
    _OURS.clear()


def _rec() -> dict:
    return json.loads(REFERENCE.read_text())


def _model():
    """Our model of the reference's case at its torque and fidelity (built once)."""
    if "lm" not in _OURS:
        from ltca.planetary.case import load_planetary_case
        from ltca.verify.planetary_whole import prepare_ours
        rec = _rec()
        case = load_planetary_case(ROOT / rec["case"])
        # no VTU here: each body's factor (3-4 GB) freed as soon as its compliance is known
        _OURS["sm"], _OURS["lm"] = prepare_ours(case, [r["phi_deg"] for r in rec["rows"]], 1e3 * rec["torque_nm"],
                                                rec["fidelity"], keep_solver=False)
    return _OURS["sm"], _OURS["lm"]


def _ours(phi_deg: float) -> dict:
    if phi_deg not in _OURS:
        from ltca.verify.planetary_whole import solve_ours
        sm, lm = _model()
        _OURS[phi_deg] = solve_ours(sm, lm, phi_deg, 1e3 * _rec()["torque_nm"])
    return _OURS[phi_deg]


def _share_diff(a: dict, b: dict) -> float:
    return max(abs(a.get(k, 0.0) - b.get(k, 0.0)) for k in set(a) | set(b))


def test_internal_full_gear_is_the_ring_held_at_its_outer_diameter():
    """The wheel of the CalculiX model: every internal tooth, the outer cylinder (``rim``) at the housing radius."""
    import numpy as np

    from ltca.fem.solids.full_gear import FullGearSpec, build_full_gear
    from ltca.planetary.case import load_planetary_case
    from ltca.planetary.model import build_satellite_model
    case = load_planetary_case(ROOT / "cases" / "eccentric_planetary_satellite.toml")
    w = build_satellite_model(case).pair.gear
    m = build_full_gear(FullGearSpec(w.xy, w.kind, w.side, w.z, 95.0, 20.0, loaded_teeth=(0,), h_flank=2.0,
                                     h_tooth=4.0, h_body=8.0, ds=0.8, internal=True))
    assert {int(n.split("_")[1]) for n in m.facets if n.startswith("flank_")} == set(range(-25, 26))
    rim = m.nodes[np.unique(m.facets["rim"][:, :3])]
    assert "bore" not in m.facets and np.allclose(np.hypot(rim[:, 0], rim[:, 1]), 95.0, atol=1e-6)
    r = np.hypot(m.nodes[:, 0], m.nodes[:, 1])
    assert r.min() == pytest.approx(w.r_tip, abs=0.01) and r.max() == pytest.approx(95.0, abs=1e-6)
    with pytest.raises(ValueError, match="r_bore"):
        FullGearSpec(w.xy, w.kind, w.side, w.z, 60.0, 20.0, internal=True)


@pytest.mark.parametrize("args,field", [(["--torque", "3000", "--positions", "5"], "--positions"),
                                        (["--positions", "-1.8"], "--torque"),
                                        (["--torque", "-1", "--positions", "-1.8"], "--torque"),
                                        (["--torque", "3000", "--band", "10"], "--band")])
def test_planetary_check_bad_input_exits_2_naming_the_field(args, field, tmp_path, capsys):
    from ltca.cli import main
    code = main(["validate", "--reference", "calculix-whole", "--case",
                 str(ROOT / "cases" / "eccentric_planetary_satellite.toml"), "--out", str(tmp_path), "--quiet", *args])
    assert code == 2 and field in capsys.readouterr().err


def test_reference_records_its_provenance():
    rec = _rec()
    assert "Version" in rec["calculix_version"] and rec["date"]
    assert rec["command"].startswith(("python3 -m tools.calculix_refs.freeze_planetary",    # the command that made it
                                      "ltca validate --reference calculix-whole --case cases/eccentric_planetary"))
    assert rec["bounds"] == BOUNDS
    assert len(rec["refinement"]) >= 2, "a frozen reference needs its contact-band refinement"
    for c in [r["ccx"] for r in rec["rows"]] + rec["refinement"]:
        assert len(c["deck_sha256"]) == 64 and c["nodes"] > 0 and c["elements"] > 0 and c["h_contact_um"] > 0
        assert c["ccx_wall_s"] > 0 and abs(sum(c["share"].values()) - 1) < 1e-9


def test_fidelity_caps_the_contact_cell_across_the_line():
    """Cells are half_width / cells_per_b wide, at most ds_max (x module in the presets): a tip edge's gap kink."""
    from ltca.case import FIDELITIES
    from ltca.cylindrical.loaded_model import Fidelity
    fid = Fidelity.from_preset(FIDELITIES["coarse"], 3.0)
    assert fid.ds_max == pytest.approx(0.12) and fid.cell_size(0.3) == pytest.approx(0.1)
    assert fid.cell_size(2.5) == pytest.approx(0.12)
    assert Fidelity.from_preset(FIDELITIES["coarse"], 3.0, ds_max=0.0).cell_size(2.5) == pytest.approx(2.5 / 3)


@pytest.mark.slow      # our 32 + 32-tooth model of the reference: about 5 min and 8 GB
def test_ours_resolves_the_wheel_tip_corner_of_pair_minus_8():
    """Satellite tooth -8 touches at the wheel's tip corner (exact unloaded gap 28.5 um beyond first contact, at
    r1 = 72.36 mm): cells of at most 0.04 module (:meth:`ltca.cylindrical.loaded_model.Fidelity.cell_size`) resolve
    that gap kink; the uncapped cells of half_width / 3 = 0.83 mm (b = 2.50 mm, nearly conformal) miss it and
    about halve the pair's share. Both lattices are checked, 5 % on the share and 1 % on the TE."""
    import dataclasses

    from ltca.verify.planetary_whole import solve_ours
    sm, lm = _model()
    o = _ours(-1.8)
    assert o["share"]["-8"] == pytest.approx(0.1020, rel=0.05) and o["te_um"] == pytest.approx(53.19, rel=0.01)
    coarse = dataclasses.replace(lm, fid=dataclasses.replace(lm.fid, ds_max=0.0))
    u = solve_ours(sm, coarse, -1.8, 1e3 * _rec()["torque_nm"])
    assert u["share"]["-8"] == pytest.approx(0.0547, rel=0.05) and u["te_um"] == pytest.approx(55.15, rel=0.01)


@pytest.mark.slow      # our 32 + 32-tooth model of the reference: about 5 min and 8 GB
def test_calculix_internal_pairs_split_the_wheel_band_at_its_tip_corner(tmp_path):
    """The CalculiX deck of the internal pair (no ccx): every tooth's wheel band is split in two, the tip-corner
    zone (tip land and the flank's first rows, radius < r_tip + max(CORNER, 2 h)) a slave against the satellite's
    flank and fillet, the rest the master of the satellite's flank and tip; the two zones share no facet."""
    import numpy as np

    import ltca.verify.whole_gear as wg
    from ltca.verify.planetary_whole import planetary_settings

    class _Written(Exception):
        pass

    def stop(*a, **k):
        raise _Written
    sm, lm = _model()
    st = planetary_settings(lm.b_nom, sm.pair.pinion.m_n, 1200.0)
    real, built = wg.write_deck, {}

    def keep(path, bodies, deck):
        built.update(bodies=bodies, deck=deck)
        return real(path, bodies, deck)
    mp = pytest.MonkeyPatch()
    mp.setattr(wg, "run_ccx", stop)
    mp.setattr(wg, "write_deck", keep)
    with pytest.raises(_Written):
        wg.solve_whole(lm, -1.8, 3e6, st, tmp_path, say=lambda m: None)
    mp.undo()
    m1, m2 = (b.mesh for b in built["bodies"])
    r_tip, zone = sm.pair.gear.r_tip, max(wg.CORNER, 2 * st.h_contact)
    radius = lambda m, f: np.hypot(*m.nodes[f[:, :3]].mean(axis=1)[:, :2].T)   # noqa: E731
    pairs = built["deck"].pairs
    corner = [p for p in pairs if p.name.startswith("W")]
    assert len(corner) >= 3 and all(p.slave[0] == "gear" and p.master[0] == "pinion" for p in corner)
    rows = lambda f: set(map(tuple, np.sort(f, axis=1)))                                # noqa: E731
    fillet = 0
    for p in corner:
        slave, master = m2.facets[p.slave[1][0]], m1.facets[p.master[1][0]]
        k = int(p.slave[1][0].split("_")[1])
        assert len(slave) and radius(m2, slave).max() < r_tip + zone
        band = m2.facets[f"band_{k}"]
        assert radius(m2, band).min() >= r_tip + zone and not rows(band) & rows(slave)
        fillet += len(rows(m1.facets[f"fillet_{k}_right"]) & rows(master))
    assert fillet > 0, "the satellite's fillet (below the form circle) is part of the corner pairs' master"
    assert all(p.slave[0] == "pinion" for p in pairs if p.name.startswith("P"))
    from ltca.fem.calculix.deck import ContactPairSpec
    two = [ContactPairSpec("W0", ("gear", ("a",)), ("pinion", ("b",))),
           ContactPairSpec("P0", ("pinion", ("c",)), ("gear", ("d",)))]
    loads = wg.tooth_loads({"W0": np.array([3.0, 0, 0]), "P0": np.array([-1.0, 0, 0])}, two, [-9, -9], (-9, -8))
    assert loads == {-9: pytest.approx(4.0), -8: 0.0}


def test_calculix_has_at_least_five_pairs_in_contact():
    """The check is multi-pair: CalculiX at one position with >= 5 pairs carrying load."""
    assert max(r["ccx"]["loaded_pairs"] for r in _rec()["rows"]) >= 5


@pytest.mark.slow      # our 32 + 32-tooth model of the reference: about 5 min and 8 GB
def test_ours_has_at_least_five_loaded_pairs():
    """At the reference's torque and position our LTCA loads at least 5 pairs (share >= 0.1 % each)."""
    rec = _rec()
    assert max(_ours(r["phi_deg"])["loaded_pairs"] for r in rec["rows"]) >= 5


def _known_out() -> dict:
    out = {}
    for i, r in enumerate(_rec()["rows"] if REFERENCE.exists() else []):
        o, c = r["ours"], r["ccx"]
        if abs(o["te_um"] / c["te_um"] - 1) > BOUNDS["te_rel"]:
            out[(i, "te")] = f"TE ours {o['te_um']:.2f} vs CalculiX {c['te_um']:.2f} um"
        if _share_diff(o["share"], c["share"]) > BOUNDS["share_abs"]:
            nz = lambda d: {k: round(v, 3) for k, v in d.items() if v >= 5e-4}      # noqa: E731
            out[(i, "share")] = f"share ours {nz(o['share'])} vs CalculiX {nz(c['share'])}"
    return out


def _cases():
    known = _known_out()
    rows = _rec()["rows"] if REFERENCE.exists() else []
    return [pytest.param(i, q, marks=[pytest.mark.xfail(strict=True, reason=known[(i, q)])] if (i, q) in known else [],
                         id=f"{r['phi_deg']:+.2f}-{q}") for i, r in enumerate(rows) for q in ("te", "share")]


@pytest.mark.slow          # our 32 + 32-tooth model of the reference: about 5 min and 8 GB
@pytest.mark.parametrize("index,quantity", _cases())
def test_ours_against_frozen_calculix(index, quantity):
    """Loaded TE within 3 % and every pair's load share within 0.03 of the frozen CalculiX values."""
    ref = _rec()["rows"][index]
    o, c = _ours(ref["phi_deg"]), ref["ccx"]
    if quantity == "te":
        assert o["te_um"] == pytest.approx(c["te_um"], rel=BOUNDS["te_rel"])
    else:
        assert _share_diff(o["share"], c["share"]) <= BOUNDS["share_abs"]


@pytest.mark.slow
@pytest.mark.calculix
def test_regenerated_reference_matches_stored(tmp_path):
    """Rerun CalculiX at the coarsest rung of the stored ladder: the same TE (0.5 %) and shares (0.005)."""
    import shutil
    if shutil.which("ccx") is None:
        pytest.skip("CalculiX (ccx) missing")
    from ltca.verify.planetary_whole import planetary_settings
    from ltca.verify.whole_gear import solve_whole
    rec = _rec()
    first = rec["refinement"][0]
    sm, lm = _model()
    st = planetary_settings(lm.b_nom, sm.pair.pinion.m_n, first["h_contact_um"])
    c = solve_whole(lm, rec["rows"][0]["phi_deg"], 1e3 * rec["torque_nm"], st, tmp_path, say=lambda m: None)
    te_um = 1e3 * sm.pair.pinion.r_base * (c.info["theta"] - c.info["theta0"])
    assert te_um == pytest.approx(first["te_um"], rel=0.005)
    assert _share_diff({str(k): v for k, v in c.share(sorted(c.pair_load)).items()}, first["share"]) < 0.005
