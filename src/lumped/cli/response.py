"""``python -m lumped response``: the forced response curve of a system file's mass (:mod:`lumped.drivers.response`)."""

from __future__ import annotations

import argparse
import sys

from lumped.cli.options import HelpFormatter
from lumped.cli.output import Output, check_output
from lumped.numerics import validate

_DESCRIPTION = """\
Follow the periodic motion of the forcing's period of a system under
P sin(omega t) on one of its masses, from omega = START to STOP (rad/s), by
shooting on the exact period map and pseudo-arclength continuation, folds
included.  One row per point along the branch, the first at START and the last
at STOP when the branch gets there: omega, amplitude_<mass> for each mass (half
of max x minus min x over the period, m), stops_per_period (slip-to-stick
switches of the friction elements that move; a held one's stick is no stop),
stable (true when every Floquet multiplier lies inside the unit circle by more
than the monodromy's computed error), max_multiplier (the largest modulus,
exactly 1 where it is 1 within that error: a marginal motion, stable false) and kind
(regular, fold, period-doubling or stops-change, the located point of a change).
The system: one mass on linear springs and a Bingham or Coulomb dashpot, or a
network of linear springs, Bingham and Coulomb elements and linear dashpots
whose springs hold every mass to the ground; no loads of its own (its x0 and
v0 are not used).  An element that sticks through a whole period may hold any
elongation in its band: it keeps the one it has along the branch, and its
neutral multiplier (exactly 1) is left out of stable and max_multiplier.
With --vary NAME=START:STOP the branch is followed in NAME instead, at the
fixed frequency --omega W: NAME is amplitude (the force's, N) or a numeric
parameter of the file written element.key or mass.key (dashpot.threshold,
spring.stiffness, m.mass); its column comes first, and a range may start on
the edge of the parameter's domain (dashpot.threshold=0:3).
Bounds, checked before any work: omega from 1e-3 of the system's fastest free
oscillation (a period of thousands of phases below it) to 100 times its
slowest natural frequency (above it the amplitude, (P/k)(omega_n/omega)^2, is
below what Newton's tolerance on the period map resolves); the fastest decay
rate at most 1e11 omega; a range at least 1e-6 of its largest value wide;
--points from 2 to 10000.  With --vary, the omega bounds hold at both ends
(not for the undamped linear systems below, whose closed form has its own).

A system without friction that has an undamped mode (springs alone, or
dashpots that leave a mode free) is not continued: its periodic motion is
unique only where omega is not omega_n/j (j = 1, 2, ...; monodromy - I
singular there).  The command writes the closed form X = (K - omega^2 M +
i omega C)^-1 F (amplitude |X|, max_multiplier 1, stable false) at --points
values evenly spaced from START to STOP, leaves out those where the motion is
not unique, and names the points omega_n/j of the range in its summary; a
--vary run at such an --omega is refused."""


def add_parser(sub: argparse._SubParsersAction) -> None:
    """The ``response`` subcommand."""
    rp = sub.add_parser(
        "response",
        help="follow a forced periodic motion in omega: its response curve",
        description=_DESCRIPTION,
        allow_abbrev=False,
        formatter_class=HelpFormatter,
    )
    rp.add_argument("--system", required=True, metavar="FILE.toml", help="the system file (examples/figure3.toml)")
    rp.add_argument("--force-on", required=True, metavar="MASS", help="the name of the mass the sine acts on")
    rp.add_argument("--amplitude", required=True, metavar="P", help="the force amplitude P > 0 (N)")
    rp.add_argument(
        "--omega",
        required=True,
        metavar="START:STOP",
        help="the interval of omega, 0 < START < STOP (rad/s); with --vary, the fixed omega W > 0",
    )
    rp.add_argument(
        "--vary",
        metavar="NAME=START:STOP",
        help="follow NAME (amplitude, or element.key / mass.key of the file) from START to STOP at the fixed --omega",
    )
    rp.add_argument(
        "--points",
        default="200",
        metavar="N",
        help="about the rows of a branch monotone in omega, 2 to 10000 [default: 200]",
    )
    rp.add_argument("--output", required=True, help="output file, .csv or .npz")


#: The API's argument names that this command's messages may begin with -> its options.
_API_NAMES = {
    "force_omega": "--omega",
    "force_amplitude": "--amplitude",
    "t_end": "--omega",
    "omega": "--omega",
    "points": "--points",
    "vary": "--vary",
}


def _interval(text: str, option: str = "--omega") -> tuple[float, float]:
    """``START:STOP`` as two floats."""
    parts = text.split(":")
    if len(parts) != 2:
        raise ValueError(f"{option} expects START:STOP, got {text!r}")
    start, stop = (validate.parse_float(option, part) for part in parts)
    if option == "--omega" and not 0 < start < stop:
        raise ValueError(f"--omega: START:STOP must satisfy 0 < START < STOP, got {text!r}")
    if not start < stop:
        raise ValueError(f"{option}: START:STOP must satisfy START < STOP, got {text!r}")
    return start, stop


def _as_options(message: str) -> str:
    """A message of the API with the names it begins with as this command's options."""
    for name, option in _API_NAMES.items():
        if message.startswith(name + ":"):
            return option + message[len(name) :]
    return message


def _vary(text: str) -> tuple[str, float, float]:
    """``NAME=START:STOP``."""
    name, sep, interval = text.partition("=")
    if not sep or not name.strip():
        raise ValueError(f"--vary expects NAME=START:STOP, got {text!r}")
    return (name.strip(), *_interval(interval, "--vary"))


def run(args: argparse.Namespace, output: Output) -> str:
    """Validate, read the system, reserve the output, follow the branch, write; returns the summary."""
    from lumped.drivers.response.curve import request, response_curve
    from lumped.drivers.response.systems import response_system
    from lumped.drivers.sweep import Progress
    from lumped.model.files import load_system

    amplitude = validate.parse_float("--amplitude", args.amplitude)
    if not amplitude > 0 or amplitude == float("inf"):
        raise ValueError(f"--amplitude must be finite and > 0, got {args.amplitude!r}")
    vary, omega = None, None
    if args.vary is None:
        start, stop = _interval(args.omega)
    else:
        vary, start, stop = _vary(args.vary)
        omega = validate.parse_float("--omega", args.omega)
        if not omega > 0 or omega == float("inf"):
            raise ValueError(f"--omega: with --vary, the fixed omega must be finite and > 0, got {args.omega!r}")
    points = validate.parse_int("--points", args.points)
    if points < 2:
        raise ValueError(f"--points must be at least 2, got {args.points!r}")
    check_output(args.output)
    network = load_system(args.system)
    try:
        response_system(network, args.force_on)
    except ValueError as err:
        raise ValueError(f"{args.system}: {str(err).split(': ', 1)[1]}") from None
    bar = Progress(sys.stderr, True, label="response", unit="")
    try:  # every bound before the output is reserved and any period is run
        request(network, args.force_on, amplitude, start, stop, points, vary, omega)
        output.create()
        curve = response_curve(network, args.force_on, amplitude, start, stop, points, bar, vary, omega)
    except ValueError as err:  # the API's names as this command's options
        raise ValueError(_as_options(str(err))) from None
    output.commit(curve.columns)
    return curve.summary
