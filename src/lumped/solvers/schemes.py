"""Second-order time stepping of the DAE (8): the θ-method and an event-capturing scheme.

Both schemes march on the grid ``t_n = n*dt`` of Algorithm 1 and return a
:class:`~lumped.model.trajectory.Trajectory` there.

* :func:`theta_method` is the θ-method with the dashpot law enforced at the
  new time level, so that its step, like Algorithm 1's, is a resolvent of the
  set-valued law (``theta = 1`` *is* Algorithm 1).  With ``theta = 1/2``
  (the trapezoidal rule) it is of order two on smooth motions but not through
  the switches: it crosses them blindly, and in stick its dashpot force
  alternates about the reaction instead of settling (measured in
  ``tests/test_schemes.py``).
* :func:`event_capturing` takes trapezoidal steps *within* one mode (slip in
  a direction, or stick), checks after each step whether the mode still
  holds, and when it does not, locates the switch inside the step, takes the
  partial step to it, applies the switching rule and completes the step.  It
  keeps order two through stops, reversals, breakaways and the switch-off of
  the forcing, and reports the events it found.

Why the trapezoidal rule inside the modes, and not a Radau IIA or a
Runge-Kutta method of higher order: its step is one scalar monotone equation,
the resolvent of the dashpot graph, so every law of :mod:`lumped.laws`
(closed form for Bingham and Coulomb, a bracketed root for any monotone law)
is stepped by the contract it already provides, without derivatives of the
law, which Herschel-Bulkley laws lack at ``v = 0``.  It is A-stable, so a
stiff viscous branch (small ``gamma``) does not limit the step.  Order two is
what the issue asks for: with the switches located to third order locally,
the global error is ``O(dt^2)``, which at ``dt = 1e-4`` is far below the
first-order error of Algorithm 1 (Acary and Brogliato, *Numerical Methods
for Nonsmooth Dynamical Systems*, 2008, chapter 9, on event-capturing and
event-driven schemes; the switching rule is that of
:mod:`lumped.solvers.exact`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from lumped.model.forcing import SwitchedSine, evaluate, validate_force
from lumped.model.oscillator import Oscillator, check_magnitudes, initial_dashpot_force
from lumped.model.trajectory import COLUMNS, Trajectory
from lumped.numerics import sine
from lumped.numerics import validate
from lumped.solvers.backward_euler import _seconds_per_step
from lumped.solvers.exact import Event

__all__ = ["CapturedRun", "event_capturing", "theta_method"]

#: Cost of one step relative to Algorithm 1's Python loop, for the run-time
#: bound: measured 2.6 (theta) and 3.0 (event-capturing) on the free decay
#: (measured with benchmarks/bench_accuracy.py --table), with a margin.
_COST_OVER_PYTHON_BE = 5.0
#: Bound on the switches located within one grid step (each a root search).
MAX_SWITCHES_PER_STEP = 64
#: Halvings of a substep tried to find where a slip started at rest is moving.
_HALVINGS = 40
_EPS = float(np.finfo(float).eps)


# --------------------------------------------------------------------------- θ-method


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


def _theta_rows(
    osc: Oscillator, dt: float, theta: float, n_steps: int, save_every: int, force: object, out: np.ndarray
) -> float:
    """March the θ-method, filling ``out`` from its row 0; return the rest's start (s)."""
    k = osc.spring.stiffness
    f_s, v, f_d, f_now = out[0, 3], out[0, 2], out[0, 4], out[0, 5]
    row, rest_start = 1, 0 if v == 0 else 1
    for first in range(1, n_steps + 1, 1 << 16):
        table = evaluate(force, np.arange(first, min(first + (1 << 16), n_steps + 1)) * dt)  # type: ignore[arg-type]
        for n, f_next in enumerate(table.tolist(), start=first):
            f_s, v, f_d = theta_step(osc, dt, theta, f_s, v, f_d, f_now, f_next)
            f_now = f_next
            if not (math.isfinite(f_s) and math.isfinite(v) and math.isfinite(f_d)):
                raise ValueError(f"the θ-method overflowed at t = {n * dt:.6g} s (step {n})")
            rest_start = n + 1 if v != 0.0 else rest_start
            if n % save_every == 0 or n == n_steps:
                out[row] = (n * dt, f_s / k, v, f_s, f_d, f_next)
                row += 1
    return rest_start * dt


