"""Command line: ``python -m lumped simulate [options]`` and ``python -m lumped sweep [options]``.

``simulate`` writes the columns ``t, x, v, F_s, F_d, F`` to a ``.csv`` or
``.npz`` file and a short summary to stderr; ``sweep`` writes one row of
summaries per parameter set of a grid (:mod:`lumped.drivers.sweep`).  A user error prints one line and exits with status 2;
an interrupted run (Ctrl-C, SIGTERM, SIGHUP) prints one line and exits with
128 + the signal number.  The output is written to a temporary file in the
target folder, created before the run (so an unwritable folder is refused at
once) and renamed when complete; every failure removes it.
"""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import re
import signal
import stat
import sys
import tempfile
import threading
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, BinaryIO

import numpy as np

from lumped import __version__
from lumped.drivers.methods import METHODS, OPTIONS, SWEEP_METHODS
from lumped.model.parameters import PARAMETERS, PER_ROW
from lumped.numerics import validate

if TYPE_CHECKING:
    from lumped.model.trajectory import Trajectory

__all__ = ["main", "build_parser"]

#: The API's argument names (what its ``ValueError`` messages begin with) -> options; the
#: options that set the system, its motion and the grid (their defaults, help and checks)
#: are those of :data:`lumped.model.parameters.PARAMETERS`.
_API_TO_OPTION = (
    {name: p.option for name, p in PARAMETERS.items()}
    | {
        "t_end/dt": "--t-end/--dt",
        "vary": "--vary",
        "periods": "--periods",
        "method": "--method",
    }
    | {name: option.flag for name, (option, _) in OPTIONS.items()}
)
_LEADING_NAME = re.compile(r"^([a-z][a-z0-9_/]*)(?=:| must)")
#: Options that take a value (the rest of the command line is names and values).
_TAKES_VALUE = frozenset(_API_TO_OPTION.values()) - {"--t-end/--dt"} | {"--method", "--output", "--system"}
#: Options that describe the single mass, refused with ``--system``.
_SINGLE_MASS = frozenset(PARAMETERS[name].option for name in PER_ROW)
#: Signals that unwind through the cleanup while a run is under way (SIGINT
#: already does, as KeyboardInterrupt).
_UNWIND_SIGNALS = tuple(getattr(signal, n) for n in ("SIGTERM", "SIGHUP") if hasattr(signal, n))


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line, status 2, no usage dump
        self.exit(2, f"{self.prog}: error: {message}\n")


