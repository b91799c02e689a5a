"""Our loaded results written into a REXS model as REXS 2.0 result attributes and components, and read back.

The writer takes a plain mapping of figures and arrays (engineer's units), so any result type can feed it:

=====================================  =========  ========================================================
key                                    shape      meaning
=====================================  =========  ========================================================
``torque_nm``                          scalar     pinion torque, N m
``roll_deg``                           (P,)       pinion roll of each mesh position, deg
``te_loaded_um``                       (P,)       loaded transmission error along the line of action, um
``mesh_stiffness_n_per_mm_um``         (P,)       mesh stiffness per face width, N/(mm um)
``face_width_mm``                      scalar     the face width the distribution runs over, mm
``face_mm``                            (F,)       axial nodes of the load distribution, from mid-face, mm
``load_distribution_n_per_mm``         (F,)       normal load per face width at the nodes, cycle mean, N/mm
``face_load_factor``                   scalar     K_Hbeta = largest / mean of the load distribution
``contact``                            mapping    points on the contact lines: ``position`` (N,) index into
                                                  roll_deg, ``face_mm`` (N,), ``diameter_mm`` (N,) on the pinion,
                                                  ``line_load_n_per_mm`` (N,), ``hertz_mpa`` (N,)
``root_stress_mpa``                    mapping    ``pinion`` and ``gear``: (P,) largest fillet stress, MPa
=====================================  =========  ========================================================

Where it goes (REXS 2.0.0 names, units and value types; :mod:`ltca.rexs.schema` checks them):
``cylindrical_stage``: ``load_distribution_along_face_width`` with ``load_distribution_node_positions`` (from the
face's datum side), ``number_of_nodes_in_mesh_width_for_loaddistribution``, ``face_load_factor_contact_stress``,
``meshing_stiffness_characteristic`` (N/mm: per face width times the face width), the loaded TE as
``custom_ltca_loaded_transmission_error`` (REXS has no attribute for it) and ``custom_ltca_torque``;
each member's ``cylindrical_stage_gear_data``: ``rotational_meshing_position`` and ``torque``, and a
``gear_root_data_set`` with ``local_tooth_root_stress``; the contact lines: a ``point_list`` (assembled in the pinion's
stage gear data: ``point_coordinates_u_coord``, ``point_coordinates_radius``, ``point_ids``, the position as
``custom_ltca_position_index``) referencing a ``meshing_contact_stage_data_set`` with ``local_normal_line_load``,
``local_hertzian_contact_stress`` and ``set_ids``. A model's REXS 1.x ``stage_gear_data`` is written as its 2.0 name.
"""
from __future__ import annotations

import math
from typing import Any, Mapping

import numpy as np

from .errors import RexsError
from .model import Attribute, Component, Ref, Relation, RexsModel

__all__ = ["results_from_dataset", "write_results", "read_results", "hertz_line_load", "TAG"]

#: name prefix of the components the writer adds (removed again when a stage's results are written anew)
TAG = "ltca result"


# ------------------------------------------------------------------------------------- from our dataset
def _geometry(case) -> dict:
    """Base radii, centre distance and working pressure angle of a case (ISO 21771:2007 eqs. (6), (18), (57))."""
    at = math.atan(math.tan(case.pressure_angle) / math.cos(case.helix_angle))
    z1, z2 = case.pinion.teeth, case.gear.teeth
    mt = case.module / math.cos(case.helix_angle)
    rb1, rb2 = 0.5 * z1 * mt * math.cos(at), 0.5 * z2 * mt * math.cos(at)
    s = -1.0 if case.gear.internal else 1.0
    if case.centre_distance is not None:
        a = case.centre_distance
    else:
        inv = math.tan(at) - at + 2 * math.tan(case.pressure_angle) * (s * case.pinion.profile_shift
                                                                      + case.gear.profile_shift) / (z2 + s * z1)
        lo, hi = 0.0, 1.5
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if math.tan(mid) - mid < inv else (lo, mid)
        a = 0.5 * mt * (z2 + s * z1) * math.cos(at) / math.cos(lo)
    awt = math.acos((rb2 + s * rb1) / a * s) if s < 0 else math.acos((rb1 + rb2) / a)
    beta_b = math.atan(math.tan(abs(case.helix_angle)) * math.cos(at))
    return dict(rb1=rb1, rb2=rb2, a=a, awt=awt, beta_b=beta_b, internal=case.gear.internal)


