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

__all__ = ["load_budget_case", "load_backlash_table"]


def _num(tab: dict, key: str, where: str, lo: float | None = 0.0, strict: bool = True,
         default: float | None = None) -> float:
    """A real number from a TOML table, checked against a lower bound; CaseError otherwise."""
    val = tab.get(key, default)
    name = f"{where}.{key}"
    if val is None:
        raise CaseError(name, None, "a number is required")
    if isinstance(val, bool) or not isinstance(val, (int, float)) or not np.isfinite(val):
        raise CaseError(name, val, "a finite number")
    if lo is not None and (val <= lo if strict else val < lo):
        raise CaseError(name, val, f"a number {'>' if strict else '>='} {lo}")
    return float(val)


def _known(tab: dict, allowed: set, where: str) -> None:
    """Reject unknown keys (typos must not pass silently)."""
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
    kind = tab.get("kind")
    if kind not in _MEMBER_KEYS:
        raise CaseError(f"{where}.kind", kind, f"one of {sorted(_MEMBER_KEYS)}")
    name = tab.get("name")
    if not isinstance(name, str) or not name:
        raise CaseError(f"{where}.name", name, "a non-empty string")
    _known(tab, _MEMBER_KEYS[kind] | {"kind", "name", "ratio", "note"}, where)
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
    doc = read_toml(path)
    try:
        _known(doc, {"budget", "member", "backlash"}, "case")
        head = doc.get("budget")
        if not isinstance(head, dict):
            raise CaseError("budget", head, "a [budget] table")
        _known(head, {"title", "torques_Nm", "initial_backlash_deg", "note"}, "budget")
        torques = head.get("torques_Nm")
        if (not isinstance(torques, list) or not torques
                or any(isinstance(t, bool) or not isinstance(t, (int, float)) or not t > 0
                       for t in torques)):
            raise CaseError("budget.torques_Nm", torques, "a non-empty list of numbers > 0")
        jphi = _num(head, "initial_backlash_deg", "budget", strict=False, default=0.0) * DEG
        members = doc.get("member")
        if not isinstance(members, list) or not members:
            raise CaseError("member", members, "at least one [[member]] table")
        train = DriveTrain(tuple(_member(m, f"member[{i}]") for i, m in enumerate(members)),
                           jphi, str(head.get("title", "")))
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
        n = tab.get("positions_per_cycle", 8)
        cycles = tab.get("cycles", 0)
        for key, v, lo in (("positions_per_cycle", n, 1), ("cycles", cycles, 0)):
            if isinstance(v, bool) or not isinstance(v, int) or v < lo:
                raise CaseError(f"backlash.{key}", v, f"an integer >= {lo} (cycles 0: one pinion revolution)")
    except CaseError as exc:
        raise CaseError(exc.field, exc.value, exc.allowed, file=path) from None
    return {"pair_case": pair, "allowance": [a * 1e-3 for a in allow], "n": n, "cycles": cycles}
