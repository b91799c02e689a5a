"""The results store of a study: one netCDF file per (variant, torque) point, written atomically as it finishes,
combined into ``study.nc`` with dimensions variant, torque and position.

Layout under the output directory::

    points/<variant id>_T<torque>.nc   each point's position dataset (incl. the pressure lattice), written to a
                                       temporary name and renamed, so a file that exists is complete
    compliance/<geometry key>.pkl      each geometry's compliance, kept for reruns
    study.nc                           the combined store (no pressure lattice or edge pattern: their flank grid differs per point)

A rerun skips every point whose file exists. Imports ltca.study.spec only.
"""
from __future__ import annotations

import json
import os
import pickle
from pathlib import Path

import numpy as np
import xarray as xr

from ..outputs import write_netcdf_atomic
from .spec import Study, Variant

__all__ = ["StudyStore", "load_study", "SCALARS"]

#: per-point headline figures kept as (variant, torque) variables: summary key -> (variable, units); NaN where a
#: kind has none (a bevel pair has no ``max_pairs_in_contact``)
SCALARS = {"te_loaded_ptp_arcsec": ("te_loaded_ptp", "arcsec"), "te_unloaded_ptp_arcsec": ("te_unloaded_ptp", "arcsec"),
           "te_loaded_mean_arcsec": ("te_loaded_mean", "arcsec"), "max_contact_pressure_mpa": ("peak_pressure", "MPa"),
           "max_flank_pressure_mpa": ("peak_flank_pressure", "MPa"),
           "mesh_stiffness_mean_n_per_mm_um": ("mesh_stiffness_mean", "N/(mm um)"),
           "max_pairs_in_contact": ("max_pairs_in_contact", "1"), "converged": ("converged", "1")}


def _coord(values: list):
    """A coordinate array: numbers as float, anything else (tables, strings, mixtures) as JSON strings."""
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        return np.asarray(values, float)
    return np.asarray([v if isinstance(v, str) else json.dumps(v, sort_keys=True) for v in values], dtype=str)


class StudyStore:
    """The files of one study under ``root``."""

    def __init__(self, root: str | Path):
        self.root = Path(root)
        self.points = self.root / "points"
        self.compliance = self.root / "compliance"

    def clean(self) -> int:
        """Remove the temporary files a killed run left behind (never a finished point); their count."""
        stale = [p for d in (self.points, self.compliance) if d.is_dir() for p in d.glob(".*.tmp*")]
        for p in stale:
            p.unlink(missing_ok=True)
        return len(stale)

    def point_path(self, vid: str, torque_nm: float) -> Path:
        """The file of point (variant ``vid``, ``torque_nm``)."""
        return self.points / f"{vid}_T{torque_nm:.9g}.nc"

    def finished(self, vid: str, torque_nm: float) -> bool:
        """Whether that point is done (its file exists: it was written atomically)."""
        return self.point_path(vid, torque_nm).is_file()

    def write_point(self, ds: xr.Dataset, vid: str, torque_nm: float, head: dict) -> Path:
        """Write one point atomically (temporary name in the same directory, then rename)."""
        self.points.mkdir(parents=True, exist_ok=True)
        path = self.point_path(vid, torque_nm)
        ds = ds.copy()
        ds.attrs.update(variant_id=vid, summary=json.dumps(head))
        write_netcdf_atomic(path, ds)
        return path

    def compliance_path(self, key: str) -> Path:
        return self.compliance / f"{key}.pkl"

    def save_compliance(self, key: str, obj) -> None:
        """Keep a geometry's compliance for reruns (atomically)."""
        self.compliance.mkdir(parents=True, exist_ok=True)
        path = self.compliance_path(key)
        tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
        tmp.write_bytes(pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL))
        os.replace(tmp, path)

    def load_compliance(self, key: str):
        """A kept compliance, or None."""
        path = self.compliance_path(key)
        return pickle.loads(path.read_bytes()) if path.is_file() else None

    def combine(self, study: Study, variants: list[Variant]) -> xr.Dataset:
        """The whole study as one Dataset (variant x torque x position), written to ``study.nc`` atomically.

        Points not (yet) computed are NaN. Coordinates along variant: ``variant_id``, ``variant_name``, each
        varied key (by its dotted name), and for a Monte Carlo study ``sample`` and the drawn deviations."""
        rows = []
        for v in variants:
            per_t = []
            for t in study.torques:
                path = self.point_path(v.id, t)
                if path.is_file():
                    with xr.open_dataset(path, engine="h5netcdf") as d:
                        d = d.load()
                    head = json.loads(d.attrs["summary"])
                    d = d.drop_vars(["pressure", "edge_pattern", "flank_roll", "face"], errors="ignore")
                    d = d.assign({var: ((), float(head.get(k, np.nan)), {"units": u})
                                  for k, (var, u) in SCALARS.items()})
                    d = d.assign(max_root_stress_pinion=((), head["max_root_stress_mpa"]["pinion"], {"units": "MPa"}),
                                 max_root_stress_gear=((), head["max_root_stress_mpa"]["gear"], {"units": "MPa"}))
                    d.attrs = {}
                    per_t.append(d.expand_dims(torque=[t]))
            rows.append(per_t)
        template = next((p[0] for p in rows if p), None)
        if template is None:
            raise FileNotFoundError(f"{self.points}: no finished point of this study")
        blank = xr.full_like(template, np.nan).isel(torque=0, drop=True)
        full = []
        for per_t in rows:
            have = {float(p.torque[0]): p for p in per_t}
            full.append(xr.concat([have.get(t, blank.expand_dims(torque=[t])) for t in study.torques], "torque",
                                  join="outer", coords="minimal", compat="override"))
        ds = xr.concat(full, "variant", join="outer", coords="minimal", compat="override")
        coords = {"variant": np.arange(len(variants)), "variant_id": ("variant", [v.id for v in variants]),
                  "variant_name": ("variant", [v.name for v in variants])}
        for key in dict.fromkeys(k for v in variants for k in v.coords):
            coords[key] = ("variant", _coord([v.coords.get(key, np.nan) for v in variants]))
        for key in dict.fromkeys(k for v in variants for k in v.drawn):
            coords[f"drawn.{key}"] = ("variant", _coord([v.drawn.get(key, np.nan) for v in variants]))
        ds = ds.assign_coords(coords)
        ds["torque"].attrs.update(units="N m", long_name="pinion torque")
        ds.attrs.update(study=study.name, kind=study.kind, study_file=str(study.file),
                        varied_keys=json.dumps(study.varied_keys),
                        points_done=int(np.isfinite(ds.te_loaded_ptp.values).sum()),
                        points_total=len(variants) * len(study.torques))
        if study.monte_carlo is not None:
            mc = study.monte_carlo
            ds.attrs.update(monte_carlo=json.dumps({"grade": mc.grade, "samples": mc.samples, "seed": mc.seed,
                                                    "members": list(mc.members), "uniform": mc.uniform,
                                                    "normal": mc.normal}))
        path = self.root / "study.nc"
        write_netcdf_atomic(path, ds)
        return ds


def load_study(out: str | Path) -> xr.Dataset:
    """The combined store of a study run into ``out`` (``study.nc``), loaded into memory.

    Parameters
    ----------
    out : path
        The study's output directory.

    Returns
    -------
    xarray.Dataset
        Dimensions variant, torque, position (and pinion_tooth, gear_tooth).
    """
    with xr.open_dataset(Path(out) / "study.nc", engine="h5netcdf") as ds:
        return ds.load()
