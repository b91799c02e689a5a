"""The planetary commands: ``ltca forming`` (method comparison), ``ltca tca`` (unloaded gaps of every pair,
both directions) and ``ltca run`` (loaded contact at every torque, both directions) of a ``[satellite]`` case.

Pair counts: a pair carries load when its share of the normal load is at least ``SHARE_MIN`` (0.1 %).
Loaded TE: the satellite rotation (wheel fixed) beyond the rigid rotation to first contact, as an arc on
the satellite's base circle (um along the line of action) and in arcsec of the satellite.
"""
from __future__ import annotations

import json
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ltca.geometry.satellite import plot_forming, rated_torque, unloaded_gaps

from ..case import FIDELITIES
from ..errors import CaseError
from ..cylindrical.loaded_model import Fidelity
from ..cylindrical.tca import ARCSEC_PER_RAD
from .case import compare_case_forming, load_planetary_case
from .loaded import positions, prepare_satellite, solve_cycle
from .model import build_satellite_model
from .report import out_dir, plot_gaps, plot_load_sharing, print_table, write_csv

__all__ = ["SHARE_MIN", "ROW_KEYS", "run_forming", "run_planetary_tca", "planetary_tca_summary", "summarise",
           "plan", "execute", "write_files", "PlanetaryPlan", "PlanetaryRun"]

SHARE_MIN = 1e-3


def run_forming(case_path, out=None) -> list[dict]:
    """Cut the satellite by (a), (b), (c) with the case's tools; table, ``forming.csv``, ``forming.png``."""
    case = load_planetary_case(case_path)
    t0 = time.perf_counter()
    cmp = compare_case_forming(case, str(case_path))      # a tool that cannot cut it: exit 2 naming the fields
    rows = cmp.table()
    for r in rows:
        dev = cmp.deviations.get(r["method"])
        r["max_dev_involute_um"] = None if dev is None else dev.max_abs_involute_um
    print(f"satellite z = {case.design.z}, m = {case.design.m} mm, x = {case.design.x}, thinning {case.design.thinning} m:"
          f" Eq. 3 thickness {case.design.eq3_thickness:.4f} mm; disk-cutter plunge for Eq. 3: x = {cmp.plunge_for_eq3:.4f}")
    print_table(rows, ["method", "passes", "s_ref", "s_minus_eq3_um", "tip_land", "pointed", "nearly_pointed",
                       "dedendum", "root_fillet_radius", "max_deviation_um", "max_dev_involute_um"])
    d = out_dir(out)
    if d is not None:
        write_csv(d / "forming.csv", rows)
        plot_forming(cmp, d / "forming.png")
    print(f"forming comparison: {time.perf_counter() - t0:.1f} s")
    return rows


def planetary_tca_summary(case, n_positions: int | None = None) -> tuple[dict, list, object]:
    """Unloaded gaps of every pair over one mesh cycle in both directions (exact, :mod:`ltca.geometry.satellite`):
    (summary, the pairs-within rows, the gaps record). Writes and prints nothing."""
    sm = build_satellite_model(case)
    n = n_positions or max(case.positions, 12)
    ug = unloaded_gaps(sm.mesh, n)
    rows = []
    for d in (1, -1):
        for lim in (10, 50, 100):
            c = ug.pairs_within(lim, d)
            rows.append(dict(direction=d, within_um=lim, pairs_min=int(c.min()), pairs_max=int(c.max())))
    ch = sm.choice
    summary = dict(z1=sm.mesh.z1, z2=sm.mesh.z2, eccentricity_mm=sm.mesh.e, alpha_w_deg=float(np.degrees(sm.mesh.alpha_w)),
                   backlash_loa_um=float(1e3 * sm.mesh.backlash * np.cos(sm.mesh.alpha_w)),
                   thinning=case.design.thinning, thinning_fit=ch.thinning_fit, method=case.method,
                   first_contact_um={str(d): float(np.max(np.abs(ug.first_contact_um[d]))) for d in (1, -1)},
                   pairs_within=rows)
    return summary, rows, (sm, ug)


