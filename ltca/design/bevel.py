"""The bevel backend of ``ltca optimise``: each candidate's pinion synthesised from its flank targets (eta2, m21
via the TE magnitude, ellipse axis), its machine settings and undercut checked, then TCA and LTCA over a mesh
cycle at every torque of the case, on bodies whose compliance is computed once.

Reuse. The gear (standard cut) never changes: its compliance is exact for every candidate. The pinion's body
compliance is computed for the start design and reused: a candidate's flank differs from the start's by
micrometres, and :func:`ltca.bevel.loaded_model.loaded_model` takes the new pair with the old bodies (the gaps,
levers and contact cells are the candidate's own). ``optimum/`` is ``ltca run`` of the optimum with a fresh
compliance; their loaded TE against the candidate's is the measured reuse error (``full_analysis`` in design.json).

Synthesis. Only a flank whose targets changed is synthesised (:func:`ltca.geometry.bevel.design.control_point_design`,
the free design and, for a case with ``blank_offset_mm``, the redesign at that offset, as
:func:`ltca.geometry.bevel.design.synthesize_pinion` does): the other flank's cut is the start design's. A candidate the
geometry cannot make (no converged synthesis, contact leaving the flank, settings outside
:data:`ltca.design.bevel_checks.MACHINE_RANGES`, undercut, no loaded contact) is infeasible with its reason.
"""
from __future__ import annotations

import copy
import itertools
import math
import pickle
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from ltca.geometry.bevel.design import control_point_design
from ltca.geometry.bevel.generation import standard_gear_cut
from ltca.geometry.bevel.machine import MemberCut
from ltca.geometry.bevel.synthesis import FlankTarget
from ltca.geometry.bevel.tca import RAD_PER_ARCSEC, Assembly, BevelPair
from ltca.geometry.bevel.undercut import undercut_check

from ..bevel.analysis import cycle_positions
from ..bevel.case import bevel_case_from_data, case_blank
from ..bevel.loaded import solve_position
from ..bevel.loaded_model import BevelFidelity, loaded_model, prepare_bodies
from ..errors import CaseError
from .bevel_checks import cycle_measures, machine_violations
from .pool import backend
from .problem import Measures
from .schema import DesignSpec

__all__ = ["BevelBackend", "SIDES"]


def _pool_cycle(cuts: tuple, torque_nm: float, asm: Assembly | None) -> dict:
    """A pool process's cycle on its copy of the backend (:func:`ltca.design.pool.backend_pool`)."""
    return backend().worker_cycle(cuts, torque_nm, asm)

#: flank name of the case -> pinion side it is cut on
SIDES = {"working": "concave", "coast": "convex"}
_FIELDS = {"path_angle_deg": "eta2", "te_magnitude_arcsec": "te_magnitude", "ellipse_major_mm": "major_axis"}
_CONVERT = {"path_angle_deg": math.radians, "te_magnitude_arcsec": lambda x: x * RAD_PER_ARCSEC,
            "ellipse_major_mm": float}
_FAILURES = (ArithmeticError, ValueError, RuntimeError, np.linalg.LinAlgError)


