"""Constitutive laws: the linear spring and the dashpots.

A dashpot here is a *graph* relating velocity and force, written the way the
paper writes eq. (6): the velocity as a function of the force, ``v = phi(F_d)``.
When ``phi`` is flat (the Bingham band ``|F_d| <= mu_s N_f``) the inverse is
set-valued, so ``F_d`` cannot be computed from ``v`` and becomes an unknown of
the differential-algebraic system (8).

One backward-Euler step (eqs. 13 to 15) reduces to a scalar equation for the
dashpot force.  With ``eta = m/dt + k*dt`` eq. (15a) reads

    F_d + eta * phi(F_d) = F~,          v = (F~ - F_d) / eta,

that is ``F_d = (I + eta*phi)^{-1}(F~)``: the *resolvent* of the monotone graph
``phi`` applied to the predictor ``F~`` of eq. (15b).  Each law provides that
resolvent; Algorithm 1 is its closed form for the Bingham graph.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from lumped.numerics import validate

__all__ = [
    "LinearSpring",
    "Dashpot",
    "BinghamDashpot",
    "MonotoneDashpot",
    "MONOTONE_SAMPLE",
    "HerschelBulkleyDashpot",
    "DashpotState",
    "BinghamForm",
    "StepBound",
    "coulomb",
]


@dataclass(frozen=True)
class LinearSpring:
    """Linear spring, eq. (5): ``x = F_s / k``.

    Parameters
    ----------
    stiffness : float, N/m
        Spring constant ``k > 0``.
    """

    stiffness: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", validate.positive("stiffness", self.stiffness))

    def force(self, x: np.ndarray | float) -> np.ndarray | float:
        """Spring force ``F_s = k x`` (N) for displacement ``x`` (m)."""
        return self.stiffness * x

    def displacement(self, force: np.ndarray | float) -> np.ndarray | float:
        """Displacement ``x = F_s / k`` (m), eq. (5)."""
        return force / self.stiffness

    def energy(self, force: np.ndarray | float) -> np.ndarray | float:
        """Stored energy ``F_s**2 / (2k)`` (J)."""
        return 0.5 * force * force / self.stiffness


class DashpotState(NamedTuple):
    """Solution of one implicit dashpot step: ``force`` (N), ``velocity`` (m/s)."""

    force: float
    velocity: float


class BinghamForm(NamedTuple):
    """A law that *is* the Bingham graph of eq. (6): ``tau`` (N) and ``c = 1/gamma`` (N s/m, ``0`` for Coulomb)."""

    threshold: float
    viscosity: float


class StepBound(NamedTuple):
    """A bound on what a law's step forms (contract point 9).

    ``value`` (``inf`` if it may overflow) is compared with
    :data:`lumped.model.oscillator.MAGNITUDE_LIMIT`; ``term`` names it in the message
    and ``parameter`` is the law's argument blamed when it alone is too large.
    """

    value: float
    term: str
    parameter: str


class Dashpot(ABC):
    """A dashpot given by its velocity-force graph ``v = phi(F_d)``.

    A new dashpot law must provide:

    1. ``velocity(force)``: the graph ``phi``, vectorised over NumPy arrays.
       It must be monotone non-decreasing with ``phi(0) = 0`` (a dashpot
       dissipates: ``F_d * v >= 0``).  It may be flat on an interval, where the
       force is not a function of the velocity.
    2. ``force_interval(velocity)``: the inverse graph, the closed interval
       ``(lo, hi)`` of forces compatible with a velocity (``lo == hi`` off the
       flat parts).  Used for plots and for the Filippov set of eq. (11).
    3. ``_resolvent_impl(predictor, eta)``: the solution ``F_d`` of
       ``F_d + eta*phi(F_d) = predictor`` together with ``v = phi(F_d)``,
       returned as a :class:`DashpotState`.  ``eta > 0`` is finite.
    4. ``threshold``: the largest ``|F_d|`` for which ``phi(F_d) = 0`` (the
       static band), ``0`` if there is none.
    5. Optionally ``slip_force(velocity)``: the force carried while slipping,
       vectorised, ``0`` at ``v = 0``.  The default inverts the graph point by
       point through ``force_interval``; a law with a closed form should
       override it (the event-driven integrator calls it at every stage).

    What a solver may ask of a law beyond its graph is a method here, with a
    generic default that any law meeting points 1 to 4 satisfies; a law
    overrides one only to be faster or more exact.  No solver asks a law for
    its class.

    6. ``bingham_form()``: the :class:`BinghamForm` ``(tau, c)`` if the law is
       the Bingham graph of eq. (6), else ``None`` (the default).  Only such a
       law has the closed forms: Algorithm 1's compiled loop
       (:mod:`lumped.solvers.backward_euler`), the exact solution
       (:mod:`lumped.solvers.exact`) and the textbook ODE
       (:mod:`lumped.solvers.textbook`).  Every other method needs only points 1 to 5.
    7. ``viscous_part()``: ``v -> F_d(v) - sgn(v) tau``, the slip force
       without its static part, as a scalar function continuous through
       ``v = 0`` (the event-driven integrator's right-hand side).  The default
       subtracts from :meth:`slip_force`.
    8. ``band_free_resolvent()``: the resolvent ``(u, v)`` of the graph with
       its band cut out, ``psi(u) = phi(u + sgn(u) tau)``, as a function of
       ``(predictor, eta)`` (the event-capturing scheme's slip step).  The
       default is the bracketed root of :class:`MonotoneDashpot` on ``psi``.
    9. ``step_bound(force, speed, eta)``: a :class:`StepBound` on the
       magnitudes the law's resolvent forms for predictors ``|F~| <= force``
       and its slip force at speeds up to ``speed``, beyond those forces
       themselves (:func:`lumped.model.oscillator.check_magnitudes` refuses a run whose
       bound passes :data:`lumped.model.oscillator.MAGNITUDE_LIMIT`).  The default,
       ``0``, says it forms none: true of a resolvent whose root lies between
       ``0`` and ``F~`` and whose law is checked finite where it is called
       (:class:`MonotoneDashpot`); a law that multiplies (``c F~``, ``K
       |v|^n``) overrides it.

    The public :meth:`resolvent` checks its arguments and calls the hook.
    """

    threshold: float

    @abstractmethod
    def velocity(self, force: np.ndarray | float) -> np.ndarray | float:
        """Velocity ``phi(F_d)`` (m/s) carried by a dashpot force (N)."""

    @abstractmethod
    def force_interval(self, velocity: float) -> tuple[float, float]:
        """Interval of dashpot forces (N) compatible with ``velocity`` (m/s)."""

    @abstractmethod
    def _resolvent_impl(self, predictor: float, eta: float) -> DashpotState:
        """Solve ``F_d + eta*phi(F_d) = predictor`` (see the class docstring)."""

    def slip_force(self, velocity: np.ndarray | float) -> np.ndarray | float:
        """Force (N) while slipping at ``velocity`` (m/s), 0 at ``v = 0`` (point 5)."""

        def one(v: float) -> float:
            return 0.0 if v == 0 else self.force_interval(v)[0]

        if np.ndim(velocity) == 0:
            return one(float(velocity))
        return np.array([one(float(v)) for v in np.ravel(velocity)]).reshape(np.shape(velocity))

    def bingham_form(self) -> BinghamForm | None:
        """``(tau, c)`` if this law is the Bingham graph of eq. (6), else ``None`` (point 6)."""
        return None

    def viscous_part(self) -> Callable[[float], float]:
        """``v -> F_d(v) - sgn(v) tau`` (N) as a scalar function, ``0`` at ``v = 0`` (point 7)."""
        tau, slip = self.threshold, self.slip_force
        return lambda v: float(slip(v)) - math.copysign(tau, v) if v != 0 else 0.0

    def band_free_resolvent(self) -> Callable[[float, float], DashpotState]:
        """Resolvent ``(u, v)`` of ``u + eta psi(u) = predictor``, ``psi`` the law without its band (point 8).

        Notes
        -----
        In slip with direction ``s`` the dashpot force is ``F_d = s tau + u``
        with ``v = psi(u) = phi(u + sgn(u) tau)`` (``psi(0) = 0``): the graph
        with the band ``[-tau, tau]`` cut out.  ``psi`` is single valued,
        continuous and monotone, and it continues the slip branch through
        ``v = 0`` (the root search of a stop in :func:`lumped.solvers.schemes.event_capturing`
        evaluates the step past it).  The default is the bracketed root of
        :class:`MonotoneDashpot` on ``psi``.
        """
        tau, phi = self.threshold, self.velocity

        def psi(u: float) -> float:
            return float(phi(u + math.copysign(tau, u))) if u != 0 else 0.0

        return MonotoneDashpot(psi)._resolvent_impl

    def step_bound(self, force: float, speed: float, eta: float) -> StepBound:
        """Bound on the magnitudes the law's step forms for ``|F~| <= force`` (N), ``|v| <= speed`` (m/s) (point 9)."""
        return StepBound(0.0, "viscous term of the dashpot law", "dashpot")

    def resolvent(self, predictor: float, eta: float) -> DashpotState:
        """Implicit dashpot step: ``F_d = (I + eta*phi)^{-1}(predictor)``.

        Parameters
        ----------
        predictor : float, N
            ``F~`` of eq. (15b).
        eta : float, kg/s
            ``m/dt + k*dt``, the factor of eq. (15a) divided by ``dt/m``.

        Returns
        -------
        DashpotState
            Dashpot force and velocity at the new time level.
        """
        predictor = validate.finite("predictor", predictor)
        eta = validate.positive("eta", eta)
        return self._resolvent_impl(predictor, eta)


@dataclass(frozen=True)
class BinghamDashpot(Dashpot):
    """Bingham dashpot, eq. (6).

    Parameters
    ----------
    threshold : float, N
        The paper's ``mu_s N_f >= 0``: the half-width of the static band.
    gamma : float, m/(N s)
        Slope ``gamma > 0`` of the velocity-force graph outside the band;
        ``inf`` gives the Coulomb law of Remark 2.1.

    Notes
    -----
    Outside the band ``F_d = sgn(v) mu_s N_f + v / gamma`` (eq. 7).  The step is
    computed with the *viscosity* ``c = 1/gamma``, which is ``0`` for Coulomb,
    so that no ``inf * 0`` ever arises (Algorithm 1, line 8, divided through by
    ``gamma``).
    """

    threshold: float = 1.0
    gamma: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "threshold", validate.non_negative("threshold", self.threshold))
        object.__setattr__(self, "gamma", validate.positive_or_inf("gamma", self.gamma))

    @property
    def viscosity(self) -> float:
        """``c = 1/gamma`` (N s/m); ``0`` for the Coulomb law."""
        return 0.0 if math.isinf(self.gamma) else 1.0 / self.gamma

    def velocity(self, force: np.ndarray | float) -> np.ndarray | float:
        excess = np.maximum(np.abs(force) - self.threshold, 0.0)
        if math.isinf(self.gamma):
            return np.where(excess > 0, np.copysign(np.inf, force), 0.0)
        return np.sign(force) * self.gamma * excess

    def force_interval(self, velocity: float) -> tuple[float, float]:
        if velocity == 0:
            return (-self.threshold, self.threshold)
        f = math.copysign(self.threshold, velocity) + self.viscosity * velocity
        return (f, f)

    def slip_force(self, velocity: np.ndarray | float) -> np.ndarray | float:
        """Force while slipping, ``sgn(v) mu_s N_f + v/gamma`` (eq. 7); 0 at v = 0."""
        return np.sign(velocity) * self.threshold + self.viscosity * velocity

    def _resolvent_impl(self, predictor: float, eta: float) -> DashpotState:
        return DashpotState(*bingham_corrector(predictor, eta, self.threshold, self.viscosity))

    def bingham_form(self) -> BinghamForm:
        return BinghamForm(self.threshold, self.viscosity)

    def viscous_part(self) -> Callable[[float], float]:
        c = self.viscosity
        return lambda v: c * v

    def band_free_resolvent(self) -> Callable[[float, float], DashpotState]:
        """``psi(u) = gamma u``: the corrector with no band (closed form, finite at ``gamma = inf``)."""
        c = self.viscosity
        return lambda p, eta: DashpotState(*bingham_corrector(p, eta, 0.0, c))

    def step_bound(self, force: float, speed: float, eta: float) -> StepBound:
        """``c |F~|``, the largest product of Algorithm 1's line 8 (:func:`bingham_corrector`)."""
        with np.errstate(over="ignore", invalid="ignore"):  # c = 0 with force = inf: nan, refused as before
            return StepBound(self.viscosity * force, "viscous term |c F~|", "gamma")


def sticks(predictor: float | np.ndarray, low: float | np.ndarray, high: float | np.ndarray) -> bool | np.ndarray:
    """The stick test: does the closed band ``[low, high]`` hold the predictor?

    Algorithm 1's line 5 is this test on the band ``[-mu_s N_f, mu_s N_f]``,
    ``|F~| <= mu_s N_f``: *closed*, so a predictor on an edge of the band
    sticks.  The network step applies the same test to every rigid piece of
    an element's step graph (``z = f + sigma w`` in ``[lo + sigma a, hi + sigma
    a]``, :func:`lumped.solvers.network_step.solve_step`), so that a Bingham element
    at the edge of its band sticks there too, and a string or locking
    dashpot at the edge of its rigid piece is taut or locked.

    Parameters
    ----------
    predictor : float, N
        ``F~`` of eq. (15b), or the network's ``z``.
    low, high : float, N
        Edges of the band, ``low <= high`` (infinite edges allowed).

    Returns
    -------
    bool or ndarray of bool
        ``low <= predictor <= high``, elementwise (``False`` for a NaN predictor).

    Notes
    -----
    This is the one Python definition; the one C definition is ``sticks1``
    (and its vector-lane form ``sticks<LANES>``) in ``_stick.h``, which
    ``_kernel.c`` (through ``bingham_corrector1``, this module's
    :func:`bingham_corrector` in C), ``_batch_lanes.h`` and ``mode_of`` in
    ``_network_kernel.c`` include; the NumPy loop of :mod:`lumped.kernels.batched`
    calls this function on arrays (elementwise; it equals ``|F~| <= tau`` on
    the band ``[-tau, tau]``: negation and ``abs`` are exact).
    ``tests/test_band_edge.py`` releases a mass on both edges of the band
    through every one of these paths and requires each to stick;
    ``tests/test_algorithm1.py`` and ``tests/test_network_kernel.py`` keep
    the C loops equal to the Python ones.
    """
    return (low <= predictor) & (predictor <= high)


def bingham_corrector(predictor: float, eta: float, threshold: float, viscosity: float) -> tuple[float, float]:
    """Corrector of Algorithm 1 (lines 5 to 10), returning ``(F_d, v)``.

    Notes
    -----
    Line 8 with ``a = 1 + dt^2 k/m`` and ``b = dt/m`` is
    ``F_d = (gamma*a*s*mu_s N_f + b*F~) / (gamma*a + b)``.  Dividing through by
    ``gamma*b`` and writing ``eta = a/b``, ``c = 1/gamma`` gives
    ``F_d = (eta*s*mu_s N_f + c*F~) / (eta + c)``, finite at ``c = 0``.  Line 9,
    ``v = gamma*(F_d - s*mu_s N_f)``, is evaluated in the algebraically equal
    form ``v = (F~ - s*mu_s N_f) / (eta + c)``, which has no cancellation and is
    also finite at ``c = 0``.
    """
    if sticks(predictor, -threshold, threshold):  # line 5: |F~| <= mu_s N_f
        return predictor, 0.0
    signed = math.copysign(threshold, predictor)
    force = (eta * signed + viscosity * predictor) / (eta + viscosity)
    return force, (predictor - signed) / (eta + viscosity)


#: Forces, relative to the threshold (or to 1 N), at which :class:`MonotoneDashpot`
#: checks that its law does not decrease: 16 a decade from 1e-6 to 1e6.
MONOTONE_SAMPLE = 10.0 ** (np.arange(-96, 97) / 16)


def coulomb(threshold: float = 1.0) -> BinghamDashpot:
    """Coulomb friction: the Bingham law with ``gamma = inf`` (Remark 2.1)."""
    return BinghamDashpot(threshold=threshold, gamma=math.inf)


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
        :data:`MONOTONE_SAMPLE` (see Notes); the message names the two forces.

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
        max_iterations: int = 200,
    ) -> None:
        if not callable(velocity_of_force):
            raise ValueError("velocity_of_force must be callable")
        self.phi = velocity_of_force
        if self._phi(0.0) != 0:
            raise ValueError("velocity_of_force must vanish at zero force")
        self.threshold = validate.non_negative("threshold", threshold)
        self.max_iterations = validate.positive_int("max_iterations", max_iterations)
        self._check_monotone()

    def _check_monotone(self) -> None:
        """Refuse a ``phi`` that decreases on the sample of the Notes (one line naming where)."""
        scale = self.threshold if self.threshold > 0 else 1.0
        for side in (1.0, -1.0):
            previous = (0.0, 0.0)
            for ratio in MONOTONE_SAMPLE:
                force = side * scale * ratio
                try:
                    phi = self._phi(force)
                except ValueError:
                    break  # not finite here: refused where a run meets it
                lo, hi = (previous, (force, phi)) if side > 0 else ((force, phi), previous)
                if hi[1] < lo[1]:
                    raise ValueError(
                        f"velocity_of_force must be monotone non-decreasing, but phi({lo[0]:.4g} N) = "
                        f"{lo[1]:.4g} > phi({hi[0]:.4g} N) = {hi[1]:.4g} (MonotoneDashpot's check, 16 forces a decade)"
                    )
                previous = (force, phi)

    def _phi(self, force: float) -> float:
        """``phi(force)`` checked: a finite real number, else a ``ValueError``."""
        try:
            raw = self.phi(force)
        except Exception as err:  # a user's callable: report its failure, named
            raise ValueError(f"velocity_of_force raised {type(err).__name__} at F = {force:.6g} N: {err}") from None
        if isinstance(raw, bool) or not isinstance(raw, (int, float, np.integer, np.floating)):
            raise ValueError(f"velocity_of_force must return a real number, got {raw!r:.40} at F = {force:.6g} N")
        if not math.isfinite(raw):
            raise ValueError(f"velocity_of_force must be finite, got {raw} at F = {force:.6g} N")
        return float(raw)

    def velocity(self, force: np.ndarray | float) -> np.ndarray | float:
        if np.ndim(force) == 0:
            return self._phi(float(force))
        return np.array([self._phi(float(f)) for f in np.ravel(force)]).reshape(np.shape(force))

    def force_interval(self, velocity: float) -> tuple[float, float]:
        if velocity == 0:
            return (-self.threshold, self.threshold)
        from scipy.optimize import brentq

        hi = math.copysign(1.0, velocity)
        for _ in range(200):
            if (self._phi(hi) - velocity) * math.copysign(1.0, velocity) >= 0:
                break
            hi *= 2.0
        else:
            raise ValueError(f"velocity {velocity} is outside the range of the law")
        f = brentq(
            lambda F: self._phi(F) - velocity, 0.0, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps
        )  # the least brentq accepts
        return (f, f)

    def _resolvent_impl(self, predictor: float, eta: float) -> DashpotState:
        from scipy.optimize import brentq

        if predictor == 0.0:
            return DashpotState(0.0, 0.0)
        phi = self._phi
        if phi(predictor) * predictor < 0:
            raise ValueError(
                "velocity_of_force must be monotone non-decreasing with phi(0) = 0; "
                f"phi({predictor:.6g}) = {phi(predictor):.6g} has the opposite sign"
            )
        lo, hi = min(0.0, predictor), max(0.0, predictor)
        force, info = brentq(
            lambda F: F + eta * phi(F) - predictor,
            lo,
            hi,
            xtol=1e-300,
            rtol=4 * np.finfo(float).eps,
            maxiter=self.max_iterations,
            full_output=True,
            disp=False,
        )
        if not info.converged:
            raise ValueError(
                f"velocity_of_force: no convergence in {self.max_iterations} "
                "iterations; is the law monotone and finite?"
            )
        return DashpotState(force, (predictor - force) / eta)


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
        if abs(predictor) <= tau:
            return DashpotState(predictor, 0.0)
        s, r = math.copysign(1.0, predictor), abs(predictor) - tau
        w = _power_speed(r, eta, K, n)
        # The force from the law, not as F~ - eta v: that difference cancels when
        # the viscous part is small against F~, and the network's iteration
        # compares forces to a few ulps (lumped.solvers.network_step).
        return DashpotState(s * (tau + K * w**n), s * w)

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
        """
        K, n = self.consistency, self.exponent
        with np.errstate(over="ignore"):
            if n == 1.0:
                step = K * force
            elif n == 2.0:
                step = max(eta * eta, 4 * K * force)
            elif n == 0.5:
                step = max(K * K, 4 * eta * force)
            else:
                step = float(np.float64(2.0) ** n) * force
            slip = float(K * np.float64(speed) ** n)
        return StepBound(max(step, slip), "viscous term of the Herschel-Bulkley step", "consistency")


def _power_speed(r: float, eta: float, K: float, n: float) -> float:
    """The root ``w > 0`` of ``K w^n + eta w = r`` (``r > 0``), see :class:`HerschelBulkleyDashpot`."""
    if n == 2.0:  # eta w + K w^2 = r: w = 2r / (eta + sqrt(eta^2 + 4 K r))
        return 2 * r / (eta + math.sqrt(eta * eta + 4 * K * r))
    if n == 0.5:  # z = sqrt(w): eta z^2 + K z = r
        z = 2 * r / (K + math.sqrt(K * K + 4 * eta * r))
        return z * z
    from scipy.optimize import brentq

    power = math.log(r / K) / n  # log of (r/K)^(1/n), which may overflow
    hi = 2 * min(r / eta, math.exp(power) if power < 700 else math.inf)  # twice: g > 0 there despite rounding
    if hi == 0.0:  # r/eta underflows: the speed is below the smallest double
        return 0.0
    return brentq(lambda w: K * w**n + eta * w - r, 0.0, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps, maxiter=200)
