"""Parameter sweeps: one row of summaries per parameter set of a grid.

A grid is the Cartesian product of axes (:class:`Axis`, one per varied
parameter; the first axis varies slowest).  Every row is one run of the
single-mass system on the shared time grid ``t_n = n*dt``, ``n = 0..N``, and is
summarised by :func:`summarize` (the definitions, in one place):

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

``dt`` and ``t_end`` cannot vary (every row shares the grid, which is what
lets :mod:`lumped.kernels.batched` advance the rows together).

Limits, all checked before any work (:func:`check_size`, then
:meth:`SweepSpec.check`): at most :data:`MAX_ROWS` rows, counted from the
sizes of the axes before any value is built or checked; an estimated memory
of at most :data:`MAX_MEMORY_BYTES`; an output file of at most
``validate.MAX_OUTPUT_BYTES`` (:data:`FILE_BYTES_PER_VALUE`, a bound); an
estimated time of at most ``validate.MAX_SECONDS`` (:meth:`SweepSpec.seconds`).
"""

from __future__ import annotations

import math
import numbers
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from lumped.drivers import methods
from lumped.kernels.batched import BATCH_KERNEL, BatchParameters, batch_backward_euler
from lumped.model import parameters
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate

__all__ = [
    "Axis",
    "SweepSpec",
    "parse_vary",
    "summarize",
    "sweep",
    "run_sweep",
    "chunk_slice",
    "check_size",
    "SUMMARY_COLUMNS",
    "FORCED_COLUMNS",
]

SUMMARY_COLUMNS = ("rest_time", "rest_position", "max_abs_x", "stops")
FORCED_COLUMNS = ("steady_amplitude", "stops_per_period")
#: The per-row parameters and their defaults (those of ``python -m lumped simulate``),
#: from :data:`lumped.model.parameters.PARAMETERS`.
PARAMETERS = {name: parameters.PARAMETERS[name].default for name in parameters.PER_ROW}
#: Methods a sweep runs, those of the registry that run a batch (:data:`lumped.drivers.methods.SWEEP_METHODS`);
#: backward Euler goes through the batched kernel.
SWEEP_METHODS = methods.SWEEP_METHODS
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
#: parameters, the checks of :meth:`SweepSpec.check` and the summaries, some
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
#: Rows whose events :meth:`SweepSpec.seconds` estimates, evenly spread over the grid.
EVENT_SAMPLE = 64


def chunk_slice(rows: int, index: int, count: int) -> slice:
    """Rows of chunk ``index`` (0-based) of ``count`` near-equal contiguous chunks of ``rows`` rows."""
    count = validate.positive_int("count", count)
    if isinstance(index, bool) or not isinstance(index, numbers.Integral) or not 0 <= index < count:
        raise ValueError(f"index must be an integer in [0, {count - 1}], got {index!r}")
    index = int(index)
    bounds = np.linspace(0, rows, count + 1).round().astype(int)
    return slice(int(bounds[index]), int(bounds[index + 1]))


class Axis(NamedTuple):
    """One varied parameter: its name (a key of :data:`PARAMETERS`) and values."""

    name: str
    values: np.ndarray


def _check_value(name: str, value: float) -> float:
    """``value`` through the check of ``name`` in :data:`lumped.model.parameters.PARAMETERS`."""
    return parameters.PARAMETERS[name].check(name, value)  # type: ignore[return-value]


def _check_values(name: str, data: np.ndarray) -> None:
    """Every value of ``data`` through the validator of ``name``, in a few array passes.

    Each validator accepts an interval (``finite``, ``positive``, ...: see
    :mod:`lumped.numerics.validate`) and refuses NaN, so checking a NaN if there is
    one, then the smallest and the largest value, checks them all.
    """
    nan = np.isnan(data)
    if nan.any():
        _check_value(name, math.nan)
    for value in (data.min(), data.max()):
        _check_value(name, float(value))


