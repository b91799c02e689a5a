"""REXS gear stages mapped to the project's cylindrical case dict (the dict a TOML case file gives).

A ``cylindrical_stage`` joins ``gear_1`` and ``gear_2`` by a ``stage`` relation; each gear's flanks (``flank``
relation: ``cylindrical_gear_flank`` in REXS 1.4/2.0, ``flank_geometry`` in 1.0/1.1) carry the normal pressure angle
and the profile shift; its tool (``ordered_reference`` in 1.x, ``manufacturing_step`` in 2.0) the basic rack; its
material (``reference``, or the material of the shaft it sits on) Young's modulus and Poisson's ratio. A planetary
stage is written as cylindrical stages too (sun-planet and planet-ring, a ``ring_gear`` as gear_2), one per planet.

The mapping, REXS attribute -> case key:

========================================================  ===========================================
``cylindrical_gear.number_of_teeth``                      ``pinion/gear.teeth`` (``ring_gear``: internal)
``cylindrical_gear.normal_module``                        ``gear_pair.module_mm`` (equal on both)
``cylindrical_gear.helix_angle_reference_diameter``       ``gear_pair.helix_angle_deg`` (gear_1's; sign: hand)
``cylindrical_gear.face_width``                           ``*.face_width_mm``
``cylindrical_gear.tip_diameter``                         ``*.tip_diameter_mm``
``*_flank.normal_pressure_angle``                         ``gear_pair.pressure_angle_deg`` (left = right)
``*_flank.addendum_modification_coefficient``             ``*.profile_shift``
``*_flank.addendum_coefficient_basic_profile``            ``*.tip_diameter_mm`` = d +- 2 m_n (h_aP* + x)
``*_flank.tooth_tip_chamfer``                             ``*.modifications.tip_chamfer_mm``
tool ``addendum_coefficient_reference_profile``           ``cutter.addendum``
tool ``dedendum_coefficient_reference_profile``           ``cutter.dedendum``
tool ``tip_radius_factor`` / ``tip_corner_radius_factor_  ``cutter.tip_radius``
reference_profile``
``cutter_wheel_tool.number_of_teeth`` / ``addendum_       ``cutter.shaper_teeth`` / ``shaper_profile_shift``
modification_coefficient``
``helix_crowning.helix_crowning_amount_*``                ``*.modifications.lead_crowning_um``
``helix_slope.helix_slope``                               ``*.modifications.lead_slope_um``
``profile_crowning.profile_crowning_at_tip/_root``        ``*.modifications.profile_crowning_um``
``tip_relief.tip_relief_depth / _datum_diameter``         ``*.modifications.tip_relief_um / _start_diameter_mm``
``cylindrical_stage.center_distance``                     ``assembly.centre_distance_mm``
``material.elastic_modulus / poisson_ratio``              ``material.youngs_modulus_mpa / poisson_ratio``
``external_load.torque_around_u_axis`` (per load case)    ``load.torque_nm`` (carried to the stage's gear_1)
========================================================  ===========================================

A bevel stage (``bevel_stage`` with ``bevel_gear`` members; none in the reference samples) would map
``number_of_teeth``, ``mean_normal_module``/``outer_pitch_diameter``, ``mean_spiral_angle`` and
``spiral_angle_pitch_direction``, ``face_width``, ``pitch_angle``, ``face_angle``, ``root_angle``,
``outer_cone_distance`` and the shaft angle onto the ``[bevel]`` blank of a bevel case; it is listed as not mapped.

Everything a stage's components carry that the case cannot hold is returned as :class:`Unmapped` with a reason.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import RexsError
from .model import Component, RexsModel
from .train import (
    GEAR_TYPES,
    MOD_TYPES,
    flanks_of,
    material_of,
    modifications_of,
    shaft_of,
    stage_gears_of,
    stage_torques,
    teeth_of,
    tools_of,
)

__all__ = ["Unmapped", "StageInfo", "stage_infos", "stage_case_dict", "GEAR_TYPES"]


@dataclass(frozen=True)
class Unmapped:
    """An attribute of the model the case cannot represent, and why."""
    component: int
    component_type: str
    attribute: str
    value: object
    unit: str | None
    reason: str


@dataclass(frozen=True)
class StageInfo:
    """A cylindrical stage of the model: its component id, name, members (REXS gear ids: ``pinion`` is gear_1 unless
    that is the ring), whether the pair is internal, the planetary stage it belongs to, and the pinion torques
    (N m) of the model's load cases (empty: none found)."""
    id: int
    name: str | None
    pinion: int
    gear: int
    internal: bool
    planetary: int | None
    torques_nm: tuple[float, ...]


