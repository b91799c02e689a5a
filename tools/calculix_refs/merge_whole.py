"""Refine chosen positions of a frozen whole-gear reference: ``python3 -m tools.calculix_refs.merge_whole FILE``.

A frozen whole-gear reference (:mod:`tools.calculix_refs.freeze_whole`) refines its contact band at the first
position only (``convergence``); its other positions stay at the base band. This script refines the named
positions of such a file ``refine`` times by 1.5 beyond the band each was frozen at (contact band, its half-width
beyond the band, the penalty slope and the tension-side fillets scaled as the freeze's ladder; every other
element size as frozen), replaces each of them by its finest run with our figures of today's code
(``ours_at_freeze``), and keeps each position's ladder, coarsest first, under ``ladders`` keyed by the roll
(``f"{roll:g}"``), the frozen run first. The rest of the file (the first position's ``convergence``, the other
positions, the original ``command``) is kept; ``merged`` records each merge's command, date, CalculiX version and
positions. CalculiX runs are kept under ``out`` and reused, as the freeze's.
"""
from __future__ import annotations

import argparse
import dataclasses
import json
import time
from pathlib import Path

import numpy as np

from ltca.verify.calculix import penalty_slope
from ltca.verify.whole_check import ours_figures, prepare_ours
from ltca.verify.whole_gear import solve_whole, whole_settings

from .freeze_whole import CONVERGED, FLANK_AT, entry
from .provenance import ccx_version, command_line, finite, run

__all__ = ["run_whole_merge", "ladder_key", "rung_settings", "ladder_change", "main"]

_FROZEN_SIZES = ("h_contact", "half_band", "h_flank", "h_tooth", "h_body", "h_fillet")


def ladder_key(roll_deg: float) -> str:
    """The key of a position's ladder in a frozen reference: the roll in deg, as ``f"{roll:g}"``."""
    return f"{float(roll_deg):g}"


def rung_settings(base, frozen: dict, n: int):
    """The settings ``n`` rungs of 1.5 finer than a frozen run (its entry ``frozen``): ``base``
    (:class:`ltca.verify.whole_gear.WholeSettings`) with the frozen element sizes and penalty, then the contact band,
    its half-width beyond the band, the penalty slope and the fillets scaled as the freeze's ladder."""
    st = dataclasses.replace(base, penalty=frozen["penalty_mpa_per_mm"],
                             **{k: frozen["mesh_sizes_mm"][k] for k in _FROZEN_SIZES})
    f = 1.5 ** -n
    h = st.h_contact * f
    return dataclasses.replace(st, h_contact=h, half_band=st.half_band - st.h_contact + h, penalty=penalty_slope(h),
                               h_fillet=st.h_fillet * f)


def ladder_change(ladder: list[dict]) -> dict:
    """Relative change of the TE, the flank peak and the root stresses over a position's last refinement (entries
    coarsest first), with the bands; empty for a ladder of one run."""
    if len(ladder) < 2:
        return {}
    a, b = ladder[-2:]
    read = {"te": lambda e: e["te"], "flank_pressure": lambda e: e.get("flank_pressure"),
            "root_pinion": lambda e: e.get("root_stress", {}).get("pinion", {}).get("max"),
            "root_gear": lambda e: e.get("root_stress", {}).get("gear", {}).get("max")}
    out = {"bands_um": [a["h_contact_um"], b["h_contact_um"]]}
    for q, f in read.items():
        if f(a) and f(b):
            out[q] = f(b) / f(a) - 1
    return out


def _check_body(base, frozen: dict, roll: float) -> None:
    from ltca.errors import CaseError
    sizes = frozen["mesh_sizes_mm"]
    if any(abs(sizes[k] / getattr(base, k) - 1) > 1e-9 for k in ("h_flank", "h_tooth", "h_body")):
        raise CaseError("--coarse-body", roll, "the body the position was frozen with (its h_flank, h_tooth, h_body)")