def hertz_line_load(p0: np.ndarray, diameter: np.ndarray, case) -> np.ndarray:
    """Normal line load (N/mm along the contact line) of a Hertzian line contact of peak pressure ``p0`` (MPa) at
    pinion diameter ``diameter`` (mm): w = pi R' p0^2 / E* (Johnson 1985, eq. 4.45), R' the relative radius of
    curvature normal to the contact line (involutes: transverse radii rho_1 = r_b1 tan, rho_2 = T1T2 -+ rho_1,
    divided by cos beta_b), E* = E / (2 (1 - nu^2)) for two members of one material."""
    g = _geometry(case)
    loa = g["a"] * math.sin(g["awt"])
    rho1 = np.sqrt(np.maximum((0.5 * np.asarray(diameter)) ** 2 - g["rb1"] ** 2, 0.0))
    rho2 = rho1 + loa if g["internal"] else loa - rho1
    with np.errstate(divide="ignore", invalid="ignore"):
        r_rel = rho1 * rho2 / (rho2 - rho1 if g["internal"] else rho1 + rho2) / math.cos(g["beta_b"])
    e_star = case.young / (2 * (1 - case.poisson ** 2))
    return np.where(r_rel > 0, math.pi * r_rel * np.asarray(p0, float) ** 2 / e_star, 0.0)


