"""The article's own figure: Algorithm 1's error against its step, from numbers.json.

Usage::

    python scripts/paper_figures.py paper/build/numbers.json paper/build/convergence.pdf

Reads the ``convergence`` object written by ``scripts/paper_numbers.py`` and
draws it with :func:`lumped.plotting.convergence`; the PDF is written by
:func:`lumped.plotting.save_figure`, with its metadata blanked, so two runs on
the same numbers give identical bytes.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from lumped import plotting  # noqa: E402


def write(numbers: Path, out: Path) -> Path:
    """Draw the convergence figure from ``numbers`` into ``out`` (a ``.pdf``); return it."""
    if out.suffix != ".pdf":
        raise ValueError(f"out: {out} is not a .pdf file")
    fig = plotting.convergence(json.loads(numbers.read_text(encoding="utf-8")))
    (path,) = plotting.save_figure(fig, out.stem, out.parent, formats=("pdf",))
    return path


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("numbers", type=Path, help="paper/build/numbers.json")
    parser.add_argument("out", type=Path, help="the PDF to write, paper/build/convergence.pdf")
    args = parser.parse_args(argv)
    print(f"wrote {write(args.numbers, args.out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
