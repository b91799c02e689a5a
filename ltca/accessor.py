"""Plots on a result's dataset, by the xarray accessor ``ltca``: ``result.dataset.ltca.plot_te(ax=ax)``. They take
``ax=None`` (a new Figure without pyplot, so no backend is touched) and return the Axes; they work the same on a
dataset read back by :func:`ltca.open_result`, whatever the gear kind (the one vocabulary of :mod:`ltca.results`).
"""
from __future__ import annotations

import numpy as np
import xarray as xr

__all__ = ["LtcaAccessor"]


def _axes(ax):
    if ax is not None:
        return ax
    from .figures import subplots
    return subplots(figsize=(7, 4))[1]


@xr.register_dataset_accessor("ltca")
class LtcaAccessor:
    """Plots of an LTCA dataset (xarray accessor ``ds.ltca``)."""

    def __init__(self, ds: xr.Dataset):
        self._ds = ds

    def plot_te(self, ax=None, unloaded: bool = True):
        """Loaded TE (arcsec, positive: the driven member lags) over the mesh cycle, a line per torque; the unloaded
        TE dashed. Returns the Axes."""
        ax = _axes(ax)
        ds = self._ds
        x = ds.cycle.values if "cycle" in ds.coords else ds.position.values
        for t in np.atleast_1d(ds.torque.values):
            d = ds.sel(torque=t)
            ax.plot(x, d.te_loaded.values, "o-", ms=3, label=f"{float(t):g} N m")
        if unloaded and "te_unloaded" in ds:
            d = ds.te_unloaded.isel(torque=0) if "torque" in ds.te_unloaded.dims else ds.te_unloaded
            ax.plot(x, d.values, "k--", lw=1, label="unloaded")
        ax.set(xlabel="position [mesh cycles]" if "cycle" in ds.coords else "position",
               ylabel="transmission error [arcsec]", title=str(ds.attrs.get("case", "")))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        return ax

    def plot_max_pressure(self, ax=None):
        """Largest flank pressure (MPa, away from edge contact where the kind gives it) over the cycle, a line per
        torque. Returns the Axes."""
        ax = _axes(ax)
        ds = self._ds
        var = "max_flank_pressure" if "max_flank_pressure" in ds else "max_pressure"
        x = ds.cycle.values if "cycle" in ds.coords else ds.position.values
        for t in np.atleast_1d(ds.torque.values):
            ax.plot(x, ds[var].sel(torque=t).values, "o-", ms=3, label=f"{float(t):g} N m")
        ax.set(xlabel="position [mesh cycles]", ylabel=f"{ds[var].attrs.get('long_name', var)} [MPa]")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        return ax
