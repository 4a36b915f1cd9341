"""Load histories read from CSV files: :func:`read_table`, a :class:`~lumped.model.forcing.Table` from ``t,F``.

The format, for a system file's ``kind = "table"`` (book/guide/systems.md) and
the command line's ``--force-table``: optional comment lines beginning with
``#`` at the top (say where the record comes from), a header naming the two
columns (``t,F`` for a force in N, ``t,a`` for a ground acceleration in
m/s^2), then one row ``time,value`` per line, times in seconds strictly
increasing, every number finite.  Blank lines may only end the file.  Every
problem is a ``ValueError`` of one line naming the file and the line.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

import numpy as np

from lumped.model.forcing import Table, first_bad_sample

__all__ = ["MAX_TABLE_BYTES", "read_lines", "read_table"]

T = TypeVar("T")

#: Largest table read (bytes): about 400,000 rows of two numbers written with 17 digits.
MAX_TABLE_BYTES = 16 * 1024**2


def read_table(path: str | os.PathLike, column: str) -> Table:
    """The table of the CSV file ``path``, whose header is ``t,<column>``.

    Raises
    ------
    ValueError
        One line beginning ``file 'PATH'``: it cannot be read, is larger
        than :data:`MAX_TABLE_BYTES`, has another header, a line that is not
        two numbers, fewer than two rows, a number that is not finite, or a
        time that does not follow the one before it (the line named).
    """
    return read_lines(path, lambda lines: _parse(lines, column))


def read_lines(path: str | os.PathLike, parse: Callable[[list[str]], T]) -> T:
    """``parse`` of the lines of the text file ``path`` (at most :data:`MAX_TABLE_BYTES`); its ``ValueError``,
    or one for a file that cannot be read, as one line beginning ``file 'PATH'`` (tables and records)."""
    if not isinstance(path, (str, os.PathLike)):
        raise ValueError(f"path must be a str or a path of a file, got {type(path).__name__}")
    where = f"file {str(path)!a}"
    try:
        size = Path(path).stat().st_size
        if size > MAX_TABLE_BYTES:
            raise ValueError(f"{where}: {size} bytes, more than the {MAX_TABLE_BYTES} read")
        text = Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        why = getattr(err, "strerror", None) or str(err)
        raise ValueError(f"{where}: cannot read it: {why}") from None
    try:
        return parse(text.splitlines())
    except ValueError as err:
        raise ValueError(f"{where}: {err}") from None


def _parse(lines: list[str], column: str) -> Table:
    """The table of a file's ``lines``; a ``ValueError`` naming the line (1-based)."""
    while lines and not lines[-1].strip():
        lines = lines[:-1]
    first = next((i for i, line in enumerate(lines) if not line.lstrip().startswith("#")), len(lines))
    header = [name.strip() for name in lines[first].split(",")] if first < len(lines) else []
    if header != ["t", column]:
        shown = repr(lines[first][:40]) if first < len(lines) else "nothing"
        raise ValueError(f"line {first + 1}: expected the header 't,{column}', got {shown}")
    rows = lines[first + 1 :]
    data = np.empty((len(rows), 2))
    for i, line in enumerate(rows):
        data[i] = _row(line, first + i + 2, column)
    if len(rows) < 2:
        raise ValueError(f"needs at least two rows of 't,{column}', got {len(rows)}")
    bad = first_bad_sample(data[:, 0], data[:, 1], ("t", column))
    if bad is not None:
        raise ValueError(f"line {first + bad[0] + 2}: {bad[1]}")
    return Table(data[:, 0], data[:, 1])


def _row(line: str, number: int, column: str) -> tuple[float, float]:
    """The two numbers of a row, or a ``ValueError`` naming its line ``number``."""
    fields = line.split(",")
    try:
        if len(fields) != 2:
            raise ValueError
        return plain_float(fields[0]), plain_float(fields[1])  # the guide's plain decimals, not float()'s 0.0_4
    except ValueError:
        raise ValueError(f"line {number}: expected two numbers 't,{column}', got {line[:40]!r}") from None


#: A plain decimal number as a CSV file of this package writes one: an optional sign, digits with at most one
#: point, an optional exponent (``-1.5e-3``, ``.5``, ``2.``); ``nan`` and ``inf`` too, for the readers to refuse
#: as not finite.  Not Python's ``float()`` grammar, which also takes ``1_000`` and ``0.0_4``.
_DECIMAL = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|[+-]?(?:nan|inf|infinity)", re.IGNORECASE)


def plain_float(text: str) -> float:
    """The number of a CSV field ``text`` (blanks around it allowed), or a ``ValueError`` if it is not a plain
    decimal number (:data:`_DECIMAL`)."""
    if not _DECIMAL.fullmatch(text.strip()):
        raise ValueError(f"{text.strip()[:40]!r} is not a plain decimal number")
    return float(text)
