"""Concatenate the CSV files of a sweep's chunks (``sweep --chunk I/N``), in the order given, into one.

Usage::

    python scripts/merge_chunks.py OUTPUT.csv CHUNK.csv...

The chunks' header lines must be equal; the rows are copied as text, byte for
byte, so the merged file is the one the whole sweep writes.  The output is
written to a temporary file and renamed (no half-written file).  A bad input
exits with status 2 and one line.
"""

from __future__ import annotations

import os
import sys


def merge(target: str, parts: list[str]) -> int:
    """Write ``parts``' header once, then their rows in order, to ``target``; returns the number of rows."""
    header, rows = None, []
    for part in parts:
        with open(part, encoding="utf-8") as fh:
            lines = fh.read().splitlines(keepends=True)
        if not lines:
            raise ValueError(f"{part}: empty, not a chunk of a sweep (no header line)")
        if header is not None and lines[0] != header:
            raise ValueError(f"{part}: its columns differ from {parts[0]}'s; chunks of one sweep have the same")
        header = lines[0]
        rows += lines[1:]
    part_file = f"{target}.part"
    with open(part_file, "w", encoding="utf-8") as fh:
        fh.writelines([header, *rows])  # type: ignore[list-item]
    os.replace(part_file, target)
    return len(rows)


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) < 2:
        print(__doc__.split("\n\n")[1].strip(), file=sys.stderr)
        return 2
    try:
        count = merge(args[0], args[1:])
    except (ValueError, OSError) as err:
        print(f"merge_chunks: {err}", file=sys.stderr)
        return 2
    print(f"wrote {args[0]} ({count} rows from {len(args) - 1} chunks)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
