"""The sweep driver: :func:`sweep` (the Python API) and :func:`run_sweep` (the rows of a :class:`SweepSpec`).

Backward Euler advances the rows together through the batched kernel
(:mod:`lumped.kernels.batched`); ``exact`` and ``event-driven`` run them one
by one through :func:`lumped.drivers.simulation.simulate` and summarise each
(:func:`lumped.drivers.sweep.summaries.summarize`).
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Mapping, Sequence

import numpy as np

from lumped.drivers import methods
from lumped.drivers.sweep import grid, limits
from lumped.drivers.sweep.spec import SweepSpec, row_oscillator
from lumped.drivers.sweep.summaries import Summary, summarize, window_start
from lumped.kernels.batched import BatchParameters, batch_backward_euler
from lumped.numerics import validate

#: Methods a sweep runs, those of the registry that run a batch (:data:`lumped.drivers.methods.SWEEP_METHODS`);
#: backward Euler goes through the batched kernel.
SWEEP_METHODS = methods.SWEEP_METHODS


def _batched(spec: SweepSpec, p: Mapping[str, np.ndarray], progress: Callable[[int, int], None] | None) -> dict:
    """Backward-Euler rows through :func:`lumped.kernels.batched.batch_backward_euler`."""
    n_steps, dt = spec.n_steps, spec.dt
    start = _window(spec, p)
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
        "stops_per_period": np.where(np.isnan(start), np.nan, s.window_stops / (spec.periods or 1)),
    }


def _window(spec: SweepSpec, p: Mapping[str, np.ndarray]) -> np.ndarray:
    """Each row's window of the forced summaries (:func:`window_start`), none without ``periods``."""
    if spec.periods is None:
        return np.full(p["mass"].size, np.nan)
    return window_start(p, spec.n_steps * spec.dt, spec.periods)


def _one_by_one(spec: SweepSpec, p: Mapping[str, np.ndarray], progress: Callable[[int, int], None] | None) -> dict:
    """Rows of ``exact`` or ``event-driven``: a single run each, through :func:`lumped.drivers.simulation.solve`."""
    from lumped.drivers.simulation import solve
    from lumped.model.forcing import SwitchedSine
    from lumped.model.problem import Problem

    n = p["mass"].size
    start = _window(spec, p)
    out = np.empty((n, len(Summary._fields)))
    for j in range(n):
        row = {name: float(v[j]) for name, v in p.items()}
        force = SwitchedSine(row["force_amplitude"], row["force_omega"], row["force_phase"], row["force_until"])
        problem = Problem.oscillator(
            row_oscillator(row), spec.t_end, x0=row["x0"], v0=row["v0"], force=None if force.is_zero else force
        )
        traj = solve(problem, spec.dt, method=spec.method, **spec.options)
        out[j] = summarize(traj, float(start[j]), spec.periods or 1)
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
        Parameter name (:data:`~.grid.PARAMETERS`) to its values, real numbers
        (booleans, strings, complex numbers and arrays of more than one
        dimension are refused); the grid is their Cartesian product, the first
        name varying slowest.  Its size is checked (:func:`~.limits.check_size`) before
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
        The parameters that do not vary (defaults :data:`~.grid.PARAMETERS`).

    Returns
    -------
    dict of str to ndarray
        One entry per column (:meth:`SweepSpec.columns`), one value per row.
    """
    if not isinstance(vary, Mapping):
        raise ValueError(f"vary must be a mapping of parameter names to 1-d sequences of values, got {_kind(vary)}")
    keys = [grid.parameter_key(name) for name in vary]
    counts = [grid.axis_size(key, values) for key, values in zip(keys, vary.values())]
    if method in SWEEP_METHODS:  # an unknown method is refused by SweepSpec.build
        _check_size(keys, counts, t_end=t_end, dt=dt, method=method, chunk=chunk, fixed=fixed)
    axes = [grid.axis(name, values) for name, values in vary.items()]
    spec = SweepSpec.build(axes, t_end=t_end, dt=dt, method=method, periods=periods, chunk=chunk, **fixed)
    return run_sweep(spec, None if chunk is None else spec.chunk(*grid.chunk_pair(chunk)))  # type: ignore[misc]


def _check_size(
    keys: Sequence[str],
    counts: Sequence[int],
    *,
    t_end: float,
    dt: float,
    method: str,
    chunk: object,
    fixed: Mapping[str, float],
) -> None:
    """:func:`~.limits.check_size` of the rows that will run, from the names and sizes of the axes alone."""
    amplitude = fixed.get("force_amplitude", 0.0)  # a varied amplitude counts as forced: an upper estimate
    forced = "force_amplitude" in keys or not (isinstance(amplitude, numbers.Real) and amplitude == 0)
    n_steps = validate.grid(t_end, dt).n_steps
    rows = None if chunk is None else grid.chunk_slice(math.prod(counts), *grid.chunk_pair(chunk))  # type: ignore[misc]
    limits.check_size(counts, n_steps=n_steps, method=method, forced=forced, rows=rows)


def _kind(value: object) -> str:
    """A value's type, shortened, for an error message."""
    return f"a {type(value).__name__}"
