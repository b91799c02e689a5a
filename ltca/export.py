"""Solid models of a case's members: every tooth, as a STEP file each, for CAD, CAM and other FE codes.

A cylindrical member is the solid of :func:`ltca.fem.solids.full_gear.gear_solid` (the generated transverse
outline of every tooth, extruded or lofted along the helix; flank modifications, of micrometres, are not in the
solid; the bore, or an internal gear's outer rim; the web of a webbed member); a bevel member the solid of
:func:`ltca.fem.solids.bevel_occ.member_solid` (every tooth lofted through exact points of both generated flanks,
fused with the blank revolved about the axis). Each solid has the blank of our FE body of that member (the same
bore, rim and web; a bevel member's blank down to its mounting, :class:`ltca.bevel.model.BevelMounting`), so its
volume is the FE body's with every tooth (:func:`member_solids` returns both specs, :func:`fe_body_volume` the FE
figure). Frames: each member's body frame (z along its axis; a bevel member's origin at the pitch apex), mm.
"""
from __future__ import annotations

import logging
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .cases import Case, load_case
from .errors import CaseError

__all__ = ["ExportedMember", "MemberSolid", "StepExport", "export_step", "fe_body_volume", "member_solids"]

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class MemberSolid:
    """What is built for one member.

    member : ``"pinion"`` or ``"gear"``;  kind : ``"cylindrical"`` or ``"bevel"``;  z : teeth;
    spec : the solid's spec (:class:`ltca.fem.solids.full_gear.FullGearSpec` or
    :class:`ltca.fem.solids.bevel_occ.BevelSolidSpec`);  body : the FE body of the same member and blank
    (:class:`ltca.fem.solids.gear_body.GearBodySpec` with every tooth, or
    :class:`ltca.fem.solids.bevel_body.BevelBodySpec`, whose unmeshed teeth are copies of the meshed ones).
    """
    member: str
    kind: str
    z: int
    spec: object
    body: object


@dataclass(frozen=True)
class ExportedMember:
    """One written member: its STEP file, teeth, OCC volume (mm^3) and build time (s)."""
    member: str
    z: int
    path: Path
    volume: float
    seconds: float


@dataclass(frozen=True)
class StepExport:
    """The STEP files of a case: its name, kind and members."""
    case: str
    kind: str
    members: tuple[ExportedMember, ...]


