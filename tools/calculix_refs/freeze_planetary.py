"""Freeze the whole-gear CalculiX reference of a planetary satellite in its central wheel:
``python3 -m tools.calculix_refs.freeze_planetary``.

The comparison of ``ltca validate --reference calculix-whole`` on a ``[satellite]`` case
(:mod:`ltca.verify.planetary_whole`) at every position, then the first position with the contact band refined
``refine`` times by 1.5 (CalculiX's convergence ladder). The CalculiX results (finest rung at the first position)
are written with their provenance (command, CalculiX version, date, deck hashes, mesh sizes) as a frozen reference
(JSON), compared by ``tests/ltca/verify/test_reference_calculix_planetary.py``.
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import sys
import time
from pathlib import Path

from ltca.verify.calculix import penalty_slope
from ltca.verify.planetary_whole import (
    BOUNDS_PLANETARY,
    ccx_folder,
    ccx_record,
    check_arguments,
    compare_positions,
    compare_row,
    planetary_settings,
    prepare_ours,
    shares,
    table_lines,
)
from ltca.verify.whole_gear import solve_whole

from .provenance import ccx_version, command_line, run

__all__ = ["run_planetary_freeze", "main"]

MODEL = ("whole gears, every tooth (fem.solids.full_gear, the wheel internal): wheel outer cylinder fixed (housing), "
         "satellite bore on a rigid body turning about the satellite axis; frictionless surface-to-surface penalty "
         "contact (ltca.verify.whole_gear)")
UNITS = {"te_um": "um along the line of action (satellite rotation x r_b1)", "te_arcsec": "arcsec of the satellite",
         "pair_load": "N", "max_pressure": "MPa", "phi_deg": "satellite position, deg (geometry.satellite.mesh)"}


def run_planetary_freeze(case_path: str, positions: list[float], torque_nm: float | None, out: str,
                         freeze: str | None, band_um: float | None = None, refine: int = 1, fidelity: str | None = None,
                         command: str | None = None, progress: bool = True, cache: str | None = None) -> int:
    """The planetary comparison at ``positions`` (deg), the ladder of ``refine`` rungs at the first one, and
    (``freeze`` a path) the frozen reference; returns 0 when every position is within the bounds, else 1."""
    from ltca.errors import CaseError
    from ltca.fem.calculix.run import ccx_path
    from ltca.planetary.case import load_planetary_case
    case = load_planetary_case(case_path)
    band_um = 600.0 if band_um is None else band_um
    fidelity = fidelity or case.fidelity
    check_arguments(case, positions, torque_nm, band_um, fidelity)
    if not 0 <= refine <= 3:
        raise CaseError("--refine", refine, "an integer from 0 to 3")
    ccx_path()
    say = (lambda m: print(m, file=sys.stderr, flush=True)) if progress else (lambda m: None)
    t0 = time.perf_counter()
    sm, lm = prepare_ours(case, positions, 1e3 * torque_nm, fidelity, cache, say)
    t_prepare = time.perf_counter() - t0
    rb1 = sm.pair.pinion.r_base
    base = planetary_settings(lm.b_nom, case.design.m, band_um)
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)
    rows = compare_positions(sm, lm, positions, torque_nm, base, outdir, say)
    ladder = [rows[0]["ccx"]]
    for i in range(1, refine + 1):
        h = base.h_contact / 1.5 ** i
        st = dataclasses.replace(base, h_contact=h, half_band=base.half_band - base.h_contact + h,
                                 penalty=penalty_slope(h))
        c = solve_whole(lm, positions[0], 1e3 * torque_nm, st, ccx_folder(outdir, positions[0], torque_nm, st),
                        say=say)
        ladder.append(ccx_record(c, rb1))
    lines = table_lines(case.name, torque_nm, fidelity, rows, t_prepare)
    lines.append(f"CalculiX contact-band refinement at phi {positions[0]:g} deg (band -> TE um, pairs, p, nodes, s):")
    for c in ladder:
        lines.append(f"  {c['h_contact_um']:5.0f} um  TE {c['te_um']:8.3f}  {c['loaded_pairs']} pairs  "
                     f"p {c['max_pressure']:6.0f}  {c['nodes']} nodes  {c['wall_s']:.0f} s  share {shares(c['share'])}")
    if len(ladder) >= 2:
        lines.append(f"  TE change over the last refinement: {100 * (ladder[-1]['te_um'] / ladder[-2]['te_um'] - 1):+.2f} %")
    print("\n".join(lines))
    result = {"case": case_path, "torque_nm": torque_nm, "fidelity": fidelity, "prepare_s": t_prepare,
              "bounds": BOUNDS_PLANETARY, "rows": rows, "refinement": ladder}
    (outdir / "planetary_whole.json").write_text(json.dumps(result, indent=1))
    if freeze:
        rec = dict(result, calculix_version=ccx_version(), command=command or "",
                   date=time.strftime("%Y-%m-%d", time.gmtime()), model=MODEL, units=UNITS)
        rec["rows"] = [compare_row(r["phi_deg"], r["ours"], ladder[-1]) if i == 0 else r for i, r in enumerate(rows)]
        Path(freeze).parent.mkdir(parents=True, exist_ok=True)
        Path(freeze).write_text(json.dumps(rec, indent=1) + "\n")
    return 0 if all(r["ok"] for r in rows) else 1


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python3 -m tools.calculix_refs.freeze_planetary",
                                description="Ours against CalculiX on the whole satellite and central wheel, the "
                                            "contact-band ladder at the first position, and the frozen reference.")
    p.add_argument("freeze", nargs="?", metavar="JSON", help="frozen reference to write (omit: compare only)")
    p.add_argument("--case", default="cases/eccentric_planetary_satellite.toml",
                   help="a [satellite] case (default cases/eccentric_planetary_satellite.toml)")
    p.add_argument("--torque", type=float, required=True, metavar="NM", help="the satellite torque, N m")
    p.add_argument("--positions", type=float, nargs="+", metavar="DEG", default=[-1.8],
                   help="satellite positions, deg (default -1.8); the ladder runs at the first")
    p.add_argument("--band", type=float, metavar="UM", help="contact-band element size, um (default 600)")
    p.add_argument("--refine", type=int, default=1, help="rungs of 1.5 of the ladder (default 1)")
    p.add_argument("--fidelity", choices=["coarse", "default", "fine"], default=None,
                   help="our fidelity (default: the case's)")
    p.add_argument("--out", default="out/planetary_freeze", help="CalculiX runs, kept and reused")
    p.add_argument("--cache", default=None, help="our mesh cache directory")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    return p


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv

    def work(a):
        return run_planetary_freeze(a.case, a.positions, a.torque, a.out, a.freeze, band_um=a.band, refine=a.refine,
                                    fidelity=a.fidelity,
                                    command=command_line("tools.calculix_refs.freeze_planetary", argv),
                                    progress=not a.quiet, cache=a.cache)
    return run(build_parser(), work, argv)


if __name__ == "__main__":
    raise SystemExit(main())
