"""What limits a spiral bevel design the synthesis cannot make, and a value of that input that works.

The pinion synthesis (Cao et al. 2008; :mod:`ltca.geometry.bevel.design`) meets three targets per flank at the mean
point: the path angle eta2, the TE magnitude and the ellipse axis.  For a given blank not every target can be met:
the path over one mesh cycle may leave the flank (a path along the face on a pair of small spiral angle), the
relative curvature along the path may be too small for the ellipse, the blade through the mean point may need a
negative ratio of roll.  Which target limits is not known in closed form, so :func:`working_values` searches: each
flank the user's targets cannot make is tried again with one target changed (the path angle first, then the
ellipse axis, then the TE magnitude), at a few values stepping away from the user's until one works, then bisected
back towards the user's value; every trial makes the flank as ``ltca tca`` and ``ltca run`` need it (its synthesis,
unloaded TCA over three cycles and separation field on the ideal mounting, and its grid of the FE body), and the
value named is one that was tried and worked.  A gear the cutter cannot cut, or a flank no target change rescues,
is tried with other cutter radii.  Bounded by a number of trials (a wall-time guard besides).

:class:`BevelDesignLimit` (a :class:`ltca.validation.DesignError`: exit 2, one line) carries the values found.
"""
from __future__ import annotations

import logging
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from ltca.geometry.bevel.design import cycle_metrics, synthesize_flank
from ltca.geometry.bevel.generation import MeshingError, standard_gear_cut
from ltca.geometry.bevel.machine import MemberCut
from ltca.geometry.bevel.separation import separation_tca
from ltca.geometry.bevel.tca import RAD_PER_ARCSEC, Assembly, BevelPair, ContactError, tca

from ..validation import DesignError
from .case import case_blank
from .loaded_model import body_grid_flanks

__all__ = ["WorkingValue", "LimitSearch", "BevelDesignLimit", "flank_failure", "working_values"]

log = logging.getLogger(__name__)

#: the flank label of the case for each pinion side
LABEL = {"concave": "working", "convex": "coast"}
#: path angles of the shipped pair (Cao et al. 2008), deg: the first value tried after the user's
_SHIPPED_ETA = {"concave": 22.0, "convex": -14.0}
#: Newton iterations of a trial's control-point design (the designs that work converge in 3 to 6)
_TRIAL_ITER = 8
_FAILURES = (ContactError, MeshingError, ValueError, np.linalg.LinAlgError, FloatingPointError)


@dataclass(frozen=True)
class WorkingValue:
    """One case field that limits the design: the user's value and a value found to work (case units).

    field : dotted case field, e.g. ``"bevel.working.path_angle_deg"``;  value : the user's value;  works : the
    value with which the flank (or the pair, for a blank field) was synthesised and its unloaded TCA ran;
    unit : ``"deg"``, ``"mm"`` or ``"arcsec"``;  failure : what failed with the user's value, one line.
    """
    field: str
    value: float
    works: float
    unit: str
    failure: str

    def words(self) -> str:
        """``'bevel.working.path_angle_deg' = 0 deg is out of reach for this blank: 21 deg works (checked)``."""
        return (f"'{self.field}' = {self.value:g} {self.unit} is out of reach for this blank: {self.works:g} "
                f"{self.unit} works (checked: synthesis, unloaded TCA, separation field and body grid)")


@dataclass(frozen=True)
class LimitSearch:
    """What :func:`working_values` found.

    failure : the first failure with the user's values (one line), or None when the pair is made on the ideal
    mounting (then the assembly errors limit, not the design);  found : one :class:`WorkingValue` per failing
    flank, or one cutter radius, empty when none was found within the budget;  trials : syntheses tried;
    seconds : wall time of the search.
    """
    failure: str | None
    found: tuple[WorkingValue, ...]
    trials: int
    seconds: float


class BevelDesignLimit(DesignError):
    """A bevel design the synthesis cannot make, naming each limiting field and a value found to work.

    ``limits`` : tuple of :class:`WorkingValue` (one per failing flank, or one blank field);  ``failure`` : the
    first failure with the user's values."""

    def __init__(self, failure: str, limits: tuple[WorkingValue, ...], file: str | None = None):
        self.limits, self.failure = tuple(limits), failure
        DesignError.__init__(self, f"spiral bevel synthesis/TCA failed ({failure})",
                             tuple(w.field for w in self.limits), "; ".join(w.words() for w in self.limits),
                             file)


