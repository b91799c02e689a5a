"""The gear train of a REXS model: which components a stage's gears relate to (flanks, tools, material, shaft,
flank modifications) and the torque each stage's gear_1 carries in each load case.

Torques: the ``external_load`` components that define a torque (``defines_torque``, ``torque_around_u_axis``, from
each load case of the load spectrum or else the component) act on the shaft they are assembled on; a shaft with one
gear hands its torque to that gear; a gear's torque is shared by the stages it meshes in side by side (a sun among
its planets), the tangential force passes unchanged through an idler (a planet between sun and ring), and gears on
one shaft share the shaft's torque. No losses: the tangential force ~ torque / z of each member (one transverse
module per mesh).
"""
from __future__ import annotations

from .errors import RexsError
from .model import Component, RexsModel

__all__ = ["GEAR_TYPES", "TOOL_TYPES", "MOD_TYPES", "stage_gears_of", "related", "flanks_of", "tools_of",
           "shaft_of", "material_of", "modifications_of", "teeth_of", "stage_torques"]

GEAR_TYPES = ("cylindrical_gear", "ring_gear")
TOOL_TYPES = ("rack_shaped_tool", "cutter_wheel_tool", "profile_tool")
MOD_TYPES = ("helix_crowning", "helix_slope", "profile_crowning", "tip_relief", "profile_slope",
             "end_relief_datum_face", "end_relief_non_datum_face", "triangular_tip_relief", "root_relief",
             "triangular_root_relief", "profile_twist", "topographical_modification", "helix_deviation",
             "profile_deviation")


# ------------------------------------------------------------------------------------------ relations
def stage_gears_of(model: RexsModel, sid: int):
    rel = [r for r in model.relations_of("stage", sid, "stage")]
    st = model.component(sid)
    if not rel:
        raise RexsError(st.label, "-", "no 'stage' relation names the gears of this stage (missing gear)",
                        None, model.file)
    r = rel[0]
    g1, g2 = r.role("gear_1"), r.role("gear_2")
    for role, g in (("gear_1", g1), ("gear_2", g2)):
        if g is None:
            raise RexsError(st.label, role, f"missing gear: the stage relation {r.id} has no {role}", None, model.file)
        if g not in model.components:
            raise RexsError(st.label, role, f"missing gear: the stage relation {r.id} names component {g}, which "
                            "the model does not contain", g, model.file)
        allowed = ("bevel_gear",) if st.type == "bevel_stage" else GEAR_TYPES
        if model.components[g].type not in allowed:
            raise RexsError(st.label, role, f"component {g} is a {model.components[g].type}, a "
                            f"{' or '.join(allowed)} expected", g, model.file)
    return g1, g2


def related(model: RexsModel, rtype: str, cid: int, role: str, other_role: str) -> list[Component]:
    out = []
    for r in model.relations_of(rtype, cid, role):
        o = r.role(other_role)
        if o is not None and o in model.components:
            out.append(model.components[o])
    return out


def flanks_of(model: RexsModel, gid: int) -> tuple[Component | None, Component | None]:
    for r in model.relations_of("flank", gid, "gear"):
        left, right = r.role("left"), r.role("right")
        return (model.components.get(left), model.components.get(right))
    return None, None


def tools_of(model: RexsModel, gear: Component, flanks) -> list[Component]:
    tools = [c for c in related(model, "ordered_reference", gear.id, "origin", "referenced") if c.type in TOOL_TYPES]
    tools += [c for c in related(model, "reference", gear.id, "origin", "referenced") if c.type in TOOL_TYPES]
    for f in flanks:
        if f is not None:
            tools += [c for c in related(model, "manufacturing_step", f.id, "workpiece", "tool")]
    seen, out = set(), []
    for t in tools:
        if t.id not in seen:
            seen.add(t.id)
            out.append(t)
    return out


def shaft_of(model: RexsModel, cid: int) -> int | None:
    for r in model.relations_of("assembly", cid, "part"):
        a = r.role("assembly")
        if a is not None and a in model.components and model.components[a].type == "shaft":
            return a
    return None


