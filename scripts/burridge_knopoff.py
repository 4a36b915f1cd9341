"""Carlson and Langer's chain (lumped.studies.burridge_knopoff): run it and write its catalogue of slip events.

Usage::

    python scripts/burridge_knopoff.py BLOCKS TRAVEL DT OUTPUT.csv

Runs ``BLOCKS`` blocks (the configuration's ``bk_blocks``) by backward Euler at the step ``DT`` (``bk_dt``, in
``1/omega_p``) while the plate travels ``TRAVEL`` (``bk_travel``, in ``D_0``), from the study's seeded initial
positions, and writes one row per slip event (``COLUMNS`` of the module, CL's units) to OUTPUT.csv and the run's
facts (its parameters, events left unfinished, steps with a block moving backwards) to OUTPUT with ``.json``.
A bad input exits with status 2 and one line.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

from lumped import studies
from lumped.numerics import validate
from lumped.studies import burridge_knopoff as bk


def main(argv: list[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 4:
        print(__doc__.split("\n\n")[2].strip(), file=sys.stderr)
        return 2
    try:
        p = bk.Parameters(blocks=validate.parse_int("BLOCKS", args[0]))
        travel, dt = validate.parse_float("TRAVEL", args[1]), validate.parse_float("DT", args[2])
        start = time.perf_counter()
        result = bk.run(p, travel, dt)
        studies.write_csv(bk.catalogue_table(p, result.catalogue), args[3], bk.COLUMNS)
        facts = bk.run_facts(p, travel, dt, result)
        Path(args[3]).with_suffix(".json").write_text(json.dumps(facts, sort_keys=True, indent=1) + "\n")
    except (ValueError, OSError) as err:
        print(f"burridge_knopoff: {err}", file=sys.stderr)
        return 2
    print(f"wrote {args[3]}: {len(result.catalogue)} events in {time.perf_counter() - start:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
