"""Flank pressure and edge contact of the loaded positions, kept apart as a gear engineer reads them.

A contact cell belongs to an edge zone when its part comes within ``delta`` (one nominal Hertz half-width, at
least one cell; two for the tip edges, whose sharp-edge pressure rise reaches further) of an edge of the contact
region, or when that edge ends its part (a cell clipped at an oblique edge, :mod:`ltca.cylindrical.cell_clip`),
checked in this order:

``pinion tip edge``
    the end of the pinion's involute at its tip (the tip circle, or where a rounding or chamfer starts);
    it presses on the gear's flank near the gear's start of active profile;
``gear tip edge``
    the gear's foot point within ``delta`` of the end of the gear's involute at its tip; it presses on the
    pinion's flank near the pinion's start of active profile;
``pinion form circle``
    the start of the pinion's involute (the active flank ends there, the lattice too);
``face end``
    the cell's part reaches within ``delta`` of a face end.

An edge is in contact when a cell touching it (within one cell) carries load; its zone's cells are then edge
cells, and it is reported, with where it happens and the load of its zone, when that load exceeds ``1e-3`` of
the position's normal force. Every other cell is flank (a contact near an edge that it does not reach
included): ``max_flank_pressure_mpa`` is the largest cell pressure among them, the Hertzian pressure away from
edge contact. A sharp edge (no rounding), a chamfer's corners, the face ends and the end of the lattice at the
form circle make a pressure singularity that the contact cells cannot resolve: the reported edge pressure there
grows as the cells are refined (mesh-dependent). A rounded edge gives a Hertzian contact of the rounding radius,
which converges once the cells resolve its half-width (reported per edge).
"""
from __future__ import annotations

import numpy as np

from ltca.geometry.cylindrical import arc_length, radius_of_arc

from .loaded import PositionResult
from .loaded_model import LoadedModel, hertz_line

__all__ = ["EDGES", "classify", "position_edges", "edge_summary", "edge_pattern"]

EDGES = ("pinion tip edge", "gear tip edge", "pinion form circle", "face end")
_LOADED = 1e-3          # share of the position's normal force above which a zone carries load
TIP = 2.0               # a tip edge's zone, in delta: the pressure rise of a sharp edge reaches a few half-widths


def _zone_width(lm: LoadedModel, torque: float, ds: float) -> float:
    return max(lm.half_width(torque), ds)


def classify(lm: LoadedModel, res: PositionResult, torque: float) -> tuple[np.ndarray, np.ndarray]:
    """Edge zone of each cell of a position (-1 flank, else the index into :data:`EDGES`), and whether the cell
    touches its edge (lies within one cell of it)."""
    model = lm.model
    p1, p2 = model.pinion, model.gear
    d = _zone_width(lm, torque, res.ds)
    s_lo = arc_length(model.pinion_range()[0], p1.r_base)
    s_end1 = arc_length(p1.r_flank_end, p1.r_base)
    s_end2 = arc_length(p2.r_flank_end, p2.r_base)
    half_z = res.area * np.cos(p1.beta_b) / (2 * res.ds)       # half the z extent of each cell's part
    to_end = 0.5 * model.face_width - np.abs(res.z) - half_z
    span = res.span if res.span is not None else np.zeros(len(res.s))   # a cell's part runs over s +- span
    dist = [s_end1 - res.s - span, ((res.gear_s - s_end2) if p2.internal else (s_end2 - res.gear_s)) - span,
            res.s - span - s_lo, to_end]
    bound = res.bound if res.bound is not None else np.zeros(len(res.s), np.uint8)
    # a cell whose part a clipped edge ends (see cell_clip) touches that edge; so does one within a cell of it
    ends = [(bound & (1 << k)) > 0 for k in range(len(dist))]
    zone = [(dist[k] <= reach) | ends[k] for k, reach in enumerate((TIP * d, TIP * d, d, d))]
    kind = np.full(len(res.s), -1)
    for k in range(len(dist) - 1, -1, -1):
        kind = np.where(zone[k], k, kind)
    k0 = np.maximum(kind, 0)
    near = (np.choose(k0, dist) <= np.where(kind == 3, 1e-9, res.ds)) | np.choose(k0, ends)
    return kind, (kind >= 0) & near


