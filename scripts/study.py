"""A parameter study of lumped.studies: one chunk of its grid, or the merge of the chunks.

Usage::

    python scripts/study.py chunk STUDY CONFIG RESOLUTION INDEX COUNT OUTPUT.csv
    python scripts/study.py merge STUDY OUTPUT.csv CHUNK.csv...

``chunk`` writes the rows of chunk ``INDEX`` of ``COUNT`` (0-based) of study
STUDY's grid at RESOLUTION (``default`` or ``full``), with the parameters of
the configuration file CONFIG (``chunk_table`` of the study's module);
``merge`` concatenates chunk files in the order given.  A bad input exits with
status 2 and one line.
"""

from __future__ import annotations

import sys

import lumped.studies.config
from lumped import studies


def _chunk(name: str, config: str, resolution: str, index: str, count: str, output: str) -> None:
    module = studies.study(name)
    if resolution not in studies.RESOLUTIONS:
        raise ValueError(f"resolution must be one of {', '.join(studies.RESOLUTIONS)}, not {resolution!r}")
    table = module.chunk_table(lumped.studies.config.load(config), resolution, (int(index), int(count)))
    studies.write_csv(table, output, module.COLUMNS)


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    try:
        if len(args) == 7 and args[0] == "chunk":
            _chunk(*args[1:])
            target = args[6]
        elif len(args) >= 4 and args[0] == "merge":
            studies.merge_csv(args[3:], args[2], studies.study(args[1]).COLUMNS)
            target = args[2]
        else:
            print(__doc__.split("\n\n")[2].strip(), file=sys.stderr)
            return 2
    except (ValueError, OSError) as err:
        print(f"study: {err}", file=sys.stderr)
        return 2
    print(f"wrote {target}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
