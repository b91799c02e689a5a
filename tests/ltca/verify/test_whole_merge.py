"""``python3 -m tools.calculix_refs.merge_whole FILE``: refining chosen positions of a frozen whole-gear
reference keeps the rest of the file, without ccx (CalculiX is replaced by a stand-in)."""
from __future__ import annotations

import dataclasses
import json
import shutil

import pytest

from fixtures.paths import CASES, ROOT

FROZEN = ROOT / "tests" / "reference" / "fzg_c14_calculix_whole.json"


def test_merge_argument_errors_before_ccx(tmp_path, capsys):
    """A position the file does not hold, or a missing file, exits 2 with the option named."""
    from tools.calculix_refs.merge_whole import main
    ref = tmp_path / "ref.json"
    shutil.copy(FROZEN, ref)
    base = ["--case", str(CASES / "fzg_c14.toml"), "--out", str(tmp_path)]
    assert main([str(ref)] + base + ["--positions", "-3"]) == 2 and "--positions" in capsys.readouterr().err
    assert main([str(tmp_path / "none.json")] + base + ["--positions", "-9"]) == 2
    assert "FILE" in capsys.readouterr().err
    assert ref.read_bytes() == FROZEN.read_bytes()


def test_rung_settings_and_ladder_change():
    """A merged rung scales the frozen band, its half-width beyond the band, the penalty and the fillets as the
    freeze's ladder does (the 0 deg 100 um rung of FZG C14 is the -9 deg 150 um run refined once)."""
    from ltca.verify.whole_gear import whole_settings
    from tools.calculix_refs.merge_whole import ladder_change, ladder_key, rung_settings
    rec = json.loads(FROZEN.read_text())
    at_150 = next(p for p in rec["convergence"] if round(p["h_contact_um"]) == 150)
    at_100 = next(p for p in rec["convergence"] if round(p["h_contact_um"]) == 100)
    base = whole_settings(0.2, 4.5, None, threads=1)
    st = rung_settings(base, at_150, 1)
    assert {k: getattr(st, k) for k in at_100["mesh_sizes_mm"]} == at_100["mesh_sizes_mm"]
    assert st.penalty == at_100["penalty_mpa_per_mm"] and st.halo == base.halo
    moved = ladder_change([at_150, at_100])
    assert moved["flank_pressure"] == pytest.approx(1433.614 / 1506.022 - 1, abs=1e-6)
    assert moved["bands_um"] == [at_150["h_contact_um"], at_100["h_contact_um"]] and ladder_change([at_100]) == {}
    assert ladder_key(-9.0) == "-9" and ladder_key(-4.5) == "-4.5"


@pytest.mark.heavy
def test_merge_keeps_the_frozen_ladder_and_other_positions(tmp_path, monkeypatch):
    """Merging -4.5 deg replaces that position by its run one rung finer than its frozen one, with our figures, and
    extends its ladder (the frozen run before it); the first position's ladder, the other positions and the original
    command stay."""
    import ltca.fem.calculix.run as ccx_run
    from ltca.verify.whole_gear import WholeResult
    from tools.calculix_refs import merge_whole as whole_merge

    def fake(lm, roll, torque, st, workdir, say=print):
        info = {"nodes": 2, "elements": 1, "nodes_pinion": 1, "nodes_gear": 1, "h_contact_mm": st.h_contact,
                "settings": dataclasses.asdict(st), "ccx_wall": 1.0, "mesh_wall": 1.0, "deck_sha256": "a" * 64,
                "p_flank": 1500.0}
        root = {m: {"max": 230.0, "per_tooth": {"0": 230.0}, "at": {"z_mm": 0.0}, "surface": {"max": 240.0}}
                for m in ("pinion", "gear")}
        return WholeResult(roll, 117.5, {0: 5912.0}, 14.7, 1500.0, 2.0, info, root)
    monkeypatch.setattr(ccx_run, "ccx_path", lambda: "ccx")
    monkeypatch.setattr(whole_merge, "solve_whole", fake)
    monkeypatch.setattr(whole_merge, "ccx_version", lambda: "This is Version 0")
    ref = tmp_path / "ref.json"
    shutil.copy(FROZEN, ref)
    before = json.loads(ref.read_text())
    assert whole_merge.run_whole_merge(str(CASES / "fzg_c14.toml"), [-4.5], str(tmp_path), str(ref), threads=1,
                                       command="python3 -m tools.calculix_refs.merge_whole x",
                                       progress=False) == 0
    after = json.loads(ref.read_text())
    assert after["convergence"] == before["convergence"] and after["command"] == before["command"]
    i = next(i for i, p in enumerate(before["positions"]) if p["roll_deg"] == -4.5)
    assert [p for j, p in enumerate(after["positions"]) if j != i] == [p for j, p in enumerate(before["positions"])
                                                                       if j != i]
    prior = before.get("ladders", {}).get("-4.5") or [{k: v for k, v in before["positions"][i].items()
                                                        if k != "ours_at_freeze"}]
    ladder = after["ladders"]["-4.5"]
    assert ladder[:-1] == prior and ladder[-2] == {k: v for k, v in before["positions"][i].items()
                                                   if k != "ours_at_freeze"}
    assert ladder[-1]["h_contact_um"] == pytest.approx(prior[-1]["h_contact_um"] / 1.5)
    assert ladder[-1]["flank_pressure"] == 1500.0
    new = after["positions"][i]
    assert {k: v for k, v in new.items() if k != "ours_at_freeze"} == ladder[-1]
    assert set(new["ours_at_freeze"]) == {"te", "stiffness", "share", "flank_pressure", "root_pinion", "root_gear"}
    assert after["merged"][-1]["positions"] == ["-4.5"] and after["merged"][-1]["refine"] == 1