def _start(
    osc: Oscillator, t_end: float, dt: float, x0: float, v0: float, save_every: int, kind: str, force: object
) -> tuple:
    """Validate the common arguments; return ``(t_end, dt, x0, v0, save_every, n_steps)``."""
    if not isinstance(osc, Oscillator):
        raise ValueError(f"oscillator must be an Oscillator, got {type(osc).__name__}")
    t_end, dt = validate.positive("t_end", t_end), validate.positive("dt", dt)
    x0, v0 = validate.finite("x0", x0), validate.finite("v0", v0)
    save_every = validate.stride("save_every", save_every)
    n_steps = validate.step_count(t_end, dt)
    if isinstance(force, SwitchedSine):
        force.check_span(n_steps * dt)  # the sine's range, to the grid's last time
    validate.output_size(n_steps, save_every)
    per_step = _COST_OVER_PYTHON_BE * _seconds_per_step(osc, None, "python", dt)  # law's cost measured there
    validate.run_time(n_steps, per_step, f"the {kind} scheme")
    return t_end, dt, x0, v0, save_every, n_steps


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
    t_end, dt, x0, v0, save_every, n_steps = _start(oscillator, t_end, dt, x0, v0, save_every, "theta", force)
    theta = validate.finite("theta", theta)
    if not 0.5 <= theta <= 1:
        raise ValueError(f"theta must lie in [0.5, 1], got {theta!r}")
    force = validate_force(force)
    check_magnitudes(oscillator, t_end, dt, x0, v0, force.amplitude if isinstance(force, SwitchedSine) else 0.0)
    out = np.empty((validate.output_rows(n_steps, min(save_every, n_steps + 1)), len(COLUMNS)))
    f0 = float(evaluate(force, np.zeros(1))[0])  # type: ignore[arg-type]
    k = oscillator.spring.stiffness
    out[0] = (0.0, x0, v0, k * x0, initial_dashpot_force(oscillator, f0, x0, v0), f0)
    rest = _theta_rows(oscillator, dt, theta, n_steps, min(save_every, n_steps + 1), force, out)
    final = (rest, float(out[-1, 1])) if out[-1, 2] == 0 else (math.nan, math.nan)
    return Trajectory.from_array(out, oscillator, method="theta", dt=dt, save_every=save_every, final_rest=final)


# --------------------------------------------------------------------------- event capturing


def _root(f: Callable[[float], float], a: float, b: float, xtol: float | None = None) -> float:
    """Brent's root of ``f`` on ``[a, b]`` (signs opposite), to about an ulp of ``b``."""
    from scipy.optimize import brentq  # imported here, as in laws: `import lumped` stays light

    return brentq(f, a, b, xtol=_EPS * abs(b) if xtol is None else xtol, rtol=4 * _EPS)


class CapturedRun(NamedTuple):
    """Result of :func:`event_capturing`: the grid ``trajectory`` and the located ``events``.

    ``events`` are :class:`~lumped.solvers.exact.Event` with the kinds of the
    exact solver: ``"stop"``, ``"reversal"``, ``"breakaway"``,
    ``"forcing-off"`` and ``"rest"`` (a stop after which the force stays zero,
    dated back to the start of that stick).
    """

    trajectory: Trajectory
    events: tuple[Event, ...]

    def event_times(self, kind: str) -> np.ndarray:
        """Times (s) of the events of one kind."""
        return np.array([e.time for e in self.events if e.kind == kind])


@dataclass(frozen=True)
class _Piece:
    """The forcing on one smooth segment ``[.., end]``: ``amplitude sin(omega t + phase)``."""

    amplitude: float
    omega: float
    phase: float
    end: float

    def __call__(self, t: float) -> float:
        return self.amplitude * sine.sin(self.omega * t + self.phase) if self.amplitude else 0.0


class _State(NamedTuple):
    """``mode`` is ``0`` (stick) or the slip direction ``+-1``; ``hold`` a time before which stick is kept."""

    t: float
    x: float
    v: float
    f_d: float
    mode: int
    hold: float = -math.inf


