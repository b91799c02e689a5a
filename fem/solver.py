"""Sparse direct factorisation of a stiffness matrix with fixed dofs condensed out.

One factorisation serves many right-hand sides (the compliance of a gear body is
``P K^-1 F`` for hundreds of unit loads). Back-ends, in the order ``"auto"`` tries them:

- ``"pardiso"``: MKL PARDISO through pypardiso, real symmetric positive definite
  (``mtype=2``, upper triangle only). About half the time and memory of
- ``"pardiso-unsym"``: pypardiso's default real unsymmetric mode (``mtype=11``), kept for
  comparison and as a fallback.
- ``"cholmod"``: scikit-sparse CHOLMOD (supernodal Cholesky), when importable.
- ``"cvxopt"``: CHOLMOD (supernodal Cholesky, AMD ordering) as shipped in cvxopt's wheels with OpenBLAS, for
  every platform pip serves (pypardiso is x86-64 only): ``pip install ltca[nomkl]``. cvxopt's dense solve takes
  one right-hand side per pass over the factor, its sparse solve (:func:`_cvxopt`) several: the loads and the
  observed rows are sparse, so they go through the sparse one.
- ``"splu"``: scipy SuperLU; always available, far slower beyond ~50k dofs.

``"auto"`` logs (module logger, INFO) which back-end factorised each matrix.

Measured on the 2-core machine: see docs/design.md, "Measurements".

Back-substitution (FZG C14 pinion body: 63k free dofs, 216 patch loads, 1476 observed rows):

- MKL's default ``iparm(8) = 2`` (which pypardiso inherits) runs two steps of iterative refinement
  in *every* phase-33 solve: three back-substitutions plus two residuals, about 3.5 times one plain
  solve. A Cholesky factor without perturbed pivots needs no refinement (the answers agree to 6e-13
  relative), so it is switched off when ``iparm(14) == 0``.
- MKL's partial solve (``iparm(31)``, sparse right-hand sides and selected solution components) is
  not used: it takes effect only when set before the analysis phase, and then the factorisation is
  about 8 times slower for a solve no faster than the plain one.
- With `observe`, ``observe @ K^-1 @ F = (K^-1 @ observe.T).T @ F`` (K symmetric), so the cheaper
  side is solved for: the loads when ``k <= r``, the observed rows when ``r < k``.
- Around the factor: PARDISO is called directly (:mod:`ltca.fem.pardiso`: no zeroed and C-reordered copy of the
  solution, no SHA-1 of the matrix), the observed rows gather only the solution rows they read
  (:class:`_Gather`), and the free block is cut in one pass over K (:func:`_free_block`).
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import Any, Callable

import numpy as np
import scipy.sparse as sp

__all__ = ["Factorization", "SubspaceFactorization", "factorize", "available_methods", "nested_dissection"]

_METHODS = ("auto", "pardiso", "pardiso-unsym", "cholmod", "cvxopt", "splu")
_log = logging.getLogger(__name__)


def available_methods() -> list[str]:
    """Back-ends importable here, best first (``"splu"`` always)."""
    out = []
    try:
        from .pardiso import mkl_rt_path
        mkl_rt_path()     # before the import: pypardiso builds a solver at import time, which searches for MKL
        import pypardiso  # noqa: F401
        out += ["pardiso", "pardiso-unsym"]
    except ImportError:
        pass
    try:
        import sksparse.cholmod  # noqa: F401
        out.append("cholmod")
    except ImportError:
        pass
    try:
        import cvxopt.cholmod  # noqa: F401
        out.append("cvxopt")
    except ImportError:
        pass
    return out + ["splu"]


@dataclass
class Factorization:
    """A factorised stiffness matrix, reusable for many right-hand sides.

    Attributes
    ----------
    free : ndarray of int, (n_free,)
        Free dofs (the complement of the fixed dofs), sorted.
    method : str
        Back-end used: ``"pardiso"``, ``"pardiso-unsym"``, ``"cholmod"``, ``"cvxopt"`` or ``"splu"``.
    n : int
        Full number of dofs, ``3 * N``.
    """

    free: np.ndarray
    method: str
    n: int
    _solve_free: Callable[[np.ndarray], np.ndarray] = field(repr=False)
    _release: Callable[[], None] | None = field(default=None, repr=False)
    _solve_sparse: Callable[[sp.csc_matrix], np.ndarray] | None = field(default=None, repr=False)

    def solve(self, F: Any, observe: sp.spmatrix | np.ndarray | None = None,
              block: int | None = None) -> np.ndarray:
        """Displacements for full-size loads.

        Parameters
        ----------
        F : array_like or sparse, (n,) or (n, k)
            Nodal loads [N] on all dofs (entries on fixed dofs are ignored: reactions).
        observe : sparse or ndarray, (r, n), optional
            If given, return ``observe @ u`` instead of ``u`` (e.g. an
            `interpolation_matrix`), computed block by block so that the full
            (n, k) displacement array never exists. When ``r < k`` the r observed
            rows are solved for instead of the k loads (``K`` is symmetric).
        block : int, optional
            Right-hand sides per back-substitution; default keeps a block near 400 MB.

        Returns
        -------
        ndarray, (n,) or (n, k), or (r,) or (r, k) with `observe`
            Displacements [mm], exactly 0 on fixed dofs.
        """
        vector = (not sp.issparse(F)) and np.ndim(F) == 1
        if self._solve_sparse is not None and not vector and not sp.issparse(F):
            F = sp.csc_matrix(np.asarray(F, dtype=float))   # loads on a few surface nodes: the sparse solve
        if sp.issparse(F):
            F = sp.csc_matrix(F)
        else:
            F = np.asarray(F, dtype=float)
            F = F[:, None] if F.ndim == 1 else F
        if F.ndim != 2 or F.shape[0] != self.n:
            raise ValueError(f"F: shape {F.shape} must be ({self.n},) or ({self.n}, k)")
        if observe is not None and observe.shape[1] != self.n:
            raise ValueError(f"observe: shape {observe.shape} must be (r, {self.n})")
        k = F.shape[1]
        if block is None:
            block = max(1, int(5e7 // max(self.free.size, 1)))
        if block < 1:
            raise ValueError(f"block = {block}: must be >= 1")
        obs_free = None if observe is None else sp.csr_matrix(observe)[:, self.free]
        if obs_free is not None and obs_free.shape[0] < k:
            # fewer observed rows than loads: solve for the rows (K symmetric) and contract
            out = self._solve_observed(obs_free, F[self.free], block)
            return out[:, 0] if vector else out
        rows = self.n if observe is None else observe.shape[0]
        out = np.zeros((rows, k))
        reads = None if obs_free is None else _Gather(obs_free)
        for s in range(0, k, block):
            b = F[:, s:s + block][self.free]
            if sp.issparse(b) and self._solve_sparse is not None:
                x = self._solve_sparse(b)
            else:
                b = b.toarray(order="F") if sp.issparse(b) else np.asfortranarray(b)
                x = self._solve_free(b).reshape(b.shape)
            if reads is None:
                out[self.free, s:s + block] = x
            else:
                out[:, s:s + block] = reads @ x
        return out[:, 0] if vector else out

    def _solve_observed(self, obs_free: sp.csr_matrix, F_free: Any, block: int) -> np.ndarray:
        """``obs_free @ Kff^-1 @ F_free`` as ``(Kff^-1 @ obs_free.T).T @ F_free``, block by block."""
        r = obs_free.shape[0]
        out = np.zeros((r, F_free.shape[1]))
        obs_t = sp.csc_matrix(obs_free.T)
        loads = _Gather(sp.csr_matrix(F_free.T))
        for s in range(0, r, block):
            if self._solve_sparse is not None:
                y = self._solve_sparse(obs_t[:, s:s + block])
            else:
                b = obs_t[:, s:s + block].toarray(order="F")
                y = self._solve_free(b).reshape(b.shape)
            out[s:s + block] = (loads @ y).T
        return out

    def release(self) -> None:
        """Free the back-end's factor memory now (PARDISO keeps it outside Python)."""
        if self._release is not None:
            self._release()
            self._release = None

    def __del__(self) -> None:  # noqa: D105
        try:
            self.release()
        except Exception:  # interpreter shutdown: nothing useful to do
            pass


