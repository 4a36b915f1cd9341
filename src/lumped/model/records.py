"""Measured records read from CSV files: :func:`read_record`, the times and the displacements of some masses.

The format, for ``python -m lumped fit --data``: optional comment lines
beginning with ``#`` at the top (say where the record comes from), a header
naming the columns, then one row of numbers per line.  The columns are ``t``
(s, finite, from 0 on, strictly increasing) and ``x_<mass>`` (m, finite) for
each measured mass (any subset of the system's); other columns are allowed
and not read, so that a ``simulate --system`` output can be read as a record.
Blank lines may only end the file.  Every problem is a ``ValueError`` of one
line naming the file and the line or the column.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from lumped.model.tables import read_lines

__all__ = ["Record", "read_record"]


class Record(NamedTuple):
    """Times ``t`` (n,) and, for each measured mass by name, its displacements ``x`` (n,)."""

    t: np.ndarray
    x: dict[str, np.ndarray]


def read_record(path: str | os.PathLike, masses: Sequence[str]) -> Record:
    """The record of the CSV file ``path`` for a system whose masses are ``masses``.

    Raises
    ------
    ValueError
        One line beginning ``file 'PATH'``: it cannot be read or is larger
        than :data:`~lumped.model.tables.MAX_TABLE_BYTES`; its header has no
        ``t``, no ``x_<mass>``, an ``x_`` column of no mass of the system, or a
        column twice; a row has another number of fields or a field that is
        not a finite number; fewer than two rows; a time below 0 or not after
        the one before it.
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
    return Record(t, {name[2:]: data[:, j] for j, name in enumerate(columns) if name != "t"})


def _row(line: str, number: int, width: int, wanted: list[int]) -> list[float]:
    """The wanted numbers of a row, or a ``ValueError`` naming its line ``number`` (and the column)."""
    fields = line.split(",")
    if len(fields) != width:
        raise ValueError(f"line {number}: {len(fields)} fields, the header has {width}")
    out = []
    for j in wanted:
        try:
            value = float(fields[j])
        except ValueError:
            raise ValueError(f"line {number}: {fields[j].strip()[:40]!r} is not a number") from None
        if not math.isfinite(value):
            raise ValueError(f"line {number}: {fields[j].strip()[:40]!r} is not a finite number")
        out.append(value)
    return out
