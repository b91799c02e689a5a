"""Freeze a whole-gear CalculiX reference of a cylindrical pair: ``python3 -m tools.calculix_refs.freeze_whole``.

The comparison of ``ltca validate --reference calculix-whole`` (:mod:`ltca.verify.whole_check`) at every
position, then CalculiX's own convergence check at the first position: the contact band and the fillets refined
``refine`` times by 1.5 (``ladder`` "finer"), coarsened ("coarser") or both ("both"). The CalculiX results
(finest rung at the first position, the base elsewhere) are written as a frozen reference (JSON) with their
provenance: CalculiX version, date, deck hash, mesh sizes, nodes and elements, wall times, the refinement
ladder and the command that regenerates them, and our figures at the time. A read-out (flank peak, root stress)
that moves more than 5 % over the ladder's last refinement is named under ``unconverged`` with its numbers:
recorded, not for comparison. ``tests/ltca/verify/test_reference_calculix.py`` compares ours with these files.
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import time
from pathlib import Path

import numpy as np

from ltca.verify.calculix import penalty_slope
from ltca.verify.whole_check import (
    ccx_folder,
    check_arguments,
    compare_positions,
    prepare_ours,
    root_stress,
    table_lines,
    write_rows,
)
from ltca.verify.whole_gear import solve_whole, whole_settings

from .provenance import ccx_version, command_line, finite, run

__all__ = ["LADDERS", "FLANK_AT", "CONVERGED", "entry", "unconverged", "run_whole_freeze", "main"]

#: the refinement ladder at the first position: factors on the base contact band and fillet size, coarsest first
LADDERS = {"finer": lambda n: [1.5 ** -i for i in range(n + 1)],
           "coarser": lambda n: [1.5 ** (n - i) for i in range(n + 1)],
           "both": lambda n: [1.5 ** (n - i) for i in range(2 * n + 1)]}

#: where the flank peak is, as a frozen reference defines it
FLANK_AT = ("the flank peak's pinion tooth, the radius (pinion frame) of the fit's centre and the slice's mid z, mm, "
            "the fitted half-width, um, and the nodes fitted (ltca.verify.fitted_peak)")
#: a read-out that moves more than this over the ladder's last refinement is not converged: the frozen reference
#: records it under ``unconverged`` with the numbers, and a test does not compare it (5 % bounds)
CONVERGED = {"flank_pressure": 0.05, "root_pinion": 0.05, "root_gear": 0.05}


def h_fillet(c) -> float:
    """The fillet element size of a run, mm (a run that records none: the flank's)."""
    st = c.info["settings"]
    return st.get("h_fillet") or st["h_flank"]


def entry(c) -> dict:
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
            "h_contact_um": 1e3 * c.info["h_contact_mm"], "h_fillet_um": 1e3 * h_fillet(c),
            "mesh_sizes_mm": {k: st.get(k) for k in ("h_contact", "half_band", "h_flank", "h_tooth", "h_body",
                                                      "h_fillet")},
            "penalty_mpa_per_mm": st["penalty"], "threads": st["threads"], "ccx_wall_s": c.info["ccx_wall"],
            "mesh_wall_s": c.info["mesh_wall"], "wall_s": c.wall}


def _read(c, quantity: str) -> float:
    return root_stress(c, quantity[5:]) if quantity.startswith("root_") else float(c.info.get("p_flank") or np.nan)


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
    """Write the frozen CalculiX reference (see the module docstring); ``ours`` (roll -> ours_figures) records our
    figures when it was frozen, so that a test can name a known disagreement. A read-out the ladder does not
    converge (:func:`unconverged`) is recorded at every position, and named under ``unconverged``."""
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
           "convergence": [entry(c) for c in ladder],
           "positions": [dict(entry(c), ours_at_freeze=ours.get(rd)) for rd, c in runs.items()]}
    if bad := unconverged(ladder):
        rec["unconverged"] = bad
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text(json.dumps(finite(rec), indent=1, allow_nan=False) + "\n")


