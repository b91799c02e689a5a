"""The ``ltca`` command: run, tca, export, import, convert, forming, study, optimise, convergence, validate, bench,
budget, chain.

User mistakes (bad case files, bad arguments) end with exit status 2 and one message naming the
field, its value and what is allowed; no traceback. A solver that does not converge ends with
status 3 and its residual. ``ltca optimise`` whose constraints no candidate meets ends with status 4
(:data:`NO_FEASIBLE_DESIGN`): the least infeasible design is written, marked ``feasible: false``.
"""
from __future__ import annotations

import argparse
import contextlib
import os
import sys
from pathlib import Path

from .errors import CaseError, ConvergenceError
from .shipped import case_path

__all__ = ["main", "build_parser", "NO_FEASIBLE_DESIGN"]

#: exit status of ``ltca optimise`` when no candidate meets the constraints
NO_FEASIBLE_DESIGN = 4


def _planetary(path: str) -> bool:
    from .case import read_toml
    return "satellite" in read_toml(path)


def _cmd_forming(a: argparse.Namespace) -> int:
    from .planetary.run import run_forming
    run_forming(a.case, out=a.out)
    return 0


def _cmd_run(a: argparse.Namespace) -> int:
    from .driver import run_to_dir
    run_to_dir(a.case, a.out, fidelity=a.fidelity, positions=a.positions, progress=not a.quiet, cache=a.cache,
               resume=a.resume, max_output_gb=a.max_output_gb, torques=a.torque, paraview_steps=a.paraview_steps)
    return 0


def _cmd_tca(a: argparse.Namespace) -> int:
    from .case import read_toml
    if _planetary(a.case):
        from .planetary.run import run_planetary_tca
        run_planetary_tca(a.case, out=a.out, n_positions=a.positions)
        return 0
    if "bevel" in read_toml(a.case):
        from .bevel.run import run_bevel_tca
        run_bevel_tca(a.case, out=a.out)
        return 0
    from .cylindrical.run import run_tca
    run_tca(a.case, out=a.out, positions=a.positions)
    return 0


def _cmd_study(a: argparse.Namespace) -> int:
    from .study import run_study
    ds = run_study(a.study, a.out, scheduler=a.scheduler, workers=a.workers, progress=not a.quiet,
                   plots=not a.no_plots)
    import json
    run = json.loads(ds.attrs["run"])
    print(json.dumps({k: run[k] for k in ("points_total", "points_computed", "points_skipped",
                                          "compliance_computed", "compliance_loaded", "wall_s")}, indent=1))
    return 3 if run["failed"] else 0


def _is_bevel(path: str) -> bool:
    from .case import read_toml
    return "bevel" in read_toml(path)


def _cmd_convergence(a: argparse.Namespace) -> int:
    if _is_bevel(a.case):
        from .verify.bevel_check import run_bevel_convergence
        run_bevel_convergence(a.case, out=a.out, positions=a.positions, progress=not a.quiet)
        return 0
    from .verify.convergence import run_convergence
    run_convergence(a.case, out=a.out, positions=a.positions, progress=not a.quiet)
    return 0


