"""Measured records read from CSV files: :func:`read_record`, the times and the displacements of some masses.

The format, for ``python -m lumped fit --data``: optional comment lines
beginning with ``#`` at the top (say where the record comes from), a header
naming the columns, then one row of numbers per line.  The columns are ``t``
(s, finite, from 0 on, strictly increasing) and ``x_<mass>`` (m, finite) for
each measured mass (any subset of the system's); other columns are allowed
and not read, so that a ``simulate --system`` output can be read as a record.
The fields read are plain decimal numbers (``-1.5e-3``; not ``0.0_4``, which
Python's ``float`` takes for 0.04).  A displacement may not exceed
:func:`largest_displacement` in magnitude, beyond which the sum of the
squared residuals of a fit would overflow.  Blank lines may only end the
file.  Every problem is a ``ValueError`` of one line naming the file and the
line or the column; :func:`check_record` checks a :class:`Record` built in
Python the same way, naming the argument.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from lumped.model.tables import plain_float, read_lines

__all__ = ["Record", "check_record", "largest_displacement", "read_record"]


class Record(NamedTuple):
    """Times ``t`` (n,) and, for each measured mass by name, its displacements ``x`` (n,)."""

    t: np.ndarray
    x: dict[str, np.ndarray]


def largest_displacement(n: int) -> float:
    """The largest ``|x|`` (m) of a record of ``n`` displacements: ``sqrt(max double / n) / 2``.

    A residual, model less data, is at most twice the larger of them in magnitude, so ``n`` such
    residuals squared and summed stay below the largest double (about 1.8e308).
    """
    return math.sqrt(sys.float_info.max / max(n, 1)) / 2


def read_record(path: str | os.PathLike, masses: Sequence[str]) -> Record:
    """The record of the CSV file ``path`` for a system whose masses are ``masses``.

    Raises
    ------
    ValueError
        One line beginning ``file 'PATH'``: it cannot be read or is larger
        than :data:`~lumped.model.tables.MAX_TABLE_BYTES`; its header has no
        ``t``, no ``x_<mass>``, an ``x_`` column of no mass of the system, or a
        column twice; a row has another number of fields or a field that is
        not a plain decimal number or not finite; fewer than two rows; a time
        below 0 or not after the one before it; a displacement beyond
        :func:`largest_displacement`.
    """
    if isinstance(masses, str) or not isinstance(masses, Sequence) or not all(isinstance(m, str) for m in masses):
        raise ValueError(f"masses must be a sequence of the system's mass names, got {masses!r:.60}")
    return read_lines(path, lambda lines: _parse(lines, list(masses)))


def _header(line: str, masses: list[str]) -> dict[str, int]:
    """The columns read (``t`` and the ``x_<mass>``) by their index in the header ``line``."""
    names = [n.strip() for n in line.split(",")]
    twice = [n for i, n in enumerate(names) if n in names[:i]]
    if twice:
        raise ValueError(f"header: the column {twice[0]!r:.40} is named twice")
    if "t" not in names:
        raise ValueError(f"header: no column 't' (the times, s); got {line[:60]!r}")
    measured = [n for n in names if n.startswith("x_")]
    unknown = [n for n in measured if n[2:] not in masses]
    if unknown:
        raise ValueError(f"header: the column {unknown[0]!r:.40} names no mass of the system ({', '.join(masses)})")
    if not measured:
        raise ValueError(f"header: no column x_<mass> of a measured mass; the system's are x_{', x_'.join(masses)}")
    return {n: names.index(n) for n in ["t", *measured]}


def _parse(lines: list[str], masses: list[str]) -> Record:
    """The record of a file's ``lines``; a ``ValueError`` naming the line (1-based) or the column."""
    while lines and not lines[-1].strip():
        lines = lines[:-1]
    first = next((i for i, line in enumerate(lines) if not line.lstrip().startswith("#")), len(lines))
    if first == len(lines):
        raise ValueError("no header line (the columns t,x_<mass>)")
    width = len(lines[first].split(","))
    columns = _header(lines[first], masses)
    rows = lines[first + 1 :]
    if len(rows) < 2:
        raise ValueError(f"needs at least two rows of data, got {len(rows)}")
    data = np.empty((len(rows), len(columns)))
    for i, line in enumerate(rows):
        data[i] = _row(line, first + i + 2, width, list(columns.values()))
    t = data[:, 0]
    if t[0] < 0:
        raise ValueError(f"line {first + 2}: the time {float(t[0])!r} is before 0")
    late = np.flatnonzero(np.diff(t) <= 0)
    if late.size:
        i = int(late[0]) + 1
        raise ValueError(
            f"line {first + i + 2}: the time {float(t[i])!r} does not follow {float(t[i - 1])!r} (t must increase)"
        )
    limit = largest_displacement(data[:, 1:].size)
    big = np.flatnonzero(np.any(np.abs(data[:, 1:]) > limit, axis=1))
    if big.size:
        j = 1 + int(np.argmax(np.abs(data[big[0], 1:]) > limit))
        raise ValueError(
            f"line {first + int(big[0]) + 2}: {list(columns)[j]} = {data[big[0], j]:.3g} m is beyond {limit:.3g} m, "
            "where the squared residuals of a fit would overflow"
        )
    return Record(t, {name[2:]: data[:, j] for j, name in enumerate(columns) if name != "t"})