def _key(name: object) -> str:
    """The parameter a ``--vary`` NAME or a ``vary`` key names (dashes or underscores)."""
    if not isinstance(name, str):
        raise ValueError(f"vary: a parameter name must be a string, got {name!r}")
    key = name.strip().lstrip("-").replace("-", "_")
    if key in ("t_end", "dt"):
        raise ValueError(f"vary: {key} cannot vary: every row of a sweep shares the time grid; run one sweep per {key}")
    if key not in PARAMETERS:
        raise ValueError(f"vary: unknown or non-numeric option {name!r}; one of {', '.join(PARAMETERS)}")
    return key


def _size(key: str, values: object) -> int:
    """The number of values of an axis, read without converting them (a 1-d sequence or array)."""
    shape = getattr(values, "shape", None)
    if shape is not None and len(shape) != 1:
        raise ValueError(f"vary: {key} must be a 1-d sequence of numbers, got an array of shape {tuple(shape)}")
    if shape is None and (isinstance(values, (str, bytes)) or not hasattr(values, "__len__")):
        raise ValueError(f"vary: {key} must be a 1-d sequence of numbers, got {type(values).__name__}")
    return int(shape[0]) if shape is not None else len(values)  # type: ignore[arg-type]


def _as_values(key: str, values: object) -> np.ndarray:
    """``values`` as a 1-d float array: real numbers only (no booleans, strings or complex numbers)."""
    _size(key, values)
    try:
        data = np.asarray(values)
    except (ValueError, TypeError):  # ragged nesting
        raise ValueError(f"vary: {key} must be a 1-d sequence of numbers") from None
    if data.ndim != 1:
        raise ValueError(f"vary: {key} must be a 1-d sequence of numbers, got an array of shape {data.shape}")
    if data.dtype.kind not in "iuf" or (
        not isinstance(values, np.ndarray) and any(isinstance(v, (bool, np.bool_)) for v in values)  # type: ignore[attr-defined]
    ):
        what = {"b": "booleans", "c": "complex numbers", "U": "strings", "S": "bytes"}.get(
            data.dtype.kind, "non-numbers"
        )
        what = "booleans" if data.dtype.kind in "iuf" else what
        raise ValueError(f"vary: {key} must hold real numbers (int or float), got {what}")
    return data.astype(float)


def axis(name: str, values: Sequence[float] | np.ndarray) -> Axis:
    """An :class:`Axis`, checked: a known, per-row parameter; valid values in a 1-d sequence.

    Raises
    ------
    ValueError
        Beginning with ``vary:``.
    """
    key = _key(name)
    data = _as_values(key, values)
    if data.size == 0:
        raise ValueError(f"vary: {key} has no values")
    try:
        _check_values(key, data)
    except ValueError as err:
        raise ValueError(f"vary: {err}") from None
    return Axis(key, data)


class VaryText(NamedTuple):
    """A parsed ``--vary`` text, its values not built yet (:meth:`axis` builds them)."""

    name: str
    start: float
    stop: float
    count: int
    log: bool

    def axis(self) -> Axis:
        """The :class:`Axis` of ``COUNT`` values, evenly or geometrically spaced, checked."""
        space = np.geomspace if self.log else np.linspace
        return axis(self.name, space(self.start, self.stop, self.count))

    @property
    def all_zero(self) -> bool:
        """Whether every value is zero (``START == STOP == 0``)."""
        return self.start == 0 and self.stop == 0


def vary_text(spec: str) -> VaryText:
    """Parse ``NAME=START:STOP:COUNT`` or ``NAME=log:START:STOP:COUNT`` without building the values.

    ``NAME`` is an option's name without the leading dashes, with dashes or
    underscores (``force-omega`` or ``force_omega``).  ``COUNT`` points from
    ``START`` to ``STOP`` inclusive, evenly spaced (``np.linspace``) or, with
    ``log:``, evenly spaced in the logarithm (``np.geomspace``; both bounds
    must be > 0).  ``COUNT = 1`` needs ``START == STOP``.
    """
    name, eq, rest = spec.partition("=")
    if not eq or not name.strip():
        raise ValueError(f"vary: expected NAME=START:STOP:COUNT, got {spec!r}")
    key = _key(name)
    parts = rest.split(":")
    log = parts[0].strip().lower() == "log"
    parts = parts[1:] if log else parts
    if len(parts) != 3:
        raise ValueError(f"vary: expected NAME=[log:]START:STOP:COUNT, got {spec!r}")
    start, stop = (_number(spec, p) for p in parts[:2])
    count = parts[2].strip()
    if not (count.isascii() and count.isdigit()) or int(count) < 1:  # "²".isdigit() is true
        raise ValueError(f"vary: COUNT must be an integer >= 1 (decimal digits), got {count!r} in {spec!r}")
    n = int(count)
    if n == 1 and start != stop:
        raise ValueError(f"vary: COUNT = 1 needs START == STOP in {spec!r}")
    if log and not (start > 0 and stop > 0):
        raise ValueError(f"vary: log spacing needs START > 0 and STOP > 0 in {spec!r}")
    if n > MAX_ROWS:
        raise ValueError(f"vary: COUNT {n} is above {MAX_ROWS:.0e}, the most rows a sweep may have, in {spec!r}")
    return VaryText(key, start, stop, n, log)


