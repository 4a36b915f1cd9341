"""The fit of issue 24 on 100 seeded synthetic records: how often two standard errors cover the truth (printed).

Run from the repository root:  python benchmarks/bench_fit.py [--trials N] [--first SEED] [--starts K]

The paper's free decay (examples/figure3.toml: m = 1 kg, k = 100 N/m, tau = 1 N, gamma = 1 m/(N s),
x0 = 0.5 m), sampled at 201 times over 4 s with Gaussian noise of 2 mm (seeds SEED to SEED + N - 1), fitted for
tau, gamma and k from tau = 0.8, gamma = 1.3, k = 101 by ``lumped.drivers.fit.fit`` with K starts (its
default 4; 1 is the local fit from the file's values alone, grown over the record).  For each
parameter it prints in how many trials ``|estimate - truth| <= 2 standard errors`` (95 expected of a
linear Gaussian model; ``tests/test_fit.py`` asserts at least 90 of 100), the mean estimate and the
mean standard error, the model runs and the wall time per fit (this machine's; not asserted anywhere),
and the same for the issue 31 start (1.1, 0.9, 95) on the noise-free record, which a fit on the whole
record alone ends at (1.42, 1.22, 100.14).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from lumped.drivers.fit import fit
from lumped.drivers.sensitivity import system_sensitivities
from lumped.model.files import load_system
from lumped.model.records import Record
from lumped.model.system_parameters import system_parameters, with_values

FREE = "dashpot.threshold,dashpot.gamma,spring.stiffness"
TRUTH = np.array([1.0, 1.0, 100.0])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--first", type=int, default=0)
    parser.add_argument("--starts", type=int, default=4)
    args = parser.parse_args()
    trials = args.trials
    net = load_system(Path(__file__).resolve().parent.parent / "examples" / "figure3.toml")
    start = with_values(net, system_parameters(net, FREE), [0.8, 1.3, 101.0])
    t = np.linspace(0.0, 4.0, 201)
    solution, _ = system_sensitivities(net, t, ["m.x0"])
    exact = solution.evaluate(t)["x"]
    hits, estimates, errors, runs = np.zeros(3, dtype=int), [], [], 0
    began = time.perf_counter()
    for seed in range(args.first, args.first + trials):
        noise = 2e-3 * np.random.default_rng(seed).standard_normal(t.size)
        result = fit(start, Record(t, {"m": exact + noise}), FREE, starts=args.starts)
        runs += result.evaluations
        hits += np.abs(result.estimate - TRUTH) <= 2 * result.standard_error
        estimates.append(result.estimate)
        errors.append(result.standard_error)
    wall = (time.perf_counter() - began) / trials
    mean, se = np.mean(estimates, axis=0), np.mean(errors, axis=0)
    for j, name in enumerate(FREE.split(",")):
        print(
            f"{name}: within 2 standard errors in {hits[j]} of {trials}; mean {mean[j]:.5g} (truth {TRUTH[j]:g}), "
            f"mean standard error {se[j]:.2g}, spread of the estimates {np.std(estimates, axis=0)[j]:.2g}"
        )
    print(f"{args.starts} starts: {runs / trials:.0f} model runs and {wall * 1e3:.0f} ms per fit")
    far = with_values(net, system_parameters(net, FREE), [1.1, 0.9, 95.0])
    began = time.perf_counter()
    result = fit(far, Record(t, {"m": exact}), FREE, starts=args.starts)
    wall = time.perf_counter() - began
    print(f"from (1.1, 0.9, 95), no noise: {result.summary()}; {result.evaluations} model runs, {wall * 1e3:.0f} ms")


if __name__ == "__main__":
    main()
