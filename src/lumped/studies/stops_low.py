"""Study "stops per cycle at low frequency" (notebook 12, ``results/studies/stops_low.csv``): the map of
:mod:`lumped.studies.stops` continued below ``r = 0.1``, down to :data:`R_LOW`, by shooting.

At low ``r`` the slowly driven mass sticks and slips many times per forcing period, and a run from rest over
many periods costs many events (about 0.3 s per point at ``r = 0.02``, ten times the cost at ``r = 0.1``).  The
steady motion is instead found directly, as the fixed point of the exact period map
(:func:`lumped.studies.stops.orbit_count`: :func:`lumped.drivers.response.shooting.find_orbit` settles from rest
until two periods agree to 1e-3, then Newton), for about a tenth of that.  At these frequencies the stick
phases erase the memory of the initial state within a period or two (the Floquet multipliers are close to 0,
column ``orbit_multiplier``), so the motion reached from rest is the one found.

The grid continues the log spacing of :func:`lumped.studies.stops.grid` at the same resolution below its first
point ``r = 0.1`` (so that the two maps join cell to cell), with the same values of ``F/P``.  Columns
(:data:`COLUMNS`): ``frequency_ratio``, ``friction_ratio``, and those of
:class:`~lumped.studies.stops.OrbitCount`: ``orbit_stops`` (stops per period; ``-1`` where Newton found no
motion of period ``T``), ``orbit_multiplier`` (largest modulus of the Floquet multipliers) and
``orbit_stuck_fraction`` (the fraction of the period spent sticking).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from lumped.drivers.sweep import chunk_slice
from lumped.numerics import validate
from lumped.studies import stops

__all__ = ["CHUNKS", "COLUMNS", "GRID", "R_LOW", "chunk_table", "grid", "rows"]

#: ``studies`` -> (points of the grid of :mod:`~lumped.studies.stops` over its range, values of F/P, chunks): the
#: first two as in that study, so that the steps agree.  A point costs about 10 to 40 ms: default (5 x 8 points),
#: about 1 CPU-s; full (75 x 120), a few CPU-minutes.
GRID = {name: (*stops.GRID[name][:2], chunks) for name, chunks in (("default", 2), ("full", 16))}
CHUNKS = {resolution: chunks for resolution, (_, _, chunks) in GRID.items()}
#: The lowest frequency ratio of the grid (the counts 8 to 14 of Hong and Liu appear between it and 0.1).
R_LOW = 0.02
COLUMNS = ("frequency_ratio", "friction_ratio", "orbit_stops", "orbit_multiplier", "orbit_stuck_fraction")


def grid(r_points: int, ratio_points: int) -> tuple[np.ndarray, np.ndarray]:
    """The axes: ``r = r_0 q^-j`` for ``j = 1, 2, ...`` while ``r >= R_LOW``, in increasing order, with ``r_0``
    and the ratio ``q`` of :func:`lumped.studies.stops.grid` (``r_points >= 2``); ``F/P`` as there."""
    r_points = validate.positive_int("r_points", r_points)
    if r_points < 2:
        raise ValueError(f"r_points must be >= 2 (the step of the grid above), got {r_points}")
    above, ratio = stops.grid(r_points, ratio_points)
    step = math.log(above[1] / above[0])
    count = math.floor(math.log(above[0] / R_LOW) / step)
    return above[0] * np.exp(-step * np.arange(count, 0, -1)), ratio


def rows(
    cfg: Mapping[str, float], r_points: int, ratio_points: int, chunk: tuple[int, int] | None = None
) -> dict[str, np.ndarray]:
    """The study's columns (:data:`COLUMNS`) for the rows of ``chunk`` of the grid (all without it); parameters
    as :func:`lumped.studies.stops.rows`, ``r`` varying slowest."""
    r, ratio = grid(r_points, ratio_points)
    rr, qq = (a.ravel() for a in np.meshgrid(r, ratio, indexing="ij"))
    part = slice(0, rr.size) if chunk is None else chunk_slice(rr.size, *chunk)
    rr, qq = rr[part], qq[part]
    orbits = [stops.orbit_count(cfg, a, b) for a, b in zip(rr, qq)]
    return {
        "frequency_ratio": rr,
        "friction_ratio": qq,
        "orbit_stops": np.array([o.stops for o in orbits], dtype=np.int64),
        "orbit_multiplier": np.array([o.multiplier for o in orbits]),
        "orbit_stuck_fraction": np.array([o.stuck_fraction for o in orbits]),
    }


def chunk_table(cfg: Mapping[str, float], resolution: str, chunk: tuple[int, int]) -> dict[str, np.ndarray]:
    """:func:`rows` of ``chunk`` on the grid of ``resolution`` (a key of :data:`GRID`)."""
    r_points, ratio_points, _ = GRID[resolution]
    return rows(cfg, r_points, ratio_points, chunk)
