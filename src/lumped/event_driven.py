"""Exact, event-driven solution for a linear spring with a Bingham or Coulomb dashpot.

The motion is a sequence of phases:

* **slip** with direction ``s = +-1``: ``F_d = s mu_s N_f + c v`` (eq. 7, with
  ``c = 1/gamma``), so ``m x'' + c x' + k x = F(t) - s mu_s N_f``, a linear ODE
  with constant coefficients solved in closed form (particular solution of the
  sine plus the matrix exponential of the free oscillator);
* **stick**: ``v = 0``, ``x`` constant and ``F_d = F(t) - k x`` (eq. 11c), valid
  while ``|F(t) - k x| <= mu_s N_f``.

Events end the phases: *stop* (``v`` reaches zero and the net force lies in the
static band), *reversal* (``v`` reaches zero outside it), *breakaway* (the net
force on a sticking mass leaves the band), *forcing-off* (``t = t_off``) and
*rest* (a stop after which the force stays zero, so the mass never moves
again).  Zeros of ``v`` are bracketed on a grid finer than every time scale of
the phase and refined with Brent's method to a few ulps of the phase time;
breakaways are solved in closed form with ``arcsin``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lumped import _validate
from lumped.forcing import SwitchedSine
from lumped.laws import BinghamDashpot
from lumped.results import COLUMNS, Trajectory
from lumped.system import Oscillator

__all__ = ["Event", "Phase", "SlipMotion", "ExactSolution", "solve_exact"]

_EPS = np.finfo(float).eps
_BLOCK = 256  # samples per block when bracketing a zero of v
_MAX_BLOCKS = 100_000  # bound on the search for one zero of v (2.6e7 samples)


@dataclass(frozen=True)
class Event:
    """A switch between phases at ``time`` (s), with the state ``x`` (m) there."""

    time: float
    kind: str
    x: float


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

    def _particular(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        m, c, k, P, w = self.m, self.c, self.k, self.P, self.w
        xc = -self.s_tau / k
        if P == 0:
            return np.full_like(t, xc), np.zeros_like(t)
        theta = w * t + self.ph
        stiff = k - m * w * w
        det = stiff * stiff + (c * w) ** 2
        if det == 0:  # undamped resonance: secular growth t cos(theta)
            a = -P / (2 * m * w)
            return xc + a * t * np.cos(theta), a * np.cos(theta) - a * w * t * np.sin(theta)
        A, B = P * stiff / det, -P * c * w / det
        sin, cos = np.sin(theta), np.cos(theta)
        return xc + A * sin + B * cos, w * (A * cos - B * sin)

    def _free(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``exp(sigma tau) C(tau)`` and ``exp(sigma tau) S(tau)`` of the free oscillator."""
        sigma = -self.c / (2 * self.m)
        disc = sigma * sigma - self.k / self.m
        if disc < 0:
            q = math.sqrt(-disc)
            e = np.exp(sigma * tau)
            return e * np.cos(q * tau), e * np.sin(q * tau) / q
        if disc == 0:
            e = np.exp(sigma * tau)
            return e, tau * e
        q = math.sqrt(disc)
        qt = np.minimum(q * tau, 700.0)
        near = np.exp(sigma * tau)
        far_p, far_m = np.exp((sigma + q) * tau), np.exp((sigma - q) * tau)
        small = q * tau < 20.0
        ec = np.where(small, near * np.cosh(qt), 0.5 * (far_p + far_m))
        es = np.where(small, near * np.sinh(qt) / q, 0.5 * (far_p - far_m) / q)
        return ec, es

    def state(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Displacement and velocity at times ``t >= t0``."""
        t = np.asarray(t, dtype=float)
        xp0, vp0 = self._particular(np.asarray(self.t0))
        y0, dy0 = self.x0 - xp0, self.v0 - vp0
        ec, es = self._free(t - self.t0)
        h = self.c / (2 * self.m)
        y = ec * y0 + es * (h * y0 + dy0)
        dy = ec * dy0 - es * (self.k / self.m * y0 + h * dy0)
        xp, vp = self._particular(t)
        return xp + y, vp + dy

    def time_scale(self) -> float:
        """Shortest time over which ``v`` can change sign twice (s)."""
        sigma = -self.c / (2 * self.m)
        disc = sigma * sigma - self.k / self.m
        scales = [math.pi / math.sqrt(-disc) if disc < 0 else 1 / (abs(sigma) + math.sqrt(disc))]
        if self.P != 0 and self.w > 0:
            scales.append(math.pi / self.w)
        return min(scales)

    def first_stop(self, t_lim: float, direction: int) -> float | None:
        """First time in ``(t0, t_lim]`` at which ``v`` returns to zero, or ``None``."""
        from scipy.optimize import brentq

        h = self.time_scale() / 32
        velocity = lambda t: float(self.state(t)[1])  # noqa: E731
        t_lim = min(t_lim, self.t0 + self.horizon())
        lo = self.t0
        for _ in range(_MAX_BLOCKS):
            if lo >= t_lim:
                return None
            grid = np.minimum(lo + h * np.arange(1, _BLOCK + 1), t_lim)
            ahead = direction * self.state(grid)[1] <= 0
            if ahead.any():
                i = int(np.argmax(ahead))
                a, b = (lo if i == 0 else grid[i - 1]), grid[i]
                if a == self.t0 and self.v0 == 0:
                    a = self._leave_rest(b, direction)
                    if a is None:
                        return self.t0
                if velocity(b) == 0:
                    return float(b)
                return brentq(velocity, a, b, xtol=1e-300, rtol=4 * _EPS, maxiter=200)
            lo = float(grid[-1])
        raise ValueError(f"t_end: no stop found in {_MAX_BLOCKS * _BLOCK} samples of a slip phase")

    def horizon(self) -> float:
        """Time after ``t0`` beyond which ``v`` cannot return to zero (s), or ``inf``.

        Without an oscillating force an over- or critically damped oscillator's
        velocity is a sum of two exponentials, which vanishes at most once; by
        ``60`` slow time constants the transient has decayed by ``e^-60`` and
        the mass is, to every printed digit, at its asymptote.  Otherwise the
        search runs to the end of the phase.
        """
        sigma = -self.c / (2 * self.m)
        disc = sigma * sigma - self.k / self.m
        if disc < 0 or (self.P != 0 and self.w > 0):
            return math.inf
        return 60.0 / (-sigma - math.sqrt(disc)) if sigma + math.sqrt(disc) < 0 else math.inf

    def _leave_rest(self, b: float, direction: int) -> float | None:
        """A time in ``(t0, b)`` where the motion from rest has the sign ``direction``."""
        tau = b - self.t0
        for _ in range(60):
            tau *= 0.5
            if direction * float(self.state(self.t0 + tau)[1]) > 0:
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


@dataclass(frozen=True, eq=False)
class ExactSolution:
    """The exact solution as phases and events, evaluable at any time.

    Attributes
    ----------
    phases : tuple of Phase
    events : tuple of Event
    rest_time : float
        Time (s) from which the mass stays at rest for ever; ``nan`` if it is
        still moving (or could still move) at ``t_end``.
    rest_position : float
        Displacement (m) at that rest; ``nan`` likewise.
    """

    oscillator: Oscillator
    force: SwitchedSine
    t_end: float
    phases: tuple[Phase, ...]
    events: tuple[Event, ...]
    rest_time: float
    rest_position: float

    def stick_intervals(self) -> list[tuple[float, float]]:
        """``(start, end)`` of every stick phase (s), merged across forcing switches."""
        out: list[tuple[float, float]] = []
        for p in self.phases:
            if p.kind != "stick":
                continue
            if out and out[-1][1] == p.start:
                out[-1] = (out[-1][0], p.end)
            else:
                out.append((p.start, p.end))
        return out

    def event_times(self, kind: str) -> np.ndarray:
        """Times (s) of all events of one kind."""
        return np.array([e.time for e in self.events if e.kind == kind])

    def evaluate(self, t: np.ndarray) -> dict[str, np.ndarray]:
        """Columns ``t, x, v, F_s, F_d, F`` at times ``t`` in ``[0, t_end]``."""
        t = np.asarray(t, dtype=float)
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
        k, law = self.oscillator.stiffness, self.oscillator.dashpot
        force = np.asarray(self.force(t), dtype=float)
        f_d = np.where(v == 0, force - k * x, law.slip_force(v))
        slip = np.array([p.motion is not None for p in self.phases])[which]
        direction = np.array([np.sign(p.motion.s_tau) if p.motion else 0 for p in self.phases])
        f_d = np.where(slip & (v == 0), direction[which] * law.threshold, f_d)
        return dict(zip(COLUMNS, (t, x, v, k * x, f_d, force)))

    def sample(self, dt: float, save_every: int = 1) -> Trajectory:
        """The exact solution on the grid ``t_n = n*dt`` used by backward Euler."""
        dt = _validate.positive("dt", dt)
        save_every = _validate.positive_int("save_every", save_every)
        n = _validate.step_count(self.t_end, dt)
        _validate.output_size(n, save_every)
        index = np.arange(0, n + 1, save_every)
        if index[-1] != n:
            index = np.append(index, n)
        cols = self.evaluate(index * dt)
        return Trajectory(**cols, oscillator=self.oscillator, method="exact", dt=dt,
                          save_every=save_every)  # fmt: skip


class _Builder:
    """Marches from event to event; ``solve_exact`` is its only user."""

    def __init__(self, osc: Oscillator, force: SwitchedSine, t_end: float, max_events: int):
        self.osc, self.force, self.t_end, self.max_events = osc, force, t_end, max_events
        self.m, self.k = osc.mass, osc.stiffness
        self.tau, self.c = osc.dashpot.threshold, osc.dashpot.viscosity
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
            raise ValueError(f"max_events: more than {self.max_events} events before t_end")

    def run(self, x: float, v: float) -> None:
        t, direction = 0.0, 0
        while t < self.t_end:
            P, w, ph, seg_end = self.forcing_at(t)
            t_lim = min(seg_end, self.t_end)
            if v == 0 and direction == 0:
                net = P * math.sin(w * t + ph) - self.k * x
                if abs(net) <= self.tau:
                    t, direction = self.stick(t, t_lim, x, P, w, ph, seg_end)
                    continue
                direction = 1 if net > 0 else -1
            elif v != 0:
                direction = 1 if v > 0 else -1
            t, x, v = self.slip(t, t_lim, x, v, direction, (P, w, ph), seg_end)
            direction = 0

    def stick(
        self, t: float, t_lim: float, x: float, P: float, w: float, ph: float, seg_end: float
    ) -> tuple[float, int]:
        """Record a stick phase from ``t``; return its end and the breakaway direction."""
        if P == 0 and seg_end == math.inf:  # the force stays zero: rest for ever
            last = self.phases[-1] if self.phases else None
            start = last.start if last and last.kind == "stick" and last.end == t else t
            self.phases.append(Phase(t, self.t_end, "stick", x))
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

    def breakaway(
        self, t0: float, t_lim: float, x: float, P: float, w: float, ph: float
    ) -> tuple[float, int]:
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

    def slip(
        self, t: float, t_lim: float, x: float, v: float, direction: int,
        forcing: tuple[float, float, float], seg_end: float,
    ) -> tuple[float, float, float]:  # fmt: skip
        """Record a slip phase from ``(t, x, v)``; return the state where it ends."""
        P, w, ph = forcing
        motion = SlipMotion(self.m, self.c, self.k, direction * self.tau, P, w, ph, t, x, v)
        t_stop = motion.first_stop(t_lim, direction)
        if t_stop is None:
            x_end, v_end = (float(a) for a in motion.state(t_lim))
            self.phases.append(Phase(t, t_lim, "slip", x, motion))
            if t_lim == seg_end and t_lim < self.t_end:
                self.event(t_lim, "forcing-off", x_end)
            return t_lim, x_end, v_end
        x_stop = float(motion.state(t_stop)[0])
        self.phases.append(Phase(t, t_stop, "slip", x, motion))
        P2, w2, ph2, _ = self.forcing_at(t_stop)
        net = P2 * math.sin(w2 * t_stop + ph2) - self.k * x_stop
        self.event(t_stop, "stop" if abs(net) <= self.tau else "reversal", x_stop)
        return t_stop, x_stop, 0.0


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
        Bound on the number of events (a ``ValueError`` beyond it).

    Returns
    -------
    ExactSolution
    """
    if not isinstance(oscillator.dashpot, BinghamDashpot):
        raise ValueError("dashpot: the exact solver needs a BinghamDashpot (any gamma)")
    if force is not None and not isinstance(force, SwitchedSine):
        raise ValueError("force: the exact solver needs a SwitchedSine or None")
    t_end = _validate.positive("t_end", t_end)
    x0, v0 = _validate.finite("x0", x0), _validate.finite("v0", v0)
    force = force or SwitchedSine()
    build = _Builder(oscillator, force, t_end, _validate.positive_int("max_events", max_events))
    build.run(x0, v0)
    events = tuple(sorted(build.events, key=lambda e: e.time))  # "rest" is dated back
    return ExactSolution(oscillator, force, t_end, tuple(build.phases), events,
                         *build.rest)  # fmt: skip
