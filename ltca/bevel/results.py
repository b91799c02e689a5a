"""Outputs of a bevel LTCA run: results.nc (xarray), summary.json, bearing-pattern VTU point clouds and the plots.

Figures per torque: loaded and unloaded TE (arcsec), peak pressure (interior cells and cells at an edge apart),
load sharing of the tooth pairs, root stress (largest principal, 0.05 mm inside the fillet) and mesh stiffness
(the normal force over the elastic approach at the torque-weighted gear lever, N/um: a secant value).  The bearing
pattern is the largest pressure over the cycle on the gear flank, gridded in the gear's axial section (cone
distance L, height Rn over the pitch cone).  Loaded contact ellipses are fitted to each pair's pressure
(p^2 quadratic in the tangent-plane coordinates, the elliptic Hertz shape).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr
from scipy.interpolate import griddata

from ltca.geometry.bevel.tca import RAD_PER_ARCSEC, tca

from .loaded import BevelPosition
from .loaded_model import LOADED

__all__ = ["edge_band", "position_arrays", "pattern_grid", "fit_ellipse", "bevel_dataset", "write_files"]

_BINS = (121, 61)


def fit_ellipse(xi: np.ndarray, eta: np.ndarray, p: np.ndarray):
    """Least-squares elliptic-Hertz fit p^2 = p0^2 (1 - (y - c)' M (y - c)) over the loaded cells.

    Returns (p0 MPa, a, b mm with a >= b, centre (2,), axes (2, 2) columns along a and b), or None when the cells
    do not define an ellipse (fewer than 8 loaded, or an open pattern cut by an edge)."""
    m = p > 0
    if m.sum() < 8:
        return None
    y = np.stack([xi[m], eta[m]], 1)
    X = np.column_stack([np.ones(m.sum()), y, y[:, 0] ** 2, y[:, 1] ** 2, y[:, 0] * y[:, 1]])
    c = np.linalg.lstsq(X, p[m] ** 2, rcond=None)[0]
    Q = np.array([[c[3], c[5] / 2], [c[5] / 2, c[4]]])
    w, V = np.linalg.eigh(Q)
    if not np.all(w < 0):
        return None
    Qi = np.linalg.inv(Q)
    centre = -0.5 * Qi @ c[1:3]
    p02 = c[0] - 0.25 * c[1:3] @ Qi @ c[1:3]
    if p02 <= 0:
        return None
    ax = np.sqrt(p02 / -w)                      # semi-axes along V's columns
    order = np.argsort(ax)[::-1]
    return float(np.sqrt(p02)), float(ax[order[0]]), float(ax[order[1]]), centre, V[:, order]


def edge_band(module: float) -> float:
    """Width (mm) of the band along the flank edges left out of the interior peak pressure: 0.12 x the outer
    module (0.61 mm for the shipped pair; its interior peak then agrees within 0.3 % over the coarse, default and
    fine fidelities at 175 N m, while the peak of the cells next to an edge grows with refinement)."""
    return 0.12 * module


def position_arrays(res: list[BevelPosition], torque_nm: float, band: float = 0.6) -> dict[str, np.ndarray]:
    """Per-position figures of one torque (arrays over positions; shares over positions x pairs)."""
    # the project's sign: the gear's lag, positive (BevelPosition.te is the gear's rotation ahead of rigid)
    te = -np.array([r.te for r in res]) / RAD_PER_ARCSEC
    te0 = -np.array([r.te0 for r in res]) / RAD_PER_ARCSEC
    pmax = np.array([r.max_pressure for r in res])
    inner = np.array([r.pressure[r.edge_dist > band].max() if np.any(r.edge_dist > band) else 0.0 for r in res])
    edge_frac = np.array([r.force[r.edge != ""].sum() / max(r.force.sum(), 1e-300) for r in res])
    share = np.array([[r.pair_share.get(j, 0.0) for j in LOADED] for r in res])
    root1 = np.array([max(r.root1.values()) if r.root1 else np.nan for r in res])
    root2 = np.array([max(r.root2.values()) if r.root2 else np.nan for r in res])
    T2 = abs(torque_nm) * 1e3
    # secant mesh stiffness: total normal force over the approach theta v_bar at the lever v_bar = T2 / sum F
    F = np.array([r.force.sum() for r in res])
    th = np.array([r.theta for r in res])
    k = np.where((F > 0) & (th > 0), F * F / np.maximum(th * T2, 1e-300) / 1e3, np.nan)
    return dict(te=te, te0=te0, pmax=pmax, pmax_interior=inner, edge_fraction=edge_frac, share=share,
                root1=root1, root2=root2, stiffness=k,
                residual=np.array([r.torque_residual for r in res]),
                pinion_balance=np.array([r.pinion_balance for r in res]))


def pattern_grid(pair, res: list[BevelPosition]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Largest pressure over the cycle on the gear flank in its axial section: (L bins, Rn bins, (nRn, nL) MPa)."""
    bl = pair.blank
    A0, Ai = bl.outer_cone_distance, bl.inner_cone_distance
    root, face = bl.cones("gear", np.array([Ai, A0]))
    Lb = np.linspace(Ai, A0, _BINS[0])
    Rb = np.linspace(root.min(), face.max(), _BINS[1])
    P = np.zeros((_BINS[1], _BINS[0]))
    GL, GR = np.meshgrid(Lb, Rb)
    for r in res:
        for j in np.unique(r.pair):
            m = r.pair == j
            if np.count_nonzero(r.pressure[m]) == 0 or m.sum() < 4:
                continue
            # linear interpolation of the cell pressures (zero on the unloaded cells around the ellipse)
            box = (GL >= r.L2[m].min()) & (GL <= r.L2[m].max()) & (GR >= r.Rn2[m].min()) & (GR <= r.Rn2[m].max())
            v = griddata((r.L2[m], r.Rn2[m]), r.pressure[m], (GL[box], GR[box]), method="linear", fill_value=0.0)
            P[box] = np.maximum(P[box], np.nan_to_num(v))
    return Lb, Rb, P


def _ellipse_outline(r: BevelPosition, j: int) -> np.ndarray | None:
    """The fitted loaded ellipse of pair j in the gear axial section, (60, 2) (L, Rn), or None."""
    m = r.pair == j
    fit = fit_ellipse(r.xi[m], r.eta[m], r.pressure[m])
    if fit is None:
        return None
    _, a, b, c, V = fit
    X = np.column_stack([np.ones(m.sum()), r.xi[m], r.eta[m]])
    coef = np.linalg.lstsq(X, np.column_stack([r.L2[m], r.Rn2[m]]), rcond=None)[0]
    s = np.linspace(0, 2 * np.pi, 60)
    pts = c[None] + np.outer(a * np.cos(s), V[:, 0]) + np.outer(b * np.sin(s), V[:, 1])
    return np.column_stack([np.ones(len(s)), pts]) @ coef


def bevel_dataset(case, pair, asm, fid, runs: dict, torques, timings: dict) -> tuple[xr.Dataset, dict, dict]:
    """The run dataset and summary of a bevel run in the one vocabulary (:mod:`ltca.results`), and what the plots
    need (per-torque arrays, patterns, ellipse outlines, unloaded paths)."""
    per, patterns, outlines, paths = {}, {}, {}, {}
    for side, rr in runs.items():
        tc = tca(rr["lm"].pair, side, asm=asm, steps_per_cycle=16, max_cycles=3.0)
        paths[side] = (tc.gear_L, tc.gear_Rn)
        for T in torques:
            if T in rr:
                per[T] = position_arrays(rr[T], T, edge_band(pair.blank.data.module))
                patterns[T] = pattern_grid(pair, rr[T])
                every = max(len(rr[T]) // 6, 1)
                outlines[T] = [e for r in rr[T][::every] for j in LOADED if (e := _ellipse_outline(r, j)) is not None]
    tq = list(torques)
    first = next(iter(runs.values()))
    phi = np.array([r.phi1 for r in first[next(k for k in first if k != "lm")]])
    c1 = 2 * np.pi / pair.blank.pinion.z
    b = pair.blank.data.face_width
    Lb, Rb, _ = patterns[tq[0]]
    for T in tq:
        per[T]["stiffness_per_mm"] = per[T]["stiffness"] / b
    ds = xr.Dataset(
        {name: (("torque", "position"), np.stack([per[T][key] for T in tq]), {"units": u, "long_name": ln})
         for name, key, u, ln in (("te_loaded", "te", "arcsec", "loaded transmission error (gear lag, positive)"),
                                  ("te_unloaded", "te0", "arcsec", "unloaded transmission error (gear lag, positive)"),
                                  ("max_pressure", "pmax", "MPa", "largest cell pressure, edge contact included"),
                                  ("max_flank_pressure", "pmax_interior", "MPa",
                                   "largest flank pressure, beyond 0.12 module from the flank edges"),
                                  ("edge_fraction", "edge_fraction", "1", "normal force at edges / total"),
                                  ("root_stress_pinion", "root1", "MPa", "max principal fillet stress, pinion"),
                                  ("root_stress_gear", "root2", "MPa", "max principal fillet stress, gear"),
                                  ("mesh_stiffness", "stiffness_per_mm", "N/(mm um)",
                                   "secant mesh stiffness (normal) per face width"),
                                  ("mesh_stiffness_total", "stiffness", "N/um", "secant mesh stiffness (normal)"),
                                  ("torque_residual", "residual", "1", "relative torque balance residual"))},
        coords={"torque": ("torque", np.array(tq), {"units": "N m", "long_name": "pinion torque (sign: flank)"}),
                "position": ("position", np.degrees(phi), {"units": "deg",
                                                           "long_name": "pinion angle from the mean point"}),
                "cycle": ("position", phi / c1, {"units": "1", "long_name": "position in mesh cycles from the "
                                                                           "mean point"}),
                "pair": ("pair", np.array(LOADED), {"units": "1", "long_name": "tooth pair (pinion tooth +j)"}),
                "L": ("L", Lb, {"units": "mm", "long_name": "gear cone distance"}),
                "Rn": ("Rn", Rb, {"units": "mm", "long_name": "gear height over the pitch cone"})})
    ds["share"] = (("torque", "position", "pair"), np.stack([per[T]["share"] for T in tq]),
                   {"units": "1", "long_name": "share of the gear torque per tooth pair"})
    ds["pattern"] = (("torque", "Rn", "L"), np.stack([patterns[T][2] for T in tq]),
                     {"units": "MPa", "long_name": "largest pressure over the cycle on the gear flank"})
    ds.attrs.update(case=case.name, fidelity=fid.name, assembly=str(asm),
                    conventions="TE positive = gear lags; position: pinion angle from the mean point")
    records = [_torque_summary(per[T], runs, T) for T in tq]
    summary = dict(case=case.name, kind="bevel", fidelity=fid.name, positions=len(phi), **records[0],
                   assembly=dict(E_mm=asm.E, P_mm=asm.P, G_mm=asm.G, sigma_deg=float(np.rad2deg(asm.d_sigma))),
                   torques=records, timings_s=timings,
                   notes=dict(max_contact_pressure_mpa="with the cells at a flank edge: singular at a sharp edge and "
                                                       "mesh-dependent (grows as the cells shrink); "
                                                       "max_flank_pressure_mpa leaves out a band of 0.12 module "
                                                       "along the edges and converges (ltca convergence gives the "
                                                       "ladder)",
                              mesh_stiffness="secant: total normal force over the elastic approach at the "
                                             "torque-weighted gear lever, mean over the cycle",
                              te="arcsec of the gear; positive: the gear lags"))
    summary["converged"] = all(r["converged"] for r in records)
    summary["max_torque_residual"] = max(r["max_torque_residual"] for r in records)
    return ds, summary, dict(per=per, patterns=patterns, outlines=outlines, paths=paths)


def write_files(d: Path, case, pair, ds: xr.Dataset, plotdata: dict, runs: dict, torques) -> list[str]:
    """results.nc, the bearing-pattern VTU per torque and the plots of a bevel run, into the folder ``d``."""
    from ..outputs import write_netcdf_atomic
    from .plots import plot_all
    for side, rr in runs.items():
        for T in torques:
            if T in rr:
                _write_vtu(d / f"bearing_pattern_{T:g}Nm.vtu", rr[T])
    write_netcdf_atomic(d / "results.nc", ds)            # in memory first: HDF5 aborts on ENOSPC
    return plot_all(d, case.name, pair, ds, plotdata["per"], plotdata["patterns"], plotdata["outlines"],
                    plotdata["paths"], runs)


def _torque_summary(a: dict, runs: dict, T: float) -> dict:
    side = "concave" if T > 0 else "convex"
    res = runs[side][T]
    edges = sorted({e for r in res for e, f in r.edge_load().items() if f > 0.01 * r.force.sum()})
    residual = float(a["residual"].max())
    return dict(torque_nm=float(T), flank="working" if T > 0 else "coast",
                te_loaded_ptp_arcsec=float(np.ptp(a["te"])), te_unloaded_ptp_arcsec=float(np.ptp(a["te0"])),
                te_loaded_mean_arcsec=float(np.mean(a["te"])),
                max_flank_pressure_mpa=float(a["pmax_interior"].max()),
                max_contact_pressure_mpa=float(a["pmax"].max()),
                edge_locations=edges, edge_force_fraction_max=float(a["edge_fraction"].max()),
                max_pair_share=float(a["share"].max()),
                max_root_stress_mpa=dict(pinion=float(np.nanmax(a["root1"])), gear=float(np.nanmax(a["root2"]))),
                mesh_stiffness_mean_n_per_um=float(np.nanmean(a["stiffness"])),
                mesh_stiffness_mean_n_per_mm_um=float(np.nanmean(a["stiffness_per_mm"])),
                converged=bool(residual < 1e-6 and all(r.residual < 1e-6 for r in res)),
                max_torque_residual=residual,
                pinion_torque_balance=[float(a["pinion_balance"].min()), float(a["pinion_balance"].max())])


def _write_vtu(path: Path, res: list[BevelPosition]) -> None:
    """Cells of all positions as a point cloud on pinion tooth 0 (pinion body frame): pressure, position, pair."""
    import meshio

    from ..vtu import write_vtu_file
    m = [r.force > 0 for r in res]
    pts = np.concatenate([r.r1[k] for r, k in zip(res, m)]) if res else np.zeros((0, 3))
    data = {"pressure_MPa": np.concatenate([r.pressure[k] for r, k in zip(res, m)]),
            "position": np.concatenate([np.full(k.sum(), i, float) for i, k in enumerate(m)]),
            "pair": np.concatenate([r.pair[k].astype(float) for r, k in zip(res, m)])}
    write_vtu_file(path, meshio.Mesh(pts, [("vertex", np.arange(len(pts))[:, None])], point_data=data))
