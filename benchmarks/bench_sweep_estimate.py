"""The sweep's up-front time estimate beside the measured time, for the single-run methods (a benchmark, not a test).

Run from the repository root:  python benchmarks/bench_sweep_estimate.py

For each sweep of ``tests/test_sweep_limits.py``'s RUNS (exact and
event-driven, free and forced), prints the estimate of
:meth:`lumped.drivers.sweep.SweepSpec.seconds`, the measured wall time (after one row
to take imports and first calls out) and their ratio.  The estimate is meant
to stay within a factor 4 of the measurement on this project's 2-core
machine; the machine may be shared, so the figures are what this run saw.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from test_sweep_limits import RUNS, spec_of  # noqa: E402

from lumped.drivers.sweep import run_sweep  # noqa: E402


def main() -> None:
    print(f"load average {os.getloadavg()[0]:.2f}")
    print(
        f"{'method':14s} {'rows':>5s} {'steps':>7s} {'estimate s':>11s} {'measured s':>11s} {'measured/estimate':>18s}"
    )
    for method, kw in RUNS:
        spec = spec_of(method, kw)
        run_sweep(spec, slice(0, 1))
        start = time.perf_counter()
        run_sweep(spec)
        measured = time.perf_counter() - start
        estimate = spec.seconds()
        print(
            f"{method:14s} {spec.rows:5d} {spec.n_steps:7d} {estimate:11.3f} {measured:11.3f} {measured / estimate:18.2f}"
        )


if __name__ == "__main__":
    main()
