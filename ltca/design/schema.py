"""The ``[design]`` table of a case: design variables with bounds, objective, constraints and search settings.

One table serves every backend (:mod:`ltca.design.problem`): the variables a backend offers are declared in
:data:`VARIABLES` (cylindrical: flank modifications; bevel: path angle eta2, TE magnitude m21 and ellipse axis per
flank), everything else is shared. Validation follows :mod:`ltca.validation`: a bad table raises
:class:`ltca.errors.CaseError` naming the dotted field (``design.variables.tip_relief_um.upper``), its value and
what is allowed; the command line turns it into exit status 2. Imports nothing of ours but ltca.errors,
ltca.validation and ltca.case (the fidelity presets).
"""
from __future__ import annotations

from dataclasses import dataclass

from ..case import FIDELITIES
from ..errors import CaseError
from ..validation import Int, List, Num, Str, Table, check_table, table_reference

__all__ = ["VariableKind", "Variable", "Constraints", "DesignSpec", "VARIABLES", "OBJECTIVES", "OPTIMISERS",
           "CYLINDRICAL_EDGES", "parse_design", "design_key_reference", "design_keys"]


@dataclass(frozen=True)
class VariableKind:
    """A design variable a backend offers: unit, the range its bounds must lie in, meaning, and whether it takes
    a ``member`` (pinion, gear or both)."""
    unit: str
    lo: float
    hi: float
    meaning: str
    member: bool = False


#: design variables per backend; a new backend declares its own here and implements them in its evaluator
VARIABLES: dict[str, dict[str, VariableKind]] = {
    "cylindrical": {
        "tip_relief_um": VariableKind("um", 0.0, 500.0, "tip relief C_a at the tip ([*.modifications] "
                                      "tip_relief_um)", True),
        "tip_relief_length_mm": VariableKind("mm", 0.0, 1000.0, "length of the tip relief along the line of action, "
                                             "from its start to the tip (sets tip_relief_start_diameter_mm)", True),
        "profile_crowning_um": VariableKind("um", 0.0, 200.0, "profile crowning C_alpha (profile_crowning_um)", True),
        "lead_crowning_um": VariableKind("um", 0.0, 200.0, "lead crowning C_beta (lead_crowning_um)", True),
        "lead_slope_um": VariableKind("um", -200.0, 200.0, "lead slope f_Hbeta (lead_slope_um)", True),
    },
    # the bevel backend (synthesis -> machine settings -> TCA -> LTCA): ltca.design.bevel
    "bevel": {
        f"{flank}_{key}": VariableKind(unit, lo, hi, f"{flank} flank: {what} (bevel.{flank}.{key})")
        for flank in ("working", "coast")
        for key, unit, lo, hi, what in (("path_angle_deg", "deg", -60.0, 60.0, "contact-path angle eta2"),
                                        ("te_magnitude_arcsec", "arcsec", 1.0, 200.0, "TE parabola magnitude m21"),
                                        ("ellipse_major_mm", "mm", 0.5, 50.0, "contact-ellipse major axis"))
    },
}
#: objectives: the loaded TE peak-to-peak (arcsec) at each of the case's torques, times its weight, then ...
OBJECTIVES = {"max_te_ptp": "the largest over the torques", "mean_te_ptp": "the mean over the torques"}
#: derivative-free optimisers of scipy.optimize (minimize methods, or differential_evolution); "cobyqa-corners" first
#: evaluates the corners of the box and its centre (2^n + 1 candidates, n <= 3) and starts COBYQA from the best (for
#: objectives with several basins, e.g. the bevel TE peak-to-peak over a mesh cycle)
OPTIMISERS = ("cobyqa", "cobyqa-corners", "powell", "nelder-mead", "differential-evolution")
#: edges of a cylindrical pair that may be named in design.constraints.edges (ltca.cylindrical.edges.EDGES)
CYLINDRICAL_EDGES = ("pinion tip edge", "gear tip edge", "pinion form circle", "face end")
MEMBERS = ("pinion", "gear", "both")


@dataclass(frozen=True)
class Variable:
    """One design variable of a case: its bounds, the search's start (None: the case's own value) and the member
    it applies to (cylindrical; ``both``: the same value on pinion and gear)."""
    name: str
    lower: float
    upper: float
    start: float | None
    member: str


