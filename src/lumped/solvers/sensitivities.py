"""Exact derivatives of the one-mass ``exact`` solution with respect to its parameters (forward sensitivities).

The exact solution (:func:`lumped.solvers.exact.solve_exact`) is a chain of
phases; :func:`sensitivities` differentiates it, phase by phase, with
respect to every numeric parameter (:data:`PARAMETER_NAMES`): the motion
``x(t), v(t)`` at any times and the events' times and positions, hence the
summaries (stop times, the rest time and the rest position).  It extends the
monodromy of :mod:`lumped.solvers.monodromy` (derivatives with respect to
the initial state only) to the system's parameters, with the same rules at
events; its ``x0`` and ``v0`` columns at the end of a forcing period are that
module's matrix (``tests/test_sensitivities.py`` checks it).

Notes
-----
The derivative is carried as ``D = d(t, x, v)/dq`` (3 x 10) at the start of
each phase, for the canonical parameters ``q = (m, k, tau, c, x0, v0, P, w,
ph, t_off)`` (``c = 1/gamma``, the force ``P sin(w t + ph)`` in its canonical
form, on until ``t_off``); :func:`sensitivities` maps them to the parameters
asked for at the end.

* **slip** in direction ``s``: the state ``y = (x, v, sin theta, cos theta,
  1)`` (``theta = w t + ph``) obeys the autonomous linear ODE ``y' = M y``,
  ``M`` holding ``-k/m, -c/m, P/m, -s tau/m`` and ``w``.  A parameter's
  derivative at a fixed time, ``u_j = dy/dq_j``, obeys ``u_j' = M u_j +
  (dM/dq_j) y``; both are solved at once by the matrix exponential of the
  block matrix ``[[M, 0], [dM/dq, I (x) M]]`` (Van Loan, *Computing integrals
  involving the matrix exponential*, IEEE Trans. Automat. Control 23 (1978)
  395-404).  The phase starts at ``t_a(q)``, so ``u_j(t_a) = dy_a/dq_j -
  f(t_a, y_a) dt_a/dq_j``, ``f = M y`` the phase's own field (this is the
  saltation of the switch that began the phase, as in the monodromy).
* a phase that ends where ``v = 0`` (a **stop** or a **reversal**) ends at
  ``t_b`` with ``dt_b = -dv_b/a_b``, ``a_b = v'(t_b-)``: then ``dx = dx_b``
  and ``dv = 0`` (the event rule ``dt_e = -(dg/dq + dg/dz dz/dq)/(dg/dt)``
  with ``g = v``).  A phase ended by the force going off moves with ``t_off``:
  ``dt_b = dt_off/dq``, and the state at it gains ``f(t_b-) dt_b``.
* **stick** at ``x_b``: ``v = 0`` whatever the parameters, so ``dv = 0`` (the
  projection); the **breakaway** at ``t_c`` where ``g = F(t_c) - k x_b - s
  tau = 0`` moves by ``dt_c = -(dF/dq - x_b dk/dq - k dx_b - s dtau/dq) /
  F'(t_c)``.

Where the sequence of events changes with a parameter (a stop with the net
force on the edge of the static band, where it turns into a reversal; a
v = 0 reached with zero acceleration; a breakaway where the force only
touches the band) the solution is not differentiable; each event carries its
distance from such a change (:attr:`EventSensitivity.margin`);
:class:`RestSwitch` gives the free decay's rest across one in closed form, and
:func:`lumped.solvers.one_sided.one_sided` the one-sided derivatives and the
jumps of any run.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from lumped.solvers.events import Event
from lumped.solvers.exact import ExactSolution
from lumped.solvers.sensitivity_chain import C_, K_, M_, OFF_, P_, PH_, TAU_, V0_, W_, X0_, Chain, Load, N, direction

__all__ = ["PARAMETER_NAMES", "EventSensitivity", "RestSwitch", "Sensitivities", "sensitivities"]

#: The parameters of a one-mass run, by the single-mass API's names
#: (:data:`lumped.model.parameters.PARAMETERS`), and ``viscosity = 1/gamma`` (N s/m).
PARAMETER_NAMES = (
    "mass",
    "stiffness",
    "threshold",
    "gamma",
    "viscosity",
    "x0",
    "v0",
    "force_amplitude",
    "force_omega",
    "force_phase",
    "force_until",
)


@dataclass(frozen=True)
class EventSensitivity:
    """An event with the derivatives of its time and position, one per parameter.

    ``margin`` (dimensionless, ``>= 0``) is how far the event is from a
    change of the event sequence, in units of the threshold: for a stop
    ``(tau - |net|)/tau`` (the band edge, where it becomes a reversal) and
    ``|m a|/tau`` (``v`` reaching zero with zero acceleration), for a
    reversal ``(|net| - tau)/tau``, for a breakaway ``|F'| / (P w)`` (the
    force only touching the band's edge); ``inf`` for the force going off.
    Near 0 the derivatives are one-sided.
    """

    event: Event
    time: np.ndarray
    x: np.ndarray
    margin: float


@dataclass(frozen=True)
class RestSwitch:
    """The rest just across the nearest change in the number of half-cycles of a free decay.

    ``kind`` is ``"gain"`` (the stop that begins the rest, at the band edge,
    turns into a reversal and one more half-cycle follows, of vanishing
    amplitude) or ``"lose"`` (the last reversal, at the band edge, turns into
    that stop).  ``event`` is that stop or reversal and ``margin`` its
    :attr:`EventSensitivity.margin`: at ``margin = 0`` the rest position is
    continuous but has a kink, ``rest_position`` being its derivative on
    the other side (exact there; elsewhere the value just across the switch,
    to first order in the margin), and the rest time jumps by
    ``rest_time_jump`` (s: half a damped period for a gain, ``inf`` when the
    free motion does not oscillate; minus the last half-cycle's duration for
    a loss).  Derived in :func:`_gain`.
    """

    kind: str
    event: Event
    margin: float
    rest_position: np.ndarray
    rest_time_jump: float


@dataclass(frozen=True)
class Sensitivities:
    """Derivatives of an exact one-mass solution, one column per parameter of ``parameters``.

    Attributes
    ----------
    parameters : tuple of str
        Names from :data:`PARAMETER_NAMES`.
    t : ndarray, (n,), s
    x, v : ndarray, (n, p)
        ``dx/dp`` and ``dv/dp`` at the times ``t`` (held fixed).
    events : tuple of EventSensitivity
        Every stop, reversal, breakaway and switch (the force going off), in time order.
    rest_time, rest_position : ndarray, (p,)
        Derivatives of the solution's ``rest_time`` and ``rest_position``
        (``nan`` where it has no rest).
    switches : tuple of RestSwitch
        The rest across the switches nearest to this one (none without a rest
        under a force that is zero for ever).
    """

    parameters: tuple[str, ...]
    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    events: tuple[EventSensitivity, ...]
    rest_time: np.ndarray
    rest_position: np.ndarray
    switches: tuple[RestSwitch, ...] = ()

    def stop_times(self) -> np.ndarray:
        """``d(time)/dp`` of every stop, (stops, p)."""
        rows = [e.time for e in self.events if e.event.kind == "stop"]
        return np.array(rows).reshape(len(rows), len(self.parameters))

    def smallest_margin(self) -> float:
        """The smallest event margin (``inf`` without events): near 0, the derivatives are one-sided."""
        return min((e.margin for e in self.events), default=math.inf)


def sensitivities(
    solution: ExactSolution, t: np.ndarray | Sequence[float] = (), parameters: Sequence[str] = PARAMETER_NAMES
) -> Sensitivities:
    """The derivatives of an exact one-mass solution with respect to ``parameters`` (module Notes).

    Parameters
    ----------
    solution : ExactSolution
        From :func:`~lumped.solvers.exact.solve_exact`.
    t : array_like, (n,), s
        Times in ``[0, t_end]`` at which to differentiate ``x`` and ``v`` (none by default).
    parameters : sequence of str
        Names from :data:`PARAMETER_NAMES`: ``gamma`` is the dashpot's ``gamma``
        (m/(N s); its derivatives are ``-c^2`` those of ``viscosity = c = 1/gamma``,
        so 0 for a Coulomb dashpot, ``gamma = inf``); the force's are those of the
        :class:`~lumped.model.forcing.SwitchedSine` given to the solver.

    Returns
    -------
    Sensitivities

    Raises
    ------
    ValueError
        An unknown parameter, a time outside ``[0, t_end]``, or a solution that is not an ``ExactSolution``.
    """
    if not isinstance(solution, ExactSolution):
        raise ValueError(f"solution must be an ExactSolution, got {type(solution).__name__}")  # noqa: TRY004 (the API's one error type)
    if isinstance(parameters, str) or not isinstance(parameters, Sequence):
        raise ValueError(f"parameters must be a sequence of names such as ('x0', 'threshold'), got {parameters!r:.60}")
    names = tuple(parameters)
    for name in names:
        if name not in PARAMETER_NAMES:
            raise ValueError(f"parameters: unknown parameter {name!r}; expected some of {', '.join(PARAMETER_NAMES)}")
    t = np.asarray(t, dtype=float).ravel()
    bad = ~((t >= 0) & (t <= solution.t_end))
    if bad.any():
        raise ValueError(f"t: times must lie in [0, t_end] = [0, {solution.t_end!r}] s, got {float(t[bad][0])!r}")
    cols = _columns(solution, names)
    chain = Chain(solution, tuple(np.flatnonzero(cols.any(axis=1))))
    dx, dv = chain.sample(solution, t)
    events = []
    for e in solution.events:
        if (found := chain.at_events.get((e.time, e.kind))) is not None:
            events.append(EventSensitivity(e, found[0][0] @ cols, found[0][1] @ cols, found[1]))
    rest = _rest(solution, chain) @ cols
    switches = _switches(solution, tuple(events), cols)
    return Sensitivities(names, t, dx @ cols, dv @ cols, tuple(events), rest[0], rest[1], switches)


def _rest(solution: ExactSolution, chain: Chain) -> np.ndarray:
    """``d(rest_time, rest_position)/dq`` (2 x 10): ``D`` at the start of the stick that begins the rest."""
    if math.isnan(solution.rest_time):
        return np.full((2, N), math.nan)
    first = next(i for i, p in enumerate(solution.phases) if p.kind == "stick" and p.start >= solution.rest_time)
    return chain.starts[first][:2]


def _columns(solution: ExactSolution, names: tuple[str, ...]) -> np.ndarray:
    """The map (10 x p) from the canonical parameters' derivatives to those of ``names``."""
    load, c = Load.of(solution.force), solution.oscillator.dashpot.bingham_form().viscosity
    out = np.zeros((N, len(names)))
    rows = {
        "mass": {M_: 1.0},
        "stiffness": {K_: 1.0},
        "threshold": {TAU_: 1.0},
        "viscosity": {C_: 1.0},
        "gamma": {C_: -c * c},  # dc/dgamma = -1/gamma^2: 0 for Coulomb
        "x0": {X0_: 1.0},
        "v0": {V0_: 1.0},
        "force_amplitude": {P_: load.sign_p},
        "force_omega": {W_: load.sign_w},  # omega < 0: w = -omega, ph = pi - phase
        "force_phase": {PH_: load.sign_w},
        "force_until": {OFF_: 1.0},
    }
    for j, name in enumerate(names):
        for i, value in rows[name].items():
            out[i, j] = value
    return out


