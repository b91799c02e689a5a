"""``ltca validate --reference calculix-whole``: ours against CalculiX on whole gears with every tooth.

Per position: our loaded contact (:func:`ltca.verify.calculix.solve_ours`, compliance of our whole-gear
body) and CalculiX on the independent full-gear model (:func:`ltca.verify.whole_gear.solve_whole`).
Compared: loaded TE (arcsec of the gear), load share per pinion tooth, mesh stiffness N/(mm um), the
flank peak pressure away from the face ends and edge contact (CalculiX: elliptic fit), the root stress of
pinion and gear (largest principal stress on the loaded teeth's tension-side fillets;
:mod:`ltca.verify.whole_root`) and wall time. The first position is also solved with the contact band and
the fillets refined ``refine`` times by 1.5 (``ladder`` "finer"), coarsened ("coarser") or both ("both"):
CalculiX's own convergence check. ``body`` "coarse" (``--coarse-body``) coarsens the elements away from the
contact band and the fillets (:data:`ltca.verify.whole_gear.BODIES`): a wide helical face.
Bounds: TE 3 %, share 0.03, stiffness 3 %. CalculiX runs are kept under ``out`` and reused.

With ``freeze`` the CalculiX results (finest rung at the first position, the base elsewhere) are written as
a frozen reference (JSON) with their provenance: CalculiX version, date, deck hash, mesh sizes, nodes and
elements, wall times, the refinement ladder and the command that regenerates them, and our figures at the
time. A read-out (flank peak, root stress) that moves more than 5 % over the ladder's last
refinement is named under ``unconverged`` with its numbers: recorded, not for comparison.
"""
from __future__ import annotations

import dataclasses
import json
import shlex
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from .calculix import penalty_slope, solve_ours
from .whole_gear import BODIES, stiffness, solve_whole, whole_settings

__all__ = ["BOUNDS_WHOLE", "run_whole_validation", "ccx_version", "ours_figures"]

BOUNDS_WHOLE = {"te_rel": 0.03, "share_abs": 0.03, "stiffness_rel": 0.03}

#: the refinement ladder at the first position: factors on the base contact band and fillet size, coarsest first
LADDERS = {"finer": lambda n: [1.5 ** -i for i in range(n + 1)],
           "coarser": lambda n: [1.5 ** (n - i) for i in range(n + 1)],
           "both": lambda n: [1.5 ** (n - i) for i in range(2 * n + 1)]}


def ccx_version() -> str:
    """The first line of ``ccx -v`` that names the version."""
    from fem.calculix.run import ccx_path
    out = subprocess.run([ccx_path(), "-v"], capture_output=True, text=True, timeout=30).stdout
    return next((ln.strip() for ln in out.splitlines() if "Version" in ln), out.strip())


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


def _root(c, member: str) -> float:
    return float(c.root.get(member, {}).get("max", np.nan))


