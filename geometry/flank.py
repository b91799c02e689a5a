"""The gridded tooth flank: the one currency every later stage consumes.

Conventions (used throughout the package)
-----------------------------------------
* Points are stored with xyz on the **last** axis: a single point is (3,), a grid is (nu, nv, 3),
  a cloud is (n, 3). Conversion to other layouts happens only at the gmsh / meshio boundary.
* Units: mm, rad. Curvatures in 1/mm.
* Each gear has its own body frame: z along the gear axis, the origin on the axis at mid-face
  (cylindrical gears) or at the pitch-cone apex (bevel gears).
* ``normals`` are unit vectors pointing **out of the material** (from the tooth into the space).
* Principal curvatures follow the sign convention of Litvin: positive for a surface that is convex
  seen from the outside (a convex involute flank has a positive curvature in the profile direction),
  negative for a concave one (internal-gear flank).
* ``u`` runs along the profile (from root to tip), ``v`` along the face width.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["Flank", "surface_curvatures"]


@dataclass(frozen=True)
class Flank:
    """A tooth flank sampled on a structured (u, v) grid, in the gear body frame.

    Parameters
    ----------
    points : ndarray, shape (nu, nv, 3)
        Surface points, mm.
    normals : ndarray, shape (nu, nv, 3)
        Unit normals out of the material.
    u : ndarray, shape (nu,)
        Profile parameter of the grid rows (e.g. roll angle in rad, or radius in mm; see ``u_name``).
    v : ndarray, shape (nv,)
        Face parameter of the grid columns (axial position in mm for cylindrical gears).
    curvatures : ndarray, shape (nu, nv, 2)
        Principal curvatures k1 >= k2, 1/mm (Litvin sign convention, see module docstring).
    directions : ndarray, shape (nu, nv, 2, 3)
        Unit principal directions belonging to ``curvatures``.
    side : str
        Which flank: ``"right"``/``"left"`` (cylindrical, seen from the tip with the tooth pointing up)
        or ``"concave"``/``"convex"`` (bevel).
    tooth : int
        Index of the tooth the flank belongs to (0 = reference tooth).
    u_name, v_name : str
        What ``u`` and ``v`` mean, for plots and reports.
    """

    points: np.ndarray
    normals: np.ndarray
    u: np.ndarray
    v: np.ndarray
    curvatures: np.ndarray
    directions: np.ndarray
    side: str = "right"
    tooth: int = 0
    u_name: str = "u"
    v_name: str = "v"
    meta: dict = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        nu, nv = len(self.u), len(self.v)
        for name, shape in (("points", (nu, nv, 3)), ("normals", (nu, nv, 3)),
                            ("curvatures", (nu, nv, 2)), ("directions", (nu, nv, 2, 3))):
            arr = getattr(self, name)
            if arr.shape != shape:
                raise ValueError(f"Flank.{name} has shape {arr.shape}, expected {shape}")
        if not np.all(np.isfinite(self.points)):
            raise ValueError("Flank.points contains non-finite values")

    @property
    def shape(self) -> tuple[int, int]:
        return len(self.u), len(self.v)

    def transformed(self, matrix: np.ndarray) -> "Flank":
        """The same flank in another frame; ``matrix`` is a 4x4 homogeneous transform (rotation + shift)."""
        R, t = matrix[:3, :3], matrix[:3, 3]
        return Flank(self.points @ R.T + t, self.normals @ R.T, self.u, self.v, self.curvatures,
                     self.directions @ R.T, self.side, self.tooth, self.u_name, self.v_name, self.meta)


def surface_curvatures(points: np.ndarray, normals: np.ndarray, u: np.ndarray, v: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray]:
    """Principal curvatures and directions of a gridded surface from its first and second forms.

    Derivatives by second-order finite differences on the (u, v) grid (``numpy.gradient``), which is
    adequate for smooth flanks on grids of 10+ points per direction; analytic curvatures should be
    preferred where a generator knows them.

    Parameters
    ----------
    points, normals : ndarray, shape (nu, nv, 3)
    u, v : ndarray, shape (nu,), (nv,)

    Returns
    -------
    k : ndarray, shape (nu, nv, 2)
        Principal curvatures k1 >= k2 (positive = convex seen along the normal, i.e. from outside).
    d : ndarray, shape (nu, nv, 2, 3)
        Unit principal directions.

    Notes
    -----
    Shape operator S = I^-1 II with I = [[E, F], [F, G]], II = [[L, M], [M, N]] and
    L = -r_uu . n etc. (sign chosen so that an outward-normal convex surface is positive); do Carmo,
    *Differential Geometry of Curves and Surfaces*, sec. 3-3.
    """
    ru = np.gradient(points, u, axis=0, edge_order=2)
    rv = np.gradient(points, v, axis=1, edge_order=2)
    ruu = np.gradient(ru, u, axis=0, edge_order=2)
    ruv = np.gradient(ru, v, axis=1, edge_order=2)
    rvv = np.gradient(rv, v, axis=1, edge_order=2)
    E = np.einsum("...i,...i", ru, ru)
    F = np.einsum("...i,...i", ru, rv)
    G = np.einsum("...i,...i", rv, rv)
    L = -np.einsum("...i,...i", ruu, normals)
    M = -np.einsum("...i,...i", ruv, normals)
    N = -np.einsum("...i,...i", rvv, normals)
    first = np.stack([np.stack([E, F], -1), np.stack([F, G], -1)], -2)
    second = np.stack([np.stack([L, M], -1), np.stack([M, N], -1)], -2)
    shape_op = np.linalg.solve(first, second)
    # symmetrise in the metric: eigen-decomposition of I^-1/2 II I^-1/2 is robust; use eig here
    w, vec = np.linalg.eig(shape_op)
    w, vec = w.real, vec.real
    order = np.argsort(-w, axis=-1)
    w = np.take_along_axis(w, order, -1)
    vec = np.take_along_axis(vec, order[..., None, :], -1)
    dirs = ru[..., None, :] * vec[..., 0, :, None] + rv[..., None, :] * vec[..., 1, :, None]
    dirs /= np.linalg.norm(dirs, axis=-1, keepdims=True)
    return w, dirs
