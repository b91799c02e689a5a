"""The mesh record of every meshed body: nodes, quadratic tetrahedra, named boundary facets.

Every solid builder of :mod:`ltca.fem.solids` (the whole cylindrical gear body, :mod:`ltca.fem.solids.gear_body`; the
bevel members, :mod:`ltca.fem.solids.bevel_body` and :mod:`ltca.fem.solids.bevel_occ`; the whole gears of the CalculiX
cross-check, :mod:`ltca.fem.solids.full_gear`) returns a :class:`BodyMesh`; the compliance path (:mod:`ltca.fem.compliance`),
the mesh cache (:mod:`ltca.fem.solids.cache`) and the CalculiX deck writer (:mod:`ltca.fem.calculix.deck`) read it.

Conventions
-----------
* Points are (n, 3) with xyz on the last axis (see ``ltca.geometry.flank``); units mm, rad.
* ``tets`` use the meshio / scikit-fem / CalculiX order of the 10-node tetrahedron
  (mid-edge nodes 01, 12, 20, 03, 13, 23). gmsh's own order swaps the last two; :mod:`ltca.fem.solids.gmsh_mesh`
  converts it.
* Elements are second order with straight edges (``Mesh.SecondOrderLinear = 1``): the mid-edge nodes
  are the edge midpoints, so every element map is affine. Corner nodes lie on the CAD surfaces.
"""
from __future__ import annotations

import hashlib
from dataclasses import dataclass, field

import numpy as np

__all__ = ["BodyMesh", "outline_hash"]


@dataclass(frozen=True)
class BodyMesh:
    """A meshed solid: one gear body (or any body the solid builders of :mod:`ltca.fem.solids` make).

    Attributes
    ----------
    nodes : ndarray, shape (N, 3)
        Node coordinates, mm.
    tets : ndarray, shape (M, 10) (order 2) or (M, 4) (order 1)
        Node indices, meshio order, positive orientation.
    facets : dict of str to ndarray, shape (k, 6) (order 2) or (k, 3)
        Boundary triangles (3 vertices, then mid-edge 01, 12, 20), oriented outward, by group name: the
        builder's names, e.g. ``"bore"`` (internal: ``"rim"``), ``"ends"``, ``"root"``,
        ``"flank_{k}_{left|right}"``, ``"fillet_{k}_{left|right}"``, ``"tip_{k}"``.
    spec_hash : str
        The ``spec_hash`` of the spec that made it (the mesh cache's key).
    seconds : float
        Wall time spent building (or loading) the mesh, s.
    hexes : ndarray, shape (H, 20), or None
        A mapped body: the 20-node serendipity hexahedra whose Kuhn split (six tetrahedra each) ``tets`` is, over the
        same nodes (order of :mod:`ltca.fem.serendipity`). The stiffness is then the hexahedra's and the tetrahedra
        carry loads and read-outs. None: a tetrahedral mesh.
    """

    nodes: np.ndarray
    tets: np.ndarray
    facets: dict[str, np.ndarray]
    spec_hash: str
    seconds: float = field(default=0.0, compare=False)
    hexes: np.ndarray | None = field(default=None, compare=False)

    @property
    def n_dofs(self) -> int:
        """Displacement degrees of freedom, 3 per node."""
        return 3 * len(self.nodes)


def outline_hash(version: str, *arrays: np.ndarray):
    """A SHA-256 object fed with a recipe ``version`` and the shapes and float bytes of ``arrays``."""
    h = hashlib.sha256(version.encode())
    for a in arrays:
        arr = np.ascontiguousarray(a, dtype=float)
        h.update(str(arr.shape).encode())
        h.update(arr.tobytes())
    return h
