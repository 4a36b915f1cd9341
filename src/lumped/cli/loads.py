"""The single mass's load on the command line: a sine, a constant or a table, and no option that does nothing.

* a sine ``P sin(omega t + phase)`` until ``--force-until``: ``--force-amplitude``,
  ``--force-omega``, ``--force-phase`` (parameters of
  :data:`lumped.model.parameters.PARAMETERS`, which a sweep varies too);
* a constant: ``--force-value P`` from ``--force-from T0`` (default 0) to
  ``--force-until T1`` (:class:`~lumped.model.forcing.Constant`);
* a table: ``--force-table FILE.csv`` with header ``t,F``
  (:func:`lumped.model.tables.read_table`).

One kind at a time (a system file adds several loads).  An option that
cannot change the load is refused in one line, naming it and why: today's
trap was ``--force-amplitude 10`` alone, a sine of frequency 0 and phase 0,
which is 0 at all times.  So is a load that cannot act during the run, from
``t = 0`` to ``--t-end``: a sine switched off at ``--force-until 0``, a
constant of 0 or switched on at or after ``--t-end``, a table that is 0 over
the run (its times outside it, or its values 0).
"""

from __future__ import annotations

import argparse
import math

from lumped.model.parameters import PARAMETERS, shown
from lumped.numerics import validate

__all__ = ["FLAGS", "OFF_AT_START", "add_options", "force", "no_sine"]

#: The options of the constant and table loads, which take a value.
FLAGS = ("--force-value", "--force-from", "--force-table")
_SINE = ("force_amplitude", "force_omega", "force_phase")
#: The refusal of a sine that ``--force-until 0`` switches off before it acts (simulate's and sweep's).
OFF_AT_START = "--force-until 0 switches the sine off at t = 0, so it never acts; give a later --force-until, or leave it out (inf)"


def add_options(parser: argparse.ArgumentParser) -> None:
    """``--force-value``, ``--force-from`` and ``--force-table`` (the sine's options are parameters)."""
    parser.add_argument(
        "--force-value",
        default=None,
        metavar="P",
        help="a constant load P (N) instead of the sine, on from --force-from to --force-until",
    )
    parser.add_argument(
        "--force-from", default=None, metavar="T0", help="time (s) at which --force-value comes on [default: 0]"
    )
    parser.add_argument(
        "--force-table",
        default=None,
        metavar="FILE.csv",
        help="a load history instead of the sine: a CSV file with the header t,F, times in s strictly "
        "increasing, linearly interpolated, zero outside its times",
    )


def force(args: argparse.Namespace, values: dict[str, object]) -> object | None:
    """The load the options describe (``None`` for none), from the parsed ``values`` of the sine's options
    and ``--t-end`` (``values["t_end"]``).

    Raises
    ------
    ValueError
        One line naming an option: kinds mixed, an option of another kind,
        an option that changes nothing, a load that cannot act before
        ``--t-end``, a bad value or table.
    """
    given = [o for o in _SINE if values[o] != PARAMETERS[o].default]
    until = values["force_until"] != math.inf
    if args.force_table is not None:
        other = [_flag(o) for o in given] + ["--force-until"] * until + _constant_flags(args)
        if other:
            raise ValueError(f"{other[0]} cannot go with --force-table, whose file is the whole load")
        return _acting_table(_table(args.force_table), args.force_table, values["t_end"])  # type: ignore[arg-type]
    if args.force_value is not None:
        if given:
            raise ValueError(
                f"{_flag(given[0])} cannot go with --force-value: one load at a time "
                "(a system file, --system, adds several)"
            )
        return _acting_constant(_constant(args, values["force_until"], until), values["t_end"])  # type: ignore[arg-type]
    if args.force_from is not None:
        raise ValueError("--force-from goes with --force-value, the constant load it switches on")
    return _acting_sine(_sine(values, given + ["force_until"] * until))


