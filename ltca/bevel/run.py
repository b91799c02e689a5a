"""Spiral bevel ``ltca tca``: synthesise the pinion of a case (Cao et al. 2008, case read by :mod:`ltca.bevel.case`),
run the TCA, print a Gleason-style settings summary and write summary.json and plots; the stage benchmark.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ltca.geometry.bevel.design import cycle_metrics, synthesize_pinion
from ltca.geometry.bevel.generation import MeshingError, generate_member, standard_gear_cut, surface_state
from ltca.geometry.bevel.machine import MemberCut
from ltca.geometry.bevel.separation import separation_tca
from ltca.geometry.bevel.sheet import member_sheet, sheet_toml
from ltca.geometry.bevel.tca import RAD_PER_ARCSEC, Assembly, BevelPair, ContactError, tca, to_pitch_coords
from ltca.geometry.bevel.undercut import undercut_check

from .analysis import synthesis_error
from .case import case_blank, load_bevel_case

__all__ = ["run_bevel_tca", "plot_bevel", "bevel_benchmark", "settings_sheet_toml"]


def _settings(cut: MemberCut) -> dict:
    out = {}
    for side in ("concave", "convex"):
        fc = cut.flank(side)
        m, c = fc.machine, fc.cutter
        out[side] = dict(blade=c.blade, point_radius_mm=c.point_radius, blade_angle_deg=np.rad2deg(c.blade_angle),
                         edge_radius_mm=c.edge_radius, radial_setting_mm=m.radial_setting,
                         cradle_angle_deg=np.rad2deg(m.cradle_angle), machine_root_angle_deg=np.rad2deg(m.root_angle),
                         machine_center_to_back_mm=m.center_to_back, blank_offset_mm=m.blank_offset,
                         sliding_base_mm=m.sliding_base, ratio_of_roll=m.ratio_of_roll,
                         modified_roll_C=m.modified_roll_c, modified_roll_D=m.modified_roll_d)
    return {s: {k: (float(v) if not isinstance(v, str) else v) for k, v in d.items()} for s, d in out.items()}


def settings_sheet_toml(pair: BevelPair) -> str:
    """The pair's complete settings sheets as ``[bevel.settings.<member>.<flank>]`` TOML tables: with the case's
    basic data (and no targets) they read back as a case that cuts the same pair."""
    return ("# settings sheets of both members (geometry.bevel.sheet): put under the case's [bevel] table, with\n"
            "# [bevel.working] and [bevel.coast] removed, to cut this pair as given\n"
            + sheet_toml({"gear": member_sheet(pair.gear), "pinion": member_sheet(pair.pinion)}))


def _print_summary(name: str, settings: dict, flanks: dict) -> None:
    keys = list(settings["gear"]["concave"])
    print(f"Spiral bevel summary: {name}")
    print(f"{'setting':28s}" + "".join(f"{m + ' ' + s:>16s}" for m in ("gear", "pinion") for s in ("concave", "convex")))
    for k in keys:
        vals = [settings[m][s][k] for m in ("gear", "pinion") for s in ("concave", "convex")]
        print(f"{k:28s}" + "".join(f"{v:>16s}" if isinstance(v, str) else f"{v:16.5f}" for v in vals))
    for fl, d in flanks.items():
        print(f"{fl:8s} flank: path {d['path_angle_deg']:7.2f} deg, TE {d['te_amplitude_arcsec']:6.2f} arcsec "
              f"(R^2 {d['te_r2']:.5f}), straightness {d['path_straightness_mm']:.3f} mm, contact ratio "
              f"{d['contact_ratio']:.2f}, ellipse {d['ellipse_major_mm']:.2f} mm")


def run_bevel_tca(case_path: str, out: str | None = None) -> dict:
    """Synthesise the pinion of a bevel case, run the TCA of both flanks, print and return the summary.

    Parameters
    ----------
    case_path : str
        TOML case with a [bevel] table (see cases/spiral_bevel_cao2008.toml).
    out : str, optional
        Directory for ``summary.json`` (created if needed).

    Returns
    -------
    dict
        ``case``, ``flanks`` ({"working", "coast"}: path_angle_deg, te_amplitude_arcsec, te_r2, contact_ratio,
        path_straightness_mm, ellipse_major_mm, targets), ``machine_settings`` ({"gear", "pinion"} x side),
        ``design`` (first design before the blank-offset redesign, per flank).
    """
    case = load_bevel_case(case_path)
    summary, pair, runs = bevel_tca_summary(case, str(case_path))
    _print_summary(case.name, summary["machine_settings"], summary["flanks"])
    if out is not None:
        d = Path(out)
        d.mkdir(parents=True, exist_ok=True)
        summary["plots"] = plot_bevel(pair, runs, d, case.name)
        from ..outputs import write_json_atomic
        write_json_atomic(d / "summary.json", summary)
        (d / "settings_sheet.toml").write_text(settings_sheet_toml(pair))
    return summary


def bevel_tca_summary(case, file: str | None = None) -> tuple[dict, BevelPair, dict]:
    """The pinion synthesised (or the pair cut as the case's settings sheets give it) and the TCA of both flanks
    as mounted: (summary, pair, {"working"|"coast": (TCAResult, SeparationResult)}). Writes and prints nothing.

    Raises DesignError (exit 2, naming the inputs) when the design has no solution in the cradle model."""
    try:
        return _tca(case)
    except (ContactError, MeshingError, ValueError) as exc:
        raise synthesis_error(case, exc, file) from None


def _tca(case) -> tuple[dict, BevelPair, dict]:
    bl = case_blank(case)
    if case.cuts:
        gear, pin, infos = case.cuts["gear"], case.cuts["pinion"], None
    else:
        gear = standard_gear_cut(bl)
        pin, infos = synthesize_pinion(bl, gear, case.targets, blank_offset=case.blank_offset)
    pair = BevelPair(bl, gear, pin)
    asm = Assembly(**case.assembly)          # [assembly] E, P, G, sigma: the TCA of the pair as mounted
    flanks, design, runs = {}, {}, {}
    for label, side in (("working", "concave"), ("coast", "convex")):
        r = tca(pair, side, asm, steps_per_cycle=16, max_cycles=3.0)
        sep = separation_tca(pair, side, asm, steps_per_cycle=16, cycles=3.0)
        runs[label] = (r, sep)
        m = cycle_metrics(r, bl)
        tg = case.targets.get(side)
        if tg is not None:
            m["targets"] = dict(path_angle_deg=float(np.rad2deg(tg.eta2)),
                                te_magnitude_arcsec=tg.te_magnitude / RAD_PER_ARCSEC, ellipse_major_mm=tg.major_axis)
        m["separation_te_range_arcsec"] = float(np.ptp(sep.te_arcsec))
        m["separation_vs_continuous_te_arcsec"] = float(np.max(np.abs(sep.te - np.interp(sep.phi1, r.phi1_3,
                                                                                          r.te_3))) / RAD_PER_ARCSEC)
        m["ease_off_max_um"] = float(np.nanmax(sep.ease_off) * 1e3)
        flanks[label] = m
        if infos is not None:
            d = infos[side]["design"]
            design[label] = dict(blank_offset_mm=d["blank_offset"], C=d["C"], D=d["D"], metrics=d["metrics"])
    settings = dict(gear=_settings(gear), pinion=_settings(pin))
    undercut = {m: {s: undercut_check(c.flank(s), bl, m).message for s in ("concave", "convex")}
                for m, c in (("gear", gear), ("pinion", pin))}
    summary = dict(case=case.name, flanks=flanks, machine_settings=settings, design=design, undercut=undercut,
                   assembly=dict(E_mm=asm.E, P_mm=asm.P, G_mm=asm.G, sigma_deg=float(np.rad2deg(asm.d_sigma))))
    return summary, pair, runs


def _ellipses(pair: BevelPair, r) -> list[np.ndarray]:
    """Contact ellipses of a continuous TCA projected into the gear axial section: list of (2, 64) (L, Rn)."""
    st = surface_state(pair.gear.flank(r.gear_side), r.params[:, 3], r.params[:, 4], r.params[:, 5])
    e1 = r.major_dir
    e2 = np.cross(st.n_w, e1)
    t = np.linspace(0, 2 * np.pi, 64)
    out = []
    for k in range(len(r.phi1)):
        a = 0.5 * min(r.major[k], 4 * pair.blank.data.face_width)
        pts = r.r2[k] + np.outer(a * np.cos(t), e1[k]) + np.outer(0.5 * r.minor[k] * np.sin(t), e2[k])
        out.append(np.array(to_pitch_coords(pts, pair.blank.gear.pitch_angle)))
    return out


def plot_bevel(pair: BevelPair, runs: dict, out: Path, title: str) -> list[str]:
    """Bearing pattern on the gear flank (axial section), TE over three cycles, pinion ease-off; PNG files.

    ``runs``: {"working"|"coast": (TCAResult, SeparationResult)}.  Returns the file names written.
    """
    from .. import figures as plt
    bl = pair.blank
    A0, Ai = bl.outer_cone_distance, bl.inner_cone_distance
    Lb = np.array([Ai, A0])
    root, face = bl.cones("gear", Lb)
    files = []
    from matplotlib.patches import Polygon
    box = np.array([[Ai, root[0]], [A0, root[1]], [A0, face[1]], [Ai, face[0]]])
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.4))
    for ax, (label, (r, sep)) in zip(axes, runs.items()):
        clip = Polygon(box, closed=True, fill=False, ec="k", lw=1.4, transform=ax.transData)
        ax.add_patch(clip)
        ax.text(Ai + 0.5, face[0] + 0.3, "toe", fontsize=8)
        ax.text(A0 - 2.5, face[1] + 0.3, "heel", fontsize=8)
        zone = sep.gear_zone()[np.abs(sep.phi1) <= 0.5 * sep.cycle + 1e-12].any(0)
        Rn = sep.gear.meta["Rn"]
        Lg = np.broadcast_to(sep.gear.v, Rn.shape)
        ax.contourf(Lg, Rn, zone.astype(float), levels=[0.5, 1.5], colors=["#9ecae1"], alpha=0.6)
        for E in _ellipses(pair, r)[::2]:
            ax.plot(E[0], E[1], color="tab:blue", lw=0.7)[0].set_clip_path(clip)
        ax.plot(r.gear_L, r.gear_Rn, "r-", lw=1.5, label="path of contact")
        i0 = int(np.argmin(np.abs(r.phi1)))
        ax.plot(r.gear_L[i0], r.gear_Rn[i0], "ko", ms=4, label="mean point M0")
        ax.set_title(f"{label}: gear {r.gear_side} flank, pinion {r.pinion_side}")
        ax.set_xlabel("cone distance L [mm] (toe left, heel right)")
        ax.set_aspect("equal")
        ax.set_xlim(Ai - 2, A0 + 2)
        ax.set_ylim(min(root) - 1, max(face) + 1.5)
        ax.legend(loc="lower right", fontsize=8)
        ax.set_ylabel("height over pitch cone Rn [mm]")
    fig.suptitle(f"{title}: bearing pattern on the gear, axial section (ellipses for {runs['working'][1].delta} mm "
                 f"approach; shaded: separation field < {runs['working'][1].delta} mm)", fontsize=10)
    fig.tight_layout()
    fig.savefig(out / "bearing_pattern.png", dpi=130)
    plt.close(fig)
    files.append("bearing_pattern.png")
    fig, ax = plt.subplots(figsize=(8, 4))
    for (label, (r, sep)), c in zip(runs.items(), ("tab:blue", "tab:orange")):
        cyc = 1.0 / sep.cycle
        ax.plot(r.phi1_3 * cyc, r.te_3 / RAD_PER_ARCSEC, "-", color=c, lw=1.8, label=f"{label}: continuous TCA")
        ax.plot(sep.phi1 * cyc, sep.te_arcsec, "o", color=c, ms=3, mfc="none", label=f"{label}: separation field")
    for x in (-1.5, -0.5, 0.5, 1.5):
        ax.axvline(x, color="0.7", lw=0.6, ls=":")
    ax.set_xlabel("pinion rotation [mesh cycles 2 pi / z1]")
    ax.set_ylabel("transmission error of the gear [arcsec]")
    ax.set_title(f"{title}: unloaded TE over three cycles (negative = gear lags)", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "transmission_error.png", dpi=130)
    plt.close(fig)
    files.append("transmission_error.png")
    fig = plt.figure(figsize=(12, 5))
    for k, (label, (r, sep)) in enumerate(runs.items()):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        fl = sep.pinion
        L = np.broadcast_to(fl.v, fl.meta["Rn"].shape)
        e = np.where(np.isfinite(sep.ease_off), sep.ease_off * 1e3, np.nan)
        ax.plot_wireframe(L, fl.meta["Rn"], e, color="tab:blue", lw=0.6)
        ax.plot_surface(L, fl.meta["Rn"], e, cmap="viridis", alpha=0.5, lw=0)
        ax.set_xlabel("L [mm] (toe - heel)")
        ax.set_ylabel("Rn [mm] (root - top)")
        ax.set_zlabel("ease-off [um]")
        ax.set_title(f"{label}: pinion {r.pinion_side} flank", fontsize=9)
        ax.view_init(elev=28, azim=-125)
    fig.suptitle(f"{title}: pinion ease-off (normal deviation from the conjugate of the gear, zero at contact)",
                 fontsize=10)
    fig.savefig(out / "ease_off.png", dpi=130)
    plt.close(fig)
    files.append("ease_off.png")
    return files


def bevel_benchmark(repeat: int = 3, case_path: str | None = None) -> dict:
    """Median wall times (s) of the spiral bevel stages on ``cases/spiral_bevel_cao2008.toml``; printed.

    ``generation``: both members, both flanks, 20 x 30 grids (depth x face); ``tca``: continuous-tangency TCA
    of one flank pair over three cycles (16 steps per cycle); ``separation``: separation-field TCA of one
    flank pair over three cycles (20 x 30 grids, off-grid refinement); ``synthesis``: both pinion flanks,
    control-point design and blank-offset redesign.
    """
    import time

    from ltca.geometry.bevel.generation import generate_flank
    if not (isinstance(repeat, int) and repeat >= 1):
        raise ValueError(f"repeat = {repeat!r} is outside the allowed range [1, inf)")
    from ..shipped import case_path as shipped_case
    path = str(shipped_case(case_path or "spiral_bevel_cao2008"))
    case = load_bevel_case(path)
    bl = case_blank(case)
    gear = standard_gear_cut(bl)
    times: dict[str, list] = {k: [] for k in ("generation", "tca", "separation", "synthesis")}
    pin = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        pin, _ = synthesize_pinion(bl, gear, case.targets, blank_offset=case.blank_offset)
        times["synthesis"].append(time.perf_counter() - t0)
    pair = BevelPair(bl, gear, pin)
    clearance = bl.pinion.dedendum - bl.gear.addendum
    for _ in range(repeat):
        t0 = time.perf_counter()
        generate_member(gear, bl, nu=20, nv=30)
        for s in ("concave", "convex"):       # the pinion from half the clearance above its root cone
            generate_flank(pin.flank(s), bl, "pinion", 20, 30, root_offset=0.5 * clearance)
        times["generation"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        tca(pair, "concave", steps_per_cycle=16, max_cycles=3.0)
        times["tca"].append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        separation_tca(pair, "concave", steps_per_cycle=16, cycles=3.0)
        times["separation"].append(time.perf_counter() - t0)
    med = {k: float(np.median(v)) for k, v in times.items()}
    print(f"spiral bevel benchmark (median of {repeat}): " + ", ".join(f"{k} {v:.2f} s" for k, v in med.items()))
    return med