def run_whole_freeze(case_path: str, positions: list[float], out: str, freeze: str | None, band_um: float | None = None,
                     refine: int = 1, fidelity: str = "default", command: str | None = None, progress: bool = True,
                     threads: int = 2, ladder: str = "finer", body: str = "default") -> int:
    """The whole-gear comparison at ``positions`` (deg), CalculiX's ladder of ``refine`` rungs at the first one, and
    (``freeze`` a path) the frozen reference; returns 0 when every position is within the bounds, else 1.

    Raises ``CaseError`` on bad arguments (before looking for ``ccx``) and ``CcxNotFound`` when it is missing."""
    from ltca.case import load_case
    from ltca.errors import CaseError
    from ltca.fem.calculix.run import ccx_path
    case = load_case(case_path)
    rolls = list(positions or [0.0, -9.0])
    check_arguments(case, case_path, rolls, band_um, fidelity, threads, body)
    if not 0 <= refine <= 3:
        raise CaseError("--refine", refine, "an integer from 0 to 3")
    if ladder not in LADDERS:
        raise CaseError("--ladder", ladder, ", ".join(LADDERS))
    ccx_path()
    torque = case.torques[0]
    lm, say, t_prepare = prepare_ours(case, fidelity, progress)
    base = whole_settings(lm.b_nom, case.module, band_um, threads=threads, body=body)
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)

    def ccx(roll, st):
        return solve_whole(lm, roll, torque, st, ccx_folder(outdir, roll, st), say=say)
    rows = compare_positions(lm, rolls, torque, base, outdir, say)
    rungs = []
    for f in LADDERS[ladder](refine):                                # coarsest first
        h = base.h_contact * f
        rungs.append(ccx(rolls[0], dataclasses.replace(base, h_contact=h, half_band=base.half_band - base.h_contact
                                                        + h, penalty=penalty_slope(h), h_fillet=base.h_fillet * f)))
    lines = table_lines(case, torque, fidelity, base, rows, t_prepare)
    lines.append(f"CalculiX refinement at roll {rolls[0]:g} (band, fillet -> TE, stiffness, flank peak, root stress, "
                 "nodes, s):")
    for c in rungs:
        lines.append(f"  {1e3 * c.info['h_contact_mm']:5.0f} um {1e3 * h_fillet(c):5.0f} um  "
                     f"TE {c.te:8.3f}  c {c.stiffness:6.3f}  p {c.info.get('p_flank', np.nan):6.0f}  "
                     f"sF {root_stress(c, 'pinion'):6.1f} {root_stress(c, 'gear'):6.1f}  {c.info['nodes']} nodes  "
                     f"{c.wall:.0f} s")
    if len(rungs) >= 2:
        lines.append(f"  TE change over the last refinement: {100 * (rungs[-1].te / rungs[-2].te - 1):+.2f} %")
    print("\n".join(lines))
    write_rows(outdir, rows, {"refinement": [entry(c) for c in rungs]})
    if freeze:
        finest = {rolls[0]: rungs[-1]} | {rd: ccx(rd, base) for rd in rolls[1:]}
        _freeze(freeze, case_path, torque, finest, rungs, command, {r["roll_deg"]: r["ours"] for r in rows},
                t_prepare)
    return 0 if all(r["ok"] for r in rows) else 1


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python3 -m tools.calculix_refs.freeze_whole",
                                description="Ours against CalculiX on whole gears, CalculiX's refinement ladder at the "
                                            "first position, and the frozen reference (a cylindrical pair).")
    p.add_argument("freeze", nargs="?", metavar="JSON", help="frozen reference to write (omit: compare only)")
    p.add_argument("--case", default="cases/fzg_c14.toml", help="case file (default cases/fzg_c14.toml)")
    p.add_argument("--positions", type=float, nargs="+", metavar="DEG",
                   help="pinion roll angles from the pitch point, deg (default 0 -9); the ladder runs at the first")
    p.add_argument("--out", default="out/whole_freeze", help="CalculiX runs, kept and reused (default out/whole_freeze)")
    p.add_argument("--band", type=float, metavar="UM", help="contact-band element size, um (default 3/4 of the Hertz "
                                                             "half-width)")
    p.add_argument("--refine", type=int, default=1, help="rungs of 1.5 of the ladder at the first position (default 1)")
    p.add_argument("--ladder", choices=list(LADDERS), default="finer",
                   help="the rungs refine the base contact band and fillets (finer, default), coarsen them (coarser) "
                        "or both; the first position is frozen at the finest rung")
    p.add_argument("--fidelity", choices=["coarse", "default", "fine"], default="default", help="our fidelity")
    p.add_argument("--coarse-body", action="store_true", help="CalculiX elements of the coarse body away from the "
                                                              "band (ltca.verify.whole_gear.BODIES): a wide face")
    p.add_argument("--threads", type=int, default=2, help="CalculiX threads (default 2)")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    return p


def main(argv: list[str] | None = None) -> int:
    import sys
    argv = sys.argv[1:] if argv is None else argv

    def work(a):
        return run_whole_freeze(a.case, a.positions, a.out, a.freeze, band_um=a.band, refine=a.refine,
                                fidelity=a.fidelity, command=command_line("tools.calculix_refs.freeze_whole", argv),
                                progress=not a.quiet, threads=a.threads, ladder=a.ladder,
                                body="coarse" if a.coarse_body else "default")
    return run(build_parser(), work, argv)


if __name__ == "__main__":
    raise SystemExit(main())
