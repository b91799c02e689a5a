"""Cross-check of the loaded contact against CalculiX on the same gear pair (issue 4).

For each mesh position both members' tooth segments (the same teeth, bore and outline as our
compliance bodies) are meshed with quadratic tetrahedra refined in a band around the unloaded contact
lines, placed in the world at the position (pinion rotated by phi1 = phi_pitch - roll, gear by
``pair.gear_frame(phi1)``), and solved by CalculiX with frictionless surface-to-surface penalty contact:
the gear's bore (a ring's rim) is fixed, the pinion's bore is a rigid body that may only turn about its
axis under the case torque. The unloaded flanks touch along a line at zero gap, which leaves the pinion's
rotation undetermined before contact closes; the pinion is therefore placed a tiny rotation ``delta``
(``preload`` of overclosure) into the gear, and ``delta`` is added back to the rotation read.

Compared per position with ours (:func:`ltca.loaded.solve_position`): loaded TE (unloaded part removed,
arcsec of the gear), load share per pinion tooth, peak pressure, wall time. The CalculiX side is refined
(contact-band element size) ``refine`` times by 1.5 each; the finest is the reference.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fem.compliance import arc_length
from fem.export import (CcxDeck, ContactLine, ContactPairSpec, DeckBody, build_refined_segment, read_results,
                        run_ccx, write_deck)
from fem.mesh import SegmentSpec
from geometry.pair import rotation_z

from .loaded import LoadedModel, solve_position
from .tca import ARCSEC, first_contact, flank_gaps

__all__ = ["CcxSettings", "PositionComparison", "ccx_ladder", "contact_lines", "solve_ccx", "solve_ours",
           "run_calculix_validation"]


@dataclass(frozen=True)
class CcxSettings:
    """Fidelity of the CalculiX model (mm, MPa/mm)."""
    h_contact: float        # element size in the contact band
    half_band: float        # half-width of the band across the contact line
    h_flank: float          # element size on the other flank, fillet and tip surfaces
    h_body: float           # element size far from the teeth
    penalty: float          # slope of the linear pressure-overclosure law
    preload: float = 5e-4   # initial overclosure at the touching lines (removed from the TE)
    threads: int = 2


def ccx_ladder(b_nom: float, module: float, refine: int = 2, penalty_factor: float = 10.0) -> list[CcxSettings]:
    """Contact-band sizes b/2, b/3, b/4.5 ... (``refine`` + 1 levels) around the nominal Hertz half-width b.

    The penalty slope is ``penalty_factor * E / h_contact`` with E = 206 GPa (scaled with the mesh, so that
    the penalty's share of the approach stays a fixed small fraction of the Hertz near field)."""
    out = []
    for level in range(refine + 1):
        h = 0.5 * b_nom / 1.5 ** level
        out.append(CcxSettings(h_contact=h, half_band=1.3 * b_nom + h, h_flank=0.2 * module, h_body=1.0 * module,
                               penalty=penalty_factor * 206000.0 / h))
    return out


def contact_lines(lm: LoadedModel, phi1: float, cap: float, nz: int = 15) -> list[tuple[int, np.ndarray, np.ndarray]]:
    """Unloaded contact lines of the pinion teeth whose gap is below ``cap`` (mm) at ``phi1``.

    Returns (tooth, points (m, 3) in the world frame, pinion outward normals (m, 3) in the world frame)."""
    model = lm.model
    s_lo, s_hi = (arc_length(r, model.pinion.r_base) for r in model.pinion_range())
    b = model.face_width
    S, Z = np.meshgrid(np.linspace(s_lo, s_hi, 400), np.linspace(-0.5 * b, 0.5 * b, nz), indexing="ij")
    R = rotation_z(phi1)[:3, :3]
    out = []
    for k in lm.teeth1:
        fg = flank_gaps(model, phi1, k, S, Z)
        g = np.where(np.isfinite(fg.gap) & (fg.lever1 > 0), fg.gap, np.inf)
        i = np.argmin(g, axis=0)
        j = np.arange(nz)
        keep = g[i, j] < cap
        if keep.sum() < 2:
            continue
        out.append((k, fg.world[i[keep], j[keep]], fg.normals[i[keep], j[keep]] @ R.T))
    return out


def _segment(profile, teeth, r_bore, b, h_flank, h_body) -> SegmentSpec:
    return SegmentSpec(outline=np.asarray(profile.xy), kind=np.asarray(profile.kind, np.int8),
                       side=np.asarray(profile.side, np.int8), z=profile.z, teeth=tuple(teeth), r_bore=r_bore,
                       face_width=b, lead_twist=float(np.tan(profile.beta) / profile.r_ref), internal=profile.internal,
                       h_flank=h_flank, h_body=h_body)


@dataclass
class PositionComparison:
    """One solver's answer at one position (arcsec, N, MPa, s)."""
    solver: str
    roll: float
    te: float                  # loaded TE minus the unloaded part, arcsec of the gear
    pair_load: dict            # pinion tooth -> normal force, N
    max_pressure: float
    wall: float
    info: dict

    def share(self, teeth) -> dict:
        tot = sum(self.pair_load.values()) or 1.0
        return {k: self.pair_load.get(k, 0.0) / tot for k in teeth}


def solve_ours(lm: LoadedModel, roll: float, torque: float, warm=None) -> tuple[PositionComparison, object]:
    """Our loaded contact at ``roll``; wall time of the contact solve only (compliance is shared)."""
    t0 = time.perf_counter()
    r = solve_position(lm, roll, torque, warm=warm)
    wall = time.perf_counter() - t0
    te = (r.theta - r.theta0) / lm.model.pair.ratio * ARCSEC
    return PositionComparison("ours", roll, te, dict(r.pair_load), r.max_pressure, wall,
                              {"theta": r.theta, "theta0": r.theta0}), r


def solve_ccx(lm: LoadedModel, roll: float, torque: float, st: CcxSettings, workdir: str | Path,
              theta_hint: float | None = None, say=print) -> PositionComparison:
    """CalculiX at ``roll`` (rad from the pitch point) under the pinion ``torque`` (N mm)."""
    model = lm.model
    p1, p2 = model.pinion, model.gear
    phi1 = model.phi_pitch - roll
    rb1 = p1.r_base
    t_all = time.perf_counter()
    hint = theta_hint if theta_hint is not None else torque / (rb1 ** 2 * 14.0e3 * model.face_width)
    lines = contact_lines(lm, phi1, cap=1.2 * hint * rb1 + 2e-3)
    T1 = rotation_z(phi1)
    T2 = model.pair.gear_frame(phi1)
    inv1, inv2 = np.linalg.inv(T1), np.linalg.inv(T2)

    def body_lines(Tinv):
        out = []
        for _, P, N in lines:
            Q = P @ Tinv[:3, :3].T + Tinv[:3, 3]
            out.append(ContactLine(Q[0], Q[-1], N[len(N) // 2] @ Tinv[:3, :3].T))
        return out
    b = model.face_width
    t0 = time.perf_counter()
    spec1 = _segment(p1, lm.body1.spec.teeth, model.r_bore1, b, st.h_flank, st.h_body)
    spec2 = _segment(p2, lm.body2.spec.teeth, model.r_bore2, b, st.h_flank, st.h_body)
    m1 = build_refined_segment(spec1, body_lines(inv1), st.h_contact, st.half_band)
    m2 = build_refined_segment(spec2, body_lines(inv2), st.h_contact, st.half_band)
    t_mesh = time.perf_counter() - t0
    side2 = "right" if model.gear_side > 0 else "left"
    master = tuple(n for j in lm.teeth2 for n in (f"flank_{j}_{side2}", f"tip_{j}"))
    pairs = tuple(ContactPairSpec(f"P{i}", ("pinion", (f"flank_{k}_right",)), ("gear", master))
                  for i, k in enumerate(lm.teeth1))
    delta = st.preload / (rb1 * np.cos(p1.beta_b))
    deck = CcxDeck(young=model.case.young, poisson=model.case.poisson, fixed=("gear", "rim" if p2.internal else "bore"),
                   driven=("pinion", "bore"), moment=-torque, pairs=pairs, penalty=st.penalty)
    work = Path(workdir)
    work.mkdir(parents=True, exist_ok=True)
    ids = write_deck(work / "job.inp", [DeckBody("pinion", m1, rotation_z(phi1 - delta)), DeckBody("gear", m2, T2)],
                     deck)
    n_dofs = 3 * (len(m1.nodes) + len(m2.nodes))
    say(f"CalculiX roll {np.degrees(roll):+.3f} deg, h_contact {1e3 * st.h_contact:.0f} um: {n_dofs} dofs, "
        f"{len(lines)} contact line(s), meshed in {t_mesh:.1f} s; solving ...")
    wall_ccx = run_ccx(work / "job.inp", threads=st.threads)
    res = read_results(work / "job", ids["rot"], tuple(p.name for p in pairs))
    theta = delta - res.rotation
    theta0 = float(first_contact(model, phi1, lm.teeth1))
    te = (theta - theta0) / model.pair.ratio * ARCSEC
    loads = {k: float(np.linalg.norm(res.pair_force.get(p.name, np.zeros(3)))) for k, p in zip(lm.teeth1, pairs)}
    wall = time.perf_counter() - t_all
    say(f"  ccx {wall_ccx:.1f} s (all {wall:.1f} s): TE {te:.3f} arcsec, loads "
        f"{ {k: round(v, 1) for k, v in loads.items()} } N, p_max {res.max_pressure:.0f} MPa")
    return PositionComparison("calculix", roll, te, loads, res.max_pressure, wall,
                              {"theta": theta, "theta0": theta0, "n_dofs": n_dofs, "ccx_wall": wall_ccx,
                               "mesh_wall": t_mesh, "h_contact": st.h_contact, "penalty": st.penalty,
                               "reaction": res.fixed_reaction.tolist()})
