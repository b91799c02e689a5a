"""Chain case file (TOML): ``[workpiece]`` and ``[[chain]]`` tables with ``[[chain.element]]``.

Every field is checked, and each chain must close on its required ratio; otherwise a
:class:`ltca.errors.CaseError` names the field. The chains and their evaluation are in
:mod:`ltca.drivetrain.chain_model`.
"""
from __future__ import annotations

import numpy as np

from ltca.drivetrain.budget_case import _known, _num, _text
from ltca.drivetrain.chain_model import DEG, LINKS, Chain, ChainElement, evaluate_chain
from ltca.errors import CaseError
from ltca.validation import check_kind

__all__ = ["load_chain_case", "chain_from_data"]


_ELEMENT_KEYS = {"name", "teeth", "pitch_diameter_mm", "link", "fi_um", "Fpr_um", "F_um", "zk",
                 "fp_um", "turns_factor", "note"}
_CHAIN_KEYS = {"name", "kind", "workpiece_teeth", "mate_teeth", "input_turn_deg",
               "closure_tolerance", "element", "note"}


def _int(tab: dict, key: str, where: str, lo: int = 1, hi: int = 10_000) -> int:
    val = tab.get(key)
    if isinstance(val, bool) or not isinstance(val, int) or not lo <= val <= hi:
        raise CaseError(f"{where}.{key}", val, f"an integer in [{lo}, {hi}]")
    return val


def _element(tab: dict, where: str, first: bool) -> ChainElement:
    if not isinstance(tab, dict):
        raise CaseError(where, tab, "a [[chain.element]] table")
    _known(tab, _ELEMENT_KEYS, where)
    name = tab.get("name")
    if not isinstance(name, str) or not name.strip() or len(name) > 200:
        raise CaseError(f"{where}.name", name, "a non-empty string of at most 200 characters")
    _text(tab, "note", where)
    link = tab.get("link")
    if not isinstance(link, str) or link not in LINKS or (link == "input") != first:
        raise CaseError(f"{where}.link", link, "'input' for the first element only, else "
                        "'mesh' or 'shaft'")
    opt = {k: (_num(tab, k, where, strict=False) if k in tab else None)
           for k in ("fi_um", "Fpr_um", "F_um", "zk", "fp_um")}
    if opt["F_um"] is None and (opt["fi_um"] is None or opt["Fpr_um"] is None):
        raise CaseError(f"{where}.fi_um", opt["fi_um"], "fi_um and Fpr_um (or a printed F_um)")
    turns = tab.get("turns_factor", False)
    if not isinstance(turns, bool):
        raise CaseError(f"{where}.turns_factor", turns, "true or false")
    return ChainElement(name, _int(tab, "teeth", where), _num(tab, "pitch_diameter_mm", where),
                        link, opt["fi_um"], opt["Fpr_um"], opt["F_um"], opt["zk"], opt["fp_um"],
                        turns)


def _chain(tab: dict, where: str, work: dict) -> Chain:
    _known(tab, _CHAIN_KEYS, where)
    _text(tab, "note", where)
    cname = _text(tab, "name", where, default=where, non_empty=True)
    kind = tab.get("kind")
    if not isinstance(kind, str) or kind not in ("indexing", "envelope"):
        raise CaseError(f"{where}.kind", kind, "'indexing' or 'envelope'")
    zp = _int(tab, "workpiece_teeth", where)
    turn = _num(tab, "input_turn_deg", where)
    if kind == "indexing":
        required = 360.0 / (zp * turn)
    else:  # crown gear of a 90 deg pair: zd = sqrt(z1^2 + z2^2) (Nguyen et al. 2020, Table 2)
        required = np.hypot(zp, _int(tab, "mate_teeth", where)) / zp
    els = tab.get("element")
    if not isinstance(els, list) or not 2 <= len(els) <= 500:
        raise CaseError(f"{where}.element", els if not isinstance(els, list) else f"{len(els)} tables",
                        "2 to 500 [[chain.element]] tables")
    elements = tuple(_element(e, f"{where}.element[{i}]", i == 0) for i, e in enumerate(els))
    radius = work["mn"] * zp / (2.0 * np.cos(work["beta"]))
    chain = Chain(cname, kind, turn, float(required), elements, radius,
                  _num(tab, "closure_tolerance", where, default=1e-6))
    ev = evaluate_chain(chain)
    if abs(ev.closure) > chain.closure_tolerance:
        raise CaseError(f"{where}.element", f"ratio {ev.i_nom:.9g}",
                        f"a chain that closes: required ratio {required:.9g} within "
                        f"{chain.closure_tolerance:g} (off by {ev.closure:+.3e})")
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
    try:
        _known(doc, {"machine", "workpiece", "chain"}, "case")
        wp = doc.get("workpiece")
        if not isinstance(wp, dict):
            raise CaseError("workpiece", wp, "a [workpiece] table")
        _known(wp, {"normal_module_mm", "spiral_angle_deg", "note"}, "workpiece")
        _text(wp, "note", "workpiece")
        if "machine" in doc:
            _known(doc["machine"], {"name", "note"}, "machine")
            _text(doc["machine"], "name", "machine")
            _text(doc["machine"], "note", "machine")
        beta = _num(wp, "spiral_angle_deg", "workpiece", strict=False)
        if beta >= 90:
            raise CaseError("workpiece.spiral_angle_deg", beta, "an angle in [0, 90) deg")
        work = {"mn": _num(wp, "normal_module_mm", "workpiece"), "beta": beta * DEG}
        chains = doc.get("chain")
        if not isinstance(chains, list) or not 1 <= len(chains) <= 100:
            raise CaseError("chain", chains if not isinstance(chains, list) else f"{len(chains)} tables",
                            "1 to 100 [[chain]] tables")
        return tuple(_chain(c, f"chain[{i}]", work) for i, c in enumerate(chains))
    except CaseError as exc:
        raise CaseError(exc.field, exc.value, exc.allowed, file=path) from None
