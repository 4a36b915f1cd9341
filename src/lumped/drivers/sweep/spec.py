"""A sweep's description, :class:`SweepSpec`: its axes, fixed parameters, time grid, method and ``K``.

:meth:`SweepSpec.build` validates it and refuses, before any work, a sweep
too large, too slow or out of range (:meth:`SweepSpec.check`, with the limits
of :mod:`lumped.drivers.sweep.limits`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from lumped.drivers import methods
from lumped.drivers.sweep import limits
from lumped.drivers.sweep.grid import PARAMETERS, Axis, check_value, chunk_pair, chunk_slice
from lumped.drivers.sweep.summaries import FORCED_COLUMNS, SUMMARY_COLUMNS, window_start
from lumped.kernels.batched import BATCH_KERNEL
from lumped.numerics import validate


@dataclass(frozen=True)
class SweepSpec:
    """A sweep: fixed parameters, axes, the time grid, the method and ``K``.

    Use :meth:`build` (it validates); :meth:`chunk` gives the rows of one of
    ``n`` contiguous chunks, for splitting a sweep into jobs.  ``output`` is
    the kind of file the rows go to (``".csv"``, ``".npz"``, or ``None`` for
    the API), for the estimates of its size and writing time.  ``periods``
    ``None`` writes no forced summaries (a system file's sweep,
    :mod:`lumped.drivers.sweep.system`).
    """

    axes: tuple[Axis, ...]
    fixed: Mapping[str, float]
    t_end: float
    dt: float
    method: str = "backward-euler"
    periods: int | None = 10
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
        periods: int | None = 10,
        options: Mapping[str, object] | None = None,
        chunk: tuple[int, int] | None = None,
        output: str | None = None,
        **fixed: float,
    ) -> SweepSpec:
        """Validate and build (``fixed`` parameters default to :data:`~.grid.PARAMETERS`).

        With ``chunk = (index, count)`` only that chunk's rows will run, and the
        up-front estimates of memory and time (:meth:`check`) are for them.
        """
        chunk = chunk_pair(chunk)
        names = [a.name for a in axes]
        for name in names:
            if names.count(name) > 1:
                raise ValueError(f"vary: {name} is varied more than once")
        for name in fixed:
            if name not in PARAMETERS:
                raise ValueError(f"{name}: not a parameter of a sweep; one of {', '.join(PARAMETERS)}")
        values = {n: check_value(n, v) for n, v in (PARAMETERS | dict(fixed)).items()}
        methods.refuse_sweep(method)
        t_end, dt, _, _ = validate.grid(t_end, dt)
        spec = cls(
            tuple(axes),
            values,
            t_end,
            dt,
            method,
            None if periods is None else validate.positive_int("periods", periods),
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
        forced = self.forced and self.periods is not None
        return tuple(a.name for a in self.axes) + SUMMARY_COLUMNS + (FORCED_COLUMNS if forced else ())

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

        First :func:`~.limits.check_size` (rows, memory, file, time from the sizes
        alone), then every row's magnitudes and forcing window, then, for
        ``exact`` and ``event-driven``, the time with the events estimated
        (:meth:`seconds`).  The estimates are for the rows that will run: all,
        or the slice ``rows`` (a chunk, :meth:`chunk`).
        """
        counts = [a.values.size for a in self.axes]
        limits.check_size(
            counts, n_steps=self.n_steps, method=self.method, forced=self.forced, output=self.output, rows=rows
        )
        self._check_rows()
        if self.method != "backward-euler":
            self.seconds(rows)

    def seconds(self, rows: slice | None = None) -> float:
        """Estimated time (s) of the rows (all, or the slice ``rows``) and of writing them; refused above the limit.

        Backward Euler: steps times :data:`~.limits.SECONDS_PER_TRAJECTORY_STEP` plus
        :data:`~.limits.SECONDS_PER_BATCHED_ROW`.  ``exact`` and ``event-driven``:
        :data:`~.limits.SECONDS_PER_RUN` with the events of :data:`~.limits.EVENT_SAMPLE` rows
        spread evenly over those that run, each estimated by the exact
        solver's upper estimate; within a factor 4 of the measured time
        (tests/test_sweep_limits.py).
        """
        index = np.arange(self.rows)[slice(None) if rows is None else rows]
        events = None
        if self.method != "backward-euler" and index.size:
            sample = index[
                np.unique(np.linspace(0, index.size - 1, min(index.size, limits.EVENT_SAMPLE)).round().astype(int))
            ]
            events = self._events(sample)
        row = limits.row_seconds(self.method, self.forced, self.n_steps, events)
        return limits.check_seconds(index.size, row, self.method, self.n_steps, self.output, len(self.columns()))

    def _events(self, sample: np.ndarray) -> np.ndarray:
        """The exact solver's upper estimate of the events of the rows ``sample``."""
        from lumped.model.forcing import SwitchedSine
        from lumped.solvers.exact import _event_estimate

        p = self.parameters()
        out = np.empty(sample.size)
        for i, j in enumerate(sample):
            row = {n: float(v[j]) for n, v in p.items()}
            force = SwitchedSine(row["force_amplitude"], row["force_omega"], row["force_phase"], row["force_until"])
            out[i] = _event_estimate(row_oscillator(row), force, self.n_steps * self.dt, row["x0"], row["v0"])
        return out

    def seconds_per_step(self) -> float:
        """Estimated cost of one trajectory-step (s) of backward Euler, of one grid point sampled otherwise."""
        if self.method == "backward-euler":
            kind = "forced" if self.forced else "free"
            return limits.SECONDS_PER_TRAJECTORY_STEP[BATCH_KERNEL][kind]
        return limits.SECONDS_PER_RUN[self.method]["sample"]

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
                    row_oscillator(row),
                    t_last,
                    self.dt,
                    row["x0"],
                    row["v0"],
                    row["force_amplitude"],
                    carries_force=carries,
                )
            except ValueError as err:
                raise ValueError(self._row_error(str(err), row, int(j))) from None
        if self.periods is None:
            return
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


def row_oscillator(row: Mapping[str, float]):  # noqa: ANN202 (an Oscillator)
    """The oscillator of a row of parameters: mass, a linear spring and a Bingham dashpot."""
    from lumped.model.oscillator import Oscillator

    return Oscillator.bingham(row["mass"], row["stiffness"], row["threshold"], row["gamma"])
