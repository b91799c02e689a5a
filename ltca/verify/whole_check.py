"""``ltca validate --reference calculix-whole``: ours against CalculiX on whole gears with every tooth.

Per position: our loaded contact (:func:`ltca.verify.calculix.solve_ours`, compliance of our whole-gear
body) and CalculiX on the independent full-gear model (:func:`ltca.verify.whole_gear.solve_whole`).
Compared: loaded TE (arcsec of the gear), load share per pinion tooth, mesh stiffness N/(mm um), the
flank peak pressure away from the face ends and edge contact (CalculiX: elliptic fit), the root stress of
pinion and gear (largest principal stress on the loaded teeth's tension-side fillets;
:mod:`ltca.verify.whole_root`) and wall time. One CalculiX run per position at the contact band ``band_um``
(default 3/4 of the Hertz half-width); ``body`` "coarse" (``--coarse-body``) coarsens the elements away from the
contact band and the fillets (:data:`ltca.verify.whole_gear.BODIES`): a wide helical face.
Bounds: TE 3 %, share 0.03, stiffness 3 %. CalculiX runs are kept under ``out`` and reused.

CalculiX's own refinement ladder and the frozen references compared by the tests are maintainer tooling
(``tools/calculix_refs``, not installed), built on :func:`check_arguments`, :func:`compare_positions` and
:func:`table_lines`.
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from .calculix import solve_ours
from .whole_gear import BODIES, stiffness, solve_whole, whole_settings

__all__ = ["BOUNDS_WHOLE", "run_whole_validation", "ours_figures", "prepare_ours", "check_arguments",
           "compare_positions", "table_lines", "root_stress"]

BOUNDS_WHOLE = {"te_rel": 0.03, "share_abs": 0.03, "stiffness_rel": 0.03}


def ours_figures(lm, r, torque: float) -> dict:
    """Our figures at one position as the frozen reference stores them: TE (arcsec of the gear), mesh stiffness
    N/(mm um), pair shares, the flank peak away from edge contact (MPa; :func:`ltca.cylindrical.edges.position_edges`)
    and the root stress of each member (largest over its loaded teeth, MPa)."""
    from ..cylindrical.edges import position_edges
    from ..cylindrical.tca import ARCSEC_PER_RAD
    total = sum(r.pair_load.values()) or 1.0
    return {"te": float((r.theta - r.theta0) / lm.model.pair.ratio * ARCSEC_PER_RAD),
            "stiffness": stiffness(lm, r.theta, r.theta0, torque),
            "share": {str(k): float(v / total) for k, v in sorted(r.pair_load.items())},
            "flank_pressure": float(position_edges(lm, r, torque)["flank_peak"]),
            "root_pinion": float(max(r.root1.values())), "root_gear": float(max(r.root2.values()))}


def root_stress(c, member: str) -> float:
    """The largest root stress of ``member`` (``"pinion"`` or ``"gear"``) in a CalculiX run, MPa (NaN: not read)."""
    return float(c.root.get(member, {}).get("max", np.nan))


def _row(roll, mine, r, c, lm, torque, teeth):
    sm, sc = mine.share(teeth), c.share(teeth)
    o = ours_figures(lm, r, torque)
    k_ours = o["stiffness"]
    return {"roll_deg": roll, "te_ours": mine.te, "te_ccx": c.te, "te_diff_pct": 100 * (mine.te / c.te - 1),
            "share_ours": sm, "share_ccx": sc, "share_diff": max(abs(sm[k] - sc[k]) for k in teeth),
            "k_ours": k_ours, "k_ccx": c.stiffness, "k_diff_pct": 100 * (k_ours / c.stiffness - 1),
            "p_ours": o["flank_pressure"], "p_ccx": c.info.get("p_flank", np.nan),
            "sr1_ours": o["root_pinion"], "sr1_ccx": root_stress(c, "pinion"),
            "sr2_ours": o["root_gear"], "sr2_ccx": root_stress(c, "gear"), "t_ours": mine.wall, "t_ccx": c.wall,
            "ccx_nodes": c.info["nodes"], "band_um": 1e3 * c.info["h_contact_mm"], "ours": o}


def prepare_ours(case, fidelity: str, progress: bool):
    """Our loaded model of ``case`` at ``fidelity`` over its cycle (first torque), the progress printer (stderr, or
    silent) and the preparation's wall time, s."""
    from ..case import FIDELITIES
    from ..cylindrical.loaded_model import Fidelity, prepare
    from ..cylindrical.model import build_model
    from ..cylindrical.run import cycle_rolls
    say = (lambda m: print(m, file=sys.stderr, flush=True)) if progress else (lambda m: None)
    t0 = time.perf_counter()
    lm = prepare(build_model(case), Fidelity.from_preset(FIDELITIES[fidelity], case.module),
                 cycle_rolls(case.positions, case.pinion.teeth), case.torques[0], progress=say)
    return lm, say, time.perf_counter() - t0


