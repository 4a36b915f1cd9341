"""Rewrite the methods' table of book/guide/cli.md from the registry, or check that it is current.

The section between the markers of :mod:`lumped.cli.reference` is
:func:`lumped.cli.reference.methods_markdown`, generated from
``lumped.drivers.methods.METHODS`` (what each method is, what it runs, its
options, whether a sweep runs it); ``--help`` prints the same table
(``tests/test_cli_reference.py`` holds the two together).

Examples::

    python scripts/guide_methods.py            # rewrite the section after a change to the registry
    python scripts/guide_methods.py --check    # exit 1 if the page differs from the registry
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from lumped.cli.reference import BEGIN, END, methods_markdown

PAGE = Path(__file__).resolve().parent.parent / "book" / "guide" / "cli.md"


def regenerated(text: str) -> str:
    """``text`` with its section between the markers replaced by the registry's table."""
    if text.count(BEGIN) != 1 or text.count(END) != 1:
        raise SystemExit(f"guide_methods: {PAGE} must hold each marker once ({BEGIN!r}, {END!r})")
    head, rest = text.split(BEGIN)
    return head + methods_markdown() + rest.split(END, 1)[1]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="do not write; exit 1 if the page is not current")
    args = parser.parse_args()
    text = PAGE.read_text()
    new = regenerated(text)
    if args.check:
        if new != text:
            print(
                f"guide_methods: {PAGE.name} differs from the registry; run scripts/guide_methods.py", file=sys.stderr
            )
            return 1
        return 0
    PAGE.write_text(new)
    return 0


if __name__ == "__main__":
    sys.exit(main())