@dataclass(frozen=True)
class Constraints:
    """Constraints of the search: peak flank pressure (MPa, at every torque; None: none) and no load at the named
    edges under a lead misalignment of +- ``misalignment_um`` at the top torque (0: not checked). Bevel: at the
    top torque, at the nominal mounting and the 8 corners of the +- (E, P, G) ``tolerance_box`` (mm), the loaded
    cells at least ``edge_margin_mm`` from the toe and the heel, and at most ``max_edge_share`` of a position's
    load on cells at an edge (None: not checked)."""
    max_flank_pressure_mpa: float | None
    misalignment_um: float
    edges: tuple[str, ...]
    edge_margin_mm: float | None = None
    max_edge_share: float | None = None
    tolerance_box: tuple[float, float, float] = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class DesignSpec:
    """A validated ``[design]`` table."""
    kind: str
    variables: tuple[Variable, ...]
    objective: str
    weights: tuple[float, ...]
    constraints: Constraints
    optimiser: str
    max_evaluations: int
    map_variables: tuple[str, str] | None
    map_points: int
    harris_torque_nm: tuple[float, ...]
    fidelity: str | None
    positions: int | None
    seed: int

    def names(self) -> tuple[str, ...]:
        return tuple(v.name for v in self.variables)


_VAR = Table({"lower": Num(-1e6, 1e6, required=True, note="lower bound, in the variable's unit"),
              "upper": Num(-1e6, 1e6, required=True, note="upper bound, in the variable's unit"),
              "start": Num(-1e6, 1e6, note="where the search starts (default: the case's own value)"),
              "member": Str(MEMBERS, default="both")})
_CONSTRAINTS = Table({
    "max_flank_pressure_mpa": Num(1.0, 1e5, "MPa", note="peak flank pressure at every torque, edges apart"),
    "misalignment_um": Num(0.0, 500.0, "um", default=0.0, note="lead misalignment tolerance +-, at the top torque"),
    "edges": List(Str(CYLINDRICAL_EDGES), 1, 8, default=["face end"]),
    "edge_margin_mm": Num(0.0, 20.0, "mm", note="bevel: loaded cells' distance to the toe and the heel"),
    "max_edge_share": Num(0.0, 1.0, note="bevel: largest share of a position's load on edge cells"),
    "tolerance_box": Table({k: Num(0.0, 2.0, "mm", default=0.0, meaning=f"half-width of the {k[0]} tolerance")
                            for k in ("E_mm", "P_mm", "G_mm")}),
})
_DESIGN = Table({
    "variables": Table({}, required=True, extra=lambda k: True),
    "objective": Str(tuple(OBJECTIVES), default="max_te_ptp"),
    "weights": List(Num(0.0, 1e6, lo_open=True), 1, 100),
    "constraints": _CONSTRAINTS,
    "optimiser": Str(OPTIMISERS, default="cobyqa"),
    "max_evaluations": Int(2, 2000, default=20),
    "map_variables": List(Str(max_len=60), 2, 2),
    "map_points": Int(0, 41, default=7),
    "harris_torque_nm": List(Num(1e-3, 1e6, "N m"), 2, 50),
    "fidelity": Str(tuple(FIDELITIES)),
    "positions": Int(2, 400),
    "seed": Int(0, 2 ** 31 - 1, default=0),
})