def _cmd_validate(a: argparse.Namespace) -> int:
    if a.reference == "analytic" and a.case and _is_bevel(a.case):
        from .verify.bevel_check import run_bevel_validate
        return run_bevel_validate(a.case, a.out, progress=not a.quiet)
    if a.reference == "analytic":
        from .verify.validate import run_validate
        return run_validate(out=a.out, progress=not a.quiet)
    a.case = a.case or str(case_path("fzg_c14"))
    from ltca.fem.calculix.run import CcxNotFound
    try:
        if a.reference == "calculix" and _is_bevel(a.case):
            if a.torque is not None and not 0 < a.torque <= 1e5:
                raise CaseError("--torque", a.torque, "one pinion torque in (0, 1e5] N m")
            from .verify.bevel_calculix import run_bevel_validation
            return run_bevel_validation(a.case, tuple(a.positions or (0.0, 0.4)), a.out, level=a.level,
                                        h0=1e-3 * (a.band or 250.0), progress=not a.quiet, torque=a.torque,
                                        threads=a.threads)
        if a.reference == "calculix-whole" and _planetary(a.case):
            from .verify.planetary_whole import run_planetary_whole_validation
            return run_planetary_whole_validation(a.case, a.positions or [-1.8], a.torque, a.out, band_um=a.band,
                                                  fidelity=a.fidelity, progress=not a.quiet, cache=a.cache)
        if a.reference == "calculix-whole":
            from .verify.whole_check import run_whole_validation
            return run_whole_validation(a.case, a.positions, a.out, band_um=a.band, fidelity=a.fidelity or "default",
                                        progress=not a.quiet, threads=a.threads,
                                        body="coarse" if a.coarse_body else "default")
        from .verify.crosscheck import run_calculix_validation
        return run_calculix_validation(a.case, a.positions, a.out, level=a.level, band_um=a.band,
                                       coarse_body=a.coarse_body, progress=not a.quiet)
    except CcxNotFound as exc:
        print(f"ltca validate: {exc}", file=sys.stderr)
        return 2


def _cmd_bench(a: argparse.Namespace) -> int:
    if _is_bevel(a.case):
        from .verify.bevel_check import run_bevel_bench
        run_bevel_bench(a.case, repeat=a.repeat, positions=a.positions or 21, fidelity=a.fidelity or "default")
        return 0
    from .verify.bench import run_bench
    run_bench(a.case, repeat=a.repeat, positions=a.positions, fidelity=a.fidelity)
    return 0


def _cmd_budget(a: argparse.Namespace) -> int:
    from .drivetrain.budget import run_budget
    run_budget(a.case, a.out)
    return 0


def _cmd_chain(a: argparse.Namespace) -> int:
    from .drivetrain.chain import run_chain
    run_chain(a.case, a.out)
    return 0


def _cmd_optimise(a: argparse.Namespace) -> int:
    from .design import optimise
    res = optimise(a.case, a.out, resume=a.resume, progress=not a.quiet, full_runs=not a.no_full_runs,
                   workers=a.workers)
    import json
    s = res.summary
    feasible = bool(s["optimum"].get("feasible", True))
    best = "optimum" if feasible else "least_infeasible"
    print(json.dumps({best: s["optimum"]["values"], "feasible": feasible, "objective_arcsec": {
        k: s[k]["objective_arcsec"] for k in ("baseline", "start", "optimum")}, "evaluations": s["evaluations"],
        "timings_s": s["timings_s"]}, indent=1))
    if not feasible:
        c = s.get("constraints", {})
        limits = ", ".join(f"{k} {v:g}" for k, v in c.items() if isinstance(v, (int, float)) and not
                           isinstance(v, bool)) or "the [design.constraints]"
        n = s["evaluations"].get("search", "?") if isinstance(s["evaluations"], dict) else s["evaluations"]
        print(f"ltca optimise: no feasible design: none of the {n} candidates searched meets the constraints "
              f"({limits}); {res.out}/design.json holds the least infeasible one (feasible: false); relax "
              "[design.constraints] or widen [design.variables]", file=sys.stderr)
        return NO_FEASIBLE_DESIGN
    return 0


def _cmd_import(a: argparse.Namespace) -> int:
    from .rexs.cli import import_command
    return import_command(a.file, stage=a.stage, out=a.out, list_only=a.list, torque=a.torque)


