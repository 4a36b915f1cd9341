"""The parameter studies of issue 12, whose data live in ``results/studies/``.

Each study is a module of this package (:data:`STUDIES`) that gives

* ``COLUMNS``: the columns of its CSV file, in order;
* ``CHUNKS``: ``studies`` (the configuration key, ``default`` or ``full``) ->
  number of chunks, each one Snakemake job (``rules/studies.smk``);
* ``chunk_table(cfg, resolution, chunk)``: the rows of chunk ``(index, count)``
  of the study's grid at that resolution, as columns.

The chunks are merged, in grid order, by :func:`merge_csv`.  Floats are
written by ``repr``, so a file reads back bit for bit; columns whose name ends
in ``stops`` are integers.
"""

from __future__ import annotations

import csv
import importlib
from collections.abc import Mapping, Sequence
from pathlib import Path
from types import ModuleType

import numpy as np

__all__ = ["STUDIES", "study", "write_csv", "read_csv", "merge_csv"]

#: Study name -> module of this package (also the name of its files in results/studies/).
STUDIES = {
    "rest": "lumped.studies.rest",
    "den_hartog": "lumped.studies.den_hartog",
    "stops": "lumped.studies.stops",
    "stops_low": "lumped.studies.stops_low",
}
#: The values of the configuration key ``studies``.
RESOLUTIONS = ("default", "full")


def study(name: str) -> ModuleType:
    """The module of study ``name`` (a key of :data:`STUDIES`)."""
    if name not in STUDIES:
        raise ValueError(f"study must be one of {', '.join(STUDIES)}, not {name!r}")
    return importlib.import_module(STUDIES[name])


def write_csv(table: Mapping[str, np.ndarray], target: str | Path, columns: Sequence[str]) -> None:
    """Write the ``columns`` of ``table`` as CSV, floats by repr, atomically (no half-written file)."""
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    part = target.with_suffix(".csv.part")
    with part.open("w", newline="", encoding="utf-8") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for values in zip(*(np.asarray(table[c]) for c in columns)):
            w.writerow([repr(v.item()) for v in values])
    part.replace(target)


def read_csv(path: str | Path, columns: Sequence[str]) -> dict[str, np.ndarray]:
    """A study file as columns (those ending in ``stops`` as integers); its header must be ``columns``."""
    with Path(path).open(newline="", encoding="utf-8") as f:
        reader = csv.reader(f)
        header = next(reader, [])
        if tuple(header) != tuple(columns):
            raise ValueError(f"{path}: columns {header}, expected {list(columns)}")
        data = list(zip(*reader)) or [()] * len(columns)
    return {
        c: np.array([int(v) for v in col], dtype=np.int64) if c.endswith("stops") else np.array(col, dtype=float)
        for c, col in zip(columns, data)
    }


def merge_csv(parts: Sequence[str | Path], target: str | Path, columns: Sequence[str]) -> None:
    """Concatenate chunk files, in the order given, into ``target``."""
    tables = [read_csv(p, columns) for p in parts]
    write_csv({c: np.concatenate([t[c] for t in tables]) for c in columns}, target, columns)