def parse_vary(spec: str) -> Axis:
    """The :class:`Axis` of a ``--vary`` text (:func:`vary_text`), its values checked."""
    return vary_text(spec).axis()


def _number(spec: str, text: str) -> float:
    try:
        value = validate.finite("START/STOP", validate.parse_float("START/STOP", text))
    except ValueError:
        raise ValueError(f"vary: START and STOP must be finite numbers, got {text.strip()!r} in {spec!r}") from None
    return value


def memory_estimate(rows: int, columns: int) -> int:
    """Estimated peak memory (bytes) of a sweep of ``rows`` rows writing ``columns`` columns."""
    per_row = len(PARAMETERS) * MEMORY_BYTES_PER_VALUE["parameter"] + columns * MEMORY_BYTES_PER_VALUE["column"]
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
        A key of :data:`SWEEP_METHODS`.
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
        estimate: the events are estimated on the values, :meth:`SweepSpec.check`).
    """
    total = math.prod(int(c) for c in counts)
    if total > MAX_ROWS:
        shape = " x ".join(str(int(c)) for c in counts)
        raise ValueError(
            f"vary: the grid has {total:.3g} rows ({shape}), more than {MAX_ROWS:.0e}; split it into several sweeps"
        )
    count = total if rows is None else len(range(total)[rows])
    columns = len(counts) + len(SUMMARY_COLUMNS) + (len(FORCED_COLUMNS) if forced else 0)
    need = memory_estimate(count, columns)
    if need > MAX_MEMORY_BYTES:
        raise ValueError(
            f"vary: {count} rows of {columns} columns would need about {need / 1024**3:.1f} GiB of memory, "
            f"more than the {MAX_MEMORY_BYTES / 1024**3:.0f} GiB allowed; split the grid into chunks"
        )
    if output is not None:
        size = count * columns * FILE_BYTES_PER_VALUE[output]
        if size > validate.MAX_OUTPUT_BYTES:
            raise ValueError(
                f"vary: the {output} file could reach {size / 1024**3:.1f} GiB ({count} rows of {columns} values, "
                f"up to {FILE_BYTES_PER_VALUE[output]} bytes each), more than the "
                f"{validate.MAX_OUTPUT_BYTES / 1024**3:.0f} GiB allowed; write .npz or split the grid"
            )
    events = None if method == "backward-euler" else np.full(1, 2.0)  # every run has an event or two
    _check_seconds(count, _row_seconds(method, forced, n_steps, events), method, n_steps, output, columns)
    return count


def _row_seconds(method: str, forced: bool, n_steps: int, events: np.ndarray | None) -> float:
    """Estimated cost (s) of one row: its steps (batched) or its run (mean over ``events`` per run)."""
    if method == "backward-euler":
        kind = "forced" if forced else "free"
        return n_steps * SECONDS_PER_TRAJECTORY_STEP[BATCH_KERNEL][kind] + SECONDS_PER_BATCHED_ROW
    cost = SECONDS_PER_RUN[method]
    per_event = cost["forced event" if forced else "free event"]
    return cost["row"] + (n_steps + 1) * cost["sample"] + per_event * float(np.mean(events))


def _check_seconds(count: int, row: float, method: str, n_steps: int, output: str | None, columns: int) -> float:
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


@dataclass(frozen=True)
class SweepSpec:
    """A sweep: fixed parameters, axes, the time grid, the method and ``K``.

    Use :meth:`build` (it validates); :meth:`chunk` gives the rows of one of
    ``n`` contiguous chunks, for splitting a sweep into jobs.  ``output`` is
    the kind of file the rows go to (``".csv"``, ``".npz"``, or ``None`` for
    the API), for the estimates of its size and writing time.
    """

    axes: tuple[Axis, ...]
    fixed: Mapping[str, float]
    t_end: float
    dt: float
    method: str = "backward-euler"
    periods: int = 10
    options: Mapping[str, object] = field(default_factory=dict)
    output: str | None = None

    @classmethod
    def build(
        cls,
        axes: Sequence[Axis],
        *,
        t_end: float = 2.0,
        dt: float = 1e-4,
        method: str = "backward-euler",
        periods: int = 10,
        options: Mapping[str, object] | None = None,
        chunk: tuple[int, int] | None = None,
        output: str | None = None,
        **fixed: float,
    ) -> SweepSpec:
        """Validate and build (``fixed`` parameters default to :data:`PARAMETERS`).

        With ``chunk = (index, count)`` only that chunk's rows will run, and the
        up-front estimates of memory and time (:meth:`check`) are for them.
        """
        chunk = _chunk(chunk)
        names = [a.name for a in axes]
        for name in names:
            if names.count(name) > 1:
                raise ValueError(f"vary: {name} is varied more than once")
        for name in fixed:
            if name not in PARAMETERS:
                raise ValueError(f"{name}: not a parameter of a sweep; one of {', '.join(PARAMETERS)}")
        values = {n: _check_value(n, v) for n, v in (PARAMETERS | dict(fixed)).items()}
        methods.refuse_sweep(method)
        spec = cls(
            tuple(axes),
            values,
            validate.positive("t_end", t_end),
            validate.positive("dt", dt),
            method,
            validate.positive_int("periods", periods),
            dict(options or {}),
            output,
        )
        spec.check(None if chunk is None else spec.chunk(*chunk))
        return spec

    @property
    def rows(self) -> int:
        """Number of parameter sets."""
        return math.prod(a.values.size for a in self.axes)

    @property
    def n_steps(self) -> int:
        """Steps of the shared grid."""
        return validate.step_count(self.t_end, self.dt)

    @property
    def forced(self) -> bool:
        """True when some row has a nonzero forcing amplitude (the forced columns are written)."""
        amp = next((a.values for a in self.axes if a.name == "force_amplitude"), None)
        return bool(np.any(amp != 0)) if amp is not None else self.fixed["force_amplitude"] != 0

    def columns(self) -> tuple[str, ...]:
        """The output columns, in order."""
        return tuple(a.name for a in self.axes) + SUMMARY_COLUMNS + (FORCED_COLUMNS if self.forced else ())

    def parameters(self, rows: slice | None = None) -> dict[str, np.ndarray]:
        """Every parameter per row (grid order: the first axis slowest)."""
        rows = slice(None) if rows is None else rows
        index = np.arange(self.rows)[rows]
        shape = tuple(a.values.size for a in self.axes)
        out = {n: np.full(index.size, v) for n, v in self.fixed.items()}
        for a, i in zip(self.axes, np.unravel_index(index, shape) if shape else ()):
            out[a.name] = a.values[i]
        return out

    def chunk(self, index: int, count: int) -> slice:
        """Rows of chunk ``index`` (0-based) of ``count`` near-equal contiguous chunks (:func:`chunk_slice`)."""
        return chunk_slice(self.rows, index, count)

    def check(self, rows: slice | None = None) -> None:
        """Refuse up front a sweep too large, too slow, out of range or with too few steps for ``periods``.

        First :func:`check_size` (rows, memory, file, time from the sizes
        alone), then every row's magnitudes and forcing window, then, for
        ``exact`` and ``event-driven``, the time with the events estimated
        (:meth:`seconds`).  The estimates are for the rows that will run: all,
        or the slice ``rows`` (a chunk, :meth:`chunk`).
        """
        counts = [a.values.size for a in self.axes]
        check_size(counts, n_steps=self.n_steps, method=self.method, forced=self.forced, output=self.output, rows=rows)
        self._check_rows()
        if self.method != "backward-euler":
            self.seconds(rows)

    def seconds(self, rows: slice | None = None) -> float:
        """Estimated time (s) of the rows (all, or the slice ``rows``) and of writing them; refused above the limit.

        Backward Euler: steps times :data:`SECONDS_PER_TRAJECTORY_STEP` plus
        :data:`SECONDS_PER_BATCHED_ROW`.  ``exact`` and ``event-driven``:
        :data:`SECONDS_PER_RUN` with the events of :data:`EVENT_SAMPLE` rows
        spread evenly over those that run, each estimated by the exact
        solver's upper estimate; within a factor 4 of the measured time
        (tests/test_sweep_limits.py).
        """
        index = np.arange(self.rows)[slice(None) if rows is None else rows]
        events = None
        if self.method != "backward-euler" and index.size:
            sample = index[np.unique(np.linspace(0, index.size - 1, min(index.size, EVENT_SAMPLE)).round().astype(int))]
            events = self._events(sample)
        row = _row_seconds(self.method, self.forced, self.n_steps, events)
        return _check_seconds(index.size, row, self.method, self.n_steps, self.output, len(self.columns()))

    def _events(self, sample: np.ndarray) -> np.ndarray:
        """The exact solver's upper estimate of the events of the rows ``sample``."""
        from lumped.model.forcing import SwitchedSine
        from lumped.solvers.exact import _event_estimate

        p = self.parameters()
        out = np.empty(sample.size)
        for i, j in enumerate(sample):
            row = {n: float(v[j]) for n, v in p.items()}
            force = SwitchedSine(row["force_amplitude"], row["force_omega"], row["force_phase"], row["force_until"])
            out[i] = _event_estimate(_oscillator(row), force, self.n_steps * self.dt, row["x0"], row["v0"])
        return out

    def seconds_per_step(self) -> float:
        """Estimated cost of one trajectory-step (s) of backward Euler, of one grid point sampled otherwise."""
        if self.method == "backward-euler":
            kind = "forced" if self.forced else "free"
            return SECONDS_PER_TRAJECTORY_STEP[BATCH_KERNEL][kind]
        return SECONDS_PER_RUN[self.method]["sample"]

    def _check_rows(self) -> None:
        """Every row's forcing argument (the sine's range), magnitudes (at once) and forcing window."""
        from lumped.model.oscillator import check_magnitudes, magnitude_failures

        p = self.parameters()
        t_last = self.n_steps * self.dt
        validate.sine_argument(p["force_omega"], p["force_phase"], np.minimum(t_last, p["force_until"]))
        args = (p["mass"], p["stiffness"], p["gamma"], t_last, self.dt, p["x0"], p["v0"], p["force_amplitude"])
        carries = self.method == "backward-euler"  # the exact solver carries x, not F_s = k x
        for j in np.flatnonzero(magnitude_failures(*args, carries_force=carries))[:1]:
            row = {n: float(v[j]) for n, v in p.items()}
            try:
                check_magnitudes(
                    _oscillator(row),
                    t_last,
                    self.dt,
                    row["x0"],
                    row["v0"],
                    row["force_amplitude"],
                    carries_force=carries,
                )
            except ValueError as err:
                raise ValueError(self._row_error(str(err), row, int(j))) from None
        start = window_start(p, t_last, self.periods)
        if np.any(start < 0):
            j = int(np.argmax(start < 0))
            raise ValueError(
                f"periods: {self.periods} forcing periods at force_omega = {p['force_omega'][j]:.6g} rad/s "
                f"last {t_last - start[j]:.6g} s, longer than the run ({t_last:.6g} s); "
                "lower periods or raise t_end"
            )

    def _row_error(self, message: str, row: Mapping[str, float], j: int) -> str:
        """A row's error: ``vary:`` first when the parameter it names varies, and the row's varied values."""
        varied = [a.name for a in self.axes]
        where = ", ".join(f"{n} = {row[n]:.6g}" for n in varied)
        named = message.split(":", 1)[0]
        return f"{'vary: ' if named in varied else ''}{message} (row {j}: {where})"


