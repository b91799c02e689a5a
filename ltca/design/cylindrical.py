"""The cylindrical backend of ``ltca optimise``: flank modifications evaluated by TCA gaps and contact solves on
bodies whose compliance is computed once.

The FE compliance of both bodies depends on the generated tooth outlines, the rim and the bore, never on the
micrometre flank modifications or the misalignment: those only change the gaps of the contact problem
(:func:`ltca.cylindrical.tca.flank_gaps`). :class:`CylindricalBackend` therefore calls
:func:`ltca.cylindrical.loaded_model.prepare` once; each candidate is a new :class:`PairModel` (profiles and
modifications, a few ms) on the same :class:`LoadedModel` bodies, then the contact cycle per torque
(:func:`ltca.cylindrical.run.analyse`), exactly as ``ltca run`` solves it.

The tip-relief length is measured along the line of action from the relief's start to the tip (the roll length
L_tip - L_start, mm); it sets ``tip_relief_start_diameter_mm`` = 2 sqrt(r_b^2 + (L_tip - length)^2) of each member.
"""
from __future__ import annotations

import dataclasses
import math
import time

import numpy as np

from ..case import FIDELITIES, CylindricalCase, parse_case
from ..cylindrical.edges import EDGES, position_edges
from ..cylindrical.loaded_model import Fidelity, LoadedModel, hertz_line, prepare
from ..cylindrical.model import PairModel, build_model
from ..cylindrical.run import analyse, cycle_rolls
from ..cylindrical.sampling import default_positions
from ..cylindrical.tca import ARCSEC_PER_RAD
from ..cylindrical.warnings import check_contact, contact_ratio_transverse
from ..errors import CaseError
from .problem import Measures
from .schema import DesignSpec

__all__ = ["CylindricalBackend"]

#: design variable -> key of [*.modifications] (the tip-relief length sets the start diameter instead)
_KEYS = {"tip_relief_um": "tip_relief_um", "profile_crowning_um": "profile_crowning_um",
         "lead_crowning_um": "lead_crowning_um", "lead_slope_um": "lead_slope_um",
         "tip_relief_length_mm": "tip_relief_start_diameter_mm"}
_FIELDS = {"tip_relief_um": "tip_relief", "profile_crowning_um": "profile_crowning",
           "lead_crowning_um": "lead_crowning", "lead_slope_um": "lead_slope"}