class BevelBackend:
    """Candidates of a bevel case: checked (:meth:`__init__`, cheap), the start design and both bodies' compliance
    once (:meth:`prepare`), then :meth:`evaluate` per candidate. Parameters as
    :class:`ltca.design.cylindrical.CylindricalBackend`."""
    kind = "bevel"
    #: every bevel variable moves the bearing pattern
    lead_variables = tuple(f"{f}_{k}" for f in SIDES for k in _FIELDS)

    def __init__(self, data: dict, spec: DesignSpec, file: str | None = None, progress=None):
        self.data, self.spec, self.file, self.progress = data, spec, file, progress
        base = copy.deepcopy({k: v for k, v in data.items() if k != "design"})
        self.case = bevel_case_from_data(base, file, Path(file).stem if file else "bevel")
        case = self.case
        if case.cuts:
            raise CaseError("bevel.settings", "settings sheets", "design varies the synthesis targets: give "
                            "[bevel.working] and [bevel.coast] instead of [bevel.settings]", file)
        self.torques_nm = tuple(case.torques)
        self.sides = sorted({"concave" if t > 0 else "convex" for t in self.torques_nm})
        for v in spec.variables:
            flank = v.name.split("_")[0]
            if SIDES[flank] not in self.sides:
                raise CaseError(f"design.variables.{v.name}", f"[{v.lower:g}, {v.upper:g}]", f"a variable of a "
                                f"loaded flank: no torque of [load] torque_nm loads the {flank} flank (a "
                                f"{'positive' if flank == 'working' else 'negative'} pinion torque)", file)
        self.blank = case_blank(case)
        req = spec.constraints.edge_margin_mm
        if req is not None and req >= 0.25 * self.blank.face_width:
            raise CaseError("design.constraints.edge_margin_mm", req, f"a margin below a quarter of the face width "
                            f"({0.25 * self.blank.face_width:.2f} mm): a pattern also needs a length", file)
        self.positions = spec.positions or case.positions
        self.fidelity = spec.fidelity or case.fidelity
        self.fid = BevelFidelity.named(self.fidelity)
        self.asm = Assembly(**case.assembly)
        self.phi = cycle_positions(self.positions, case.basic.z1)
        self.prepare_seconds = 0.0
        self.gear = None
        self.bodies: dict = {}
        self._cuts: dict = {}
        self._start_targets: dict = {}
        #: a process pool started after :meth:`prepare` (it shares the bodies): a candidate's cycles run side by side
        self.pool = None
        self._worker_pair: tuple = (None, None)

    # ------------------------------------------------------------------------------------------ values
    def baseline(self) -> dict[str, float]:
        """The case's own flank targets (``[bevel.working]``, ``[bevel.coast]``) of every design variable."""
        b = self.data["bevel"]
        return {v.name: float(b[v.name.split("_")[0]][v.name.split("_", 1)[1]]) for v in self.spec.variables}

    def start(self) -> dict[str, float]:
        """Where the search starts: the table's ``start`` or the case's value, within the bounds."""
        base = self.baseline()
        return {v.name: v.start if v.start is not None else float(np.clip(base[v.name], v.lower, v.upper))
                for v in self.spec.variables}

    def targets(self, values: dict[str, float]) -> dict[str, FlankTarget]:
        """Pinion side -> flank targets of a design (the case's, with the design variables set)."""
        out = {}
        for flank, side in SIDES.items():
            tg = self.case.targets[side]
            for key, field in _FIELDS.items():
                x = values.get(f"{flank}_{key}")
                if x is not None:
                    tg = replace(tg, **{field: _CONVERT[key](float(x))})
            out[side] = tg
        return out

    def _flank(self, side: str, tg: FlankTarget):
        """The synthesised flank cut of a target (cached), as :func:`synthesize_pinion` makes it."""
        key = (side, tg)
        if key not in self._cuts:
            fc, info = control_point_design(self.blank, self.gear, side, tg)
            off = self.case.blank_offset
            if off is not None:
                fc, info = control_point_design(self.blank, self.gear, side, tg, off, (info["C"], info["D"]), fc)
            if len(self._cuts) > 64:
                self._cuts.pop(next(iter(self._cuts)))
            self._cuts[key] = fc
        return self._cuts[key]

    def pair(self, values: dict[str, float]) -> BevelPair:
        """The pair of a design: the gear, and the pinion synthesised for its targets.

        Raises
        ------
        ValueError, RuntimeError
            The geometry cannot make the design (synthesis, machine ranges, undercut): the reason in the message.
        """
        cuts = {}
        for side, tg in self.targets(values).items():
            fc = self._flank(side, tg)
            bad = machine_violations(fc, self.blank.mean_cone_distance)
            if bad:
                raise ValueError(f"{side} pinion flank: machine settings out of range: " + "; ".join(bad))
            if tg != self._start_targets[side]:
                uc = undercut_check(fc, self.blank, "pinion", 21)
                if uc.undercut:
                    raise ValueError(uc.message)
            cuts[side] = fc
        return BevelPair(self.blank, self.gear, MemberCut("pinion", self.blank.pinion.z, cuts["concave"],
                                                          cuts["convex"]))

    def settings(self, values: dict[str, float]) -> dict[str, float]:
        """The flank targets and the pinion machine settings of a design (deg, mm, arcsec)."""
        pair = self.pair(values)
        out = {}
        for flank, side in SIDES.items():
            tg = self.targets(values)[side]
            out.update({f"bevel.{flank}.path_angle_deg": math.degrees(tg.eta2),
                        f"bevel.{flank}.te_magnitude_arcsec": tg.te_magnitude / RAD_PER_ARCSEC,
                        f"bevel.{flank}.ellipse_major_mm": tg.major_axis})
            ms = pair.pinion.flank(side).machine
            for key in ("radial_setting", "cradle_angle", "root_angle", "center_to_back", "blank_offset",
                        "sliding_base", "ratio_of_roll", "modified_roll_c", "modified_roll_d"):
                x = float(getattr(ms, key))
                out[f"pinion.{side}.{key}" + ("_deg" if "angle" in key else "_mm" if key in (
                    "radial_setting", "center_to_back", "blank_offset", "sliding_base") else "")] = \
                    math.degrees(x) if "angle" in key else x
        return out

    def case_dict(self, values: dict[str, float]) -> dict:
        """The case file of a design as a dict (its [design] table dropped; the optimiser's positions and
        fidelity in [analysis]), for ``optimum.toml``."""
        d = copy.deepcopy({k: v for k, v in self.data.items() if k != "design"})
        for name, x in values.items():
            flank, key = name.split("_", 1)
            d["bevel"][flank][key] = round(float(x), 6)
        d.setdefault("analysis", {}).update(positions=self.positions, fidelity=self.fidelity)
        return d

    # ------------------------------------------------------------------------------------------ analysis
    def prepare(self, top_torque_nm: float) -> None:
        """The gear cut, the start design's pinion and both bodies' compliance for every loaded flank, once."""
        t0 = time.perf_counter()
        self.gear = standard_gear_cut(self.blank)
        self._start_targets = self.targets(self.start())
        try:
            pair = self.pair(self.start())
        except _FAILURES as exc:
            raise CaseError("design.variables", self.start(), f"a start design the geometry can make ({exc})",
                            self.file) from None
        for side in self.sides:
            self.bodies[side] = prepare_bodies(pair, side, self.fid, self.case.young, self.case.poisson,
                                               None, self.progress, mounting=self.case.mounting)
        self.prepare_seconds = time.perf_counter() - t0

    def _cycle(self, pair: BevelPair, torque_nm: float, asm: Assembly | None = None):
        side = "concave" if torque_nm > 0 else "convex"
        lm = loaded_model(pair, self.bodies[side], asm or self.asm)
        return lm, [solve_position(lm, float(p), abs(torque_nm) * 1e3) for p in self.phi]

    def cycle(self, values: dict[str, float], torque_nm: float, asm: Assembly | None = None):
        """A design's loaded cycle at one torque (N m) and mounting (default: the case's): (model, positions)."""
        return self._cycle(self.pair(values), torque_nm, asm)

    def corners(self) -> list[Assembly]:
        """The nominal mounting and the corners of the tolerance box (the nominal alone for a zero box)."""
        box = self.spec.constraints.tolerance_box
        out = [self.asm]
        if any(x > 0 for x in box):
            for s in itertools.product((-1.0, 1.0), repeat=3):
                out.append(replace(self.asm, E=self.asm.E + s[0] * box[0], P=self.asm.P + s[1] * box[1],
                                   G=self.asm.G + s[2] * box[2]))
        return out

    def te_ptp(self, values: dict[str, float], torques_nm) -> list[float]:
        """Loaded TE peak-to-peak (arcsec) of a design at each torque (N m); NaN where it cannot be made."""
        try:
            pair = self.pair(values)
            return [cycle_measures(*self._cycle(pair, t))["te_ptp"] for t in torques_nm]
        except _FAILURES:
            return [math.nan] * len(torques_nm)

    def evaluate(self, values: dict[str, float]) -> Measures:
        """Loaded TE peak-to-peak and peak interior pressure at every torque; the edge load share and the edge
        margin at the top torque over the nominal mounting and the tolerance box's corners. With :attr:`pool`
        the cycles run in its processes (the same numbers: each cycle is computed alone)."""
        t0 = time.perf_counter()
        n = len(self.torques_nm)
        top = max(self.torques_nm, key=abs)
        c = self.spec.constraints
        tasks = [(t, None) for t in self.torques_nm]
        if c.edge_margin_mm is not None or c.max_edge_share is not None:
            tasks += [(top, asm) for asm in self.corners()[1:]]
        try:
            pair = self.pair(values)
            if self.pool is None:
                ms = [cycle_measures(*self._cycle(pair, t, asm)) for t, asm in tasks]
            else:
                cuts = (pair.pinion.concave, pair.pinion.convex)
                ms = self.pool.starmap(_pool_cycle, [(cuts, t, asm) for t, asm in tasks], chunksize=1)
        except _FAILURES as exc:
            return Measures((math.nan,) * n, (math.nan,) * n, 0.0, time.perf_counter() - t0, 1,
                            math.inf, f"{type(exc).__name__}: {exc}"[:400])
        at_top = [ms[self.torques_nm.index(top)]] + ms[n:]
        share, margin = max(m["edge_share"] for m in at_top), min(m["margin"] for m in at_top)
        return Measures(tuple(m["te_ptp"] for m in ms[:n]), tuple(m["pressure"] for m in ms[:n]), share,
                        time.perf_counter() - t0, len(tasks), margin)

    def worker_cycle(self, cuts: tuple, torque_nm: float, asm: Assembly | None) -> dict:
        """:func:`ltca.design.bevel_checks.cycle_measures` of a candidate pinion's cycle in a pool process (the
        pinion's cuts are sent; the pair is kept for the candidate's next cycles, so is its flank table)."""
        key = pickle.dumps(cuts)
        if self._worker_pair[0] != key:
            self._worker_pair = (key, BevelPair(self.blank, self.gear, MemberCut("pinion", self.blank.pinion.z,
                                                                                    *cuts)))
        return cycle_measures(*self._cycle(self._worker_pair[1], torque_nm, asm))

    def box_report(self, values: dict[str, float]) -> dict:
        """A design at the top torque at the nominal mounting and each corner of the tolerance box: loaded TE
        peak-to-peak, toe / heel margin (``edge_margin_mm``), top margin, edge load share, the edges loaded and
        the peak interior pressure (:mod:`ltca.design.bevel_checks`; the seed-vs-optimum table)."""
        pair = self.pair(values)
        top = max(self.torques_nm, key=abs)
        rows = []
        for asm in self.corners():
            m = cycle_measures(*self._cycle(pair, top, asm))
            rows.append({"E_mm": asm.E, "P_mm": asm.P, "G_mm": asm.G, "te_ptp_arcsec": m["te_ptp"],
                         "edge_margin_mm": m["margin"], "top_margin_mm": m["top_margin"],
                         "edge_share": m["edge_share"], "edges": m["edges"],
                         "max_interior_pressure_mpa": m["pressure"]})
        return {"torque_nm": top, "corners": rows}

    def pressure_floor(self) -> float:
        """A true lower bound of the peak flank pressure at the top torque (MPa): the gear's normal load (at
        least T2 over its outer pitch radius) spread evenly over the whole working flank of every pair that can
        carry load (three)."""
        bl = self.blank
        T2 = max(abs(t) for t in self.torques_nm) * 1e3 * bl.gear.z / bl.pinion.z
        F = T2 / (0.5 * bl.data.module * bl.gear.z)
        return F / (3 * bl.face_width * (bl.gear.addendum + bl.pinion.addendum))

    def full_run(self, case_path: Path, out: Path) -> dict:
        """``ltca run`` of a design's case file (synthesis and compliance afresh): TE peak-to-peak per torque."""
        import contextlib
        import io

        from ..driver import run_to_dir
        with contextlib.redirect_stdout(io.StringIO()):
            s = run_to_dir(str(case_path), str(out), positions=self.positions, fidelity=self.fidelity, progress=False)
        return {f"{v['torque_nm']:g}": v["te_loaded_ptp_arcsec"] for v in s["torques"]}
