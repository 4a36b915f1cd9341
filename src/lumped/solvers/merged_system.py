"""The merged linear system of one step with its modes fixed: assembly and solve.

With every element's piece fixed (:mod:`lumped.solvers.network_step`), the
points joined by rigid pieces are one unknown each (a cluster's root, the
others at fixed velocity offsets from it) and every free piece ``f = a + b w``
adds ``b`` between its points' unknowns and its known part to the load.  The
matrix is the inertias plus a weighted graph Laplacian: symmetric positive
definite, solved as a scalar, a dense matrix (up to 48 unknowns), a band
(a chain in file order is tridiagonal) or a sparse matrix.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

import numpy as np

from lumped.laws.step_graph import Piece

__all__ = ["assemble", "solve_merged"]

#: Largest unknown count solved as a dense matrix.
_DENSE = 48


class Topology(Protocol):
    """The points of the elements (``first``, ``second``) and the mass count."""

    first: Sequence[int]
    second: Sequence[int]
    n_mass: int


def assemble(
    topo: Topology,
    inertia: np.ndarray,
    rhs: np.ndarray,
    pieces: list[Piece],
    col: list[int],
    offset: list[float],
    size: int,
) -> tuple[dict, np.ndarray]:
    """The merged system as ``{(row, col): value}`` and its right-hand side."""
    entries: dict[tuple[int, int], float] = {}
    load = np.zeros(size)
    for i in range(topo.n_mass):
        c = col[i]
        if c >= 0:
            load[c] += rhs[i] - inertia[i] * offset[i]
            entries[c, c] = entries.get((c, c), 0.0) + inertia[i]
    for e, p in enumerate(pieces):
        i, j = topo.first[e], topo.second[e]
        ci, cj = col[i], col[j]
        if p.rigid or ci == cj:  # fixed rate, or inside one cluster: cancels
            continue
        known = p.a + p.b * (offset[j] - offset[i])
        for c, other, sign in ((cj, ci, 1.0), (ci, cj, -1.0)):
            if c < 0:
                continue
            load[c] -= sign * known
            if p.b:
                entries[c, c] = entries.get((c, c), 0.0) + p.b
                if other >= 0:
                    entries[c, other] = entries.get((c, other), 0.0) - p.b
    return entries, load


def solve_merged(entries: dict, load: np.ndarray) -> np.ndarray:
    """Solve the symmetric positive definite system: scalar, dense or band."""
    size = load.size
    if size == 0:
        return load
    if size == 1:
        return load / entries[0, 0]
    band = max(abs(r - c) for r, c in entries)
    if size <= _DENSE or band > 8:
        matrix = np.zeros((size, size))
        for (r, c), value in entries.items():
            matrix[r, c] = value
        if size <= _DENSE:
            return np.linalg.solve(matrix, load)
        from scipy.sparse import csc_matrix
        from scipy.sparse.linalg import spsolve

        return spsolve(csc_matrix(matrix), load)
    from scipy.linalg import solveh_banded  # here, as spsolve above: the command line starts without SciPy

    upper = np.zeros((band + 1, size))
    for (r, c), value in entries.items():
        if r <= c:
            upper[band + r - c, c] = value
    return solveh_banded(upper, load)
