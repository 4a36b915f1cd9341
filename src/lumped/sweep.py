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
* ``stops``: steps ``n >= 1`` with ``v_n == 0`` and ``v_{n-1} != 0``, i.e.
  steps entering the stick branch of the corrector from motion.  Starting at
  rest (``v0 = 0``) is not a stop.
* for a *periodic* row (``force_amplitude != 0``, ``force_omega != 0`` and
  ``force_until >= t_N``): over the window ``t_n >= t_N - K T``,
  ``T = 2 pi/|omega|``, ``K`` = ``periods``: ``steady_amplitude`` (largest
  ``|x_n|``, m) and ``stops_per_period`` (stops in the window divided by
  ``K``).  The two columns are present when some row of the grid is forced
  (``force_amplitude != 0``); they are ``nan`` in the other rows.

``dt`` and ``t_end`` cannot vary (every row shares the grid, which is what
lets :mod:`lumped.batched` advance the rows together).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from lumped import _validate
from lumped.batched import BATCH_KERNEL, BatchParameters, batch_backward_euler
from lumped.results import Trajectory

__all__ = [
    "Axis",
    "SweepSpec",
    "parse_vary",
    "summarize",
    "sweep",
    "run_sweep",
    "chunk_slice",
    "SUMMARY_COLUMNS",
    "FORCED_COLUMNS",
]

SUMMARY_COLUMNS = ("rest_time", "rest_position", "max_abs_x", "stops")
FORCED_COLUMNS = ("steady_amplitude", "stops_per_period")
#: The per-row parameters and their defaults (those of ``python -m lumped simulate``).
PARAMETERS = {
    "mass": 1.0,
    "stiffness": 100.0,
    "gamma": 1.0,
    "threshold": 1.0,
    "x0": 0.0,
    "v0": 0.0,
    "force_amplitude": 0.0,
    "force_omega": 0.0,
    "force_phase": 0.0,
    "force_until": math.inf,
}
#: Methods a sweep runs; backward Euler goes through the batched kernel.
SWEEP_METHODS = ("backward-euler", "exact", "event-driven")
#: Largest number of rows of a grid.
MAX_ROWS = 100_000_000
#: Estimated cost (s) per trajectory-step of the batched kernels, unforced and forced grids: about twice
#: what benchmarks/bench_sweep.py measures on this project's 2-core machine under load (compiled: 0.5-1.1 ns
#: free; forced, the project's sine in the vector lanes, 1.2-1.5 ns when quiet and 2.5-4 ns loaded on the
#: AVX-512 loop, about twice that on AVX2; NumPy: 12 ns free, 130 ns forced), so a single-core, loaded or
#: AVX2-only machine stays within the estimate.
SECONDS_PER_TRAJECTORY_STEP = {
    "compiled": {"free": 2.5e-9, "forced": 8e-9},
    "python": {"free": 2.5e-8, "forced": 2.6e-7},
}
#: Estimated cost (s) per grid point of a sampled single run (exact, event-driven).
SECONDS_PER_SAMPLE = 1e-6


def chunk_slice(rows: int, index: int, count: int) -> slice:
    """Rows of chunk ``index`` (0-based) of ``count`` near-equal contiguous chunks of ``rows`` rows."""
    count = _validate.positive_int("count", count)
    if not isinstance(index, int) or not 0 <= index < count:
        raise ValueError(f"index must be an integer in [0, {count - 1}], got {index!r}")
    bounds = np.linspace(0, rows, count + 1).round().astype(int)
    return slice(int(bounds[index]), int(bounds[index + 1]))


class Axis(NamedTuple):
    """One varied parameter: its name (a key of :data:`PARAMETERS`) and values."""

    name: str
    values: np.ndarray


def _check_value(name: str, value: float) -> float:
    from lumped.cli import _CHECKS  # the command line's table: one home for the ranges

    return _CHECKS[name](name, value)  # type: ignore[return-value]


