"""``report.html`` of a bevel ``ltca run``: one self-contained page (no server, no script, no external file: the
plots are embedded as base64 PNG), rendered by Jinja2 from ``templates/report.html.j2``.

It holds the results per torque, our results beside the ISO 10300 Method B1 nominal contact and root stresses
(:mod:`ltca.bevel.iso10300`, every K factor 1) with the virtual cylindrical gears and factors behind them and
what in them is assumed, the plots, the warnings, the assembly errors, the inputs and the timings.
"""
from __future__ import annotations

import datetime as _dt
import math
from pathlib import Path

import numpy as np

from ..html_page import embedded_plots, render_page
from .iso10300 import Iso10300B1, VirtualGears, iso10300_b1, virtual_gears

__all__ = ["PLOTS", "iso_rows", "report_context", "render_report", "write_bevel_report"]

#: the plots of a bevel run in the order the page shows them, with their captions
PLOTS = (
    ("te.png", "Loaded and unloaded transmission error over the mesh cycle, per torque (arcsec of the gear; "
               "positive: the gear lags)."),
    ("bearing_pattern.png", "Bearing pattern: the largest pressure over the cycle on the gear flank in its axial "
                            "section, with the fitted loaded contact ellipses and the unloaded path of contact."),
    ("load_sharing.png", "Share of the gear torque carried by each tooth pair over the cycle, per torque."),
)

_SOURCE_H = "ISO 10300-2 Method B1, sigma_H0 (K = 1)"
_SOURCE_F = "ISO 10300-3 Method B1, sigma_F0 (K = 1)"


def _edge_radii(pair, torque_nm: float) -> tuple[float, float]:
    """Edge radius of the blades cutting the loaded flank's fillet of pinion and gear (mm)."""
    side = "concave" if torque_nm > 0 else "convex"
    other = "convex" if side == "concave" else "concave"
    return (float(pair.pinion.flank(side).cutter.edge_radius), float(pair.gear.flank(other).cutter.edge_radius))


def iso_rows(records: list[dict], figures: list[Iso10300B1]) -> list[dict]:
    """Our figures beside ISO 10300's, one row per quantity and torque (the ``iso10300`` list of summary.json)."""
    rows = []
    for r, iso in zip(records, figures):
        t = r["torque_nm"]
        pairs = (("peak flank pressure (interior) vs nominal contact stress", r["max_flank_pressure_mpa"],
                  iso.sigma_H0, _SOURCE_H),
                 ("pinion root stress, max over the cycle", r["max_root_stress_mpa"]["pinion"], iso.sigma_F0_pinion,
                  _SOURCE_F),
                 ("gear root stress, max over the cycle", r["max_root_stress_mpa"]["gear"], iso.sigma_F0_gear,
                  _SOURCE_F))
        for q, ours, ref, src in pairs:
            rows.append({"quantity": q, "torque_nm": float(t), "ours": float(ours), "reference": float(ref),
                         "unit": "MPa", "ratio": float(ours / ref) if ref else math.nan, "source": src})
    return rows


def _virtual_table(v) -> list[tuple[str, float, str]]:
    deg = math.degrees
    return [("mean pitch diameters d_m1 / d_m2", f"{v.d_m1:.3f} / {v.d_m2:.3f}", "mm"),
            ("mean normal module m_mn", f"{v.m_mn:.4f}", "mm"),
            ("virtual reference diameters d_v1 / d_v2", f"{v.d_v1:.3f} / {v.d_v2:.3f}", "mm"),
            ("virtual teeth z_v1 / z_v2 (transverse)", f"{v.z_v1:.3f} / {v.z_v2:.3f}", ""),
            ("virtual teeth z_vn1 / z_vn2 (normal section)", f"{v.z_vn1:.3f} / {v.z_vn2:.3f}", ""),
            ("transverse pressure angle alpha_vet", f"{deg(v.alpha_vet):.4f}", "deg"),
            ("base helix angle beta_vb", f"{deg(v.beta_vb):.4f}", "deg"),
            ("path of contact g_va", f"{v.g_va:.4f}", "mm"),
            ("transverse / face contact ratio eps_va / eps_vb", f"{v.eps_va:.4f} / {v.eps_vb:.4f}", ""),
            ("effective face width b_eff (assumed 0.85 b)", f"{v.b_eff:.3f}", "mm"),
            ("middle contact line l_bm", f"{v.l_bm:.4f}", "mm"),
            ("relative curvature radius rho_rel", f"{v.rho_rel:.4f}", "mm")]