def _cmd_export(a: argparse.Namespace) -> int:
    if a.step is None and a.hfm is None:
        raise CaseError("--step", None, "give --step DIR (STEP solids) and/or --hfm FILE (a bevel pair's "
                        "HypoidFaceMilled script)")
    if a.hfm is not None:
        if not _is_bevel(a.case):
            raise CaseError("--hfm", a.hfm, "a bevel case's pair (the script holds face-milled bevel members)")
        from .bevel.hfm_export import export_hfm
        print(f"{export_hfm(a.case, a.hfm)}\tHypoidFaceMilled script (blank, machine and cutter blocks)")
    if a.step is not None:
        from .export import export_step
        res = export_step(a.case, a.step, progress=None if a.quiet else print)
        for m in res.members:
            print(f"{m.path}\t{m.member}\t{m.z} teeth\t{m.volume:.1f} mm^3")
    return 0


def _cmd_convert(a: argparse.Namespace) -> int:
    from .bevel.case import bevel_case_from_data, check_bevel_torques
    from .bevel.hfm_case import case_data, case_toml
    from .bevel.hfm_script import read_hfm
    torques = list(check_bevel_torques(list(a.torque), "--torque")) if a.torque else None
    data, notes = case_data(read_hfm(a.file), torques=torques)
    bevel_case_from_data(data, a.file)             # every check of a case file, before anything is written
    text = case_toml(data, notes, a.file)
    if a.out is None:
        print(text, end="")
    else:
        Path(a.out).write_text(text, encoding="utf-8")
        print(f"wrote {a.out} ({len(notes)} value(s) of the script not carried as written, listed in the file)")
    return 0


def _cmd_keys(a: argparse.Namespace) -> int:
    from .keys import keys_markdown, keys_text, kind_json_schema
    if a.json_schema:
        import json
        print(json.dumps(kind_json_schema(a.json_schema), indent=1))
        return 0
    print(keys_markdown(a.table, a.kind) if a.markdown else keys_text(a.table, a.kind), end="")
    return 0


def _nonnegative_int(text: str) -> int:
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not an integer") from None
    if not 0 <= v <= 100000:
        raise argparse.ArgumentTypeError(f"{v}: must be in [0, 100000]")
    return v


def _positive_int(text: str) -> int:
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not an integer") from None
    if v < 1:
        raise argparse.ArgumentTypeError(f"{v}: must be >= 1")
    return v


