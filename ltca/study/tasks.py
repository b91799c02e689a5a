"""The three kinds of study task, run on Dask workers: plan a variant, compute a geometry's compliance once, solve
one (variant, torque) point. Each takes and returns plain picklable records, so any worker can run any task.

- :func:`plan_variant`: the variant's pair model and the cheap part of
  :func:`ltca.cylindrical.loaded_model.prepare` (teeth in mesh, both bodies' compliance specs), and the
  **geometry key**: a hash of everything that fixes the two FE bodies (each body's mesh spec hash, i.e. the
  generated tooth outline with teeth, shifts, tip, cutter, thickness; the modelled teeth, bore, rim/web, face
  width and element sizes; and the rest of the compliance spec: loaded teeth and flank, grid, read depth,
  Young's modulus, Poisson's ratio). Variants with the same key share one compliance.
- :func:`compute_compliance`: both bodies' compliance of one geometry, stripped of what only the VTU writer
  needs (mesh, factorisation, patch loads), so it is small enough to hand from worker to worker.
- :func:`solve_point`: the contact cycle of a variant at one torque with a compliance computed before; the
  same functions as ``ltca run`` (:func:`ltca.cylindrical.run.analyse`, ``position_dataset``, ``summary``),
  so a point equals a standalone run of that variant.

A bevel pair's tasks are :mod:`ltca.study.bevel_tasks` (one compliance per loaded flank, shared by every
assembly error and torque of that flank); the three functions here hand a bevel variant on to them, so the
runner is the same for every kind: a kind supplies "plan a variant" (with its compliance key per torque),
"compute a shared compliance" and "solve one point".

Imports ltca.case, ltca.cylindrical and fem.
"""
from __future__ import annotations

import dataclasses
import functools
import hashlib
import os
import time
from dataclasses import dataclass

import numpy as np

from ltca.fem.compliance import BodyCompliance, body_compliance, body_spec

from ..case import FIDELITIES, CylindricalCase, parse_case
from ..cylindrical.loaded_model import BodyPlan, Fidelity, plan_bodies, prepare
from ..cylindrical.model import PairModel, build_model
from ..cylindrical.results import position_dataset, summary
from ..cylindrical.run import analyse, cycle_rolls
from ..errors import CaseError, ConvergenceError

__all__ = ["VariantPlan", "Compliance", "geometry_key", "plan_variant", "compute_compliance", "solve_point",
           "TaskFailure", "unwrap"]


@dataclass(frozen=True)
class TaskFailure:
    """A task's user-level failure (a variant the geometry cannot make: exit status 2; a solve that did not
    converge: 3), returned instead of raised: a raised exception makes each Dask worker log a traceback on the
    console, for a mistake that deserves one line. :func:`unwrap` raises it again on the client."""
    status: int
    message: str
    residual: float = float("nan")
    iterations: int = 0


class VariantError(CaseError):
    """A variant's CaseError (or another exit-2 failure) from a worker, carried back as its one-line message."""

    def __init__(self, message: str):
        CaseError.__init__(self, "variant", None, message)
        self.args = (message,)

    def __str__(self) -> str:
        return self.args[0]


class VariantNotConverged(ConvergenceError):
    """A variant's ConvergenceError from a worker, carried back as its message and residual."""

    def __init__(self, message: str, residual: float, iterations: int):
        RuntimeError.__init__(self, message)
        self.residual, self.iterations = residual, iterations


def unwrap(result):
    """A task's result; a :class:`TaskFailure` raised again as VariantError / VariantNotConverged."""
    if isinstance(result, TaskFailure):
        if result.status == 3:
            raise VariantNotConverged(result.message, result.residual, result.iterations)
        raise VariantError(result.message)
    return result


def _user_errors(fn):
    """Run ``fn``; a failure the command line reports in one line (exit 2 or 3, :func:`ltca.exit_codes.classify`)
    is returned as a :class:`TaskFailure`; a bug is raised as it is (its traceback is wanted)."""
    @functools.wraps(fn)
    def task(*args, **kwargs):
        try:
            return fn(*args, **kwargs)
        except Exception as exc:      # sorted by the command line's own rule (ltca.exit_codes)
            from ..exit_codes import classify
            if isinstance(exc, CaseError):
                return TaskFailure(2, str(exc))
            if isinstance(exc, ConvergenceError):
                return TaskFailure(3, str(exc), float(exc.residual), int(exc.iterations))
            status, message = classify(exc)
            if status == 1:
                raise
            return TaskFailure(status, message, float(getattr(exc, "residual", float("nan"))),
                               int(getattr(exc, "iterations", 0)))
    return task


@dataclass(frozen=True)
class VariantPlan:
    """A planned variant: its geometry key and the body plan (teeth in mesh, compliance specs, Hertz)."""
    key: str
    plan: BodyPlan
    seconds: float

    def compliance_key(self, torque_nm: float) -> str:
        """The key of the compliance a point at ``torque_nm`` solves on (one per geometry: every torque)."""
        return self.key