def position_edges(lm: LoadedModel, res: PositionResult, torque: float) -> dict:
    """Flank peak, and the load and peak pressure of each edge zone at one position (N, MPa); an edge is in
    contact (``loaded``) when a cell touching it carries load and its zone more than 1e-3 of the normal force."""
    kind, touch = classify(lm, res, torque)
    total = res.force.sum()
    load = np.array([res.force[kind == k].sum() for k in range(len(EDGES))])
    peak = np.array([res.pressure[kind == k].max() if (kind == k).any() else 0.0 for k in range(len(EDGES))])
    touched = np.array([res.force[touch & (kind == k)].sum() > 1e-9 * total for k in range(len(EDGES))])
    loaded = touched & (load > _LOADED * total)
    # the flank: every cell away from an edge in contact (a contact near an edge that it does not reach is flank)
    flank = (kind < 0) | ~touched[np.maximum(kind, 0)]
    carried = flank & (res.pressure > 0)          # a flank peak is a loaded flank cell's (none: index -1, 0 MPa)
    i = int(np.argmax(np.where(carried, res.pressure, -1.0))) if carried.any() else -1
    return {"kind": np.where(flank, -1, kind), "flank_peak": float(res.pressure[i]) if i >= 0 else 0.0,
            "flank_index": i, "edge_load": np.where(loaded, load, 0.0), "edge_pressure": np.where(loaded, peak, 0.0),
            "loaded": loaded}


def _edge_model(lm: LoadedModel, k: int) -> tuple[str, bool, str]:
    """How edge k is modelled, whether its pressure depends on the cells, and why."""
    p1, p2 = lm.model.pinion, lm.model.gear
    if k in (0, 1):
        edge = (p1 if k == 0 else p2).tip_edge
        if edge is None:
            return "sharp", True, "a sharp edge: the pressure there is singular and grows as the cells are refined"
        if edge.kind == "chamfer":
            return edge.describe(), True, "the chamfer's corners are sharp: their pressure grows with refinement"
        return edge.describe(), False, "a rounded edge: Hertzian contact of the rounding radius"
    if k == 2:
        return "end of the involute", True, "the active flank ends at the form circle: contact there is cut off"
    return "sharp face ends", True, "both faces end at the same plane without end relief: the end pressure " \
                                   "depends on the cells"


def edge_summary(lm: LoadedModel, results: list[PositionResult], torque: float) -> dict:
    """Summary keys: the flank peak with its place, and the edge contacts (see the module docstring)."""
    model = lm.model
    p1, p2 = model.pinion, model.gear
    per = [position_edges(lm, r, torque) for r in results]
    roll = np.degrees([r.roll for r in results])
    if all(e["flank_index"] < 0 for e in per):
        _no_flank(lm, results, per, torque)
    j = int(np.argmax([e["flank_peak"] for e in per]))
    r, e = results[j], per[j]
    i = e["flank_index"]
    out = {"max_flank_pressure_mpa": round(e["flank_peak"], 6)}      # as the other figures
    if i >= 0:
        d1 = 2 * radius_of_arc(r.s[i], p1.r_base)
        d2 = 2 * radius_of_arc(r.gear_s[i], p2.r_base)
        out["max_flank_pressure_at"] = {
            "roll_deg": round(float(roll[j]), 4), "pinion_tooth": int(r.tooth[i]),
            "pinion_diameter_mm": round(float(d1), 3), "gear_diameter_mm": round(float(d2), 3),
            "z_mm": round(float(r.z[i]), 3),
            "pinion_roll_angle_deg": round(float(np.degrees(np.sqrt(2 * r.s[i] / p1.r_base))), 3),
            "pairs_in_contact": int(sum(v > _LOADED * r.force.sum() for v in r.pair_load.values()))}
    records = []
    for k, name in enumerate(EDGES):
        at = [n for n, x in enumerate(per) if x["loaded"][k]]
        if not at:
            continue
        cells = [(results[n], per[n]["kind"] == k) for n in at]   # the zone of edge k at each of those positions
        loaded = [(res, m & (res.force > 0)) for res, m in cells]
        dia1 = np.concatenate([2 * radius_of_arc(res.s[m], p1.r_base) for res, m in loaded])
        dia2 = np.concatenate([2 * radius_of_arc(res.gear_s[m], p2.r_base) for res, m in loaded])
        zz = np.concatenate([res.z[m] for res, m in loaded])
        loads = np.array([per[n]["edge_load"][k] for n in at])
        peaks = np.array([per[n]["edge_pressure"][k] for n in at])
        how, dependent, why = _edge_model(lm, k)
        rec = {"edge": name, "modelled_as": how, "mesh_dependent": dependent, "why": why,
               "positions": len(at), "roll_deg": [round(float(roll[n]), 4) for n in at],
               "pinion_diameter_mm": [round(float(dia1.min()), 3), round(float(dia1.max()), 3)],
               "gear_diameter_mm": [round(float(dia2.min()), 3), round(float(dia2.max()), 3)],
               "z_mm": [round(float(zz.min()), 3), round(float(zz.max()), 3)],
               "max_load_n": round(float(loads.max()), 3), "max_load_roll_deg": round(float(roll[at[loads.argmax()]]), 4),
               "max_pressure_mpa": round(float(peaks.max()), 3),
               "max_pressure_roll_deg": round(float(roll[at[peaks.argmax()]]), 4)}
        if k in (0, 1) and not dependent:
            rec.update(_rounding_resolution(lm, results[at[peaks.argmax()]], per[at[peaks.argmax()]]["kind"] == k,
                                            (p1 if k == 0 else p2).tip_edge.size))
            if rec["cells_per_hertz_half_width"] < 3:
                rec["mesh_dependent"] = True
                rec["why"] += "; under-resolved here: raise cells_per_b"
        records.append(rec)
    out["edge_contact"] = records
    out["edge_note"] = _note(records)
    return out


