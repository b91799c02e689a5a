"""CalculiX on whole gears with every tooth: the check that shares no assumption with our body.

Both members are meshed by :func:`ltca.fem.solids.full_gear.build_full_gear` (every tooth, the real bore, a web
where the case has one; not our compliance body :mod:`ltca.fem.solids.gear_body`), refined in a band around
the unloaded contact lines at the position, placed in the world (pinion rotated by phi1 = phi_pitch - roll,
gear by ``pair.gear_frame(phi1)``) and solved by CalculiX with frictionless penalty contact. Supports as on
the shafts: the gear's bore nodes are fixed; the pinion's bore nodes form a rigid body whose reference
node may only turn about the gear axis, and the pinion torque acts there. As in
:mod:`ltca.verify.calculix`, the pinion starts a small rotation ``delta`` into the gear (an ISO-like
stiffness estimate, not ours) and ``delta`` is added back to the rotation read.

Internal pairs (the satellite of an eccentric reducer in its central wheel): the wheel is the
ring out to ``model.r_bore2`` and is held on that outer cylinder (``rim``, the housing); the pinion
(satellite) bore turns about the satellite axis. Such a pair has a large backlash, so the satellite is first
turned by the rigid rotation to first contact ``theta0`` (the unloaded geometry, not our compliance), the
contact lines are taken there, and ``delta`` is counted on top of it. With ``fine_lines_only`` only the teeth
that carry a contact line get the fine flank size (a 50/51-tooth pair is too large otherwise).
Most pairs of a tooth difference of one touch at a tip edge: the wheel's tip corner on the satellite flank, or
the satellite's tip corner on the wheel flank. CalculiX's surface-to-surface contact pushes along the master's
normal, so the smooth side is the master, and the loaded contact of one tooth can reach both corners
whatever its unloaded line does (Kapitonov et al. 2014 at 3000 N m: tooth -6, first touching mid-flank, spreads to the
wheel's tip corner; with the satellite as slave there its nodes took up to 33 GPa at 3-6.5 um overclosure
against the wheel's tip land and pushed along its normal, lever 65.2 mm about the satellite axis instead of
r_b1 = 70.48 mm). So every tooth of an internal pair has two pairs on one partition of the wheel's band: the
wheel's tip-corner zone (:func:`wheel_corner_zone`: the tip land and the flank's first facet rows) as slave
against the satellite's flank and fillet, and the rest of the wheel's flank as master of the satellite's
flank and tip (the satellite's tip corner on the wheel flank). A tooth's load sums both (:func:`tooth_loads`).

Read per position: loaded TE (arcsec of the gear, unloaded part removed), load per pinion tooth, mesh
stiffness ``(T / r_b1) / (b (theta - theta0) r_b1)`` in N/(mm um) (as
:func:`ltca.cylindrical.results.mesh_stiffness`), the elliptic-fit peak flank pressure over the whole face
and away from the face ends (``info["p_flank"]``, as ours keeps its flank peak apart from edge contact; where:
``info["p_flank_at"]``),
and the root stress of each member (largest principal nodal stress on the loaded teeth's tension-side
fillets, as ours reads it: :mod:`ltca.verify.whole_root`). Each run is kept in its folder with
``result.json`` (keyed by the deck's SHA-256) and reused; read-outs a record lacks are added from the
kept ``job.frd``.
"""
from __future__ import annotations

import hashlib
import json
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from ltca.fem.calculix.deck import CcxDeck, ContactPairSpec, DeckBody, write_deck
from ltca.fem.calculix.run import read_results, run_ccx
from ltca.fem.solids.full_gear import FullGearSpec, build_full_gear, tooth_label
from ltca.fem.solids.refinement import ContactLine, facets_near_lines, line_size_expression
from ltca.geometry.pair import rotation_z

from ..cylindrical.loaded_model import LoadedModel
from ..cylindrical.tca import ARCSEC_PER_RAD, first_contact
from .calculix import _fitted_peak, contact_lines, penalty_slope
from .fitted_peak import fitted_peak
from .whole_root import Member, fillet_stress

