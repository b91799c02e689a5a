"""Root (fillet) stress of the whole-gear CalculiX model, read as our solver reads its own.

Our solver's root stress (:meth:`ltca.fem.compliance.BodyCompliance.root_max`, points from
:func:`ltca.fem.fillet.fillet_points`) is, per loaded tooth, the largest principal stress at points
``DEPTH`` = 0.05 mm inside the fillet on the side of the loaded flank (the tension side of an external
gear), over the fillet's whole length (outline kind 1) and the face ``|z| <= 0.45 b``; a member's root
stress is the largest over its loaded teeth. Here the same, on CalculiX's results: its nodal stresses
(``*EL FILE`` ``S``: extrapolated from the integration points and averaged at the nodes;
:func:`ltca.fem.calculix.run.read_nodal_stress`) interpolated with the quadratic shape functions at points
0.05 mm inside the same fillets (densely: every ``step`` along the fillet and along the face, so the
maximum is not missed between points), and their largest principal stress, computed here (nothing of our
compliance code is used). Ours averages its element stresses at the nodes the same way
(:func:`ltca.fem.readout.nodal_stress`) and reads 0.1 mm apart along the fillet, 1 mm along the face
(:data:`ltca.fem.fillet.ROOT_STEP`). The depth matters: near a fillet of radius rho the stress falls by about
2 x / rho over a depth x (relative stress gradient of a notch, about 2/rho), some 5 % at 0.05 mm in a
2 mm fillet. The largest principal nodal stress on the fillet surface itself is given beside it for
information (``surface``). Where the maximum lies: the tooth, the radius from the member's axis, the
face position z and the angle of the fillet's outward normal from the tooth's centre line.

Units: mm, MPa.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ltca.fem.calculix.run import read_nodal_stress
from ltca.fem.elastic import p2_shape
from ltca.fem.readout import locate_points

__all__ = ["DEPTH", "FACE_SPAN", "Member", "fillet_stress", "fillet_points", "largest_principal"]

#: depth of the read-out points below the fillet surface, mm (as ours)
DEPTH = 0.05
#: the face span of the read-out, fraction of the face width (``|z| <= FACE_SPAN b / 2``), as ours
FACE_SPAN = 0.9


@dataclass(frozen=True)
class Member:
    """One gear of the deck: name, mesh (body frame), node offset in the deck (CalculiX id = offset + i + 1),
    transverse outline (xy (n, 2), kind, side codes) of tooth 0, the loaded side code (+1 right, -1 left),
    the number of teeth, the loaded teeth and the helical twist tan(beta) / r (rad/mm; the section at z is turned
    by ``twist`` z, as in :mod:`ltca.fem.solids.full_gear`)."""
    name: str
    mesh: object
    offset: int
    outline: tuple[np.ndarray, np.ndarray, np.ndarray]
    side: int
    z: int
    teeth: tuple[int, ...]
    twist: float = 0.0

    @property
    def side_name(self) -> str:
        return "right" if self.side > 0 else "left"


def largest_principal(sig: np.ndarray) -> np.ndarray:
    """Largest principal stress of Voigt stresses (k, 6) ordered xx, yy, zz, yz, xz, xy, MPa."""
    xx, yy, zz, yz, xz, xy = np.asarray(sig, float).T
    T = np.stack([np.stack([xx, xy, xz], -1), np.stack([xy, yy, yz], -1), np.stack([xz, yz, zz], -1)], -2)
    return np.linalg.eigvalsh(T)[:, -1]


def fillet_points(outline, side: int, face_width: float, step: float = 0.1,
                  twist: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Points ``DEPTH`` inside the ``side`` fillet of tooth 0 (m, 3), about ``step`` apart along the fillet and
    along the face over ``|z| <= FACE_SPAN b / 2`` (a helical gear's turned by ``twist`` z), and the angle (deg)
    of the outward normal at each from the tooth's centre line (+y) in the transverse section."""
    xy, kind, sd = (np.asarray(a) for a in outline)
    idx = np.flatnonzero((kind == 1) & (sd == side))
    if idx.size < 2:
        return np.zeros((0, 3)), np.zeros(0)
    pts = xy[idx]
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    t_s = np.linspace(0, s[-1], max(2, int(np.ceil(s[-1] / step)) + 1))
    p = np.column_stack([np.interp(t_s, s, pts[:, 0]), np.interp(t_s, s, pts[:, 1])])
    tang = np.gradient(p, axis=0)
    tang /= np.linalg.norm(tang, axis=1, keepdims=True)
    inward = np.stack([tang[:, 1], -tang[:, 0]], 1)      # the outline's orientation, as ours (external gear)
    q = p + DEPTH * inward
    angle = np.degrees(np.arctan2(-inward[:, 0], -inward[:, 1]))
    half = 0.5 * FACE_SPAN * face_width
    zs = np.linspace(-half, half, max(2, int(np.ceil(2 * half / step)) + 1))
    X = np.column_stack([np.repeat(q, len(zs), axis=0), np.tile(zs, len(q))])
    c, s = np.cos(twist * X[:, 2]), np.sin(twist * X[:, 2])
    X[:, 0], X[:, 1] = c * X[:, 0] - s * X[:, 1], s * X[:, 0] + c * X[:, 1]
    return X, np.repeat(angle, len(zs))


