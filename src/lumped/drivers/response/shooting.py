"""Periodic motions by shooting: the fixed point of the exact period map, found by Newton with the monodromy matrix.

A motion of the forcing's period ``T = 2 pi/omega`` is a fixed point of the
period map ``Pi`` (:func:`lumped.drivers.response.systems.period_map`: one
mass's, :func:`lumped.solvers.monodromy.period_map`, or a network's,
:func:`lumped.solvers.network_monodromy.network_period_map`):
``Pi(z) = z`` with ``z`` the state at ``t = 0`` (``(x, v)``, or a network's
positions then velocities).  Newton's step solves ``(M - I) dz = -(Pi(z) -
z)`` with the analytic monodromy matrix ``M`` (stick phases included: their
projection makes ``M`` singular, never ``M - I``, but for a network's
element that sticks through the period, whose elongation is then free:
:func:`newton_step` keeps it).  Its eigenvalues are the Floquet multipliers:
the motion is stable when all lie inside the unit circle.

Lengths are measured in the units of the problem: ``X_s = P/k`` (the static
deflection) for ``x``, ``X_s omega_n`` for ``v``, ``omega_n = sqrt(k/m)`` for
``omega`` (:class:`~lumped.drivers.response.systems.Scales`);
:data:`NEWTON_TOL` is a residual in those units.
"""

from __future__ import annotations

from typing import NamedTuple

import math

import numpy as np

from lumped.drivers.response.systems import LoadedNetwork, Scales, period_map
from lumped.model.oscillator import Oscillator
from lumped.numerics import validate
from lumped.solvers.monodromy import RESOLUTION, PeriodMap
from lumped.solvers.network_monodromy import NetworkPeriodMap

__all__ = [
    "NEWTON_TOL",
    "Orbit",
    "Scales",
    "balance",
    "find_orbit",
    "monodromy_error",
    "multiplier_margin",
    "newton_step",
]

#: Newton stops when ``|Pi(z) - z|`` (largest component, in :class:`Scales` units) is below this:
#: the map's :data:`~lumped.solvers.monodromy.RESOLUTION`, some 1e5 ulps of unit amplitude, above the
#: period map's own round-off (its event times are refined to a few ulps of the period), far below any
#: amplitude a response curve shows.
NEWTON_TOL = RESOLUTION
#: The error of a computed monodromy matrix, in ulps of its (balanced) norm per unit of work: each phase's factor
#: ``expm(B h)`` is computed by scaling and squaring to some tens of ulps times ``max(1, rho(B) h)`` (the
#: squarings' growth, Higham 2005), its projection, saltation and event time (refined to a few ulps of the
#: period) add a few more; 256 covers them with room, composed over the phases (first order: the errors add).
MULTIPLIER_ULPS = 256
#: Newton iterations before a fixed point is declared not found.
MAX_NEWTON = 40
#: Periods of motion from rest (at most) that bring the first guess near the orbit.
SETTLE_PERIODS = 400


class Orbit(NamedTuple):
    """A periodic motion: its frequency (rad/s), its state (positions, then velocities) at ``t = 0`` and one
    period of it."""

    omega: float
    state: np.ndarray
    period: PeriodMap | NetworkPeriodMap

    @property
    def multipliers(self) -> np.ndarray:
        """The Floquet multipliers (complex): eigenvalues of the monodromy matrix, but for a network the
        neutral ones of elements that stick through the period (see :attr:`NetworkPeriodMap.multipliers`)."""
        return self.period.multipliers

    @property
    def margin(self) -> float:
        """The error bound of the multipliers' moduli (:func:`multiplier_margin` of ``W^T M W``, the neutral
        directions of held elements left out, and of the work of the phases composed)."""
        w = self.period.free_basis
        return multiplier_margin(w.T @ self.period.monodromy @ w, _work(self.period))

    @property
    def max_multiplier(self) -> float:
        """The largest modulus of a multiplier; exactly 1 where it is 1 within :attr:`margin` (a marginal motion:
        an undamped system's, or one at a fold), so that no last bit decides it."""
        mu = float(np.max(np.abs(self.multipliers), initial=0.0))
        return 1.0 if abs(mu - 1.0) <= self.margin else mu

    @property
    def stable(self) -> bool:
        """True when every multiplier lies inside the unit circle by more than :attr:`margin` (asymptotically
        stable); False where one lies outside, and at the margin (:attr:`max_multiplier` exactly 1)."""
        return self.max_multiplier < 1.0

    @property
    def amplitude(self) -> float:
        """Half of ``max x - min x`` over the period (m), of the loaded mass."""
        return self.period.amplitude

    @property
    def amplitudes(self) -> np.ndarray:
        """Half of ``max x - min x`` over the period (m), of each mass."""
        return self.period.amplitudes

    @property
    def stops(self) -> int:
        """Stops per period."""
        return self.period.stops