class _Terminated(BaseException):
    """Raised by the SIGTERM/SIGHUP handler; a BaseException, like KeyboardInterrupt,
    so that no ``except Exception`` on the way swallows it."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


_DESCRIPTION = """\
Vibrations of a mass on a linear spring and a Bingham (or Coulomb) dashpot,
solved as a differential-algebraic system (Darbha, Nakshatrala and Rajagopal).
The simulate command integrates one motion and writes t, x, v, F_s, F_d, F to
a .csv or .npz file; the sweep command writes one row of summaries (rest time
and position, largest |x|, stops, ...) per parameter set of a grid."""

_EXAMPLE = """\
example (free vibration from x0 = 0.5 m, the paper's Figures 11 to 14):
  python -m lumped simulate --x0 0.5 --t-end 4 --output run.csv

a sweep of the initial displacement (one row per x0):
  python -m lumped sweep --vary x0=-1:1:2001 --t-end 4 --output rest.csv

Run "python -m lumped simulate --help" or "python -m lumped sweep --help" for the options."""


def _method_help() -> str:
    """One line per registered method (:data:`lumped.drivers.methods.METHODS`): its name and its description."""
    lines = (f"{name}: {m.description}" for name, m in METHODS.items())
    return "; ".join(lines) + " [default: backward-euler]"


def _add_method_options(parser: argparse.ArgumentParser, sweep: bool = False) -> None:
    """``--method`` and the methods' options (``--rtol``), from the registry; a sweep's lists its methods."""
    names = SWEEP_METHODS if sweep else tuple(METHODS)
    metavar = "{" + ",".join(names) + "}"
    parser.add_argument(
        "--method", default="backward-euler", metavar=metavar, **({} if sweep else {"help": _method_help()})
    )
    for option, users in OPTIONS.values():
        takers = f"of --method {', '.join(users)}"
        text = (
            f"{option.help} {takers} [default: {option.default:g}]"
            if sweep
            else (
                f"{option.help} {takers}, {option.accepted} [default: {option.default:g}]; refused with other methods"
            )
        )
        parser.add_argument(option.flag, default=None, help=text)


class _HelpFormatter(argparse.HelpFormatter):
    """Wraps option help at spaces only: "event-capturing" is never split at its hyphen."""

    def _split_lines(self, text: str, width: int) -> list[str]:
        import textwrap

        return textwrap.wrap(" ".join(text.split()), width, break_on_hyphens=False)


class _SweepHelpFormatter(_HelpFormatter):
    """Option help wrapped as :class:`_HelpFormatter`; the description keeps its paragraphs."""

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        import textwrap

        paragraphs = text.split("\n\n")
        return "\n\n".join(
            textwrap.fill(" ".join(p.split()), width, initial_indent=indent, subsequent_indent=indent)
            for p in paragraphs
        )


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (defaults are the paper's values, section 3).

    Abbreviated option names are not accepted: ``--x0`` and ``--x00`` must not
    silently mean the same thing, and every option's value is checked by name.
    ``--method`` lists the names of :data:`lumped.drivers.methods.METHODS`; a bad one is
    refused by :func:`_clean` with the API's message.
    """
    parser = _Parser(
        prog="lumped",
        description=_DESCRIPTION,
        epilog=_EXAMPLE,
        allow_abbrev=False,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--version", action="version", version=f"lumped {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True, parser_class=_Parser)
    sim = sub.add_parser(
        "simulate",
        help="integrate one motion and write it to a file",
        description="Integrate one motion and write it to a .csv or .npz file.",
        allow_abbrev=False,
        formatter_class=_HelpFormatter,
    )
    for p in PARAMETERS.values():
        sim.add_argument(p.option, default=p.default_text, help=f"{p.help} [default: {p.default_text}]")
    sim.add_argument(
        "--system",
        default=None,
        metavar="FILE.toml",
        help="a network of masses and elements described in a TOML file (see "
        "book/guide/systems.md, example examples/figure3.toml); only --t-end, --dt, --save-every, --method, "
        f"{', '.join(o.flag for o, _ in OPTIONS.values())}, --output go with it "
        f"(a method other than {', '.join(n for n, m in METHODS.items() if m.runs_networks)} needs one mass)",
    )
    _add_method_options(sim)
    required = sim.add_argument_group("required arguments")
    required.add_argument("--output", required=True, help="output file, .csv or .npz")
    _add_sweep(sub)
    return parser


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


def _add_sweep(sub: argparse._SubParsersAction) -> None:
    """The ``sweep`` subcommand: the single-mass options of ``simulate`` and its own."""
    from lumped.drivers import sweep

    limits = dict(
        rows=sweep.MAX_ROWS,
        memory=sweep.MAX_MEMORY_BYTES / 1024**3,
        file=validate.MAX_OUTPUT_BYTES / 1024**3,
        csv=sweep.FILE_BYTES_PER_VALUE[".csv"],
        npz=sweep.FILE_BYTES_PER_VALUE[".npz"],
        seconds=validate.MAX_SECONDS,
    )
    sw = sub.add_parser(
        "sweep",
        help="run a grid of parameter sets and write one row of summaries per set",
        description=_SWEEP_DESCRIPTION.format(**limits),
        allow_abbrev=False,
        formatter_class=_SweepHelpFormatter,
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
    _add_method_options(sw, sweep=True)
    sw.add_argument("--output", required=True, help="output file, .csv or .npz")


def option_message(message: str) -> str:
    """An API error message in the command line's words.

    The API's messages begin with the argument's name followed by ``:`` or
    `` must`` (``"force_amplitude: ..."``); that name becomes the option
    (``"--force-amplitude: ..."``).  Only the leading name is replaced: the
    rest may be a formula or echo the user's value.  A message that does not
    begin with an argument name is returned unchanged.

    Parameters
    ----------
    message : str
        The text of a ``ValueError`` raised by :mod:`lumped`.

    Returns
    -------
    str
    """
    lead = _LEADING_NAME.match(message)
    if lead is None or lead.group(1) not in _API_TO_OPTION:
        return message
    return _API_TO_OPTION[lead.group(1)] + message[lead.end() :]


def _is_option(item: str) -> bool:
    """``--name`` (not a value such as ``-1e-4``, ``-inf`` or ``--5``)."""
    return item.startswith("--") and item[2:3].isalpha()


def _attach_values(argv: Sequence[str]) -> list[str]:
    """Write ``--opt VALUE`` as ``--opt=VALUE``.

    argparse takes a value such as ``-1e-4`` or ``-inf`` for an option name;
    attached with ``=`` it reaches the validators, which explain what is wrong.
    An option followed by another option (``--mass --output o.csv``) is left
    alone, so that argparse reports the missing value.
    """
    out: list[str] = []
    items = iter(argv)
    for item in items:
        if item in _TAKES_VALUE:
            value = next(items, None)
            if value is not None and _is_option(value):
                out.extend([item, value])
                continue
            item = item if value is None else f"{item}={value}"
        out.append(item)
    return out


def _refuse_repeats(items: Sequence[str]) -> None:
    """Refuse an option given twice (argparse would silently keep the last)."""
    seen: set[str] = set()
    for item in items:
        name = item.split("=", 1)[0]
        if name in _TAKES_VALUE and name in seen:
            raise ValueError(f"{name} is given more than once")
        seen.add(name)


def _parse(argv: Sequence[str]) -> argparse.Namespace:
    """Parse the command line; raises SystemExit (usage, --help) or ValueError."""
    items = _attach_values(argv)
    if items[:1] in (["simulate"], ["sweep"]):
        _refuse_repeats([i for i in items[1:] if not i.startswith("--vary")])
    args = build_parser().parse_args(items)
    if getattr(args, "system", None) is not None:
        single = [i.split("=", 1)[0] for i in items[1:] if i.split("=", 1)[0] in _SINGLE_MASS]
        if single:
            raise ValueError(
                f"{single[0]} describes the single mass; it cannot be given "
                "with --system, whose file describes the whole system"
            )
    return args


def _check_output(path: str) -> str:
    """Refuse an ``--output`` that cannot name the file to write, with the reason."""
    name = os.path.basename(path)
    if not path.strip():
        raise ValueError("--output expects a file name, got an empty value")
    if os.path.isdir(path) or not name:
        raise ValueError(f"--output: {path!r} is a directory; name a .csv or .npz file")
    if name.lower() in (".csv", ".npz"):
        raise ValueError(f"--output: {path!r} has no file name before the suffix")
    if os.path.splitext(name)[1].lower() not in (".csv", ".npz"):
        raise ValueError(f"--output must end in .csv or .npz, got {path!r}")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise ValueError(f"--output: directory {folder!r} does not exist")
    return path


def _clean(args: argparse.Namespace) -> dict[str, object]:
    """Parse and validate every option; the messages use the API's names."""
    values: dict[str, object] = {}
    for name, p in PARAMETERS.items():
        parse = validate.parse_int if p.integer else validate.parse_float
        values[name] = p.check(name, parse(name, getattr(args, name)))
    if args.method not in METHODS:
        raise ValueError(f"--method must be one of {', '.join(METHODS)}; got {args.method!r}")
    values["options"] = _method_options(args)
    _check_output(args.output)
    n = validate.step_count(values["t_end"], values["dt"])  # type: ignore[arg-type]
    validate.output_size(n, values["save_every"])  # type: ignore[arg-type]
    return values


def _method_options(args: argparse.Namespace) -> dict[str, object]:
    """The options of ``--method`` given on the command line (``--rtol``), checked by the registry."""
    method = METHODS[args.method]
    given = {name: getattr(args, name) for name in OPTIONS if getattr(args, name) is not None}
    method.takes(given)  # refuses an option the method does not take, before its value is read
    return method.check_options({name: validate.parse_float(name, text) for name, text in given.items()})


def _new_file_mode(path: str) -> int:
    """Mode for the output: that of the file it replaces, else 0o666 less the umask."""
    with contextlib.suppress(OSError):
        return stat.S_IMODE(os.stat(path).st_mode)
    umask = os.umask(0)  # reading the umask means setting it; put it back at once
    os.umask(umask)
    return 0o666 & ~umask


@contextlib.contextmanager
def _signals_blocked() -> Iterator[None]:
    """Hold back the unwinding signals (so a rename and its record are not split)."""
    held = {signal.SIGINT, *_UNWIND_SIGNALS}
    if not hasattr(signal, "pthread_sigmask"):  # not POSIX: nothing to hold
        yield
        return
    old = signal.pthread_sigmask(signal.SIG_BLOCK, held)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, old)


class _Output:
    """The output file: a temporary file in the target folder, then a rename.

    :meth:`create` makes the temporary file (before the run, so that a folder
    that cannot be written is refused at once), :meth:`commit` fills and
    renames it, :meth:`discard` removes it unless committed.  ``written`` tells
    whether the rename happened.
    """

    def __init__(self, path: str) -> None:
        self.path = path
        self.tmp: str | None = None
        self.written = False

    def create(self) -> None:
        """Create the temporary file with the final file's mode."""
        folder = os.path.dirname(os.path.abspath(self.path))
        try:
            fd, self.tmp = tempfile.mkstemp(dir=folder, prefix=os.path.basename(self.path) + ".", suffix=".part")
            try:
                os.fchmod(fd, _new_file_mode(self.path))  # mkstemp's 0o600 ignores the umask
            finally:
                os.close(fd)
        except OSError as err:
            why = err.strerror or str(err)
            raise ValueError(f"--output: cannot create a file in {folder!r}: {why}") from None

    def commit(self, columns: dict[str, np.ndarray]) -> None:
        """Write ``columns`` to the temporary file and rename it to the output."""
        assert self.tmp is not None, "create() first"
        try:
            with open(self.tmp, "wb") as fh:
                _dump(fh, columns, os.path.splitext(self.path)[1].lower())
            with _signals_blocked():
                os.replace(self.tmp, self.path)
                self.written = True
        except OSError as err:
            why = err.strerror or str(err)
            raise ValueError(f"--output: cannot write {self.path!r}: {why}") from None

    def discard(self) -> None:
        """Remove the temporary file if it is still there."""
        if self.tmp is not None and not self.written:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(self.tmp)


def _dump(fh: BinaryIO, columns: dict[str, np.ndarray], suffix: str) -> None:
    """Write the columns as ``.npz`` arrays or as ``.csv`` with a header line."""
    if suffix == ".npz":
        np.savez(fh, **columns)
    else:
        data = np.column_stack(list(columns.values()))
        np.savetxt(fh, data, fmt="%.17g", delimiter=",", header=",".join(columns), comments="")


def _compute(values: dict[str, object], method: str) -> Trajectory:
    """Run ``method`` through the driver :func:`lumped.drivers.simulation.simulate`."""
    from lumped.drivers.simulation import simulate
    from lumped.model.forcing import SwitchedSine
    from lumped.model.oscillator import Oscillator

    v = values
    osc = Oscillator.bingham(v["mass"], v["stiffness"], v["threshold"], v["gamma"])  # type: ignore[arg-type]
    force = SwitchedSine(v["force_amplitude"], v["force_omega"], v["force_phase"], v["force_until"])  # type: ignore[arg-type]
    return simulate(
        osc,
        v["t_end"],
        v["dt"],
        x0=v["x0"],
        v0=v["v0"],  # type: ignore[arg-type]
        force=None if force.is_zero else force,
        method=method,
        save_every=v["save_every"],
        **v["options"],  # type: ignore[arg-type]
    )  # type: ignore[arg-type]


def _summary(traj: Trajectory) -> str:
    """Rest time and position as the method found them, or the last state."""
    if math.isnan(traj.rest_time):
        return f"still moving at t = {traj.t[-1]:.6g} s (x = {traj.x[-1]:.9g} m)"
    return f"at rest from t = {traj.rest_time:.10g} s at x = {traj.rest_position:.10g} m"


def _raise_terminated(signum: int, frame: object) -> None:
    raise _Terminated(signum)


@contextlib.contextmanager
def _signals_unwind() -> Iterator[None]:
    """While active, SIGTERM and SIGHUP raise :class:`_Terminated`.

    Signals that the caller ignores (``nohup``) stay ignored; the previous
    handlers are restored on exit.  Outside the main thread nothing changes
    (Python delivers signals to the main thread only).
    """
    old = {}
    if threading.current_thread() is threading.main_thread():
        for sig in _UNWIND_SIGNALS:
            if signal.getsignal(sig) is not signal.SIG_IGN:
                old[sig] = signal.signal(sig, _raise_terminated)
    try:
        yield
    finally:
        for sig, handler in old.items():
            signal.signal(sig, signal.SIG_DFL if handler is None else handler)


def _simulate_system(args: argparse.Namespace, output: _Output) -> str:
    """``--system``: read the file, reserve the output, run the network, write."""
    from lumped.drivers.simulation import solve
    from lumped.model.files import load_system
    from lumped.model.problem import Problem

    values = {
        name: PARAMETERS[name].check(name, parse(name, getattr(args, name)))
        for name, parse in (
            ("t_end", validate.parse_float),
            ("dt", validate.parse_float),
            ("save_every", validate.parse_int),
        )
    }
    if args.method not in METHODS:
        raise ValueError(f"--method must be one of {', '.join(METHODS)}; got {args.method!r}")
    options = _method_options(args)
    _check_output(args.output)
    network = load_system(args.system)
    if not METHODS[args.method].runs_networks:
        _one_mass(network, args)
    output.create()
    try:
        problem = Problem(network, values["t_end"])
        traj = solve(problem, values["dt"], method=args.method, save_every=values["save_every"], **options)
    except ValueError as err:
        raise ValueError(_system_message(str(err), args.system, network)) from None
    output.commit(traj.system_columns(os.path.splitext(args.output)[1].lower()))
    return traj.summary()


#: The single-mass API's parameter names -> (table, key) of a one-mass system file.
_SYSTEM_ENTRIES = {
    "mass": ("mass", "mass"),
    "x0": ("mass", "x0"),
    "v0": ("mass", "v0"),
    "stiffness": ("element", "stiffness"),
    "threshold": ("element", "threshold"),
    "gamma": ("element", "gamma"),
    "force_amplitude": ("force", "amplitude"),
    "force_omega": ("force", "omega"),
    "force_phase": ("force", "phase"),
    "force_until": ("force", "until"),
}


def _system_message(message: str, path: str, network: object) -> str:
    """A run's error in the words of the system file: the entry and key for a single-mass parameter.

    The runs of a one-mass file go through the single-mass API, whose messages
    begin with its parameter's name (``x0: ...``); ``--x0`` is not an option
    here, so the file, the entry and its key are named instead.
    """
    lead = _LEADING_NAME.match(message)
    if lead is None or lead.group(1) not in _SYSTEM_ENTRIES:
        return message
    table, key = _SYSTEM_ENTRIES[lead.group(1)]
    entries = {
        "mass": [repr(m.name) for m in network.masses],  # type: ignore[attr-defined]
        "element": [repr(e.name) for e in network.elements if hasattr(e, key)],  # type: ignore[attr-defined]
        "force": [f"on {f.on!r}" for f in network.loads],  # type: ignore[attr-defined]
    }[table]
    where = " ".join([f"[[{table}]]", ", ".join(entries), key]).replace("  ", " ")
    return f"system file {path!r}: {where}{message[lead.end() :]}"


def _one_mass(network: object, args: argparse.Namespace) -> None:
    """Refuse a network that the single-mass ``--method`` cannot run (not one mass, or a law
    the method does not take), naming the file."""
    from lumped.model.problem import one_mass_form

    try:
        form = one_mass_form(network)  # type: ignore[arg-type]
    except ValueError as err:
        where = f"{args.system} {err}" if str(err).startswith("has ") else f"{args.system}: {err}"
        raise ValueError(f"--method {args.method} needs a one-mass system; {where}") from None
    reason = METHODS[args.method].refusal(form.oscillator)
    if reason is not None:
        raise ValueError(f"{reason} ({args.system})")


def _simulate(args: argparse.Namespace, output: _Output) -> str:
    """Validate, reserve the output file, run, write; returns the summary."""
    if args.system is not None:
        return _simulate_system(args, output)
    values = _clean(args)
    output.create()
    traj = _compute(values, args.method)
    output.commit(traj.columns())
    return _summary(traj)


def _sweep_spec(args: argparse.Namespace):  # noqa: ANN202 (a lumped.drivers.sweep.SweepSpec)
    """Parse and validate the sweep's options into a :class:`~lumped.drivers.sweep.SweepSpec`.

    The grid's size (rows, memory, file, time) is checked from the ``--vary``
    counts before any of its values is built or checked.
    """
    from lumped.drivers.sweep import SWEEP_METHODS, SweepSpec, check_size, vary_text

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
    options = _method_options(args) if args.method in METHODS else {}
    t_end, dt = values.pop("t_end"), values.pop("dt")
    periods = validate.parse_int("periods", args.periods)
    suffix = os.path.splitext(_check_output(args.output))[1].lower()
    if args.method in SWEEP_METHODS:  # another is refused by SweepSpec.build
        forced = values["force_amplitude"] != 0 or any(v.name == "force_amplitude" and not v.all_zero for v in varies)
        n_steps = validate.step_count(t_end, dt)
        check_size([v.count for v in varies], n_steps=n_steps, method=args.method, forced=forced, output=suffix)
    axes = [v.axis() for v in varies]
    return SweepSpec.build(
        axes, t_end=t_end, dt=dt, method=args.method, periods=periods, options=options, output=suffix, **values
    )


def _sweep(args: argparse.Namespace, output: _Output) -> str:
    """Validate, refuse what is too large, reserve the output, run the rows, write."""
    import time

    from lumped.drivers.sweep import Progress, run_sweep

    spec = _sweep_spec(args)
    output.create()
    start = time.perf_counter()
    long = spec.seconds() > 5.0
    rows = run_sweep(spec, progress=Progress(sys.stderr, sys.stderr.isatty() or long))
    output.commit(rows)
    return f"{spec.rows} rows in {time.perf_counter() - start:.3g} s"


def _fail(status: int, message: str, command: str = "simulate") -> int:
    print(f"lumped {command}: " + " ".join(message.split()), file=sys.stderr)  # one line
    return status


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status (0, 2 for a user error, 128 + signal)."""
    output = None
    argv = list(sys.argv[1:] if argv is None else argv)
    command = "sweep" if argv[:1] == ["sweep"] else "simulate"
    try:
        with _signals_unwind():
            args = _parse(argv)
            output = _Output(args.output)
            summary = (_sweep if command == "sweep" else _simulate)(args, output)
    except SystemExit as stop:  # argparse: usage errors (status 2) and --help (status 0)
        return int(stop.code or 0)
    except (KeyboardInterrupt, _Terminated) as stop:
        done = f"wrote {output.path}" if output and output.written else "no output written"
        return _fail(128 + getattr(stop, "signum", signal.SIGINT), f"interrupted; {done}", command)
    except ValueError as err:
        return _fail(2, "error: " + option_message(str(err)), command)
    except MemoryError:
        return _fail(2, "error: out of memory; raise --save-every or --dt", command)
    except ArithmeticError as err:  # the API should refuse such input first: report it
        return _fail(2, f"error: the {args.method} run failed: {type(err).__name__}: {err}", command)
    finally:
        if output is not None:
            output.discard()
    print(f"lumped {command} ({args.method}): {summary}; wrote {args.output}", file=sys.stderr)
    return 0
