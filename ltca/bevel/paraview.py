"""The ParaView time series of a bevel loaded run: the parts of each position fed to the one writer,
:func:`ltca.paraview.write_series`.

Each step has three parts, in the mesh frame S_h of the pair (:func:`ltca.geometry.bevel.tca.mesh_frames`, the
assembly errors included) at that pinion angle, the gear at its kinematic angle:

- ``pinion`` and ``gear``: the FE bodies cut to their loaded teeth and the blank under them
  (:class:`ltca.paraview.BodyPart`: displacement, von Mises and principal stresses of the FE solution under the
  position's contact forces, gathered on each body's compliance grid);
- ``flank``: the loaded flank of every pinion tooth that can carry load, as a quad surface on a lattice of depth
  fraction x cone distance (the body's own flank coordinates; bins about the size of a contact cell) with the cell
  field ``contact_pressure_mpa``: the largest contact-cell pressure in each bin, so its peak is the solver's peak
  at that position.

The time value is the position in mesh cycles from the mean point (the ``cycle`` coordinate of ``results.nc``).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ltca.geometry.bevel.sampling import flank_at
from ltca.geometry.bevel.tca import mesh_frames

from ..paraview import BodyPart, flank_mesh, select_steps
from ..paraview import write_series as write_pvd
from .loaded import BevelPosition, _weights_of
from .loaded_model import body_t, member_flanks
from .model import BevelLoadedModel

__all__ = ["loaded_teeth_tets", "write_series"]

#: largest number of lattice bins along either flank direction
MAX_BINS = 400


def _rotz(angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def loaded_teeth_tets(body, z: int) -> np.ndarray:
    """Tets of a bevel body within half a pitch (about its axis) of a loaded tooth's centre line: halfway between the
    tooth's concave and convex flank facets at the same distance from the apex (a spiral tooth turns along its face
    width)."""
    nodes, tets, facets = body.mesh.nodes, body.mesh.tets, body.mesh.facets
    c = nodes[tets[:, :4]].mean(axis=1)
    theta, rc = np.arctan2(c[:, 1], c[:, 0]), np.linalg.norm(c, axis=1)
    keep = np.zeros(len(tets), bool)
    for k in body.spec.loaded:
        sides = [facets.get(f"flank_{k}_{s}") for s in ("concave", "convex")]
        if any(f is None for f in sides):
            return np.arange(len(tets))
        pts = nodes[np.concatenate([np.unique(f) for f in sides])]
        a = np.arctan2(pts[:, 1], pts[:, 0])
        a0 = np.angle(np.exp(1j * a).mean())
        rel, r = np.angle(np.exp(1j * (a - a0))), np.linalg.norm(pts, axis=1)
        edges = np.linspace(r.min(), r.max(), 13)
        at = np.clip(np.digitize(r, edges) - 1, 0, 11)
        full = [b for b in range(12) if np.any(at == b)]
        centre = np.interp(rc, [r[at == b].mean() for b in full], [rel[at == b].mean() for b in full])
        keep |= np.abs(np.angle(np.exp(1j * (theta - a0 - centre)))) <= np.pi / z
    return np.flatnonzero(keep)


def _frame(B: np.ndarray, O: np.ndarray, angle: float) -> np.ndarray:
    """4 x 4 placement of a body turned by ``angle`` about its axis, then set in the mesh frame by (B, O)."""
    M = np.eye(4)
    M[:3, :3] = B @ _rotz(angle)
    M[:3, 3] = O
    return M


class _Flank:
    """The loaded pinion flank of every loaded tooth on a lattice (n_t x n_L bins) in the body frame."""

    def __init__(self, lm: BevelLoadedModel, results: list[BevelPosition]):
        fl, _, shift = member_flanks(lm.pair, "pinion")
        side = lm.side
        self.fl, self.shift = fl[side], (shift if side == "convex" else 0.0)
        self.off = lm.bodies.off1
        self.teeth = tuple(lm.bodies.body1.spec.loaded)
        self.z = lm.pair.blank.pinion.z
        self.L0, self.L1 = float(self.fl.v[0]), float(self.fl.v[-1])
        area = np.concatenate([r.area for r in results])
        ds = float(np.sqrt(np.median(area))) if area.size else 1.0
        T, L = np.meshgrid(np.linspace(0.0, 1.0, 5), np.linspace(self.L0, self.L1, 5), indexing="ij")
        X = flank_at(self.fl, T, L)[0]
        depth = float(np.linalg.norm(np.diff(X, axis=0), axis=-1).sum(axis=0).max())
        face = float(np.linalg.norm(np.diff(X, axis=1), axis=-1).sum(axis=1).max())
        self.nt = int(np.clip(np.ceil(depth / ds), 4, MAX_BINS))
        self.nL = int(np.clip(np.ceil(face / ds), 4, MAX_BINS))

    def surface(self) -> tuple[np.ndarray, np.ndarray]:
        """Points (tooth, t edge, L edge, 3 -> flattened) in the pinion body frame and the quads (m, 4)."""
        T, L = np.meshgrid(np.linspace(0.0, 1.0, self.nt + 1), np.linspace(self.L0, self.L1, self.nL + 1),
                           indexing="ij")
        X = flank_at(self.fl, T, L)[0] @ _rotz(self.shift).T
        c1 = 2 * np.pi / self.z
        pts = np.stack([X @ _rotz(k * c1).T for k in self.teeth])
        idx = np.arange(pts.shape[0] * pts.shape[1] * pts.shape[2]).reshape(pts.shape[:3])
        quads = np.stack([idx[:, :-1, :-1], idx[:, 1:, :-1], idx[:, 1:, 1:], idx[:, :-1, 1:]], -1).reshape(-1, 4)
        return pts.reshape(-1, 3), quads

    def pressure(self, lm: BevelLoadedModel, r: BevelPosition) -> np.ndarray:
        """Largest cell pressure (MPa) in each bin, (tooth x t bin x L bin,), 0 where no cell lies."""
        field = np.zeros((len(self.teeth), self.nt, self.nL))
        if r.pressure.size:
            t = body_t(lm.pair.blank, "pinion", self.off, r.L1, r.Rn1)
            it = np.clip(np.floor(t * self.nt).astype(int), 0, self.nt - 1)
            iL = np.clip(np.floor((r.L1 - self.L0) / (self.L1 - self.L0) * self.nL).astype(int), 0, self.nL - 1)
            k = np.searchsorted(self.teeth, r.pair)
            np.maximum.at(field, (k, it, iL), r.pressure)
        return field.reshape(-1)


def write_series(out: Path, lm: BevelLoadedModel, results: list[BevelPosition], cycle: np.ndarray, torque_nm: float,
                 steps: int | None = None, name: str = "") -> dict:
    """Write ``paraview.pvd`` and its VTU parts for ``results`` (one torque, N m, over the positions ``cycle``,
    mesh cycles from the mean point) into ``out`` (module docstring).

    Returns ``{"pvd": path, "steps": [position index], "cycle": [...], "flank_peak_mpa": [...], "files": n}``."""
    pair, B = lm.pair, lm.bodies
    cycle = np.asarray(cycle, float)
    pick = select_steps(cycle, steps)
    flank = _Flank(lm, results)
    pts, quads = flank.surface()
    bl = pair.blank
    bodies = (BodyPart(B.body1, B.young, B.poisson, loaded_teeth_tets(B.body1, bl.pinion.z)),
              BodyPart(B.body2, B.young, B.poisson, loaded_teeth_tets(B.body2, bl.gear.z)))
    weights = [_weights_of(lm, results[k].pair, results[k]) for k in pick]
    U = [body.displacements(np.stack([w[i].T @ results[k].force for w, k in zip(weights, pick)], axis=1))
         for i, body in enumerate(bodies)]
    B1, O1, B2, O2 = mesh_frames(pair.blank, lm.asm)
    # each body's loaded flank sits on its tooth 0 turned by the convex flank's design rotation (the gap
    # evaluator's flanks are unturned): turn the body back by it
    shift2 = member_flanks(pair, "gear")[2] if lm.gaps.gear_side == "convex" else 0.0
    peaks = []

    def parts():
        for j, k in enumerate(pick):
            r = results[k]
            f1 = _frame(B1, O1, r.phi1 - flank.shift)
            f2 = _frame(B2, O2, lm.gaps.phi2_0 - lm.gaps.ratio * r.phi1 - shift2)
            p = flank.pressure(lm, r).astype(np.float32)
            peaks.append(float(p.max(initial=0.0)))
            yield cycle[k], [("pinion", bodies[0].mesh(U[0][:, j], f1)), ("gear", bodies[1].mesh(U[1][:, j], f2)),
                             ("flank", flank_mesh(pts, quads, p, f1))]
    pv = write_pvd(out, parts(), f"{name}, {torque_nm:g} N m (pinion); timestep = position in mesh cycles from "
                                 "the mean point")
    return {"pvd": pv["pvd"], "steps": [int(k) for k in pick], "cycle": [float(cycle[k]) for k in pick],
            "flank_peak_mpa": peaks, "files": pv["files"]}
