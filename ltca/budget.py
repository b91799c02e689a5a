"""Drive-train stiffness and hysteresis budget: torsional members in series (seed 003).

Each member turns the torque on the reference shaft into an angular deflection referred to that
shaft; the members are in series, so the deflections add. The initial hysteresis (backlash seen at
the reference shaft under load) is Wang et al., Eq. (19)::

    B0 = (1/kg + 1/ka + 1/ks + 1/kc) T + j_phi0

with k_i the (secant) torsional stiffness of gear mesh, shaft, ball spline and coupling at the load T.

Source: Wang Guangjian et al., Chinese Journal of Engineering, p. 1061 (seed 003, shared/seeds/003_*.txt),
Table 2 (stiffnesses) and Table 3 (deformations at 2.5, 5, 7.5, 10 N m).

Member models (SI-consistent inside: N, mm, rad)
------------------------------------------------
* ``TorsionMember``  theta = T / k, k in N mm/rad.
* ``ShaftMember``    k = G pi (d^4 - d_i^4) / (32 L) (hollow circular shaft, Saint-Venant torsion).
* ``MeshMember``     gear mesh with stiffness per face width c [N/(mm mm)]: the normal force at the base
  circle is F = T / r_b, the approach along the line of action F / (c b), so theta = T / (c b r_b^2).
* ``BallSplineMember`` Hertzian ball contacts, k = c_s P^(1/3) [N/m] with P = T / r the force at the
  ball pitch radius r (Table 2); secant use: delta = P / k = P^(2/3) / c_s, theta = delta / r.

Radii implied by Table 3 (the seed page gives no gear or spline data; derivation in the report and in
``cases/budget_wang.toml``): the gear row is linear with slope in [0.0220, 0.0225] 1e-3 deg/(N m)
which, with c = 20 N/(um mm), needs b r_b^2 in [127.3e3, 130.2e3] mm^3 (we take b = 20 mm,
r_b = 80 mm); the spline row is proportional to T^(2/3) (secant form, not the integrated tangent form
which would scale by 3/2) and needs r = 16.0 mm (interval 15.99-16.02 mm).

``ratio`` of a member is its shaft speed over the reference shaft speed: the member carries T / ratio
and its own angle referred to the reference shaft is theta_member / ratio.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np

from ltca.errors import CaseError

__all__ = ["TorsionMember", "ShaftMember", "MeshMember", "BallSplineMember", "Member",
           "DriveTrain", "BudgetResult", "compute_budget", "load_budget_case", "plot_budget",
           "write_budget_csv", "run_budget"]

DEG = np.pi / 180.0


@dataclass(frozen=True)
class TorsionMember:
    """Linear torsional spring (shaft or coupling with a given stiffness).

    Parameters
    ----------
    name : str
    stiffness : float
        Torsional stiffness, N mm/rad (> 0).
    ratio : float
        Speed of the member's shaft over the reference shaft's speed (default 1).
    """
    name: str
    stiffness: float
    ratio: float = 1.0

    def angle(self, torque: np.ndarray) -> np.ndarray:
        """Own twist, rad, under the member torque ``torque`` (N mm)."""
        return np.asarray(torque, float) / self.stiffness


@dataclass(frozen=True)
class ShaftMember:
    """Circular (optionally hollow) shaft: k = G pi (d^4 - d_i^4) / (32 L).

    Parameters
    ----------
    name : str
    shear_modulus : float
        G, MPa (N/mm^2).
    diameter, length, bore : float
        Outer diameter, twisted length and bore diameter, mm.
    ratio : float
        Shaft speed over the reference speed.
    """
    name: str
    shear_modulus: float
    diameter: float
    length: float
    bore: float = 0.0
    ratio: float = 1.0

    @property
    def stiffness(self) -> float:
        """Torsional stiffness, N mm/rad (polar moment pi (d^4 - d_i^4)/32)."""
        polar = np.pi * (self.diameter**4 - self.bore**4) / 32.0
        return self.shear_modulus * polar / self.length

    def angle(self, torque: np.ndarray) -> np.ndarray:
        """Own twist, rad, under the member torque (N mm)."""
        return np.asarray(torque, float) / self.stiffness


@dataclass(frozen=True)
class MeshMember:
    """Gear mesh with a stiffness per unit face width (ISO 6336-1 c_gamma style).

    Parameters
    ----------
    name : str
    stiffness_per_width : float
        c, N/(mm mm) (20 N/(um mm) = 2.0e4 N/(mm mm), seed 003 Table 2).
    face_width, base_radius : float
        b and r_b of the gear on the member's shaft, mm.
    ratio : float
        Speed of that gear's shaft over the reference speed.
    """
    name: str
    stiffness_per_width: float
    face_width: float
    base_radius: float
    ratio: float = 1.0

    @property
    def stiffness(self) -> float:
        """Torsional mesh stiffness c b r_b^2, N mm/rad."""
        return self.stiffness_per_width * self.face_width * self.base_radius**2

    def angle(self, torque: np.ndarray) -> np.ndarray:
        """Mesh deflection as a rotation of the member's gear, rad (torque in N mm)."""
        return np.asarray(torque, float) / self.stiffness