class _Capture:
    """The event-capturing march; :func:`event_capturing` is its only user."""

    def __init__(self, osc: Oscillator, force: SwitchedSine) -> None:
        self.m, self.k, self.tau = osc.mass, osc.spring.stiffness, osc.dashpot.threshold
        self.force = force
        self.law, self.resolvent = osc.dashpot, osc.dashpot.band_free_resolvent()  # contract point 8
        self.events: list[Event] = []
        self.stick_since = math.nan
        zero = force.is_zero
        self.on = _Piece(0.0 if zero else force.amplitude, force.omega, force.phase, force.until)
        self.off = _Piece(0.0, 0.0, 0.0, math.inf)

    def piece(self, t: float) -> _Piece:
        """The forcing piece holding just after ``t``."""
        return self.on if t < self.force.until and self.on.amplitude != 0 else self.off

    def slip_step(self, s: int, st: _State, h: float, p: _Piece) -> tuple[float, float, float]:
        """Trapezoidal step of size ``h`` in slip mode ``s``: ``(x, v, F_d)`` (see :func:`theta_step`)."""
        m, k = self.m, self.k
        g_now = p(st.t) - k * st.x - st.f_d
        eta = 2 * m / h + k * h / 2
        predictor = (2 * m / h) * st.v + p(st.t + h) - k * st.x + g_now - (k * h / 2) * st.v
        u, v = self.resolvent(predictor - s * self.tau, eta)
        return st.x + h / 2 * (st.v + v), v, s * self.tau + u

    def event(self, t: float, kind: str, x: float) -> None:
        """Record an event at ``t`` (s) with the displacement ``x`` (m)."""
        self.events.append(Event(t, kind, x))

    def enter_stick(self, t: float, x: float, f_d: float, hold: float) -> _State:
        """Stick from ``t``; record ``"rest"`` when the force is zero for ever."""
        if math.isnan(self.stick_since):
            self.stick_since = t
        st = _State(t, x, 0.0, f_d, 0, hold)
        self.check_rest(st)
        return st

    def check_rest(self, st: _State) -> None:
        """Record ``"rest"`` (dated at the start of the stick) once the force is zero for ever."""
        p = self.piece(st.t)
        forever = st.mode == 0 and p.amplitude == 0 and p.end == math.inf
        if forever and not any(e.kind == "rest" and e.time == self.stick_since for e in self.events):
            self.event(self.stick_since, "rest", st.x)

    def at_zero_velocity(self, st: _State, s: int) -> _State:
        """Switching rule at ``v = 0`` after slipping with direction ``s`` (see :mod:`lumped.solvers.exact`)."""
        net = self.piece(st.t)(st.t) - self.k * st.x
        if -s * net > self.tau:  # m v' = net - s tau points to -s, beyond the band
            self.event(st.t, "reversal", st.x)
            return _State(st.t, st.x, 0.0, -s * self.tau, -s)
        self.event(st.t, "stop", st.x)
        return self.enter_stick(st.t, st.x, net, hold=-math.inf)

    def breakaway(self, st: _State, s: int, kind: str = "breakaway") -> _State:
        """Slip from rest in direction ``s``; ``kind=""`` records no event (as the exact solver at ``t_off``)."""
        if kind:
            self.event(st.t, kind, st.x)
        self.stick_since = math.nan
        return _State(st.t, st.x, 0.0, s * self.tau, s)

    def stick(self, st: _State, t_next: float, p: _Piece) -> _State:
        """Stick to ``t_next`` unless the net force leaves the band first (located on the closed form)."""
        x = st.x
        net = p(t_next) - self.k * x
        if abs(net) <= self.tau or t_next <= st.hold:
            return _State(t_next, x, 0.0, net, 0, st.hold)
        s = 1 if net > 0 else -1
        excess = lambda t: s * (p(t) - self.k * x) - self.tau
        t_b = st.t if excess(st.t) >= 0 else _root(excess, st.t, t_next)
        return self.breakaway(_State(t_b, x, 0.0, p(t_b) - self.k * x, 0), s)

    def slip(self, st: _State, t_next: float, p: _Piece) -> _State:
        """Slip to ``t_next``, or to the zero of the step map's velocity and the switch there."""
        s, h = st.mode, t_next - st.t
        x, v, f_d = self.slip_step(s, st, h, p)
        if s * v > 0:
            return _State(t_next, x, v, f_d, s)
        lo = 0.0 if st.v != 0 else self.moving_substep(s, st, h, p)
        if lo is None:  # the slip from rest ends at once: stick to the grid point
            return self.enter_stick(st.t, st.x, p(st.t) - self.k * st.x, hold=t_next)
        h_stop = h if v == 0 else _root(lambda a: self.speed(s, st, a, p), lo, h, xtol=_EPS * t_next)
        x = self.slip_step(s, st, h_stop, p)[0] if h_stop != h else x
        return self.at_zero_velocity(_State(st.t + h_stop, x, 0.0, f_d, s), s)

    def speed(self, s: int, st: _State, a: float, p: _Piece) -> float:
        """``s v`` after a slip step of size ``a`` (``s v_n`` at ``a = 0``)."""
        return s * st.v if a == 0 else s * self.slip_step(s, st, a, p)[1]

    def moving_substep(self, s: int, st: _State, h: float, p: _Piece) -> float | None:
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
            st = self.switch_forcing(st, p) if st.t == self.force.until > 0 else st
            end = min(t_next, p.end)
            st = self.stick(st, end, p) if st.mode == 0 else self.slip(st, end, p)
        raise ValueError(
            f"the event-capturing scheme found more than {MAX_SWITCHES_PER_STEP} switches "
            f"in the step ending at t = {t_next:.6g} s (stick-slip chatter); lower dt"
        )

    def switch_forcing(self, st: _State, p: _Piece) -> _State:
        """At ``t = t_off``: record the event; a sticking mass may break away under the new force."""
        if self.force.is_zero or any(e.kind == "forcing-off" for e in self.events):
            return st
        self.event(st.t, "forcing-off", st.x)
        if st.mode != 0:
            return st
        net = p(st.t) - self.k * st.x
        if abs(net) > self.tau:  # the forcing-off event is the switch, as in the exact solver
            return self.breakaway(st, 1 if net > 0 else -1, kind="")
        self.check_rest(st)
        return st._replace(f_d=net)

    def initial(self, x0: float, v0: float) -> _State:
        """The mode at ``t = 0``: slip in the direction of ``v0``, or of the net force, or stick."""
        if v0 != 0:
            s = 1 if v0 > 0 else -1
            return _State(0.0, x0, v0, self.law.force_interval(v0)[0], s)
        net = self.piece(0.0)(0.0) - self.k * x0
        if abs(net) <= self.tau:
            return self.enter_stick(0.0, x0, net, -math.inf)
        s = 1 if net > 0 else -1
        return _State(0.0, x0, 0.0, s * self.tau, s)


