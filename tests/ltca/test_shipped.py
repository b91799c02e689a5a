"""Shipped cases found by name (ltca.shipped): a path, a stem, a name under the case folder, an unknown name."""
from __future__ import annotations

import pytest

from ltca.errors import CaseError
from ltca.shipped import case_path, shipped_cases, shipped_studies, study_path


def test_names_and_paths(tmp_path):
    names = shipped_cases()
    assert {"fzg_c14", "spiral_bevel_cao2008", "crosscheck/fzg_c14_bore20"} <= set(names)
    assert case_path("fzg_c14").name == "fzg_c14.toml" and case_path("fzg_c14").is_file()
    assert case_path("fzg_c14.toml") == case_path("cases/fzg_c14") == case_path("fzg_c14")
    assert case_path("crosscheck/fzg_c14_bore20").parent.name == "crosscheck"
    assert case_path("fzg_c14_bore20") == case_path("crosscheck/fzg_c14_bore20")
    own = tmp_path / "fzg_c14.toml"          # an existing file wins over a shipped name
    own.write_text("")
    assert case_path(own) == own and case_path(str(own)) == own
    assert "fzg_torque_misalignment" in shipped_studies()
    assert study_path("fzg_torque_misalignment").is_file()


def test_unknown_name_lists_the_shipped_cases():
    with pytest.raises(CaseError) as exc:
        case_path("fzg_c15")
    msg = str(exc.value)
    assert "'CASE'" in msg and "'fzg_c15'" in msg and "fzg_c14" in msg and "spiral_bevel_cao2008" in msg


def test_cli_unknown_case_exits_2(capsys):
    from ltca.cli import main
    assert main(["tca", "no_such_case"]) == 2
    err = capsys.readouterr().err
    assert "no_such_case" in err and "fzg_c14" in err and "Traceback" not in err
