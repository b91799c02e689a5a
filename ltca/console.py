"""The console output of ``ltca run``: a table per gear kind, from a result and its summary. Command layer: the
only place besides :mod:`ltca.cli` and the command modules that prints."""
from __future__ import annotations

import json

__all__ = ["print_result"]


def print_result(result, head: dict, say=None) -> None:
    """Print the run's tables (``say`` receives the progress-level lines such as edge contacts)."""
    if result.case.kind == "cylindrical":
        st = result._state
        print_cylindrical(head, result.dataset, result.case.name, st.plan.positions, st.plan.case.cycles, say)
    elif result.case.kind == "bevel":
        print_bevel(result, head)
    else:
        print_planetary(result, head)


def print_cylindrical(head: dict, dataset, name: str, n_pos: int, cycles: int, say=None) -> None:
    """The console output of ``ltca run`` of a cylindrical case: edge contacts (``say``), the headline JSON and the
    tables per torque and of the TE harmonics."""
    from .cylindrical.sweep import harmonics_table, torque_table
    if say is not None:
        for rec in head["torques"]:
            for e in rec.get("edge_contact", []):
                say(f"  edge contact at {rec['torque_nm']:g} N m, {e['edge']} ({e['modelled_as']}): up to "
                    f"{e['max_load_n']:.0f} N at {e['positions']} position(s), roll {min(e['roll_deg']):+.2f} .. "
                    f"{max(e['roll_deg']):+.2f} deg, pinion diameter {e['pinion_diameter_mm'][0]:.2f} .. "
                    f"{e['pinion_diameter_mm'][1]:.2f} mm, peak {e['max_pressure_mpa']:.0f} MPa"
                    + (f" - MESH-DEPENDENT (not a flank pressure): {e['why']}" if e["mesh_dependent"] else ""))
    print(json.dumps({k: head[k] for k in ("torque_nm", "te_loaded_ptp_arcsec", "te_unloaded_ptp_arcsec",
                                           "max_flank_pressure_mpa", "max_flank_pressure_at", "edge_note",
                                           "max_contact_pressure_mpa", "max_root_stress_mpa",
                                           "mesh_stiffness_mean_n_per_mm_um", "max_pairs_in_contact",
                                           "converged", "timings_s") if k in head}, indent=1))
    print(f"{name}: {n_pos} positions per mesh cycle x {cycles} cycle(s), every torque:")
    print(torque_table(head["torques"]))
    print(harmonics_table(dataset))


def print_bevel(result, head: dict) -> None:
    """The console table of ``ltca run`` of a bevel case."""
    p = result._state.plan
    asm = p.asm
    print(f"Spiral bevel LTCA: {result.case.name} ({p.fid.name}, {p.positions} positions per cycle, assembly "
          f"E {asm.E:g} P {asm.P:g} G {asm.G:g} mm)")
    print(f"{'torque N m':>10s} {'flank':8s} {'TE p-p loaded':>13s} {'unloaded':>9s} {'p flank MPa':>11s} "
          f"{'p max MPa':>10s} {'max share':>9s} {'root MPa':>9s} {'k N/um':>7s}  edges")
    for t in head["torques"]:
        print(f"{t['torque_nm']:10g} {t['flank']:8s} {t['te_loaded_ptp_arcsec']:13.2f} "
              f"{t['te_unloaded_ptp_arcsec']:9.2f} {t['max_flank_pressure_mpa']:11.0f} "
              f"{t['max_contact_pressure_mpa']:10.0f} {t['max_pair_share']:9.3f} "
              f"{t['max_root_stress_mpa']['pinion']:9.0f} {t['mesh_stiffness_mean_n_per_um']:7.0f}  "
              f"{', '.join(t['edge_locations']) or '-'}")
    print("TE in arcsec (positive: the gear lags); p flank: peak pressure away from the flank edges (its "
          "convergence: ltca convergence); p max: with the edge cells (singular at a sharp edge, grows as the "
          "cells shrink)")


def print_planetary(result, head: dict) -> None:
    """The console table of ``ltca run`` of a planetary case (both directions per torque)."""
    from .planetary.analysis import ROW_KEYS, SHARE_MIN
    from .planetary.run import print_table as _table
    _table([{k: (({p: round(v, 3) for p, v in r[k].items() if v >= SHARE_MIN}) if k == "mean_share" else r[k])
                  for k in ROW_KEYS} for r in head["results"]], ROW_KEYS)
    t = head["timings_s"]
    print(f"timings: prepare {t['prepare']:.1f} s, contact {t['contact']:.1f} s, total {t['total']:.1f} s")
