"""``report.html``: one self-contained page of a cylindrical ``ltca run`` (no server, no script, no external
file: the plots are embedded as base64 PNG), rendered by Jinja2 from ``templates/report.html.j2``.

It holds the results per torque, our results beside ISO 6336 and Hertz (:func:`ltca.cylindrical.iso6336.
iso_comparisons`), the plots, the warnings (design checks, sampling, pressures, edge contact, unconverged
positions), the derived geometry (:func:`ltca.cylindrical.derived.derived_geometry`), the inputs and the timings.
"""
from __future__ import annotations

import datetime as _dt
from pathlib import Path

import numpy as np

from ..html_page import embedded_plots, render_page

__all__ = ["PLOTS", "report_context", "render_report", "write_run_report"]

#: the plots of a run in the order the page shows them, with their captions
PLOTS = (
    ("te.png", "Loaded and unloaded transmission error over the mesh cycle, per torque: gear rotation lag in arcsec "
               "(left) and on the line of action in um (right)."),
    ("te_ptp.png", "Loaded TE peak-to-peak against torque."),
    ("te_harmonics.png", "Loaded TE amplitudes of the first mesh orders, per torque."),
    ("load_sharing.png", "Share of the normal load carried by each pinion tooth, per torque."),
    ("bearing_pattern_diameter.png", "Bearing pattern (envelope of the contact pressure over the cycle) against the "
                                     "pinion diameter, with the root form diameter, SAP, EAP and tip form diameter."),
    ("bearing_pattern.png", "Bearing pattern on the pinion flank against the involute roll angle, edge contact "
                            "marked; one colour scale for every torque (the flank peak)."),
    ("root_stress.png", "Largest principal fillet stress of pinion and gear over the cycle, per torque."),
)


def _g(v) -> str:
    """A case value, or 'from the blank' where the case leaves it to the geometry (None)."""
    return "from the blank" if v is None else f"{v:g}"


def _inputs(case) -> list[tuple[str, str]]:
    p, g = case.pinion, case.gear
    deg = np.degrees
    return [
        ("normal module m_n", f"{case.module:g} mm"),
        ("normal pressure angle alpha_n", f"{deg(case.pressure_angle):g} deg"),
        ("helix angle beta", f"{deg(case.helix_angle):g} deg"),
        ("teeth z1 / z2", f"{p.teeth} / {g.teeth}{' (internal gear)' if g.internal else ''}"),
        ("profile shift x1 / x2", f"{_g(p.profile_shift)} / {_g(g.profile_shift)}"),
        ("face width b1 / b2", f"{_g(p.face_width)} / {_g(g.face_width)} mm"),
        ("tip diameter d_a1 / d_a2", f"{_g(p.tip_diameter)} / {_g(g.tip_diameter)} mm"),
        ("basic rack h_aP0 / h_fP0 / rho_aP0", f"{case.rack_addendum:g} / {case.rack_dedendum:g} / "
                                               f"{case.rack_tip_radius:g} mm"),
        ("Young's modulus / Poisson ratio", f"{case.young:g} MPa / {case.poisson:g}"),
        ("pinion torque(s)", ", ".join(f"{t * 1e-3:g}" for t in case.torques) + " N m"),
    ]


def report_context(case, case_path: str, head: dict, geometry: dict, comparisons: list[dict], striping: dict,
                   plots_dir: Path, timings: dict, n_pos: int, fidelity: str, unconverged: list[str],
                   paraview: str | None = None, command: str | None = None) -> dict:
    """Everything the template shows. ``head`` is the run's summary (``torques`` records, ``warnings``),
    ``striping`` {torque N m: index}, ``timings`` {stage: s}, ``plots_dir`` the folder holding the PNGs."""
    records = head["torques"]
    edges = [dict(e, torque_nm=r["torque_nm"]) for r in records for e in r.get("edge_contact", [])]
    try:
        text = Path(case_path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        text = "(not readable)"
    try:
        import tomllib
        description = str(tomllib.loads(text).get("case", {}).get("description", ""))
    except (ImportError, ValueError, AttributeError):
        description = ""
    from .pattern import STRIPING_LIMIT
    return {
        "case_name": case.name, "description": description,
        "torques": [f"{t * 1e-3:g}" for t in case.torques], "positions": n_pos, "cycles": case.cycles,
        "fidelity": fidelity, "written": _dt.datetime.now().isoformat(timespec="seconds"),
        "command": command or f"ltca run {case_path}", "records": records, "comparisons": comparisons,
        "striping": sorted(striping.items()), "striping_limit": STRIPING_LIMIT,
        "plots": embedded_plots(plots_dir, PLOTS),
        "warnings": head.get("warnings", []), "edges": edges, "unconverged": unconverged,
        "max_residual": max(float(r.get("max_torque_residual", 0.0)) for r in records),
        "geometry": geometry, "inputs": _inputs(case), "case_path": str(case_path), "case_text": text,
        "timings": list(timings.items()), "paraview": paraview,
    }


def render_report(context: dict) -> str:
    """The page's HTML from :func:`report_context`'s dictionary (Jinja2, autoescaped)."""
    return render_page("ltca.cylindrical", context)


def write_run_report(stage: Path, lm, case_path: str, head: dict, ds, n_pos: int, fidelity: str,
                     unconverged: list[str], timings: dict, paraview: str | None = None) -> dict:
    """The report's own plot (bearing pattern against diameter), its ISO comparisons and striping indices, and
    ``report.html``, all into ``stage`` beside the run's other plots; returns {"comparisons", "striping"} (for
    summary.json). ``ds`` is the run dataset (every torque), ``timings`` {stage: s} shown on the page."""
    from ..outputs import atomic_path
    from .derived import derived_geometry
    from .iso6336 import iso_comparisons
    from .pattern import plot_pattern_diameter, striping_index
    model = lm.model
    geometry = derived_geometry(model)
    plot_pattern_diameter(ds, geometry["active"], model.pinion.r_base, Path(stage) / "bearing_pattern_diameter.png",
                          model.case.name)
    comparisons = iso_comparisons(lm, ds, geometry["eps_alpha"])
    striping = {float(t): striping_index(ds.pressure.sel(torque=t).max(("position", "pinion_tooth")).values)
                for t in ds.torque.values}
    ctx = report_context(model.case, case_path, head, geometry, comparisons, striping, Path(stage), timings, n_pos,
                         fidelity, unconverged, paraview)
    with atomic_path(Path(stage) / "report.html") as tmp:
        Path(tmp).write_text(render_report(ctx), encoding="utf-8")
    return {"comparisons": comparisons, "striping": striping}