def material_of(model: RexsModel, gear: Component) -> Component | None:
    mats = [c for c in related(model, "reference", gear.id, "origin", "referenced") if c.type == "material"]
    if not mats:
        shaft = shaft_of(model, gear.id)
        if shaft is not None:
            mats = [c for c in related(model, "reference", shaft, "origin", "referenced") if c.type == "material"]
    return mats[0] if mats else None


def modifications_of(model: RexsModel, flank: Component | None) -> list[Component]:
    if flank is None:
        return []
    return [c for c in related(model, "reference", flank.id, "origin", "referenced") if c.type in MOD_TYPES]


# ------------------------------------------------------------------------------------------ torques
def teeth_of(c: Component) -> int:
    return abs(c.integer("number_of_teeth"))


def stages_of_gear(model: RexsModel, stage_gears: dict[int, tuple[int, int]], gid: int) -> list[int]:
    return [s for s, (a, b) in stage_gears.items() if gid in (a, b)]


def torque_per_load_case(model: RexsModel) -> list[tuple[str, dict[int, float]]]:
    """(load case label, {shaft id: torque N m}) from the external loads that define a torque."""
    loads = [c for c in model.of_type("external_load")]
    defining = [c for c in loads if c.has("defines_torque") and c.boolean("defines_torque")]
    cases = [(f"load case {lc.id}", lc) for lc in model.load_cases] or [("model", None)]
    out = []
    for label, lc in cases:
        shafts = {}
        for c in defining:
            src = lc.components.get(c.id) if lc is not None else None
            comp = src if src is not None and src.has("torque_around_u_axis") else c
            if not comp.has("torque_around_u_axis"):
                continue
            t = comp.number("torque_around_u_axis", "torque")
            shaft = shaft_of(model, c.id)
            if shaft is not None and t != 0.0:
                shafts[shaft] = abs(t)
        out.append((label, shafts))
    return out


def stage_torques(model: RexsModel, stage_gears: dict[int, tuple[int, int]]) -> dict[int, list[float]]:
    """Torque (N m) on each stage's gear_1 per load case, carried from the torque-defining loads through the gear
    train without losses: a gear's torque is shared by the stages it meshes in side by side (a sun among its
    planets); the tangential force passes unchanged through an idler (a planet between sun and ring); gears on one
    shaft share the shaft's torque."""
    gears = {g for pair in stage_gears.values() for g in pair}
    radius = {g: teeth_of(model.components[g]) for g in gears}       # tangential force ~ torque / z (same m_t)
    shaft_gears: dict[int, list[int]] = {}
    for g in gears:
        s = shaft_of(model, g)
        if s is not None:
            shaft_gears.setdefault(s, []).append(g)
    result: dict[int, list[float]] = {s: [] for s in stage_gears}

    def other(s: int, g: int) -> int:
        a, b = stage_gears[s]
        return b if a == g else a

    for _label, shafts in torque_per_load_case(model):
        force: dict[int, float] = {}                               # stage -> tangential force x (1 / m_t)

        def drive(g: int, torque: float, force: dict[int, float]) -> None:
            open_ = [s for s in stages_of_gear(model, stage_gears, g) if s not in force]
            if not open_:
                return
            f = torque / radius[g] / len(open_)
            frontier, reached = [], []
            for s in open_:
                force[s] = f
                frontier.append((other(s, g), f))
            while frontier:                                        # idlers pass the same force on
                p, fp = frontier.pop(0)
                for t in [t for t in stages_of_gear(model, stage_gears, p) if t not in force]:
                    force[t] = fp
                    frontier.append((other(t, p), fp))
                reached.append((p, fp))
            for p, fp in reached:                                  # gears on one shaft share its torque
                for h in shaft_gears.get(shaft_of(model, p), []) if shaft_of(model, p) is not None else []:
                    if h != p:
                        drive(h, fp * radius[p], force)

        for shaft, t in shafts.items():
            on = shaft_gears.get(shaft, [])
            if len(on) == 1:
                drive(on[0], t, force)
        for s, f in force.items():
            result[s].append(f * radius[stage_gears[s][0]])
    return result