def _cylindrical(case: Case) -> tuple[MemberSolid, ...]:
    from ltca.fem.solids.full_gear import FullGearSpec
    from ltca.fem.solids.gear_body import GearBodySpec

    from .cylindrical.model import build_model
    model = build_model(case.record)
    out = []
    for name, p, r_bore, web in (("pinion", model.pinion, model.r_bore1, model.web1),
                                 ("gear", model.gear, model.r_bore2, model.web2)):
        twist = float(np.tan(p.beta) / p.r_ref) if abs(p.beta) > 1e-12 else 0.0
        if twist and web is not None:
            raise CaseError(f"{name}.rim_thickness_mm", web[0], "no rim (a solid disc) for a helical member's solid "
                            "model: the webbed solid is built for spur gears")
        xy, kind, side = np.asarray(p.xy, float), np.asarray(p.kind), np.asarray(p.side)
        module = 2.0 * p.r_ref * np.cos(p.beta) / p.z
        spec = FullGearSpec(xy, kind, side, p.z, r_bore, model.face_width, web=web, twist=twist,
                            internal=bool(p.internal))
        teeth = tuple(range(-(p.z // 2), p.z - p.z // 2))
        body = GearBodySpec(xy, kind.astype(np.int8), side.astype(np.int8), p.z, teeth, r_bore, model.face_width,
                            twist, bool(p.internal), rim=web, far_teeth="full", h_flank=0.15 * module,
                            h_body=0.3 * module)
        out.append(MemberSolid(name, "cylindrical", p.z, spec, body))
    return tuple(out)


def _bevel(case: Case) -> tuple[MemberSolid, ...]:
    from ltca.fem.solids.bevel_body import BevelBodySpec, blank_outline
    from ltca.fem.solids.bevel_occ import BevelSolidSpec

    from .bevel.analysis import build_pair
    from .bevel.loaded_model import member_flanks
    rec = case.record
    pair = build_pair(rec)
    bl = pair.blank
    support = rec.mounting.supports(bl)
    out = []
    for name in ("pinion", "gear"):
        mb = bl.member(name)
        fl, off, shift = member_flanks(pair, name)
        # a fine map: the far sector's chords and the spaces' polar steps cost no volume worth naming
        body = BevelBodySpec(fl["concave"], fl["convex"], mb.z, off, shift, support=support[name],
                             divisions=(16, 10, 6, 8, 4, 24 * mb.z))
        jm = len(fl["concave"].v) // 2
        rn = np.asarray(fl["concave"].meta["Rn"])[:, jm]
        thick = mb.mean_normal_thickness / (np.cos(bl.data.spiral_angle) * mb.mean_pitch_radius)
        spec = BevelSolidSpec(fl["concave"], fl["convex"], mb.z, mb.pitch_angle, off, "concave", thick,
                              float(np.interp(0.0, rn, fl["concave"].u)), float(fl["concave"].v[jm]),
                              blank_outline(body), {}, np.zeros((1, 3)), 1.0, 5.0, sections=11, rows=13)
        out.append(MemberSolid(name, "bevel", mb.z, spec, body))
    return tuple(out)


def member_solids(case: Case | str | Path) -> tuple[MemberSolid, ...]:
    """The solids to build for a cylindrical or bevel case (a :class:`ltca.cases.Case`, a path or a shipped name).

    Raises :class:`ltca.errors.CaseError` for a case of another kind or a member this builder cannot make."""
    case = case if isinstance(case, Case) else load_case(case)
    if case.kind == "cylindrical":
        return _cylindrical(case)
    if case.kind == "bevel":
        return _bevel(case)
    raise CaseError("file", f"a {case.kind} case", "a cylindrical or bevel gear pair for a solid model", case.file)


def export_step(case: Case | str | Path, out_dir: str | Path,
                progress: Callable[[str], None] | None = None) -> StepExport:
    """Write each member of a case with every tooth as a STEP solid: ``<out_dir>/<case>_<member>.step``.

    Parameters
    ----------
    case : Case, str or Path
        A cylindrical or bevel case, its file or a shipped case's name.
    out_dir : str or Path
        The folder (made if missing).
    progress : callable(str), optional
        A line per member written.

    Returns
    -------
    StepExport
        The files and each solid's OCC volume (mm^3).
    """
    from ltca.fem.solids.bevel_occ import member_solid
    from ltca.fem.solids.full_gear import gear_solid
    from ltca.fem.solids.step import write_step

    from .outputs import check_out_dir
    say = progress or (lambda m: None)
    case = case if isinstance(case, Case) else load_case(case)
    check_out_dir(str(out_dir), "--step")
    out = Path(out_dir)
    stem = "".join(c if c.isalnum() or c in "-_." else "_" for c in case.name) or case.kind
    members = []
    for ms in member_solids(case):
        if ms.kind == "cylindrical":
            build = (lambda s=ms.spec: gear_solid(s))
        else:
            build = (lambda s=ms.spec: member_solid(s, say))
        try:
            res = write_step(build, out / f"{stem}_{ms.member}.step")
        except Exception as exc:      # an OCC failure names the member, not a kernel stack
            if isinstance(exc, (CaseError, OSError)):
                raise
            raise RuntimeError(f"{ms.member}: the OpenCASCADE solid could not be built ({exc})") from exc
        log.info("%s: %d teeth, %.1f mm^3, %s", ms.member, ms.z, res.volume, res.path)
        say(f"{ms.member}: {ms.z} teeth, volume {res.volume / 1e3:.2f} cm^3 -> {res.path} ({res.seconds:.1f} s)")
        members.append(ExportedMember(ms.member, ms.z, res.path, res.volume, res.seconds))
    return StepExport(case.name, case.kind, tuple(members))


def fe_body_volume(ms: MemberSolid, cache_dir=None) -> float:
    """The volume of the member's FE body with every tooth, mm^3, from its mesh record (straight-edged tetrahedra).

    A cylindrical body is meshed with every tooth (:func:`ltca.fem.solids.gear_body.build_gear_body`, at the
    ``body`` spec's sizes: 0.15 module at the teeth, 0.3 module inside, finer than an analysis's); a solid disc
    over at most 6 ``h_body`` of its face width, scaled to the whole width (its transverse sections are congruent:
    the same outline, turned along a helix), so that a wide gear meshes in minutes. A bevel body
    meshes a few teeth on its blank (:func:`ltca.fem.solids.bevel_body.build_bevel_body`): its tetrahedra are split
    at the root cone (outline edge 0) into the blank and the teeth, and the volume is the blank's plus z times the
    mean tooth's."""
    from ltca.fem.solids.step import mesh_volume
    if ms.kind == "cylindrical":
        from dataclasses import replace

        from ltca.fem.solids.gear_body import build_gear_body
        b = ms.body.face_width
        part = b if ms.body.rim is not None else min(b, 6.0 * ms.body.h_body)
        return mesh_volume(build_gear_body(replace(ms.body, face_width=part), cache_dir)) * b / part
    from ltca.fem.solids.bevel_body import blank_outline, build_bevel_body
    m = build_bevel_body(ms.body, cache_dir)
    X = m.nodes[m.tets[:, :4]]
    v = np.abs(np.einsum("ij,ij->i", np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), X[:, 3] - X[:, 0])) / 6.0
    c = X.mean(axis=1)
    O = blank_outline(ms.body)
    d = O[1] - O[0]

    def side(P):
        return d[0] * (P[..., 1] - O[0, 1]) - d[1] * (P[..., 0] - O[0, 0])
    tooth = side(np.column_stack([c[:, 2], np.hypot(c[:, 0], c[:, 1])])) * side(O[2]) < 0
    return float(v[~tooth].sum() + ms.z * v[tooth].sum() / len(ms.body.teeth))
