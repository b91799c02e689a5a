"""``ltca validate --reference calculix-whole`` on a planetary case: the satellite in its central wheel.

Ours: the planetary LTCA (:mod:`ltca.planetary.loaded`: both whole bodies' compliance, every pair that can
close). CalculiX: the independent whole-gear model (:func:`ltca.verify.whole_gear.solve_whole`): both gears
meshed with every tooth by :func:`ltca.fem.solids.full_gear.build_full_gear` (the wheel as the internal ring out to
its housing diameter), the wheel's outer cylinder fixed, the satellite's bore (its eccentric bearing's seat) on
a rigid body turning about the satellite axis under the torque, frictionless penalty contact on every
satellite tooth whose unloaded gap after the rigid rotation to first contact is below an ISO-like bound
(``1.2 T / (r_b1 b c') + 2 um``, c' = 14 N/(mm um): far more than the loaded TE, so every pair that could
close can). Same quantities on both sides:

* position phi (deg): the satellite rotation of :mod:`ltca.geometry.satellite.mesh` (0: satellite tooth 0 centred
  in a wheel space on the line of centres), the roll of the pair model;
* loaded TE: satellite rotation (wheel fixed) beyond the rigid rotation to first contact, um along the line of
  action (times r_b1) and arcsec of the satellite;
* share: normal load of satellite tooth k over the sum (pair index k as in ``ltca run``; CalculiX: the norm of
  the summed forces of the tooth's two contact pairs, wheel tip corner and flank,
  :func:`ltca.verify.whole_gear.tooth_loads`); a pair carries load when its share is at least
  :data:`ltca.planetary.run.SHARE_MIN`;
* peak flank pressure, MPa (CalculiX: elliptic fit across the band on the satellite, and the largest nodal
  value; information only: most pairs of this mesh touch at a tip edge, where the pressure is singular and
  both figures depend on the mesh).

Bounds: TE 3 %, every share 0.03. One CalculiX run per position at the contact band ``band_um``. CalculiX's
refinement ladder and the frozen reference the tests compare with are maintainer tooling
(``tools/calculix_refs/freeze_planetary.py``, not installed), built on :func:`compare_positions`.
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

from ..cylindrical.tca import ARCSEC_PER_RAD
from .calculix import penalty_slope
from .whole_gear import WholeSettings, solve_whole

__all__ = ["BOUNDS_PLANETARY", "planetary_settings", "prepare_ours", "solve_ours", "check_arguments",
           "ccx_record", "compare_row", "compare_positions", "table_lines", "run_planetary_whole_validation"]

BOUNDS_PLANETARY = {"te_rel": 0.03, "share_abs": 0.03}


def planetary_settings(b_nom: float, module: float, band_um: float) -> WholeSettings:
    """CalculiX fidelity for the 50/51-tooth pair: contact band ``band_um`` (um) across the unloaded lines,
    0.5 m on the teeth with a contact line, 4/3 m on every other tooth, 8/3 m far from the teeth, one thread.

    ``b_nom`` (mm) is the Hertz half-width of the whole torque on one pair; the band reaches ``0.8 b_nom`` beyond
    the line (more than the widest contact of a shared load) and the contact surfaces ``1.5 b_nom``."""
    h = 1e-3 * band_um
    return WholeSettings(h_contact=h, half_band=0.8 * b_nom + h, h_flank=0.5 * module, h_tooth=4.0 * module / 3,
                         h_body=8.0 * module / 3, penalty=penalty_slope(h), halo=1.5 * b_nom, threads=1,
                         fine_lines_only=True)


def check_arguments(case, positions, torque_nm, band_um, fidelity) -> None:
    """Raise ``CaseError`` naming the first bad argument of a check of the planetary ``case``."""
    from ..case import FIDELITIES
    from ..errors import CaseError
    half = 180.0 / case.design.z
    if not positions or any(not np.isfinite(p) or abs(p) > half + 1e-9 for p in positions):
        raise CaseError("--positions", positions, f"satellite positions in deg with |phi| <= {half:.4f}")
    if torque_nm is None or not np.isfinite(torque_nm) or not 0 < torque_nm <= 1e5:
        raise CaseError("--torque", torque_nm, "one satellite torque in (0, 1e5] N m")
    if not 100.0 <= band_um <= 3000.0:
        raise CaseError("--band", band_um, "a contact-band element size from 100 to 3000 um")
    if fidelity not in FIDELITIES:
        raise CaseError("--fidelity", fidelity, ", ".join(FIDELITIES))


def _record(share: dict, theta: float, theta0: float, rb1: float, p: float, wall: float) -> dict:
    from ..planetary.run import SHARE_MIN
    return {"te_um": 1e3 * rb1 * (theta - theta0), "te_arcsec": ARCSEC_PER_RAD * (theta - theta0),
            "share": {str(k): float(v) for k, v in sorted(share.items())},
            "loaded_pairs": sum(v >= SHARE_MIN for v in share.values()), "max_pressure": float(p), "wall_s": wall}


def compare_row(phi: float, ours: dict, c: dict) -> dict:
    """One position compared: TE difference (%), largest share difference, within the bounds."""
    keys = set(ours["share"]) | set(c["share"])
    dsh = max(abs(ours["share"].get(k, 0.0) - c["share"].get(k, 0.0)) for k in keys)
    dte = ours["te_um"] / c["te_um"] - 1
    return {"phi_deg": phi, "ours": ours, "ccx": c, "te_diff_pct": 100 * dte, "share_diff": dsh,
            "ok": abs(dte) <= BOUNDS_PLANETARY["te_rel"] and dsh <= BOUNDS_PLANETARY["share_abs"]}


def ccx_record(c, rb1: float) -> dict:
    """One CalculiX run as the comparison (and a frozen reference) stores it."""
    rec = _record(c.share(sorted(c.pair_load)), c.info["theta"], c.info["theta0"], rb1, c.max_pressure, c.wall)
    rec.update(pair_load={str(k): v for k, v in sorted(c.pair_load.items())}, deck_sha256=c.info["deck_sha256"],
               nodes=c.info["nodes"], elements=c.info["elements"], h_contact_um=1e3 * c.info["h_contact_mm"],
               ccx_wall_s=c.info["ccx_wall"], mesh_wall_s=c.info["mesh_wall"], max_pressure_nodal=c.info["p_max_nodal"],
               settings={k: v for k, v in c.info["settings"].items()})
    return rec


def prepare_ours(case, positions_deg, torque: float, fidelity: str, cache=None, say=None, keep_solver: bool = True):
    """Our planetary model for the check: (SatelliteModel, LoadedModel) with the teeth in mesh over the case's
    cycle positions and ``positions_deg``, compliance for ``torque`` (N mm); ``keep_solver`` as
    :func:`ltca.planetary.loaded.prepare_satellite`'s."""
    from ..case import FIDELITIES
    from ..cylindrical.loaded_model import Fidelity
    from ..planetary.loaded import positions as cycle_positions, prepare_satellite
    from ..planetary.model import build_satellite_model
    sm = build_satellite_model(case)
    phis = np.unique(np.concatenate([cycle_positions(sm, case.positions), np.radians(positions_deg)]))
    lm = prepare_satellite(sm, Fidelity.from_preset(FIDELITIES[fidelity], case.design.m, slices=4), phis, torque,
                           case.far_teeth, cache, say, keep_solver)
    return sm, lm


