"""``ltca convergence``: wall time against error over a ladder of fidelities.

Each rung is a complete cold analysis (mesh, compliance, contact at every position). Errors are
relative to the finest rung: loaded TE (largest deviation over the positions, relative to the
reference's mean loaded TE), peak contact pressure at the pitch point and over the cycle, and the
largest root stress of the pinion and of the gear over the positions (each rung meshes the read fillets at its own
``fillet`` size, :mod:`ltca.fem.fillet`).
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from ..case import FIDELITIES, load_case
from ..cylindrical.loaded_model import Fidelity, prepare
from ..cylindrical.loaded import te_arcsec
from ..cylindrical.model import build_model
from ..outputs import write_json
from ..cylindrical.run import analyse, cycle_rolls

__all__ = ["LADDER", "run_convergence"]

#: (label, preset, overrides) from cheapest to the reference (last).
LADDER: list[tuple[str, str, dict]] = [
    ("coarse", "coarse", {}),
    ("default, no near field", "default", {"near_field": False}),
    ("default, contact cells / 2", "default", {"cells_per_b": 3, "slices": 8}),
    ("default", "default", {}),
    ("default, contact cells x 2", "default", {"cells_per_b": 8, "slices": 20}),
    ("fine flank mesh", "default", {"h_flank": 0.2, "h_body": 1.0}),
    ("fine (reference)", "fine", {}),
]


def _rung(model, params, rolls, torque, progress):
    t0 = time.perf_counter()
    fid = Fidelity.from_preset(params, model.case.module)
    lm = prepare(model, fid, rolls, torque, progress=progress)
    res = analyse(lm, rolls, torque)
    wall = time.perf_counter() - t0
    pitch = int(np.argmin(np.abs(rolls)))
    return {"wall_s": wall, "te": te_arcsec(lm, [r.theta for r in res]),
            "p_pitch": res[pitch].max_pressure, "p_max": max(r.max_pressure for r in res),
            "root": max(max(r.root1.values()) for r in res), "root_gear": max(max(r.root2.values()) for r in res),
            "dofs": lm.body1.n_dofs + lm.body2.n_dofs, "h_flank": fid.h_flank}


def run_convergence(case_path: str, out: str = "out/convergence", positions: int = 8, progress: bool = True,
                    ladder: list | None = None) -> list[dict]:
    """Run the ladder, print the table, write convergence.json/csv and a time-against-error plot."""
    case = load_case(case_path)
    model = build_model(case)
    rolls = cycle_rolls(positions, case.pinion.teeth)
    rolls = np.sort(np.append(rolls[np.abs(rolls) > 1e-12], 0.0))    # include the pitch point
    torque = case.torques[0]
    rows = []
    for label, preset, over in (ladder or LADDER):
        if progress:
            print(f"  rung: {label} ...", flush=True)
        rows.append({"label": label, **_rung(model, FIDELITIES[preset] | over, rolls, torque, None)})
    ref = rows[-1]
    te_scale = float(np.mean(ref["te"]))
    for r in rows:
        r["err_te"] = float(np.max(np.abs(r["te"] - ref["te"])) / te_scale)
        r["err_p_pitch"] = float(abs(r["p_pitch"] / ref["p_pitch"] - 1))
        r["err_p_max"] = float(abs(r["p_max"] / ref["p_max"] - 1))
        r["err_root"] = float(abs(r["root"] / ref["root"] - 1))
        r["err_root_gear"] = float(abs(r["root_gear"] / ref["root_gear"] - 1))
    print(f"{case.name}, {len(rolls)} positions, T = {torque * 1e-3:g} N m; errors relative to '{ref['label']}'")
    print(f"{'rung':28} {'h_flank':>7} {'dofs':>8} {'wall [s]':>9} {'TE err':>8} {'p pitch':>8} {'p max':>8} "
          f"{'root 1':>8} {'root 2':>8}")
    for r in rows:
        print(f"{r['label']:28} {r['h_flank']:7.2f} {r['dofs']:8d} {r['wall_s']:9.1f} {100 * r['err_te']:7.2f}% "
              f"{100 * r['err_p_pitch']:7.2f}% {100 * r['err_p_max']:7.2f}% {100 * r['err_root']:7.2f}% "
              f"{100 * r['err_root_gear']:7.2f}%")
    outdir = Path(out)
    outdir.mkdir(parents=True, exist_ok=True)
    write_json(outdir / "convergence.json", {"case": case.name, "rungs": [
        {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in r.items()} for r in rows]})
    from .. import figures as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, lab in (("err_te", "loaded TE"), ("err_p_pitch", "peak pressure (pitch point)"),
                     ("err_root", "pinion root stress"), ("err_root_gear", "gear root stress")):
        ax.loglog([r["wall_s"] for r in rows[:-1]], [max(r[key], 1e-5) for r in rows[:-1]], "o", label=lab)
    for r in rows[:-1]:
        ax.annotate(r["label"], (r["wall_s"], max(r["err_te"], 1e-5)), fontsize=7)
    ax.set(xlabel="wall time, cold [s]", ylabel=f"relative error vs '{ref['label']}'", title=f"{case.name}: speed "
           "against error")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    fig.tight_layout()
    fig.savefig(outdir / "convergence.png", dpi=110)
    plt.close(fig)
    return rows