def results_from_dataset(ds, case, torque_nm: float | None = None) -> dict:
    """The writer's mapping from a run's dataset (``results.nc`` of ``ltca run``, or one torque's position dataset)
    of ``case``. The line load along each contact line has the shape the peak pressure on the flank lattice gives
    through Hertz (:func:`hertz_line_load`; an edge contact's peak above the position's flank peak counted at the
    flank peak) and the tooth's normal load (``pair_load``) as its integral; the load
    distribution is each position's line load summed over the teeth at each face slice, per face width
    (/ cos beta_b), averaged over the positions; K_Hbeta is its largest over its mean value."""
    if "torque" in ds.dims:
        tq = np.asarray(ds["torque"].values, float)
        k = 0 if torque_nm is None else int(np.argmin(np.abs(tq - float(torque_nm))))
        if torque_nm is not None and abs(tq[k] - float(torque_nm)) > 1e-6 * max(1.0, abs(float(torque_nm))):
            raise RexsError("results.nc", "torque", f"no analysis at {torque_nm} N m; the torques are "
                            f"{[float(x) for x in tq]}", torque_nm)
        t = float(tq[k])
        ds = ds.isel(torque=k)
    elif "torque" in ds.coords:
        t = float(ds["torque"].values)
    else:
        t = float(ds.attrs.get("torque_nm", torque_nm))
    g = _geometry(case)
    roll = np.asarray(ds["roll"].values, float)
    p = np.asarray(ds["pressure"].values, float)                    # (position, tooth, flank_roll, face)
    u = np.radians(np.asarray(ds["flank_roll"].values, float))
    diam = 2 * g["rb1"] * np.sqrt(1 + u ** 2)
    face = np.asarray(ds["face"].values, float)
    # the line load's shape: Hertz from the lattice pressure, an edge contact's peak (above the position's flank
    # peak) counted at the flank peak; the written Hertzian stress is the lattice pressure itself
    cap = np.asarray(ds["max_flank_pressure"].values, float)[:, None, None, None] if "max_flank_pressure" in ds else p
    w = hertz_line_load(np.minimum(p, cap), diam[None, None, :, None], case)   # N/mm along the line
    # each tooth's line load scaled to its normal load (pair_load, exact): F = sum_slices w dz / cos beta_b
    dz = float(face[1] - face[0]) if len(face) > 1 else float(case.pinion.face_width)
    line = w.max(axis=2)                                          # (position, tooth, face)
    total = line.sum(axis=2) * dz / math.cos(g["beta_b"])
    pair = np.asarray(ds["pair_load"].values, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        scale = np.where(total > 0, pair / total, 0.0)
    w = w * scale[:, :, None, None]
    per_slice = (line * scale[:, :, None]).sum(axis=1) / math.cos(g["beta_b"])  # (position, face): N per mm of face
    dist = per_slice.mean(axis=0)
    pos, tooth, prof, fz = np.nonzero(p > 0)
    keep = np.ones(len(pos), bool)
    # one point per contact line and slice: the lattice point of the largest pressure across the line
    best = p.argmax(axis=2)
    sel = prof == best[pos, tooth, fz]
    pos, tooth, prof, fz = pos[sel & keep], tooth[sel & keep], prof[sel & keep], fz[sel & keep]
    b = float(max(case.pinion.face_width, case.gear.face_width)) if not hasattr(case, "face_width") else case.face_width
    return {
        "torque_nm": t,
        "roll_deg": roll,
        "te_loaded_um": np.asarray(ds["te_loaded_um"].values, float),
        "mesh_stiffness_n_per_mm_um": np.asarray(ds["mesh_stiffness"].values, float),
        "face_width_mm": float(face[-1] - face[0] + (face[1] - face[0])) if len(face) > 1 else b,
        "face_mm": face,
        "load_distribution_n_per_mm": dist,
        "face_load_factor": float(dist.max() / dist.mean()) if dist.mean() > 0 else float("nan"),
        "contact": {"position": pos.astype(int), "face_mm": face[fz], "diameter_mm": diam[prof],
                    "line_load_n_per_mm": w[pos, tooth, prof, fz], "hertz_mpa": p[pos, tooth, prof, fz]},
        "root_stress_mpa": {"pinion": np.nanmax(np.asarray(ds["root_stress_pinion"].values, float), axis=1),
                            "gear": np.nanmax(np.asarray(ds["root_stress_gear"].values, float), axis=1)},
    }


# ------------------------------------------------------------------------------------- writing
def _floats(x) -> list[float]:
    return [float(v) for v in np.asarray(x, float).ravel()]


def _set(c: Component, aid: str, unit: str, vtype: str, value: Any) -> None:
    c.attributes[aid] = Attribute(aid, unit, value, vtype)


def _stage_gear_data(model: RexsModel, stage_id: int, gear_id: int) -> Component:
    for r in model.relations_of("stage_gear_data", stage_id, "stage"):
        if r.role("gear") == gear_id and r.role("stage_gear_data") in model.components:
            c = model.components[r.role("stage_gear_data")]
            if c.type == "stage_gear_data":
                c.type = "cylindrical_stage_gear_data"
            return c
    c = Component(model.next_id(), "cylindrical_stage_gear_data", f"{TAG}: stage {stage_id} gear {gear_id}")
    model.components[c.id] = c
    model.relations.append(Relation(model.next_relation_id(), "stage_gear_data",
                                    (Ref(stage_id, "stage", "cylindrical_stage"),
                                     Ref(gear_id, "gear", model.components[gear_id].type),
                                     Ref(c.id, "stage_gear_data", c.type))))
    return c


def _drop_previous(model: RexsModel, stage_id: int) -> None:
    mark = f"{TAG} [stage {stage_id}]"
    gone = {cid for cid, c in model.components.items() if (c.name or "").startswith(mark)}
    for cid in gone:
        del model.components[cid]
    model.relations = [r for r in model.relations if not any(x.id in gone for x in r.refs)]


def _new(model: RexsModel, ctype: str, stage_id: int, what: str) -> Component:
    c = Component(model.next_id(), ctype, f"{TAG} [stage {stage_id}] {what}")
    model.components[c.id] = c
    return c


def write_results(model: RexsModel, stage_id: int, pinion_id: int, gear_id: int, res: Mapping[str, Any],
                  ratio: float) -> dict[int, list[str]]:
    """Write one stage's results (the mapping of this module's table) into ``model``; returns {component id:
    attribute ids written} (for :func:`ltca.rexs.schema.check_model` ``only=``). ``ratio`` = z_gear / z_pinion.
    Results written before for the stage are replaced."""
    st = model.component(stage_id)
    if st.type != "cylindrical_stage":
        raise RexsError(st.label, "-", "results are written to a cylindrical_stage", stage_id, model.file)
    _drop_previous(model, stage_id)
    written: dict[int, list[str]] = {}

    def put(c, aid, unit, vtype, value):
        _set(c, aid, unit, vtype, value)
        written.setdefault(c.id, []).append(aid)

    b = float(res["face_width_mm"])
    face = np.asarray(res["face_mm"], float)
    put(st, "load_distribution_along_face_width", "N / mm", "floating_point_array",
        _floats(res["load_distribution_n_per_mm"]))
    put(st, "load_distribution_node_positions", "mm", "floating_point_array", _floats(face + 0.5 * b))
    put(st, "number_of_nodes_in_mesh_width_for_loaddistribution", "none", "integer", int(len(face)))
    put(st, "face_load_factor_contact_stress", "none", "floating_point", float(res["face_load_factor"]))
    put(st, "meshing_stiffness_characteristic", "N / mm", "floating_point_array",
        _floats(np.asarray(res["mesh_stiffness_n_per_mm_um"], float) * b * 1e3))
    put(st, "custom_ltca_loaded_transmission_error", "mum", "floating_point_array", _floats(res["te_loaded_um"]))
    put(st, "custom_ltca_torque", "N m", "floating_point", float(res["torque_nm"]))
    roll = np.asarray(res["roll_deg"], float)
    data = {}
    for gid, key, rot, torque in ((pinion_id, "pinion", roll, res["torque_nm"]),
                                  (gear_id, "gear", -roll / ratio, res["torque_nm"] * ratio)):
        sgd = _stage_gear_data(model, stage_id, gid)
        data[key] = sgd
        put(sgd, "rotational_meshing_position", "deg", "floating_point_array", _floats(rot))
        put(sgd, "torque", "N m", "floating_point", float(torque))
        root = _new(model, "gear_root_data_set", stage_id, f"root stress {key}")
        put(root, "local_tooth_root_stress", "MPa", "floating_point_array", _floats(res["root_stress_mpa"][key]))
        model.relations.append(Relation(model.next_relation_id(), "reference",
                                        (Ref(sgd.id, "origin", sgd.type), Ref(root.id, "referenced", root.type))))
    c = res["contact"]
    n = len(np.asarray(c["face_mm"]))
    pts = _new(model, "point_list", stage_id, "contact lines")
    put(pts, "point_ids", "none", "integer_array", list(range(1, n + 1)))
    put(pts, "point_coordinates_u_coord", "mm", "floating_point_array", _floats(np.asarray(c["face_mm"]) + 0.5 * b))
    put(pts, "point_coordinates_radius", "mm", "floating_point_array", _floats(0.5 * np.asarray(c["diameter_mm"])))
    put(pts, "custom_ltca_position_index", "none", "integer_array", [int(k) for k in np.asarray(c["position"])])
    mesh = _new(model, "meshing_contact_stage_data_set", stage_id, "contact lines")
    put(mesh, "set_ids", "none", "integer_array", [pts.id])
    put(mesh, "local_normal_line_load", "N / mm", "floating_point_array", _floats(c["line_load_n_per_mm"]))
    put(mesh, "local_hertzian_contact_stress", "MPa", "floating_point_array", _floats(c["hertz_mpa"]))
    model.relations.append(Relation(model.next_relation_id(), "assembly",
                                    (Ref(data["pinion"].id, "assembly", data["pinion"].type),
                                     Ref(pts.id, "part", pts.type))))
    model.relations.append(Relation(model.next_relation_id(), "reference",
                                    (Ref(pts.id, "origin", pts.type), Ref(mesh.id, "referenced", mesh.type))))
    return written


# ------------------------------------------------------------------------------------- reading back
def _array(c: Component, aid: str) -> np.ndarray:
    if aid not in c.attributes:
        raise RexsError(c.label, aid, "missing: a result written by ltca is expected here", None, c.file)
    return np.asarray([float(v) for v in c.attributes[aid].value], float)


def read_results(model: RexsModel, stage_id: int, pinion_id: int, gear_id: int) -> dict:
    """The mapping :func:`write_results` wrote for a stage, read back from the model."""
    st = model.component(stage_id)
    nodes = _array(st, "load_distribution_node_positions")
    stiff = _array(st, "meshing_stiffness_characteristic")
    sgd = {k: _stage_gear_data(model, stage_id, g) for k, g in (("pinion", pinion_id), ("gear", gear_id))}
    roots = {}
    for k, c in sgd.items():
        for r in model.relations_of("reference", c.id, "origin"):
            t = model.components.get(r.role("referenced"))
            if t is not None and t.type == "gear_root_data_set":
                roots[k] = _array(t, "local_tooth_root_stress")
    pts = next(model.components[r.role("part")] for r in model.relations_of("assembly", sgd["pinion"].id, "assembly")
               if model.components.get(r.role("part")) is not None
               and model.components[r.role("part")].type == "point_list")
    mesh = next(model.components[r.role("referenced")] for r in model.relations_of("reference", pts.id, "origin")
                if model.components[r.role("referenced")].type == "meshing_contact_stage_data_set")
    b = 2 * float(nodes[0]) if len(nodes) == 1 else float(nodes[0] + nodes[-1])
    face = nodes - 0.5 * b
    return {
        "torque_nm": float(st.attributes["custom_ltca_torque"].value),
        "roll_deg": _array(sgd["pinion"], "rotational_meshing_position"),
        "te_loaded_um": _array(st, "custom_ltca_loaded_transmission_error"),
        "mesh_stiffness_n_per_mm_um": stiff / (b * 1e3),
        "face_width_mm": b,
        "face_mm": face,
        "load_distribution_n_per_mm": _array(st, "load_distribution_along_face_width"),
        "face_load_factor": float(st.attributes["face_load_factor_contact_stress"].value),
        "contact": {"position": _array(pts, "custom_ltca_position_index").astype(int),
                    "face_mm": _array(pts, "point_coordinates_u_coord") - 0.5 * b,
                    "diameter_mm": 2 * _array(pts, "point_coordinates_radius"),
                    "line_load_n_per_mm": _array(mesh, "local_normal_line_load"),
                    "hertz_mpa": _array(mesh, "local_hertzian_contact_stress")},
        "root_stress_mpa": roots,
    }