def _row(roll, mine, r, c, lm, torque, teeth):
    sm, sc = mine.share(teeth), c.share(teeth)
    o = ours_figures(lm, r, torque)
    k_ours = o["stiffness"]
    return {"roll_deg": roll, "te_ours": mine.te, "te_ccx": c.te, "te_diff_pct": 100 * (mine.te / c.te - 1),
            "share_ours": sm, "share_ccx": sc, "share_diff": max(abs(sm[k] - sc[k]) for k in teeth),
            "k_ours": k_ours, "k_ccx": c.stiffness, "k_diff_pct": 100 * (k_ours / c.stiffness - 1),
            "p_ours": o["flank_pressure"], "p_ccx": c.info.get("p_flank", np.nan),
            "sr1_ours": o["root_pinion"], "sr1_ccx": _root(c, "pinion"),
            "sr2_ours": o["root_gear"], "sr2_ccx": _root(c, "gear"), "t_ours": mine.wall, "t_ccx": c.wall,
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


def run_whole_validation(case_path: str, positions: list[float], out: str, band_um: float | None = None,
                         refine: int = 1, fidelity: str = "default", freeze: str | None = None,
                         command: str | None = None, progress: bool = True, threads: int = 2,
                         ladder: str = "finer", body: str = "default") -> int:
    """Ours against whole-gear CalculiX at pinion rolls ``positions`` (deg); returns 0 within bounds, else 1.

    Prints the table and writes ``whole_gear.csv`` and ``whole_gear.json`` to ``out``. Raises ``CaseError``
    on bad arguments (before looking for ``ccx``) and ``CcxNotFound`` when ``ccx`` is missing."""
    from fem.calculix.run import ccx_path
    from ..case import FIDELITIES, load_case
    from ..errors import CaseError
    case = load_case(case_path)
    pitch_deg = 360.0 / case.pinion.teeth
    rolls = list(positions or [0.0, -9.0])
    if any(not np.isfinite(r) or abs(r) > 0.5 * pitch_deg + 1e-9 for r in rolls):
        raise CaseError("--positions", rolls, f"roll angles in deg with |roll| <= {0.5 * pitch_deg:.4f}")
    if not 0 <= refine <= 3:
        raise CaseError("--refine", refine, "an integer from 0 to 3")
    if band_um is not None and not 20.0 <= band_um <= 2000.0:
        raise CaseError("--band", band_um, "a contact-band element size from 20 to 2000 um")
    if body not in BODIES:
        raise CaseError("--coarse-body", body, ", ".join(BODIES))
    if ladder not in LADDERS:
        raise CaseError("--ladder", ladder, ", ".join(LADDERS))
    if not 1 <= threads <= 64:
        raise CaseError("--threads", threads, "an integer from 1 to 64")
    if fidelity not in FIDELITIES:
        raise CaseError("--fidelity", fidelity, ", ".join(FIDELITIES))
    if case.gear.internal:
        raise CaseError("--case", case_path, "an external pair (the whole-gear CalculiX model has no ring gear)")
    ccx_path()
    torque = case.torques[0]
    lm, say, t_prepare = prepare_ours(case, fidelity, progress)
    base = whole_settings(lm.b_nom, case.module, band_um, threads=threads, body=body)
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)

    def ccx(roll, st):
        return solve_whole(lm, roll, torque, st, outdir / f"ccx_whole_r{roll:+.4f}_b{1e3 * st.h_contact:.0f}", say=say)
    rows, rungs = [], []
    for rd in rolls:
        mine, r = solve_ours(lm, np.radians(rd), torque)
        c = ccx(rd, base)
        teeth = sorted(set(mine.pair_load) | set(c.pair_load))
        rows.append(_row(rd, mine, r, c, lm, torque, teeth))
    for f in LADDERS[ladder](refine):                                # coarsest first
        h = base.h_contact * f
        rungs.append(ccx(rolls[0], dataclasses.replace(base, h_contact=h, half_band=base.half_band - base.h_contact
                                                        + h, penalty=penalty_slope(h), h_fillet=base.h_fillet * f)))
    sh = lambda d: "/".join(f"{d[k]:.3f}" for k in sorted(d))
    lines = [f"{case.name} at {torque * 1e-3:g} N m: ours ({fidelity}) against CalculiX on whole gears, every tooth "
             f"(contact band {1e3 * base.h_contact:.0f} um, tension-side fillets {1e3 * base.h_fillet:.0f} um)",
             f"{'roll':>6} {'TE ours':>8} {'TE ccx':>8} {'dTE%':>6} {'share ours':>17} {'share ccx':>17} {'dsh':>5} "
             f"{'c ours':>6} {'c ccx':>6} {'dc%':>6} {'p ours':>6} {'p ccx':>6} {'sF1 o':>6} {'sF1 c':>6} "
             f"{'sF2 o':>6} {'sF2 c':>6} {'t ours':>6} {'t ccx':>6}"]
    ok_all = True
    for r in rows:
        ok = (abs(r["te_diff_pct"]) <= 100 * BOUNDS_WHOLE["te_rel"] and r["share_diff"] <= BOUNDS_WHOLE["share_abs"]
              and abs(r["k_diff_pct"]) <= 100 * BOUNDS_WHOLE["stiffness_rel"])
        r["ok"] = ok
        ok_all &= ok
        lines.append(f"{r['roll_deg']:6.2f} {r['te_ours']:8.3f} {r['te_ccx']:8.3f} {r['te_diff_pct']:+6.2f} "
                     f"{sh(r['share_ours']):>17} {sh(r['share_ccx']):>17} {r['share_diff']:5.3f} {r['k_ours']:6.2f} "
                     f"{r['k_ccx']:6.2f} {r['k_diff_pct']:+6.2f} {r['p_ours']:6.0f} {r['p_ccx']:6.0f} "
                     f"{r['sr1_ours']:6.1f} {r['sr1_ccx']:6.1f} {r['sr2_ours']:6.1f} {r['sr2_ccx']:6.1f} "
                     f"{r['t_ours']:6.2f} {r['t_ccx']:6.0f}{'' if ok else '  OUT'}")
    lines.append(f"ours: compliance {t_prepare:.1f} s once, then the contact solve per position (t ours); CalculiX: "
                 "mesh + solve per position (t ccx), s. p: flank peak away from the face ends / edge contact; sF1, "
                 "sF2: root stress of pinion and gear, MPa")
    lines.append(f"CalculiX refinement at roll {rolls[0]:g} (band, fillet -> TE, stiffness, flank peak, root stress, "
                 "nodes, s):")
    for c in rungs:
        lines.append(f"  {1e3 * c.info['h_contact_mm']:5.0f} um {1e3 * _h_fillet(c):5.0f} um  "
                     f"TE {c.te:8.3f}  c {c.stiffness:6.3f}  p {c.info.get('p_flank', np.nan):6.0f}  "
                     f"sF {_root(c, 'pinion'):6.1f} {_root(c, 'gear'):6.1f}  {c.info['nodes']} nodes  {c.wall:.0f} s")
    if len(rungs) >= 2:
        lines.append(f"  TE change over the last refinement: {100 * (rungs[-1].te / rungs[-2].te - 1):+.2f} %")
    print("\n".join(lines))
    keys = ["roll_deg", "te_ours", "te_ccx", "te_diff_pct", "share_ours", "share_ccx", "share_diff", "k_ours",
            "k_ccx", "k_diff_pct", "p_ours", "p_ccx", "sr1_ours", "sr1_ccx", "sr2_ours", "sr2_ccx", "t_ours", "t_ccx",
            "ccx_nodes", "band_um", "ok"]
    fmt = lambda v: sh(v) if isinstance(v, dict) else str(v)
    (outdir / "whole_gear.csv").write_text(",".join(keys) + "\n" + "".join(
        ",".join(fmt(r[k]) for k in keys) + "\n" for r in rows))
    (outdir / "whole_gear.json").write_text(json.dumps({"rows": rows, "refinement": [_entry(c) for c in rungs]},
                                                       indent=1, default=float))
    if freeze:
        finest = {rolls[0]: rungs[-1]} | {rd: ccx(rd, base) for rd in rolls[1:]}
        _freeze(freeze, case_path, torque, finest, rungs, command, {r["roll_deg"]: r["ours"] for r in rows},
                t_prepare)
    return 0 if ok_all else 1


