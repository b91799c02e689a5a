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
the tool records of :mod:`geometry.satellite.tools` check their own ranges and their messages are turned
into the field of the case that holds the value.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from geometry.satellite import METHODS, DiskCutter, HobThreePass, SatelliteDesign, SpecialHob
from geometry.satellite.rating import RatingInputs
from geometry.satellite.wheel import CentralWheelDesign

from ..case import FIDELITIES, read_toml
from ..errors import CaseError

__all__ = ["PlanetaryCase", "is_planetary", "load_planetary_case", "parse_planetary_case"]

DEG = math.pi / 180
_N = (int, float)
_ANY = lambda v: True     # noqa: E731

# key: (types, required, default, check, words)
_SAT = {
    "teeth": (int, True, None, lambda v: 12 <= v <= 400, "an integer in [12, 400]"),
    "module_mm": (_N, True, None, lambda v: 0.1 <= v <= 100, "a number in [0.1, 100] mm"),
    "pressure_angle_deg": (_N, False, 20.0, lambda v: 10 <= v <= 35, "a number in [10, 35] deg"),
    "profile_shift": (_N, False, 0.0, lambda v: -2 <= v <= 2, "a number in [-2, 2]"),
    "thinning": (_N, False, 0.0, lambda v: 0 <= v < 1, "a number in [0, 1) (Eq. 3: s = ... - k m)"),
    "face_width_mm": (_N, True, None, lambda v: 0.5 <= v <= 2000, "a number in [0.5, 2000] mm"),
    "tip_diameter_mm": (_N, False, None, lambda v: v > 0, "a positive number, mm"),
    "bore_diameter_mm": (_N, True, None, lambda v: v > 0, "a positive number, mm (the eccentric bearing's seat)"),
    "method": (str, False, "special_hob", lambda v: v in METHODS, f"one of {list(METHODS)}"),
}
_TOOLS = {
    "hob_three_pass": {"shift_mm": (_N, False, None, _ANY, "a number in [0, 2] mm (None: k m / 2)"),
                       "lead_angle_deg": (_N, False, 0.0, _ANY, "a number in [0, 11.4] deg")},
    "disk_cutter": {"x_plunge": (_N, False, -1.3, _ANY, "a number in [-2.5, 0.5]"),
                    "teeth": (int, False, 14, _ANY, "an integer in [1, 100] (a disk cutter with no teeth cuts nothing)"),
                    "profile_teeth": (int, False, None, _ANY, "an integer in [12, 400]")},
    "special_hob": {"thickening": (_N, False, None, _ANY, "a number in [0, 1)")},
}
_CUTTER = {"addendum": (_N, False, 1.25, _ANY, "a number in (0.5, 2] x module"),
           "dedendum": (_N, False, 1.0, _ANY, "a number in [1, 2] x module"),
           "tip_radius": (_N, False, 0.38, _ANY, "a number in [0, 0.5] x module")}
_WHEEL = {
    "tooth_difference": (int, False, 1, _ANY, "an integer in [1, 8] (z2 - z1 < 1: the satellite cannot be "
                         "assembled inside the wheel)"),
    "eccentricity_mm": (_N, False, None, _ANY, "a positive number, mm (default one module)"),
    "profile_shift": (_N, False, 0.0, _ANY, "a number in [-1, 1]"),
    "shaper_teeth": (int, False, 25, _ANY, "an integer in [8, z2 - 5]"),
    "shaper_profile_shift": (_N, False, 0.0, _ANY, "a number in [-1, 1]"),
    "shaper_addendum": (_N, False, 1.25, _ANY, "a number in (0.5, 2] x module"),
    "shaper_tip_radius": (_N, False, 0.25, _ANY, "a number in [0, 0.5] x module"),
    "far_tip_clearance_mm": (_N, False, 0.5, _ANY, "a number in [0, 5] mm"),
    "tip_diameter_mm": (_N, False, None, _ANY, "a positive number, mm"),
    "outer_diameter_mm": (_N, True, None, lambda v: v > 0, "a positive number, mm (held in the housing)"),
}
_MATERIAL = {"name": (str, False, "steel", None, "a string"),
             "youngs_modulus_mpa": (_N, False, 206000.0, lambda v: 1e3 <= v <= 1e6, "a number in [1e3, 1e6] MPa"),
             "poisson_ratio": (_N, False, 0.3, lambda v: 0 <= v < 0.5, "a number in [0, 0.5)"),
             "sigma_flim_mpa": (_N, False, RatingInputs().sigma_Flim, lambda v: 0 < v <= 2000,
                                "a number in (0, 2000] MPa")}