class _Budget:
    """Trials left and the time budget of one search."""

    def __init__(self, trials: int, seconds: float):
        self.trials, self.end, self.used = trials, time.perf_counter() + seconds, 0

    def take(self) -> bool:
        if self.used >= self.trials or time.perf_counter() > self.end:
            return False
        self.used += 1
        return True


def flank_failure(blank, gear: MemberCut, side: str, target, blank_offset: float | None = None,
                  max_iter: int = 20) -> tuple[str | None, BevelPair | None]:
    """(None, the pair with this flank on the pinion) when the pinion flank ``side`` is made for ``target`` as
    ``ltca tca`` and ``ltca run`` need it: synthesised, its unloaded TCA over three cycles and its separation field
    on the ideal mounting, and its grid of the FE body; else (the failure in one line, None).  ``max_iter``: Newton
    iterations of the control-point design (fewer: a quicker refusal of a slow design)."""
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        try:
            fc, _ = synthesize_flank(blank, gear, side, target, blank_offset, max_iter)
            pair = BevelPair(blank, gear, MemberCut("pinion", blank.pinion.z, fc, fc))
            cycle_metrics(tca(pair, side, Assembly(), steps_per_cycle=16, max_cycles=3.0), blank)
            separation_tca(pair, side, Assembly(), steps_per_cycle=16, cycles=3.0)
            _body_grid(fc, blank, "pinion")
        except _FAILURES as exc:
            return _line(exc), None
    return None, pair


def _body_grid(fc, blank, member: str) -> None:
    """The flank's grid of the FE body (:func:`ltca.bevel.loaded_model.body_grid_flanks`); raises its
    MeshingError."""
    body_grid_flanks({"flank": fc}, blank, member)


def _line(exc: BaseException) -> str:
    return f"{type(exc).__name__}: {' '.join(str(exc).split())[:160]}"


def _bisect(works, x0: float, x1: float, steps: int, digits: int, log_scale: bool) -> float:
    """The working value nearest ``x0`` found by ``steps`` bisections between ``x0`` (fails) and ``x1`` (works)."""
    for _ in range(steps):
        mid = float(np.sqrt(x0 * x1)) if log_scale else 0.5 * (x0 + x1)
        mid = round(mid, digits)
        if mid in (round(x0, digits), round(x1, digits)):
            break
        ok = works(mid)
        if ok is None:
            break
        x0, x1 = (x0, mid) if ok else (mid, x1)
    return x1


def _search(works, x0: float, anchors: list[float], digits: int, log_scale: bool, steps: int = 2) -> float | None:
    """The first anchor that works, bisected back towards ``x0``; None if none works (or the budget ends)."""
    for a in anchors:
        ok = works(round(a, digits))
        if ok is None:
            return None
        if ok:
            return _bisect(works, x0, round(a, digits), steps, digits, log_scale)
    return None


def _target_plans(case, side: str) -> list[tuple[str, str, float, list[float], int, bool, Callable]]:
    """(field, unit, user's value, anchors, digits, log scale, target with the field changed) per target field."""
    tg = case.targets[side]
    label = LABEL[side]
    eta = round(float(np.degrees(tg.eta2)), 6)
    steps = [_SHIPPED_ETA[side]] + sorted({eta + d for d in (-30, -20, -10, 10, 20, 30)}, key=lambda a: abs(a - eta))
    etas = [a for a in steps if -60 <= a <= 60 and abs(a - eta) > 0.5]
    ell = float(tg.major_axis)
    te = float(tg.te_magnitude / RAD_PER_ARCSEC)
    return [
        (f"bevel.{label}.path_angle_deg", "deg", eta, etas, 0, False,
         lambda v: replace(tg, eta2=float(np.radians(v)))),
        (f"bevel.{label}.ellipse_major_mm", "mm", ell,
         [a for a in (2 * ell, 0.5 * ell, 3 * ell, 0.3 * ell) if 0.5 <= a <= 50], 1, True,
         lambda v: replace(tg, major_axis=float(v))),
        (f"bevel.{label}.te_magnitude_arcsec", "arcsec", te,
         [a for a in (2 * te, 0.5 * te, 4 * te, 0.25 * te) if 1 <= a <= 200], 1, True,
         lambda v: replace(tg, te_magnitude=float(v) * RAD_PER_ARCSEC)),
    ]


