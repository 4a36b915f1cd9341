"""Cost per step of the belt oscillator beside Algorithm 1's kernel, printed (a benchmark, not a test).

Run from the repository root:  python benchmarks/bench_belt.py [--quick]

The belt oscillator is issue 33's block on a belt: 1 kg on a spring of 1 N/m
to the ground and a friction contact (static 1 N, kinetic 0.5 N) on a belt at
0.2 m/s, started at rest at x = 0, dt = 1e-3 s; it sticks and slips for the
whole run (a limit cycle of period about 7 s).  Its contact is run

1. with a Stribeck fall (``stribeck_velocity = 0.1`` m/s, each decay), the
   slip speed a root in every slipping step, and
2. as static above kinetic without a Stribeck velocity (closed forms per step),

by the compiled one-mass friction loop (``solver="auto"`` takes it:
``_friction_kernel.c``), and, in the same run, Algorithm 1's compiled kernel
(``_kernel.c``) on the paper's oscillator (1 kg, 1 N/m, a Coulomb dashpot of
0.5 N, released at 5 m), free (at rest after 16 s) and under ``2 sin t`` N
(moving most of the time).  Each cost is ``(T(N) - T(1)) / (N - 1)``, the
best of several repeats, so that the set-up (checks, the initial forces)
drops out; saving every ``N/100``-th step.  The times are the process's CPU
time (``time.process_time``), which the other jobs of a shared machine
inflate less than the wall time; compare figures from one run only.
Target (issue 33): the Stribeck belt at most 2 x Algorithm 1's kernel per
step.  The Python step's cost is printed for comparison (2000 steps).
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import lumped as L
from lumped import Driver, Friction, Mass, Network, Spring, simulate_network
from lumped.solvers import backward_euler
from lumped.solvers import friction_compiled

DT = 1e-3


def belt(**law: object) -> Network:
    """The block on the belt with a contact of ``law`` (static 1 N, kinetic 0.5 N and ``law``)."""
    contact = Friction("contact", ("belt", "m"), **{"static": 1.0, "kinetic": 0.5, **law})
    return Network([Mass("m", 1.0)], [Spring("spring", ("ground", "m"), 1.0), contact], drivers=[Driver("belt", 0.2)])


def best_of(repeats: int, fn) -> float:  # noqa: ANN001
    """Smallest CPU time (s) of ``repeats`` calls of ``fn``."""
    times = []
    for _ in range(repeats):
        start = time.process_time()
        fn()
        times.append(time.process_time() - start)
    return min(times)


def per_step(run, steps: int, repeats: int) -> float:  # noqa: ANN001
    """Cost of one step (s) without the set-up: ``(T(N) - T(1)) / (N - 1)``; ``run(n)`` runs ``n`` steps."""
    setup = best_of(repeats, lambda: run(1))
    return max(best_of(repeats, lambda: run(steps)) - setup, 0.0) / (steps - 1)


def network_run(net: Network, solver: str = "auto"):  # noqa: ANN201
    return lambda n: simulate_network(net, n * DT, DT, save_every=max(1, n // 100), solver=solver)


def algorithm1_run(force: L.SwitchedSine | None):  # noqa: ANN201
    osc = L.Oscillator.bingham(1.0, 1.0, 0.5, float("inf"))
    return lambda n: L.backward_euler(osc, n * DT, DT, x0=5.0, force=force, save_every=max(1, n // 100))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="10 times fewer steps, one repeat")
    args = parser.parse_args()
    steps, repeats = (10**6, 1) if args.quick else (10**7, 5)
    print(
        f"python {sys.version.split()[0]}, {os.cpu_count()} cores, Algorithm 1 kernel: {backward_euler.KERNEL}, "
        f"friction kernel: {friction_compiled.KERNEL}; {steps:.0e} steps of dt = {DT:g} s"
    )
    free = per_step(algorithm1_run(None), steps, repeats)
    force = L.SwitchedSine(2.0, 1.0)
    moving = (algorithm1_run(force)(10**5).velocities != 0).mean()
    forced = per_step(algorithm1_run(force), steps, repeats)
    print(
        f"Algorithm 1's kernel, free: {free * 1e9:.1f} ns/step; under 2 sin t: {forced * 1e9:.1f} ns/step "
        f"(moving {moving:.0%} of the steps)"
    )
    cases = {
        "static/kinetic, no Stribeck": belt(),
        "Stribeck, exponential": belt(stribeck_velocity=0.1),
        "Stribeck, gaussian": belt(stribeck_velocity=0.1, decay="gaussian"),
        "Stribeck, rational": belt(stribeck_velocity=0.1, decay="rational"),
    }
    for name, net in cases.items():
        tr = simulate_network(net, 100.0, DT, save_every=100)
        stuck = tr.rigid[1:, 1].mean()
        cost = per_step(network_run(net), steps, repeats)
        print(
            f"belt oscillator, {name} ({tr.solver}, stuck {stuck:.0%} of the steps): {cost * 1e9:.1f} ns/step "
            f"= {cost / free:.2f} x Algorithm 1 free, {cost / forced:.2f} x forced (target 2 x)"
        )
    python = per_step(network_run(cases["Stribeck, exponential"], "python"), 2000, 1)
    print(f"belt oscillator, Stribeck, exponential, Python step: {python * 1e6:.1f} us/step")


if __name__ == "__main__":
    main()
