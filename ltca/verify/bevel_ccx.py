"""CalculiX on the whole spiral bevel pair: the independent FE check of the bevel LTCA.

Both members are OpenCASCADE solids with every tooth (:mod:`ltca.fem.solids.bevel_occ`: lofted from exact flank
points, fused with a revolved blank, gmsh tetrahedra refined on the contact zones), not our mapped body
(:mod:`ltca.fem.solids.bevel_body`).  Supports as in service: the pinion's bore (a shaft seat of radius
``r_bore1``) is a rigid body that may only turn about the pinion axis and carries the pinion torque; the
gear's back face (a mounting face ``back_depth`` whole depths under the heel's root) is fixed.  Contact:
frictionless surface-to-surface penalty contact, linear pressure-overclosure law of slope 10 E / h.

World frame: the pinion's axis frame in the mesh (:func:`ltca.geometry.bevel.tca.mesh_frames`, not rotated), so the
pinion turns about world z.  At pinion angle phi1 the gear is set where it first touches (the smallest closing
rotation g_min of the unloaded gaps, :mod:`ltca.geometry.bevel.gaps`); the pinion is turned ``preload`` into it and
the torque added.  The loaded approach as a gear rotation is theta = (z1/z2)(preload + s psi) with psi the
pinion's rotation read and s the closing sense; our counterpart is :attr:`BevelPosition.theta`.  The contact
zone of pair j (refined, and the contact surfaces) is where the unloaded normal gap is below ``cap_refine`` and
``cap_contact`` (geometry only, not our loaded solution).

Contact roles and the top edges.  CalculiX's surface-to-surface contact measures a slave point's overclosure
along the normal of the master facet it is paired with, so a sharp corner is a slave against a smooth master
that reaches past it.  The pinion's top edge (the edge ours reports at phi1 = 0) lies in the pinion's flank band,
a slave against the gear's flank.  The gear's top edge meets the pinion's lower flank, so each pair j is split at
the gear's tip corner (depth ``max(corner, 2 h_zone)`` under the gear's face cone, the blank's,
:func:`under_top`): ``P`` the pinion band beyond that depth (slave) against the gear's flank below it (master),
``W`` the gear's tip-corner zone (slave) against the pinion's whole flank (master); a pair's torque sums both.
Both members' top-edge lines of the wide zone are refined with the zone: otherwise nodes of one member's top
edge sink 16-18 um into the extended plane of the other's coarse facets (nodal spikes of 70-85 GPa).  With the
split and the refined edge lines (phi1 = 0, 450 um zone) the nodal maximum is 2.7 GPa at the pinion's top edge,
the gear's corner carries nothing (as ours) and the pair torques sum to 0.998 of the torque.

Read per position: theta (arcsec of the gear), each pair's torque share about the pinion axis (total contact
force of the pair times its pressure centroid), and the peak flank pressure away from the edges (pinion top,
gear top, toe and heel: farther than ``edge_mm``, :func:`interior`), from a quadratic fit of p^2 (the elliptic
Hertz shape) around the highest node that is no isolated spike (:mod:`ltca.verify.bevel_ccx_read`).  Runs are kept
in their folder with ``result.json`` keyed by the deck's SHA-256; a kept run is read out again from its
``job.dat`` and ``job.frd`` (a changed read-out applies without rerunning CalculiX).
"""
from __future__ import annotations

import hashlib
import json
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from ltca.fem.calculix.deck import CcxDeck, ContactPairSpec, DeckBody, write_deck
from ltca.fem.calculix.run import read_results, run_ccx
from ltca.fem.solids.bevel_occ import BevelSolidSpec, build_bevel_solid
from ltca.geometry.bevel.generation import generate_flank
from ltca.geometry.bevel.tca import RAD_PER_ARCSEC, mesh_frames, to_pitch_coords

from ..bevel.cells import pair_minima
from ..bevel.model import LOADED, BevelLoadedModel
from .bevel_ccx_read import interior, read_pairs
from .calculix import penalty_slope

__all__ = ["BevelCcxSettings", "BevelCcxResult", "solve_bevel_ccx", "bevel_ladder", "interior", "under_top"]


