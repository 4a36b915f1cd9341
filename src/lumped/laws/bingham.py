"""The Bingham dashpot of eq. (6), Algorithm 1's stick test and corrector, and Coulomb friction.

:func:`sticks` (Algorithm 1's line 5) and :func:`bingham_corrector` (lines 5
to 10) are the one Python definition of each; their one C copy is
``_stick.h`` (see :func:`sticks`, Notes).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lumped.laws.contract import BinghamForm, Dashpot, DashpotState, StepBound
from lumped.numerics import validate

__all__ = ["BinghamDashpot", "sticks", "bingham_corrector", "coulomb"]


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
    ``_network_elements.h`` include; the NumPy loop of :mod:`lumped.kernels.batched`
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


def coulomb(threshold: float = 1.0) -> BinghamDashpot:
    """Coulomb friction: the Bingham law with ``gamma = inf`` (Remark 2.1)."""
    return BinghamDashpot(threshold=threshold, gamma=math.inf)
