"""A sweep's limits and its estimates of memory, file size and time, all checked before any work.

First :func:`check_size`, from the sizes of the axes alone: at most
:data:`MAX_ROWS` rows, counted before any value is built or checked; an
estimated memory of at most :data:`MAX_MEMORY_BYTES`; an output file of at
most ``validate.MAX_OUTPUT_BYTES`` (:data:`FILE_BYTES_PER_VALUE`, a bound);
an estimated time of at most ``validate.MAX_SECONDS``.  Then
:meth:`lumped.drivers.sweep.spec.SweepSpec.check` checks the values and, for
the single-run methods, the time with the events estimated
(:meth:`~lumped.drivers.sweep.spec.SweepSpec.seconds`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from lumped.drivers.sweep.summaries import FORCED_COLUMNS, SUMMARY_COLUMNS
from lumped.kernels.batched import BATCH_KERNEL
from lumped.model import parameters
from lumped.numerics import validate

#: Largest number of rows of a grid: the product of the sizes of the axes,
#: checked before any value is built.  At about 330 bytes a row
#: (:data:`MEMORY_BYTES_PER_VALUE`) it is some 3.3 GB of memory.
MAX_ROWS = 10_000_000
#: Largest memory (bytes) a sweep may take by :func:`memory_estimate`.
MAX_MEMORY_BYTES = 4 * 1024**3
#: Memory (bytes) per row and per parameter or output column: the parameters
#: are held once per row, in the kernel's copy and in its temporaries, the
#: columns in the kernel's sums, the output and the file's buffer; measured
#: (peak RSS less the interpreter's) at 320 bytes a row for the free decay
#: with one axis (10 parameters, 5 columns), about 300 with two axes and the
#: forced columns; the model gives 440 and 520 (8 bytes * (3*10 + 4*5) and
#: 8 * (30 + 4*8)).
MEMORY_BYTES_PER_VALUE = {"parameter": 8 * 3, "column": 8 * 4}
#: Bound on the bytes a value takes in the output file: ``%.17g`` writes at
#: most 24 characters (sign, 17 digits, point, ``e-308``) and a separator in
#: ``.csv``; ``.npz`` stores 8 bytes.
FILE_BYTES_PER_VALUE = {".csv": 25, ".npz": 8}
#: Cost (s) of writing one value: ``np.savetxt`` took 0.83 us a value on this
#: project's 2-core machine (random doubles); ``.npz`` writes the arrays whole.
WRITE_SECONDS_PER_VALUE = {".csv": 1.7e-6, ".npz": 2e-8}
#: Estimated cost (s) per trajectory-step of the batched kernels, unforced and forced grids: about twice
#: what benchmarks/bench_sweep.py measures on this project's 2-core machine under load (compiled: 0.5-1.1 ns
#: free; forced, the project's sine in the vector lanes, 1.2-1.5 ns when quiet and 2.5-4 ns loaded on the
#: AVX-512 loop, about twice that on AVX2; NumPy: 12 ns free, 130 ns forced), so a single-core, loaded or
#: AVX2-only machine stays within the estimate.
SECONDS_PER_TRAJECTORY_STEP = {
    "compiled": {"free": 2.5e-9, "forced": 8e-9},
    "python": {"free": 2.5e-8, "forced": 2.6e-7},
}
#: Estimated cost (s) per row of the batched sweep besides its steps: the
#: parameters, the checks of :meth:`~lumped.drivers.sweep.spec.SweepSpec.check` and the summaries, some
#: thirty passes over arrays of a row's values.
SECONDS_PER_BATCHED_ROW = 1e-6
#: Estimated cost (s) of a single-run row (exact, event-driven): per row, per
#: grid point sampled and per event, the latter from the solver's own upper
#: estimate of the number of events (``lumped.solvers.exact._event_estimate``).
#: Measured in sweeps on this project's 2-core machine: exact 0.3 to 0.76 ms a
#: row at 5 grid points (8.4 estimated events of the free Bingham decay), 1.8
#: ms at 20001 (52 ns a point), 31 us per estimated event
#: of a free Coulomb decay, 50 to 186 us of a forced run (eq. 17b, 10 to 25 s);
#: event-driven 3.2 ms a row of the free Bingham decay at 5 grid points (8.4
#: estimated events), 75 ns a point, 0.83 ms per estimated event of a 200 s
#: Coulomb decay and 0.28 ms of the forced run.  The constants are about twice
#: those, but where one cost must serve a range: a forced exact event (1.2e-4
#: s, the geometric middle) and an event-driven event of either law (0.6 ms
#: against 0.83 for the long Coulomb decay).  tests/test_sweep_limits.py holds
#: the estimate within a factor 4 of a measured run.
SECONDS_PER_RUN = {
    "exact": {"row": 5e-4, "sample": 1.1e-7, "free event": 6e-5, "forced event": 1.2e-4},
    "event-driven": {"row": 2e-3, "sample": 1.5e-7, "free event": 6e-4, "forced event": 6e-4},
}
#: Rows whose events :meth:`~lumped.drivers.sweep.spec.SweepSpec.seconds` estimates, evenly spread over the grid.
EVENT_SAMPLE = 64


def memory_estimate(rows: int, columns: int) -> int:
    """Estimated peak memory (bytes) of a sweep of ``rows`` rows writing ``columns`` columns."""
    per_row = len(parameters.PER_ROW) * MEMORY_BYTES_PER_VALUE["parameter"] + columns * MEMORY_BYTES_PER_VALUE["column"]
    return rows * per_row


def check_size(
    counts: Sequence[int],
    *,
    n_steps: int,
    method: str,
    forced: bool,
    output: str | None = None,
    rows: slice | None = None,
) -> int:
    """Refuse a grid too large from the sizes of its axes alone, before any value is built or checked.

    Parameters
    ----------
    counts : sequence of int
        The sizes of the axes; the grid has their product of rows.
    n_steps : int
        Steps of the shared grid.
    method : str
        A key of :data:`lumped.drivers.methods.SWEEP_METHODS`.
    forced : bool
        Whether some row may be forced (the forced columns are written).
    output : {".csv", ".npz"}, optional
        The output file's kind, for its size and its writing time.
    rows : slice, optional
        The rows that run (a chunk); all by default.

    Returns
    -------
    int
        The number of rows that run.

    Raises
    ------
    ValueError
        Beginning with ``vary:``: more than :data:`MAX_ROWS` rows, more than
        :data:`MAX_MEMORY_BYTES` of memory, a file that could exceed
        ``validate.MAX_OUTPUT_BYTES``, or a time estimated above
        ``validate.MAX_SECONDS`` (for ``exact`` and ``event-driven``, a lower
        estimate: the events are estimated on the values,
        :meth:`~lumped.drivers.sweep.spec.SweepSpec.check`).
    """
    total = _check_rows(counts)
    count = total if rows is None else len(range(total)[rows])
    columns = len(counts) + len(SUMMARY_COLUMNS) + (len(FORCED_COLUMNS) if forced else 0)
    _check_memory(count, columns)
    if output is not None:
        _check_file(count, columns, output)
    events = None if method == "backward-euler" else np.full(1, 2.0)  # every run has an event or two
    check_seconds(count, row_seconds(method, forced, n_steps, events), method, n_steps, output, columns)
    return count


def _check_rows(counts: Sequence[int]) -> int:
    """The number of rows of a grid of axes of sizes ``counts``; refused above :data:`MAX_ROWS`."""
    total = math.prod(int(c) for c in counts)
    if total > MAX_ROWS:
        shape = " x ".join(str(int(c)) for c in counts)
        raise ValueError(
            f"vary: the grid has {total:.3g} rows ({shape}), more than {MAX_ROWS:.0e}; split it into several sweeps"
        )
    return total


def _check_memory(count: int, columns: int) -> None:
    """Refuse ``count`` rows of ``columns`` columns above :data:`MAX_MEMORY_BYTES` by :func:`memory_estimate`."""
    need = memory_estimate(count, columns)
    if need > MAX_MEMORY_BYTES:
        raise ValueError(
            f"vary: {count} rows of {columns} columns would need about {need / 1024**3:.1f} GiB of memory, "
            f"more than the {MAX_MEMORY_BYTES / 1024**3:.0f} GiB allowed; split the grid into chunks"
        )


def _check_file(count: int, columns: int, output: str) -> None:
    """Refuse an ``output`` file (``".csv"``, ``".npz"``) that could exceed ``validate.MAX_OUTPUT_BYTES``."""
    size = count * columns * FILE_BYTES_PER_VALUE[output]
    if size > validate.MAX_OUTPUT_BYTES:
        raise ValueError(
            f"vary: the {output} file could reach {size / 1024**3:.1f} GiB ({count} rows of {columns} values, "
            f"up to {FILE_BYTES_PER_VALUE[output]} bytes each), more than the "
            f"{validate.MAX_OUTPUT_BYTES / 1024**3:.0f} GiB allowed; write .npz or split the grid"
        )


def row_seconds(method: str, forced: bool, n_steps: int, events: np.ndarray | None) -> float:
    """Estimated cost (s) of one row: its steps (batched) or its run (mean over ``events`` per run)."""
    if method == "backward-euler":
        kind = "forced" if forced else "free"
        return n_steps * SECONDS_PER_TRAJECTORY_STEP[BATCH_KERNEL][kind] + SECONDS_PER_BATCHED_ROW
    cost = SECONDS_PER_RUN[method]
    per_event = cost["forced event" if forced else "free event"]
    return cost["row"] + (n_steps + 1) * cost["sample"] + per_event * float(np.mean(events))


def check_seconds(count: int, row: float, method: str, n_steps: int, output: str | None, columns: int) -> float:
    """The estimate (s) of ``count`` rows at ``row`` seconds each and the writing; refused above MAX_SECONDS."""
    write = 0.0 if output is None else count * columns * WRITE_SECONDS_PER_VALUE[output]
    estimate = count * row + write
    if estimate > validate.MAX_SECONDS:
        raise ValueError(
            f"vary: {count} rows of {method} ({n_steps} steps each) would take about {estimate:.3g} s "
            f"({row:.2g} s a row{f', {write:.3g} s to write the file' if write else ''}), more than the "
            f"{validate.MAX_SECONDS:.0f} s allowed; fewer rows, a coarser dt, a shorter t_end, or chunks"
        )
    return estimate
