"""Validation against references: Hertz at the pitch point, ISO 6336-1 stiffness, kinematic oracles.

``ltca validate`` runs these on the shipped cases and prints measured vs reference, error and time.
References (../shared/reference/): fzg_c14.csv (geometry, F_bt = 5912.1 N, p0 = 1347.3 MPa,
b = 199.5 um), hertz.md (formulas), iso6336_stiffness.md (c', c'_th).
"""
from __future__ import annotations

import dataclasses
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..cylindrical.loaded_model import LoadedModel, hertz_line
from ..cylindrical.loaded import solve_position
from ..cylindrical.model import PairModel

__all__ = ["HertzCheck", "pitch_point_hertz", "iso6336_stiffness", "run_validate", "fit_elliptic"]


@dataclass(frozen=True)
class HertzCheck:
    """Pitch-point contact compared with Hertz for the line load the solve finds at mid-face."""
    line_load_mean: float        # N/mm, face-averaged (normal force of the pitch-point pair / face width)
    line_load_mid: float         # N/mm at mid-face
    line_load_min: float         # N/mm over the face
    line_load_max: float
    p0: float                    # MPa, fitted peak at mid-face
    b: float                     # mm, fitted half-width at mid-face
    p0_hertz: float              # MPa, Hertz for line_load_mid
    b_hertz: float               # mm
    p_max_cell: float            # MPa, largest cell pressure at mid-face
    total_force: float           # N

    @property
    def p0_error(self) -> float:
        return self.p0 / self.p0_hertz - 1

    @property
    def b_error(self) -> float:
        return self.b / self.b_hertz - 1


def fit_elliptic(x: np.ndarray, p: np.ndarray) -> tuple[float, float, float]:
    """Fit p(x) = p0 sqrt(1 - (x - x0)^2 / b^2) by least squares on p^2 (a parabola); returns p0, b, x0.

    Only cells with p > 0.25 max(p) enter, so cells straddling the contact edge do not bias the fit."""
    use = p > 0.25 * p.max()
    c2, c1, c0 = np.polyfit(x[use], p[use] ** 2, 2)
    x0 = -c1 / (2 * c2)
    p0sq = c0 - c1 ** 2 / (4 * c2)
    return float(np.sqrt(p0sq)), float(np.sqrt(-p0sq / c2)), float(x0)


