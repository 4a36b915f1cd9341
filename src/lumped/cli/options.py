"""The reading of the command line shared by its subcommands: the parser, the options of the methods, argv.

The parser prints a user error on one line (:class:`Parser`); ``--method`` and
the methods' options (``--rtol``) come from the registry
(:data:`lumped.drivers.methods.METHODS`); ``--opt VALUE`` is written
``--opt=VALUE`` before argparse sees it (:func:`attach_values`), so that a
value such as ``-1e-4`` reaches the validators, and an option given twice is
refused (:func:`refuse_repeats`).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from lumped.cli.loads import FLAGS as LOAD_FLAGS
from lumped.cli.messages import API_TO_OPTION
from lumped.cli.reference import sweep_option_names
from lumped.drivers.methods import ALIASES, METHODS, OPTIONS, SWEEP_METHODS
from lumped.model.parameters import PARAMETERS, PER_ROW
from lumped.numerics import validate

#: The options of ``response`` that take a value (:mod:`lumped.cli.response`).
RESPONSE_FLAGS = ("--force-on", "--amplitude", "--omega", "--points")
#: The options of ``fit`` (:mod:`lumped.cli.fit`) and ``simulate --sensitivities`` that take a value.
FIT_FLAGS = ("--data", "--free", "--sensitivities")
#: Options that take a value (the rest of the command line is names and values).
TAKES_VALUE = frozenset(API_TO_OPTION.values()) - {"--t-end/--dt"} | {
    "--method",
    "--output",
    "--system",
    "--chunk",
    *LOAD_FLAGS,
    *RESPONSE_FLAGS,
    *FIT_FLAGS,
}
#: Options that describe the single mass, refused with ``--system``.
SINGLE_MASS = frozenset(PARAMETERS[name].option for name in PER_ROW) | frozenset(LOAD_FLAGS)


class Parser(argparse.ArgumentParser):
    """An argument parser that reports a user error on one line, without the usage."""

    def error(self, message: str) -> None:  # one line, status 2, no usage dump
        self.exit(2, f"{self.prog}: error: {message}\n")


class HelpFormatter(argparse.HelpFormatter):
    """Wraps option help at spaces only: "event-locating" is never split at its hyphen.  The description
    and the epilog are filled paragraph by paragraph; a paragraph with indented lines (the methods' table of
    :func:`lumped.cli.reference.methods_help`) is kept as it is."""

    def _split_lines(self, text: str, width: int) -> list[str]:
        import textwrap

        return textwrap.wrap(" ".join(text.split()), width, break_on_hyphens=False)

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        import textwrap

        def fill(p: str) -> str:
            if any(line.startswith(" ") for line in p.splitlines()):
                return p
            return textwrap.fill(" ".join(p.split()), width, initial_indent=indent, subsequent_indent=indent)

        return "\n\n".join(fill(p) for p in text.split("\n\n"))


def add_method_options(parser: argparse.ArgumentParser, sweep: bool = False) -> None:
    """``--method`` and the methods' options (``--rtol``), from the registry; a sweep's lists its methods and
    offers only their options.  The methods themselves are described in the epilog
    (:func:`lumped.cli.reference.methods_help`)."""
    names = SWEEP_METHODS if sweep else tuple(METHODS)
    metavar = "{" + ",".join(names) + "}"
    which = "one of the methods a sweep runs" if sweep else "the method"
    parser.add_argument(
        "--method",
        default="backward-euler",
        metavar=metavar,
        help=f"{which} (listed below with what each runs and its options) [default: backward-euler]",
    )
    for option, users in OPTIONS.values():
        if sweep and option.name not in sweep_option_names():
            continue
        users = tuple(u for u in users if u in names)
        takers = f"of --method {', '.join(users)}"
        text = (
            f"{option.help} {takers} [default: {option.default:g}]"
            if sweep
            else (
                f"{option.help} {takers}, {option.accepted} [default: {option.default:g}]; refused with other methods"
            )
        )
        parser.add_argument(option.flag, default=None, help=text)


def method_options(args: argparse.Namespace) -> dict[str, object]:
    """The options of ``--method`` given on the command line (``--rtol``), checked by the registry."""
    method = METHODS[args.method]
    given = {name: getattr(args, name, None) for name in OPTIONS if getattr(args, name, None) is not None}
    method.takes(given, command_line=True)  # refuses an option the method does not take, before its value is read
    return method.check_options({name: validate.parse_float(name, text) for name, text in given.items()})


def check_method(name: str) -> None:
    """Refuse a ``--method`` that is not in the registry (:data:`lumped.drivers.methods.METHODS`);
    for a former name (:data:`~lumped.drivers.methods.ALIASES`), say on stderr which method it selects."""
    if name not in METHODS:
        raise ValueError(f"--method must be one of {', '.join(METHODS)}; got {name!r}")
    if name in ALIASES:
        print(f"note: --method {name} is an alias of {ALIASES[name]}", file=sys.stderr)


def _is_option(item: str) -> bool:
    """``--name`` (not a value such as ``-1e-4``, ``-inf`` or ``--5``)."""
    return item.startswith("--") and item[2:3].isalpha()


def attach_values(argv: Sequence[str]) -> list[str]:
    """Write ``--opt VALUE`` as ``--opt=VALUE``.

    argparse takes a value such as ``-1e-4`` or ``-inf`` for an option name;
    attached with ``=`` it reaches the validators, which explain what is wrong.
    An option followed by another option (``--mass --output o.csv``) is left
    alone, so that argparse reports the missing value.
    """
    out: list[str] = []
    items = iter(argv)
    for item in items:
        if item in TAKES_VALUE:
            value = next(items, None)
            if value is not None and _is_option(value):
                out.extend([item, value])
                continue
            item = item if value is None else f"{item}={value}"
        out.append(item)
    return out


def refuse_repeats(items: Sequence[str]) -> None:
    """Refuse an option given twice (argparse would silently keep the last)."""
    seen: set[str] = set()
    for item in items:
        name = item.split("=", 1)[0]
        if name in TAKES_VALUE and name in seen:
            raise ValueError(f"{name} is given more than once")
        seen.add(name)


def refuse_single_mass(items: Sequence[str]) -> None:
    """Refuse an option of the single mass (:data:`SINGLE_MASS`) given with ``--system``."""
    single = [i.split("=", 1)[0] for i in items if i.split("=", 1)[0] in SINGLE_MASS]
    if single:
        raise ValueError(
            f"{single[0]} describes the single mass; it cannot be given "
            "with --system, whose file describes the whole system"
        )
