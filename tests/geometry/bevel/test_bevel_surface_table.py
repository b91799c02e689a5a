"""The tabulated bevel flank (geometry.bevel.surface_table) against the exact Newton solve of the equation of
meshing: at random points over the whole box (not the cell centres the table checks itself), both members, both
flanks of the shipped pair, every point the table serves within 1e-7 mm in position; the points it does not
serve are the exact solve's own answer (bit for bit); the solved/not solved flags agree with the exact solve's
inside the box. And the loaded analysis with the table equals the analysis without it to far below a 5 % guard.
"""
from __future__ import annotations

import numpy as np
import pytest

from ltca.geometry.bevel.gaps import MeshGaps
from ltca.geometry.bevel.surface_table import SurfaceTable
from ltca.geometry.bevel.tca import RAD_PER_ARCSEC


@pytest.fixture(scope="module")
def pair(bevel_pair):
    """The shipped pair (the session's :func:`fixtures.bevel.bevel_pair`)."""
    return bevel_pair


@pytest.mark.parametrize("side", ["concave", "convex"])
def test_table_equals_the_exact_surface(pair, side):
    mg = MeshGaps(pair, side)
    for M in (mg.P, mg.G):
        tb = M.table
        assert isinstance(tb, SurfaceTable) and tb.branches[0].usable
        rng = np.random.default_rng(7)
        t = rng.uniform(-0.2, 1.2, 6000)
        L = rng.uniform(M.Ai - 0.5, M.A0 + 0.5, 6000)
        r, n, ok = M.surface(t, L)
        re, ne, oke = M.exact_surface(t, L)
        which = tb.served(t, L)
        served = which >= 0
        # the table serves most of the working flank (the straight blade's branch)
        flank = (t > 0.3) & (t < 1) & (L > M.Ai) & (L < M.A0)
        assert served[flank].mean() > 0.95, f"{M.name}: served {served[flank].mean():.3f}"
        assert np.all(ok[served]) and np.all(oke[served])
        err = np.abs(r - re).max(-1)[served]
        assert err.max() < 1e-7, f"{M.name} {side}: position error {err.max():.2e} mm"
        assert np.abs(n - ne).max(-1)[served].max() < 1e-5
        # not served, inside the box: the exact answer itself
        rest = ~served & (t >= tb.box[0]) & (t <= tb.box[1]) & (L >= tb.box[2]) & (L <= tb.box[3])
        assert np.array_equal(ok[rest], oke[rest])
        assert np.array_equal(r[rest & ok], re[rest & ok])


def test_table_shape_is_checked(pair):
    mg = MeshGaps(pair, "concave", table=None)
    assert mg.P.table is None
    with pytest.raises(ValueError, match="shape"):
        SurfaceTable(mg.P.exact_surface, mg.P.axial, (0, 1), (mg.P.Ai, mg.P.A0), shape=(5, 40))


@pytest.mark.heavy
def test_loaded_cycle_with_and_without_the_table(pair, bevel_bodies_coarse):
    """The loaded TE and the peak pressure of a cycle (175 N m, coarse bodies) with the tabulated flanks equal the
    exact ones within 1e-3 arcsec and 0.01 %: the table is not a model change."""
    import ltca.geometry.bevel.gaps as gaps_module
    from ltca.bevel.loaded import solve_position
    from ltca.bevel.loaded_model import loaded_model
    bodies = bevel_bodies_coarse
    phi = np.linspace(-0.5, 0.5, 3) * 2 * np.pi / pair.blank.pinion.z
    out = {}
    for table in (1e-7, None):
        init = gaps_module.MeshGaps.__init__
        gaps_module.MeshGaps.__init__ = lambda self, *a, _i=init, _t=table, **k: _i(self, *a, **{**k, "table": _t})
        try:
            lm = loaded_model(pair, bodies)
            assert (lm.gaps.P.table is None) == (table is None)
            res = [solve_position(lm, float(p), 175e3) for p in phi]
        finally:
            gaps_module.MeshGaps.__init__ = init
        out[table] = (np.array([r.te for r in res]) / RAD_PER_ARCSEC, np.array([r.pressure.max() for r in res]))
    assert np.allclose(out[1e-7][0], out[None][0], atol=1e-3, rtol=0)
    assert np.allclose(out[1e-7][1], out[None][1], rtol=1e-4)
