"""The satellite and the central wheel of a planetary case as one cylindrical pair model.

The satellite (external, cut by the case's method, :func:`ltca.geometry.satellite.form_satellite`) and the
central wheel (internal, shaper cut, :func:`ltca.geometry.satellite.generate_central_wheel`) are placed at the
eccentricity as a :class:`ltca.cylindrical.model.PairModel`, so that the cylindrical separation field,
contact cells and contact solve run on this pair unchanged. Two assumptions of the cylindrical chain do
not hold here and are replaced:

* the working pitch circle (``r_w1 = e z1 / (z2 - z1)`` = 150 mm for Kapitonov et al. 2014) lies far outside both
  gears, so the pair is not calibrated at a pitch point: the wheel phase is the symmetric placement of
  :class:`ltca.geometry.satellite.EccentricMesh` (satellite tooth 0 centred in a wheel space on the line of
  centres at ``phi1 = 0``), and a pinion angle ``phi1`` of the pair is the mesh position ``phi = -phi1``
  of :mod:`ltca.geometry.satellite.mesh` (``phi_pitch = 0``, roll = phi);
* the teeth in mesh are not +-3 around the pitch point but every pair whose unloaded gap
  (:func:`ltca.geometry.satellite.unloaded_gaps`) can close under the largest torque (:mod:`.loaded`).

The satellite drives clockwise with its right flanks (direction +1); the wheel, fixed in its housing,
carries the load on its left flanks (``gear_side = -1``, measured, not assumed).
"""
from __future__ import annotations

from dataclasses import dataclass


from ltca.geometry.modification import FlankModification
from ltca.geometry.pair import CylindricalPair
from ltca.geometry.profile import ToothProfile
from ltca.geometry.satellite import EccentricMesh, form_satellite, generate_central_wheel
from ltca.geometry.satellite.forming import FormedTooth
from ltca.geometry.satellite.wheel import WheelChoice

from ..cylindrical.model import PairModel
from ..errors import CaseError

__all__ = ["EccentricPair", "SatelliteModel", "build_satellite_model"]


class EccentricPair(CylindricalPair):
    """:class:`ltca.geometry.pair.CylindricalPair` with the wheel at the symmetric placement (no pitch-point
    calibration: the working pitch circle of a tooth difference of one lies outside both gears)."""

    def _calibrate(self) -> float:
        return 0.0


@dataclass(frozen=True)
class SatelliteModel:
    """Geometry of a planetary case: the formed satellite, the wheel, the exact mesh and the pair model.

    formed : FormedTooth (method, tool, thickness, tip land).   wheel : ToothProfile.   choice : WheelChoice
    (z2, x2, alpha_w, backlash).   mesh : EccentricMesh (exact gaps, both directions).   pair : PairModel
    (cylindrical chain; ``pair.pinion`` is the satellite, ``pair.gear`` the wheel).
    """

    formed: FormedTooth
    wheel: ToothProfile
    choice: WheelChoice
    mesh: EccentricMesh
    pair: PairModel

    @property
    def satellite(self) -> ToothProfile:
        return self.formed.profile


def _gear_side(pm: PairModel, mesh: EccentricMesh) -> int:
    """Side label of the wheel outline touched first by the satellite's right flanks (drive)."""
    w = mesh.window(0.0)
    return int(w.drive_at["side2"]) or -1


def build_satellite_model(case) -> SatelliteModel:
    """Form the satellite, cut the wheel and place both (module doc). ``case``: :class:`PlanetaryCase`."""
    try:
        formed = form_satellite(case.design, case.method, case.tool)
    except (ValueError, IndexError, ArithmeticError) as exc:
        from .case import forming_error
        raise forming_error(case.method, exc) from None
    try:
        wheel, choice = generate_central_wheel(case.design, case.wheel)
    except (ValueError, IndexError, ArithmeticError) as exc:
        raise CaseError("wheel", case.wheel, f"a central wheel that can be cut and assembled: {exc}") from None
    sat = formed.profile
    if wheel.r_root + 0.5 * case.design.m >= 0.5 * case.wheel_outer_diameter:
        raise CaseError("wheel.outer_diameter_mm", case.wheel_outer_diameter,
                        f"larger than the wheel root diameter plus one module ({2 * wheel.r_root + case.design.m:.3f} mm)")
    if 0.5 * case.bore_diameter >= sat.r_root - 0.5 * case.design.m:
        raise CaseError("satellite.bore_diameter_mm", case.bore_diameter,
                        f"below the satellite root diameter minus one module ({2 * sat.r_root - case.design.m:.3f} mm)")
    e = choice.a
    try:
        mesh = EccentricMesh(sat, wheel, e)
    except ValueError as exc:
        raise CaseError("wheel.eccentricity_mm", e, f"an eccentricity at which the pair meshes: {exc}") from None
    if mesh.backlash <= 0:
        raise CaseError("satellite.thinning", case.design.thinning,
                        f"a thinning that lets the satellite into the wheel (>= {choice.thinning_fit:.4f}; "
                        f"backlash {mesh.backlash:.4f} mm)")
    b = case.face_width
    pair = EccentricPair(sat, wheel, e, b)
    pm = PairModel(case, sat, wheel, pair, FlankModification(), FlankModification(), b, 0.5 * case.bore_diameter,
                   0.5 * case.wheel_outer_diameter, -1, 0.0, 0, contact_search="flank")
    side = _gear_side(pm, mesh)
    if side != pm.gear_side:
        pm = PairModel(case, sat, wheel, pair, FlankModification(), FlankModification(), b, pm.r_bore1, pm.r_bore2,
                       side, 0.0, 0, contact_search="flank")
    return SatelliteModel(formed, wheel, choice, mesh, pm)


def rigid_rotation_check(sm: SatelliteModel, phi: float) -> float:
    """Difference (rad) between the first drive contact of the pair model and the exact mesh window at
    position ``phi``: the two geometric routes to the same number (tests)."""
    from ..cylindrical.tca import first_contact
    teeth = range(-sm.pair.pinion.z // 4, 1)
    return float(first_contact(sm.pair, -phi, teeth) + sm.mesh.window(phi).drive)
