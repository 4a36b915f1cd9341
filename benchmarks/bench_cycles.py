"""Limit cycles by continuation against long runs: Leine et al.'s benchmark over belt speeds 0.05 to 0.5 m/s.

Run from the repository root:  python benchmarks/bench_cycles.py

The block of Leine, van Campen, de Kraker and van den Steen (Nonlinear
Dynamics 16 (1998) 41-54): m = k = 1, on a belt through the slip curve
F_s/(1 + 3 s), F_s = 1 N (tests/test_friction_event_driven.py's benchmark).
Prints, in one run:

* the cycle branch by :func:`lumped.drivers.cycles.continuation.continue_branches`
  from 0.05 to 0.5 m/s with ``points`` = 101 (a step moves the belt by 4.5e-3 m/s
  at most): its cycles, its time and the time per cycle;
* the long runs at the same belt speeds: the event-driven method (DOP853 at its
  rtol 1e-12, :func:`lumped.solvers.event_driven_network.solve_contact`) from the
  system's initial state (at rest where the spring is relaxed), extended by half
  again until the extremes of the last two periods (breakaway to breakaway, each
  extreme at a zero of the speed by Brent's method on the dense output) agree to
  1e-8 m: their time, the time per run, and the largest difference of the
  extremes from the continuation's;
* the ratio of the two times (the issue's target: continuation at least 20 times
  cheaper).

The first line gives the load average: the machine may be shared, and the
figures are what this run saw.
"""

from __future__ import annotations

import os
import time

import numpy as np

from lumped.drivers.cycles.continuation import continue_branches
from lumped.laws import SlipCurve, Spring
from lumped.laws.slip_elements import Contact
from lumped.model.network import Driver, Mass, Network
from lumped.numerics.roots import brentq
from lumped.solvers.event_driven_network import March, solve_contact

START, STOP, POINTS = 0.05, 0.5, 101
#: Two periods' extremes within this of each other (m): the run has settled.
SETTLED = 1e-8
FS, DELTA = 1.0, 3.0


def leine(V: float) -> Network:
    law = SlipCurve(FS, lambda s: FS / (1 + DELTA * s), fall=FS * DELTA)
    elements = [Spring("k", ("ground", "m"), 1.0), Contact("c", ("belt", "m"), law)]
    return Network([Mass("m", 1.0)], elements, drivers=[Driver("belt", V)])


def extremes(march: March, t0: float, t1: float) -> tuple[float, float]:
    """The largest and smallest position between ``t0`` and ``t1``: at the zeros of the speed in each slip phase
    (Brent's method on the phase's dense output), and at the ends."""
    found = [float(x) for x in march.state(np.array([t0, t1]))[0]]
    for ph in march.phases:
        if ph.motion is None or ph.end <= t0 or ph.start >= t1:
            continue
        a, b = max(ph.start, t0), min(ph.end, t1)
        grid = np.linspace(a, b, 65)
        v = ph.motion.state(grid)[1] + march.mdl.V
        for i in np.flatnonzero(np.sign(v[1:]) * np.sign(v[:-1]) < 0):
            speed = lambda t, ph=ph: float(ph.motion.state(np.array([t]))[1][0]) + march.mdl.V
            t = brentq(speed, float(grid[i]), float(grid[i + 1]))
            found.append(float(ph.motion.state(np.array([t]))[0][0]))
    return max(found), min(found)


def long_run(V: float) -> tuple[float, float, float]:
    """``(x_max, x_min, t_end)`` of the last period of a run from rest that has settled to :data:`SETTLED`."""
    net, t_end = leine(V), 3 * (2 * np.pi + 2 * FS / V)  # three periods of the harmonic slip and its stick
    while True:
        march = solve_contact(net, t_end, rtol=1e-12)
        breaks = [e.time for e in march.events if e.kind == "breakaway"]
        if len(breaks) >= 3:
            last, before = extremes(march, breaks[-2], breaks[-1]), extremes(march, breaks[-3], breaks[-2])
            if max(abs(last[0] - before[0]), abs(last[1] - before[1])) <= SETTLED:
                return last[0], last[1], t_end
        t_end *= 1.5


def main() -> None:
    print(f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}")
    start = time.perf_counter()
    rows = continue_branches(leine(0.2), "belt.velocity", START, STOP, points=POINTS)
    branch_time = time.perf_counter() - start
    cycles = [r for r in rows if r.branch == "cycle"]
    kinds = sorted({r.kind for r in cycles})
    print(
        f"continuation: {len(cycles)} cycles from {START} to {STOP} m/s in {branch_time:.2f} s, "
        f"{1e3 * branch_time / len(cycles):.1f} ms per cycle (kinds: {', '.join(kinds)})"
    )
    start = time.perf_counter()
    runs = [long_run(r.value) for r in cycles]
    runs_time = time.perf_counter() - start
    spans = [t for *_, t in runs]
    print(
        f"long runs: {len(runs)} runs in {runs_time:.2f} s, {1e3 * runs_time / len(runs):.1f} ms per run "
        f"(each {min(spans):.0f} to {max(spans):.0f} s of motion until settled to {SETTLED:g} m)"
    )
    diff = max(
        max(abs(x_max - r.cycle.x_max[0]), abs(x_min - r.cycle.x_min[0]))
        for (x_max, x_min, _), r in zip(runs, cycles, strict=True)
    )
    print(f"largest difference of the extremes, continuation against long runs: {diff:.2e} m")
    print(f"continuation {runs_time / branch_time:.1f} times cheaper than the long runs")


if __name__ == "__main__":
    main()