@dataclass
class SubspaceFactorization:
    """A factorisation of a stiffness on a subspace ``u = T v`` of the displacements, solving for full-size loads.

    The body's stiffness in ``v`` (e.g. the serendipity hexahedra of :mod:`ltca.fem.serendipity`) is factorised by
    ``inner``; loads and read-outs stay on the full dofs: ``u = T K_v^-1 T^T F``.

    Attributes
    ----------
    inner : Factorization
        Of the stiffness in v, (n_v, n_v).
    T : scipy.sparse.csr_matrix, (n, n_v)
        The full dofs of v.
    """

    inner: Factorization
    T: sp.csr_matrix = field(repr=False)

    @property
    def method(self) -> str:
        """The back-end of ``inner``."""
        return self.inner.method

    @property
    def n(self) -> int:
        """Full number of dofs."""
        return self.T.shape[0]

    def solve(self, F: Any, observe: sp.spmatrix | np.ndarray | None = None,
              block: int | None = None) -> np.ndarray:
        """Displacements for full-size loads, as :meth:`Factorization.solve` (same shapes and ``observe``)."""
        if (F.shape if sp.issparse(F) else np.shape(F))[0] != self.n:
            raise ValueError(f"F: shape {np.shape(F)} must be ({self.n},) or ({self.n}, k)")
        Fv = self.T.T @ F
        if observe is None:
            return self.T @ self.inner.solve(Fv, block=block)
        if observe.shape[1] != self.n:
            raise ValueError(f"observe: shape {observe.shape} must be (r, {self.n})")
        return self.inner.solve(Fv, observe=sp.csr_matrix(observe @ self.T), block=block)

    def release(self) -> None:
        """Free the back-end's factor memory now."""
        self.inner.release()


