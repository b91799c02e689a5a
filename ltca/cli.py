"""The ``ltca`` command: run, tca, import, forming, study, optimise, convergence, validate, bench, budget, chain.

User mistakes (bad case files, bad arguments) end with exit status 2 and one message naming the
field, its value and what is allowed; no traceback. A solver that does not converge ends with
status 3 and its residual.
"""
from __future__ import annotations

import argparse
import sys

from .errors import CaseError, ConvergenceError

__all__ = ["main", "build_parser"]


def _planetary(path: str) -> bool:
    from .case import read_toml
    return "satellite" in read_toml(path)


def _cmd_forming(a: argparse.Namespace) -> int:
    from .planetary.run import run_forming
    run_forming(a.case, out=a.out)
    return 0


def _cmd_run(a: argparse.Namespace) -> int:
    from .case import read_toml
    if "bevel" in read_toml(a.case):
        from .bevel.analysis import run_bevel_ltca
        run_bevel_ltca(a.case, out=a.out, positions=a.positions, fidelity=a.fidelity, torques=a.torque,
                       progress=not a.quiet, cache=a.cache)
        return 0
    if _planetary(a.case):
        from .planetary.run import run_planetary
        run_planetary(a.case, out=a.out, fidelity=a.fidelity, n_positions=a.positions, progress=not a.quiet,
                      cache=a.cache, torques_nm=a.torque)
        return 0
    from .cylindrical.run import run_case
    run_case(a.case, out=a.out, fidelity=a.fidelity, positions=a.positions, progress=not a.quiet,
             cache=a.cache, resume=a.resume, max_output_gb=a.max_output_gb, torques=a.torque,
             paraview_steps=a.paraview_steps)
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
    a.case = a.case or "cases/fzg_c14.toml"
    if a.reference == "calculix" and _is_bevel(a.case):
        if a.torque is not None and not 0 < a.torque <= 1e5:
            raise CaseError("--torque", a.torque, "one pinion torque in (0, 1e5] N m")
        from fem.calculix.run import CcxNotFound
        from .verify.bevel_calculix import run_bevel_validation
        from .verify.whole_check import command_line
        try:
            return run_bevel_validation(a.case, tuple(a.positions or (0.0, 0.4)), a.out,
                                        refine=2 if a.refine is None else a.refine, level=a.level,
                                        h0=1e-3 * (a.band or 250.0), freeze=a.freeze,
                                        command=command_line(sys.argv[1:]), progress=not a.quiet,
                                        torque=a.torque, threads=a.threads)
        except CcxNotFound as exc:
            print(f"ltca validate: {exc}", file=sys.stderr)
            return 2
    if a.reference == "calculix-whole" and _planetary(a.case):
        from fem.calculix.run import CcxNotFound
        from .verify.planetary_whole import run_planetary_whole_validation
        from .verify.whole_check import command_line
        try:
            return run_planetary_whole_validation(a.case, a.positions or [-1.8], a.torque, a.out, band_um=a.band,
                                                  refine=1 if a.refine is None else a.refine, fidelity=a.fidelity,
                                                  freeze=a.freeze, command=command_line(sys.argv[1:]),
                                                  progress=not a.quiet, cache=a.cache)
        except CcxNotFound as exc:
            print(f"ltca validate: {exc}", file=sys.stderr)
            return 2
    if a.reference == "calculix-whole" and a.merge:
        from fem.calculix.run import CcxNotFound
        from .verify.whole_check import command_line
        from .verify.whole_merge import run_whole_merge
        try:
            return run_whole_merge(a.case, a.positions, a.out, a.merge, refine=1 if a.refine is None else a.refine,
                                   fidelity=a.fidelity or "default", command=command_line(sys.argv[1:]),
                                   progress=not a.quiet, threads=a.threads,
                                   body="coarse" if a.coarse_body else "default")
        except CcxNotFound as exc:
            print(f"ltca validate: {exc}", file=sys.stderr)
            return 2
    if a.reference == "calculix-whole":
        from fem.calculix.run import CcxNotFound
        from .verify.whole_check import command_line, run_whole_validation
        try:
            return run_whole_validation(a.case, a.positions, a.out, band_um=a.band,
                                        refine=1 if a.refine is None else a.refine,
                                        fidelity=a.fidelity or "default", freeze=a.freeze,
                                        command=command_line(sys.argv[1:]), progress=not a.quiet,
                                        threads=a.threads, ladder=a.ladder,
                                        body="coarse" if a.coarse_body else "default")
        except CcxNotFound as exc:
            print(f"ltca validate: {exc}", file=sys.stderr)
            return 2
    if a.reference == "calculix":
        from fem.calculix.run import CcxNotFound
        from .verify.crosscheck import run_calculix_validation
        try:
            return run_calculix_validation(a.case, a.positions, a.out, refine=2 if a.refine is None else a.refine,
                                           level=a.level,
                                           band_um=a.band, coarse_body=a.coarse_body, pressure=a.pressure_ladder,
                                           progress=not a.quiet)
        except CcxNotFound as exc:
            print(f"ltca validate: {exc}", file=sys.stderr)
            return 2
    from .verify.validate import run_validate
    return run_validate(out=a.out, progress=not a.quiet)


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
    print(json.dumps({"optimum": s["optimum"]["values"], "objective_arcsec": {
        k: s[k]["objective_arcsec"] for k in ("baseline", "start", "optimum")}, "evaluations": s["evaluations"],
        "timings_s": s["timings_s"]}, indent=1))
    return 0


