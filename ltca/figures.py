"""Figures without pyplot.

The library draws on :class:`matplotlib.figure.Figure` objects, so it never picks or changes a backend, never opens a window and never registers a figure with a notebook. :func:`subplots` and
:func:`figure` take pyplot's arguments; :func:`close` releases a figure's artists.
"""
from __future__ import annotations

from matplotlib import cm
from matplotlib.figure import Figure

__all__ = ["subplots", "figure", "close", "cm"]


def subplots(nrows: int = 1, ncols: int = 1, *, sharex=False, sharey=False, squeeze: bool = True,
             subplot_kw: dict | None = None, gridspec_kw: dict | None = None, **fig_kw):
    """A new figure and its grid of axes, as :func:`matplotlib.pyplot.subplots` returns them."""
    fig = Figure(**fig_kw)
    axes = fig.subplots(nrows, ncols, sharex=sharex, sharey=sharey, squeeze=squeeze, subplot_kw=subplot_kw,
                        gridspec_kw=gridspec_kw)
    return fig, axes


def figure(**fig_kw) -> Figure:
    """A new figure, as :func:`matplotlib.pyplot.figure` returns it."""
    return Figure(**fig_kw)


def close(fig: Figure) -> None:
    """Release a figure's artists (a Figure without pyplot is not registered anywhere)."""
    fig.clear()