def _row(line: str, number: int, width: int, wanted: list[int]) -> list[float]:
    """The wanted numbers of a row, or a ``ValueError`` naming its line ``number`` (and the column)."""
    fields = line.split(",")
    if len(fields) != width:
        raise ValueError(f"line {number}: {len(fields)} fields, the header has {width}")
    out = []
    for j in wanted:
        try:
            value = plain_float(fields[j])
        except ValueError as err:
            raise ValueError(f"line {number}: {err}") from None
        if not math.isfinite(value):
            raise ValueError(f"line {number}: {fields[j].strip()[:40]!r} is not a finite number")
        out.append(value)
    return out


def check_record(record: object, masses: Sequence[str], what: str = "record") -> Record:
    """``record`` as a :class:`Record` of float arrays for a system whose masses are ``masses``.

    Raises
    ------
    ValueError
        One line beginning with ``what``: not a :class:`Record` (a plain tuple is refused, not guessed at);
        times that are not a 1-D array of at least two finite values from 0 on, strictly increasing; no
        measured mass, one the system does not have, or displacements of another shape than the times,
        not finite, or beyond :func:`largest_displacement`.
    """
    if not isinstance(record, Record):
        raise ValueError(f"{what}: expected a lumped.Record(t, {{mass: x}}), got {type(record).__name__}")  # noqa: TRY004 (the API's one error type)
    t, x = (_floats(f"{what}.t", record.t), record.x)
    if t.ndim != 1 or t.size < 2:
        raise ValueError(f"{what}.t: expected a 1-D array of at least two times, got shape {t.shape}")
    if not np.all(np.isfinite(t)) or t[0] < 0 or np.any(np.diff(t) <= 0):
        raise ValueError(f"{what}.t: the times must be finite, from 0 on and strictly increasing")
    if not isinstance(x, dict) or not x:
        raise ValueError(f"{what}.x: expected a dict of each measured mass's displacements, got {_shown(x)}")
    unknown = [name for name in x if name not in masses]
    if unknown:
        raise ValueError(f"{what}.x: {_shown(unknown[0])} names no mass of the system ({', '.join(masses)})")
    out = {name: _floats(f"{what}.x[{name!r}]", values) for name, values in x.items()}
    limit = largest_displacement(sum(v.size for v in out.values()))
    for name, values in out.items():
        where = f"{what}.x[{name!r}]"
        if values.shape != t.shape:
            raise ValueError(
                f"{where}: {values.shape[0] if values.ndim == 1 else values.shape} values for {t.size} times"
            )
        if not np.all(np.isfinite(values)):
            raise ValueError(f"{where}: the displacements must be finite")
        if np.max(np.abs(values)) > limit:
            raise ValueError(
                f"{where}: |x| up to {np.max(np.abs(values)):.3g} m, beyond {limit:.3g} m, where "
                "the squared residuals of a fit would overflow"
            )
    return Record(t, out)


def _shown(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def _floats(where: str, values: object) -> np.ndarray:
    """``values`` as an array of floats, or a one-line ``ValueError`` naming ``where``."""
    try:
        out = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{where}: expected an array of numbers, got {_shown(values)}") from None
    return out
