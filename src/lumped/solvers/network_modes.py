"""The modes of a piecewise-linear network and their switches, shared by its ``exact`` and ``event-locating`` methods.

A friction element (one that can stick: Bingham, Coulomb, a friction
contact with a linear slip curve) is in one of three modes: sticking (0) or
slipping one way (+-1); the mode of the network
fixes its linear phase (:func:`lumped.solvers.network_phase.phase`).  This
module holds what both methods do at the boundaries of phases:

* :func:`initial_mode` and :func:`select`, the choice of a consistent mode
  among the elements at zero rate: all start sticking, those breaking away
  slip in the direction of their force; while a sticking element's reaction
  leaves its closed band (:func:`lumped.laws.sticks`, the one stick test of
  every method: a force exactly at its threshold holds), the one furthest out slips in
  the direction of its force, and a slipping one whose rate would turn back
  sticks again;
* :func:`event_rows`, the event functions of a phase as linear rows on its
  state (a slipping element's rate times its direction: a *stop* at 0; a
  sticking element's ``threshold -+ force``: a *breakaway* at 0);
* :func:`zero_set`, the elements whose mode is to be chosen after an event;
* :func:`final_rest`, each mass's rest: the start of its last run of phases
  in which a path of sticking elements holds it to the ground;
* :func:`event_after`, an event as the trajectory reports it (the one
  :class:`~lumped.solvers.events.Event` of every method).
"""

from __future__ import annotations

import math

import numpy as np
from lumped.laws import sticks
from lumped.model.network import Network
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate
from lumped.solvers.events import Event
from lumped.solvers.network_phase import Parts, Phase, generator_one, phase, refusal

__all__ = [
    "crossed",
    "event_after",
    "event_rows",
    "final_rest",
    "grid_index",
    "grid_rows",
    "initial_mode",
    "rest_event",
    "select",
    "trajectory",
    "zero_set",
]


def rates(p: Parts, v: np.ndarray) -> np.ndarray:
    """The elements' rates (m/s, (E,)) at the masses' velocities ``v``, driven points' included."""
    w = p.b.T @ v
    return w if p.drive is None else w + p.drive


def initial_mode(p: Parts, v: np.ndarray) -> tuple[np.ndarray, list[int]]:
    """Slip in the direction of the initial rate; friction elements at zero rate are to be chosen."""
    w = rates(p, v)
    mode = np.where(p.friction, np.sign(w), 0).astype(int)
    return mode, [int(e) for e in np.flatnonzero(p.friction & (w == 0))]


def _consistent(
    p: Parts, ph: Phase, zero: list[int], forced: set[int], load: np.ndarray | None
) -> tuple[int, int] | None:
    """``None`` if the mode of ``ph`` holds at its start (with the further ``load``), else ``(element, new mode)``."""
    _, _, acc, f = ph.values(ph.z0, load)
    out = [e for e in zero if ph.mode[e] == 0 and not sticks(f[e], -p.tau[e], p.tau[e])]
    if out:
        e = max(out, key=lambda e: abs(f[e]) / p.tau[e])
        return e, int(np.sign(f[e]))
    rel = p.b.T @ acc
    margin = 1e-12 * float(np.max(p.tau)) / float(np.min(p.m))
    back = [e for e in zero if ph.mode[e] != 0 and e not in forced and rel[e] * ph.mode[e] < -margin]
    return (back[0], 0) if back else None


def select(
    p: Parts,
    t: float,
    x: np.ndarray,
    v: np.ndarray,
    mode: np.ndarray,
    zero: list[int],
    forced: dict,
    load: np.ndarray | None = None,
) -> Phase:
    """The phase of the mode chosen at ``t`` for the elements ``zero`` (the module's rule), with the
    elements of ``forced`` slipping the way given and the further ``load`` on the masses (if any)."""
    trial = mode.copy()
    trial[zero] = 0
    for e, s in forced.items():
        trial[e] = s
    for _ in range(3 * len(zero) + 3):
        ph = phase(p, t, x, v, trial)
        change = _consistent(p, ph, zero, set(forced), load)
        if change is None:
            return ph
        trial[change[0]] = change[1]
    raise ArithmeticError(f"t = {t!r}: no consistent mode found for the elements {zero} at zero rate")


def event_rows(p: Parts, ph: Phase) -> tuple[np.ndarray, np.ndarray, list[tuple[int, str]]]:
    """The event functions of ``ph`` as rows on ``z`` (each starts positive) and on a further load ``F``
    (``rows @ z + feed @ F``), with ``(element, kind)``."""
    w = p.b.T @ ph.rows("v")
    one = generator_one(p, ph.a.shape[0])
    if p.drive is not None:
        w[:, one] += p.drive
    f, f_in = ph.rows("f"), ph.feed[3 * ph.n :]
    rows, feed, what = [], [], []
    for e in np.flatnonzero(p.friction):
        if ph.mode[e] != 0:
            rows.append(ph.mode[e] * w[e])
            feed.append(np.zeros(ph.n))
            what.append((int(e), "stop"))
        else:
            unit = np.zeros(ph.a.shape[0])
            unit[one] = p.tau[e]  # the generator "1"
            rows += [unit - f[e], unit + f[e]]
            feed += [-f_in[e], f_in[e]]
            what += [(int(e), "breakaway")] * 2
    return np.array(rows).reshape(len(rows), ph.a.shape[0]), np.array(feed).reshape(len(rows), ph.n), what