#: the rows of the case-key reference: (table, key, type, unit, default, allowed, meaning)
_DOC = {
    "objective": ("string", "-", "'max_te_ptp'", "one of " + ", ".join(repr(k) for k in OBJECTIVES),
                  "loaded TE peak-to-peak (arcsec) at each torque of [load], times its weight: the largest or mean"),
    "weights": ("list", "-", "all 1", "a list of positive numbers, one per torque of [load] torque_nm",
                "weight of each torque in the objective"),
    "optimiser": ("string", "-", "'cobyqa'", "one of " + ", ".join(repr(k) for k in OPTIMISERS),
                  "derivative-free optimiser of scipy.optimize, on the variables scaled to [0, 1]"),
    "max_evaluations": ("integer", "-", "20", "an integer in [2, 2000]", "candidate designs the search may evaluate"),
    "map_variables": ("list", "-", "the first two variables", "two variable names of this table",
                      "the two variables of the objective map (the others at the optimum)"),
    "map_points": ("integer", "-", "7", "an integer in [0, 41] (0: no map)", "map points per variable"),
    "harris_torque_nm": ("list", "N m", "8 torques up to 1.5 x the largest", "a list of 2 to 50 numbers in "
                         "[1e-3, 1e6] N m", "torques of the Harris map (TE peak-to-peak against torque)"),
    "fidelity": ("string", "-", "[analysis] fidelity", f"one of {sorted(FIDELITIES)}", "fidelity of every candidate"),
    "positions": ("integer", "-", "[analysis] positions", "an integer in [2, 400]", "positions per mesh cycle of "
                  "every candidate"),
    "seed": ("integer", "-", "0", "an integer in [0, 2^31 - 1]", "random seed of differential-evolution"),
}
_DOC_VAR = {
    "lower": ("number", "variable's", "required", "within the variable's range", "lower bound"),
    "upper": ("number", "variable's", "required", "within the variable's range, above lower", "upper bound"),
    "start": ("number", "variable's", "the case's value", "within [lower, upper]", "where the search starts"),
    "member": ("string", "-", "'both'", "one of 'pinion', 'gear', 'both'", "the member the modification is on "
               "(cylindrical)"),
}
_DOC_CON = {
    "max_flank_pressure_mpa": ("number", "MPa", "none", "a number in [1, 1e5] MPa, above the Hertz pressure of the "
                               "full line contact", "largest peak flank pressure (edges apart) at every torque"),
    "misalignment_um": ("number", "um", "0.0", "a number in [0, 500] um (0: not checked)", "lead misalignment "
                        "tolerance: at the top torque and +- this misalignment the edges below carry no load"),
    "edges": ("list", "-", "['face end']", "names of ltca.cylindrical.edges.EDGES", "edges that must carry no load "
              "under the misalignment tolerance"),
    "edge_margin_mm": ("number", "mm", "none", "a number in [0, 20] mm, below a quarter of the face width "
                       "(bevel)", "bevel: at the top torque, at the nominal mounting and every corner of "
                       "tolerance_box, the loaded contact cells lie at least this far from the toe and the heel "
                       "(cone distance in the gear and the pinion axial section)"),
    "max_edge_share": ("number", "-", "none", "a number in [0, 1] (bevel)", "bevel: at the top torque, at the "
                       "nominal mounting and every corner of tolerance_box, at most this share of a position's "
                       "normal load on cells at an edge (the pinion top at the mesh entry, toe, heel, ...)"),
}