__all__ = ["WholeSettings", "WholeResult", "whole_settings", "BODIES", "solve_whole", "stiffness", "FLANK_SLICES",
           "CORNER", "wheel_corner_zone", "tooth_loads"]

CORNER = 0.25   # mm: least radial depth of an internal wheel's tip-corner zone (wheel_corner_zone)


@dataclass(frozen=True)
class WholeSettings:
    """Fidelity of the whole-gear CalculiX model (mm, MPa/mm)."""
    h_contact: float          # element size in the contact band
    half_band: float          # half-width of the band across the contact line
    h_flank: float            # the loaded teeth's flanks, fillets and tips
    h_tooth: float            # every other tooth
    h_body: float             # far from the teeth
    penalty: float            # slope of the linear pressure-overclosure law
    grow_across: float = 0.4
    grow_depth: float = 0.8
    halo: float = 0.6         # contact surfaces reach this far from the unloaded contact lines
    preload: float = 0.2      # initial overclosure rotation, fraction of an ISO-like TE estimate (c' = 14)
    threads: int = 2
    h_fillet: float | None = None   # the loaded teeth's fillets (root stress); None: h_flank
    fine_lines_only: bool = False   # h_flank only on the teeth with a contact line (else every tooth in the model)


#: element sizes (x module) of the loaded teeth's flanks, the other teeth, the body and the loaded teeth's fillets, the
#: growth of the contact band's sizes (x WholeSettings') and whether only the teeth with a contact line get the flank
#: size. "coarse" (``--coarse-body``): a wide face whose default deck is too large for one thread (helical C14, b = 40
#: mm: 300 k nodes at the default, 125-155 k coarse at a 225-150 um band)
BODIES = {"default": dict(flank=0.3, tooth=0.5, body=1.2, fillet=0.15, grow=1.0, lines_only=False),
          "coarse": dict(flank=0.45, tooth=0.75, body=1.6, fillet=0.225, grow=1.5, lines_only=True)}


def whole_settings(b_nom: float, module: float, band_um: float | None = None, threads: int = 2,
                   fillet_mm: float | None = None, body: str = "default") -> WholeSettings:
    """Settings with a contact band of ``band_um`` (default 3/4 of the nominal Hertz half-width ``b_nom``),
    tension-side fillets of ``fillet_mm`` on the loaded teeth (default ``BODIES[body]``, 0.15 module) and the other
    element sizes of ``BODIES[body]``."""
    h = band_um * 1e-3 if band_um else 0.75 * b_nom
    k = BODIES[body]
    return WholeSettings(h_contact=h, half_band=1.3 * b_nom + h, h_flank=k["flank"] * module,
                         h_tooth=k["tooth"] * module, h_body=k["body"] * module, penalty=penalty_slope(h),
                         grow_across=0.4 * k["grow"], grow_depth=0.8 * k["grow"], halo=2.0 * b_nom, threads=threads,
                         h_fillet=fillet_mm or k["fillet"] * module, fine_lines_only=k["lines_only"])


@dataclass
class WholeResult:
    """CalculiX's answer at one position (arcsec, N, N/(mm um), MPa, s)."""
    roll_deg: float
    te: float
    pair_load: dict
    stiffness: float
    max_pressure: float
    wall: float
    info: dict
    root: dict = field(default_factory=dict)    # member -> {"max": MPa, "per_tooth", "at"} (whole_root)

    def share(self, teeth) -> dict:
        tot = sum(self.pair_load.values()) or 1.0
        return {int(k): self.pair_load.get(int(k), 0.0) / tot for k in teeth}


def stiffness(lm: LoadedModel, theta: float, theta0: float, torque: float) -> float:
    """Mesh stiffness per face width along the line of action, N/(mm um) (ISO 6336-1 c_gamma form)."""
    rb, b = lm.model.pinion.r_base, lm.model.face_width
    return float((torque / rb) / (b * (theta - theta0) * rb * 1e3))


