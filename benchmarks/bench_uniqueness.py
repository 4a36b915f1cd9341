"""Time of the dt-bound refusal of a 2000-mass falling-friction chain, printed (a benchmark, not a test).

Run from the repository root:  python benchmarks/bench_uniqueness.py [--quick]

The chains: ``bench_chain.py``'s 2000 blocks of 1 kg on a Stribeck floor (each
contact falling exponentially from its static ~1 N to 0.6 N over 0.02 m/s, a
fall of up to 25 N s/m), leaf springs to a moving plate and coupling springs,
and the same blocks joined to their neighbours by falling contacts (static
2 N, kinetic 1 N, Stribeck velocity 0.1 m/s) instead of coupling springs.
``dt = 0.5`` s is above both bounds, so ``check_step`` refuses it and bisects
for the largest admissible step (some 40 factorisations of ``A(dt)``, see
``lumped.solvers.uniqueness``).

Printed: the best wall time of several repeats of the refusal (target: under
2 s; a dense Cholesky per probe took 60-95 s on a loaded machine), and the
step it names.
"""

from __future__ import annotations

import argparse
import os
import sys
import time

from lumped import Driver, Friction, Mass, Network, Spring
from lumped.solvers.uniqueness import check_step

sys.path.insert(0, os.path.dirname(__file__))
from bench_chain import floor_chain

N = 2000
DT = 0.5


def coupled_chain(n: int) -> Network:
    """``n`` blocks on leaf springs to a moving plate, neighbours joined by falling contacts."""
    masses = [Mass(f"m{i}", 1.0) for i in range(n)]
    elements = [Spring(f"leaf{i}", ("plate", f"m{i}"), 10.0) for i in range(n)]
    law = {"static": 2.0, "kinetic": 1.0, "stribeck_velocity": 0.1}
    elements += [Friction(f"c{i}", (f"m{i - 1}", f"m{i}"), **law) for i in range(1, n)]
    return Network(masses, elements, (), [Driver("plate", 0.1)])


def refusal(net: Network, repeats: int) -> tuple[float, str]:
    """The best wall time of ``check_step(net, DT)``'s refusal, and its message's named step."""
    best, message = float("inf"), ""
    for _ in range(repeats):
        start = time.perf_counter()
        try:
            check_step(net, DT)
        except ValueError as error:
            message = str(error)
        best = min(best, time.perf_counter() - start)
    return best, message.rsplit("; ", 1)[-1]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one repeat")
    repeats = 1 if parser.parse_args().quick else 3
    for label, net in (("Stribeck floor", floor_chain(N, stribeck_velocity=0.02)), ("falling links", coupled_chain(N))):
        seconds, named = refusal(net, repeats)
        print(f"{N}-mass chain, {label}: refusal of dt = {DT} s in {seconds:.3f} s (target < 2 s), {named}")


if __name__ == "__main__":
    main()
