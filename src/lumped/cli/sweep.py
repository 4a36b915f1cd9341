"""``python -m lumped sweep``: a grid of parameter sets, one row of summaries per set (:mod:`lumped.drivers.sweep`)."""

from __future__ import annotations

import argparse
import math
import os
import sys
import time

import numpy as np

from lumped.cli.loads import OFF_AT_START, no_sine
from lumped.cli.options import HelpFormatter, add_method_options, method_options
from lumped.cli.output import Output, check_output
from lumped.cli.reference import methods_help
from lumped.drivers.methods import METHODS, SWEEP_METHODS
from lumped.model.parameters import PARAMETERS, shown
from lumped.numerics import validate

_SWEEP_DESCRIPTION = """\
Run the single-mass system for every parameter set of a grid and write one row
per set (.csv or .npz): the varied parameters, then rest_time, rest_position
(nan while still moving), max_abs_x, stops and, when some row is forced,
steady_amplitude and stops_per_period over the last --periods forcing periods
(nan in rows whose forcing is zero, constant or ends before the run).

stops counts the grid steps that enter the stick branch from motion (v_n = 0,
v_{{n-1}} != 0), as the method's samples show them, not the exact solution's
stops: backward Euler also sticks for one step at some velocity reversals the
exact motion passes through (from --x0 0.5: 3 stops, --method exact: 1).

Refused before any work: more than {rows:.0e} rows (the product of the --vary
counts, checked before any value), more than {memory:.0f} GiB of memory by the
estimate (some 300 to 500 bytes a row), an output file that could exceed
{file:.0f} GiB ({csv} bytes a value in .csv, {npz} in .npz), or more than {seconds:.0f} s by
the estimate (steps, runs and their events, writing the file); the message
states the estimate.  Split a larger grid into several sweeps, or run it in
chunks (--chunk I/N, one job each, concatenated in order: the whole grid's rows).

With --system FILE.toml each row is the run "simulate --system FILE.toml"
makes with the varied parameters of the file, named entry.key as in the file
(--vary fric.static=0.5:1.5:11, m1.x0, belt.velocity, force.amplitude); only
--vary, --t-end, --dt, --method and its options, --chunk and --output go with
it.  Columns: the varied parameters, then for each mass rest_time_<mass>,
rest_position_<mass> (empty cells while it moves at the end), max_abs_x_<mass>
and stops_<mass>, defined as above.  A file of the paper's form (one spring,
one Bingham dashpot, a sine or constant load) runs in the batched kernel, any
other row by row, in processes when the run is long.  See
book/guide/sweeps.md (the website's Sweeps page) for the definitions."""


def add_parser(sub: argparse._SubParsersAction) -> None:
    """The ``sweep`` subcommand: the single-mass options of ``simulate`` and its own."""
    from lumped.drivers.sweep import limits

    bounds = dict(
        rows=limits.MAX_ROWS,
        memory=limits.MAX_MEMORY_BYTES / 1024**3,
        file=validate.MAX_OUTPUT_BYTES / 1024**3,
        csv=limits.FILE_BYTES_PER_VALUE[".csv"],
        npz=limits.FILE_BYTES_PER_VALUE[".npz"],
        seconds=validate.MAX_SECONDS,
    )
    sw = sub.add_parser(
        "sweep",
        help="one row of summaries per parameter set of a grid",
        description=_SWEEP_DESCRIPTION.format(**bounds),
        allow_abbrev=False,
        epilog=methods_help(sweep=True),
        formatter_class=HelpFormatter,
    )
    for p in PARAMETERS.values():
        if p.name != "save_every":  # a sweep keeps summaries, not trajectories
            sw.add_argument(p.option, default=None, help=f"{p.help} [default: {p.default_text}]")
    sw.add_argument(
        "--vary",
        action="append",
        default=[],
        metavar="NAME=[log:]START:STOP:COUNT",
        help="vary the option NAME (without dashes; force-omega or force_omega), or with --system the file's "
        "parameter NAME (entry.key: fric.static), over COUNT values from START to "
        "STOP, evenly or (log:) geometrically spaced; repeat for a grid, the first --vary varying slowest",
    )
    sw.add_argument(
        "--periods", default=None, help="K, the final forcing periods of the forced summaries [default: 10]"
    )
    sw.add_argument(
        "--system",
        default=None,
        metavar="FILE.toml",
        help="sweep the parameters of a system file (book/guide/systems.md) instead of the single mass's",
    )
    sw.add_argument(
        "--chunk",
        default=None,
        metavar="I/N",
        help="only the rows of chunk I (0 to N-1) of N near-equal contiguous chunks of the grid, for a job of a "
        "cluster; the N chunks' rows, concatenated in order, are the whole grid's [default: every row]",
    )
    add_method_options(sw, sweep=True)
    sw.add_argument("--output", required=True, help="output file, .csv or .npz")


