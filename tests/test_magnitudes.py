"""Magnitudes where the representation of Algorithm 1 fails are refused, naming the parameter at fault (issue 19).

Algorithm 1 carries the displacement as the spring force, ``x = F_s/k``; a
subnormal parameter or product (below ``2^-1022``) keeps fewer than the 53
bits of a double, and ``k = 1e-322`` gave ``x = 0`` on every row while
``v = 1``.  :func:`lumped.model.oscillator.check_magnitudes` derives the bounds; the
sweep applies the same bounds to every row at once
(:func:`lumped.model.oscillator.magnitude_failures`).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import lumped as L
from lumped.cli import main
from lumped.model.oscillator import TINY, check_magnitudes, magnitude_failures

#: (command-line options, the option the one line must begin with, methods that refuse it)
BOTH, BE = ("backward-euler", "exact"), ("backward-euler",)
CASES = [
    (["--stiffness", "1e-322", "--threshold", "0", "--gamma", "inf", "--v0", "1"], "--stiffness", BOTH),
    (["--mass", "1e-320"], "--mass", BOTH),  # was blamed on --x0
    (["--mass", "1e-320", "--x0", "0.5"], "--mass", BOTH),
    (["--gamma", "1e-320"], "--gamma", BOTH),  # 1/gamma = inf; was blamed on --v0 by the exact method
    (["--stiffness", "1e-300", "--dt", "1e-10", "--t-end", "1e-9"], "--stiffness", BE),  # k dt = 1e-310
    (["--mass", "1e-10", "--dt", "1e300", "--t-end", "2e300"], "--dt", BE),  # m/dt = 1e-310
]


RUNS = [(argv, option, method) for argv, option, methods in CASES for method in methods]


@pytest.mark.parametrize(("argv", "option", "method"), RUNS, ids=[" ".join([*a, m]) for a, _, m in RUNS])
def test_subnormal_magnitudes_are_refused_naming_the_parameter(tmp_path, capsys, argv, option, method):
    out = tmp_path / "run.csv"
    status = main(["simulate", *argv, "--method", method, "--output", str(out)])
    err = capsys.readouterr().err.strip()
    assert status == 2 and len(err.splitlines()) == 1, err
    assert err.startswith(f"lumped simulate: error: {option}:") and "normal double" in err, err
    assert not out.exists()


def test_a_tiny_state_beside_larger_terms_runs():
    """v0 = 1e-320 beside x0 = 0.5 loses nothing that matters: accepted."""
    tr = L.backward_euler(L.Oscillator.bingham(), 0.1, 1e-3, x0=0.5, v0=1e-320)
    assert tr.x[0] == 0.5


def test_the_issue_case_through_the_api():
    """Before the check the run gave x = 0 on every row while v = 1 (the exact method gives 1.0)."""
    with pytest.raises(ValueError, match=r"^stiffness: .* below the smallest normal double"):
        L.Oscillator.bingham(stiffness=1e-322, threshold=0.0, gamma=math.inf)
    osc = L.Oscillator.bingham(stiffness=1e-306, threshold=0.0, gamma=math.inf)  # normal, but k dt is not
    with pytest.raises(ValueError, match=r"^stiffness: k\*dt = 1e-309 is below the smallest normal double"):
        L.backward_euler(osc, 1.0, 1e-3, v0=1.0)


@pytest.mark.parametrize("k", [TINY, 1e-300, 1.0, 1e300])
def test_normal_values_at_the_bounds_still_run(k):
    """The bound is the smallest normal double itself: k = TINY with k dt and k x0 >= TINY runs."""
    osc = L.Oscillator.bingham(stiffness=k, threshold=0.0, gamma=math.inf)
    dt = 1.0 if k < 1 else 1e-3
    x0 = 4.0 if k < 1 else 1e-3
    tr = L.backward_euler(osc, 4 * dt, dt, x0=x0)
    assert tr.x[0] == x0  # F_s(0)/k gives x0 back: no digit lost


@pytest.mark.parametrize(
    "row",
    [
        dict(mass=1.0, stiffness=100.0, threshold=1.0, gamma=1.0, x0=0.5, v0=0.0, amplitude=0.0),
        dict(mass=1e-300, stiffness=100.0, threshold=1.0, gamma=1.0, x0=0.5, v0=0.0, amplitude=0.0),
        dict(mass=1.0, stiffness=1e-306, threshold=0.0, gamma=math.inf, x0=0.0, v0=1.0, amplitude=0.0),
        dict(mass=1.0, stiffness=1.0, threshold=0.0, gamma=math.inf, x0=1e-320, v0=0.0, amplitude=0.0),
        dict(mass=1e-300, stiffness=1.0, threshold=0.0, gamma=math.inf, x0=1.0, v0=0.0, amplitude=0.0),
        dict(mass=1.0, stiffness=1e-200, threshold=1.0, gamma=1.0, x0=1e-110, v0=0.0, amplitude=0.0),
        dict(mass=1.0, stiffness=100.0, threshold=1.0, gamma=1.0, x0=1e160, v0=0.0, amplitude=0.0),
        dict(mass=1.0, stiffness=100.0, threshold=1.0, gamma=1e-300, x0=0.0, v0=1.0, amplitude=0.0),
        dict(mass=1.0, stiffness=100.0, threshold=1.0, gamma=1.0, x0=0.0, v0=0.0, amplitude=1e300),
        dict(mass=2.0**-996, stiffness=2.0**-996, threshold=0.0, gamma=math.inf, x0=1e-10, v0=0.0, amplitude=0.0),
        dict(mass=2.0**-996, stiffness=2.0**-996, threshold=1.0, gamma=math.inf, x0=1e-10, v0=0.0, amplitude=0.0),
        dict(mass=1.0, stiffness=1e-300, threshold=0.0, gamma=1.0, x0=0.0, v0=1e-20, amplitude=1e-310),
    ],
)
def test_the_array_form_agrees_with_the_scalar_check(row):
    """magnitude_failures (a sweep's rows at once) refuses exactly what check_magnitudes refuses."""
    osc = L.Oscillator.bingham(row["mass"], row["stiffness"], row["threshold"], row["gamma"])
    try:
        check_magnitudes(osc, 2.0, 1e-3, row["x0"], row["v0"], row["amplitude"])
        refused = False
    except ValueError:
        refused = True
    args = [np.array([row[n]]) for n in ("mass", "stiffness", "gamma")]
    state = (np.array([row["x0"]]), np.array([row["v0"]]), row["amplitude"])
    bad = magnitude_failures(*args, 2.0, 1e-3, *state)
    assert bad.tolist() == [refused]


def test_a_sweep_refuses_a_subnormal_row_naming_the_parameter(tmp_path, capsys):
    out = tmp_path / "s.csv"
    assert main(["sweep", "--vary", "mass=1e-320:1:3", "--output", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("lumped sweep: error: --vary: mass: 1e-320 is below the smallest normal double"), err


@pytest.mark.parametrize("exponent", [-900, -996])
def test_a_run_whose_every_force_is_subnormal_is_refused(exponent):
    """m = k = 2^e, x0 = 1e-10, no threshold: every force is about 2^e 1e-10.

    Scaling m and k by a power of two scales m/dt, k dt and every force exactly, so
    while the forces stay normal the displacements are those of m = k = 1 bit for
    bit (2^-900 1e-10 = 1.2e-281).  At 2^-996 they are about 1.5e-310, subnormal,
    and the run differed from the unscaled one by 3.4e-13 of x0: refused, naming x0.
    """
    scaled = L.Oscillator.bingham(2.0**exponent, 2.0**exponent, 0.0, math.inf)
    unscaled = L.backward_euler(L.Oscillator.bingham(1.0, 1.0, 0.0, math.inf), 1.0, 1e-3, x0=1e-10)
    if exponent == -900:
        assert np.array_equal(L.backward_euler(scaled, 1.0, 1e-3, x0=1e-10).x, unscaled.x)
    else:  # the exact solver carries x itself: it runs and keeps x0 to the last bit at t = 0
        assert L.solve_exact(scaled, 1.0, x0=1e-10).sample(1e-3).x[0] == 1e-10
        with pytest.raises(
            ValueError, match=r"^x0: every spring and external force of the run stays below 1\.\d+e-310 N"
        ):
            L.backward_euler(scaled, 1.0, 1e-3, x0=1e-10)


def test_a_run_whose_every_force_is_subnormal_is_refused_on_the_command_line(tmp_path, capsys):
    out = tmp_path / "run.csv"
    argv = ["simulate", "--mass", "1e-300", "--stiffness", "1e-300", "--threshold", "0", "--gamma", "inf"]
    assert main([*argv, "--x0", "1e-10", "--output", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert (
        err.startswith("lumped simulate: error: --x0: every spring and external force of the run stays below")
        and len(err.splitlines()) == 1
    )
    assert not out.exists()
