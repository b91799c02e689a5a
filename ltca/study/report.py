"""Study outputs from the combined store: the summary table (CSV) and the plots.

- ``summary.csv``: one row per (variant, torque): id, name, varied keys, drawn deviations, headline figures.
- ``harris_map.png``: loaded TE peak-to-peak against torque, one line per variant (a Harris map of the
  modification variants), when the study has more than one torque.
- ``response_surface.png``: TE peak-to-peak over the first two varied axes with more than one value (the
  torque counts as an axis), at the first value of the others.
- ``mc_histograms.png`` and ``mc_cdf.png`` (Monte Carlo): histograms and empirical CDFs of the loaded TE
  peak-to-peak and of the peak flank pressure, with the 95th percentile marked, at each torque.
- ``mc_checks.json`` (Monte Carlo): the drawn deviations against the class's tolerances
  (:func:`ltca.study.montecarlo.check_draws`), the drawn case keys against their laws
  (:func:`ltca.study.montecarlo.check_key_draws`), and the mean and 95th percentile of each figure.

Imports ltca.case and ltca.study (spec, store, montecarlo).
"""
from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import xarray as xr

from ..case import parse_case
from ..outputs import write_json
from .montecarlo import check_draws, check_key_draws, member_tolerances
from .spec import Study
from .store import SCALARS

__all__ = ["write_outputs", "summary_rows", "mc_statistics"]


def _figures() -> list[str]:
    return [v for v, _ in SCALARS.values()] + ["max_root_stress_pinion", "max_root_stress_gear"]


def summary_rows(ds: xr.Dataset) -> list[dict]:
    """One dict per (variant, torque) of the store: coordinates along variant, torque, headline figures."""
    vcoords = [c for c in ds.coords if ds[c].dims == ("variant",)]
    rows = []
    for i in range(ds.sizes["variant"]):
        for j, t in enumerate(ds.torque.values):
            row = {c: ds[c].values[i].item() for c in vcoords}
            row["torque_nm"] = float(t)
            row.update({f: ds[f].values[i, j].item() for f in _figures()})
            rows.append(row)
    return rows


def mc_statistics(ds: xr.Dataset) -> dict:
    """Mean, standard deviation and 95th percentile of loaded TE peak-to-peak and peak pressure per torque."""
    out = {}
    for j, t in enumerate(ds.torque.values):
        rec = {}
        for var in ("te_loaded_ptp", "peak_pressure"):
            x = ds[var].values[:, j]
            x = x[np.isfinite(x)]
            if x.size:
                rec[var] = {"n": int(x.size), "mean": float(x.mean()), "std": float(x.std(ddof=1)) if x.size > 1
                            else 0.0, "p95": float(np.percentile(x, 95)), "min": float(x.min()),
                            "max": float(x.max())}
        out[f"{float(t):g}"] = rec
    return out


def _label(ds: xr.Dataset, i: int, keys: list[str]) -> str:
    parts = [str(ds.variant_name.values[i])] if len(set(ds.variant_name.values.tolist())) > 1 else []
    parts += [f"{k.split('.')[-1]}={ds[k].values[i]}" for k in keys if k in ds.coords]
    return ", ".join(parts) or str(ds.variant_id.values[i])


