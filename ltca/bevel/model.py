"""The records of the bevel LTCA: model size (:class:`BevelFidelity`), both members' compliance for one flank pair
(:class:`BevelBodies`) and that pair in one assembly (:class:`BevelLoadedModel`).  Built by
:mod:`ltca.bevel.loaded_model`; read by :mod:`ltca.bevel.cells` and :mod:`ltca.bevel.loaded`."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ltca.fem.compliance import BodyCompliance
from ltca.geometry.bevel.gaps import MeshGaps
from ltca.geometry.bevel.tca import Assembly, BevelPair

__all__ = ["LOADED", "MESHED", "BevelFidelity", "BevelMounting", "BevelBodies", "BevelLoadedModel"]

#: teeth of each member that can carry load (pair j: pinion tooth +j, gear tooth -j) and the meshed ones
LOADED = (-1, 0, 1)
MESHED = (-2, -1, 0, 1, 2)


@dataclass(frozen=True)
class BevelFidelity:
    """Model size: compliance grid, body mesh divisions, contact cells (see the module docstrings).

    grid : (n_t, n_L) compliance grid per loaded flank;  divisions : body mesh (n_L, n_t, n_s, n_g, n_rim,
    n_far);  depth : read depth of the regular part, mm;  cells : (along the major, across the minor axis)
    cells over the window of each pair;  window : (major, minor) window approach as multiples of the Hertz
    approach of the whole load on one pair;  near_field : add the half-space near field at the cells.
    """
    name: str = "default"
    grid: tuple[int, int] = (9, 13)
    divisions: tuple[int, int, int, int, int, int] = (12, 8, 4, 3, 3, 16)
    depth: float = 0.5
    cells: tuple[int, int] = (33, 17)
    window: tuple[float, float] = (1.6, 1.0)
    near_field: bool = True

    @classmethod
    def named(cls, name: str) -> "BevelFidelity":
        """``coarse``, ``default`` or ``fine`` (the convergence ladder)."""
        table = {"coarse": cls("coarse", (7, 9), (10, 7, 4, 3, 2, 12), 0.5, (25, 13)),
                 "default": cls(),
                 "fine": cls("fine", (11, 17), (14, 14, 7, 4, 4, 24), 0.5, (45, 23))}
        if name not in table:
            raise ValueError(f"fidelity = {name!r}: allowed {sorted(table)}")
        return table[name]


@dataclass(frozen=True)
class BevelMounting:
    """How both members are held in service: the blank of each body runs down to its mounting (mm).

    pinion_seat_diameter : diameter of the pinion's shaft seat, a cylinder held as on a rigid shaft; None:
        0.45 x the pinion's root diameter at the toe (an integral shaft pinion).
    gear_mounting_distance : axial distance from the pitch apex (the crossing point) to the gear's back
        mounting face, a plane held rigidly; None: the face 1.2 whole depths behind the heel's root, along the
        back cone.
    """
    pinion_seat_diameter: float | None = None
    gear_mounting_distance: float | None = None

    def supports(self, blank) -> dict[str, tuple[str, float]]:
        """``{"pinion": ("seat", rho), "gear": ("face", Z)}`` in each member's body frame (mm), for
        :class:`ltca.fem.solids.bevel_body.BevelBodySpec`; ``blank`` is the pair's
        :class:`ltca.geometry.bevel.blank.BevelBlank`."""
        toe1, heel2 = blank.root_point("pinion", "toe"), blank.root_point("gear", "heel")
        seat = 0.45 * toe1[1] if self.pinion_seat_diameter is None else 0.5 * self.pinion_seat_diameter
        if self.gear_mounting_distance is None:
            g = blank.member("gear").pitch_angle
            face = heel2[0] + np.sin(g) * 1.2 * blank.whole_depth
            if face >= 0.8 * face_limit(blank):
                # a gear of small pitch angle: a back face behind the heel would cut its toe off (the front cone
                # reaches the axis first), so it sits on a shaft seat as a pinion does
                return {"pinion": ("seat", float(seat)),
                        "gear": ("seat", float(0.45 * blank.root_point("gear", "toe")[1]))}
        else:
            face = self.gear_mounting_distance
        return {"pinion": ("seat", float(seat)), "gear": ("face", float(face))}


def face_limit(blank) -> float:
    """The largest axial position of the gear's back mounting face (mm from the pitch apex): where the gear's front
    cone, continued down from the toe's root, reaches the axis."""
    g = blank.member("gear").pitch_angle
    toe = blank.root_point("gear", "toe")
    return float(toe[0] + toe[1] * np.tan(g)) if g < 0.5 * np.pi - 1e-9 else float("inf")


@dataclass
class BevelBodies:
    """Compliance of both members for one flank pair (pinion ``side``), reusable over assemblies and torques."""
    side: str
    body1: BodyCompliance
    body2: BodyCompliance
    off1: float
    off2: float
    fid: BevelFidelity
    young: float
    poisson: float
    mounting: BevelMounting = BevelMounting()
    timings: dict = field(default_factory=dict)


@dataclass
class BevelLoadedModel:
    """One flank pair in one assembly, ready for :func:`ltca.bevel.loaded.solve_position`."""
    pair: BevelPair
    bodies: BevelBodies
    gaps: MeshGaps
    asm: Assembly
    g_ref: float          # gear rotation closing the first contact at phi1 = 0 (TE reference), rad

    @property
    def side(self) -> str:
        return self.bodies.side

    @property
    def fid(self) -> BevelFidelity:
        return self.bodies.fid
