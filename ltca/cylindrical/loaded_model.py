"""The loaded model of a cylindrical pair: the fidelity knobs, and both bodies' compliance computed once
(:func:`prepare`, the costly step) for the teeth in mesh over the positions, ready for any number of positions
and torques; the contact of each position is solved in :mod:`ltca.cylindrical.loaded`.
"""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass, field

import numpy as np

from ltca.fem.compliance import BodyCompliance, ComplianceSpec, pair_compliance
from ltca.geometry.cylindrical import arc_length

from .model import PairModel
from .tca import flank_gaps, unloaded_tca

__all__ = ["Fidelity", "LoadedModel", "BodyPlan", "plan_bodies", "prepare", "hertz_line"]


@dataclass(frozen=True)
class Fidelity:
    """The knobs of one analysis (lengths in mm)."""
    h_flank: float          # FE element size at the flanks
    h_body: float           # FE element size far from the teeth
    grid: tuple[int, int]   # compliance grid per loaded flank (profile, face)
    cells_per_b: float      # contact cells per nominal Hertz half-width (profile direction)
    slices: int             # contact cells along the face
    near_field: bool        # half-space near-field correction on/off
    depth: float            # read depth d of the FE regular part (and 2d), mm; default 0.75 h_flank
    window: float = 3.0     # strip half-width in nominal Hertz half-widths
    slice_length: float = 0.0   # longest contact cell along a helical face, mm (0: ``slices`` alone)
    ds_max: float = 0.0     # widest contact cell across the line, mm (0: ``cells_per_b`` alone); see :meth:`cell_size`
    fillet: float = 0.0     # element size on the read fillets / their smallest radius of curvature (0: h_flank)

    @staticmethod
    def from_preset(params: dict, module: float, **override) -> "Fidelity":
        p = dict(params)
        p.update({k: v for k, v in override.items() if v is not None})
        h = p["h_flank"] * module
        return Fidelity(h_flank=h, h_body=p["h_body"] * module, grid=tuple(p["grid"]),
                        cells_per_b=p["cells_per_b"], slices=p["slices"], near_field=p["near_field"],
                        depth=p.get("depth", 0.75 * h) if p["near_field"] else 0.0, window=p.get("window", 2.0),
                        slice_length=p.get("slice_length", 0.0) * module, ds_max=p.get("ds_max", 0.0) * module,
                        fillet=p.get("fillet", 0.0))

    def cell_size(self, half_width: float) -> float:
        """Contact cell size across the line (mm) for a nominal Hertz half-width ``half_width`` (mm):
        ``half_width / cells_per_b``, at most ``ds_max``.

        The cap is for tip-edge contact: a sharp edge makes a kink in the unloaded gap, and cells sample
        it at their centres only, so its minimum is missed by up to half a cell times the slope jump. A
        nearly conformal pair (internal, tooth difference one) has a nominal half-width of most of a
        module, and cells from it alone miss the kink by more than its share of the deflection. On the
        eccentric planetary pair at 3000 N m, 0.83 mm cells read the gap at the wheel's tip corner on
        satellite tooth -8 12 um too wide and halved that pair's share; every cell size of 0.04 module
        or less gives the same share within 1 %."""
        ds = half_width / self.cells_per_b
        return min(ds, self.ds_max) if self.ds_max > 0 else ds

    def for_pair(self, face_width: float, helical: bool) -> "Fidelity":
        """The knobs for a pair: a helical face gets at least ``face_width / slice_length`` slices. The contact
        line crosses the flank's tip and root edges there at a small angle (about 10 deg on helical C14), and a
        cell as long as a slice of a wide face resolves that crossing too coarsely: the TE and the pressure near
        the edges ripple as the crossing passes from one slice to the next."""
        if not helical or self.slice_length <= 0:
            return self
        return dataclasses.replace(self, slices=max(self.slices, int(np.ceil(face_width / self.slice_length - 1e-9))))


def hertz_line(w: float, R: float, E: float, nu: float) -> tuple[float, float]:
    """Hertz line contact of two equal materials: half-width b (mm) and peak p0 (MPa) for load w (N/mm).

    b = sqrt(4 w R / (pi E*)), p0 = 2 w / (pi b), 1/E* = 2 (1 - nu^2)/E (Johnson, Contact Mechanics, 4.2).
    """
    Es = E / (2 * (1 - nu ** 2))
    b = np.sqrt(4 * w * R / (np.pi * Es))
    return float(b), float(2 * w / (np.pi * b))


@dataclass
class LoadedModel:
    """The pair with both bodies' compliance, ready for any number of positions and torques."""
    model: PairModel
    fid: Fidelity
    teeth1: tuple[int, ...]
    teeth2: tuple[int, ...]
    body1: BodyCompliance
    body2: BodyCompliance
    b_nom: float              # Hertz half-width of the nominal line load at torque_nom, mm
    R_nom: float
    torque_nom: float         # N mm
    timings: dict = field(default_factory=dict)

    def without_solver(self) -> LoadedModel:
        """The same model with both bodies' factor freed (:meth:`ltca.fem.compliance.BodyCompliance.without_solver`):
        for studies and checks that write no VTU; ``self`` can no longer write one."""
        return dataclasses.replace(self, body1=self.body1.without_solver(), body2=self.body2.without_solver())

    def half_width(self, torque: float) -> float:
        """Nominal Hertz half-width at another torque: b grows as sqrt(load) (Johnson 4.2)."""
        return self.b_nom * np.sqrt(torque / self.torque_nom)


