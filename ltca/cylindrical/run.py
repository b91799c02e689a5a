"""The cylindrical ``ltca tca``: the unloaded TCA of a case file, its table and plot; the position loop's names
(:mod:`ltca.cylindrical.loop`) for scripts. ``ltca run`` is :mod:`ltca.driver`."""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from ..case import load_case
from ..errors import CaseError
from .loop import analyse, cycle_rolls
from .model import build_model
from .tca import unloaded_tca

__all__ = ["run_tca", "tca_summary", "cycle_rolls", "analyse"]


def tca_summary(case, positions: int | None = None, file: str | None = None) -> tuple[dict, np.ndarray, object]:
    """The unloaded TCA of a cylindrical case over one mesh cycle: (summary, rolls in rad, the TCA record).

    Writes and prints nothing; ``summary`` has the contact ratios, the working pressure angle, the unloaded TE
    peak-to-peak (arcsec) and the contact path per position."""
    from ..sizing import MAX_POSITIONS
    from .warnings import check_contact, contact_ratio_transverse, design_warnings
    model = build_model(case)
    check_contact(model, str(file or case.name))
    warnings = design_warnings(model)
    n = positions or case.positions
    if n > MAX_POSITIONS:
        raise CaseError("--positions", n, f"an integer in [1, {MAX_POSITIONS}] (as analysis.positions)")
    rolls = cycle_rolls(n, case.pinion.teeth)
    r = unloaded_tca(model, rolls)
    head = {"case": case.name, "positions": n, "te_unloaded_ptp_arcsec": float(np.ptp(r.te_arcsec)),
            "contact_ratio_transverse": r.eps_alpha, "contact_ratio_overlap": r.eps_beta,
            "working_pressure_angle_deg": float(np.degrees(model.pair.alpha_w)),
            "centre_distance_mm": model.pair.a, "path": {"roll_deg": np.degrees(rolls).tolist(),
                                                         "tooth": r.contact_tooth.tolist(),
                                                         "radius_mm": r.contact_r.tolist(),
                                                         "z_mm": r.contact_z.tolist(),
                                                         "te_arcsec": r.te_arcsec.tolist()},
            "contact_ratio_tip_circles": contact_ratio_transverse(model), "warnings": warnings}
    return head, rolls, r


def run_tca(case_path: str, out: str | None = None, positions: int | None = None) -> dict:
    """``ltca tca`` of a cylindrical case file: :func:`tca_summary`, its table, and with ``out`` the summary and
    plot."""
    case = load_case(case_path)
    head, rolls, r = tca_summary(case, positions, str(case_path))
    n = head["positions"]
    for w in head["warnings"]:
        print(f"ltca tca: warning: {w}", file=sys.stderr)
    print(f"{case.name}: eps_alpha = {r.eps_alpha:.4f}, eps_beta = {r.eps_beta:.4f}, "
          f"alpha_wt = {head['working_pressure_angle_deg']:.4f} deg, unloaded TE ptp = "
          f"{head['te_unloaded_ptp_arcsec']:.4f} arcsec")
    print(f"{'roll [deg]':>11} {'tooth':>5} {'r [mm]':>9} {'z [mm]':>8} {'TE [arcsec]':>12}")
    for i in range(n):
        print(f"{np.degrees(rolls[i]):11.3f} {r.contact_tooth[i]:5d} {r.contact_r[i]:9.4f} {r.contact_z[i]:8.3f} "
              f"{r.te_arcsec[i]:12.4f}")
    if out:
        from ..outputs import check_out_dir, write_json_atomic
        check_out_dir(out)
        write_json_atomic(Path(out) / "summary.json", head)
        from matplotlib.figure import Figure
        fig = Figure(figsize=(7, 4))
        ax = fig.add_subplot()
        ax.plot(np.degrees(rolls), r.te_arcsec, "o-")
        ax.set(xlabel="pinion roll from the pitch point [deg]", ylabel="unloaded TE [arcsec]", title=case.name)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        from ..outputs import atomic_path
        with atomic_path(Path(out) / "te_unloaded.png") as tmp:
            fig.savefig(tmp, dpi=110, format="png")
    return head
