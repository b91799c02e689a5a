"""Validation against references: Hertz at the pitch point, ISO 6336-1 stiffness, kinematic oracles.

``ltca validate`` runs these on the shipped cases and prints measured vs reference, error and time.
References (tests/reference/ of the repository): fzg_c14.csv (geometry, F_bt = 5912.1 N, p0 = 1347.3 MPa,
b = 199.5 um), hertz.md (formulas), iso6336_stiffness.md (c', c'_th). The references themselves live in
:mod:`ltca.cylindrical.iso6336` (``report.html`` shows them too) and are importable from here as before.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from ..cylindrical.iso6336 import HertzCheck, fit_elliptic, iso6336_stiffness, pitch_point_hertz
from ..cylindrical.loaded import solve_position

__all__ = ["HertzCheck", "pitch_point_hertz", "iso6336_stiffness", "run_validate", "fit_elliptic"]


def run_validate(out: str = "out/validate", progress: bool = True) -> int:
    """Run the validation cases; print measured vs reference, error and time. Returns an exit status.

    (The CalculiX cross-check is ``ltca.verify.crosscheck.run_calculix_validation``.)"""
    from ..case import FIDELITIES, load_case
    from ..cylindrical.loaded_model import Fidelity, prepare
    from ..cylindrical.model import build_model
    from ..cylindrical.run import cycle_rolls
    from ..cylindrical.tca import unloaded_tca
    from ..shipped import cases_dir
    root = cases_dir()
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
