"""``ltca validate --reference calculix --case <bevel case>``: our bevel LTCA against CalculiX.

At each pinion angle (fractions of a mesh cycle 2 pi / z1 from the mean point) at the case's middle torque:
our loaded contact (:func:`ltca.bevel.loaded.solve_position`, default fidelity) and CalculiX on the independent
whole-member model (:func:`ltca.verify.bevel_ccx.solve_bevel_ccx`).  Compared: the loaded approach theta (loaded
minus unloaded TE, arcsec of the gear), the torque share of each tooth pair, the interior peak flank pressure
(away from the edges; ours: the largest cell pressure of the cells at no edge) and the wall time.  One CalculiX
run per position at the contact-zone size h0 / 1.5^``level``.  Bounds: TE 3 %, share 0.03, peak pressure 5 % of
CalculiX.

CalculiX's ladder of contact-zone sizes and the frozen reference read by
``tests/ltca/verify/test_reference_calculix_bevel.py`` are maintainer tooling
(``tools/calculix_refs/freeze_bevel.py`` and
``recompare_bevel.py``, not installed), built on :func:`compare_positions` and :func:`table_lines`.
"""
from __future__ import annotations

import json
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from ltca.geometry.bevel.tca import RAD_PER_ARCSEC, Assembly

from ..bevel.analysis import build_pair
from ..bevel.case import load_bevel_case
from ..bevel.loaded import solve_position
from ..bevel.loaded_model import BevelFidelity, loaded_model, prepare_bodies
from .bevel_ccx import BevelCcxSettings, bevel_ladder, interior, solve_bevel_ccx

__all__ = ["BOUNDS_BEVEL", "run_bevel_validation", "ours_at", "bevel_model", "mounted", "middle_torque", "compare",
           "within_bounds", "ccx_entry", "compare_positions", "table_lines"]

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


def compare(o: dict, c) -> dict:
    """Deviations of ours ``o`` (:func:`ours_at`) from CalculiX ``c``: TE %, largest share difference, interior
    peak %."""
    pairs = sorted(set(o["share"]) | set(c.share))
    dsh = max(abs(o["share"].get(j, 0.0) - c.share.get(j, 0.0)) for j in pairs)
    return {"te_err_pct": 100 * (o["theta"] / c.theta_arcsec - 1), "share_err": dsh,
            "p_err_pct": 100 * (o["p_interior"] / c.p_interior - 1) if c.p_interior > 0 else float("nan")}


def within_bounds(e: dict) -> bool:
    """Whether the deviations ``e`` (:func:`compare`) lie within :data:`BOUNDS_BEVEL`."""
    return (abs(e["te_err_pct"]) <= 100 * BOUNDS_BEVEL["te_rel"] and e["share_err"] <= BOUNDS_BEVEL["share_abs"]
            and abs(e["p_err_pct"]) <= 100 * BOUNDS_BEVEL["pressure_rel"])


def ccx_entry(c) -> dict:
    """One CalculiX run as a comparison row (and a frozen reference) stores it."""
    return {"theta": c.theta_arcsec, "share": c.share, "p_interior": c.p_interior, "p_nodal_max": c.p_nodal_max,
            "h_zone_um": 1e3 * c.info["h_zone_mm"], "nodes": c.info["nodes"], "elements": c.info["elements"],
            "wall": c.wall, "ccx_wall": c.info["ccx_wall"], "deck_sha256": c.info["deck_sha256"],
            "snap_um": c.info["snap_um"], "torque_balance": c.info["torque_balance"]}


def compare_positions(lm, fractions, torque: float, runs: dict) -> list[dict]:
    """One row per pinion angle (fraction of a mesh cycle): ours at ``torque`` (N m) against the CalculiX run
    ``runs[fraction]``."""
    cycle = 2 * np.pi / lm.pair.blank.pinion.z
    rows = []
    for f in fractions:
        o = ours_at(lm, f * cycle, torque)
        c = runs[f]
        e = compare(o, c)
        rows.append({"fraction": f, "phi1": f * cycle, "ours": o, "ccx": ccx_entry(c), **e, "ok": within_bounds(e)})
    return rows


def shares(d: dict) -> str:
    """Pair shares as ``a/b/c``, by pair."""
    return "/".join(f"{d[k]:.3f}" for k in sorted(d))


