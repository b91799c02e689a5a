"""The convergence and validate commands run and report what they promise."""
from __future__ import annotations

import json

import pytest

from fixtures.paths import CASES, ROOT


@pytest.mark.heavy
def test_convergence_ladder_reports_time_and_error(tmp_path, capsys):
    from ltca.verify.convergence import run_convergence
    ladder = [("coarse", "coarse", {}), ("coarse, contact cells x 2", "coarse", {"cells_per_b": 6, "slices": 12}),
              ("coarse (reference)", "coarse", {"cells_per_b": 8, "slices": 14})]
    rows = run_convergence(str(CASES / "fzg_c14.toml"), out=str(tmp_path), positions=4, progress=False,
                           ladder=ladder)
    out = capsys.readouterr().out
    assert "wall [s]" in out and "TE err" in out
    assert rows[-1]["err_te"] == 0.0 and all(r["wall_s"] > 0 for r in rows)
    # on the same compliance the contact grid moves the loaded TE by well under 1 % (measured 0.4 / 0.6 %:
    # not monotone at these sizes, the cell lattice's phase against the contact line changes with ds)
    assert rows[0]["err_te"] < 0.015 and rows[1]["err_te"] < 0.015
    # the same FE: the root stresses move only with the load distribution
    assert max(r["err_root"] for r in rows) < 0.01 and max(r["err_root_gear"] for r in rows) < 0.01
    assert json.loads((tmp_path / "convergence.json").read_text())["rungs"][0]["label"] == "coarse"
    assert (tmp_path / "convergence.png").stat().st_size > 0


#: FZG C14's largest root stress over the convergence positions at the fine fidelity, pinion and gear, MPa
FINE_ROOT = (232.1, 223.7)


@pytest.mark.slow
def test_root_stress_converges_over_the_presets(tmp_path):
    """FZG C14's largest root stress over 5 positions, coarse / default / fine: the read fillets meshed at
    0.4 / 0.4 / 0.35 of their smallest radius of curvature (fem.fillet), the nodal-averaged stress read 0.1 mm
    apart along them. Coarse and default within 3 % of the fine, pinion and gear; the fine rung within 3 % of
    :data:`FINE_ROOT` (about 100 s: slow)."""
    from ltca.verify.convergence import run_convergence
    ladder = [("coarse", "coarse", {}), ("default", "default", {}), ("fine (reference)", "fine", {})]
    rows = run_convergence(str(CASES / "fzg_c14.toml"), out=str(tmp_path), positions=4, progress=False, ladder=ladder)
    for r in rows[:-1]:
        assert r["err_root"] < 0.03 and r["err_root_gear"] < 0.03, (r["label"], r["root"], r["root_gear"])
    assert rows[-1]["root"] == pytest.approx(FINE_ROOT[0], rel=0.03)
    assert rows[-1]["root_gear"] == pytest.approx(FINE_ROOT[1], rel=0.03)


@pytest.mark.slow
def test_validate_command_passes(tmp_path, capsys):
    from ltca.verify.validate import run_validate
    assert run_validate(out=str(tmp_path)) == 0
    out = capsys.readouterr().out
    assert "pitch point p0 with near field" in out
    assert (tmp_path / "validation.csv").exists()


@pytest.mark.parametrize("option", ["--freeze", "--merge", "--ladder", "--refine", "--pressure-ladder"])
def test_validate_leaves_ladders_and_frozen_references_to_the_tooling(option, capsys):
    """The options of CalculiX's ladders and of the frozen references are not ``ltca validate``'s (exit 2, argparse);
    the maintainer tooling's scripts have them."""
    from ltca.cli import main
    with pytest.raises(SystemExit) as exc:
        main(["validate", "--reference", "calculix-whole", option, "1"])
    assert exc.value.code == 2 and option in capsys.readouterr().err


@pytest.mark.parametrize("args,field", [(["--reference", "calculix", "--level", "9"], "--level"),
                                        (["--reference", "calculix", "--case", "cases/spiral_bevel_cao2008.toml",
                                          "--level", "9"], "--level"),
                                        (["--reference", "calculix", "--case", "cases/spiral_bevel_cao2008.toml",
                                          "--positions", "3"], "--positions")])
def test_calculix_checks_name_a_bad_argument_before_ccx(args, field, tmp_path, capsys, monkeypatch):
    """A bad argument of the one-run CalculiX checks exits 2 naming the option, whether or not ccx is installed."""
    from ltca.cli import main
    monkeypatch.chdir(ROOT)
    assert main(["validate", *args, "--out", str(tmp_path), "--quiet"]) == 2
    assert field in capsys.readouterr().err


@pytest.mark.parametrize("script", ["freeze_whole", "merge_whole", "freeze_bevel", "recompare_bevel",
                                    "freeze_planetary", "ladder_cylindrical"])
def test_tooling_scripts_run_from_the_checkout(script):
    """Every script of tools/calculix_refs runs as ``python3 -m tools.calculix_refs.<script>`` from the repository
    root: ``--help`` exits 0 (recompare_bevel without its FILE NOTE: 2, with its usage)."""
    import subprocess
    import sys
    proc = subprocess.run([sys.executable, "-m", f"tools.calculix_refs.{script}", "--help"], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    if script == "recompare_bevel":
        assert proc.returncode == 2 and "FILE NOTE" in proc.stderr
    else:
        assert proc.returncode == 0 and f"tools.calculix_refs.{script}" in proc.stdout, proc.stderr


def test_freeze_names_a_bad_argument_before_ccx(tmp_path, capsys):
    """The freeze scripts check their arguments before looking for ccx: exit 2 with the option named."""
    from tools.calculix_refs import freeze_bevel, freeze_whole
    assert freeze_whole.main(["--case", str(CASES / "fzg_c14.toml"), "--positions", "40", "--out", str(tmp_path)]) == 2
    assert "--positions" in capsys.readouterr().err
    assert freeze_whole.main(["--case", str(CASES / "fzg_c14.toml"), "--ladder", "finer", "--refine", "5",
                              "--out", str(tmp_path)]) == 2
    assert "--refine" in capsys.readouterr().err
    assert freeze_bevel.main(["--level", "2", "--refine", "1", "--out", str(tmp_path)]) == 2
    assert "--refine" in capsys.readouterr().err
