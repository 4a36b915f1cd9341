"""Sweeps of a system file's parameters: :func:`sweep_system`, the API of ``python -m lumped sweep --system``.

Every row is one run of the file's network with the varied parameters,
named ``entry.key`` as in the file (:mod:`lumped.model.system_parameters`:
``fric.static``, ``m1.x0``, ``belt.velocity``, ``force.amplitude``), set to the
row's values by :func:`~lumped.model.system_parameters.with_values`: the run
``python -m lumped simulate --system`` makes of a file with those values, by
:func:`lumped.solve`.  The grid is the Cartesian product of the axes, the
first varying slowest.  The columns: the varied parameters (named
``entry.key``), then for each mass, in the file's order,
``rest_time_<mass>``, ``rest_position_<mass>``, ``max_abs_x_<mass>`` and
``stops_<mass>``, defined as the single-mass sweep's
(:mod:`lumped.drivers.sweep.summaries`, :func:`~.summaries.mass_summaries`;
``nan`` rest while the mass moves at the end).

Two paths, the same numbers as the single run, bit for bit (tested):

* backward Euler on a file of the paper's form (one mass, one spring and one
  Bingham dashpot to the ground, no load or one sine or constant load on from
  ``t = 0``), which the single run hands to Algorithm 1: the rows go to the
  single-mass sweep (:class:`~lumped.drivers.sweep.spec.SweepSpec`), whose
  batched kernel advances them together with Algorithm 1's arithmetic;
* any other file or method: the rows one by one through :func:`lumped.solve`,
  in :data:`workers` processes (``concurrent.futures``, the rows' results
  taken in grid order) when the run is estimated above
  :data:`PROCESS_SECONDS` and this process may use more than one CPU.

Before any run every value of every axis goes through the file's own checks
(the mass, element, driver or load that holds it) and every row's network is
built (a pair of values that only together break a rule, such as a static
friction below the kinetic one, is refused); for backward Euler every row's
step is checked (its uniqueness bound, the loads' span) and the time of the
rows that run is estimated and refused above ``validate.MAX_SECONDS``.
"""

from __future__ import annotations

import math
import multiprocessing
import os
import signal
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import ProcessPoolExecutor
from typing import NamedTuple

import numpy as np

from lumped.drivers import methods
from lumped.drivers.sweep import grid, limits
from lumped.drivers.sweep.summaries import SUMMARY_COLUMNS, mass_columns, mass_summaries
from lumped.model.network import Network
from lumped.model.system_parameters import ONE_MASS_NAMES, SystemParameter, system_parameters, with_values
from lumped.numerics import validate

__all__ = [
    "PROCESS_SECONDS",
    "Prepared",
    "SystemAxis",
    "SystemSweep",
    "prepare",
    "run",
    "sweep_system",
    "system_key",
    "workers",
]

#: Runs estimated above this many seconds go to worker processes (fork and start cost some 0.1 s).
PROCESS_SECONDS = 2.0


class SystemAxis(NamedTuple):
    """One varied parameter of a system: the :class:`~lumped.model.system_parameters.SystemParameter` and its
    values (checked by the item that holds it)."""

    parameter: SystemParameter
    values: np.ndarray

    @property
    def name(self) -> str:
        """``entry.key``."""
        return self.parameter.name


class SystemSweep(NamedTuple):
    """A system's sweep, checked: the network, the axes, the grid, the method and its options."""

    network: Network
    axes: tuple[SystemAxis, ...]
    t_end: float
    dt: float
    method: str
    options: Mapping[str, object]

    @property
    def rows(self) -> int:
        """Number of parameter sets."""
        return math.prod(a.values.size for a in self.axes)

    @property
    def n_steps(self) -> int:
        """Steps of the shared grid."""
        return validate.step_count(self.t_end, self.dt)

    def columns(self) -> tuple[str, ...]:
        """The output columns, in order."""
        return tuple(a.name for a in self.axes) + mass_columns(self.network.mass_names)

    def values(self, rows: slice | None = None) -> np.ndarray:
        """The varied values of the rows (all, or the slice ``rows``), shape ``(rows, axes)``, grid order."""
        index = np.arange(self.rows)[slice(None) if rows is None else rows]
        shape = tuple(a.values.size for a in self.axes)
        picks = np.unravel_index(index, shape)
        return np.column_stack([a.values[i] for a, i in zip(self.axes, picks)]).reshape(index.size, len(self.axes))

    def network_of(self, values: Sequence[float]) -> Network:
        """The network of one row: the file's with the varied parameters set to ``values``."""
        return with_values(self.network, [a.parameter for a in self.axes], values)

    def row_text(self, values: Sequence[float]) -> str:
        """``fric.static = 0.5, m.x0 = 0.1``: a row's values, for a message."""
        return ", ".join(f"{a.name} = {v:.6g}" for a, v in zip(self.axes, values))