def _switches(
    solution: ExactSolution, events: tuple[EventSensitivity, ...], cols: np.ndarray
) -> tuple[RestSwitch, ...]:
    """The :class:`RestSwitch` es of a rest under a force zero from the last stop on (none otherwise)."""
    if math.isnan(solution.rest_time):
        return ()
    load = Load.of(solution.force)
    free = [e for e in events if e.event.kind in ("stop", "reversal") and (load.P == 0 or not load.on(e.event.time))]
    if not free or free[-1].event.kind != "stop" or free[-1].event.time != solution.rest_time:
        return ()
    stop, out = free[-1], [_gain(solution, free[-1], cols)]
    before = [e for e in events if e.event.time < stop.event.time]
    if len(free) > 1 and before and before[-1] is free[-2]:  # the last slip ran from that reversal to the stop
        last = free[-2]
        out.append(RestSwitch("lose", last.event, last.margin, last.x, last.event.time - stop.event.time))
    return tuple(out)


def _gain(solution: ExactSolution, stop: EventSensitivity, cols: np.ndarray) -> RestSwitch:
    """The rest after one more half-cycle from the stop ``stop`` at the band edge.

    Notes
    -----
    Having slipped with sign ``s`` to ``x_s = s tau/k`` (the band edge), the
    mass reverses with the centre ``c' = s tau/k`` of the free motion in
    direction ``-s``, from the offset ``x_s - c'``; half a damped period
    ``pi/q`` later it stops at ``c' - rho (x_s - c')``, ``rho = exp(-pi h/q)``.
    So its derivative is ``(1 + rho) dc' - rho dx_s`` at the edge (where the
    offset vanishes), with ``dc' = s (dtau/k - tau dk/k^2)``.  Without
    oscillation (``c >= 2 sqrt(k m)``) it creeps to ``c'`` for ever: ``rho =
    0`` and the rest time is infinite.
    """
    from lumped.solvers.closed_form import _modes

    osc = solution.oscillator
    m, k, tau = osc.mass, osc.stiffness, osc.threshold
    modes = _modes(m, osc.dashpot.bingham_form().viscosity, k)
    s = next(direction(p) for p in solution.phases if p.motion is not None and p.end == stop.event.time)
    rho, jump = (
        (math.exp(-math.pi * modes.h / modes.q), math.pi / modes.q) if modes.kind == "under" else (0.0, math.inf)
    )
    centre = s * (cols[TAU_] / k - tau * cols[K_] / k**2)
    return RestSwitch("gain", stop.event, stop.margin, (1 + rho) * centre - rho * stop.x, jump)
