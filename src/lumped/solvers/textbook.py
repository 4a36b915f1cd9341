"""The textbook model the paper criticises (section 2.2), for comparison only.

The ODE ``m x'' = F(t) - k x - sgn(v) (mu_s N_f + |v|/gamma)`` with the
convention ``sgn(0) = 0`` prescribes the dashpot force from the velocity alone.
For a mass released at rest inside the static band, ``|x0| < mu_s N_f / k``, it
has no classical solution: ``F_d(v=0) = 0`` accelerates the mass, any motion
brings a friction force of the full threshold that reverses it, and numerical
integrators chatter or stall.  Three ways of meeting it are provided:

* fixed-step explicit schemes (:func:`integrate_fixed`, ``"euler"`` and ``"rk4"``);
* an adaptive ``scipy.integrate.solve_ivp`` run under a budget of
  right-hand-side evaluations and wall time (:func:`integrate_adaptive`);
* the regularisation ``sgn(v) -> tanh(v/eps)`` (``eps`` argument of both).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import sign_changes
from lumped.numerics import validate

__all__ = ["TextbookModel", "integrate_fixed", "integrate_adaptive", "AdaptiveOutcome", "FixedStepResult"]


@dataclass(frozen=True)
class TextbookModel:
    """Right-hand side of the textbook ODE in first-order form.

    Parameters
    ----------
    oscillator : Oscillator
        Must have a :class:`~lumped.laws.BinghamDashpot`.
    force : callable or None
        ``F(t)`` (N).
    eps : float or None
        ``None`` for ``sgn`` with ``sgn(0) = 0``; a positive velocity scale
        (m/s) for the regularisation ``tanh(v/eps)``.
    """

    oscillator: Oscillator
    force: Callable[[float], float] | None = None
    eps: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.oscillator, Oscillator):
            raise ValueError(f"oscillator must be an Oscillator, got {type(self.oscillator).__name__}")
        if self.oscillator.dashpot.bingham_form() is None:  # the law's contract, point 6
            raise ValueError("dashpot: the textbook model needs a BinghamDashpot")
        if self.eps is not None:
            object.__setattr__(self, "eps", validate.positive("eps", self.eps))

    def dashpot_force(self, v: float | np.ndarray) -> float | np.ndarray:
        """``sgn(v) mu_s N_f + v/gamma`` (or with ``tanh(v/eps)`` in place of sgn)."""
        law = self.oscillator.dashpot.bingham_form()
        switch = np.sign(v) if self.eps is None else np.tanh(np.asarray(v) / self.eps)
        return switch * law.threshold + law.viscosity * v

    def creep_rates(self) -> tuple[float, float]:
        """The creep rates ``x'/x`` (1/s) of the ``tanh`` model near ``x = 0``: quasi-static, and with inertia.

        Returns
        -------
        quasi_static : float
            ``-k eps/(tau + c eps)``, from the force balance without inertia,
            ``k x + tau tanh(v/eps) + c v = 0`` (``c = 1/gamma``), linearised at ``x = 0``.
        with_inertia : float
            The slow root of ``m s^2 + b s + k = 0`` with ``b = c + tau/eps``,
            the same linearisation with ``m x''`` kept; it exceeds the
            quasi-static rate by about ``m k/b^2`` relative.

        Notes
        -----
        The slow root is written ``-2k/(b + sqrt(b^2 - 4mk))`` (no cancellation); ``nan`` when
        ``b^2 < 4mk``, where the linearised motion oscillates instead of creeping.
        """
        if self.eps is None:
            raise ValueError("eps: the creep rates are those of the tanh model; give eps")
        law, osc = self.oscillator.dashpot.bingham_form(), self.oscillator
        k, m, c, tau = osc.stiffness, osc.mass, law.viscosity, law.threshold
        b = c + tau / self.eps
        disc = b * b - 4 * m * k
        slow = -2 * k / (b + math.sqrt(disc)) if disc >= 0 else math.nan
        return -k * self.eps / (tau + c * self.eps), slow

    def rhs(self, t: float, z: np.ndarray) -> np.ndarray:
        """``(x', v')`` for the state ``z = (x, v)``."""
        x, v = z
        f = 0.0 if self.force is None else float(self.force(t))
        osc = self.oscillator
        return np.array([v, (f - osc.stiffness * x - self.dashpot_force(v)) / osc.mass])


@dataclass(frozen=True)
class FixedStepResult:
    """Fixed-step run: arrays ``t, x, v, F_d`` and the count of velocity sign changes."""

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    F_d: np.ndarray

    @property
    def sign_changes(self) -> int:
        """Number of times ``sgn(v)`` changes between successive nonzero values."""
        return sign_changes(self.v)


#: Estimated cost (s) of one step of the fixed-step loops, for the run-time
#: bound (measured about 4e-6 s for Euler and 1.6e-5 s for RK4; a margin of 1.5x).
SECONDS_PER_STEP = {"euler": 6e-6, "rk4": 2.4e-5}


def integrate_fixed(
    model: TextbookModel,
    t_end: float,
    dt: float,
    *,
    x0: float = 0.0,
    v0: float = 0.0,
    scheme: str = "euler",
) -> FixedStepResult:
    """Integrate the textbook ODE with a fixed-step explicit scheme.

    Parameters
    ----------
    scheme : {"euler", "rk4"}
        Forward Euler or the classical fourth-order Runge-Kutta method.
    """
    if scheme not in ("euler", "rk4"):
        raise ValueError(f"scheme must be 'euler' or 'rk4', got {scheme!r}")
    t_end, dt, _, n = validate.grid(t_end, dt)
    validate.output_size(n, 1, 4)
    validate.run_time(n, SECONDS_PER_STEP[scheme], f"the {scheme} loop")
    z, f = np.array([validate.finite("x0", x0), validate.finite("v0", v0)]), model.rhs
    out = np.empty((n + 1, 2))
    out[0] = z
    for i in range(n):
        t = i * dt
        if scheme == "euler":
            z = z + dt * f(t, z)
        else:
            k1 = f(t, z)
            k2 = f(t + dt / 2, z + dt / 2 * k1)
            k3 = f(t + dt / 2, z + dt / 2 * k2)
            z = z + dt / 6 * (k1 + 2 * k2 + 2 * k3 + f(t + dt, z + dt * k3))
        out[i + 1] = z
    t = np.arange(n + 1) * dt
    return FixedStepResult(t, out[:, 0], out[:, 1], model.dashpot_force(out[:, 1]))


@dataclass(frozen=True)
class AdaptiveOutcome:
    """Result of a budgeted adaptive run.

    Attributes
    ----------
    finished : bool
        Whether the integrator reached ``t_end`` within the budget.
    t_reached : float
        Last time (s) the integrator accepted.
    nfev : int
        Right-hand-side evaluations used.
    wall_time : float
        Seconds spent.
    message : str
        One line saying how the attempt ended.
    t, x, v : ndarray
        Accepted steps (up to ``t_reached``).
    """

    finished: bool
    t_reached: float
    nfev: int
    wall_time: float
    message: str
    t: np.ndarray
    x: np.ndarray
    v: np.ndarray

    @property
    def median_step(self) -> float:
        """Median accepted step (s); ``nan`` with fewer than two steps."""
        return float(np.median(np.diff(self.t))) if self.t.size > 1 else math.nan


#: Smallest relative tolerance the scipy solvers accept without changing it.
RTOL_MIN = 100 * float(np.finfo(float).eps)


def integrate_adaptive(
    model: TextbookModel,
    t_end: float,
    *,
    x0: float = 0.0,
    v0: float = 0.0,
    method: str = "RK45",
    rtol: float = 1e-8,
    atol: float = 1e-10,
    max_nfev: int = 200_000,
    max_seconds: float = 10.0,
) -> AdaptiveOutcome:
    """Run one of ``scipy.integrate.solve_ivp``'s methods on the model under a budget.

    The loop is the one ``solve_ivp`` runs (``solver.step()`` until the solver
    finishes or fails) with a check between steps: once ``max_nfev``
    right-hand-side evaluations or ``max_seconds`` of wall time are spent, the
    attempt ends and the outcome reports how far it got.

    Parameters
    ----------
    method : str
        A ``solve_ivp`` method name: RK45, RK23, DOP853, Radau, BDF or LSODA.
    rtol, atol : float
        Tolerances passed to the solver: finite, ``rtol >= 100 eps``, ``atol > 0``.
    max_nfev : int
        Budget of right-hand-side evaluations.
    max_seconds : float
        Budget of wall time (s).
    """
    from scipy import integrate

    names = ("RK45", "RK23", "DOP853", "Radau", "BDF", "LSODA")
    METHODS = {name: getattr(integrate, name) for name in names}  # noqa: N806
    if method not in METHODS:
        raise ValueError(f"method must be one of {sorted(METHODS)}, got {method!r}")
    t_end = validate.positive("t_end", t_end)
    rtol = validate.positive("rtol", rtol)
    if rtol < RTOL_MIN:  # scipy would raise it silently, with only a warning
        raise ValueError(f"rtol must be >= {RTOL_MIN:.3g} (100 machine epsilons), got {rtol}")
    atol = validate.positive("atol", atol)
    max_nfev = validate.positive_int("max_nfev", max_nfev)
    max_seconds = validate.positive("max_seconds", max_seconds)
    z0 = np.array([validate.finite("x0", x0), validate.finite("v0", v0)])
    start = time.perf_counter()
    solver = METHODS[method](model.rhs, 0.0, z0, t_end, rtol=rtol, atol=atol)
    ts, zs = [0.0], [z0]
    while solver.status == "running":
        if solver.nfev >= max_nfev or time.perf_counter() - start > max_seconds:
            break
        failure = solver.step()
        if solver.status == "failed":
            break
        ts.append(solver.t)
        zs.append(solver.y.copy())
    wall = time.perf_counter() - start
    z = np.array(zs)
    finished = solver.status == "finished"
    if finished:
        message = f"{method}: reached t = {t_end:g} s with {solver.nfev} evaluations"
    elif solver.status == "failed":
        message = f"{method}: failed at t = {ts[-1]:.6g} s: {failure}"
    else:
        message = (
            f"{method}: budget exhausted ({solver.nfev} evaluations, {wall:.2f} s) at t = {ts[-1]:.6g} of {t_end:g} s"
        )
    return AdaptiveOutcome(finished, float(ts[-1]), int(solver.nfev), wall, message, np.array(ts), z[:, 0], z[:, 1])
