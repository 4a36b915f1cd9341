"""The ``moreau-jean`` method: the Moreau-Jean (Euler-Moreau) θ-scheme of nonsmooth mechanics.

The time-stepping scheme of Moreau and Jean, as INRIA's Siconos runs it
(``MoreauJeanOSI`` for mechanical systems, ``EulerMoreauOSI`` for its
first-order form, which the FrictionOscillator example uses): the smooth
forces by the θ-rule, the set-valued force fully implicit at the new level,
and the position by ``x_{n+1} = x_n + dt ((1-theta) v_n + theta v_{n+1})``.
Here the smooth forces are the spring, the dashpot's viscous slope ``c v``
and the load; the set-valued force is the dashpot's band (the Bingham
threshold, or Coulomb friction).  Each step is a relay problem on one
velocity, solved exactly by Algorithm 1's corrector
(:func:`lumped.laws.bingham.bingham_corrector`), so ``theta = 1`` *is*
Algorithm 1, bit for bit.

It differs from the ``theta`` method (:mod:`lumped.solvers.theta`), which
averages the whole dashpot force, band included, over the step: here the
band's reaction is the new level's alone, so in stick it settles on the
θ-averaged reaction instead of alternating about it.
``tests/test_moreau_jean_siconos.py`` runs Siconos' own FrictionOscillator
example beside it.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from lumped.laws.bingham import bingham_corrector
from lumped.model.forcing import SwitchedSine, validate_force
from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate
from lumped.solvers.grid import march, start_run

__all__ = ["BINGHAM_REASON", "DEFAULT_THETA", "moreau_jean", "moreau_jean_step", "validate_theta"]

#: Siconos' choice in its FrictionOscillator example: the midpoint weight.
DEFAULT_THETA = 0.5
#: Why it runs only a law with a Bingham form (its refusal of another law names it).
BINGHAM_REASON = "its relay needs a Bingham or Coulomb law (a band and a viscous slope)"


def validate_theta(theta: object) -> float:
    """``theta`` as a float in ``(0, 1]``, or ``ValueError`` naming it."""
    value = validate.finite("theta", theta)
    if not 0 < value <= 1:
        raise ValueError(f"theta must lie in (0, 1], got {theta!r}")
    return value


def moreau_jean_step(
    m: float, k: float, dt: float, theta: float, tau: float, c: float, state: tuple[float, float, float, float]
) -> tuple[float, float, float]:
    """One Moreau-Jean step; ``state = (F_s, v, F_n, F_{n+1})``; returns ``(F_s, v, F_d)`` at ``n+1``.

    Parameters
    ----------
    m, k, dt, theta : float
        kg, N/m, s, and the weight of the new level in ``(0, 1]``.
    tau, c : float
        The band's half-width (N) and the viscous slope ``1/gamma`` (N s/m) of
        the law's Bingham form.
    state : tuple of float
        Spring force (N) and velocity (m/s) at ``t_n``, load (N) at ``t_n`` and ``t_{n+1}``.

    Notes
    -----
    The scheme, with ``F_d = c v + tau s`` and ``s`` in ``Sgn(v)``::

        m (v_{n+1} - v_n) = dt [theta (F - k x - c v)_{n+1} + (1-theta) (F - k x - c v)_n] - dt tau s_{n+1}
        x_{n+1} = x_n + dt (theta v_{n+1} + (1-theta) v_n).

    Put the second into the first and divide by ``dt``: the relay problem
    ``(eta + theta c) v_{n+1} + tau s_{n+1} = F~`` with ``eta = m/dt +
    k dt theta^2`` and ``F~ = (m/dt - (1-theta)(k dt theta + c)) v_n +
    theta F_{n+1} + (1-theta) F_n - F_s,n``, which is Algorithm 1's corrector
    with viscosity ``theta c``.  It returns ``theta c v_{n+1} + tau s_{n+1}``;
    the dashpot force at the new level adds ``(1-theta) c v_{n+1}``.  At
    ``theta = 1`` every ``(1-theta)`` term is ``+-0`` and every other
    operation is Algorithm 1's (eqs. 14, 15) in the same order.
    """
    f_s, v, f_now, f_next = state
    eta = m / dt + k * dt * theta * theta
    rest = 1 - theta
    predictor = (m / dt - rest * (k * dt * theta + c)) * v + (theta * f_next + rest * f_now) - f_s
    f_d, v_next = bingham_corrector(predictor, eta, tau, c * theta)
    return f_s + dt * k * (theta * v_next + rest * v), v_next, f_d + rest * c * v_next


def moreau_jean(
    oscillator: Oscillator,
    t_end: float,
    dt: float,
    *,
    theta: float = DEFAULT_THETA,
    x0: float = 0.0,
    v0: float = 0.0,
    force: SwitchedSine | Callable[[np.ndarray], np.ndarray] | None = None,
    save_every: int = 1,
) -> Trajectory:
    """Integrate the DAE (8) with the Moreau-Jean θ-scheme (:func:`moreau_jean_step`) on ``t_n = n*dt``.

    Parameters
    ----------
    theta : float
        Weight of the new level of the smooth forces, in ``(0, 1]``; ``1/2``
        (the default, Siconos' FrictionOscillator) is the midpoint rule on
        them, ``1`` is Algorithm 1.
    oscillator, t_end, dt, x0, v0, force, save_every
        As for :func:`~lumped.solvers.backward_euler.backward_euler`; the law
        must have a Bingham form (a Bingham or Coulomb dashpot).

    Returns
    -------
    Trajectory
        ``method = "moreau-jean"``, columns as Algorithm 1's, ``F_d`` the
        dashpot force at the new level (``c v + tau s``); its ``rest_time``
        is the first grid point of the final run of ``v == 0``.
    """
    t_end, dt, x0, v0, save_every, n_steps = start_run(oscillator, t_end, dt, x0, v0, save_every, "moreau-jean", force)
    theta = validate_theta(theta)
    if oscillator.dashpot.bingham_form() is None:
        law = type(oscillator.dashpot).__name__
        raise ValueError(f"method: 'moreau-jean' cannot run a {law}: {BINGHAM_REASON}")
    force = validate_force(force)
    m, k = oscillator.mass, oscillator.spring.stiffness
    tau, c = oscillator.dashpot.bingham_form()  # type: ignore[misc]
    step = lambda f_s, v, f_d, f_now, f_next: moreau_jean_step(m, k, dt, theta, tau, c, (f_s, v, f_now, f_next))
    run = (t_end, dt, x0, v0, save_every, n_steps)
    return march(oscillator, step, run, force, "moreau-jean", "the moreau-jean scheme")