def run_planetary_tca(case_path, out=None, n_positions: int | None = None) -> dict:
    """``ltca tca`` of a planetary case file: :func:`planetary_tca_summary`, its table, and with ``out`` the gaps
    (CSV, plot) and the summary."""
    case = load_planetary_case(case_path)
    summary, rows, (sm, ug) = planetary_tca_summary(case, n_positions)
    print(f"internal pair z1 {sm.mesh.z1} / z2 {sm.mesh.z2}, e = {sm.mesh.e} mm, alpha_w = {summary['alpha_w_deg']:.3f} deg, "
          f"satellite cut by {case.method}; first contact before the involute contact: "
          f"{summary['first_contact_um']} um (0: involutes touch first)")
    print_table(rows)
    d = out_dir(out)
    if d is not None:
        write_csv(d / "gaps.csv", [dict(direction=s, phi_deg=float(np.degrees(p)), pair=int(k), gap_um=float(g))
                                   for s in (1, -1) for i, p in enumerate(ug.phi) for k, g in zip(ug.pairs, ug.gap_um[s][i])
                                   if g < 1000])
        plot_gaps(d / "gaps.png", ug.phi, ug.pairs, ug.gap_um)
        (d / "summary.json").write_text(json.dumps(summary, indent=1))
    return summary


def _mirror(results: list) -> list[dict]:
    """Reverse-direction records from the drive results at the mirrored positions (module doc of .loaded)."""
    return [dict(pair_load={-k: v for k, v in r.pair_load.items()}, root1={-k: v for k, v in r.root1.items()},
                 root2={-k: v for k, v in r.root2.items()}, res=r) for r in results[::-1]]


def summarise(results: list, direction: int, torque: float, rb1: float) -> dict:
    """One torque and direction over the cycle: pairs carrying load, shares, TE, pressure, root stress."""
    recs = ([dict(pair_load=r.pair_load, root1=r.root1, root2=r.root2, res=r) for r in results] if direction > 0
            else _mirror(results))
    pairs = sorted({k for rc in recs for k in rc["pair_load"]})
    F = np.array([[rc["pair_load"].get(k, 0.0) for k in pairs] for rc in recs])
    tot = F.sum(axis=1, keepdims=True)
    share = F / tot
    n_loaded = (share >= SHARE_MIN).sum(axis=1)
    dth = np.array([rc["res"].theta - rc["res"].theta0 for rc in recs])
    return dict(direction=direction, torque_nm=torque / 1e3, pairs_min=int(n_loaded.min()), pairs_max=int(n_loaded.max()),
                loaded_pairs=[k for j, k in enumerate(pairs) if share[:, j].max() >= SHARE_MIN],
                mean_share={k: float(share[:, j].mean()) for j, k in enumerate(pairs)},
                max_share={k: float(share[:, j].max()) for j, k in enumerate(pairs)},
                share_sum_error=float(np.max(np.abs(share.sum(axis=1) - 1))),
                torque_residual=float(max(rc["res"].torque_residual for rc in recs)),
                te_um_mean=float(1e3 * rb1 * dth.mean()), te_um_ptp=float(1e3 * rb1 * np.ptp(dth)),
                te_arcsec_mean=float(ARCSEC_PER_RAD * dth.mean()),
                peak_pressure_mpa=float(max(rc["res"].max_pressure for rc in recs)),
                root_stress_satellite_mpa=float(max(max(rc["root1"].values(), default=0) for rc in recs)),
                root_stress_wheel_mpa=float(max(max(rc["root2"].values(), default=0) for rc in recs)),
                per_position=[dict(phi_deg=float(np.degrees(direction * rc["res"].roll)),
                                   forces_n={k: float(v) for k, v in rc["pair_load"].items()}) for rc in recs])


@dataclass(frozen=True)
class PlanetaryPlan:
    """A validated planetary run: the case (torques N mm on the satellite), positions, fidelity."""
    case: object
    positions: int
    fidelity_name: str
    warnings: tuple[str, ...] = ()

    @property
    def torques_nm(self) -> tuple[float, ...]:
        return tuple(t * 1e-3 for t in self.case.torques) if self.case.torques else ()


@dataclass
class PlanetaryRun:
    """What :func:`execute` found: the model, the loaded model, the rated torque, the rows per torque and
    direction, the drive-direction results per torque, timings."""
    plan: PlanetaryPlan
    sm: object
    lm: object
    rating: object
    torques: tuple[float, ...]
    phis: np.ndarray
    rows: list
    plot: list
    results: list
    timings: dict


