"""The ``exact`` method: the exact piecewise solution for a linear spring and a Bingham or Coulomb dashpot.

The motion is a sequence of phases, slip and stick, ended by events (stop,
reversal, breakaway, switch (the force going off), rest), marched by
:class:`~lumped.solvers.events.PhaseMarch`.  Slip phases are solved in closed
form (:class:`~lumped.solvers.closed_form.SlipMotion`: a linear ODE with
constant coefficients, its stops found in closed form or refined with Brent's
method to a few ulps of the phase time); stick phases are exact (eq. 11c) and
breakaways are solved in closed form with ``arcsin``.  :class:`ExactSolution`
holds the phases and events and evaluates the solution at any time.

Before marching, :func:`solve_exact` refuses (with a ``ValueError`` naming the
argument to change) runs whose forces could overflow, whose forcing phase
carries no significant digit, or that would have more than ``max_events``
events; so every run either finishes quickly or stops at once.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from lumped.laws import coulomb
from lumped.model.forcing import SwitchedSine, as_sine
from lumped.model.oscillator import MAGNITUDE_LIMIT, Oscillator, check_magnitudes
from lumped.model.trajectory import COLUMNS, Trajectory
from lumped.numerics import validate
from lumped.numerics.sine import MAX_ARGUMENT
from lumped.solvers.closed_form import SlipMotion, _Modes, _modes
from lumped.solvers.events import Event, Phase, PhaseMarch, SlipFactory

__all__ = ["ExactSolution", "MAX_PHASE", "solve_exact"]

#: Largest forcing argument ``|omega| t + |phase|`` (rad): the range of the
#: project's sine (:data:`lumped.numerics.sine.MAX_ARGUMENT`), the one bound that every
#: method, the sweep and the command line share.
MAX_PHASE = MAX_ARGUMENT


def _finite(quantity: str, values: np.ndarray, t: np.ndarray) -> None:
    """Refuse a non-finite value of a computed ``quantity`` (never return NaN or inf)."""
    bad = ~np.isfinite(values)
    if bad.any():
        raise ValueError(
            f"t_end: the exact solution's {quantity} is not finite at t = "
            f"{float(np.asarray(t)[bad][0]):.6g} s (beyond double precision); "
            "shorten t_end or bring the parameters nearer unity"
        )


@dataclass(frozen=True, eq=False)
class ExactSolution:
    """The exact solution as phases and events, evaluable at any time in ``[0, t_end]``.

    Attributes
    ----------
    phases : tuple of Phase
    events : tuple of Event
    rest_time : float
        Time (s) from which the mass stays at rest *for ever*: a stop after
        which the force is zero for all later times.  ``nan`` if it is still
        moving at ``t_end``, or sticks there under a force that is still on
        (and so could move again).  For the rest at the end of a sampled grid,
        whatever happens later, see ``Trajectory.final_rest`` from
        :meth:`sample`.
    rest_position : float
        Displacement (m) at that rest; ``nan`` likewise.
    x0, v0 : float
        The initial state, kept so that :meth:`sample` can extend the solution.
    max_events : int
        The bound the solution was computed with.
    """

    #: The ``Trajectory.method`` of :meth:`sample`.
    method: ClassVar[str] = "exact"
    oscillator: Oscillator
    force: SwitchedSine
    t_end: float
    phases: tuple[Phase, ...]
    events: tuple[Event, ...]
    rest_time: float
    rest_position: float
    x0: float = 0.0
    v0: float = 0.0
    max_events: int = 100_000

    def stick_intervals(self) -> list[tuple[float, float]]:
        """``(start, end)`` of every stick phase (s), merged across forcing switches."""
        return [(a, b) for a, b, _ in self._stick_runs()]

    def _stick_runs(self) -> list[tuple[float, float, float]]:
        """``(start, end, x)`` of the merged stick phases."""
        out: list[tuple[float, float, float]] = []
        for p in self.phases:
            if p.kind != "stick":
                continue
            if out and out[-1][1] == p.start:
                out[-1] = (out[-1][0], p.end, out[-1][2])
            else:
                out.append((p.start, p.end, p.x_start))
        return out

    def rest_through(self, t: float) -> tuple[float, float]:
        """``(start, x)`` of the stick interval holding at time ``t``, or ``(nan, nan)``.

        At ``t = t_end`` this is the rest at the end of the run, with the exact
        event time of its start; it may end later (contrast ``rest_time``).
        """
        for a, b, x in reversed(self._stick_runs()):
            if a <= t <= b:
                return (a, x)
        return (math.nan, math.nan)

    def event_times(self, kind: str) -> np.ndarray:
        """Times (s) of all events of one kind."""
        return np.array([e.time for e in self.events if e.kind == kind])

    def evaluate(self, t: np.ndarray) -> dict[str, np.ndarray]:
        """Columns ``t, x, v, F_s, F_d, F`` at times ``t`` in ``[0, t_end]``.

        Raises
        ------
        ValueError
            If a time lies outside ``[0, t_end]`` (no extrapolation), or a
            value is not finite.
        """
        t = np.asarray(t, dtype=float)
        outside = ~((t >= 0) & (t <= self.t_end))
        if outside.any():
            raise ValueError(
                f"t: times must lie in [0, t_end] = [0, {self.t_end!r}] s, got {float(t[outside].flat[0])!r}"
            )
        which, x, v = self._phase_states(t)
        k, law = self.oscillator.stiffness, self.oscillator.dashpot
        force = np.asarray(self.force(t), dtype=float)
        f_d = np.where(v == 0, force - k * x, law.slip_force(v))
        slip = np.array([p.motion is not None for p in self.phases])[which]
        direction = np.array([np.sign(p.motion.s_tau) if p.motion else 0 for p in self.phases])
        f_d = np.where(slip & (v == 0), direction[which] * law.threshold, f_d)
        cols = dict(zip(COLUMNS, (t, x, v, k * x, f_d, force)))
        for name in COLUMNS[1:]:
            _finite(name, cols[name], t)
        return cols

    def _phase_states(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Index of the phase holding at each ``t``, and ``x, v`` there."""
        x, v = np.empty_like(t), np.zeros_like(t)
        starts = np.array([p.start for p in self.phases])
        which = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(starts) - 1)
        order = np.argsort(which, kind="stable")  # indices grouped by phase, O(n log n)
        bounds = np.searchsorted(which[order], np.arange(len(self.phases) + 1))
        for p, lo, hi in zip(self.phases, bounds[:-1], bounds[1:]):
            sel = order[lo:hi]
            if p.motion is None:
                x[sel] = p.x_start
            elif sel.size:
                x[sel], v[sel] = p.motion.state(t[sel])
        return which, x, v

    def extended(self, t_end: float) -> ExactSolution:
        """The same motion solved to a later ``t_end`` (``self`` if not later)."""
        if t_end <= self.t_end:
            return self
        return solve_exact(self.oscillator, t_end, x0=self.x0, v0=self.v0, force=self.force, max_events=self.max_events)

    def sample(self, dt: float, save_every: int = 1) -> Trajectory:
        """The exact solution on the grid ``t_n = n*dt`` used by backward Euler.

        The grid ends at the first ``t_N >= t_end`` (:func:`lumped.numerics.validate.step_count`);
        when ``t_N`` lies past ``t_end`` (by any amount, round-off included) the
        motion is solved again to ``t_N``, so every value is the exact solution
        at its time.  ``final_rest`` is :meth:`rest_through` at ``t_N``.
        """
        _, dt, save_every, n = validate.grid(self.t_end, dt, save_every)
        validate.output_size(n, save_every)
        index = np.arange(0, n + 1, save_every)
        if index[-1] != n:
            index = np.append(index, n)
        times = index * dt
        sol = self.extended(float(times[-1]))
        return Trajectory.of_oscillator(
            **sol.evaluate(times),
            oscillator=self.oscillator,
            method=self.method,
            dt=dt,
            save_every=save_every,
            final_rest=sol.rest_through(float(times[-1])),
            events=tuple(e for e in sol.events if e.time <= times[-1]),
        )


