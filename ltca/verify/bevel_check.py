"""Bevel LTCA checks on the command line: ``ltca validate`` (elliptic Hertz with and without the near field,
the light-load limit, the V-H table of pattern shifts), ``ltca convergence`` (the fidelity ladder: time against
error) and ``ltca bench`` (cold medians of the stages' wall times) for a case with a [bevel] table.

References: elliptic Hertz (:mod:`ltca.fem.hertz`) with the relative curvature of the unloaded TCA's contact ellipse
(Litvin's curvature analysis of both generated surfaces, :func:`ltca.geometry.bevel.tca.tca`); the TCA's contact point
for the direction of the pattern shift under the assembly errors (the Gleason V-H check reads the same shifts on
a test machine: V is the offset E, H the pinion axial P).
"""
from __future__ import annotations

import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from ltca.fem.hertz import elliptic_hertz
from ltca.geometry.bevel.tca import RAD_PER_ARCSEC, Assembly, tca

from ..bevel.analysis import analyse_torque, build_pair, cycle_positions
from ..bevel.case import load_bevel_case
from ..bevel.loaded import solve_position
from ..bevel.loaded_model import BevelFidelity, loaded_model, prepare_bodies
from ..bevel.results import edge_band, fit_ellipse, position_arrays
from ..outputs import write_json_atomic

__all__ = ["hertz_check", "vh_table", "run_bevel_validate", "run_bevel_convergence", "run_bevel_bench"]


def _say(progress: bool):
    return (lambda m: print(m, file=sys.stderr)) if progress else (lambda m: None)


def hertz_check(pair, lm, torque_nm: float = 5.0) -> dict:
    """The pressure ellipse of the pair at the mean point against elliptic Hertz (TCA curvature), light load."""
    r = tca(pair, lm.side, steps_per_cycle=16, max_cycles=1.0)
    i0 = int(np.argmin(np.abs(r.phi1)))
    d = 0.00632
    A, B = d / (0.5 * r.major[i0]) ** 2, d / (0.5 * r.minor[i0]) ** 2
    res = solve_position(lm, 0.0, torque_nm * 1e3)
    m = res.pair == 0
    fit = fit_ellipse(res.xi[m], res.eta[m], res.pressure[m])
    hz = elliptic_hertz(res.force[m].sum(), A, B, lm.bodies.young, lm.bodies.poisson)
    out = dict(torque_nm=torque_nm, force_n=float(res.force[m].sum()), hertz_p0=hz.p0, hertz_a=hz.a, hertz_b=hz.b,
               share=float(res.pair_share.get(0, 0.0)), edges=res.edge_load(), max_cell_pressure=res.max_pressure)
    if fit is not None:
        p0, a, b = fit[:3]
        out.update(p0=p0, a=a, b=b, err_p0=p0 / hz.p0 - 1, err_a=a / hz.a - 1, err_b=b / hz.b - 1)
    return out


def vh_table(pair, bodies, torque_nm: float = 175.0, step: float = 0.05) -> list[dict]:
    """Shift of the loaded contact (pair at the mean position) and of the unloaded TCA point per 0.1 mm of E, P, G
    (central differences over +-``step`` mm): along the face (cone distance L, + towards the heel) and the profile
    (Rn, + towards the top), mm per 0.1 mm."""
    def point(asm):
        res = solve_position(loaded_model(pair, bodies, asm), 0.0, torque_nm * 1e3)
        w = res.force * (res.pair == 0)
        r = tca(pair, bodies.side, asm=asm, steps_per_cycle=16, max_cycles=1.0)
        i = int(np.argmin(np.abs(r.phi1)))
        return np.array([w @ res.L2, w @ res.Rn2]) / w.sum(), np.array([r.gear_L[i], r.gear_Rn[i]])
    rows = []
    for name in ("E", "P", "G"):
        (lp, up), (lm_, um) = point(Assembly(**{name: step})), point(Assembly(**{name: -step}))
        f = 0.1 / (2 * step)
        rows.append(dict(error=name, loaded_dL=float((lp - lm_)[0] * f), loaded_dRn=float((lp - lm_)[1] * f),
                         tca_dL=float((up - um)[0] * f), tca_dRn=float((up - um)[1] * f)))
    return rows


