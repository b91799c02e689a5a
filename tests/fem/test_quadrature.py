"""The facet quadrature of the surface loads (:mod:`ltca.fem.loads`): scikit-fem's degree-5 triangle rule is the
7-point rule of Strang & Fix 1973 (table 4.1), it and its uniform subdivisions integrate every polynomial of
degree 5 exactly (int over the unit triangle of x^a y^b = a! b! / (a + b + 2)!), and the patch loads are unit
forces."""
from __future__ import annotations

from math import factorial

import numpy as np
import pytest

from ltca.fem.loads import _base_rule, _triangle_rule


def test_base_rule_is_strang_fix_seven_points():
    pts, wts = _base_rule()
    # Strang & Fix 1973, table 4.1: the centroid (0.225) and the orbits (a, b, b) of the two other weights
    a1, b1, w1 = 0.0597158717897698, 0.4701420641051151, 0.1323941527885062
    a2, b2, w2 = 0.7974269853530873, 0.1012865073234563, 0.1259391805448271
    table = {(1 / 3, 1 / 3, 1 / 3): 0.225}
    for a, b, w in ((a1, b1, w1), (a2, b2, w2)):
        table.update({(a, b, b): w, (b, a, b): w, (b, b, a): w})
    assert len(pts) == 7
    for p, w in zip(pts, wts):
        key = min(table, key=lambda k: np.abs(np.subtract(k, p)).max())
        assert p == pytest.approx(key, abs=1e-13) and w == pytest.approx(table[key], abs=1e-13)


@pytest.mark.parametrize("refine", [0, 1, 2])
def test_rule_integrates_degree_five_exactly(refine):
    pts, wts = _triangle_rule(refine)
    assert len(wts) == 7 * 4 ** refine and wts.sum() == pytest.approx(1.0, abs=1e-14)
    x, y = pts[:, 1], pts[:, 2]
    for a in range(6):
        for b in range(6 - a):
            exact = factorial(a) * factorial(b) / factorial(a + b + 2)      # over the unit triangle, area 1/2
            assert 0.5 * wts @ (x ** a * y ** b) == pytest.approx(exact, rel=1e-12), (a, b)
    # and not degree 6 on the single triangle (the rule is what it says)
    if refine == 0:
        assert 0.5 * wts @ x ** 6 != pytest.approx(factorial(6) / factorial(8), rel=1e-6)
