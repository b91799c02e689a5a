"""Plots (PNG) and the ParaView file (VTU) of a cylindrical loaded analysis."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from .. import figures as plt

__all__ = ["plot_all", "plot_data", "write_vtu"]


def _save(fig, path: Path) -> None:
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _by_torque(ds: xr.Dataset) -> xr.Dataset:
    return ds if "torque" in ds.dims else ds.expand_dims(torque=[float(ds.attrs.get("torque_nm", np.nan))])


def plot_data(ds: xr.Dataset) -> dict:
    """What each PNG shows, per torque (the run dataset of :func:`ltca.cylindrical.sweep.run_dataset`; a single
    torque's position dataset is taken as one torque): the data :func:`plot_all` draws, so that tests check it.

    Keys: ``te`` {torque: (roll deg, loaded TE arcsec, loaded TE um)} and ``te_unloaded`` (roll, arcsec, um);
    ``te_ptp`` (torques, ptp arcsec, ptp um); ``load_sharing`` {torque: {pinion tooth: (roll, share)}};
    ``bearing_pattern`` {torque: (flank roll deg, face mm, pressure (profile, face) MPa)} with ``pressure_range``
    (the shared colour scale: the largest flank pressure, edge contact excluded) and ``edge_marks`` {torque: {edge:
    (profile indices, face indices)}} of edge contact; ``root_stress`` {torque: (roll, pinion MPa, gear MPa)};
    ``harmonics`` {torque: (mesh orders, amplitude arcsec)}."""
    ds = _by_torque(ds)
    torques = [float(t) for t in ds.torque.values]
    roll = ds["position"].values
    out: dict = {"torques": torques, "te": {}, "load_sharing": {}, "bearing_pattern": {}, "root_stress": {},
                 "harmonics": {}}
    for t in torques:
        d = ds.sel(torque=t)
        um = d.te_loaded_um.values if "te_loaded_um" in d else np.full(roll.shape, np.nan)
        out["te"][t] = (roll, d.te_loaded.values, um)
        total = d.pair_load.sum("pinion_tooth").values
        shares = {}
        for k in d.pinion_tooth.values:
            share = np.divide(d.pair_load.sel(pinion_tooth=k).values, total, out=np.zeros_like(total),
                              where=total > 0)
            if share.max() > 0:
                shares[int(k)] = (roll, share)
        out["load_sharing"][t] = shares
        pattern = d.pressure.max(("position", "pinion_tooth")).values
        out["bearing_pattern"][t] = (ds.flank_roll.values, ds.face.values, pattern)
        out["root_stress"][t] = (roll, d.root_stress_pinion.max("pinion_tooth").values,
                                 d.root_stress_gear.max("gear_tooth").values)
        if "te_mesh_harmonic" in d:
            out["harmonics"][t] = (ds.mesh_order.values, d.te_mesh_harmonic.values)
    d0 = ds.isel(torque=0)
    out["te_unloaded"] = (roll, d0.te_unloaded.values,
                          d0.te_unloaded_um.values if "te_unloaded_um" in d0 else np.full(roll.shape, np.nan))
    out["te_ptp"] = (np.array(torques), np.array([np.ptp(out["te"][t][1]) for t in torques]),
                     np.array([np.ptp(out["te"][t][2]) for t in torques]))
    # the shared colour scale follows the flank pressure (edge contact excluded), when the run has it
    top = (float(ds.max_flank_pressure.max()) if "max_flank_pressure" in ds else
           max(float(np.nanmax(p[2])) for p in out["bearing_pattern"].values()))
    out["pressure_range"] = (0.0, top or 1.0)
    out["edge_names"] = [str(e) for e in ds.edge.values] if "edge" in ds.coords else []
    out["edge_marks"] = {}
    if "edge_pattern" in ds:
        for t in torques:
            bits = ds.edge_pattern.sel(torque=t).values.astype(int)
            out["edge_marks"][t] = {name: np.nonzero(bits & (1 << k)) for k, name in enumerate(out["edge_names"])
                                    if np.any(bits & (1 << k))}
    return out


def _grid(n: int, width: float = 5.2, height: float = 3.6):
    cols = min(n, 3)
    rows = -(-n // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(width * cols, height * rows), squeeze=False)
    for ax in axes.flat[n:]:
        ax.set_visible(False)
    return fig, list(axes.flat[:n])


def plot_all(ds: xr.Dataset, out: Path, title: str) -> list[Path]:
    """TE (arcsec and um on the line of action, one line per torque), TE peak-to-peak against torque, TE
    harmonics, load sharing and bearing pattern per torque (one colour scale), root stress; returns the files."""
    out = Path(out)
    data = plot_data(ds)
    torques = data["torques"]
    colours = plt.cm.viridis(np.linspace(0.0, 0.85, max(len(torques), 1)))
    files = []
    x_roll = "pinion roll from the pitch point [deg]"

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4))
    for c, t in zip(colours, torques):
        x, y, um = data["te"][t]
        a1.plot(x, y, "o-", ms=3, color=c, label=f"loaded, {t:g} N m")
        a2.plot(x, um, "o-", ms=3, color=c, label=f"loaded, {t:g} N m")
    x, y, um = data["te_unloaded"]
    a1.plot(x, y, "k--", label="unloaded")
    a2.plot(x, um, "k--", label="unloaded")
    a1.set(xlabel=x_roll, ylabel="transmission error of the gear [arcsec]", title=f"{title}: TE")
    a2.set(xlabel=x_roll, ylabel="transmission error on the line of action [um]", title=f"{title}: TE")
    for a in (a1, a2):
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    _save(fig, out / "te.png")
    files.append(out / "te.png")

    fig, a1 = plt.subplots(figsize=(6, 4))
    tq, ptp, ptp_um = data["te_ptp"]
    order = np.argsort(tq)
    a1.plot(tq[order], ptp[order], "o-", color="C0")
    a1.set(xlabel="pinion torque [N m]", ylabel="loaded TE peak-to-peak [arcsec]", title=f"{title}: TE against torque")
    a1.grid(alpha=0.3)
    a2 = a1.twinx()
    a2.plot(tq[order], ptp_um[order], "s--", color="C1")
    a2.set_ylabel("loaded TE peak-to-peak on the line of action [um]", color="C1")
    _save(fig, out / "te_ptp.png")
    files.append(out / "te_ptp.png")

    if data["harmonics"]:
        fig, ax = plt.subplots(figsize=(7, 4))
        w = 0.8 / len(torques)
        for i, (c, t) in enumerate(zip(colours, torques)):
            orders, amp = data["harmonics"][t]
            ax.bar(orders + (i - (len(torques) - 1) / 2) * w, np.nan_to_num(amp), w, color=c, label=f"{t:g} N m")
        ax.set(xlabel="mesh order", ylabel="loaded TE amplitude [arcsec]", title=f"{title}: TE harmonics "
               "(orders not resolved by the positions left empty)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3, axis="y")
        _save(fig, out / "te_harmonics.png")
        files.append(out / "te_harmonics.png")

    fig, axes = _grid(len(torques))
    for ax, t in zip(axes, torques):
        for k, (x, share) in data["load_sharing"][t].items():
            ax.plot(x, share, "o-", ms=3, label=f"pinion tooth {k}")
        ax.set(xlabel=x_roll, ylabel="load share [-]", ylim=(-0.02, 1.02), title=f"{title}: load sharing, {t:g} N m")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    _save(fig, out / "load_sharing.png")
    files.append(out / "load_sharing.png")

    vmin, vmax = data["pressure_range"]
    fig, axes = _grid(len(torques))
    m = None
    styles = (("x", "cyan", 16), ("+", "lime", 22), ("v", "white", 10), (".", "deepskyblue", 5))
    over = False
    for ax, t in zip(axes, torques):
        x, z, p = data["bearing_pattern"][t]
        over |= bool(np.nanmax(p) > vmax)
        m = ax.pcolormesh(x, z, p.T, shading="nearest", cmap="inferno", vmin=vmin, vmax=vmax)
        # edge contact (often a mesh-dependent spike) saturates the flank-pressure scale and is marked
        for name, (i, j) in data["edge_marks"].get(t, {}).items():
            mk, col, size = styles[list(data["edge_names"]).index(name) % len(styles)]
            ax.scatter(x[i], z[j], s=size, marker=mk, color=col, linewidths=0.8, label=f"edge contact: {name}")
        if data["edge_marks"].get(t):
            ax.legend(loc="upper left", fontsize=7, framealpha=0.8)
        ax.set(xlabel="pinion involute roll angle [deg] (root -> tip)", ylabel="face width position [mm]",
               title=f"{title}: bearing pattern, {t:g} N m")
    fig.tight_layout()
    fig.colorbar(m, ax=axes, label="contact pressure [MPa], scale: flank peak of all torques",
                 extend="max" if over else "neither")
    fig.savefig(out / "bearing_pattern.png", dpi=110)
    plt.close(fig)
    files.append(out / "bearing_pattern.png")

    fig, ax = plt.subplots(figsize=(7, 4))
    for c, t in zip(colours, torques):
        x, sp, sg = data["root_stress"][t]
        ax.plot(x, sp, "o-", ms=3, color=c, label=f"pinion, {t:g} N m")
        ax.plot(x, sg, "s--", ms=3, color=c, label=f"gear, {t:g} N m")
    ax.set(xlabel=x_roll, ylabel="max principal fillet stress [MPa]", title=f"{title}: root stress (max over teeth)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    _save(fig, out / "root_stress.png")
    files.append(out / "root_stress.png")
    return files


def write_vtu(path: Path, body, grid_force: np.ndarray, frame: np.ndarray) -> None:
    """One body's mesh with the displacement of a loaded position, in the world frame, as VTU.

    ``grid_force`` (n_grid,) are the cell forces gathered on the body's compliance grid; the load is
    re-applied to the factorised model once (patch loads), so the field is the FE solution itself."""
    import meshio

    from ..vtu import write_vtu_file
    u = body.factorization.solve(body.patch @ grid_force).reshape(-1, 3)
    R, t = frame[:3, :3], frame[:3, 3]
    pts = body.mesh.nodes @ R.T + t
    write_vtu_file(path, meshio.Mesh(pts, [("tetra10", body.mesh.tets)],
                                     point_data={"displacement_mm": u @ R.T,
                                                 "displacement_magnitude_um": 1e3 * np.linalg.norm(u, axis=1)}))