_LOAD = {"torques_percent_of_rated": (list, False, None, None, "a list of numbers in (0, 500] %"),
         "torque_nm": ((list, int, float), False, None, None, "a number or a list of numbers in (0, 1e6] N m")}
_ANALYSIS = {"positions": (int, False, 6, lambda v: 1 <= v <= 500, "an integer in [1, 500] (per mesh cycle)"),
             "fidelity": (str, False, "coarse", lambda v: v in FIDELITIES, f"one of {sorted(FIDELITIES)}"),
             "far_teeth": (str, False, "none", lambda v: v in ("none", "full"), "'none' or 'full'")}
_TOP = {"case", "satellite", "cutter", "wheel", "material", "load", "analysis"}


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


def _table(data: dict, name: str, spec: dict, file, required: bool = True, nested: tuple = ()) -> dict:
    raw = data.get(name.split(".")[-1], None) if "." not in name else data
    if raw is None:
        if required:
            raise CaseError(name, None, "required table", file)
        raw = {}
    if not isinstance(raw, dict):
        raise CaseError(name, raw, "a table", file)
    for k in raw:
        if k not in spec and k not in nested:
            raise CaseError(f"{name}.{k}", raw[k], f"unknown key; allowed: {sorted(spec) + list(nested)}", file)
    out = {}
    for k, (typ, req, default, ok, words) in spec.items():
        if k not in raw:
            if req:
                raise CaseError(f"{name}.{k}", None, f"required; {words}", file)
            out[k] = default
            continue
        v = raw[k]
        if isinstance(v, bool) or not isinstance(v, typ) or (ok is not None and not ok(v)):
            raise CaseError(f"{name}.{k}", v, words, file)
        out[k] = float(v) if typ is _N else v
    return out


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


def _torques(raw: list, field: str, lo: float, hi: float, file) -> tuple[float, ...]:
    if not raw or any(isinstance(v, bool) or not isinstance(v, _N) or not lo < v <= hi for v in raw):
        raise CaseError(field, raw, f"a non-empty list of numbers in ({lo:g}, {hi:g}]", file)
    return tuple(float(v) for v in raw)


