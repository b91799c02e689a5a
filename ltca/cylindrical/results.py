"""Result records of a cylindrical loaded analysis: the xarray dataset (netCDF) and the headline summary.

Names are the same everywhere: the dataset variables, the summary keys and the plot labels.
Units: engineer's units (arcsec, MPa, N, deg, mm) at this edge.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from .edges import EDGES, edge_pattern, position_edges
from .loaded import PositionResult, te_arcsec
from .loaded_model import LoadedModel

__all__ = ["position_dataset", "summary", "pressure_on_lattice", "mesh_stiffness"]


def pressure_on_lattice(lm: LoadedModel, res: PositionResult) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pressure of one position on a fixed pinion-flank grid, (tooth, profile, face) in MPa (cells binned by
    arc length step ``ds`` and face slice; the largest cell pressure of a bin).

    Returns the field and the lattice's roll angles (deg) and axial positions (mm)."""
    from geometry.cylindrical import arc_length
    model, fid = lm.model, lm.fid
    rb = model.pinion.r_base
    s_lo, s_hi = (arc_length(r, rb) for r in model.pinion_range())
    ds = res.ds
    n_lat = max(1, int(np.floor((s_hi - s_lo) / ds)))
    field = np.zeros((len(lm.teeth1), n_lat, fid.slices))
    t_idx = np.searchsorted(np.asarray(lm.teeth1), res.tooth)
    # the contact cells follow the contact line (a sheared lattice on a helical flank): bin them by arc length
    i = np.clip(np.floor((res.s - s_lo) / ds).astype(int), 0, n_lat - 1)
    np.maximum.at(field, (t_idx, i, res.slice), res.pressure)
    s = s_lo + (np.arange(n_lat) + 0.5) * ds
    roll = np.degrees(np.sqrt(2 * s / rb))     # involute roll angle at arc length s: s = rb u^2 / 2
    b = model.face_width
    z = -0.5 * b + b / fid.slices * (np.arange(fid.slices) + 0.5)
    return field, roll, z


def mesh_stiffness(lm: LoadedModel, theta: np.ndarray, theta0: np.ndarray, torque: float) -> np.ndarray:
    """Mesh stiffness per face width along the line of action, N/(mm um), from the loaded rotation.

    c = (T / r_b1) / (b * (theta - theta0) * r_b1): the transverse normal load over the face width
    divided by the elastic approach along the line of action (ISO 6336-1 definition of c_gamma)."""
    rb, b = lm.model.pinion.r_base, lm.model.face_width
    return (torque / rb) / (b * (np.asarray(theta) - np.asarray(theta0)) * rb * 1e3)


def position_dataset(lm: LoadedModel, results: list[PositionResult], torque: float) -> xr.Dataset:
    """All positions of one torque as an xarray Dataset (engineer's units)."""
    teeth1, teeth2 = list(lm.teeth1), list(lm.teeth2)
    roll = np.degrees([r.roll for r in results])
    theta = np.array([r.theta for r in results])
    theta0 = np.array([r.theta0 for r in results])
    fields = [pressure_on_lattice(lm, r) for r in results]
    press = np.stack([f[0] for f in fields])
    edges = [position_edges(lm, r, torque) for r in results]
    ds = xr.Dataset(
        {
            "te_loaded": ("position", te_arcsec(lm, theta), {"units": "arcsec", "long_name": "loaded TE (gear lag)"}),
            "te_unloaded": ("position", te_arcsec(lm, theta0), {"units": "arcsec", "long_name": "unloaded TE"}),
            "pair_load": (("position", "pinion_tooth"), np.array([[r.pair_load.get(k, 0.0) for k in teeth1]
                                                                  for r in results]), {"units": "N"}),
            "max_pressure": ("position", np.array([r.max_pressure for r in results]),
                             {"units": "MPa", "long_name": "largest cell pressure, edge contact included"}),
            "max_flank_pressure": ("position", np.array([e["flank_peak"] for e in edges]),
                                   {"units": "MPa", "long_name": "largest flank pressure, away from edge contact"}),
            "edge_load": (("position", "edge"), np.array([e["edge_load"] for e in edges]),
                          {"units": "N", "long_name": "normal load within a Hertz half-width of an edge in contact"}),
            "edge_pattern": (("flank_roll", "face"), edge_pattern(lm, results, torque),
                             {"long_name": "edge contact on the flank lattice, bit k: edge k"}),
            "root_stress_pinion": (("position", "pinion_tooth"),
                                   np.array([[r.root1.get(k, np.nan) for k in teeth1] for r in results]),
                                   {"units": "MPa", "long_name": "max principal fillet stress"}),
            "root_stress_gear": (("position", "gear_tooth"),
                                 np.array([[r.root2.get(k, np.nan) for k in teeth2] for r in results]),
                                 {"units": "MPa", "long_name": "max principal fillet stress"}),
            "mesh_stiffness": ("position", mesh_stiffness(lm, theta, theta0, torque), {"units": "N/(mm um)"}),
            "torque_residual": ("position", np.array([r.torque_residual for r in results])),
            "torque_ratio": ("position", np.array([r.torque_ratio for r in results])),
            "pressure": (("position", "pinion_tooth", "flank_roll", "face"), press, {"units": "MPa"}),
        },
        coords={"roll": ("position", roll, {"units": "deg", "long_name": "pinion roll from the pitch point"}),
                "pinion_tooth": teeth1, "gear_tooth": teeth2,
                "flank_roll": ("flank_roll", fields[0][1], {"units": "deg", "long_name": "involute roll angle"}),
                "face": ("face", fields[0][2], {"units": "mm"}), "edge": list(EDGES)},
        attrs={"torque_nm": torque * 1e-3, "case": lm.model.case.name},
    )
    return ds


def summary(lm: LoadedModel, ds: xr.Dataset, timings: dict, converged: bool, edges: dict | None = None) -> dict:
    """Headline figures of one torque (the keys of summary.json); ``edges``: the flank peak and edge contact keys
    of :func:`ltca.cylindrical.edges.edge_summary`."""
    def f(x):
        return float(np.round(float(x), 6))
    return {
        "case": lm.model.case.name,
        "torque_nm": f(ds.attrs["torque_nm"]),
        "positions": int(ds.sizes["position"]),
        "te_loaded_ptp_arcsec": f(np.ptp(ds.te_loaded.values)),
        "te_unloaded_ptp_arcsec": f(np.ptp(ds.te_unloaded.values)),
        "te_loaded_mean_arcsec": f(ds.te_loaded.mean()),
        **(edges or {}),
        "max_contact_pressure_mpa": f(ds.max_pressure.max()),
        "max_root_stress_mpa": {"pinion": f(np.nanmax(ds.root_stress_pinion.values)),
                                "gear": f(np.nanmax(ds.root_stress_gear.values))},
        "mesh_stiffness_mean_n_per_mm_um": f(ds.mesh_stiffness.mean()),
        "max_pairs_in_contact": int((ds.pair_load > 1e-6 * float(ds.pair_load.sum("pinion_tooth").max())).sum(
            "pinion_tooth").max()),
        "converged": bool(converged),
        "max_torque_residual": float(ds.torque_residual.max()),
        "teeth_modelled": {"pinion": list(lm.body1.spec.teeth), "gear": list(lm.body2.spec.teeth)},
        "dofs": {"pinion": lm.body1.n_dofs, "gear": lm.body2.n_dofs},
        "fidelity": {k: (list(v) if isinstance(v, tuple) else v) for k, v in lm.fid.__dict__.items()},
        "timings_s": {k: f(v) for k, v in timings.items()},
    }
