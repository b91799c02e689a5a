"""The ParaView time series of a loaded run, for every gear kind: one ``paraview.pvd`` with a step per mesh position.

A kind feeds the writer its parts per position (:func:`write_series`); this module builds the parts' meshes:

- :class:`BodyPart`: an FE body (P2 tets, or the part of it near the loaded teeth) with the point field
  ``displacement_mm`` (and its magnitude in um) and the cell fields ``von_mises_mpa`` and
  ``principal_stress_mpa`` (sigma_1 >= sigma_2 >= sigma_3, at the tet centroid): the load of the position's
  contact cells is put back on the factorised model as patch loads, so the fields are the FE solution itself
  (without the half-space near field of the contact);
- :func:`flank_mesh`: the loaded flanks as a quad surface with the cell field ``contact_pressure_mpa`` (the kind
  bins its contact cells on the surface's lattice, the largest cell pressure in each bin, so the surface's peak is
  the solver's peak at that position).

Files: ``paraview.pvd`` and ``paraview_<part>_<step>.vtu`` beside it (meshio, zlib-compressed, float32 fields;
:mod:`ltca.vtu`), every part in the world frame of its position.
"""
from __future__ import annotations

import logging
import time
from pathlib import Path
from typing import Iterable, Sequence
from xml.sax.saxutils import quoteattr

import numpy as np

from ltca.fem.readout import element_stress_matrix

from .vtu import write_vtu_file

__all__ = ["select_steps", "stress_fields", "BodyPart", "flank_mesh", "write_series"]

log = logging.getLogger(__name__)


def select_steps(position: np.ndarray, steps: int | None, centre: float = 0.0) -> np.ndarray:
    """Indices of the positions written: all when ``steps`` is None or not fewer than the positions, else
    ``steps`` spread evenly, always with the position nearest ``centre`` (the pitch point of a cylindrical
    pair, the mean point of a bevel pair)."""
    n = len(position)
    if steps is None or steps >= n:
        return np.arange(n)
    pick = set(np.round(np.linspace(0, n - 1, max(steps, 1))).astype(int).tolist())
    pick.add(int(np.argmin(np.abs(np.asarray(position) - centre))))
    return np.array(sorted(pick))


def stress_fields(sigma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Von Mises stress (n,) and principal stresses (n, 3), descending, of Voigt stresses (n, 6) (xx, yy, zz, yz,
    xz, xy), MPa."""
    xx, yy, zz, yz, xz, xy = sigma.T
    vm = np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3 * (yz ** 2 + xz ** 2 + xy ** 2))
    T = np.stack([np.stack([xx, xy, xz], -1), np.stack([xy, yy, yz], -1), np.stack([xz, yz, zz], -1)], -2)
    return vm, np.linalg.eigvalsh(T)[:, ::-1]


def _frame(frame: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    frame = np.asarray(frame, float)
    return frame[:3, :3], frame[:3, 3]


class BodyPart:
    """One FE body's tets ``keep`` (all when None) with the matrix from the body's displacements to the stress
    at those tets' centroids.

    Parameters
    ----------
    body : ltca.fem.compliance.BodyCompliance
        A body that still holds its mesh, factorisation and patch loads.
    young, poisson : float
        MPa, 1.
    keep : ndarray of int, optional
        Indices of the tets written.
    """

    def __init__(self, body, young: float, poisson: float, keep: np.ndarray | None = None):
        if body.factorization is None:
            raise ValueError("the body's factorisation was freed (BodyCompliance.without_solver): no ParaView "
                             "fields can be computed")
        self.body = body
        nodes, tets = body.mesh.nodes, body.mesh.tets
        keep = np.arange(len(tets)) if keep is None else np.asarray(keep)
        used = np.unique(tets[keep])
        self.nodes = used
        self.tets = np.searchsorted(used, tets[keep]).astype(np.int32)
        self.S = element_stress_matrix(nodes, tets, young, poisson, keep, np.full(4, 0.25))

    def displacements(self, grid_forces: np.ndarray) -> np.ndarray:
        """Displacements (n_dofs, k) of the whole body for forces (n_grid, k) on its compliance grid, N, one
        back-substitution."""
        b = self.body
        return np.asarray(b.factorization.solve(np.asarray(b.patch @ grid_forces)))

    def mesh(self, u: np.ndarray, frame: np.ndarray):
        """The part as a ``meshio.Mesh`` in the world frame ``frame`` (4, 4) of the body, under the body's
        displacements ``u`` (n_dofs,), mm."""
        import meshio
        vm, principal = stress_fields((self.S @ u).reshape(-1, 6))
        u = u.reshape(-1, 3)[self.nodes]
        R, t = _frame(frame)
        pts = self.body.mesh.nodes[self.nodes] @ R.T + t
        mag = 1e3 * np.linalg.norm(u, axis=1)
        return meshio.Mesh(pts.astype(np.float32), [("tetra10", self.tets)],
                           point_data={"displacement_mm": (u @ R.T).astype(np.float32),
                                       "displacement_magnitude_um": mag.astype(np.float32)},
                           cell_data={"von_mises_mpa": [vm.astype(np.float32)],
                                      "principal_stress_mpa": [principal.astype(np.float32)]})


def flank_mesh(points: np.ndarray, quads: np.ndarray, pressure: np.ndarray, frame: np.ndarray):
    """Loaded flanks as a quad surface: ``points`` (n, 3) in the body frame, ``quads`` (m, 4) point indices, the
    cell field ``contact_pressure_mpa`` (m,), MPa; placed by the world frame ``frame`` (4, 4)."""
    import meshio
    R, t = _frame(frame)
    return meshio.Mesh((np.asarray(points) @ R.T + t).astype(np.float32), [("quad", np.asarray(quads, np.int32))],
                       cell_data={"contact_pressure_mpa": [np.asarray(pressure, np.float32).reshape(-1)]})


def write_series(out: str | Path, steps: Iterable[tuple[float, Sequence[tuple[str, object]]]], comment: str) -> dict:
    """Write the VTU parts of every step and ``paraview.pvd`` listing them into ``out``.

    Parameters
    ----------
    out : str or Path
        The folder.
    steps : iterable of (timestep, [(part name, meshio.Mesh), ...])
        Per written position: its time value (the kind's position coordinate) and its parts, in order; may be a
        generator (each step's meshes are written, then dropped).
    comment : str
        One line in the PVD saying what the run and the time value are.

    Returns
    -------
    dict
        ``{"pvd": path, "files": number of files written, "timesteps": [...]}``.
    """
    out = Path(out)
    t0 = time.perf_counter()
    rows, times, files = [], [], 0
    for j, (timestep, parts) in enumerate(steps):
        times.append(float(timestep))
        for i, (name, mesh) in enumerate(parts):
            f = f"paraview_{name}_{j:03d}.vtu"
            write_vtu_file(out / f, mesh)
            files += 1
            rows.append(f'    <DataSet timestep="{timestep:.6g}" part="{i}" name={quoteattr(name)} file={quoteattr(f)}/>')
    text = ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
            f'  <!-- {comment.replace("--", "-")} -->\n'
            "  <Collection>\n" + "\n".join(rows) + "\n  </Collection>\n</VTKFile>\n")
    (out / "paraview.pvd").write_text(text)
    log.info("ParaView series: %d steps, %d files (%.1f s)", len(times), files + 1, time.perf_counter() - t0)
    return {"pvd": out / "paraview.pvd", "files": files + 1, "timesteps": times}
