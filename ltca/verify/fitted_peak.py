"""The elliptic-fit peak of CalculiX's contact pressure over face slices, and where it is.

Nodal contact pressures of penalty contact on quadratic faces scatter by tens of per cent at a few elements per
contact width; the fit of p^2 by a parabola across the band (:func:`ltca.cylindrical.iso6336.fit_elliptic`) is the
robust peak, the same estimator ``ltca validate`` uses for ours. Per contact line and face slice, the slave nodes
within 0.05 mm of the line's tangent plane with a positive pressure enter; a slice with fewer than five nodes
above a quarter of its largest pressure is skipped.
"""
from __future__ import annotations

import numpy as np

__all__ = ["fitted_peak"]


def fitted_peak(mesh, lines, nodes: np.ndarray, pressure: np.ndarray, b: float, slices: int = 14,
                window: tuple[float, float] | None = None) -> dict:
    """Largest elliptic-fit peak over face slices of the slave nodes, and where.

    Parameters
    ----------
    mesh
        The slave body's mesh (``nodes`` (n, 3) in its own frame, mm).
    lines : list of ContactLine
        The unloaded contact lines in the same frame.
    nodes, pressure : ndarray
        CalculiX's contact nodes (1-based ids into ``mesh.nodes``; others are ignored) and their pressure, MPa.
    b : float
        Face width, mm: the slices are ``b / slices`` long.
    slices : int
        Number of face slices.
    window : tuple of float, optional
        z range (mm): only the slices inside it count (cut into slices of about ``b / slices``).

    Returns
    -------
    dict
        ``p`` the peak (MPa, 0 when no slice fits), ``line`` the index of its contact line (-1 when none),
        ``r_mm`` the radius of the fit's centre in the slave's frame, ``z_mm`` the slice's mid z, ``half_width_um``
        the fit's half-width and ``nodes`` the nodes fitted.
    """
    from ..cylindrical.iso6336 import fit_elliptic
    ok = (nodes >= 1) & (nodes <= len(mesh.nodes)) & (pressure > 0)
    X, p = mesh.nodes[nodes[ok] - 1], pressure[ok]
    best = {"p": 0.0, "line": -1, "r_mm": float("nan"), "z_mm": float("nan"), "half_width_um": float("nan"),
            "nodes": 0}
    edges = np.linspace(-0.5 * b, 0.5 * b, slices + 1)
    if window is not None:
        n = max(1, int(round((window[1] - window[0]) / (b / slices))))
        edges = np.linspace(window[0], window[1], n + 1)
    for i, ln in enumerate(lines):
        p0, d = np.asarray(ln.p0), np.asarray(ln.p1) - np.asarray(ln.p0)
        el = d / np.linalg.norm(d)
        t_dir = np.cross(np.asarray(ln.normal), el)
        t_dir /= np.linalg.norm(t_dir)
        near = np.abs((X - p0) @ np.asarray(ln.normal)) < 0.05
        t = (X - p0) @ t_dir
        for lo, hi in zip(edges[:-1], edges[1:]):
            m = near & (X[:, 2] >= lo) & (X[:, 2] <= hi)
            if np.count_nonzero(m & (p > 0.25 * p[m].max(initial=0))) >= 5:
                with np.errstate(invalid="ignore"):
                    pk, half, x0 = fit_elliptic(t[m], p[m])
                if np.isfinite(pk) and pk > best["p"]:
                    zc = 0.5 * (lo + hi)
                    on_line = p0 + el * (zc - p0[2]) / el[2] if abs(el[2]) > 1e-12 else p0
                    c = on_line + x0 * t_dir
                    best = {"p": float(pk), "line": i, "r_mm": float(np.hypot(c[0], c[1])), "z_mm": float(zc),
                            "half_width_um": float(1e3 * half), "nodes": int(np.count_nonzero(m))}
    return best