def _factor_table(iso: Iso10300B1) -> list[tuple[str, str]]:
    p, g = iso.pinion, iso.gear
    return [("mid-zone factor Z_M-B", f"{iso.Z_MB:.4f}"), ("load sharing factor Z_LS (e_LS = "
                                                          f"{iso.e_ls:g})", f"{iso.Z_LS:.4f}"),
            ("elasticity factor Z_E [sqrt(MPa)]", f"{iso.Z_E:.2f}"),
            ("tooth form factors Y_Fa1 / Y_Fa2", f"{p.Y_Fa:.4f} / {g.Y_Fa:.4f}"),
            ("stress correction factors Y_Sa1 / Y_Sa2", f"{p.Y_Sa:.4f} / {g.Y_Sa:.4f}"),
            ("contact ratio factor Y_eps", f"{iso.Y_eps:.4f}"), ("bevel spiral angle factor Y_BS", f"{iso.Y_BS:.4f}"),
            ("load sharing factor Y_LS = Z_LS^2", f"{iso.Y_LS:.4f}"),
            ("profile shift / thickness coefficients x_hm1 / x_sm1", f"{p.x_hm:.4f} / {round(p.x_sm, 9) + 0.0:.4f}")]


def report_context(case, case_path: str, head: dict, virtual: VirtualGears | None, figures: list[Iso10300B1],
                   plots_dir: Path) -> dict:
    """Everything the template shows; ``head`` is the run's summary (``torques`` records, ``warnings``,
    ``iso10300`` rows), ``virtual`` the pair's virtual cylindrical gears, ``figures`` the ISO figures per
    torque."""
    records = head["torques"]
    try:
        text = Path(case_path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        text = "(not readable)"
    d = case.basic
    deg = np.degrees
    inputs = [("teeth z1 / z2", f"{d.z1} / {d.z2}"), ("outer transverse module", f"{d.module:g} mm"),
              ("face width", f"{d.face_width:g} mm"), ("mean spiral angle", f"{deg(d.spiral_angle):g} deg"),
              ("normal pressure angle", f"{deg(d.pressure_angle):g} deg"),
              ("shaft angle", f"{deg(d.shaft_angle):g} deg"), ("gear hand", d.hand),
              ("cutter radius", f"{d.cutter_radius:g} mm"),
              ("Young's modulus / Poisson ratio", f"{case.young:g} MPa / {case.poisson:g}"),
              ("pinion torque(s)", ", ".join(f"{r['torque_nm']:g}" for r in records) + " N m")]
    asm = head.get("assembly", {})
    return {"case_name": case.name, "fidelity": head.get("fidelity", ""), "positions": head.get("positions"),
            "torques": [f"{r['torque_nm']:g}" for r in records],
            "written": _dt.datetime.now().isoformat(timespec="seconds"), "command": f"ltca run {case_path}",
            "records": records, "iso": head.get("iso10300", []), "virtual": _virtual_table(virtual) if virtual else [],
            "factors": _factor_table(figures[0]) if figures else [],
            "plots": embedded_plots(plots_dir, PLOTS), "warnings": head.get("warnings", []), "assembly": asm,
            "max_residual": max(float(r.get("max_torque_residual", 0.0)) for r in records),
            "converged": all(r.get("converged", False) for r in records), "inputs": inputs,
            "case_path": str(case_path), "case_text": text,
            "timings": [(k, float(v)) for k, v in head.get("timings_s", {}).items()]}


def render_report(context: dict) -> str:
    """The page's HTML from :func:`report_context`'s dictionary (Jinja2, autoescaped)."""
    return render_page("ltca.bevel", context)


def write_bevel_report(stage: Path, case, pair, head: dict, case_path: str) -> list[dict]:
    """The ISO 10300 figures of every torque into ``head["iso10300"]`` and ``report.html`` into ``stage`` (beside
    the run's plots); returns the comparison rows."""
    from ..outputs import atomic_path
    records = head["torques"]
    try:
        figures = [iso10300_b1(pair.blank, r["torque_nm"], case.young, case.poisson,
                               _edge_radii(pair, r["torque_nm"])) for r in records]
        virtual = virtual_gears(pair.blank)
    except ValueError as exc:       # a pair outside the standard's formulae here: the report without them
        figures, virtual = [], None
        head.setdefault("warnings", []).append(f"ISO 10300 Method B1 not computed for this pair: {exc}")
    rows = iso_rows(records, figures)
    head["iso10300"] = rows
    head["iso10300_factors"] = {f"{f.torque_nm:g}": {k: v for k, v in f.as_dict().items()
                                                     if k not in ("pinion", "gear")} for f in figures}
    ctx = report_context(case, case_path, head, virtual, figures, Path(stage))
    with atomic_path(Path(stage) / "report.html") as tmp:
        Path(tmp).write_text(render_report(ctx), encoding="utf-8")
    return rows
