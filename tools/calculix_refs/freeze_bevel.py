"""Freeze the CalculiX reference of a spiral bevel pair: ``python3 -m tools.calculix_refs.freeze_bevel``.

The comparison of ``ltca validate --reference calculix`` on a ``[bevel]`` case (:mod:`ltca.verify.bevel_calculix`),
with CalculiX's convergence check at the first position: a ladder of contact-zone sizes h0, h0/1.5, h0/1.5^2 ...
up to ``refine`` (Richardson estimate over the last three); the other positions at rung ``level``. The first
position is compared at the finest rung. The CalculiX values are written as a frozen reference with their
provenance (command, mesh sizes, CalculiX version, date), read by
``tests/ltca/verify/test_reference_calculix_bevel.py``;
:mod:`tools.calculix_refs.recompare_bevel` re-evaluates ours on such a file after a change of our model.
"""
from __future__ import annotations

import argparse
import datetime
import json
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

from ltca.verify.bevel_calculix import (
    BOUNDS_BEVEL,
    bevel_model,
    ccx_folder,
    check_arguments,
    compare_positions,
    middle_torque,
    mounted,
    shares,
    table_lines,
)
from ltca.verify.bevel_ccx import bevel_ladder, solve_bevel_ccx

from .convergence import richardson
from .provenance import ccx_version, command_line, run

__all__ = ["MODEL", "run_bevel_freeze", "main"]

MODEL = ("whole members (every tooth), gmsh OCC lofted teeth fused with a revolved blank, C3D10, contact flank nodes "
         "on the exact surface; pinion bore rigid body turning about its axis under the torque, gear back face fixed; "
         "frictionless surface-to-surface penalty contact (10 E / h)")


def run_bevel_freeze(case_path: str, fractions=(0.0, 0.4), out: str = "out/validate_bevel_ccx", refine: int = 2,
                     level: int = 1, h0: float = 0.25, freeze: str | None = None, command: str = "",
                     progress: bool = True, torque: float | None = None, threads: int = 2) -> int:
    """The bevel comparison with the ladder of ``refine`` rungs at the first position and (``freeze`` a path) the
    frozen reference; exit status 0 when inside the bounds."""
    from ltca.errors import CaseError
    from ltca.fem.calculix.run import ccx_path
    check_arguments(fractions, level, h0, threads)
    if not level <= refine <= 4:
        raise CaseError("--refine", refine, f"an integer from --level ({level}) to 4")
    ccx_path()
    say = (lambda m: print(m, file=sys.stderr, flush=True)) if progress else (lambda m: None)
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)
    case, lm, t_comp = bevel_model(case_path, cache=str(outdir / "cache"), say=say)
    torque = middle_torque(case) if torque is None else float(torque)
    cycle = 2 * np.pi / lm.pair.blank.pinion.z
    ladder_st = [replace(mounted(st, case, lm), threads=threads) for st in bevel_ladder(refine + 1, h0)]

    def ccx(f, st):
        return solve_bevel_ccx(lm, f * cycle, torque * 1e3, st, ccx_folder(outdir, f, st), cache=str(outdir / "cad"),
                               say=say)
    # the rungs up to ``level`` first, then the other positions, then the finer rungs (an interrupted run keeps
    # the comparison at every position; every run is reused on a rerun)
    ladder = [ccx(fractions[0], st) for st in ladder_st[:level + 1]]
    others = {f: ccx(f, ladder_st[level]) for f in fractions[1:]}
    ladder += [ccx(fractions[0], st) for st in ladder_st[level + 1:refine + 1]]
    rows = compare_positions(lm, fractions, torque, {fractions[0]: ladder[-1], **others})
    rich = {k: richardson([getattr(c, a) for c in ladder[-3:]], 1.5) for k, a in
            (("theta", "theta_arcsec"), ("p_interior", "p_interior"))} if len(ladder) >= 3 else {}
    lines = table_lines(case, torque, rows, t_comp)
    lines.append(f"CalculiX contact-zone refinement at phi1/cycle = {fractions[0]:g} (h -> TE, shares, p interior, "
                 "nodal max, nodes, s):")
    for c in ladder:
        lines.append(f"  {1e3 * c.info['h_zone_mm']:5.0f} um  TE {c.theta_arcsec:8.3f}  share {shares(c.share)}  "
                     f"p {c.p_interior:6.0f}  nodal {c.p_nodal_max:6.0f}  {c.info['nodes']} nodes  {c.wall:.0f} s")
    for k, v in rich.items():
        if v is not None:
            lines.append(f"  Richardson estimate of {k}: {v[0]:.3f} (order {v[1]:.2f})")
    print("\n".join(lines))
    rec = {"case": case_path, "torque_nm": torque, "calculix_version": ccx_version(),
           "date": datetime.date.today().isoformat(), "command": command, "bounds": BOUNDS_BEVEL, "model": MODEL,
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


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python3 -m tools.calculix_refs.freeze_bevel",
                                description="Our spiral bevel LTCA against CalculiX on whole members, the contact-zone "
                                            "ladder at the first position, and the frozen reference.")
    p.add_argument("freeze", nargs="?", metavar="JSON", help="frozen reference to write (omit: compare only)")
    p.add_argument("--case", default="cases/spiral_bevel_cao2008.toml",
                   help="a [bevel] case (default cases/spiral_bevel_cao2008.toml)")
    p.add_argument("--positions", type=float, nargs="+", metavar="CYCLES", default=[0.0, 0.4],
                   help="pinion angles in mesh cycles from the mean point (default 0 0.4); the ladder runs at the first")
    p.add_argument("--band", type=float, default=250.0, metavar="UM", help="contact-zone size at rung 0, um "
                                                                           "(default 250)")
    p.add_argument("--refine", type=int, default=2, help="finest rung of the ladder at the first position (default 2)")
    p.add_argument("--level", type=int, default=1, help="the rung used at the other positions (default 1)")
    p.add_argument("--torque", type=float, default=None, metavar="NM",
                   help="pinion torque, N m (default: the case's middle torque)")
    p.add_argument("--threads", type=int, default=2, help="CalculiX threads (default 2)")
    p.add_argument("--out", default="out/validate_bevel_ccx", help="CalculiX runs, kept and reused")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    return p


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv

    def work(a):
        return run_bevel_freeze(a.case, tuple(a.positions), a.out, refine=a.refine, level=a.level, h0=1e-3 * a.band,
                                freeze=a.freeze, command=command_line("tools.calculix_refs.freeze_bevel", argv),
                                progress=not a.quiet, torque=a.torque, threads=a.threads)
    return run(build_parser(), work, argv)


if __name__ == "__main__":
    raise SystemExit(main())
