"""``ltca validate --reference calculix --case <bevel case>``: our bevel LTCA against CalculiX.

At each pinion angle (fractions of a mesh cycle 2 pi / z1 from the mean point) at the case's middle torque:
our loaded contact (:func:`ltca.bevel.loaded.solve_position`, default fidelity) and CalculiX on the independent
whole-member model (:func:`ltca.verify.bevel_ccx.solve_bevel_ccx`).  Compared: the loaded approach theta (loaded
minus unloaded TE, arcsec of the gear), the torque share of each tooth pair, the interior peak flank pressure
(away from the edges; ours: the largest cell pressure of the cells at no edge) and the wall time.  The first
position is solved on a ladder of contact-zone sizes h0, h0/1.5, h0/1.5^2 (CalculiX's convergence, Richardson
estimate), the others at ``level``.  Bounds: TE 3 %, share 0.03, peak pressure 5 % of CalculiX.

With ``freeze`` the CalculiX values are written as a frozen reference with their provenance (command, mesh
sizes, CalculiX version, date), read by ``tests/test_reference_calculix_bevel.py``.
"""
from __future__ import annotations

import datetime
import json
import sys
import time
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from geometry.bevel.tca import RAD_PER_ARCSEC, Assembly

from ..bevel.analysis import build_pair
from ..bevel.case import load_bevel_case
from ..bevel.loaded import solve_position
from ..bevel.loaded_model import BevelFidelity, loaded_model, prepare_bodies
from .bevel_ccx import BevelCcxSettings, bevel_ladder, interior, solve_bevel_ccx
from .calculix import richardson

__all__ = ["BOUNDS_BEVEL", "run_bevel_validation", "recompare", "ours_at", "bevel_model", "mounted"]

BOUNDS_BEVEL = {"te_rel": 0.03, "share_abs": 0.03, "pressure_rel": 0.05}


def bevel_model(case_path: str, fidelity: str = "default", cache=None, say=None):
    """Case, our loaded model of its working flank and the compliance wall time (s)."""
    case = load_bevel_case(case_path)
    t0 = time.perf_counter()
    pair = build_pair(case)
    bodies = prepare_bodies(pair, "concave", BevelFidelity.named(fidelity), case.young, case.poisson, cache, say,
                            mounting=case.mounting)
    return case, loaded_model(pair, bodies, Assembly(**case.assembly)), time.perf_counter() - t0


def mounted(st: BevelCcxSettings, case: dict, lm) -> BevelCcxSettings:
    """CalculiX settings ``st`` with the case's mounting (pinion shaft seat, gear back face), which both models
    read."""
    sup = case.mounting.supports(lm.pair.blank)
    return replace(st, r_bore1=sup["pinion"][1], back_face_z=sup["gear"][1])


