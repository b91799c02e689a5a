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

__all__ = ["position_dataset", "summary", "pressure_on_lattice", "flank_lattice", "roll_step", "mesh_stiffness",
           "MAX_LATTICE", "MIN_LATTICE"]

#: profile bins of the pressure lattice at most, and at least
MAX_LATTICE = 240
MIN_LATTICE = 40


def roll_step(results: list[PositionResult], pitch_angle: float) -> float:
    """Pinion rotation between neighbouring positions (rad); one mesh cycle when there is a single position."""
    r = np.unique(np.round([p.roll for p in results], 12))
    d = np.diff(r)
    return float(d[d > 0].min()) if (d > 0).any() else float(pitch_angle)


def flank_lattice(lm: LoadedModel, step: float) -> tuple[float, float, int]:
    """The pinion-flank pressure lattice: (u_lo, du, n) in involute roll angle (rad), from the form circle to
    the tip. It depends on the geometry and the position step only, never on the torque: the contact point's
    roll angle advances by exactly the pinion rotation, so one bin per position step (between MIN_LATTICE and
    MAX_LATTICE bins) puts each contact line in its own column of the bearing pattern without gaps."""
    rb = lm.model.pinion.r_base
    u_lo, u_hi = (float(np.sqrt(max((r / rb) ** 2 - 1.0, 0.0))) for r in lm.model.pinion_range())
    n = int(np.clip(np.ceil((u_hi - u_lo) / step - 1e-9), MIN_LATTICE, MAX_LATTICE))
    return u_lo, (u_hi - u_lo) / n, n