def _spec(args: argparse.Namespace):  # noqa: ANN202 (a lumped.drivers.sweep.SweepSpec and the chunk's rows)
    """Parse and validate the sweep's options into a :class:`~lumped.drivers.sweep.SweepSpec` and the rows
    that run (``None``: all; a slice with ``--chunk``).

    The grid's size (rows, memory, file, time) is checked from the ``--vary``
    counts before any of its values is built or checked.
    """
    from lumped.drivers.sweep import SweepSpec, check_size, chunk_slice, vary_text

    varies = [vary_text(text) for text in args.vary]
    given = {name: getattr(args, name) for name in PARAMETERS if getattr(args, name, None) is not None}
    for v in varies:
        if v.name in given:
            raise ValueError(f"{PARAMETERS[v.name].option} is also varied by --vary {v.name}; give one of the two")
    values = {
        name: p.check(name, validate.parse_float(name, given.get(name, p.default_text)))
        for name, p in PARAMETERS.items()
        if name != "save_every"
    }
    options = method_options(args) if args.method in METHODS else {}
    t_end, dt = values.pop("t_end"), values.pop("dt")
    periods = validate.parse_int("periods", "10" if args.periods is None else args.periods)
    chunk = parse_chunk(args.chunk)
    suffix = os.path.splitext(check_output(args.output))[1].lower()
    forced = values["force_amplitude"] != 0 or any(v.name == "force_amplitude" and not v.all_zero for v in varies)
    if forced and not any(v.name in ("force_omega", "force_phase") for v in varies):
        if values["force_omega"] == 0 and math.sin(values["force_phase"]) == 0:  # every row's sine is 0
            what = f"--force-amplitude {shown(values['force_amplitude'])}" if "force_amplitude" in given else None
            remedy = "give or vary --force-omega, or --force-phase 1.5707963267948966"
            raise ValueError(no_sine(what or "--vary force_amplitude", remedy))
    if forced and values["force_until"] == 0 and not any(v.name == "force_until" for v in varies):
        raise ValueError(OFF_AT_START)  # every row's sine is off before it acts
    if args.method in SWEEP_METHODS:  # another is refused by SweepSpec.build
        n_steps = validate.step_count(t_end, dt)
        counts = [v.count for v in varies]
        rows = None if chunk is None else chunk_slice(math.prod(counts), *chunk)
        check_size(counts, n_steps=n_steps, method=args.method, forced=forced, output=suffix, rows=rows)
    axes = [v.axis() for v in varies]
    spec = SweepSpec.build(
        axes,
        t_end=t_end,
        dt=dt,
        method=args.method,
        periods=periods,
        options=options,
        output=suffix,
        chunk=chunk,
        **values,
    )
    return spec, None if chunk is None else spec.chunk(*chunk)


def parse_chunk(text: str | None) -> tuple[int, int] | None:
    """``--chunk I/N`` as ``(I, N)``, ``0 <= I < N``, or None when not given."""
    if text is None:
        return None
    index, slash, count = text.partition("/")
    parts = (index.strip(), count.strip())
    if not slash or not all(p.isascii() and p.isdigit() for p in parts):
        raise ValueError(f"--chunk expects I/N, two whole numbers such as 0/4, got {text!r}")
    i, n = int(parts[0]), int(parts[1])
    if not 0 <= i < n:
        raise ValueError(f"--chunk: I must be 0 to N-1 (chunks are counted from 0), got {text!r}")
    return i, n


def run(args: argparse.Namespace, output: Output) -> str:
    """Validate, refuse what is too large, reserve the output, run the rows, write; returns the summary."""
    from lumped.drivers.sweep import Progress, run_sweep

    if args.system is not None:
        return _run_system(args, output)
    spec, rows = _spec(args)
    output.create()
    start = time.perf_counter()
    long = spec.seconds(rows) > 5.0
    got = run_sweep(spec, rows, progress=Progress(sys.stderr, sys.stderr.isatty() or long))
    output.commit(got)
    return f"{_rows_text(len(next(iter(got.values()))), spec.rows, args.chunk)} in {time.perf_counter() - start:.3g} s"


def _rows_text(count: int, total: int, chunk: str | None) -> str:
    """``12 rows``, or ``3 rows (chunk 1/4 of 12)``."""
    return f"{count} row{'' if count == 1 else 's'}" + ("" if chunk is None else f" (chunk {chunk} of {total})")


def _run_system(args: argparse.Namespace, output: Output) -> str:
    """``--system``: read the file, check every row, reserve the output, run the rows, write."""
    from lumped.drivers.sweep import Progress
    from lumped.drivers.sweep import system as by_file
    from lumped.drivers.sweep.grid import vary_text
    from lumped.model.files import load_system

    if args.periods is not None:
        raise ValueError("--periods sets the single mass's forced summaries; a --system sweep writes none")
    grid_values = {
        n: PARAMETERS[n].check(n, validate.parse_float(n, getattr(args, n) or PARAMETERS[n].default_text))
        for n in ("t_end", "dt")
    }
    options = method_options(args) if args.method in METHODS else {}
    chunk = parse_chunk(args.chunk)
    suffix = os.path.splitext(check_output(args.output))[1].lower()
    if not args.vary:
        raise ValueError("--vary: a --system sweep needs at least one --vary entry.key=START:STOP:COUNT")
    network = load_system(args.system)
    varies = [vary_text(text, by_file.system_key(network)) for text in args.vary]
    names = [v.name for v in varies]
    twice = [n for i, n in enumerate(names) if n in names[:i]]
    if twice:
        raise ValueError(f"vary: {twice[0]} is varied more than once")
    vary = {v.name: v.values() for v in varies}
    ready = by_file.prepare(network, vary, **grid_values, method=args.method, chunk=chunk, output=suffix, **options)
    output.create()
    start = time.perf_counter()
    got = by_file.run(ready, Progress(sys.stderr, sys.stderr.isatty() or ready.seconds > 5.0))
    output.commit(_cells(got) if suffix == ".csv" else got)
    count = len(next(iter(got.values())))
    total = math.prod(v.count for v in varies)
    return f"{_rows_text(count, total, args.chunk)} in {time.perf_counter() - start:.3g} s"


def _cells(columns: dict) -> dict:
    """The columns for the CSV: a rest time or position of a mass that moves at the end (``nan``) as an empty cell."""
    out = {}
    for name, col in columns.items():
        if name.startswith(("rest_time_", "rest_position_")):
            col = np.array([None if math.isnan(v) else v for v in col], dtype=object)
        out[name] = col
    return out
