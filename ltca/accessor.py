"""Plots on a result's dataset, by the xarray accessor ``ltca``: ``result.dataset.ltca.plot_te(ax=ax)``.

They take ``ax=None`` (a new Figure without pyplot, so no backend is touched) and return the Axes; they work the same on a
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
        """Loaded TE (arcsec, positive: the driven member lags) over the mesh cycle, a line per torque.

        The unloaded TE dashed. Returns the Axes.
        """
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
        """Largest flank pressure (MPa) over the cycle, a line per torque.

        Away from edge contact where the kind gives it. Returns the Axes.
        """
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

    def plot_pattern(self, torque: float | None = None, ax=None, vmax: float | None = None):
        """Bearing pattern: the largest contact pressure (MPa) over the mesh cycle on the flank, at one torque.

        Cylindrical pairs: over the pinion's involute roll angle (deg, root to tip) and the face width (mm);
        spiral bevel pairs: over the gear's cone distance and height over the pitch cone (mm). The edge-contact
        peaks of a sharp edge are mesh-dependent: give ``vmax`` (MPa, e.g. the ``max_flank_pressure_mpa`` of
        the torque) to saturate them.

        Parameters
        ----------
        torque : float, optional
            Torque (N m) of the dataset's ``torque`` coordinate, the nearest taken; default the largest.
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; default a new figure's.
        vmax : float, optional
            Top of the colour scale (MPa); default the pattern's peak.

        Returns
        -------
        matplotlib.axes.Axes
            The Axes, with the pattern as its first collection (for a colour bar).
        """
        ds = self._ds
        if "pressure_envelope" in ds:
            var, x, y = "pressure_envelope", "flank_roll", "face"
            xlabel, ylabel = "pinion involute roll angle [deg] (root -> tip)", "face width position [mm]"
        elif "pattern" in ds:
            var, x, y = "pattern", "L", "Rn"
            xlabel, ylabel = "gear cone distance [mm]", "height over the pitch cone [mm]"
        else:
            raise ValueError("a dataset with a bearing pattern (`pressure_envelope` of a cylindrical pair or "
                             "`pattern` of a spiral bevel pair)")
        ax = _axes(ax)
        tq = float(np.max(ds.torque.values)) if torque is None else float(torque)
        d = ds[var].sel(torque=tq, method="nearest")
        p = d.transpose(y, x).values
        ax.pcolormesh(ds[x].values, ds[y].values, p, shading="nearest", cmap="inferno", vmin=0.0,
                      vmax=float(np.nanmax(p)) if vmax is None else vmax)
        ax.set(xlabel=xlabel, ylabel=ylabel,
               title=f"{ds.attrs.get('case', '')}: bearing pattern, {float(d.torque):g} N m".lstrip(": "))
        return ax