def pressure_on_lattice(lm: LoadedModel, res: PositionResult, step: float | None = None
                        ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pressure of one position on the fixed pinion-flank lattice (:func:`flank_lattice`), (tooth, profile, face)
    in MPa: each cell's pressure goes to every profile bin its width [s - ds/2, s + ds/2] covers, the largest
    cell pressure of a bin is kept (no peak is lost).

    ``step`` is the pinion rotation between positions (rad; default one mesh cycle / 30).
    Returns the field and the lattice's roll angles (deg) and axial positions (mm)."""
    model, fid = lm.model, lm.fid
    rb = model.pinion.r_base
    u_lo, du, n_lat = flank_lattice(lm, step if step is not None else model.pitch_angle / 30)
    field = np.zeros((len(lm.teeth1), n_lat, fid.slices), dtype=np.float32)
    t_idx = np.searchsorted(np.asarray(lm.teeth1), res.tooth)
    # the contact cells follow the contact line (a sheared lattice on a helical flank): bin them by roll angle,
    # s = rb u^2 / 2 on the involute
    ua = np.sqrt(2 * np.maximum(res.s - 0.5 * res.ds, 0.0) / rb)
    ub = np.sqrt(2 * np.maximum(res.s + 0.5 * res.ds, 0.0) / rb)
    i0 = np.clip(np.floor((ua - u_lo) / du).astype(int), 0, n_lat - 1)
    i1 = np.clip(np.floor((ub - u_lo) / du).astype(int), 0, n_lat - 1)
    for k in range(int((i1 - i0).max(initial=0)) + 1):
        sel = i0 + k <= i1
        np.maximum.at(field, (t_idx[sel], i0[sel] + k, res.slice[sel]), res.pressure[sel].astype(np.float32))
    roll = np.degrees(u_lo + (np.arange(n_lat) + 0.5) * du)
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
    step = roll_step(results, lm.model.pitch_angle)
    fields = [pressure_on_lattice(lm, r, step) for r in results]
    press = np.stack([f[0] for f in fields])
    edges = [position_edges(lm, r, torque) for r in results]
    um_loa = lm.model.pinion.r_base * 1e3          # pinion rotation (rad) -> um along the line of action
    P, PT, GT = ("position",), ("position", "pinion_tooth"), ("position", "gear_tooth")
    ds = xr.Dataset(
        {
            "te_loaded": (P, te_arcsec(lm, theta), {"units": "arcsec", "long_name": "loaded transmission error "
                                                    "(gear rotation lag)"}),
            "te_unloaded": (P, te_arcsec(lm, theta0), {"units": "arcsec", "long_name": "unloaded transmission error "
                                                       "(gear rotation lag)"}),
            "te_loaded_um": (P, theta * um_loa, {"units": "um", "long_name": "loaded transmission error along the "
                                                 "line of action"}),
            "te_unloaded_um": (P, theta0 * um_loa, {"units": "um", "long_name": "unloaded transmission error along "
                                                    "the line of action"}),
            "pair_load": (PT, np.array([[r.pair_load.get(k, 0.0) for k in teeth1] for r in results]),
                          {"units": "N", "long_name": "normal load on each pinion tooth"}),
            "max_pressure": (P, np.array([r.max_pressure for r in results]),
                             {"units": "MPa", "long_name": "largest cell pressure, edge contact included"}),
            "max_flank_pressure": (P, np.array([e["flank_peak"] for e in edges]),
                                   {"units": "MPa", "long_name": "largest flank pressure, away from edge contact"}),
            "edge_load": (("position", "edge"), np.array([e["edge_load"] for e in edges]),
                          {"units": "N", "long_name": "normal load within a Hertz half-width of an edge in contact"}),
            "edge_pattern": (("flank_roll", "face"), edge_pattern(lm, results, torque, flank_lattice(lm, step)),
                             {"units": "1", "long_name": "edge contact on the flank lattice, bit k: edge k"}),
            "root_stress_pinion": (PT, np.array([[r.root1.get(k, np.nan) for k in teeth1] for r in results]),
                                   {"units": "MPa", "long_name": "max principal fillet stress, pinion"}),
            "root_stress_gear": (GT, np.array([[r.root2.get(k, np.nan) for k in teeth2] for r in results]),
                                 {"units": "MPa", "long_name": "max principal fillet stress, gear"}),
            "mesh_stiffness": (P, mesh_stiffness(lm, theta, theta0, torque),
                               {"units": "N/(mm um)", "long_name": "mesh stiffness per face width"}),
            "torque_residual": (P, np.array([r.torque_residual for r in results]),
                                {"units": "1", "long_name": "relative torque balance residual"}),
            "torque_ratio": (P, np.array([r.torque_ratio for r in results]),
                             {"units": "1", "long_name": "gear torque / pinion torque"}),
            "pressure": (("position", "pinion_tooth", "flank_roll", "face"), press,
                         {"units": "MPa", "long_name": "contact pressure on the pinion flank at each position"}),
        },
        coords={"position": ("position", roll, {"units": "deg", "long_name": "pinion roll from the pitch point"}),
                "cycle": ("position", np.radians(roll) / lm.model.pitch_angle,
                          {"units": "1", "long_name": "position in mesh cycles from the pitch point"}),
                "roll": ("position", roll, {"units": "deg", "long_name": "pinion roll from the pitch point "
                                            "(the position coordinate)"}),
                "pinion_tooth": ("pinion_tooth", teeth1, {"units": "1", "long_name": "pinion tooth index"}),
                "gear_tooth": ("gear_tooth", teeth2, {"units": "1", "long_name": "gear tooth index"}),
                "flank_roll": ("flank_roll", fields[0][1], {"units": "deg", "long_name": "pinion involute roll "
                                                            "angle (root -> tip)"}),
                "face": ("face", fields[0][2], {"units": "mm", "long_name": "axial position from mid-face"}),
                "edge": ("edge", list(EDGES), {"units": "1", "long_name": "edge of the contact (see summary edge_contact)"})},
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
        "mesh_stiffness_mean_n_per_um": f(ds.mesh_stiffness.mean() * lm.model.face_width),
        "max_pairs_in_contact": int((ds.pair_load > 1e-6 * float(ds.pair_load.sum("pinion_tooth").max())).sum(
            "pinion_tooth").max()),
        "converged": bool(converged),
        "max_torque_residual": float(ds.torque_residual.max()),
        "teeth_modelled": {"pinion": list(lm.body1.spec.teeth), "gear": list(lm.body2.spec.teeth)},
        "dofs": {"pinion": lm.body1.n_dofs, "gear": lm.body2.n_dofs},
        "fidelity": {k: (list(v) if isinstance(v, tuple) else v) for k, v in lm.fid.__dict__.items()},
        "timings_s": {k: f(v) for k, v in timings.items()},
    }
