"""Ours against CalculiX on our own body over a mesh cycle, with CalculiX's own convergence checks:
``python3 -m tools.calculix_refs.ladder_cylindrical``.

The comparison of ``ltca validate --reference calculix`` (:mod:`ltca.verify.crosscheck`: every position solved by
both, CalculiX at one rung of its contact-band ladder, :func:`ltca.verify.calculix.ccx_ladder`).
Two ladders say how far that rung is from converged:

* the **band ladder** at the first position refines the whole contact band (3b/4, b/2, b/3 of the
  nominal Hertz half-width b) and gives converged TE and peak pressure by Richardson extrapolation;
* the **pressure ladder** at the other positions whose narrowest contact the band does not resolve
  (fewer than 3 elements per half-width; double contact near the pinion root has b ~ 100 um) refines a 2 mm window of that contact at mid-face only
  (:class:`ltca.verify.calculix.Focus`, sizes b/2, b/3, b/4.5 of its local half-width) on a coarse rest
  (rung 0, our coarse fidelity's element sizes), with the penalty slope scaled to the window's element
  size (:func:`ltca.verify.calculix.penalty_slope`), and the peak pressure fitted in the window is extrapolated
  the same way. Ours is compared in the same window.

Each CalculiX run is kept in its own folder under ``out`` and reused when the same deck is asked for again.
"""
from __future__ import annotations

import dataclasses
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ltca.cylindrical.loaded_model import LoadedModel
from ltca.verify.calculix import (Focus, PositionComparison, ccx_ladder, narrowest_contact, penalty_slope, solve_ccx,
                                  solve_ours)
from ltca.verify.crosscheck import BOUNDS, BOUNDS_HELICAL_TE, COARSE_BODY, default_rolls_deg, plot_rows

from .convergence import richardson
from .provenance import run

__all__ = ["PressureLadder", "pressure_ladder", "run_calculix_ladders", "main"]


@dataclass
class PressureLadder:
    """CalculiX's peak pressure in a focus window, refined (MPa, mm), and ours in the same window."""
    roll_deg: float
    tooth: int
    half_width: float               # our contact half-width of that tooth at mid-face, mm
    runs: list[PositionComparison]  # coarse to fine
    converged: float                # Richardson estimate (the finest run's value when not monotone)
    order: float | None             # observed order, None when not monotone
    ours: float                     # our peak pressure in the same window

    @property
    def finest_per_b(self) -> float:
        return self.half_width / self.runs[-1].info["focus"]["h"]


def pressure_ladder(lm: LoadedModel, roll_deg: float, torque: float, res, outdir: Path, rungs: int = 3,
                    half_length: float = 1.0, say=print) -> PressureLadder:
    """Refine CalculiX on the narrowest contact of our solution ``res`` at ``roll_deg`` (see module doc)."""
    roll = np.radians(roll_deg)
    k, bl = narrowest_contact(res)
    base = ccx_ladder(lm.b_nom, lm.model.case.module, 0, body=COARSE_BODY)[0]
    runs = []
    for j in range(rungs):
        h = 0.5 * bl / 1.5 ** j
        f = Focus(tooth=k, z0=0.0, half_length=half_length, h=h, half_band=1.5 * bl + h)
        st = dataclasses.replace(base, penalty=penalty_slope(h))
        runs.append(solve_ccx(lm, roll, torque, st, outdir / f"ccx_r{roll_deg:+.4f}_F{j}", say=say, focus=f))
    est = richardson([c.max_pressure for c in runs[-3:]], 1.5) if len(runs) >= 3 else None
    win = (res.tooth == k) & (np.abs(res.z) <= half_length)
    ours = float(res.pressure[win].max()) if win.any() else float("nan")
    return PressureLadder(roll_deg, k, bl, runs, est[0] if est else runs[-1].max_pressure,
                          est[1] if est else None, ours)


