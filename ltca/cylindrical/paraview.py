"""The ParaView time series of a loaded run: one ``paraview.pvd`` with a step per mesh position.

Each step has three parts (the PVD ``part`` attribute), in the world frame of that position:

- ``pinion`` and ``gear``: the FE bodies (P2 tets) with the point field ``displacement_mm`` (and its magnitude in
  um) and the cell fields ``von_mises_mpa`` and ``principal_stress_mpa`` (sigma_1 >= sigma_2 >= sigma_3, at the tet
  centroid): the load of the position's contact cells is put back on the factorised model as patch loads, so the
  fields are the FE solution itself (without the half-space near field of the contact);
- ``flank``: the loaded pinion flanks as a quad surface on the flank lattice of ``results.nc`` (involute roll
  bins x face slices, exact involute helicoid points) with the cell field ``contact_pressure_mpa``: the largest
  contact-cell pressure in each lattice bin (:func:`ltca.cylindrical.results.pressure_on_lattice`), so its peak is
  the solver's peak at that position.

Files: ``paraview.pvd`` and ``paraview_<part>_<step>.vtu`` beside it (zlib-compressed, float32 fields). The
series covers the first torque; ``steps`` limits it to that many positions spread over the cycle (the pitch
position among them when it is one of the positions).
"""
from __future__ import annotations

from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from ltca.fem.readout import element_stress_matrix
from ltca.geometry.cylindrical import flank_point_normal
from ltca.geometry.pair import rotation_z

from .loaded import PositionResult, weights_of
from .loaded_model import LoadedModel
from .results import flank_lattice, pressure_on_lattice, roll_step
from .vtu import write_vtu_file

__all__ = ["select_steps", "write_series", "stress_fields"]


def select_steps(rolls_deg: np.ndarray, steps: int | None) -> np.ndarray:
    """Indices of the positions written: all when ``steps`` is None or not fewer than the positions, else
    ``steps`` spread evenly, always with the position nearest the pitch point (roll 0)."""
    n = len(rolls_deg)
    if steps is None or steps >= n:
        return np.arange(n)
    pick = set(np.round(np.linspace(0, n - 1, max(steps, 1))).astype(int).tolist())
    pick.add(int(np.argmin(np.abs(rolls_deg))))
    return np.array(sorted(pick))