class _Gather:
    """``A @ X`` for a sparse ``A`` (r, n) that reads few of the n rows of a tall dense ``X`` (n, k) in either memory
    order: the rows read are gathered first. scipy's own product copies a Fortran-ordered ``X`` (the order
    PARDISO returns) whole into C order, about 0.5 s on a 68k x 216 back-substitution (0.09 s for this)."""

    def __init__(self, A: sp.csr_matrix):
        self.rows = np.unique(A.indices)
        self.A = A[:, self.rows]

    def __matmul__(self, X: np.ndarray) -> np.ndarray:
        return np.asarray(self.A @ X[self.rows])


def _free_block(K: sp.csr_matrix, free: np.ndarray, upper: bool = False) -> sp.csr_matrix:
    """``K[free][:, free]`` for a boolean mask ``free``, with ``upper`` its upper triangle (``sp.triu``), by one
    pass over K's entries: the same matrix (explicit zeros kept, each row in K's order). scipy's column fancy
    indexing and ``triu`` took 0.15-0.3 s on a 68k-dof gear body."""
    K.sum_duplicates()
    rows = np.repeat(np.arange(K.shape[0]), np.diff(K.indptr))
    keep = free[rows] & free[K.indices]
    if upper:
        keep &= K.indices >= rows
    new = np.cumsum(free) - 1
    m = int(new[-1]) + 1
    indptr = np.zeros(m + 1, dtype=np.int64)
    np.cumsum(np.bincount(new[rows[keep]], minlength=m), out=indptr[1:])
    return sp.csr_matrix((K.data[keep], new[K.indices[keep]], indptr), shape=(m, m))


def _cholmod(Kff: sp.csr_matrix):
    from sksparse.cholmod import cholesky

    fac = cholesky(sp.csc_matrix(Kff))
    return (lambda b: fac(b)), None