def _cmd_import(a: argparse.Namespace) -> int:
    from .rexs.cli import import_command
    return import_command(a.file, stage=a.stage, out=a.out, list_only=a.list, torque=a.torque)


def _cmd_keys(a: argparse.Namespace) -> int:
    from .keys import keys_markdown, keys_text
    print(keys_markdown(a.table) if a.markdown else keys_text(a.table), end="")
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
    p = argparse.ArgumentParser(prog="ltca", description="Finite-element loaded tooth contact analysis of gears.")
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    r = sub.add_parser("run", help="loaded TCA over a mesh cycle: TE, bearing pattern, load sharing, root stress",
                       description="Loaded tooth contact analysis of a case over one mesh cycle. Writes "
                                   "summary.json, results.nc, PNG plots, report.html (one self-contained page), "
                                   "a VTU and the ParaView series paraview.pvd into --out.")
    r.add_argument("case", help="case file (.toml)")
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
    r.add_argument("--paraview-steps", type=_nonnegative_int, default=10, metavar="N",
                   help="positions of the first torque in the ParaView series paraview.pvd (displacement, stress, "
                        "flank pressure), spread over the cycle with the pitch position; 0: none, more than the "
                        "positions: all (default 10; FZG C14: about 0.15 s and 1.3 MB per position)")
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

    k = sub.add_parser("keys", help="reference of every case key: unit, default, allowed range, meaning",
                       description="Prints every key of a cylindrical case file (generated from the schema in "
                                   "ltca/case.py): type, unit, default, allowed range and meaning. "
                                   "docs/case_keys.md is `ltca keys --markdown`.")
    k.add_argument("table", nargs="?", default=None,
                   help="only this table, e.g. load, pinion, pinion.modifications (default: every table)")
    k.add_argument("--markdown", action="store_true", help="print Markdown tables (docs/case_keys.md)")
    k.set_defaults(func=_cmd_keys)

    o = sub.add_parser("optimise", help="design optimisation driven by the LTCA: the [design] table's variables",
                       description="Searches the [design] variables of a case (flank modifications of a cylindrical "
                                   "pair) for the smallest loaded TE peak-to-peak under the constraints, each "
                                   "candidate a loaded analysis on a compliance computed once. Writes design.json, "
                                   "history.jsonl, settings.csv, the optimum's case file and LTCA outputs, the "
                                   "Harris map and the objective map into --out.")
    o.add_argument("case", help="case file (.toml) with a [design] table")
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
    t.add_argument("case", help="case file (.toml): cylindrical, [bevel] or [satellite]")
    t.add_argument("--out", default=None, help="output directory for summary.json and plots")
    t.add_argument("--positions", type=_positions, help="mesh positions per cycle (override, at most 2000)")
    t.set_defaults(func=_cmd_tca)

    s = sub.add_parser("study", help="load-case and tolerance studies on Dask (grid, variants, ISO 1328 Monte Carlo)",
                       description="Runs every variant of a study file at every torque on a Dask cluster: one "
                                   "compliance per geometry, each point written as it finishes (a rerun skips "
                                   "them). Writes study.nc, summary.csv, plots and run.json into --out.")
    s.add_argument("study", help="study file (.toml)")
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
    f.add_argument("case", help="case file (.toml) with a [satellite] table")
    f.add_argument("--out", default=None, help="output directory for forming.csv and forming.png")
    f.set_defaults(func=_cmd_forming)

    c = sub.add_parser("convergence", help="time against error over a ladder of fidelities",
                       description="Runs a ladder of fidelities (flank element size, contact grid, near-field "
                                   "correction on/off) and prints wall time against the error in loaded TE, "
                                   "peak pressure and root stress relative to the finest.")
    c.add_argument("case", help="case file (.toml)")
    c.add_argument("--out", default="out/convergence", help="output directory (default: out/convergence)")
    c.add_argument("--positions", type=_positions, default=8, help="mesh positions per cycle (default 8)")
    c.add_argument("--quiet", action="store_true", help="no progress output")
    c.set_defaults(func=_cmd_convergence)

    v = sub.add_parser("validate", help="run the validation cases: measured vs reference, error, time",
                       description="Runs the validation cases and prints measured vs reference, error and time.")
    v.add_argument("--out", default="out/validate", help="output directory (default: out/validate)")
    v.add_argument("--reference", choices=["analytic", "calculix", "calculix-whole"], default="analytic",
                   help="analytic references and tables (default); calculix: the CalculiX cross-check on our body "
                        "(slow: 5-15 min per position on 2 cores, plus 30-45 min per pressure ladder); calculix-whole: "
                        "CalculiX on whole gears with every tooth and their own supports, independent of our body "
                        "(7-25 min per CalculiX run on one thread of a busy machine, FZG C14)")
    v.add_argument("--case", default=None,
                   help="case for --reference calculix (default cases/fzg_c14.toml); a [bevel] case with the "
                        "analytic reference runs the bevel checks (elliptic Hertz, light-load limit, V-H table)")
    v.add_argument("--positions", type=float, nargs="+", metavar="DEG",
                   help="pinion roll angles from the pitch point for --reference calculix (default 0 +-4.5 +-9); a "
                        "[bevel] case: pinion angles in mesh cycles from the mean point (default 0 0.4)")
    v.add_argument("--refine", type=int, default=None,
                   help="CalculiX contact-band refinements at the first position (its convergence check; default 2, "
                        "calculix-whole 1)")
    v.add_argument("--level", type=int, default=1,
                   help="the rung of the CalculiX ladder used at every position (0 coarsest; default 1)")
    v.add_argument("--band", type=float, metavar="UM",
                   help="CalculiX contact-band element size at rung 0, um (default 3/4 of the Hertz half-width)")
    v.add_argument("--coarse-body", action="store_true",
                   help="CalculiX elements of our coarse fidelity away from the contact band (0.45 x module on "
                        "the flank, 1.6 x module in the body; calculix-whole: flanks with a contact line 0.45, other "
                        "teeth 0.75, body 1.6, loaded fillets 0.225 x module, the band's growth x 1.5: a wide face)")
    v.add_argument("--pressure-ladder", choices=["auto", "all", "none"], default="auto",
                   help="where CalculiX refines a mid-face window of the narrowest contact three times for a "
                        "converged peak pressure: auto (positions whose narrowest contact has < 3 band elements per "
                        "half-width, other than the band ladder's first position), all or none")
    v.add_argument("--fidelity", choices=["coarse", "default", "fine"], default=None,
                   help="our fidelity for --reference calculix-whole (default: default; a [satellite] case: its own)")
    v.add_argument("--torque", type=float, default=None, metavar="NM",
                   help="calculix on a [bevel] case: the pinion torque, N m (default: the case's middle torque); "
                        "calculix-whole on a [satellite] case: the satellite torque, N m (required there)")
    v.add_argument("--cache", default=None, help="calculix-whole on a [satellite] case: our mesh cache directory")
    v.add_argument("--freeze", metavar="JSON",
                   help="calculix-whole, and calculix on a [bevel] case: write the CalculiX results as a frozen "
                        "reference with provenance")
    v.add_argument("--merge", metavar="JSON",
                   help="calculix-whole: refine the --positions of this frozen reference by --refine rungs of 1.5 "
                        "beyond the band each was frozen at and merge them into it, with each position's ladder "
                        "(the other positions and the first position's ladder kept; ltca.verify.whole_merge)")
    v.add_argument("--ladder", choices=["finer", "coarser", "both"], default="finer",
                   help="calculix-whole: the --refine rungs at the first position refine the base contact band and "
                        "fillets by 1.5 each (finer, default), coarsen them (coarser) or both (both); the first "
                        "position is frozen at the finest rung")
    v.add_argument("--threads", type=int, default=2,
                   help="calculix-whole and the bevel calculix check: CalculiX threads (OMP_NUM_THREADS, "
                        "CCX_NPROC_EQUATION_SOLVER; default 2)")
    v.add_argument("--quiet", action="store_true", help="no progress output")
    v.set_defaults(func=_cmd_validate)

    be = sub.add_parser("bench", help="cold wall time of an analysis (median of runs) beside its Hertz error",
                        description="Runs the case cold several times and prints the median time per stage and "
                                    "the pitch-point error against Hertz.")
    be.add_argument("case", help="case file (.toml)")
    be.add_argument("--repeat", type=_positive_int, default=3, help="cold runs; the median is reported (default 3)")
    be.add_argument("--positions", type=_positions, help="mesh positions per cycle (default: the case's)")
    be.add_argument("--fidelity", choices=["coarse", "default", "fine"], help="override the case's fidelity")
    be.set_defaults(func=_cmd_bench)

    b = sub.add_parser("budget", help="drive-train stiffness and backlash budget (Wang et al.)",
                       description="Torsional deflection of a drive train of members in series, per torque.")
    b.add_argument("case", help="budget case file (.toml) with [budget] and [[member]] tables")
    b.add_argument("--out", default=None, help="output directory for the CSV and plots (default: print only)")
    b.set_defaults(func=_cmd_budget)

    ch = sub.add_parser("chain", help="machine kinematic-chain ratio errors (indexing and generating chains)",
                        description="Ratio errors of indexing and generating chains and the tooth errors they make.")
    ch.add_argument("case", help="chain case file (.toml) with [[chain]] and [workpiece] tables")
    ch.add_argument("--out", default=None, help="output directory for the CSV tables (default: print only)")
    ch.set_defaults(func=_cmd_chain)
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
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