def _harris(ds: xr.Dataset, keys: list[str], path: Path, plt) -> None:
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for i in range(ds.sizes["variant"]):
        ax.plot(ds.torque.values, ds.te_loaded_ptp.values[i], "o-", label=_label(ds, i, keys))
    ax.set(xlabel="pinion torque [N m]", ylabel="loaded TE peak-to-peak [arcsec]", title=f"{ds.attrs['study']}: "
           "Harris map")
    ax.grid(alpha=0.3)
    if ds.sizes["variant"] <= 12:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _surface(ds: xr.Dataset, keys: list[str], path: Path, plt) -> bool:
    axes = [k for k in keys if k in ds.coords and ds[k].dtype.kind == "f" and len(np.unique(ds[k].values)) > 1]
    if ds.sizes["torque"] > 1:
        axes.append("torque")
    if len(axes) < 2:
        return False
    a, b = axes[:2]
    pick = np.ones(ds.sizes["variant"], bool)
    for k in keys:                                       # the other varied keys at their first value
        if k in ds.coords and k not in (a, b):
            pick &= ds[k].values == ds[k].values[0]
    sub = ds.isel(variant=np.flatnonzero(pick))
    if b == "torque":
        xs, ys = np.unique(sub[a].values), sub.torque.values
        Z = np.array([[float(sub.te_loaded_ptp.values[np.flatnonzero(sub[a].values == x)[0], j]) for x in xs]
                      for j in range(len(ys))])
    else:
        xs, ys = np.unique(sub[a].values), np.unique(sub[b].values)
        Z = np.full((len(ys), len(xs)), np.nan)
        for i in range(sub.sizes["variant"]):
            Z[np.searchsorted(ys, sub[b].values[i]), np.searchsorted(xs, sub[a].values[i])] = \
                sub.te_loaded_ptp.values[i, -1]
    fig, ax = plt.subplots(figsize=(6.5, 5))
    X, Y = np.meshgrid(xs, ys)
    if len(xs) > 1 and len(ys) > 1 and np.isfinite(Z).all():
        cs = ax.contourf(X, Y, Z, levels=12, cmap="viridis")
        fig.colorbar(cs, ax=ax, label="loaded TE peak-to-peak [arcsec]")
    sc = ax.scatter(X.ravel(), Y.ravel(), c=Z.ravel(), edgecolors="k", cmap="viridis")
    if not (len(xs) > 1 and len(ys) > 1):
        fig.colorbar(sc, ax=ax, label="loaded TE peak-to-peak [arcsec]")
    ax.set(xlabel=a, ylabel="pinion torque [N m]" if b == "torque" else b,
           title="response surface" + ("" if b == "torque" else f" at {float(ds.torque.values[-1]):g} N m"))
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return True


def _monte_carlo(ds: xr.Dataset, out: Path, plt) -> None:
    figs = {"te_loaded_ptp": "loaded TE peak-to-peak [arcsec]", "peak_pressure": "peak flank pressure [MPa]"}
    for name in ("mc_histograms.png", "mc_cdf.png"):
        fig, axs = plt.subplots(1, 2, figsize=(11, 4))
        for ax, (var, label) in zip(axs, figs.items()):
            for j, t in enumerate(ds.torque.values):
                x = np.sort(ds[var].values[:, j][np.isfinite(ds[var].values[:, j])])
                if not x.size:
                    continue
                p95 = np.percentile(x, 95)
                if name == "mc_histograms.png":
                    ax.hist(x, bins=max(5, int(np.sqrt(x.size))), alpha=0.6, label=f"{t:g} N m")
                else:
                    ax.step(x, np.arange(1, x.size + 1) / x.size, where="post", label=f"{t:g} N m")
                    ax.axhline(0.95, color="grey", lw=0.8)
                ax.axvline(p95, color="k", ls="--", lw=1)
                ax.annotate(f"P95 = {p95:.3g}", (p95, 0.5), xycoords=("data", "axes fraction"), rotation=90,
                            fontsize=8, ha="right")
            ax.set(xlabel=label, ylabel="samples" if name == "mc_histograms.png" else "cumulative fraction")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=8)
        fig.suptitle(f"{ds.attrs['study']}: {ds.sizes['variant']} samples")
        fig.tight_layout()
        fig.savefig(out / name, dpi=110)
        plt.close(fig)


def write_outputs(ds: xr.Dataset, out: Path, study: Study, plots: bool = True) -> None:
    """Write ``summary.csv``, the plots and (Monte Carlo) ``mc_checks.json`` into ``out``."""
    rows = summary_rows(ds)
    with open(out / "summary.csv.tmp", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    (out / "summary.csv.tmp").replace(out / "summary.csv")
    if study.monte_carlo is not None:
        mc = study.monte_carlo
        drawn = [v.drawn for v in study.expand()]
        checks = {}
        if mc.grade is not None:
            case = parse_case(study.base)
            tols = {m: member_tolerances(case, m, mc.grade) for m in mc.members}
            checks.update(tolerances_um={m: t.as_dict() for m, t in tols.items()},
                          deviations=check_draws(drawn, tols))
        if mc.uniform or mc.normal:
            checks["drawn_keys"] = check_key_draws(drawn, mc.uniform, mc.normal)
        write_json(out / "mc_checks.json", {**checks, "results": mc_statistics(ds)})
    if not plots:
        return
    from .. import figures as plt
    keys = json.loads(ds.attrs.get("varied_keys", "[]"))
    if ds.sizes["torque"] > 1:
        _harris(ds, keys, out / "harris_map.png", plt)
    _surface(ds, keys, out / "response_surface.png", plt)
    if study.monte_carlo is not None:
        _monte_carlo(ds, out, plt)