def run_calculix_ladders(case_path: str, positions: list[float] | None, out: str, refine: int = 2,
                            level: int | None = 1, band_um: float | None = None, coarse_body: bool = False,
                            pressure: str = "auto", progress: bool = True) -> int:
    """Ours against CalculiX on a case at pinion roll angles ``positions`` (deg from the pitch point).

    Every position is solved by CalculiX at ladder rung ``level`` (contact band 3b/4 / 1.5^level; default 1,
    b/2; None: the finest); then the first position at the other rungs up to ``refine`` (the CalculiX
    convergence check, which says how far ``level`` is from converged). ``pressure`` says where the pressure
    ladder runs (:func:`pressure_ladder`): "auto" where the band has fewer than 3 elements per half-width
    of the narrowest contact, except at the first position when the band ladder has its three rungs (its
    estimate is the reference there); "all"; or "none". Where a ladder ran, its converged peak is the
    reference pressure. Each CalculiX run is kept (deck, results, ``result.json``) in its own folder under
    ``out`` and reused when the same deck is asked for again, so an interrupted validation resumes where
    it stopped. Prints a table, writes ``calculix.csv``, ``convergence.csv``, ``pressure_ladder.csv`` and
    ``calculix.png`` to ``out`` and returns 0 when all positions are within :data:`BOUNDS`, 1
    otherwise. Raises ``CaseError`` on a bad case or
    position list and ``ltca.fem.calculix.run.CcxNotFound`` (with the install command) when ``ccx`` is missing."""
    from ltca.fem.calculix.run import ccx_path
    from ltca.case import FIDELITIES, load_case
    from ltca.errors import CaseError
    from ltca.cylindrical.loaded_model import Fidelity, prepare
    from ltca.cylindrical.model import build_model
    from ltca.cylindrical.run import cycle_rolls
    ccx_path()
    say = (lambda m: print(m, file=sys.stderr, flush=True)) if progress else (lambda m: None)
    if refine < 0 or refine > 4:
        raise CaseError("--refine", refine, "an integer from 0 to 4")
    if pressure not in ("auto", "all", "none"):
        raise CaseError("--pressure-ladder", pressure, "auto, all or none")
    case = load_case(case_path)
    pitch_deg = 360.0 / case.pinion.teeth
    rolls_deg = list(positions) if positions else default_rolls_deg(case.pinion.teeth)
    bad = [r for r in rolls_deg if not np.isfinite(r) or abs(r) > 0.5 * pitch_deg + 1e-9]
    if bad:
        raise CaseError("--positions", bad, f"pinion roll angles in deg within one mesh cycle "
                        f"(|roll| <= {0.5 * pitch_deg:.4f})")
    torque = case.torques[0]
    model = build_model(case)
    t0 = time.perf_counter()
    fid = Fidelity.from_preset(FIDELITIES["default"], case.module)
    lm = prepare(model, fid, cycle_rolls(case.positions, case.pinion.teeth), torque, progress=say)
    t_prepare = time.perf_counter() - t0
    if band_um is not None and not (np.isfinite(band_um) and 10.0 <= band_um <= 2000.0):
        raise CaseError("--band", band_um, "a contact-band element size from 10 to 2000 um")
    ladder = ccx_ladder(lm.b_nom, case.module, refine, h0=band_um * 1e-3 if band_um else None,
                        body=(0.45, 1.6) if coarse_body else (0.3, 1.3))
    helical = abs(case.helix_angle) > 1e-9
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)
    if level is None:
        level = len(ladder) - 1
    if not 0 <= level < len(ladder):
        raise CaseError("--level", level, f"an integer from 0 to --refine ({refine})")
    rows, conv, focused = [], [], {}
    # every position at `level` first (each CalculiX run is kept in its folder as it finishes), then the
    # other rungs of the ladder at the first position: the costly fine rungs come last
    for rd in rolls_deg:
        roll = np.radians(rd)
        mine, res = solve_ours(lm, roll, torque)
        c = solve_ccx(lm, roll, torque, ladder[level], outdir / f"ccx_r{rd:+.4f}_L{level}", say=say)
        conv.append((rd, level, c))
        teeth = sorted(set(mine.pair_load) | set(c.pair_load))
        # CalculiX's resolution of the narrowest contact: its band elements per (our) contact half-width
        per_b = narrowest_contact(res)[1] / ladder[level].h_contact
        banded = rd == rolls_deg[0] and len(ladder) >= 3     # the band ladder converges this one
        if not helical and (pressure == "all" or (pressure == "auto" and per_b < 3.0 and not banded)):
            focused[rd] = (res, per_b)
        for sol in (mine, c):
            rows.append({"roll_deg": rd, "solver": sol.solver, "reference": True, "te_arcsec": sol.te,
                         "share": sol.share(teeth), "max_pressure_mpa": sol.max_pressure, "wall_s": sol.wall,
                         "n_dofs": sol.info.get("n_dofs", lm.body1.n_dofs + lm.body2.n_dofs), "per_b": per_b})
    for lev in range(len(ladder)):
        if lev != level:
            rd = rolls_deg[0]
            conv.append((rd, lev, solve_ccx(lm, np.radians(rd), torque, ladder[lev], outdir / f"ccx_r{rd:+.4f}_L{lev}",
                                            say=say)))
    conv.sort(key=lambda x: (x[0] != rolls_deg[0], x[1]))
    # unresolved positions first: their ladders are the reference pressures
    order = sorted(focused, key=lambda rd: focused[rd][1])
    ladders = {rd: pressure_ladder(lm, rd, torque, focused[rd][0], outdir, say=say) for rd in order}
    first = sorted((c for rd, _, c in conv if rd == rolls_deg[0]), key=lambda c: -c.info["h_contact"])
    band_est = {what: richardson([getattr(c, key) for c in first[-3:]], 1.5) if len(first) >= 3 else None
                for what, key in (("TE", "te"), ("peak pressure", "max_pressure"))}
    for j in range(0, len(rows), 2):   # converged peaks replace the band rung's
        pl = ladders.get(rows[j]["roll_deg"])
        if pl is not None:
            rows[j]["max_pressure_mpa"], rows[j + 1]["max_pressure_mpa"] = pl.ours, pl.converged
            rows[j + 1]["per_b"] = pl.finest_per_b
            rows[j + 1]["converged"] = "*"
        elif j == 0 and band_est["peak pressure"] is not None:
            rows[1]["max_pressure_mpa"] = band_est["peak pressure"][0]
            rows[1]["per_b"] *= ladder[level].h_contact / first[-1].info["h_contact"]
            rows[1]["converged"] = "+"
    # ---- table
    bound_te = BOUNDS_HELICAL_TE if helical else BOUNDS["te_rel"]
    ok_all = True
    lines = [f"{case.name} at {torque * 1e-3:g} N m: ours (default fidelity) against CalculiX "
             f"(contact band {1e3 * ladder[level].h_contact:.0f} um)",
             f"{'roll':>7} {'TE ours':>8} {'TE ccx':>8} {'dTE%':>6} {'share ours':>18} {'share ccx':>18} {'dshare':>6} "
             f"{'p ours':>6} {'p ccx':>6} {'dp%':>6} {'el/b':>5} {'t ours':>7} {'t ccx':>7} {'ratio':>6}"]
    csv = ["roll_deg,te_ours_arcsec,te_ccx_arcsec,te_diff_pct,share_ours,share_ccx,share_diff_max,p_ours_mpa,"
           "p_ccx_mpa,p_diff_pct,ccx_elements_per_half_width,t_ours_s,t_ccx_s,time_ratio,ccx_dofs,ok"]
    t_ours_sum = t_ccx_sum = 0.0
    for j in range(0, len(rows), 2):
        a, c = rows[j], rows[j + 1]
        teeth = sorted(a["share"])
        dte = c["te_arcsec"] and (a["te_arcsec"] / c["te_arcsec"] - 1)
        dsh = max(abs(a["share"][k] - c["share"][k]) for k in teeth)
        dp = c["max_pressure_mpa"] and (a["max_pressure_mpa"] / c["max_pressure_mpa"] - 1)
        ok = abs(dte) <= bound_te and (helical or (dsh <= BOUNDS["share_abs"] and abs(dp) <= BOUNDS["pressure_rel"]))
        ok_all &= ok
        flag = "" if ok else ("  p unresolved by CalculiX (< 2 el/b)" if abs(dte) <= bound_te and
                              dsh <= BOUNDS["share_abs"] and c["per_b"] < 2 else "  OUT")
        flag = (" " + c["converged"] if c.get("converged") else "") + flag
        ratio = c["wall_s"] / a["wall_s"]
        t_ours_sum += a["wall_s"]
        t_ccx_sum += c["wall_s"]
        sh = lambda r: "/".join(f"{r['share'][k]:.3f}" for k in teeth)
        lines.append(f"{a['roll_deg']:7.3f} {a['te_arcsec']:8.2f} {c['te_arcsec']:8.2f} {100 * dte:+6.2f} {sh(a):>18} "
                     f"{sh(c):>18} {dsh:6.3f} {a['max_pressure_mpa']:6.0f} {c['max_pressure_mpa']:6.0f} "
                     f"{100 * dp:+6.1f} {c['per_b']:5.1f} {a['wall_s']:7.2f} {c['wall_s']:7.0f} {ratio:6.0f}{flag}")
        csv.append(f"{a['roll_deg']},{a['te_arcsec']},{c['te_arcsec']},{100 * dte},{sh(a)},{sh(c)},{dsh},"
                   f"{a['max_pressure_mpa']},{c['max_pressure_mpa']},{100 * dp},{c['per_b']},{a['wall_s']},{c['wall_s']},{ratio},"
                   f"{c['n_dofs']},{ok}")
    n = len(rows) // 2
    cyc_ours = t_prepare + case.positions * t_ours_sum / n
    cyc_ccx = case.positions * t_ccx_sum / n
    lines.append(f"wall time per position: ours {t_ours_sum / n:.2f} s (contact solve; compliance {t_prepare:.1f} s once), "
                 f"CalculiX {t_ccx_sum / n:.0f} s; ratio {t_ccx_sum / t_ours_sum:.0f}")
    lines.append(f"whole cycle ({case.positions} positions, extrapolated): ours {cyc_ours:.0f} s incl. compliance, "
                 f"CalculiX {cyc_ccx:.0f} s; ratio {cyc_ccx / cyc_ours:.0f}")
    fine = max((x for x in conv if x[0] == rolls_deg[0]), key=lambda x: x[1])[2]
    if fine.info["h_contact"] < ladder[level].h_contact:
        lines.append(f"converged CalculiX (the band ladder's finest rung, {1e3 * fine.info['h_contact']:.0f} um, at roll "
                     f"{rolls_deg[0]:g}): {fine.wall:.0f} s per position, ratio {fine.wall * n / t_ours_sum:.0f}; "
                     f"whole cycle ratio {case.positions * fine.wall / cyc_ours:.0f}")
    lines.append("CalculiX runs (convergence ladder at the first position; contact band size -> TE, loads, peak "
                 "pressure, dofs, time):")
    cl = ["roll_deg,level,h_contact_um,penalty_mpa_per_mm,n_dofs,te_arcsec,pair_load_n,p_fit_mpa,p_nodal_max_mpa,wall_s"]
    for rd, lev, c in conv:
        loads = "/".join(f"{v:.1f}" for _, v in sorted(c.pair_load.items()))
        lines.append(f"  roll {rd:7.3f} level {lev}: {1e3 * c.info['h_contact']:5.0f} um  TE {c.te:8.3f}  loads {loads:>20} N"
                     f"  p fit {c.max_pressure:6.0f} (nodal max {c.info.get('p_max_nodal', 0):.0f}) MPa  {c.info['n_dofs']} dofs  {c.wall:.0f} s")
        cl.append(f"{rd},{lev},{1e3 * c.info['h_contact']},{c.info['penalty']},{c.info['n_dofs']},{c.te},{loads},"
                  f"{c.max_pressure},{c.info.get('p_max_nodal', 0)},{c.wall}")
    if len(first) >= 3:
        a0 = rows[0]
        for what, key, mine in (("TE", "te", a0["te_arcsec"]), ("peak pressure", "max_pressure", a0["max_pressure_mpa"])):
            est = band_est[what]
            if est is not None:
                lines.append(f"converged CalculiX {what} at roll {rolls_deg[0]:g} (Richardson, observed order "
                             f"{est[1]:.2f}): {est[0]:.2f}; ours {mine:.2f} ({100 * (mine / est[0] - 1):+.2f} %)")
            else:
                lines.append(f"CalculiX {what} at roll {rolls_deg[0]:g} does not converge monotonically over the "
                             f"ladder: {[round(getattr(c, key), 2) for c in first]}")
    pl_csv = ["roll_deg,tooth,half_width_um,h_focus_um,n_dofs,te_arcsec,p_window_mpa,p_face_fit_mpa,wall_s"]
    for rd, pl in ladders.items():
        lines.append(f"pressure ladder at roll {rd:g} (tooth {pl.tooth}, our half-width {1e3 * pl.half_width:.0f} um, "
                     f"mid-face window; rest of the band {1e3 * pl.runs[0].info['h_contact']:.0f} um):")
        for c in pl.runs:
            h = c.info["focus"]["h"]
            lines.append(f"  {1e3 * h:5.1f} um ({pl.half_width / h:4.1f} el/b)  p fit {c.max_pressure:6.0f} MPa  "
                         f"TE {c.te:7.2f}  {c.info['n_dofs']} dofs  {c.wall:.0f} s")
            pl_csv.append(f"{rd},{pl.tooth},{1e3 * pl.half_width},{1e3 * h},{c.info['n_dofs']},{c.te},{c.max_pressure},"
                          f"{c.info['p_fit']},{c.wall}")
        how = (f"Richardson, observed order {pl.order:.2f}" if pl.order is not None else
               "finest rung: the ladder is not monotone")
        lines.append(f"  converged CalculiX {pl.converged:.0f} MPa ({how}); ours in the window {pl.ours:.0f} "
                     f"({100 * (pl.ours / pl.converged - 1):+.2f} %)")
    if any(r.get("converged") for r in rows):
        lines.append("p ccx is converged CalculiX where marked: + the band ladder's Richardson estimate (whole face), "
                     "* the pressure ladder's (mid-face window of the narrowest contact; p ours in the same window); "
                     "el/b is then that of the finest rung; elsewhere the band rung's fitted peak")
    print("\n".join(lines))
    if ladders:
        (outdir / "pressure_ladder.csv").write_text("\n".join(pl_csv) + "\n")
    (outdir / "calculix.csv").write_text("\n".join(csv) + "\n")
    (outdir / "convergence.csv").write_text("\n".join(cl) + "\n")
    plot_rows(rows, outdir / "calculix.png", f"{case.name}: ours vs CalculiX")
    return 0 if ok_all else 1


