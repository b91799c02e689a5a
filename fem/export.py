"""CalculiX input decks of positioned tooth segments in contact, and their results read back.

A deck holds several bodies (``SegmentMesh`` placed in the world by a 4x4 frame), written as C3D10
elements of one linear-elastic material. One body's named facet group is fixed; another body's facet
group is tied by ``*RIGID BODY`` to a reference node on an axis that may only rotate about that axis
(the other five rigid-body dofs are held) and loaded by a moment about it. Frictionless
surface-to-surface penalty contact (``*CONTACT PAIR, TYPE=SURFACE TO SURFACE``, linear
pressure-overclosure law) joins named slave facet groups to master groups. The results read back are
the rotation of the axis, the total contact force of each pair and the contact pressure at the slave
nodes (CalculiX 2.20 keywords; G. Dhondt, *CalculiX CrunchiX User's Manual*).

For contact-line refinement, :func:`build_refined_segment` meshes a segment like
:func:`fem.mesh.build_segment` with an extra size field: ``h_contact`` in a band around given line
segments on the flank, growing with the distance across the band and with the depth below it.

Units: mm, N, MPa, rad. Point arrays are (n, 3).
"""
from __future__ import annotations

import dataclasses
import os
import re
import shutil
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .mesh import SegmentMesh, SegmentSpec, build_segment

__all__ = ["ContactLine", "build_refined_segment", "facets_near_lines", "DeckBody", "ContactPairSpec", "CcxDeck", "write_deck",
           "CcxResult", "read_results", "run_ccx", "ccx_path", "CCX_INSTALL", "CcxNotFound", "CcxFailed"]

CCX_INSTALL = "apt-get update && apt-get install -y calculix-ccx"
# C3D10 faces (CalculiX / Abaqus numbering S1..S4) by the vertex each one omits
_FACE_OF_MISSING_VERTEX = np.array([3, 4, 2, 1])   # missing 0 -> S3 (2-4-3), 1 -> S4, 2 -> S2, 3 -> S1


class CcxNotFound(RuntimeError):
    """The CalculiX solver ``ccx`` is not on the PATH."""

    def __init__(self) -> None:
        super().__init__(f"CalculiX (command 'ccx') is not installed; install it with: {CCX_INSTALL}")


class CcxFailed(RuntimeError):
    """ccx ran but did not produce a converged result; the message ends with the tail of its log."""


# ----------------------------------------------------------------------------------------------
# meshing with contact-line refinement
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ContactLine:
    """A straight contact line on a flank in a body's frame (mm).

    ``p0``, ``p1`` are its end points, ``normal`` the flank's outward unit normal there."""
    p0: np.ndarray
    p1: np.ndarray
    normal: np.ndarray


def _line_size_expression(line: ContactLine, h: float, half_band: float, grow_across: float,
                          grow_depth: float) -> str:
    """gmsh MathEval size: h within ``half_band`` of the line on the flank, growing linearly outside it."""
    p0, p1 = np.asarray(line.p0, float), np.asarray(line.p1, float)
    length = float(np.linalg.norm(p1 - p0))
    el = (p1 - p0) / length
    n = np.asarray(line.normal, float)
    n = n - (n @ el) * el
    n /= np.linalg.norm(n)
    t = np.cross(n, el)
    c = 0.5 * (p0 + p1)

    def coord(v: np.ndarray) -> str:
        return f"((x-({c[0]:.9g}))*({v[0]:.9g})+(y-({c[1]:.9g}))*({v[1]:.9g})+(z-({c[2]:.9g}))*({v[2]:.9g}))"

    def excess(expr: str, lim: float) -> str:   # max(|expr| - lim, 0)
        return f"0.5*(Abs({expr})-{lim:.9g}+Abs(Abs({expr})-{lim:.9g}))"

    return (f"{h:.9g}+{grow_across:.9g}*{excess(coord(t), half_band)}+{grow_depth:.9g}*Abs({coord(n)})"
            f"+{grow_across:.9g}*{excess(coord(el), 0.5 * length + half_band)}")


