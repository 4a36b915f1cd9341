"""Study "stops per cycle" (notebook 12, ``results/studies/stops.csv``): the steady number of stops per forcing period
of the harmonically forced Coulomb oscillator over the plane of the friction ratio ``F/P`` and the frequency ratio
``r = omega/omega_n``, the quantity Hong and Liu (2000) mapped from their exact solution.

Every row is one run of :func:`lumped.solvers.exact.solve_exact` from rest (``x0 = v0 = 0``) under ``P sin(omega t)``
with the committed mass and stiffness (``omega_n = sqrt(k/m)``), a Coulomb dashpot (``gamma = inf``) of the committed
threshold ``tau = F`` and ``P = F / (F/P)``: for Coulomb friction the motion scaled by ``P/k`` depends only on
``F/P`` and ``r`` (divide ``m x'' + k x + F sgn(x') = P sin(omega t)`` by ``P``), so fixing ``F`` loses nothing.

The run lasts :data:`TRANSIENT` + 2 :data:`PERIODS` forcing periods ``T = 2 pi/omega``.  The stops are counted from
the solution's events, not from samples: a *stop* is an event where ``v`` reaches zero with the net force
``P sin(omega t) - k x`` inside the static band ``[-F, F]``, so that the mass sticks (for a time that may be zero, or
shorter than any sampling step); a zero of ``v`` outside the band is a reversal, not a stop.  Counting events
rather than sampling the solution as :func:`lumped.drivers.sweep.sweep` does (``method="exact"``, about 1 us per sample) is
both cheaper and exact: no stop is missed for being shorter than the step, and where stops are long the two
definitions agree (``tests/test_stops_study.py``).  The file's columns
(:data:`COLUMNS`):

* ``frequency_ratio``: ``r = omega/omega_n``; ``friction_ratio``: ``F/P``;
* ``window_stops``: stops in the last window of :data:`PERIODS` periods, ``t > t_end - K T``;
* ``previous_stops``: stops in the window before it, ``t_end - 2 K T < t <= t_end - K T``;
* ``stops_per_period``: ``window_stops / K``;
* ``settled``: 1 when the two windows hold the same number of stops (the count has reached its periodic value),
  else 0;
* ``stuck_fraction``: the fraction of the last window the mass spends sticking (0 for nonstop motion);
* ``orbit_stops``: stops per period of the periodic motion of the forcing's period found by shooting
  (:func:`lumped.drivers.response.shooting.find_orbit`, Newton on the exact period map) from the run's last state,
  an independent check of ``stops_per_period``: where the run has not converged to a motion of period ``T``,
  the two differ (:func:`orbit_count`; ``-1`` where Newton finds no such motion, ``-2`` where the motion it finds
  steps over a stop, :func:`steps_over_a_stop`);
* ``orbit_multiplier``: the largest modulus of that motion's Floquet multipliers (below 1: stable; close to 1:
  a run from rest approaches it slowly, by a factor of about this value per period);
* ``stepped_over``: 1 when the run itself steps over a stop (:func:`steps_over_a_stop`; its counts may then miss
  that stop), else 0.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import NamedTuple

import numpy as np

from lumped.drivers.response.shooting import find_orbit
from lumped.drivers.sweep import chunk_slice
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.numerics import validate
from lumped.numerics.roots import brentq
from lumped.solvers.closed_form import SlipMotion
from lumped.solvers.exact import ExactSolution, solve_exact

__all__ = [
    "CHUNKS",
    "COLUMNS",
    "GRID",
    "PERIODS",
    "TRANSIENT",
    "Count",
    "OrbitCount",
    "count_stops",
    "grid",
    "last_state",
    "orbit_count",
    "rows",
    "run",
    "steps_over_a_stop",
]

#: ``studies`` (the configuration key) -> (values of r, values of F/P, chunks).  An exact run costs about 10 to
#: 80 ms (more at low r, where there are more events per period), and its shooting and check (orbit_count,
#: steps_over_a_stop) about as much again: default, about 3 CPU-s in all; full, about half an hour of CPU.
GRID = {"default": (12, 8, 2), "full": (160, 120, 16)}
CHUNKS = {resolution: chunks for resolution, (_, _, chunks) in GRID.items()}
#: The range of ``r = omega/omega_n``, log-spaced (stop counts grow as ``r`` falls).
R_RANGE = (0.1, 3.0)
#: ``K``: forcing periods per counting window (4 also sees motions that repeat every 2 or 4 periods).
PERIODS = 4
#: Forcing periods run before the two windows (the transient from rest).  On the default grid, 24 (with K = 4)
#: leaves 2 rows of 96 unsettled; runs of 10 to 16 periods (K = 2 or 3) called those two rows settled, with another
#: count: a short run can mistake a slow transient for a steady state.
TRANSIENT = 24
COLUMNS = (
    "frequency_ratio",
    "friction_ratio",
    "window_stops",
    "previous_stops",
    "stops_per_period",
    "settled",
    "stuck_fraction",
    "orbit_stops",
    "orbit_multiplier",
    "stepped_over",
)


class Count(NamedTuple):
    """Stops of one run in its two counting windows, and the fraction of the last one spent sticking."""

    window_stops: int
    previous_stops: int
    stuck_fraction: float

    @property
    def settled(self) -> bool:
        """Whether the two windows hold the same number of stops."""
        return self.window_stops == self.previous_stops


class OrbitCount(NamedTuple):
    """The periodic motion of the forcing's period at one point of the map: its stops per period, the largest
    modulus of its Floquet multipliers and the fraction of the period it spends sticking; ``stops == -1`` (and the
    other two 0) where Newton found no such motion, ``-2`` where the motion found steps over a stop."""

    stops: int
    multiplier: float
    stuck_fraction: float


def grid(r_points: int, ratio_points: int) -> tuple[np.ndarray, np.ndarray]:
    """The axes: ``r`` log-spaced over :data:`R_RANGE`, ``F/P`` at the midpoints of ``ratio_points`` cells of (0, 1)."""
    r_points = validate.positive_int("r_points", r_points)
    ratio_points = validate.positive_int("ratio_points", ratio_points)
    r = np.geomspace(*R_RANGE, r_points)
    return r, (np.arange(ratio_points) + 0.5) / ratio_points


def count_stops(solution: ExactSolution, period: float, periods: int) -> Count:
    """Stop events of ``solution`` in its last two windows of ``periods`` forcing periods (s).

    The last window is ``(t_end - K T, t_end]`` and the one before ``(t_end - 2 K T, t_end - K T]``; the stuck
    fraction is the length of the stick phases inside the last window over ``K T``.
    """
    width = periods * period
    edge, start = solution.t_end - width, solution.t_end - 2 * width
    stops = solution.event_times("stop")
    stuck = sum(max(0.0, min(b, solution.t_end) - max(a, edge)) for a, b in solution.stick_intervals())
    return Count(
        int(np.count_nonzero(stops > edge)),
        int(np.count_nonzero((stops > start) & (stops <= edge))),
        min(stuck / width, 1.0),
    )


def run(cfg: Mapping[str, float], frequency_ratio: float, friction_ratio: float) -> ExactSolution:
    """The exact Coulomb run from rest of one point of the map, over ``TRANSIENT + 2 PERIODS`` forcing periods.

    Parameters
    ----------
    cfg : mapping
        ``mass`` (kg), ``stiffness`` (N/m) and ``threshold`` (``F``, N).
    frequency_ratio : float
        ``r = omega/omega_n > 0``.
    friction_ratio : float
        ``F/P > 0``; the force amplitude is ``P = F / (F/P)`` (N).
    """
    r = validate.positive("frequency_ratio", frequency_ratio)
    ratio = validate.positive("friction_ratio", friction_ratio)
    osc = Oscillator.bingham(cfg["mass"], cfg["stiffness"], cfg["threshold"], math.inf)
    omega = r * math.sqrt(cfg["stiffness"] / cfg["mass"])
    t_end = (TRANSIENT + 2 * PERIODS) * 2 * math.pi / omega
    force = SwitchedSine(cfg["threshold"] / ratio, omega)
    return solve_exact(osc, t_end, force=force)


def orbit_count(
    cfg: Mapping[str, float], frequency_ratio: float, friction_ratio: float, guess: np.ndarray | None = None
) -> OrbitCount:
    """The periodic motion of period ``T`` at one point of the map, by shooting on the exact period map.

    Newton (:func:`lumped.drivers.response.shooting.find_orbit`) starts from ``guess``, the state ``(x, v)`` (m,
    m/s) at a time ``t = n T``, or without it from the state a run from rest reaches (``find_orbit``'s own
    settling).  Its stops are the stop events of one period ``(0, T]`` (the definition of :func:`count_stops`).
    A motion whose period :func:`steps_over_a_stop` is refused (``stops = -2``): its count would miss that stop.
    Parameters as :func:`run`.
    """
    r = validate.positive("frequency_ratio", frequency_ratio)
    ratio = validate.positive("friction_ratio", friction_ratio)
    osc = Oscillator.bingham(cfg["mass"], cfg["stiffness"], cfg["threshold"], math.inf)
    omega = r * math.sqrt(cfg["stiffness"] / cfg["mass"])
    try:
        orbit = find_orbit(osc, cfg["threshold"] / ratio, omega, guess)
    except ValueError:  # no motion of period T near the guess (Newton's message names omega)
        return OrbitCount(-1, 0.0, 0.0)
    period = orbit.period.solution
    if steps_over_a_stop(period):
        return OrbitCount(-2, 0.0, 0.0)
    stuck = sum(min(b, period.t_end) - a for a, b in period.stick_intervals())
    return OrbitCount(orbit.stops, orbit.max_multiplier, min(stuck / period.t_end, 1.0))


def steps_over_a_stop(solution: ExactSolution) -> bool:
    """Whether a slip phase of ``solution`` turns its velocity against its direction ``s``: a stop it stepped over.

    Within a slip phase ``s v > 0`` until the stop that ends it.  The exact solver brackets that stop on a grid
    (:mod:`lumped.solvers.closed_form`), and near a grazing, where ``s v`` dips below zero for less than the
    grid's spacing, it can miss it and slip on with ``s v < 0``.  The dips are the local minima of ``s v``, where
    ``s a`` turns from negative to positive (``a`` the phase's acceleration); they are bracketed here on a grid of
    spacing ``pi / (64 omega_n)`` (a 128th of the period of the free oscillation, the time between two of its
    velocity's minima) and refined by Brent's method.  Minima in the first interval of a phase (where a
    slip from a breakaway starts at ``v = 0``, its acceleration 0 up to round-off) and in the last (where a
    tangential stop ends it) are not judged.
    """
    for phase in solution.phases:
        m = phase.motion
        if m is None or not phase.end > phase.start:
            continue
        s = math.copysign(1.0, m.s_tau)
        n = 2 + math.ceil((phase.end - phase.start) * 64 * math.sqrt(m.k / m.m) / math.pi)
        t = np.linspace(phase.start, phase.end, n)
        x, v = m.state(t[1:-1])
        if np.any(s * v < 0):
            return True
        # s a on the grid: the equation of SlipMotion.acceleration, evaluated on arrays
        a = s * (m.P * np.sin(m.w * t[1:-1] + m.ph) - m.s_tau - m.c * v - m.k * x) / m.m
        for i in np.flatnonzero((a[:-1] < 0) & (a[1:] >= 0)) + 1:
            if s * m.velocity(brentq(lambda u, m=m, s=s: _along(m, s, u), t[i], t[i + 1])) < 0:
                return True
    return False


def _along(motion: SlipMotion, s: float, t: float) -> float:
    """``s a(t)``: the slip phase's acceleration along its direction ``s`` (m/s^2)."""
    return s * motion.acceleration(t, *(float(a) for a in motion.state(t)))


def last_state(solution: ExactSolution) -> np.ndarray:
    """``(x, v)`` at the end of ``solution`` (m, m/s)."""
    end = solution.evaluate(np.array([solution.t_end]))
    return np.array([end["x"][0], end["v"][0]])


def rows(
    cfg: Mapping[str, float], r_points: int, ratio_points: int, chunk: tuple[int, int] | None = None
) -> dict[str, np.ndarray]:
    """The study's columns (:data:`COLUMNS`) for the rows of ``chunk`` of the grid (all without it).

    Parameters
    ----------
    cfg : mapping
        ``mass`` (kg), ``stiffness`` (N/m) and ``threshold`` (N), as :func:`lumped.studies.config.load` gives them.
    r_points, ratio_points : int
        Sizes of the axes of :func:`grid`; ``r`` varies slowest.
    chunk : (int, int), optional
        ``(index, count)``: the ``index``-th of ``count`` near-equal contiguous slices of the rows
        (:func:`lumped.drivers.sweep.chunk_slice`); the chunks concatenate to the whole.
    """
    r, ratio = grid(r_points, ratio_points)
    rr, qq = (a.ravel() for a in np.meshgrid(r, ratio, indexing="ij"))
    part = _slice(rr.size, chunk)
    rr, qq = rr[part], qq[part]
    omega_n = math.sqrt(cfg["stiffness"] / cfg["mass"])
    runs = [run(cfg, a, b) for a, b in zip(rr, qq)]
    counts = [count_stops(s, 2 * math.pi / (a * omega_n), PERIODS) for s, a in zip(runs, rr)]
    orbits = [orbit_count(cfg, a, b, last_state(s)) for s, a, b in zip(runs, rr, qq)]
    window = np.array([c.window_stops for c in counts], dtype=np.int64)
    return {
        "frequency_ratio": rr,
        "friction_ratio": qq,
        "window_stops": window,
        "previous_stops": np.array([c.previous_stops for c in counts], dtype=np.int64),
        "stops_per_period": window / PERIODS,
        "settled": np.array([float(c.settled) for c in counts]),
        "stuck_fraction": np.array([c.stuck_fraction for c in counts]),
        "orbit_stops": np.array([o.stops for o in orbits], dtype=np.int64),
        "orbit_multiplier": np.array([o.multiplier for o in orbits]),
        "stepped_over": np.array([float(steps_over_a_stop(s)) for s in runs]),
    }


def _slice(n: int, chunk: tuple[int, int] | None) -> slice:
    """Rows of ``chunk = (index, count)`` of ``n`` rows (all for ``None``)."""
    return slice(0, n) if chunk is None else chunk_slice(n, *chunk)


def chunk_table(cfg: Mapping[str, float], resolution: str, chunk: tuple[int, int]) -> dict[str, np.ndarray]:
    """:func:`rows` of ``chunk`` on the grid of ``resolution`` (a key of :data:`GRID`)."""
    r_points, ratio_points, _ = GRID[resolution]
    return rows(cfg, r_points, ratio_points, chunk)