def crossed(what: list[tuple[int, str]], g0: np.ndarray, g1: np.ndarray, at_start: bool) -> np.ndarray:
    """The rows of :func:`event_rows` past their event at the end of an interval (values ``g1``, ``g0`` at its
    start): a slipping element's rate at or below zero (a *stop*), a sticking element's margin below zero (a
    *breakaway*: the stick band is closed, :func:`lumped.laws.sticks`, so a force exactly at its threshold
    holds).  At a phase's start, not those leaving their event level upwards (the event that began it)."""
    strict = np.array([kind == "breakaway" for _, kind in what], dtype=bool)
    past1 = np.where(strict, g1 < 0, g1 <= 0)
    if not at_start:
        return np.flatnonzero(past1)
    past0 = np.where(strict, g0 < 0, g0 <= 0)
    return np.flatnonzero(past1 & ~(past0 & (g1 >= g0)))


def zero_set(p: Parts, ph: Phase, v: np.ndarray, fired: list[int]) -> list[int]:
    """Friction elements sticking, just fired, or slipping at a rate within 1e-9 of the speeds."""
    w = rates(p, v)
    speeds = np.abs(v) if p.drive is None else np.concatenate((np.abs(v), np.abs(p.drive)))
    tol = 1e-9 * float(np.max(speeds, initial=0.0))
    return [int(e) for e in np.flatnonzero(p.friction) if ph.mode[e] == 0 or e in fired or abs(w[e]) <= tol]


def event_after(t: float, fired: list[tuple[int, str]], x: np.ndarray, mode: np.ndarray, names: list[str]) -> Event:
    """The event at ``t`` of the elements ``fired`` (``(element, kind)``; none for a load's switch), with the
    positions ``x`` there and the ``mode`` chosen after it: a stop after which its element slips is a
    reversal (:data:`~lumped.solvers.events.KINDS`)."""
    if not fired:
        return Event(t, "switch", tuple(float(a) for a in x), (), tuple(int(s) for s in mode))
    first, kind = fired[0]
    if kind == "stop" and mode[first] != 0:
        kind = "reversal"
    elements = tuple(names[e] for e in dict.fromkeys(e for e, _ in fired))
    return Event(t, kind, tuple(float(a) for a in x), elements, tuple(int(s) for s in mode))


def rest_event(network: Network, p: Parts, phases: list[Phase]) -> Event | None:
    """The network's *rest* (:data:`~lumped.solvers.events.KINDS`), the one-mass march's rule: ``None`` unless
    the last phase holds every mass to the ground, no point is driven and every load is off for ever (a sine
    or a constant past its ``until``); then no mass moves again, from the start of the last run of phases
    that hold every mass (the latest of :func:`final_rest`'s starts)."""
    last = phases[-1]
    driven = p.drive is not None and bool(np.any(p.drive != 0))
    forms = [load.force.closed_form() for load in network.loads]
    loaded = any(f is None or (f.amplitude != 0 and last.start < f.until) for f in forms)
    if driven or loaded or not last.grounded.all():
        return None
    x = last.values(last.z0)[0]
    start = float(np.max(final_rest(phases, x)[0]))
    return Event(start, "rest", tuple(float(a) for a in x), (), tuple(int(s) for s in last.mode))


def final_rest(phases: list[Phase], x_end: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start of each mass's last run of grounded phases (``nan`` if it moves at the end), and its position."""
    rest = np.full(x_end.size, math.nan)
    for i in range(x_end.size):
        for ph in reversed(phases):
            if not ph.grounded[i]:
                break
            rest[i] = ph.start
    return rest, np.where(np.isnan(rest), math.nan, x_end)


def grid_rows(
    network: object, method: str, t_end: float, dt: float, save_every: int, *, any_load: bool, slip: bool = False
) -> tuple[np.ndarray, float, int]:
    """``(index, dt, save_every)``: the saved grid indices ``n`` of ``t_n = n*dt`` (the last always kept)
    and the checked arguments, after the method's refusal of ``network`` (one line naming what blocks it;
    ``any_load`` and ``slip`` as :func:`~lumped.solvers.network_phase.refusal`'s)."""
    if not isinstance(network, Network):
        raise ValueError(f"network must be a Network, got {type(network).__name__}")
    if (reason := refusal(network, method, any_load=any_load, slip=slip)) is not None:
        raise ValueError(reason)
    return grid_index(t_end, dt, save_every)


def grid_index(t_end: float, dt: float, save_every: int) -> tuple[np.ndarray, float, int]:
    """``(index, dt, save_every)``: the saved grid indices ``n`` of ``t_n = n*dt`` (the last always kept) and
    the checked arguments (:func:`lumped.numerics.validate.grid`, the output's size)."""
    t_end, dt, save_every, n = validate.grid(t_end, dt, save_every)
    validate.output_size(n, save_every)
    index = np.arange(0, n + 1, save_every)
    return (index if index[-1] == n else np.append(index, n)), dt, save_every


def trajectory(
    network: Network,
    p: Parts,
    index: np.ndarray,
    dt: float,
    save_every: int,
    rows: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
    phases: list[Phase],
    events: list[Event],
    method: str,
) -> Trajectory:
    """The :class:`Trajectory` of a run by phases: ``rows`` are positions, velocities, forces and the
    sticking flags at the saved times (springs' states are their forces; no element is rigid at t = 0)."""
    x, v, f, rigid = rows
    times = index * dt
    rest = rest_event(network, p, phases)
    events = sorted(events + ([rest] if rest else []), key=lambda e: e.time)  # a rest is dated back
    rigid = rigid & p.friction[None, :]
    rigid[0] = False
    return Trajectory(
        t=times,
        positions=x,
        velocities=v,
        forces=f,
        applied=network.load_table(times),
        network=network,
        method=method,
        dt=dt,
        save_every=save_every,
        states=np.where(p.k[None, :] > 0, f, 0.0),
        rigid=rigid,
        final_rest=final_rest(phases, x[-1]),
        solver=method,
        events=tuple(events),
    )
