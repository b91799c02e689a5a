"""The bevel m21 against the design torque (physics): a constrained scan of the working flank's TE
magnitude m21 at a fixed path angle eta2, with each design torque as the only (top) torque.

What it shows (the path angle eta2 = 22 deg of Cao et al. 2008, 8 positions, coarse fidelity). The loaded TE
peak-to-peak over m21 has two basins: the lowest m21 (1 arcsec: the neighbouring pairs share the load early and
flatten the loaded TE, 4.4 arcsec at 175 and 350 N m), where the loaded pattern runs along the path past the
transfer points into the toe (toe/heel margin 0.16 mm); and an interior minimum, where the parabola absorbs the
pair's elastic approach (loaded minus unloaded TE) with the pattern 3-7 mm off the toe and heel. The interior
minimum moves up with the torque, m21 about 0.27-0.36 times the approach: 13, 25, 35 and >= 55 arcsec at 35, 100,
175 and 350 N m (bodies held at their mounting; loaded TE p-p there 2.91, 3.75, 5.39, 7.93 arcsec). The constraint
(``margin_mm`` off the toe and the heel, :func:`ltca.design.bevel_checks.edge_margin`) removes the first basin at
175 and 350 N m; the constrained optimum is the interior one at every torque. The smallest m21 that keeps the margin
grows with the torque too (3, 7, 9, 19 arcsec at the nominal mounting; a +-0.05 mm E/P/G box needs more).

What a row holds (per m21 and torque, at the case's mounting, unless ``corners``: the worst over the tolerance
box): loaded TE peak-to-peak (arcsec), the elastic approach (mean loaded minus mean unloaded TE, arcsec), the
toe / heel and top margins (mm), the largest edge load share, the interior peak pressure (MPa), the edges loaded.
Per torque the summary gives the smallest m21 that keeps the margin (the constraint's boundary, between two scan
points: the first feasible one), the constrained optimum and its margins, the unconstrained optimum, and which
constraint is active at the constrained optimum; with a tolerance box, the constrained optimum and the boundary
design are checked again over its corners (``*_over_box``: the smallest margins, the largest edge share).

Reproduce the table (one process, about 2 min on 2 cores)::

    python3 -m ltca.design.bevel_torque cases/spiral_bevel_optimise.toml --out out/m21_torque.json
"""
from __future__ import annotations

import argparse
import copy
import json
import sys

import numpy as np

from .bevel_checks import cycle_measures

__all__ = ["M21", "TORQUES", "scan", "summarise", "run", "main"]

#: default scan: m21 (arcsec) and design torques (N m)
M21 = (1.0, 3.0, 5.0, 7.0, 9.0, 11.0, 13.0, 16.0, 19.0, 22.0, 25.0, 28.0, 31.0, 35.0, 40.0, 45.0, 50.0, 55.0)
TORQUES = (35.0, 100.0, 175.0, 350.0)


def _backend(data: dict, file: str, torques, m21_upper: float, box_mm):
    from .bevel import BevelBackend
    from .schema import parse_design
    d = copy.deepcopy(data)
    d["load"]["torque_nm"] = [float(t) for t in torques]
    design = d.setdefault("design", {})
    design["variables"] = {"working_te_magnitude_arcsec": {"lower": 1.0, "upper": float(m21_upper)}}
    design["constraints"] = {"tolerance_box": dict(zip(("E_mm", "P_mm", "G_mm"), map(float, box_mm))),
                             "edge_margin_mm": 1.0} if any(x > 0 for x in box_mm) else {}
    spec = parse_design(d, "bevel", len(torques), file)
    return BevelBackend(d, spec, file)