def _half_cycles_to_rest(amplitude: float, band: float, modes: _Modes) -> float:
    """Half-cycles of free decay from a turning point at ``|x| = amplitude`` to rest.

    Notes
    -----
    Moving with sign ``s`` the mass oscillates about ``-s band`` (``band =
    tau/k``) and each half-cycle shrinks the offset by ``rho = exp(-pi h/q)``,
    so the turning points obey ``u' = rho (u - band) - band``, that is
    ``u_n + beta = rho^n (u_0 + beta)`` with ``beta = band (1 + rho)/(1 - rho)``.
    The mass stops at the first ``u_n <= band``.  Without viscosity
    (``rho = 1``) ``u`` falls by ``2 band`` per half-cycle; with real roots the
    velocity vanishes at most once.
    """
    if amplitude <= band:
        return 0.0
    if modes.kind != "under":
        return 1.0
    if band == 0:
        return math.inf
    decrement = math.pi * modes.h / modes.q  # log(1/rho)
    if decrement == 0:
        return (amplitude - band) / (2 * band)
    one_minus_rho = -math.expm1(-decrement)
    beta = band * (2 - one_minus_rho) / one_minus_rho
    return math.log1p((amplitude - band) / (band + beta)) / decrement


def _event_estimate(osc: Oscillator, force: SwitchedSine, t_end: float, x0: float, v0: float) -> float:
    """About how many events the solution has before ``t_end`` (an upper estimate).

    While the force acts (for ``t_on``) a slipping mass reverses at most about
    every half damped period ``pi/q`` and sticks, breaks away and stops a
    few times per forcing period: ``t_on (q + 2 omega)/pi``.  Afterwards the
    free decay takes :func:`_half_cycles_to_rest` from the largest amplitude
    the energy allows, ``|x0| + sqrt(m/k)|v0| + 2 P t_on / sqrt(m k)`` (the
    bound of :func:`~lumped.model.oscillator.check_magnitudes`), and at most
    ``(t_end - t_on) q/pi + 1`` half-cycles fit before ``t_end``.
    """
    m, k = osc.mass, osc.stiffness
    modes = _modes(m, osc.dashpot.bingham_form().viscosity, k)
    P, w, _ = (0.0, 0.0, 0.0) if force.is_zero else force.canonical()
    t_on = min(t_end, force.until) if P else 0.0
    forced = t_on * (modes.q + 2 * w) / math.pi + 2 if P else 0.0
    amplitude = (
        abs(x0) + math.sqrt(m / k) * abs(v0) + 2 * P * t_on / (math.sqrt(m) * math.sqrt(k))
    )  # sqrt(m k) underflows at m = 1e-200
    band = osc.dashpot.threshold / k
    fit = (t_end - t_on) * modes.q / math.pi + 1
    cycles = min(_half_cycles_to_rest(amplitude, band, modes), fit)
    return forced + cycles + 2