class _Used:
    """The attributes a mapping consumed, by component id."""

    def __init__(self):
        self.ids: dict[int, set[str]] = {}
        self.reasons: dict[tuple[int, str], str] = {}

    def take(self, c: Component, *attrs: str) -> None:
        self.ids.setdefault(c.id, set()).update(attrs)

    def skip(self, c: Component, attr: str, reason: str) -> None:
        self.reasons[(c.id, attr)] = reason


# ------------------------------------------------------------------------------------------ stage list
def _pinion_first(model: RexsModel, g1: int, g2: int) -> tuple[int, int]:
    c1 = model.components[g1]
    if c1.type == "ring_gear" or (c1.has("number_of_teeth") and c1.integer("number_of_teeth") < 0):
        return g2, g1
    return g1, g2


def _internal(c: Component) -> bool:
    return c.type == "ring_gear" or c.integer("number_of_teeth") < 0


def stage_infos(model: RexsModel) -> list[StageInfo]:
    """Every cylindrical stage of the model (by component id), with its pinion torques per load case."""
    stage_gears = {}
    for st in model.of_type("cylindrical_stage"):
        stage_gears[st.id] = stage_gears_of(model, st.id)
    torques = stage_torques(model, stage_gears) if stage_gears else {}
    planet_of = {}
    for ps in model.of_type("planetary_stage"):
        members = set()
        for r in model.relations:
            if any(x.id == ps.id for x in r.refs) and r.type in ("central_shaft", "planet_shaft"):
                members.update(g for g in (r.role("shaft"),) if g is not None)
        for s, (a, b) in stage_gears.items():
            if shaft_of(model, a) in members or shaft_of(model, b) in members:
                planet_of[s] = ps.id
    out = []
    for s, (g1, g2) in stage_gears.items():
        p, g = _pinion_first(model, g1, g2)
        tq = torques.get(s, [])
        if p != g1:      # the torque was carried to gear_1; the case's pinion is gear_2 (gear_1 is the ring)
            tq = [t * teeth_of(model.components[p]) / teeth_of(model.components[g1]) for t in tq]
        out.append(StageInfo(s, model.components[s].name, p, g, _internal(model.components[g]), planet_of.get(s),
                             tuple(tq)))
    return out


# ------------------------------------------------------------------------------------------ one stage
def _same(a: float, b: float, tol: float = 1e-9) -> bool:
    return abs(a - b) <= tol * max(1.0, abs(a), abs(b))


def _flank_value(model, used, gear, flanks, attr, dimension, required, default=None):
    """A value given on the gear's flanks (left and right must agree; the gear itself in older files)."""
    vals = []
    for f in flanks:
        if f is not None and f.has(attr):
            vals.append((f, f.number(attr, dimension)))
    if not vals and gear.has(attr):
        vals = [(gear, gear.number(attr, dimension))]
    if not vals:
        if required:
            where = ", ".join(f.label for f in flanks if f is not None) or gear.label
            raise RexsError(where, attr, f"missing: needed for {gear.label}", None, model.file)
        return default
    for c, v in vals[1:]:
        if not _same(v, vals[0][1]):
            raise RexsError(c.label, attr, f"left and right flanks differ ({vals[0][1]} and {v}): asymmetric flanks "
                            "are not supported by the cylindrical case", v, model.file)
    for c, _ in vals:
        used.take(c, attr)
    return vals[0][1]