@dataclass(frozen=True)
class Compliance:
    """Both bodies' compliance of one geometry, and where and how long it was computed."""
    key: str
    body1: BodyCompliance
    body2: BodyCompliance
    seconds: float
    pid: int


def _setup(case_dict: dict) -> tuple[CylindricalCase, PairModel, Fidelity]:
    case = parse_case(case_dict)
    return case, build_model(case), Fidelity.from_preset(FIDELITIES[case.fidelity], case.module)


def geometry_key(model: PairModel, plan: BodyPlan) -> str:
    """SHA-256 (hex, 24 chars) of everything that changes the two FE bodies (see the module docstring).

    Parameters
    ----------
    model : PairModel
        The variant's pair (its generated tooth profiles).
    plan : BodyPlan
        Its compliance specs (:func:`ltca.cylindrical.loaded_model.plan_bodies`).
    """
    h = hashlib.sha256()
    for profile, spec in ((model.pinion, plan.spec1), (model.gear, plan.spec2)):
        h.update(body_spec(profile, spec).spec_hash.encode())
        h.update(repr(tuple((f.name, _plain(getattr(spec, f.name))) for f in dataclasses.fields(spec))).encode())
    return h.hexdigest()[:24]


def _plain(v):
    """Floats and tuples of floats in a repr that does not depend on numpy's scalar types."""
    if isinstance(v, (tuple, list)):
        return tuple(_plain(x) for x in v)
    if isinstance(v, (float, np.floating)):
        return float(v).hex()
    if isinstance(v, np.integer):
        return int(v)
    return v


@_user_errors
def plan_variant(case_dict: dict) -> VariantPlan:
    """Plan one variant (cheap: an unloaded TCA); see the module docstring.

    Parameters
    ----------
    case_dict : dict
        The variant's resolved case, as read from TOML.
    """
    if "bevel" in case_dict:
        from . import bevel_tasks
        return bevel_tasks.plan_variant(case_dict)
    t0 = time.perf_counter()
    case, model, fid = _setup(case_dict)
    plan = plan_bodies(model, fid, cycle_rolls(case.positions, case.pinion.teeth), max(case.torques))
    return VariantPlan(geometry_key(model, plan), plan, time.perf_counter() - t0)


@_user_errors
def compute_compliance(case_dict: dict, vplan: VariantPlan, torque_nm: float | None = None) -> Compliance:
    """Both bodies' compliance of the variant's geometry (the costly step, once per compliance key).

    Parameters
    ----------
    case_dict : dict
        Any variant of that geometry (resolved case, as read from TOML).
    vplan : VariantPlan
        Its plan.
    torque_nm : float, optional
        A torque the compliance serves (picks a bevel pair's loaded flank; not used for a cylindrical pair).
    """
    if not isinstance(vplan, VariantPlan):
        from . import bevel_tasks
        return bevel_tasks.compute_compliance(case_dict, vplan, torque_nm)
    t0 = time.perf_counter()
    _, model, _ = _setup(case_dict)
    bodies = []
    for profile, spec in ((model.pinion, vplan.plan.spec1), (model.gear, vplan.plan.spec2)):
        bodies.append(body_compliance(profile, spec).without_solver())
    return Compliance(vplan.key, bodies[0], bodies[1], time.perf_counter() - t0, os.getpid())


@_user_errors
def solve_point(case_dict: dict, vplan: VariantPlan, compliance: Compliance, torque_nm: float):
    """The loaded contact of one variant over its positions at one torque, with a compliance computed before.

    Parameters
    ----------
    case_dict : dict
        The variant's resolved case.
    vplan : VariantPlan
        Its plan (the same geometry key as ``compliance``).
    compliance : Compliance
        Both bodies of that geometry.
    torque_nm : float
        Pinion torque, N m.

    Returns
    -------
    ds : xarray.Dataset
        :func:`ltca.cylindrical.results.position_dataset` of the point.
    head : dict
        Its :func:`ltca.cylindrical.results.summary` (the keys of ``summary.json``).
    """
    if not isinstance(vplan, VariantPlan):
        from . import bevel_tasks
        return bevel_tasks.solve_point(case_dict, vplan, compliance, torque_nm)
    if compliance.key != vplan.key:
        raise ValueError(f"compliance {compliance.key} handed to a variant of geometry {vplan.key}")
    t0 = time.perf_counter()
    case, model, fid = _setup(case_dict)
    lm = prepare(model, fid, cycle_rolls(case.positions, case.pinion.teeth), max(case.torques),
                 bodies=(compliance.body1, compliance.body2), plan=vplan.plan)
    rolls = cycle_rolls(case.positions, case.pinion.teeth, case.cycles)
    torque = torque_nm * 1e3
    t1 = time.perf_counter()
    results = analyse(lm, rolls, torque)
    t_contact = time.perf_counter() - t1
    ds = position_dataset(lm, results, torque)
    timings = {"geometry": vplan.seconds, "compliance": compliance.seconds, "contact": t_contact,
               "contact_per_position": t_contact / len(rolls), "total": time.perf_counter() - t0}
    head = summary(lm, ds, timings, all(r.residual < 1e-6 for r in results))
    return ds, head
