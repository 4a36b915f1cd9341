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
admissible ``dt`` below it.  ``A`` is factored by Cholesky for up to
:data:`DENSE_MASSES` masses; a larger network uses the sufficient
Gershgorin bound without the springs, ``m_i/dt > sum_e lambda_e (1 + [e joins
two masses])``.
"""

from __future__ import annotations

import math

import numpy as np

from lumped.model.network import Network

__all__ = ["DENSE_MASSES", "check_step", "largest_step"]

#: Largest network whose bound is the exact test of ``A(dt)`` (a dense Cholesky factorisation).
DENSE_MASSES = 2000


def _matrices(net: Network) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``M`` (diagonal, as a vector), ``K = B_s^T K B_s`` and ``L = B_f^T Lambda B_f`` over the masses."""
    n = len(net.masses)
    first, second = net.incidence()
    mass = np.array([m.mass for m in net.masses])
    k, lam = np.zeros((n, n)), np.zeros((n, n))
    for e, el in enumerate(net.elements):
        weight = el.linear_stiffness
        target = k
        if weight is None:
            weight, target = el.steepest_fall, lam
        if not weight:
            continue
        # weight * outer(b, b), b the element's incidence row (+1 at second, -1 at first, masses only),
        # added entry by entry: O(1) an element, not O(n^2) (the entries and their order of sums as before)
        i, j = int(first[e]), int(second[e])
        for p in (j, i):
            if p < n:
                target[p, p] += weight
        if i < n and j < n:
            target[i, j] -= weight
            target[j, i] -= weight
    return mass, k, lam


def _definite(mass: np.ndarray, k: np.ndarray, lam: np.ndarray, dt: float) -> bool:
    """True if ``A(dt)`` is positive definite (its Cholesky factorisation exists)."""
    try:
        np.linalg.cholesky(np.diag(mass / dt) + dt * k - lam)
    except np.linalg.LinAlgError:
        return False
    return True


def _gershgorin(net: Network, dt: float) -> bool:
    """The sufficient bound of a large network: ``m_i/dt`` above twice (once to a fixed point) each fall."""
    n = len(net.masses)
    first, second = net.incidence()
    load = np.zeros(n + 1)
    for e, el in enumerate(net.elements):
        lam = el.steepest_fall
        if lam:
            both = 2.0 if first[e] < n and second[e] < n else 1.0
            load[first[e]] += both * lam
            load[second[e]] += both * lam
    mass = np.array([m.mass for m in net.masses])
    return bool(np.all(mass / dt > load[:n]))


def _admissible(net: Network) -> object:
    """The test ``dt -> bool`` of the network."""
    if len(net.masses) > DENSE_MASSES:
        return lambda dt: _gershgorin(net, dt)
    mass, k, lam = _matrices(net)
    return lambda dt: _definite(mass, k, lam, dt)


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