def _member(model, used, gear: Component, module: float, helix_deg: float, unmapped: list) -> dict:
    flanks = flanks_of(model, gear.id)
    z = teeth_of(gear)
    used.take(gear, "number_of_teeth", "normal_module", "helix_angle_reference_diameter", "face_width")
    m: dict = {"teeth": z, "face_width_mm": gear.number("face_width", "length")}
    if _internal(gear):
        m["internal"] = True
    x = _flank_value(model, used, gear, flanks, "addendum_modification_coefficient", "none", False, None)
    if x is None:
        unmapped.append(Unmapped(gear.id, gear.type, "addendum_modification_coefficient", None, None,
                                 "not given: profile shift 0 assumed"))
        x = 0.0
    m["profile_shift"] = x
    d = z * module / math.cos(math.radians(helix_deg))
    sign = -1.0 if _internal(gear) else 1.0
    if gear.has("tip_diameter"):
        da = gear.number("tip_diameter", "length")
        ok = (d - 2.5 * module < da < d + 2 * module * (abs(x) + 2.5)) if sign > 0 else \
            (d - 2 * module * (abs(x) + 2.5) < da < d + 2.5 * module)
        if ok:
            m["tip_diameter_mm"] = da
            used.take(gear, "tip_diameter")
        else:
            used.skip(gear, "tip_diameter", f"implausible for this gear (reference diameter {d:.3f} mm, module "
                      f"{module} mm): not used, the tip follows from the module, shift and rack")
    else:
        hap = _flank_value(model, used, gear, flanks, "addendum_coefficient_basic_profile", "none", False, None)
        if hap is not None:
            m["tip_diameter_mm"] = d + sign * 2 * module * (hap + x)
    chamfer = _flank_value(model, used, gear, flanks, "tooth_tip_chamfer", "length", False, 0.0)
    mods: dict = {}
    if chamfer:
        mods["tip_chamfer_mm"] = chamfer
    for f in flanks:
        for mod in modifications_of(model, f):
            _modification(model, used, mod, mods)
    if mods:
        m["modifications"] = mods
    return m


def _modification(model, used, mod: Component, mods: dict) -> None:
    """One flank modification component into the member's modifications (both flanks give the same)."""
    def put(key, value):
        if key in mods and not _same(mods[key], value):
            raise RexsError(mod.label, key, f"left and right flank modifications differ ({mods[key]} and {value}): "
                            "the case holds one set per member", value, model.file)
        mods[key] = value
    if mod.type == "helix_crowning":
        a = [mod.number(k, "length") for k in ("helix_crowning_amount_datum_face",
                                                "helix_crowning_amount_non_datum_face") if mod.has(k)]
        if a and all(_same(v, a[0]) for v in a):
            put("lead_crowning_um", a[0] * 1e3)
            used.take(mod, "helix_crowning_amount_datum_face", "helix_crowning_amount_non_datum_face")
    elif mod.type == "helix_slope" and mod.has("helix_slope"):
        put("lead_slope_um", mod.number("helix_slope", "length") * 1e3)
        used.take(mod, "helix_slope")
    elif mod.type == "profile_crowning":
        a = [mod.number(k, "length") for k in ("profile_crowning_at_tip", "profile_crowning_at_root") if mod.has(k)]
        if a and all(_same(v, a[0]) for v in a):
            put("profile_crowning_um", a[0] * 1e3)
            used.take(mod, "profile_crowning_at_tip", "profile_crowning_at_root")
    elif mod.type == "tip_relief" and mod.has("tip_relief_depth"):
        put("tip_relief_um", mod.number("tip_relief_depth", "length") * 1e3)
        used.take(mod, "tip_relief_depth")
        if mod.has("tip_relief_datum_diameter"):
            put("tip_relief_start_diameter_mm", mod.number("tip_relief_datum_diameter", "length"))
            used.take(mod, "tip_relief_datum_diameter")


