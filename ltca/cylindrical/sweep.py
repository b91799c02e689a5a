"""One run over all its torques: the ``results.nc`` dataset, TE harmonics, the per-torque summary records and the
console tables of ``ltca run``.

Each torque's :func:`ltca.cylindrical.results.position_dataset` shares the positions and the flank lattice (the
lattice depends on the geometry and the position step, never on the torque), so the torques join exactly: a
``torque`` coordinate (N m), a ``position`` coordinate (pinion roll, deg), no padding. Every variable and
coordinate carries ``units`` and ``long_name``.
"""
from __future__ import annotations

import math

import numpy as np
import pandas as pd
import xarray as xr

__all__ = ["run_dataset", "te_harmonics", "torque_record", "torque_table", "harmonics_table", "NC_ENCODING",
           "MESH_ORDERS", "ROTATION_ORDERS", "check_attrs"]

MESH_ORDERS = 5          # TE amplitudes of the first mesh orders
ROTATION_ORDERS = 5      # and of the first pinion rotation orders (a full pinion revolution analysed)

#: the pressure field is mostly zero: gzip shrinks it tenfold
NC_ENCODING = {"pressure": {"zlib": True, "complevel": 4}}


def te_harmonics(te: np.ndarray, per_cycle: int, cycles: int, z1: int) -> tuple[np.ndarray, np.ndarray | None]:
    """Amplitudes (half peak-to-peak of each sine) of the first :data:`MESH_ORDERS` mesh orders of ``te``
    (..., positions), sampled ``per_cycle`` times per mesh cycle over ``cycles`` cycles; and of the first
    :data:`ROTATION_ORDERS` pinion rotation orders when whole pinion revolutions are analysed (``cycles`` a
    multiple of ``z1``), else None. Orders at or above the Nyquist limit are NaN (not resolved)."""
    te = np.asarray(te, float)
    n = te.shape[-1]
    spec = np.abs(np.fft.rfft(te - te.mean(axis=-1, keepdims=True), axis=-1)) * 2.0 / n

    def take(bins):
        out = np.full(te.shape[:-1] + (len(bins),), np.nan)
        for i, b in enumerate(bins):
            if 0 < b < n / 2:              # strictly below Nyquist: a resolved sine
                out[..., i] = spec[..., b]
        return out
    mesh = take([m * cycles for m in range(1, MESH_ORDERS + 1)])
    rot = None
    if cycles % z1 == 0:
        revs = cycles // z1
        rot = take([r * revs for r in range(1, ROTATION_ORDERS + 1)])
    return mesh, rot


def run_dataset(datasets: list[xr.Dataset], per_cycle: int, cycles: int, z1: int) -> xr.Dataset:
    """The torques' position datasets as one Dataset with a ``torque`` coordinate (N m), TE peak-to-peak and the
    TE harmonics per torque and the bearing-pattern envelope."""
    torques = [float(d.attrs["torque_nm"]) for d in datasets]
    parts = [d.drop_attrs(deep=False) for d in datasets]
    index = pd.Index(torques, name="torque")
    ds = xr.concat(parts, dim=index, data_vars="all", coords="different", compat="equals", join="exact",
                   combine_attrs="drop_conflicts")
    ds["torque"].attrs.update(units="N m", long_name="pinion torque")
    ds.attrs.update(datasets[0].attrs)
    ds.attrs.pop("torque_nm", None)
    ds.attrs.update(positions_per_cycle=per_cycle, mesh_cycles=cycles,
                    conventions="TE positive = gear lags; um along the line of action = pinion rotation x base radius")
    for var, unit in (("te_loaded", "arcsec"), ("te_loaded_um", "um")):
        ds[f"{var.replace('_um', '')}_ptp{'_um' if unit == 'um' else ''}"] = (
            ("torque",), np.ptp(ds[var].values, axis=1),
            {"units": unit, "long_name": f"loaded transmission error peak-to-peak ({unit})"})
    for var, unit in (("te_loaded", "arcsec"), ("te_loaded_um", "um")):
        mesh, rot = te_harmonics(ds[var].values, per_cycle, cycles, z1)
        suffix = "_um" if unit == "um" else ""
        ds[f"te_mesh_harmonic{suffix}"] = (("torque", "mesh_order"), mesh, {
            "units": unit, "long_name": f"loaded TE amplitude per mesh order ({unit}; NaN: above the Nyquist "
                                        "limit of the positions)"})
        if rot is not None:
            ds[f"te_rotation_harmonic{suffix}"] = (("torque", "rotation_order"), rot, {
                "units": unit, "long_name": f"loaded TE amplitude per pinion rotation order ({unit})"})
    ds = ds.assign_coords(mesh_order=("mesh_order", np.arange(1, MESH_ORDERS + 1),
                                      {"units": "1", "long_name": "harmonic of the tooth mesh frequency"}))
    if "rotation_order" in ds.dims:
        ds = ds.assign_coords(rotation_order=("rotation_order", np.arange(1, ROTATION_ORDERS + 1),
                                              {"units": "1", "long_name": "harmonic of the pinion rotation"}))
    ds["pressure_envelope"] = ds.pressure.max(("position", "pinion_tooth")).assign_attrs(
        units="MPa", long_name="bearing pattern: largest contact pressure over the positions and teeth")
    check_attrs(ds)
    return ds