def _flank_value(case, blank, gear, side: str, failure: str, budget: _Budget) -> WorkingValue | None:
    """The first target field of the flank with a value that works (module docstring)."""
    for field, unit, x0, anchors, digits, log_scale, target in _target_plans(case, side):
        seen: dict[float, BevelPair | None] = {}

        def works(v, target=target, seen=seen):
            if v not in seen:
                if not budget.take():
                    return None
                fail, pair = flank_failure(blank, gear, side, target(v), case.blank_offset, _TRIAL_ITER)
                log.debug("%s = %g: %s", field, v, fail or "works")
                seen[v] = pair
            return seen[v] is not None

        found = _search(works, x0, anchors, digits, log_scale)
        if found is not None:
            return WorkingValue(field, x0, found, unit, failure)
        if budget.used >= budget.trials:
            return None
    return None


def _pair_failure(case, cutter_radius: float | None = None) -> tuple[str | None, list[str], object, object]:
    """(failure of the gear cut or None, failing pinion sides, blank, gear) for the case's targets, optionally
    with another cutter radius (mm)."""
    basic = case.basic if cutter_radius is None else replace(case.basic, cutter_radius=cutter_radius)
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore", RuntimeWarning)
        try:
            blank = case_blank(replace(case, basic=basic))
            gear = standard_gear_cut(blank)
            for s in ("concave", "convex"):
                _body_grid(gear.flank(s), blank, "gear")
        except _FAILURES as exc:
            return _line(exc), [], None, None
    fails = {s: flank_failure(blank, gear, s, case.targets[s], case.blank_offset)[0] for s in ("concave", "convex")}
    first = next((f for f in fails.values() if f), None)
    return first, [s for s, f in fails.items() if f], blank, gear


def _cutter_value(case, failure: str, budget: _Budget) -> WorkingValue | None:
    """A cutter radius (a multiple of the mean cone distance, 0.6 to 1.2 as real face-milling heads) with which both
    flanks are made for the user's targets."""
    rc = float(case.basic.cutter_radius)
    Am = case_blank(case).mean_cone_distance
    anchors = sorted({round(f * Am, 1) for f in (0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2)} - {round(rc, 1)},
                     key=lambda a: abs(a - rc))
    for a in anchors:
        if not budget.take():
            return None
        fail, _, _, _ = _pair_failure(case, a)
        log.debug("bevel.cutter_radius_mm = %g: %s", a, fail or "works")
        if fail is None:
            return WorkingValue("bevel.cutter_radius_mm", rc, a, "mm", failure)
    return None


def working_values(case, trials: int = 24, seconds: float = 900.0) -> LimitSearch:
    """Why the case's pinion cannot be made on the ideal mounting, and for each failing flank a target value that
    works (or a cutter radius that works for the whole pair).

    Parameters
    ----------
    case : BevelCase
        A case with synthesis targets (not settings sheets).
    trials, seconds : int, float
        At most this many trials (each a flank's synthesis, unloaded TCA, separation field and body grid, 1 to 4 s
        on one core), and a guard on the wall time: the trials bound the search, so that ``ltca tca`` and ``ltca
        run`` of a case find the same values on a loaded machine.

    Returns
    -------
    LimitSearch
    """
    t0 = time.perf_counter()
    budget = _Budget(trials, seconds)
    failure, sides, blank, gear = _pair_failure(case)
    if failure is None:
        return LimitSearch(None, (), 0, time.perf_counter() - t0)
    found = []
    if blank is not None:
        for side in sides:
            w = _flank_value(case, blank, gear, side, failure, budget)
            if w is None:
                found = []
                break
            found.append(w)
    if not found:
        w = _cutter_value(case, failure, budget)
        found = [w] if w is not None else []
    dt = time.perf_counter() - t0
    log.info("bevel design limit: %s; %d trials, %.1f s: %s", failure, budget.used, dt,
             "; ".join(w.words() for w in found) or "no working value found")
    return LimitSearch(failure, tuple(found), budget.used, dt)