def check_arguments(case, case_path: str, rolls: list[float], band_um: float | None, fidelity: str, threads: int,
                    body: str) -> None:
    """Raise ``CaseError`` naming the first bad argument of a whole-gear check of ``case``."""
    from ..case import FIDELITIES
    from ..errors import CaseError
    pitch_deg = 360.0 / case.pinion.teeth
    if any(not np.isfinite(r) or abs(r) > 0.5 * pitch_deg + 1e-9 for r in rolls):
        raise CaseError("--positions", rolls, f"roll angles in deg with |roll| <= {0.5 * pitch_deg:.4f}")
    if band_um is not None and not 20.0 <= band_um <= 2000.0:
        raise CaseError("--band", band_um, "a contact-band element size from 20 to 2000 um")
    if body not in BODIES:
        raise CaseError("--coarse-body", body, ", ".join(BODIES))
    if not 1 <= threads <= 64:
        raise CaseError("--threads", threads, "an integer from 1 to 64")
    if fidelity not in FIDELITIES:
        raise CaseError("--fidelity", fidelity, ", ".join(FIDELITIES))
    if case.gear.internal:
        raise CaseError("--case", case_path, "an external pair (the whole-gear CalculiX model has no ring gear)")


def ccx_folder(outdir: Path, roll: float, st) -> Path:
    """The folder of one CalculiX run under ``outdir``: by roll (deg) and contact band (um)."""
    return outdir / f"ccx_whole_r{roll:+.4f}_b{1e3 * st.h_contact:.0f}"


def compare_positions(lm, rolls: list[float], torque: float, st, outdir: Path, say) -> list[dict]:
    """Ours and CalculiX (settings ``st``) at each pinion roll (deg): one comparison row per position, with the
    bounds' verdict ``ok``."""
    rows = []
    for rd in rolls:
        mine, r = solve_ours(lm, np.radians(rd), torque)
        c = solve_whole(lm, rd, torque, st, ccx_folder(outdir, rd, st), say=say)
        teeth = sorted(set(mine.pair_load) | set(c.pair_load))
        row = _row(rd, mine, r, c, lm, torque, teeth)
        row["ok"] = bool(abs(row["te_diff_pct"]) <= 100 * BOUNDS_WHOLE["te_rel"]
                         and row["share_diff"] <= BOUNDS_WHOLE["share_abs"]
                         and abs(row["k_diff_pct"]) <= 100 * BOUNDS_WHOLE["stiffness_rel"])
        rows.append(row)
    return rows


def _shares(d: dict) -> str:
    return "/".join(f"{d[k]:.3f}" for k in sorted(d))


