"""ISO 6336 and Hertz references of a cylindrical pair, beside the loaded analysis (``ltca validate`` and
``report.html``).

- :func:`pitch_point_hertz`: the pitch-point contact solved finely and compared with Hertz for the line load
  the solve finds at mid-face (:class:`HertzCheck`);
- :func:`iso6336_stiffness`: ISO 6336-1 Method B single stiffness c' and its theoretical value c'_th, and
  c_gamma = c' (0.75 eps_alpha + 0.25);
- :func:`root_stress_nominal`: the ISO 6336-3 nominal tooth-root stress sigma_F0 = F_t / (b m_n) Y_F Y_S Y_eps
  (load at the tip, form and stress-correction factors measured on the generated outline by the 30 deg
  tangents, :func:`ltca.geometry.satellite.rating.root_section`), to set beside the fillet stress of the LTCA.

References (tests/reference/): fzg_c14.csv, GEARpie REPORT/C14.txt (F_bt = 5912.1 N, p0 = 1347.3 MPa,
b = 199.5 um), hertz.md, iso6336_stiffness.md.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from .loaded import solve_position
from .loaded_model import LoadedModel, hertz_line
from .model import PairModel

__all__ = [
    "HertzCheck",
    "fit_elliptic",
    "pitch_point_hertz",
    "iso6336_stiffness",
    "c_gamma_iso",
    "RootNominal",
    "root_stress_nominal",
    "iso_comparisons",
]


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


def pitch_point_hertz(lm: LoadedModel, torque: float, cells_per_b: float = 10.0) -> HertzCheck | None:
    """Solve the pitch-point position and compare the mid-face pressure with Hertz; None when no cell at mid-face
    carries load (nothing to compare)."""
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
    if lat.size == 0 or not (res.pressure[m] > 0).any():
        return None          # no contact at mid-face (a misalignment or a lead modification moved it to a face end)
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
    """ISO 6336-1 Method B single stiffness: (c', c'_th) in N/(mm um) (ISO 6336-1, Method B).

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


def c_gamma_iso(c_prime: float, eps_alpha: float) -> float:
    """ISO 6336-1 mesh stiffness c_gamma = c' (0.75 eps_alpha + 0.25), N/(mm um) (spur and helical)."""
    return float(c_prime * (0.75 * eps_alpha + 0.25))


@dataclass(frozen=True)
class RootNominal:
    """ISO 6336-3 nominal root stress of one member (MPa) and its factors (load at the tip)."""

    member: str
    Y_F: float
    Y_S: float
    Y_eps: float
    F_t: float            # N, nominal tangential load at the reference circle
    sigma_F0: float       # MPa, F_t / (b m_n) Y_F Y_S Y_eps


def root_stress_nominal(model: PairModel, torque: float, eps_alpha: float) -> list[RootNominal]:
    """ISO 6336-3 nominal root stress sigma_F0 of each external member at pinion torque ``torque`` (N mm).

    Y_F and Y_S for the load at the tip corner (:func:`ltca.geometry.satellite.rating.root_section`), Y_eps =
    0.25 + 0.75 / eps_alpha_n turns that into the load at the outer point of single contact (ISO 6336-3:1996
    Method C); Y_beta = Y_B = Y_DT = 1 and no load factors (K = 1): the nominal value the LTCA's fillet stress is
    set beside. Internal members are left out (their 60 deg tangent section is not implemented)."""
    from ltca.geometry.satellite.rating import root_section
    case = model.case
    beta_b = model.pinion.beta_b
    eps_n = eps_alpha / np.cos(beta_b) ** 2
    Y_eps = 0.25 + 0.75 / eps_n
    F_t = torque / model.pinion.r_ref
    out = []
    for name, prof in (("pinion", model.pinion), ("gear", model.gear)):
        if prof.internal:
            continue
        try:
            sec = root_section(prof)
        except (ValueError, IndexError):
            continue
        sigma = F_t / (model.face_width * case.module) * sec.Y_F * sec.Y_S * Y_eps
        out.append(RootNominal(name, float(sec.Y_F), float(sec.Y_S), float(Y_eps), float(F_t), float(sigma)))
    return out


def _row(quantity: str, torque_nm: float, ours: float, ref: float, unit: str, source: str, note: str = "") -> dict:
    dev = 100.0 * (ours / ref - 1.0) if ref and np.isfinite(ref) and np.isfinite(ours) else float("nan")
    return {"quantity": quantity, "torque_nm": float(torque_nm), "ours": float(ours), "reference": float(ref),
            "unit": unit, "source": source, "deviation_pct": float(dev), "note": note}


def iso_comparisons(lm: LoadedModel, ds, eps_alpha: float) -> list[dict]:
    """Our results beside ISO 6336 and Hertz, one row per quantity and torque of the run dataset ``ds`` (engineer's
    units, :func:`ltca.cylindrical.sweep.run_dataset`): single-pair stiffness at the pitch point against c',
    the cycle's mean mesh stiffness against c_gamma, the pitch-point peak pressure and half-width against Hertz
    (:func:`pitch_point_hertz`, one fine solve per torque), the largest fillet stress against sigma_F0.

    Each row: ``quantity, torque_nm, ours, reference, unit, source, deviation_pct, note``."""
    model = lm.model
    cp, cth = iso6336_stiffness(model)
    cg = c_gamma_iso(cp, eps_alpha)
    rows = []
    for t in np.atleast_1d(ds.torque.values):
        d = ds.sel(torque=t)
        k = int(np.argmin(np.abs(d.position.values)))
        load = d.pair_load.isel(position=k).values
        pairs = int((load > 1e-6 * load.sum()).sum())
        rows.append(_row("single-pair stiffness at the pitch point", t, float(d.mesh_stiffness.isel(position=k)), cp,
                         "N/(mm um)", f"ISO 6336-1 c' (Method B; c'_th {cth:.2f})",
                         f"roll {float(d.position[k]):+.2f} deg, {pairs} pair(s) in contact"))
        rows.append(_row("mean mesh stiffness", t, float(d.mesh_stiffness.mean()), cg, "N/(mm um)",
                         f"ISO 6336-1 c_gamma = c' (0.75 eps_alpha + 0.25), eps_alpha {eps_alpha:.3f}"))
        hc = pitch_point_hertz(lm, 1e3 * float(t))
        if hc is None:       # nothing to compare: said in the stiffness row's note, never a NaN row
            rows[-1]["note"] = ("pitch-point Hertz check left out: no contact at mid-face at the pitch point "
                                "(misalignment or lead modifications carry the load to a face end)")
        else:
            rows.append(_row("pitch-point peak pressure p0 (mid-face fit)", t, hc.p0, hc.p0_hertz, "MPa",
                             f"Hertz for the mid-face line load {hc.line_load_mid:.1f} N/mm"))
            rows.append(_row("pitch-point Hertz half-width b", t, 1e3 * hc.b, 1e3 * hc.b_hertz, "um", "Hertz"))
        for rn in root_stress_nominal(model, 1e3 * float(t), eps_alpha):
            var = d[f"root_stress_{rn.member}"]
            rows.append(_row(f"{rn.member} root stress, max over the cycle", t, float(np.nanmax(var.values)),
                             rn.sigma_F0, "MPa", "ISO 6336-3 sigma_F0 = F_t/(b m_n) Y_F Y_S Y_eps",
                             f"Y_F {rn.Y_F:.3f}, Y_S {rn.Y_S:.3f}, Y_eps {rn.Y_eps:.3f}; no load factors"))
    return rows