@dataclass(frozen=True)
class BevelCcxSettings:
    """Fidelity and model choices of the bevel CalculiX check (mm, MPa/mm, rad)."""
    h_zone: float = 0.25
    h_body: float = 5.0
    h_tooth: float = 2.5
    grow: float = 0.45
    cap_refine: float = 0.012
    cap_contact: float = 0.040
    penalty_factor: float = 10.0
    preload_arcsec: float = 20.0      # gear arcsec of initial overclosure
    r_bore1: float = 9.0
    back_depth: float = 1.2
    back_face_z: float | None = None  # the gear's back face (mounting distance, mm); None: back_depth below the heel
    edge_mm: float = 0.8
    corner: float = 0.25              # least depth of the gear's tip-corner zone under its face cone
    threads: int = 2


def bevel_ladder(levels: int = 3, h0: float = 0.25) -> list[BevelCcxSettings]:
    """Contact-zone sizes h0, h0/1.5, h0/1.5^2 ..."""
    return [BevelCcxSettings(h_zone=h0 / 1.5 ** i) for i in range(levels)]


@dataclass
class BevelCcxResult:
    """CalculiX at one position (arcsec of the gear, N, MPa, s)."""
    phi1: float
    theta_arcsec: float
    share: dict
    pair_force: dict
    p_interior: float
    p_nodal_max: float
    wall: float
    info: dict


def _rz(a: float) -> np.ndarray:
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _frame(R: np.ndarray, o=np.zeros(3)) -> np.ndarray:
    T = np.eye(4)
    T[:3, :3], T[:3, 3] = R, o
    return T


def _outline(lm: BevelLoadedModel, member: str, st: BevelCcxSettings) -> tuple[np.ndarray, dict]:
    """Blank polygon (Z, rho), edge 0 the root cone toe -> heel, and the support edge."""
    bl = lm.pair.blank
    g = bl.member(member).pitch_angle
    A, B = bl.root_point(member, "toe"), bl.root_point(member, "heel")
    d = np.array([np.sin(g), -np.cos(g)])                   # into the material along the front/back cones
    if member == "pinion":                                  # down to the shaft seat rho = r_bore1
        return np.array([A, B, B + d * (B[1] - st.r_bore1) / np.cos(g), A + d * (A[1] - st.r_bore1) / np.cos(g)]), \
            {"bore": 2}
    C = B + d * st.back_depth * bl.whole_depth              # gear: down to the back (mounting) face Z = Z_C
    if st.back_face_z is not None:
        C = B + d * (st.back_face_z - B[0]) / d[0]
    return np.array([A, B, C, A + d * (C[0] - A[0]) / d[0]]), {"back": 2}


def _zones(lm: BevelLoadedModel, phi1: float, g_min: float, ang2: float, cap: float) -> dict:
    """Per pair j: pinion points (pinion frame, tooth j) and gear points (gear frame) with gap < cap, and the
    top-edge lines among them (the pinion's top row, the gear's top line on the pinion: the lowest row over the gear
    flank), which are refined too."""
    gp = lm.gaps
    T, L = np.meshgrid(np.linspace(0.0, 1.0, 61), np.linspace(*gp.L_range, 161), indexing="ij")
    B1, O1, B2, O2 = mesh_frames(lm.pair.blank, lm.asm)
    out = {}
    for j in LOADED:
        r = gp.gaps(phi1 + j * gp.c1, T, L)
        over = np.isfinite(r.g)
        m = over & ((r.g - g_min) * r.v2 < cap)
        if not m.any():
            continue
        edge = np.zeros_like(m)
        edge[-1] = True
        edge[np.argmax(over, axis=0), np.arange(T.shape[1])] = True
        p1 = r.r1[m] @ _rz(j * gp.c1).T                     # tooth j in the pinion body frame
        h = (p1 @ _rz(phi1).T) @ B1.T + O1
        p2 = ((h - O2) @ B2) @ _rz(ang2)                     # into the gear body frame at its angle ang2
        out[j] = (p1, p2, edge[m])
    return out


def _member(lm, member: str, st: BevelCcxSettings, zone: np.ndarray, snap: tuple, cache, say):
    bl = lm.pair.blank
    mb = bl.member(member)
    cut = lm.pair.pinion if member == "pinion" else lm.pair.gear
    off = 0.03 * bl.data.module
    fl = {s: generate_flank(cut.flank(s), bl, member, 13, 11, off) for s in ("concave", "convex")}
    rn = np.asarray(fl["concave"].meta["Rn"])[:, 5]
    anchor = lm.side if member == "pinion" else lm.gaps.gear_side
    outline, sup = _outline(lm, member, st)
    spec = BevelSolidSpec(fl["concave"], fl["convex"], mb.z, mb.pitch_angle, off, anchor,
                          mb.mean_normal_thickness / (np.cos(bl.data.spiral_angle) * mb.mean_pitch_radius),
                          float(np.interp(0.0, rn, fl["concave"].u)), bl.mean_cone_distance, outline, sup, zone,
                          st.h_zone, st.h_body, st.grow, st.h_tooth, snap_teeth=snap, cad_cache=cache)
    return build_bevel_solid(spec, say), spec


