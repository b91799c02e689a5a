"""A generated bevel flank tabulated once and interpolated: the exact surface at the cost of a spline.

The LTCA's gap evaluator asks a flank for its point and normal at flank coordinates (t, L) (depth fraction,
cone distance) thousands of times per mesh cycle, in small batches; each exact answer is a Newton solve of the
equation of meshing (:func:`ltca.geometry.bevel.generation.solve_axial_points`), about a dozen blade evaluations. The
flank does not change with the torque, the mounting errors or the position, so it is solved once on a node grid
and interpolated: the polar angle a(t, L) of the point in its axial section (Z, rho)(t, L) -- which puts the
point exactly in that section, as the exact solve does -- and the unit normal, by bicubic splines
(:class:`scipy.interpolate.RectBivariateSpline`).

The generated flank is not smooth everywhere: where the blade's straight part meets its edge radius the surface's
curvature jumps, and a spline across that line is wrong by micrometres and rings for several cells. So the table
holds *smooth branches* -- for a bevel flank, the surface that the straight part of the blade generates,
continued past its tangency with the edge radius -- each with a validity field w(t, L) (there the blade
parameter u, mm, >= 0 on the straight part): a branch serves a point only where its w > ``margin``, i.e. where
the real flank is that branch; everything else (the fillet, the edge of the branch) is solved exactly, and
points far outside the box are not solved at all. (The edge circle's branch, continued, folds between roots of
the equation of meshing a few tenths of a millimetre from where it is the flank; it is left exact.)

Every cell is also checked at build time: the spline against the smooth branch at the cell's centre; a cell off by
more than ``tol`` (position, mm) or ``10 tol`` (normal), or with an unsolved node, is marked, with its neighbours,
and left to the exact solve (measured in ``tests/geometry/bevel/test_bevel_surface_table.py`` at random points: the
largest error,
not the centre's).
"""
from __future__ import annotations

from typing import Callable, Sequence

import numpy as np
from scipy.interpolate import RectBivariateSpline

__all__ = ["SurfaceTable"]

Exact = Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]
Smooth = Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]


