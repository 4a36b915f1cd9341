"""Command line: ``python -m lumped COMMAND [options]``, COMMAND one of ``simulate``, ``sweep``, ``response``,
``cycles``, ``fit``.

``cycles`` finds steady sliding on a belt and its limit cycles, or continues them over a parameter
(:mod:`lumped.drivers.cycles`); ``fit`` estimates a system file's parameters from a record (:mod:`lumped.drivers.fit`);
``response`` follows a forced periodic motion in omega
(:mod:`lumped.drivers.response`) and writes its response curve;
``simulate`` writes the columns ``t, x, v, F_s, F_d, F`` to a ``.csv`` or
``.npz`` file and a short summary to stderr; ``sweep`` writes one row of
summaries per parameter set of a grid (:mod:`lumped.drivers.sweep`).  A user
error prints one line and exits with status 2; an interrupted run (Ctrl-C,
SIGTERM, SIGHUP) prints one line and exits with 128 + the signal number.  The
output is written to a temporary file in the target folder, created before the
run (so an unwritable folder is refused at once) and renamed when complete;
every failure removes it.  An output that is one of the command's input files
is refused before anything else (:func:`lumped.cli.output.refuse_inputs`).

This module holds the entry point (:func:`main`) and the parser
(:func:`build_parser`), which imports a subcommand's module only when that
command runs (or for ``--help``), so that ``simulate`` starts as fast as it can;
the rest, one module each:

* :mod:`~lumped.cli.simulate`, :mod:`~lumped.cli.system`,
  :mod:`~lumped.cli.sweep`, :mod:`~lumped.cli.response`, :mod:`~lumped.cli.cycles` and :mod:`~lumped.cli.fit`: the
  subcommands
  (``simulate --system`` in ``system``, ``simulate --sensitivities`` in :mod:`~lumped.cli.sensitivity`);
* :mod:`~lumped.cli.options`: the parser's class, the methods' options and the
  reading of ``argv``; :mod:`~lumped.cli.reference`: the methods' table of
  ``--help`` and of ``book/guide/cli.md``, from the registry;
* :mod:`~lumped.cli.messages`: the API's argument names as options
  (:func:`option_message`);
* :mod:`~lumped.cli.output`: the output file; :mod:`~lumped.cli.signals`: interrupts.
"""

from __future__ import annotations

import argparse
import importlib
import signal
import sys
from collections.abc import Sequence
from types import ModuleType

from lumped.cli.messages import option_message
from lumped.cli.options import Parser, attach_values, refuse_repeats, refuse_single_mass
from lumped.cli.output import Output, refuse_inputs
from lumped.cli.signals import Terminated, signals_unwind

__all__ = ["COMMANDS", "build_parser", "main", "option_message"]

#: The subcommands, each a module of this package with ``add_parser(sub)`` and ``run(args, output)``.  A
#: command's module is imported when it is run (:func:`command_module`), all of them only for ``--help``:
#: ``simulate`` loads no code of the fit, the response curves or the limit cycles.
COMMANDS = ("simulate", "sweep", "response", "cycles", "fit")

_DESCRIPTION = """\
Vibrations of masses on springs and Bingham (or Coulomb) dashpots, solved as
differential-algebraic systems (Darbha, Nakshatrala and Rajagopal): one motion,
a grid of runs, a response curve, the limit cycles on a belt or a fit to a
record, one command each."""

_EXAMPLE = """\
example (free vibration from x0 = 0.5 m, the paper's Figures 11 to 14):
  python -m lumped simulate --x0 0.5 --t-end 4 --output run.csv

a sweep of the initial displacement (one row per x0):
  python -m lumped sweep --vary x0=-1:1:2001 --t-end 4 --output rest.csv

Run "python -m lumped COMMAND --help" for the options of a command ({commands})."""


def command_module(command: str) -> ModuleType:
    """The module of ``command``, one of :data:`COMMANDS`, imported now (``lumped.cli.simulate``, ...)."""
    return importlib.import_module(f"{__name__}.{command}")


class _Version(argparse.Action):
    """``--version``: the distribution's version, read only when asked (reading it costs an import)."""

    def __call__(self, parser: argparse.ArgumentParser, *_: object) -> None:
        import lumped

        print(f"lumped {lumped.__version__}")  # to stdout, as argparse's own version action
        parser.exit()


def build_parser(commands: Sequence[str] = COMMANDS) -> argparse.ArgumentParser:
    """The argument parser (defaults are the paper's values, section 3), with the subcommands ``commands``.

    Abbreviated option names are not accepted: ``--x0`` and ``--x00`` must not
    silently mean the same thing, and every option's value is checked by name.
    ``--method`` lists the names of :data:`lumped.drivers.methods.METHODS`; a bad one is
    refused by :func:`lumped.cli.options.check_method` with the API's message.
    :func:`main` builds the parser of the one command given, which parses its
    arguments as the whole parser does, and the whole parser otherwise (``--help``, a bad command).
    """
    parser = Parser(
        prog="lumped",
        description=_DESCRIPTION,
        allow_abbrev=False,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    parser.add_argument("--version", action=_Version, nargs=0, help="show program's version number and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True, parser_class=Parser)
    for command in commands:
        command_module(command).add_parser(sub)
    parser.epilog = _EXAMPLE.format(commands=", ".join(COMMANDS))  # each command, one line of help above
    return parser


def _parse(argv: Sequence[str]) -> argparse.Namespace:
    """Parse the command line; raises SystemExit (usage, --help) or ValueError."""
    items = attach_values(argv)
    known = bool(items) and items[0] in COMMANDS
    if known:
        refuse_repeats([i for i in items[1:] if not i.startswith("--vary")])
    args = build_parser(items[:1] if known else COMMANDS).parse_args(items)
    if getattr(args, "system", None) is not None and args.command not in ("response", "cycles", "fit"):
        refuse_single_mass(items[1:])
    return args


def _fail(status: int, message: str, command: str = "simulate") -> int:
    """Print ``message`` on one line to stderr; returns ``status``."""
    print(f"lumped {command}: " + " ".join(message.split()), file=sys.stderr)  # one line
    return status


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point; returns the exit status (0, 2 for a user error, 128 + signal)."""
    output = None
    argv = list(sys.argv[1:] if argv is None else argv)
    command = argv[0] if argv[:1] and argv[0] in COMMANDS else "simulate"
    try:
        with signals_unwind():
            args = _parse(argv)
            refuse_inputs(args)
            output = Output(args.output) if args.output is not None else None
            summary = command_module(args.command).run(args, output)
    except SystemExit as stop:  # argparse: usage errors (status 2) and --help (status 0)
        return int(stop.code or 0)
    except (KeyboardInterrupt, Terminated) as stop:
        done = f"wrote {output.path}" if output and output.written else "no output written"
        return _fail(128 + getattr(stop, "signum", signal.SIGINT), f"interrupted; {done}", command)
    except ValueError as err:
        return _fail(2, "error: " + option_message(str(err)), command)
    except MemoryError:
        return _fail(2, "error: out of memory; raise --save-every or --dt", command)
    except ArithmeticError as err:  # the API should refuse such input first: report it
        what = getattr(args, "method", command)
        return _fail(2, f"error: the {what} run failed: {type(err).__name__}: {err}", command)
    finally:
        if output is not None:
            output.discard()
    how = "" if command in ("response", "cycles", "fit") else f" ({args.method})"
    wrote = f"; wrote {args.output}" if args.output is not None else ""
    print(f"lumped {command}{how}: {summary}{wrote}", file=sys.stderr)
    return 0
