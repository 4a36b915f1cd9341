"""The one event machinery: events, phases, the switching rules and the march through phases.

A motion of one mass is a sequence of *phases*: **slip** with direction
``s = +-1`` and **stick** (``v = 0``, ``x`` constant, ``F_d = F(t) - k x``,
eq. 11c, valid while ``|F(t) - k x| <= mu_s N_f``).  *Events* end them, with
the kinds :data:`KINDS` that every method reports for one mass or many:
*stop* (``v`` reaches zero and the net force lies in the static band),
*reversal* (``v`` reaches zero outside it), *breakaway* (the net force on a
sticking mass leaves the band), *switch* (a load comes on or goes off: here
the sine at ``t = t_off``) and *rest* (a stop after which the force stays
zero, so the mass never moves again; it is dated back to the start of that
stick).

Every method that locates events uses this module:

* :class:`Event`, the one event record of every method and every network
  (the network marches of :mod:`lumped.solvers.network_modes` and
  :mod:`lumped.solvers.event_driven_network` make it too), and :class:`Phase`;
* :class:`Piece`, the forcing on one smooth segment (the switched sine is
  two: on until ``t_off``, then off for ever);
* :class:`EventMarch`, the bookkeeping: which forcing piece holds, the net
  force on a held mass, the record of events (with its bound), the mode of a
  mass (stick or slip, from ``v`` and the net force, eq. 11), the rule at a
  zero of ``v`` (stop or reversal) and the rest;
* :class:`PhaseMarch`, the march from phase to phase of the ``exact`` and
  ``event-driven`` methods: stick phases and breakaways in closed form, slip
  phases from the method's :data:`SlipFactory` (the closed form of
  :mod:`lumped.solvers.closed_form`, or the integrator of
  :mod:`lumped.solvers.event_driven`).

The ``event-locating`` scheme (:mod:`lumped.solvers.event_capturing`) is an
:class:`EventMarch` that walks the time grid instead, step by step.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

import numpy as np

from lumped.laws import sticks
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.model.problem import DASHPOT
from lumped.numerics import sine

__all__ = ["Event", "EventMarch", "KINDS", "Phase", "PhaseMarch", "Piece", "SlipFactory", "SlipPhase", "STICK"]

#: The mode of a sticking mass; a slipping one's is its direction ``+-1``.
STICK = 0
#: The kinds of :class:`Event`, the same for every method and any number of masses.
KINDS = ("stop", "reversal", "breakaway", "switch", "rest")


@dataclass(frozen=True)
class Event:
    """An event of a motion followed phase by phase: the one event record of every method, for any network.

    Attributes
    ----------
    time : float, s
    kind : str
        One of :data:`KINDS`: ``"stop"`` (an element's rate reaches zero and
        it sticks), ``"reversal"`` (it reaches zero and slips back at once),
        ``"breakaway"`` (a sticking element's force leaves its static band),
        ``"switch"`` (a load comes on or goes off) or ``"rest"`` (no mass moves
        again: dated back to the start of the stick that lasts for ever).
    x : tuple of float, m
        Each mass's position at the event, in the network's order.
    elements : tuple of str
        The elements that fired (their names); none for a switch or a rest.
    mode : tuple of int
        Each element's mode from the event on: ``0`` sticking (or an element
        that cannot stick), ``+-1`` slipping with its elongation rate's sign.
        For one mass run as an :class:`~lumped.model.oscillator.Oscillator`
        the elements are :func:`~lumped.model.problem.oscillator_network`'s,
        the spring's and the dashpot's.
    """

    time: float
    kind: str
    x: tuple[float, ...]
    elements: tuple[str, ...] = ()
    mode: tuple[int, ...] = ()


class SlipPhase(Protocol):
    """The motion of a slip phase, as the march and the solutions use it.

    ``s_tau`` (N) is the direction times the threshold; ``first_stop(t_lim,
    direction)`` the first time in ``(t0, t_lim]`` at which ``v`` returns to
    zero, or ``None``; ``state(t)`` the displacement and velocity at times
    ``t`` of the phase.
    """

    s_tau: float

    def first_stop(self, t_lim: float, direction: int) -> float | None: ...

    def state(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]: ...


@dataclass(frozen=True)
class Phase:
    """``kind`` is ``"stick"`` or ``"slip"``; ``motion`` is set for slip phases."""

    start: float
    end: float
    kind: str
    x_start: float
    motion: SlipPhase | None = None


@dataclass(frozen=True)
class Piece:
    """The forcing on one smooth segment ``[.., end]``: ``amplitude sin(omega t + phase)``."""

    amplitude: float
    omega: float
    phase: float
    end: float

    def __call__(self, t: float) -> float:
        """The force at ``t`` (N) with the project's sine (:func:`lumped.numerics.sine.sin`)."""
        return self.amplitude * sine.sin(self.omega * t + self.phase) if self.amplitude else 0.0

    @property
    def zero_for_ever(self) -> bool:
        """True for the last piece of a forcing that ends (or never was): no force after it starts."""
        return self.amplitude == 0 and self.end == math.inf