def plan(case, fidelity=None, positions=None, torques_nm=None, max_output_gb: float = 2.0, file=None):
    """Validate a planetary run's settings (no FE work)."""
    import dataclasses

    from ..case import check_torques
    if torques_nm is not None:
        case = dataclasses.replace(case, torques=tuple(1e3 * t for t in check_torques(list(torques_nm), "--torque")),
                                   torque_fractions=())
    fid_name = fidelity or case.fidelity
    if fid_name not in FIDELITIES:
        raise CaseError("--fidelity", fid_name, f"one of {sorted(FIDELITIES)}", file)
    n = positions or case.positions
    if not 1 <= n <= 500:
        raise CaseError("--positions", n, "an integer in [1, 500] (as analysis.positions)", file)
    return PlanetaryPlan(case, n, fid_name)


def execute(p: PlanetaryPlan, progress=None, cache=None, store=None) -> PlanetaryRun:
    """The loaded contact of the satellite in the wheel at every torque, both directions."""
    say = progress or (lambda *a, **k: None)
    t_start = time.perf_counter()
    case = p.case
    sm = build_satellite_model(case)
    rating = rated_torque(sm.satellite, case.rating)
    torques = case.torques or tuple(f * rating.torque_Nm * 1e3 for f in case.torque_fractions)
    fid = Fidelity.from_preset(FIDELITIES[p.fidelity_name], case.design.m, slices=4)
    phis = positions(sm, p.positions)
    t0 = time.perf_counter()
    lm = prepare_satellite(sm, fid, phis, max(torques), case.far_teeth, cache, say)
    t_prep = time.perf_counter() - t0
    rb1 = sm.pair.pinion.r_base
    rows, plot, results, t_contact = [], [], [], 0.0
    for T in torques:
        t0 = time.perf_counter()
        res = solve_cycle(lm, sm, phis, T)
        results.append(res)
        t_contact += time.perf_counter() - t0
        label = f"{100 * T / (rating.torque_Nm * 1e3):.0f} % ({T / 1e3:.0f} N m)"
        entry = {"label": label, "pairs": {}, "mean_share": {}, "max_share": {}}
        for d in (1, -1):
            s = summarise(res, d, T, rb1)
            s["percent_of_rated"] = 100 * T / (rating.torque_Nm * 1e3)
            rows.append(s)
            ks = sorted(s["mean_share"])
            entry["pairs"][d] = ks
            entry["mean_share"][d] = [s["mean_share"][k] for k in ks]
            entry["max_share"][d] = [s["max_share"][k] for k in ks]
        plot.append(entry)
    say(f"rated torque (ISO 6336-3, S_F {case.rating.S_Fmin}, b {case.face_width} mm): {rating.torque_Nm:.1f} N m; "
        f"teeth modelled: satellite {list(lm.teeth1)}, wheel {list(lm.teeth2)}; {len(phis)} positions")
    timings = dict(prepare=t_prep, contact=t_contact, total=time.perf_counter() - t_start, **lm.timings)
    return PlanetaryRun(p, sm, lm, rating, tuple(torques), phis, rows, plot, results, timings)


ROW_KEYS = ["direction", "percent_of_rated", "torque_nm", "pairs_min", "pairs_max", "loaded_pairs", "mean_share",
            "te_um_mean", "te_arcsec_mean", "peak_pressure_mpa", "root_stress_satellite_mpa",
            "root_stress_wheel_mpa", "torque_residual"]


def write_files(run: PlanetaryRun, d: Path, ds) -> None:
    """results.nc, load_sharing.csv, torques.csv and load_sharing.png of a planetary run into the folder ``d``."""
    from ..outputs import write_bytes_atomic
    rows = run.rows
    write_bytes_atomic(d / "results.nc", ds.to_netcdf(engine="h5netcdf"))
    write_csv(d / "load_sharing.csv", [dict(direction=r["direction"], percent_of_rated=r["percent_of_rated"],
                                            torque_nm=r["torque_nm"], phi_deg=p["phi_deg"], pair=k, force_n=f,
                                            share=f / sum(p["forces_n"].values()))
                                       for r in rows for p in r["per_position"] for k, f in p["forces_n"].items()])
    write_csv(d / "torques.csv", [{k: (json.dumps(r[k]) if isinstance(r[k], (dict, list)) else r[k])
                                   for k in ROW_KEYS} for r in rows])
    plot_load_sharing(d / "load_sharing.png", run.plot)