def solve_ours(sm, lm, phi_deg: float, torque: float) -> dict:
    """Our loaded contact at satellite position ``phi_deg`` under ``torque`` (N mm): TE, shares, loaded pairs,
    peak pressure, wall time of the contact solve (:func:`ltca.planetary.loaded.solve_cycle`)."""
    from ..planetary.loaded import solve_cycle
    t1 = time.perf_counter()
    r = solve_cycle(lm, sm, np.radians([phi_deg]), torque)[0]
    tot = sum(r.pair_load.values())
    return _record({k: v / tot for k, v in r.pair_load.items()}, r.theta, r.theta0, sm.pair.pinion.r_base,
                   r.max_pressure, time.perf_counter() - t1)


def ccx_folder(outdir: Path, phi: float, torque_nm: float, st) -> Path:
    """The folder of one CalculiX run under ``outdir``: by position (deg), torque (N m) and contact band (um)."""
    return outdir / f"ccx_planetary_p{phi:+.4f}_t{torque_nm:g}_b{1e3 * st.h_contact:.0f}"


def compare_positions(sm, lm, positions: list[float], torque_nm: float, st: WholeSettings, outdir: Path,
                      say) -> list[dict]:
    """Ours and CalculiX (settings ``st``) at each satellite position (deg): one comparison row per position."""
    rb1 = sm.pair.pinion.r_base
    rows = []
    for phi in positions:
        ours = solve_ours(sm, lm, phi, 1e3 * torque_nm)
        c = solve_whole(lm, phi, 1e3 * torque_nm, st, ccx_folder(outdir, phi, torque_nm, st), say=say)
        rows.append(compare_row(phi, ours, ccx_record(c, rb1)))
    return rows


