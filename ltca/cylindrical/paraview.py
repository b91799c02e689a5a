"""The ParaView time series of a cylindrical loaded run (also a planetary satellite in its wheel, the same model):
the parts of each position fed to the one writer, :func:`ltca.paraview.write_series`.

Each step has three parts (the PVD ``part`` attribute), in the world frame of that position:

- ``pinion`` and ``gear``: the FE bodies cut to their loaded teeth (:class:`ltca.paraview.BodyPart`: displacement,
  von Mises and principal stresses of the FE solution under the position's contact forces);
- ``flank``: the loaded pinion flanks as a quad surface on the flank lattice of ``results.nc`` (involute roll
  bins x face slices, exact involute helicoid points) with the cell field ``contact_pressure_mpa``: the largest
  contact-cell pressure in each lattice bin (:func:`ltca.cylindrical.results.pressure_on_lattice`), so its peak is
  the solver's peak at that position.

The series covers one torque; ``steps`` limits it to that many positions spread over the cycle (the pitch
position among them when it is one of the positions).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ltca.geometry.cylindrical import flank_point_normal
from ltca.geometry.pair import rotation_z

from ..paraview import BodyPart, flank_mesh, select_steps
from ..paraview import write_series as write_pvd
from .loaded import PositionResult, weights_of
from .loaded_model import LoadedModel
from .results import flank_lattice, pressure_on_lattice, roll_step

__all__ = ["loaded_teeth_tets", "write_series"]


def loaded_teeth_tets(body, profile) -> np.ndarray:
    """Tets of a body near its loaded teeth: centroid within half a pitch of a loaded tooth's centre line and
    above the root circle less one module (for a ring gear below it plus one module)."""
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
    return np.flatnonzero(near & on_tooth)


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
                 steps: int | None = None, comment: str | None = None) -> dict:
    """Write ``paraview.pvd`` and its VTU parts for ``results`` (one torque, N mm) into ``out`` (module docstring).

    Returns ``{"pvd": path, "steps": [position index], "roll_deg": [...], "flank_peak_mpa": [...], "files": n}``."""
    model = lm.model
    rolls = np.degrees([r.roll for r in results])
    pick = select_steps(rolls, steps)
    step = roll_step(results, model.pitch_angle)
    pts, quads = _flank_surface(lm, step)
    E, nu = model.case.young, model.case.poisson
    bodies = (BodyPart(lm.body1, E, nu, loaded_teeth_tets(lm.body1, model.pinion)),
              BodyPart(lm.body2, E, nu, loaded_teeth_tets(lm.body2, model.gear)))
    weights = [weights_of(lm, results[k]) for k in pick]
    U = [body.displacements(np.stack([w[i].T @ results[k].force for w, k in zip(weights, pick)], axis=1))
         for i, body in enumerate(bodies)]
    peaks = []

    def parts():
        for j, k in enumerate(pick):
            r = results[k]
            frame1 = rotation_z(model.phi_pitch - r.roll)
            frame2 = model.pair.gear_frame(model.phi_pitch - r.roll)
            field, _, _ = pressure_on_lattice(lm, r, step)
            p = field.reshape(-1).astype(np.float32)
            peaks.append(float(p.max(initial=0.0)))
            yield rolls[k], [("pinion", bodies[0].mesh(U[0][:, j], frame1)),
                             ("gear", bodies[1].mesh(U[1][:, j], frame2)),
                             ("flank", flank_mesh(pts, quads, p, frame1))]
    text = comment or f"{model.case.name}, {torque * 1e-3:g} N m; timestep = pinion roll from the pitch point, deg"
    pv = write_pvd(out, parts(), text)
    return {"pvd": pv["pvd"], "steps": [int(k) for k in pick], "roll_deg": [float(rolls[k]) for k in pick],
            "flank_peak_mpa": peaks, "files": pv["files"]}
