"""Batched against single-run Algorithm 1, and the sweep command's wall time (a benchmark, not a test).

Run from the repository root:  python benchmarks/bench_sweep.py

Prints ns per trajectory-step of the batched kernel, free (the decay from
``x0`` over [-1, 1]) and forced (the same with ``3 sin(3 t)``, one of the
project's sines per trajectory-step) side by side: through
``batch_backward_euler`` (the widest loop, its calls bounded in work) for 1e4
and 1e5 trajectories, and for each vector loop the CPU runs (AVX-512, AVX2,
SSE2), the kernel called directly on 1e4 trajectories, with its CPU time
summed over the threads (what the loop costs, whatever else runs); beside the single-run
kernel's ns per step, best of a few runs; and the wall time of ``python -m
lumped sweep --vary x0=-1:1:20001 --t-end 4 --dt 1e-4`` (interpreter start-up,
imports and writing the file included).  The machine may be shared: the
figures are what this run saw.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import lumped as L
from lumped.kernels import batched
from lumped.solvers import backward_euler


def best(run, repeats: int = 3) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def _params(n: int, amplitude: float) -> batched.BatchParameters:
    return batched.BatchParameters(1.0, 100.0, 1.0, 1.0, np.linspace(-1, 1, n), 0.0, amplitude, 3.0, 0.0, np.inf)


def batched_ns(n: int, t_end: float, amplitude: float = 0.0) -> float:
    steps = round(t_end / 1e-4)
    return best(lambda: batched.batch_backward_euler(_params(n, amplitude), t_end, 1e-4), 2) / (n * steps) * 1e9


def path_ns(path: str, n: int, t_end: float, amplitude: float) -> tuple[float, float]:
    """One vector loop of the compiled kernel, called directly (one call, all steps): wall and CPU ns.

    The CPU time is summed over the threads, so on a shared machine it says what the loop costs when
    the wall time says what this run got; on an idle machine the wall time is about CPU / threads.
    """
    steps = round(t_end / 1e-4)
    par = np.ascontiguousarray(batched._as_columns(_params(n, amplitude)))
    nw, sums = np.full(n, steps + 1.0), np.empty((7, n))
    wall, cpu = [], []
    for _ in range(2):
        start, start_cpu = time.perf_counter(), time.process_time()
        batched._compiled_batch(1e-4, 1, steps, steps, 0, par, nw, sums, np.empty(0), path)
        wall.append(time.perf_counter() - start)
        cpu.append(time.process_time() - start_cpu)
    return min(wall) / (n * steps) * 1e9, min(cpu) / (n * steps) * 1e9


def single_ns() -> float:
    osc = L.Oscillator.bingham()
    return best(lambda: L.backward_euler(osc, 40.0, 1e-4, x0=0.5, save_every=1000)) / 400_000 * 1e9


def sweep_wall() -> float:
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "rest.npz")
        cmd = [sys.executable, "-m", "lumped", "sweep", "--vary", "x0=-1:1:20001", "--t-end", "4", "--dt", "1e-4"]
        return best(lambda: subprocess.run([*cmd, "--output", out], check=True, capture_output=True), 2)


def main() -> None:
    compiled = batched.BATCH_KERNEL == "compiled"
    kernel = __import__("lumped.kernels._batch_kernel", fromlist=["threads"]) if compiled else None
    threads, path = (kernel.threads(), kernel.best_path()) if kernel else (1, "numpy")
    print(
        f"kernels: batched {batched.BATCH_KERNEL} ({path} loop by default, {threads} threads), "
        f"single-run {backward_euler.KERNEL}; "
        f"load average {os.getloadavg()[0]:.2f}"
    )
    print(f"single-run kernel:          {single_ns():7.2f} ns per step")
    print("ns per trajectory-step:             free   forced")
    for n, t_end in ((10_000, 2.0), (100_000, 0.4)):
        free, forced = batched_ns(n, t_end), batched_ns(n, t_end, amplitude=3.0)
        print(f"batched, {n:.0e} trajectories:    {free:7.2f}  {forced:7.2f}")
    print("per loop, 1e4 trajectories:       free   forced   CPU (both threads): free   forced")
    for name in kernel.paths() if kernel else ():
        (free, free_cpu), (forced, forced_cpu) = path_ns(name, 10_000, 2.0, 0.0), path_ns(name, 10_000, 2.0, 3.0)
        print(f"  {name:29s} {free:7.2f}  {forced:7.2f}   {free_cpu:24.2f}  {forced_cpu:7.2f}")
    print(f"sweep --vary x0=-1:1:20001 --t-end 4 --dt 1e-4: {sweep_wall():.2f} s wall")


if __name__ == "__main__":
    main()