def _tool(tool: Component, module: float) -> dict:
    """A tool's basic-rack values as cutter keys (x module)."""
    out = {}
    for key, names in (("addendum", ("addendum_coefficient_reference_profile",)),
                       ("dedendum", ("dedendum_coefficient_reference_profile",)),
                       ("tip_radius", ("tip_radius_factor", "tip_corner_radius_factor_reference_profile"))):
        for n in names:
            if tool.has(n):
                out[key] = tool.number(n, "none")
                break
        else:
            absolute = {"addendum": "addendum_reference_profile", "dedendum": "dedendum_reference_profile",
                        "tip_radius": "tip_corner_radius_reference_profile"}[key]
            if tool.has(absolute):
                out[key] = tool.number(absolute, "length") / module
                names = (absolute,)
        out.setdefault("_attrs", {})[key] = [n for n in names if tool.has(n)]
    if tool.type == "cutter_wheel_tool":
        if tool.has("number_of_teeth"):
            out["shaper_teeth"] = tool.integer("number_of_teeth")
            out["_attrs"]["shaper_teeth"] = ["number_of_teeth"]
        if tool.has("addendum_modification_coefficient"):
            out["shaper_profile_shift"] = tool.number("addendum_modification_coefficient")
            out["_attrs"]["shaper_profile_shift"] = ["addendum_modification_coefficient"]
    return out


