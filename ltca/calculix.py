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

import dataclasses
import hashlib
import json
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from geometry.cylindrical import arc_length
from fem.export import (CcxDeck, ContactLine, ContactPairSpec, DeckBody, build_refined_segment, facets_near_lines,
                        read_results, run_ccx, write_deck)
from fem.compliance import segment_spec
from geometry.pair import rotation_z

from .loaded import LoadedModel, solve_position
from .tca import ARCSEC_PER_RAD, first_contact, flank_gaps

__all__ = ["CcxSettings", "PositionComparison", "ccx_ladder", "richardson", "contact_lines", "solve_ccx", "solve_ours",
           "run_calculix_validation"]


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
        out.append(CcxSettings(h_contact=h, half_band=1.3 * b_nom + h, h_flank=body[0] * module, h_body=body[1] * module,
                               penalty=penalty_factor * 206000.0 / h, halo=2.0 * b_nom))
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


def _fitted_peak(mesh, lines: list[ContactLine], nodes: np.ndarray, pressure: np.ndarray, b: float,
                 slices: int = 14) -> float:
    """Largest elliptic-fit peak (Hertz shape across the contact line) over face slices of the slave nodes.

    Nodal contact pressures of penalty contact on quadratic faces scatter by tens of per cent at a few
    elements per contact width; the fit of p^2 by a parabola across the band (``fit_elliptic``) is the
    robust peak, the same estimator ``ltca validate`` uses for ours."""
    from .validate import fit_elliptic
    ok = (nodes >= 1) & (nodes <= len(mesh.nodes)) & (pressure > 0)
    X, p = mesh.nodes[nodes[ok] - 1], pressure[ok]
    best = 0.0
    edges = np.linspace(-0.5 * b, 0.5 * b, slices + 1)
    for ln in lines:
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
                    pk = fit_elliptic(t[m], p[m])[0]
                if np.isfinite(pk):
                    best = max(best, pk)
    return float(best)


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
    spec1 = segment_spec(p1, lm.body1.spec.teeth, model.r_bore1, b, st.h_flank, st.h_body)
    spec2 = segment_spec(p2, lm.body2.spec.teeth, model.r_bore2, b, st.h_flank, st.h_body)
    L1, L2 = body_lines(inv1), body_lines(inv2)
    m1 = build_refined_segment(spec1, L1, st.h_contact, st.half_band, st.grow_across, st.grow_depth)
    m2 = build_refined_segment(spec2, L2, st.h_contact, st.half_band, st.grow_across, st.grow_depth)
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
    if done.exists():   # a finished run of this very deck (a crash or a re-run loses nothing already solved)
        rec = json.loads(done.read_text())
        if rec.get("deck_sha256") == digest:
            say(f"CalculiX roll {np.degrees(roll):+.3f} deg, h_contact {1e3 * st.h_contact:.0f} um: "
                f"reusing {done} (ccx {rec['wall']:.0f} s)")
            return PositionComparison("calculix", roll, rec["te"], {int(k): v for k, v in rec["pair_load"].items()},
                                      rec["max_pressure"], rec["wall"], rec["info"])
    say(f"CalculiX roll {np.degrees(roll):+.3f} deg, h_contact {1e3 * st.h_contact:.0f} um: {n_dofs} dofs, "
        f"{len(lines)} contact line(s), meshed in {t_mesh:.1f} s; solving ...")
    wall_ccx = run_ccx(work / "job.inp", threads=st.threads)
    res = read_results(work / "job", ids["rot"], tuple(p.name for p in pairs))
    z_slave = m1.nodes[np.clip(res.contact_nodes - 1, 0, len(m1.nodes) - 1), 2]
    mid = (res.contact_nodes <= len(m1.nodes)) & (np.abs(z_slave) < 0.35 * b)
    p_mid = float(res.contact_pressure[mid].max()) if mid.any() else 0.0
    p_fit = _fitted_peak(m1, L1, res.contact_nodes, res.contact_pressure, b)
    theta = delta - res.rotation
    theta0 = float(first_contact(model, phi1, lm.teeth1))
    te = (theta - theta0) / model.pair.ratio * ARCSEC_PER_RAD
    loads = {k: 0.0 for k in lm.teeth1}
    loads.update({k: float(np.linalg.norm(res.pair_force.get(p.name, np.zeros(3)))) for k, p in zip(loaded, pairs)})
    wall = time.perf_counter() - t_all
    say(f"  ccx {wall_ccx:.1f} s (all {wall:.1f} s): TE {te:.3f} arcsec, loads "
        f"{ {k: round(v, 1) for k, v in loads.items()} } N, p_max {res.max_pressure:.0f} MPa (mid-face {p_mid:.0f}, "
        f"elliptic fit {p_fit:.0f})")
    out = PositionComparison("calculix", roll, te, loads, p_fit or res.max_pressure, wall,
                             {"theta": theta, "theta0": theta0, "n_dofs": n_dofs, "ccx_wall": wall_ccx,
                              "mesh_wall": t_mesh, "h_contact": st.h_contact, "p_max_mid": p_mid, "p_fit": p_fit,
                              "penalty": st.penalty, "reaction": res.fixed_reaction.tolist(),
                              "p_max_nodal": res.max_pressure})
    done.write_text(json.dumps({"deck_sha256": digest, "te": out.te, "pair_load": out.pair_load,
                                "max_pressure": out.max_pressure, "wall": out.wall, "info": out.info}, indent=1))
    return out


