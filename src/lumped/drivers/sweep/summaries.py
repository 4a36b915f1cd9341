"""A sweep's summaries of a row, the definitions in one place (:func:`summarize`).

Every row of a sweep is one run of the single-mass system on the shared time
grid ``t_n = n*dt``, ``n = 0..N``, and is summarised in these columns:

* ``rest_time``, ``rest_position``: start (s) and displacement (m) of the run
  of ``v == 0`` that lasts to ``t_N``, as ``Trajectory.rest_time`` (the grid
  step for backward Euler, the exact event time for ``exact``); ``nan`` when
  the mass moves at ``t_N``.  A mass that starts at rest and never moves has
  ``rest_time = 0``.
* ``max_abs_x``: largest ``|x_n|`` over ``n = 0..N`` (m), ``x_0`` included.
* ``stops``: grid steps ``n >= 1`` with ``v_n == 0`` and ``v_{n-1} != 0``,
  i.e. steps entering the stick branch of the corrector from motion.  Starting
  at rest (``v0 = 0``) is not a stop.  It counts what the method's samples
  show, not the exact solution's stop events: backward Euler (Algorithm 1)
  also sticks for one step at some velocity reversals that the exact motion
  passes through without stopping, and each such step counts (the free decay
  from ``x0 = 0.5`` has 3 where the exact solution stops once, and
  ``method="exact"`` counts 1).  With ``exact`` or ``event-driven`` a reversal
  falls on a grid point only by chance, so there the column is the number of
  stops that last past a grid point.
* for a *periodic* row (``force_amplitude != 0``, ``force_omega != 0`` and
  ``force_until >= t_N``): over the window ``t_n >= t_N - K T``,
  ``T = 2 pi/|omega|``, ``K`` = ``periods``: ``steady_amplitude`` (largest
  ``|x_n|``, m) and ``stops_per_period`` (stops in the window divided by
  ``K``).  The two columns are present when some row of the grid is forced
  (``force_amplitude != 0``); they are ``nan`` in the other rows.

The batched backward Euler forms the same summaries inside its kernel
(:mod:`lumped.kernels.batched`); :func:`summarize` forms them from a
single run's trajectory.

A sweep of a system file (:mod:`lumped.drivers.sweep.system`) writes the
first four for each mass, by the same definitions on that mass's ``x`` and
``v`` (:func:`mass_summaries`): ``rest_time_<mass>``,
``rest_position_<mass>``, ``max_abs_x_<mass>``, ``stops_<mass>``
(:func:`mass_columns`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import NamedTuple

import numpy as np

from lumped.model.trajectory import Trajectory

#: The summaries of every row, in order.
SUMMARY_COLUMNS = ("rest_time", "rest_position", "max_abs_x", "stops")
#: The summaries of the periodic rows, written when some row is forced.
FORCED_COLUMNS = ("steady_amplitude", "stops_per_period")


def window_start(p: Mapping[str, np.ndarray], t_last: float, periods: int) -> np.ndarray:
    """Start (s) of the last ``periods`` forcing periods of each periodic row, ``nan`` elsewhere.

    A row is periodic when ``force_amplitude != 0``, ``force_omega != 0`` and
    ``force_until >= t_last`` (the forcing lasts to the end).
    """
    omega = np.abs(p["force_omega"])
    periodic = (p["force_amplitude"] != 0) & (omega != 0) & (p["force_until"] >= t_last)
    with np.errstate(divide="ignore"):
        start = t_last - periods * (2 * np.pi / omega)
    return np.where(periodic, start, np.nan)


class Summary(NamedTuple):
    """The summaries of one row (see the module docstring for the definitions)."""

    rest_time: float
    rest_position: float
    max_abs_x: float
    stops: int
    steady_amplitude: float
    stops_per_period: float


def summarize(traj: Trajectory, window: float, periods: int) -> Summary:
    """The summaries of one run saved at every grid point (``save_every == 1``).

    Parameters
    ----------
    traj : Trajectory
        A single run on the grid ``t_n = n*dt``.
    window : float, s
        Start of the window of the last ``periods`` forcing periods, ``nan``
        for a row that is not periodic (:func:`window_start`).
    periods : int
        ``K``.
    """
    stop = stop_mask(traj.v)
    inside = traj.t >= window
    steady = float(np.max(np.abs(traj.x[inside]))) if inside.any() else math.nan
    per_period = np.count_nonzero(stop & inside) / periods if inside.any() else math.nan
    return Summary(
        traj.rest_time,
        traj.rest_position,
        float(np.max(np.abs(traj.x))),
        int(np.count_nonzero(stop)),
        steady,
        per_period,
    )


def stop_mask(v: np.ndarray) -> np.ndarray:
    """The stops of a velocity history ``v`` (grid points ``n = 0..N``, first axis): ``v_n == 0`` and
    ``v_{n-1} != 0`` (``n >= 1``); a start at rest is not one."""
    v = np.asarray(v)
    return np.concatenate((np.zeros((1,) + v.shape[1:], dtype=bool), (v[1:] == 0) & (v[:-1] != 0)))


def mass_columns(masses: list[str] | tuple[str, ...]) -> tuple[str, ...]:
    """The per-mass summary columns of a system's sweep: for each mass, :data:`SUMMARY_COLUMNS` ``_<mass>``."""
    return tuple(f"{c}_{m}" for m in masses for c in SUMMARY_COLUMNS)


def mass_summaries(traj: Trajectory) -> dict[str, float]:
    """:data:`SUMMARY_COLUMNS` of every mass of a run saved at every grid point (``save_every == 1``), by
    :func:`mass_columns` name; the rest from ``Trajectory.rest_times`` and ``rest_positions`` (``nan`` while
    the mass moves at the end), as :func:`summarize` takes them for the one mass."""
    names = traj.network.mass_names
    stops = np.count_nonzero(stop_mask(traj.velocities), axis=0)
    peak = np.max(np.abs(traj.positions), axis=0)
    values = zip(traj.rest_times, traj.rest_positions, peak, stops)
    out: dict[str, float] = {}
    for name, (rest_time, rest_position, max_abs_x, count) in zip(names, values):
        row = (float(rest_time), float(rest_position), float(max_abs_x), int(count))
        out |= {f"{c}_{name}": v for c, v in zip(SUMMARY_COLUMNS, row)}
    return out
