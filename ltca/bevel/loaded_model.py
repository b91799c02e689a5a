"""What the bevel LTCA solves on: the generated pair, the flank pair and assembly, both member bodies' compliance.

The bodies (:func:`ltca.fem.bevel_compliance.bevel_compliance`) do not depend on the assembly errors (each lives in
its own body frame), so one :class:`BevelBodies` serves every E, P, G, Sigma and every torque; only the gap
evaluator (:class:`ltca.geometry.bevel.gaps.MeshGaps`) is rebuilt per assembly.
"""
from __future__ import annotations

import logging
import time
from dataclasses import replace

import numpy as np

from ltca.fem.bevel_compliance import BevelComplianceSpec, bevel_compliance
from ltca.fem.solids.bevel_body import convex_shift
from ltca.geometry.bevel.gaps import MeshGaps
from ltca.geometry.bevel.gaps import depth_fraction as body_t
from ltca.geometry.bevel.generation import MeshingError, generate_flank
from ltca.geometry.bevel.tca import Assembly, BevelPair

from .model import LOADED, MESHED, BevelBodies, BevelFidelity, BevelLoadedModel, BevelMounting

__all__ = ["BevelFidelity", "BevelMounting", "BevelBodies", "BevelLoadedModel", "prepare_bodies", "member_flanks",
           "loaded_model", "body_t", "LOADED", "MESHED", "BODY_GRID", "body_grid_offsets", "body_grid_flanks"]

log = logging.getLogger(__name__)


#: (depth, face) nodes of the flank grid a body is built on
BODY_GRID = (9, 13)


def body_grid_offsets(blank) -> tuple[float, float]:
    """Where the body's flank grid starts above the root cone, mm, in the order tried: a little above it; where a
    cutter's fillet does not reach that low (a synthesised pinion of another pair), where the TCA's own grid starts
    (half the clearance)."""
    return 0.03 * blank.data.module, 0.5 * (blank.pinion.dedendum - blank.gear.addendum)


def body_grid_flanks(cuts: dict, blank, member: str) -> tuple[dict, float]:
    """The flanks of ``cuts`` (side -> :class:`ltca.geometry.bevel.machine.FlankCut`) generated on the body's flank
    grid (:data:`BODY_GRID`) at the first of :func:`body_grid_offsets` where all of them generate, and that offset
    (mm); raises the MeshingError of the last offset."""
    offs = body_grid_offsets(blank)
    for k, off in enumerate(offs):
        try:
            return {s: generate_flank(fc, blank, member, *BODY_GRID, off) for s, fc in cuts.items()}, off
        except MeshingError as exc:
            if k == len(offs) - 1:
                raise
            log.info("%s flank grid %.3f mm above the root cone not generated (%s); starting at %.3f mm, where the "
                     "TCA's grid starts", member, off, exc, offs[k + 1])


def member_flanks(pair: BevelPair, member: str) -> tuple[dict, float, float]:
    """The member's two generated flanks on the body's axial grid, the grid's root offset (mm) and the rotation
    of the convex flank that gives the design thickness (rad), as :class:`ltca.fem.solids.bevel_body.BevelBodySpec`
    takes them."""
    bl = pair.blank
    mb, cut = bl.member(member), (pair.pinion if member == "pinion" else pair.gear)
    fl, off = body_grid_flanks({s: cut.flank(s) for s in ("concave", "convex")}, bl, member)
    jm = 6
    rn = fl["concave"].meta["Rn"][:, jm]
    t_pitch = float(np.interp(0.0, rn, fl["concave"].u))
    # design thickness on the pitch cone at the mean point (a synthesised pinion's two flanks are set apart)
    thick = mb.mean_normal_thickness / (np.cos(bl.data.spiral_angle) * mb.mean_pitch_radius)
    shift = convex_shift(fl["concave"], fl["convex"], mb.z, t_pitch, float(fl["concave"].v[jm]), thick)
    return fl, off, shift


def _member(pair: BevelPair, member: str, side: str, fid: BevelFidelity, E: float, nu: float, support, cache_dir,
            say):
    mb = pair.blank.member(member)
    fl, off, shift = member_flanks(pair, member)
    spec = BevelComplianceSpec(side, LOADED, MESHED, fid.grid, fid.depth if fid.near_field else 0.0, E, nu,
                               divisions=fid.divisions, support=support)
    return bevel_compliance(fl["concave"], fl["convex"], mb.z, off, shift, spec, cache_dir, say), off


def prepare_bodies(pair: BevelPair, pinion_side: str, fid: BevelFidelity = BevelFidelity(), young: float = 206000.0,
                   poisson: float = 0.3, cache_dir=None, progress=None,
                   mounting: BevelMounting = BevelMounting()) -> BevelBodies:
    """Both members' compliance for the flank pair with the pinion ``pinion_side`` loaded, each body down to its
    ``mounting`` (the pinion's shaft seat, the gear's back face)."""
    say = progress or (lambda msg: None)
    t0 = time.perf_counter()
    gear_side = "convex" if pinion_side == "concave" else "concave"
    sup = mounting.supports(pair.blank)
    b1, off1 = _member(pair, "pinion", pinion_side, fid, young, poisson, sup["pinion"], cache_dir, say)
    b2, off2 = _member(pair, "gear", gear_side, fid, young, poisson, sup["gear"], cache_dir, say)
    return BevelBodies(pinion_side, b1, b2, off1, off2, fid, young, poisson, mounting,
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