def _spec(profile, r_bore, web, b, teeth, st: WholeSettings, lines, side: str | None = None) -> FullGearSpec:
    exprs = tuple(line_size_expression(ln, st.h_contact, st.half_band, st.grow_across, st.grow_depth) for ln in lines)
    if st.fine_lines_only:
        pitch = 2 * np.pi / profile.z
        teeth = sorted({tooth_label(int(np.round(np.arctan2(-x, y) / -pitch)), profile.z)
                        for x, y, _ in (0.5 * (np.asarray(ln.p0) + np.asarray(ln.p1)) for ln in lines)})
    return FullGearSpec(np.asarray(profile.xy), np.asarray(profile.kind), np.asarray(profile.side), profile.z, r_bore,
                        b, web=web, loaded_teeth=tuple(teeth), h_flank=st.h_flank, h_tooth=st.h_tooth,
                        h_body=st.h_body, size_fields=exprs, h_fillet=st.h_fillet,
                        fillet_side=side, twist=twist(profile), internal=bool(profile.internal))


def wheel_corner_zone(mesh, facets: np.ndarray, r_tip: float, h_contact: float) -> np.ndarray:
    """Which ``facets`` (k, 6) of an internal wheel's band make its tip-corner zone: centroid radius below
    ``r_tip + max(CORNER, 2 h_contact)`` (the tip land and the flank's first facet rows), mm."""
    c = mesh.nodes[facets[:, :3]].mean(axis=1)
    return np.hypot(c[:, 0], c[:, 1]) < r_tip + max(CORNER, 2.0 * h_contact)


def tooth_loads(pair_force: dict, pairs, loaded: list, teeth) -> dict:
    """Normal load (N) of each pinion tooth: the norm of the sum of its pairs' contact forces on the pinion (a
    pair's force acts on its slave, so a gear-slave pair counts negated)."""
    f = {int(k): np.zeros(3) for k in teeth}
    for k, p in zip(loaded, pairs):
        f[int(k)] = f[int(k)] + (1.0 if p.slave[0] == "pinion" else -1.0) * pair_force.get(p.name, np.zeros(3))
    return {k: float(np.linalg.norm(v)) for k, v in f.items()}


def twist(profile) -> float:
    """tan(beta) / r of a member, rad/mm: its transverse section at z is the one at z = 0 turned by this z."""
    return float(np.tan(profile.beta) / profile.r_ref) if abs(profile.beta) > 1e-12 else 0.0


