"""``python -m lumped sweep``: a grid of parameter sets, one row of summaries per set (:mod:`lumped.drivers.sweep`)."""

from __future__ import annotations

import argparse
import math
import os
import sys
import time

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
states the estimate.  Split a larger grid into several sweeps.  See book/guide/sweeps.md
(the website's Sweeps page) for the definitions."""


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
        help="vary the option NAME (without dashes; force-omega or force_omega) over COUNT values from START to "
        "STOP, evenly or (log:) geometrically spaced; repeat for a grid, the first --vary varying slowest",
    )
    sw.add_argument(
        "--periods", default="10", help="K, the final forcing periods of the forced summaries [default: 10]"
    )
    add_method_options(sw, sweep=True)
    sw.add_argument("--output", required=True, help="output file, .csv or .npz")


def _spec(args: argparse.Namespace):  # noqa: ANN202 (a lumped.drivers.sweep.SweepSpec)
    """Parse and validate the sweep's options into a :class:`~lumped.drivers.sweep.SweepSpec`.

    The grid's size (rows, memory, file, time) is checked from the ``--vary``
    counts before any of its values is built or checked.
    """
    from lumped.drivers.sweep import SweepSpec, check_size, vary_text

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
    periods = validate.parse_int("periods", args.periods)
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
        check_size([v.count for v in varies], n_steps=n_steps, method=args.method, forced=forced, output=suffix)
    axes = [v.axis() for v in varies]
    return SweepSpec.build(
        axes, t_end=t_end, dt=dt, method=args.method, periods=periods, options=options, output=suffix, **values
    )


def run(args: argparse.Namespace, output: Output) -> str:
    """Validate, refuse what is too large, reserve the output, run the rows, write; returns the summary."""
    from lumped.drivers.sweep import Progress, run_sweep

    spec = _spec(args)
    output.create()
    start = time.perf_counter()
    long = spec.seconds() > 5.0
    rows = run_sweep(spec, progress=Progress(sys.stderr, sys.stderr.isatty() or long))
    output.commit(rows)
    return f"{spec.rows} rows in {time.perf_counter() - start:.3g} s"
