"""Exact points of a generated bevel flank between and beyond its grid nodes (geometry.bevel.sampling)."""
import numpy as np
import pytest

from ltca.geometry.bevel.blank import BevelBasicData, design_blank
from ltca.geometry.bevel.generation import generate_member, standard_gear_cut
from ltca.geometry.bevel.sampling import axial_target, fillet_boundary, flank_at


@pytest.fixture(scope="module")
def setup():
    blank = design_blank(BevelBasicData())
    return blank, generate_member(standard_gear_cut(blank), blank, nu=12, nv=15)


def test_flank_at_reproduces_grid_nodes(setup):
    _, fl = setup
    for f in fl.values():
        T, L = np.meshgrid(f.u, f.v, indexing="ij")
        Z, rho = axial_target(f, T, L)
        assert np.allclose(Z, f.meta["Z"], atol=1e-10) and np.allclose(rho, f.meta["rho"], atol=1e-10)
        p, n, u = flank_at(f, T, L)
        assert np.abs(p - f.points).max() < 1e-8
        assert np.abs(n - f.normals).max() < 1e-8
        assert np.allclose(u, f.meta["params"][..., 0], atol=1e-7)


def test_flank_at_between_and_beyond_nodes_is_on_the_generated_surface(setup):
    _, fl = setup
    f = fl["convex"]
    t = np.array([0.05, 0.5, 1.04, 0.33])
    L = np.array([f.v[0] - 0.6, 0.5 * (f.v[3] + f.v[4]), f.v[-1] + 0.6, f.v[7]])
    p, n, u = flank_at(f, t, L)
    Z, rho = axial_target(f, t, L)
    assert np.allclose(p[:, 2], Z, atol=1e-9) and np.allclose(np.hypot(p[:, 0], p[:, 1]), rho, atol=1e-9)
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-12)


def test_fillet_boundary_is_the_blade_tangency(setup):
    _, fl = setup
    for f in fl.values():
        tb = fillet_boundary(f)
        assert np.all((tb > 0) & (tb < 0.5))
        u = flank_at(f, tb, f.v)[2]
        assert np.abs(u).max() < 1e-4                      # mm along the blade
        below = flank_at(f, tb - 0.02, f.v)[2]
        assert np.all(below < 0)                           # fillet (edge radius) below, straight blade above