def axis(name: str, values: Sequence[float] | np.ndarray) -> Axis:
    """An :class:`Axis`, checked: a known, per-row parameter; valid, distinct-free values.

    Raises
    ------
    ValueError
        Beginning with ``vary:``.
    """
    key = name.strip().lstrip("-").replace("-", "_")
    if key in ("t_end", "dt"):
        raise ValueError(f"vary: {key} cannot vary: every row of a sweep shares the time grid; run one sweep per {key}")
    if key not in PARAMETERS:
        raise ValueError(f"vary: unknown or non-numeric option {name!r}; one of {', '.join(PARAMETERS)}")
    data = np.asarray(values, dtype=float).ravel()
    if data.size == 0:
        raise ValueError(f"vary: {key} has no values")
    try:
        for value in data:
            _check_value(key, float(value))
    except ValueError as err:
        raise ValueError(f"vary: {err}") from None
    return Axis(key, data)


def parse_vary(spec: str) -> Axis:
    """Parse ``NAME=START:STOP:COUNT`` or ``NAME=log:START:STOP:COUNT``.

    ``NAME`` is an option's name without the leading dashes, with dashes or
    underscores (``force-omega`` or ``force_omega``).  ``COUNT`` points from
    ``START`` to ``STOP`` inclusive, evenly spaced (``np.linspace``) or, with
    ``log:``, evenly spaced in the logarithm (``np.geomspace``; both bounds
    must be > 0).  ``COUNT = 1`` needs ``START == STOP``.
    """
    name, eq, rest = spec.partition("=")
    if not eq or not name.strip():
        raise ValueError(f"vary: expected NAME=START:STOP:COUNT, got {spec!r}")
    parts = rest.split(":")
    log = parts[0].strip().lower() == "log"
    parts = parts[1:] if log else parts
    if len(parts) != 3:
        raise ValueError(f"vary: expected NAME=[log:]START:STOP:COUNT, got {spec!r}")
    start, stop = (_number(spec, p) for p in parts[:2])
    count = parts[2].strip()
    if not count.isdigit() or int(count) < 1:
        raise ValueError(f"vary: COUNT must be an integer >= 1 in {spec!r}")
    n = int(count)
    if n == 1 and start != stop:
        raise ValueError(f"vary: COUNT = 1 needs START == STOP in {spec!r}")
    if log and not (start > 0 and stop > 0):
        raise ValueError(f"vary: log spacing needs START > 0 and STOP > 0 in {spec!r}")
    if n > MAX_ROWS:
        raise ValueError(f"vary: COUNT {n} is above {MAX_ROWS:.0e} in {spec!r}")
    values = np.geomspace(start, stop, n) if log else np.linspace(start, stop, n)
    return axis(name, values)


def _number(spec: str, text: str) -> float:
    try:
        value = _validate.finite("START/STOP", _validate.parse_float("START/STOP", text))
    except ValueError:
        raise ValueError(f"vary: START and STOP must be finite numbers, got {text.strip()!r} in {spec!r}") from None
    return value


