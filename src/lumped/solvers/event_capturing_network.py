"""The ``event-locating`` method for networks: trapezoidal steps within a mode, switching at located events.

A network of linear springs, Bingham and Coulomb elements and linear
dashpots is linear while its mode is fixed (which friction elements stick,
which way the others slip: :mod:`lumped.solvers.network_phase`).  Within a
mode, :func:`solve_capturing_network` takes trapezoidal steps of the mode's
linear ODE ``z' = A z + G F(t)`` on the grid ``t_n = n*dt``,

    (I - h/2 A) z_{n+1} = (I + h/2 A) z_n + h/2 G (F(t_n) + F(t_{n+1})),

with the loads ``F`` evaluated as functions of time (any load: sines,
constants, tables, ground motion, their sums, a callable).  After each step
it evaluates the mode's event functions (a slipping element's rate times its
direction, a sticking element's ``threshold -+ force``:
:func:`lumped.solvers.network_modes.event_rows`); when one has crossed zero
it locates the crossing inside the step by Brent's method on the partial
trapezoidal step ``s -> z(t_n + s)``, takes the partial step, chooses the
new mode there as the ``exact`` method does
(:func:`lumped.solvers.network_modes.select`) and completes the step.  A load
that may jump (a sine's ``until``, a constant's ``from`` and ``until``, a
table's ends: :func:`lumped.model.forcing.jumps`) splits the step at its
time in the same way.

The order is two through stops, breakaways and load switches, as for one
mass (:mod:`lumped.solvers.event_capturing`): the trapezoidal rule is of
order two within a mode, and a crossing located on its partial step is in
error by ``O(dt^3)`` locally.  It is A-stable, so stiff viscous branches do
not limit the step.  The one-mass method steps the dashpot's resolvent and
so runs any monotone law; this one steps the linear ODE of each mode, so it
runs the networks whose modes are linear (:func:`lumped.solvers.network_phase.refusal`).  Between the
trapezoidal rule and the ``exact`` method (the same modes, the same
switching rule, but each phase by the matrix exponential) the only
difference is the integration within a mode, which is what the
work-precision study of networks measures.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from lumped.model.forcing import jumps
from lumped.model.network import Network
from lumped.model.trajectory import Trajectory
from lumped.numerics.roots import brentq
from lumped.solvers.events import Event
from lumped.solvers.network_modes import (
    crossed,
    event_after,
    event_rows,
    grid_rows,
    initial_mode,
    select,
    trajectory,
    zero_set,
)
from lumped.solvers.network_phase import Parts, Phase, parts

__all__ = ["MAX_SWITCHES_PER_STEP", "solve_capturing_network"]

#: Bound on the events located within one grid step.
MAX_SWITCHES_PER_STEP = 64
_EPS = float(np.finfo(float).eps)


class _Mode(NamedTuple):
    """The mode's phase, its event rows on ``(z, F)``, and the trapezoidal matrices of the full step."""

    ph: Phase
    rows: np.ndarray
    feed: np.ndarray
    what: list[tuple[int, str]]
    full: tuple[np.ndarray, np.ndarray]