class _Branch:
    """Bicubic splines of one smooth branch over the rows of the box where it solves, cells checked."""

    def __init__(self, smooth: Smooth, axial: Callable, t: np.ndarray, L: np.ndarray, tol: float, reach: float):
        self._axial = axial
        # the rows of the box where the branch is tabulated, then the same number of rows over just those rows (a
        # fillet branch spans a tenth of the depth and is curved on the edge radius)
        found = self._rows(smooth, t, L, reach)
        self.usable = found is not None
        if not self.usable:
            return
        t = np.linspace(found[0][0], found[0][-1], len(t))
        found = self._rows(smooth, t, L, reach)
        self.usable = found is not None
        if not self.usable:
            return
        t, r, n, w = found
        self.t, self.L = t, L
        a = np.arctan2(r[..., 1], r[..., 0])
        self._a0 = float(np.median(a))
        self._sa = RectBivariateSpline(self.t, L, self._a0 + (a - self._a0 + np.pi) % (2 * np.pi) - np.pi)
        self._sn = [RectBivariateSpline(self.t, L, n[..., k]) for k in range(3)]
        self._sw = RectBivariateSpline(self.t, L, w, kx=1, ky=1)
        # every cell checked at its centre against the branch; marked cells (and their neighbours) are left to
        # the exact solve
        tc, Lc = 0.5 * (self.t[1:] + self.t[:-1]), 0.5 * (L[1:] + L[:-1])
        TC, LC = np.meshgrid(tc, Lc, indexing="ij")
        re, ne, oke, _ = smooth(TC.ravel(), LC.ravel())
        rs, ns = self.spline(TC.ravel(), LC.ravel())
        err = np.max(np.abs(rs - re), axis=-1)
        nerr = np.max(np.abs(ns - ne), axis=-1)
        bad = (~oke | ~(err <= tol) | ~(nerr <= 10 * tol)).reshape(TC.shape)
        grown = bad.copy()
        grown[1:] |= bad[:-1]
        grown[:-1] |= bad[1:]
        grown[:, 1:] |= grown[:, :-1].copy()
        grown[:, :-1] |= grown[:, 1:].copy()
        self.bad = grown

    @staticmethod
    def _rows(smooth: Smooth, t: np.ndarray, L: np.ndarray, reach: float):
        """The longest run of node rows where every node solves and lies within ``reach`` of where the branch is
        the flank (a branch continued far from there may fold, or jump between roots of the equation of
        meshing): (t, points, normals, w) of those rows, or None for fewer than 8."""
        T, LL = np.meshgrid(t, L, indexing="ij")
        r, n, ok, w = smooth(T.ravel(), LL.ravel())
        w = w.reshape(T.shape)
        rows = np.append((ok.reshape(T.shape) & (w > -reach)).all(1), False)
        best, i0 = (0, 0, 0), 0
        for k, good in enumerate(rows):
            if not good:
                if k - i0 > best[0]:
                    best = (k - i0, i0, k)
                i0 = k + 1
        n_rows, i0, i1 = best
        if n_rows < 8:
            return None
        return t[i0:i1], r.reshape(T.shape + (3,))[i0:i1], n.reshape(T.shape + (3,))[i0:i1], w[i0:i1]

    def spline(self, t: np.ndarray, L: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        Z, rho = self._axial(t, L)
        a = self._sa.ev(t, L)
        r = np.stack([rho * np.cos(a), rho * np.sin(a), Z], -1)
        n = np.stack([s.ev(t, L) for s in self._sn], -1)
        return r, n / np.linalg.norm(n, axis=-1, keepdims=True)

    def served(self, t: np.ndarray, L: np.ndarray, margin: float) -> np.ndarray:
        if not self.usable:
            return np.zeros(np.shape(t), bool)
        i = np.clip(np.searchsorted(self.t, t, side="right") - 1, 0, len(self.t) - 2)
        j = np.clip(np.searchsorted(self.L, L, side="right") - 1, 0, len(self.L) - 2)
        use = (t >= self.t[0]) & (t <= self.t[-1]) & (L >= self.L[0]) & (L <= self.L[-1]) & ~self.bad[i, j]
        use[use] = self._sw.ev(t[use], L[use]) > margin
        return use


class SurfaceTable:
    """Bicubic tables of a flank's smooth branches over a box of flank coordinates, exact where they cannot serve.

    Parameters
    ----------
    exact : callable
        ``exact(t, L) -> (points (n, 3), normals (n, 3), ok (n,))`` in the member's body frame, mm: the flank.
    axial : callable
        ``axial(t, L) -> (Z, rho)``, the axial-section place of flank coordinates, mm.
    t_box, L_box : (lo, hi)
        The box tabulated: depth fraction and cone distance (mm). Each branch keeps the longest run of node
        rows that all solve; a branch of fewer than 8 rows serves nothing.
    shape : (nt, nL)
        Nodes in t and L (>= 8 each).
    tol : float
        Largest position error accepted at a cell's centre, mm (normals: ``10 tol``).
    branches : sequence of callables
        ``smooth(t, L) -> (points, normals, ok, w (n,))``: a smooth branch and its validity field (the flank is
        this branch where w > 0). Default: ``exact`` with w = 1 (a flank smooth everywhere).
    margin : float
        A branch serves where its interpolated w exceeds this (the units of w).
    reach : float
        A branch is tabulated over the rows of nodes whose w all exceed ``-reach``.
    """

    def __init__(self, exact: Exact, axial: Callable, t_box: tuple[float, float], L_box: tuple[float, float],
                 shape: tuple[int, int] = (121, 41), tol: float = 1e-7, branches: Sequence[Smooth] = (),
                 margin: float = 1e-3, reach: float = 0.5):
        nt, nl = shape
        if min(nt, nl) < 8:
            raise ValueError(f"shape = {shape!r}: at least 8 nodes in t and in L")
        self._exact, self.tol, self.margin = exact, float(tol), float(margin)
        self.box = (*t_box, *L_box)
        t, L = np.linspace(*t_box, nt), np.linspace(*L_box, nl)
        branches = branches or [lambda t, L: (*exact(t, L), np.ones(np.shape(t)))]
        self.branches = [_Branch(b, axial, t, L, self.tol, reach) for b in branches]

    def served(self, t: np.ndarray, L: np.ndarray) -> np.ndarray:
        """(n,) int: the branch that answers each point, -1 where none does (solved exactly)."""
        which = np.full(np.shape(t), -1)
        for k, b in enumerate(self.branches):
            free = which < 0
            use = np.zeros(np.shape(t), bool)
            use[free] = b.served(t[free], L[free], self.margin)
            which[use] = k
        return which

    def surface(self, t: np.ndarray, L: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Points, unit normals (body frame) and solved flags at flank coordinates (n,): a table where one
        serves, the exact solve elsewhere, nothing far outside the box (NaN, not solved)."""
        t, L = np.asarray(t, float).ravel(), np.asarray(L, float).ravel()
        which = self.served(t, L)
        r = np.full((len(t), 3), np.nan)
        n = np.full((len(t), 3), np.nan)
        ok = np.ones(len(t), bool)
        for k, b in enumerate(self.branches):
            use = which == k
            if use.any():
                r[use], n[use] = b.spline(t[use], L[use])
        far = (which < 0) & ((t < self.box[0]) | (t > self.box[1]) | (L < self.box[2]) | (L > self.box[3]))
        ok[far] = False
        rest = (which < 0) & ~far
        if rest.any():
            r[rest], n[rest], ok[rest] = self._exact(t[rest], L[rest])
        return r, n, ok