def _positions(text: str) -> int:
    """Mesh positions per cycle on the command line: capped as analysis.positions in a case file."""
    from .sizing import MAX_POSITIONS
    v = _positive_int(text)
    if v > MAX_POSITIONS:
        raise argparse.ArgumentTypeError(f"{v}: must be in [1, {MAX_POSITIONS}] (as analysis.positions)")
    return v


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="ltca", description="Finite-element loaded tooth contact analysis of gears.")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND", parser_class=_Parser)

    r = sub.add_parser("run", help="loaded TCA over a mesh cycle: TE, bearing pattern, load sharing, root stress",
                       description="Loaded tooth contact analysis of a case over one mesh cycle. Writes "
                                   "summary.json, results.nc, PNG plots, report.html (one self-contained page), "
                                   "a VTU and the ParaView series paraview.pvd into --out.")
    r.add_argument("case", help="case file (.toml) or a shipped case's name, e.g. fzg_c14")
    r.add_argument("--out", default="out", help="output directory (default: out)")
    r.add_argument("--fidelity", choices=["coarse", "default", "fine"], help="override the case's fidelity")
    r.add_argument("--positions", type=_positions, help="mesh positions per cycle (override, at most 2000)")
    r.add_argument("--torque", type=float, nargs="+", metavar="NM",
                   help="pinion torque(s) in N m, one analysis each; replaces the case's [load] torque_nm "
                        "(e.g. --torque 100 200 300)")
    r.add_argument("--resume", action="store_true",
                   help="take over the positions an interrupted run on the same --out finished; compute the rest")
    r.add_argument("--max-output-gb", type=float, default=2.0, metavar="GB",
                   help="refuse a run whose results and memory are estimated above this (default 2 GB)")
    r.add_argument("--cache", default=None, help="directory for the mesh cache (default: none, cold run)")
    r.add_argument("--paraview-steps", type=_nonnegative_int, default=None, metavar="N",
                   help="positions of the first torque in the ParaView series paraview.pvd (displacement, stress, "
                        "flank pressure; every gear kind), spread over the cycle with the pitch (bevel: mean) "
                        "position; 0: none, more than the positions: all (default 10; FZG C14: about 0.15 s and "
                        "1.3 MB per position)")
    r.add_argument("--quiet", action="store_true", help="no progress output")
    r.set_defaults(func=_cmd_run)

    im = sub.add_parser("import", help="a gear stage of a REXS model (.rexs, .rexsj, .rexsz) as a case file",
                        description="Reads a REXS model (XML .rexs, JSON .rexsj or zipped .rexsz; REXS 1.x or 2.0) "
                                    "and writes one cylindrical stage as a TOML case that `ltca run` accepts; "
                                    "--list lists the stages and what the file holds that a case cannot.")
    im.add_argument("file", help="REXS model file")
    im.add_argument("--stage", type=int, help="component id of the cylindrical_stage to import")
    im.add_argument("--out", help="case file to write (default: print the case)")
    im.add_argument("--list", action="store_true", help="list the stages (id, gears, torques) and the unmapped "
                                                        "attributes")
    im.add_argument("--torque", type=float, nargs="+", metavar="NM",
                    help="pinion torque(s) in N m, replacing the torques of the model's load cases")
    im.set_defaults(func=_cmd_import)

    ex = sub.add_parser("export", help="solid models: each member with every tooth as a STEP file (CAD, CAM, FE)",
                        description="Writes each member of a cylindrical or bevel case, every tooth, as an "
                                    "OpenCASCADE solid in a STEP file (mm, the member's body frame), and prints "
                                    "each file with its volume. A bevel member takes minutes (one boolean fuse "
                                    "of all teeth with the blank). --hfm writes a bevel pair's settings as a "
                                    "HypoidFaceMilled / Transmission3D input script (`ltca convert` reads it back).")
    ex.add_argument("case", help="case file (.toml) or a shipped case's name")
    ex.add_argument("--step", metavar="DIR", help="folder for the STEP files (made if missing)")
    ex.add_argument("--hfm", metavar="FILE", help="a bevel pair's HypoidFaceMilled / Transmission3D script: blank, "
                    "machine and cutter blocks of both members (given or synthesised settings)")
    ex.add_argument("--quiet", action="store_true", help="no progress lines")
    ex.set_defaults(func=_cmd_export)

    cv = sub.add_parser("convert", help="a HypoidFaceMilled / Transmission3D script as a bevel case file",
                        description="Reads the blank, machine and cutter blocks of both members of a "
                                    "HypoidFaceMilled / Transmission3D input script and writes the pair as a bevel "
                                    "case (its settings sheets as given) that `ltca run` accepts. The program's other "
                                    "menus are skipped (-v lists them); blank values the case's designed blank does "
                                    "not reproduce are listed in the file.")
    cv.add_argument("file", help="the script (text)")
    cv.add_argument("--out", help="case file to write (default: print the case)")
    cv.add_argument("--torque", type=float, nargs="+", metavar="NM",
                    help="pinion torque(s) in N m for the case's [load] (> 0 drives on the pinion's concave flank)")
    cv.set_defaults(func=_cmd_convert)

    k = sub.add_parser("keys", help="reference of every case key: unit, default, allowed range, meaning",
                       description="Prints every key of the case files of every kind (cylindrical, bevel, "
                                   "planetary, budget, chain, study, design), walked from the tables each kind "
                                   "declares in ltca/validation.py: type, unit, default, allowed range and meaning. "
                                   "docs/case_keys.md is `ltca keys --markdown`.")
    k.add_argument("table", nargs="?", default=None,
                   help="only this table, e.g. load, pinion, pinion.modifications, member (default: every table)")
    k.add_argument("--kind", action="append", metavar="KIND",
                   help="only this kind (repeatable): cylindrical, bevel, planetary, budget, chain, study, design")
    k.add_argument("--markdown", action="store_true", help="print Markdown tables (docs/case_keys.md)")
    k.add_argument("--json-schema", metavar="KIND",
                   help="print the JSON Schema of a kind's case file, for a TOML editor's completion and checks "
                        "(a first line '#:schema FILE.json' in the case)")
    k.set_defaults(func=_cmd_keys)

    o = sub.add_parser("optimise", help="design optimisation driven by the LTCA: the [design] table's variables",
                       description="Searches the [design] variables of a case (flank modifications of a cylindrical "
                                   "pair) for the smallest loaded TE peak-to-peak under the constraints, each "
                                   "candidate a loaded analysis on a compliance computed once. Writes design.json, "
                                   "history.jsonl, settings.csv, the optimum's case file and LTCA outputs, the "
                                   "Harris map and the objective map into --out.")
    o.add_argument("case", help="case file (.toml) with a [design] table, or a shipped case's name")
    o.add_argument("--out", default="out/optimise", help="output directory (default: out/optimise)")
    o.add_argument("--resume", action="store_true",
                   help="take over the candidates an interrupted run on the same --out finished; go on from there")
    o.add_argument("--no-full-runs", action="store_true",
                   help="skip the full LTCA of the optimum (ltca run with a fresh compliance)")
    o.add_argument("--workers", type=_positive_int, default=None,
                   help="processes for the objective map and the Harris curves (default: the cores, at most 2)")
    o.add_argument("--quiet", action="store_true", help="no progress output")
    o.set_defaults(func=_cmd_optimise)

    t = sub.add_parser("tca", help="unloaded tooth contact analysis (separation, path, TE, contact ratio)",
                       description="Unloaded TCA: separation field, contact path, unloaded TE, contact ratio. "
                                   "A case with a [bevel] table: spiral bevel pinion synthesis from eta2 and m21 "
                                   "and the TCA of both flanks, with a Gleason-style settings summary.")
    t.add_argument("case", help="case file (.toml): cylindrical, [bevel] or [satellite]; or a shipped case's name")
    t.add_argument("--out", default=None, help="output directory for summary.json and plots")
    t.add_argument("--positions", type=_positions, help="mesh positions per cycle (override, at most 2000)")
    t.set_defaults(func=_cmd_tca)

    s = sub.add_parser("study", help="load-case and tolerance studies on Dask (grid, variants, Monte Carlo)",
                       description="Runs every variant of a study file (over a cylindrical or a bevel case) at "
                                   "every torque on a Dask cluster: one compliance per geometry (a bevel pair: per "
                                   "loaded flank, whatever the assembly errors), each point written as it "
                                   "finishes (a rerun skips them). Writes study.nc, summary.csv, plots and "
                                   "run.json into --out.")
    s.add_argument("study", help="study file (.toml) or a shipped study's name, e.g. fzg_torque_misalignment")
    s.add_argument("--out", default="out/study", help="output directory (default: out/study)")
    s.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="address of a running Dask scheduler, e.g. tcp://127.0.0.1:8786 (default: a LocalCluster)")
    s.add_argument("--workers", type=_positive_int, default=None,
                   help="workers of the LocalCluster (default: the cores of this machine)")
    s.add_argument("--no-plots", action="store_true", help="summary CSV and store only")
    s.add_argument("--quiet", action="store_true", help="no progress output")
    s.set_defaults(func=_cmd_study)
    f = sub.add_parser("forming", help="satellite forming methods compared (eccentric planetary): table, CSV, "
                                       "overlay plot",
                       description="Cuts the satellite of a [satellite] case by the standard hob in three passes, "
                                   "the disk cutter and the special hob; prints thickness against Eq. 3, tip land, "
                                   "dedendum, fillet and the deviation from the special hob; writes forming.csv and "
                                   "forming.png into --out.")
    f.add_argument("case", help="case file (.toml) with a [satellite] table, or a shipped case's name")
    f.add_argument("--out", default=None, help="output directory for forming.csv and forming.png")
    f.set_defaults(func=_cmd_forming)

    c = sub.add_parser("convergence", help="time against error over a ladder of fidelities",
                       description="Runs a ladder of fidelities (flank element size, contact grid, near-field "
                                   "correction on/off) and prints wall time against the error in loaded TE, "
                                   "peak pressure and root stress relative to the finest.")
    c.add_argument("case", help="case file (.toml) or a shipped case's name")
    c.add_argument("--out", default="out/convergence", help="output directory (default: out/convergence)")
    c.add_argument("--positions", type=_positions, default=8, help="mesh positions per cycle (default 8)")
    c.add_argument("--quiet", action="store_true", help="no progress output")
    c.set_defaults(func=_cmd_convergence)

    v = sub.add_parser("validate", help="run the validation cases: measured vs reference, error, time",
                       description="Runs the validation cases and prints measured vs reference, error and time. "
                                   "CalculiX's refinement ladders and the frozen references of the tests are "
                                   "maintainer tooling in the repository (tools/calculix_refs), not installed.")
    v.add_argument("--out", default="out/validate", help="output directory (default: out/validate)")
    v.add_argument("--reference", choices=["analytic", "calculix", "calculix-whole"], default="analytic",
                   help="analytic references and tables (default); calculix: the CalculiX cross-check on our body "
                        "(5-15 min per position on 2 cores), on a [bevel] case CalculiX on both whole members; "
                        "calculix-whole: CalculiX on whole gears with every tooth and their own supports, independent "
                        "of our body (7-25 min per CalculiX run on one thread of a busy machine, FZG C14)")
    v.add_argument("--case", default=None,
                   help="case for --reference calculix (default cases/fzg_c14.toml); a [bevel] case with the "
                        "analytic reference runs the bevel checks (elliptic Hertz, light-load limit, V-H table)")
    v.add_argument("--positions", type=float, nargs="+", metavar="DEG",
                   help="pinion roll angles from the pitch point for --reference calculix (default 0 +-4.5 +-9); a "
                        "[bevel] case: pinion angles in mesh cycles from the mean point (default 0 0.4)")
    v.add_argument("--level", type=int, default=1,
                   help="calculix: CalculiX's contact band is --band refined this many times by 1.5 (0 to 4; "
                        "default 1)")
    v.add_argument("--band", type=float, metavar="UM",
                   help="CalculiX contact-band element size, um (default 3/4 of the Hertz half-width; a [bevel] case "
                        "250, a [satellite] case 600)")
    v.add_argument("--coarse-body", action="store_true",
                   help="CalculiX elements of our coarse fidelity away from the contact band (0.45 x module on "
                        "the flank, 1.6 x module in the body; calculix-whole: flanks with a contact line 0.45, other "
                        "teeth 0.75, body 1.6, loaded fillets 0.225 x module, the band's growth x 1.5: a wide face)")
    v.add_argument("--fidelity", choices=["coarse", "default", "fine"], default=None,
                   help="our fidelity for --reference calculix-whole (default: default; a [satellite] case: its own)")
    v.add_argument("--torque", type=float, default=None, metavar="NM",
                   help="calculix on a [bevel] case: the pinion torque, N m (default: the case's middle torque); "
                        "calculix-whole on a [satellite] case: the satellite torque, N m (required there)")
    v.add_argument("--cache", default=None, help="calculix-whole on a [satellite] case: our mesh cache directory")
    v.add_argument("--threads", type=int, default=2,
                   help="calculix-whole and the bevel calculix check: CalculiX threads (OMP_NUM_THREADS, "
                        "CCX_NPROC_EQUATION_SOLVER; default 2)")
    v.add_argument("--quiet", action="store_true", help="no progress output")
    v.set_defaults(func=_cmd_validate)

    be = sub.add_parser("bench", help="cold wall time of an analysis (median of runs) beside its Hertz error",
                        description="Runs the case cold several times and prints the median time per stage and "
                                    "the pitch-point error against Hertz.")
    be.add_argument("case", help="case file (.toml) or a shipped case's name")
    be.add_argument("--repeat", type=_positive_int, default=3, help="cold runs; the median is reported (default 3)")
    be.add_argument("--positions", type=_positions, help="mesh positions per cycle (default: the case's)")
    be.add_argument("--fidelity", choices=["coarse", "default", "fine"], help="override the case's fidelity")
    be.set_defaults(func=_cmd_bench)

    b = sub.add_parser("budget", help="drive-train stiffness and backlash budget (Wang et al.)",
                       description="Torsional deflection of a drive train of members in series, per torque.")
    b.add_argument("case", help="budget case file (.toml) with [budget] and [[member]] tables, or a shipped "
                   "case's name")
    b.add_argument("--out", default=None, help="output directory for the CSV and plots (default: print only)")
    b.set_defaults(func=_cmd_budget)

    ch = sub.add_parser("chain", help="machine kinematic-chain ratio errors (indexing and generating chains)",
                        description="Ratio errors of indexing and generating chains and the tooth errors they make.")
    ch.add_argument("case", help="chain case file (.toml) with [[chain]] and [workpiece] tables, or a shipped "
                    "case's name")
    ch.add_argument("--out", default=None, help="output directory for the CSV tables (default: print only)")
    ch.set_defaults(func=_cmd_chain)
    verbose = ("diagnostics on stderr: -v the run's summary, each position's rounds, widenings and residual, the "
               "mesh cache; -vv also the debug messages")
    p.add_argument("-v", "--verbose", action="count", default=0, help=verbose)
    for c in sub.choices.values():
        c.add_argument("-v", "--verbose", action="count", default=0, dest="verbose_here", help=verbose)
    return p