def check_attrs(ds: xr.Dataset) -> None:
    """Every variable and coordinate has ``units`` and ``long_name`` (a bug otherwise)."""
    for name in list(ds.data_vars) + list(ds.coords):
        missing = {"units", "long_name"} - set(ds[name].attrs)
        if missing:
            raise AssertionError(f"results.nc: {name} has no {sorted(missing)}")


def _num(x):
    x = float(x)
    return None if not math.isfinite(x) else float(np.round(x, 6))


def torque_record(ds: xr.Dataset, head: dict) -> dict:
    """One torque's headline figures for ``summary.json`` ``torques``: the summary of that torque (the keys shared
    by every torque, such as the model size and fidelity, left out) plus TE in um and its harmonics, read from the
    run dataset ``ds`` at that torque."""
    t = head["torque_nm"]
    d = ds.isel(torque=int(np.argmin(np.abs(ds["torque"].values - t))))   # head["torque_nm"] is rounded (6 decimals)
    rec = {k: v for k, v in head.items() if k not in ("case", "teeth_modelled", "dofs", "fidelity", "positions")}
    rec["te_loaded_ptp_um"] = _num(d.te_loaded_ptp_um)
    rec["te_mesh_harmonics_arcsec"] = [_num(v) for v in d.te_mesh_harmonic.values]
    rec["te_mesh_harmonics_um"] = [_num(v) for v in d.te_mesh_harmonic_um.values]
    if "te_rotation_harmonic" in d:
        rec["te_rotation_harmonics_arcsec"] = [_num(v) for v in d.te_rotation_harmonic.values]
    return rec


def torque_table(records: list[dict]) -> str:
    """The console table of ``ltca run``: one line per torque."""
    lines = [f"{'torque':>9} {'TE ptp':>9} {'TE ptp':>8} {'TE mean':>9} {'p max':>7} {'root p.':>8} {'root g.':>8} "
             f"{'c_gamma':>9} {'pairs':>5} {'conv.':>5}",
             f"{'[N m]':>9} {'[arcsec]':>9} {'[um]':>8} {'[arcsec]':>9} {'[MPa]':>7} {'[MPa]':>8} {'[MPa]':>8} "
             f"{'[N/mm/um]':>9} {'':>5} {'':>5}"]
    for r in records:
        lines.append(f"{r['torque_nm']:9.4g} {r['te_loaded_ptp_arcsec']:9.3f} {r['te_loaded_ptp_um']:8.3f} "
                     f"{r['te_loaded_mean_arcsec']:9.2f} {r['max_contact_pressure_mpa']:7.0f} "
                     f"{r['max_root_stress_mpa']['pinion']:8.1f} {r['max_root_stress_mpa']['gear']:8.1f} "
                     f"{r['mesh_stiffness_mean_n_per_mm_um']:9.2f} {r['max_pairs_in_contact']:5d} "
                     f"{'yes' if r['converged'] else 'NO':>5}")
    return "\n".join(lines)


def harmonics_table(ds: xr.Dataset) -> str:
    """Loaded TE amplitudes per mesh order (and rotation order) and torque, arcsec and um; '-' = not resolved by
    the positions (at or above the Nyquist limit)."""
    def cell(v):
        return f"{v:8.3f}" if np.isfinite(v) else f"{'-':>8}"
    out = []
    for kind, dim, label in (("mesh", "mesh_order", "mesh order"), ("rotation", "rotation_order", "rotation order")):
        var = f"te_{kind}_harmonic"
        if var not in ds:
            continue
        orders = ds[dim].values
        out.append(f"loaded TE amplitude per {label} [arcsec | um]")
        out.append(f"{'torque [N m]':>12} " + " ".join(f"{o:>8d}" for o in orders) + " |"
                   + " ".join(f"{o:>8d}" for o in orders))
        for t in ds.torque.values:
            a, u = ds[var].sel(torque=t).values, ds[f"{var}_um"].sel(torque=t).values
            out.append(f"{t:12.4g} " + " ".join(cell(v) for v in a) + " |" + " ".join(cell(v) for v in u))
    return "\n".join(out)