def nested_dissection(A: sp.csr_matrix, block: int = 1) -> np.ndarray | None:
    """A fill-reducing ordering of a symmetric sparse matrix: METIS's nested dissection (pymetis) of its graph.

    Parameters
    ----------
    A : scipy.sparse.csr_matrix, (m, m)
        Its pattern is the graph (both triangles).
    block : int
        Rows come in consecutive groups of this many sharing one pattern (the 3 dofs of a node): the graph of the
        groups is ordered, each group's rows kept together (a graph ``block**2`` times smaller).

    Returns
    -------
    ndarray of int, (m,) or None
        ``perm`` with row ``perm[k]`` eliminated k-th; None where pymetis is not installed.
    """
    try:
        import pymetis
    except ImportError:
        return None
    m = A.shape[0]
    if block < 1 or m % block:
        raise ValueError(f"block = {block}: must divide the {m} rows")
    rows = np.repeat(np.arange(m), np.diff(A.indptr)) // block
    G = sp.csr_matrix((np.ones(A.nnz, dtype=np.int32), (rows, A.indices // block)), shape=(m // block, m // block))
    G = sp.csr_matrix(G + G.T)
    G.setdiag(0)
    G.eliminate_zeros()
    graph = getattr(pymetis, "CSRAdjacency", None)
    if graph is not None:
        perm, _ = pymetis.nested_dissection(adjacency=graph(G.indptr, G.indices))
    else:                                           # pymetis before 2025.2
        perm, _ = pymetis.nested_dissection(xadj=G.indptr, adjncy=G.indices)
    perm = np.asarray(perm, dtype=np.int64)
    return (block * perm[:, None] + np.arange(block)).ravel()


def _cvxopt(Kff: sp.csr_matrix, block: int = 1):
    """CHOLMOD through cvxopt: supernodal ``P K P' = L L'`` of the lower triangle, P METIS's nested dissection
    (:func:`nested_dissection`) where pymetis is installed, else CHOLMOD's own AMD.

    On the spiral bevel gear body (206 k dofs) METIS's ordering cut cvxopt's numerical factorisation from 24.9 s to
    8.2 s (AMD leaves about three times the flops; cvxopt's CHOLMOD has no METIS of its own), for 0.4 s of ordering.

    Returns ``solve(b)`` for dense b (m,) or (m, k), and ``solve_sparse(B)`` for a sparse B (m, k) giving a dense
    (m, k) array. cvxopt's dense ``cholmod.solve`` calls CHOLMOD once per column, a pass over the whole factor for
    each (memory-bound: about 0.09 s a column on a 68k-dof gear body), while its ``cholmod.spsolve`` hands CHOLMOD
    all columns at once, which solves them a few at a time per pass."""
    from cvxopt import cholmod, matrix, spmatrix

    def cvx_sparse(A) -> spmatrix:
        A = A.tocoo()
        return spmatrix(matrix(A.data.astype(np.float64)), matrix(A.row.astype(np.int64)),
                        matrix(A.col.astype(np.int64)), A.shape)

    low = cvx_sparse(sp.tril(Kff))
    perm = nested_dissection(Kff, block)
    _log.info("cvxopt CHOLMOD ordering: %s", "AMD (pymetis not installed)" if perm is None else "METIS")
    options = dict(cholmod.options)
    cholmod.options["supernodal"] = 2
    try:
        fac = cholmod.symbolic(low, uplo="L") if perm is None else \
            cholmod.symbolic(low, p=matrix(perm.astype(int)), uplo="L")
        cholmod.numeric(low, fac)
    finally:
        cholmod.options.clear()
        cholmod.options.update(options)
    del low

    def solve(b: np.ndarray) -> np.ndarray:
        x = matrix(np.array(b, dtype=np.float64, order="F").reshape(b.shape[0], -1))
        cholmod.solve(fac, x)
        return np.asarray(x).reshape(b.shape)

    def solve_sparse(B: sp.spmatrix) -> np.ndarray:
        B = sp.csc_matrix(B)
        out = np.zeros(B.shape, order="F")
        for s in range(0, B.shape[1], 64):      # CHOLMOD takes 4 columns a pass: chunks only bound the memory
            X = cholmod.spsolve(fac, cvx_sparse(B[:, s:s + 64]))
            ptr, rows, vals = (np.asarray(a).ravel() for a in X.CCS)
            cols = np.repeat(np.arange(X.size[1]), np.diff(ptr))
            out[rows.astype(np.int64), s + cols] = vals
        return out

    return solve, None, solve_sparse


def _splu(Kff: sp.csr_matrix):
    from scipy.sparse.linalg import splu

    lu = splu(sp.csc_matrix(Kff), permc_spec="MMD_AT_PLUS_A")
    return (lambda b: lu.solve(b)), None


def factorize(K: sp.spmatrix, fixed_dofs: np.ndarray, method: str = "auto") -> Factorization:
    """Factorise ``K`` restricted to the free dofs.

    Parameters
    ----------
    K : sparse, (n, n)
        Symmetric positive semi-definite stiffness [N/mm], e.g. `fem.elastic.assemble_stiffness`.
    fixed_dofs : ndarray of int or bool, (n_fixed,) or (n,)
        Dofs held at zero (indices, or a boolean mask of length n). Must remove the rigid-body modes.
    method : {"auto", "pardiso", "pardiso-unsym", "cholmod", "cvxopt", "splu"}
        Back-end; ``"auto"`` takes the first importable of pardiso, cholmod, cvxopt, splu and logs its choice.

    Returns
    -------
    Factorization
    """
    if method not in _METHODS:
        raise ValueError(f"method = {method!r}: must be one of {_METHODS}")
    if not sp.issparse(K) or K.shape[0] != K.shape[1]:
        raise ValueError(f"K: must be a square sparse matrix, got {type(K).__name__} "
                         f"of shape {getattr(K, 'shape', None)}")
    n = K.shape[0]
    fixed = np.asarray(fixed_dofs)
    mask = np.ones(n, dtype=bool)
    if fixed.dtype == bool:
        if fixed.shape != (n,):
            raise ValueError(f"fixed_dofs: boolean mask of shape {fixed.shape}, must be ({n},)")
        mask[fixed] = False
    else:
        fixed = fixed.astype(np.int64).ravel()
        if fixed.size and (fixed.min() < 0 or fixed.max() >= n):
            raise ValueError(f"fixed_dofs: indices in [{fixed.min()}, {fixed.max()}], "
                             f"allowed [0, {n - 1}]")
        mask[fixed] = False
    free = np.flatnonzero(mask)
    if free.size == 0:
        raise ValueError("fixed_dofs: all dofs are fixed, nothing to solve")
    K = sp.csr_matrix(K, dtype=np.float64)
    if method == "auto":
        method = available_methods()[0]
        _log.info("factorising %d free dofs with %s", free.size, method)
    # PARDISO's symmetric mode reads the upper triangle only
    Kff = _free_block(K, mask, upper=method == "pardiso")
    if method in ("pardiso", "pardiso-unsym"):
        from .pardiso import pardiso_factor
        solve, release = pardiso_factor(Kff, symmetric=method == "pardiso")
    elif method == "cholmod":
        solve, release = _cholmod(Kff)
    elif method == "cvxopt":
        # whole nodes held (the 3 dofs of a node free or fixed together): order the graph of the nodes
        f3 = free.reshape(-1, 3) if free.size % 3 == 0 else None
        triples = f3 is not None and not (f3[:, 0] % 3).any() and bool((np.diff(f3, axis=1) == 1).all())
        solve, release, solve_sparse = _cvxopt(Kff, 3 if triples else 1)
        return Factorization(free=free, method=method, n=n, _solve_free=solve, _release=release,
                             _solve_sparse=solve_sparse)
    else:
        solve, release = _splu(Kff)
    return Factorization(free=free, method=method, n=n, _solve_free=solve, _release=release)
