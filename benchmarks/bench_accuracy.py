"""The accuracy targets of issue 10, side by side in one run, printed (a benchmark, not a test).

Run from the repository root:  python benchmarks/bench_accuracy.py [--quick] [--table]

1. Herschel-Bulkley (m = 1 kg, k = 100 N/m, tau = 1 N, x0 = 0.5 m, 4 s;
   the study's cases K = 1, n = 1/2 and n = 2, whose backward-Euler step has
   a closed form, n = 3/2, where it is a bracketed root solve, and K = 20,
   n = 1/2, which creeps), each written as a one-mass system file and run through the
   command line: backward Euler at ``--dt 1e-4`` against ``--method
   event-driven --rtol R``, with R the largest of 1e-4, 1e-5, ..., 1e-12
   whose relative error (rest position for n > 1, position at the end for
   n < 1) is at most 1e-8 against the reference (event-driven at the
   smallest rtol DOP853 accepts).  Both write the same ``.npz`` rows (the
   grid of ``--dt 1e-4``).  The times are wall times of the whole command,
   best of several: interpreter start-up and imports (about 0.5 s, the same
   for both), reading the file, the solve, sampling and writing the output;
   nothing is subtracted.
2. The paper's free decay (x0 = 0.5 m): event-driven at rtol 1e-10 and 1e-12
   against ``exact``.
3. The event-locating scheme's rest-position error on the free decay at
   the original's step, dt = 1e-4, beside Algorithm 1's.
4. The tanh-regularised textbook model (LSODA) on the free decay: its error
   in "rest position" (its position at 4 s: it never sticks) for each eps
   and rtol of the study, with steps and wall time, and the cheapest
   setting that reaches 1e-3, if any.

``--table`` adds the work-precision study of ``lumped.studies.accuracy`` with wall
times (best of 3): the data of the wall-time work-precision diagram, which
the pipeline draws against a deterministic work count instead
(figures/README.md says why).
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import lumped as L
from lumped.solvers.event_driven import RTOL_RANGE
from lumped.studies import accuracy as A

HB_CASES = {  # label -> (consistency K, exponent n)
    "n = 1/2, K = 1": (1.0, 0.5),
    "n = 2, K = 1": (1.0, 2.0),
    "n = 3/2, K = 1": (1.0, 1.5),
    "n = 1/2, K = 20 (creeps)": (20.0, 0.5),
}
SYSTEM = """\
[[mass]]
name = "m"
mass = 1.0
x0 = 0.5
[[element]]
name = "k"
kind = "spring"
between = ["ground", "m"]
stiffness = 100.0
[[element]]
name = "d"
kind = "herschel-bulkley"
between = ["ground", "m"]
threshold = 1.0
consistency = {K}
exponent = {n}
"""
TARGET = 1e-8
T_END = 4.0


def cli(system: str, method: list[str], repeats: int) -> tuple[float, float]:
    """Best wall time (s) of ``python -m lumped simulate`` on ``system`` and its last x (m)."""
    with tempfile.TemporaryDirectory() as tmp:
        path, out = os.path.join(tmp, "hb.toml"), os.path.join(tmp, "run.npz")
        with open(path, "w") as fh:
            fh.write(system)
        cmd = [sys.executable, "-m", "lumped", "simulate", "--system", path, "--t-end", str(T_END), "--dt", "1e-4"]
        best = math.inf
        for _ in range(repeats):
            start = time.perf_counter()
            subprocess.run([*cmd, "--method", *method, "--output", out], check=True, capture_output=True)
            best = min(best, time.perf_counter() - start)
        return best, float(np.load(out)["x"][-1, 0])


def largest_rtol(osc: L.Oscillator, value: float) -> tuple[float, float]:
    """The largest rtol (decades from 1e-4) whose final position is within TARGET of ``value``, and its error."""
    for rtol in 10.0 ** -np.arange(4, 13):
        sol = L.solve_event_driven(osc, T_END, x0=0.5, rtol=rtol)
        err = abs(float(sol.evaluate(np.array([T_END]))["x"][0]) - value) / abs(value)
        if err <= TARGET:
            return float(rtol), err
    return math.nan, math.nan


def bench_herschel_bulkley(repeats: int) -> None:
    print(f"1. Herschel-Bulkley through the command line (t_end = {T_END} s, output on the grid of dt = 1e-4)")
    for label, (K, n) in HB_CASES.items():
        osc = L.Oscillator(1.0, L.LinearSpring(100.0), L.HerschelBulkleyDashpot(1.0, K, n))
        ref = L.solve_event_driven(osc, T_END, x0=0.5, rtol=RTOL_RANGE[0])
        value = float(ref.evaluate(np.array([T_END]))["x"][0])
        what = "rest position" if n > 1 else "position at the end"
        system = SYSTEM.format(K=K, n=n)
        be_secs, be_x = cli(system, ["backward-euler"], repeats)
        rtol, _ = largest_rtol(osc, value)
        ed_secs, ed_x = cli(system, ["event-driven", "--rtol", f"{rtol:g}"], repeats)
        be_err, ed_err = (abs(x - value) / abs(value) for x in (be_x, ed_x))
        verdict = "met" if ed_err <= TARGET and ed_secs <= be_secs else "NOT met"
        print(f"   {label}: {what} {value:.12g} m (reference)")
        print(f"      backward Euler, dt = 1e-4:   {be_secs:6.3f} s, relative error {be_err:.2e}")
        print(
            f"      event-driven, rtol = {rtol:.0e}: {ed_secs:6.3f} s, relative error {ed_err:.2e}  -> target {verdict}"
        )


def bench_free_decay() -> None:
    case = A.cases()["free-decay"]
    exact = L.solve_exact(case.oscillator, case.t_end, x0=case.x0)
    print(f"2. Paper's free decay: exact rest position {exact.rest_position:.12g} m at {exact.rest_time:.12g} s")
    for rtol in (1e-10, 1e-12):
        start = time.perf_counter()
        sol = L.solve_event_driven(case.oscillator, case.t_end, x0=case.x0, rtol=rtol)
        secs = time.perf_counter() - start
        err = abs(sol.rest_position - exact.rest_position) / abs(exact.rest_position)
        t_err = abs(sol.rest_time - exact.rest_time) / exact.rest_time
        print(f"   event-driven, rtol = {rtol:.0e}: relative difference {err:.1e} (rest position), {t_err:.1e} (time)")
        print(
            f"      {secs:.3f} s, {sol.steps} steps; target 1e-10: {'met' if max(err, t_err) <= 1e-10 else 'NOT met'}"
        )


def bench_event_capturing() -> None:
    ref = A.reference(A.cases()["free-decay"])
    print("3. Free decay at the original's step dt = 1e-4, relative rest-position error")
    for method in ("backward-euler", "event-locating"):
        r = A.run("free-decay", method, 1e-4, ref=ref, repeats=3)
        verdict = (
            ""
            if method == "backward-euler"
            else f"  -> target 0.1 %: {'met' if r.relative_position_error <= 1e-3 else 'NOT met'}"
        )
        print(f"   {method:16s} {100 * r.relative_position_error:8.4f} %  ({r.wall_time:.3f} s){verdict}")


def bench_tanh() -> None:
    ref = A.reference(A.cases()["free-decay"])
    print("4. tanh model (LSODA) on the free decay: error of x(t_end) against the rest position")
    reached = []
    for eps in A.TANH_EPS:
        for rtol in A.TANH_RTOLS:
            r = A.run("free-decay", "tanh", rtol, eps=eps, ref=ref, repeats=1)
            if r.relative_position_error <= 1e-3:
                reached.append((r.wall_time, eps, rtol, r.work))
            print(
                f"   eps = {eps:.0e}, rtol = {rtol:.0e}: relative error {r.relative_position_error:.2e}, "
                f"{r.work} steps, {r.wall_time:.3f} s"
            )
    if reached:
        secs, eps, rtol, steps = min(reached)
        print(f"   reaches 1e-3 first at eps = {eps:.0e}, rtol = {rtol:.0e}: {steps} steps, {secs:.3f} s")
    else:
        print("   reaches 1e-3 at no eps and rtol of the study: it creeps")


def bench_table() -> None:
    print("5. Work-precision with wall times (best of 3): case, method, resolution, relative position error, s")
    study = A.study(repeats=3)
    for r in study.results:
        eps = f" eps {r.eps:.0e}" if not math.isnan(r.eps) else ""
        print(
            f"   {r.case:12s} {r.method:16s} {r.resolution:.2e}{eps:10s} {r.relative_position_error:10.2e} "
            f"{r.max_x_error:10.2e} {r.work:7d} steps {r.wall_time:.4f} s"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one repeat per command")
    parser.add_argument("--table", action="store_true", help="also the whole study with wall times")
    args = parser.parse_args()
    bench_herschel_bulkley(1 if args.quick else 3)
    bench_free_decay()
    bench_event_capturing()
    bench_tanh()
    if args.table:
        bench_table()


if __name__ == "__main__":
    main()