def _rotate(points: np.ndarray, tooth: int, z: int) -> np.ndarray:
    a = -tooth * 2 * np.pi / z                             # tooth k is tooth 0 turned by -k 2 pi / z
    c, s = np.cos(a), np.sin(a)
    return np.column_stack([c * points[:, 0] - s * points[:, 1], s * points[:, 0] + c * points[:, 1], points[:, 2]])


def _where(k: int, X: np.ndarray, angle: float | None, value: float) -> dict:
    x, y, zc = X
    return {"tooth": int(k), "r_mm": float(np.hypot(x, y)), "z_mm": float(zc),
            "normal_deg": None if angle is None else float(angle), "value": float(value)}


def fillet_stress(frd: str | Path, members: list[Member], face_width: float, step: float = 0.1) -> dict:
    """Largest principal fillet stress per member and loaded tooth from a CalculiX ``.frd``.

    Parameters
    ----------
    frd : path
        The result file (nodal stresses written by a deck with ``stress_output``).
    members : list of Member
        The gears of the deck, with their loaded side and teeth.
    face_width : float
        b, mm.
    step : float
        Spacing of the read-out points along the fillet and the face, mm.

    Returns
    -------
    dict
        ``{name: {"max": MPa, "per_tooth": {tooth: MPa}, "at": {"tooth", "r_mm", "z_mm", "normal_deg"},
        "surface": {"max": MPa, "at": {...}}}}``: ``max`` at ``DEPTH`` inside (the compared value),
        ``surface`` the largest nodal value on the fillet surface; empty when the file has no stresses.
    """
    ids, sig = read_nodal_stress(frd)
    if ids.size == 0:
        return {}
    order = np.argsort(ids)
    ids, sig = ids[order], sig[order]
    out = {}
    for m in members:
        mesh = m.mesh
        base, angle = fillet_points(m.outline, m.side, face_width, step, m.twist)
        per, best, surf = {}, None, None
        for k in m.teeth:
            group = f"fillet_{k}_{m.side_name}"
            if group not in mesh.facets or base.size == 0:
                continue
            fnodes = np.unique(mesh.facets[group])
            near = np.flatnonzero(np.isin(mesh.tets[:, :4], fnodes).any(axis=1))   # tets touching the fillet
            X = _rotate(base, k, m.z)
            elem, bary = locate_points(mesh.nodes, mesh.tets[near], X)
            tet = mesh.tets[near][elem]                                              # (n, 10)
            pos = np.searchsorted(ids, tet + m.offset + 1).clip(0, len(ids) - 1)
            if not np.all(ids[pos] == tet + m.offset + 1):
                raise ValueError(f"{frd}: nodal stresses missing at the {m.name}'s fillet {group}")
            s = largest_principal(np.einsum("na,nav->nv", p2_shape(bary), sig[pos]))
            i = int(np.argmax(s))
            per[int(k)] = float(s[i])
            if best is None or s[i] > best["value"]:
                best = _where(k, X[i], angle[i], s[i])
            on = fnodes[np.abs(mesh.nodes[fnodes, 2]) <= 0.5 * FACE_SPAN * face_width + 1e-9]
            s_on = largest_principal(sig[np.searchsorted(ids, on + m.offset + 1).clip(0, len(ids) - 1)])
            j = int(np.argmax(s_on))
            if surf is None or s_on[j] > surf["value"]:
                surf = _where(k, mesh.nodes[on[j]], None, s_on[j])
        if best is not None:
            value = best.pop("value")
            out[m.name] = {"max": value, "per_tooth": per, "at": best,
                           "surface": {"max": surf.pop("value"), "at": surf}}
    return out