def run_bevel_validate(case_path: str, out: str, progress: bool = True) -> int:
    """Elliptic Hertz (with and without the near field), the light-load limit, torque balance, the V-H table."""
    say = _say(progress)
    case = load_bevel_case(case_path)
    pair = build_pair(case)
    d = Path(out)
    d.mkdir(parents=True, exist_ok=True)
    report: dict = {"case": case.name}
    for near in (True, False):
        fid = BevelFidelity() if near else BevelFidelity(name="default-no-near-field", near_field=False)
        t0 = time.perf_counter()
        bodies = prepare_bodies(pair, "concave", fid, case.young, case.poisson, progress=say,
                                mounting=case.mounting)
        lm = loaded_model(pair, bodies)
        h = hertz_check(pair, lm)
        h["seconds"] = time.perf_counter() - t0
        report["hertz_near_field" if near else "hertz_without_near_field"] = h
        if near:
            keep = (bodies, lm)
    bodies, lm = keep
    lim = {}
    for T in (1.0, 0.1, 0.01, 0.001):
        res = solve_position(lm, 0.0, T * 1e3)
        lim[f"{T:g}"] = dict(te_minus_te0_arcsec=(res.te - res.te0) / RAD_PER_ARCSEC, residual=res.torque_residual)
    report["light_load_limit"] = lim
    report["vh_table_mm_per_0.1mm"] = vh_table(pair, bodies)
    write_json_atomic(d / "bevel_validate.json", report)
    print(f"Bevel validation: {case.name}")
    for key in ("hertz_near_field", "hertz_without_near_field"):
        h = report[key]
        if "p0" not in h:
            print(f"  {key:26s} no elliptic pressure: peak cell {h['max_cell_pressure']:.0f} MPa = "
                  f"{h['max_cell_pressure'] / h['hertz_p0']:.1f} x Hertz p0 {h['hertz_p0']:.1f} MPa (the coarse FE "
                  "alone cannot resolve the contact)")
            continue
        print(f"  {key:26s} p0 {h['p0']:7.1f} vs Hertz {h['hertz_p0']:7.1f} MPa ({100 * h['err_p0']:+.2f} %), "
              f"a {h['a']:.3f} vs {h['hertz_a']:.3f} mm ({100 * h['err_a']:+.2f} %), "
              f"b {h['b']:.4f} vs {h['hertz_b']:.4f} mm ({100 * h['err_b']:+.2f} %)")
    for T, v in lim.items():
        print(f"  {T:>6s} N m: loaded - unloaded TE {v['te_minus_te0_arcsec']:+.4f} arcsec, "
              f"balance {v['residual']:.1e}")
    print("  V-H: shift per 0.1 mm     loaded dL   dRn   |  TCA dL   dRn  (mm; L + heel, Rn + top)")
    for r in report["vh_table_mm_per_0.1mm"]:
        print(f"    {r['error']}                       {r['loaded_dL']:+.3f} {r['loaded_dRn']:+.3f} | "
              f"{r['tca_dL']:+.3f} {r['tca_dRn']:+.3f}")
    h = report["hertz_near_field"]
    ok = abs(h.get("err_p0", 1)) <= 0.03 and abs(h.get("err_a", 1)) <= 0.05 and abs(h.get("err_b", 1)) <= 0.05
    return 0 if ok else 1


def _cycle_figures(lm, n: int, torque_nm: float) -> dict:
    res = analyse_torque(lm, cycle_positions(n, lm.pair.blank.pinion.z), torque_nm)
    a = position_arrays(res, torque_nm, edge_band(lm.pair.blank.data.module))
    return dict(te_pp=float(np.ptp(a["te"])), te_mean=float(np.mean(a["te"])), p_int=float(a["pmax_interior"].max()),
                share=float(a["share"].max()), root=float(np.nanmax(a["root1"])),
                stiffness=float(np.nanmean(a["stiffness"])))


