"""The normal-contact complementarity problem of loaded tooth contact analysis.

Find cell forces F >= 0 and one rigid unknown theta (approach in mm, or rotation in rad) with

    gap = g0 + C F - h theta >= 0,    F . gap = 0,    h . F = load,

which is the KKT system of the convex quadratic programme  min 1/2 F'CF + g0'F  s.t.  F >= 0, h'F = load
(C symmetric positive definite; theta is the multiplier of the balance).

Method
------
1. Primal-dual active set (the Conry & Seireg 1971 / Kalker scheme; Hintermueller, Ito & Kunisch,
   SIAM J. Optim. 13 (2003) 865): on the active set A solve the saddle system
   [[C_AA, -h_A], [h_A', 0]] [F_A; theta] = [-g0_A; load] by a Cholesky factor of C_AA, then drop the
   cells with F < 0 and add the inactive cells with gap < 0, all at once.  Usually 3-10 iterations.
2. Anti-cycling: if an active set repeats, or the iteration stalls, switch to the primal active-set
   method of Lawson & Hanson (*Solving Least Squares Problems*, 1974, ch. 23) adapted to the balance
   constraint: feasible iterates, step back to the first force reaching zero, add the most violated cell.
   The objective decreases strictly, so no set repeats and the method terminates.

The cold start solves a Winkler (diagonal) version of the problem for theta and activates the cells that
it loads; ``active0`` warm-starts from the previous mesh position.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import LinAlgError, cho_factor, cho_solve

__all__ = ["ContactSolution", "ContactNotConverged", "solve_contact"]

_ADVICE = "refine the contact grid, increase max_iter, or warm-start with active0 from a nearby position"


class ContactNotConverged(RuntimeError):
    """The contact solver stopped before meeting ``tol``.

    Attributes
    ----------
    residual : float
        Relative complementarity / balance violation reached.
    iterations : int
        Linear solves performed.
    advice : str
        What to try.
    """

    def __init__(self, residual: float, iterations: int, advice: str = _ADVICE):
        self.residual, self.iterations, self.advice = float(residual), int(iterations), advice
        super().__init__(f"contact solve did not converge after {iterations} iterations "
                         f"(residual {residual:.3e}); try: {advice}")


@dataclass(frozen=True)
class ContactSolution:
    """Result of :func:`solve_contact`.

    Attributes
    ----------
    force : ndarray, shape (n,)
        Normal force per cell, N, >= 0.
    approach : float
        The rigid unknown theta (mm if h = 1, rad if h are lever arms in mm).
    gap : ndarray, shape (n,)
        Loaded gap, mm, >= 0; exactly 0 on active cells, +inf where g0 is +inf.
    iterations : int
        Number of linear (Cholesky) solves.
    residual : float
        max of: penetration / deflection scale, ``|gap|`` on active cells / deflection scale,
        ``|h.F - load| / load``, measured on the raw (unclipped) solution.
    active : ndarray of bool, shape (n,)
        Cells carrying load.
    """

    force: np.ndarray
    approach: float
    gap: np.ndarray
    iterations: int
    residual: float
    active: np.ndarray


def _check_inputs(C, g0, h, load, active0, tol, max_iter):
    C = np.asarray(C, dtype=float)
    g0 = np.asarray(g0, dtype=float)
    if g0.ndim != 1 or g0.size == 0:
        raise ValueError(f"g0 has shape {g0.shape}: must be a non-empty 1-D array (n,) of gaps in mm")
    n = g0.size
    if C.shape != (n, n):
        raise ValueError(f"C has shape {C.shape}: must be ({n}, {n}) to match g0")
    if np.isnan(g0).any() or np.isneginf(g0).any():
        raise ValueError("g0 contains NaN or -inf: gaps must be finite or +inf (cell can never touch)")
    h = np.broadcast_to(np.asarray(h, dtype=float), (n,))
    fin = np.isfinite(g0)
    if not fin.any():
        raise ValueError("g0 is +inf everywhere: no cell can touch, the load cannot be carried")
    if not (np.isfinite(h[fin]).all() and (h[fin] > 0).all()):
        bad = h[fin][~(np.isfinite(h[fin]) & (h[fin] > 0))][0]
        raise ValueError(f"h = {bad!r} on a cell with finite g0: lever arms must be finite and > 0")
    if not (np.isfinite(load) and load > 0):
        raise ValueError(f"load = {load!r}: must be finite and > 0 (N, or N mm with lever arms)")
    if not (np.isfinite(tol) and tol > 0):
        raise ValueError(f"tol = {tol!r}: must be finite and > 0")
    if int(max_iter) != max_iter or max_iter < 1:
        raise ValueError(f"max_iter = {max_iter!r}: must be an integer >= 1")
    idx = np.flatnonzero(fin)
    Cf = C if idx.size == n else C[np.ix_(idx, idx)]          # no copy in the common case
    if not np.isfinite(Cf.sum()) and not np.isfinite(Cf).all():  # one cheap pass first
        raise ValueError("C contains non-finite values on cells with finite g0")
    mask0 = None
    if active0 is not None:
        a0 = np.asarray(active0)
        if a0.dtype == bool:
            if a0.shape != (n,):
                raise ValueError(f"active0 has shape {a0.shape}: a boolean mask must have shape ({n},)")
            mask0 = a0.copy()
        else:
            if a0.size and (a0.min() < 0 or a0.max() >= n):
                raise ValueError(f"active0 holds indices outside [0, {n - 1}]")
            mask0 = np.zeros(n, bool)
            mask0[a0.astype(int)] = True
        mask0 = mask0[idx]
    return Cf, g0[idx], np.ascontiguousarray(h[idx]), float(load), mask0, idx, n


def _winkler(c, g0, h, load):
    """Diagonal (Winkler) problem F_i = max(0, (h_i theta - g0_i) / c_i), h.F(theta) = load, solved
    exactly on the sorted break points (h.F is piecewise linear and increasing in theta)."""
    k = h * h / c                                 # d(h_i F_i)/d theta once cell i is loaded
    t = g0 / h                                    # theta at which cell i starts to touch
    order = np.argsort(t)
    ts, ks = t[order], k[order]
    cum_k = np.cumsum(ks)
    theta = (load + np.cumsum(ks * ts)) / cum_k   # theta if exactly the first j+1 cells are loaded
    j = int(np.argmax(theta <= np.append(ts[1:], np.inf)))
    return np.maximum(0.0, (h * theta[j] - g0) / c)


def _winkler_start(Cf, g0, h, load, sweeps=1):
    """Cold-start active set: Winkler solutions with springs diag(C) scaled by the energy ratio
    F'CF / F'diag(C)F of the previous sweep (cheap: one matvec per sweep)."""
    c = np.diag(Cf).copy()
    for _ in range(sweeps):
        F = _winkler(c, g0, h, load)
        c *= (F @ (Cf @ F)) / (F @ (c * F))       # energy-weighted spring scale
    F = _winkler(c, g0, h, load)
    # Winkler over-estimates the contact extent (Hertz: by sqrt 2 in radius, the Winkler region being
    # where g0 < approach instead of g0 < approach / 2): keep the cells within half the approach.
    t = g0 / h
    on = F > 0
    return t <= 0.5 * (t.min() + t[on].max())


def _solve_active(Cf, g0, h, load, A):
    """Saddle solve on the active mask A: returns F_A, theta (raises LinAlgError if C_AA not SPD)."""
    cf = cho_factor(Cf[np.ix_(A, A)], lower=True, overwrite_a=True, check_finite=False)
    rhs = np.column_stack([g0[A], h[A]])
    u, v = cho_solve(cf, rhs, check_finite=False).T
    hA = h[A]
    theta = (load + hA @ u) / (hA @ v)
    return theta * v - u, theta


def _gaps(Cf, g0, h, F, theta):
    """Loaded gaps and elastic deflections C F (F is zero off the active set; one dense matvec,
    cheaper than copying the active columns)."""
    defl = Cf @ F
    return g0 + defl - h * theta, defl


def _residual(h, load, F, gap, defl, A):
    scale = max(np.abs(defl[A]).max() if A.any() else 1.0, np.finfo(float).tiny)
    r = [abs(h @ F - load) / load, max(0.0, -gap.min()) / scale]
    if A.any():
        r.append(np.abs(gap[A]).max() / scale)
        r.append(max(0.0, -F.min()) / max(F.max(), np.finfo(float).tiny))
    return float(max(r)), scale


def _lawson_hanson(Cf, g0, h, load, F, it, max_iter, tol):
    """Primal active set with feasible iterates (F >= 0, h.F = load); see module docstring."""
    P = F > 0
    blocked = np.zeros(F.size, bool)
    while True:
        added = None
        while True:                                   # inner loop: optimum on P with step-back
            if it >= max_iter:
                raise _Stop(it)
            it += 1
            z, theta = _solve_active(Cf, g0, h, load, P)
            if (z > 0).all():
                F[:] = 0.0
                F[P] = z
                break
            FP = F[P]
            neg = z <= 0
            ratios = FP[neg] / (FP[neg] - z[neg])
            k = int(np.argmin(ratios))
            alpha = ratios[k]
            FP = FP + alpha * (z - FP)
            FP[np.flatnonzero(neg)[k]] = 0.0              # the blocking cell leaves exactly
            FP[FP <= 0] = 0.0
            F[P] = FP
            idx = np.flatnonzero(P)
            P[idx[FP <= 0]] = False
            if added is not None and not P[added] and alpha == 0.0:
                blocked[added] = True                  # numerically degenerate: do not re-add at once
        if added is not None and P[added]:
            blocked[:] = False
        gap, defl = _gaps(Cf, g0, h, F, theta)
        res, scale = _residual(h, load, F, gap, defl, P)
        cand = np.where(P | blocked, np.inf, gap)
        j = int(np.argmin(cand))
        if res <= tol or not cand[j] < -tol * scale:
            return F, theta, gap, P, it, res
        P[j] = True
        added = j


class _Stop(Exception):
    def __init__(self, it):
        self.it = it


def solve_contact(C, g0, h, load: float, active0=None, tol: float = 1e-9,
                  max_iter: int = 200) -> ContactSolution:
    """Solve the frictionless normal contact problem with one rigid unknown.

    Parameters
    ----------
    C : ndarray, shape (n, n)
        Symmetric positive-definite compliance of both bodies at the cells, mm/N.
    g0 : ndarray, shape (n,)
        Initial (unloaded) gaps, mm; +inf marks cells that can never touch (they are dropped).
    h : ndarray, shape (n,) or float
        Lever arms > 0 (mm; theta in rad and load a torque in N mm), or 1 (theta an approach in mm,
        load a force in N).
    load : float
        Total load > 0, h . F = load.
    active0 : ndarray of bool (n,) or of int, optional
        Warm start (e.g. the active set of the previous mesh position). Default: Winkler estimate.
    tol : float
        Relative tolerance on penetration, active gaps and balance (see ContactSolution.residual).
    max_iter : int
        Maximum number of linear solves.

    Returns
    -------
    ContactSolution

    Raises
    ------
    ValueError
        Bad shapes or values (the message names the argument).
    ContactNotConverged
        ``max_iter`` reached or stagnation above ``tol``; carries residual, iterations, advice.
    """
    Cf, g0f, hf, load, mask0, idx, n = _check_inputs(C, g0, h, load, active0, tol, max_iter)
    A = mask0 if mask0 is not None and mask0.any() else _winkler_start(Cf, g0f, hf, load)
    seen = set()
    it = 0
    F = np.zeros(g0f.size)
    theta = 0.0
    res = np.inf
    try:
        while True:                                    # 1. primal-dual active set
            key = np.packbits(A).tobytes()
            if key in seen or it >= max_iter:
                break
            seen.add(key)
            it += 1
            FA, theta = _solve_active(Cf, g0f, hf, load, A)
            F[:] = 0.0
            F[A] = FA
            gap, defl = _gaps(Cf, g0f, hf, F, theta)
            res, scale = _residual(hf, load, F, gap, defl, A)
            add = ~A & (gap < -tol * scale)
            n_add = int(add.sum())
            if n_add > max(A.sum(), 8):                # grow at most geometrically: most violated first
                cut = np.partition(gap[add], int(A.sum()))[int(A.sum())]
                add &= gap < cut
            A_new = (A & (F > 0)) | add
            if not A_new.any():
                A_new[np.argmin(gap)] = True
            if np.array_equal(A_new, A) or (res <= tol and (F >= 0).all()):
                break
            A = A_new
        if not (res <= tol and (F >= 0).all()):        # 2. guaranteed fallback
            Ff = np.maximum(F, 0.0)
            if not (hf @ Ff > 0):
                Ff[:] = 0.0
                j = int(np.argmin(g0f / hf))
                Ff[j] = 1.0
            Ff *= load / (hf @ Ff)
            F, theta, gap, A, it, res = _lawson_hanson(Cf, g0f, hf, load, Ff, it, max_iter, tol)
    except _Stop as stop:
        raise ContactNotConverged(res, stop.it) from None
    except LinAlgError:
        raise ContactNotConverged(np.inf, it, "C is not positive definite on the active set: check for "
                                  "duplicated cells or a non-symmetric compliance") from None
    if not res <= tol:
        raise ContactNotConverged(res, it)
    force = np.zeros(n)
    force[idx] = np.maximum(F, 0.0)
    gap_out = np.full(n, np.inf)
    gap_out[idx] = np.where(A, 0.0, np.maximum(gap, 0.0))
    active = np.zeros(n, bool)
    active[idx] = A & (F > 0)
    return ContactSolution(force=force, approach=float(theta), gap=gap_out, iterations=int(it),
                           residual=float(res), active=active)