def scan(backend, eta2_deg: float, m21s, torques, corners: bool = False, say=None) -> list[dict]:
    """Rows (module docstring) of every m21 (arcsec) at every torque (N m) at path angle ``eta2_deg``; a design
    the geometry cannot make is a row with its ``failure``."""
    from ltca.geometry.bevel.tca import RAD_PER_ARCSEC
    rows = []
    for m in m21s:
        values = {"working_path_angle_deg": float(eta2_deg), "working_te_magnitude_arcsec": float(m)}
        for t in torques:
            row = {"m21_arcsec": float(m), "torque_nm": float(t), "eta2_deg": float(eta2_deg)}
            try:
                worst = None
                for asm in (backend.corners() if corners else [None]):
                    lm, res = backend.cycle(values, t, asm)
                    c = cycle_measures(lm, res)
                    if worst is None:
                        te = np.array([r.te for r in res]) - np.array([r.te0 for r in res])
                        worst = dict(te_ptp_arcsec=c["te_ptp"], approach_arcsec=float(-te.mean() / RAD_PER_ARCSEC),
                                     edge_margin_mm=c["margin"], top_margin_mm=c["top_margin"],
                                     edge_share=c["edge_share"], pressure_mpa=c["pressure"], edges=c["edges"])
                    else:
                        worst.update(edge_margin_mm=min(worst["edge_margin_mm"], c["margin"]),
                                     top_margin_mm=min(worst["top_margin_mm"], c["top_margin"]),
                                     edge_share=max(worst["edge_share"], c["edge_share"]),
                                     edges=sorted(set(worst["edges"]) | set(c["edges"])))
                row.update(worst)
            except (ArithmeticError, ValueError, RuntimeError, np.linalg.LinAlgError) as exc:
                row["failure"] = f"{type(exc).__name__}: {exc}"[:200]
            rows.append(row)
            if say:
                say(json.dumps(row))
    return rows


def summarise(rows: list[dict], margin_mm: float) -> list[dict]:
    """Per torque: the smallest m21 keeping the toe / heel margin, the constrained and the unconstrained optimum
    (least loaded TE peak-to-peak) with their margins, and the active constraint."""
    out = []
    for t in sorted({r["torque_nm"] for r in rows}):
        rs = sorted((r for r in rows if r["torque_nm"] == t and "failure" not in r), key=lambda r: r["m21_arcsec"])
        ok = [r for r in rs if r["edge_margin_mm"] >= margin_mm]
        free = min(rs, key=lambda r: r["te_ptp_arcsec"])
        rec = {"torque_nm": t, "margin_required_mm": margin_mm,
               "unconstrained": {k: free[k] for k in ("m21_arcsec", "te_ptp_arcsec", "edge_margin_mm")}}
        if ok:
            first = ok[0]
            below = [r for r in rs if r["m21_arcsec"] < first["m21_arcsec"]]
            best = min(ok, key=lambda r: r["te_ptp_arcsec"])
            rec["smallest_feasible_m21_arcsec"] = first["m21_arcsec"]
            rec["largest_infeasible_below_arcsec"] = below[-1]["m21_arcsec"] if below else None
            rec["constrained"] = {k: best[k] for k in ("m21_arcsec", "te_ptp_arcsec", "edge_margin_mm",
                                                       "top_margin_mm", "edge_share", "pressure_mpa",
                                                       "approach_arcsec", "edges")}
            rec["active_constraint"] = ("none" if free["edge_margin_mm"] >= margin_mm else
                                        "edge_margin_mm" if best is first and below else
                                        "none at the optimum (edge_margin_mm excludes the unconstrained optimum)")
        out.append(rec)
    return out


def run(case_path: str, eta2_deg: float = 22.0, m21s=M21, torques=TORQUES, margin_mm: float = 1.0,
        box_mm=(0.05, 0.05, 0.05), say=None) -> dict:
    """Scan and summary of a bevel case (its working flank; the compliance once for the largest torque)."""
    from ..case import read_toml
    data = read_toml(case_path)
    b = _backend(data, str(case_path), torques, max(m21s), box_mm)
    b.prepare(max(torques))
    rows = scan(b, eta2_deg, m21s, torques, False, say)
    summary = summarise(rows, margin_mm)
    if any(x > 0 for x in box_mm):
        # the constrained optimum and the constraint's boundary of each torque over the tolerance box's corners
        for rec in summary:
            for key, m in (("constrained", rec.get("constrained", {}).get("m21_arcsec")),
                           ("smallest_feasible", rec.get("smallest_feasible_m21_arcsec"))):
                if m is not None:
                    r = scan(b, eta2_deg, [m], [rec["torque_nm"]], True, say)[0]
                    rec[f"{key}_over_box"] = {k: r.get(k) for k in ("m21_arcsec", "edge_margin_mm", "top_margin_mm",
                                                                    "edge_share", "failure") if k in r}
    return {"case": str(case_path), "eta2_deg": eta2_deg, "positions": b.positions, "fidelity": b.fidelity,
            "tolerance_box_mm": list(box_mm), "rows": rows, "summary": summary}