@dataclass(frozen=True)
class SweepSpec:
    """A sweep: fixed parameters, axes, the time grid, the method and ``K``.

    Use :meth:`build` (it validates); :meth:`chunk` gives the rows of one of
    ``n`` contiguous chunks, for splitting a sweep into jobs.
    """

    axes: tuple[Axis, ...]
    fixed: Mapping[str, float]
    t_end: float
    dt: float
    method: str = "backward-euler"
    periods: int = 10
    options: Mapping[str, object] = field(default_factory=dict)

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
        **fixed: float,
    ) -> SweepSpec:
        """Validate and build (``fixed`` parameters default to :data:`PARAMETERS`).

        With ``chunk = (index, count)`` only that chunk's rows will run, and the
        up-front estimates of memory and time (:meth:`check`) are for them.
        """
        names = [a.name for a in axes]
        for name in names:
            if names.count(name) > 1:
                raise ValueError(f"vary: {name} is varied more than once")
        for name in fixed:
            if name not in PARAMETERS:
                raise ValueError(f"{name}: not a parameter of a sweep; one of {', '.join(PARAMETERS)}")
        values = {n: _check_value(n, v) for n, v in (PARAMETERS | dict(fixed)).items()}
        if method not in SWEEP_METHODS:
            raise ValueError(f"method: a sweep runs {', '.join(SWEEP_METHODS)}; got {method!r}")
        spec = cls(
            tuple(axes),
            values,
            _validate.positive("t_end", t_end),
            _validate.positive("dt", dt),
            method,
            _validate.positive_int("periods", periods),
            dict(options or {}),
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
        return _validate.step_count(self.t_end, self.dt)

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
        """Refuse up front a sweep too large, too slow or with too few steps for ``periods``.

        The memory and time estimates are for the rows that will run: all, or
        the slice ``rows`` (a chunk, :meth:`chunk`).
        """
        if self.rows > MAX_ROWS:
            raise ValueError(f"vary: the grid has {self.rows:.3g} rows, more than {MAX_ROWS:.0e}")
        count = self.rows if rows is None else len(range(self.rows)[rows])
        need = count * (len(self.columns()) + len(PARAMETERS)) * 8
        if need > _validate.MAX_OUTPUT_BYTES:
            raise ValueError(
                f"vary: the sweep would need about {need / 1024**3:.1f} GiB, "
                f"more than the {_validate.MAX_OUTPUT_BYTES / 1024**3:.0f} GiB allowed"
            )
        _validate.run_time(count * self.n_steps, self.seconds_per_step(), f"{self.method} rows", "vary")
        self._check_rows()

    def seconds_per_step(self) -> float:
        """Estimated cost of one trajectory-step (s); a grid with a forced row is costed as forced throughout."""
        if self.method == "backward-euler":
            kind = "forced" if self.forced else "free"
            return SECONDS_PER_TRAJECTORY_STEP[BATCH_KERNEL][kind]
        return SECONDS_PER_SAMPLE

    def _check_rows(self) -> None:
        """Per-row checks of the forcing's argument (the sine's range), the magnitudes and the window."""
        from lumped.system import check_magnitudes

        p = self.parameters()
        t_last = self.n_steps * self.dt
        _validate.sine_argument(p["force_omega"], p["force_phase"], np.minimum(t_last, p["force_until"]))
        for j in range(self.rows):
            row = {n: float(v[j]) for n, v in p.items()}
            check_magnitudes(_oscillator(row), t_last, self.dt, row["x0"], row["v0"], row["force_amplitude"])
        start = window_start(p, t_last, self.periods)
        if np.any(start < 0):
            j = int(np.argmax(start < 0))
            raise ValueError(
                f"periods: {self.periods} forcing periods at force_omega = {p['force_omega'][j]:.6g} rad/s "
                f"last {t_last - start[j]:.6g} s, longer than the run ({t_last:.6g} s); "
                "lower periods or raise t_end"
            )


def _oscillator(row: Mapping[str, float]):  # noqa: ANN202 (an Oscillator)
    from lumped.system import Oscillator

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
    """Backward-Euler rows through :func:`lumped.batched.batch_backward_euler`."""
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
    """Rows of ``exact`` or ``event-driven``: a single run each, through :func:`lumped.driver.simulate`."""
    from lumped.driver import simulate
    from lumped.forcing import SwitchedSine

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
        Parameter name (:data:`PARAMETERS`) to its values; the grid is their
        Cartesian product, the first name varying slowest.
    t_end, dt : float, s
        The shared time grid, as for :func:`~lumped.timestepping.backward_euler`.
    method : {"backward-euler", "exact", "event-driven"}
    periods : int
        ``K``, the number of final forcing periods of the forced summaries.
    chunk : (int, int), optional
        ``(index, count)``: only the rows of chunk ``index`` of ``count``
        (:meth:`SweepSpec.chunk`); the chunks of a grid concatenate to the whole.
    **fixed : float
        The parameters that do not vary (defaults :data:`PARAMETERS`).

    Returns
    -------
    dict of str to ndarray
        One entry per column (:meth:`SweepSpec.columns`), one value per row.
    """
    axes = [axis(name, values) for name, values in vary.items()]
    spec = SweepSpec.build(axes, t_end=t_end, dt=dt, method=method, periods=periods, chunk=chunk, **fixed)
    return run_sweep(spec, None if chunk is None else spec.chunk(*chunk))


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