def build_refined_segment(spec: SegmentSpec, lines: list[ContactLine], h_contact: float, half_band: float,
                          grow_across: float = 0.3, grow_depth: float = 0.6,
                          focus: tuple[tuple[ContactLine, float, float], ...] = ()) -> SegmentMesh:
    """Mesh ``spec`` with elements of size ``h_contact`` (mm) within ``half_band`` (mm) of ``lines``.

    Outside the band the size grows by ``grow_across`` per mm along the flank and ``grow_depth`` per mm
    below it, up to the segment's own graded sizes (``SegmentSpec.size_fields``). ``focus`` adds finer
    zones, each (line, h, half_band): typically a short piece of one contact line where the pressure peak
    is resolved (the smallest size wins)."""
    for h in (h_contact, *(f[1] for f in focus)):
        if not 0 < h <= spec.h_flank:
            raise ValueError(f"contact element size {h} must be in (0, h_flank = {spec.h_flank}]")
    exprs = tuple(_line_size_expression(ln, h_contact, half_band, grow_across, grow_depth) for ln in lines)
    exprs += tuple(_line_size_expression(ln, h, hb, grow_across, grow_depth) for ln, h, hb in focus)
    return build_segment(dataclasses.replace(spec, size_fields=exprs), cache_dir=None)


def facets_near_lines(mesh: SegmentMesh, groups: tuple[str, ...], lines: list[ContactLine],
                      halo: float) -> np.ndarray:
    """The facets (k, 6) of ``groups`` whose centroid lies within ``halo`` (mm) of any of ``lines``.

    Contact surfaces restricted to where contact can occur keep CalculiX's contact search small."""
    tri = np.concatenate([mesh.facets[g] for g in groups if g in mesh.facets] or [np.zeros((0, 6), int)])
    c = mesh.nodes[tri[:, :3]].mean(axis=1)
    near = np.zeros(len(tri), dtype=bool)
    for ln in lines:
        p0, d = np.asarray(ln.p0, float), np.asarray(ln.p1, float) - np.asarray(ln.p0, float)
        t = np.clip((c - p0) @ d / max(d @ d, 1e-300), 0.0, 1.0)
        near |= np.linalg.norm(c - (p0 + t[:, None] * d), axis=1) < halo
    return tri[near]


