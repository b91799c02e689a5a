"""Budget case file (TOML): ``[budget]`` torques and initial backlash, ``[[member]]`` list, optional ``[backlash]``.

Every field is checked; a missing, mistyped, out-of-range or unknown one is a :class:`ltca.errors.CaseError`
naming it. The member models are in :mod:`ltca.drivetrain.budget_model`; ``_num`` and ``_known`` also serve
:mod:`ltca.drivetrain.chain_case`.
"""
from __future__ import annotations

import os

import numpy as np

from ltca.drivetrain.budget_model import (DEG, BallSplineMember, DriveTrain, MeshMember, Member, ShaftMember,
                                          TorsionMember)
from ltca.errors import CaseError
from ltca.validation import Int, List, Num, Str, check_kind

__all__ = ["load_budget_case", "budget_from_data", "load_backlash_table"]


#: physically meaningful ranges of every number of the budget and chain kinds (ltca.validation.Num)
BOUNDS = {
    "stiffness_Nm_per_rad": Num(1e-1, 1e10, "N m/rad"), "stiffness_Nm_per_deg": Num(1e-3, 2e8, "N m/deg"),
    "shear_modulus_MPa": Num(100, 5e5, "MPa"), "diameter_mm": Num(0.5, 1e4, "mm"), "length_mm": Num(0.1, 1e5, "mm"),
    "bore_mm": Num(0, 1e4, "mm"), "stiffness_N_per_um_mm": Num(0.1, 100, "N/(um mm)"),
    "face_width_mm": Num(0.5, 5000, "mm"), "base_radius_mm": Num(0.5, 1e4, "mm"),
    "coefficient_N_per_m": Num(1e3, 1e12, "N^(2/3)/m"), "pitch_radius_mm": Num(0.5, 5000, "mm"),
    "ratio": Num(1e-3, 1e3), "initial_backlash_deg": Num(0, 10, "deg"),
    # chain kind
    "fi_um": Num(0, 5000, "um"), "Fpr_um": Num(0, 5000, "um"), "F_um": Num(0, 5000, "um"), "zk": Num(0, 1e4),
    "fp_um": Num(0, 5000, "um"), "pitch_diameter_mm": Num(0.5, 1e5, "mm"), "input_turn_deg": Num(1e-3, 36000, "deg"),
    "closure_tolerance": Num(1e-12, 0.1, lo_open=False), "normal_module_mm": Num(0.1, 100, "mm"),
    "spiral_angle_deg": Num(0, 89.9, "deg"),
}
TORQUES = List(Num(1e-3, 1e7, "N m"), 1, 100)


def _num(tab: dict, key: str, where: str, lo: float | None = 0.0, strict: bool = True,
         default: float | None = None) -> float:
    """A real number from a TOML table, checked against its physical range (:data:`BOUNDS`) and a lower bound;
    CaseError otherwise."""
    val = tab.get(key, default)
    name = f"{where}.{key}"
    if val is None:
        raise CaseError(name, None, "a number is required" + (f"; {BOUNDS[key].words()}" if key in BOUNDS else ""))
    if isinstance(val, bool) or not isinstance(val, (int, float)) or not np.isfinite(val):
        raise CaseError(name, val, "a finite number" + (f"; {BOUNDS[key].words()}" if key in BOUNDS else ""))
    if lo is not None and (val <= lo if strict else val < lo):
        raise CaseError(name, val, f"a number {'>' if strict else '>='} {lo}")
    if key in BOUNDS:
        BOUNDS[key].check(val, name, None)
    return float(val)


def _text(tab: dict, key: str, where: str, default: str = "", non_empty: bool = False) -> str:
    """A string field (name, title, note), type-checked."""
    if key not in tab:
        return default
    return Str(non_empty=non_empty, max_len=2000).check(tab[key], f"{where}.{key}", None)


def _known(tab: dict, allowed: set, where: str) -> None:
    """Reject unknown keys (typos must not pass silently)."""
    if not isinstance(tab, dict):
        raise CaseError(where, tab, f"a table with the keys {sorted(allowed)}")
    for key in tab:
        if key not in allowed:
            raise CaseError(f"{where}.{key}", tab[key], f"one of the keys {sorted(allowed)}")


_MEMBER_KEYS = {
    "torsion": {"stiffness_Nm_per_rad", "stiffness_Nm_per_deg"},
    "shaft": {"shear_modulus_MPa", "diameter_mm", "length_mm", "bore_mm"},
    "mesh": {"stiffness_N_per_um_mm", "face_width_mm", "base_radius_mm"},
    "ball_spline": {"coefficient_N_per_m", "pitch_radius_mm"},
}