def balance(matrix: np.ndarray) -> np.ndarray:
    """``D^-1 A D`` with ``D`` diagonal (powers of 2, no permutation) that evens out the rows' and columns' norms
    (:func:`scipy.linalg.matrix_balance`): exact, and a similarity."""
    import scipy.linalg  # here, not at import: importing lumped loads no SciPy solver (tests/test_imports.py)

    return scipy.linalg.matrix_balance(matrix, permute=False)[0]


def monodromy_error(monodromy: np.ndarray, work: float) -> tuple[np.ndarray, float]:
    """The balanced monodromy ``D^-1 M D`` (a similarity: the same multipliers, ``M - I`` singular with it) and
    the bound of its computed error's 2-norm: ``MULTIPLIER_ULPS eps`` times ``work`` (the phases' ``sum max(1,
    rho(B) h)``) times its norm.  By Weyl's inequality no singular value of ``D^-1 M D - I`` moves by more."""
    balanced = balance(monodromy)
    return balanced, float(MULTIPLIER_ULPS * np.finfo(float).eps * work * np.linalg.norm(balanced, 2))


def multiplier_margin(monodromy: np.ndarray, work: float) -> float:
    """The error bound of the moduli of the eigenvalues of a computed monodromy matrix: :func:`monodromy_error`
    times the condition of the balanced matrix's eigenvectors (Bauer-Fike: an eigenvalue moves by at most
    ``cond(V) |E|`` for an error ``E``); 0 for an empty matrix."""
    if not monodromy.size:
        return 0.0
    balanced, error = monodromy_error(monodromy, work)
    _, v = np.linalg.eig(balanced)
    v = v / np.linalg.norm(v, axis=0)
    return error * float(np.linalg.cond(v))


def _work(period: PeriodMap | NetworkPeriodMap) -> float:
    """``sum max(1, rho(B) h)`` over the phases of the period: the work of composing its monodromy matrix."""
    if isinstance(period, PeriodMap):
        osc, phases = period.solution.oscillator, period.solution.phases
        rho = math.sqrt(osc.stiffness / osc.mass) + osc.dashpot.bingham_form().viscosity / osc.mass
        ends = [p.start for p in phases[1:]] + [period.solution.t_end]
        return sum(max(1.0, rho * (e - p.start)) for p, e in zip(phases, ends))
    ends = [p.start for p in period.phases[1:]] + [period.t_end]
    return sum(
        max(1.0, float(np.max(np.abs(np.linalg.eigvals(p.a)), initial=0.0)) * (e - p.start))
        for p, e in zip(period.phases, ends)
    )


def _settle(system: Oscillator | LoadedNetwork, amplitude: float, omega: float, scales: Scales) -> np.ndarray:
    """The state after up to :data:`SETTLE_PERIODS` periods from rest (until two periods agree to 1e-3)."""
    z = np.zeros(2 if isinstance(system, Oscillator) else 2 * system.parts.m.size)
    for _ in range(SETTLE_PERIODS):
        nxt = period_map(system, amplitude, omega, z).end
        if np.max(np.abs(scales.state(nxt - z))) < 1e-3:
            return nxt
        z = nxt
    return z


def _singular(pm: PeriodMap | NetworkPeriodMap) -> bool:
    """True when ``W^T (M - I) W`` (the neutral directions of held elements left out) is singular within the
    computed monodromy's error (:func:`monodromy_error`): Newton's step is then not defined by the map."""
    w = pm.free_basis
    m = w.T @ pm.monodromy @ w
    if not m.size:
        return False
    if not np.all(np.isfinite(m)):
        return True
    balanced, error = monodromy_error(m, _work(pm))
    return bool(np.linalg.svd(balanced - np.eye(m.shape[0]), compute_uv=False)[-1] <= error)


def newton_step(pm: PeriodMap | NetworkPeriodMap, z: np.ndarray) -> np.ndarray:
    """The Newton step on ``Pi(z) = z``: ``(M - I) dz = -(Pi(z) - z)``; with held elements (a network's
    elements that stick through the period) within the states that keep their elongations, where ``M - I`` is
    regular: ``W^T (M - I) W a = -W^T (Pi(z) - z)``, ``dz = W a``."""
    if not pm.neutral.shape[0]:
        return -np.linalg.solve(pm.monodromy - np.eye(z.size), pm.end - z)
    w = pm.free_basis
    return -w @ np.linalg.solve(w.T @ (pm.monodromy - np.eye(z.size)) @ w, w.T @ (pm.end - z))


