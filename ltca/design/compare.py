"""The starting design beside the optimum (against Cao et al. 2008): one table of the flank targets, the
loaded TE peak-to-peak at each torque of the case and the edge figures over the mounting tolerance box.

For the bevel case the starting design is the case's own (the targets of Cao et al. 2008: working eta2 22 deg / m21 8.25
arcsec, coast 14 deg / 11.25 arcsec, the coast path angle -14 deg in our sign convention, see
``cases/spiral_bevel_optimise.toml``). The box figures are the worst over the nominal mounting and the corners of
``[design.constraints] tolerance_box`` at the top torque (:meth:`ltca.design.bevel.BevelBackend.box_report`):
the smallest toe / heel and top margins (mm), the largest edge load share and interior peak pressure. The table
goes to ``design.json`` (``seed_vs_optimum``) and ``seed_vs_optimum.csv``.
"""
from __future__ import annotations

import math

__all__ = ["seed_table", "table_csv"]

#: flank-target rows of the table: settings key -> label
_TARGETS = {"bevel.working.path_angle_deg": "working path angle eta2 (deg)",
            "bevel.working.te_magnitude_arcsec": "working TE magnitude m21 (arcsec)",
            "bevel.coast.path_angle_deg": "coast path angle eta2 (deg)",
            "bevel.coast.te_magnitude_arcsec": "coast TE magnitude m21 (arcsec)"}


def _worst(corners: list[dict]) -> dict[str, float]:
    """The worst figures over the rows of one design's tolerance box."""
    return {"edge_margin_mm": min(r["edge_margin_mm"] for r in corners),
            "top_margin_mm": min(r["top_margin_mm"] for r in corners),
            "edge_share": max(r["edge_share"] for r in corners),
            "max_interior_pressure_mpa": max(r["max_interior_pressure_mpa"] for r in corners),
            "te_ptp_arcsec": max(r["te_ptp_arcsec"] for r in corners)}


def seed_table(torques_nm, settings: dict[str, dict], te_ptp: dict[str, list], box: dict[str, dict],
               feasible: dict[str, bool], tolerance_box_mm) -> dict:
    """The seed-vs-optimum table.

    Parameters
    ----------
    torques_nm : sequence of float
        The case's torques, N m.
    settings : {"baseline": {...}, "optimum": {...}}
        Each design's case keys (:meth:`ltca.design.bevel.BevelBackend.settings`).
    te_ptp : {"baseline": [...], "optimum": [...]}
        Loaded TE peak-to-peak at each torque, arcsec (the candidates' own evaluations).
    box : {"baseline": box_report, "optimum": box_report}
        Each design over the tolerance box (:meth:`ltca.design.bevel.BevelBackend.box_report`).
    feasible : {"baseline": bool, "optimum": bool}
    tolerance_box_mm : (E, P, G)
        Half-widths of the box, mm.

    Returns
    -------
    dict
        ``rows`` (quantity, unit, baseline, optimum), ``box_torque_nm``, ``tolerance_box_mm`` and, per design,
        ``corners`` (the box report's rows).
    """
    names = ("baseline", "optimum")
    rows = [{"quantity": label, "baseline": settings["baseline"].get(key, math.nan),
             "optimum": settings["optimum"].get(key, math.nan)} for key, label in _TARGETS.items()]
    for k, t in enumerate(torques_nm):
        rows.append({"quantity": f"loaded TE peak-to-peak at {t:g} N m (arcsec)",
                     **{n: float(te_ptp[n][k]) for n in names}})
    worst = {n: _worst(box[n]["corners"]) for n in names}
    top = box["baseline"]["torque_nm"]
    for key, label in (("edge_margin_mm", "smallest toe/heel margin over the box (mm)"),
                       ("top_margin_mm", "smallest top margin over the box (mm)"),
                       ("edge_share", "largest edge load share over the box (-)"),
                       ("max_interior_pressure_mpa", "largest interior peak pressure over the box (MPa)"),
                       ("te_ptp_arcsec", "largest loaded TE peak-to-peak over the box (arcsec)")):
        rows.append({"quantity": f"{label} at {top:g} N m", **{n: worst[n][key] for n in names}})
    rows.append({"quantity": "feasible", **{n: bool(feasible[n]) for n in names}})
    return {"box_torque_nm": top, "tolerance_box_mm": [float(x) for x in tolerance_box_mm], "rows": rows,
            "corners": {n: box[n]["corners"] for n in names}}


def table_csv(table: dict) -> str:
    """The table's rows as CSV text (quantity, baseline, optimum)."""
    def cell(x):
        return str(x) if isinstance(x, bool) else f"{x:.6g}"
    return "quantity,baseline,optimum\n" + "".join(f"\"{r['quantity']}\",{cell(r['baseline'])},{cell(r['optimum'])}\n"
                                                    for r in table["rows"])
