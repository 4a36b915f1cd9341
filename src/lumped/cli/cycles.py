"""``python -m lumped cycles``: steady sliding and the limit cycles of one mass on a belt (:mod:`lumped.drivers.cycles`)."""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from lumped.cli.options import HelpFormatter
from lumped.cli.output import Output, check_output
from lumped.numerics import validate

_DESCRIPTION = """\
Self-excited oscillations of one mass on a moving belt: steady sliding (the
mass at rest, the contact slipping at the belt's speed), the eigenvalues of its
linearisation, and its limit cycles (stick-slip included), found by shooting
on the return map to the section x = x* with the period unknown.
The system: one mass held by linear springs to points at rest, linear
dashpots, and one friction contact (kind friction, any falling law) on a
[[driver]] at a constant velocity; no load.  A file without a driven point,
or whose contact cannot lose stability (a law that starts at static and
never falls, a linear dashpot for a contact), is refused with the reason.
Without --vary: the equilibrium's row, then one row per cycle found at the
file's parameters, from the file's initial state (a long event-driven run
until the cycle settles, then Newton) and from the branch born at the
nearest Hopf point in the belt's speed (within a factor 10 of the file's).
With --vary NAME=START:STOP the equilibria and the cycles are continued over
the range: NAME is a numeric parameter of the file written element.key,
mass.key or driver.velocity (belt.velocity, fric.static, spring.stiffness);
--vary START:STOP alone varies the velocity of the file's one driver.
Columns (one row per equilibrium or cycle): NAME (with --vary), branch
(equilibrium or cycle), period (s), max_<mass> and min_<mass> (m: the
extremes over the period; the position for an equilibrium), stick_time (s per
period with the contact stuck), stable (true or false: by more than the
computed error; a value within it of the boundary, or a Hopf point's
equilibrium, is false),
max_multiplier (a cycle's largest Floquet multiplier in modulus, the trivial
one left out), max_real_part (an equilibrium's largest real part of an
eigenvalue, 1/s) and kind (regular, hopf, fold, stick-slip-onset,
stick-change, period-doubling: the located point of a change).  A value that
does not apply to a row is an empty cell.
The work is bounded: each branch takes at most 100 returns to the section a
point (at least 3000; the Hopf branch without --vary 300), each some 0.05 s,
and where they are spent it ends at its last point and the summary says so;
progress goes to stderr, a line a second."""


def add_parser(sub: argparse._SubParsersAction) -> None:
    """The ``cycles`` subcommand."""
    cp = sub.add_parser(
        "cycles",
        help="steady sliding on a belt and its limit cycles, or their branches",
        description=_DESCRIPTION,
        allow_abbrev=False,
        formatter_class=HelpFormatter,
    )
    cp.add_argument(
        "--system", required=True, metavar="FILE.toml", help="the system file (examples/stribeck_belt.toml)"
    )
    cp.add_argument(
        "--vary",
        action="append",  # kept to refuse a second one (run): argparse's default would keep the last
        metavar="NAME=START:STOP",
        help="continue over NAME (driver.velocity, element.key, mass.key) from START to STOP; "
        "START:STOP alone: the velocity of the file's one driver",
    )
    cp.add_argument(
        "--points", default="50", metavar="N", help="about the rows of each branch, 2 to 10000 [default: 50]"
    )
    cp.add_argument("--output", required=True, help="output file, .csv")


def _vary(text: str) -> tuple[str | None, float, float]:
    """``NAME=START:STOP`` or ``START:STOP`` (no name: the belt's speed)."""
    name, sep, interval = text.rpartition("=")
    if sep and not name.strip():
        raise ValueError(f"--vary expects NAME=START:STOP or START:STOP, got {text!r}")
    parts = interval.split(":")
    if len(parts) != 2:
        raise ValueError(f"--vary expects NAME=START:STOP or START:STOP, got {text!r}")
    start, stop = (validate.parse_float("--vary", part) for part in parts)
    if not start < stop:
        raise ValueError(f"--vary: START:STOP must satisfy START < STOP, got {interval!r}")
    return (name.strip() or None), start, stop


def _as_options(message: str, system: str) -> str:
    """An API message in this command's words: ``cycles:`` becomes the file, ``vary:`` and ``points:`` options."""
    for lead, option in (("cycles: ", f"{system}: "), ("vary:", "--vary:"), ("points:", "--points:")):
        if message.startswith(lead):
            return option + message[len(lead) :]
    return message


def _cells(columns: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The columns for the CSV: a ``nan`` (a value that does not apply) as an empty cell."""
    out = {}
    for name, col in columns.items():
        if col.dtype.kind == "f":
            col = np.array([None if math.isnan(v) else float(v) for v in col], dtype=object)
        out[name] = col
    return out


def run(args: argparse.Namespace, output: Output) -> str:
    """Validate, read the system, reserve the output, find the cycles, write; returns the summary."""
    from lumped.drivers.cycles.api import MAX_POINTS, belt_parameter, cycles, request
    from lumped.drivers.sweep import Progress
    from lumped.model.files import load_system

    if args.vary is not None and len(args.vary) > 1:
        raise ValueError("--vary is given more than once: cycles continues in one parameter")
    vary = None if args.vary is None else _vary(args.vary[0])
    points = validate.parse_int("--points", args.points)
    if not 2 <= points <= MAX_POINTS:
        raise ValueError(f"--points: between 2 and {MAX_POINTS} rows, got {points}")
    check_output(args.output, (".csv",))
    network = load_system(args.system)
    bar = Progress(sys.stderr, True, every=1.0, label="cycles", unit="")  # a line a second: a branch's points
    try:  # every check before the output is reserved and any run is made
        if vary is not None and vary[0] is None:
            vary = (belt_parameter(network), vary[1], vary[2])
        request(network, vary, points)  # type: ignore[arg-type]
        output.create()
        table = cycles(network, vary=vary, points=points, progress=bar)  # type: ignore[arg-type]
    except ValueError as err:
        raise ValueError(_as_options(str(err), args.system)) from None
    output.commit(_cells(table.columns))
    return table.summary