def parse_design(data: dict, kind: str, n_torques: int, file: str | None = None) -> DesignSpec:
    """Validate the ``[design]`` table of a case (as read from TOML) for a backend ``kind`` whose case has
    ``n_torques`` torques.

    Raises
    ------
    CaseError
        Naming the field: unknown variable, bounds reversed or outside the variable's range, start outside the
        bounds, unknown objective or optimiser, weights not one per torque, a map variable not in the table.
    """
    if "design" not in data:
        raise CaseError("design", None, "a [design] table with the variables, objective and constraints "
                        "(see docs/case_keys.md, [design])", file)
    d = check_table(data["design"], _DESIGN, "design", file)
    offered = VARIABLES[kind]
    raw_vars = data["design"]["variables"]
    if not raw_vars:
        raise CaseError("design.variables", "{}", "at least one variable: " + ", ".join(offered), file)
    variables = []
    for name, raw in raw_vars.items():
        path = f"design.variables.{name}"
        if name not in offered:
            raise CaseError(path, raw, f"unknown variable; a {kind} design offers " + ", ".join(offered), file)
        v = check_table(raw, _VAR, path, file)
        vk = offered[name]
        for key in ("lower", "upper"):
            if not vk.lo <= v[key] <= vk.hi:
                raise CaseError(f"{path}.{key}", v[key], f"a number in [{vk.lo:g}, {vk.hi:g}] {vk.unit}", file)
        if v["upper"] <= v["lower"]:
            raise CaseError(f"{path}.upper", v["upper"], f"greater than lower = {v['lower']:g} (bounds reversed or "
                            "empty)", file)
        if v["start"] is not None and not v["lower"] <= v["start"] <= v["upper"]:
            raise CaseError(f"{path}.start", v["start"], f"within the bounds [{v['lower']:g}, {v['upper']:g}]", file)
        if not vk.member and "member" in raw:
            raise CaseError(f"{path}.member", raw["member"], "not given: this variable belongs to no one member", file)
        variables.append(Variable(name, v["lower"], v["upper"], v["start"], v["member"]))
    names = [v.name for v in variables]
    weights = tuple(d["weights"]) if d["weights"] is not None else (1.0,) * n_torques
    if len(weights) != n_torques:
        raise CaseError("design.weights", d["weights"], f"one weight per torque of [load] torque_nm ({n_torques})",
                        file)
    mv = d["map_variables"]
    if mv is not None:
        for i, n in enumerate(mv):
            if n not in names:
                raise CaseError(f"design.map_variables[{i}]", n, "a variable of [design.variables]: "
                                + ", ".join(names), file)
        if mv[0] == mv[1]:
            raise CaseError("design.map_variables[1]", mv[1], "another variable than map_variables[0]", file)
    map_vars = tuple(mv) if mv is not None else (tuple(names[:2]) if len(names) >= 2 else None)
    c = d["constraints"]
    raw_c = data["design"].get("constraints") or {}
    allowed_edges = CYLINDRICAL_EDGES
    if kind == "bevel":
        if "edges" in raw_c:
            raise CaseError("design.constraints.edges", raw_c["edges"], "not given for a bevel case: "
                            "design.constraints.edge_margin_mm keeps the pattern off every edge", file)
        c["edges"] = []
    for i, e in enumerate(c["edges"]):
        if e not in allowed_edges:
            raise CaseError(f"design.constraints.edges[{i}]", e, "one of " + ", ".join(map(repr, allowed_edges)),
                            file)
    box = c["tolerance_box"] or {}
    if kind != "bevel":
        for key in ("edge_margin_mm", "max_edge_share", "tolerance_box"):
            if key in raw_c:
                raise CaseError(f"design.constraints.{key}", raw_c[key], "not given: a bevel constraint", file)
    elif c["misalignment_um"] > 0:
        raise CaseError("design.constraints.misalignment_um", c["misalignment_um"], "not given for a bevel case: "
                        "the mounting tolerances are design.constraints.tolerance_box", file)
    if any(box.get(k, 0.0) > 0 for k in ("E_mm", "P_mm", "G_mm")) and c["edge_margin_mm"] is None \
            and c["max_edge_share"] is None:
        raise CaseError("design.constraints.edge_margin_mm", None, "an edge margin (mm) or max_edge_share for "
                        "the tolerance box to be checked against", file)
    constraints = Constraints(c["max_flank_pressure_mpa"], c["misalignment_um"], tuple(c["edges"]),
                              c["edge_margin_mm"], c["max_edge_share"], tuple(float(box.get(k, 0.0)) for k in ("E_mm", "P_mm", "G_mm")))
    return DesignSpec(kind, tuple(variables), d["objective"], weights, constraints,
                      d["optimiser"], d["max_evaluations"], map_vars, d["map_points"],
                      tuple(d["harris_torque_nm"] or ()), d["fidelity"], d["positions"], d["seed"])


def design_key_reference() -> list[dict]:
    """The ``[design]`` keys as rows of the case-key reference (:func:`ltca.validation.table_reference`'s format),
    walked from :data:`_DESIGN` and :data:`_VAR` (so no accepted key is missing) with the wording of ``_DOC*``
    (defaults and ranges that depend on the case); the free-form ``[design.variables]`` lists the variables each
    backend offers."""
    hand = {("design", k): v for k, v in _DOC.items()} | {("design.constraints", k): v for k, v in _DOC_CON.items()} \
        | {("design.variables.NAME", k): v for k, v in _DOC_VAR.items()}
    walked = table_reference(Table({"design": _DESIGN})) + table_reference(_VAR, "design.variables.NAME")
    rows = []
    for r in walked:
        if r["table"] == "design.variables":          # the free-form table: one row per offered variable below
            continue
        doc = hand.get((r["table"], r["key"]))
        if doc is not None:
            r = dict(r, type=doc[0], unit=doc[1], default=doc[2], allowed=doc[3], meaning=doc[4])
        rows.append({k: v for k, v in r.items() if k != "array"})
    for kind, offered in VARIABLES.items():
        for name, vk in offered.items():
            rows.append(dict(table="design.variables", key=name, type="table", unit=vk.unit, default="-",
                             allowed=f"bounds in [{vk.lo:g}, {vk.hi:g}] {vk.unit}",
                             meaning=f"{kind}: {vk.meaning}"))
    return rows


def design_keys() -> set[str]:
    """Every dotted key of the reference rows (``design.constraints.misalignment_um``, ...)."""
    return {f"{r['table']}.{r['key']}" for r in design_key_reference()}
