"""Drive-train stiffness and hysteresis budget (Wang et al.): the ``ltca budget`` command and its outputs.

Table, CSV and plot of a :class:`BudgetResult`, and the backlash curve of a gear pair shifted by the
budget (Eq. 20-21). The members and Eq. (19) are in :mod:`ltca.drivetrain.budget_model`, the case file in
:mod:`ltca.drivetrain.budget_case`; their public names are importable from here as well.
"""
from __future__ import annotations

import os

import numpy as np

from ltca.drivetrain.budget_case import load_backlash_table, load_budget_case
from ltca.drivetrain.budget_model import (
    DEG,
    BallSplineMember,
    BudgetResult,
    DriveTrain,
    Member,
    MeshMember,
    ShaftMember,
    TorsionMember,
    compute_budget,
)

__all__ = ["TorsionMember", "ShaftMember", "MeshMember", "BallSplineMember", "Member",
           "DriveTrain", "BudgetResult", "compute_budget", "load_budget_case", "plot_budget",
           "write_budget_csv", "run_budget"]


def write_budget_csv(result: BudgetResult, path: str) -> None:
    """CSV in 1e-3 deg: one row per torque, one column per member, then total and B0."""
    cols = ["torque_Nm", *[f"{n}_mdeg" for n in result.names], "total_mdeg", "B0_mdeg"]
    data = np.column_stack([result.torque, *(result.deflection / DEG * 1e3),
                            result.total / DEG * 1e3, result.hysteresis / DEG * 1e3])
    np.savetxt(path, data, delimiter=",", header=",".join(cols), comments="", fmt="%.6g")


def plot_budget(result: BudgetResult, path: str) -> None:
    """Stacked bars of member deflections and the B0 line against torque (PNG, Agg backend)."""
    from .. import figures as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    width = 0.6 * (np.min(np.diff(result.torque)) if result.torque.size > 1 else 1.0)
    bottom = np.zeros_like(result.torque)
    for name, row in zip(result.names, result.deflection / DEG * 1e3):
        ax.bar(result.torque, row, width, bottom=bottom, label=name)
        bottom = bottom + row
    ax.plot(result.torque, result.hysteresis / DEG * 1e3, "k-o", label="B0 (Eq. 19)")
    ax.set_xlabel("torque / (N m)")
    ax.set_ylabel("deflection / (1e-3 deg)")
    ax.set_title(result.title or "drive-train budget", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def backlash_from_pair(spec: dict, result: BudgetResult) -> list:
    """Wang et al. Eq. 20-21 on a cylindrical pair: unloaded double-flank TE by TCA, shifted by the budget.

    The TE is that of the gear; the budget's deflections are taken as referred to the same shaft."""
    import dataclasses

    from ..case import load_case
    from ..cylindrical.model import build_model
    from ..cylindrical.run import cycle_rolls
    from ..cylindrical.tca import ARCSEC_PER_RAD, double_flank_tca
    from .backlash import backlash_curves
    case = load_case(spec["pair_case"])
    case = dataclasses.replace(
        case, pinion=dataclasses.replace(case.pinion, thickness_allowance=spec["allowance"][0]),
        gear=dataclasses.replace(case.gear, thickness_allowance=spec["allowance"][1]))
    model = build_model(case)
    cycles = spec["cycles"] or case.pinion.teeth
    roll = cycle_rolls(spec["n"], case.pinion.teeth, cycles)
    drive, coast = double_flank_tca(model, roll)
    return [backlash_curves(roll, drive / ARCSEC_PER_RAD, coast / ARCSEC_PER_RAD, float(d)) for d in result.total]


def run_budget(case_path: str, out_dir: str | None) -> BudgetResult:
    """CLI entry ``ltca budget CASE [--out DIR]``: print the table; write CSV and PNG into out_dir.

    With a ``[backlash]`` table, also the backlash curve of the named gear pair from its unloaded
    drive- and coast-side TE and the loaded curves shifted by each torque's total deflection."""
    train, torques = load_budget_case(case_path)
    result = compute_budget(train, torques)
    print(result.table())
    spec = load_backlash_table(case_path)
    curves = backlash_from_pair(spec, result) if spec else []
    for T, c in zip(torques, curves):
        arcsec = np.pi / 180 / 3600
        print(f"backlash at {T:g} N m: unloaded {c.backlash.min() / arcsec:.2f} .. {c.backlash.max() / arcsec:.2f} "
              f"arcsec, loaded separation {c.loaded_hysteresis.min() / arcsec:.2f} .. "
              f"{c.loaded_hysteresis.max() / arcsec:.2f} arcsec")
    if out_dir:
        os.makedirs(out_dir, exist_ok=True)
        write_budget_csv(result, os.path.join(out_dir, "budget.csv"))
        plot_budget(result, os.path.join(out_dir, "budget.png"))
        if curves:
            from .backlash import plot_backlash
            plot_backlash(curves[-1], os.path.join(out_dir, "backlash.png"),
                          f"{result.title}: backlash, loaded at {torques[-1]:g} N m")
            with open(os.path.join(out_dir, "backlash.csv"), "w") as fh:
                fh.write("roll_deg,te_drive_arcsec,te_coast_arcsec,backlash_arcsec,"
                         + ",".join(f"loaded_drive_{T:g}Nm,loaded_coast_{T:g}Nm" for T in torques) + "\n")
                arc = np.pi / 180 / 3600
                c0 = curves[0]
                for i in range(len(c0.roll_angle)):
                    row = [np.degrees(c0.roll_angle[i]), c0.te_drive[i] / arc, c0.te_coast[i] / arc,
                           c0.backlash[i] / arc]
                    for c in curves:
                        row += [c.loaded_drive[i] / arc, c.loaded_coast[i] / arc]
                    fh.write(",".join(f"{v:.6g}" for v in row) + "\n")
    return result
