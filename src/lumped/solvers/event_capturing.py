"""The ``event-locating`` method: trapezoidal steps within modes, switching at located events.

What it is, in the vocabulary of nonsmooth dynamics (Acary and Brogliato,
*Numerical Methods for Nonsmooth Dynamical Systems*, 2008): an *event-driven*
scheme on a fixed grid, that is, time stepping *with event location*.  It
integrates each smooth mode and locates every switch inside its step, so it is
not an event-capturing (time-stepping) scheme such as Algorithm 1 or
``moreau-jean``, which write the step as a set-valued problem and see a switch
only at a grid point, at most first order through it.  The module and the
function keep their first name, ``event_capturing``; the registry's method is
``event-locating``, with ``event-capturing`` as its alias
(:data:`lumped.drivers.methods.ALIASES`).

:func:`event_capturing` marches on the grid ``t_n = n*dt`` of Algorithm 1
(:mod:`lumped.solvers.grid`) and returns a
:class:`~lumped.model.trajectory.Trajectory` there, with the events it
found.  It takes trapezoidal steps (the θ-method of
:mod:`lumped.solvers.theta` at ``theta = 1/2``) *within* one mode (slip in
a direction, or stick), checks after each step whether the mode still
holds, and when it does not, locates the switch inside the step, takes the
partial step to it, applies the switching rule and completes the step.  It
keeps order two through stops, reversals, breakaways and the switch-off of
the forcing.

Why the trapezoidal rule inside the modes, and not a Radau IIA or a
Runge-Kutta method of higher order: its step is one scalar monotone equation,
the resolvent of the dashpot graph, so every law of :mod:`lumped.laws`
(closed form for Bingham and Coulomb, a bracketed root for any monotone law)
is stepped by the contract it already provides, without derivatives of the
law, which Herschel-Bulkley laws lack at ``v = 0``.  It is A-stable, so a
stiff viscous branch (small ``gamma``) does not limit the step.  Order two is
what the issue asks for: with the switches located to third order locally,
the global error is ``O(dt^2)``, which at ``dt = 1e-4`` is far below the
first-order error of Algorithm 1 (Acary and Brogliato 2008, chapter 9, on
event-capturing and event-driven schemes; the switching rule is that of
:mod:`lumped.solvers.exact`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from lumped.laws import sticks
from lumped.model.forcing import SwitchedSine, as_sine
from lumped.model.oscillator import Oscillator, check_magnitudes
from lumped.model.trajectory import COLUMNS, Trajectory
from lumped.numerics import validate
from lumped.numerics.roots import brentq
from lumped.solvers.events import STICK, Event, EventMarch, Piece
from lumped.solvers.grid import start_run

__all__ = ["CapturedRun", "event_capturing"]

#: Bound on the switches located within one grid step (each a root search).
MAX_SWITCHES_PER_STEP = 64
#: Halvings of a substep tried to find where a slip started at rest is moving.
_HALVINGS = 40
_EPS = float(np.finfo(float).eps)


def _root(f: Callable[[float], float], a: float, b: float, xtol: float | None = None) -> float:
    """Brent's root of ``f`` on ``[a, b]`` (signs opposite), to about an ulp of ``b`` (or to ``xtol``)."""
    return brentq(f, a, b, xtol=_EPS * abs(b) if xtol is None else xtol)


class CapturedRun(NamedTuple):
    """Result of :func:`event_capturing`: the grid ``trajectory`` and the located ``events``.

    ``events`` are :class:`~lumped.solvers.events.Event` with the kinds of the
    exact solver: ``"stop"``, ``"reversal"``, ``"breakaway"``,
    ``"switch"`` and ``"rest"`` (a stop after which the force stays zero,
    dated back to the start of that stick).
    """

    trajectory: Trajectory
    events: tuple[Event, ...]

    def event_times(self, kind: str) -> np.ndarray:
        """Times (s) of the events of one kind."""
        return np.array([e.time for e in self.events if e.kind == kind])


