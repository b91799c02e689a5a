"""A gear body meshed in a child process (fem.solids.mesh_job): the very mesh of the calling process, a cached body
without a child, the body meshed here when the child fails, a running child killed by cancel."""
from __future__ import annotations

import logging
import time

import numpy as np
import pytest


@pytest.fixture(scope="module")
def spec(fzg_model):
    from ltca.fem.solids import GearBodySpec
    p = fzg_model.pinion
    return GearBodySpec(np.asarray(p.xy), np.asarray(p.kind, np.int8), np.asarray(p.side, np.int8), p.z, (-1, 0, 1),
                        15.0, 14.0, h_flank=2.0, h_body=6.0)


def _same(a, b) -> bool:
    return (np.array_equal(a.nodes, b.nodes) and np.array_equal(a.tets, b.tets) and a.facets.keys() == b.facets.keys()
            and all(np.array_equal(a.facets[k], b.facets[k]) for k in a.facets) and a.spec_hash == b.spec_hash)


def test_child_mesh_is_the_mesh_made_here(spec, tmp_path):
    from ltca.fem.solids import build_gear_body
    from ltca.fem.solids.mesh_job import BodyMeshJob
    job = BodyMeshJob(spec, tmp_path)
    assert job._proc is not None                      # meshed by a child, not loaded or meshed here
    mesh = job.result()
    assert job._proc.returncode == 0 and _same(mesh, build_gear_body(spec))
    assert (tmp_path / f"body_{spec.spec_hash}.npz").exists()           # the child stored it in the cache
    again = BodyMeshJob(spec, tmp_path)
    assert again._proc is None and _same(again.result(), mesh)          # a cached body needs no child


def test_failed_child_meshes_here(spec, monkeypatch, caplog):
    from ltca.fem.solids import build_gear_body, mesh_job
    monkeypatch.setattr(mesh_job, "_CHILD", "import sys; sys.exit('no gmsh here')")
    with caplog.at_level(logging.WARNING, logger=mesh_job.__name__):
        mesh = mesh_job.BodyMeshJob(spec).result()
    assert _same(mesh, build_gear_body(spec))
    assert "exited with 1 (no gmsh here)" in caplog.text


def test_cancel_kills_a_running_child(spec, monkeypatch):
    from ltca.fem.solids import mesh_job
    monkeypatch.setattr(mesh_job, "_CHILD", "import time; time.sleep(60)")
    job = mesh_job.BodyMeshJob(spec)
    t0 = time.perf_counter()
    job.cancel()
    assert job._proc.returncode is not None and job._proc.returncode < 0 and time.perf_counter() - t0 < 10
