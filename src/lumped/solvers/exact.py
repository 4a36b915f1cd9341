"""Exact, event-driven solution for a linear spring with a Bingham or Coulomb dashpot.

The motion is a sequence of phases:

* **slip** with direction ``s = +-1``: ``F_d = s mu_s N_f + c v`` (eq. 7, with
  ``c = 1/gamma``), so ``m x'' + c x' + k x = F(t) - s mu_s N_f``, a linear ODE
  with constant coefficients solved in closed form (particular solution of the
  sine plus the free oscillator, written with its characteristic roots);
* **stick**: ``v = 0``, ``x`` constant and ``F_d = F(t) - k x`` (eq. 11c), valid
  while ``|F(t) - k x| <= mu_s N_f``.

Events end the phases: *stop* (``v`` reaches zero and the net force lies in the
static band), *reversal* (``v`` reaches zero outside it), *breakaway* (the net
force on a sticking mass leaves the band), *forcing-off* (``t = t_off``) and
*rest* (a stop after which the force stays zero, so the mass never moves
again).

Zeros of ``v`` are found in closed form when the force is constant over the
phase (the velocity is then a damped sine, or a sum of two exponentials that
vanishes at most once); under a sinusoidal force they are bracketed on a grid
graded from the fastest time scale of the phase to the slowest relevant one and
refined with Brent's method to a few ulps of the phase time.  Breakaways are
solved in closed form with ``arcsin``.

Before marching, :func:`solve_exact` refuses (with a ``ValueError`` naming the
argument to change) runs whose forces could overflow, whose forcing phase
carries no significant digit, or that would have more than ``max_events``
events; so every run either finishes quickly or stops at once.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property
from typing import ClassVar

import numpy as np

from lumped.laws import coulomb
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import MAGNITUDE_LIMIT, Oscillator, check_magnitudes
from lumped.model.trajectory import COLUMNS, Trajectory
from lumped.numerics import validate
from lumped.numerics.sine import MAX_ARGUMENT

__all__ = ["Event", "Phase", "SlipMotion", "ExactSolution", "solve_exact"]

_EPS = np.finfo(float).eps
_BLOCK = 256  # samples per block when bracketing a zero of v
_MAX_BLOCKS = 100_000  # bound on the search for one zero of v (2.6e7 samples)
_PER_SCALE = 32  # samples per time scale of the bracketing grid
_GRADE = 1.25  # growth factor of the grid from the fast to the slow time scale
#: Largest forcing argument ``|omega| t + |phase|`` (rad): the range of the
#: project's sine (:data:`lumped.numerics.sine.MAX_ARGUMENT`), the one bound that every
#: method, the sweep and the command line share.
MAX_PHASE = MAX_ARGUMENT


@dataclass(frozen=True)
class Event:
    """A switch between phases at ``time`` (s), with the state ``x`` (m) there."""

    time: float
    kind: str
    x: float


@dataclass(frozen=True)
class _Modes:
    """Free motion of ``m x'' + c x' + k x = 0``, from the roots of ``m l^2 + c l + k``.

    ``kind`` is ``"under"`` (roots ``-h +- i q``), ``"critical"`` (double root
    ``slow = fast = -h``) or ``"over"`` (real roots ``fast < slow < 0``).
    ``h = c/(2m)`` (1/s) and ``omega2 = k/m`` (1/s^2).
    """

    kind: str
    h: float
    omega2: float
    q: float = 0.0
    slow: float = 0.0
    fast: float = 0.0


def _modes(m: float, c: float, k: float) -> _Modes:
    """Characteristic roots, computed without forming ``c^2`` or ``4 m k``.

    Notes
    -----
    With ``zeta = c / (2 sqrt(m k))``, the roots are ``-h (1 +- sqrt(1 - 1/zeta^2))``.
    The slow one is written ``-2 k / (c (1 + r))`` (their product is ``k/m``),
    which keeps its digits when ``zeta`` is large.
    """
    h, omega_n = c / (2 * m), math.sqrt(k) / math.sqrt(m)
    modes = _Modes("under", h, k / m)
    zeta = h / omega_n
    if zeta < 1:
        modes = dataclasses.replace(modes, q=omega_n * math.sqrt((1 - zeta) * (1 + zeta)))
    elif zeta == 1:
        modes = dataclasses.replace(modes, kind="critical", slow=-h, fast=-h)
    else:
        r = math.sqrt((1 - 1 / zeta) * (1 + 1 / zeta))
        slow, fast = -2 * k / (c * (1 + r)), -h * (1 + r)
        modes = dataclasses.replace(modes, kind="over", slow=slow, fast=fast)
    rates = (modes.h, modes.omega2, modes.q, modes.fast)
    if not all(math.isfinite(r) for r in rates):
        raise ValueError(
            f"mass: the rates c/m = {h:.3g} 1/s and k/m = {k / m:.3g} 1/s^2 of the oscillator "
            "exceed double precision; raise mass (or lower stiffness or 1/gamma)"
        )
    return modes


def _first_zero(a: float, b: float) -> float:
    """Smallest ``theta > 0`` with ``a cos(theta) + b sin(theta) = 0`` (0 if immediate).

    ``tan(theta) = -a/b``; the arctangent of the ratio keeps its digits when the
    zero is close to 0 or to ``pi`` (a mass stopped at once by a huge band).
    """
    if b == 0:
        return 0.0 if a == 0 else math.pi / 2
    ratio = -a / b
    if ratio == 0 and a != 0:  # underflow: the zero is at 0+ or just before pi
        return 0.0 if a * b < 0 else math.pi
    theta = math.atan(ratio)
    return theta if theta > 0 else theta + math.pi


@dataclass(frozen=True)
class SlipMotion:
    """Closed-form motion ``m x'' + c x' + k x = P sin(w t + ph) - s tau``.

    ``t0, x0, v0`` is the state at the start of the phase; ``P, w, ph`` are the
    canonical forcing parameters (``P = 0`` when the force is off).
    """

    m: float
    c: float
    k: float
    s_tau: float
    P: float
    w: float
    ph: float
    t0: float
    x0: float
    v0: float

    @cached_property
    def modes(self) -> _Modes:
        """Roots of the free oscillator (see :func:`_modes`)."""
        return _modes(self.m, self.c, self.k)

    @property
    def is_free(self) -> bool:
        """True when the force is constant over the phase (no sine)."""
        return self.P == 0 or self.w == 0

    def _particular(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        m, c, k, P, w = self.m, self.c, self.k, self.P, self.w
        xc = -self.s_tau / k
        if P == 0:
            return np.full_like(t, xc), np.zeros_like(t)
        theta = w * t + self.ph
        stiff, drag = k - m * w * w, c * w
        if stiff == 0 and drag == 0:  # undamped resonance: secular growth t cos(theta)
            a = -P / (2 * m * w)
            return xc + a * t * np.cos(theta), a * np.cos(theta) - a * w * t * np.sin(theta)
        norm = math.hypot(stiff, drag)  # the amplitudes without squaring k (k = 1e300)
        A, B = P * (stiff / norm) / norm, -P * (drag / norm) / norm
        sin, cos = np.sin(theta), np.cos(theta)
        return xc + A * sin + B * cos, w * (A * cos - B * sin)

    def _free(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``exp(sigma tau) C(tau)`` and ``exp(sigma tau) S(tau)`` of the free oscillator.

        ``C`` and ``S`` solve the free equation with ``C(0) = 1, C'(0) = -h`` and
        ``S(0) = 0, S'(0) = 1`` shifted by ``exp(-h tau)``: the displacement is
        ``ec y0 + es (h y0 + y0')``.  For real roots ``ec = (e_s + e_f)/2`` and
        ``es = (e_s - e_f)/(slow - fast)``, the difference taken with ``expm1``
        where the two exponentials are close.
        """
        md = self.modes
        with np.errstate(over="ignore", under="ignore"):  # exp(-huge) = 0 is the decay
            return self._free_impl(md, tau)

    @staticmethod
    def _free_impl(md: _Modes, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        if md.kind == "under":
            e = np.exp(-md.h * tau)
            return e * np.cos(md.q * tau), e * np.sin(md.q * tau) / md.q
        if md.kind == "critical":
            e = np.exp(-md.h * tau)
            return e, tau * e
        gap = md.slow - md.fast
        e_slow, e_fast = np.exp(md.slow * tau), np.exp(md.fast * tau)
        close = gap * tau < 1.0
        diff = np.where(close, e_fast * np.expm1(np.minimum(gap * tau, 1.0)), e_slow - e_fast)
        return 0.5 * (e_slow + e_fast), diff / gap

    def _offsets(self) -> tuple[float, float]:
        """Initial displacement and velocity relative to the particular solution."""
        xp0, vp0 = self._particular(np.asarray(self.t0))
        return float(self.x0 - xp0), float(self.v0 - vp0)

    def state(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Displacement and velocity at times ``t >= t0``."""
        t = np.asarray(t, dtype=float)
        y0, dy0 = self._offsets()
        ec, es = self._free(t - self.t0)
        h, omega2 = self.modes.h, self.modes.omega2
        y = ec * y0 + es * (h * y0 + dy0)
        dy = ec * dy0 - es * (omega2 * y0 + h * dy0)
        xp, vp = self._particular(t)
        return xp + y, vp + dy

    def velocity(self, t: float) -> float:
        """``v(t)`` as a float (m/s)."""
        return float(self.state(t)[1])

    def time_scales(self) -> tuple[float, float]:
        """Fastest time scale of the phase and the slowest one a zero of ``v`` can hide in (s).

        The fast one is ``1/omega_n`` (or the fast decay time); the slow one is
        the shortest interval between two sign changes of ``v`` once the fast
        transient is gone: half a damped period, the slow decay time, half a
        forcing period.
        """
        md = self.modes
        if md.kind == "under":
            fast, slow = 1 / math.sqrt(md.omega2), math.pi / md.q
        else:
            fast, slow = -1 / md.fast, -1 / md.slow
        if self.P != 0 and self.w > 0:
            slow = min(slow, math.pi / self.w)
        return min(fast, slow), slow

    def first_stop(self, t_lim: float, direction: int) -> float | None:
        """First time in ``(t0, t_lim]`` at which ``v`` returns to zero, or ``None``.

        The result does not depend on ``t_lim`` beyond whether it is reached,
        so a solution extended to a later ``t_end`` keeps its events.
        """
        if not self.is_free:
            return self._scan(t_lim, direction)
        tau = self._free_stop()
        if tau is None or self.t0 + tau > t_lim:
            return None
        if self.modes.kind != "under" and tau > 0:
            return self._polish(self.t0 + tau, direction)
        return self.t0 + tau

    def _free_stop(self) -> float | None:
        """Closed-form first zero ``tau > 0`` of the free velocity, or ``None``.

        Notes
        -----
        Underdamped: ``v = exp(-h tau) (a cos q tau + b sin q tau)`` with
        ``a = y0'`` and ``b = -(omega2 y0 + h y0')/q`` (:func:`_first_zero`).  Real roots:
        ``v = l_s A e^{l_s tau} + l_f B e^{l_f tau}`` vanishes at most once, at
        ``tau = log(-l_f B / (l_s A)) / (l_s - l_f)``, taken through logarithms
        so that no ratio overflows.
        """
        y0, dy0 = self._offsets()
        if y0 == 0 and dy0 == 0:
            return 0.0  # at rest on the centre: it stops at once
        md = self.modes
        if md.kind == "under":
            return _first_zero(dy0, -(md.omega2 * y0 + md.h * dy0) / md.q) / md.q
        if dy0 == 0:
            return None  # from rest a sum of two exponentials has no further zero
        if md.kind == "critical":
            tau = -dy0 / (md.slow * (dy0 - md.slow * y0))
            return tau if tau > 0 else None
        num, den = md.slow * y0 - dy0, md.fast * y0 - dy0  # l_s y0 - y0', l_f y0 - y0'
        if num == 0 or den == 0 or (num > 0) != (den > 0):
            return None  # one exponential only, or both of the sign of v: no zero
        log_rates = math.log(-md.fast) - math.log(-md.slow)
        tau = (log_rates + math.log(abs(num)) - math.log(abs(den))) / (md.slow - md.fast)
        return tau if tau > 0 else None

    def _polish(self, t: float, direction: int) -> float:
        """Brent's method on ``t +- 1e-6 (t - t0)`` when that brackets the zero, else ``t``."""
        from scipy.optimize import brentq

        a, b = self.t0 + (t - self.t0) * (1 - 1e-6), self.t0 + (t - self.t0) * (1 + 1e-6)
        if not direction * self.velocity(a) > 0 >= direction * self.velocity(b):
            return t
        return brentq(self.velocity, a, b, xtol=1e-300, rtol=4 * _EPS, maxiter=200)

    def _grid(self, t_lim: float):  # noqa: ANN202 (a generator of arrays)
        """Blocks of sample times ``t0 + tau``: geometric from the fast scale, then uniform.

        The grid does not depend on ``t_lim`` (only where it stops), so the
        brackets found before ``t_lim`` are those of any later ``t_lim``.
        """
        fast, slow = (s / _PER_SCALE for s in self.time_scales())
        # Below 1e-12 of the slow spacing (or a few ulps of t0) v is rounding
        # noise at the start of a slip from rest: start the grid there.
        fast = max(fast, 1e-12 * slow, 4 * math.ulp(self.t0))
        geo = np.zeros(0)
        if fast * (_GRADE - 1) < slow:
            n_geo = math.ceil(math.log(slow / (fast * (_GRADE - 1))) / math.log(_GRADE))
            geo = fast * _GRADE ** np.arange(n_geo)
            yield from np.array_split(self.t0 + geo, -(-n_geo // _BLOCK))
        start = geo[-1] if geo.size else 0.0
        blocks = (t_lim - self.t0 - start) / (slow * _BLOCK) + 1
        if blocks > _MAX_BLOCKS:
            raise ValueError(
                f"t_end: a slip phase would need {blocks * _BLOCK:.3g} samples to bracket its "
                f"stop, more than {_MAX_BLOCKS * _BLOCK:.3g}; shorten t_end or use backward Euler"
            )
        for j in range(math.ceil(blocks)):
            yield self.t0 + (start + slow * (j * _BLOCK + np.arange(1, _BLOCK + 1)))

    def _scan(self, t_lim: float, direction: int) -> float | None:
        """First zero of ``v`` after ``t0``, bracketed on :meth:`_grid`, refined by Brent."""
        lo = self.t0
        for grid in self._grid(t_lim):
            if lo >= t_lim:
                return None
            ahead = direction * self.state(grid)[1] <= 0
            if ahead.any():
                i = int(np.argmax(ahead))
                a = lo if i == 0 else float(grid[i - 1])
                return self._refine(a, float(grid[i]), t_lim, direction)
            lo = float(grid[-1])
        return None

    def _refine(self, a: float, b: float, t_lim: float, direction: int) -> float | None:
        """The zero of ``v`` in the bracket ``(a, b]``, if it lies before ``t_lim``."""
        from scipy.optimize import brentq

        if a >= t_lim or (b > t_lim and direction * self.velocity(t_lim) > 0):
            return None
        if a == self.t0 and self.v0 == 0:
            a = self._leave_rest(b, direction)
            if a is None:
                return self.t0
        if self.velocity(b) == 0:
            return min(b, t_lim)
        root = brentq(self.velocity, a, b, xtol=1e-300, rtol=4 * _EPS, maxiter=200)
        return min(root, t_lim)

    def _leave_rest(self, b: float, direction: int) -> float | None:
        """A time in ``(t0, b)`` where the motion from rest has the sign ``direction``."""
        tau = b - self.t0
        for _ in range(60):
            tau *= 0.5
            if direction * self.velocity(self.t0 + tau) > 0:
                return self.t0 + tau
        return None


@dataclass(frozen=True)
class Phase:
    """``kind`` is ``"stick"`` or ``"slip"``; ``motion`` is set for slip phases."""

    start: float
    end: float
    kind: str
    x_start: float
    motion: SlipMotion | None = None


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
        dt = validate.positive("dt", dt)
        save_every = validate.stride("save_every", save_every)
        n = validate.step_count(self.t_end, dt)
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


class _Builder:
    """Marches from event to event; ``solve_exact`` is its only user."""

    def __init__(self, osc: Oscillator, force: SwitchedSine, t_end: float, max_events: int):
        self.osc, self.force, self.t_end, self.max_events = osc, force, t_end, max_events
        self.m, self.k = osc.mass, osc.stiffness
        self.tau = osc.dashpot.threshold
        self.phases: list[Phase] = []
        self.events: list[Event] = []
        self.rest: tuple[float, float] = (math.nan, math.nan)

    def forcing_at(self, t: float) -> tuple[float, float, float, float]:
        """Canonical ``(P, w, ph)`` of the forcing piece holding just after ``t``, and its end."""
        f = self.force
        if t < f.until and not f.is_zero:
            return (*f.canonical(), f.until)
        return (0.0, 0.0, 0.0, math.inf)

    def event(self, t: float, kind: str, x: float) -> None:
        self.events.append(Event(t, kind, x))
        if len(self.events) > self.max_events:
            raise ValueError(
                f"t_end: more than max_events = {self.max_events} events before t_end; "
                "shorten t_end or use backward Euler"
            )

    def run(self, x: float, v: float) -> None:
        """March from ``(0, x, v)`` to ``t_end``; every pass but the last adds an event.

        ``nxt`` is what comes next: ``"stick"``, a slip direction ``+-1``, or
        ``None`` (decided from ``v`` and the net force).  After a stop the
        mass sticks even if round-off puts the net force a few ulps outside
        the band, and a reversal always reverses: otherwise a mass stopping
        on the band edge would slip and stop again without end.
        """
        t, nxt, stalled = 0.0, None, 0
        while t < self.t_end:
            P, w, ph, seg_end = self.forcing_at(t)
            t_lim = min(seg_end, self.t_end)
            nxt = self.decide(t, x, v, P * math.sin(w * t + ph)) if nxt is None else nxt
            if nxt == "stick":
                t, direction = self.stick(t, t_lim, x, P, w, ph, seg_end)
                nxt = direction or None
                continue
            t_before = t
            t, x, v, nxt = self.slip(t, t_lim, x, v, nxt, (P, w, ph), seg_end)
            stalled = stalled + 1 if t == t_before else 0
            if stalled > 8:
                raise ValueError(
                    f"x0: the exact solver makes no progress at t = {t!r} s: the net force "
                    "stays on the edge of the static band to round-off; perturb x0 or the force"
                )
        if nxt == "stick" and self.phases[-1].kind == "slip":  # a stop exactly at t_end
            P, w, ph, seg_end = self.forcing_at(t)
            self.stick(t, t, x, P, w, ph, seg_end)

    def decide(self, t: float, x: float, v: float, force: float) -> str | int:
        """``"stick"`` or the slip direction of a mass at ``(t, x, v)`` under ``force``."""
        if v != 0:
            return 1 if v > 0 else -1
        net = force - self.k * x
        if abs(net) <= self.tau:
            return "stick"
        return 1 if net > 0 else -1

    def stick(
        self, t: float, t_lim: float, x: float, P: float, w: float, ph: float, seg_end: float
    ) -> tuple[float, int]:
        """Record a stick phase from ``t``; return its end and the breakaway direction."""
        if P == 0 and seg_end == math.inf:  # the force stays zero: rest for ever
            last = self.phases[-1] if self.phases else None
            start = last.start if last and last.kind == "stick" and last.end == t else t
            self.phases.append(Phase(t, max(t, self.t_end), "stick", x))
            self.rest = (start, x)
            self.event(start, "rest", x)
            return self.t_end, 0
        t_b, direction = self.breakaway(t, t_lim, x, P, w, ph)
        self.phases.append(Phase(t, t_b, "stick", x))
        if direction != 0:
            self.event(t_b, "breakaway", x)
        elif t_b == seg_end and t_b < self.t_end:
            self.event(t_b, "forcing-off", x)
        return t_b, direction

    def breakaway(self, t0: float, t_lim: float, x: float, P: float, w: float, ph: float) -> tuple[float, int]:
        """First time in ``[t0, t_lim]`` at which ``|P sin(w t + ph) - k x|`` exceeds tau."""
        best, direction = t_lim, 0
        if P == 0 or w == 0:
            return best, direction
        theta0 = w * t0 + ph
        for sign, level in ((1, self.k * x + self.tau), (-1, self.k * x - self.tau)):
            ratio = level / P
            if abs(ratio) >= 1:
                continue
            base = math.asin(ratio) if sign > 0 else math.pi - math.asin(ratio)
            n = math.ceil((theta0 - base) / (2 * math.pi) - 1e-12)
            t_cross = max((base + 2 * math.pi * n - ph) / w, t0)
            if t_cross < best:
                best, direction = t_cross, sign
        return best, direction

    def motion(self, t: float, x: float, v: float, direction: int, forcing: tuple[float, float, float]) -> SlipMotion:
        """The slip motion from ``(t, x, v)``: ``first_stop(t_lim, direction)``, ``state(t)``, ``s_tau``."""
        P, w, ph = forcing
        c = self.osc.dashpot.bingham_form().viscosity
        return SlipMotion(self.m, c, self.k, direction * self.tau, P, w, ph, t, x, v)

    def slip(
        self,
        t: float,
        t_lim: float,
        x: float,
        v: float,
        direction: int,
        forcing: tuple[float, float, float],
        seg_end: float,
    ) -> tuple[float, float, float, str | int | None]:
        """Record a slip phase from ``(t, x, v)``; return where it ends and what follows."""
        motion = self.motion(t, x, v, direction, forcing)
        t_stop = motion.first_stop(t_lim, direction)
        if t_stop is None:
            x_end, v_end = (float(a) for a in motion.state(t_lim))
            self.phases.append(Phase(t, t_lim, "slip", x, motion))
            if t_lim == seg_end and t_lim < self.t_end:
                self.event(t_lim, "forcing-off", x_end)
            return t_lim, x_end, v_end, None
        x_stop = float(motion.state(t_stop)[0])
        self.phases.append(Phase(t, t_stop, "slip", x, motion))
        P2, w2, ph2, _ = self.forcing_at(t_stop)
        net = P2 * math.sin(w2 * t_stop + ph2) - self.k * x_stop
        # At a zero of v after slipping with sign s, m v' = net - s tau points
        # against s: the motion reverses only if the net force lies beyond -s tau.
        reverses = -direction * net > self.tau
        self.event(t_stop, "reversal" if reverses else "stop", x_stop)
        return t_stop, x_stop, 0.0, -direction if reverses else "stick"


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
            f"t_end: the exact solution would have about {shown} events before t_end, more than "
            f"max_events = {max_events}; shorten t_end or use backward Euler"
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
    coulomb_part = dataclasses.replace(osc, dashpot=coulomb(osc.threshold))
    check_magnitudes(coulomb_part, t_on, dt, x0, v0, P, carries_force=False)  # x is carried, not F_s = k x


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

    Parameters
    ----------
    oscillator : Oscillator
        Its dashpot must be a :class:`~lumped.laws.BinghamDashpot` (any
        ``gamma``, ``inf`` included).
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
    if force is not None and not isinstance(force, SwitchedSine):
        raise ValueError("force: the exact solver needs a SwitchedSine or None")
    t_end = validate.positive("t_end", t_end)
    x0, v0 = validate.finite("x0", x0), validate.finite("v0", v0)
    max_events = validate.positive_int("max_events", max_events)
    force = force or SwitchedSine()
    _check_inputs(oscillator, force, t_end, x0, v0, max_events)
    build = _Builder(oscillator, force, t_end, max_events)
    build.run(x0, v0)
    events = tuple(sorted(build.events, key=lambda e: e.time))  # "rest" is dated back
    _finite("event time", np.array([e.time for e in events]), np.array([e.time for e in events]))
    _finite("displacement", np.array([p.x_start for p in build.phases]), np.array([p.start for p in build.phases]))
    return ExactSolution(
        oscillator, force, t_end, tuple(build.phases), events, *build.rest, x0=x0, v0=v0, max_events=max_events
    )
