"""Run Siconos' FrictionOscillator example and write its rows (the peer of ``--method moreau-jean``).

Run with the Python that has Siconos (Debian's ``python3-siconos`` installs
it for the system interpreter, not for a virtual environment)::

    /usr/bin/python3 scripts/siconos_friction_oscillator.py [--t-end 40] [--output rows.csv]

The system is the example's (siconos/siconos-tutorials,
examples/mechanics/FrictionOscillator/FrictionOscillator.py): a unit mass on a
unit spring with Coulomb friction of bound 1, ``x' = A x + B lambda`` with
``A = [[0, 1], [-k/m, 0]]``, ``B = [0, 1]``, the relay ``y = C x = v`` (the
velocity at the new level) with ``lambda`` in ``-Sgn(y)`` (``RelayNSL(1, -1,
1)``), integrated by ``EulerMoreauOSI(theta)`` (the smooth part by the
θ-rule, ``r = B lambda`` at the new level) with a Lemke relay solver, from
``x0 = 12``, ``v0 = 6`` at ``h = 0.01``, ``theta = 1/2``.

It writes one row per step, as the example keeps them: ``t, x, v, lambda, y``
(``lambda`` is the friction force on the mass, so ``-lambda`` is our dashpot
force ``F_d``; ``y`` is the relay's velocity), with 17 significant digits.
It imports only Siconos and NumPy, so that it runs outside the project's
environment; ``tests/test_moreau_jean_siconos.py`` runs it and compares.
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np


def run(t_end: float, h: float = 0.01, theta: float = 0.5, x0: float = 12.0, v0: float = 6.0) -> np.ndarray:
    """The example's rows ``(t, x, v, lambda, y)`` from ``t = 0`` to the first step at or after ``t_end``."""
    import siconos.kernel as sk
    import siconos.numerics as sn

    m, stiffness, bound = 1.0, 1.0, 1.0
    a = np.array([[0.0, 1.0], [-stiffness / m, 0.0]])
    oscillator = sk.FirstOrderLinearTIDS([x0, v0], a)
    relation = sk.FirstOrderLinearR(np.array([[0.0, 1.0]]), np.array([[0.0], [1.0]]))
    interaction = sk.Interaction(sk.RelayNSL(1, -bound, bound), relation)
    system = sk.NonSmoothDynamicalSystem(0.0, t_end)
    system.insertDynamicalSystem(oscillator)
    system.link(interaction, oscillator)
    relay = sk.Relay()
    relay.setSolverId(sn.SICONOS_RELAY_LEMKE)
    relay.numericsSolverOptions().dparam[0] = 1e-8  # the example's tolerance
    simulation = sk.TimeStepping(system, sk.TimeDiscretisation(0.0, h), sk.EulerMoreauOSI(theta), relay)
    x, lam, y = oscillator.x(), interaction.lambda_(0), interaction.y(0)
    rows = [(0.0, x[0], x[1], lam[0], y[0])]
    while simulation.hasNextEvent():
        simulation.computeOneStep()
        rows.append((simulation.nextTime(), x[0], x[1], lam[0], y[0]))
        simulation.nextStep()
    return np.array(rows)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--t-end", type=float, default=40.0, help="end of the run (s), default 40")
    parser.add_argument("--output", default="-", help="CSV file to write (default: standard output)")
    args = parser.parse_args(argv)
    if not (math.isfinite(args.t_end) and args.t_end > 0):
        parser.error(f"--t-end must be a positive number, got {args.t_end}")
    rows = run(args.t_end)
    out = sys.stdout if args.output == "-" else open(args.output, "w", encoding="utf-8")  # noqa: SIM115
    try:
        out.write("t,x,v,lambda,y\n")
        np.savetxt(out, rows, delimiter=",", fmt="%.17g")
    finally:
        if out is not sys.stdout:
            out.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