def richardson(values: list[float], ratio: float) -> tuple[float, float] | None:
    """Extrapolated limit and observed order of three values on meshes refined by ``ratio`` each time.

    p = ln((f0 - f1) / (f1 - f2)) / ln(ratio), f = f2 + (f2 - f1) / (ratio^p - 1); None when the
    differences change sign (no monotone convergence) or vanish."""
    f0, f1, f2 = values
    d1, d2 = f0 - f1, f1 - f2
    if d1 == 0 or d2 == 0 or d1 * d2 < 0:
        return None
    p = np.log(d1 / d2) / np.log(ratio)
    return float(f2 - d2 / (ratio ** p - 1)), float(p)


def _narrowest_half_width(res) -> float:
    """Smallest contact half-width (mm) among the loaded pinion teeth at mid-face: half the loaded extent of the
    mid slice's cells across the contact line (one cell size ``res.ds`` per loaded cell)."""
    mid = int(np.median(res.slice))
    widths = []
    for k in np.unique(res.tooth):
        m = (res.tooth == k) & (res.slice == mid) & (res.force > 0)
        if m.sum() >= 2:
            widths.append(0.5 * m.sum() * res.ds)
    return min(widths) if widths else float("nan")


BOUNDS = {"te_rel": 0.03, "share_abs": 0.03, "pressure_rel": 0.05}   # issue 4, spur pair
BOUNDS_HELICAL_TE = 0.05


def _default_rolls_deg(z1: int) -> list[float]:
    """Five positions over one mesh cycle: pitch point, two single-contact and two double-contact ones."""
    return [round(f * 360.0 / z1, 4) for f in (0.0, -0.4, -0.2, 0.2, 0.4)]