def system_key(network: Network) -> Callable[[str], str]:
    """The ``key`` of :func:`~lumped.drivers.sweep.grid.vary_text` for ``network``: a ``--vary`` NAME checked
    as one of its parameters (``entry.key``); a one-line ``vary:`` error listing them otherwise."""
    return lambda name: _parameter(network, name.strip()).name


def _parameter(network: Network, name: str) -> SystemParameter:
    """The parameter ``name`` of ``network``; a key that an entry has but that is not a number (``fric.kind``,
    ``m.name``) is refused as such, the system's numeric parameters listed."""
    try:
        return system_parameters(network, [name], "vary")[0]
    except ValueError as err:
        if not isinstance(name, str):
            raise
        item, _, key = name.rpartition(".")
        entries = [*network.masses, *network.elements, *network.drivers]
        if any(getattr(e, "name", None) == item and hasattr(e, key) for e in entries):
            listed = str(err).partition("; ")[2]
            raise ValueError(f"vary: {name!r} is not a numeric parameter{'; ' + listed if listed else ''}") from None
        raise


def system_axis(network: Network, name: str, values: object) -> SystemAxis:
    """A :class:`SystemAxis`: ``name`` a parameter of ``network``, ``values`` real numbers in a 1-d sequence;
    a NaN, the least and the greatest value through the check of the item that holds it (:func:`check_values`
    checks the others)."""
    param = _parameter(network, name)
    data = grid._as_values(name, values)
    if data.size == 0:
        raise ValueError(f"vary: {name} has no values")
    axis = SystemAxis(param, data)
    check_values(network, axis, np.unique([data.min(), data.max(), *data[np.isnan(data)][:1]]))
    return axis


def check_values(network: Network, axis: SystemAxis, values: np.ndarray | None = None) -> None:
    """``values`` (every distinct value of ``axis`` by default) through the check of the mass, element, driver
    or load that holds the parameter: its own message, after ``vary: name = value``."""
    for value in np.unique(axis.values) if values is None else values:
        if not math.isfinite(value):
            raise ValueError(f"vary: {axis.name} must hold finite numbers, got {value}")
        try:
            with_values(network, [axis.parameter], [value])
        except ValueError as err:
            raise ValueError(f"vary: {axis.name} = {value:.6g}: {err}") from None


def build(
    network: Network,
    vary: Mapping[str, object],
    *,
    t_end: float,
    dt: float,
    method: str = "backward-euler",
    options: Mapping[str, object] | None = None,
) -> SystemSweep:
    """A :class:`SystemSweep`, its arguments checked (the rows are checked by :func:`check`)."""
    if not isinstance(network, Network):
        raise ValueError(f"network must be a Network, got {type(network).__name__}")
    if not isinstance(vary, Mapping) or not vary:
        raise ValueError("vary must map one or more of the system's parameters (entry.key) to their values")
    methods.refuse_sweep(method)
    options = methods.get(method).check_options(dict(options or {}))
    t_end, dt, _, _ = validate.grid(t_end, dt)
    counts = [grid.axis_size(name, values) for name, values in vary.items()]
    limits._check_rows(counts)
    axes = tuple(system_axis(network, name, values) for name, values in vary.items())
    return SystemSweep(network, axes, t_end, dt, method, options)


def workers(rows: int) -> int:
    """The processes a sweep of ``rows`` one-by-one rows may use: the CPUs this process may run on (in a SLURM
    job, at most its ``SLURM_CPUS_PER_TASK``), at most ``rows``."""
    cpus = len(os.sched_getaffinity(0))
    given = os.environ.get("SLURM_CPUS_PER_TASK", "")
    if given.isdigit() and int(given) >= 1:
        cpus = min(cpus, int(given))
    return max(1, min(rows, cpus))


