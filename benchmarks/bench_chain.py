"""Cost of the compiled sparse step on a chain of blocks on a rough floor, printed (a benchmark, not a test).

Run from the repository root:  python benchmarks/bench_chain.py [--quick]

The chain: ``N`` blocks of 1 kg, each on a friction contact to the floor
(static ``mu_s`` drawn uniformly in 0.9..1.1 N, seeded, kinetic 0.6 N: a
static/kinetic law), each pulled by a leaf spring (10 N/m) from a plate moving
at 0.1 m/s (a driven point), neighbours joined by coupling springs (50 N/m):
the layout of Burridge and Knopoff.  Every floor contact closes a loop through
the ground, so the forest kernel cannot run it; the sparse step's merged
system is tridiagonal in file order.  From ``t = 0.9`` s the blocks
stick-slip.  ``dt = 1e-3`` s, 3 s of motion (3000 steps; ``--quick``: 1 s
past the first slips at 1000 blocks, 1500 steps at 100,000), saved every
500th step.

Printed, each the best of several repeats (one at 100,000 blocks, whose run
of 3000 steps takes some 20 s and set-up a few) of (T(steps) - T(1 step)) / (steps - 1) / N (so that the set-up and the initial forces, solved once, drop out),
in wall time on this machine (and the CPU time, which other jobs on a shared
machine disturb less): the cost per block and step at 1000 and at
100,000 blocks (target: at most 0.1 us at both, linear in N), the same at
1000 blocks on a Stribeck floor (the friction falling exponentially from
static to kinetic, Stribeck velocity 0.02 m/s: each iteration linearises the
slipping contacts' curves, so a step takes more iterations), and in the
same run the per-mass cost of today's forest chain (``bench_network.py``'s:
springs and Bingham dashpots between neighbours, forced) at 1000 masses.
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

from lumped import Driver, Friction, Mass, Network, Spring, simulate_network
from lumped.solvers import network_compiled as kernel

sys.path.insert(0, os.path.dirname(__file__))
from bench_network import chain as forest_chain

DT = 1e-3
#: The Stribeck floor's velocity (m/s): the friction falls from static to kinetic over a few cm/s.
STRIBECK_VELOCITY = 0.02


def floor_chain(n: int, seed: int = 1, stribeck_velocity: float | None = None) -> Network:
    """``n`` blocks on a static/kinetic floor (or, with ``stribeck_velocity``, a Stribeck floor falling
    exponentially from static to kinetic), leaf springs to a moving plate, coupling springs."""
    static = np.random.default_rng(seed).uniform(0.9, 1.1, n)
    masses = [Mass(f"m{i}", 1.0) for i in range(n)]
    elements = []
    for i in range(n):
        law = {"static": float(static[i]), "kinetic": 0.6, "stribeck_velocity": stribeck_velocity}
        elements.append(Friction(f"c{i}", (f"m{i}", "ground"), **law))
        elements.append(Spring(f"leaf{i}", ("plate", f"m{i}"), 10.0))
        if i:
            elements.append(Spring(f"k{i}", (f"m{i - 1}", f"m{i}"), 50.0))
    return Network(masses, elements, (), [Driver("plate", 0.1)])


def best_of(repeats: int, fn) -> np.ndarray:
    """Smallest wall and CPU times (s) of ``repeats`` calls of ``fn``."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter(), time.process_time()
        fn()
        times.append((time.perf_counter() - start[0], time.process_time() - start[1]))
    return np.min(times, axis=0)


def per_mass_step(net: Network, steps: int, repeats: int) -> tuple[np.ndarray, str, float]:
    """Cost (s, wall and CPU) per mass and step without the set-up, the path that ran, the share of
    saved block-steps slipping."""
    run = lambda k: simulate_network(net, k * DT, DT, save_every=min(k, 500), solver="active-set")
    tr = run(steps)
    moving = float((tr.velocities != 0).mean())
    setup = best_of(repeats, lambda: run(1))
    total = best_of(repeats, lambda: run(steps))
    return np.maximum(total - setup, 0.0) / (steps - 1) / len(net.masses), tr.solver, moving


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer steps, one repeat")
    args = parser.parse_args()
    repeats = 1 if args.quick else 3
    print(f"python {sys.version.split()[0]}, {os.cpu_count()} cores, network kernel: {kernel.KERNEL}")
    for n, steps in ((1000, 2000 if args.quick else 3000), (100_000, 1500 if args.quick else 3000)):
        cost, path, moving = per_mass_step(floor_chain(n), steps, repeats if n < 10_000 else 1)  # one: 20 s a run
        print(
            f"floor chain, {n:6d} blocks, {steps} steps ({path}; {moving:.0%} of saved block-steps moving): "
            f"{cost[0] * 1e6:.4f} us per block and step (target 0.1; CPU time {cost[1] * 1e6:.4f} us)"
        )
    steps = 2000 if args.quick else 3000
    cost, path, moving = per_mass_step(floor_chain(1000, stribeck_velocity=STRIBECK_VELOCITY), steps, repeats)
    print(
        f"Stribeck floor chain, 1000 blocks, {steps} steps ({path}; {moving:.0%} of saved block-steps moving): "
        f"{cost[0] * 1e6:.4f} us per block and step (CPU time {cost[1] * 1e6:.4f} us)"
    )
    cost, path, _ = per_mass_step(forest_chain(1000), 3000, repeats)
    print(
        f"forest chain (bench_network.py), 1000 masses, 3000 steps ({path}): {cost[0] * 1e6:.4f} us per mass "
        f"and step (CPU time {cost[1] * 1e6:.4f} us)"
    )


if __name__ == "__main__":
    main()
