"""A regularised Bingham dashpot (Papanastasiou type): the law Remark 2.3 invites.

Remark 2.3 of the paper: "for more complicated models, one may have to employ
a Newton-Raphson scheme to solve the nonlinear equation, which can be written
just in terms of ``F_d^(n+1)``".  This file is such a model, added through the
:class:`~lumped.laws.Dashpot` contract alone: no solver knows it.  It runs
through backward Euler (the generic loop), the θ-method, the event-locating
scheme and the event-driven integrator; it is not the Bingham graph, so the
closed forms (Algorithm 1's compiled loop, the exact solution) refuse it
(contract point 6).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from lumped.laws.contract import Dashpot, DashpotState, StepBound
from lumped.numerics import validate

__all__ = ["PapanastasiouDashpot"]

#: Bound on the Newton iterations of one solve (see :func:`_speed`).
MAX_NEWTON = 200


@dataclass(frozen=True)
class PapanastasiouDashpot(Dashpot):
    """Bingham dashpot regularised after Papanastasiou (1987).

    ``F_d(v) = sgn(v) tau (1 - exp(-|v|/eps)) + c v``, a smooth, strictly
    increasing function of the velocity; as ``eps -> 0`` it tends to the
    Bingham law (eq. 7) for every ``v != 0``.

    Parameters
    ----------
    yield_force : float, N
        ``tau >= 0``, the Bingham threshold the law regularises (the paper's
        ``mu_s N_f``).  The graph has no flat part, so the contract's
        ``threshold`` (point 4) is ``0``: the mass never sticks, it creeps.
    gamma : float, m/(N s)
        Slope of the Bingham branch, ``gamma > 0``; ``c = 1/gamma``.
        ``inf`` (no viscous part) is allowed: ``|F_d| < tau`` then.
    eps : float, m/s
        Regularisation speed ``eps > 0``: the force reaches ``1 - 1/e`` of
        ``tau`` at ``|v| = eps``.

    Notes
    -----
    The resolvent (contract point 3), ``F + eta phi(F) = F~``, is written in
    the speed ``w = |v|``: ``g(w) = tau (1 - exp(-w/eps)) + (c + eta) w - |F~|
    = 0``.  ``g`` is increasing and concave (``g'' = -tau/eps^2 exp(-w/eps)
    < 0``) with ``g(0) = -|F~| <= 0``, so Newton's method from ``w = 0``
    increases monotonically to the root: the tangent lies above the curve,
    so each iterate stays below the root (Remark 2.3's Newton-Raphson,
    safeguarded by concavity alone).  The force is then taken from the law,
    ``sgn(F~) F_d(w)``.  The graph ``phi`` itself is the same equation with
    ``eta = 0``; with ``c = 0`` it has the closed form ``w = -eps log(1 -
    |F|/tau)`` and is infinite for ``|F| >= tau``.
    """

    yield_force: float = 1.0
    gamma: float = 1.0
    eps: float = 1e-3
    threshold: float = field(default=0.0, init=False)  # no flat part (contract point 4)

    def __post_init__(self) -> None:
        object.__setattr__(self, "yield_force", validate.non_negative("yield_force", self.yield_force))
        object.__setattr__(self, "gamma", validate.positive_or_inf("gamma", self.gamma))
        object.__setattr__(self, "eps", validate.positive("eps", self.eps))

    @property
    def viscosity(self) -> float:
        """``c = 1/gamma`` (N s/m); ``0`` for ``gamma = inf``."""
        return 0.0 if math.isinf(self.gamma) else 1.0 / self.gamma

    def slip_force(self, velocity: np.ndarray | float) -> np.ndarray | float:
        """``sgn(v) tau (1 - exp(-|v|/eps)) + c v`` (N) at ``velocity`` (m/s)."""
        out = np.sign(velocity) * (self.yield_force * -np.expm1(-np.abs(velocity) / self.eps))
        out = out + self.viscosity * np.asarray(velocity, dtype=float)
        return float(out) if np.ndim(out) == 0 else out

    def velocity(self, force: np.ndarray | float) -> np.ndarray | float:
        def one(f: float) -> float:
            return math.copysign(self._speed(abs(f), self.viscosity), f) if f != 0 else 0.0

        if np.ndim(force) == 0:
            return one(float(force))
        return np.array([one(float(f)) for f in np.ravel(force)]).reshape(np.shape(force))

    def force_interval(self, velocity: float) -> tuple[float, float]:
        f = float(self.slip_force(velocity))
        return (f, f)

    def _resolvent_impl(self, predictor: float, eta: float) -> DashpotState:
        w = self._speed(abs(predictor), self.viscosity + eta)
        s = math.copysign(1.0, predictor)
        return DashpotState(s * self._slip_magnitude(w), s * w)

    def viscous_part(self) -> Callable[[float], float]:
        tau, c, eps = self.yield_force, self.viscosity, self.eps
        return lambda v: math.copysign(tau * -math.expm1(-abs(v) / eps), v) + c * v

    def band_free_resolvent(self) -> Callable[[float, float], DashpotState]:
        """No band to cut out: the resolvent itself (contract point 8)."""
        return self._resolvent_impl

    def step_bound(self, force: float, speed: float, eta: float) -> StepBound:
        """Newton's slope ``tau/eps + c + eta`` and the slip force's ``c speed`` (contract point 9).

        Every other product of the step is at most ``|F~|``: ``(c + eta) w
        <= g(w) + |F~|`` on the iterates, which stay below the root.
        """
        with np.errstate(over="ignore"):
            slope, viscous = self.yield_force / self.eps + self.viscosity + eta, self.viscosity * speed
        name = "eps" if slope >= viscous else "gamma"
        return StepBound(max(slope, viscous), "viscous term of the regularised Bingham step", name)

    def _slip_magnitude(self, w: float) -> float:
        """``tau (1 - exp(-w/eps)) + c w`` (N) for ``w >= 0``."""
        return self.yield_force * -math.expm1(-w / self.eps) + self.viscosity * w

    def _speed(self, r: float, slope: float) -> float:
        """The root ``w >= 0`` of ``tau (1 - exp(-w/eps)) + slope w = r`` (Notes), ``inf`` if none."""
        tau, eps = self.yield_force, self.eps
        if slope == 0.0:  # the graph with c = 0: closed form, infinite beyond the yield force
            return -eps * math.log1p(-r / tau) if r < tau else math.inf
        w = 0.0
        for _ in range(MAX_NEWTON):
            g = tau * -math.expm1(-w / eps) + slope * w - r
            step = g / (tau / eps * math.exp(-w / eps) + slope)
            if not w - step > w:  # no more progress: the root, to rounding (Notes)
                return w
            w -= step
        raise ValueError(
            f"PapanastasiouDashpot: Newton's method did not settle in {MAX_NEWTON} iterations at r = {r:.6g} N"
        )
