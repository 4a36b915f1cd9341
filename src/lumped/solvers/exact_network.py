"""The ``exact`` method for networks: closed forms per phase, events located, modes chosen.

A network of linear springs, Bingham and Coulomb elements, linear
dashpots and friction contacts whose slip curve is linear (static above
kinetic, a viscous part), with points driven at constant velocities, under
constant and sine loads (:func:`lumped.solvers.network_phase.refusal`
says what else blocks it) moves, between events, by the linear ODE of its
mode (:mod:`lumped.solvers.network_phase`: the matrix exponential of the
first-order system with the loads' generators and, with driven points, the
ramp ``t - start``).  :func:`solve_exact_network`
marches from phase to phase:

1. within a phase, every event function is a linear map of the state ``z``:
   a slipping element's rate times its direction (a *stop* when it reaches
   0), a sticking element's ``threshold -+ force`` (a *breakaway* when
   either reaches 0; a contact's threshold is its static force); they are tabulated on a sub-grid of a fiftieth of the
   phase's shortest period, ``z_{j+1} = expm(A h) z_j``, and the first sign
   change is located by :func:`lumped.numerics.roots.brentq` on
   ``expm(A (t - t_j)) z_j``;
2. a load coming on or going off (``until``, a constant's ``from``) ends a
   phase too (a *switch*);
3. at an event the new mode is chosen among the elements at zero rate
   (:func:`lumped.solvers.network_modes.select`, shared with the
   ``event-locating`` method): a contact that stops sticks if its holding
   force is within its static bound, and else slips on, the other way, at
   once; one that breaks away slips in the direction of its force, against
   its kinetic force.

Each mass's final rest is the start of the last run of phases in which a
path of sticking elements holds it to the ground (as the independent
reference of ``tests/references.py`` defines it).
"""

from __future__ import annotations

import math

import numpy as np
from lumped.model.network import Network
from lumped.model.trajectory import Trajectory
from lumped.numerics.expm import expm
from lumped.numerics.roots import brentq
from lumped.numerics.sine import MAX_ARGUMENT
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
from lumped.solvers.network_phase import Parts, Phase, parts, switch_times

__all__ = ["MAX_EVENTS", "MAX_SUBSTEPS", "check_span", "march", "sample", "solve_exact_network"]

#: Most phases of one run before it is refused (each costs a few matrix exponentials).
MAX_EVENTS = 20_000
#: Sub-steps per shortest period of a phase, for bracketing the events.
_PER_PERIOD = 50
#: Most bracketing sub-steps of one phase (about 15 s of work, at 15 us each) before the run is refused.
MAX_SUBSTEPS = 1_000_000
#: ``exp(x)`` underflows to 0 below this: a mode decayed by more carries no digit into the motion.
_DECAYED = math.log(np.finfo(float).tiny)


def step_for(ph: Phase, span: float) -> float:
    """The bracketing sub-step: a fiftieth of the shortest period (of the motion and the loads)."""
    fastest = float(np.max(np.abs(np.linalg.eigvals(ph.a)), initial=0.0))
    if fastest == 0:
        return span / _PER_PERIOD
    return min(2 * math.pi / fastest / _PER_PERIOD, span / 4)


def _next_event(p: Parts, ph: Phase, t_lim: float) -> tuple[float, list[tuple[int, str]]]:
    """The first event of ``ph`` in ``(start, t_lim]``: its time and ``(element, kind)`` fired; none at ``t_lim``."""
    rows, _, what = event_rows(p, ph)
    if not what:
        return t_lim, []
    h = step_for(ph, t_lim - ph.start)
    step = expm(ph.a * h)
    t0, z = ph.start, ph.z0
    for _ in range(MAX_SUBSTEPS):
        if t0 >= t_lim:
            break
        t1 = min(t0 + h, t_lim)
        z1 = step @ z if t1 == t0 + h else expm(ph.a * (t1 - t0)) @ z
        g0, g1 = rows @ z, rows @ z1
        hit = crossed(what, g0, g1, t0 == ph.start)
        if hit.size:
            return _locate(ph, rows, what, hit, t0, z, t1, g0)
        t0, z = t1, z1
    if t0 < t_lim:
        raise ValueError(
            f"t_end: the phase from t = {ph.start:.6g} s has no event in {MAX_SUBSTEPS} sub-steps of {h:.3g} s (a "
            f"fiftieth of its shortest period), {(t_lim - ph.start) / h:.3g} of which reach t = {t_lim:.6g} s; "
            "shorten t_end (or dt: the grid's last time may lie past t_end) or use backward Euler"
        )
    return t_lim, []


def _comes_back(ph: Phase, row: np.ndarray, t0: float, z: np.ndarray, t1: float) -> float:
    """When an event function that starts at zero (to round-off) is below zero at ``t1``: ``t0`` if it falls at
    once, else (it first rises: a slip that reverses and stops again within the sub-step) the time in
    ``(t0, t1]`` at which it comes back to zero, found past its peak."""
    value = lambda s: float(row @ (expm(ph.a * (s - t0)) @ z))
    rate = lambda s: float(row @ (ph.a @ (expm(ph.a * (s - t0)) @ z)))
    if not (rate(t0) > 0 and rate(t1) < 0):
        return t0
    peak = brentq(rate, t0, t1)
    return brentq(value, peak, t1) if value(peak) > 0 else t0