def parse_planetary_case(data: dict, file: str | None = None) -> PlanetaryCase:
    """Validate a planetary case dictionary (from TOML) and convert its units."""
    for k in data:
        if k not in _TOP:
            raise CaseError(k, data[k], f"unknown table; allowed: {sorted(_TOP)}", file)
    meta = data.get("case", {})
    sat = _table(data, "satellite", _SAT, file, nested=tuple(_TOOLS))
    cut = _table(data, "cutter", _CUTTER, file, required=False)
    m = sat["module_mm"]
    design = _make(SatelliteDesign, "satellite", file, dict(
        z=sat["teeth"], m=m, alpha=sat["pressure_angle_deg"] * DEG, x=sat["profile_shift"], thinning=sat["thinning"],
        rack_addendum_coef=cut["addendum"], rack_dedendum_coef=cut["dedendum"],
        rack_tip_radius_coef=cut["tip_radius"], d_tip=sat["tip_diameter_mm"]),
        dict(z="teeth", m="module_mm", alpha="pressure_angle_deg", x="profile_shift", d_tip="tip_diameter_mm",
             rack_addendum_coef="../cutter.addendum", rack_dedendum_coef="../cutter.dedendum",
             rack_tip_radius_coef="../cutter.tip_radius"))
    tools = {}
    raw_sat = data["satellite"]
    for name, spec in _TOOLS.items():
        t = _table(raw_sat.get(name, {}), f"satellite.{name}", spec, file, required=False)
        if name == "hob_three_pass":
            tools[name] = _make(HobThreePass, f"satellite.{name}", file,
                                dict(shift=t["shift_mm"], lead_angle=t["lead_angle_deg"] * DEG),
                                dict(shift="shift_mm", lead_angle="lead_angle_deg"))
        elif name == "disk_cutter":
            tools[name] = _make(DiskCutter, f"satellite.{name}", file,
                                dict(x_plunge=t["x_plunge"], n_teeth=t["teeth"], z_profile=t["profile_teeth"]),
                                dict(n_teeth="teeth", z_profile="profile_teeth"))
        else:
            tools[name] = _make(SpecialHob, f"satellite.{name}", file, dict(thickening=t["thickening"]), {})
    w = _table(data, "wheel", _WHEEL, file)
    if w["tooth_difference"] < 1:
        raise CaseError("wheel.tooth_difference", w["tooth_difference"], _WHEEL["tooth_difference"][4], file)
    wheel = _make(CentralWheelDesign, "wheel", file, dict(
        tooth_difference=w["tooth_difference"], eccentricity=w["eccentricity_mm"], x2=w["profile_shift"],
        shaper_teeth=w["shaper_teeth"], shaper_shift=w["shaper_profile_shift"],
        shaper_addendum_coef=w["shaper_addendum"], shaper_tip_radius_coef=w["shaper_tip_radius"],
        far_tip_clearance=w["far_tip_clearance_mm"], d_tip=w["tip_diameter_mm"]),
        dict(eccentricity="eccentricity_mm", x2="profile_shift", shaper_shift="shaper_profile_shift",
             shaper_addendum_coef="shaper_addendum", shaper_tip_radius_coef="shaper_tip_radius",
             far_tip_clearance="far_tip_clearance_mm", d_tip="tip_diameter_mm"))
    mat = _table(data, "material", _MATERIAL, file, required=False)
    if isinstance(data.get("load"), dict) and "torques_nm" in data["load"]:
        raise CaseError("load.torques_nm", data["load"]["torques_nm"], "renamed: write torque_nm = a number or a "
                        "list of numbers (N m)", file)
    load = _table(data, "load", _LOAD, file)
    if (load["torque_nm"] is None) == (load["torques_percent_of_rated"] is None):
        raise CaseError("load", data.get("load"), "exactly one of torque_nm or torques_percent_of_rated", file)
    torques, fractions = (), ()
    if load["torque_nm"] is not None:
        t = load["torque_nm"]
        torques = tuple(1e3 * t for t in _torques(t if isinstance(t, list) else [t], "load.torque_nm", 0, 1e6, file))
    else:
        fractions = tuple(0.01 * t for t in _torques(load["torques_percent_of_rated"],
                                                      "load.torques_percent_of_rated", 0, 500, file))
    an = _table(data, "analysis", _ANALYSIS, file, required=False)
    rating = RatingInputs(sigma_Flim=mat["sigma_flim_mpa"], b=sat["face_width_mm"])
    return PlanetaryCase(
        name=str(meta.get("name", "planetary")), design=design, method=sat["method"], tools=tools, wheel=wheel,
        face_width=sat["face_width_mm"], bore_diameter=sat["bore_diameter_mm"],
        wheel_outer_diameter=w["outer_diameter_mm"], material=mat["name"], young=mat["youngs_modulus_mpa"],
        poisson=mat["poisson_ratio"], rating=rating, torques=torques, torque_fractions=fractions,
        positions=an["positions"], fidelity=an["fidelity"], far_teeth=an["far_teeth"], source=meta.get("source"))


def load_planetary_case(path: str | Path) -> PlanetaryCase:
    """Read and validate a planetary case file."""
    return parse_planetary_case(read_toml(path), str(path))
