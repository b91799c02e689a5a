"""Diagnostics through ``logging``: the library adds only a null handler; each position's rounds, widenings and
residual, the mesh cache and the run's summary (solver, convergence) reach a logger at INFO; ``ltca -v`` routes
them to stderr and a later command without it is silent again."""
from __future__ import annotations

import logging

import numpy as np
import pytest

from fixtures.paths import CASES


def test_the_library_configures_no_handler():
    import ltca  # noqa: F401
    from ltca import core, position  # noqa: F401
    handlers = logging.getLogger("ltca").handlers
    assert handlers and all(isinstance(h, logging.NullHandler) for h in handlers)
    assert not logging.getLogger("ltca.position").handlers


def _problem():
    """Two uncoupled cells (1e-4 mm/N each) on levers of 10 mm under 100 N mm, the second 2 um open: the first
    carries the 10 N and closes 1 um, the second stays open."""
    C = np.diag([1e-4, 1e-4])
    return C, np.array([0.0, 2e-3]), np.array([10.0, 10.0]), 100.0, None


def test_each_position_logs_rounds_widenings_and_residual(caplog):
    from ltca.position import solve_rounds
    grows = iter([True, False])
    with caplog.at_level(logging.INFO, logger="ltca"):
        _, sol = solve_rounds(lambda: None, lambda sy: _problem(), lambda sy, s: next(grows), 5, "test position")
    assert sol.force == pytest.approx([10.0, 0.0])
    rec = [r for r in caplog.records if r.name == "ltca.position"]
    assert len(rec) == 1 and rec[0].levelno == logging.INFO
    msg = rec[0].getMessage()
    assert "test position" in msg and "2 round(s) (1 widening(s)" in msg and "residual" in msg


def test_a_window_still_growing_after_the_last_round_is_a_warning(caplog):
    from ltca.position import solve_rounds
    with caplog.at_level(logging.INFO, logger="ltca"):
        solve_rounds(lambda: None, lambda sy: _problem(), lambda sy, s: True, 3, "test position")
    levels = [r.levelno for r in caplog.records if r.name == "ltca.position"]
    assert levels == [logging.WARNING, logging.INFO]
    assert "after 3 rounds" in caplog.records[0].getMessage()


def test_mesh_cache_miss_store_and_hit_are_logged(caplog, tmp_path):
    from ltca.fem.solids.cache import load_cached, store_cached
    from ltca.fem.solids.mesh_record import BodyMesh
    mesh = BodyMesh(np.zeros((4, 3)), np.array([[0, 1, 2, 3]]), {"bore": np.array([[0, 1, 2]])}, "k1")
    with caplog.at_level(logging.INFO, logger="ltca"):
        assert load_cached(tmp_path, "body", "k1") is None
        store_cached(tmp_path, "body", mesh)
        hit = load_cached(tmp_path, "body", "k1")
    assert hit is not None and hit.tets.tolist() == [[0, 1, 2, 3]]
    msgs = [r.getMessage() for r in caplog.records if r.name == "ltca.fem.solids.cache"]
    assert [m.split(":")[0] for m in msgs] == ["mesh cache miss", "mesh cache stored", "mesh cache hit"]
    assert "4 nodes, 1 tets" in msgs[-1]


@pytest.mark.heavy
def test_cli_verbose_routes_the_run_log_to_stderr(tmp_path, capsys):
    from ltca.cli import main
    out = tmp_path / "o"
    assert main(["run", str(CASES / "fzg_c14.toml"), "--out", str(out), "--fidelity", "coarse", "--positions", "2",
                 "--torque", "100", "--paraview-steps", "0", "--quiet", "-v"]) == 0
    err = capsys.readouterr().err
    lines = [x for x in err.splitlines() if x.startswith("ltca: ")]
    core = [x for x in lines if x.startswith("ltca: INFO: ltca.core: ")]
    # the run's two positions, then its summary (the report may solve more positions after it)
    position = [x for x in lines[:lines.index(core[0])] if x.startswith("ltca: INFO: ltca.position: contact at roll")]
    assert len(position) == 2 and all("residual" in x and "round(s)" in x for x in position)
    assert any("dofs" in x and "factorisation" in x for x in core)       # the solver of each body
    assert any("converged True" in x for x in core)
    # without -v the loggers are silent again
    assert main(["tca", str(CASES / "fzg_c14.toml")]) == 0
    assert not any(isinstance(h, logging.StreamHandler) and not isinstance(h, logging.NullHandler)
                   for h in logging.getLogger("ltca").handlers)
