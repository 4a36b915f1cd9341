"""Command line: ``python -m lumped simulate [options]``.

Writes the columns ``t, x, v, F_s, F_d, F`` to a ``.csv`` or ``.npz`` file and a
short summary to stderr.  A user error prints one line and exits with status 2.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import tempfile
from collections.abc import Sequence

import numpy as np

from lumped import _validate

__all__ = ["main", "build_parser"]

_CHECKS = {  # option -> (validator, API keyword)
    "mass": _validate.positive,
    "stiffness": _validate.positive,
    "gamma": _validate.positive_or_inf,
    "threshold": _validate.non_negative,
    "x0": _validate.finite,
    "v0": _validate.finite,
    "force_amplitude": _validate.finite,
    "force_omega": _validate.finite,
    "force_phase": _validate.finite,
    "force_until": _validate.time_or_inf,
    "t_end": _validate.positive,
    "dt": _validate.positive,
    "save_every": _validate.positive_int,
}


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, status 2, no usage dump
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (defaults are the paper's values, section 3)."""
    parser = _Parser(prog="lumped", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    sim = sub.add_parser("simulate", help="integrate one motion and write it to a file")
    options = [
        ("--mass", "1", "mass m > 0 (kg)"),
        ("--stiffness", "100", "spring constant k > 0 (N/m)"),
        ("--gamma", "1", "Bingham slope gamma > 0 (m/(N s)); inf for Coulomb"),
        ("--threshold", "1", "static threshold mu_s N_f >= 0 (N)"),
        ("--x0", "0", "initial displacement (m)"),
        ("--v0", "0", "initial velocity (m/s)"),
        ("--force-amplitude", "0", "forcing amplitude P (N)"),
        ("--force-omega", "0", "forcing angular frequency (rad/s)"),
        ("--force-phase", "0", "forcing phase (rad)"),
        ("--force-until", "inf", "time after which the force is zero (s)"),
        ("--t-end", "2", "final time > 0 (s)"),
        ("--dt", "1e-4", "time step > 0 (s)"),
        ("--save-every", "1", "keep every K-th grid point"),
    ]
    for flag, default, text in options:
        sim.add_argument(flag, default=default, help=f"{text} [default: {default}]")
    sim.add_argument("--method", default="backward-euler",
                     help="backward-euler (Algorithm 1) or exact [default: backward-euler]")  # fmt: skip
    sim.add_argument("--output", required=True, help="output file, .csv or .npz")
    return parser


def _clean(args: argparse.Namespace) -> dict[str, object]:
    """Validate every option, naming it as the user typed it."""
    from lumped.simulate import METHODS

    values = {}
    for name, check in _CHECKS.items():
        option = "--" + name.replace("_", "-")
        parse = _validate.parse_int if check is _validate.positive_int else _validate.parse_float
        values[name] = check(option, parse(option, getattr(args, name)))
    if args.method not in METHODS:
        raise ValueError(f"--method must be one of {', '.join(METHODS)}; got {args.method!r}")
    suffix = os.path.splitext(args.output)[1].lower()
    if suffix not in (".csv", ".npz"):
        raise ValueError(f"--output must end in .csv or .npz, got {args.output!r}")
    folder = os.path.dirname(os.path.abspath(args.output))
    if not os.path.isdir(folder):
        raise ValueError(f"--output: directory {folder!r} does not exist")
    n = _validate.step_count(values["t_end"], values["dt"], "--t-end/--dt")  # type: ignore[arg-type]
    try:
        _validate.output_size(n, values["save_every"])  # type: ignore[arg-type]
    except ValueError as err:
        message = str(err).replace("save_every", "--save-every").replace(" dt", " --dt")
        raise ValueError(message) from None
    return values


def _write(path: str, columns: dict[str, np.ndarray]) -> None:
    """Write atomically: a temporary file in the same folder, then rename."""
    folder = os.path.dirname(os.path.abspath(path))
    suffix = os.path.splitext(path)[1].lower()
    fd, tmp = tempfile.mkstemp(dir=folder, suffix=suffix)
    try:
        with os.fdopen(fd, "wb") as fh:
            if suffix == ".npz":
                np.savez(fh, **columns)
            else:
                data = np.column_stack(list(columns.values()))
                np.savetxt(fh, data, fmt="%.17g", delimiter=",", header=",".join(columns),
                           comments="")  # fmt: skip
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def _run(values: dict[str, object], method: str, output: str) -> str:
    from lumped.event_driven import solve_exact
    from lumped.forcing import SwitchedSine
    from lumped.simulate import simulate
    from lumped.system import Oscillator

    v = values
    osc = Oscillator.bingham(v["mass"], v["stiffness"], v["threshold"], v["gamma"])  # type: ignore[arg-type]
    force = SwitchedSine(v["force_amplitude"], v["force_omega"], v["force_phase"],
                         v["force_until"])  # type: ignore[arg-type]  # fmt: skip
    common = dict(x0=v["x0"], v0=v["v0"], force=None if force.is_zero else force)
    if method == "exact":  # keep the solution: its rest time is an event, not a grid point
        sol = solve_exact(osc, v["t_end"], **common)  # type: ignore[arg-type]
        traj = sol.sample(v["dt"], v["save_every"])  # type: ignore[arg-type]
        rest_time, rest_position = sol.rest_time, sol.rest_position
    else:
        traj = simulate(osc, v["t_end"], v["dt"], method=method, save_every=v["save_every"],
                        **common)  # type: ignore[arg-type]  # fmt: skip
        rest_time, rest_position = traj.rest_time, traj.rest_position
    _write(output, traj.columns())
    if math.isnan(rest_time):
        return f"still moving at t = {traj.t[-1]:.6g} s (x = {traj.x[-1]:.9g} m)"
    return f"at rest from t = {rest_time:.10g} s at x = {rest_position:.10g} m"


def _attach_values(argv: Sequence[str]) -> list[str]:
    """Write ``--opt VALUE`` as ``--opt=VALUE``.

    argparse takes a value such as ``-1e-4`` or ``-inf`` for an option name;
    attached with ``=`` it reaches the validators, which explain what is wrong.
    """
    takes_value = {"--" + name.replace("_", "-") for name in _CHECKS} | {"--method", "--output"}
    out: list[str] = []
    items = iter(argv)
    for item in items:
        value = next(items, None) if item in takes_value else None
        out.append(item if value is None else f"{item}={value}")
    return out


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status."""
    parser = build_parser()
    try:
        args = parser.parse_args(_attach_values(sys.argv[1:] if argv is None else argv))
    except SystemExit as stop:  # usage errors (status 2) and --help (status 0)
        return int(stop.code or 0)
    try:
        values = _clean(args)
        summary = _run(values, args.method, args.output)
    except ValueError as err:
        print(f"lumped simulate: error: {err}", file=sys.stderr)
        return 2
    except MemoryError:
        print("lumped simulate: error: out of memory; raise --save-every or --dt", file=sys.stderr)
        return 2
    print(f"lumped simulate ({args.method}): {summary}; wrote {args.output}", file=sys.stderr)
    return 0