def _locate(ph, rows, what, fired, t0, z, t1, g0) -> tuple[float, list[tuple[int, str]]]:  # noqa: ANN001
    """The earliest root among the rows ``fired`` in ``(t0, t1]``, and every row that fires there."""
    roots = {}
    for r in fired:
        if g0[r] <= 0:
            roots[r] = _comes_back(ph, rows[r], t0, z, t1) if t0 == ph.start else t0
            continue
        roots[r] = brentq(lambda s, r=r: float(rows[r] @ (expm(ph.a * (s - t0)) @ z)), t0, t1)
    first = min(roots.values())
    near = 1e-12 * max(1.0, abs(first))
    return first, sorted({what[r] for r, s in roots.items() if s - first <= near})


def march(
    p: Parts, x: np.ndarray, v: np.ndarray, t_end: float, names: list[str], max_events: int = MAX_EVENTS
) -> tuple[list[Phase], list[Event]]:
    """The phases from the state ``(x, v)`` (m, m/s; (n,) each) at ``t = 0`` to ``t_end`` and the events
    between them (``names`` the elements', for the events)."""
    mode, zero = initial_mode(p, v)
    phases = [select(p, 0.0, x, v, mode, zero, {})]
    events: list[Event] = []
    breaks = switch_times(p, t_end) + [t_end]
    while True:
        ph = phases[-1]
        t_lim = next(b for b in breaks if b > ph.start)
        t, fired = _next_event(p, ph, t_lim)
        if t >= t_end:
            return phases, events
        x, v, _, f = ph.values(ph.z(t))
        elements = [e for e, _ in fired]
        forced = {e: int(np.sign(f[e])) for e, kind in fired if kind == "breakaway"}
        zero = zero_set(p, ph, v, elements)
        phases.append(select(p, t, x, v, ph.mode, zero, forced))
        events.append(event_after(t, fired, x, phases[-1].mode, names))
        if len(events) > max_events:
            raise ValueError(f"t_end: more than the {max_events} events a run may have before t_end = {t_end:g} s")


def check_span(ph: Phase, t: float) -> None:
    """Refuse a time ``t`` at which the phase ``ph`` keeps no digit of its motion (one line).

    ``z(t) = expm(a (t - start)) z0`` carries each eigenvalue ``l`` of ``a`` as ``exp(l (t - start))``: a mode
    decayed below the smallest double (``Re l (t - start) < log(tiny)``) is exactly 0, but one that survives
    with a phase ``|Im l| (t - start)`` beyond :data:`~lumped.numerics.sine.MAX_ARGUMENT` (the range of
    every sine of the project, as the loads' own :func:`~lumped.model.forcing.check_span`) has lost it.
    """
    span = t - ph.start
    lam = np.linalg.eigvals(ph.a)
    live = lam.real * span > _DECAYED
    turns = float(np.max(np.abs(lam.imag[live]), initial=0.0)) * span
    if turns > MAX_ARGUMENT:
        raise ValueError(
            f"dt: the exact motion at t = {t:.6g} s (the grid's last time) has a phase of {turns:.3g} rad since "
            f"t = {ph.start:.6g} s, beyond the {MAX_ARGUMENT:.0e} rad of double precision; lower dt or t_end"
        )


def sample(phases: list[Phase], times: np.ndarray) -> tuple[np.ndarray, ...]:
    """Positions, velocities, forces (rows per time) and the rigid flags, from the phase holding each time.

    Raises
    ------
    ValueError
        At a time whose phase is beyond double precision (:func:`check_span`), or a value that is not finite.
    """
    starts = np.array([ph.start for ph in phases])
    which = np.searchsorted(starts, times, side="right") - 1
    rows = [[], [], [], []]
    for i, ph in enumerate(phases):
        at = times[which == i]
        if not at.size:
            continue
        check_span(ph, float(at[-1]))
        with np.errstate(over="ignore", invalid="ignore"):  # beyond double precision: refused below
            y = np.array([ph.z(s) for s in at]) @ ph.out.T
        n = ph.n
        rows[0].append(y[:, :n])
        rows[1].append(y[:, n : 2 * n])
        rows[2].append(y[:, 3 * n :])
        rows[3].append(np.repeat((ph.mode == 0)[None, :], at.size, axis=0))
    out = tuple(np.vstack(r) for r in rows)
    bad = ~np.all(np.isfinite(np.hstack(out[:3])), axis=1)
    if bad.any():
        raise ValueError(
            f"dt: the exact motion is not finite at t = {float(times[bad][0]):.6g} s (the grid's last time is "
            f"{float(times[-1]):.6g} s; beyond double precision); lower dt or t_end"
        )
    return out


def solve_exact_network(
    network: Network, t_end: float, dt: float, *, save_every: int = 1, max_events: int = MAX_EVENTS
) -> Trajectory:
    """The exact motion of ``network`` sampled on the grid ``t_n = n*dt`` (as :meth:`ExactSolution.sample`).

    Raises
    ------
    ValueError
        For a bad argument, or a network whose phases have no closed form
        (one line naming the element or load that blocks it).
    """
    index, dt, save_every = grid_rows(network, "exact", t_end, dt, save_every, any_load=False, slip=True)
    p = parts(network)
    x0, v0 = (a[:-1] for a in network.initial_positions())
    phases, events = march(p, x0, v0, float(index[-1] * dt), network.element_names, max_events)
    rows = sample(phases, index * dt)
    return trajectory(network, p, index, dt, save_every, rows, phases, events, "exact")