def build_parser():
    import argparse
    p = argparse.ArgumentParser(prog="python3 -m tools.calculix_refs.ladder_cylindrical",
                                description="Ours against CalculiX on our body over a mesh cycle, with the band ladder "
                                            "at the first position and pressure ladders where the band does not "
                                            "resolve the narrowest contact.")
    p.add_argument("--case", default="cases/fzg_c14.toml", help="case file (default cases/fzg_c14.toml)")
    p.add_argument("--positions", type=float, nargs="+", metavar="DEG",
                   help="pinion roll angles from the pitch point, deg (default 0 +-4.5 +-9 of a 16-tooth pinion)")
    p.add_argument("--out", default="out/calculix_ladders", help="CalculiX runs, kept and reused")
    p.add_argument("--refine", type=int, default=2, help="band refinements at the first position (default 2)")
    p.add_argument("--level", type=int, default=1, help="the band rung used at every position (default 1)")
    p.add_argument("--band", type=float, metavar="UM", help="contact-band size at rung 0, um (default 3/4 of the "
                                                             "Hertz half-width)")
    p.add_argument("--coarse-body", action="store_true", help="our coarse fidelity's element sizes away from the band")
    p.add_argument("--pressure-ladder", choices=["auto", "all", "none"], default="auto",
                   help="where a mid-face window of the narrowest contact is refined three times (default auto)")
    p.add_argument("--quiet", action="store_true", help="no progress output")
    return p


def main(argv: list[str] | None = None) -> int:
    def work(a):
        return run_calculix_ladders(a.case, a.positions, a.out, refine=a.refine, level=a.level, band_um=a.band,
                                    coarse_body=a.coarse_body, pressure=a.pressure_ladder, progress=not a.quiet)
    return run(build_parser(), work, argv)


if __name__ == "__main__":
    raise SystemExit(main())