def _h_fillet(c) -> float:
    """The fillet element size of a run, mm (a run that records none: the flank's)."""
    st = c.info["settings"]
    return st.get("h_fillet") or st["h_flank"]


def _entry(c) -> dict:
    """One CalculiX run as the frozen reference stores it."""
    st = c.info["settings"]
    pairs = sum(v > 0.01 for v in c.share(sorted(c.pair_load)).values())
    return {"roll_deg": c.roll_deg, "contact": {1: "single", 2: "double"}.get(pairs, f"{pairs} pairs"),
            "te": c.te, "stiffness": c.stiffness,
            "share": {str(k): v for k, v in c.share(sorted(c.pair_load)).items()},
            "pair_load": {str(k): v for k, v in c.pair_load.items()},
            "flank_pressure": c.info.get("p_flank"), "flank_at": c.info.get("p_flank_at"),
            "max_pressure": c.max_pressure,
            "root_stress": c.root, "deck_sha256": c.info["deck_sha256"], "nodes": c.info["nodes"],
            "elements": c.info["elements"], "nodes_pinion": c.info["nodes_pinion"], "nodes_gear": c.info["nodes_gear"],
            "h_contact_um": 1e3 * c.info["h_contact_mm"], "h_fillet_um": 1e3 * _h_fillet(c),
            "mesh_sizes_mm": {k: st.get(k) for k in ("h_contact", "half_band", "h_flank", "h_tooth", "h_body",
                                                      "h_fillet")},
            "penalty_mpa_per_mm": st["penalty"], "threads": st["threads"], "ccx_wall_s": c.info["ccx_wall"],
            "mesh_wall_s": c.info["mesh_wall"], "wall_s": c.wall}