def _plot(rows: list[dict], out: Path, title: str) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    for solver, mk in (("ours", "o"), ("calculix", "s")):
        r = sorted((x for x in rows if x["solver"] == solver and x["reference"]), key=lambda x: x["roll_deg"])
        if not r:
            continue
        roll = [x["roll_deg"] for x in r]
        ax[0].plot(roll, [x["te_arcsec"] for x in r], mk + "-", label=solver)
        ax[1].plot(roll, [x["max_pressure_mpa"] for x in r], mk + "-", label=solver)
        for k in sorted({k for x in r for k in x["share"]}):
            ax[2].plot(roll, [x["share"].get(k, 0.0) for x in r], mk + "-", label=f"{solver} tooth {k}")
    for a, yl in zip(ax, ("loaded TE - unloaded [arcsec]", "peak pressure [MPa]", "load share")):
        a.set(xlabel="pinion roll from the pitch point [deg]", ylabel=yl)
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def run_calculix_validation(case_path: str, positions: list[float] | None, out: str, refine: int = 2,
                            level: int | None = 1, band_um: float | None = None, coarse_body: bool = False,
                            progress: bool = True) -> int:
    """Ours against CalculiX on a case at pinion roll angles ``positions`` (deg from the pitch point).

    Every position is solved by CalculiX at ladder rung ``level`` (contact band 3b/4 / 1.5^level; default 1,
    b/2; None: the finest); then the first position at the other rungs up to ``refine`` (the CalculiX
    convergence check, which says how far ``level`` is from converged). Each CalculiX run is kept (deck,
    results, ``result.json``) in its own folder under ``out`` and reused when the same deck is asked for
    again, so an interrupted validation resumes where it stopped. Prints a
    table, writes ``calculix.csv``, ``convergence.csv`` and ``calculix.png`` to ``out`` and returns 0
    when all positions are within the issue's bounds, 1 otherwise. Raises ``CaseError`` on a bad case or
    position list and ``fem.export.CcxNotFound`` (with the install command) when ``ccx`` is missing."""
    import sys
    from fem.export import ccx_path
    from .case import FIDELITIES, load_case
    from .errors import CaseError
    from .loaded import Fidelity, prepare
    from .model import build_model
    from .run import cycle_rolls
    ccx_path()
    say = (lambda m: print(m, file=sys.stderr, flush=True)) if progress else (lambda m: None)
    if refine < 0 or refine > 4:
        raise CaseError("--refine", refine, "an integer from 0 to 4")
    case = load_case(case_path)
    pitch_deg = 360.0 / case.pinion.teeth
    rolls_deg = list(positions) if positions else _default_rolls_deg(case.pinion.teeth)
    bad = [r for r in rolls_deg if not np.isfinite(r) or abs(r) > 0.5 * pitch_deg + 1e-9]
    if bad:
        raise CaseError("--positions", bad, f"pinion roll angles in deg within one mesh cycle "
                        f"(|roll| <= {0.5 * pitch_deg:.4f})")
    torque = case.torques[0]
    model = build_model(case)
    t0 = time.perf_counter()
    fid = Fidelity.from_preset(FIDELITIES["default"], case.module)
    lm = prepare(model, fid, cycle_rolls(case.positions, case.pinion.teeth), torque, progress=say)
    t_prepare = time.perf_counter() - t0
    if band_um is not None and not (np.isfinite(band_um) and 10.0 <= band_um <= 2000.0):
        raise CaseError("--band", band_um, "a contact-band element size from 10 to 2000 um")
    ladder = ccx_ladder(lm.b_nom, case.module, refine, h0=band_um * 1e-3 if band_um else None,
                        body=(0.45, 1.6) if coarse_body else (0.3, 1.3))
    helical = abs(case.helix_angle) > 1e-9
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)
    if level is None:
        level = len(ladder) - 1
    if not 0 <= level < len(ladder):
        raise CaseError("--level", level, f"an integer from 0 to --refine ({refine})")
    rows, conv = [], []
    # every position at `level` first (each CalculiX run is kept in its folder as it finishes), then the
    # other rungs of the ladder at the first position: the costly fine rungs come last
    for rd in rolls_deg:
        roll = np.radians(rd)
        mine, res = solve_ours(lm, roll, torque)
        c = solve_ccx(lm, roll, torque, ladder[level], outdir / f"ccx_r{rd:+.4f}_L{level}", say=say)
        conv.append((rd, level, c))
        teeth = sorted(set(mine.pair_load) | set(c.pair_load))
        # CalculiX's resolution of the narrowest contact: its band elements per (our) contact half-width
        per_b = _narrowest_half_width(res) / ladder[level].h_contact
        for sol in (mine, c):
            rows.append({"roll_deg": rd, "solver": sol.solver, "reference": True, "te_arcsec": sol.te,
                         "share": sol.share(teeth), "max_pressure_mpa": sol.max_pressure, "wall_s": sol.wall,
                         "n_dofs": sol.info.get("n_dofs", lm.body1.n_dofs + lm.body2.n_dofs), "per_b": per_b})
    for lev in range(len(ladder)):
        if lev != level:
            rd = rolls_deg[0]
            conv.append((rd, lev, solve_ccx(lm, np.radians(rd), torque, ladder[lev], outdir / f"ccx_r{rd:+.4f}_L{lev}",
                                            say=say)))
    conv.sort(key=lambda x: (x[0] != rolls_deg[0], x[1]))
    # ---- table
    bound_te = BOUNDS_HELICAL_TE if helical else BOUNDS["te_rel"]
    ok_all = True
    lines = [f"{case.name} at {torque * 1e-3:g} N m: ours (default fidelity) against CalculiX "
             f"(contact band {1e3 * ladder[level].h_contact:.0f} um)",
             f"{'roll':>7} {'TE ours':>8} {'TE ccx':>8} {'dTE%':>6} {'share ours':>18} {'share ccx':>18} {'dshare':>6} "
             f"{'p ours':>6} {'p ccx':>6} {'dp%':>6} {'el/b':>5} {'t ours':>7} {'t ccx':>7} {'ratio':>6}"]
    csv = ["roll_deg,te_ours_arcsec,te_ccx_arcsec,te_diff_pct,share_ours,share_ccx,share_diff_max,p_ours_mpa,"
           "p_ccx_mpa,p_diff_pct,ccx_elements_per_half_width,t_ours_s,t_ccx_s,time_ratio,ccx_dofs,ok"]
    t_ours_sum = t_ccx_sum = 0.0
    for j in range(0, len(rows), 2):
        a, c = rows[j], rows[j + 1]
        teeth = sorted(a["share"])
        dte = c["te_arcsec"] and (a["te_arcsec"] / c["te_arcsec"] - 1)
        dsh = max(abs(a["share"][k] - c["share"][k]) for k in teeth)
        dp = c["max_pressure_mpa"] and (a["max_pressure_mpa"] / c["max_pressure_mpa"] - 1)
        ok = abs(dte) <= bound_te and (helical or (dsh <= BOUNDS["share_abs"] and abs(dp) <= BOUNDS["pressure_rel"]))
        ok_all &= ok
        flag = "" if ok else ("  p unresolved by CalculiX (< 2 el/b)" if abs(dte) <= bound_te and
                              dsh <= BOUNDS["share_abs"] and c["per_b"] < 2 else "  OUT")
        ratio = c["wall_s"] / a["wall_s"]
        t_ours_sum += a["wall_s"]
        t_ccx_sum += c["wall_s"]
        sh = lambda r: "/".join(f"{r['share'][k]:.3f}" for k in teeth)
        lines.append(f"{a['roll_deg']:7.3f} {a['te_arcsec']:8.2f} {c['te_arcsec']:8.2f} {100 * dte:+6.2f} {sh(a):>18} "
                     f"{sh(c):>18} {dsh:6.3f} {a['max_pressure_mpa']:6.0f} {c['max_pressure_mpa']:6.0f} "
                     f"{100 * dp:+6.1f} {c['per_b']:5.1f} {a['wall_s']:7.2f} {c['wall_s']:7.0f} {ratio:6.0f}{flag}")
        csv.append(f"{a['roll_deg']},{a['te_arcsec']},{c['te_arcsec']},{100 * dte},{sh(a)},{sh(c)},{dsh},"
                   f"{a['max_pressure_mpa']},{c['max_pressure_mpa']},{100 * dp},{c['per_b']},{a['wall_s']},{c['wall_s']},{ratio},"
                   f"{c['n_dofs']},{ok}")
    n = len(rows) // 2
    cyc_ours = t_prepare + case.positions * t_ours_sum / n
    cyc_ccx = case.positions * t_ccx_sum / n
    lines.append(f"wall time per position: ours {t_ours_sum / n:.2f} s (contact solve; compliance {t_prepare:.1f} s once), "
                 f"CalculiX {t_ccx_sum / n:.0f} s; ratio {t_ccx_sum / t_ours_sum:.0f}")
    lines.append(f"whole cycle ({case.positions} positions, extrapolated): ours {cyc_ours:.0f} s incl. compliance, "
                 f"CalculiX {cyc_ccx:.0f} s; ratio {cyc_ccx / cyc_ours:.0f}")
    lines.append("CalculiX runs (convergence ladder at the first position; contact band size -> TE, loads, peak "
                 "pressure, dofs, time):")
    cl = ["roll_deg,level,h_contact_um,penalty_mpa_per_mm,n_dofs,te_arcsec,pair_load_n,p_fit_mpa,p_nodal_max_mpa,wall_s"]
    for rd, lev, c in conv:
        loads = "/".join(f"{v:.1f}" for _, v in sorted(c.pair_load.items()))
        lines.append(f"  roll {rd:7.3f} level {lev}: {1e3 * c.info['h_contact']:5.0f} um  TE {c.te:8.3f}  loads {loads:>20} N"
                     f"  p fit {c.max_pressure:6.0f} (nodal max {c.info.get('p_max_nodal', 0):.0f}) MPa  {c.info['n_dofs']} dofs  {c.wall:.0f} s")
        cl.append(f"{rd},{lev},{1e3 * c.info['h_contact']},{c.info['penalty']},{c.info['n_dofs']},{c.te},{loads},"
                  f"{c.max_pressure},{c.info.get('p_max_nodal', 0)},{c.wall}")
    first = sorted((c for rd, _, c in conv if rd == rolls_deg[0]), key=lambda c: -c.info["h_contact"])
    if len(first) >= 3:
        a0 = rows[0]
        for what, key, mine in (("TE", "te", a0["te_arcsec"]), ("peak pressure", "max_pressure", a0["max_pressure_mpa"])):
            est = richardson([getattr(c, key) for c in first[-3:]], 1.5)
            if est is not None:
                lines.append(f"converged CalculiX {what} at roll {rolls_deg[0]:g} (Richardson, observed order "
                             f"{est[1]:.2f}): {est[0]:.2f}; ours {mine:.2f} ({100 * (mine / est[0] - 1):+.2f} %)")
            else:
                lines.append(f"CalculiX {what} at roll {rolls_deg[0]:g} does not converge monotonically over the "
                             f"ladder: {[round(getattr(c, key), 2) for c in first]}")
    print("\n".join(lines))
    (outdir / "calculix.csv").write_text("\n".join(csv) + "\n")
    (outdir / "convergence.csv").write_text("\n".join(cl) + "\n")
    _plot(rows, outdir / "calculix.png", f"{case.name}: ours vs CalculiX")
    return 0 if ok_all else 1
