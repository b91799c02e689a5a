"""Meshing of a gear body with contact-line refinement, and the facets near those lines.

:func:`build_refined_body` meshes a whole gear body like :func:`ltca.fem.solids.gear_body.build_gear_body` with an extra
size field: ``h_contact`` in a band around given line segments on the flank, growing with the distance across
the band and with the depth below it. :func:`facets_near_lines` keeps the facets of named groups near the
lines (the contact surfaces of a CalculiX deck, :mod:`ltca.fem.calculix.deck`).

Units: mm. Point arrays are (n, 3).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from .gear_body import GearBodySpec, build_gear_body
from .mesh_record import BodyMesh

__all__ = ["ContactLine", "build_refined_body", "facets_near_lines", "line_size_expression"]


@dataclass(frozen=True)
class ContactLine:
    """A straight contact line on a flank in a body's frame (mm).

    ``p0``, ``p1`` are its end points, ``normal`` the flank's outward unit normal there."""
    p0: np.ndarray
    p1: np.ndarray
    normal: np.ndarray


def line_size_expression(line: ContactLine, h: float, half_band: float, grow_across: float,
                          grow_depth: float) -> str:
    """gmsh MathEval size: h within ``half_band`` of the line on the flank, growing linearly outside it."""
    p0, p1 = np.asarray(line.p0, float), np.asarray(line.p1, float)
    length = float(np.linalg.norm(p1 - p0))
    el = (p1 - p0) / length
    n = np.asarray(line.normal, float)
    n = n - (n @ el) * el
    n /= np.linalg.norm(n)
    t = np.cross(n, el)
    c = 0.5 * (p0 + p1)

    def coord(v: np.ndarray) -> str:
        return f"((x-({c[0]:.9g}))*({v[0]:.9g})+(y-({c[1]:.9g}))*({v[1]:.9g})+(z-({c[2]:.9g}))*({v[2]:.9g}))"

    def excess(expr: str, lim: float) -> str:   # max(|expr| - lim, 0)
        return f"0.5*(Abs({expr})-{lim:.9g}+Abs(Abs({expr})-{lim:.9g}))"

    return (f"{h:.9g}+{grow_across:.9g}*{excess(coord(t), half_band)}+{grow_depth:.9g}*Abs({coord(n)})"
            f"+{grow_across:.9g}*{excess(coord(el), 0.5 * length + half_band)}")


def build_refined_body(spec: GearBodySpec, lines: list[ContactLine], h_contact: float, half_band: float,
                          grow_across: float = 0.3, grow_depth: float = 0.6,
                          focus: tuple[tuple[ContactLine, float, float], ...] = ()) -> BodyMesh:
    """Mesh ``spec`` with elements of size ``h_contact`` (mm) within ``half_band`` (mm) of ``lines``.

    Outside the band the size grows by ``grow_across`` per mm along the flank and ``grow_depth`` per mm
    below it, up to the body's own graded sizes (``GearBodySpec.size_fields``). ``focus`` adds finer
    zones, each (line, h, half_band): typically a short piece of one contact line where the pressure peak
    is resolved (the smallest size wins)."""
    for h in (h_contact, *(f[1] for f in focus)):
        if not 0 < h <= spec.h_flank:
            raise ValueError(f"contact element size {h} must be in (0, h_flank = {spec.h_flank}]")
    exprs = tuple(line_size_expression(ln, h_contact, half_band, grow_across, grow_depth) for ln in lines)
    exprs += tuple(line_size_expression(ln, h, hb, grow_across, grow_depth) for ln, h, hb in focus)
    return build_gear_body(dataclasses.replace(spec, size_fields=exprs))


def facets_near_lines(mesh: BodyMesh, groups: tuple[str, ...], lines: list[ContactLine],
                      halo: float) -> np.ndarray:
    """The facets (k, 6) of ``groups`` whose centroid lies within ``halo`` (mm) of any of ``lines``.

    Contact surfaces restricted to where contact can occur keep CalculiX's contact search small."""
    tri = np.concatenate([mesh.facets[g] for g in groups if g in mesh.facets] or [np.zeros((0, 6), int)])
    c = mesh.nodes[tri[:, :3]].mean(axis=1)
    near = np.zeros(len(tri), dtype=bool)
    for ln in lines:
        p0, d = np.asarray(ln.p0, float), np.asarray(ln.p1, float) - np.asarray(ln.p0, float)
        t = np.clip((c - p0) @ d / max(d @ d, 1e-300), 0.0, 1.0)
        near |= np.linalg.norm(c - (p0 + t[:, None] * d), axis=1) < halo
    return tri[near]
