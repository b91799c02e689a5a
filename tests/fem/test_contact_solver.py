"""The contact complementarity solver: hand-solved cases, KKT conditions, an independent QP solve,
warm start, input checks, non-convergence, and timings at n = 1000 and 3000."""
import time

import numpy as np
import pytest
from scipy.optimize import minimize

from ltca.fem.contact import ContactNotConverged, solve_contact
from ltca.fem.halfspace import surface_influence_matrix

E, NU = 206000.0, 0.3


def _flank_problem(nx, ny, seed=0, force=2000.0):
    """Gear-like problem: half-space compliance of two steel bodies on an nx x ny grid of 20 x 50 um
    cells, crowned gaps plus 0.5 um roughness, lever arms 30..33 mm (theta a rotation, load a torque)."""
    rng = np.random.default_rng(seed)
    dx, dy = 0.02, 0.05
    x = (np.arange(nx) - (nx - 1) / 2) * dx
    y = (np.arange(ny) - (ny - 1) / 2) * dy
    X, Y = np.meshgrid(x, y, indexing="ij")
    xs = np.column_stack([X.ravel(), Y.ravel()])
    C = 2 * surface_influence_matrix(xs, xs, np.tile([dx / 2, dy / 2], (len(xs), 1)), E, NU)
    g0 = xs[:, 0] ** 2 / (2 * 8.0) + xs[:, 1] ** 2 / (2 * 200.0) + 5e-4 * rng.random(len(xs))
    h = 30.0 + 3.0 * (xs[:, 0] - x[0]) / (x[-1] - x[0])
    return C, g0, h, force * 31.5                    # torque, N mm


def _check_kkt(C, g0, h, load, sol, tol=1e-10):
    fin = np.isfinite(g0)
    gap = g0[fin] + C[np.ix_(fin, fin)] @ sol.force[fin] - h[fin] * sol.approach
    scale = np.abs(C @ sol.force).max()
    assert np.all(sol.force >= 0)
    assert np.all(sol.gap >= 0)
    assert gap.min() > -tol * scale                                   # no penetration
    assert np.abs(sol.force[fin] * gap).max() < tol * scale * sol.force.max()   # complementarity
    assert abs(h @ sol.force - load) < 1e-10 * load                   # balance
    assert np.array_equal(sol.active, sol.force > 0)
    assert np.all(sol.gap[sol.active] == 0)


def test_hand_solved_two_cells():
    # C = [[2, 1], [1, 2]], g0 = [0, 0.5], h = 1.  One cell: F = (P, 0), theta = 2P, gap2 = 0.5 - P
    # (valid for P < 0.5).  Both cells: 2F1 + F2 = theta, F1 + 2F2 + 0.5 = theta, F1 + F2 = P
    # -> F1 = (P + 0.5)/2, F2 = (P - 0.5)/2, theta = 2F1 + F2; at P = 1: (0.75, 0.25), theta = 1.75.
    C = np.array([[2.0, 1.0], [1.0, 2.0]])
    g0 = np.array([0.0, 0.5])
    s = solve_contact(C, g0, np.ones(2), 0.25)
    assert np.allclose(s.force, [0.25, 0.0], atol=1e-14) and s.approach == pytest.approx(0.5)
    assert np.allclose(s.gap, [0.0, 0.25]) and list(s.active) == [True, False]
    s = solve_contact(C, g0, np.ones(2), 1.0)
    assert np.allclose(s.force, [0.75, 0.25]) and s.approach == pytest.approx(1.75)
    assert np.allclose(s.gap, 0.0) and s.active.all()


def test_infinite_gaps_are_dropped_and_lever_arms():
    # Same C, g0 with lever arms h = (1, 2) plus a cell that can never touch.  Cell 1 alone: F1 = T,
    # theta = 2T, gap2 = 0.5 + T - 2 theta = 0.5 - 3T (so T = 0.1 touches one cell).  Both cells:
    # 2F1 + F2 = theta, F1 + 2F2 + 0.5 = 2 theta, F1 + 2F2 = T -> theta = (T + 0.5)/2,
    # F2 = (2T - theta)/3, F1 = T - 2F2; at T = 1: theta = 0.75, F = (1/6, 5/12).
    C = np.array([[2.0, 1.0, 0.3], [1.0, 2.0, 0.3], [0.3, 0.3, 2.0]])
    g0 = np.array([0.0, 0.5, np.inf])
    h = np.array([1.0, 2.0, -1.0])                   # h is not checked where g0 is infinite
    s = solve_contact(C, g0, h, 0.1)
    assert np.allclose(s.force, [0.1, 0.0, 0.0]) and s.approach == pytest.approx(0.2)
    assert s.gap[1] == pytest.approx(0.2)
    s = solve_contact(C, g0, h, 1.0)
    assert np.allclose(s.force, [1 / 6, 5 / 12, 0.0]) and s.approach == pytest.approx(0.75)
    assert s.gap[2] == np.inf and not s.active[2] and s.active[:2].all()


