"""The events the work-precision study compares: those of a grid trajectory, and their pairing with the reference's.

* :data:`KINDS`: the event kinds compared;
* :func:`grid_events`: the events of a trajectory on a grid, read from its velocities;
* :func:`match_events`: per kind, the largest error of the events paired in order.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence

import numpy as np

from lumped.solvers.events import Event

__all__ = ["KINDS", "grid_events", "match_events"]

#: The event kinds compared (of :data:`lumped.solvers.events.KINDS`), with the issue's names: stick to slip,
#: slip to stick, reversal, forcing switched off (the one switch of the cases; ``"rest"`` repeats a ``"stop"``).
KINDS: Mapping[str, str] = {
    "breakaway": "stick to slip",
    "stop": "slip to stick",
    "reversal": "reversal",
    "switch": "forcing switched off",
}


def _reversal(t: np.ndarray, x: np.ndarray, v: np.ndarray, i: int, j: int) -> Event:
    """The zero of the line through ``(t_i, v_i)`` and ``(t_j, v_j)`` (opposite signs), ``x`` likewise."""
    a = v[i] / (v[i] - v[j])
    return Event(float(t[i] + a * (t[j] - t[i])), "reversal", (float(x[i] + a * (x[j] - x[i])),))


def _stick_events(t: np.ndarray, x: np.ndarray, first: int, last: int) -> list[Event]:
    """A stop at the first point of a stick run (none at ``t = 0``), a breakaway at its last (none at the end).

    A run of one point at ``t = 0`` gives nothing: it is the release at rest
    of a mass outside the band, which slips at once (the exact solver records
    no event there either).
    """
    out = [Event(float(t[first]), "stop", (float(x[first]),))] if first > 0 else []
    if last < t.size - 1 and last > 0:  # v = 0 at t = 0 alone is a release from rest, not a stick
        out.append(Event(float(t[last]), "breakaway", (float(x[last]),)))
    return out


def grid_events(t: np.ndarray, x: np.ndarray, v: np.ndarray, t_off: float | None = None) -> tuple[Event, ...]:
    """Events of a trajectory on a grid, read from its velocities (``v == 0`` exactly is stick).

    Parameters
    ----------
    t, x, v : ndarray, shape (n,)
        Times (s), increasing; displacements (m); velocities (m/s).
    t_off : float or None
        Switch-off time of the forcing (s), if inside the run.

    Returns
    -------
    tuple of Event
        In time order.  A *reversal* is a change of sign of ``v`` with at
        most one grid point of ``v == 0`` between the two signs (a scheme
        stepping across a reversal may land on ``v = 0`` for one step),
        dated at the zero of the line through the last velocity of one sign
        and the first of the other.  Every other run of ``v == 0`` is a
        stick: a *stop* at its first grid time (none for a run from
        ``t = 0``) and a *breakaway* at its last (none for a run to the
        end, or for ``v = 0`` at ``t = 0`` alone, a release from rest).  the *switch* is at ``t_off`` with ``x`` interpolated
        linearly (exact on a grid through ``t_off``).
    """
    t, x, v = (np.asarray(a, dtype=float) for a in (t, x, v))
    zero = np.flatnonzero(v == 0)
    runs = np.split(zero, np.flatnonzero(np.diff(zero) != 1) + 1) if zero.size else []
    events, moving = [], np.flatnonzero(v != 0)
    for i, j in itertools.pairwise(moving):
        if j - i <= 2 and v[i] * v[j] < 0:
            events.append(_reversal(t, x, v, i, j))
    for run_ in runs:
        lone = run_.size == 1 and 0 < run_[0] < v.size - 1 and v[run_[0] - 1] * v[run_[0] + 1] < 0
        if not lone:
            events += _stick_events(t, x, int(run_[0]), int(run_[-1]))
    if t_off is not None and t[0] < t_off <= t[-1]:
        events.append(Event(float(t_off), "switch", (float(np.interp(t_off, t, x)),)))
    return tuple(sorted(events, key=lambda e: e.time))


def match_events(found: Sequence[Event], wanted: Sequence[Event]) -> dict[str, float]:
    """Per kind of :data:`KINDS` present in ``wanted``: the largest error of the pairs matched in order.

    The ``i``-th event of a kind in ``found`` is paired with the ``i``-th of
    that kind in ``wanted``; the error is in time (s), in displacement (m)
    for the ``switch``.  If the count of any kind differs, every kind is
    ``nan``: the motion took another course (a half-cycle more or less, a
    spurious stick), and pairing its events in order would compare
    different switches.  A kind absent from ``wanted`` is left out.
    """
    out: dict[str, float] = {}
    counts = [(sum(e.kind == k for e in found), sum(e.kind == k for e in wanted)) for k in KINDS]
    paired = all(a == b for a, b in counts)
    for kind in KINDS:
        want = [e for e in wanted if e.kind == kind]
        got = [e for e in found if e.kind == kind]
        if not want:
            continue
        if not paired:
            out[kind] = math.nan
            continue
        values = [(a.x[0], b.x[0]) if kind == "switch" else (a.time, b.time) for a, b in zip(got, want)]
        out[kind] = max(abs(a - b) for a, b in values)
    return out
