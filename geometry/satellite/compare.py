"""Comparison of the satellite forming methods of Kapitonov et al. 2014 against the special hob (c), and its plot.

Profile deviation of a method from (c): at points of the (c) right-half outline (fillet, involute, tip
corner), the distance along the (c) outline normal to the other method's outline, in um, positive where
the other method leaves MORE metal than (c): the root of the signed distance ``f(d)`` of ``p + d n`` to the
other outline (:class:`ltca.geometry.outline.GearOutline`) nearest to d = 0 (``p`` a (c) point, ``n`` its
outward normal), bracketed on a grid and bisected; NaN where the normal line misses the other outline.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..outline import GearOutline
from .forming import FormedTooth, form_disk_cutter, form_hob_three_pass, form_special_hob
from .tools import DiskCutter, HobThreePass, SatelliteDesign, SpecialHob

__all__ = ["Deviation", "FormingComparison", "profile_deviation", "compare_forming", "plot_forming",
           "plunge_for_thickness"]


@dataclass(frozen=True)
class Deviation:
    """Deviation of one method from (c) along the (c) right half, root to tip.

    radius : (n,) mm.   roll_angle : (n,) rad of the (c) involute (NaN below the base circle).
    kind : (n,) int8 of the (c) point (1 fillet, 2 involute, 3 tip corner).   deviation_um : (n,) um.
    max_abs_um / max_abs_involute_um : over all points / over the (c) involute, um (NaN ignored).
    """

    radius: np.ndarray
    roll_angle: np.ndarray
    kind: np.ndarray
    deviation_um: np.ndarray
    max_abs_um: float
    max_abs_involute_um: float


@dataclass(frozen=True)
class FormingComparison:
    """The three methods and their deviations from (c): ``teeth`` by method name, ``deviations`` for (a), (b)."""

    design: SatelliteDesign
    teeth: dict
    deviations: dict
    plunge_for_eq3: float

    def table(self) -> list[dict]:
        """One row per method: thickness vs Eq. 3, tip land, pointed, dedendum, fillet radius, passes (mm)."""
        rows = []
        for name, t in self.teeth.items():
            dev = self.deviations.get(name)
            rows.append(dict(method=name, passes=t.passes, s_ref=t.s_ref, s_eq3=t.s_eq3,
                             s_minus_eq3_um=1e3 * (t.s_ref - t.s_eq3), tip_land=t.tip_land, r_tip=t.r_tip,
                             pointed=t.pointed, nearly_pointed=t.nearly_pointed, r_root=t.r_root,
                             dedendum=t.dedendum, root_fillet_radius=t.root_fillet_radius,
                             max_deviation_um=None if dev is None else dev.max_abs_um))
        return rows


def _normals(p: np.ndarray) -> np.ndarray:
    """Unit normals of the right-half polyline p (centre -> mid-gap), pointing out of the material."""
    t = np.gradient(p, axis=0)
    n = np.stack([-t[:, 1], t[:, 0]], axis=1)
    return n / np.linalg.norm(n, axis=1, keepdims=True)


def profile_deviation(ref: FormedTooth, other: FormedTooth, reach: float = 2.5, step: float = 0.1,
                      n_points: int = 400) -> Deviation:
    """Deviation (um) of ``other`` from ``ref`` along the ``ref`` outline normal, fillet to tip corner.

    The crossing of the normal line with the other outline nearest to the ``ref`` point is bracketed on a
    grid of ``step`` mm within ``+-reach`` mm and bisected to 0.1 nm; NaN where there is none. About
    ``n_points`` (c) points, fillet to tip corner.
    """
    pr = ref.profile
    sel = (pr.xy[:, 0] > 0) & (pr.kind > 0)
    corner = np.nonzero(sel & (pr.kind == 3))[0]
    sel &= (pr.kind != 3)
    if len(corner):
        sel[corner[-1]] = True
    idx = np.nonzero(sel)[0]
    idx = np.unique(np.append(idx[::max(1, len(idx) // n_points)], idx[-1]))
    p = pr.xy[idx]
    n = _normals(pr.xy)[idx]
    ol = GearOutline(other.profile)

    def f(d):
        return ol.query(p + d[:, None] * n).distance

    # bracket the crossing nearest to d = 0 on a coarse grid, then bisect
    grid = np.arange(-reach, reach + 1e-12, step)
    order = np.argsort(np.abs(grid[:-1] + 0.5 * step), kind="stable")
    F = np.stack([f(np.full(len(p), g)) for g in grid])                 # (ng, n)
    change = (np.sign(F[:-1]) != np.sign(F[1:]))[order]
    has = change.any(axis=0)
    j = order[np.argmax(change, axis=0)]
    lo, hi = grid[j], grid[j] + step
    flo = F[j, np.arange(len(p))]
    for _ in range(int(np.ceil(np.log2(step / 1e-7)))):
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        left = np.sign(fm) == np.sign(flo)
        lo, hi, flo = np.where(left, mid, lo), np.where(left, hi, mid), np.where(left, fm, flo)
    dev = np.where(has, 1e3 * 0.5 * (lo + hi), np.nan)
    R = np.hypot(*p.T)
    roll = np.where(R >= pr.r_base, np.sqrt(np.maximum(R ** 2 - pr.r_base ** 2, 0)) / pr.r_base, np.nan)
    kind = pr.kind[idx]
    inv = kind == 2
    return Deviation(radius=R, roll_angle=roll, kind=kind, deviation_um=dev,
                     max_abs_um=float(np.nanmax(np.abs(dev))) if np.isfinite(dev).any() else float("nan"),
                     max_abs_involute_um=float(np.nanmax(np.abs(dev[inv]))) if np.isfinite(dev[inv]).any()
                     else float("nan"))


def plunge_for_thickness(design: SatelliteDesign, s_target: float | None = None,
                         tool: DiskCutter = DiskCutter()) -> float:
    """Disk-cutter shift coefficient that gives the reference thickness ``s_target`` (default Eq. 3)."""
    s_target = design.eq3_thickness if s_target is None else s_target

    def f(xb):
        return form_disk_cutter(design, DiskCutter(xb, tool.n_teeth, tool.z_profile)).s_ref - s_target
    return float(brentq(f, -2.0, 0.0, xtol=1e-6))


def compare_forming(design: SatelliteDesign = SatelliteDesign(), hob: HobThreePass = HobThreePass(),
                    disk: DiskCutter = DiskCutter(), special: SpecialHob = SpecialHob()) -> FormingComparison:
    """Cut the satellite by (a), (b), (c) and measure (a) and (b) against (c)."""
    teeth = {"hob_three_pass": form_hob_three_pass(design, hob), "disk_cutter": form_disk_cutter(design, disk),
             "special_hob": form_special_hob(design, special)}
    ref = teeth["special_hob"]
    devs = {k: profile_deviation(ref, teeth[k]) for k in ("hob_three_pass", "disk_cutter")}
    return FormingComparison(design=design, teeth=teeth, deviations=devs,
                             plunge_for_eq3=plunge_for_thickness(design, tool=disk))


def plot_forming(cmp: FormingComparison, path) -> None:
    """PNG: the three teeth overlaid (top) and the deviations of (a), (b) from (c) against radius (bottom)."""
    from matplotlib.figure import Figure

    style = {"special_hob": ("k", "(c) special hob, 1 pass"), "hob_three_pass": ("C0", "(a) standard hob, 3 passes"),
             "disk_cutter": ("C3", "(b) disk cutter, x = %.2f" % cmp.teeth["disk_cutter"].tool.x_plunge)}
    fig = Figure(figsize=(7, 9))
    ax, bx = fig.subplots(2, 1, gridspec_kw={"height_ratios": [3, 2]})
    for name, t in cmp.teeth.items():
        c, lab = style[name]
        ax.plot(t.profile.xy[:, 0], t.profile.xy[:, 1], color=c, lw=1.2 if name == "special_hob" else 0.9,
                ls="-" if name != "hob_three_pass" else "--", label=lab)
    r = cmp.teeth["special_hob"].profile.r_ref
    a = np.linspace(-np.pi / cmp.design.z, np.pi / cmp.design.z, 50)
    ax.plot(r * np.sin(a), r * np.cos(a), color="0.6", lw=0.6, ls=":", label="reference circle")
    ax.set_aspect("equal")
    ax.set_xlabel("x, mm")
    ax.set_ylabel("y, mm")
    ax.legend(fontsize=8)
    ax.set_title("Satellite z = %d, m = %g mm, x = %g, thinning %.2f m" % (
        cmp.design.z, cmp.design.m, cmp.design.x, cmp.design.thinning))
    for name, dev in cmp.deviations.items():
        c, lab = style[name]
        bx.plot(dev.radius, dev.deviation_um, color=c, label=lab + " (max |%.1f| um)" % dev.max_abs_um)
    bx.axhline(0, color="k", lw=0.5)
    bx.set_xlabel("radius on (c), mm")
    bx.set_ylabel("deviation from (c) along its normal, um (+ more metal)")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