def test_against_independent_qp_solver():
    # KKT solution == minimiser of 1/2 F'CF + g0'F subject to F >= 0, h'F = load (SLSQP, scipy).
    C, g0, h, load = _flank_problem(6, 3, seed=3, force=3.0)
    s = solve_contact(C, g0, h, load)
    res = minimize(lambda F: 0.5 * F @ C @ F + g0 @ F, np.full(18, load / h.sum()),
                   jac=lambda F: C @ F + g0, method="SLSQP", bounds=[(0, None)] * 18,
                   constraints=[dict(type="eq", fun=lambda F: h @ F - load, jac=lambda F: h)],
                   options=dict(ftol=1e-16, maxiter=500))
    assert res.success
    f = lambda F: 0.5 * F @ C @ F + g0 @ F
    print(f"\nQP: max |F - F_slsqp| / max F = {np.abs(s.force - res.x).max() / s.force.max():.1e}, "
          f"objective {f(s.force):.10e} vs SLSQP {f(res.x):.10e}")
    assert f(s.force) <= f(res.x) + 1e-12 * abs(f(res.x))      # ours is the (unique) minimiser
    assert np.allclose(s.force, res.x, atol=1e-4 * s.force.max())
    assert 1 < s.active.sum() < 18                   # a genuinely partial contact


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_kkt_on_gear_like_problem(seed):
    C, g0, h, load = _flank_problem(30, 20, seed)
    s = solve_contact(C, g0, h, load)
    _check_kkt(C, g0, h, load, s)
    assert s.residual < 1e-9


def test_warm_start_same_answer_fewer_iterations():
    C, g0, h, load = _flank_problem(30, 20, seed=4)
    prev = solve_contact(C, g0, h, load)
    g1 = g0 + 2e-4 * (np.arange(g0.size) % 20) / 20   # the next mesh position: slightly other gaps
    cold = solve_contact(C, g1, h, 1.03 * load)
    warm = solve_contact(C, g1, h, 1.03 * load, active0=prev.active)
    assert np.allclose(warm.force, cold.force, rtol=0, atol=1e-10 * cold.force.max())
    assert warm.approach == pytest.approx(cold.approach, rel=1e-12)
    assert warm.iterations < cold.iterations
    _check_kkt(C, g1, h, 1.03 * load, warm)


@pytest.mark.parametrize("bad", ["load0", "loadneg", "Cshape", "g0nan", "hneg", "maxit", "act"])
def test_bad_input_raises(bad):
    C, g0, h = np.eye(3), np.zeros(3), np.ones(3)
    kw = dict(C=C, g0=g0, h=h, load=1.0)
    name = {"load0": "load", "loadneg": "load", "Cshape": "C", "g0nan": "g0", "hneg": "h",
            "maxit": "max_iter", "act": "active0"}[bad]
    kw.update({"load0": dict(load=0.0), "loadneg": dict(load=-5.0), "Cshape": dict(C=np.eye(4)),
               "g0nan": dict(g0=np.array([0, np.nan, 1.0])), "hneg": dict(h=np.array([1, 0, 1.0])),
               "maxit": dict(max_iter=0), "act": dict(active0=np.array([5]))}[bad])
    with pytest.raises(ValueError, match=name):
        solve_contact(**kw)


def test_max_iter_one_raises_contact_not_converged():
    C, g0, h, load = _flank_problem(30, 20, seed=5)
    with pytest.raises(ContactNotConverged, match="refine the contact grid") as info:
        solve_contact(C, g0, h, load, max_iter=1)
    assert info.value.iterations == 1 and info.value.residual > 1e-9
    assert "max_iter" in info.value.advice and isinstance(info.value, RuntimeError)


@pytest.mark.heavy
@pytest.mark.parametrize("nx,ny", [(40, 25), (60, 50)])
def test_timing(nx, ny):
    C, g0, h, load = _flank_problem(nx, ny, seed=6)
    t_cold = []
    for _ in range(3):
        t = time.perf_counter()
        s = solve_contact(C, g0, h, load)
        t_cold.append(time.perf_counter() - t)
    t = time.perf_counter()
    w = solve_contact(C, g0 * 1.01, h, load, active0=s.active)
    t_warm = time.perf_counter() - t
    print(f"\nn = {nx * ny}: active {s.active.sum()}, cold {min(t_cold) * 1e3:.0f} ms "
          f"({s.iterations} it), warm {t_warm * 1e3:.0f} ms ({w.iterations} it)")
    _check_kkt(C, g0, h, load, s)


def test_lawson_hanson_fallback_matches():
    # The anti-cycling fallback (private) started from a single loaded cell must reach the same KKT point.
    from ltca.fem.contact import _lawson_hanson
    C, g0, h, load = _flank_problem(12, 8, seed=7, force=40.0)
    ref = solve_contact(C, g0, h, load)
    F = np.zeros(g0.size)
    j = int(np.argmax(g0 / h))                       # the worst possible start: the last cell to touch
    F[j] = load / h[j]
    F, theta, gap, P, it, res = _lawson_hanson(C, g0, h, load, F, 0, 2000, 1e-9)
    print(f"\nLawson-Hanson: {it} solves for {P.sum()} active cells")
    assert res < 1e-9 and 1 < P.sum() < g0.size
    assert np.allclose(F, ref.force, atol=1e-9 * ref.force.max())
    assert theta == pytest.approx(ref.approach, rel=1e-10)
