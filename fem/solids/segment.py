"""Tooth-segment solids of cylindrical gears meshed by gmsh, with a mesh cache keyed by the spec's hash.

The section comes from :mod:`fem.solids.section`, the gmsh construction from :mod:`fem.solids.segment_gmsh`;
the records and conventions are those of :mod:`fem.solids.spec`.
"""
from __future__ import annotations

import os
import time
from pathlib import Path

import numpy as np

from .segment_gmsh import mesh_with_gmsh
from .session import gmsh_session
from .spec import SegmentMesh, SegmentSpec

__all__ = ["build_segment"]


def build_segment(spec: SegmentSpec, cache_dir: str | os.PathLike | None = None,
                  progress: bool = False) -> SegmentMesh:
    """Mesh a tooth segment with graded (quadratic) tetrahedra.

    Parameters
    ----------
    spec : SegmentSpec
        Geometry and mesh sizes.
    cache_dir : path, optional
        If given, meshes are stored there as ``segment_<spec_hash>.npz`` and reloaded on a hit.
    progress : bool
        Let gmsh print to the terminal.

    Returns
    -------
    SegmentMesh
    """
    t0 = time.perf_counter()
    key = spec.spec_hash
    path = None
    if cache_dir is not None:
        path = Path(cache_dir) / f"segment_{key}.npz"
        if path.exists():
            with np.load(path) as d:
                facets = {k[len("facet__"):]: d[k] for k in d.files if k.startswith("facet__")}
                return SegmentMesh(d["nodes"], d["tets"], facets, key, time.perf_counter() - t0)
    with gmsh_session(progress):
        nodes, tets, facets = mesh_with_gmsh(spec)
    mesh = SegmentMesh(nodes, tets, facets, key, time.perf_counter() - t0)
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".tmp{os.getpid()}.npz")
        np.savez(tmp, nodes=nodes, tets=tets, **{f"facet__{k}": v for k, v in facets.items()})
        os.replace(tmp, path)
    return mesh