class _State(NamedTuple):
    """``mode`` is ``STICK`` (0) or the slip direction ``+-1``; ``hold`` a time before which stick is kept."""

    t: float
    x: float
    v: float
    f_d: float
    mode: int
    hold: float = -math.inf


class _Capture(EventMarch):
    """The event-locating march over the time grid; :func:`event_capturing` is its only user.

    The events, forcing pieces and switching rules are those of
    :class:`~lumped.solvers.events.EventMarch`; the forcing is the switched
    sine as given (not canonical), evaluated with the project's sine.
    """

    def __init__(self, osc: Oscillator, force: SwitchedSine) -> None:
        on = Piece(0.0 if force.is_zero else force.amplitude, force.omega, force.phase, force.until)
        super().__init__(osc, force, on)
        self.law, self.resolvent = osc.dashpot, osc.dashpot.band_free_resolvent()  # contract point 8
        self.stick_since = math.nan

    def slip_step(self, s: int, st: _State, h: float, p: Piece) -> tuple[float, float, float]:
        """Trapezoidal step of size ``h`` in slip mode ``s``: ``(x, v, F_d)`` (see :func:`.theta.theta_step`)."""
        m, k = self.m, self.k
        g_now = p(st.t) - k * st.x - st.f_d
        eta = 2 * m / h + k * h / 2
        predictor = (2 * m / h) * st.v + p(st.t + h) - k * st.x + g_now - (k * h / 2) * st.v
        u, v = self.resolvent(predictor - s * self.tau, eta)
        return st.x + h / 2 * (st.v + v), v, s * self.tau + u

    def enter_stick(self, t: float, x: float, f_d: float, hold: float) -> _State:
        """Stick from ``t``; record ``"rest"`` when the force is zero for ever."""
        if math.isnan(self.stick_since):
            self.stick_since = t
        st = _State(t, x, 0.0, f_d, STICK, hold)
        self.check_rest(st)
        return st

    def check_rest(self, st: _State) -> None:
        """Record ``"rest"`` (dated at the start of the stick) once the force is zero for ever."""
        if st.mode == STICK and self.piece(st.t).zero_for_ever:
            self.record_rest(self.stick_since, st.x)

    def at_zero_velocity(self, st: _State, s: int) -> _State:
        """Switching rule at ``v = 0`` after slipping with direction ``s`` (:meth:`.EventMarch.stop_or_reverse`)."""
        net = self.net(st.t, st.x)
        mode = self.stop_or_reverse(st.t, st.x, s, net)
        if mode != STICK:
            return _State(st.t, st.x, 0.0, mode * self.tau, mode)
        return self.enter_stick(st.t, st.x, net, hold=-math.inf)

    def breakaway(self, st: _State, s: int, kind: str = "breakaway") -> _State:
        """Slip from rest in direction ``s``; ``kind=""`` records no event (as the exact solver at ``t_off``)."""
        if kind:
            self.event(st.t, kind, st.x, s)
        self.stick_since = math.nan
        return _State(st.t, st.x, 0.0, s * self.tau, s)

    def stick(self, st: _State, t_next: float, p: Piece) -> _State:
        """Stick to ``t_next`` unless the net force leaves the band first (located on the closed form)."""
        x = st.x
        net = p(t_next) - self.k * x
        if sticks(net, -self.tau, self.tau) or t_next <= st.hold:
            return _State(t_next, x, 0.0, net, STICK, st.hold)
        s = 1 if net > 0 else -1
        excess = lambda t: s * (p(t) - self.k * x) - self.tau
        t_b = st.t if excess(st.t) >= 0 else _root(excess, st.t, t_next)
        return self.breakaway(_State(t_b, x, 0.0, p(t_b) - self.k * x, STICK), s)

    def slip(self, st: _State, t_next: float, p: Piece) -> _State:
        """Slip to ``t_next``, or to the zero of the step map's velocity and the switch there."""
        s, h = st.mode, t_next - st.t
        x, v, f_d = self.slip_step(s, st, h, p)
        if s * v > 0:
            return _State(t_next, x, v, f_d, s)
        lo = 0.0 if st.v != 0 else self.moving_substep(s, st, h, p)
        if lo is None:  # the slip from rest ends at once: stick to the grid point
            return self.enter_stick(st.t, st.x, p(st.t) - self.k * st.x, hold=t_next)
        h_stop = h if v == 0 else _root(lambda a: self.speed(s, st, a, p), lo, h, xtol=_EPS * t_next)
        if h_stop == 0.0:  # stopped where the substep starts (a speed the band kills at once)
            x = st.x
        elif h_stop != h:
            x = self.slip_step(s, st, h_stop, p)[0]
        return self.at_zero_velocity(_State(st.t + h_stop, x, 0.0, f_d, s), s)

    def speed(self, s: int, st: _State, a: float, p: Piece) -> float:
        """``s v`` after a slip step of size ``a`` (``s v_n`` at ``a = 0``)."""
        return s * st.v if a == 0 else s * self.slip_step(s, st, a, p)[1]

    def moving_substep(self, s: int, st: _State, h: float, p: Piece) -> float | None:
        """A substep ``a < h`` after which a slip begun at ``v = 0`` moves in direction ``s``."""
        a = h
        for _ in range(_HALVINGS):
            a /= 2
            if s * self.slip_step(s, st, a, p)[1] > 0:
                return a
        return None

    def advance(self, st: _State, t_next: float) -> _State:
        """From ``st`` to the grid time ``t_next``, through every switch in between."""
        for _ in range(MAX_SWITCHES_PER_STEP):
            if st.t >= t_next:
                return st
            p = self.piece(st.t)
            st = self.switch_forcing(st) if st.t == self.force.until > 0 else st
            end = min(t_next, p.end)
            st = self.stick(st, end, p) if st.mode == STICK else self.slip(st, end, p)
        raise ValueError(
            f"the event-locating scheme found more than {MAX_SWITCHES_PER_STEP} switches "
            f"in the step ending at t = {t_next:.6g} s (stick-slip chatter); lower dt"
        )

    def switch_forcing(self, st: _State) -> _State:
        """At ``t = t_off``: record the event; a sticking mass may break away under the new force."""
        if self.force.is_zero or any(e.kind == "switch" for e in self.events):
            return st
        net = self.net(st.t, st.x)
        breaks = st.mode == STICK and abs(net) > self.tau
        self.event(st.t, "switch", st.x, (1 if net > 0 else -1) if breaks else st.mode)
        if st.mode != STICK:
            return st
        if breaks:  # the switch is the event, as in the exact solver
            return self.breakaway(st, 1 if net > 0 else -1, kind="")
        self.check_rest(st)
        return st._replace(f_d=net)

    def initial(self, x0: float, v0: float) -> _State:
        """The mode at ``t = 0``: slip in the direction of ``v0``, or of the net force, or stick."""
        net = self.net(0.0, x0)
        s = self.mode(v0, net)
        if v0 != 0:
            return _State(0.0, x0, v0, self.law.force_interval(v0)[0], s)
        if s == STICK:
            return self.enter_stick(0.0, x0, net, -math.inf)
        return _State(0.0, x0, 0.0, s * self.tau, s)