class Prepared(NamedTuple):
    """A sweep checked and ready to run (:func:`prepare`): the sweep, the rows that run, and how: the
    single-mass sweep that runs them batched (and the names of its columns), or their values one by one on
    ``workers`` processes."""

    spec: SystemSweep
    rows: slice | None
    batch: object
    values: np.ndarray | None
    workers: int
    #: The estimated time (s) of the rows, on ``workers`` processes.
    seconds: float


def sweep_system(
    network: Network,
    vary: Mapping[str, Sequence[float] | np.ndarray],
    *,
    t_end: float = 2.0,
    dt: float = 1e-4,
    method: str = "backward-euler",
    chunk: tuple[int, int] | None = None,
    output: str | None = None,
    progress: Callable[[int, int], None] | None = None,
    **options: object,
) -> dict[str, np.ndarray]:
    """Summaries of ``network`` (a system file, :func:`lumped.model.files.load_system`) over the grid ``vary``.

    Parameters
    ----------
    network : Network
    vary : mapping of str to 1-d array
        A parameter's name, ``entry.key`` as in the file, to its values; the grid is their Cartesian
        product, the first name varying slowest.
    t_end, dt : float, s
        The grid every row runs on.
    method : {"backward-euler", "exact", "event-driven"}
        A method of :data:`lumped.drivers.methods.SWEEP_METHODS`; ``options`` are its own (as for
        :func:`lumped.solve`).
    chunk : (int, int), optional
        ``(index, count)``: only the rows of chunk ``index`` of ``count`` contiguous chunks
        (:func:`~lumped.drivers.sweep.grid.chunk_slice`); the chunks concatenate to the whole.
    output : {".csv", ".npz"}, optional
        The kind of file the rows go to, for the estimate of its size.
    progress : callable, optional
        ``progress(done, total)``.

    Returns
    -------
    dict of str to ndarray
        One entry per column (see the module's docstring), one value per row; the ``stops_<mass>`` as integers.

    Raises
    ------
    ValueError
        One line, before any run (:func:`prepare`): an unknown or non-numeric parameter, a value its item
        refuses (``vary:``), a row whose network or step is refused (the row's values named), a grid too
        large or too slow.
    """
    ready = prepare(network, vary, t_end=t_end, dt=dt, method=method, chunk=chunk, output=output, **options)
    return run(ready, progress)


def prepare(
    network: Network,
    vary: Mapping[str, Sequence[float] | np.ndarray],
    *,
    t_end: float = 2.0,
    dt: float = 1e-4,
    method: str = "backward-euler",
    chunk: tuple[int, int] | None = None,
    output: str | None = None,
    **options: object,
) -> Prepared:
    """:func:`sweep_system`'s checks, every one before any run (its arguments); :func:`run` runs the rows."""
    spec = build(network, vary, t_end=t_end, dt=dt, method=method, options=options)
    rows = None if chunk is None else grid.chunk_slice(spec.rows, *grid.chunk_pair(chunk))  # type: ignore[misc]
    count = len(range(spec.rows)[slice(None) if rows is None else rows])
    columns = len(spec.columns())
    limits._check_memory(count, columns)
    if output is not None:
        limits._check_file(count, columns, output)
    batch = _batch(spec, rows, output)
    if batch is not None:  # the single mass's checks: interval domains, whose ends system_axis checked
        return Prepared(spec, rows, batch, None, 1, batch[0].seconds(rows))
    values = spec.values(rows)
    if len(values) > 1:  # the first row's estimate for all, before every value and row is checked
        _check_time(spec, check(spec, values[:1]) * len(values), workers(len(values)), len(values))
    for axis in spec.axes:
        check_values(spec.network, axis)
    seconds = check(spec, values)
    n_workers = workers(len(values)) if seconds > PROCESS_SECONDS else 1
    _check_time(spec, seconds, n_workers, len(values))
    return Prepared(spec, rows, None, values, n_workers, seconds / n_workers)


