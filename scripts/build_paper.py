"""Typeset ``paper/paper.typ`` into ``paper/paper.pdf`` with the ``typst`` Python package.

Usage::

    python scripts/build_paper.py [--out paper/paper.pdf] [--draft] [FIGURE ...]

The figures are the PDF files ``figures/figNN_<slug>.pdf`` (``NN`` = 01..14,
the original's figure numbers), embedded as vector graphics at the size they
were drawn; when none are given on the command line they are found by that
pattern.  The article also embeds ``paper/build/convergence.pdf``
(``scripts/paper_figures.py``).  Their names go to ``paper/build/figures.json``,
which the article reads.  A missing figure is an error unless ``--draft`` is
given, in which case the article shows an empty frame in its place.

The PDF is deterministic: the document date is fixed in ``paper.typ``
(from ``paper/metadata.yaml``), system fonts are ignored: the text is set in
DejaVu Serif from Matplotlib's own font files (:data:`FIGURE_FONTS`, the font
of the figures, so figures and text share one family), the mathematics in the
fonts embedded in the ``typst`` package, so two builds from the same inputs are
byte-identical.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path

import matplotlib

ROOT = Path(__file__).resolve().parent.parent

#: Matplotlib's font files: the article's text is set in the figures' DejaVu Serif.
FIGURE_FONTS = str(Path(matplotlib.get_data_path()) / "fonts" / "ttf")
FIGURE_COUNT = 14
#: The article's own figure (``scripts/paper_figures.py``), key ``"convergence"`` of figures.json.
CONVERGENCE = ROOT / "paper" / "build" / "convergence.pdf"
#: The accuracy study's figure and numbers (rules/accuracy.smk), key ``"accuracy"`` of figures.json.
ACCURACY = ROOT / "paper" / "build" / "accuracy.pdf"
STUDY = ROOT / "results" / "accuracy" / "study.json"
_PATTERN = re.compile(r"fig(\d\d)_[A-Za-z0-9_-]+\.pdf$")


def figure_table(files: list[str]) -> dict[str, str]:
    """Map ``"01"``..``"14"`` to root-relative paths (``/figures/...``) for Typst."""
    table: dict[str, str] = {}
    for name in files:
        match = _PATTERN.search(Path(name).name)
        if not match:
            raise ValueError(f"figure: {name!r} is not named figures/figNN_<slug>.pdf")
        number = match.group(1)
        if number in table:
            raise ValueError(f"figure: two files for Figure {int(number)}: {table[number]}, {name}")
        table[number] = "/" + Path(name).resolve().relative_to(ROOT).as_posix()
    return table


def find_figures() -> list[str]:
    """The PDF files in ``figures/`` that follow the naming pattern."""
    return sorted(str(p) for p in (ROOT / "figures").glob("fig[0-9][0-9]_*.pdf"))


def build(out: Path, figures: list[str], draft: bool = False) -> Path:
    """Write ``paper/build/figures.json`` and compile the article to ``out``."""
    import typst

    table = figure_table(figures)
    missing = [f"{n:02d}" for n in range(1, FIGURE_COUNT + 1) if f"{n:02d}" not in table]
    if missing and not draft:
        raise FileNotFoundError(f"figures missing for Figure(s) {', '.join(missing)} (use --draft)")
    if CONVERGENCE.is_file():
        table["convergence"] = "/" + CONVERGENCE.relative_to(ROOT).as_posix()
    elif not draft:
        raise FileNotFoundError(f"{CONVERGENCE} not found: run scripts/paper_figures.py first")
    if ACCURACY.is_file():
        table["accuracy"] = "/" + ACCURACY.relative_to(ROOT).as_posix()
    elif not draft:
        raise FileNotFoundError(f"{ACCURACY} not found: run scripts/accuracy_figure.py first")
    if not STUDY.is_file():
        raise FileNotFoundError(f"{STUDY} not found: run scripts/accuracy_study.py first")
    numbers = ROOT / "paper" / "build" / "numbers.json"
    if not numbers.is_file():
        raise FileNotFoundError(f"{numbers} not found: run scripts/paper_numbers.py first")
    listing = ROOT / "paper" / "build" / "figures.json"
    listing.write_text(json.dumps(table, indent=1, sort_keys=True) + "\n", encoding="utf-8")
    out.parent.mkdir(parents=True, exist_ok=True)
    typst.compile(
        str(ROOT / "paper" / "paper.typ"),
        output=str(out),
        root=str(ROOT),
        ignore_system_fonts=True,
        font_paths=[FIGURE_FONTS],
        sys_inputs={"draft": "true" if draft else "false"},
    )
    return out


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("figures", nargs="*", help="figures/figNN_<slug>.pdf files")
    parser.add_argument("--out", type=Path, default=ROOT / "paper" / "paper.pdf")
    parser.add_argument("--draft", action="store_true", help="allow missing figures")
    args = parser.parse_args(argv)
    figures = [f for f in args.figures if f.endswith(".pdf")] or find_figures()
    path = build(args.out, figures, args.draft)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
