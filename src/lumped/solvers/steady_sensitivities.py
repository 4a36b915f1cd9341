"""The derivative of a periodic motion, and of its amplitude, with respect to the parameters.

A motion of the forcing's period ``T = 2 pi/omega`` starts from a fixed
point ``z*`` of the period map: ``Pi(z*; p) = z*``
(:mod:`lumped.solvers.monodromy`).  By the implicit function theorem

    ``dz*/dp = (I - M)^{-1} dPi/dp``,  ``dPi/dp = dz(T)/dp + f(T, z(T)) dT/dp``,

with ``M = dPi/dz`` the monodromy matrix, ``dz(T)/dp`` the derivative at the
fixed time ``T`` with the initial state held, and ``f`` the vector field at
``T`` (the end of the period moves with ``omega``: ``dT/domega = -T/omega``).
:func:`fixed_point_derivative` is this formula's one home: it takes ``M``,
``dz(T)/dp``, ``f(T)`` and ``dT/dp`` as arrays, so that a network's period
map can plug its own in.  :func:`steady_sensitivities` applies it to one mass,
with ``dz(T)/dp`` and ``M`` from :func:`lumped.solvers.sensitivities.sensitivities`
(its ``x0`` and ``v0`` columns at ``T`` are ``M``).

Notes
-----
The amplitude ``A = (max x - min x)/2`` over the period is the difference of
two extremes of the periodic ``x(t; p)``; at each, ``v = 0``, so by the
envelope theorem its derivative is ``dx/dp`` at that time held fixed:
the sensitivities' column of ``p`` plus their ``x0`` and ``v0`` columns times
``dz*/dp`` (the motion at a fixed time moves with its initial state).  ``x``
is monotone in each phase, so the extremes lie among the phases' starts and
the end (as :attr:`lumped.solvers.monodromy.PeriodMap.amplitude` finds them).

Where the event sequence of the period changes with ``p`` (a stop that turns
into a reversal at the band's edge, a breakaway where the force only touches
the band: the stops per period change), the period's smallest event margin
(:attr:`SteadySensitivities.margin`) is 0 and the derivatives are those of
the side whose sequence the motion has;
:func:`lumped.drivers.steady_sensitivity.steady_amplitude_sensitivities`
gives both sides there.  Where a stop appears on the band's edge under the
moving force the two agree: the stick starts with zero acceleration, so
moving its start changes the motion at second order only, and ``A`` is
``C^1`` though the stops per period jump (``tests/test_steady_sensitivities.py``).

A network's periodic motion (:func:`network_steady_sensitivities`) takes the
same formula with the network's period map
(:class:`~lumped.solvers.network_monodromy.NetworkPeriodMap`) and its
sensitivities (:func:`~lumped.solvers.network_sensitivities.network_sensitivities`,
whose ``x0`` and ``v0`` columns at ``T`` are ``M``).  An element that sticks
through the period keeps its elongation (the neutral direction of ``M``, where
``I - M`` is singular): the elongation is held as the parameter moves, and the
formula is solved on the other states (``W^T (I - M) W a = W^T dPi/dp``,
``dz* = W a``, ``W`` the map's ``free_basis``).  A mass's extremes lie at an
event (where its velocity may jump: the derivative of its position there is
the event's, its time moving), at ``t = 0`` or ``T`` (``dz*/dp``), or at a
zero of its velocity inside a phase (the derivative at that time held fixed).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from lumped.solvers.exact import ExactSolution
from lumped.solvers.network_monodromy import NetworkPeriodMap
from lumped.solvers.network_sensitivities import Parameter, network_sensitivities
from lumped.solvers.sensitivities import sensitivities

__all__ = [
    "NETWORK_STEADY_KINDS",
    "STEADY_PARAMETERS",
    "SteadySensitivities",
    "fixed_point_derivative",
    "network_steady_sensitivities",
    "steady_sensitivities",
]

#: The parameters a periodic motion under a sine that stays on depends on (names of
#: :data:`lumped.solvers.sensitivities.PARAMETER_NAMES`); the initial state does not enter.
STEADY_PARAMETERS = ("mass", "stiffness", "threshold", "gamma", "viscosity", "force_amplitude", "force_omega")


#: The kinds of a network's parameters (:data:`lumped.solvers.network_sensitivities.KINDS`) a periodic motion
#: depends on.
NETWORK_STEADY_KINDS = ("mass", "stiffness", "viscosity", "threshold", "amplitude", "omega")


def fixed_point_derivative(
    monodromy: np.ndarray,
    end: np.ndarray,
    field: np.ndarray | None = None,
    period: np.ndarray | None = None,
    free: np.ndarray | None = None,
) -> np.ndarray:
    """``dz*/dp = (I - M)^{-1} (dz(T)/dp + f(T) dT/dp)`` of a fixed point ``z* = Pi(z*; p)`` (module docstring).

    Parameters
    ----------
    monodromy : ndarray, (n, n)
        ``M = dPi/dz`` at the fixed point.
    end : ndarray, (n, p)
        ``dz(T)/dp`` at the end of the period held fixed, the initial state held.
    field : ndarray, (n,), optional
        ``f(T, z(T))``, the state's rate at the end (zero by default).
    period : ndarray, (p,), optional
        ``dT/dp`` (zero by default).
    free : ndarray, (n, r), optional
        A basis ``W`` of the states that keep the neutral directions of ``M`` (where ``I - M`` is singular):
        the fixed point moves within it (module Notes).

    Returns
    -------
    ndarray, (n, p)
    """
    rhs = np.array(end, dtype=float)
    if field is not None and period is not None:
        rhs = rhs + np.outer(field, period)
    if free is not None:
        return free @ np.linalg.solve(free.T @ (np.eye(monodromy.shape[0]) - monodromy) @ free, free.T @ rhs)
    return np.linalg.solve(np.eye(monodromy.shape[0]) - monodromy, rhs)


@dataclass(frozen=True)
class SteadySensitivities:
    """The amplitude of a periodic motion and its derivatives, one per parameter of ``parameters``.

    Attributes
    ----------
    parameters : tuple of str
    amplitude : float, m
        Half of ``max x - min x`` over the period.
    derivatives : ndarray, (p,)
        ``dA/dp``.
    state : ndarray, (2,)
        The fixed point ``z* = (x, v)`` at ``t = 0`` (m, m/s).
    state_derivatives : ndarray, (2, p)
        ``dz*/dp``.
    stops : int
        Stops per period.
    margin : float
        The period's smallest event margin (:attr:`~lumped.solvers.sensitivities.EventSensitivity.margin`):
        near 0, a stop appears or vanishes nearby and the derivatives are one-sided.
    """

    parameters: tuple[str, ...]
    amplitude: float
    derivatives: np.ndarray
    state: np.ndarray
    state_derivatives: np.ndarray
    stops: int
    margin: float


def steady_sensitivities(solution: ExactSolution, parameters: Sequence[str]) -> SteadySensitivities:
    """The amplitude's derivatives of the periodic motion whose one period ``solution`` is (module Notes).

    Parameters
    ----------
    solution : ExactSolution
        One forcing period, ``t_end = 2 pi/omega``, from a fixed point of the period map under a sine that
        stays on (:attr:`lumped.drivers.response.Orbit.period`'s ``solution``).
    parameters : sequence of str
        Names from :data:`STEADY_PARAMETERS`.

    Raises
    ------
    ValueError
        A parameter the periodic motion does not depend on, or a solution that is not one such period.
    """
    names = tuple(parameters)
    for name in names:
        if name not in STEADY_PARAMETERS:
            raise ValueError(
                f"parameters: the steady amplitude has no derivative in {name!r}; expected some of "
                f"{', '.join(STEADY_PARAMETERS)}"
            )
    force = solution.force
    if not (
        force.omega != 0 and math.isinf(force.until) and math.isclose(solution.t_end, 2 * math.pi / abs(force.omega))
    ):
        raise ValueError("solution: expected one period 2 pi/omega of motion under a sine that stays on")
    phases, T = solution.phases, solution.t_end
    times = np.array([p.start for p in phases] + [T])
    sens = sensitivities(solution, times, [*names, "x0", "v0"])
    p = len(names)
    end = np.array([sens.x[-1, :p], sens.v[-1, :p]])
    M = np.array([sens.x[-1, p:], sens.v[-1, p:]])
    field, dperiod = _end_field(solution), np.zeros(p)
    if "force_omega" in names:  # T = 2 pi/|omega|
        dperiod[names.index("force_omega")] = -T / force.omega
    dz = fixed_point_derivative(M, end, field, dperiod)
    dx = sens.x[:, :p] + sens.x[:, p:] @ dz  # x at each phase start and the end, the fixed point moving
    ends = solution.evaluate(np.array([0.0, T]))
    xs = np.array([ph.x_start for ph in phases] + [float(ends["x"][1])])
    hi, lo = int(np.argmax(xs)), int(np.argmin(xs))
    stops = sum(1 for e in solution.events if e.kind == "stop" and e.time > 0)
    z = np.array([ends["x"][0], ends["v"][0]])
    return SteadySensitivities(
        names, 0.5 * float(xs[hi] - xs[lo]), 0.5 * (dx[hi] - dx[lo]), z, dz, stops, sens.smallest_margin()
    )


def network_steady_sensitivities(
    period: NetworkPeriodMap, state: np.ndarray, parameters: Sequence[Parameter], names: list[str]
) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """The amplitudes of a network's periodic motion and their derivatives (module Notes).

    Parameters
    ----------
    period : NetworkPeriodMap
        One period from the fixed point ``state`` (positions, then velocities; (2n,)) under the sine of its parts.
    parameters : sequence of Parameter
        Of the kinds :data:`NETWORK_STEADY_KINDS`.
    names : list of str
        The elements' names.

    Returns
    -------
    (amplitudes (n,), their derivatives (n, p), dz*/dp (2n, p), the period's smallest event margin)
    """
    params = tuple(parameters)
    for prm in params:
        if prm.kind not in NETWORK_STEADY_KINDS:
            raise ValueError(f"parameters: the steady amplitude does not depend on the {prm.kind} of a mass or load")
    n, T, k = period.parts.m.size, period.t_end, len(params)
    (hi, t_hi), (lo, t_lo) = period.extremes
    times = np.unique(np.concatenate([t_hi, t_lo, [T]]))
    own = [Parameter("x0", i) for i in range(n)] + [Parameter("v0", i) for i in range(n)]
    sens = network_sensitivities(period.parts, state[:n], state[n:], times, [*params, *own], names)
    end = np.concatenate([sens.x[-1, :, :k], sens.v[-1, :, :k]])
    monodromy = np.concatenate([sens.x[-1, :, k:], sens.v[-1, :, k:]])
    last = period.phases[-1]
    _, v_end, a_end, _ = last.values(last.z(T))
    dperiod = np.array([-T / period.parts.loads[0][1].omega if prm.kind == "omega" else 0.0 for prm in params])
    free = period.free_basis if period.held.size else None
    dz = fixed_point_derivative(monodromy, end, np.concatenate([v_end, a_end]), dperiod, free)
    at_events = {e.event.time: e.x for e in sens.events}

    def dx(i: int, t: float) -> np.ndarray:
        """``d x_i/dp`` at the extreme at ``t``, the fixed point moving."""
        if t == 0.0 or t == T:
            return dz[i]
        if t in at_events:  # the position at the event, its time moving
            d = at_events[t]
        else:  # a zero of v_i: the time held
            d = sens.x[int(np.searchsorted(times, t)), :, :]
        return d[i, :k] + d[i, k:] @ dz

    derivatives = np.array([0.5 * (dx(i, t_hi[i]) - dx(i, t_lo[i])) for i in range(n)])
    return 0.5 * (hi - lo), derivatives, dz, sens.smallest_margin()


def _end_field(solution: ExactSolution) -> np.ndarray:
    """``f = (v, a)`` at ``t_end``: zero in a stick."""
    last = solution.phases[-1]
    if last.motion is None:
        return np.zeros(2)
    x, v = (float(a) for a in last.motion.state(solution.t_end))
    return np.array([v, last.motion.acceleration(solution.t_end, x, v)])
