"""The ``theta`` method: the θ-method for the DAE (8), the law enforced at the new time level.

:func:`theta_method` marches on the grid ``t_n = n*dt`` of Algorithm 1
(:mod:`lumped.solvers.grid`) and returns a
:class:`~lumped.model.trajectory.Trajectory` there.  Its step,
:func:`theta_step`, is like Algorithm 1's a resolvent of the set-valued law
(``theta = 1`` *is* Algorithm 1).  With ``theta = 1/2`` (the trapezoidal
rule) it is of order two on smooth motions but not through the switches: it
crosses them blindly, and in stick its dashpot force alternates about the
reaction instead of settling (measured in ``tests/test_schemes.py``).  The
``event-locating`` scheme (:mod:`lumped.solvers.event_capturing`) takes the
same trapezoidal steps within modes and locates the switches.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from lumped.model.forcing import SwitchedSine, validate_force
from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate
from lumped.solvers.grid import march, start_run

__all__ = ["theta_method", "theta_step"]


def theta_step(
    osc: Oscillator, dt: float, theta: float, f_s: float, v: float, f_d: float, f_now: float, f_next: float
) -> tuple[float, float, float]:
    """One step of the θ-method for the DAE (8); returns ``(F_s, v, F_d)`` at ``n+1``.

    Parameters
    ----------
    osc : Oscillator
    dt : float, s
    theta : float
        Weight of the new time level, ``1/2 <= theta <= 1``.
    f_s, v, f_d : float, N, m/s, N
        Spring force, velocity and dashpot force at ``t_n``.
    f_now, f_next : float, N
        External force at ``t_n`` and ``t_{n+1}``.

    Notes
    -----
    The scheme is ``x_{n+1} = x_n + dt (theta v_{n+1} + (1-theta) v_n)`` and
    ``m (v_{n+1} - v_n) = dt (theta G_{n+1} + (1-theta) G_n)`` with ``G = F - k x
    - F_d`` (eqs. 8), and ``v_{n+1} = phi(F_d,n+1)`` (eq. 6) at the new level.
    Divide the second equation by ``theta dt`` and put the first into its
    ``k x_{n+1}``::

        F_d,n+1 + eta v_{n+1} = F~,      eta = m/(theta dt) + k theta dt,
        F~ = (m/(theta dt)) v_n + F_{n+1} - F_s,n
             + (1 - theta) (G_n/theta - k dt v_n).

    With ``v_{n+1} = phi(F_d,n+1)`` this is ``F_d,n+1 = (I + eta phi)^{-1}(F~)``,
    the resolvent of :mod:`lumped.laws` with another predictor and ``eta``;
    then ``v_{n+1} = (F~ - F_d,n+1)/eta`` and ``F_s,n+1 = F_s,n + dt k (theta
    v_{n+1} + (1-theta) v_n)``.  At ``theta = 1`` the extra term is ``0`` and
    every operation is Algorithm 1's (eqs. 14, 15), in the same order, so the
    two agree bit for bit.
    """
    m, k = osc.mass, osc.spring.stiffness
    g_now = f_now - f_s - f_d
    eta = m / (theta * dt) + k * theta * dt
    predictor = (m / (theta * dt)) * v + f_next - f_s + (1 - theta) * (g_now / theta - k * dt * v)
    f_d, v_next = osc.dashpot._resolvent_impl(predictor, eta)
    return f_s + dt * k * (theta * v_next + (1 - theta) * v), v_next, f_d


def theta_method(
    oscillator: Oscillator,
    t_end: float,
    dt: float,
    *,
    theta: float = 0.5,
    x0: float = 0.0,
    v0: float = 0.0,
    force: SwitchedSine | Callable[[np.ndarray], np.ndarray] | None = None,
    save_every: int = 1,
) -> Trajectory:
    """Integrate the DAE (8) with the θ-method (:func:`theta_step`) on ``t_n = n*dt``.

    A shim of the one entry point, kept for what it adds:
    ``lumped.solve(Problem.oscillator(oscillator, t_end, x0=x0, v0=v0,
    force=force), dt, method="theta")`` runs it at ``theta = 1/2``; called
    directly it takes any ``theta`` in ``[1/2, 1]``.

    Parameters
    ----------
    theta : float
        Weight of the new level, in ``[1/2, 1]`` (the scheme is A-stable
        there); ``1/2`` is the trapezoidal rule, ``1`` is Algorithm 1.
    oscillator, t_end, dt, x0, v0, force, save_every
        As for :func:`~lumped.solvers.backward_euler.backward_euler`.

    Returns
    -------
    Trajectory
        ``method = "theta"``; its ``rest_time`` is the first grid point of the
        final run of ``v == 0``.

    Notes
    -----
    Measured against the exact solution (``tests/test_schemes.py``), at
    ``theta = 1/2``:

    * without a static band (no switches) the order is 2;
    * through switches the maximum displacement error is of order one
      (fitted slopes 0.9 to 1.4): a step across a stop or a reversal averages
      ``G`` over both sides of the jump of ``F_d``, a momentum error
      ``O(dt)`` whose factor depends on where the switch falls in its step.
      The rest position of the free decay happens to converge faster
      (relative error 1.2e-3 at ``dt = 1e-3``, 1.2e-5 at ``1e-4``), that of
      eq. (17b) erratically;
    * in stick ``F_d,n+1 + F_d,n = F_n+1 + F_n - 2 k x``: the dashpot force
      alternates about the reaction with the amplitude the last slip step
      left (0.21 N in the free decay at ``dt = 1e-3``) and never settles;
    * the resolvent returns ``v = 0`` whenever the predictor falls in the
      band, so some reversals become one-step stops that the exact motion
      does not have (Coulomb under eq. 17b).

    """
    t_end, dt, x0, v0, save_every, n_steps = start_run(oscillator, t_end, dt, x0, v0, save_every, "theta", force)
    theta = validate.finite("theta", theta)
    if not 0.5 <= theta <= 1:
        raise ValueError(f"theta must lie in [0.5, 1], got {theta!r}")
    force = validate_force(force)
    step = lambda f_s, v, f_d, f_now, f_next: theta_step(oscillator, dt, theta, f_s, v, f_d, f_now, f_next)
    return march(oscillator, step, (t_end, dt, x0, v0, save_every, n_steps), force, "theta", "the θ-method")