def pitch_point_hertz(lm: LoadedModel, torque: float, cells_per_b: float = 10.0) -> HertzCheck:
    """Solve the pitch-point position and compare the mid-face pressure with Hertz."""
    fine = dataclasses.replace(lm, fid=dataclasses.replace(lm.fid, cells_per_b=cells_per_b, window=2.5))
    res = solve_position(fine, 0.0, torque)
    model = lm.model
    nsl = fine.fid.slices
    dz = model.face_width / nsl
    # line load of the pair at the pitch point (tooth 0); another pair may share the load (internal pairs)
    w_slices = np.array([res.force[(res.slice == j) & (res.tooth == 0)].sum() for j in range(nsl)]) / dz
    mid = [nsl // 2 - 1, nsl // 2] if nsl % 2 == 0 else [nsl // 2]
    m = np.isin(res.slice, mid) & (res.tooth == 0)
    # average the central slice(s) cell by cell (same lattice index)
    lat = np.unique(res.lattice[m])
    p = np.array([res.pressure[m & (res.lattice == i)].mean() for i in lat])
    s = np.array([res.s[m & (res.lattice == i)].mean() for i in lat])
    s0 = float(np.sum(s * p) / np.sum(p))
    if np.count_nonzero(p > 0.25 * p.max()) >= 4:
        p0, b, _ = fit_elliptic(s, p)
    else:   # degenerate (e.g. no near field): the peak cell and half the loaded extent
        ds = np.diff(s).min() if len(s) > 1 else 0.0
        p0, b = float(p.max()), 0.5 * ds * np.count_nonzero(p > 0)
    w_mid = float(np.mean(w_slices[mid]))
    # relative radius of curvature at the contact point (transverse involute radii, 1/cos(beta_b) normal)
    rb1 = model.pinion.r_base
    rho1 = np.sqrt(2 * rb1 * s0)            # s = L^2 / (2 rb): L = rho1, the involute's radius of curvature
    pair = model.pair
    L_total = pair.a * np.sin(pair.alpha_w)
    # external: rho2 = T1T2 - rho1; internal (concave ring flank, negative radius): rho2 = -(rho1 + a sin alpha_w)
    rho2 = -(rho1 + L_total) if model.gear.internal else (L_total - rho1)
    R = 1.0 / (1.0 / rho1 + 1.0 / rho2) / np.cos(model.pinion.beta_b)
    bh, ph = hertz_line(w_mid * np.cos(model.pinion.beta_b), R, model.case.young, model.case.poisson)
    total = float(res.force[res.tooth == 0].sum())
    return HertzCheck(total / model.face_width, w_mid, float(w_slices.min()), float(w_slices.max()), p0, b, ph, bh,
                      float(p.max()), total)


def iso6336_stiffness(model: PairModel) -> tuple[float, float]:
    """ISO 6336-1 Method B single stiffness: (c', c'_th) in N/(mm um) (shared/reference/iso6336_stiffness.md).

    C_M = 0.8, C_R = 1 (solid discs), C_B from the basic rack dedendum; virtual tooth numbers
    zn = z / (cos^2 beta_b cos beta); the internal gear's terms vanish (zn2 infinite)."""
    case = model.case
    beta = case.helix_angle
    bb = model.pinion.beta_b
    zn1 = case.pinion.teeth / (np.cos(bb) ** 2 * np.cos(beta))
    zn2 = np.inf if case.gear.internal else case.gear.teeth / (np.cos(bb) ** 2 * np.cos(beta))
    x1, x2 = case.pinion.profile_shift, case.gear.profile_shift
    C = [0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182]
    q = (C[0] + C[1] / zn1 + C[2] / zn2 + C[3] * x1 + C[4] * x1 / zn1 + C[5] * x2 + C[6] * x2 / zn2
         + C[7] * x1 ** 2 + C[8] * x2 ** 2)
    c_th = 1.0 / q
    hfp = case.rack_addendum / case.module
    CB = (1 + 0.5 * (1.2 - hfp)) * (1 - 0.02 * (20 - np.degrees(case.pressure_angle)))
    return float(c_th * 0.8 * 1.0 * CB * np.cos(beta)), float(c_th)


def run_validate(out: str = "out/validate", progress: bool = True) -> int:
    """Run the validation cases; print measured vs reference, error and time. Returns an exit status.

    (The CalculiX cross-check is ``ltca.verify.crosscheck.run_calculix_validation``.)"""
    from ..case import FIDELITIES, load_case
    from ..cylindrical.loaded_model import Fidelity, prepare
    from ..cylindrical.model import build_model
    from ..cylindrical.run import cycle_rolls
    from ..cylindrical.tca import unloaded_tca
    root = Path(__file__).resolve().parent.parent.parent / "cases"
    rows = []
    t0 = time.perf_counter()
    case = load_case(root / "fzg_c14.toml")
    model = build_model(case)
    tca = unloaded_tca(model, cycle_rolls(30, case.pinion.teeth))
    rows.append(("FZG C14 unloaded TE ptp, unmodified involute", float(np.ptp(tca.te_arcsec)), "< 0.05 arcsec",
                 float(np.ptp(tca.te_arcsec)) < 0.05, time.perf_counter() - t0))
    rows.append(("FZG C14 transverse contact ratio", tca.eps_alpha, "1.44 (GEARpie)", abs(tca.eps_alpha - 1.44) < 0.005,
                 0.0))
    info = None   # rows that report, not judge
    rolls = cycle_rolls(30, case.pinion.teeth)
    for near in (True, False):
        t0 = time.perf_counter()
        fid = Fidelity.from_preset(FIDELITIES["default"] | {"near_field": near}, case.module)
        lm = prepare(model, fid, rolls, case.torques[0], progress=(lambda m: None))
        hc = pitch_point_hertz(lm, case.torques[0])
        dt = time.perf_counter() - t0
        tag = "with" if near else "without"
        rows.append((f"pitch point p0 {tag} near field [MPa]", hc.p0, f"{hc.p0_hertz:.1f} (Hertz, local w), "
                     f"err {100 * hc.p0_error:+.1f} %", abs(hc.p0_error) < 0.03 if near else info, dt))
        rows.append((f"pitch point half-width {tag} near field [um]", 1e3 * hc.b, f"{1e3 * hc.b_hertz:.1f}, err "
                     f"{100 * hc.b_error:+.1f} %", abs(hc.b_error) < 0.05 if near else info, 0.0))
        if near:
            rows.append(("pitch point face-averaged line load [N/mm]", hc.line_load_mean, "422.29 (F_bt / b)",
                         abs(hc.line_load_mean / 422.29 - 1) < 1e-4, 0.0))
            rows.append(("pitch point line load min .. max over the face [N/mm]", hc.line_load_min,
                         f"max {hc.line_load_max:.1f} (mid-face {hc.line_load_mid:.1f})", info, 0.0))
            res = solve_position(lm, 0.0, case.torques[0])
            from ..cylindrical.results import mesh_stiffness
            c = float(mesh_stiffness(lm, res.theta, res.theta0, case.torques[0]))
            cp, cth = iso6336_stiffness(model)
            rows.append(("single-pair stiffness [N/(mm um)]", c, f"[{0.8 * cp:.2f}, {1.2 * cth:.2f}] (ISO c'={cp:.2f},"
                         f" c'_th={cth:.2f})", 0.8 * cp <= c <= 1.2 * cth, 0.0))
            rows.append(("torque ratio at the pitch point", res.torque_ratio, "1.5 (z2/z1)",
                         abs(res.torque_ratio - 1.5) < 1e-3, 0.0))
    print(f"{'check':52} {'measured':>12}  {'reference':32} {'ok':>3} {'time [s]':>9}")
    for name, val, ref, ok, dt in rows:
        flag = "-" if ok is None else ("yes" if ok else "NO")
        print(f"{name:52} {val:12.4f}  {ref:32} {flag:>3} {dt:9.1f}")
    Path(out).mkdir(parents=True, exist_ok=True)
    with open(Path(out) / "validation.csv", "w") as fh:
        fh.write("check,measured,reference,ok,time_s\n")
        for name, val, ref, ok, dt in rows:
            fh.write(f"\"{name}\",{val},\"{ref}\",{ok},{dt:.2f}\n")
    return 0 if all(r[3] is not False for r in rows) else 1
