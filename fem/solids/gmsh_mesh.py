"""Meshing of a labelled gmsh model into a :class:`ltca.fem.solids.mesh_record.BodyMesh`: a fresh model with fixed
options, the background size field, physical groups, generation and the read-back of nodes, tetrahedra (meshio
order) and outward-oriented named facets.

The shared gmsh steps of the solid builders (:mod:`ltca.fem.solids.gear_body`, :mod:`ltca.fem.solids.full_gear`,
:mod:`ltca.fem.solids.bevel_occ`); each builds and labels its own CAD. The gmsh calls run in a fixed order with fixed
numbers: the mesh, and any deck written from it, is bit-identical for one spec. gmsh must be initialised
(:func:`ltca.fem.solids.session.gmsh_session`).
"""
from __future__ import annotations

import contextlib
from typing import Callable, Iterator

import numpy as np

__all__ = ["fresh_model", "background_size", "mesh_labelled", "extract_mesh"]

_GMSH_TO_MESHIO_TET10 = np.array([0, 1, 2, 3, 4, 5, 6, 7, 9, 8])
_FLIP_TRI6 = np.array([0, 2, 1, 5, 4, 3])


def background_size(field: int | list[int], expressions: tuple[str, ...] = ()) -> None:
    """Make gmsh size field(s) ``field``, with the ``MathEval`` size ``expressions`` (in x, y, z, mm), the background
    mesh size of the current model: their minimum where there are several."""
    import gmsh

    fld = gmsh.model.mesh.field
    tags = [field] if isinstance(field, int) else list(field)
    for expr in expressions:
        f = fld.add("MathEval")
        fld.setString(f, "F", expr)
        tags.append(f)
    if len(tags) == 1:
        fld.setAsBackgroundMesh(tags[0])
        return
    m = fld.add("Min")
    fld.setNumbers(m, "FieldsList", tags)
    fld.setAsBackgroundMesh(m)


class _FaceIndex:
    """Sorted keys of all tetrahedron faces, to find the tetrahedron behind a boundary triangle."""

    def __init__(self, tets: np.ndarray, n_nodes: int) -> None:
        self.n = np.int64(n_nodes)
        faces = tets[:, [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]]]      # face i opposite vertex i
        self.keys = self._key(faces.reshape(-1, 3))
        self.order = np.argsort(self.keys)
        self.opp = tets[:, :4].reshape(-1)

    def _key(self, tri: np.ndarray) -> np.ndarray:
        s = np.sort(tri.astype(np.int64), axis=1)
        return (s[:, 0] * self.n + s[:, 1]) * self.n + s[:, 2]

    def opposite(self, tri: np.ndarray) -> np.ndarray:
        """The fourth vertex of the tetrahedron owning each triangle (k, >=3) -> (k,)."""
        tk = self._key(tri[:, :3])
        hit = self.order[np.clip(np.searchsorted(self.keys, tk, sorter=self.order), 0,
                                 len(self.order) - 1)]
        if not np.all(self.keys[hit] == tk):
            raise RuntimeError("boundary triangle that is not a tetrahedron face")
        return self.opp[hit]


def _orient_outward(tri: np.ndarray, faces: _FaceIndex, nodes: np.ndarray) -> np.ndarray:
    """Flip boundary triangles (k, 3 or 6) whose normal points into their tetrahedron."""
    if len(tri) == 0:
        return tri
    v = nodes[tri[:, :3]]
    nrm = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    inward = np.einsum("ij,ij->i", nrm, nodes[faces.opposite(tri)] - v[:, 0]) > 0
    out = tri.copy()
    out[inward] = tri[inward][:, _FLIP_TRI6[:tri.shape[1]]]
    return out


@contextlib.contextmanager
def fresh_model(name: str, options: dict[str, float]) -> Iterator[None]:
    """A new gmsh model with ``options`` set, for the duration of a ``with`` block; on exit the model is removed
    and the previous model and option values are restored (gmsh must be initialised)."""
    import gmsh

    old = {k: gmsh.option.getNumber(k) for k in options}
    prev_model = gmsh.model.getCurrent() if gmsh.model.list() else ""
    gmsh.model.add(name)
    try:
        for k, v in options.items():
            gmsh.option.setNumber(k, v)
        yield
    finally:
        gmsh.model.remove()
        if prev_model and prev_model in gmsh.model.list():
            gmsh.model.setCurrent(prev_model)
        for k, v in old.items():
            gmsh.option.setNumber(k, v)


def mesh_labelled(labels: dict[int, str], volumes: list[int], order: int,
                  set_sizes: Callable[[list[int]], None]) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Size (``set_sizes`` gets the flank, fillet and tip surfaces), group, mesh and read the current model."""
    import gmsh

    fine = [t for t, s in labels.items() if s.split("_")[0] in ("flank", "fillet", "tip")]
    set_sizes(fine)
    for label in sorted(set(labels.values())):
        gmsh.model.addPhysicalGroup(2, [t for t, s in labels.items() if s == label], name=label)
    gmsh.model.addPhysicalGroup(3, volumes, name="body")
    gmsh.model.mesh.generate(3)
    if order == 2:
        gmsh.model.mesh.setOrder(2)
    return extract_mesh(labels, order)


def extract_mesh(labels: dict[int, str], order: int) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Nodes, tetrahedra (meshio order) and named, outward-oriented facets of the current gmsh model.

    ``labels`` maps boundary surface tags to facet group names; nodes of no tetrahedron are dropped.
    """
    import gmsh

    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    nodes = coords.reshape(-1, 3)
    etype, npe = (11, 10) if order == 2 else (4, 4)
    _, conn = gmsh.model.mesh.getElementsByType(etype)
    tets = index[conn.astype(np.int64)].reshape(-1, npe)
    if order == 2:
        tets = tets[:, _GMSH_TO_MESHIO_TET10]
    used = np.zeros(len(nodes), dtype=bool)
    used[tets] = True
    index[tags.astype(np.int64)] = np.cumsum(used) - 1              # drop nodes of no tetrahedron
    nodes = nodes[used]
    tets = np.cumsum(used)[tets] - 1
    ttype, tpe = (9, 6) if order == 2 else (2, 3)
    parts: dict[str, list[np.ndarray]] = {}
    for tag, label in labels.items():
        _, conn = gmsh.model.mesh.getElementsByType(ttype, tag)
        parts.setdefault(label, []).append(index[conn.astype(np.int64)].reshape(-1, tpe))
    faces = _FaceIndex(tets, len(nodes))
    facets = {k: _orient_outward(np.concatenate(v), faces, nodes) for k, v in sorted(parts.items())}
    return nodes, tets, facets
