"""Flank compliance of a bevel member: its mapped whole body (:mod:`ltca.fem.solids.bevel_body`) on the one compliance
path of every gear type (:func:`ltca.fem.compliance.flank_compliance`: FE far field on a coarse flank grid, read at
two depths with the half-space part of the same patch loads removed, plus the near field at the cells).

The compliance grid is the loaded flank's own axial-section grid: depth fraction t from the flank grid's lowest
row (a small root offset above the root cone) to the face cone, and cone distance L from toe to heel; points and
normals are exact (:func:`ltca.geometry.bevel.sampling.flank_at`).  Tooth k's grid is tooth 0's turned by
k 2 pi / z about the member axis.  Root stresses are read 0.05 mm inside the loaded fillet (between the root
offset row and the fillet / flank boundary), along the face.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ltca.geometry.bevel.sampling import fillet_boundary, flank_at
from ltca.geometry.flank import Flank

from .compliance import BodyCompliance, flank_compliance
from .solids.bevel_body import BevelBodySpec, build_bevel_body

__all__ = ["BevelComplianceSpec", "bevel_compliance"]


@dataclass(frozen=True)
class BevelComplianceSpec:
    """What to model for one bevel member (mm, MPa).

    side : the loaded flank ("concave" or "convex");  loaded : teeth whose ``side`` flank carries load;
    teeth : teeth meshed (the loaded ones plus a neighbour each side);  grid : (n_t, n_L) compliance grid nodes;
    depth : read depth d of the regular part (also 2d), mm, capped at 15 % of the local tooth thickness; 0: no
    near field;  rim_depth : blank under the root cone, mm (without a support);  support : the mounting in
    service, ``("seat", rho)`` or ``("face", Z)``;  divisions : mesh divisions; both of
    :class:`ltca.fem.solids.bevel_body.BevelBodySpec`;  root_points : (along the fillet, along the face);
    periodic : load the centre loaded tooth only and read its neighbours (:mod:`ltca.fem.periodic`: the mapped body's
    teeth are turned copies on a body of revolution), else load every loaded tooth.
    """
    side: str
    loaded: tuple[int, ...]
    teeth: tuple[int, ...]
    grid: tuple[int, int]
    depth: float
    young: float
    poisson: float
    rim_depth: float = 10.0
    divisions: tuple[int, int, int, int, int, int] = (16, 8, 6, 4, 4, 24)
    root_points: tuple[int, int] = (4, 7)
    support: tuple[str, float] | None = None
    periodic: bool = True

    def __post_init__(self) -> None:
        if self.side not in ("concave", "convex"):
            raise ValueError(f"side = {self.side!r}: allowed 'concave' or 'convex'")
        if not set(self.loaded) <= set(self.teeth):
            raise ValueError(f"loaded = {self.loaded}: must be among the meshed teeth {self.teeth}")
        if min(self.grid) < 3:
            raise ValueError(f"grid = {self.grid}: at least 3 x 3 nodes")


class _Grid(NamedTuple):
    points: np.ndarray
    normals: np.ndarray


def _rotz(p: np.ndarray, a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.stack([c * p[..., 0] - s * p[..., 1], s * p[..., 0] + c * p[..., 1], p[..., 2]], -1)


def bevel_compliance(concave: Flank, convex: Flank, z: int, root_offset: float, convex_shift: float,
                     spec: BevelComplianceSpec, cache_dir=None, progress=None) -> BodyCompliance:
    """Mesh, factorise and load one bevel member; its compliance on the loaded flank grid.

    Parameters
    ----------
    concave, convex : Flank
        The member's generated flanks (same axial grid, lowest row ``root_offset`` above the root cone).
    z : int
        Teeth of the member.
    root_offset : float
        mm.
    convex_shift : float
        Rotation of the convex flank onto tooth 0 (:func:`ltca.fem.solids.bevel_body.convex_shift`), rad.
    spec : BevelComplianceSpec
    cache_dir : path, optional
        Mesh cache.
    progress : callable(str), optional

    Returns
    -------
    BodyCompliance
        ``s_grid`` is the depth fraction t, ``z_grid`` the cone distance L (mm) of the compliance grid.
    """
    say = progress or (lambda msg: None)
    t0 = time.perf_counter()
    body = BevelBodySpec(concave, convex, z, root_offset, convex_shift, spec.teeth, spec.rim_depth, spec.divisions,
                         spec.support)
    mesh = build_bevel_body(body, cache_dir=cache_dir)
    t_mesh = time.perf_counter() - t0
    say(f"meshed bevel z={z}: {len(mesh.nodes)} nodes, {len(mesh.tets)} tets ({t_mesh:.1f} s)")
    fl = concave if spec.side == "concave" else convex
    shift = 0.0 if spec.side == "concave" else convex_shift
    ns, nz = spec.grid
    t_grid = np.linspace(0.0, 1.0, ns)
    L_grid = np.linspace(float(fl.v[0]), float(fl.v[-1]), nz)
    T, L = np.meshgrid(t_grid, L_grid, indexing="ij")
    X0, N0, _ = flank_at(fl, T, L)
    X0, N0 = _rotz(X0, shift), _rotz(N0, shift)
    pitch = 2 * np.pi / z
    flanks = [_Grid(_rotz(X0, k * pitch), _rotz(N0, k * pitch)) for k in spec.loaded]
    # local tooth thickness per row (chord between the two flanks at the same axial-section point)
    other, o_shift = (convex, convex_shift) if spec.side == "concave" else (concave, 0.0)
    Xo = _rotz(flank_at(other, T, L)[0], o_shift)
    a = np.arctan2(X0[..., 1], X0[..., 0]) - np.arctan2(Xo[..., 1], Xo[..., 0])
    a = np.abs((a + np.pi) % (2 * np.pi) - np.pi)
    a = np.minimum(a, pitch - a)
    thick = (a * np.hypot(X0[..., 0], X0[..., 1])).min(1)
    depth = np.minimum(spec.depth, 0.15 * thick)
    spacing = float(max(np.linalg.norm(np.diff(X0, axis=0), axis=-1).max(),
                        np.linalg.norm(np.diff(X0, axis=1), axis=-1).max()))
    # root points: inside the loaded fillet, between the root offset row and the fillet / flank boundary
    tb = np.interp(np.linspace(fl.v[0], fl.v[-1], spec.root_points[1]), fl.v, fillet_boundary(fl))
    f = np.linspace(0.0, 1.0, spec.root_points[0])[:, None]
    Tr = f * np.maximum(tb, 0.05)[None, :]
    Lr = np.broadcast_to(np.linspace(fl.v[0], fl.v[-1], spec.root_points[1])[None, :], Tr.shape)
    Lr = np.clip(Lr, fl.v[0] + 0.02 * (fl.v[-1] - fl.v[0]), fl.v[-1] - 0.02 * (fl.v[-1] - fl.v[0]))
    Pr, Nr, _ = flank_at(fl, Tr, Lr)
    base = _rotz(Pr - 0.05 * Nr, shift).reshape(-1, 3)
    R = np.concatenate([_rotz(base, k * pitch) for k in spec.loaded])
    root_tooth = np.repeat(np.asarray(spec.loaded), len(base))
    names = [f"flank_{k}_{spec.side}" for k in spec.loaded]
    return flank_compliance(spec, mesh, "bore", flanks, t_grid, L_grid, depth, spacing, names, R, root_tooth,
                            {"mesh": t_mesh}, say, pitch=pitch if spec.periodic else None)