#: The forcing after ``t_off`` (or of a zero force): nothing, for ever.
OFF = Piece(0.0, 0.0, 0.0, math.inf)


class EventMarch:
    """The bookkeeping of a march through events, shared by every event-locating method.

    A subclass walks the motion (phase by phase, or step by step on a grid)
    and asks this class which forcing piece holds (:meth:`piece`), what the
    net force on a held mass is (:meth:`net`), which mode a mass is in
    (:meth:`mode`) and what happens at a zero of ``v`` (:meth:`stop_or_reverse`);
    it records the events with :meth:`event` and the rest with
    :meth:`record_rest`.  ``on`` is the forcing piece until ``t_off`` (its
    amplitude ``0`` for a zero force); :meth:`force_at` is how the subclass
    evaluates a piece.
    """

    def __init__(self, osc: Oscillator, force: SwitchedSine, on: Piece, max_events: int | None = None) -> None:
        self.m, self.k, self.tau = osc.mass, osc.stiffness, osc.threshold
        self.force, self.on, self.off = force, on, OFF
        self.max_events = max_events
        self.events: list[Event] = []
        #: ``(start, x)`` of the rest, ``(nan, nan)`` until one is recorded.
        self.rest: tuple[float, float] = (math.nan, math.nan)

    def piece(self, t: float) -> Piece:
        """The forcing piece holding just after ``t``."""
        return self.on if t < self.force.until and self.on.amplitude != 0 else self.off

    def force_at(self, p: Piece, t: float) -> float:
        """The force of the piece ``p`` at ``t`` (N): ``p(t)``, the project's sine."""
        return p(t)

    def net(self, t: float, x: float) -> float:
        """``F(t) - k x`` (N): the net force on a mass held at ``x``, with the piece holding just after ``t``."""
        return self.force_at(self.piece(t), t) - self.k * x

    def event(self, t: float, kind: str, x: float, mode: int) -> None:
        """Record an event at ``t`` (s) with the displacement ``x`` (m) and the mass's ``mode`` after it (its
        dashpot's: :data:`STICK` or the slip direction); refuse one past ``max_events``."""
        fired = () if kind in ("switch", "rest") else (DASHPOT,)
        self.events.append(Event(t, kind, (x,), fired, (0, mode)))
        if self.max_events is not None and len(self.events) > self.max_events:
            raise ValueError(
                f"t_end: more than the {self.max_events} events a run may have before t_end; "
                "shorten t_end or use backward Euler"
            )

    def mode(self, v: float, net: float) -> int:
        """:data:`STICK` or the slip direction ``+-1`` of a mass moving at ``v`` under the net force ``net``."""
        if v != 0:
            return 1 if v > 0 else -1
        if sticks(net, -self.tau, self.tau):  # the one stick test: |net| <= tau
            return STICK
        return 1 if net > 0 else -1

    def stop_or_reverse(self, t: float, x: float, direction: int, net: float) -> int:
        """Record the stop or reversal at a zero of ``v`` after slipping with sign ``direction``; return the next mode.

        At a zero of ``v`` after slipping with sign ``s``, ``m v' = net - s tau``
        points against ``s``: the motion reverses only if the net force lies
        beyond ``-s tau``; otherwise the mass sticks.
        """
        reverses = -direction * net > self.tau
        mode = -direction if reverses else STICK
        self.event(t, "reversal" if reverses else "stop", x, mode)
        return mode

    def record_rest(self, start: float, x: float) -> None:
        """Record the rest (once) of a mass sticking at ``x`` since ``start`` under a force zero for ever."""
        if not any(e.kind == "rest" and e.time == start for e in self.events):
            self.rest = (start, x)
            self.event(start, "rest", x, STICK)


#: A slip phase's motion from ``(t, x, v)`` in direction ``s`` under the
#: forcing ``(P, w, ph)`` (canonical, ``P sin(w t + ph)``): the method's strategy.
SlipFactory = Callable[[float, float, float, int, tuple[float, float, float]], SlipPhase]


