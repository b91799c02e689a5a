"""The loaded contact of one mesh position, written once for every gear kind.

A kind supplies its contact cells and their gaps; this module does the rest:

- :func:`cell_compliance`: the cells' compliance, the two bodies' FE far field interpolated to the cells plus the
  half-space near field between the cells of one tooth pair (Vijayakar's split: the coarse FE mesh carries the
  bodies' bending and the half-space the local contact flattening),
  ``C = W1 C1 W1' + W2 C2 W2' + sum_pairs N_pair``, symmetrised;
- :func:`solve_rounds`: the complementarity solve with torque balance (:func:`ltca.fem.contact.solve_contact`),
  repeated while the kind widens a cell window whose rim carries load (or adds a tooth pair the loaded rotation
  closes);
- :func:`root_stresses`: the fillet stresses of both bodies by superposition of their stored unit-load responses.

Units: mm, N, MPa, rad.
"""
from __future__ import annotations

from typing import Callable, Iterable

import numpy as np
import scipy.sparse as sp

from ltca.fem.contact import ContactNotConverged, ContactSolution, solve_contact

from .errors import ConvergenceError

__all__ = ["cell_compliance", "solve_rounds", "root_stresses"]


def cell_compliance(body1, W1: sp.spmatrix, body2, W2: sp.spmatrix,
                    near_blocks: Iterable[tuple[np.ndarray, np.ndarray]] | None) -> np.ndarray:
    """Compliance of the contact cells, (n, n) mm/N, symmetric.

    Parameters
    ----------
    body1, body2 : fem.compliance.BodyCompliance
        Each body's compliance ``C`` on its flank grid.
    W1, W2 : scipy.sparse matrix, (n, n_grid)
        Interpolation weights of the cells on each body's grid.
    near_blocks : iterable of (index array, (k, k) array), or None
        The half-space near field of each tooth pair's cells (indices into the n cells). None: no near field;
        the coarse FE alone is nearly singular at sub-element spacing, so a trace (1e-6 of the mean diagonal)
        regularises it.
    """
    C = np.asarray(W1 @ (W1 @ body1.C).T) + np.asarray(W2 @ (W2 @ body2.C).T)
    if near_blocks is None:
        C[np.diag_indices(len(C))] += 1e-6 * np.mean(np.diag(C))
    else:
        for idx, block in near_blocks:
            C[np.ix_(idx, idx)] += block
    return 0.5 * (C + C.T)


def solve_rounds(assemble: Callable[[], object], solve_args: Callable[[object], tuple],
                 grow: Callable[[object, ContactSolution], bool], rounds: int, where: str,
                 tol: float = 1e-9) -> tuple[object, ContactSolution]:
    """Solve one position's contact, again after each round in which the kind grows its cells.

    Parameters
    ----------
    assemble : callable () -> system
        Builds the kind's cell system from its current windows.
    solve_args : callable (system) -> (C, gap0, lever, torque, active0)
        The complementarity problem of the system: compliance (n, n), initial gaps (n,) along the lever's
        direction (mm), levers (n,) of the balanced torque (mm/rad), the torque (N mm), a starting active set or None.
    grow : callable (system, solution) -> bool
        Widens windows whose rim carries load (or adds pairs the loaded rotation closes); True to solve again.
    rounds : int
        At most this many solves.
    where : str
        Names the position in a convergence error.

    Raises
    ------
    ConvergenceError
        The contact problem did not converge (residual and advice in the message).
    """
    for _ in range(rounds):
        sy = assemble()
        C, gap0, lever, torque, active0 = solve_args(sy)
        try:
            sol = solve_contact(C, gap0, lever, torque, tol=tol, active0=active0)
        except ContactNotConverged as exc:
            raise ConvergenceError(where, exc.residual, exc.iterations, exc.advice) from None
        if not grow(sy, sol):
            break
    return sy, sol


def root_stresses(body1, W1: sp.spmatrix, body2, W2: sp.spmatrix, force: np.ndarray
                  ) -> tuple[dict[int, float], dict[int, float]]:
    """Largest principal fillet stress (MPa) per loaded tooth of each body under the cell forces (n,), N."""
    return body1.root_max(W1.T @ force), body2.root_max(W2.T @ force)
