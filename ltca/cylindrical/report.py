"""Plots (PNG) and the ParaView file (VTU) of a cylindrical loaded analysis."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

__all__ = ["plot_all", "write_vtu"]


def _save(fig, path: Path) -> None:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_all(ds: xr.Dataset, out: Path, title: str) -> list[Path]:
    """TE, load sharing, bearing pattern and root stress plots; returns the files written."""
    out = Path(out)
    files = []
    roll = ds["roll"].values
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(roll, ds.te_loaded, "o-", label=f"loaded, {ds.attrs['torque_nm']:g} N m")
    ax.plot(roll, ds.te_unloaded, "s--", label="unloaded")
    ax.set(xlabel="pinion roll from the pitch point [deg]", ylabel="transmission error of the gear [arcsec]",
           title=f"{title}: transmission error")
    ax.grid(alpha=0.3)
    ax.legend()
    _save(fig, out / "te.png")
    files.append(out / "te.png")

    fig, ax = plt.subplots(figsize=(7, 4))
    total = ds.pair_load.sum("pinion_tooth")
    for k in ds.pinion_tooth.values:
        share = ds.pair_load.sel(pinion_tooth=k) / total
        if float(share.max()) > 0:
            ax.plot(roll, share, "o-", label=f"pinion tooth {k}")
    ax.set(xlabel="pinion roll from the pitch point [deg]", ylabel="load share [-]", ylim=(-0.02, 1.02),
           title=f"{title}: load sharing")
    ax.grid(alpha=0.3)
    ax.legend()
    _save(fig, out / "load_sharing.png")
    files.append(out / "load_sharing.png")

    pattern = ds.pressure.max(("position", "pinion_tooth"))
    fig, ax = plt.subplots(figsize=(7, 4))
    # the colour scale follows the flank pressure; edge contact (often a mesh-dependent spike) saturates it and
    # is marked
    top = float(ds.max_flank_pressure.max()) if "max_flank_pressure" in ds else float(pattern.max())
    m = ax.pcolormesh(ds.flank_roll, ds.face, pattern.T, shading="nearest", cmap="inferno", vmin=0.0,
                      vmax=top or None)
    fig.colorbar(m, ax=ax, label="max contact pressure [MPa] (scale: flank peak)",
                 extend="max" if float(pattern.max()) > top else "neither")
    if "edge_pattern" in ds and int(ds.edge_pattern.max()) > 0:
        styles = (("x", "cyan", 16), ("+", "lime", 22), ("v", "white", 10), (".", "deepskyblue", 5))
        for k, name in enumerate(ds.edge.values):
            i, j = np.nonzero(ds.edge_pattern.values & (1 << k))
            if len(i):
                mk, col, size = styles[k % len(styles)]
                ax.scatter(ds.flank_roll.values[i], ds.face.values[j], s=size, marker=mk, color=col, linewidths=0.8,
                           label=f"edge contact: {name}")
        ax.legend(loc="upper left", fontsize=7, framealpha=0.8)
    ax.set(xlabel="pinion involute roll angle [deg] (root -> tip)", ylabel="face width position [mm]",
           title=f"{title}: bearing pattern (pinion flank)")
    _save(fig, out / "bearing_pattern.png")
    files.append(out / "bearing_pattern.png")

    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(roll, ds.root_stress_pinion.max("pinion_tooth"), "o-", label="pinion (max over teeth)")
    ax.plot(roll, ds.root_stress_gear.max("gear_tooth"), "s-", label="gear (max over teeth)")
    ax.set(xlabel="pinion roll from the pitch point [deg]", ylabel="max principal fillet stress [MPa]",
           title=f"{title}: root stress")
    ax.grid(alpha=0.3)
    ax.legend()
    _save(fig, out / "root_stress.png")
    files.append(out / "root_stress.png")
    return files


def write_vtu(path: Path, body, grid_force: np.ndarray, frame: np.ndarray) -> None:
    """One body's mesh with the displacement of a loaded position, in the world frame, as VTU.

    ``grid_force`` (n_grid,) are the cell forces gathered on the body's compliance grid; the load is
    re-applied to the factorised model once (patch loads), so the field is the FE solution itself."""
    import meshio
    u = body.factorization.solve(body.patch @ grid_force).reshape(-1, 3)
    R, t = frame[:3, :3], frame[:3, 3]
    pts = body.mesh.nodes @ R.T + t
    meshio.write(str(path), meshio.Mesh(pts, [("tetra10", body.mesh.tets)],
                                        point_data={"displacement_mm": u @ R.T,
                                                    "displacement_magnitude_um": 1e3 * np.linalg.norm(u, axis=1)}))