def _chunk(chunk: object) -> tuple[int, int] | None:
    """``chunk`` as ``(index, count)``, integers (NumPy's too), or None; checked by :func:`chunk_slice`."""
    if chunk is None:
        return None
    if isinstance(chunk, (str, bytes)) or not isinstance(chunk, Sequence) or len(chunk) != 2:
        raise ValueError(f"chunk must be a pair (index, count), got {chunk!r}")
    return chunk[0], chunk[1]  # type: ignore[return-value]


def _oscillator(row: Mapping[str, float]):  # noqa: ANN202 (an Oscillator)
    from lumped.model.oscillator import Oscillator

    return Oscillator.bingham(row["mass"], row["stiffness"], row["threshold"], row["gamma"])


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
    stop = np.concatenate(([False], (traj.v[1:] == 0) & (traj.v[:-1] != 0)))
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


def _batched(spec: SweepSpec, p: Mapping[str, np.ndarray], progress: Callable[[int, int], None] | None) -> dict:
    """Backward-Euler rows through :func:`lumped.kernels.batched.batch_backward_euler`."""
    n_steps, dt = spec.n_steps, spec.dt
    start = window_start(p, n_steps * dt, spec.periods)
    grid_t = np.arange(n_steps + 1) * dt  # the grid's times, as the single run forms them
    first = np.where(np.isnan(start), n_steps + 1, np.searchsorted(grid_t, np.nan_to_num(start), side="left"))
    c = np.where(np.isinf(p["gamma"]), 0.0, 1.0 / p["gamma"])
    params = BatchParameters(
        p["mass"],
        p["stiffness"],
        p["threshold"],
        c,
        p["x0"],
        p["v0"],
        p["force_amplitude"],
        p["force_omega"],
        p["force_phase"],
        p["force_until"],
    )
    s = batch_backward_euler(params, spec.t_end, dt, window=first, progress=progress)
    at_rest = s.v_end == 0
    return {
        "rest_time": np.where(at_rest, s.rest_step * dt, np.nan),
        "rest_position": np.where(at_rest, s.x_end, np.nan),
        "max_abs_x": s.max_abs_x,
        "stops": s.stops,
        "steady_amplitude": s.window_max_abs_x,
        "stops_per_period": np.where(np.isnan(start), np.nan, s.window_stops / spec.periods),
    }