@pytest.mark.heavy
def test_the_check_runs_once_per_position_and_the_freeze_adds_its_ladder(tmp_path, monkeypatch, capsys):
    """``ltca validate --reference calculix-whole`` runs CalculiX once per position at the base band; the freeze
    script adds the ladder at the first position (``--refine 1 --ladder both``: 1.5, 1, 1/1.5 of the band) and
    writes a reference that records its command, the ladder and our figures (CalculiX replaced by a stand-in)."""
    import ltca.fem.calculix.run as ccx_run
    from ltca.verify import whole_check
    from ltca.verify.whole_gear import WholeResult
    from tools.calculix_refs import freeze_whole
    runs = []

    def fake(lm, roll, torque, st, workdir, say=print):
        runs.append((roll, round(1e3 * st.h_contact, 3)))
        info = {"nodes": 2, "elements": 1, "nodes_pinion": 1, "nodes_gear": 1, "h_contact_mm": st.h_contact,
                "settings": dataclasses.asdict(st), "ccx_wall": 1.0, "mesh_wall": 1.0, "deck_sha256": "a" * 64,
                "p_flank": 1500.0}
        root = {m: {"max": 230.0, "per_tooth": {"0": 230.0}, "at": {"z_mm": 0.0}} for m in ("pinion", "gear")}
        return WholeResult(roll, 117.5, {0: 5912.0}, 14.7, 1500.0, 2.0, info, root)
    monkeypatch.setattr(ccx_run, "ccx_path", lambda: "ccx")
    monkeypatch.setattr(whole_check, "solve_whole", fake)
    monkeypatch.setattr(freeze_whole, "solve_whole", fake)
    monkeypatch.setattr(freeze_whole, "ccx_version", lambda: "This is Version 0")
    case = str(CASES / "fzg_c14.toml")
    whole_check.run_whole_validation(case, [0.0, -9.0], str(tmp_path / "check"), band_um=150.0, progress=False)
    assert runs == [(0.0, 150.0), (-9.0, 150.0)]
    assert (tmp_path / "check" / "whole_gear.csv").read_text().count("\n") == 3
    runs.clear()
    ref = tmp_path / "ref.json"
    assert freeze_whole.main([str(ref), "--case", case, "--positions", "0", "-9", "--band", "150", "--refine", "1",
                              "--ladder", "both", "--out", str(tmp_path / "freeze"), "--quiet"]) in (0, 1)
    assert runs == [(0.0, 150.0), (-9.0, 150.0), (0.0, 225.0), (0.0, 150.0), (0.0, 100.0), (-9.0, 150.0)]
    rec = json.loads(ref.read_text())
    assert rec["command"].startswith("python3 -m tools.calculix_refs.freeze_whole " + str(ref))
    assert [e["h_contact_um"] for e in rec["convergence"]] == pytest.approx([225.0, 150.0, 100.0])
    assert [p["h_contact_um"] for p in rec["positions"]] == pytest.approx([100.0, 150.0])
    assert set(rec["positions"][0]["ours_at_freeze"]) == {"te", "stiffness", "share", "flank_pressure",
                                                          "root_pinion", "root_gear"}