def _member(tab: dict, where: str) -> Member:
    if not isinstance(tab, dict):
        raise CaseError(where, tab, "a [[member]] table")
    kind = tab.get("kind")
    if not isinstance(kind, str) or kind not in _MEMBER_KEYS:
        raise CaseError(f"{where}.kind", kind, f"one of {sorted(_MEMBER_KEYS)}")
    name = tab.get("name")
    if not isinstance(name, str) or not name.strip() or len(name) > 200:
        raise CaseError(f"{where}.name", name, "a non-empty string of at most 200 characters")
    _known(tab, _MEMBER_KEYS[kind] | {"kind", "name", "ratio", "note"}, where)
    _text(tab, "note", where)
    ratio = _num(tab, "ratio", where, default=1.0)
    if kind == "torsion":
        given = [k for k in ("stiffness_Nm_per_rad", "stiffness_Nm_per_deg") if k in tab]
        if len(given) != 1:
            raise CaseError(f"{where}.stiffness_Nm_per_rad", None,
                            "exactly one of stiffness_Nm_per_rad, stiffness_Nm_per_deg")
        k = _num(tab, given[0], where) * 1e3 * (1.0 / DEG if given[0].endswith("deg") else 1.0)
        return TorsionMember(name, k, ratio)
    if kind == "shaft":
        d = _num(tab, "diameter_mm", where)
        bore = _num(tab, "bore_mm", where, strict=False, default=0.0)
        if bore >= d:
            raise CaseError(f"{where}.bore_mm", bore, f"a number below diameter_mm = {d}")
        return ShaftMember(name, _num(tab, "shear_modulus_MPa", where), d,
                           _num(tab, "length_mm", where), bore, ratio)
    if kind == "mesh":
        return MeshMember(name, _num(tab, "stiffness_N_per_um_mm", where) * 1e3,
                          _num(tab, "face_width_mm", where), _num(tab, "base_radius_mm", where), ratio)
    # ball spline: c_s [N^(2/3)/m] -> [N^(2/3)/mm]
    return BallSplineMember(name, _num(tab, "coefficient_N_per_m", where) * 1e-3,
                            _num(tab, "pitch_radius_mm", where), ratio)


def load_budget_case(path: str) -> tuple[DriveTrain, np.ndarray]:
    """Read a budget case (TOML): ``[budget]`` torques and initial backlash, ``[[member]]`` list.

    Returns
    -------
    (DriveTrain, torques in N m)

    Raises
    ------
    CaseError
        On a missing, mistyped, out-of-range or unknown field.
    """
    from ..case import read_toml
    return budget_from_data(read_toml(path), path)


def budget_from_data(doc: dict, path: str | None = None) -> tuple[DriveTrain, np.ndarray]:
    """:func:`load_budget_case` of a case already read from TOML; ``path`` names the file in messages."""
    check_kind(doc, "budget", path)
    try:
        _known(doc, {"budget", "member", "backlash"}, "case")
        head = doc.get("budget")
        if not isinstance(head, dict):
            raise CaseError("budget", head, "a [budget] table")
        for old in ("torques_Nm", "torques_nm"):
            if old in head:
                raise CaseError(f"budget.{old}", head[old], "renamed: write torque_nm = a number or a list of "
                                "numbers (N m), the spelling of every case kind")
        _known(head, {"title", "torque_nm", "initial_backlash_deg", "note"}, "budget")
        if "torque_nm" not in head:
            raise CaseError("budget.torque_nm", None, f"required; {TORQUES.words()}")
        t = head["torque_nm"]
        torques = TORQUES.check(t if isinstance(t, list) else [t], "budget.torque_nm", None)
        title = _text(head, "title", "budget")
        _text(head, "note", "budget")
        jphi = _num(head, "initial_backlash_deg", "budget", strict=False, default=0.0) * DEG
        members = doc.get("member")
        if not isinstance(members, list) or not members:
            raise CaseError("member", members, "at least one [[member]] table")
        if len(members) > 1000:
            raise CaseError("member", f"{len(members)} tables", "at most 1000 [[member]] tables")
        train = DriveTrain(tuple(_member(m, f"member[{i}]") for i, m in enumerate(members)), jphi, title)
    except CaseError as exc:
        raise CaseError(exc.field, exc.value, exc.allowed, file=path) from None
    return train, np.asarray(torques, float)



def load_backlash_table(path: str) -> dict | None:
    """The optional ``[backlash]`` table: a cylindrical pair whose double-flank TE gives the backlash curve."""
    from ..case import read_toml
    tab = read_toml(path).get("backlash")
    if tab is None:
        return None
    try:
        if not isinstance(tab, dict):
            raise CaseError("backlash", tab, "a [backlash] table")
        _known(tab, {"pair_case", "thickness_allowance_um", "positions_per_cycle", "cycles"}, "backlash")
        pair = tab.get("pair_case")
        if not isinstance(pair, str):
            raise CaseError("backlash.pair_case", pair, "the path of a cylindrical gear case, relative to this file")
        pair = os.path.join(os.path.dirname(os.path.abspath(path)), pair)
        allow = tab.get("thickness_allowance_um", [0.0, 0.0])
        if (not isinstance(allow, list) or len(allow) != 2
                or any(isinstance(a, bool) or not isinstance(a, (int, float)) or not 0 <= a <= 2000 for a in allow)):
            raise CaseError("backlash.thickness_allowance_um", allow, "[pinion, gear] tooth thinning in um, each "
                            "in [0, 2000]")
        n = Int(1, 200).check(tab.get("positions_per_cycle", 8), "backlash.positions_per_cycle", None)
        cycles = Int(0, 200, note="cycles 0: one pinion revolution").check(tab.get("cycles", 0), "backlash.cycles",
                                                                            None)
    except CaseError as exc:
        raise CaseError(exc.field, exc.value, exc.allowed, file=path) from None
    return {"pair_case": pair, "allowance": [a * 1e-3 for a in allow], "n": n, "cycles": cycles}
