"""Speed of the network integrator, printed (a benchmark, not a test).

Run from the repository root:  python benchmarks/bench_network.py [--quick]

The chain is the one of ``tests/test_network.py``: mass ``i`` (``1 + 0.5 i``
kg, released at ``x0 = 0.1 (i + 1)`` m) joined to mass ``i - 1``, or to the
ground for ``i = 0``, by a spring (``100 + 20 i`` N/m) in parallel with a
Bingham dashpot (threshold 1 N, gamma 1); the last mass is forced by
``10 sin(5 pi t)`` N, here without end so that every step is a forced one.
``dt = 1e-3`` s.  Measures, each as the best wall time of several repeats:

1. the one-mass network (the paper's system) on 1e6 steps: the path
   ``solver="auto"`` takes (Algorithm 1), Algorithm 1 called directly, and
   the compiled active-set step (``solver="active-set"``);
2. a 100-mass chain, 1e5 steps, and a 1000-mass chain, 1e4 steps (target:
   at most 10 s each), compiled;
3. the cost per step for 10, 100 and 1000 masses on 1e4 steps, less the
   time of a one-step run (so the set-up and the initial forces, solved
   once, drop out), per step and per mass; and the Python step's (200
   steps, 10 and 100 masses), for comparison;
4. the same cost for the 100-mass *ring*: the chain with one more spring and
   Bingham dashpot from its last mass back to the ground, so that its links
   close one loop (the compiled step's chord, ``_network_loop.h``), per mass
   and step against the 100-mass chain's (target: at most 2 times);
5. the methods of order two and the exact one on the 10-mass chain, 2000
   steps: ``event-locating`` (trapezoidal steps per mode, in Python) and
   ``exact`` (matrix exponentials per phase), per step, beside backward
   Euler's compiled step.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time

import lumped as L
from lumped import Bingham, Load, Mass, Network, Spring, simulate_network
from lumped.solvers import backward_euler
from lumped.solvers import network_compiled as kernel

DT = 1e-3
FORCE = L.SwitchedSine(10.0, 5 * math.pi, 0.0)


def chain(n: int) -> Network:
    """The chain of ``tests/test_network.py`` (Bingham, gamma = 1), forced without end."""
    masses = [Mass(f"m{i}", 1.0 + 0.5 * i, 0.1 * (i + 1)) for i in range(n)]
    elements = []
    for i in range(n):
        a = "ground" if i == 0 else f"m{i - 1}"
        elements.append(Spring(f"k{i}", (a, f"m{i}"), 100.0 + 20 * i))
        elements.append(Bingham(f"b{i}", (a, f"m{i}"), 1.0, 1.0))
    return Network(masses, elements, [Load(f"m{n - 1}", FORCE)])


def ring(n: int) -> Network:
    """:func:`chain` closed into a ring: a spring and a Bingham dashpot from its last mass to the ground."""
    net = chain(n)
    closing = [
        Spring(f"k{n}", (f"m{n - 1}", "ground"), 100.0 + 20 * n),
        Bingham(f"b{n}", (f"m{n - 1}", "ground"), 1.0, 1.0),
    ]
    return Network(net.masses, [*net.elements, *closing], net.loads)


def best_of(repeats: int, fn) -> float:  # noqa: ANN001
    """Smallest wall time (s) of ``repeats`` calls of ``fn``."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def run(net: Network, steps: int, solver: str = "auto") -> L.Trajectory:
    return simulate_network(net, steps * DT, DT, save_every=max(1, steps // 100), solver=solver)


def bench_one_mass(steps: int, repeats: int) -> None:
    net, osc = chain(1), L.Oscillator.bingham(1.0, 100.0, 1.0, 1.0)
    path = run(net, 10).solver
    secs = best_of(repeats, lambda: run(net, steps))
    direct = best_of(
        repeats, lambda: L.backward_euler(osc, steps * DT, DT, x0=0.1, force=FORCE, save_every=steps // 100)
    )
    compiled = best_of(repeats, lambda: run(net, steps, "active-set"))
    print(
        f"one mass, {steps:.0e} steps: network path (solver='auto' takes {path!r}) {secs:.3f} s; "
        f"Algorithm 1 called directly ({backward_euler.KERNEL} kernel) {direct:.3f} s; "
        f"the compiled active-set step {compiled:.3f} s ({compiled / direct:.1f} x Algorithm 1)"
    )


def bench_chain(n: int, steps: int, repeats: int) -> None:
    net = chain(n)
    tr = run(net, 10)
    secs = best_of(repeats, lambda: run(net, steps))
    print(
        f"{n}-mass chain, {steps:.0e} steps ({tr.solver}): {secs:.2f} s = {secs / steps * 1e3:.4f} ms/step "
        f"(target 10 s)"
    )


def per_step(net: Network, steps: int, repeats: int, solver: str) -> float:
    """Cost of one step (s) without the set-up: (T(N) - T(1)) / (N - 1), on the chain's own motion."""
    setup = best_of(repeats, lambda: run(net, 1, solver))
    return max(best_of(repeats, lambda: run(net, steps, solver)) - setup, 0.0) / (steps - 1)


def bench_per_step(steps: int, repeats: int) -> None:
    base = None
    for n in (10, 100, 1000):
        cost = per_step(chain(n), steps, repeats, "active-set")
        base = base or cost / n
        print(
            f"cost per step, {n:4d} masses, compiled: {cost * 1e3:.4f} ms/step = {cost / n * 1e6:.4f} us "
            f"per mass and step ({cost / n / base:.2f} x the 10-mass figure per mass)"
        )
    for n in (10, 100):  # the Python step, for comparison (1000 masses: minutes)
        cost = per_step(chain(n), 200, 1, "python")
        print(f"cost per step, {n:4d} masses, Python step: {cost * 1e3:.3f} ms/step")


def bench_ring(n: int, steps: int, repeats: int) -> None:
    net = ring(n)
    path = run(net, 10).solver
    chain_cost, ring_cost = (per_step(make(n), steps, repeats, "active-set") for make in (chain, ring))
    print(
        f"cost per step, {n}-mass ring ({path}): {ring_cost * 1e3:.4f} ms/step = {ring_cost / n * 1e6:.4f} us per mass "
        f"and step, {ring_cost / chain_cost:.2f} x the {n}-mass chain's {chain_cost / n * 1e6:.4f} us (target 2 x)"
    )


def bench_accurate(n: int, steps: int, repeats: int) -> None:
    net = chain(n)
    for method in ("backward-euler", "event-locating", "exact"):
        cost = best_of(repeats, lambda m=method: L.solve(L.Problem(net, steps * DT), DT, method=m)) / steps
        print(f"cost per step, {n}-mass chain, {method}: {cost * 1e3:.4f} ms/step (set-up included)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="10 times fewer steps, one repeat")
    args = parser.parse_args()
    scale, repeats = (10, 1) if args.quick else (1, 3)
    print(f"python {sys.version.split()[0]}, {os.cpu_count()} cores, network kernel: {kernel.KERNEL}")
    bench_one_mass(10**6 // scale, repeats)
    bench_chain(100, 10**5 // scale, repeats)
    bench_chain(1000, 10**4 // scale, repeats)
    bench_per_step(10**4 // scale, repeats)
    bench_ring(100, 10**4 // scale, repeats)
    bench_accurate(10, 2000 // scale, repeats)


if __name__ == "__main__":
    main()
