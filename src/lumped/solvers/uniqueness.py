"""When a backward-Euler step of a network with falling friction is unique: the bound on ``dt``.

With every mode fixed, one backward-Euler step minimises the potential of
:class:`lumped.model.network.Network` (Notes).  A friction contact whose slip
curve falls with slope up to ``lambda_e`` (``Element.steepest_fall``) adds a
term whose second derivative is at least ``-lambda_e``; the springs add
``dt k_e``.  So the step's potential, in the masses' velocities, is strictly
convex, and the step unique (under the contacts' rule), when

    A(dt) = M/dt + dt B_s^T K B_s - B_f^T Lambda B_f

is positive definite (``B`` the incidence rows of the springs and of the
falling contacts, masses only: the ground and the driven points have no
unknown velocity).  Other elements are monotone and only add to ``A``; they
are left out, so the bound is sufficient for every network and exact for one
mass with springs and one contact: ``m/dt + k dt > lambda``.

:func:`check_step` refuses a ``dt`` that fails it, naming the largest
admissible ``dt`` below it.  ``A`` is sparse (a chain is tridiagonal) and is
factored by a sparse ``L D L^T`` for up to :data:`EXACT_MASSES` masses; a
larger network uses the sufficient Gershgorin bound without the springs,
``m_i/dt > sum_e lambda_e (1 + [e joins two masses])``, which is below the
exact bound (the springs only add to ``A``, and a Gershgorin disc holds every
eigenvalue of ``L`` scaled by ``M^-1``).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

from lumped.model.network import Network

__all__ = ["EXACT_MASSES", "check_step", "largest_step"]

#: Largest network whose bound is the exact test of ``A(dt)`` (a sparse ``L D L^T`` factorisation per probe,
#: whose fill a general network's graph may make dense).
EXACT_MASSES = 2000


def _entries(net: Network) -> tuple[np.ndarray, dict, dict]:
    """``M`` (diagonal, as a vector) and the entries ``{(row, column): value}`` of ``K = B_s^T K B_s`` and
    ``L = B_f^T Lambda B_f`` over the masses (each element adds ``weight * outer(b, b)``, ``b`` its incidence row:
    +1 at second, -1 at first, masses only), summed in the elements' order: O(1) an element."""
    n = len(net.masses)
    first, second = net.incidence()
    mass = np.array([m.mass for m in net.masses])
    k: dict = {}
    lam: dict = {}
    for e, el in enumerate(net.elements):
        weight = el.linear_stiffness
        target = k
        if weight is None:
            weight, target = el.steepest_fall, lam
        if not weight:
            continue
        i, j = int(first[e]), int(second[e])
        for p in (j, i):
            if p < n:
                target[p, p] = target.get((p, p), 0.0) + weight
        if i < n and j < n:
            for pair in ((i, j), (j, i)):
                target[pair] = target.get(pair, 0.0) - weight
    return mass, k, lam


class _Sparse:
    """``A(dt)`` of a network as a sparse matrix, built once, factored per ``dt`` by a sparse ``L D L^T``.

    Each probe's matrix has the entries of ``diag(M/dt) + dt K - L`` (the dense matrix's, summed in the same
    order).  SuperLU factors it in a fill-reducing symmetric order (minimum degree on ``A + A^T``) with the
    diagonal as pivot (``diag_pivot_thresh = 0``, symmetric mode), so ``A = P^T L U P`` with ``U = D L^T``: by
    Sylvester's law of inertia ``A`` is positive definite exactly when every pivot ``D`` is positive.  SuperLU
    leaves the diagonal only for a pivot that is exactly zero (the rows then permuted unlike the columns), or
    stops at a singular factor: in both cases ``A`` is not definite.  A probe costs what the factor's fill costs
    (``O(n)`` for a chain or a star, against a dense Cholesky's ``O(n^3)``).
    """

    def __init__(self, mass: np.ndarray, k: dict, lam: dict) -> None:
        n = len(mass)
        self.mass, self.k, self.lam = mass, self._matrix(k, n), self._matrix(lam, n)

    @staticmethod
    def _matrix(entries: dict, n: int) -> sp.csc_matrix:
        """The entries as an ``n x n`` sparse matrix."""
        rows = [r for r, _ in entries]
        cols = [c for _, c in entries]
        return sp.csc_matrix((list(entries.values()), (rows, cols)), shape=(n, n))

    def definite(self, dt: float) -> bool:
        """True if ``A(dt)`` is positive definite (every pivot of its ``L D L^T`` factorisation positive)."""
        a = (sp.diags(self.mass / dt) + dt * self.k - self.lam).tocsc()  # the dense sum's order
        try:
            lu = splu(a, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        except RuntimeError:  # an exactly singular factor
            return False
        return bool(np.array_equal(lu.perm_r, lu.perm_c) and np.all(lu.U.diagonal() > 0))


def _gershgorin(net: Network) -> tuple[np.ndarray, np.ndarray]:
    """The masses and their loads in the sufficient bound of a large network, ``m_i/dt > load_i``: each fall
    counted twice at both its masses (once at a mass held to a fixed point), as a row of ``M^-1 L``'s Gershgorin
    disc reaches ``L_ii + sum_j |L_ij|``."""
    n = len(net.masses)
    first, second = net.incidence()
    load = np.zeros(n + 1)
    for e, el in enumerate(net.elements):
        lam = el.steepest_fall
        if lam:
            both = 2.0 if first[e] < n and second[e] < n else 1.0
            load[first[e]] += both * lam
            load[second[e]] += both * lam
    return np.array([m.mass for m in net.masses]), load[:n]


def _admissible(net: Network) -> object:
    """The test ``dt -> bool`` of the network (its matrices built once, each probe a factorisation or a
    comparison)."""
    if len(net.masses) > EXACT_MASSES:
        mass, load = _gershgorin(net)
        return lambda dt: bool(np.all(mass / dt > load))
    return _Sparse(*_entries(net)).definite


def largest_step(net: Network, dt: float) -> float:
    """The edge below ``dt`` (a step that fails the test) where the test starts to fail: ``dt`` halved
    until the test holds (it does as ``dt -> 0``, where ``M/dt`` dominates), then bisected to 1e-12
    relative between that admissible step and its double."""
    test = _admissible(net)
    lo = dt
    for _ in range(2100):  # 2^-2100 underflows: the test holds long before
        if test(lo):
            break
        lo /= 2
    hi = min(2 * lo, dt)
    while hi - lo > 1e-12 * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if test(mid) else (lo, mid)
    return lo


def _down(value: float) -> float:
    """``value`` rounded down to 3 significant digits (a step that is admissible as printed)."""
    scale = 10.0 ** (math.floor(math.log10(value)) - 2)
    return math.floor(value / scale) * scale


def check_step(net: Network, dt: float) -> None:
    """Refuse, in one ``ValueError``, a ``dt`` whose backward-Euler step may not be unique (see the module)."""
    falling = [el for el in net.elements if el.steepest_fall > 0]
    if not falling or _admissible(net)(dt):
        return
    steepest = max(falling, key=lambda el: el.steepest_fall)
    best = largest_step(net, dt)
    raise ValueError(
        f"dt: {dt:g} s is too long for a unique backward-Euler step: the tension of {steepest.name!r} falls with its rate "
        f"by up to {steepest.steepest_fall:.4g} N s/m, more than the masses' m/dt and the springs' k dt "
        f"outweigh; take dt <= {_down(best):.3g} s"
    )
