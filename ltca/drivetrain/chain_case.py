"""Chain case file (TOML): ``[workpiece]`` and ``[[chain]]`` tables with ``[[chain.element]]``.

The kind is declared as :mod:`ltca.validation` tables (:data:`CASE`); a missing, mistyped, out-of-range or unknown
field is a :class:`ltca.errors.CaseError` naming it. After the table check: the first element alone is the input,
an element gives fi' and Fpr (or a printed F), an envelope chain gives its mate's teeth, and each chain closes on
its required ratio. The chains and their evaluation are in :mod:`ltca.drivetrain.chain_model`.
"""
from __future__ import annotations

import numpy as np

from ltca.drivetrain.chain_model import DEG, LINKS, Chain, ChainElement, evaluate_chain
from ltca.errors import CaseError
from ltca.validation import Bool, Int, Num, Str, Table, TableList, check_kind, check_table

__all__ = ["load_chain_case", "chain_from_data", "CASE"]

_NOTE = Str(max_len=2000, default="", meaning="free text")
_UM = dict(lo=0, hi=5000, unit="um")

#: one gear (or worm, or rack-driven pinion) of a chain
ELEMENT = Table({
    "name": Str(non_empty=True, max_len=200, required=True, meaning="the element's name in tables"),
    "teeth": Int(1, 10_000, required=True, meaning="teeth z (starts of a worm)"),
    "pitch_diameter_mm": Num(0.5, 1e5, "mm", required=True, meaning="pitch diameter D in dphi = 2 F / D"),
    "link": Str(LINKS, required=True, meaning="'input': the first element only; 'mesh': driven by the previous "
                                              "element; 'shaft': on the previous element's shaft"),
    "fi_um": Num(**_UM, meaning="kinematic error fi' (with Fpr_um, or a printed F_um)"),
    "Fpr_um": Num(**_UM, meaning="cumulative pitch error Fpr"),
    "F_um": Num(**_UM, meaning="printed total error F, overrides fi + zk fp"),
    "zk": Num(0, 1e4, meaning="printed teeth zk, overrides frac(turns) z"),
    "fp_um": Num(**_UM, meaning="printed pitch error fp, overrides Fpr / z"),
    "turns_factor": Bool(default=False, meaning="dphi from F times the element's revolutions (as printed in "
                                                "the source's envelope tables)"),
    "note": _NOTE,
})
#: one kinematic chain
CHAIN = Table({
    "name": Str(non_empty=True, max_len=2000, meaning="the chain's name (default: chain[i])"),
    "kind": Str(("indexing", "envelope"), required=True, meaning="indexing: 1/zp turn of the workpiece per "
                                                                   "input cycle; envelope: the crown-gear ratio"),
    "workpiece_teeth": Int(1, 10_000, required=True, meaning="teeth zp of the workpiece"),
    "mate_teeth": Int(1, 10_000, note="required for an envelope chain", meaning="teeth of the workpiece's mate"),
    "input_turn_deg": Num(1e-3, 36000, "deg", required=True, meaning="rotation of the first element per cycle"),
    "closure_tolerance": Num(1e-12, 0.1, default=1e-6, meaning="allowed |i_nominal / i_required - 1|"),
    "element": TableList(ELEMENT, 2, 500, required=True, meaning="the elements from the input to the workpiece"),
    "note": _NOTE,
})
#: the chain kind
CASE = Table({
    "machine": Table({"name": Str(max_len=2000, default="", meaning="the machine tool"), "note": _NOTE}),
    "workpiece": Table({
        "normal_module_mm": Num(0.1, 100, "mm", required=True, meaning="mean normal module m_n"),
        "spiral_angle_deg": Num(0, 89.9, "deg", required=True, meaning="mean spiral angle beta"),
        "note": _NOTE,
    }, required=True),
    "chain": TableList(CHAIN, 1, 100, required=True, meaning="the kinematic chains"),
})


def _element(e: dict, where: str, first: bool, file: str | None) -> ChainElement:
    if (e["link"] == "input") != first:
        raise CaseError(f"{where}.link", e["link"], "'input' for the first element only, else 'mesh' or 'shaft'",
                        file)
    if e["F_um"] is None and (e["fi_um"] is None or e["Fpr_um"] is None):
        raise CaseError(f"{where}.fi_um", e["fi_um"], "fi_um and Fpr_um (or a printed F_um)", file)
    return ChainElement(e["name"], e["teeth"], e["pitch_diameter_mm"], e["link"], e["fi_um"], e["Fpr_um"],
                        e["F_um"], e["zk"], e["fp_um"], e["turns_factor"])


def _chain(c: dict, where: str, work: dict, file: str | None) -> Chain:
    zp, turn = c["workpiece_teeth"], c["input_turn_deg"]
    if c["kind"] == "indexing":
        required = 360.0 / (zp * turn)
    else:  # crown gear of a 90 deg pair: zd = sqrt(z1^2 + z2^2) (Nguyen et al. 2020, Table 2)
        if c["mate_teeth"] is None:
            raise CaseError(f"{where}.mate_teeth", None, "required for an envelope chain; an integer in "
                            "[1, 10000]", file)
        required = np.hypot(zp, c["mate_teeth"]) / zp
    elements = tuple(_element(e, f"{where}.element[{i}]", i == 0, file) for i, e in enumerate(c["element"]))
    radius = work["mn"] * zp / (2.0 * np.cos(work["beta"]))
    chain = Chain(c["name"] or where, c["kind"], turn, float(required), elements, radius, c["closure_tolerance"])
    ev = evaluate_chain(chain)
    if abs(ev.closure) > chain.closure_tolerance:
        raise CaseError(f"{where}.element", f"ratio {ev.i_nom:.9g}",
                        f"a chain that closes: required ratio {required:.9g} within "
                        f"{chain.closure_tolerance:g} (off by {ev.closure:+.3e})", file)
    return chain


def load_chain_case(path: str) -> tuple[Chain, ...]:
    """Read a chain case (TOML): ``[workpiece]`` and ``[[chain]]`` with ``[[chain.element]]``.

    Raises
    ------
    CaseError
        Naming the field on any bad, unknown or missing value, or a chain that does not close.
    """
    from ..case import read_toml
    return chain_from_data(read_toml(path), path)


def chain_from_data(doc: dict, path: str | None = None) -> tuple[Chain, ...]:
    """:func:`load_chain_case` of a case already read from TOML; ``path`` names the file in messages."""
    check_kind(doc, "chain", path)
    c = check_table(doc, CASE, "", path)
    wp = c["workpiece"]
    work = {"mn": wp["normal_module_mm"], "beta": wp["spiral_angle_deg"] * DEG}
    return tuple(_chain(ch, f"chain[{i}]", work, path) for i, ch in enumerate(c["chain"]))