def run_bevel_convergence(case_path: str, out: str, positions: int = 8, torque_nm: float = 175.0,
                          progress: bool = True) -> list[dict]:
    """The fidelity ladder coarse / default / fine: wall time against the change of each figure from the finest."""
    say = _say(progress)
    case = load_bevel_case(case_path)
    pair = build_pair(case)
    rows = []
    for name in ("coarse", "default", "fine"):
        t0 = time.perf_counter()
        bodies = prepare_bodies(pair, "concave", BevelFidelity.named(name), case.young, case.poisson,
                                progress=say, mounting=case.mounting)
        t1 = time.perf_counter()
        f = _cycle_figures(loaded_model(pair, bodies), positions, torque_nm)
        f.update(fidelity=name, compliance_s=t1 - t0, positions_s=time.perf_counter() - t1,
                 dofs=bodies.body1.n_dofs + bodies.body2.n_dofs)
        rows.append(f)
        say(f"{name}: {f}")
    ref = rows[-1]
    print(f"Bevel convergence at {torque_nm:g} N m, {positions} positions (errors against 'fine')")
    print(f"{'fidelity':9s} {'dofs':>8s} {'compl. s':>9s} {'pos. s':>7s} {'TE mean':>9s} {'err':>7s} {'TE p-p':>7s} "
          f"{'err':>7s} {'p int':>7s} {'err':>7s} {'root':>6s} {'err':>7s}")
    for r in rows:
        e = lambda k: 100 * (r[k] / ref[k] - 1)                                       # noqa: E731
        print(f"{r['fidelity']:9s} {r['dofs']:8d} {r['compliance_s']:9.1f} {r['positions_s']:7.1f} {r['te_mean']:9.2f} "
              f"{e('te_mean'):+6.2f}% {r['te_pp']:7.2f} {e('te_pp'):+6.1f}% {r['p_int']:7.0f} {e('p_int'):+6.2f}% "
              f"{r['root']:6.0f} {e('root'):+6.2f}%")
    d = Path(out)
    d.mkdir(parents=True, exist_ok=True)
    write_json_atomic(d / "bevel_convergence.json", {"torque_nm": torque_nm, "positions": positions, "rows": rows})
    return rows


def run_bevel_bench(case_path: str, repeat: int = 3, positions: int = 21, fidelity: str = "default") -> dict:
    """Cold medians: synthesis, compliance (both bodies, meshes not cached), one torque over ``positions``, each
    further torque, and the time per position after the compliance."""
    case = load_bevel_case(case_path)
    runs = []
    for _ in range(repeat):
        t = {}
        t0 = time.perf_counter()
        pair = build_pair(case)
        t["synthesis"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        bodies = prepare_bodies(pair, "concave", BevelFidelity.named(fidelity), case.young, case.poisson,
                                mounting=case.mounting)
        lm = loaded_model(pair, bodies)
        t["compliance"] = time.perf_counter() - t0
        phi = cycle_positions(positions, pair.blank.pinion.z)
        for k, T in enumerate((175.0, 350.0)):
            t0 = time.perf_counter()
            analyse_torque(lm, phi, T)
            t["first_torque" if k == 0 else "further_torque"] = time.perf_counter() - t0
        t["one_flank_one_torque_total"] = t["synthesis"] + t["compliance"] + t["first_torque"]
        t["per_position"] = t["further_torque"] / positions
        runs.append(t)
    med = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
    print(f"Bevel bench ({fidelity}, {positions} positions, {repeat} cold runs, medians):")
    for k, v in med.items():
        print(f"  {k:28s} {v:8.2f} s")
    print(json.dumps({"medians_s": med}))
    return med
