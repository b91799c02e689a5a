"""The optimisation problem, independent of the gear kind: what a backend measures for one candidate, how that
becomes the objective and the constraint violation, and which backend serves a case.

A backend (:class:`ltca.design.cylindrical.CylindricalBackend`, :class:`ltca.design.bevel.BevelBackend`) is any
object with

``kind``
    ``"cylindrical"`` / ``"bevel"``: the key of its variables in :data:`ltca.design.schema.VARIABLES`;
``lead_variables``
    the variables that can move the contact off the edges (the constraint's "impossible at the start" check);
``baseline() -> dict``
    the case's own value of every design variable;
``evaluate(values) -> Measures``
    one candidate: the full analysis (cylindrical: TCA gaps and contact solves; bevel: synthesis, machine
    settings, TCA and LTCA) at every torque of the case, and the edge check under the misalignment tolerance;
``te_ptp(values, torques_nm) -> list``
    loaded TE peak-to-peak (arcsec) at other torques (the Harris map);
``pressure_floor() -> float``
    the lowest peak flank pressure any design can reach at the top torque (MPa);
``settings(values) -> dict``, ``case_dict(values) -> dict``
    the case keys a design sets, and its whole case file (``optimum.toml``);
``prepare(top_torque_nm)``
    the one costly step (the bodies' compliance), for every torque up to the given one;
``torques_nm``, ``prepare_seconds``, ``positions``, ``fidelity``
    the case's torques (N m), the one-off cost and the analysis settings.

The driver (:mod:`ltca.design.driver`) picks the backend of a case and only talks to this interface.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .schema import DesignSpec

__all__ = ["Measures", "Evaluation", "score", "PENALTY"]

#: an infeasible candidate costs its objective plus PENALTY x (1 + 10 x violation) x the start's objective, so the
#: search never prefers it to a feasible one and still sees which infeasible candidates are closer
PENALTY = 1.0


@dataclass(frozen=True)
class Measures:
    """What a backend measures for one candidate.

    Attributes
    ----------
    te_ptp_arcsec : tuple of float
        Loaded TE peak-to-peak at each torque of the case, arcsec.
    flank_pressure_mpa : tuple of float
        Peak flank pressure (edges apart) at each torque, MPa.
    edge_share : float
        Largest share of a position's normal load on the constrained edges at +- the misalignment tolerance (0:
        none, or not checked).
    seconds : float
        Wall time of the candidate, s.
    cycles : int
        Contact cycles solved (one per torque, two more for the misalignment check).
    edge_margin_mm : float
        Bevel: smallest distance of the loaded contact cells to the toe and the heel at the top torque over the
        tolerance box, mm (inf: not measured).
    failure : str
        Bevel: why the geometry cannot make the design (synthesis, machine settings, undercut, no contact); ''
        for a real design. A failed candidate has NaN measures and is infeasible.
    """
    te_ptp_arcsec: tuple[float, ...]
    flank_pressure_mpa: tuple[float, ...]
    edge_share: float
    seconds: float
    cycles: int
    edge_margin_mm: float = math.inf
    failure: str = ""


@dataclass(frozen=True)
class Evaluation:
    """One candidate scored: objective (arcsec), constraint violation (0: feasible) and its parts."""
    values: dict
    measures: Measures
    objective: float
    pressure_violation: float
    edge_violation: float
    design_violation: float = 0.0

    @property
    def violation(self) -> float:
        return self.pressure_violation + self.edge_violation + self.design_violation

    @property
    def feasible(self) -> bool:
        return self.violation <= 0.0

    def penalised(self, scale: float) -> float:
        """The value the optimiser minimises: the objective, plus a penalty when infeasible (see PENALTY)."""
        if self.feasible:
            return self.objective
        if not math.isfinite(self.objective):           # a design the geometry cannot make
            return 2.0 * PENALTY * scale * (1.0 + 10.0 * self.violation)
        return self.objective + PENALTY * scale * (1.0 + 10.0 * self.violation)


def score(spec: DesignSpec, values: dict, m: Measures) -> Evaluation:
    """The objective and the constraint violations of measured candidate ``m``.

    The objective is the loaded TE peak-to-peak at each torque times its weight, the largest
    (``max_te_ptp``) or the weighted mean (``mean_te_ptp``). The pressure violation is the relative excess of
    the largest peak flank pressure over the limit; the edge violation is the edge load share (none allowed).
    Bevel: the shortfall of the edge margin (toe, heel) relative to the required one (at least 0.1 mm) and the
    edge load share above ``max_edge_share``, both at the top torque over the tolerance box. A design the geometry cannot make (``failure``)
    has the design violation 1 and a NaN objective."""
    if m.failure:
        return Evaluation(dict(values), m, math.nan, 0.0, 0.0, 1.0)
    w = spec.weights
    te = [wi * x for wi, x in zip(w, m.te_ptp_arcsec)]
    objective = max(te) if spec.objective == "max_te_ptp" else sum(te) / sum(w)
    lim = spec.constraints.max_flank_pressure_mpa
    p_v = max(0.0, max(m.flank_pressure_mpa) / lim - 1.0) if lim is not None else 0.0
    e_v = m.edge_share if spec.constraints.misalignment_um > 0 else 0.0
    req, lim_share = spec.constraints.edge_margin_mm, spec.constraints.max_edge_share
    if req is not None:
        e_v += max(0.0, req - m.edge_margin_mm) / max(req, 0.1)
    if lim_share is not None:
        e_v += max(0.0, m.edge_share - lim_share)
    return Evaluation(dict(values), m, float(objective), float(p_v), float(e_v))
