"""Speed of the solvers, printed (a benchmark, not a test).

Run from the repository root:  python benchmarks/bench_speed.py [--quick]

Measures, each as the best of several repeats:
1. Algorithm 1 (backward Euler) on 1e7 steps through the API, compiled kernel
   and, on fewer steps, the pure-Python twin;
2. the same 1e7 steps through the command line, interpreter start-up, imports
   and writing the ``.npz`` file included, as a multiple of the compiled loop's
   time in 1, and its parts: the interpreter alone, with ``import numpy``, and
   the whole command for one step (start-up, the package's imports, the
   output); the modules' bytecode is cached, as an installed package's is
   (``PYTHONDONTWRITEBYTECODE`` is dropped for these runs, the cache kept in
   a temporary folder), so that the figures are not those of compiling every
   module's source each time;
3. the exact event-driven solver to rest for the free vibration ``x0 = 0.5``, and the paper's forced
   problem (eq. 17b, Figures 6 to 9) by ``exact`` through the one entry ``lumped.solve``, sampled on
   the paper's grid (``dt = 1e-4``, 25,001 rows): the route a user takes;
4. ``solve_ivp`` on the textbook ``sgn(0) = 0`` model and on its ``tanh``
   regularisation over the same motion, for comparison.
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time

import lumped as L
from lumped.solvers import backward_euler, textbook


def best_of(repeats: int, fn) -> float:  # noqa: ANN001
    """Smallest wall time (s) of ``repeats`` calls of ``fn``."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def _run(osc: L.Oscillator, kernel: str, steps: int) -> None:
    """Algorithm 1 through the API, ``steps`` steps of ``dt = 1e-4`` from ``x0 = 0.5``."""
    L.backward_euler(osc, steps * 1e-4, 1e-4, x0=0.5, save_every=1000, kernel=kernel)


def bench_api(osc: L.Oscillator, n: int, repeats: int) -> None:
    _run(osc, "auto", 10)  # load the kernel once
    secs = best_of(repeats, lambda: _run(osc, "auto", n))
    print(f"Algorithm 1, API, {backward_euler.KERNEL} kernel: {n:.0e} steps in {secs:.3f} s = {n / secs:.3g} steps/s")
    n_py = max(n // 100, 1000)
    secs = best_of(1, lambda: _run(osc, "python", n_py))
    print(f"Algorithm 1, API, pure-Python loop: {n_py:.0e} steps in {secs:.3f} s = {n_py / secs:.3g} steps/s")


def _cached_env(cache: str) -> dict[str, str]:
    """This environment with the modules' bytecode written to and read from ``cache``."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    return env | {"PYTHONPYCACHEPREFIX": cache}


def bench_cli(osc: L.Oscillator, n: int, repeats: int) -> None:
    """The command line's ``n`` steps against the compiled loop of the same steps, and the parts of its time.

    Each repeat times every part in turn (the loop through the API in this process, then the commands), so
    that on a shared machine the best of each comes from the same conditions as the others.
    """
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "run.npz")
        cmd = [sys.executable, "-m", "lumped", "simulate", "--x0", "0.5", "--dt", "1e-4", "--save-every", "1000"]
        env = _cached_env(os.path.join(tmp, "pycache"))
        call = lambda *c: lambda: subprocess.run(c, check=True, capture_output=True, env=env)  # noqa: E731
        call(*cmd, "--t-end", "1e-4", "--output", out)()  # write the bytecode cache
        parts = {
            "loop": lambda: _run(osc, "auto", n),
            "command": call(*cmd, "--t-end", repr(n * 1e-4), "--output", out),
            "one step": call(*cmd, "--t-end", "1e-4", "--output", out),
            "numpy": call(sys.executable, "-c", "import numpy"),
            "python": call(sys.executable, "-c", "pass"),
        }
        best = {name: math.inf for name in parts}
        for _ in range(repeats):
            for name, fn in parts.items():
                best[name] = min(best[name], best_of(1, fn))
    loop, secs, one, bare, python = (best[k] for k in ("loop", "command", "one step", "numpy", "python"))
    print(f"Algorithm 1, command line: {n:.0e} steps in {secs:.3f} s wall, start-up included = {n / secs:.3g} steps/s")
    print(
        f"Algorithm 1, command line against the compiled loop of the same steps: {secs / loop:.2f} times "
        f"({secs:.3f} s / {loop:.3f} s) = the interpreter {python:.3f} s + import numpy {bare - python:.3f} s "
        f"+ the package's imports, parsing and a one-step output {one - bare:.3f} s + the loop {loop:.3f} s "
        f"+ the rest (the longer output, timing noise) {secs - one - loop:.3f} s"
    )


def bench_exact(osc: L.Oscillator, repeats: int) -> None:
    sol = L.solve_exact(osc, 5.0, x0=0.5)
    secs = best_of(repeats, lambda: L.solve_exact(osc, 5.0, x0=0.5))
    print(
        f"exact solver, free vibration x0 = 0.5: rest at t = {sol.rest_time:.10f} s, "
        f"x = {sol.rest_position:.10f} m, {len(sol.events)} events, in {secs * 1e3:.2f} ms"
    )


def bench_exact_forced(repeats: int) -> None:
    """The paper's problem (17b) by ``exact`` through :func:`lumped.solve`, on its own grid."""
    from lumped.studies import examples

    ex = examples.paper()["forced_large"]
    problem = L.Problem.oscillator(ex.oscillator, ex.t_end, x0=ex.x0, v0=ex.v0, force=ex.force)
    run = lambda: L.solve(problem, ex.dt, method="exact")  # noqa: E731
    tr = run()
    secs = best_of(repeats, run)
    print(
        f"exact, the paper's problem (17b) through lumped.solve on dt = {ex.dt:g} s ({tr.t.size} rows): "
        f"rest at t = {tr.rest_time:.10f} s, {len(tr.events)} events, in {secs * 1e3:.2f} ms"
    )


def bench_textbook(osc: L.Oscillator, budget: float) -> None:
    cases = [
        ("sgn(0) = 0, RK45", textbook.TextbookModel(osc), "RK45"),
        ("tanh(v/1e-3), RK45", textbook.TextbookModel(osc, eps=1e-3), "RK45"),
        ("tanh(v/1e-3), Radau", textbook.TextbookModel(osc, eps=1e-3), "Radau"),
    ]
    for label, model, method in cases:
        out = textbook.integrate_adaptive(
            model, 5.0, x0=0.5, method=method, rtol=1e-8, max_nfev=2_000_000, max_seconds=budget
        )
        print(
            f"solve_ivp on the textbook model, {label}, x0 = 0.5 over 5 s: "
            f"{out.wall_time:.3f} s, {out.nfev} evaluations; {out.message}"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="1e6 steps, one repeat")
    args = parser.parse_args()
    n, repeats = (10**6, 1) if args.quick else (10**7, 3)
    osc = L.Oscillator.bingham()  # the paper's parameters
    print(f"python {sys.version.split()[0]}, {os.cpu_count()} cores")
    bench_api(osc, n, repeats)
    bench_cli(osc, n, 1 if args.quick else 5)
    bench_exact(osc, 20)
    bench_exact_forced(20)
    bench_textbook(osc, 5.0 if args.quick else 30.0)


if __name__ == "__main__":
    main()
