"""The study tasks of a spiral bevel pair: plan a variant, compute one loaded flank's compliance, solve a point.

Reuse. The two FE bodies of a bevel pair live in their own body frames, so their compliance does not depend on
the assembly errors E, P, G and the shaft angle error (:mod:`ltca.bevel.loaded_model`: only the gap evaluator is
rebuilt per assembly), nor on the torque; it depends on the pair (the ``[bevel]`` table: blank, cutter, flank
targets), the material, the mounting, the fidelity and the loaded flank (the torque's sign). The **compliance
key** hashes exactly these, so every variant of a study over the assembly keys and every torque of one sign
share one compliance, computed once on a worker (with the synthesised pair, which the same inputs fix too).

A point is :func:`ltca.bevel.analysis.analyse_torque` over the variant's positions on
:func:`ltca.bevel.loaded_model.loaded_model` of the shared bodies in the variant's assembly, and its dataset and
summary are :func:`ltca.bevel.results.bevel_dataset` (the vocabulary of :mod:`ltca.results`), the functions of
``ltca run``: a point equals a standalone run of that variant at that torque.

Imports ltca.bevel, ltca.errors and geometry.
"""
from __future__ import annotations

import hashlib
import json
import os
import time
from dataclasses import dataclass, replace

from ltca.geometry.bevel.tca import Assembly, BevelPair

from ..bevel.analysis import FLANK, analyse_torque, build_pair, cycle_positions
from ..bevel.case import BevelCase, bevel_case_from_data
from ..bevel.loaded_model import BevelBodies, BevelFidelity, loaded_model, prepare_bodies

__all__ = ["BevelVariantPlan", "BevelCompliance", "plan_variant", "compute_compliance", "solve_point", "side_of"]

#: case tables that do not change the bodies (the assembly errors, the torques, the positions, the names)
_NOT_GEOMETRY = ("assembly", "load", "case")

#: the synthesised pair of each geometry in this worker process (synthesis takes tens of seconds)
_PAIRS: dict[str, BevelPair] = {}


def side_of(torque_nm: float) -> str:
    """The pinion flank loaded by a pinion torque: concave (working) for > 0, convex (coast) for < 0."""
    return "concave" if torque_nm > 0 else "convex"


def _case(case_dict: dict) -> BevelCase:
    return bevel_case_from_data({k: v for k, v in case_dict.items() if k != "design"}, None, "variant")


@dataclass(frozen=True)
class BevelVariantPlan:
    """A planned bevel variant: the hash of its geometry (everything but assembly, torques, positions and names)
    and its fidelity."""
    key: str
    fidelity: str
    seconds: float

    def compliance_key(self, torque_nm: float) -> str:
        """The key of the compliance a point at ``torque_nm`` solves on: the geometry and the loaded flank."""
        return f"{self.key}-{FLANK[side_of(torque_nm)]}"


@dataclass(frozen=True)
class BevelCompliance:
    """One loaded flank's compliance of both members (without their solvers), the synthesised pair, and where
    and how long it was computed."""
    key: str
    pair: BevelPair
    bodies: BevelBodies
    seconds: float
    pid: int


def plan_variant(case_dict: dict) -> BevelVariantPlan:
    """Validate a bevel variant and hash its geometry (no synthesis, no FE work).

    Parameters
    ----------
    case_dict : dict
        The variant's resolved case, as read from TOML.
    """
    t0 = time.perf_counter()
    case = _case(case_dict)
    geo = {k: v for k, v in case_dict.items() if k not in _NOT_GEOMETRY}
    an = dict(geo.get("analysis", {}))
    an.pop("positions", None)
    an["fidelity"] = case.fidelity
    geo["analysis"] = an
    key = hashlib.sha256(json.dumps(geo, sort_keys=True, default=str).encode()).hexdigest()[:24]
    return BevelVariantPlan(key, case.fidelity, time.perf_counter() - t0)


def _pair(key: str, case: BevelCase) -> BevelPair:
    if key not in _PAIRS:
        _PAIRS[key] = build_pair(case)
    return _PAIRS[key]


def compute_compliance(case_dict: dict, vplan: BevelVariantPlan, torque_nm: float) -> BevelCompliance:
    """The synthesised pair and both members' compliance for the flank ``torque_nm`` loads (once per key).

    Parameters
    ----------
    case_dict : dict
        Any variant of that geometry.
    vplan : BevelVariantPlan
        Its plan.
    torque_nm : float
        A pinion torque (N m) of the flank: its sign picks the flank.
    """
    t0 = time.perf_counter()
    case = _case(case_dict)
    pair = _pair(vplan.key, case)
    b = prepare_bodies(pair, side_of(torque_nm), BevelFidelity.named(case.fidelity), case.young, case.poisson,
                       None, None, mounting=case.mounting)
    b = replace(b, body1=b.body1.without_solver(), body2=b.body2.without_solver())
    return BevelCompliance(vplan.compliance_key(torque_nm), pair, b, time.perf_counter() - t0, os.getpid())


def solve_point(case_dict: dict, vplan: BevelVariantPlan, compliance: BevelCompliance, torque_nm: float):
    """The loaded contact of a bevel variant over its positions at one torque, on a shared compliance.

    Parameters
    ----------
    case_dict : dict
        The variant's resolved case.
    vplan : BevelVariantPlan
        Its plan.
    compliance : BevelCompliance
        The compliance of its geometry and of the torque's flank.
    torque_nm : float
        Pinion torque, N m (the sign picks the flank).

    Returns
    -------
    ds : xarray.Dataset
        :func:`ltca.bevel.results.bevel_dataset` of the point, without its torque dimension (position, pair,
        and the bearing pattern over Rn x L).
    head : dict
        Its summary (the keys of ``summary.json`` of ``ltca run``, this torque's).
    """
    from ..bevel.results import bevel_dataset
    if compliance.key != vplan.compliance_key(torque_nm):
        raise ValueError(f"compliance {compliance.key} handed to a point of {vplan.compliance_key(torque_nm)}")
    t0 = time.perf_counter()
    case = _case(case_dict)
    asm = Assembly(**case.assembly)
    lm = loaded_model(compliance.pair, compliance.bodies, asm)
    t1 = time.perf_counter()
    phi = cycle_positions(case.positions, case.basic.z1)
    res = analyse_torque(lm, phi, torque_nm)
    t_contact = time.perf_counter() - t1
    timings = {"geometry": vplan.seconds, "compliance": compliance.seconds, "reference": t1 - t0,
               "contact": t_contact, "contact_per_position": t_contact / len(phi)}
    runs = {side_of(torque_nm): {"lm": lm, torque_nm: res}}
    ds, head, _ = bevel_dataset(case, compliance.pair, asm, compliance.bodies.fid, runs, [torque_nm], timings)
    timings["total"] = time.perf_counter() - t0
    return ds.isel(torque=0, drop=True), head
