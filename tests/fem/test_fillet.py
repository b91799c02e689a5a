"""The root-stress read-out: fillet radius and element size, read-out points, nodal-averaged stress.

The fillet's smallest radius of curvature is exact on a circular arc; FZG C14's generated fillets (rack tip radius
0.38 m = 1.71 mm) are about 1.96 mm (pinion) and 1.88 mm (gear). The read-out points lie ``DEPTH`` inside the
fillet, ``ROOT_STEP`` apart. The nodal-averaged stress (CalculiX's ``*EL FILE S``) is exact for a linear stress
field and continuous across the elements; on the refined fillet it reads the same as the element stress within a
few per cent where the mesh resolves the fillet.
"""
from __future__ import annotations

import numpy as np
import pytest

from ltca.fem import fillet as ff


def _arc_outline(rho: float = 2.0, n: int = 400):
    """A tooth-like outline whose right fillet (kind 1, side +1) is a circular arc of radius rho."""
    t = np.linspace(0.0, 0.5 * np.pi, n)
    arc = np.column_stack([rho * np.cos(t), rho * np.sin(t)])
    flank = np.column_stack([np.zeros(20), rho + np.linspace(0.05, 3.0, 20)])
    xy = np.concatenate([arc[::-1], flank])
    kind = np.r_[np.ones(n, int), np.full(20, 2)]
    side = np.ones(n + 20, int)
    return xy, kind, side


def test_fillet_radius_of_an_arc_and_the_element_size():
    xy, kind, side = _arc_outline(2.0)
    assert ff.fillet_radius(xy, kind, side, +1) == pytest.approx(2.0, rel=1e-3)
    assert ff.fillet_radius(xy, kind, side, -1) == np.inf                     # no left fillet
    assert ff.fillet_size(xy, kind, side, +1, 0.4, 1.35) == pytest.approx(0.8, rel=1e-3)
    assert ff.fillet_size(xy, kind, side, +1, 0.4, 0.5) == 0.5                # at most h_flank
    assert ff.fillet_size(xy, kind, side, +1, 0.0, 1.35) is None              # no refinement
    assert ff.fillet_size(xy, kind, side, -1, 0.4, 1.35) is None


def test_fzg_fillet_radii_and_read_out_points(fzg_model):
    p, g = fzg_model.pinion, fzg_model.gear
    assert ff.fillet_radius(p.xy, p.kind, p.side, +1) == pytest.approx(1.956, abs=0.01)
    assert ff.fillet_radius(g.xy, g.kind, g.side, fzg_model.gear_side) == pytest.approx(1.883, abs=0.01)
    b = fzg_model.face_width
    X = ff.fillet_points(p, +1, b, False)
    xy = np.asarray(p.xy)[(np.asarray(p.kind) == 1) & (np.asarray(p.side) == 1)]
    length = np.hypot(*np.diff(xy, axis=0).T).sum()
    n_s, n_z = int(np.ceil(length / ff.ROOT_STEP[0])) + 1, int(np.ceil(0.9 * b / ff.ROOT_STEP[1])) + 1
    assert X.shape == (n_s * n_z, 3)
    assert np.abs(X[:, 2]).max() == pytest.approx(0.45 * b)
    # every point DEPTH from the fillet (the dense outline), inside the material (nearer the centre than the outline)
    d = np.min(np.hypot(X[:, None, 0] - xy[None, ::4, 0], X[:, None, 1] - xy[None, ::4, 1]), axis=1)
    assert np.allclose(d, ff.DEPTH, atol=3e-3)
    assert ff.fillet_points(p, +1, b, False, (4, 3)).shape == (12, 3)


def test_nodal_stress_exact_for_a_linear_field_and_continuous():
    from skfem import MeshTet

    from ltca.fem import readout
    from ltca.fem.elastic import lame
    m = MeshTet().refined(2)
    rng = np.random.default_rng(1)
    nodes = m.p.T + 0.02 * rng.standard_normal(m.p.T.shape) * ((m.p.T > 0) & (m.p.T < 1)).all(axis=1)[:, None]
    edges = np.array([[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]])
    t = m.t.T
    keys = np.sort(t[:, edges], axis=2).reshape(-1, 2)
    uniq, inv = np.unique(keys, axis=0, return_inverse=True)
    nodes = np.concatenate([nodes, 0.5 * (nodes[uniq[:, 0]] + nodes[uniq[:, 1]])])
    tets = np.concatenate([t, len(m.p.T) + inv.reshape(-1, 6)], axis=1)
    E, nu = 210e3, 0.3
    lam, mu = lame(E, nu)

    def quad(x):                                  # quadratic displacement: linear stress, exact in P2
        return np.stack([x[:, 0] ** 2 + x[:, 1] * x[:, 2], x[:, 1] ** 2 - 2 * x[:, 0] * x[:, 2],
                         x[:, 2] * x[:, 0] + 3 * x[:, 1]], axis=1) * 1e-3

    pts = rng.random((200, 3))
    x0, x1, x2 = pts.T
    G = np.zeros((len(pts), 3, 3))
    G[:, 0] = np.stack([2 * x0, x2, x1], 1)
    G[:, 1] = np.stack([-2 * x2, 2 * x1, -2 * x0], 1)
    G[:, 2] = np.stack([x2, np.full_like(x0, 3.0), x0], 1)
    eps = 0.5e-3 * (G + G.transpose(0, 2, 1))
    sig = lam * np.trace(eps, axis1=1, axis2=2)[:, None, None] * np.eye(3) + 2 * mu * eps
    exact = sig[:, [0, 1, 2, 1, 0, 0], [0, 1, 2, 2, 2, 1]]
    u = quad(nodes).ravel()
    for recovery in ("element", "nodal"):
        S = readout.stress_matrix(nodes, tets, E, nu, pts, recovery=recovery)
        assert np.abs((S @ u).reshape(-1, 6) - exact).max() < 1e-9 * np.abs(exact).max()
    P, A = readout.nodal_stress(nodes, tets, E, nu, pts)
    assert P.shape == (6 * len(pts), A.shape[0]) and A.shape[1] == 3 * len(nodes)
    # a cubic field: the element stress jumps across an inner face, the nodal-averaged stress does not
    faces = np.sort(tets[:, [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]]].reshape(-1, 3), axis=1)
    _, first, count = np.unique(faces, axis=0, return_index=True, return_counts=True)
    f = faces[first[np.flatnonzero(count == 2)[0]]]
    c = nodes[f].mean(axis=0)
    n = np.cross(nodes[f[1]] - nodes[f[0]], nodes[f[2]] - nodes[f[0]])
    face_pts = c + 1e-7 * np.array([[1.0], [-1.0]]) * n / np.linalg.norm(n)
    cubic = (np.prod(nodes, axis=1)[:, None] * nodes * np.array([1.0, 0.5, -0.3]) * 1e-3).ravel()
    jump = {rec: np.ptp((readout.stress_matrix(nodes, tets, E, nu, face_pts, recovery=rec) @ cubic).reshape(2, 6),
                        axis=0).max() for rec in ("element", "nodal")}
    assert jump["element"] > 0.1 and jump["nodal"] < 1e-4 * jump["element"], jump
    with pytest.raises(ValueError, match="recovery"):
        readout.stress_matrix(nodes, tets, E, nu, pts, recovery="spr")
