"""CalculiX input decks of positioned gear bodies in contact.

A deck holds several bodies (``BodyMesh`` placed in the world by a 4x4 frame), written as C3D10
elements of one linear-elastic material. One body's named facet group is fixed; another body's facet
group is tied by ``*RIGID BODY`` to a reference node on an axis that may only rotate about that axis
(the other five rigid-body dofs are held) and loaded by a moment about it. Frictionless
surface-to-surface penalty contact (``*CONTACT PAIR, TYPE=SURFACE TO SURFACE``, linear
pressure-overclosure law) joins named slave facet groups to master groups (CalculiX 2.20 keywords;
G. Dhondt, *CalculiX CrunchiX User's Manual*).

The bodies (with contact-line refinement: :mod:`ltca.fem.solids.refinement`; whole gears: :mod:`ltca.fem.solids.full_gear`,
:mod:`ltca.fem.solids.bevel_occ`) are meshed by :mod:`ltca.fem.solids`, ``ccx`` is run and
its results read back by :mod:`ltca.fem.calculix.run`.

Units: mm, N, MPa, rad. Point arrays are (n, 3).
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..solids.mesh_record import BodyMesh

__all__ = ["DeckBody", "ContactPairSpec", "CcxDeck", "write_deck"]

# C3D10 faces (CalculiX / Abaqus numbering S1..S4) by the vertex each one omits
_FACE_OF_MISSING_VERTEX = np.array([3, 4, 2, 1])   # missing 0 -> S3 (2-4-3), 1 -> S4, 2 -> S2, 3 -> S1


@dataclass(frozen=True)
class DeckBody:
    """One meshed body placed in the world: ``world = frame[:3, :3] @ body + frame[:3, 3]``."""
    name: str
    mesh: BodyMesh
    frame: np.ndarray


@dataclass(frozen=True)
class ContactPairSpec:
    """A contact pair: facet groups of the slave body against facet groups of the master body."""
    name: str
    slave: tuple[str, tuple[str, ...]]     # (body name, facet group names)
    master: tuple[str, tuple[str, ...]]


@dataclass(frozen=True)
class CcxDeck:
    """What the deck says besides the bodies (mm, N, MPa).

    ``fixed`` is (body, facet group) held in all directions; ``driven`` is (body, facet group) tied to a
    rigid reference node on the world z axis through ``axis_origin`` that may only rotate about z, loaded
    by ``moment`` (N mm, counter-clockwise positive). ``penalty`` is the slope of the linear
    pressure-overclosure law, MPa/mm; ``tension`` its small tension at large clearances, MPa.
    ``stress_output`` also writes the nodal stresses (``*EL FILE`` ``S``: extrapolated from the integration
    points and averaged over the elements at a node) to the ``.frd`` file."""
    young: float
    poisson: float
    fixed: tuple[str, str]
    driven: tuple[str, str]
    moment: float
    pairs: tuple[ContactPairSpec, ...]
    penalty: float
    tension: float = 0.01
    axis_origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
    increments: tuple[float, float, float, float] = (1.0, 1.0, 1e-4, 1.0)
    solver: str = "SPOOLES"
    small_sliding: bool = True
    stress_output: bool = False


def _face_numbers(tets: np.ndarray, tri: np.ndarray, n_nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """Element index and CalculiX face number (1..4) of boundary triangles (k, >=3) of a tet mesh."""
    n = np.int64(n_nodes)

    def key(t: np.ndarray) -> np.ndarray:
        s = np.sort(t.astype(np.int64), axis=1)
        return (s[:, 0] * n + s[:, 1]) * n + s[:, 2]
    faces = tets[:, [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]]].reshape(-1, 3)   # face i omits vertex i
    keys = key(faces)
    order = np.argsort(keys)
    tk = key(tri[:, :3])
    hit = order[np.clip(np.searchsorted(keys, tk, sorter=order), 0, len(order) - 1)]
    if not np.all(keys[hit] == tk):
        raise ValueError("a facet is not the face of a tetrahedron of its mesh")
    return hit // 4, _FACE_OF_MISSING_VERTEX[hit % 4]


def _id_lines(ids: np.ndarray, per_line: int = 16) -> str:
    ids = np.asarray(ids, dtype=np.int64)
    rows = [", ".join(map(str, ids[i:i + per_line])) for i in range(0, len(ids), per_line)]
    return "\n".join(rows) + "\n"


def write_deck(path: str | os.PathLike, bodies: list[DeckBody], deck: CcxDeck) -> dict:
    """Write the CalculiX input deck ``path`` (``.inp``); returns the node ids of the reference nodes.

    Returns
    -------
    dict
        ``{"ref": id, "rot": id, "node_offset": {body: offset}, "elem_offset": {body: offset}}``; node
        ``i`` of body ``b`` is CalculiX node ``node_offset[b] + i + 1`` (elements alike).
    """
    byname = {b.name: b for b in bodies}
    out = ["*HEADING", "ltca: gear bodies in contact (fem.calculix.deck)", "*NODE, NSET=NALL"]
    node_off, elem_off, n0, e0 = {}, {}, 0, 0
    elem_blocks = []
    for b in bodies:
        T = np.asarray(b.frame, float)
        X = b.mesh.nodes @ T[:3, :3].T + T[:3, 3]
        ids = np.arange(n0 + 1, n0 + len(X) + 1)
        out.append("\n".join(f"{i}, {x:.10g}, {y:.10g}, {z:.10g}" for i, (x, y, z) in zip(ids, X)))
        tets = b.mesh.tets + n0 + 1
        if tets.shape[1] != 10:
            raise ValueError(f"body {b.name}: C3D10 needs quadratic tetrahedra, got {tets.shape[1]} nodes")
        eids = np.arange(e0 + 1, e0 + len(tets) + 1)
        rows = np.column_stack([eids, tets])
        elem_blocks.append(f"*ELEMENT, TYPE=C3D10, ELSET=E_{b.name}\n"
                           + "\n".join(", ".join(map(str, r)) for r in rows))
        node_off[b.name], elem_off[b.name] = n0, e0
        n0, e0 = n0 + len(X), e0 + len(tets)
    out += elem_blocks
    out.append("*ELSET, ELSET=EALL\n" + ", ".join(f"E_{b.name}" for b in bodies))
    ref, rot = n0 + 1, n0 + 2
    ox, oy, oz = deck.axis_origin
    out.append(f"*NODE, NSET=NREF\n{ref}, {ox:.10g}, {oy:.10g}, {oz:.10g}\n*NODE, NSET=NROT\n{rot}, {ox:.10g}, "
               f"{oy:.10g}, {oz:.10g}")
    for set_name, (body, group) in (("NFIX", deck.fixed), ("NRIGID", deck.driven)):
        b = byname[body]
        out.append(f"*NSET, NSET={set_name}\n" + _id_lines(np.unique(b.mesh.facets[group]) + node_off[body] + 1))
    for surf_name, (body, groups) in [(f"S{p.name}", p.slave) for p in deck.pairs] + \
                                     [(f"M{p.name}", p.master) for p in deck.pairs]:
        b = byname[body]
        tri = np.concatenate([b.mesh.facets[g] for g in groups if g in b.mesh.facets])
        el, face = _face_numbers(b.mesh.tets, tri, len(b.mesh.nodes))
        out.append(f"*SURFACE, NAME={surf_name}, TYPE=ELEMENT\n" +
                   "\n".join(f"{e + elem_off[body] + 1}, S{f}" for e, f in zip(el, face)))
    out += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{deck.young:.10g}, {deck.poisson:.10g}",
            "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL",
            f"*RIGID BODY, NSET=NRIGID, REF NODE={ref}, ROT NODE={rot}",
            "*SURFACE INTERACTION, NAME=SI", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
            f"{deck.penalty:.10g}, {deck.tension:.10g}"]
    for p in deck.pairs:
        sliding = ", SMALL SLIDING" if deck.small_sliding else ""
        out.append(f"*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE{sliding}\nS{p.name}, M{p.name}")
    out += ["*BOUNDARY", "NFIX, 1, 3", f"{ref}, 1, 3", f"{rot}, 1, 2",
            "*STEP, INC=200", f"*STATIC, SOLVER={deck.solver}", ", ".join(f"{v:g}" for v in deck.increments),
            "*CLOAD", f"{rot}, 3, {deck.moment:.10g}",
            "*NODE PRINT, NSET=NROT", "U", "*NODE PRINT, NSET=NFIX, TOTALS=ONLY", "RF",
            *[f"*CONTACT PRINT, SLAVE=S{p.name}, MASTER=M{p.name}\nCF" for p in deck.pairs],
            "*CONTACT FILE", "CSTR", *(["*EL FILE", "S"] if deck.stress_output else []), "*END STEP"]
    Path(path).write_text("\n".join(out) + "\n")
    return {"ref": ref, "rot": rot, "node_offset": node_off, "elem_offset": elem_off}