# ----------------------------------------------------------------------------------------------
# the deck
# ----------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class DeckBody:
    """One meshed body placed in the world: ``world = frame[:3, :3] @ body + frame[:3, 3]``."""
    name: str
    mesh: SegmentMesh
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
    pressure-overclosure law, MPa/mm; ``tension`` its small tension at large clearances, MPa."""
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
    out = ["*HEADING", "ltca: tooth segments in contact (fem.export)", "*NODE, NSET=NALL"]
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
        elem_blocks.append(f"*ELEMENT, TYPE=C3D10, ELSET=E_{b.name}\n" + "\n".join(", ".join(map(str, r)) for r in rows))
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
        out.append(f"*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE{', SMALL SLIDING' if deck.small_sliding else ''}"
                   f"\nS{p.name}, M{p.name}")
    out += ["*BOUNDARY", "NFIX, 1, 3", f"{ref}, 1, 3", f"{rot}, 1, 2",
            "*STEP, INC=200", f"*STATIC, SOLVER={deck.solver}", ", ".join(f"{v:g}" for v in deck.increments),
            "*CLOAD", f"{rot}, 3, {deck.moment:.10g}",
            "*NODE PRINT, NSET=NROT", "U", "*NODE PRINT, NSET=NFIX, TOTALS=ONLY", "RF",
            *[f"*CONTACT PRINT, SLAVE=S{p.name}, MASTER=M{p.name}\nCF" for p in deck.pairs],
            "*CONTACT FILE", "CSTR", "*END STEP"]
    Path(path).write_text("\n".join(out) + "\n")
    return {"ref": ref, "rot": rot, "node_offset": node_off, "elem_offset": elem_off}


# ----------------------------------------------------------------------------------------------
# running ccx and reading its results
# ----------------------------------------------------------------------------------------------
def ccx_path() -> str:
    """Absolute path of ``ccx``; raises :class:`CcxNotFound` (with the install command) if missing."""
    exe = shutil.which("ccx")
    if exe is None:
        raise CcxNotFound()
    return exe


def run_ccx(inp: str | os.PathLike, threads: int = 2, timeout: float = 3600.0) -> float:
    """Run ``ccx`` on the deck ``inp`` (``job.inp`` -> ``job.dat``, ``job.frd``) in its folder.

    Returns the wall time in s. Raises :class:`CcxFailed` with the tail of the log if ccx stops
    without finishing the job (no convergence, bad input)."""
    exe = ccx_path()
    inp = Path(inp)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), CCX_NPROC_EQUATION_SOLVER=str(threads),
               CCX_NPROC_RESULTS=str(threads))
    t0 = time.perf_counter()
    with open(inp.with_suffix(".log"), "w") as log:
        proc = subprocess.run([exe, "-i", inp.stem], cwd=inp.parent, env=env, stdout=log, stderr=subprocess.STDOUT,
                              timeout=timeout)
    wall = time.perf_counter() - t0
    text = inp.with_suffix(".log").read_text(errors="replace")
    if proc.returncode != 0 or "Job finished" not in text or "*ERROR" in text:
        tail = "\n".join(text.splitlines()[-15:])
        raise CcxFailed(f"ccx failed on {inp} (exit {proc.returncode}):\n{tail}")
    return wall


@dataclass
class CcxResult:
    """What a contact deck gives back (mm, N, MPa, rad).

    rotation : rotation of the driven axis about +z, rad (counter-clockwise positive)
    pair_force : contact pair name -> total contact force vector on the slave, N (3,), last increment
    fixed_reaction : total reaction force at the fixed nodes, N (3,)
    contact_nodes : (k,) CalculiX ids of slave nodes with contact output; contact_pressure (k,) MPa;
    contact_opening : (k,) mm (negative = penetration)
    """
    rotation: float
    pair_force: dict
    fixed_reaction: np.ndarray
    contact_nodes: np.ndarray
    contact_pressure: np.ndarray
    contact_opening: np.ndarray
    wall: float = 0.0
    extra: dict = field(default_factory=dict)

    @property
    def max_pressure(self) -> float:
        return float(self.contact_pressure.max()) if self.contact_pressure.size else 0.0


_FLOAT = re.compile(r"[-+]?\d*\.\d+(?:[EeDd][-+]?\d+)?")


def _dat_blocks(text: str) -> list[tuple[str, list[list[float]]]]:
    """The .dat file as (header line, numeric rows) blocks, last increment last."""
    blocks: list[tuple[str, list[list[float]]]] = []
    for line in text.splitlines():
        s = line.strip()
        if not s:
            continue
        if s[0].isalpha():
            blocks.append((s, []))
        elif blocks:
            blocks[-1][1].append([float(v.replace("D", "E")) for v in s.split()])
    return blocks


def _frd_contact(frd: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Slave node ids, opening and pressure of the last CONTACT block of a .frd file."""
    ids, vals = [], []
    current = None
    with open(frd, errors="replace") as fh:
        for line in fh:
            if line.startswith(" -4"):
                current = line.split()[1]
                if current == "CONTACT":
                    ids, vals = [], []
            elif current == "CONTACT" and line.startswith(" -1"):
                m = re.match(r"\s*(\d+)", line[3:13])
                ids.append(int(m.group(1)))
                vals.append([float(v) for v in _FLOAT.findall(line[13:])])
            elif line.startswith(" -3"):
                current = None if current != "CONTACT" else "done"
    if not ids:
        return np.zeros(0, int), np.zeros(0), np.zeros(0)
    v = np.array(vals)
    return np.array(ids), v[:, 0], v[:, 3]


def read_results(job: str | os.PathLike, rot_node: int, pairs: tuple[str, ...]) -> CcxResult:
    """Read the results of the deck written by :func:`write_deck` from ``job.dat`` and ``job.frd``."""
    job = Path(job)
    blocks = _dat_blocks(job.with_suffix(".dat").read_text(errors="replace"))
    rotation, reaction, forces, slave = np.nan, np.full(3, np.nan), {}, None
    for head, rows in blocks:
        h = head.lower()
        if h.startswith("displacements") and "nrot" in h:
            row = next(r for r in rows if int(r[0]) == rot_node)
            rotation = row[3]
        elif h.startswith("total force") and "nfix" in h and rows:
            reaction = np.array(rows[-1][-3:])
        elif h.startswith("statistics for slave set"):
            slave = head.split()[4].rstrip(",")
        elif h.startswith("total surface force") and slave is not None and rows:
            name = next((p for p in pairs if f"S{p}".upper() == slave.upper()), None)
            if name is not None:
                forces[name] = np.array(rows[0][:3])
    ids, opening, pressure = _frd_contact(job.with_suffix(".frd"))
    return CcxResult(float(rotation), forces, reaction, ids, pressure, opening)
