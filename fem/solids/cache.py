"""Mesh cache: a meshed solid stored as ``<prefix>_<spec_hash>.npz`` and reloaded on a hit."""
from __future__ import annotations

import logging
import os
import time
from pathlib import Path

import numpy as np

from .mesh_record import BodyMesh

__all__ = ["load_cached", "store_cached"]

log = logging.getLogger(__name__)


def load_cached(cache_dir, prefix: str, key: str) -> BodyMesh | None:
    """The mesh stored as ``<prefix>_<key>.npz`` in ``cache_dir``, or None (no cache, or a miss)."""
    if cache_dir is None:
        return None
    t0 = time.perf_counter()
    path = Path(cache_dir) / f"{prefix}_{key}.npz"
    if not path.exists():
        log.info("mesh cache miss: %s (meshing)", path)
        return None
    with np.load(path) as d:
        facets = {k[len("facet__"):]: d[k] for k in d.files if k.startswith("facet__")}
        hexes = d["hexes"] if "hexes" in d.files else None
        mesh = BodyMesh(d["nodes"], d["tets"], facets, key, time.perf_counter() - t0, hexes)
    log.info("mesh cache hit: %s (%d nodes, %d tets, %.2f s)", path, len(mesh.nodes), len(mesh.tets), mesh.seconds)
    return mesh


def store_cached(cache_dir, prefix: str, mesh: BodyMesh) -> None:
    """Store ``mesh`` as ``<prefix>_<spec_hash>.npz`` in ``cache_dir`` (a temporary name, then renamed)."""
    if cache_dir is None:
        return
    path = Path(cache_dir) / f"{prefix}_{mesh.spec_hash}.npz"
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(f".tmp{os.getpid()}.npz")
    extra = {} if mesh.hexes is None else {"hexes": mesh.hexes}
    np.savez(tmp, nodes=mesh.nodes, tets=mesh.tets, **extra, **{f"facet__{k}": v for k, v in mesh.facets.items()})
    os.replace(tmp, path)
    log.info("mesh cache stored: %s", path)
