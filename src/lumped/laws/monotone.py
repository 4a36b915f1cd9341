"""Monotone dashpot laws beyond Bingham's: any ``v = phi(F_d)``, and Herschel-Bulkley's power law.

:class:`MonotoneDashpot` takes any monotone callable and solves its step by
Brent's method (:mod:`lumped.laws.monotone_graph`);
:class:`HerschelBulkleyDashpot` is the yield-stress power law, with closed
forms where the exponent allows and Brent's method on a bracket elsewhere.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lumped.laws import monotone_graph
from lumped.laws.bingham import bingham_corrector, sticks
from lumped.laws.contract import BinghamForm, Dashpot, DashpotState, StepBound
from lumped.numerics import validate
from lumped.numerics.roots import MAXITER, brentq

__all__ = ["MonotoneDashpot", "HerschelBulkleyDashpot"]


class MonotoneDashpot(Dashpot):
    """Dashpot given by any monotone law ``v = phi(F_d)`` (Remark 2.3).

    Parameters
    ----------
    velocity_of_force : callable
        ``phi``: monotone non-decreasing, ``phi(0) = 0``, finite for finite force.
        It is called with floats in the step and with arrays in plots.
    threshold : float, N
        Half-width of the flat part around zero, if any (used by plots and by
        the stick test of results); ``0`` by default.
    max_iterations : int
        Bound on the root finder's iterations per step.

    Raises
    ------
    ValueError
        If ``phi(0) != 0``, or if ``phi`` decreases on the sample of
        :data:`lumped.laws.MONOTONE_SAMPLE` (see Notes); the message names the two forces.

    Notes
    -----
    **The monotonicity check.**  A law that decreases somewhere makes the
    resolvent's root non-unique and the event-driven march wander, so ``phi``
    is evaluated at construction at ``F = 0`` and ``F = +-s 10^(j/16)``,
    ``j = -96 ... 96``: 16 forces per decade (neighbours 15 % apart) from
    ``1e-6 s`` to ``1e6 s`` on each side, with ``s`` the threshold if it is
    positive, else 1 N.  A decrease between neighbouring samples is refused.
    The sample stops on each side at the first force where ``phi`` raises or
    is not finite (a law such as ``expm1(F)`` overflows long before ``1e6``;
    the run refuses such values where it meets them).  A dip narrower than
    the spacing, or beyond the sample, is not seen here.

    **The resolvent.**  The resolvent equation ``g(F) = F + eta*phi(F) - F~ = 0`` has ``g``
    strictly increasing, ``g(0) = -F~`` and ``g(F~) = eta*phi(F~)``, whose sign
    is that of ``F~``; so the root lies between ``0`` and ``F~`` and Brent's
    method (bracketing, hence safeguarded) finds it to a few ulps.
    """

    def __init__(
        self,
        velocity_of_force: Callable[[float], float],
        threshold: float = 0.0,
        max_iterations: int = MAXITER,
    ) -> None:
        if not callable(velocity_of_force):
            raise ValueError("velocity_of_force must be callable")
        self.phi = velocity_of_force
        if self._phi(0.0) != 0:
            raise ValueError("velocity_of_force must vanish at zero force")
        self.threshold = validate.non_negative("threshold", threshold)
        self.max_iterations = validate.positive_int("max_iterations", max_iterations)
        monotone_graph.check_monotone(self._phi, self.threshold)

    def _phi(self, force: float) -> float:
        """``phi(force)`` checked: a finite real number, else a ``ValueError``."""
        return monotone_graph.checked(self.phi, force)

    def velocity(self, force: np.ndarray | float) -> np.ndarray | float:
        if np.ndim(force) == 0:
            return self._phi(float(force))
        return np.array([self._phi(float(f)) for f in np.ravel(force)]).reshape(np.shape(force))

    def force_interval(self, velocity: float) -> tuple[float, float]:
        if velocity == 0:
            return (-self.threshold, self.threshold)
        f = monotone_graph.inverse(self._phi, velocity)
        return (f, f)

    def _resolvent_impl(self, predictor: float, eta: float) -> DashpotState:
        return DashpotState(*monotone_graph.resolvent(self._phi, predictor, eta, self.max_iterations))


@dataclass(frozen=True)
class HerschelBulkleyDashpot(Dashpot):
    """Herschel-Bulkley dashpot: a yield threshold and a power-law slip.

    ``|F_d| <= tau`` at rest; ``F_d = sgn(v) (tau + K |v|^n)`` while slipping,
    that is ``phi(F) = sgn(F) ((|F| - tau)/K)^(1/n)`` beyond the band.

    Parameters
    ----------
    threshold : float, N
        ``tau >= 0``, the half-width of the static band (the paper's ``mu_s N_f``).
    consistency : float, N (s/m)^n
        ``K > 0``.
    exponent : float
        ``n > 0``.  ``n = 1`` is the Bingham law (eq. 6) with ``gamma = 1/K``;
        ``n < 1`` thins (shear-thinning), ``n > 1`` thickens.

    Notes
    -----
    Write ``w = |v|`` and ``r = |F~| - tau``.  Outside the band the resolvent
    equation ``F + eta phi(F) = F~`` reads ``g(w) = K w^n + eta w - r = 0``,
    with ``g`` strictly increasing, ``g(0) = -r < 0`` and ``g >= 0`` at
    ``min(r/eta, (r/K)^(1/n))`` (either term alone reaches ``r`` there); the
    bracket is taken twice as wide, so that rounding cannot make ``g`` negative
    at its end.
    For ``n = 1`` the step is Algorithm 1's corrector itself
    (:func:`bingham_corrector` with ``c = K``), so the law then gives the
    Bingham numbers bit for bit; ``n = 2`` and ``n = 1/2`` are quadratics,
    solved in the form without cancellation; other exponents use Brent's
    method on the bracket, to a few ulps.
    """

    threshold: float = 1.0
    consistency: float = 1.0
    exponent: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "threshold", validate.non_negative("threshold", self.threshold))
        object.__setattr__(self, "consistency", validate.positive("consistency", self.consistency))
        object.__setattr__(self, "exponent", validate.positive("exponent", self.exponent))

    def velocity(self, force: np.ndarray | float) -> np.ndarray | float:
        excess = np.maximum(np.abs(force) - self.threshold, 0.0)
        with np.errstate(over="ignore"):
            out = np.sign(force) * (excess / self.consistency) ** (1.0 / self.exponent)
        return float(out) if np.ndim(out) == 0 else out

    def force_interval(self, velocity: float) -> tuple[float, float]:
        if velocity == 0:
            return (-self.threshold, self.threshold)
        f = float(self.slip_force(velocity))
        return (f, f)

    def slip_force(self, velocity: np.ndarray | float) -> np.ndarray | float:
        """``sgn(v) (tau + K |v|^n)`` (N) at ``velocity`` (m/s); 0 at ``v = 0``."""
        s = np.sign(velocity)
        if self.exponent == 1.0:  # the Bingham form, operation for operation
            out = s * self.threshold + self.consistency * velocity
        else:
            out = s * self.threshold + s * (self.consistency * np.abs(velocity) ** self.exponent)
        return float(out) if np.ndim(out) == 0 else out

    def _resolvent_impl(self, predictor: float, eta: float) -> DashpotState:
        tau, K, n = self.threshold, self.consistency, self.exponent
        if n == 1.0:
            return DashpotState(*bingham_corrector(predictor, eta, tau, K))
        if sticks(predictor, -tau, tau):  # the one stick test (Algorithm 1, line 5)
            return DashpotState(predictor, 0.0)
        s, r = math.copysign(1.0, predictor), abs(predictor) - tau
        w = _power_speed(r, eta, K, n)
        # The force from the law, not as F~ - eta v: that difference cancels when
        # the viscous part is small against F~, and the network's iteration
        # compares forces to a few ulps (lumped.solvers.network_step).
        return DashpotState(s * (tau + K * w**n), s * w)

    def bingham_form(self) -> BinghamForm | None:
        """``(tau, K)`` at ``n = 1``, Bingham's graph with ``c = K`` exactly (no ``1/gamma`` is formed), else ``None``.

        ``F_d = sgn(v)(tau + K |v|)`` is eq. (7) with ``mu_s N_f = tau`` and
        ``1/gamma = K``, so the closed forms of point 6 (the exact solution,
        Algorithm 1's loop) apply to it as they stand; the linear dashpot
        (``tau = 0``) is this case.
        """
        return BinghamForm(self.threshold, self.consistency) if self.exponent == 1.0 else None

    def viscous_part(self) -> Callable[[float], float]:
        K, n = self.consistency, self.exponent
        if n == 1.0:
            return lambda v: K * v  # the Bingham form, so that n = 1 gives its numbers
        return lambda v: math.copysign(K * abs(v) ** n, v)

    def band_free_resolvent(self) -> Callable[[float, float], DashpotState]:
        """``psi`` is this law with ``tau = 0``: its own closed forms."""
        return HerschelBulkleyDashpot(0.0, self.consistency, self.exponent)._resolvent_impl

    def step_bound(self, force: float, speed: float, eta: float) -> StepBound:
        """The largest product of the step: see Notes of :func:`_power_speed`; and ``K speed^n``.

        With ``r <= |F~| <= force``: ``K F~`` at ``n = 1`` (the corrector);
        ``eta^2`` and ``4 K r`` at ``n = 2``; ``K^2`` and ``4 eta r`` at ``n =
        1/2``; else ``K w^n <= 2^n r`` and ``eta w <= 2 r`` on Brent's bracket.
        The slip force's viscous part is at most ``K speed^n``.

        The parameter blamed is the one that makes the larger term large: the
        exponent for ``2^n`` and for ``speed^n`` above ``K``, else the consistency.
        """
        K, n = self.consistency, self.exponent
        with np.errstate(over="ignore"):
            power = float(np.float64(speed) ** n)
            if n == 1.0:
                step, by = K * force, "consistency"
            elif n == 2.0:
                step, by = max(eta * eta, 4 * K * force), "consistency"
            elif n == 0.5:
                step, by = max(K * K, 4 * eta * force), "consistency"
            else:
                step, by = (float(np.float64(2.0) ** n) * force if force else 0.0), "exponent"
            slip = float(K * np.float64(power))
        if slip > step:
            by = "exponent" if power > K else "consistency"
        return StepBound(max(step, slip), "viscous term of the Herschel-Bulkley step", by)


def _power_speed(r: float, eta: float, K: float, n: float) -> float:
    """The root ``w > 0`` of ``K w^n + eta w = r`` (``r > 0``), see :class:`HerschelBulkleyDashpot`."""
    if n == 2.0:  # eta w + K w^2 = r: w = 2r / (eta + sqrt(eta^2 + 4 K r))
        return 2 * r / (eta + math.sqrt(eta * eta + 4 * K * r))
    if n == 0.5:  # z = sqrt(w): eta z^2 + K z = r
        z = 2 * r / (K + math.sqrt(K * K + 4 * eta * r))
        return z * z
    power = math.log(r / K) / n  # log of (r/K)^(1/n), which may overflow
    hi = 2 * min(r / eta, math.exp(power) if power < 700 else math.inf)  # twice: g > 0 there despite rounding
    if hi == 0.0:  # r/eta underflows: the speed is below the smallest double
        return 0.0
    return brentq(lambda w: K * w**n + eta * w - r, 0.0, hi)
