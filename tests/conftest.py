"""Shared fixtures: the FZG C14 compliance is computed once per test session and reused by every
test that changes only gaps (micro-geometry, errors, misalignment, load), as the design intends."""
from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
CASES = ROOT / "cases"
REFERENCE = Path(__file__).resolve().parent / "reference"
if str(ROOT) not in sys.path:           # the maintainer tooling (tools/, not installed) is imported from the checkout
    sys.path.append(str(ROOT))


@pytest.fixture(scope="session")
def fzg_case():
    from ltca.case import load_case
    return load_case(CASES / "fzg_c14.toml")


@pytest.fixture(scope="session")
def fzg_model(fzg_case):
    from ltca.cylindrical.model import build_model
    return build_model(fzg_case)


@pytest.fixture(scope="session")
def fzg_lm(fzg_case, fzg_model, tmp_path_factory):
    """FZG C14 at the default fidelity (flank elements 0.3 m = 1.35 mm), both bodies' compliance (no factors: the
    session keeps about 0.5 GB)."""
    from ltca.case import FIDELITIES
    from ltca.cylindrical.loaded_model import Fidelity, prepare
    from ltca.cylindrical.run import cycle_rolls
    fid = Fidelity.from_preset(FIDELITIES["default"], fzg_case.module)
    return prepare(fzg_model, fid, cycle_rolls(30, 16), fzg_case.torques[0],
                   cache_dir=tmp_path_factory.mktemp("mesh")).without_solver()     # no test writes its VTU


def with_case(lm, **changes):
    """The same bodies (compliance) with another case: new gaps, same FE."""
    from ltca.cylindrical.model import build_model
    case = dataclasses.replace(lm.model.case, **changes)
    return dataclasses.replace(lm, model=build_model(case))


@pytest.fixture(scope="session")
def helical_lm(tmp_path_factory):
    """Helical C14 at the default fidelity (38 face slices on its 40 mm face), both bodies' compliance (20-60 s; no
    factors: the session keeps about 1 GB)."""
    from ltca.case import FIDELITIES, load_case
    from ltca.cylindrical.loaded_model import Fidelity, prepare
    from ltca.cylindrical.model import build_model
    from ltca.cylindrical.run import cycle_rolls
    case = load_case(CASES / "helical_c14.toml")
    fid = Fidelity.from_preset(FIDELITIES["default"], case.module)
    return prepare(build_model(case), fid, cycle_rolls(30, case.pinion.teeth), case.torques[0],
                   cache_dir=tmp_path_factory.mktemp("helical_mesh")).without_solver()   # 1.3 GB of factors freed
