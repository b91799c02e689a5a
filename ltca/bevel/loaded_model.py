"""What the bevel LTCA solves on: the generated pair, the flank pair and assembly, both member bodies' compliance.

The bodies (:func:`fem.bevel_compliance.bevel_compliance`) do not depend on the assembly errors (each lives in
its own body frame), so one :class:`BevelBodies` serves every E, P, G, Sigma and every torque; only the gap
evaluator (:class:`geometry.bevel.gaps.MeshGaps`) is rebuilt per assembly.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from fem.bevel_compliance import BevelComplianceSpec, bevel_compliance
from fem.compliance import BodyCompliance
from fem.solids.bevel_body import convex_shift
from geometry.bevel.blank import BevelBlank, MemberBlank
from geometry.bevel.gaps import MeshGaps, depth_fraction as body_t
from geometry.bevel.generation import generate_flank
from geometry.bevel.tca import Assembly, BevelPair

__all__ = ["BevelFidelity", "BevelBodies", "BevelLoadedModel", "prepare_bodies", "loaded_model", "body_t"]

#: teeth of each member that can carry load (pair j: pinion tooth +j, gear tooth -j) and the meshed ones
LOADED = (-1, 0, 1)
MESHED = (-2, -1, 0, 1, 2)


@dataclass(frozen=True)
class BevelFidelity:
    """Model size: compliance grid, body mesh divisions, contact cells (see the module docstrings).

    grid : (n_t, n_L) compliance grid per loaded flank;  divisions : body mesh (n_L, n_t, n_s, n_g, n_rim,
    n_far);  depth : read depth of the regular part, mm;  cells : (along the major, across the minor axis)
    cells over the window of each pair;  window : (major, minor) window approach as multiples of the Hertz
    approach of the whole load on one pair;  near_field : add the half-space near field at the cells.
    """
    name: str = "default"
    grid: tuple[int, int] = (9, 13)
    divisions: tuple[int, int, int, int, int, int] = (14, 7, 5, 3, 3, 16)
    depth: float = 0.5
    cells: tuple[int, int] = (33, 17)
    window: tuple[float, float] = (1.6, 1.0)
    near_field: bool = True

    @classmethod
    def named(cls, name: str) -> "BevelFidelity":
        """``coarse``, ``default`` or ``fine`` (the convergence ladder)."""
        table = {"coarse": cls("coarse", (7, 9), (10, 5, 4, 3, 2, 12), 0.5, (25, 13)),
                 "default": cls(),
                 "fine": cls("fine", (11, 17), (20, 10, 7, 4, 4, 24), 0.5, (45, 23))}
        if name not in table:
            raise ValueError(f"fidelity = {name!r}: allowed {sorted(table)}")
        return table[name]


@dataclass
class BevelBodies:
    """Compliance of both members for one flank pair (pinion ``side``), reusable over assemblies and torques."""
    side: str
    body1: BodyCompliance
    body2: BodyCompliance
    off1: float
    off2: float
    fid: BevelFidelity
    young: float
    poisson: float
    timings: dict = field(default_factory=dict)


@dataclass
class BevelLoadedModel:
    """One flank pair in one assembly, ready for :func:`ltca.bevel.loaded.solve_position`."""
    pair: BevelPair
    bodies: BevelBodies
    gaps: MeshGaps
    asm: Assembly
    g_ref: float          # gear rotation closing the first contact at phi1 = 0 (TE reference), rad

    @property
    def side(self) -> str:
        return self.bodies.side

    @property
    def fid(self) -> BevelFidelity:
        return self.bodies.fid


def _member(pair: BevelPair, member: str, side: str, fid: BevelFidelity, E: float, nu: float, cache_dir, say):
    bl = pair.blank
    mb, cut = bl.member(member), (pair.pinion if member == "pinion" else pair.gear)
    off = 0.03 * bl.data.module
    fl = {s: generate_flank(cut.flank(s), bl, member, 9, 13, off) for s in ("concave", "convex")}
    jm = 6
    rn = fl["concave"].meta["Rn"][:, jm]
    t_pitch = float(np.interp(0.0, rn, fl["concave"].u))
    # design thickness on the pitch cone at the mean point (a synthesised pinion's two flanks are set apart)
    thick = mb.mean_normal_thickness / (np.cos(bl.data.spiral_angle) * mb.mean_pitch_radius)
    shift = convex_shift(fl["concave"], fl["convex"], mb.z, t_pitch, float(fl["concave"].v[jm]), thick)
    whole = mb.addendum + mb.dedendum
    rim = 1.2 * whole if member == "pinion" else 1.5 * whole
    spec = BevelComplianceSpec(side, LOADED, MESHED, fid.grid, fid.depth if fid.near_field else 0.0, E, nu, rim,
                               fid.divisions)
    return bevel_compliance(fl["concave"], fl["convex"], mb.z, off, shift, spec, cache_dir, say), off


def prepare_bodies(pair: BevelPair, pinion_side: str, fid: BevelFidelity = BevelFidelity(), young: float = 206000.0,
                   poisson: float = 0.3, cache_dir=None, progress=None) -> BevelBodies:
    """Both members' compliance for the flank pair with the pinion ``pinion_side`` loaded."""
    say = progress or (lambda msg: None)
    t0 = time.perf_counter()
    gear_side = "convex" if pinion_side == "concave" else "concave"
    b1, off1 = _member(pair, "pinion", pinion_side, fid, young, poisson, cache_dir, say)
    b2, off2 = _member(pair, "gear", gear_side, fid, young, poisson, cache_dir, say)
    return BevelBodies(pinion_side, b1, b2, off1, off2, fid, young, poisson,
                       {"compliance": time.perf_counter() - t0})


def loaded_model(pair: BevelPair, bodies: BevelBodies, asm: Assembly = Assembly()) -> BevelLoadedModel:
    """The flank pair of ``bodies`` in the assembly ``asm``, with its TE reference."""
    from .cells import pair_minimum
    gaps = MeshGaps(pair, bodies.side, asm)
    lm = BevelLoadedModel(pair, bodies, gaps, asm, 0.0)
    m = pair_minimum(lm, 0.0, 0)
    if m is None:
        raise ValueError(f"assembly {asm}: no contact of the {bodies.side} pinion flank at the mean position")
    return replace(lm, g_ref=float(m.g))
