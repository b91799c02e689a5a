"""The root fillet of a generated tooth outline: its read-out points and the element size that resolves it.

The root stress is read as the largest principal stress at points ``DEPTH`` = 0.05 mm inside the fillet on the
side of the loaded flank (:meth:`ltca.fem.compliance.BodyCompliance.root_max`; CalculiX's is read the same way in
:mod:`ltca.verify.whole_root`), averaged at the nodes (:func:`ltca.fem.readout.nodal_stress`). Near a fillet of radius
rho the stress falls by about 2 x / rho over a depth x (relative stress gradient of a notch, about 2 / rho:
Peterson's Stress Concentration Factors, 3rd ed., 2008, ch. 1): on FZG C14 by 20 % between 0.05 and 0.3 mm. The
straight-edged quadratic tetrahedra (:mod:`ltca.fem.solids.mesh_record`) are linear in stress and replace the fillet by
chords of sagitta h^2 / (8 rho) with kinks of h / rho rad between them. At h = 1.35 mm on a 2 mm fillet (FZG C14's
flank element size at the default fidelity) the sagitta is 0.11 mm, twice the read depth, and the stress read
0.05 mm inside varies by +-10 % from element to element along the face. The read fillets are therefore meshed
at a fraction of their smallest radius of curvature (:func:`fillet_size`; 0.4 at the coarse and default
fidelities, 0.35 at the fine: ``ltca.case.FIDELITIES``), whatever the flank element size, and the reads are
``ROOT_STEP`` apart.

Units: mm. Outlines are (n, 2) transverse points with ``kind`` codes (1 fillet) and ``side`` codes (-1, +1), as
generated (``ltca.geometry.involute.ToothProfile``).
"""
from __future__ import annotations

import numpy as np

__all__ = ["DEPTH", "ROOT_STEP", "fillet_points", "fillet_radius", "fillet_size"]

#: depth of the root-stress read-out points below the fillet surface, mm
DEPTH = 0.05
#: largest spacing of the read-out points along the fillet and along the face, mm. Along the fillet as CalculiX's
#: read-out (:mod:`ltca.verify.whole_root`): 10 points over FZG C14's 3.8 mm fillet (0.42 mm apart) missed the
#: peak by up to 6 %. Along a spur face the stress is nearly flat.
ROOT_STEP = (0.1, 1.0)


def _fillet_run(xy: np.ndarray, kind: np.ndarray, side: np.ndarray, sd: int) -> np.ndarray:
    """Indices of the ``sd`` side's fillet points (outline kind 1), or of its root arc when there is no fillet."""
    idx = np.flatnonzero((kind == 1) & (side == sd))
    if idx.size < 2:
        idx = np.flatnonzero((kind == 0) & (side == sd))
    return idx


def fillet_radius(xy: np.ndarray, kind: np.ndarray, side: np.ndarray, sd: int, samples: int = 41) -> float:
    """Smallest radius of curvature (mm) of the ``sd`` side's fillet of a tooth outline.

    The fillet is resampled at ``samples`` points equally spaced in arc length and the radius of the circle
    through every three consecutive points is taken (the curvature of a smooth curve to O(ds^2)).

    Parameters
    ----------
    xy : ndarray, (n, 2)
        Transverse outline, mm.
    kind, side : ndarray, (n,)
        Outline codes (kind 1: fillet).
    sd : int
        Side of the fillet, +1 right, -1 left.
    samples : int
        Points along the fillet, >= 3.

    Returns
    -------
    float
        Smallest radius of curvature, mm; ``inf`` when the outline has no fillet on that side.
    """
    xy, kind, side = np.asarray(xy, float), np.asarray(kind), np.asarray(side)
    idx = np.flatnonzero((kind == 1) & (side == sd))
    if idx.size < 3:
        return float("inf")
    pts = xy[idx]
    s = np.r_[0.0, np.cumsum(np.hypot(*np.diff(pts, axis=0).T))]
    t = np.linspace(0.0, s[-1], max(3, samples))
    p = np.column_stack([np.interp(t, s, pts[:, 0]), np.interp(t, s, pts[:, 1])])
    a, b, c = p[:-2], p[1:-1], p[2:]
    u, v = b - a, c - a
    area2 = np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
    abc = np.linalg.norm(u, axis=1) * np.linalg.norm(c - b, axis=1) * np.linalg.norm(v, axis=1)
    with np.errstate(divide="ignore"):
        radius = abc / (2.0 * area2)
    return float(np.min(radius))


def fillet_size(xy: np.ndarray, kind: np.ndarray, side: np.ndarray, sd: int, fraction: float,
                h_flank: float) -> float | None:
    """Element size (mm) on the ``sd`` fillet: ``fraction`` of its smallest radius of curvature, at most ``h_flank``.

    Returns None when ``fraction`` is 0 (no refinement) or the outline has no fillet on that side."""
    if not fraction > 0:
        return None
    rho = fillet_radius(xy, kind, side, sd)
    return float(min(h_flank, fraction * rho)) if np.isfinite(rho) else None


def fillet_points(profile, side: int, face_width: float, internal: bool, count: tuple[int, int] | None = None,
                  step: tuple[float, float] = ROOT_STEP) -> np.ndarray:
    """Points ``DEPTH`` inside the ``side`` fillet of tooth 0, (m, 3): the root-stress read-out.

    Equally spaced in arc length along the fillet (outline kind 1; the root arc when there is none) and along the
    face over ``|z| <= 0.45 b``, turned with the helix (``tan(beta) / r_ref`` rad per mm of axial position).

    Parameters
    ----------
    profile : geometry.involute.ToothProfile
    side : int
        +1 right, -1 left fillet.
    face_width : float
        b, mm.
    internal : bool
        Internal gear (material outside the outline).
    count : (int, int), optional
        Points along the fillet and along the face; default: ``step`` apart.
    step : (float, float)
        Largest spacing along the fillet and along the face, mm (when ``count`` is None).
    """
    xy, kind, sd = np.asarray(profile.xy, float), np.asarray(profile.kind), np.asarray(profile.side)
    idx = _fillet_run(xy, kind, sd, side)
    if idx.size < 2:
        return np.zeros((0, 3))
    pts = xy[idx]
    s = np.r_[0.0, np.cumsum(np.hypot(*np.diff(pts, axis=0).T))]
    span = 0.9 * face_width
    n_s, n_z = count if count is not None else (int(np.ceil(s[-1] / step[0])) + 1, int(np.ceil(span / step[1])) + 1)
    t_s = np.linspace(0.0, s[-1], max(n_s, 2))
    p = np.column_stack([np.interp(t_s, s, pts[:, 0]), np.interp(t_s, s, pts[:, 1])])
    # the tangent of the dense outline at each point (its orientation puts the material on the right)
    j = np.clip(np.searchsorted(s, t_s), 1, len(pts) - 1)
    t = pts[np.clip(j + 1, 0, len(pts) - 1)] - pts[j - 1]
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    inward = np.stack([t[:, 1], -t[:, 0]], 1) * (-1.0 if internal else 1.0)
    p2 = p + DEPTH * inward
    z = np.linspace(-0.5 * span, 0.5 * span, max(n_z, 2))
    ang = np.tan(profile.beta) / profile.r_ref * z[None, :]
    c, s_ = np.cos(ang), np.sin(ang)
    x = c * p2[:, 0, None] - s_ * p2[:, 1, None]
    y = s_ * p2[:, 0, None] + c * p2[:, 1, None]
    return np.stack([x, y, np.broadcast_to(z, x.shape)], -1).reshape(-1, 3)
