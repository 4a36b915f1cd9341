"""Backward Euler converges to the exact solution at observed order 1.

The order is the slope of log(error) against log(dt), fitted over a halving
sequence of steps (diffrax's ``test_ode_order``), and asserted in [0.9, 1.1].
For the maximum displacement error the ranges are the brief's 4e-3 ... 2.5e-4
(the Coulomb case, undamped but for friction, needs smaller steps to be in the
asymptotic range over 2 s).  For the rest position the range starts where the
discrete solution stops after the same number of half-cycles as the exact
one: coarser steps lose a half-cycle to the numerical damping of backward
Euler, a jump rather than an O(dt) error.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import lumped as L

PAPER = dict(mass=1.0, stiffness=100.0, threshold=1.0)

# name -> (gamma, solver kwargs, t_end, dts)
CASES = {
    "free-x0-0.5": (1.0, dict(x0=0.5), 5.0, [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4]),
    "forced-17b": (1.0, dict(force=L.paper_forcing(10.0)), 3.0, [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4]),
    "coulomb-free": (math.inf, dict(x0=0.5), 2.0, [1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5]),
    "overdamped-17b": (0.01, dict(force=L.paper_forcing(10.0)), 3.0, [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4]),
    "v0-phase": (2.0, dict(x0=0.1, v0=-3.0, force=L.SwitchedSine(-4.0, 7.0, 0.3, 1.5)), 3.0,
                 [1e-3, 5e-4, 2.5e-4, 1.25e-4]),
}  # fmt: skip


def _order(dts, errors) -> float:
    return float(np.polyfit(np.log(dts), np.log(errors), 1)[0])


@pytest.mark.parametrize("case", CASES)
def test_max_displacement_error_is_first_order(case):
    gamma, kwargs, t_end, dts = CASES[case]
    osc = L.Oscillator.bingham(gamma=gamma, **PAPER)
    sol = L.solve_exact(osc, t_end, **kwargs)
    errors = [
        np.abs(L.backward_euler(osc, t_end, dt, **kwargs).x - sol.sample(dt).x).max()
        for dt in dts
    ]
    assert 0.9 <= _order(dts, errors) <= 1.1


# Rest position: the free decay needs dt <= 1e-3 for backward Euler to stop
# after the same number of half-cycles as the exact solution (at 2e-3 and
# 4e-3 it stops one earlier: a jump, not O(dt)).
REST = {
    "free-x0-0.5": (1.0, dict(x0=0.5), 5.0, [1e-3, 5e-4, 2.5e-4, 1.25e-4]),
    "forced-17b": (1.0, dict(force=L.paper_forcing(10.0)), 3.0, [4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4]),
}


@pytest.mark.parametrize("case", REST)
def test_rest_position_error_is_first_order(case):
    gamma, kwargs, t_end, dts = REST[case]
    osc = L.Oscillator.bingham(gamma=gamma, **PAPER)
    sol = L.solve_exact(osc, t_end, **kwargs)
    errors = [abs(L.backward_euler(osc, t_end, dt, **kwargs).rest_position - sol.rest_position)
              for dt in dts]  # fmt: skip
    assert 0.9 <= _order(dts, errors) <= 1.1


@pytest.mark.parametrize("case", REST)
def test_rest_time_error_is_order_dt(case):
    # The rest time of backward Euler is a grid point, so its error has an
    # O(dt) part plus a quantisation in [0, dt): the fitted slope is noisy but
    # the error divided by dt stays bounded (measured: at most ~3.5).
    gamma, kwargs, t_end, dts = REST[case]
    osc = L.Oscillator.bingham(gamma=gamma, **PAPER)
    sol = L.solve_exact(osc, t_end, **kwargs)
    for_each = [abs(L.backward_euler(osc, t_end, dt, **kwargs).rest_time - sol.rest_time) / dt
                for dt in dts]  # fmt: skip
    assert max(for_each) <= 5.0