class PhaseMarch(EventMarch):
    """Marches from event to event, one phase at a time, to ``t_end``; ``slip`` makes the slip phases.

    The forcing is taken in its canonical form (:meth:`SwitchedSine.canonical`,
    ``P >= 0``, ``w >= 0``) and evaluated with :func:`math.sin`, as the closed
    forms of the phases are written.
    """

    def __init__(self, osc: Oscillator, force: SwitchedSine, t_end: float, max_events: int, slip: SlipFactory):
        on = Piece(0.0, 0.0, 0.0, force.until) if force.is_zero else Piece(*force.canonical(), force.until)
        super().__init__(osc, force, on, max_events)
        self.t_end, self.slip_motion = t_end, slip
        self.phases: list[Phase] = []

    def force_at(self, p: Piece, t: float) -> float:
        """``P sin(w t + ph)`` (N) with :func:`math.sin`."""
        return p.amplitude * math.sin(p.omega * t + p.phase)

    def run(self, x: float, v: float) -> None:
        """March from ``(0, x, v)`` to ``t_end``; every pass but the last adds an event.

        ``nxt`` is what comes next: :data:`STICK`, a slip direction ``+-1``, or
        ``None`` (decided from ``v`` and the net force).  After a stop the
        mass sticks even if round-off puts the net force a few ulps outside
        the band, and a reversal always reverses: otherwise a mass stopping
        on the band edge would slip and stop again without end.
        """
        t, nxt, stalled = 0.0, None, 0
        while t < self.t_end:
            p = self.piece(t)
            t_lim = min(p.end, self.t_end)
            nxt = self.mode(v, self.net(t, x)) if nxt is None else nxt
            if nxt == STICK:
                t, direction = self.stick(t, t_lim, x, p)
                nxt = direction or None
                continue
            t_before = t
            t, x, v, nxt = self.slip(t, t_lim, x, v, nxt, p)
            stalled = stalled + 1 if t == t_before else 0
            if stalled > 8:
                raise ValueError(
                    f"x0: the exact solver makes no progress at t = {t!r} s: the net force "
                    "stays on the edge of the static band to round-off; perturb x0 or the force"
                )
        if nxt == STICK and self.phases[-1].kind == "slip":  # a stop exactly at t_end
            self.stick(t, t, x, self.piece(t))

    def stick(self, t: float, t_lim: float, x: float, p: Piece) -> tuple[float, int]:
        """Record a stick phase from ``t``; return its end and the breakaway direction."""
        if p.zero_for_ever:  # the force stays zero: rest for ever
            last = self.phases[-1] if self.phases else None
            start = last.start if last and last.kind == "stick" and last.end == t else t
            self.phases.append(Phase(t, max(t, self.t_end), "stick", x))
            self.record_rest(start, x)
            return self.t_end, 0
        t_b, direction = self.breakaway(t, t_lim, x, p)
        self.phases.append(Phase(t, t_b, "stick", x))
        if direction != 0:
            self.event(t_b, "breakaway", x, direction)
        elif t_b == p.end and t_b < self.t_end:  # the mode after it: as run() chooses it next
            self.event(t_b, "switch", x, self.mode(0.0, self.net(t_b, x)))
        return t_b, direction

    def breakaway(self, t0: float, t_lim: float, x: float, p: Piece) -> tuple[float, int]:
        """First time in ``[t0, t_lim]`` at which ``|P sin(w t + ph) - k x|`` exceeds tau (closed form)."""
        P, w, ph = p.amplitude, p.omega, p.phase
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
        self, t: float, t_lim: float, x: float, v: float, direction: int, p: Piece
    ) -> tuple[float, float, float, int | None]:
        """Record a slip phase from ``(t, x, v)``; return where it ends and what follows."""
        motion = self.slip_motion(t, x, v, direction, (p.amplitude, p.omega, p.phase))
        t_stop = motion.first_stop(t_lim, direction)
        if t_stop is None:
            x_end, v_end = (float(a) for a in motion.state(t_lim))
            self.phases.append(Phase(t, t_lim, "slip", x, motion))
            if t_lim == p.end and t_lim < self.t_end:  # the mode after it: as run() chooses it next
                self.event(t_lim, "switch", x_end, self.mode(v_end, self.net(t_lim, x_end)))
            return t_lim, x_end, v_end, None
        x_stop = float(motion.state(t_stop)[0])
        self.phases.append(Phase(t, t_stop, "slip", x, motion))
        return t_stop, x_stop, 0.0, self.stop_or_reverse(t_stop, x_stop, direction, self.net(t_stop, x_stop))
