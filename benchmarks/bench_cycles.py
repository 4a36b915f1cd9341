"""Limit cycles by continuation against long runs, on two branches in belt speed.

Run from the repository root:  python benchmarks/bench_cycles.py

The issue asks continuation of a cycle branch (at least 100 points) to be at
least 20 times cheaper than long runs that give the same amplitudes, each run
until the cycle settles to 1e-8.  Its premise is that long runs settle slowly.
Two branches, in one run:

1. **Leine's branch**: the block of Leine, van Campen, de Kraker and van den
   Steen (Nonlinear Dynamics 16 (1998) 41-54), m = k = 1 on a belt through the
   slip curve F_s/(1 + 3 s), F_s = 1 N, belt speeds 0.05 to 0.5 m/s with
   ``points`` = 101.  Every cycle there sticks once a period, so its one
   nontrivial multiplier is exactly 0 (the saltation at a stop has rank one):
   a long run is on the cycle from its first stop on.  Continuation needs one
   period of integration per point, and takes one (a cycle stuck at the
   section crosses it at the belt's speed, so the corrector's first return is
   the cycle, and ``dP/dV = 1`` there exactly: no difference quotient; the
   line printed counts the periods integrated per cycle, 1.01); a long run
   needs its transient to the first stop and then at least three turning
   points of each kind to see two differences.  The ratio of the motion each
   integrates (in periods, measured) bounds what continuation can gain there
   at equal cost per period, and it is about 4, not 20.
2. **A supercritical bubble**: the same m = k = 1 with a Gaussian Stribeck law
   (static 2 N, kinetic 1 N, Stribeck velocity 0.1 m/s, no viscous part) and a
   dashpot of 8.55 N s/m to the ground.  About steady sliding, with ``y = x'``
   and ``g`` the slip curve, ``m y' + K x = -(C + g'(V)) y + g''(V) y^2/2 -
   g'''(V) y^3/6 + ...``: first-order averaging gives the amplitude equation
   ``a' = -(c_eff + g'''(V) omega^2 a^2/8) a/(2m)``, so a Hopf point
   (``c_eff = C + g'(V) = 0``) is supercritical where ``g'''(V) > 0``.  An
   exponential or rational fall has ``g''' < 0`` at every speed (the
   Veraszto-Stepan law is subcritical whatever its viscous part, which is
   linear and adds nothing to ``g'''``); the Gaussian ``exp(-z^2)``, ``z =
   s/v_s``, has ``g''' = (static - kinetic)(12 z - 8 z^3) exp(-z^2)/v_s^3 > 0``
   below ``z = sqrt(3/2)``.  Its fall ``-g'`` peaks at ``z = 1/sqrt 2`` at
   ``sqrt(2/e) (static - kinetic)/v_s = 8.578`` N s/m, so a dashpot just
   below it, 8.55, makes steady sliding unstable between two Hopf points
   (0.0667 and 0.0748 m/s, both at ``z < 1``: both supercritical) and a
   bubble of stable cycles without a stick joins them, its multipliers from
   0.84 in the middle to 1 at the ends: slow transients.  The continuation
   runs over the two Hopf points (0.1 % beyond each) with ``points`` = 101.

The long runs, on both branches: the event-driven method (DOP853 at its rtol
1e-12, :func:`lumped.solvers.event_driven_network.solve_contact`) for three
periods of the cycle (where two differences of turning points can first be
seen), then one period at a time, each piece from the state where the last
ended, until settled: the turning points of the position (the zeros of the
speed in the slip phases, by Brent's method on the dense output): for the
maxima and for the minima alike, with ``d_n`` the difference of the last two,
the run has settled when the distance to the limit that a geometric tail
gives, ``d_n^2 / (d_{n-1} - d_n)``, is at most 1e-8 m (or ``d_n = 0``).
Leine's runs start from the system's initial state, at rest where the spring
is relaxed; the bubble's from steady sliding displaced by 1e-3 m (a stated
perturbation: an eighth to a half of the cycles' amplitudes in the rows run), for
each cycle row whose multiplier is at most 0.99 (nearer the Hopf points a run
needs more than ``ln(1e5)/0.01`` = 1150 periods and none is run: the rows
left out are the long runs' most expensive ones, so the ratio printed is a
lower bound for the whole branch).  Each run's extremes are compared with the
continuation's.  A continuation point of the bubble costs more than one
period: Newton's returns at a fixed speed (two, three near the Hopf points,
where the amplitude grows as a square root and the predictor is poorer) and
the one-sided difference of ``dP/dV`` from the cycle's own speed (one), each
return at the shooting's rtol 1e-13 with the map's derivative; so the
measured ratio there is below the bound in periods.  Two returns a point is
the least Newton takes (the predicted speed, then the corrected one, which
must be integrated for the cycle's data); only ``dP/dV`` from the variational
equations along the same return would take away the third.

Times are CPU seconds of this process (``time.process_time``): the machine
may be shared.  The first line gives the load average.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from lumped.drivers.cycles import shooting
from lumped.drivers.cycles.continuation import BranchPoint, continue_branches
from lumped.drivers.cycles.equilibria import hopf_points, steady_sliding
from lumped.laws import LinearDashpot, SlipCurve, Spring
from lumped.laws.slip_elements import Contact
from lumped.laws.stribeck import Friction
from lumped.model.network import Driver, Mass, Network
from lumped.model.system_parameters import system_parameters, with_values
from lumped.numerics.roots import brentq
from lumped.solvers.event_driven_network import March, solve_contact

POINTS = 101
#: A long run has settled when its estimated distance to the limit cycle is at most this (m).
SETTLED = 1e-8
#: The bubble's long runs: rows with a multiplier above this are not run (module docstring).
LARGEST_MULTIPLIER = 0.99
#: The bubble's long runs start at steady sliding displaced by this (m).
DISPLACEMENT = 1e-3
#: A long run gives up after this many pieces.
MAX_PIECES = 20_000
FS, DELTA = 1.0, 3.0
#: The bubble's dashpot (N s/m): below the Gaussian law's largest fall, sqrt(2/e) (2 - 1)/0.1 = 8.578.
BUBBLE_DAMPING = 8.55


def leine(V: float) -> Network:
    law = SlipCurve(FS, lambda s: FS / (1 + DELTA * s), fall=FS * DELTA)
    elements = [Spring("k", ("ground", "m"), 1.0), Contact("c", ("belt", "m"), law)]
    return Network([Mass("m", 1.0)], elements, drivers=[Driver("belt", V)])


def bubble(V: float) -> Network:
    law = Friction("f", ("belt", "m"), static=2.0, kinetic=1.0, stribeck_velocity=0.1, decay="gaussian")
    elements = [Spring("k", ("ground", "m"), 1.0), law, LinearDashpot("d", ("ground", "m"), BUBBLE_DAMPING)]
    return Network([Mass("m", 1.0)], elements, drivers=[Driver("belt", V)])


class LongRun(NamedTuple):
    """The last maximum and minimum of a settled run (m) and the motion it took (s)."""

    x_max: float
    x_min: float
    t_end: float


def turning_points(march: March, offset: float) -> list[tuple[float, float, bool]]:
    """``(t, x, is_max)`` at the zeros of the speed in the slip phases of ``march`` (times shifted by ``offset``)."""
    found = []
    for ph in march.phases:
        if ph.motion is None:
            continue  # stuck: the speed is the belt's
        grid = np.linspace(ph.start, ph.end, 65)
        v = ph.motion.state(grid)[1] + march.mdl.V
        for i in np.flatnonzero(np.sign(v[1:]) * np.sign(v[:-1]) < 0):
            speed = lambda t, ph=ph: float(ph.motion.state(np.array([t]))[1][0]) + march.mdl.V
            t = brentq(speed, float(grid[i]), float(grid[i + 1]))
            found.append((offset + t, float(ph.motion.state(np.array([t]))[0][0]), bool(v[i] > 0)))
    return found


def settled(values: list[float]) -> bool:
    """Whether the last three of a sequence converging geometrically are within :data:`SETTLED` of its limit."""
    if len(values) < 3:
        return False
    d_last, d_before = abs(values[-1] - values[-2]), abs(values[-2] - values[-3])
    return d_last == 0 or (d_last < d_before and d_last**2 / (d_before - d_last) <= SETTLED)


def long_run(net: Network, period: float) -> LongRun:
    """The run from ``net``'s initial state until its turning points settle: a first piece of three periods
    (``period``, the cycle's: where a settled run can first be seen), then one period at a time, each piece from
    the state where the last ended."""
    mass = net.masses[0]
    start = system_parameters(net, [f"{mass.name}.x0", f"{mass.name}.v0"])
    maxima: list[float] = []
    minima: list[float] = []
    t = 0.0
    for piece in range(MAX_PIECES):
        span = (3 if piece == 0 else 1) * period
        march = solve_contact(net, span, rtol=1e-12)
        for _, x, is_max in turning_points(march, t):
            (maxima if is_max else minima).append(x)
        t += span
        if settled(maxima) and settled(minima):
            return LongRun(maxima[-1], minima[-1], t)
        x, v = march.state(np.array([span]))
        net = with_values(net, start, [float(x[0]), float(v[0])])
    raise RuntimeError(f"a long run did not settle in {MAX_PIECES} periods")


def cpu(fn: Callable[[], object]) -> tuple[object, float]:
    start = time.process_time()
    out = fn()
    return out, time.process_time() - start


def continuation(net: Network, start: float, stop: float) -> tuple[list[BranchPoint], float, float]:
    """The cycle rows of the branches over ``start:stop``, their CPU time, and the motion the shooting integrated
    (s): the returns of :func:`lumped.drivers.cycles.shooting._fly`, counted by a wrapper that changes nothing."""
    fly, motion = shooting._fly, [0.0]

    def counted(*args: object, **kwargs: object) -> shooting._Flight:
        flight = fly(*args, **kwargs)
        motion[0] += flight.time
        return flight

    shooting._fly = counted
    try:
        rows, seconds = cpu(lambda: continue_branches(net, "belt.velocity", start, stop, points=POINTS))
    finally:
        shooting._fly = fly
    return [r for r in rows if r.branch == "cycle"], seconds, motion[0]  # type: ignore[union-attr]


def compare(
    title: str,
    cycles: list[BranchPoint],
    seconds: float,
    motion: float,
    runs: list[BranchPoint],
    member: Callable[[float], Network],
) -> None:
    """Run the long runs of ``runs`` and print the comparison."""
    kinds = sorted({r.kind for r in cycles})
    flights = motion / sum(r.cycle.period for r in cycles)  # periods integrated per cycle
    print(
        f"{title}: continuation {len(cycles)} cycles in {seconds:.2f} s CPU, {1e3 * seconds / len(cycles):.1f} ms "
        f"per cycle (kinds: {', '.join(kinds)}), {flights:.2f} periods integrated per cycle"
    )
    done, run_seconds = cpu(lambda: [long_run(member(r.value), r.cycle.period) for r in runs])
    periods = [run.t_end / r.cycle.period for run, r in zip(done, runs, strict=True)]  # type: ignore[attr-defined]
    diff = max(
        max(abs(run.x_max - r.cycle.x_max[0]), abs(run.x_min - r.cycle.x_min[0]))  # type: ignore[attr-defined]
        for run, r in zip(done, runs, strict=True)  # type: ignore[call-overload]
    )
    per_cycle = seconds / len(cycles)
    per_run = run_seconds / len(runs)
    print(
        f"{title}: long runs {len(runs)} runs in {run_seconds:.2f} s CPU, {1e3 * per_run:.1f} ms per run, "
        f"{min(periods):.1f} to {max(periods):.0f} periods each ({np.mean(periods):.1f} on average); extremes "
        f"within {diff:.1e} m of the continuation's"
    )
    print(
        f"{title}: per cycle, long runs {np.mean(periods):.1f} periods against continuation's {flights:.2f}: "
        f"at equal cost per period continuation is at most {np.mean(periods) / flights:.1f} times cheaper; "
        f"measured {per_run / per_cycle:.1f} times cheaper"
    )


def main() -> None:
    print(f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}")
    cycles, seconds, motion = continuation(leine(0.2), 0.05, 0.5)
    compare("Leine 0.05-0.5 m/s", cycles, seconds, motion, cycles, leine)

    low, high = hopf_points(bubble(0.07), "belt.velocity", 0.05, 0.09)
    cycles, seconds, motion = continuation(bubble(0.07), low * 0.999, high * 1.001)
    runs = [r for r in cycles if r.kind == "regular" and r.cycle.max_multiplier <= LARGEST_MULTIPLIER]
    multipliers = [r.cycle.max_multiplier for r in cycles if r.kind == "regular"]
    print(
        f"bubble: Hopf points {low:.6f} and {high:.6f} m/s; multipliers {min(multipliers):.3f} to "
        f"{max(multipliers):.5f}; long runs for the {len(runs)} rows at most {LARGEST_MULTIPLIER}, from steady "
        f"sliding displaced by {DISPLACEMENT:g} m"
    )

    def displaced(V: float) -> Network:
        net = bubble(V)
        x0 = float(steady_sliding(net).position[0]) + DISPLACEMENT
        return with_values(net, system_parameters(net, ["m.x0"]), [x0])

    compare("bubble", cycles, seconds, motion, runs, displaced)


if __name__ == "__main__":
    main()
