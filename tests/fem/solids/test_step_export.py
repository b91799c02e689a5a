"""Solid models (``ltca export CASE --step DIR``): each member with every tooth as a STEP solid.

The STEP file is read back in gmsh (OpenCASCADE) and its volume compared with two independent figures: the
FE body's with every tooth, from our mesh record (gmsh tetrahedra of the cylindrical body; the mapped bevel body,
blank plus z teeth), within 0.5 %; and for a spur gear the exact figure, the area of the generated transverse
outline (every tooth, a dense polygon) less the bore, times the face width.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[3]
pytest.importorskip("gmsh")


def _outline_area(spec) -> float:
    """Area inside the whole gear's transverse outline (the profile turned to every tooth), mm^2."""
    xy = np.asarray(spec.outline, float)
    P = np.concatenate([xy @ np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])
                        for a in -2 * np.pi * np.arange(spec.z) / spec.z])
    return 0.5 * abs(float(np.sum(P[:, 0] * np.roll(P[:, 1], -1) - np.roll(P[:, 0], -1) * P[:, 1])))


def _check(name: str, tmp_path: Path) -> list[tuple[str, float, float]]:
    from ltca.export import export_step, fe_body_volume, member_solids
    from ltca.fem.solids.step import step_volume
    res = export_step(name, tmp_path)
    out = []
    for ms, em in zip(member_solids(name), res.members):
        assert em.path.is_file() and em.path.suffix == ".step" and em.z == ms.z
        vol, n = step_volume(em.path)            # opens in gmsh: one solid
        assert n == 1 and vol == pytest.approx(em.volume, rel=1e-9)
        fe = fe_body_volume(ms)
        out.append((ms.member, vol, fe))
        assert vol == pytest.approx(fe, rel=5e-3), (name, ms.member, vol, fe)
    return out


@pytest.mark.heavy
def test_spur_pair_step_volume(tmp_path):
    """FZG C14 (spur): each member's STEP volume is the outline area less the bore times the face width (to the
    spline fit, 1e-4) and the FE body's within 0.5 %."""
    from ltca.export import member_solids
    rows = _check("fzg_c14", tmp_path)
    for ms, (_, vol, _) in zip(member_solids("fzg_c14"), rows):
        exact = (_outline_area(ms.spec) - np.pi * ms.spec.r_bore ** 2) * ms.spec.face_width
        assert vol == pytest.approx(exact, rel=1e-4)


def _shipped_pairs() -> list[str]:
    """The shipped cylindrical and bevel cases, one per distinct geometry (variants differ in load and errors)."""
    from ltca.cases import load_case
    from ltca.shipped import cases_dir
    seen, out = set(), []
    for f in sorted(cases_dir().glob("*.toml")):
        c = load_case(f)
        if c.kind not in ("cylindrical", "bevel"):
            continue
        key = (c.kind, repr({k: v for k, v in c.data.items() if k in ("gear_pair", "pinion", "gear", "bevel")}))
        if key not in seen:
            seen.add(key)
            out.append(f.stem)
    return out


@pytest.mark.slow
@pytest.mark.parametrize("name", _shipped_pairs())
def test_every_shipped_pair_step_volume(name, tmp_path):
    """Every shipped pair's STEP solids (a bevel member fuses its teeth one at a time: minutes) against the FE
    bodies, within 0.5 %."""
    _check(name, tmp_path)


def test_export_command_bad_input(tmp_path):
    """A case of another kind and a missing --step: exit 2 with one line, no traceback."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    for args in (["budget_wang", "--step", str(tmp_path)], ["fzg_c14"]):
        p = subprocess.run([sys.executable, "-m", "ltca.cli", "export", *args], capture_output=True, text=True,
                           env=env, cwd=str(ROOT), timeout=120, check=False)
        assert p.returncode == 2, p.stderr
        assert "Traceback" not in p.stderr and p.stderr.startswith("ltca export")
