"""Whole members as STEP solids (ISO 10303-21) for CAD, CAM and other FE codes.

The solids are the OpenCASCADE ones of the CalculiX cross-check, built by gmsh's OCC kernel: a cylindrical gear
by :func:`ltca.fem.solids.full_gear.gear_solid` (every tooth's generated outline, extruded or lofted along the
helix, the bore or the ring's outer rim, a web), a bevel member by :func:`ltca.fem.solids.bevel_occ.member_solid`
(every tooth lofted through exact points of the generated flanks, fused with the revolved blank). The file holds
the member's solid in its body frame (z along the axis; mm). Its volume is measured by OCC on the file as written,
read back (:func:`step_volume`; not on the shape in memory before the transfer, where OCC gave a holed extrusion's
volume without its hole), and the volume of a tetrahedral mesh record by :func:`mesh_volume`.
"""
from __future__ import annotations

import contextlib
import os
import sys
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .gmsh_mesh import fresh_model
from .mesh_record import BodyMesh
from .session import gmsh_session

__all__ = ["StepSolid", "mesh_volume", "step_volume", "write_step"]

_OPTIONS = {"General.NumThreads": 2, "Geometry.Tolerance": 1e-6, "Geometry.OCCParallel": 1}


@dataclass(frozen=True)
class StepSolid:
    """A written STEP file: its path, the OCC volume of its solid(s) (mm^3), the number of solids and the wall
    time (s)."""
    path: Path
    volume: float
    solids: int
    seconds: float


def _volume(dimtags) -> float:
    import gmsh
    return float(sum(gmsh.model.occ.getMass(d, t) for d, t in dimtags if d == 3))


@contextlib.contextmanager
def _quiet_stdout() -> Iterator[None]:
    """OpenCASCADE's STEP writer prints its transfer statistics on file descriptor 1: sent to /dev/null."""
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "wb") as null:
            os.dup2(null.fileno(), 1)
            yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)


def write_step(build: Callable[[], list], path: str | Path) -> StepSolid:
    """Build a solid with ``build`` (a function that makes the OCC volumes in the current gmsh model and returns
    their (dim, tag) pairs, e.g. ``lambda: gear_solid(spec)``) and write it to ``path`` (``.step``)."""
    import gmsh
    t0 = time.perf_counter()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with gmsh_session(False), fresh_model("step_export", _OPTIONS):
        vols = [d for d in build() if d[0] == 3]
        gmsh.model.occ.synchronize()
        if not vols:
            raise ValueError(f"{path.name}: the solid builder made no volume")
        # only the solids go to the file (no construction points or curves left over by the loft)
        keep = set(vols)
        for dim in (2, 1, 0):
            for d in gmsh.model.getBoundary(list(keep), combined=False, oriented=False, recursive=True):
                keep.add((d[0], abs(d[1])))
        stray = [e for dim in (0, 1, 2) for e in gmsh.model.getEntities(dim) if e not in keep]
        if stray:
            gmsh.model.occ.remove(stray)
            gmsh.model.occ.synchronize()
        with _quiet_stdout():
            gmsh.write(str(path))
    volume, n = step_volume(path)          # measured on the file as written (and proof that it opens)
    if n != len(vols):
        raise ValueError(f"{path.name}: {len(vols)} solids written, {n} read back")
    return StepSolid(path, volume, n, time.perf_counter() - t0)


def step_volume(path: str | Path) -> tuple[float, int]:
    """Open a STEP file in gmsh (OCC): the total volume of its solids (mm^3) and their number."""
    import gmsh
    with gmsh_session(False), fresh_model("step_read", _OPTIONS), _quiet_stdout():
        vols = [d for d in gmsh.model.occ.importShapes(str(path)) if d[0] == 3]
        gmsh.model.occ.synchronize()
        return _volume(vols), len(vols)


def mesh_volume(mesh: BodyMesh) -> float:
    """Volume of a mesh record's tetrahedra (corner nodes; straight-edged elements), mm^3."""
    X = np.asarray(mesh.nodes)[np.asarray(mesh.tets)[:, :4]]
    v = np.einsum("ij,ij->i", np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), X[:, 3] - X[:, 0])
    return float(np.abs(v).sum() / 6.0)