def _row(st: _State, k: float, run: _Capture) -> tuple[float, ...]:
    """Output row ``t, x, v, F_s, F_d, F`` (the force as :class:`SwitchedSine` gives it, on at ``t_off``)."""
    return (st.t, st.x, st.v, k * st.x, st.f_d, run.on(st.t) if st.t <= run.force.until else 0.0)


def _capture_rows(run: _Capture, st: _State, dt: float, n_steps: int, stride: int, out: np.ndarray) -> _State:
    """March the event-locating scheme from ``st`` over the grid, filling ``out``; return the last state."""
    k = run.k
    out[0], row = _row(st, k, run), 1
    for n in range(1, n_steps + 1):
        st = run.advance(st, n * dt)
        if not (math.isfinite(st.x) and math.isfinite(st.v) and math.isfinite(st.f_d)):
            raise ValueError(f"the event-locating scheme overflowed at t = {n * dt:.6g} s (step {n})")
        if n % stride == 0 or n == n_steps:
            out[row], row = _row(st, k, run), row + 1
    return st


def event_capturing(
    oscillator: Oscillator,
    t_end: float,
    dt: float,
    *,
    x0: float = 0.0,
    v0: float = 0.0,
    force: SwitchedSine | None = None,
    save_every: int = 1,
) -> CapturedRun:
    """Integrate the DAE (8) by trapezoidal steps within modes, switching at located events.

    A shim of the one entry point, kept for what it adds:
    ``lumped.solve(Problem.oscillator(oscillator, t_end, x0=x0, v0=v0,
    force=force), dt, method="event-locating")`` gives its ``trajectory``;
    called directly it returns the :class:`CapturedRun`, with the located
    events beside the grid.

    Parameters
    ----------
    force : SwitchedSine or None
        The switched sine of eq. (17) (its switch-off time is a known event);
        a general callable is refused, since its breaks are unknown.
    oscillator, t_end, dt, x0, v0, save_every
        As for :func:`~lumped.solvers.backward_euler.backward_euler`; any
        :class:`~lumped.laws.Dashpot` whose ``velocity`` accepts a float.

    Returns
    -------
    CapturedRun
        The trajectory on ``t_n = n*dt`` (``method = "event-locating"``,
        ``final_rest`` dated at the located stop) and the events.

    Notes
    -----
    A mode is *slip* with direction ``s`` (``F_d = s tau + u``, ``v =
    psi(u)``, see the law's ``band_free_resolvent``) or *stick* (``v = 0``, ``x``
    fixed, ``F_d = F - k x``, eq. 11c).  In slip, a trapezoidal step of size
    ``h`` (:func:`~lumped.solvers.theta.theta_step` at ``theta = 1/2``, ``G_n`` from the consistent
    ``F_d``) is accepted while ``s v > 0``; otherwise the stop is the zero of
    the step map's velocity ``v(h')`` on ``(0, h]`` (Brent), whose error is the
    step's local error ``O(h^3)``.  There the rule of the exact solver applies:
    reverse if ``-s (F - k x) > tau``, else stick.  In stick the breakaway is
    the root of ``|F(t) - k x| = tau`` on the closed-form forcing.  The
    switch-off time ``t_off`` ends a substep.  Two switches inside one step
    less than a step apart in the *forcing* (a net force that leaves and
    re-enters the band within ``dt``) are not seen, as in any fixed-step
    scheme.  A slip that starts at rest and reverses within ``2^-40`` of the
    step is taken as a stick to the next grid point (bounded loops).

    Measured (``tests/test_schemes.py``, halvings from ``dt = 1e-3``): order
    2.00 for the maximum displacement error, the rest position and time and
    the event times, on the free decay, eq. (17b) and Coulomb; for
    Herschel-Bulkley laws ``|F_d| = tau + K |v|^n``, 2.00 at ``n = 2`` and, at
    ``n = 1/2``, whose slip branch is not Lipschitz at ``v = 0`` (the step is
    solved for the force, where ``psi`` is smooth), 1.99 for the rest
    position and 1.92 for the event times.
    """
    t_end, dt, x0, v0, save_every, n_steps = start_run(
        oscillator, t_end, dt, x0, v0, save_every, "event-locating", force
    )
    if force is not None and as_sine(force) is None:
        raise ValueError("force: the event-locating scheme needs a SwitchedSine or None")
    force = as_sine(force) or SwitchedSine()
    check_magnitudes(oscillator, t_end, dt, x0, v0, force.amplitude)
    run = _Capture(oscillator, force)
    stride = min(save_every, n_steps + 1)
    out = np.empty((validate.output_rows(n_steps, stride), len(COLUMNS)))
    st = _capture_rows(run, run.initial(x0, v0), dt, n_steps, stride, out)
    final = (run.stick_since, st.x) if st.mode == STICK else (math.nan, math.nan)
    events = tuple(sorted(run.events, key=lambda e: e.time))
    traj = Trajectory.from_array(
        out, oscillator, method="event-locating", dt=dt, save_every=save_every, final_rest=final, events=events
    )
    return CapturedRun(traj, events)