def no_sine(what: str, remedy: str) -> str:
    """The refusal of an amplitude that applies no force (``what``), with its ``remedy``."""
    return (
        f"{what} applies no force: with --force-omega 0 and --force-phase 0, "
        f"P sin(omega t + phase) is 0 at all times; {remedy} for a constant load"
    )


def _flag(name: str) -> str:
    return PARAMETERS[name].option


def _constant_flags(args: argparse.Namespace) -> list[str]:
    return [flag for flag in FLAGS[:2] if getattr(args, flag[2:].replace("-", "_")) is not None]


def _table(path: str) -> object:
    from lumped.model.tables import read_table

    try:
        return read_table(path, "F")
    except ValueError as err:
        raise ValueError(f"--force-table: {err}") from None


def _constant(args: argparse.Namespace, until: float, until_given: bool) -> object:
    from lumped.model.forcing import Constant

    value = validate.parse_float("--force-value", args.force_value)
    start = 0.0 if args.force_from is None else validate.parse_float("--force-from", args.force_from)
    if value == 0 and (args.force_from is not None or until_given):
        flag = "--force-from" if args.force_from is not None else "--force-until"
        raise ValueError(f"{flag} does nothing: --force-value is 0")
    if value == 0:
        raise ValueError("--force-value 0 applies no force; leave it out for a run without load")
    try:
        return Constant(value, start, until)
    except ValueError as err:  # Constant names its fields value, start, until
        words = {"value": "--force-value", "start": "--force-from", "until": "--force-until"}
        raise ValueError(" ".join(words.get(w, w) for w in str(err).split(" "))) from None


def _sine(values: dict[str, object], given: list[str]) -> object | None:
    """The sine of the parameters, ``None`` if it is zero at all times (refused if an option was given for it)."""
    from lumped.model.forcing import SwitchedSine

    p, w, ph, until = (values[n] for n in (*_SINE, "force_until"))
    sine = SwitchedSine(p, w, ph, until)  # type: ignore[arg-type]
    if not sine.is_zero:
        return sine
    if p != 0:  # omega = 0 and sin(phase) = 0: phase 0
        raise ValueError(no_sine(f"--force-amplitude {shown(p)}", f"give --force-omega, or --force-value {shown(p)}"))
    if given:
        raise ValueError(f"{_flag(given[0])} does nothing: --force-amplitude is 0, so the sine is 0 at all times")
    return None


def _acting_sine(sine: object | None) -> object | None:
    """``sine``, or a ``ValueError`` if ``--force-until`` switches it off at ``t = 0``, before it acts."""
    if sine is not None and sine.until == 0:  # type: ignore[attr-defined]
        raise ValueError(OFF_AT_START)
    return sine


def _acting_constant(load: object, t_end: float) -> object:
    """``load``, or a ``ValueError`` if ``--force-from`` switches it on at or after ``--t-end``."""
    if load.start >= t_end:  # type: ignore[attr-defined]
        raise ValueError(
            f"--force-from {_time(load.start)} is not before --t-end {_time(t_end)}: "  # type: ignore[attr-defined]
            "the constant load would come on at or after the end of the run, so it never acts"
        )
    return load


def _acting_table(table: object, path: str, t_end: float) -> object:
    """``table``, or a ``ValueError`` if it is 0 from ``t = 0`` to ``t_end``.

    The force is piecewise linear between the samples, so it is 0 on ``[0, t_end]``
    exactly when it is 0 at both ends and at every sample time between them.
    """
    import numpy as np

    t = table.t  # type: ignore[attr-defined]
    points = np.concatenate([[0.0, t_end], t[(t > 0) & (t < t_end)]])
    if not np.any(table(points)):  # type: ignore[operator]
        raise ValueError(
            f"--force-table: file {path!r} is 0 from t = 0 to --t-end {_time(t_end)} s "
            f"(its times run from {_time(float(t[0]))} to {_time(float(t[-1]))} s), so the load never acts"
        )
    return table


def _time(value: float) -> str:
    """A time as written by hand (:func:`~lumped.model.parameters.shown`) when that is exact, else in full."""
    return shown(value) if float(shown(value)) == value else repr(value)