def table_lines(case, torque: float, rows: list[dict], t_comp: float) -> list[str]:
    """The comparison table of ``rows`` (:func:`compare_positions`), one line per position."""
    lines = [f"{case.name}: working flank at {torque:g} N m (pinion), ours (default fidelity) against CalculiX "
             "(whole members, gmsh OCC solids, C3D10, penalty contact; pinion bore on a rigid body, gear back face "
             "fixed)",
             f"{'phi1/cycle':>10} {'TE ours':>8} {'TE ccx':>8} {'dTE%':>6} {'share ours':>13} {'share ccx':>13} "
             f"{'dsh':>5} {'p ours':>6} {'p ccx':>6} {'dp%':>6} {'t ours':>6} {'t ccx':>6}"]
    for r in rows:
        lines.append(f"{r['fraction']:10.3f} {r['ours']['theta']:8.2f} {r['ccx']['theta']:8.2f} "
                     f"{r['te_err_pct']:+6.2f} "
                     f"{shares(r['ours']['share']):>13} {shares(r['ccx']['share']):>13} {r['share_err']:5.3f} "
                     f"{r['ours']['p_interior']:6.0f} {r['ccx']['p_interior']:6.0f} {r['p_err_pct']:+6.2f} "
                     f"{r['ours']['wall']:6.2f} {r['ccx']['wall']:6.0f}{'' if r['ok'] else '  OUT'}")
    lines.append("TE: loaded minus unloaded, arcsec of the gear; p: interior peak flank pressure, MPa; ours: "
                 f"compliance {t_comp:.1f} s once + t ours per position; CalculiX: mesh + solve per position (s)")
    lines.append("wall-time ratio CalculiX / ours per position: "
                 + ", ".join(f"{r['ccx']['wall'] / (r['ours']['wall'] + t_comp / len(rows)):.0f}" for r in rows)
                 + " (ours with its compliance shared over the positions)")
    return lines


def check_arguments(fractions, level: int, h0: float, threads: int) -> None:
    """Raise ``CaseError`` naming the first bad argument of a bevel CalculiX check."""
    from ..errors import CaseError
    if not fractions or any(not np.isfinite(f) or abs(f) > 1.0 for f in fractions):
        raise CaseError("--positions", list(fractions), "pinion angles in mesh cycles with |angle| <= 1")
    if not 0 <= level <= 4:
        raise CaseError("--level", level, "an integer from 0 to 4")
    if not 0.02 <= h0 <= 2.0:
        raise CaseError("--band", 1e3 * h0, "a contact-zone element size from 20 to 2000 um")
    if not 1 <= threads <= 64:
        raise CaseError("--threads", threads, "an integer from 1 to 64")


def run_bevel_validation(case_path: str, fractions=(0.0, 0.4), out: str = "out/validate_bevel_ccx", level: int = 1,
                         h0: float = 0.25, progress: bool = True, torque: float | None = None,
                         threads: int = 2) -> int:
    """Ours against CalculiX at pinion angles ``fractions`` x 2 pi / z1 under the pinion ``torque`` (N m; default
    the case's middle torque), CalculiX on ``threads`` at the contact-zone size ``h0`` / 1.5^``level`` (mm); writes
    ``bevel_calculix.json`` to ``out``; exit status 0 when inside the bounds."""
    from ltca.fem.calculix.run import ccx_path
    check_arguments(fractions, level, h0, threads)
    ccx_path()
    say = (lambda m: print(m, file=sys.stderr, flush=True)) if progress else (lambda m: None)
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)
    case, lm, t_comp = bevel_model(case_path, cache=str(outdir / "cache"), say=say)
    torque = middle_torque(case) if torque is None else float(torque)
    cycle = 2 * np.pi / lm.pair.blank.pinion.z
    st = replace(mounted(bevel_ladder(level + 1, h0)[level], case, lm), threads=threads)
    runs = {f: solve_bevel_ccx(lm, f * cycle, torque * 1e3, st, ccx_folder(outdir, f, st), cache=str(outdir / "cad"),
                               say=say) for f in fractions}
    rows = compare_positions(lm, fractions, torque, runs)
    print("\n".join(table_lines(case, torque, rows, t_comp)))
    rec = {"case": case_path, "torque_nm": torque, "bounds": BOUNDS_BEVEL, "compliance_wall_s": t_comp, "rows": rows}
    (outdir / "bevel_calculix.json").write_text(json.dumps(rec, indent=1, default=float) + "\n")
    return 0 if all(r["ok"] for r in rows) else 1


def ccx_folder(outdir: Path, fraction: float, st: BevelCcxSettings) -> Path:
    """The folder of one CalculiX run under ``outdir``: by pinion angle (mesh cycles) and contact-zone size (um)."""
    return outdir / f"ccx_{fraction:+.3f}_h{1e3 * st.h_zone:.0f}"
