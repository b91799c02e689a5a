"""Tooth-segment solids of cylindrical gears meshed by gmsh (a few teeth on a slice of the rim), with a mesh
cache keyed by the spec's hash.

Not part of the installed package: the product meshes whole gear bodies (:mod:`ltca.fem.solids.gear_body`); a segment
with free radial cut faces bends like a curved cantilever about its bore, so its stiffness depends on where it is
cut. Kept for comparison with the whole body. The section comes from :mod:`tools.segment_mesh.section`, the gmsh
construction from :mod:`tools.segment_mesh.mesher`; the mesh is a :class:`ltca.fem.solids.mesh_record.BodyMesh`.
"""
from __future__ import annotations

import os
import time

from ltca.fem.solids.cache import load_cached, store_cached
from ltca.fem.solids.mesh_record import BodyMesh
from ltca.fem.solids.session import gmsh_session

from .mesher import mesh_with_gmsh
from .spec import SegmentSpec

__all__ = ["SegmentSpec", "build_segment"]


def build_segment(spec: SegmentSpec, cache_dir: str | os.PathLike | None = None,
                  progress: bool = False) -> BodyMesh:
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
    BodyMesh
    """
    t0 = time.perf_counter()
    cached = load_cached(cache_dir, "segment", spec.spec_hash)
    if cached is not None:
        return cached
    with gmsh_session(progress):
        nodes, tets, facets = mesh_with_gmsh(spec)
    mesh = BodyMesh(nodes, tets, facets, spec.spec_hash, time.perf_counter() - t0)
    store_cached(cache_dir, "segment", mesh)
    return mesh
