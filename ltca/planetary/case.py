"""Case files of the eccentric planetary satellite (Kapitonov et al. 2014): a TOML case with a ``[satellite]`` table.

Tables (engineer's units, converted once here to mm, rad, N mm, MPa):

* ``[satellite]`` teeth, module_mm, pressure_angle_deg, profile_shift, thinning (Eq. 3 coefficient k),
  face_width_mm, tip_diameter_mm (optional), bore_diameter_mm (the eccentric bearing's seat), method
  (``hob`` | ``hob_three_pass`` | ``disk_cutter`` | ``special_hob``: the satellite analysed), and one
  sub-table per tool: ``[satellite.hob_three_pass]`` shift_mm, lead_angle_deg; ``[satellite.disk_cutter]``
  x_plunge, teeth, profile_teeth; ``[satellite.special_hob]`` thickening;
* ``[cutter]`` the basic rack per module: addendum, dedendum, tip_radius;
* ``[wheel]`` tooth_difference, eccentricity_mm, profile_shift, shaper_teeth, shaper_profile_shift,
  shaper_addendum, shaper_tip_radius, far_tip_clearance_mm, tip_diameter_mm, outer_diameter_mm (held in the
  housing);
* ``[material]`` name, youngs_modulus_mpa, poisson_ratio, sigma_flim_mpa (root bending endurance, for
  the ISO 6336-3 rated torque);
* ``[load]`` torques_percent_of_rated (list) or torque_nm (a number or a list), on the satellite, both directions;
* ``[analysis]`` positions (per mesh cycle), fidelity, far_teeth (``none`` | ``full``).

Every mistake raises :class:`ltca.errors.CaseError` naming the field (exit status 2 on the command line);
the tool records of :mod:`ltca.geometry.satellite.tools` check their own ranges and their messages are turned
into the field of the case that holds the value.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from ltca.geometry.satellite import METHODS, DiskCutter, HobThreePass, SatelliteDesign, SpecialHob
from ltca.geometry.satellite.rating import RatingInputs
from ltca.geometry.satellite.wheel import CentralWheelDesign

from ..case import FIDELITIES, TORQUE, read_toml
from ..errors import CaseError
from ..validation import DesignError, Int, List, Num, OneOrList, Str, Table, check_table

__all__ = ["PlanetaryCase", "is_planetary", "load_planetary_case", "parse_planetary_case", "compare_case_forming",
           "forming_error"]

DEG = math.pi / 180
_POS_MM = 1e5       # an upper bound for diameters, mm (400 teeth of module 100 make 40 000 mm)


_TOOLS = {
    "hob_three_pass": Table({"shift_mm": Num(0, 2, "mm", note="default k m / 2"),
                             "lead_angle_deg": Num(0, 11.4, "deg", default=0.0)}),
    "disk_cutter": Table({"x_plunge": Num(-2.5, 0.5, default=-1.3),
                          "teeth": Int(1, 100, default=14, note="a disk cutter with no teeth cuts nothing"),
                          "profile_teeth": Int(12, 400, note="default the satellite's teeth")}),
    "special_hob": Table({"thickening": Num(0, 1, hi_open=True, note="default the satellite's thinning")}),
}
_SAT = Table({
    "teeth": Int(12, 400, required=True),
    "module_mm": Num(0.1, 100, "mm", required=True),
    "pressure_angle_deg": Num(10, 35, "deg", default=20.0),
    "profile_shift": Num(-2, 2, default=0.0),
    "thinning": Num(0, 1, hi_open=True, default=0.0, note="Eq. 3: s = ... - k m"),
    "face_width_mm": Num(0.5, 2000, "mm", required=True),
    "tip_diameter_mm": Num(0, _POS_MM, "mm", lo_open=True),
    "bore_diameter_mm": Num(0, _POS_MM, "mm", lo_open=True, required=True, note="the eccentric bearing's seat"),
    "method": Str(choices=tuple(METHODS), default="special_hob"),
    **_TOOLS}, required=True)
_CUTTER = Table({"addendum": Num(0.5, 2, "x module", lo_open=True, default=1.25),
                 "dedendum": Num(1, 2, "x module", default=1.0),
                 "tip_radius": Num(0, 0.5, "x module", default=0.38)})
_WHEEL = Table({
    "tooth_difference": Int(1, 8, default=1, note="z2 - z1 < 1: the satellite cannot be assembled inside the wheel"),
    "eccentricity_mm": Num(0, 1000, "mm", lo_open=True, note="default one module"),
    "profile_shift": Num(-1, 1, default=0.0),
    "shaper_teeth": Int(8, 395, default=25, note="at most z2 - 5"),
    "shaper_profile_shift": Num(-1, 1, default=0.0),
    "shaper_addendum": Num(0.5, 2, "x module", lo_open=True, default=1.25),
    "shaper_tip_radius": Num(0, 0.5, "x module", default=0.25),
    "far_tip_clearance_mm": Num(0, 5, "mm", default=0.5),
    "tip_diameter_mm": Num(0, _POS_MM, "mm", lo_open=True),
    "outer_diameter_mm": Num(0, _POS_MM, "mm", lo_open=True, required=True, note="held in the housing"),
}, required=True)
_MATERIAL = Table({"name": Str(max_len=200, default="steel"),
                   "youngs_modulus_mpa": Num(1e3, 1e6, "MPa", default=206000.0),
                   "poisson_ratio": Num(0, 0.5, hi_open=True, default=0.3),
                   "sigma_flim_mpa": Num(0, 2000, "MPa", lo_open=True, default=RatingInputs().sigma_Flim)})
_LOAD = Table({"torques_percent_of_rated": List(Num(0, 500, "%", lo_open=True), 1, 100),
               "torque_nm": OneOrList(TORQUE, 1, 100, distinct=True,
                                     meaning="satellite torque, or a list of torques analysed one after the other")},
              required=True)
_ANALYSIS = Table({"positions": Int(1, 500, default=6, note="per mesh cycle"),
                   "fidelity": Str(choices=tuple(sorted(FIDELITIES)), default="coarse"),
                   "far_teeth": Str(choices=("none", "full"), default="none")})
_CASE = Table({"name": Str(non_empty=True, max_len=200, default="planetary"),
               "description": Str(max_len=2000, default=""),
               "source": Str(max_len=2000, default=None)})
CASE = Table({"case": _CASE, "satellite": _SAT, "cutter": _CUTTER, "wheel": _WHEEL, "material": _MATERIAL,
              "load": _LOAD, "analysis": _ANALYSIS})


@dataclass(frozen=True)
class PlanetaryCase:
    """A validated planetary case (mm, rad, MPa; torques N mm on the satellite, or fractions of the rated)."""
    name: str
    design: SatelliteDesign
    method: str
    tools: dict                   # method -> tool record (HobThreePass, DiskCutter, SpecialHob)
    wheel: CentralWheelDesign
    face_width: float
    bore_diameter: float
    wheel_outer_diameter: float
    material: str
    young: float
    poisson: float
    rating: RatingInputs
    torques: tuple[float, ...]    # N mm; empty when given as fractions of the rated torque
    torque_fractions: tuple[float, ...]
    positions: int
    fidelity: str
    far_teeth: str
    source: str | None = None

    @property
    def tool(self):
        """The tool of the analysed method (None for the plain hob)."""
        return self.tools.get(self.method)


def is_planetary(data: dict) -> bool:
    """True for a case with a ``[satellite]`` table."""
    return "satellite" in data


def _make(cls, field: str, file, kwargs: dict, names: dict):
    """Construct a geometry record; its ValueError ('Cls.attr = ...') becomes a CaseError on the case field."""
    try:
        return cls(**kwargs)
    except ValueError as exc:
        msg = str(exc)
        attr = msg.split(" = ")[0].split(".")[-1] if " = " in msg else ""
        key = names.get(attr, attr)
        val = kwargs.get(attr)
        raise CaseError(f"{field}.{key}" if key else field, val, msg.split(": ", 1)[-1], file) from None


def parse_planetary_case(data: dict, file: str | None = None) -> PlanetaryCase:
    """Validate a planetary case dictionary (from TOML) and convert its units."""
    if isinstance(data.get("load"), dict) and "torques_nm" in data["load"]:
        raise CaseError("load.torques_nm", data["load"]["torques_nm"], "renamed: write torque_nm = a number or a "
                        "list of numbers (N m)", file)
    c = check_table(data, CASE, "", file)
    meta, sat, cut, w, mat, load, an = (c[k] for k in ("case", "satellite", "cutter", "wheel", "material", "load",
                                                       "analysis"))
    m = sat["module_mm"]
    design = _make(SatelliteDesign, "satellite", file, dict(
        z=sat["teeth"], m=m, alpha=sat["pressure_angle_deg"] * DEG, x=sat["profile_shift"], thinning=sat["thinning"],
        rack_addendum_coef=cut["addendum"], rack_dedendum_coef=cut["dedendum"],
        rack_tip_radius_coef=cut["tip_radius"], d_tip=sat["tip_diameter_mm"]),
        dict(z="teeth", m="module_mm", alpha="pressure_angle_deg", x="profile_shift", d_tip="tip_diameter_mm",
             rack_addendum_coef="../cutter.addendum", rack_dedendum_coef="../cutter.dedendum",
             rack_tip_radius_coef="../cutter.tip_radius"))
    t = sat["hob_three_pass"]
    tools = {"hob_three_pass": _make(HobThreePass, "satellite.hob_three_pass", file,
                                     dict(shift=t["shift_mm"], lead_angle=t["lead_angle_deg"] * DEG),
                                     dict(shift="shift_mm", lead_angle="lead_angle_deg"))}
    t = sat["disk_cutter"]
    tools["disk_cutter"] = _make(DiskCutter, "satellite.disk_cutter", file,
                                 dict(x_plunge=t["x_plunge"], n_teeth=t["teeth"], z_profile=t["profile_teeth"]),
                                 dict(n_teeth="teeth", z_profile="profile_teeth"))
    tools["special_hob"] = _make(SpecialHob, "satellite.special_hob", file,
                                 dict(thickening=sat["special_hob"]["thickening"]), {})
    z2 = sat["teeth"] + w["tooth_difference"]
    if w["shaper_teeth"] > z2 - 5:
        raise CaseError("wheel.shaper_teeth", w["shaper_teeth"], f"an integer in [8, {z2 - 5}] (z2 - 5, z2 = "
                        f"satellite.teeth + wheel.tooth_difference = {z2})", file)
    wheel = _make(CentralWheelDesign, "wheel", file, dict(
        tooth_difference=w["tooth_difference"], eccentricity=w["eccentricity_mm"], x2=w["profile_shift"],
        shaper_teeth=w["shaper_teeth"], shaper_shift=w["shaper_profile_shift"],
        shaper_addendum_coef=w["shaper_addendum"], shaper_tip_radius_coef=w["shaper_tip_radius"],
        far_tip_clearance=w["far_tip_clearance_mm"], d_tip=w["tip_diameter_mm"]),
        dict(eccentricity="eccentricity_mm", x2="profile_shift", shaper_shift="shaper_profile_shift",
             shaper_addendum_coef="shaper_addendum", shaper_tip_radius_coef="shaper_tip_radius",
             far_tip_clearance="far_tip_clearance_mm", d_tip="tip_diameter_mm"))
    if (load["torque_nm"] is None) == (load["torques_percent_of_rated"] is None):
        raise CaseError("load", data.get("load"), "exactly one of torque_nm or torques_percent_of_rated", file)
    torques, fractions = (), ()
    if load["torque_nm"] is not None:
        torques = tuple(1e3 * t for t in load["torque_nm"])
    else:
        fractions = tuple(0.01 * t for t in load["torques_percent_of_rated"])
    rating = RatingInputs(sigma_Flim=mat["sigma_flim_mpa"], b=sat["face_width_mm"])
    return PlanetaryCase(
        name=meta["name"], design=design, method=sat["method"], tools=tools, wheel=wheel,
        face_width=sat["face_width_mm"], bore_diameter=sat["bore_diameter_mm"],
        wheel_outer_diameter=w["outer_diameter_mm"], material=mat["name"], young=mat["youngs_modulus_mpa"],
        poisson=mat["poisson_ratio"], rating=rating, torques=torques, torque_fractions=fractions,
        positions=an["positions"], fidelity=an["fidelity"], far_teeth=an["far_teeth"], source=meta["source"])


def load_planetary_case(path: str | Path) -> PlanetaryCase:
    """Read and validate a planetary case file."""
    return parse_planetary_case(read_toml(path), str(path))


#: the case fields of each forming tool, besides the satellite's own shift and thinning
_TOOL_FIELDS = {"hob_three_pass": ("satellite.hob_three_pass.shift_mm",),
                "disk_cutter": ("satellite.disk_cutter.x_plunge", "satellite.disk_cutter.profile_teeth"),
                "special_hob": ("satellite.special_hob.thickening",), "hob": ()}


def forming_error(method: str, exc: BaseException, file: str | None = None) -> DesignError:
    """A forming tool that cannot cut this satellite, as one line naming the fields that drive it."""
    text = " ".join(str(exc).split())[:240] or type(exc).__name__
    return DesignError(f"the satellite cannot be cut by {method} ({text})",
                       (*_TOOL_FIELDS.get(method, ()), "satellite.profile_shift", "satellite.thinning"),
                       "move the profile shift or the thinning towards the shipped case (x = -0.5, k = 0.6), or "
                       f"adjust the {method} tool", file)


def compare_case_forming(case: PlanetaryCase, file: str | None = None):
    """:func:`ltca.geometry.satellite.compare.compare_forming` with the case's tools; a tool that cannot cut this satellite
    (a vanishing tip, an empty profile, no disk-cutter plunge giving the Eq. 3 thickness) is a
    :class:`~ltca.validation.DesignError` naming the method and its fields (exit status 2), not a traceback."""
    from ltca.geometry.satellite.compare import compare_forming, plunge_for_thickness
    from ltca.geometry.satellite.forming import form_disk_cutter, form_hob_three_pass, form_special_hob
    hob, disk, special = (case.tools[k] for k in ("hob_three_pass", "disk_cutter", "special_hob"))
    try:
        return compare_forming(case.design, hob, disk, special)
    except (ValueError, IndexError, ArithmeticError) as exc:
        first = exc
    # which step failed: each method alone (only on this path; the comparison above does them all at once)
    steps = (("hob_three_pass", lambda: form_hob_three_pass(case.design, hob)),
             ("disk_cutter", lambda: form_disk_cutter(case.design, disk)),
             ("special_hob", lambda: form_special_hob(case.design, special)))
    for method, step in steps:
        try:
            step()
        except (ValueError, IndexError, ArithmeticError) as exc:
            raise forming_error(method, exc, file) from None
    try:
        plunge_for_thickness(case.design, tool=disk)
    except (ValueError, IndexError, ArithmeticError):
        raise DesignError("no disk-cutter plunge x in [-2, 0] cuts the Eq. 3 tooth thickness "
                          f"({case.design.eq3_thickness:.4f} mm) of this satellite",
                          ("satellite.profile_shift", "satellite.thinning", "satellite.disk_cutter.profile_teeth"),
                          "move the profile shift or the thinning towards the shipped case (x = -0.5, k = 0.6)",
                          file) from None
    raise forming_error("the three methods", first, file) from None