def _check_inputs(osc: Oscillator, force: SwitchedSine, t_end: float, x0: float, v0: float, max_events: int) -> None:
    """Refuse, before any work, runs that would overflow, lose the phase or take too long.

    Notes
    -----
    The energy bound of :func:`~lumped.model.oscillator.check_magnitudes` is applied to
    the Coulomb version of the oscillator with ``dt = max(t_on, sqrt(m/k))``:
    the exact solution forms no backward-Euler predictor, and with that
    ``dt`` its momentum term is at most the spring-force bound.  The viscous
    force is checked here instead: in slip ``m v' = G - c v`` with ``|G| <=
    |F| + |F_s| + tau``, so ``c|v|`` never exceeds ``max(c|v0|, max|G|)``.
    """
    check_scales(osc, force, t_end, x0, v0)
    if not osc.dashpot.bingham_form().viscosity * abs(v0) <= MAGNITUDE_LIMIT:
        raise ValueError(f"v0: the initial viscous force |v0|/gamma exceeds {MAGNITUDE_LIMIT:.0e} N; lower v0")
    estimate = _event_estimate(osc, force, t_end, x0, v0)
    if estimate > max_events:
        shown = f"{estimate:.2g}" if estimate < 1e300 else "more than 1e300"
        raise ValueError(
            f"t_end: the exact solution would have about {shown} events before t_end, more than the "
            f"{max_events} a run may have; shorten t_end or use backward Euler"
        )


def check_scales(osc: Oscillator, force: SwitchedSine, t_end: float, x0: float, v0: float) -> None:
    """Refuse a forcing argument beyond :data:`MAX_PHASE` or forces that could overflow (any dashpot law).

    The Coulomb part of the bound of :func:`_check_inputs`; it uses only the
    threshold of the dashpot, so every event-driven solver shares it.
    """
    P = 0.0 if force.is_zero else force.canonical()[0]
    t_on = min(t_end, force.until) if P else t_end
    force.check_span(t_end)
    m, k = osc.mass, osc.stiffness
    dt = max(t_on, math.sqrt(m) / math.sqrt(k))
    coulomb_part = _coulomb_part(osc)
    check_magnitudes(coulomb_part, t_on, dt, x0, v0, P, carries_force=False)  # x is carried, not F_s = k x