#: where the flank peak is, as a frozen reference defines it
FLANK_AT = ("the flank peak's pinion tooth, the radius (pinion frame) of the fit's centre and the slice's mid z, mm, "
            "the fitted half-width, um, and the nodes fitted (ltca.verify.fitted_peak)")
#: a read-out that moves more than this over the ladder's last refinement is not converged: the frozen reference
#: records it under ``unconverged`` with the numbers, and a test does not compare it (5 % bounds)
CONVERGED = {"flank_pressure": 0.05, "root_pinion": 0.05, "root_gear": 0.05}


def _read(c, quantity: str) -> float:
    return _root(c, quantity[5:]) if quantity.startswith("root_") else float(c.info.get("p_flank") or np.nan)


def unconverged(ladder) -> dict:
    """quantity -> why it is not converged: its change over the last refinement of the ``ladder`` (CalculiX runs,
    coarsest first) exceeds :data:`CONVERGED`."""
    if len(ladder) < 2:
        return {}
    a, b = ladder[-2:]
    out = {}
    for q, bound in CONVERGED.items():
        va, vb = _read(a, q), _read(b, q)
        if np.isfinite(va) and np.isfinite(vb) and abs(vb / va - 1) > bound:
            out[q] = (f"CalculiX {q} {va:.1f} -> {vb:.1f} MPa ({100 * (vb / va - 1):+.1f} %) over the refinement "
                      f"{1e3 * a.info['h_contact_mm']:.0f} -> {1e3 * b.info['h_contact_mm']:.0f} um band at roll "
                      f"{b.roll_deg:g} deg: more than {100 * bound:g} %, not converged")
    return out


def _freeze(path: str, case_path: str, torque: float, runs: dict, ladder, command: str | None, ours: dict,
            t_prepare: float) -> None:
    """Write the frozen CalculiX reference (see the module docstring); ``ours`` (roll -> :func:`ours_figures`)
    records our figures when it was frozen, so that a test can name a known disagreement. A read-out the ladder
    does not converge (:func:`unconverged`) is recorded at every position, and named under ``unconverged``."""
    rec = {"case": case_path, "torque_nm": torque * 1e-3, "calculix_version": ccx_version(),
           "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
           "model": "whole gears, every tooth, bore fixed (gear) / bore on a rigid body turning about the axis "
                    "(pinion); fem.solids.full_gear + ltca.verify.whole_gear",
           "command": command or "", "units": {"te": "arcsec of the gear", "stiffness": "N/(mm um)",
                                               "pair_load": "N", "max_pressure": "MPa", "flank_pressure": "MPa",
                                               "root_stress": "MPa, r_mm and z_mm in mm"},
           "definitions": {
               "flank_pressure": "largest elliptic-fit peak over face slices of b/14, the one at each face end left "
                                 "out (ours: flank peak away from edge contact, ltca.cylindrical.edges)",
               "root_stress": "largest principal nodal stress on the loaded teeth's tension-side fillets, "
                              "|z| <= 0.45 b (ltca.verify.whole_root; ours: fem.compliance root_max)",
               "max_pressure": "largest elliptic-fit peak over all face slices (face ends included)",
               "flank_at": FLANK_AT},
           "ours_compliance_wall_s": t_prepare,
           "convergence": [_entry(c) for c in ladder],
           "positions": [dict(_entry(c), ours_at_freeze=ours.get(rd)) for rd, c in runs.items()]}
    if bad := unconverged(ladder):
        rec["unconverged"] = bad
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(json.dumps(_finite(rec), indent=1, allow_nan=False) + "\n")


def _finite(v):
    """The record with NaN (a quantity not read) as null: strict JSON."""
    if isinstance(v, dict):
        return {k: _finite(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_finite(x) for x in v]
    return None if isinstance(v, float) and not np.isfinite(v) else v


def command_line(argv: list[str]) -> str:
    """The command that regenerates a frozen reference, as typed."""
    return "ltca " + " ".join(shlex.quote(a) for a in argv)