def _centroids(mesh, tri: np.ndarray) -> np.ndarray:
    return mesh.nodes[tri[:, :3]].mean(axis=1)


def under_top(bl, member: str, X: np.ndarray) -> np.ndarray:
    """Depth of body-frame points X (mm) under ``member``'s face cone (the blank's, not our model's), mm; negative
    beyond its top."""
    mb = bl.member(member)
    L, Rn = to_pitch_coords(X, mb.pitch_angle)
    return mb.addendum - (bl.outer_cone_distance - L) * np.tan(mb.addendum_angle) - Rn


def _near(mesh, group: str, pts: np.ndarray, halo: float) -> np.ndarray:
    from scipy.spatial import cKDTree
    tri = mesh.facets[group]
    d = cKDTree(pts).query(_centroids(mesh, tri))[0]
    return tri[d < halo]


def solve_bevel_ccx(lm: BevelLoadedModel, phi1: float, torque1: float, st: BevelCcxSettings, workdir, cache=None,
                    say=print) -> BevelCcxResult:
    """CalculiX at pinion angle ``phi1`` (rad) under the pinion torque ``torque1`` (N mm)."""
    t_all = time.perf_counter()
    gp, bl = lm.gaps, lm.pair.blank
    mins = [m for m in pair_minima(lm, phi1, LOADED) if m is not None]
    g_min = min(m.g for m in mins)
    ratio, s2 = gp.ratio, float(gp._s2)
    ang2 = gp.phi2_0 - ratio * phi1 + s2 * g_min
    fine = _zones(lm, phi1, g_min, ang2, st.cap_refine)
    wide = _zones(lm, phi1, g_min, ang2, st.cap_contact)
    pairs_j = sorted(fine)
    say(f"bevel CalculiX phi1 {phi1:+.5f} rad, zone {1e3 * st.h_zone:.0f} um: pairs {pairs_j} in the contact zone")
    # refined: the fine zone and the top-edge lines of the wide one (a corner on the other member's coarse chords
    # meets facets that stand proud of its curved flank)
    zone = [np.vstack([fine[j][i] for j in pairs_j] + [wide[j][i][wide[j][2]] for j in pairs_j]) for i in (0, 1)]
    m1, s1 = _member(lm, "pinion", st, zone[0], tuple(pairs_j), cache, say)
    m2, s2spec = _member(lm, "gear", st, zone[1], tuple(-j for j in pairs_j), cache, say)
    B1, O1, B2, O2 = mesh_frames(bl, lm.asm)
    delta = st.preload_arcsec * RAD_PER_ARCSEC / ratio                  # pinion overclosure, rad
    T1 = _frame(_rz(phi1 + s2 * delta))
    T2 = _frame(B1.T @ B2 @ _rz(ang2), B1.T @ (O2 - O1))
    # the gear in the pinion's body frame at the deck angles (T1^-1 T2): where the pinion's facets lie under its top
    G12 = np.linalg.inv(T1) @ T2
    f1, f2, pairs, owner = dict(m1.facets), dict(m2.facets), [], []
    groups, depth = {"pinion": f1, "gear": f2}, max(st.corner, 2.0 * st.h_zone)
    for j in pairs_j:
        band1 = _near(m1, f"flank_{j}_{lm.side}", wide[j][0], 3 * st.h_zone)
        band2 = _near(m2, f"flank_{-j}_{gp.gear_side}", wide[j][1], 3 * st.h_zone + 0.5)
        corner2 = under_top(bl, "gear", _centroids(m2, band2)) < depth
        X1 = (_centroids(m1, band1) - G12[:3, 3]) @ G12[:3, :3]          # pinion facets in the gear frame
        # masters: the whole flank (a slave point past a master's border would meet the plane of its last facet)
        whole2 = m2.facets[f"flank_{-j}_{gp.gear_side}"]
        f1[f"c{j}"], f2[f"c{j}"] = band1[under_top(bl, "gear", X1) >= depth], whole2[under_top(bl, "gear", _centroids(
            m2, whole2)) >= depth]
        f1[f"w{j}"], f2[f"w{j}"] = m1.facets[f"flank_{j}_{lm.side}"], band2[corner2]
        for name, sl, ma, key in ((f"P{j + 1}", "pinion", "gear", f"c{j}"), (f"W{j + 1}", "gear", "pinion", f"w{j}")):
            if len(groups[sl][key]) and len(groups[ma][key]):
                pairs.append(ContactPairSpec(name, (sl, (key,)), (ma, (key,))))
                owner.append(j)
    m1 = type(m1)(m1.nodes, m1.tets, f1, m1.spec_hash, m1.seconds)
    m2 = type(m2)(m2.nodes, m2.tets, f2, m2.spec_hash, m2.seconds)
    deck = CcxDeck(young=lm.bodies.young, poisson=lm.bodies.poisson, fixed=("gear", "back"),
                   driven=("pinion", "bore"), moment=s2 * torque1, pairs=tuple(pairs),
                   penalty=penalty_slope(st.h_zone, st.penalty_factor, lm.bodies.young))
    work = Path(workdir)
    work.mkdir(parents=True, exist_ok=True)
    ids = write_deck(work / "job.inp", [DeckBody("pinion", m1, T1), DeckBody("gear", m2, T2)], deck)
    digest = hashlib.sha256((work / "job.inp").read_bytes()).hexdigest()
    info = {"nodes": len(m1.nodes) + len(m2.nodes), "elements": len(m1.tets) + len(m2.tets),
            "nodes_pinion": len(m1.nodes), "nodes_gear": len(m2.nodes), "h_zone_mm": st.h_zone,
            "settings": asdict(st), "mesh_wall": m1.seconds + m2.seconds, "deck_sha256": digest,
            "snap_um": [1e3 * s1.extra["snap_mm"], 1e3 * s2spec.extra["snap_mm"]], "pairs": pairs_j}
    done = work / "result.json"
    stored = json.loads(done.read_text()) if done.exists() else None
    reuse = stored is not None and stored.get("info", {}).get("deck_sha256") == digest
    if reuse and not all((work / f"job.{x}").exists() for x in ("dat", "frd")):
        say(f"  reusing {done} (results files gone: its stored read-out)")
        return BevelCcxResult(**{k: stored[k] for k in stored if k != "share" and k != "pair_force"},
                              share={int(k): v for k, v in stored["share"].items()},
                              pair_force={int(k): v for k, v in stored["pair_force"].items()})
    if reuse:
        say(f"  reusing {work} (read out again)")
        wall = stored["info"]["ccx_wall"]
    else:
        say(f"  {3 * info['nodes']} dofs, {len(pairs)} contact pair(s), meshed in {info['mesh_wall']:.0f} s; ccx ...")
        wall = run_ccx(work / "job.inp", threads=st.threads)
    res = read_results(work / "job", ids["rot"], tuple(p.name for p in pairs))
    theta = ratio * (delta + s2 * res.rotation)
    X = np.vstack([m1.nodes @ T1[:3, :3].T, m2.nodes @ T2[:3, :3].T + T2[:3, 3]])
    torques, forces, p_int, pmax = read_pairs(lm, res, X, m1.nodes, T2, groups, pairs, owner, pairs_j, st.edge_mm,
                                              2.5 * st.h_zone)
    tot = sum(torques.values()) or 1.0
    out = BevelCcxResult(float(phi1), theta / RAD_PER_ARCSEC, {j: v / tot for j, v in torques.items()}, forces,
                         p_int, pmax, stored["wall"] if reuse else time.perf_counter() - t_all,
                         dict(info, ccx_wall=wall, psi=res.rotation, delta=delta,
                              torque_balance=tot / torque1, reaction=res.fixed_reaction.tolist()))
    say(f"  ccx {wall:.0f} s: theta {out.theta_arcsec:.2f} arcsec, share "
        f"{ {j: round(v, 3) for j, v in out.share.items()} }, p interior {out.p_interior:.0f} MPa "
        f"(nodal max {pmax:.0f}), torque balance {tot / torque1:.3f}")
    done.write_text(json.dumps(asdict(out), indent=1))
    return out