def stress_fields(sigma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Von Mises stress (n,) and principal stresses (n, 3), descending, of Voigt stresses (n, 6) (xx, yy, zz, yz,
    xz, xy), MPa."""
    xx, yy, zz, yz, xz, xy = sigma.T
    vm = np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2) + 3 * (yz ** 2 + xz ** 2 + xy ** 2))
    T = np.stack([np.stack([xx, xy, xz], -1), np.stack([xy, yy, yz], -1), np.stack([xz, yz, zz], -1)], -2)
    return vm, np.linalg.eigvalsh(T)[:, ::-1]


class _Body:
    """One FE body cut to its loaded teeth (the tets whose centroid lies within half a pitch of a loaded tooth's
    centre line and above the root circle less one module; for a ring gear below it plus one module), with the
    matrix from the body's displacements to the stress at those tets' centroids."""

    def __init__(self, body, profile, young: float, poisson: float):
        self.body = body
        nodes, tets = body.mesh.nodes, body.mesh.tets
        c = nodes[tets[:, :4]].mean(axis=1)
        r = np.hypot(c[:, 0], c[:, 1])
        m = profile.m_n
        near = r <= profile.r_root + m if profile.internal else r >= profile.r_root - m
        pitch = 2 * np.pi / profile.z
        theta = np.arctan2(c[:, 1], c[:, 0])
        on_tooth = np.zeros(len(tets), bool)
        for k in body.spec.loaded:
            d = np.angle(np.exp(1j * (theta - (0.5 * np.pi - k * pitch))))
            on_tooth |= np.abs(d) <= 0.5 * pitch
        keep = np.flatnonzero(near & on_tooth)
        used = np.unique(tets[keep])
        self.nodes = used
        self.tets = np.searchsorted(used, tets[keep]).astype(np.int32)
        self.S = element_stress_matrix(nodes, tets, young, poisson, keep, np.full(4, 0.25))

    def displacements(self, grid_forces: np.ndarray) -> np.ndarray:
        """Displacements (n_dofs, k) of the whole body for grid forces (n_grid, k), one back-substitution."""
        b = self.body
        return np.asarray(b.factorization.solve(np.asarray(b.patch @ grid_forces)))

    def write(self, path: Path, u: np.ndarray, frame: np.ndarray) -> None:
        import meshio
        vm, principal = stress_fields((self.S @ u).reshape(-1, 6))
        u = u.reshape(-1, 3)[self.nodes]
        R, t = frame[:3, :3], frame[:3, 3]
        pts = self.body.mesh.nodes[self.nodes] @ R.T + t
        mag = 1e3 * np.linalg.norm(u, axis=1)
        mesh = meshio.Mesh(pts.astype(np.float32), [("tetra10", self.tets)],
                           point_data={"displacement_mm": (u @ R.T).astype(np.float32),
                                       "displacement_magnitude_um": mag.astype(np.float32)},
                           cell_data={"von_mises_mpa": [vm.astype(np.float32)],
                                      "principal_stress_mpa": [principal.astype(np.float32)]})
        write_vtu_file(path, mesh)


def _flank_surface(lm: LoadedModel, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Points (tooth, profile edge, face edge, 3) of the loaded pinion flanks on the pressure lattice (pinion frame)
    and the quads (tooth x profile bin x face slice, 4)."""
    p1 = lm.model.pinion
    u_lo, du, n = flank_lattice(lm, step)
    r = p1.r_base * np.sqrt(1 + (u_lo + du * np.arange(n + 1)) ** 2)
    r = np.clip(r, p1.r_base, p1.r_tip)
    b, ns = lm.model.face_width, lm.fid.slices
    z = np.linspace(-0.5 * b, 0.5 * b, ns + 1)
    R, Z = np.meshgrid(r, z, indexing="ij")
    pts = np.stack([flank_point_normal(p1, +1, R, Z, tooth=int(k))[0] for k in lm.teeth1])
    nt = len(lm.teeth1)
    idx = np.arange(nt * (n + 1) * (ns + 1)).reshape(nt, n + 1, ns + 1)
    quads = np.stack([idx[:, :-1, :-1], idx[:, 1:, :-1], idx[:, 1:, 1:], idx[:, :-1, 1:]], -1).reshape(-1, 4)
    return pts.reshape(-1, 3), quads


def write_series(out: Path, lm: LoadedModel, results: list[PositionResult], torque: float,
                 steps: int | None = None) -> dict:
    """Write ``paraview.pvd`` and its VTU parts for ``results`` (one torque, N mm) into ``out`` (module docstring).

    Returns ``{"pvd": path, "steps": [position index], "roll_deg": [...], "flank_peak_mpa": [...], "files": n}``."""
    import meshio
    out = Path(out)
    model = lm.model
    rolls = np.degrees([r.roll for r in results])
    pick = select_steps(rolls, steps)
    step = roll_step(results, model.pitch_angle)
    pts, quads = _flank_surface(lm, step)
    bodies = (_Body(lm.body1, model.pinion, model.case.young, model.case.poisson),
              _Body(lm.body2, model.gear, model.case.young, model.case.poisson))
    weights = [weights_of(lm, results[k]) for k in pick]
    U = [body.displacements(np.stack([w[i].T @ results[k].force for w, k in zip(weights, pick)], axis=1))
         for i, body in enumerate(bodies)]
    rows, peaks = [], []
    for j, k in enumerate(pick):
        r = results[k]
        frame1 = rotation_z(model.phi_pitch - r.roll)
        frame2 = model.pair.gear_frame(model.phi_pitch - r.roll)
        names = []
        for i, (name, frame) in enumerate((("pinion", frame1), ("gear", frame2))):
            f = f"paraview_{name}_{j:03d}.vtu"
            bodies[i].write(out / f, U[i][:, j], frame)
            names.append(f)
        field, _, _ = pressure_on_lattice(lm, r, step)
        p = field.reshape(-1).astype(np.float32)
        peaks.append(float(p.max(initial=0.0)))
        R, t = frame1[:3, :3], frame1[:3, 3]
        f = f"paraview_flank_{j:03d}.vtu"
        write_vtu_file(out / f, meshio.Mesh((pts @ R.T + t).astype(np.float32), [("quad", quads.astype(np.int32))],
                                            cell_data={"contact_pressure_mpa": [p]}))
        names.append(f)
        rows += [f'    <DataSet timestep="{rolls[k]:.6g}" part="{i}" name={quoteattr(n.split("_")[1])} '
                 f'file={quoteattr(n)}/>'
                 for i, n in enumerate(names)]
    text = ('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
            f'  <!-- {model.case.name}, {torque * 1e-3:g} N m; timestep = pinion roll from the pitch point, deg -->\n'
            "  <Collection>\n" + "\n".join(rows) + "\n  </Collection>\n</VTKFile>\n")
    (out / "paraview.pvd").write_text(text)
    return {"pvd": out / "paraview.pvd", "steps": [int(k) for k in pick], "roll_deg": [float(rolls[k]) for k in pick],
            "flank_peak_mpa": peaks, "files": 3 * len(pick) + 1}
