"""Run the test suite and nbval under perturbed floating-point environments; print a pass/fail table.

No test and no stored notebook output may follow the last bits of round-off
(issue 19).  This runs ``python -m pytest`` (the unit tests and nbval on the
committed notebooks, as the README's test command does) once per environment:

* ``reference``: the environment as it is;
* ``pure-python``: ``LUMPED_PURE_PYTHON=1``, the Python/NumPy kernels in place
  of the C ones (other sums and, through NumPy, other sine and exponential);
* ``numpy-baseline``: ``NPY_DISABLE_CPU_FEATURES`` switching off NumPy's
  AVX2/AVX-512 dispatch (its other SIMD loops for sin, exp, sums);
* ``one-thread``: ``OMP_NUM_THREADS=1`` (the batched kernel's lanes on one thread);
* ``libm-ulp``: ``LUMPED_PURE_PYTHON=1`` and ``scripts/perturb/sitecustomize.py``,
  which moves every result of ``math`` and NumPy's sin, cos, tan, exp, expm1,
  log, tanh, sinh and cosh by one ulp (the strongest: another machine's libm).

Each run prints one row (environment, outcome, counts, seconds) and, for a
failure, the failing test ids and the file holding pytest's output.  Exit status 0 when every environment passes,
1 when one fails, 2 on a bad argument.  The whole table takes about 2 minutes
per environment on 2 cores.

Examples::

    python scripts/perturbed_check.py                     # every environment, the whole suite
    python scripts/perturbed_check.py --env libm-ulp tests/test_dop853.py notebooks/09_which_method.ipynb
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PERTURB = ROOT / "scripts" / "perturb"
#: NumPy 2's names for its dispatch targets above the x86-64-v2 baseline (numpy refuses unknown ones).
NUMPY_DISPATCH = "X86_V3 X86_V4 AVX512_ICL AVX512_SPR"

ENVIRONMENTS: dict[str, dict[str, str]] = {
    "reference": {},
    "pure-python": {"LUMPED_PURE_PYTHON": "1"},
    "numpy-baseline": {"NPY_DISABLE_CPU_FEATURES": NUMPY_DISPATCH},
    "one-thread": {"OMP_NUM_THREADS": "1"},
    "libm-ulp": {"LUMPED_PURE_PYTHON": "1", "PYTHONPATH": str(PERTURB)},
}


def environment(name: str) -> dict[str, str]:
    """The process environment of ``name``: this one, the variables of other environments cleared, then set."""
    env = {k: v for k, v in os.environ.items() if k not in {v for e in ENVIRONMENTS.values() for v in e}}
    env.update(ENVIRONMENTS[name])
    if "PYTHONPATH" in ENVIRONMENTS[name] and os.environ.get("PYTHONPATH"):
        env["PYTHONPATH"] += os.pathsep + os.environ["PYTHONPATH"]
    return env


def run(name: str, targets: list[str]) -> tuple[bool, str, float, list[str]]:
    """Run pytest on ``targets`` in environment ``name``: (passed, summary line, seconds, failing ids)."""
    start = time.monotonic()
    cmd = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", *targets]
    proc = subprocess.run(cmd, cwd=ROOT, env=environment(name), capture_output=True, text=True)
    seconds = time.monotonic() - start
    log = Path(tempfile.gettempdir()) / f"perturbed_check-{name}.log"
    log.write_text(proc.stdout + proc.stderr, encoding="utf-8")
    lines = proc.stdout.strip().splitlines()
    summary = re.sub(r"\x1b\[[0-9;]*m", "", lines[-1]) if lines else proc.stderr.strip()[-200:]
    failed = [line.split(" ", 1)[1].split(" - ")[0] for line in lines if line.startswith(("FAILED ", "ERROR "))]
    return proc.returncode == 0, summary.strip("= "), seconds, failed


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        description=__doc__.splitlines()[0], epilog="environments: " + ", ".join(ENVIRONMENTS)
    )
    parser.add_argument("targets", nargs="*", help="test files or notebooks (default: the whole suite, nbval included)")
    parser.add_argument(
        "--env", action="append", metavar="NAME", help="an environment to run (repeatable; default: all)"
    )
    args = parser.parse_args(argv)
    names = args.env or list(ENVIRONMENTS)
    unknown = [n for n in names if n not in ENVIRONMENTS]
    if unknown:
        print(
            f"perturbed_check: unknown environment {unknown[0]}; choose from {', '.join(ENVIRONMENTS)}", file=sys.stderr
        )
        return 2
    missing = [t for t in args.targets if not (ROOT / t.split("::")[0]).exists()]
    if missing:
        print(f"perturbed_check: no such test file or notebook: {missing[0]}", file=sys.stderr)
        return 2
    ok = True
    print(f"{'environment':16s} {'outcome':7s} {'seconds':>7s}  pytest's summary")
    for name in names:
        passed, summary, seconds, failed = run(name, args.targets)
        ok &= passed
        print(f"{name:16s} {'pass' if passed else 'FAIL':7s} {seconds:7.0f}  {summary}", flush=True)
        for test in failed:
            print(f"{'':16s} {'':7s} {'':7s}  failed: {test}")
        if not passed:
            print(
                f"{'':16s} {'':7s} {'':7s}  pytest's output: {Path(tempfile.gettempdir()) / f'perturbed_check-{name}.log'}"
            )
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
