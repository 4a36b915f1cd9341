"""Run the work-precision study and write it as strict JSON.

Usage::

    python scripts/accuracy_study.py results/accuracy/study.json

A command-line wrapper of :func:`lumped.studies.accuracy.study` at its default
resolutions (about 20 s on one core), on the repository's parameter file
without ``--config`` overrides (:func:`lumped.studies.accuracy.cases`: the study
compares methods on fixed cases); the layout is
:func:`lumped.studies.accuracy.to_json`'s.  No wall time is written, so two
runs write the same bytes.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from lumped.studies import accuracy


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1 or not args[0].endswith(".json"):
        print(__doc__.split("\n\n")[1].strip(), file=sys.stderr)
        return 2
    data = accuracy.to_json(accuracy.study())
    target = Path(args[0])
    target.parent.mkdir(parents=True, exist_ok=True)
    text = json.dumps(data, indent=1, sort_keys=True, allow_nan=False) + "\n"
    tmp = target.with_suffix(".json.part")
    tmp.write_text(text, encoding="utf-8")
    tmp.replace(target)  # no half-written file if the run stops
    print(f"wrote {target}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