def run_planetary_whole_validation(case_path: str, positions: list[float], torque_nm: float | None, out: str,
                                   band_um: float | None = None, fidelity: str | None = None, progress: bool = True,
                                   cache: str | None = None) -> int:
    """Ours against whole-gear CalculiX at satellite positions ``positions`` (deg) under ``torque_nm`` (N m on the
    satellite); returns 0 within the bounds, else 1. Writes ``planetary_whole.json`` to ``out``.

    Raises ``CaseError`` on bad arguments (before looking for ``ccx``) and ``CcxNotFound`` when it is missing."""
    from ltca.fem.calculix.run import ccx_path
    from ..planetary.case import load_planetary_case
    case = load_planetary_case(case_path)
    band_um = 600.0 if band_um is None else band_um
    fidelity = fidelity or case.fidelity
    check_arguments(case, positions, torque_nm, band_um, fidelity)
    ccx_path()
    say = (lambda m: print(m, file=sys.stderr, flush=True)) if progress else (lambda m: None)
    t0 = time.perf_counter()
    sm, lm = prepare_ours(case, positions, 1e3 * torque_nm, fidelity, cache, say)
    t_prepare = time.perf_counter() - t0
    base = planetary_settings(lm.b_nom, case.design.m, band_um)
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)
    rows = compare_positions(sm, lm, positions, torque_nm, base, outdir, say)
    print("\n".join(table_lines(case.name, torque_nm, fidelity, rows, t_prepare)))
    result = {"case": case_path, "torque_nm": torque_nm, "fidelity": fidelity, "prepare_s": t_prepare,
              "bounds": BOUNDS_PLANETARY, "rows": rows}
    (outdir / "planetary_whole.json").write_text(json.dumps(result, indent=1))
    return 0 if all(r["ok"] for r in rows) else 1


def shares(d: dict) -> str:
    """Pair shares of at least 5e-4 as ``pair:share`` words."""
    return " ".join(f"{k}:{v:.3f}" for k, v in d.items() if v >= 5e-4)


def table_lines(name, torque_nm, fidelity, rows, t_prepare) -> list[str]:
    """The comparison table of ``rows`` (:func:`compare_positions`), three lines per position."""
    lines = [f"{name} at {torque_nm:g} N m on the satellite: ours ({fidelity}) against CalculiX on whole gears",
             f"{'phi':>6} {'TE ours':>8} {'TE ccx':>8} {'dTE%':>6} {'pairs':>5} {'p ours':>6} {'p ccx':>6} {'dsh':>5}"
             f" {'t ours':>6} {'t ccx':>6}   (TE um along the line of action, p MPa, t s)"]
    for r in rows:
        o, c = r["ours"], r["ccx"]
        lines.append(f"{r['phi_deg']:6.2f} {o['te_um']:8.3f} {c['te_um']:8.3f} {r['te_diff_pct']:+6.2f} "
                     f"{o['loaded_pairs']:>2}/{c['loaded_pairs']:<2} {o['max_pressure']:6.0f} {c['max_pressure']:6.0f} "
                     f"{r['share_diff']:5.3f} {o['wall_s']:6.2f} {c['wall_s']:6.0f}{'' if r['ok'] else '  OUT'}")
        lines.append(f"       share ours {shares(o['share'])}")
        lines.append(f"       share ccx  {shares(c['share'])}")
    lines.append(f"ours: compliance {t_prepare:.1f} s once, then the contact solve (t ours); CalculiX: mesh + solve")
    return lines
