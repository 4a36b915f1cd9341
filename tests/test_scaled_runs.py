"""Exact rescalings of the paper's run (issue 19): the solvers give the same nondimensional answer.

Multiplying mass, stiffness, threshold and force amplitude by ``s`` and
``gamma`` by ``1/s`` leaves ``x(t)`` and ``v(t)`` unchanged and multiplies
every force by ``s``.  With ``s`` a power of two of even exponent, every
quantity the solvers form is homogeneous in ``s`` and rescaled *exactly*
(products, quotients and ``sqrt`` of powers of two round the same way as the
unscaled numbers) as long as nothing underflows or overflows: so the answers
must agree bit for bit, and any ``inf``, ``0`` or subnormal on the way (such
as ``sqrt(m k)`` at ``m = 2**-664``) shows up as a difference.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import lumped as L
from lumped.cli import main

SCALES = [2.0**-664, 2.0**664, 2.0**-1000]  # about 1e-200, 1e200, 1e-301
GAMMAS = [1.0, math.inf, 0.01]  # underdamped, Coulomb, overdamped slip


def oscillator(s: float, gamma: float) -> L.Oscillator:
    return L.Oscillator(mass=s, spring=L.LinearSpring(100 * s), dashpot=L.BinghamDashpot(s, gamma / s))


@pytest.mark.parametrize("solve", [L.solve_exact, L.solve_event_driven], ids=["exact", "event-driven"])
@pytest.mark.parametrize("gamma", GAMMAS)
@pytest.mark.parametrize("s", SCALES)
def test_rescaled_run_is_the_paper_run(solve, gamma: float, s: float) -> None:
    paper = solve(oscillator(1.0, gamma), 3.0, x0=0.5, force=L.SwitchedSine(10.0, 5.0, 0.3, 2.0)).sample(1e-3)
    scaled = solve(oscillator(s, gamma), 3.0, x0=0.5, force=L.SwitchedSine(10.0 * s, 5.0, 0.3, 2.0)).sample(1e-3)
    assert np.array_equal(scaled.x, paper.x) and np.array_equal(scaled.v, paper.v)
    assert np.array_equal(scaled.F_d, paper.F_d * s)


@pytest.mark.parametrize("method", ["exact", "event-driven"])
def test_command_line_on_the_issue_rescaling(tmp_path, capsys, method: str) -> None:
    """The command of the issue (decimal magnitudes) runs; a power-of-two one matches bit for bit."""

    def run(name: str, s: float, gamma: str) -> np.lib.npyio.NpzFile:
        out = tmp_path / f"{name}.npz"
        magnitudes = {"--mass": s, "--stiffness": 100 * s, "--threshold": s, "--force-amplitude": 10 * s}
        args = [a for flag, value in magnitudes.items() for a in (flag, repr(value))]
        common = ["--gamma", gamma, "--x0", "0.5", "--force-omega", "5", "--t-end", "1", "--dt", "1e-3"]
        status = main(["simulate", "--method", method, *args, *common, "--output", str(out)])
        assert status == 0, capsys.readouterr().err
        return np.load(out)

    run("issue", 1e-200, "1e200")  # the issue's magnitudes: ZeroDivisionError before
    paper, scaled = run("paper", 1.0, "1"), run("scaled", 2.0**-664, repr(2.0**664))
    assert np.array_equal(scaled["x"], paper["x"]) and np.array_equal(scaled["v"], paper["v"])