class CylindricalBackend:
    """Candidates of a cylindrical case: the pair checked (:meth:`__init__`, cheap), the compliance once
    (:meth:`prepare`), then :meth:`evaluate` per candidate.

    Parameters
    ----------
    data : dict
        The case as read from TOML (its ``[design]`` table included).
    spec : DesignSpec
        The validated ``[design]`` table.
    file : str, optional
        The case file, for messages.
    progress : callable, optional
        Receives one-line progress messages.
    """
    kind = "cylindrical"
    #: variables that move the contact along the face: the only ones that can free the face ends under misalignment
    lead_variables = ("lead_crowning_um", "lead_slope_um")

    def __init__(self, data: dict, spec: DesignSpec, file: str | None = None, progress=None):
        self.data, self.spec, self.file = data, spec, file
        self.case: CylindricalCase = parse_case(data, file)
        self.model: PairModel = build_model(self.case)
        check_contact(self.model, file)
        self._check_lengths()
        case = self.case
        fid_name = spec.fidelity or case.fidelity
        self.positions = spec.positions or (default_positions(self.model) if case.positions_auto else case.positions)
        self.fidelity = fid_name
        self.torques_nm = tuple(t * 1e-3 for t in case.torques)
        self.rolls = cycle_rolls(self.positions, case.pinion.teeth, case.cycles)
        self.lm: LoadedModel | None = None
        self.prepare_seconds = 0.0
        self.progress = progress

    def prepare(self, top_torque_nm: float) -> None:
        """Both bodies' compliance, once, for every torque up to ``top_torque_nm`` (N m): the costly step."""
        case = self.case
        fid = Fidelity.from_preset(FIDELITIES[self.fidelity], case.module)
        t0 = time.perf_counter()
        self.lm = prepare(self.model, fid, cycle_rolls(self.positions, case.pinion.teeth),
                          1e3 * max(top_torque_nm, max(case.torques) * 1e-3), progress=self.progress)
        self.prepare_seconds = time.perf_counter() - t0

    # ------------------------------------------------------------------------------------------ values
    def _members(self, member: str) -> tuple[str, ...]:
        return ("pinion", "gear") if member == "both" else (member,)

    def _roll_lengths(self, name: str) -> tuple[float, float, float]:
        """Base radius, roll length at the tip and at the form circle of a member, mm."""
        p = self.model.pinion if name == "pinion" else self.model.gear
        r_form = max(p.r_form_left, p.r_form_right)
        return p.r_base, math.sqrt(p.r_tip ** 2 - p.r_base ** 2), math.sqrt(max(r_form ** 2 - p.r_base ** 2, 0.0))

    def _check_lengths(self) -> None:
        for v in self.spec.variables:
            if v.name != "tip_relief_length_mm":
                continue
            if v.lower <= 0:
                raise CaseError(f"design.variables.{v.name}.lower", v.lower, "a length > 0 mm (the relief starts "
                                "below the tip)", self.file)
            for m in self._members(v.member):
                if m == "gear" and self.model.gear.internal:
                    raise CaseError(f"design.variables.{v.name}.member", v.member, "'pinion': the tip relief of a "
                                    "ring gear is not a design variable", self.file)
                _, L_tip, L_form = self._roll_lengths(m)
                if v.upper >= L_tip - L_form:
                    raise CaseError(f"design.variables.{v.name}.upper", v.upper, f"below the {m}'s active roll "
                                    f"length {L_tip - L_form:.3f} mm (the relief starts above the form circle)",
                                    self.file)

    def baseline(self) -> dict[str, float]:
        """The case's own value of every design variable (for ``both``: the pinion's)."""
        out = {}
        for v in self.spec.variables:
            m = self._members(v.member)[0]
            mods = getattr(self.case, m).modifications
            if v.name == "tip_relief_length_mm":
                rb, L_tip, _ = self._roll_lengths(m)
                prof = self.model.pinion if m == "pinion" else self.model.gear
                rs = 0.5 * mods.tip_relief_start_diameter if mods.tip_relief_start_diameter else \
                    prof.r_tip - 0.4 * (prof.r_tip - max(prof.r_form_left, prof.r_form_right))
                out[v.name] = L_tip - math.sqrt(max(rs ** 2 - rb ** 2, 0.0))
            else:
                out[v.name] = 1e3 * getattr(mods, _FIELDS[v.name])
        return out

    def settings(self, values: dict[str, float]) -> dict[str, float]:
        """The case keys a design sets (``pinion.modifications.tip_relief_um`` -> value in the key's unit)."""
        out = {}
        for v in self.spec.variables:
            for m in self._members(v.member):
                x = values[v.name]
                if v.name == "tip_relief_length_mm":
                    rb, L_tip, _ = self._roll_lengths(m)
                    x = 2 * math.sqrt(rb ** 2 + (L_tip - x) ** 2)
                out[f"{m}.modifications.{_KEYS[v.name]}"] = float(x)
        return out

    def case_dict(self, values: dict[str, float]) -> dict:
        """The case file of a design as a dict (its [design] table dropped), for ``optimum.toml``."""
        import copy
        d = copy.deepcopy({k: v for k, v in self.data.items() if k != "design"})
        for key, x in self.settings(values).items():
            m, _, k = key.split(".")
            d.setdefault(m, {}).setdefault("modifications", {})[k] = round(x, 6)
        return d

    def case_with(self, values: dict[str, float], misalignment_um: float = 0.0) -> CylindricalCase:
        """The validated case of a design (and an extra lead misalignment, um)."""
        case = parse_case(self.case_dict(values), self.file)
        if misalignment_um:
            case = dataclasses.replace(case, lead_misalignment=case.lead_misalignment + 1e-3 * misalignment_um)
        return case

    # ------------------------------------------------------------------------------------------ analysis
    def loaded(self, values: dict[str, float], misalignment_um: float = 0.0) -> LoadedModel:
        """The compliance computed once with the gaps of this design."""
        return dataclasses.replace(self.lm, model=build_model(self.case_with(values, misalignment_um)))

    def _cycle(self, lm: LoadedModel, torque_nm: float):
        return analyse(lm, self.rolls, 1e3 * torque_nm)

    def te_ptp(self, values: dict[str, float], torques_nm) -> list[float]:
        """Loaded TE peak-to-peak (arcsec) of a design at each torque (N m): the Harris map."""
        lm = self.loaded(values)
        return [float(np.ptp([r.theta for r in self._cycle(lm, t)])) / lm.model.pair.ratio * ARCSEC_PER_RAD
                for t in torques_nm]

    def evaluate(self, values: dict[str, float]) -> Measures:
        """Loaded TE peak-to-peak and peak flank pressure at every torque, and the largest share of the normal
        load on the constrained edges at +- the misalignment tolerance at the top torque."""
        t0 = time.perf_counter()
        lm = self.loaded(values)
        ptp, pressure, cycles = [], [], 0
        for t in (x * 1e-3 for x in self.case.torques):
            res = self._cycle(lm, t)
            cycles += 1
            ptp.append(float(np.ptp([r.theta for r in res])) / lm.model.pair.ratio * ARCSEC_PER_RAD)
            pressure.append(max(position_edges(lm, r, 1e3 * t)["flank_peak"] for r in res))
        share = 0.0
        tol = self.spec.constraints.misalignment_um
        if tol > 0:
            top = max(self.case.torques) * 1e-3
            idx = [EDGES.index(e) for e in self.spec.constraints.edges]
            for sign in (+1.0, -1.0):
                lm_m = self.loaded(values, sign * tol)
                for r in self._cycle(lm_m, top):
                    e = position_edges(lm_m, r, 1e3 * top)
                    share = max(share, float(e["edge_load"][idx].sum() / max(r.force.sum(), 1e-300)))
                cycles += 1
        return Measures(tuple(ptp), tuple(pressure), share, time.perf_counter() - t0, cycles)

    # ------------------------------------------------------------------------------------------ design rules
    def pressure_floor(self) -> float:
        """The lowest peak flank pressure any modification can give at the top torque (MPa): the Hertz pressure of
        the normal load spread evenly over the longest contact lines the pair can have, ceil(eps_alpha + eps_beta)
        face widths, with the largest relative radius of curvature on the active path. Crowning, relief and
        errors concentrate the load and only raise the peak."""
        model, case = self.model, self.case
        p1, p2 = model.pinion, model.gear
        eps_b = abs(model.face_width * math.sin(case.helix_angle) / (math.pi * case.module))
        length = math.ceil(contact_ratio_transverse(model) + eps_b) * model.face_width / math.cos(p1.beta_b)
        w = max(case.torques) / (p1.r_base * math.cos(p1.beta_b)) / length
        loa = model.pair.a * math.sin(model.pair.alpha_w)
        rho1 = np.linspace(math.sqrt(max(p1.r_form_right ** 2 - p1.r_base ** 2, 0.0)),
                           math.sqrt(p1.r_tip ** 2 - p1.r_base ** 2), 200)
        rho2 = (rho1 - loa) if p2.internal else (loa - rho1)
        ok = rho2 > 1e-6 if not p2.internal else rho2 > rho1 + 1e-6
        R = (rho1 * rho2 / (rho2 - rho1) if p2.internal else rho1 * rho2 / (rho1 + rho2))[ok]
        return hertz_line(w, float(R.max()) / math.cos(p1.beta_b), case.young, case.poisson)[1]

    def pair_deflection_um(self, torque_nm: float, values: dict[str, float] | None = None) -> dict:
        """The tooth-pair deflection at a torque from our own LTCA, for the classic rule "linear tip relief = the
        deflection of the tooth pair at the design load": delta = F_bt / (b c_gamma), the load on the line of action
        over the face width and the mesh stiffness c_gamma (ISO 6336-1: the mean over the mesh cycle; the
        ``mesh_stiffness_mean_n_per_mm_um`` of ``ltca run``), of the case's own modifications (or ``values``).

        Also returned, as the bounds of the rule: with the single-pair stiffness c' (the largest mesh stiffness
        where one pair carries the load) the whole approach of one pair, body included; and the pair's own part,
        2 (delta_1 - delta_2) from the approach with one pair (delta_1) and with two sharing (delta_2), without the
        deflection common to every pair (rim, web, bore), which a relief does not need to take up."""
        from ..cylindrical.results import mesh_stiffness
        lm = self.loaded(values or self.baseline())
        res = self._cycle(lm, torque_nm)
        c = mesh_stiffness(lm, np.array([r.theta for r in res]), np.array([r.theta0 for r in res]), 1e3 * torque_nm)
        pairs = np.array([sum(v > 1e-3 * r.force.sum() for v in r.pair_load.values()) for r in res])
        F_t = 1e3 * torque_nm / self.model.pinion.r_base       # transverse load on the line of action, N
        w = F_t / self.model.face_width                       # N/mm
        out = {"deflection_um": float(w / c.mean()), "mesh_stiffness_n_per_mm_um": float(c.mean())}
        if (pairs == 1).any():
            d1 = w / c[pairs == 1].max()
            out.update(single_pair_stiffness_n_per_mm_um=float(c[pairs == 1].max()), deflection_single_pair_um=d1)
            if (pairs == 2).any():
                out["deflection_pair_only_um"] = float(2 * (d1 - w / c[pairs == 2].max()))
        return out
