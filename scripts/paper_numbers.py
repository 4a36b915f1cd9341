"""Write every number and verdict of the article to a JSON file.

Usage::

    python scripts/paper_numbers.py paper/build/numbers.json

A command-line wrapper of :func:`lumped.studies.replication.compute` (the layout of
the JSON is described there), with the configuration :func:`lumped.studies.config.load`
finds (``$LUMPED_CONFIG`` in the pipeline).  The article
(``paper/paper.typ``) reads the JSON with Typst's ``json()``;
``tests/test_paper_numbers.py`` checks the values against independent
references.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from lumped.studies.replication import compute


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    target = Path(args[0])
    target.parent.mkdir(parents=True, exist_ok=True)
    target.write_text(json.dumps(compute(), indent=1, sort_keys=True, allow_nan=False) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