def _row(st: _State, k: float, run: _Capture) -> tuple[float, ...]:
    """Output row ``t, x, v, F_s, F_d, F`` (the force as :class:`SwitchedSine` gives it, on at ``t_off``)."""
    return (st.t, st.x, st.v, k * st.x, st.f_d, run.on(st.t) if st.t <= run.force.until else 0.0)


def _capture_rows(run: _Capture, st: _State, dt: float, n_steps: int, stride: int, out: np.ndarray) -> _State:
    """March the event-capturing scheme from ``st`` over the grid, filling ``out``; return the last state."""
    k = run.k
    out[0], row = _row(st, k, run), 1
    for n in range(1, n_steps + 1):
        st = run.advance(st, n * dt)
        if not (math.isfinite(st.x) and math.isfinite(st.v) and math.isfinite(st.f_d)):
            raise ValueError(f"the event-capturing scheme overflowed at t = {n * dt:.6g} s (step {n})")
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
        The trajectory on ``t_n = n*dt`` (``method = "event-capturing"``,
        ``final_rest`` dated at the located stop) and the events.

    Notes
    -----
    A mode is *slip* with direction ``s`` (``F_d = s tau + u``, ``v =
    psi(u)``, see :func:`_collapsed_resolvent`) or *stick* (``v = 0``, ``x``
    fixed, ``F_d = F - k x``, eq. 11c).  In slip, a trapezoidal step of size
    ``h`` (:func:`theta_step` at ``theta = 1/2``, ``G_n`` from the consistent
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
    t_end, dt, x0, v0, save_every, n_steps = _start(oscillator, t_end, dt, x0, v0, save_every, "event-capturing", force)
    if force is not None and not isinstance(force, SwitchedSine):
        raise ValueError("force: the event-capturing scheme needs a SwitchedSine or None")
    force = force or SwitchedSine()
    check_magnitudes(oscillator, t_end, dt, x0, v0, force.amplitude)
    run = _Capture(oscillator, force)
    stride = min(save_every, n_steps + 1)
    out = np.empty((validate.output_rows(n_steps, stride), len(COLUMNS)))
    st = _capture_rows(run, run.initial(x0, v0), dt, n_steps, stride, out)
    final = (run.stick_since, st.x) if st.mode == 0 else (math.nan, math.nan)
    traj = Trajectory.from_array(
        out, oscillator, method="event-capturing", dt=dt, save_every=save_every, final_rest=final
    )
    return CapturedRun(traj, tuple(sorted(run.events, key=lambda e: e.time)))