def table_lines(case, torque: float, fidelity: str, st, rows: list[dict], t_prepare: float) -> list[str]:
    """The comparison table of ``rows`` (:func:`compare_positions`), one line per position."""
    lines = [f"{case.name} at {torque * 1e-3:g} N m: ours ({fidelity}) against CalculiX on whole gears, every tooth "
             f"(contact band {1e3 * st.h_contact:.0f} um, tension-side fillets {1e3 * st.h_fillet:.0f} um)",
             f"{'roll':>6} {'TE ours':>8} {'TE ccx':>8} {'dTE%':>6} {'share ours':>17} {'share ccx':>17} {'dsh':>5} "
             f"{'c ours':>6} {'c ccx':>6} {'dc%':>6} {'p ours':>6} {'p ccx':>6} {'sF1 o':>6} {'sF1 c':>6} "
             f"{'sF2 o':>6} {'sF2 c':>6} {'t ours':>6} {'t ccx':>6}"]
    for r in rows:
        lines.append(f"{r['roll_deg']:6.2f} {r['te_ours']:8.3f} {r['te_ccx']:8.3f} {r['te_diff_pct']:+6.2f} "
                     f"{_shares(r['share_ours']):>17} {_shares(r['share_ccx']):>17} {r['share_diff']:5.3f} "
                     f"{r['k_ours']:6.2f} {r['k_ccx']:6.2f} {r['k_diff_pct']:+6.2f} {r['p_ours']:6.0f} "
                     f"{r['p_ccx']:6.0f} {r['sr1_ours']:6.1f} {r['sr1_ccx']:6.1f} {r['sr2_ours']:6.1f} "
                     f"{r['sr2_ccx']:6.1f} {r['t_ours']:6.2f} {r['t_ccx']:6.0f}{'' if r['ok'] else '  OUT'}")
    lines.append(f"ours: compliance {t_prepare:.1f} s once, then the contact solve per position (t ours); CalculiX: "
                 "mesh + solve per position (t ccx), s. p: flank peak away from the face ends / edge contact; sF1, "
                 "sF2: root stress of pinion and gear, MPa")
    return lines


_CSV_KEYS = ["roll_deg", "te_ours", "te_ccx", "te_diff_pct", "share_ours", "share_ccx", "share_diff", "k_ours",
             "k_ccx", "k_diff_pct", "p_ours", "p_ccx", "sr1_ours", "sr1_ccx", "sr2_ours", "sr2_ccx", "t_ours", "t_ccx",
             "ccx_nodes", "band_um", "ok"]


def write_rows(outdir: Path, rows: list[dict], extra: dict | None = None) -> None:
    """``whole_gear.csv`` and ``whole_gear.json`` (the rows, and ``extra`` entries) in ``outdir``."""
    fmt = lambda v: _shares(v) if isinstance(v, dict) else str(v)       # noqa: E731
    (outdir / "whole_gear.csv").write_text(",".join(_CSV_KEYS) + "\n" + "".join(
        ",".join(fmt(r[k]) for k in _CSV_KEYS) + "\n" for r in rows))
    (outdir / "whole_gear.json").write_text(json.dumps({"rows": rows, **(extra or {})}, indent=1, default=float))


def run_whole_validation(case_path: str, positions: list[float], out: str, band_um: float | None = None,
                         fidelity: str = "default", progress: bool = True, threads: int = 2,
                         body: str = "default") -> int:
    """Ours against whole-gear CalculiX at pinion rolls ``positions`` (deg; default 0 and -9); returns 0 within
    bounds, else 1.

    Prints the table and writes ``whole_gear.csv`` and ``whole_gear.json`` to ``out``. Raises ``CaseError``
    on bad arguments (before looking for ``ccx``) and ``CcxNotFound`` when ``ccx`` is missing."""
    from ltca.fem.calculix.run import ccx_path
    from ..case import load_case
    case = load_case(case_path)
    rolls = list(positions or [0.0, -9.0])
    check_arguments(case, case_path, rolls, band_um, fidelity, threads, body)
    ccx_path()
    torque = case.torques[0]
    lm, say, t_prepare = prepare_ours(case, fidelity, progress)
    base = whole_settings(lm.b_nom, case.module, band_um, threads=threads, body=body)
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)
    rows = compare_positions(lm, rolls, torque, base, outdir, say)
    print("\n".join(table_lines(case, torque, fidelity, base, rows, t_prepare)))
    write_rows(outdir, rows)
    return 0 if all(r["ok"] for r in rows) else 1