@functools.lru_cache(maxsize=64)
def _coulomb_part(osc: Oscillator) -> Oscillator:
    """``osc`` with its dashpot's Coulomb part alone (built once per oscillator: a response curve solves one
    oscillator thousands of times)."""
    return dataclasses.replace(osc, dashpot=coulomb(osc.threshold))


def _closed_form(osc: Oscillator) -> SlipFactory:
    """The exact method's slip phases: :class:`~lumped.solvers.closed_form.SlipMotion`."""
    m, k, tau = osc.mass, osc.stiffness, osc.threshold
    c = osc.dashpot.bingham_form().viscosity
    return lambda t, x, v, direction, forcing: SlipMotion(m, c, k, direction * tau, *forcing, t, x, v)


def solve_exact(
    oscillator: Oscillator,
    t_end: float,
    *,
    x0: float = 0.0,
    v0: float = 0.0,
    force: SwitchedSine | None = None,
    max_events: int = 100_000,
) -> ExactSolution:
    """Exact solution of the DAE (8) for a Bingham or Coulomb dashpot.

    A shim of the one entry point, kept for what it adds:
    ``lumped.solve(Problem.oscillator(oscillator, t_end, x0=x0, v0=v0,
    force=force), dt, method="exact")`` samples this solution on a grid
    (:meth:`ExactSolution.sample`); called directly it returns the solution in
    continuous time (its phases and events, the motion at any time), which
    the sensitivities and the studies read, and takes ``max_events``.

    Parameters
    ----------
    oscillator : Oscillator
        Its dashpot law must have a Bingham form (the law's contract, point 6):
        a :class:`~lumped.laws.BinghamDashpot` (any ``gamma``, ``inf``
        included) or a Herschel-Bulkley law of exponent 1, the linear dashpot
        (``threshold = 0``) among them.
    t_end : float, s
        Final time ``> 0``.
    x0, v0 : float, m and m/s
        Initial state; any velocity is allowed.
    force : SwitchedSine or None
        ``P sin(omega t + phase)`` until ``t_off``, zero afterwards.
    max_events : int
        Bound on the number of events.  A run estimated up front to exceed it
        is refused at once (:func:`_event_estimate`); the march also stops
        there.

    Returns
    -------
    ExactSolution

    Raises
    ------
    ValueError
        One line beginning with the argument to change: bad input, forces
        that could overflow (``x0``, ``v0``, ``force_amplitude``), a forcing
        argument ``|omega| t + |phase|`` above :data:`MAX_PHASE` (``force_omega``), more than
        ``max_events`` events (``t_end``), or a value that is not finite.
    """
    if not isinstance(oscillator, Oscillator):
        raise ValueError(f"oscillator must be an Oscillator, got {type(oscillator).__name__}")
    if oscillator.dashpot.bingham_form() is None:  # the closed forms (the law's contract, point 6)
        raise ValueError("dashpot: the exact solver needs a BinghamDashpot (any gamma)")
    if force is not None and as_sine(force) is None:
        raise ValueError("force: the exact solver needs a SwitchedSine or None")
    t_end = validate.positive("t_end", t_end)
    x0, v0 = validate.finite("x0", x0), validate.finite("v0", v0)
    max_events = validate.positive_int("max_events", max_events)
    force = as_sine(force) or SwitchedSine()
    _check_inputs(oscillator, force, t_end, x0, v0, max_events)
    build = PhaseMarch(oscillator, force, t_end, max_events, _closed_form(oscillator))
    build.run(x0, v0)
    events = tuple(sorted(build.events, key=lambda e: e.time))  # "rest" is dated back
    _finite("event time", np.array([e.time for e in events]), np.array([e.time for e in events]))
    _finite("displacement", np.array([p.x_start for p in build.phases]), np.array([p.start for p in build.phases]))
    return ExactSolution(
        oscillator, force, t_end, tuple(build.phases), events, *build.rest, x0=x0, v0=v0, max_events=max_events
    )
