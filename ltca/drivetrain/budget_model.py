"""Drive-train stiffness and hysteresis budget: torsional members in series (seed 003).

Each member turns the torque on the reference shaft into an angular deflection referred to that
shaft; the members are in series, so the deflections add. The initial hysteresis (backlash seen at
the reference shaft under load) is Wang et al., Eq. (19)::

    B0 = (1/kg + 1/ka + 1/ks + 1/kc) T + j_phi0

with k_i the (secant) torsional stiffness of gear mesh, shaft, ball spline and coupling at the load T.

Source: Wang Guangjian et al., Chinese Journal of Engineering, p. 1061 (seed 003),
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

from dataclasses import dataclass, field

import numpy as np

__all__ = ["DEG", "TorsionMember", "ShaftMember", "MeshMember", "BallSplineMember", "Member",
           "DriveTrain", "BudgetResult", "compute_budget"]

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
