"""Cross-check of the loaded contact against CalculiX on the same gear pair.

For each mesh position both members' whole-gear bodies (the same teeth, bore and outline as our
compliance bodies) are meshed with quadratic tetrahedra refined in a band around the unloaded contact
lines, placed in the world at the position (pinion rotated by phi1 = phi_pitch - roll, gear by
``pair.gear_frame(phi1)``), and solved by CalculiX with frictionless surface-to-surface penalty contact:
the gear's bore (a ring's rim) is fixed, the pinion's bore is a rigid body that may only turn about its
axis under the case torque. The unloaded flanks touch along a line at zero gap, which leaves the pinion's
rotation undetermined before contact closes; the pinion is therefore placed a tiny rotation ``delta``
(``preload`` of overclosure) into the gear, and ``delta`` is added back to the rotation read.

Compared per position with ours (:func:`ltca.cylindrical.loaded.solve_position`): loaded TE (unloaded part removed,
arcsec of the gear), load share per pinion tooth, peak pressure, wall time. The validation command that
runs the comparison is :mod:`ltca.verify.crosscheck`; CalculiX's own convergence ladders are maintainer tooling
(``tools/calculix_refs``, not installed).
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ltca.geometry.cylindrical import arc_length
from ltca.fem.calculix.deck import CcxDeck, ContactPairSpec, DeckBody, write_deck
from ltca.fem.calculix.run import read_results, run_ccx
from ltca.fem.solids import ContactLine, build_refined_body, facets_near_lines
from ltca.fem.compliance import body_spec
from ltca.geometry.pair import rotation_z

from ..cylindrical.loaded_model import LoadedModel
from ..cylindrical.loaded import solve_position
from ..cylindrical.tca import ARCSEC_PER_RAD, first_contact, flank_gaps

__all__ = ["CcxSettings", "Focus", "penalty_slope", "PositionComparison", "ccx_ladder", "contact_lines", "solve_ccx",
           "solve_ours", "narrowest_contact"]


@dataclass(frozen=True)
class CcxSettings:
    """Fidelity of the CalculiX model (mm, MPa/mm)."""
    h_contact: float        # element size in the contact band
    half_band: float        # half-width of the band across the contact line
    h_flank: float          # element size on the other flank, fillet and tip surfaces
    h_body: float           # element size far from the teeth
    penalty: float          # slope of the linear pressure-overclosure law
    grow_across: float = 0.4  # size growth per mm across the band (along the flank)
    grow_depth: float = 0.8   # size growth per mm below the flank
    halo: float = 0.6         # contact surfaces extend this far from the unloaded contact lines
    preload: float = 0.2      # initial overclosure rotation, as a fraction of an ISO-stiffness estimate of the TE
    threads: int = 2


@dataclass(frozen=True)
class Focus:
    """A finer zone of the CalculiX mesh on one contact line, where its peak pressure is resolved (mm).

    The contact line of pinion tooth ``tooth`` between z = ``z0`` -+ ``half_length`` gets elements of size
    ``h`` within ``half_band`` across it; the peak pressure is then fitted in that window only."""
    tooth: int
    z0: float
    half_length: float
    h: float
    half_band: float


def penalty_slope(h: float, factor: float = 10.0, young: float = 206000.0) -> float:
    """Slope (MPa/mm) of CalculiX's linear pressure-overclosure law for contact elements of size ``h`` (mm):
    ``factor * E / h``. Scaled with the mesh, the penalty's softening of the contact (a layer of
    overclosure p / slope under the Hertz pressure) vanishes with the element size instead of biasing the
    converged peak pressure (by ~2 % at b ~ 100 um with the slope held at a 150 um band's)."""
    return factor * young / h


def ccx_ladder(b_nom: float, module: float, refine: int = 2, penalty_factor: float = 10.0,
               h0: float | None = None, body: tuple[float, float] = (0.3, 1.3)) -> list[CcxSettings]:
    """Contact-band sizes 3b/4, b/2, b/3 ... (``refine`` + 1 levels) around the nominal Hertz half-width b.

    ``h0`` (mm) replaces the first size 3b/4 (coarser ladders for long contact lines, where only the TE
    is compared and the TE hardly depends on the contact-band size); ``body`` are the element sizes on the
    other flank surfaces and far from the teeth, in modules (default: our default fidelity's).
    The penalty slope is ``penalty_factor * E / h_contact`` with E = 206 GPa (scaled with the mesh, so that
    the penalty's share of the approach stays a fixed small fraction of the Hertz near field: 0.3 % of the
    FZG pitch-point TE at b/2). The contact surfaces reach 2 b either side of the unloaded contact line."""
    out = []
    for level in range(refine + 1):
        h = (h0 or 0.75 * b_nom) / 1.5 ** level
        out.append(CcxSettings(h_contact=h, half_band=1.3 * b_nom + h, h_flank=body[0] * module,
                               h_body=body[1] * module, penalty=penalty_slope(h, penalty_factor), halo=2.0 * b_nom))
    return out


def contact_lines(lm: LoadedModel, phi1: float, cap: float, nz: int = 15,
                  theta0: float = 0.0) -> list[tuple[int, np.ndarray, np.ndarray]]:
    """Unloaded contact lines of the pinion teeth whose gap is below ``cap`` (mm) at ``phi1``.

    ``theta0`` (rad): the gaps are counted after this rigid pinion rotation to first contact (a pair with
    backlash, such as the eccentric internal pair). Returns (tooth, points (m, 3) in the world frame,
    pinion outward normals (m, 3) in the world frame)."""
    model = lm.model
    s_lo, s_hi = (arc_length(r, model.pinion.r_base) for r in model.pinion_range())
    b = model.face_width
    S, Z = np.meshgrid(np.linspace(s_lo, s_hi, 400), np.linspace(-0.5 * b, 0.5 * b, nz), indexing="ij")
    R = rotation_z(phi1)[:3, :3]
    out = []
    for k in lm.teeth1:
        fg = flank_gaps(model, phi1, k, S, Z)
        g = np.where(np.isfinite(fg.gap) & (fg.lever1 > 0), fg.gap - fg.lever1 * theta0, np.inf)
        i = np.argmin(g, axis=0)
        j = np.arange(nz)
        keep = g[i, j] < cap
        if keep.sum() < 2:
            continue
        out.append((k, fg.world[i[keep], j[keep]], fg.normals[i[keep], j[keep]] @ R.T))
    return out


def _window(line: ContactLine, focus: Focus) -> ContactLine:
    """The piece of ``line`` between z = z0 -+ half_length (clipped to the line)."""
    p0, p1 = np.asarray(line.p0, float), np.asarray(line.p1, float)
    f = (np.clip([focus.z0 - focus.half_length, focus.z0 + focus.half_length], min(p0[2], p1[2]), max(p0[2], p1[2]))
         - p0[2]) / (p1[2] - p0[2])
    return ContactLine(p0 + f[0] * (p1 - p0), p0 + f[1] * (p1 - p0), line.normal)


def _fitted_peak(mesh, lines: list[ContactLine], nodes: np.ndarray, pressure: np.ndarray, b: float,
                 slices: int = 14, window: tuple[float, float] | None = None) -> float:
    """Largest elliptic-fit peak (Hertz shape across the contact line) over face slices of the slave nodes
    (:func:`ltca.verify.fitted_peak.fitted_peak`, which also says where)."""
    from .fitted_peak import fitted_peak
    return fitted_peak(mesh, lines, nodes, pressure, b, slices, window)["p"]


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
    te = (r.theta - r.theta0) / lm.model.pair.ratio * ARCSEC_PER_RAD
    mid = np.abs(r.z) < 0.35 * lm.model.face_width
    p_mid = float(r.pressure[mid].max()) if mid.any() else 0.0
    return PositionComparison("ours", roll, te, dict(r.pair_load), r.max_pressure, wall,
                              {"theta": r.theta, "theta0": r.theta0, "p_max_mid": p_mid}), r


def solve_ccx(lm: LoadedModel, roll: float, torque: float, st: CcxSettings, workdir: str | Path,
              theta_hint: float | None = None, say=print, focus: Focus | None = None) -> PositionComparison:
    """CalculiX at ``roll`` (rad from the pitch point) under the pinion ``torque`` (N mm).

    With ``focus`` the mesh is refined further on a piece of one contact line, and ``max_pressure`` is the
    peak fitted in that window (``info['p_fit']`` keeps the whole-face fit)."""
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
    # the deck's own sizes (TE and sharing, no root stress: its fillets are not refined, fem.fillet)
    spec1 = body_spec(p1, dataclasses.replace(lm.body1.spec, h_flank=st.h_flank, h_body=st.h_body, fillet=0.0))
    spec2 = body_spec(p2, dataclasses.replace(lm.body2.spec, h_flank=st.h_flank, h_body=st.h_body, fillet=0.0))
    L1, L2 = body_lines(inv1), body_lines(inv2)
    F1 = F2 = ()
    if focus is not None:
        i_focus = [k for k, _, _ in lines].index(focus.tooth)   # ValueError: the focus tooth is not in contact
        F1 = ((_window(L1[i_focus], focus), focus.h, focus.half_band),)
        F2 = ((_window(L2[i_focus], focus), focus.h, focus.half_band),)
    m1 = build_refined_body(spec1, L1, st.h_contact, st.half_band, st.grow_across, st.grow_depth, focus=F1)
    m2 = build_refined_body(spec2, L2, st.h_contact, st.half_band, st.grow_across, st.grow_depth, focus=F2)
    t_mesh = time.perf_counter() - t0
    # contact surfaces: the driving flank (pinion) and the loaded flank and tip (gear) near each contact line
    side2 = "right" if model.gear_side > 0 else "left"
    master = tuple(n for j in lm.teeth2 for n in (f"flank_{j}_{side2}", f"tip_{j}"))
    f1, f2 = dict(m1.facets), dict(m2.facets)
    pairs, loaded = [], []
    for i, (k, _, _) in enumerate(lines):
        f1[f"band_{k}"] = facets_near_lines(m1, (f"flank_{k}_right",), [L1[i]], st.halo)
        f2[f"band_{k}"] = facets_near_lines(m2, master, [L2[i]], st.halo)
        pairs.append(ContactPairSpec(f"P{i}", ("pinion", (f"band_{k}",)), ("gear", (f"band_{k}",))))
        loaded.append(k)
    m1, m2 = dataclasses.replace(m1, facets=f1), dataclasses.replace(m2, facets=f2)
    # start towards the loaded state (ISO-like estimate c' = 14 N/(mm um), independent of our solve) so that
    # the contact iterations begin with the right contact lines closed; delta is added back to the TE
    delta = st.preload * torque / (rb1 ** 2 * 14.0e3 * model.face_width)
    deck = CcxDeck(young=model.case.young, poisson=model.case.poisson, fixed=("gear", "rim" if p2.internal else "bore"),
                   driven=("pinion", "bore"), moment=-torque, pairs=pairs, penalty=st.penalty)
    work = Path(workdir)
    work.mkdir(parents=True, exist_ok=True)
    ids = write_deck(work / "job.inp", [DeckBody("pinion", m1, rotation_z(phi1 - delta)), DeckBody("gear", m2, T2)],
                     deck)
    n_dofs = 3 * (len(m1.nodes) + len(m2.nodes))
    digest = hashlib.sha256((work / "job.inp").read_bytes()).hexdigest()
    done = work / "result.json"
    tag = f", focus {1e3 * focus.h:.0f} um on tooth {focus.tooth}" if focus else ""
    if done.exists():   # a finished run of this very deck (a crash or a re-run loses nothing already solved)
        rec = json.loads(done.read_text())
        if rec.get("deck_sha256") == digest:
            say(f"CalculiX roll {np.degrees(roll):+.3f} deg, h_contact {1e3 * st.h_contact:.0f} um{tag}: "
                f"reusing {done} (ccx {rec['wall']:.0f} s)")
            return PositionComparison("calculix", roll, rec["te"], {int(k): v for k, v in rec["pair_load"].items()},
                                      rec["max_pressure"], rec["wall"], rec["info"])
    say(f"CalculiX roll {np.degrees(roll):+.3f} deg, h_contact {1e3 * st.h_contact:.0f} um{tag}: {n_dofs} dofs, "
        f"{len(lines)} contact line(s), meshed in {t_mesh:.1f} s; solving ...")
    wall_ccx = run_ccx(work / "job.inp", threads=st.threads)
    res = read_results(work / "job", ids["rot"], tuple(p.name for p in pairs))
    z_slave = m1.nodes[np.clip(res.contact_nodes - 1, 0, len(m1.nodes) - 1), 2]
    mid = (res.contact_nodes <= len(m1.nodes)) & (np.abs(z_slave) < 0.35 * b)
    p_mid = float(res.contact_pressure[mid].max()) if mid.any() else 0.0
    p_fit = _fitted_peak(m1, L1, res.contact_nodes, res.contact_pressure, b)
    p_focus = None
    if focus is not None:
        p_focus = _fitted_peak(m1, [L1[i_focus]], res.contact_nodes, res.contact_pressure, b,
                               window=(focus.z0 - focus.half_length, focus.z0 + focus.half_length))
    theta = delta - res.rotation
    theta0 = float(first_contact(model, phi1, lm.teeth1))
    te = (theta - theta0) / model.pair.ratio * ARCSEC_PER_RAD
    loads = {k: 0.0 for k in lm.teeth1}
    loads.update({k: float(np.linalg.norm(res.pair_force.get(p.name, np.zeros(3)))) for k, p in zip(loaded, pairs)})
    wall = time.perf_counter() - t_all
    say(f"  ccx {wall_ccx:.1f} s (all {wall:.1f} s): TE {te:.3f} arcsec, loads "
        f"{ {k: round(v, 1) for k, v in loads.items()} } N, p_max {res.max_pressure:.0f} MPa (mid-face {p_mid:.0f}, "
        f"elliptic fit {p_fit:.0f}{f', in the focus window {p_focus:.0f}' if p_focus else ''})")
    out = PositionComparison("calculix", roll, te, loads, p_focus or p_fit or res.max_pressure, wall,
                             {"theta": theta, "theta0": theta0, "n_dofs": n_dofs, "ccx_wall": wall_ccx,
                              "mesh_wall": t_mesh, "h_contact": st.h_contact, "p_max_mid": p_mid, "p_fit": p_fit,
                              "penalty": st.penalty, "reaction": res.fixed_reaction.tolist(),
                              "p_max_nodal": res.max_pressure, "p_focus": p_focus,
                              "focus": dataclasses.asdict(focus) if focus else None})
    done.write_text(json.dumps({"deck_sha256": digest, "te": out.te, "pair_load": out.pair_load,
                                "max_pressure": out.max_pressure, "wall": out.wall, "info": out.info}, indent=1))
    return out


def narrowest_contact(res) -> tuple[int, float]:
    """The loaded pinion tooth with the narrowest contact at mid-face, and its half-width (mm): half the loaded
    extent of the mid slice's cells across the contact line (one cell size ``res.ds`` per loaded cell)."""
    mid = int(np.median(res.slice))
    widths = {}
    for k in np.unique(res.tooth):
        m = (res.tooth == k) & (res.slice == mid) & (res.force > 0)
        if m.sum() >= 2:
            widths[int(k)] = 0.5 * m.sum() * res.ds
    if not widths:
        return 0, float("nan")
    k = min(widths, key=widths.get)
    return k, float(widths[k])