def _resolve_files(a: argparse.Namespace) -> None:
    """A CASE or STUDY argument that is not a file but a shipped case's or study's name: that file
    (:mod:`ltca.shipped`). Anything else stays as given: the command's reader names what is missing."""
    from pathlib import Path

    from .shipped import study_path
    if getattr(a, "case", None) and not Path(a.case).exists():
        with contextlib.suppress(CaseError):
            a.case = str(case_path(a.case))
    if a.command == "study" and not Path(a.study).exists():
        with contextlib.suppress(CaseError):
            a.study = str(study_path(a.study))


def _check_out_file(path: Path, option: str = "--out") -> None:
    """A file an option names for writing: not a folder, in a folder that exists and can be written."""
    if path.is_dir():
        raise CaseError(option, str(path), "a file to write, not a folder")
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise CaseError(option, str(path), f"a file in an existing folder ({folder} does not exist)")
    if not os.access(folder, os.W_OK):
        raise CaseError(option, str(path), f"a file in a writable folder ({folder} is not writable)")


def _check_options(a: argparse.Namespace) -> None:
    """Command-line options validated like case fields: CaseError (one line: option, value, allowed; exit 2)
    before any work."""

    from .validation import Int, Num
    if getattr(a, "workers", None) is not None:
        Int(1, 256, note="worker processes").check(a.workers, "--workers", None)
    if getattr(a, "repeat", None) is not None:
        Int(1, 1000, note="cold runs").check(a.repeat, "--repeat", None)
    if getattr(a, "max_output_gb", None) is not None:
        Num(0, 1e4, "GB", lo_open=True).check(a.max_output_gb, "--max-output-gb", None)
    if a.command == "run" and a.torque is not None:
        if _is_bevel(a.case):
            from .bevel.case import check_bevel_torques
            check_bevel_torques(list(a.torque), "--torque")
        else:
            from .case import check_torques
            check_torques(list(a.torque), "--torque")
    if a.command == "validate":
        if a.torque is not None:
            Num(0, 1e6, "N m", lo_open=True).check(a.torque, "--torque", None)
        if a.band is not None:
            Num(0, 1e4, "um", lo_open=True).check(a.band, "--band", None)
        for opt, lo, hi in (("level", 0, 8), ("threads", 1, 256)):
            if getattr(a, opt) is not None:
                Int(lo, hi).check(getattr(a, opt), f"--{opt}", None)
        for i, x in enumerate(a.positions or ()):
            Num(-360, 360, "deg or cycles").check(x, f"--positions[{i}]", None)
    out = getattr(a, "out", None)
    if out is not None and not str(out).strip():
        raise CaseError("--out", out, "a non-empty path")
    if out is not None and a.command in ("import", "convert"):
        _check_out_file(Path(out))
    elif out is not None:                   # every command that writes a folder: refused before any work
        from .outputs import check_out_dir
        check_out_dir(out)
    if getattr(a, "hfm", None) is not None:
        if not a.hfm.strip():
            raise CaseError("--hfm", a.hfm, "a non-empty path")
        _check_out_file(Path(a.hfm), "--hfm")
    if getattr(a, "cache", None) is not None:
        if not a.cache.strip():
            raise CaseError("--cache", a.cache, "a folder for the mesh cache (a non-empty path)")
        from .outputs import check_out_dir
        check_out_dir(a.cache, "--cache")
    if getattr(a, "scheduler", None) is not None:
        from .study.runner import check_scheduler_address
        check_scheduler_address(a.scheduler)