def run(ready: Prepared, progress: Callable[[int, int], None] | None = None) -> dict[str, np.ndarray]:
    """The rows of a :func:`prepare` d sweep, in :func:`sweep_system`'s columns."""
    spec, values = ready.spec, ready.values
    if ready.batch is not None:
        return _batched(spec, ready.batch, ready.rows, progress)
    sums = _run_rows(spec, values, ready.workers, progress)  # type: ignore[arg-type]
    out = {a.name: values[:, i] for i, a in enumerate(spec.axes)}  # type: ignore[index]
    for name in mass_columns(spec.network.mass_names):
        col = np.array([s[name] for s in sums], dtype=float)
        out[name] = col.astype(np.int64) if name.startswith("stops_") else col
    return out


def check(spec: SystemSweep, values: np.ndarray) -> float:
    """Every row's network built (its items' checks) and, for backward Euler, its step checked; the
    estimated time (s) of running them one by one.  A refusal names the row's values."""
    from lumped.drivers.network import check_active_set, paper_form

    solver = str(spec.options.get("solver", "auto"))
    seconds = 0.0
    for j, row in enumerate(values):
        try:
            net = spec.network_of(row)
            if spec.method == "backward-euler" and paper_form(net, solver) is None:
                seconds += check_active_set(net, spec.dt, spec.n_steps, 1, solver)[2]
            else:  # Algorithm 1 or a single-mass method: the single-mass sweep's estimate of a row
                seconds += limits.row_seconds(spec.method, bool(net.loads), spec.n_steps, np.full(1, 2.0))
        except ValueError as err:
            raise ValueError(f"{err} (row {j}: {spec.row_text(row)})") from None
    return seconds


def _check_time(spec: SystemSweep, seconds: float, n_workers: int, rows: int) -> None:
    """Refuse rows estimated to take more than ``validate.MAX_SECONDS`` on ``n_workers`` processes."""
    wall = seconds / n_workers
    if wall > validate.MAX_SECONDS:
        raise ValueError(
            f"vary: {rows} rows of {spec.method} ({spec.n_steps} steps each) would take about {wall:.3g} s "
            f"on {n_workers} process{'es' if n_workers > 1 else ''}, more than the {validate.MAX_SECONDS:.0f} s "
            "allowed; fewer rows, a coarser dt, a shorter t_end, or chunks"
        )


# ---- rows one by one ------------------------------------------------------------------------------------

#: The sweep a worker process runs rows of (set before the fork: the network is not pickled).
_WORKER: SystemSweep | None = None


def _row(spec: SystemSweep, values: Sequence[float]) -> dict[str, float]:
    """One row: the single run :func:`lumped.solve` makes of the row's network, summarised per mass."""
    from lumped.drivers.simulation import solve
    from lumped.model.problem import Problem

    try:
        traj = solve(Problem(spec.network_of(values), spec.t_end), spec.dt, method=spec.method, **spec.options)
    except ValueError as err:  # a refusal the method makes as it runs (exact, event-driven): the row named
        raise ValueError(f"{err} (the row {spec.row_text(values)})") from None
    return mass_summaries(traj)


def _worker_rows(values: np.ndarray) -> list[dict[str, float]]:
    """Rows run in a worker process, of the sweep it inherited (:data:`_WORKER`)."""
    return [_row(_WORKER, row) for row in values]  # type: ignore[arg-type]