def _teeth_in_mesh(model: PairModel, rolls: np.ndarray, cap: float):
    tca = unloaded_tca(model, rolls, teeth=range(-3, 4), ns=120, nz=5)
    near = np.isfinite(tca.min_gap) & (tca.min_gap < cap)
    teeth1 = tuple(int(k) for k in tca.teeth[near.any(axis=0)])
    s_lo = arc_length(model.pinion_range()[0], model.pinion.r_base)
    s_hi = arc_length(model.pinion_range()[1], model.pinion.r_base)
    g2 = set()
    for roll in rolls[:: max(1, len(rolls) // 8)].tolist() + [rolls[-1]]:
        for k in teeth1:
            fg = flank_gaps(model, model.phi_pitch - roll, k, np.linspace(s_lo, s_hi, 60), 0.0)
            g2.update(int(t) for t in np.unique(fg.gear_tooth[np.isfinite(fg.gap) & (fg.gap < 2 * cap)]))
    return tca, teeth1, tuple(sorted(g2))


@dataclass(frozen=True)
class BodyPlan:
    """What :func:`prepare` computes before the costly step: the teeth in mesh, both bodies' compliance specs
    and the nominal Hertz contact. Cheap (an unloaded TCA); the specs and profiles fix the FE bodies."""
    teeth1: tuple[int, ...]
    teeth2: tuple[int, ...]
    spec1: ComplianceSpec
    spec2: ComplianceSpec
    b_nom: float
    R_nom: float
    torque_nom: float
    t_tca: float


def plan_bodies(model: PairModel, fid: Fidelity, rolls: np.ndarray, torque: float, progress=None) -> BodyPlan:
    """Choose the teeth in mesh over ``rolls`` at ``torque`` (N mm) and the compliance spec of each body."""
    say = progress or (lambda m: None)
    case = model.case
    fid = fid.for_pair(model.face_width, abs(model.pinion.beta) > 1e-12)
    t0 = time.perf_counter()
    p1, p2 = model.pinion, model.gear
    b = model.face_width
    w_nom = torque / (p1.r_base * b)
    rho1 = p1.r_base * np.tan(model.pair.alpha_w)
    rho2 = p2.r_base * np.tan(model.pair.alpha_w)
    R_nom = 1.0 / (1 / rho1 - 1 / rho2) if p2.internal else 1.0 / (1 / rho1 + 1 / rho2)
    R_nom /= np.cos(p1.beta_b)
    b_nom, _ = hertz_line(w_nom * np.cos(p1.beta_b), R_nom, case.young, case.poisson)
    # gaps below the expected deflection (ISO c' ~ 14 N/(mm um)) with a margin can close under load
    cap = 3.0 * w_nom / 14.0e3 + 0.01
    _, teeth1, teeth2 = _teeth_in_mesh(model, rolls, cap)
    say(f"teeth in mesh: pinion {list(teeth1)}, gear {list(teeth2)}; modelled with one neighbour each side")

    def spec(teeth, side, r_range, r_bore, web):
        return ComplianceSpec(teeth=tuple(range(min(teeth) - 1, max(teeth) + 2)), loaded=teeth, side=side,
                              r_range=r_range, grid=fid.grid, face_width=b, r_bore=r_bore, web=web, h_flank=fid.h_flank,
                              h_body=fid.h_body, depth=fid.depth, young=case.young, poisson=case.poisson,
                              fillet=fid.fillet)
    return BodyPlan(teeth1, teeth2, spec(teeth1, +1, model.pinion_range(), model.r_bore1, model.web1),
                    spec(teeth2, model.gear_side, model.gear_range(), model.r_bore2, model.web2),
                    b_nom, R_nom, torque, time.perf_counter() - t0)


def prepare(model: PairModel, fid: Fidelity, rolls: np.ndarray, torque: float, cache_dir=None,
            progress=None, bodies: tuple[BodyCompliance, BodyCompliance] | None = None,
            plan: BodyPlan | None = None) -> LoadedModel:
    """Choose the teeth in mesh over ``rolls`` and compute both bodies' compliance (the costly step).

    ``bodies``, when given, are the two compliances of these very bodies computed before (the same
    :func:`plan_bodies` specs and profiles); they are used as they are and nothing is computed. ``plan``, when
    given, is the :func:`plan_bodies` of these very arguments, computed before."""
    say = progress or (lambda m: None)
    fid = fid.for_pair(model.face_width, abs(model.pinion.beta) > 1e-12)
    plan = plan or plan_bodies(model, fid, rolls, torque, say)
    timings = {"tca": plan.t_tca}
    if bodies is None:
        body1, body2 = pair_compliance((model.pinion, model.gear), (plan.spec1, plan.spec2), cache_dir, say)
    else:
        body1, body2 = bodies
        if body1.spec != plan.spec1 or body2.spec != plan.spec2:
            raise ValueError("prepare: the given bodies were computed for other compliance specs")
    for name in ("mesh", "assembly", "factorisation", "setup", "solves"):
        timings[name] = body1.timings.get(name, 0) + body2.timings.get(name, 0)
    return LoadedModel(model, fid, plan.teeth1, plan.teeth2, body1, body2, plan.b_nom, plan.R_nom, torque, timings)
