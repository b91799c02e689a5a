"""``ltca validate --reference calculix``: ours against CalculiX on the same bodies over a mesh cycle.

Every position is solved by both: ours (:func:`ltca.verify.calculix.solve_ours`) and CalculiX on our whole-gear
bodies refined in a band around the unloaded contact lines (:func:`ltca.verify.calculix.solve_ccx`), at one rung
``level`` of the contact-band sizes 3b/4, b/2, b/3 ... of the nominal Hertz half-width b
(:func:`ltca.verify.calculix.ccx_ladder`). Compared: loaded TE, load share per pinion tooth, the fitted peak
pressure (with CalculiX's elements per contact half-width, which says whether its band resolves the contact) and
wall time. Bounds: TE 3 % (helical 5 %), share 0.03, peak pressure 5 % (spur). Each CalculiX run is kept in its own
folder under ``out`` and reused when the same deck is asked for again, so an interrupted check resumes.

CalculiX's own convergence ladders (the band refined at the first position, a focus window refined on the narrowest
contact) are maintainer tooling (``tools/calculix_refs/ladder_cylindrical.py``, not installed).
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from .calculix import ccx_ladder, narrowest_contact, solve_ccx, solve_ours

__all__ = ["BOUNDS", "BOUNDS_HELICAL_TE", "COARSE_BODY", "default_rolls_deg", "plot_rows", "run_calculix_validation"]

BOUNDS = {"te_rel": 0.03, "share_abs": 0.03, "pressure_rel": 0.05}   # spur pair
BOUNDS_HELICAL_TE = 0.05
COARSE_BODY = (0.45, 1.6)       # element sizes away from the contact, modules (our coarse fidelity)


def default_rolls_deg(z1: int) -> list[float]:
    """Five positions over one mesh cycle: pitch point, two single-contact and two double-contact ones."""
    return [round(f * 360.0 / z1, 4) for f in (0.0, -0.4, -0.2, 0.2, 0.4)]


def plot_rows(rows: list[dict], out: Path, title: str) -> None:
    """TE, peak pressure and load shares of both solvers against the roll angle, written to ``out`` (PNG)."""
    from .. import figures as plt
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    for solver, mk in (("ours", "o"), ("calculix", "s")):
        r = sorted((x for x in rows if x["solver"] == solver and x["reference"]), key=lambda x: x["roll_deg"])
        if not r:
            continue
        roll = [x["roll_deg"] for x in r]
        ax[0].plot(roll, [x["te_arcsec"] for x in r], mk + "-", label=solver)
        ax[1].plot(roll, [x["max_pressure_mpa"] for x in r], mk + "-", label=solver)
        for k in sorted({k for x in r for k in x["share"]}):
            ax[2].plot(roll, [x["share"].get(k, 0.0) for x in r], mk + "-", label=f"{solver} tooth {k}")
    for a, yl in zip(ax, ("loaded TE - unloaded [arcsec]", "peak pressure [MPa]", "load share")):
        a.set(xlabel="pinion roll from the pitch point [deg]", ylabel=yl)
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def run_calculix_validation(case_path: str, positions: list[float] | None, out: str, level: int = 1,
                            band_um: float | None = None, coarse_body: bool = False, progress: bool = True) -> int:
    """Ours against CalculiX on a case at pinion roll angles ``positions`` (deg from the pitch point; default five
    over a mesh cycle), CalculiX's contact band at rung ``level`` (3b/4 / 1.5^level, or ``band_um`` / 1.5^level).

    Prints a table, writes ``calculix.csv`` and ``calculix.png`` to ``out`` and returns 0 when all positions are
    within :data:`BOUNDS`, 1 otherwise. Raises ``CaseError`` on a bad case or argument and
    ``ltca.fem.calculix.run.CcxNotFound`` (with the install command) when ``ccx`` is missing."""
    from ltca.fem.calculix.run import ccx_path
    from ..case import FIDELITIES, load_case
    from ..cylindrical.loaded_model import Fidelity, prepare
    from ..cylindrical.model import build_model
    from ..cylindrical.run import cycle_rolls
    from ..errors import CaseError
    if not 0 <= level <= 4:
        raise CaseError("--level", level, "an integer from 0 to 4")
    if band_um is not None and not (np.isfinite(band_um) and 10.0 <= band_um <= 2000.0):
        raise CaseError("--band", band_um, "a contact-band element size from 10 to 2000 um")
    case = load_case(case_path)
    pitch_deg = 360.0 / case.pinion.teeth
    rolls_deg = list(positions) if positions else default_rolls_deg(case.pinion.teeth)
    bad = [r for r in rolls_deg if not np.isfinite(r) or abs(r) > 0.5 * pitch_deg + 1e-9]
    if bad:
        raise CaseError("--positions", bad, f"pinion roll angles in deg within one mesh cycle "
                        f"(|roll| <= {0.5 * pitch_deg:.4f})")
    ccx_path()
    say = (lambda m: print(m, file=sys.stderr, flush=True)) if progress else (lambda m: None)
    torque = case.torques[0]
    t0 = time.perf_counter()
    lm = prepare(build_model(case), Fidelity.from_preset(FIDELITIES["default"], case.module),
                 cycle_rolls(case.positions, case.pinion.teeth), torque, progress=say)
    t_prepare = time.perf_counter() - t0
    st = ccx_ladder(lm.b_nom, case.module, level, h0=band_um * 1e-3 if band_um else None,
                    body=COARSE_BODY if coarse_body else (0.3, 1.3))[level]
    helical = abs(case.helix_angle) > 1e-9
    bound_te = BOUNDS_HELICAL_TE if helical else BOUNDS["te_rel"]
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)
    lines = [f"{case.name} at {torque * 1e-3:g} N m: ours (default fidelity) against CalculiX "
             f"(contact band {1e3 * st.h_contact:.0f} um)",
             f"{'roll':>7} {'TE ours':>8} {'TE ccx':>8} {'dTE%':>6} {'share ours':>18} {'share ccx':>18} {'dshare':>6} "
             f"{'p ours':>6} {'p ccx':>6} {'dp%':>6} {'el/b':>5} {'t ours':>7} {'t ccx':>7} {'ratio':>6}"]
    csv = ["roll_deg,te_ours_arcsec,te_ccx_arcsec,te_diff_pct,share_ours,share_ccx,share_diff_max,p_ours_mpa,"
           "p_ccx_mpa,p_diff_pct,ccx_elements_per_half_width,t_ours_s,t_ccx_s,time_ratio,ccx_dofs,ok"]
    rows, ok_all, t_ours, t_ccx = [], True, 0.0, 0.0
    for rd in rolls_deg:
        roll = np.radians(rd)
        a, res = solve_ours(lm, roll, torque)
        c = solve_ccx(lm, roll, torque, st, outdir / f"ccx_r{rd:+.4f}_L{level}", say=say)
        teeth = sorted(set(a.pair_load) | set(c.pair_load))
        per_b = narrowest_contact(res)[1] / st.h_contact       # CalculiX's band elements per (our) half-width
        sa, sc = a.share(teeth), c.share(teeth)
        dte = c.te and (a.te / c.te - 1)
        dsh = max(abs(sa[k] - sc[k]) for k in teeth)
        dp = c.max_pressure and (a.max_pressure / c.max_pressure - 1)
        ok = abs(dte) <= bound_te and (helical or (dsh <= BOUNDS["share_abs"] and abs(dp) <= BOUNDS["pressure_rel"]))
        ok_all &= ok
        flag = "" if ok else ("  p unresolved by CalculiX (< 2 el/b)" if abs(dte) <= bound_te and
                              dsh <= BOUNDS["share_abs"] and per_b < 2 else "  OUT")
        t_ours += a.wall
        t_ccx += c.wall
        sh = lambda d: "/".join(f"{d[k]:.3f}" for k in teeth)     # noqa: E731
        lines.append(f"{rd:7.3f} {a.te:8.2f} {c.te:8.2f} {100 * dte:+6.2f} {sh(sa):>18} {sh(sc):>18} {dsh:6.3f} "
                     f"{a.max_pressure:6.0f} {c.max_pressure:6.0f} {100 * dp:+6.1f} {per_b:5.1f} {a.wall:7.2f} "
                     f"{c.wall:7.0f} {c.wall / a.wall:6.0f}{flag}")
        csv.append(f"{rd},{a.te},{c.te},{100 * dte},{sh(sa)},{sh(sc)},{dsh},{a.max_pressure},{c.max_pressure},"
                   f"{100 * dp},{per_b},{a.wall},{c.wall},{c.wall / a.wall},{c.info['n_dofs']},{ok}")
        for sol, share in ((a, sa), (c, sc)):
            rows.append({"roll_deg": rd, "solver": sol.solver, "reference": True, "te_arcsec": sol.te, "share": share,
                         "max_pressure_mpa": sol.max_pressure})
    n = len(rolls_deg)
    lines.append(f"wall time per position: ours {t_ours / n:.2f} s (contact solve; compliance {t_prepare:.1f} s once), "
                 f"CalculiX {t_ccx / n:.0f} s; ratio {t_ccx / t_ours:.0f}. el/b: CalculiX's band elements per contact "
                 "half-width (below 3 its peak pressure is not resolved)")
    print("\n".join(lines))
    (outdir / "calculix.csv").write_text("\n".join(csv) + "\n")
    plot_rows(rows, outdir / "calculix.png", f"{case.name}: ours vs CalculiX")
    return 0 if ok_all else 1