def solve_whole(lm: LoadedModel, roll_deg: float, torque: float, st: WholeSettings, workdir: str | Path,
                say=print) -> WholeResult:
    """CalculiX on the whole gears at pinion roll ``roll_deg`` (deg from the pitch point), pinion ``torque`` (N mm)."""
    model = lm.model
    p1, p2 = model.pinion, model.gear
    if p1.internal or (p2.internal and abs(p1.beta) > 1e-12):
        raise NotImplementedError("the whole-gear CalculiX model is built for an external pinion (internal pairs: "
                                  "spur only)")
    roll = np.radians(roll_deg)
    phi1 = model.phi_pitch - roll
    rb1, b = p1.r_base, model.face_width
    t_all = time.perf_counter()
    hint = torque / (rb1 ** 2 * 14.0e3 * b)
    theta0 = float(first_contact(model, phi1, lm.teeth1))
    lead = theta0 if p2.internal else 0.0        # external pairs are calibrated at the pitch point (theta0 ~ 0)
    lines = [(k, P @ rotation_z(-lead)[:3, :3].T, N @ rotation_z(-lead)[:3, :3].T)
             for k, P, N in contact_lines(lm, phi1, cap=1.2 * hint * rb1 + 2e-3, theta0=lead)]
    T1, T2 = rotation_z(phi1 - lead), model.pair.gear_frame(phi1)

    def body_lines(T):
        Ti = np.linalg.inv(T)
        return [ContactLine(P[0] @ Ti[:3, :3].T + Ti[:3, 3], P[-1] @ Ti[:3, :3].T + Ti[:3, 3],
                            N[len(N) // 2] @ Ti[:3, :3].T) for _, P, N in lines]
    L1, L2 = body_lines(T1), body_lines(T2)
    t0 = time.perf_counter()
    side2 = "right" if model.gear_side > 0 else "left"
    support2 = "rim" if p2.internal else "bore"
    m1 = build_full_gear(_spec(p1, model.r_bore1, model.web1, b, lm.teeth1, st, L1, "right"))
    m2 = build_full_gear(_spec(p2, model.r_bore2, model.web2, b, lm.teeth2, st, L2, side2))
    t_mesh = time.perf_counter() - t0
    master = tuple(n for n in m2.facets for j in lm.teeth2
                   if n in (f"flank_{j}_{side2}", f"tip_{j}", f"tip_{j}_left", f"tip_{j}_right"))
    f1, f2, pairs, loaded = dict(m1.facets), dict(m2.facets), [], []
    for i, (k, _, _) in enumerate(lines):
        own = (f"flank_{k}_right",) + ((f"tip_{k}", f"tip_{k}_right") if p2.internal else ())
        band1, band2 = facets_near_lines(m1, own, [L1[i]], st.halo), facets_near_lines(m2, master, [L2[i]], st.halo)
        if p2.internal:     # the wheel's tip corner: its own pair, the satellite's flank and fillet the master
            corner = wheel_corner_zone(m2, band2, p2.r_tip, st.h_contact)
            f1[f"corner_{k}"] = facets_near_lines(m1, (f"flank_{k}_right", f"fillet_{k}_right"), [L1[i]], st.halo)
            f2[f"corner_{k}"], band2 = band2[corner], band2[~corner]
            if len(f1[f"corner_{k}"]) and len(f2[f"corner_{k}"]):
                pairs.append(ContactPairSpec(f"W{i}", ("gear", (f"corner_{k}",)), ("pinion", (f"corner_{k}",))))
                loaded.append(k)
        f1[f"band_{k}"], f2[f"band_{k}"] = band1, band2
        if len(band1) and len(band2):
            pairs.append(ContactPairSpec(f"P{i}", ("pinion", (f"band_{k}",)), ("gear", (f"band_{k}",))))
            loaded.append(k)
    m1 = type(m1)(m1.nodes, m1.tets, f1, m1.spec_hash, m1.seconds)
    m2 = type(m2)(m2.nodes, m2.tets, f2, m2.spec_hash, m2.seconds)
    delta = lead + st.preload * hint
    deck = CcxDeck(young=model.case.young, poisson=model.case.poisson, fixed=("gear", support2),
                   driven=("pinion", "bore"), moment=-torque, pairs=tuple(pairs), penalty=st.penalty,
                   stress_output=True)
    work = Path(workdir)
    work.mkdir(parents=True, exist_ok=True)
    ids = write_deck(work / "job.inp", [DeckBody("pinion", m1, rotation_z(phi1 - delta)), DeckBody("gear", m2, T2)],
                     deck)
    digest = hashlib.sha256((work / "job.inp").read_bytes()).hexdigest()
    mesh_info = {"nodes": len(m1.nodes) + len(m2.nodes), "elements": len(m1.tets) + len(m2.tets),
                 "nodes_pinion": len(m1.nodes), "nodes_gear": len(m2.nodes), "h_contact_mm": st.h_contact,
                 "settings": asdict(st), "mesh_wall": t_mesh}
    members = [Member(nm, m, ids["node_offset"][nm], (np.asarray(p.xy), np.asarray(p.kind), np.asarray(p.side)), sd,
                      p.z, tuple(t), twist(p)) for nm, m, p, sd, t in (("pinion", m1, p1, 1, lm.teeth1),
                                                                       ("gear", m2, p2, model.gear_side, lm.teeth2))]
    done = work / "result.json"
    if done.exists():
        rec = json.loads(done.read_text())
        if rec.get("deck_sha256") == digest:
            say(f"whole-gear CalculiX roll {roll_deg:+.3f} deg, band {1e3 * st.h_contact:.0f} um: reusing {done}")
            if ({"root"} - set(rec) or {"p_flank", "p_flank_at"} - set(rec["info"])) and (work / "job.frd").exists():
                res = read_results(work / "job", ids["rot"], tuple(p.name for p in pairs))
                _readouts(rec, work, res, m1, L1, members, b, [k for k, _, _ in lines])
                done.write_text(json.dumps(rec, indent=1))
            return WholeResult(roll_deg, rec["te"], {int(k): v for k, v in rec["pair_load"].items()}, rec["stiffness"],
                               rec["max_pressure"], rec["wall"], rec["info"], rec.get("root", {}))
    say(f"whole-gear CalculiX roll {roll_deg:+.3f} deg, band {1e3 * st.h_contact:.0f} um: {3 * mesh_info['nodes']} "
        f"dofs, {len(lines)} contact line(s), meshed in {t_mesh:.1f} s; solving ...")
    wall_ccx = run_ccx(work / "job.inp", threads=st.threads)
    res = read_results(work / "job", ids["rot"], tuple(p.name for p in pairs))
    theta = delta - res.rotation
    loads = tooth_loads(res.pair_force, pairs, loaded, lm.teeth1)
    p_fit = _fitted_peak(m1, L1, res.contact_nodes, res.contact_pressure, b)
    out = WholeResult(roll_deg, (theta - theta0) / model.pair.ratio * ARCSEC_PER_RAD, loads,
                      stiffness(lm, theta, theta0, torque), p_fit, time.perf_counter() - t_all,
                      dict(mesh_info, theta=theta, theta0=theta0, ccx_wall=wall_ccx, deck_sha256=digest,
                           p_max_nodal=res.max_pressure, reaction=res.fixed_reaction.tolist()))
    say(f"  ccx {wall_ccx:.0f} s: TE {out.te:.3f} arcsec, loads { {k: round(v, 1) for k, v in loads.items()} } N, "
        f"c {out.stiffness:.2f} N/(mm um), p fit {p_fit:.0f} MPa")
    rec = {"deck_sha256": digest, "te": out.te, "pair_load": out.pair_load, "stiffness": out.stiffness,
           "max_pressure": out.max_pressure, "wall": out.wall, "info": out.info}
    done.write_text(json.dumps(rec, indent=1))            # kept before the stress read-out: a run is costly
    _readouts(rec, work, res, m1, L1, members, b, [k for k, _, _ in lines])
    out.root = rec["root"]
    done.write_text(json.dumps(rec, indent=1))
    say(f"  flank peak (face-end slices left out) {rec['info']['p_flank']:.0f} MPa; root stress "
        + ", ".join(f"{k} {v['max']:.0f} MPa (tooth {v['at']['tooth']}, r {v['at']['r_mm']:.2f} mm, "
                    f"z {v['at']['z_mm']:+.2f} mm)" for k, v in out.root.items()))
    return out


#: face slices (b/14 each, as our default fidelity's) whose elliptic-fit peaks make the flank peak: all but the
#: one at each face end, which ours counts as face-end edge contact (:mod:`ltca.cylindrical.edges`)
FLANK_SLICES = 14


def _readouts(rec: dict, work: Path, res, m1, L1, members, b: float, teeth: list) -> None:
    """Add the root stress (``rec["root"]``) and the flank peak away from the face ends (``rec["info"]["p_flank"]``,
    MPa, the elliptic fit over the inner slices; ``p_flank_at``: its pinion tooth (``teeth`` per line), radius and z,
    mm, and fitted half-width, um) to a run's record."""
    cut = b / FLANK_SLICES
    at = fitted_peak(m1, L1, res.contact_nodes, res.contact_pressure, b, window=(-0.5 * b + cut, 0.5 * b - cut))
    rec["info"]["p_flank"] = at["p"]
    rec["info"]["p_flank_at"] = {"tooth": int(teeth[at["line"]]) if at["line"] >= 0 else None,
                                 **{k: at[k] for k in ("r_mm", "z_mm", "half_width_um", "nodes")}}
    rec["root"] = fillet_stress(work / "job.frd", members, b)