def run_whole_merge(case_path: str, positions: list[float], out: str, merge: str, refine: int = 1,
                    fidelity: str = "default", command: str | None = None, progress: bool = True, threads: int = 2,
                    body: str = "default") -> int:
    """Refine ``positions`` (pinion rolls, deg) of the frozen reference ``merge`` by ``refine`` rungs and merge them
    into it (see the module docstring); prints each position's ladder against ours. Returns 0.

    Raises ``CaseError`` on bad arguments (a position the file lacks, another case, another body) before looking
    for ``ccx``, and ``CcxNotFound`` when it is missing."""
    from ltca.fem.calculix.run import ccx_path
    from ltca.case import FIDELITIES, load_case
    from ltca.cylindrical.loaded import solve_position
    from ltca.errors import CaseError
    path = Path(merge)
    if not path.is_file():
        raise CaseError("FILE", merge, "a frozen whole-gear reference (JSON) of tools.calculix_refs.freeze_whole")
    try:
        rec = json.loads(path.read_text(encoding="utf-8"))
    except ValueError as exc:                     # not JSON, or not UTF-8
        raise CaseError("FILE", merge, f"a frozen whole-gear reference (it is not JSON: {exc})") from None
    if not isinstance(rec, dict) or "case" not in rec:
        raise CaseError("FILE", merge, "a frozen whole-gear reference (an object with the case and positions)")
    if Path(rec["case"]).name != Path(case_path).name:
        raise CaseError("--case", case_path, f"the case of {merge}: {rec['case']}")
    frozen = {ladder_key(p["roll_deg"]): i for i, p in enumerate(rec["positions"])}
    rolls = list(positions or [])
    if not rolls or any(ladder_key(r) not in frozen for r in rolls):
        raise CaseError("--positions", rolls, "rolls frozen in the file: " + " ".join(frozen))
    if not 1 <= refine <= 3:
        raise CaseError("--refine", refine, "an integer from 1 to 3 (rungs beyond the frozen band)")
    if fidelity not in FIDELITIES:
        raise CaseError("--fidelity", fidelity, ", ".join(FIDELITIES))
    if not 1 <= threads <= 64:
        raise CaseError("--threads", threads, "an integer from 1 to 64")
    ccx_path()
    case = load_case(case_path)
    torque = case.torques[0]
    lm, say, t_prepare = prepare_ours(case, fidelity, progress)
    base = whole_settings(lm.b_nom, case.module, None, threads=threads, body=body)
    for rd in rolls:
        _check_body(base, rec["positions"][frozen[ladder_key(rd)]], rd)
    ladders = rec.setdefault("ladders", {})
    rec.setdefault("definitions", {}).setdefault("flank_at", FLANK_AT)
    lines = [f"{case.name} at {torque * 1e-3:g} N m: frozen positions refined by {refine} rung(s) of 1.5 "
             "(band, fillet -> TE, stiffness, flank peak, root stress pinion / gear, nodes, ccx s); ours at the end"]
    for rd in rolls:
        key = ladder_key(rd)
        frozen_run = {k: v for k, v in rec["positions"][frozen[key]].items() if k != "ours_at_freeze"}
        ladder = ladders.get(key) or [frozen_run]
        start = ladder[-1]
        for n in range(1, refine + 1):
            st = rung_settings(base, start, n)
            c = solve_whole(lm, rd, torque, st, Path(out) / f"ccx_whole_r{rd:+.4f}_b{1e3 * st.h_contact:.0f}", say=say)
            ladder = ladder + [entry(c)]
        r = solve_position(lm, np.radians(rd), torque)
        ours = ours_figures(lm, r, torque)
        ladders[key] = ladder
        rec["positions"][frozen[key]] = dict(ladder[-1], ours_at_freeze=ours)
        lines.append(f"roll {rd:g} deg:")
        for e in ladder:
            rs = {k: v.get("max", np.nan) for k, v in e.get("root_stress", {}).items()}
            lines.append(f"  {e['h_contact_um']:5.0f} um {e['h_fillet_um']:5.0f} um  TE {e['te']:8.3f}  "
                         f"c {e['stiffness']:6.3f}  p {e.get('flank_pressure') or np.nan:6.0f}  "
                         f"sF {rs.get('pinion', np.nan):6.1f} {rs.get('gear', np.nan):6.1f}"
                         f"  {e['nodes']} nodes  {e['ccx_wall_s']:.0f} s")
        moved = ladder_change(ladder)
        lines.append("  over the last refinement: " + ", ".join(
            f"{q} {100 * v:+.2f} %" + (" (moves more than the bound)" if abs(v) > CONVERGED.get(q, 1.0) else "")
            for q, v in moved.items() if q != "bands_um"))
        lines.append(f"  ours: TE {ours['te']:.3f}, c {ours['stiffness']:.3f}, p {ours['flank_pressure']:.0f} "
                     f"({100 * (ours['flank_pressure'] / ladder[-1]['flank_pressure'] - 1):+.1f} %), sF "
                     f"{ours['root_pinion']:.1f} {ours['root_gear']:.1f}")
    print("\n".join(lines))
    rec.setdefault("merged", []).append({
        "command": command or "", "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "calculix_version": ccx_version(), "positions": [ladder_key(r) for r in rolls], "refine": refine,
        "ours_compliance_wall_s": t_prepare})
    path.write_text(json.dumps(finite(rec), indent=1, allow_nan=False) + "\n")
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="python3 -m tools.calculix_refs.merge_whole",
                                description="Refine positions of a frozen whole-gear reference by rungs of 1.5 beyond "
                                            "the band each was frozen at and merge them into it, with their ladders.")
    p.add_argument("merge", metavar="FILE", help="the frozen reference (JSON), rewritten in place")
    p.add_argument("--case", default="cases/fzg_c14.toml", help="its case file (default cases/fzg_c14.toml)")
    p.add_argument("--positions", type=float, nargs="+", metavar="DEG", help="frozen rolls to refine, deg")
    p.add_argument("--out", default="out/whole_freeze", help="CalculiX runs, kept and reused (default out/whole_freeze)")
    p.add_argument("--refine", type=int, default=1, help="rungs of 1.5 beyond the frozen band (1 to 3; default 1)")
    p.add_argument("--fidelity", choices=["coarse", "default", "fine"], default="default", help="our fidelity")
    p.add_argument("--coarse-body", action="store_true", help="the coarse CalculiX body the file was frozen with")
    p.add_argument("--threads", type=int, default=2, help="CalculiX threads (default 2)")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    return p


def main(argv: list[str] | None = None) -> int:
    import sys
    argv = sys.argv[1:] if argv is None else argv

    def work(a):
        return run_whole_merge(a.case, a.positions, a.out, a.merge, refine=a.refine, fidelity=a.fidelity,
                               command=command_line("tools.calculix_refs.merge_whole", argv), progress=not a.quiet,
                               threads=a.threads, body="coarse" if a.coarse_body else "default")
    return run(build_parser(), work, argv)


if __name__ == "__main__":
    raise SystemExit(main())