def middle_torque(case: dict) -> float:
    """The middle of the case's positive torques, N m."""
    tq = sorted(t for t in case.torques if t > 0)
    return float(tq[len(tq) // 2])


def ours_at(lm, phi1: float, torque_nm: float, edge_mm: float = BevelCcxSettings.edge_mm) -> dict:
    """Our theta (arcsec of the gear), pair shares, interior and overall peak pressure (MPa), wall time (s).

    Interior: cells at no edge and farther than ``edge_mm`` from both members' tops, toes and heels (the
    CalculiX side's criterion, :func:`ltca.verify.bevel_ccx.interior`)."""
    t0 = time.perf_counter()
    r = solve_position(lm, phi1, torque_nm * 1e3)
    inner = r.pressure[(r.edge == "") & interior(lm, r.L1, r.Rn1, r.L2, r.Rn2, edge_mm)]
    return {"theta": r.theta / RAD_PER_ARCSEC, "share": {int(k): float(v) for k, v in r.pair_share.items()},
            "p_interior": float(inner.max()) if inner.size else 0.0, "p_max": r.max_pressure,
            "edge_load": r.edge_load(), "wall": time.perf_counter() - t0}


def _compare(o: dict, c) -> dict:
    pairs = sorted(set(o["share"]) | set(c.share))
    dsh = max(abs(o["share"].get(j, 0.0) - c.share.get(j, 0.0)) for j in pairs)
    return {"te_err_pct": 100 * (o["theta"] / c.theta_arcsec - 1), "share_err": dsh,
            "p_err_pct": 100 * (o["p_interior"] / c.p_interior - 1) if c.p_interior > 0 else float("nan")}


def _ok(e: dict) -> bool:
    return (abs(e["te_err_pct"]) <= 100 * BOUNDS_BEVEL["te_rel"] and e["share_err"] <= BOUNDS_BEVEL["share_abs"]
            and abs(e["p_err_pct"]) <= 100 * BOUNDS_BEVEL["pressure_rel"])


def run_bevel_validation(case_path: str, fractions=(0.0, 0.4), out: str = "out/validate_bevel_ccx", refine: int = 2,
                         level: int = 1, h0: float = 0.25, freeze: str | None = None, command: str = "",
                         progress: bool = True, torque: float | None = None, threads: int = 2) -> int:
    """Ours against CalculiX at pinion angles ``fractions`` x 2 pi / z1 under the pinion ``torque`` (N m; default
    the case's middle torque), CalculiX on ``threads``; exit status 0 when inside the bounds."""
    from fem.calculix.run import ccx_path
    from .whole_check import ccx_version
    ccx_path()
    say = (lambda m: print(m, file=sys.stderr, flush=True)) if progress else (lambda m: None)
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)
    case, lm, t_comp = bevel_model(case_path, cache=str(outdir / "cache"), say=say)
    torque = middle_torque(case) if torque is None else float(torque)
    cycle = 2 * np.pi / lm.pair.blank.pinion.z
    ladder_st = [replace(mounted(st, case, lm), threads=threads) for st in bevel_ladder(max(refine, level) + 1, h0)]

    def ccx(f, st):
        return solve_bevel_ccx(lm, f * cycle, torque * 1e3, st, outdir / f"ccx_{f:+.3f}_h{1e3 * st.h_zone:.0f}",
                               cache=str(outdir / "cad"), say=say)
    # the rungs up to ``level`` first, then the other positions, then the finer rungs (an interrupted run keeps
    # the comparison at every position; every run is reused on a rerun)
    ladder = [ccx(fractions[0], st) for st in ladder_st[:level + 1]]
    others = {f: ccx(f, ladder_st[level]) for f in fractions[1:]}
    ladder += [ccx(fractions[0], st) for st in ladder_st[level + 1:refine + 1]]
    rows = []
    for i, f in enumerate(fractions):
        o = ours_at(lm, f * cycle, torque)
        c = ladder[-1] if i == 0 else others[f]
        e = _compare(o, c)
        rows.append({"fraction": f, "phi1": f * cycle, "ours": o, "ccx": {
            "theta": c.theta_arcsec, "share": c.share, "p_interior": c.p_interior, "p_nodal_max": c.p_nodal_max,
            "h_zone_um": 1e3 * c.info["h_zone_mm"], "nodes": c.info["nodes"], "elements": c.info["elements"],
            "wall": c.wall, "ccx_wall": c.info["ccx_wall"], "deck_sha256": c.info["deck_sha256"],
            "snap_um": c.info["snap_um"], "torque_balance": c.info["torque_balance"]}, **e, "ok": _ok(e)})
    rich = {k: richardson([getattr(c, a) for c in ladder], 1.5) for k, a in
            (("theta", "theta_arcsec"), ("p_interior", "p_interior"))} if len(ladder) >= 3 else {}
    sh = lambda d: "/".join(f"{d[k]:.3f}" for k in sorted(d))        # noqa: E731
    lines = [f"{case.name}: working flank at {torque:g} N m (pinion), ours (default fidelity) against CalculiX "
             "(whole members, gmsh OCC solids, C3D10, penalty contact; pinion bore on a rigid body, gear back face "
             "fixed)",
             f"{'phi1/cycle':>10} {'TE ours':>8} {'TE ccx':>8} {'dTE%':>6} {'share ours':>13} {'share ccx':>13} "
             f"{'dsh':>5} {'p ours':>6} {'p ccx':>6} {'dp%':>6} {'t ours':>6} {'t ccx':>6}"]
    for r in rows:
        lines.append(f"{r['fraction']:10.3f} {r['ours']['theta']:8.2f} {r['ccx']['theta']:8.2f} "
                     f"{r['te_err_pct']:+6.2f} "
                     f"{sh(r['ours']['share']):>13} {sh(r['ccx']['share']):>13} {r['share_err']:5.3f} "
                     f"{r['ours']['p_interior']:6.0f} {r['ccx']['p_interior']:6.0f} {r['p_err_pct']:+6.2f} "
                     f"{r['ours']['wall']:6.2f} {r['ccx']['wall']:6.0f}{'' if r['ok'] else '  OUT'}")
    lines.append("TE: loaded minus unloaded, arcsec of the gear; p: interior peak flank pressure, MPa; ours: "
                 f"compliance {t_comp:.1f} s once + t ours per position; CalculiX: mesh + solve per position (s)")
    lines.append("wall-time ratio CalculiX / ours per position: "
                 + ", ".join(f"{r['ccx']['wall'] / (r['ours']['wall'] + t_comp / len(rows)):.0f}" for r in rows)
                 + " (ours with its compliance shared over the positions)")
    lines.append(f"CalculiX contact-zone refinement at phi1/cycle = {fractions[0]:g} (h -> TE, shares, p interior, "
                 "nodal max, nodes, s):")
    for c in ladder:
        lines.append(f"  {1e3 * c.info['h_zone_mm']:5.0f} um  TE {c.theta_arcsec:8.3f}  share {sh(c.share)}  "
                     f"p {c.p_interior:6.0f}  nodal {c.p_nodal_max:6.0f}  {c.info['nodes']} nodes  {c.wall:.0f} s")
    for k, v in rich.items():
        if v is not None:
            lines.append(f"  Richardson estimate of {k}: {v[0]:.3f} (order {v[1]:.2f})")
    print("\n".join(lines))
    rec = {"case": case_path, "torque_nm": torque, "calculix_version": ccx_version(),
           "date": datetime.date.today().isoformat(), "command": command, "bounds": BOUNDS_BEVEL,
           "model": "whole members (every tooth), gmsh OCC lofted teeth fused with a revolved blank, C3D10, contact "
                    "flank nodes on the exact surface; pinion bore rigid body turning about its axis under the "
                    "torque, gear back face fixed; frictionless surface-to-surface penalty contact (10 E / h)",
           "units": {"theta": "arcsec of the gear (loaded minus unloaded TE)", "p_interior": "MPa", "wall": "s"},
           "compliance_wall_s": t_comp, "rows": rows,
           "refinement": [{"h_zone_um": 1e3 * c.info["h_zone_mm"], "theta": c.theta_arcsec, "share": c.share,
                           "p_interior": c.p_interior, "p_nodal_max": c.p_nodal_max, "nodes": c.info["nodes"],
                           "wall": c.wall} for c in ladder],
           "richardson": {k: (list(v) if v is not None else None) for k, v in rich.items()}}
    text = json.dumps(rec, indent=1, default=float) + "\n"
    (outdir / "bevel_calculix.json").write_text(text)
    if freeze:
        Path(freeze).parent.mkdir(parents=True, exist_ok=True)
        Path(freeze).write_text(text)
    return 0 if all(r["ok"] for r in rows) else 1


def recompare(frozen: str, note: str) -> list[dict]:
    """Our figures at a frozen reference's rows again, after a change of our model, CalculiX's kept as frozen.

    CalculiX is not rerun (gmsh's meshes of the same solids differ by some nodes between runs, so a rerun is a new
    ladder of 15-35 min per rung); each row's ``ours`` and its deviations are replaced, and ``recompared`` records
    when and why (``note``). Returns the new rows."""
    path = Path(frozen)
    rec = json.loads(path.read_text())
    case, lm, t_comp = bevel_model(rec["case"])
    rows = []
    for r in rec["rows"]:
        o = ours_at(lm, r["phi1"], rec["torque_nm"])
        c = r["ccx"]
        ccx = SimpleNamespace(theta_arcsec=c["theta"], p_interior=c["p_interior"],
                              share={int(k): v for k, v in c["share"].items()})
        e = _compare(o, ccx)
        rows.append({**r, "ours": o, **e, "ok": _ok(e)})
    rec["rows"] = rows
    rec["compliance_wall_s"] = t_comp
    rec.setdefault("recompared", []).append({"date": datetime.date.today().isoformat(), "note": note})
    path.write_text(json.dumps(rec, indent=1, default=float) + "\n")
    return rows


if __name__ == "__main__":                                      # python3 -m ltca.verify.bevel_calculix FILE NOTE
    for row in recompare(sys.argv[1], " ".join(sys.argv[2:])):
        print(f"{row['fraction']:.3f}: TE {row['te_err_pct']:+.2f} %, share {row['share_err']:.3f}, "
              f"p {row['p_err_pct']:+.2f} %, ok {row['ok']}")