@dataclass(frozen=True)
class BallSplineMember:
    """Ball spline with Hertzian stiffness k = c_s P^(1/3) (seed 003 Table 2: c_s = 9.768e7).

    Parameters
    ----------
    name : str
    coefficient : float
        c_s in N^(2/3)/mm (the seed's 9.768e7 N^(2/3)/m is 9.768e4 in these units).
    pitch_radius : float
        Ball pitch radius r, mm: P = T / r and theta = delta / r.
    ratio : float
        Spline shaft speed over the reference speed.
    """
    name: str
    coefficient: float
    pitch_radius: float
    ratio: float = 1.0

    def angle(self, torque: np.ndarray) -> np.ndarray:
        """Twist, rad: delta = P/k(P) = P^(2/3)/c_s (secant stiffness), theta = delta / r."""
        force = np.abs(np.asarray(torque, float)) / self.pitch_radius
        return np.sign(torque) * force ** (2.0 / 3.0) / self.coefficient / self.pitch_radius


Member = TorsionMember | ShaftMember | MeshMember | BallSplineMember


@dataclass(frozen=True)
class DriveTrain:
    """Members in series plus the initial backlash of the gear pair.

    Parameters
    ----------
    members : tuple of Member
    initial_backlash : float
        j_phi0 of Eq. (19), rad at the reference shaft.
    title : str
    """
    members: tuple
    initial_backlash: float = 0.0
    title: str = ""


@dataclass(frozen=True)
class BudgetResult:
    """Deflections of each member (referred to the reference shaft) for a list of torques.

    Attributes
    ----------
    names : tuple of str
    torque : ndarray (nT,)
        Reference-shaft torque, N m.
    deflection : ndarray (nM, nT)
        Each member's deflection referred to the reference shaft, rad.
    total : ndarray (nT,)
        Sum over members, rad.
    hysteresis : ndarray (nT,)
        B0 = total + j_phi0 (Eq. 19), rad.
    initial_backlash : float
        j_phi0, rad.
    """
    names: tuple
    torque: np.ndarray
    deflection: np.ndarray
    total: np.ndarray
    hysteresis: np.ndarray
    initial_backlash: float
    title: str = ""
    extra: dict = field(default_factory=dict)

    def table(self) -> str:
        """Plain text table in 1e-3 deg, laid out as seed 003 Table 3."""
        head = f"{'member':<22}" + "".join(f"{t:>10.3g} N m" for t in self.torque)
        lines = [self.title, "deflection / (1e-3 deg), referred to the reference shaft", head]
        rows = list(zip(self.names, self.deflection)) + [("total", self.total),
                                                         ("B0 = total + j_phi0", self.hysteresis)]
        for name, row in rows:
            lines.append(f"{name:<22}" + "".join(f"{v / DEG * 1e3:>14.2f}" for v in row))
        return "\n".join(line for line in lines if line)


def compute_budget(train: DriveTrain, torques_Nm: np.ndarray) -> BudgetResult:
    """Deflection budget of a drive train for a list of torques (Wang et al. Eq. 19).

    Parameters
    ----------
    train : DriveTrain
    torques_Nm : array_like
        Torques on the reference shaft, N m.

    Returns
    -------
    BudgetResult
    """
    torque = np.atleast_1d(np.asarray(torques_Nm, float))
    t_nmm = torque * 1e3
    rows = [m.angle(t_nmm / m.ratio) / m.ratio for m in train.members]
    defl = np.array(rows) if rows else np.zeros((0, torque.size))
    total = defl.sum(axis=0)
    return BudgetResult(names=tuple(m.name for m in train.members), torque=torque,
                        deflection=defl, total=total, hysteresis=total + train.initial_backlash,
                        initial_backlash=train.initial_backlash, title=train.title)


# ---------------------------------------------------------------- case file, table, CSV, plot

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
    from .case import read_toml
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