class _March:
    """The state of a run: time, the mode, its state ``z``, the phases begun (for the rests) and the events."""

    def __init__(self, net: Network, p: Parts, dt: float, t_end: float) -> None:
        self.net, self.p, self.dt = net, p, dt
        self.breaks = sorted({t for load in net.loads for t in jumps(load.force) if 0 < t < t_end})
        x, v = (a[:-1] for a in net.initial_positions())
        mode, zero = initial_mode(p, v)
        self.t = 0.0
        self.events: list[Event] = []
        self.phases: list[Phase] = []
        self._enter(select(p, 0.0, x, v, mode, zero, {}, self.after(0.0)))

    def _force(self, t: float) -> np.ndarray:
        return self.net.load_table(np.array([t]))[0]

    def after(self, t: float) -> np.ndarray:
        """The external force on each mass just after ``t`` (a load that jumps at ``t`` has jumped)."""
        return self._force(math.nextafter(t, math.inf) if t in self.breaks else t)

    def before(self, t: float) -> np.ndarray:
        """The external force on each mass just before ``t`` (a load that jumps at ``t`` has not yet)."""
        return self._force(math.nextafter(t, -math.inf) if t in self.breaks else t)

    def _enter(self, ph: Phase) -> None:
        rows, feed, what = event_rows(self.p, ph)
        self.mode = _Mode(ph, rows, feed, what, self._matrices(ph, self.dt))
        self.z = ph.z0.copy()
        self.phases.append(ph)

    @staticmethod
    def _matrices(ph: Phase, h: float) -> tuple[np.ndarray, np.ndarray]:
        """``((I - h/2 A)^-1 (I + h/2 A), (I - h/2 A)^-1 h/2 G)`` of the trapezoidal step of length ``h``."""
        eye = np.eye(ph.a.shape[0])
        lhs = eye - 0.5 * h * ph.a
        return np.linalg.solve(lhs, eye + 0.5 * h * ph.a), np.linalg.solve(lhs, 0.5 * h * ph.gin)

    def advance(self, z: np.ndarray, f0: np.ndarray, t0: float, t1: float) -> np.ndarray:
        """The trapezoidal step from ``z`` at ``t0`` (load ``f0`` just after it) to ``t1``."""
        h = t1 - t0
        step, drive = self.mode.full if h == self.dt else self._matrices(self.mode.ph, h)
        return step @ z + drive @ (f0 + self.before(t1))

    def g(self, z: np.ndarray, load: np.ndarray) -> np.ndarray:
        """The mode's event functions at the state ``z`` under ``load``."""
        return self.mode.rows @ z + self.mode.feed @ load

    def step_to(self, t1: float) -> None:
        """Advance from ``self.t`` to the grid time ``t1``, locating and applying every event on the way."""
        for _ in range(MAX_SWITCHES_PER_STEP):
            t0, z0 = self.t, self.z
            f0 = self.after(t0)
            end = next((b for b in self.breaks if t0 < b <= t1), t1)
            z1 = self.advance(z0, f0, t0, end)
            fired = []
            if self.mode.what:
                g0 = self.g(z0, f0)
                fired = self._fired(g0, self.g(z1, self.before(end)), t0)
            if fired:
                at, fired = self._locate(z0, f0, t0, end, g0, fired)
                self.t, self.z = at, (self.advance(z0, f0, t0, at) if at > t0 else z0)
                self._switch(fired)
                continue
            self.t, self.z = end, z1
            if end in self.breaks:
                self._switch([])  # a load comes on or goes off
            if end == t1:
                return
        raise ArithmeticError(f"t = {self.t!r}: more than {MAX_SWITCHES_PER_STEP} events within one step")

    def _fired(self, g0: np.ndarray, g1: np.ndarray, t0: float) -> list[int]:
        """The rows at or below zero at the step's end (at a phase's start, not those leaving zero upwards)."""
        return [int(r) for r in crossed(self.mode.what, g0, g1, t0 == self.mode.ph.start)]

    def _locate(self, z0, f0, t0, t1, g0, fired) -> tuple[float, list[tuple[int, str]]]:  # noqa: ANN001
        """The earliest crossing among the rows ``fired`` on the partial steps, and every row crossing there."""
        roots = {}
        for r in fired:

            def g(s: float, r: int = r) -> float:
                return float(self.g(self.advance(z0, f0, t0, s), self.before(s))[r])

            if g0[r] <= 0:
                roots[r] = t0
            elif g(t1) > 0:  # the partial step's rounding differs from the full step's: the crossing is at its end
                roots[r] = t1
            else:
                roots[r] = brentq(g, t0, t1, xtol=4 * _EPS * max(1.0, abs(t1)))
        first = min(roots.values())
        near = 1e-12 * max(1.0, abs(first))
        return first, sorted({self.mode.what[r] for r, s in roots.items() if s - first <= near})

    def _switch(self, fired: list[tuple[int, str]]) -> None:
        """Choose the mode after an event (``fired``) or a load switch (none) at ``self.t``, and enter it."""
        ph, t = self.mode.ph, self.t
        load = self.after(t)
        x, v, _, f = ph.values(self.z, load)
        elements = [e for e, _ in fired]
        forced = {e: int(np.sign(f[e])) for e, kind in fired if kind == "breakaway"}
        zero = zero_set(self.p, ph, v, elements)
        self._enter(select(self.p, t, x, v, ph.mode, zero, forced, load))
        self.events.append(event_after(t, fired, x, self.mode.ph.mode, self.net.element_names))

    def sample(self) -> tuple[np.ndarray, ...]:
        """Positions, velocities, forces (under the load at this time) and the sticking flags now."""
        x, v, _, f = self.mode.ph.values(self.z, self._force(self.t))
        return x, v, f, self.mode.ph.mode == 0


def solve_capturing_network(network: Network, t_end: float, dt: float, *, save_every: int = 1) -> Trajectory:
    """The event-locating motion of ``network`` on the grid ``t_n = n*dt`` (every ``save_every``-th row kept).

    Raises
    ------
    ValueError
        For a bad argument, or a network with a mode that is not linear
        (one line naming the element that blocks it).
    """
    index, dt, save_every = grid_rows(network, "event-locating", t_end, dt, save_every, any_load=True)
    n = int(index[-1])
    p = parts(network, with_loads=False)  # the loads are stepped as functions of time
    march = _March(network, p, dt, n * dt)
    samples: list[tuple[np.ndarray, ...]] = [march.sample()]
    kept = set(index.tolist())
    for step in range(1, n + 1):
        march.step_to(step * dt)
        if step in kept:
            samples.append(march.sample())
    rows = tuple(np.array(r) for r in zip(*samples))
    return trajectory(network, p, index, dt, save_every, rows, march.phases, march.events, "event-locating")