def least_norm_step(pm: PeriodMap | NetworkPeriodMap, z: np.ndarray) -> np.ndarray:
    """The least-norm Newton step where ``W^T (M - I) W`` is singular within its computed error: the directions
    whose singular values (of the balanced matrix, :func:`monodromy_error`) lie within the error are left out.
    On a continuum of periodic motions (the marginal families of a friction oscillator at ``omega_n/2n``) it
    converges to the nearest one; where there is none (an undamped resonance) it makes no progress, and
    :func:`find_orbit` refuses after :data:`MAX_NEWTON` steps."""
    import scipy.linalg  # here, not at import (tests/test_imports.py)

    w = pm.free_basis
    a = w.T @ pm.monodromy @ w
    balanced, (scale, _) = scipy.linalg.matrix_balance(a, permute=False, separate=True)
    error = MULTIPLIER_ULPS * np.finfo(float).eps * _work(pm) * np.linalg.norm(balanced, 2)
    u, sigma, vt = np.linalg.svd(balanced - np.eye(a.shape[0]))
    keep = sigma > error
    y = -(vt[keep].T @ ((u[:, keep].T @ (w.T @ (pm.end - z) / scale)) / sigma[keep]))
    return w @ (scale * y)


def check_system(system: object) -> Oscillator | LoadedNetwork:
    """``system`` if the period map runs it, else one ``ValueError`` (a :class:`~lumped.model.network.Network`
    is first made one by :func:`~lumped.drivers.response.systems.response_system`, which refuses what the
    period map cannot run: driven points, friction whose graph is not monotone, ...)."""
    if not isinstance(system, (Oscillator, LoadedNetwork)):
        raise ValueError(
            f"system must be an Oscillator or a LoadedNetwork (a network made one by response_system), "
            f"got {type(system).__name__}"
        )
    return system


def find_orbit(
    system: Oscillator | LoadedNetwork,
    amplitude: float,
    omega: float,
    guess: np.ndarray | None = None,
    tol: float = NEWTON_TOL,
) -> Orbit:
    """The periodic motion under ``amplitude sin(omega t)`` near ``guess`` (or the one reached from rest).

    Parameters
    ----------
    system : Oscillator or LoadedNetwork
        A Bingham or Coulomb oscillator, or a network with its loaded mass
        (:mod:`~lumped.drivers.response.systems`).
    amplitude, omega : float
        ``P`` (N) and ``omega`` (rad/s), both ``> 0``.
    guess : array of shape (2,) or (2n,), optional
        The state (positions, then velocities) at ``t = 0`` to start Newton
        from; without it, the state after a run from rest
        (:data:`SETTLE_PERIODS` periods at most).
    tol : float
        :data:`NEWTON_TOL` by default.

    Raises
    ------
    ValueError
        ``force_omega: ...`` when Newton does not converge in :data:`MAX_NEWTON` steps; where ``M - I`` is
        singular within its computed error (:func:`monodromy_error`) its steps are least-norm
        (:func:`least_norm_step`), and the message says so (an undamped system at ``omega = omega_n/j``, whose
        periodic motion is not unique, or a fold).
    """
    check_system(system)
    amplitude, omega = validate.positive("force_amplitude", amplitude), validate.positive("force_omega", omega)
    scales = Scales.of(system, amplitude)
    z = _settle(system, amplitude, omega, scales) if guess is None else np.asarray(guess, dtype=float)
    singular = False
    for _ in range(MAX_NEWTON):
        pm = period_map(system, amplitude, omega, z)
        if np.max(np.abs(scales.state(pm.end - z))) <= tol:
            return Orbit(omega, z, pm)
        singular = _singular(pm)
        z = z + (least_norm_step(pm, z) if singular else newton_step(pm, z))
    if singular:
        raise ValueError(
            f"force_omega: no isolated periodic motion at omega = {omega:.6g} rad/s: monodromy - I is singular "
            "within its computed error and Newton's least-norm steps found none (omega = omega_n/j of an undamped "
            "mode, or a fold)"
        )
    raise ValueError(f"force_omega: Newton found no periodic motion at omega = {omega:.6g} rad/s in {MAX_NEWTON} steps")
