"""Transverse section of a tooth segment as an ordered chain of labelled curves.

The closed boundary of the section of :class:`tools.segment_mesh.spec.SegmentSpec` (teeth outlines, two radial cuts,
the bore or rim arcs), cut into pieces: every run of equal (kind, side) codes of the tooth outline is
one spline piece named after its facet group. :mod:`tools.segment_mesh.mesher` sweeps the pieces into the solid
and names its surfaces by them. Conventions as in :mod:`tools.segment_mesh.spec`.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ltca.fem.solids.planar import rot2

from .spec import SegmentSpec

__all__ = ["SectionPiece", "section_pieces"]

_KIND_NAMES = {0: "root", 1: "fillet", 2: "flank", 3: "tip"}
_SIDE_NAMES = {-1: "left", 1: "right"}


@dataclass(frozen=True)
class SectionPiece:
    """One curve of the transverse section (fields: see the comments)."""

    label: str                 # facet group name
    kind: str                  # "spline", "line" or "arc" (arc centred on the axis)
    pts: np.ndarray            # (m, 2) points through which the curve passes (arc: start, end)
    ref: np.ndarray            # (p, 2) dense polyline of the curve, for labelling surfaces


def _subsample(pts: np.ndarray, ds: float, n_min: int = 4, n_max: int = 400) -> np.ndarray:
    """Points of a dense polyline at about ``ds`` arc-length spacing, end points kept exactly."""
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    n = int(np.clip(np.ceil(s[-1] / ds) + 1, n_min, n_max))
    idx = np.unique(np.searchsorted(s, np.linspace(0.0, s[-1], n)).clip(0, len(pts) - 1))
    idx[0], idx[-1] = 0, len(pts) - 1
    return pts[np.unique(idx)]


def section_pieces(spec: SegmentSpec) -> list[SectionPiece]:
    """The closed transverse boundary as an ordered chain of pieces (clockwise over the teeth)."""
    xy = np.asarray(spec.outline, dtype=float)
    kind = np.asarray(spec.kind, dtype=int)
    side = np.asarray(spec.side, dtype=int)
    pitch = 2.0 * np.pi / spec.z
    brk = np.flatnonzero((np.diff(kind) != 0) | (np.diff(side) != 0)) + 1
    starts, ends = np.r_[0, brk], np.r_[brk, len(xy) - 1]      # run i covers starts[i]..ends[i]
    ds = 0.1
    gap = np.linalg.norm(rot2(xy[:1], -pitch) - xy[-1:])
    if gap > 1e-3:
        raise ValueError(f"outline end points are {gap:.3g} mm apart from their neighbours' after a "
                         f"rotation by 2 pi / z: outline must run from mid-gap +pi/z to -pi/z")
    pieces: list[SectionPiece] = []
    for k in spec.teeth:
        for a, b in zip(starts, ends):
            if b <= a:
                continue
            dense = rot2(xy[a:b + 1], -k * pitch)
            kd, sd = int(kind[a]), int(side[a])
            if kd == 0:
                label = "root"
            elif kd == 3 or sd == 0:
                label = f"{_KIND_NAMES[kd]}_{k}"
            else:
                label = f"{_KIND_NAMES[kd]}_{k}_{_SIDE_NAMES[sd]}"
            pieces.append(SectionPiece(label, "spline", _subsample(dense, ds), dense))
    p_end, p_start = pieces[-1].pts[-1], pieces[0].pts[0]
    b_end = p_end * spec.r_bore / np.linalg.norm(p_end)
    b_start = p_start * spec.r_bore / np.linalg.norm(p_start)
    cut = "cut"
    closing = "rim" if spec.internal else "bore"
    pieces.append(SectionPiece(cut, "line", np.array([p_end, b_end]), np.linspace(p_end, b_end, 50)))
    a0 = np.arctan2(b_end[1], b_end[0])
    span = len(spec.teeth) * pitch                               # counter-clockwise back to b_start
    n_arc = int(np.ceil(span / (np.pi / 2)))
    ang = a0 + np.linspace(0.0, span, n_arc + 1)
    for i in range(n_arc):
        t = np.linspace(ang[i], ang[i + 1], 200)
        ref = spec.r_bore * np.c_[np.cos(t), np.sin(t)]
        pieces.append(SectionPiece(closing, "arc", ref[[0, -1]], ref))
    pieces.append(SectionPiece(cut, "line", np.array([b_start, p_start]), np.linspace(b_start, p_start, 50)))
    return pieces