def write_budget_csv(result: BudgetResult, path: str) -> None:
    """CSV in 1e-3 deg: one row per torque, one column per member, then total and B0."""
    cols = ["torque_Nm", *[f"{n}_mdeg" for n in result.names], "total_mdeg", "B0_mdeg"]
    data = np.column_stack([result.torque, *(result.deflection / DEG * 1e3),
                            result.total / DEG * 1e3, result.hysteresis / DEG * 1e3])
    np.savetxt(path, data, delimiter=",", header=",".join(cols), comments="", fmt="%.6g")


def plot_budget(result: BudgetResult, path: str) -> None:
    """Stacked bars of member deflections and the B0 line against torque (PNG, Agg backend)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    width = 0.6 * (np.min(np.diff(result.torque)) if result.torque.size > 1 else 1.0)
    bottom = np.zeros_like(result.torque)
    for name, row in zip(result.names, result.deflection / DEG * 1e3):
        ax.bar(result.torque, row, width, bottom=bottom, label=name)
        bottom = bottom + row
    ax.plot(result.torque, result.hysteresis / DEG * 1e3, "k-o", label="B0 (Eq. 19)")
    ax.set_xlabel("torque / (N m)")
    ax.set_ylabel("deflection / (1e-3 deg)")
    ax.set_title(result.title or "drive-train budget", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def _backlash_table(path: str) -> dict | None:
    """The optional ``[backlash]`` table: a cylindrical pair whose double-flank TE gives the backlash curve."""
    from .case import read_toml
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


def backlash_from_pair(spec: dict, result: BudgetResult) -> list:
    """Seed 003 Eq. 20-21 on a cylindrical pair: unloaded double-flank TE by TCA, shifted by the budget.

    The TE is that of the gear; the budget's deflections are taken as referred to the same shaft."""
    import dataclasses

    from .backlash import backlash_curves
    from .case import load_case
    from .model import build_model
    from .run import cycle_rolls
    from .tca import ARCSEC_PER_RAD, double_flank_tca
    case = load_case(spec["pair_case"])
    case = dataclasses.replace(
        case, pinion=dataclasses.replace(case.pinion, thickness_allowance=spec["allowance"][0]),
        gear=dataclasses.replace(case.gear, thickness_allowance=spec["allowance"][1]))
    model = build_model(case)
    cycles = spec["cycles"] or case.pinion.teeth
    roll = cycle_rolls(spec["n"], case.pinion.teeth, cycles)
    drive, coast = double_flank_tca(model, roll)
    return [backlash_curves(roll, drive / ARCSEC_PER_RAD, coast / ARCSEC_PER_RAD, float(d)) for d in result.total]


def run_budget(case_path: str, out_dir: str | None) -> BudgetResult:
    """CLI entry ``ltca budget CASE [--out DIR]``: print the table; write CSV and PNG into out_dir.

    With a ``[backlash]`` table, also the backlash curve of the named gear pair from its unloaded
    drive- and coast-side TE and the loaded curves shifted by each torque's total deflection."""
    train, torques = load_budget_case(case_path)
    result = compute_budget(train, torques)
    print(result.table())
    spec = _backlash_table(case_path)
    curves = backlash_from_pair(spec, result) if spec else []
    for T, c in zip(torques, curves):
        arcsec = np.pi / 180 / 3600
        print(f"backlash at {T:g} N m: unloaded {c.backlash.min() / arcsec:.2f} .. {c.backlash.max() / arcsec:.2f} "
              f"arcsec, loaded separation {c.loaded_hysteresis.min() / arcsec:.2f} .. "
              f"{c.loaded_hysteresis.max() / arcsec:.2f} arcsec")
    if out_dir:
        os.makedirs(out_dir, exist_ok=True)
        write_budget_csv(result, os.path.join(out_dir, "budget.csv"))
        plot_budget(result, os.path.join(out_dir, "budget.png"))
        if curves:
            from .backlash import plot_backlash
            plot_backlash(curves[-1], os.path.join(out_dir, "backlash.png"),
                          f"{result.title}: backlash, loaded at {torques[-1]:g} N m")
            with open(os.path.join(out_dir, "backlash.csv"), "w") as fh:
                fh.write("roll_deg,te_drive_arcsec,te_coast_arcsec,backlash_arcsec,"
                         + ",".join(f"loaded_drive_{T:g}Nm,loaded_coast_{T:g}Nm" for T in torques) + "\n")
                arc = np.pi / 180 / 3600
                c0 = curves[0]
                for i in range(len(c0.roll_angle)):
                    row = [np.degrees(c0.roll_angle[i]), c0.te_drive[i] / arc, c0.te_coast[i] / arc,
                           c0.backlash[i] / arc]
                    for c in curves:
                        row += [c.loaded_drive[i] / arc, c.loaded_coast[i] / arc]
                    fh.write(",".join(f"{v:.6g}" for v in row) + "\n")
    return result
