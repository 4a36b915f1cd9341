"""Response curves: time per point of the one-mass and the two-mass curve, and continuation against brute force.

Run from the repository root:  python benchmarks/bench_response.py

Prints, best of 3 runs each:

* the Coulomb oscillator of notebook 13 (m = 1 kg, k = 100 N/m, F = 1 N, F/P = 0.8)
  over r = omega/omega_n in [0.2, 3]: its branch by ``response_curve`` (the API
  of ``python -m lumped response``), the points on it and the time per point;
* the two-mass example, ``examples/two_mass_response.toml`` over 2 to 25 rad/s
  (its header's command): the same;

then, best of 3 too, the brute-force sweep that gives the Coulomb curve at the same
frequencies, notebook 11's protocol (a run of the exact solver from rest for
30 s plus two windows of five periods, :func:`lumped.studies.den_hartog.steady_state`),
the ratio of the two times, and how many of those runs have not settled (their two windows' amplitudes
differ by more than 1e-8 relative, notebook 11's test): a brute force that gave every point of the curve would
need longer runs there.  The first line gives the load average: the
machine may be shared, and the figures are what this run saw.
"""

from __future__ import annotations

import math
import os
import time
from pathlib import Path

import lumped as L
from lumped.model.problem import oscillator_network
from lumped.studies.den_hartog import steady_state

ROOT = Path(__file__).resolve().parent.parent
M, K, F, RATIO = 1.0, 100.0, 1.0, 0.8


def best(run, repeats: int = 3) -> tuple[float, object]:
    """The shortest wall time of ``repeats`` calls, and the last call's result."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        out = run()
        times.append(time.perf_counter() - start)
    return min(times), out


def main() -> None:
    print(f"{os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.2f}")
    wn = math.sqrt(K / M)
    one = oscillator_network(L.Oscillator.bingham(M, K, F, math.inf))
    seconds, curve = best(lambda: L.response_curve(one, "m", F / RATIO, 0.2 * wn, 3.0 * wn, points=200))
    omega = curve.columns["omega"]
    print(
        f"one mass (Coulomb, F/P = {RATIO}): {omega.size} points in {seconds:.2f} s, {1e3 * seconds / omega.size:.1f} ms per point"
    )
    two = L.load_system(ROOT / "examples" / "two_mass_response.toml")
    seconds2, curve2 = best(lambda: L.response_curve(two, "m1", 5.0, 2.0, 25.0, points=30))
    n2 = curve2.columns["omega"].size
    print(
        f"two masses (examples/two_mass_response.toml): {n2} points in {seconds2:.2f} s, {1e3 * seconds2 / n2:.1f} ms per point"
    )
    osc = L.Oscillator.bingham(M, K, F, math.inf)
    brute, runs = best(lambda: [steady_state(osc, F / RATIO, float(w)) for w in omega])
    print(
        f"brute force at the same {omega.size} frequencies (runs from rest, 30 s + 10 periods): {brute:.1f} s, "
        f"{1e3 * brute / omega.size:.0f} ms per point; continuation {brute / seconds:.0f} times cheaper"
    )
    unsettled = sum(1 for run in runs if abs(run.amplitude - run.previous) > 1e-8 * run.amplitude)
    print(f"brute-force points not settled to 1e-8 (notebook 11's test): {unsettled} of {omega.size}")


if __name__ == "__main__":
    main()