def _table(res: dict) -> str:
    lines = [f"eta2 = {res['eta2_deg']:g} deg, toe/heel margin >= {res['summary'][0]['margin_required_mm']:g} mm, "
             f"box {res['tolerance_box_mm']} mm",
             "torque N m | smallest m21 keeping the margin | constrained optimum m21, TE p-p, toe/heel margin, top "
             "margin, edge share, approach | unconstrained m21, TE p-p, margin | active"]
    for s in res["summary"]:
        c, u = s.get("constrained"), s["unconstrained"]
        lo = s.get("largest_infeasible_below_arcsec")
        first = f"{s['smallest_feasible_m21_arcsec']:g} (infeasible at {lo:g})" if c and lo is not None else \
            (f"{s['smallest_feasible_m21_arcsec']:g}" if c else "none")
        cs = (f"{c['m21_arcsec']:g}, {c['te_ptp_arcsec']:.2f}, {c['edge_margin_mm']:.2f}, {c['top_margin_mm']:.2f}, "
              f"{c['edge_share']:.3f}, {c['approach_arcsec']:.1f}") if c else "none"
        lines.append(f"{s['torque_nm']:g} | {first} | {cs} | {u['m21_arcsec']:g}, {u['te_ptp_arcsec']:.2f}, "
                     f"{u['edge_margin_mm']:.2f} | {s.get('active_constraint', '-')}")
    boxed = [s for s in res["summary"] if "constrained_over_box" in s]
    if boxed:
        lines.append("over the tolerance box: torque N m | optimum m21: toe/heel margin, top margin, edge share | "
                     "smallest m21 of the nominal mounting: the same")
        for s in boxed:
            a, b = s["constrained_over_box"], s.get("smallest_feasible_over_box", {})
            lines.append(f"{s['torque_nm']:g} | " + " | ".join(
                f"{r['m21_arcsec']:g}: {r['edge_margin_mm']:.2f}, {r['top_margin_mm']:.2f}, {r['edge_share']:.3f}"
                if "edge_margin_mm" in r else "-" for r in (a, b)))
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """``python3 -m ltca.design.bevel_torque CASE [--eta2 DEG] [--torques ...] [--m21 ...] [--margin MM]
    [--box E P G] [--out FILE.json]``: the scan, its table on stdout."""
    ap = argparse.ArgumentParser(prog="python3 -m ltca.design.bevel_torque", description=__doc__.split("\n\n")[0])
    ap.add_argument("case")
    ap.add_argument("--eta2", type=float, default=22.0, help="working path angle, deg (default 22, Cao et al. 2008)")
    ap.add_argument("--torques", type=float, nargs="+", default=list(TORQUES), help="design torques, N m")
    ap.add_argument("--m21", type=float, nargs="+", default=list(M21), help="TE magnitudes to scan, arcsec")
    ap.add_argument("--margin", type=float, default=1.0, help="required toe/heel margin, mm")
    ap.add_argument("--box", type=float, nargs=3, default=[0.05, 0.05, 0.05],
                    help="tolerance box E P G, mm (0 0 0: none)")
    ap.add_argument("--out", help="write the rows and the summary as JSON")
    a = ap.parse_args(argv)
    res = run(a.case, a.eta2, a.m21, a.torques, a.margin, tuple(a.box),
              say=lambda msg: print(msg, file=sys.stderr, flush=True))
    if a.out:
        from ..outputs import write_json_atomic
        write_json_atomic(a.out, res)
    print(_table(res))
    return 0


if __name__ == "__main__":
    sys.exit(main())
