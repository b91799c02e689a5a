"""Tooth-segment solids of cylindrical gears meshed by gmsh, with a mesh cache keyed by the spec's hash.

The section comes from :mod:`fem.solids.section`, the gmsh construction from :mod:`fem.solids.segment_gmsh`;
the records and conventions are those of :mod:`fem.solids.spec`.
"""
from __future__ import annotations

import os
import time

from .cache import load_cached, store_cached
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
    cached = load_cached(cache_dir, "segment", spec.spec_hash)
    if cached is not None:
        return cached
    with gmsh_session(progress):
        nodes, tets, facets = mesh_with_gmsh(spec)
    mesh = SegmentMesh(nodes, tets, facets, spec.spec_hash, time.perf_counter() - t0)
    store_cached(cache_dir, "segment", mesh)
    return mesh