def _no_flank(lm: LoadedModel, results: list[PositionResult], per: list[dict], torque: float) -> None:
    """Every loaded cell of every position lies in the zone of an edge in contact: there is no flank (Hertzian)
    pressure to report. A DesignError (exit status 2) naming the edges that carry the load and the fields that
    put it there, rather than a flank pressure of 0 MPa."""
    from ..validation import DesignError
    loads = np.array([e["edge_load"] for e in per]).max(axis=0)
    carried = [f"{name} (up to {loads[k]:.0f} N)" for k, name in enumerate(EDGES) if loads[k] > 0]
    b = lm.half_width(torque)
    where = {0: "pinion.modifications", 1: "gear.modifications", 2: "pinion.modifications"}
    fields = ["load.torque_nm"]
    for k, name in enumerate(EDGES):
        if loads[k] > 0 and k in where:
            fields += [f"{where[k]}.profile_form_um", f"{where[k]}.tip_relief_um"]
    advice = ("move the form deviations and misalignment towards 0 um (a flank that meets its mate away from the "
              "edges), or add tip relief / crowning")
    if loads[3] > 0:
        fields += ["assembly.lead_misalignment_um", "pinion.modifications.lead_form_um",
                   "pinion.modifications.lead_crowning_um", "analysis.fidelity"]
        # the contact runs along the face while the lead separation f z / b stays below the elastic approach
        # w / c' (c' = 14 N/(mm um), ISO 6336-1 typical single stiffness): a quarter of the face at f = 4 w / c'
        w = torque / (lm.model.pinion.r_base * lm.model.face_width)
        advice = (f"a lead misalignment of at most about {4 * w / 14.0:.0f} um (the contact then spans a quarter of "
                  "the face), lead crowning, or the fidelity 'fine' (more face slices); " + advice)
    raise DesignError(f"no contact away from the edges at any of the {len(results)} positions at "
                      f"{torque * 1e-3:g} N m: the load is carried at the {', '.join(carried) or 'edges'} only "
                      f"(Hertz half-width {b:.3g} mm; edge pressures are mesh-dependent), so no flank pressure can be "
                      "read", list(dict.fromkeys(fields)), advice, None)


def _rounding_resolution(lm: LoadedModel, res: PositionResult, zone: np.ndarray, radius: float) -> dict:
    """Local Hertz half-width of the contact on a rounded edge (cylinder of the rounding radius on a flank) and
    how many cells across it resolve it."""
    dz = lm.model.face_width / lm.fid.slices
    sl = np.unique(res.slice[zone])
    w = max(res.force[zone & (res.slice == j)].sum() for j in sl) / dz
    b, p0 = hertz_line(w, radius, lm.model.case.young, lm.model.case.poisson)
    return {"hertz_half_width_um": round(1e3 * b, 2), "cells_per_hertz_half_width": round(b / res.ds, 2)}


def _note(records: list[dict]) -> str:
    if not records:
        return "no edge contact: the load stays on the flanks"
    parts = []
    for r in records:
        state = "mesh-dependent" if r["mesh_dependent"] else "resolved"
        parts.append(f"{r['edge']} ({r['modelled_as']}) carries up to {r['max_load_n']:.0f} N at "
                     f"{r['positions']} position(s), peak {r['max_pressure_mpa']:.0f} MPa: {state}")
    return "edge contact: " + "; ".join(parts) + ". Edge pressures where an edge is sharp depend on the contact " \
        "cells and are not a flank (Hertzian) pressure; read max_flank_pressure_mpa for the flank."


def edge_pattern(lm: LoadedModel, results: list[PositionResult], torque: float,
                 lattice: tuple[float, float, int]) -> np.ndarray:
    """Where edge contact happened on the pinion flank lattice ``(u_lo, du, n)`` (involute roll angle bins, rad,
    of :func:`ltca.cylindrical.results.flank_lattice`) x face slices, over all positions and teeth: bit ``k`` set
    for :data:`EDGES` [k], as uint8, shape (n, slices)."""
    u_lo, du, n_lat = lattice
    rb = lm.model.pinion.r_base
    out = np.zeros((n_lat, lm.fid.slices), np.uint8)
    for res in results:
        e = position_edges(lm, res, torque)
        hit = (e["kind"] >= 0) & (res.force > 0)
        u = np.sqrt(2 * np.maximum(res.s[hit], 0.0) / rb)          # s = rb u^2 / 2 on the involute
        i = np.clip(np.floor((u - u_lo) / du).astype(int), 0, n_lat - 1)
        np.bitwise_or.at(out, (i, res.slice[hit]), (1 << e["kind"][hit]).astype(np.uint8))
    return out