class _Parser(argparse.ArgumentParser):
    """argparse with its error as one line (``ltca run: error: argument --positions: ...``), exit status 2."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def main(argv: list[str] | None = None) -> int:
    import matplotlib
    matplotlib.use("Agg")       # the command line writes files; the library never picks a backend
    args = build_parser().parse_args(argv)
    _logging(max(args.verbose, getattr(args, "verbose_here", 0)))
    try:
        _resolve_files(args)
        _check_options(args)
        return int(args.func(args) or 0)
    except CaseError as exc:
        print(f"ltca {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except ConvergenceError as exc:
        print(f"ltca {args.command}: not converged: {exc}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # noqa: BLE001 - the one place that sorts every failure into an exit status
        return _unexpected(args.command, exc)


def _logging(level: int) -> None:
    """Route the library's diagnostics (the ``ltca`` loggers) to stderr: INFO and above with -v, DEBUG with -vv;
    without -v the command's own tables and warnings say what matters and the loggers stay silent."""
    import logging
    root = logging.getLogger("ltca")
    root.handlers = [h for h in root.handlers if not getattr(h, "_ltca_cli", False)]
    if level <= 0:
        root.setLevel(logging.NOTSET)
        return
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("ltca: %(levelname)s: %(name)s: %(message)s"))
    handler._ltca_cli = True
    root.addHandler(handler)
    root.setLevel(logging.INFO if level == 1 else logging.DEBUG)


def _unexpected(command: str, exc: BaseException) -> int:
    """Exceptions that are not CaseError/ConvergenceError: a user's design the geometry cannot make (exit 2, with
    the fields and advice), a full disk (exit 2), a solver that did not converge (exit 3), or a bug (traceback)."""
    from .exit_codes import classify
    status, message = classify(exc)
    if status == 1:
        import traceback
        traceback.print_exc()
        print(f"ltca {command}: internal error ({type(exc).__name__}); this is a bug: please report it with the "
              "case file and the command line", file=sys.stderr)
        return 1
    print(f"ltca {command}: {'error' if status == 2 else 'not converged'}: {message}", file=sys.stderr)
    return status


if __name__ == "__main__":
    sys.exit(main())
