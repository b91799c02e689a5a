"""Budget case file (TOML): ``[budget]`` torques and initial backlash, ``[[member]]`` list, optional ``[backlash]``.

The kind is declared as :mod:`ltca.validation` tables (:data:`CASE`); a missing, mistyped, out-of-range or unknown
field is a :class:`ltca.errors.CaseError` naming it, the cross-field checks (one stiffness of a torsion member, a
bore below the diameter) follow the table check. The member models are in :mod:`ltca.drivetrain.budget_model`.
"""
from __future__ import annotations

import os

import numpy as np

from ltca.drivetrain.budget_model import (
    DEG,
    BallSplineMember,
    DriveTrain,
    Member,
    MeshMember,
    ShaftMember,
    TorsionMember,
)
from ltca.errors import CaseError
from ltca.validation import Int, List, Num, OneOrList, Str, Table, TableList, Tagged, check_kind, check_table

__all__ = ["load_budget_case", "budget_from_data", "load_backlash_table", "CASE"]

_NOTE = Str(max_len=2000, default="", meaning="free text")
_COMMON = {
    "name": Str(non_empty=True, max_len=200, required=True, meaning="the member's name in tables and plots"),
    "ratio": Num(1e-3, 1e3, default=1.0, meaning="speed of the member's shaft over the reference shaft's; the "
                                                 "member's twist is seen divided by it at the reference"),
    "note": _NOTE,
}


def _member_table(kind: str, **fields) -> Table:
    return Table({"kind": Str((kind,), required=True), **_COMMON, **fields})


#: the four member kinds and their stiffness data (physically meaningful ranges)
MEMBER = Tagged("kind", {
    "torsion": _member_table(
        "torsion",
        stiffness_Nm_per_rad=Num(1e-1, 1e10, "N m/rad", meaning="torsional stiffness (give it or the next)"),
        stiffness_Nm_per_deg=Num(1e-3, 2e8, "N m/deg", meaning="torsional stiffness per degree")),
    "shaft": _member_table(
        "shaft",
        shear_modulus_MPa=Num(100, 5e5, "MPa", required=True, meaning="shear modulus G"),
        diameter_mm=Num(0.5, 1e4, "mm", required=True, meaning="outer diameter"),
        length_mm=Num(0.1, 1e5, "mm", required=True, meaning="twisted length"),
        bore_mm=Num(0, 1e4, "mm", default=0.0, note="below diameter_mm", meaning="bore of a hollow shaft")),
    "mesh": _member_table(
        "mesh",
        stiffness_N_per_um_mm=Num(0.1, 100, "N/(um mm)", required=True,
                                  meaning="mesh stiffness per face width (ISO 6336-1 c_gamma)"),
        face_width_mm=Num(0.5, 5000, "mm", required=True, meaning="face width in contact"),
        base_radius_mm=Num(0.5, 1e4, "mm", required=True, meaning="base radius of the member's gear")),
    "ball_spline": _member_table(
        "ball_spline",
        coefficient_N_per_m=Num(1e3, 1e12, "N^(2/3)/m", required=True,
                                meaning="Hertzian coefficient c_s of k = c_s P^(1/3)"),
        pitch_radius_mm=Num(0.5, 5000, "mm", required=True, meaning="ball pitch radius")),
}, meaning="the member's model: torsion spring, shaft, gear mesh or ball spline")

#: the optional backlash curve of a cylindrical pair (its unloaded double-flank TE)
BACKLASH = Table({
    "pair_case": Str(non_empty=True, max_len=1000, required=True,
                     meaning="the path of a cylindrical gear case, relative to this file"),
    "thickness_allowance_um": List(Num(0, 2000, "um"), 2, 2, default=[0.0, 0.0],
                                   meaning="[pinion, gear] normal tooth thinning"),
    "positions_per_cycle": Int(1, 200, default=8, meaning="positions per mesh cycle of the TE"),
    "cycles": Int(0, 200, default=0, note="0: one pinion revolution", meaning="mesh cycles of the TE"),
})

TORQUES = OneOrList(Num(1e-3, 1e7, "N m"), 1, 100, required=True,
                    meaning="torques at the reference shaft; one budget each")

#: the budget kind
CASE = Table({
    "budget": Table({
        "title": Str(max_len=2000, default="", meaning="title of the tables and plots"),
        "torque_nm": TORQUES,
        "initial_backlash_deg": Num(0, 10, "deg", default=0.0, meaning="initial backlash j_phi0 of the pair"),
        "note": _NOTE,
    }, required=True),
    "member": TableList(MEMBER, 1, 1000, required=True, meaning="the members in series"),
    "backlash": BACKLASH,
})


def _member(m: dict, raw: dict, where: str, file: str | None) -> Member:
    """A member's model from its checked table ``m`` (``raw``: as written, to see which keys are given)."""
    name, ratio, kind = m["name"], m["ratio"], m["kind"]
    if kind == "torsion":
        given = [k for k in ("stiffness_Nm_per_rad", "stiffness_Nm_per_deg") if k in raw]
        if len(given) != 1:
            raise CaseError(f"{where}.stiffness_Nm_per_rad", None,
                            "exactly one of stiffness_Nm_per_rad, stiffness_Nm_per_deg", file)
        k = m[given[0]] * 1e3 * (1.0 / DEG if given[0].endswith("deg") else 1.0)
        return TorsionMember(name, k, ratio)
    if kind == "shaft":
        if m["bore_mm"] >= m["diameter_mm"]:
            raise CaseError(f"{where}.bore_mm", m["bore_mm"], f"a number below diameter_mm = {m['diameter_mm']}",
                            file)
        return ShaftMember(name, m["shear_modulus_MPa"], m["diameter_mm"], m["length_mm"], m["bore_mm"], ratio)
    if kind == "mesh":
        return MeshMember(name, m["stiffness_N_per_um_mm"] * 1e3, m["face_width_mm"], m["base_radius_mm"], ratio)
    # ball spline: c_s [N^(2/3)/m] -> [N^(2/3)/mm]
    return BallSplineMember(name, m["coefficient_N_per_m"] * 1e-3, m["pitch_radius_mm"], ratio)


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
    head = doc.get("budget")
    for old in ("torques_Nm", "torques_nm"):
        if isinstance(head, dict) and old in head:
            raise CaseError(f"budget.{old}", head[old], "renamed: write torque_nm = a number or a list of "
                            "numbers (N m), the spelling of every case kind", path)
    c = check_table(doc, CASE, "", path)
    members = tuple(_member(m, raw, f"member[{i}]", path)
                    for i, (m, raw) in enumerate(zip(c["member"], doc["member"])))
    b = c["budget"]
    train = DriveTrain(members, b["initial_backlash_deg"] * DEG, b["title"])
    return train, np.asarray(b["torque_nm"], float)


def load_backlash_table(path: str) -> dict | None:
    """The optional ``[backlash]`` table: a cylindrical pair whose double-flank TE gives the backlash curve."""
    from ..case import read_toml
    tab = read_toml(path).get("backlash")
    if tab is None:
        return None
    b = BACKLASH.check(tab, "backlash", path)
    pair = os.path.join(os.path.dirname(os.path.abspath(path)), b["pair_case"])
    return {"pair_case": pair, "allowance": [a * 1e-3 for a in b["thickness_allowance_um"]],
            "n": b["positions_per_cycle"], "cycles": b["cycles"]}