def stage_case_dict(model: RexsModel, stage_id: int, info: StageInfo | None = None,
                    torque_nm: float | list[float] | None = None) -> tuple[dict, list[Unmapped], set]:
    """The case dict (as a TOML case file gives it) of cylindrical stage ``stage_id``, the attributes of its
    components the case cannot represent, and the ids of the components it read.

    ``torque_nm`` replaces the torques of the model's load cases; a stage with neither is a :class:`RexsError`."""
    st = model.component(stage_id)
    if st.type != "cylindrical_stage":
        raise RexsError(st.label, "-", "not a cylindrical_stage", stage_id, model.file)
    info = info or next(i for i in stage_infos(model) if i.id == stage_id)
    used, unmapped = _Used(), []
    pin, gear = model.components[info.pinion], model.components[info.gear]
    for g in (pin, gear):
        for a in ("number_of_teeth", "normal_module", "face_width"):
            if not g.has(a):
                raise RexsError(g.label, a, f"missing: needed for stage {stage_id}", None, model.file)
    module = pin.number("normal_module", "length")
    if not _same(module, gear.number("normal_module", "length")):
        raise RexsError(gear.label, "normal_module", f"differs from the mating gear's {module} mm (no mesh)",
                        gear.number("normal_module", "length"), model.file)
    b1 = pin.number("helix_angle_reference_diameter", "angle") if pin.has("helix_angle_reference_diameter") else 0.0
    b2 = gear.number("helix_angle_reference_diameter", "angle") if gear.has("helix_angle_reference_diameter") else 0.0
    want = b1 if info.internal else -b1
    if not _same(abs(b1), abs(b2)) or (abs(b1) > 1e-9 and not _same(b2, want)):
        raise RexsError(gear.label, "helix_angle_reference_diameter",
                        f"must be {want} deg to mesh with {pin.label} ({'same' if info.internal else 'opposite'} "
                        "hand)", b2, model.file)
    alpha = [_flank_value(model, used, g, flanks_of(model, g.id), "normal_pressure_angle", "angle", True)
             for g in (pin, gear)]
    if not _same(alpha[0], alpha[1]):
        raise RexsError(gear.label, "normal_pressure_angle", f"differs from the mating gear's {alpha[0]} deg",
                        alpha[1], model.file)
    data: dict = {"case": {"name": f"{st.name or 'stage'} [{stage_id}]"[:200],
                           "source": f"REXS {model.version} ({model.application_id or 'unknown'}), "
                                     f"{model.file}: cylindrical_stage {stage_id}, gears {pin.id} and "
                                     f"{gear.id}"[:2000]},
                  "gear_pair": {"module_mm": module, "pressure_angle_deg": alpha[0], "helix_angle_deg": b1}}
    # tools: the case has one cutter; the pinion's tool first, a differing value of the gear's tool is listed
    cutter, cutter_src = {}, {}
    for g in (pin, gear):
        for tool in tools_of(model, g, flanks_of(model, g.id)):
            vals = _tool(tool, module)
            attrs = vals.pop("_attrs")
            for k, v in vals.items():
                if k.startswith("shaper") and not _internal(g):
                    continue
                if k not in cutter or _same(cutter[k], v):
                    cutter[k] = v
                    cutter_src[k] = tool
                    used.take(tool, *attrs.get(k, []))
                else:
                    for n in attrs.get(k, []):
                        used.skip(tool, n, f"the case has one cutter: {cutter_src[k].label} gives {k} = {cutter[k]}")
    if cutter:
        data["cutter"] = cutter
    data["pinion"] = _member(model, used, pin, module, b1, unmapped)
    data["gear"] = _member(model, used, gear, module, b2, unmapped)
    if st.has("center_distance"):
        data["assembly"] = {"centre_distance_mm": st.number("center_distance", "length")}
        used.take(st, "center_distance")
    if st.has("common_face_width"):
        bc = st.number("common_face_width", "length")
        if _same(bc, min(data["pinion"]["face_width_mm"], data["gear"]["face_width_mm"])):
            used.take(st, "common_face_width")
    mats = [material_of(model, g) for g in (pin, gear)]
    mat = {}
    for mc in mats:
        if mc is None:
            continue
        for key, attr, dim in (("youngs_modulus_mpa", "elastic_modulus", "stress"), ("poisson_ratio", "poisson_ratio",
                                                                                     "none")):
            if not mc.has(attr):
                continue
            v = mc.number(attr, dim)
            if key not in mat or _same(mat[key], v):
                mat[key] = v
                used.take(mc, attr)
            else:
                used.skip(mc, attr, f"the case has one material for both members: {mat[key]} of the pinion's used")
    if mat:
        data["material"] = mat
    else:
        unmapped.append(Unmapped(stage_id, st.type, "material", None, None,
                                 "not given: no material for either gear, the case's default steel is used"))
    torques = torque_nm if torque_nm is not None else list(info.torques_nm)
    if isinstance(torques, (int, float)):
        torques = [float(torques)]
    torques = list(dict.fromkeys(round(float(t), 12) for t in torques))
    if not torques:
        raise RexsError(st.label, "torque", "missing: no external load defines a torque that reaches this stage "
                        "(give one with --torque)", None, model.file)
    data["load"] = {"torque_nm": torques[0] if len(torques) == 1 else torques}
    # everything else the stage's components carry
    comps = [st, pin, gear] + [f for g in (pin, gear) for f in flanks_of(model, g.id) if f is not None]
    comps += [t for g in (pin, gear) for t in tools_of(model, g, flanks_of(model, g.id))]
    comps += [m for f in comps[3:] for m in modifications_of(model, f)]
    comps += [m for m in mats if m is not None]
    for r in model.relations_of("stage_gear_data", stage_id, "stage"):
        sgd = r.role("stage_gear_data")
        if sgd in model.components:
            comps.append(model.components[sgd])
    seen = set()
    for c in comps:
        if c.id in seen:
            continue
        seen.add(c.id)
        for a in c.attributes.values():
            if a.id in used.ids.get(c.id, set()):
                continue
            reason = used.reasons.get((c.id, a.id), _why(c, a.id))
            unmapped.append(Unmapped(c.id, c.type, a.id, a.value if not hasattr(a.value, "tag") else "<coded>",
                                     a.unit, reason))
    return data, unmapped, seen


def _why(c: Component, attr: str) -> str:
    if attr in ("support_vector", "u_axis_vector", "w_axis_vector", "u_coordinate_on_shaft",
                "reference_component_for_position", "rotating_angle_around_neg_u_axis"):
        return "placement in the gear unit: the case models the pair alone"
    if c.type == "material":
        return "material property the linear-elastic analysis does not use"
    if c.type in MOD_TYPES:
        return f"flank modification {c.type} has no case key"
    return "no case key for this attribute"