def _one_by_one(spec: SweepSpec, p: Mapping[str, np.ndarray], progress: Callable[[int, int], None] | None) -> dict:
    """Rows of ``exact`` or ``event-driven``: a single run each, through :func:`lumped.drivers.simulation.simulate`."""
    from lumped.drivers.simulation import simulate
    from lumped.model.forcing import SwitchedSine

    n = p["mass"].size
    start = window_start(p, spec.n_steps * spec.dt, spec.periods)
    out = np.empty((n, len(Summary._fields)))
    for j in range(n):
        row = {name: float(v[j]) for name, v in p.items()}
        force = SwitchedSine(row["force_amplitude"], row["force_omega"], row["force_phase"], row["force_until"])
        traj = simulate(
            _oscillator(row),
            spec.t_end,
            spec.dt,
            x0=row["x0"],
            v0=row["v0"],
            force=None if force.is_zero else force,
            method=spec.method,
            **spec.options,
        )
        out[j] = summarize(traj, float(start[j]), spec.periods)
        if progress is not None and (j % 64 == 63 or j == n - 1):
            progress(j + 1, n)
    return {name: out[:, i] for i, name in enumerate(Summary._fields)}


def run_sweep(
    spec: SweepSpec, rows: slice | None = None, progress: Callable[[int, int], None] | None = None
) -> dict[str, np.ndarray]:
    """The rows of ``spec`` (all, or the slice ``rows``, e.g. :meth:`SweepSpec.chunk`).

    Returns
    -------
    dict of str to ndarray
        :meth:`SweepSpec.columns`, in order: the varied parameters, then the
        summaries (``stops`` as integers).
    """
    p = spec.parameters(rows)
    run = _batched if spec.method == "backward-euler" else _one_by_one
    sums = run(spec, p, progress)
    out = {a.name: p[a.name] for a in spec.axes}
    for name in spec.columns()[len(spec.axes) :]:
        out[name] = sums[name].astype(np.int64) if name == "stops" else np.asarray(sums[name], dtype=float)
    return out


