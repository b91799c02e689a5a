"""The planetary commands: ``ltca forming`` (method comparison) and ``ltca tca`` (unloaded gaps of every pair,
both directions) of a ``[satellite]`` case, with their console tables; ``ltca run`` goes through the one core
(:mod:`ltca.core`, the kind :mod:`ltca.kinds.planetary` over :mod:`.analysis`) and prints with
:func:`ltca.console.print_planetary`.
"""
from __future__ import annotations

import json
import time

import numpy as np

from ltca.geometry.satellite import plot_forming

from .analysis import planetary_tca_summary
from .case import compare_case_forming, load_planetary_case
from .report import format_table, out_dir, plot_gaps, write_csv

__all__ = ["run_forming", "run_planetary_tca", "print_table"]


def print_table(rows: list[dict], keys: list[str] | None = None) -> str:
    """Print the fixed-width text table of ``rows`` (:func:`.report.format_table`) and return it."""
    text = format_table(rows, keys)
    print(text)
    return text


def run_forming(case_path, out=None) -> list[dict]:
    """Cut the satellite by (a), (b), (c) with the case's tools; table, ``forming.csv``, ``forming.png``."""
    case = load_planetary_case(case_path)
    t0 = time.perf_counter()
    cmp = compare_case_forming(case, str(case_path))      # a tool that cannot cut it: exit 2 naming the fields
    rows = cmp.table()
    for r in rows:
        dev = cmp.deviations.get(r["method"])
        r["max_dev_involute_um"] = None if dev is None else dev.max_abs_involute_um
    print(f"satellite z = {case.design.z}, m = {case.design.m} mm, x = {case.design.x}, thinning {case.design.thinning} m:"
          f" Eq. 3 thickness {case.design.eq3_thickness:.4f} mm; disk-cutter plunge for Eq. 3: x = {cmp.plunge_for_eq3:.4f}")
    print_table(rows, ["method", "passes", "s_ref", "s_minus_eq3_um", "tip_land", "pointed", "nearly_pointed",
                       "dedendum", "root_fillet_radius", "max_deviation_um", "max_dev_involute_um"])
    d = out_dir(out)
    if d is not None:
        write_csv(d / "forming.csv", rows)
        plot_forming(cmp, d / "forming.png")
    print(f"forming comparison: {time.perf_counter() - t0:.1f} s")
    return rows


def run_planetary_tca(case_path, out=None, n_positions: int | None = None) -> dict:
    """``ltca tca`` of a planetary case file: :func:`planetary_tca_summary`, its table, and with ``out`` the gaps
    (CSV, plot) and the summary."""
    case = load_planetary_case(case_path)
    summary, rows, (sm, ug) = planetary_tca_summary(case, n_positions)
    print(f"internal pair z1 {sm.mesh.z1} / z2 {sm.mesh.z2}, e = {sm.mesh.e} mm, alpha_w = {summary['alpha_w_deg']:.3f} deg, "
          f"satellite cut by {case.method}; first contact before the involute contact: "
          f"{summary['first_contact_um']} um (0: involutes touch first)")
    print_table(rows)
    d = out_dir(out)
    if d is not None:
        write_csv(d / "gaps.csv", [dict(direction=s, phi_deg=float(np.degrees(p)), pair=int(k), gap_um=float(g))
                                   for s in (1, -1) for i, p in enumerate(ug.phi) for k, g in zip(ug.pairs, ug.gap_um[s][i])
                                   if g < 1000])
        plot_gaps(d / "gaps.png", ug.phi, ug.pairs, ug.gap_um)
        (d / "summary.json").write_text(json.dumps(summary, indent=1))
    return summary
