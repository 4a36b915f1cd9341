"""Parameter sweeps: one row of summaries per parameter set of a grid.

A grid is the Cartesian product of axes (one per varied parameter; the first
axis varies slowest).  Every row is one run of the single-mass system on the
shared time grid ``t_n = n*dt``, ``n = 0..N``; ``dt`` and ``t_end`` cannot vary
(every row shares the grid, which is what lets :mod:`lumped.kernels.batched`
advance the rows together).  The modules, in the order a sweep uses them:

* :mod:`~lumped.drivers.sweep.grid`: the per-row parameters, the axes
  (:func:`axis`, :func:`parse_vary` of a ``--vary`` text) and the chunks of
  the rows (:func:`chunk_slice`);
* :mod:`~lumped.drivers.sweep.limits`: the limits (:data:`MAX_ROWS`, memory,
  file, time) and the estimates checked against them before any work
  (:func:`check_size`);
* :mod:`~lumped.drivers.sweep.spec`: :class:`SweepSpec`, a sweep validated;
* :mod:`~lumped.drivers.sweep.summaries`: the columns of a row and their
  definitions (:func:`summarize`);
* :mod:`~lumped.drivers.sweep.run`: the driver, :func:`sweep` (the Python
  API) and :func:`run_sweep` (the rows of a :class:`SweepSpec`);
* :mod:`~lumped.drivers.sweep.progress`: :class:`Progress`, on stderr;
* :mod:`~lumped.drivers.sweep.system`: :func:`sweep_system`, the sweep of a
  system file's parameters (``entry.key``), one row per set, the summaries for
  each mass (``sweep --system``).

The names below are the public API.  Each lives in one of those modules, which
is the one to patch in a test: the limits are read from
:mod:`~lumped.drivers.sweep.limits`, not from this package.
"""

from lumped.drivers.sweep.grid import PARAMETERS, Axis, VaryText, axis, chunk_slice, parse_vary, vary_text
from lumped.drivers.sweep.limits import (
    EVENT_SAMPLE,
    FILE_BYTES_PER_VALUE,
    MAX_MEMORY_BYTES,
    MAX_ROWS,
    SECONDS_PER_BATCHED_ROW,
    SECONDS_PER_RUN,
    SECONDS_PER_TRAJECTORY_STEP,
    check_size,
    memory_estimate,
)
from lumped.drivers.sweep.progress import Progress
from lumped.drivers.sweep.run import SWEEP_METHODS, run_sweep, sweep
from lumped.drivers.sweep.spec import SweepSpec
from lumped.drivers.sweep.summaries import FORCED_COLUMNS, SUMMARY_COLUMNS, Summary, summarize, window_start
from lumped.drivers.sweep.system import sweep_system

__all__ = [
    "Axis",
    "VaryText",
    "axis",
    "parse_vary",
    "vary_text",
    "chunk_slice",
    "PARAMETERS",
    "MAX_ROWS",
    "MAX_MEMORY_BYTES",
    "FILE_BYTES_PER_VALUE",
    "SECONDS_PER_TRAJECTORY_STEP",
    "SECONDS_PER_BATCHED_ROW",
    "SECONDS_PER_RUN",
    "EVENT_SAMPLE",
    "check_size",
    "memory_estimate",
    "SweepSpec",
    "SUMMARY_COLUMNS",
    "FORCED_COLUMNS",
    "Summary",
    "summarize",
    "window_start",
    "SWEEP_METHODS",
    "sweep",
    "run_sweep",
    "Progress",
    "sweep_system",
]