def sweep(
    vary: Mapping[str, Sequence[float] | np.ndarray],
    *,
    t_end: float = 2.0,
    dt: float = 1e-4,
    method: str = "backward-euler",
    periods: int = 10,
    chunk: tuple[int, int] | None = None,
    **fixed: float,
) -> dict[str, np.ndarray]:
    """Summaries of the single-mass system over the grid ``vary`` (the Python API of the sweep command).

    Parameters
    ----------
    vary : mapping of str to 1-d array
        Parameter name (:data:`PARAMETERS`) to its values, real numbers
        (booleans, strings, complex numbers and arrays of more than one
        dimension are refused); the grid is their Cartesian product, the first
        name varying slowest.  Its size is checked (:func:`check_size`) before
        any value is.
    t_end, dt : float, s
        The shared time grid, as for :func:`~lumped.solvers.backward_euler.backward_euler`.
    method : {"backward-euler", "exact", "event-driven"}
    periods : int
        ``K``, the number of final forcing periods of the forced summaries.
    chunk : (int, int), optional
        ``(index, count)``, Python or NumPy integers: only the rows of chunk
        ``index`` of ``count`` (:meth:`SweepSpec.chunk`); the chunks of a grid
        concatenate to the whole.
    **fixed : float
        The parameters that do not vary (defaults :data:`PARAMETERS`).

    Returns
    -------
    dict of str to ndarray
        One entry per column (:meth:`SweepSpec.columns`), one value per row.
    """
    if not isinstance(vary, Mapping):
        raise ValueError(f"vary must be a mapping of parameter names to 1-d sequences of values, got {_kind(vary)}")
    keys = [_key(name) for name in vary]
    counts = [_size(key, values) for key, values in zip(keys, vary.values())]
    if method in SWEEP_METHODS:  # an unknown method is refused by SweepSpec.build
        amplitude = fixed.get("force_amplitude", 0.0)  # a varied amplitude counts as forced: an upper estimate
        forced = "force_amplitude" in keys or not (isinstance(amplitude, numbers.Real) and amplitude == 0)
        n_steps = validate.step_count(validate.positive("t_end", t_end), validate.positive("dt", dt))
        rows = None if chunk is None else chunk_slice(math.prod(counts), *_chunk(chunk))  # type: ignore[misc]
        check_size(counts, n_steps=n_steps, method=method, forced=forced, rows=rows)
    axes = [axis(name, values) for name, values in vary.items()]
    spec = SweepSpec.build(axes, t_end=t_end, dt=dt, method=method, periods=periods, chunk=chunk, **fixed)
    return run_sweep(spec, None if chunk is None else spec.chunk(*_chunk(chunk)))  # type: ignore[misc]


def _kind(value: object) -> str:
    """A value's type, shortened, for an error message."""
    return f"a {type(value).__name__}"


class Progress:
    """Progress of a sweep on a text stream (stderr), called as ``progress(done, total)``.

    On a terminal one line is rewritten in place (``\\r``) and ended at the
    last row; elsewhere (a log file) a line is written at most every
    ``every`` seconds, and none at all when ``enabled`` is false.  It writes
    to the stream only, never to the output file.
    """

    def __init__(self, stream, enabled: bool, every: float = 10.0) -> None:  # noqa: ANN001 (a text stream)
        self.stream, self.enabled, self.every = stream, enabled, every
        self.tty = bool(getattr(stream, "isatty", lambda: False)())
        self.start = self.last = time.monotonic()

    def __call__(self, done: int, total: int) -> None:
        now = time.monotonic()
        if not self.enabled or (not self.tty and now - self.last < self.every and done < total):
            return
        self.last = now
        line = f"sweep: {done}/{total} rows ({100 * done / total:.0f}%, {now - self.start:.1f} s)"
        end = "\n" if done == total or not self.tty else ""
        self.stream.write(("\r" if self.tty else "") + line + end)
        self.stream.flush()