def _run_rows(
    spec: SystemSweep, values: np.ndarray, n_workers: int, progress: Callable[[int, int], None] | None
) -> list[dict[str, float]]:
    """The rows' summaries in grid order, in this process or in ``n_workers`` forked ones."""
    global _WORKER
    n = len(values)
    if n_workers <= 1:
        results = (_row(spec, row) for row in values)
        return [_report(progress, j, n, r) for j, r in enumerate(results)]
    _WORKER = spec
    context = multiprocessing.get_context("fork")
    pool = ProcessPoolExecutor(n_workers, mp_context=context, initializer=_quiet)
    size = max(1, n // (8 * n_workers))  # blocks of rows: some eight a worker, for the progress and the balance
    try:
        blocks = [pool.submit(_worker_rows, values[i : i + size]) for i in range(0, n, size)]
        out: list[dict[str, float]] = []
        for block in blocks:  # grid order
            out += block.result()
            if progress is not None:
                progress(len(out), n)
    except BaseException:  # a refused row, Ctrl-C, SIGTERM: stop the workers now, not after their rows
        for process in list((pool._processes or {}).values()):  # no public way before Python 3.14
            process.terminate()
        pool.shutdown(wait=False)
        raise
    finally:
        _WORKER = None
    pool.shutdown()
    return out


def _quiet() -> None:
    """A worker's signals: Ctrl-C and SIGTERM/SIGHUP are the parent's to handle (it stops the workers)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    for name in ("SIGTERM", "SIGHUP"):
        signal.signal(getattr(signal, name), signal.SIG_DFL)


def _report(progress: Callable[[int, int], None] | None, j: int, n: int, result: dict) -> dict:
    if progress is not None and (j % 16 == 15 or j == n - 1):
        progress(j + 1, n)
    return result


# ---- a file of the paper's form: the batched kernel -------------------------------------------------------


def _batch(spec: SystemSweep, rows: slice | None, output: str | None):
    """The single-mass sweep that runs ``spec``'s rows as the single runs do (Algorithm 1), or ``None``.

    Backward Euler with ``solver`` ``"auto"`` on a file of the paper's form with a Bingham dashpot and
    no load or one that is a sine on from ``t = 0`` (a constant too), every varied parameter one of the
    single mass's (:data:`~lumped.model.system_parameters.ONE_MASS_NAMES`).
    """
    from lumped.drivers.network import paper_form
    from lumped.drivers.sweep.spec import SweepSpec
    from lumped.laws import BinghamDashpot
    from lumped.model.forcing import SwitchedSine, as_sine, one_force

    if spec.method != "backward-euler" or spec.options.get("solver", "auto") != "auto":
        return None
    form = paper_form(spec.network)
    load = one_force([load.force for load in spec.network.loads])
    force = as_sine(load)  # the load as one sine (Forcing, point 4), or None
    if form is None or type(form.oscillator.dashpot) is not BinghamDashpot:
        return None
    if load is not None and force is None:
        return None
    if any((a.parameter.table, a.parameter.key) not in ONE_MASS_NAMES for a in spec.axes):
        return None
    osc, mass = form.oscillator, spec.network.masses[0]
    sine = force or SwitchedSine(0.0)
    fixed = {
        "mass": osc.mass,
        "stiffness": osc.stiffness,
        "threshold": osc.dashpot.threshold,
        "gamma": osc.dashpot.gamma,
        "x0": mass.x0,
        "v0": mass.v0,
        "force_amplitude": sine.amplitude,
        "force_omega": sine.omega,
        "force_phase": sine.phase,
        "force_until": sine.until,
    }
    axes = [grid.Axis(ONE_MASS_NAMES[a.parameter.table, a.parameter.key], a.values) for a in spec.axes]
    spring, dashpot = form.springs[0].name, form.dashpot.name
    names = {"mass": f"{mass.name}.mass", "x0": f"{mass.name}.x0", "v0": f"{mass.name}.v0"}
    names |= {"stiffness": f"{spring}.stiffness", "threshold": f"{dashpot}.threshold", "gamma": f"{dashpot}.gamma"}
    names |= {ax.name: a.name for ax, a in zip(axes, spec.axes)}
    for a in axes:
        fixed.pop(a.name)
    try:
        return SweepSpec.build(axes, t_end=spec.t_end, dt=spec.dt, periods=None, output=output, **fixed), names
    except ValueError as err:
        raise ValueError(_file_words(str(err), names)) from None


def _file_words(message: str, names: Mapping[str, str]) -> str:
    """A single-mass sweep's message with the varied parameters' names as the file's (``entry.key``)."""
    for one, file_name in names.items():
        if one != file_name:
            message = message.replace(f"{one} = ", f"{file_name} = ")
            for lead in ("", "vary: "):
                if message.startswith((f"{lead}{one}:", f"{lead}{one} ")):
                    message = f"{lead}{file_name}{message[len(lead) + len(one) :]}"
    return message


def _batched(spec: SystemSweep, batch, rows: slice | None, progress) -> dict[str, np.ndarray]:
    """The rows by the single-mass sweep's batched kernel, in this sweep's columns."""
    from lumped.drivers.sweep.run import run_sweep

    one, _ = batch
    got = run_sweep(one, rows, progress)
    (mass,) = spec.network.mass_names
    out = {a.name: got[ax.name] for a, ax in zip(spec.axes, one.axes)}
    out |= {f"{c}_{mass}": got[c] for c in SUMMARY_COLUMNS}
    return out
