"""The textbook ODE with sgn(0) = 0 (section 2.2): chatter, stalls, creep."""

from __future__ import annotations

import math

import numpy as np
import pytest
import references

import lumped as L
from lumped.solvers.textbook import TextbookModel, integrate_adaptive, integrate_fixed

X0 = 0.005  # Figure 10: inside the static band tau/k = 0.01


def test_forward_euler_chatters_where_the_dae_rests(paper_oscillator):
    # From rest at x0 = 0.005, sgn(0) = 0 gives F_d = 0, the spring pushes the
    # mass, friction +-tau reverses it within a step: the velocity changes
    # sign about every other step (measured 2506 in 5000 steps).  Backward
    # Euler on the DAE keeps v == 0 and F_d = -k x0 (test_algorithm1).
    dt, t_end = 1e-4, 0.5
    r = integrate_fixed(TextbookModel(paper_oscillator), t_end, dt, x0=X0)
    n = len(r.t) - 1
    assert r.sign_changes == references.sign_changes(r.v) >= n // 4
    # the chatter amplitude is one step's worth of acceleration (tau + k x)/m dt
    assert np.abs(r.v).max() <= 2 * (1.0 + 100.0 * 0.01) * dt
    tail = r.F_d[n // 2 :][r.v[n // 2 :] != 0]
    # F_d = sgn(v) tau + v/gamma: +-tau up to c |v| <= 1 * 2e-4 -- never the
    # static value -k x0 = -0.5 that the DAE gives.
    assert np.all(np.abs(np.abs(tail) - 1.0) <= np.abs(r.v).max())
    assert np.all(np.abs(tail + 100.0 * X0) > 0.4)
    assert np.any(tail > 0) and np.any(tail < 0)
    dae = L.backward_euler(paper_oscillator, t_end, dt, x0=X0)
    assert np.all(dae.F_d[1:] == -100.0 * X0) and np.all(dae.v == 0)


def test_rk4_drifts_where_the_dae_rests(paper_oscillator):
    # RK4 averages the sign flips inside each step instead: v stays negative
    # and alternates in size (~1.7e-5 / 6.7e-5 m/s), so the mass slides
    # towards the origin inside the band (measured 2.7e-6 m in 0.1 s), with a
    # dashpot force at -tau, never the static -k x0 = -0.5.
    r = integrate_fixed(TextbookModel(paper_oscillator), 0.1, 1e-4, x0=X0, scheme="rk4")
    assert np.all(r.v[1:] < 0)
    assert r.x[-1] < X0 - 1e-6
    assert np.all(np.abs(r.F_d[1:] + 1.0) <= np.abs(r.v).max())


def test_adaptive_rk45_runs_out_of_budget(paper_oscillator):
    # The step-size control keeps meeting the jump of sgn at v = 0 and shrinks
    # the step towards zero; 20000 evaluations do not reach t = 1 s.
    out = integrate_adaptive(TextbookModel(paper_oscillator), 1.0, x0=X0, max_nfev=20_000, max_seconds=60.0)
    assert not out.finished
    assert "budget" in out.message
    assert out.nfev >= 20_000
    assert out.t_reached < 1e-2
    assert out.t[-1] == out.t_reached and len(out.t) == len(out.x) == len(out.v)


def test_adaptive_finishes_outside_the_band(paper_oscillator):
    # Control: the same integrator, released far outside the band with a
    # regularised law, does finish; so the stall above is the model's fault.
    out = integrate_adaptive(TextbookModel(paper_oscillator, eps=1e-2), 0.5, x0=0.5, max_nfev=200_000)
    assert out.finished and "reached" in out.message and out.t_reached == 0.5


@pytest.mark.parametrize("eps", [1e-2, 3e-3])
@pytest.mark.parametrize("x0", [0.001, 0.005])
def test_tanh_regularisation_creeps_at_the_predicted_rate(paper_oscillator, eps, x0):
    # Near v = 0, tau tanh(v/eps) ~ tau v/eps: an overdamped viscous law with
    # C = tau/eps + c (c = 1/gamma = 1 here).  m x'' + C x' + k x = 0 has the
    # slow root s = (-C + sqrt(C^2 - 4 m k)) / (2m) ~ -k/C ~ -k eps/tau, so
    # after the fast mode (rate C/m >= 100/s) dies x ~ exp(s t): the mass
    # creeps inside the static band where the DAE has it at rest.
    # Tolerance: the cubic of tanh makes the law softer, so the creep is
    # faster by the factor artanh(y)/y with y = k x/tau <= k x0/tau (the
    # quasi-static rate); fitted slope / s lies in [1, artanh(y0)/y0], with
    # 1e-4 below for the RK4 error and the fast-mode remainder (e^-20).
    m, k, tau, c = 1.0, 100.0, 1.0, 1.0
    model = TextbookModel(paper_oscillator, eps=eps)
    r = integrate_fixed(model, 3.0, 1e-3, x0=x0, scheme="rk4")
    window = r.t >= 0.2
    slope = references.slope(r.t[window], np.log(r.x[window]))
    big_c = tau / eps + c
    s = (-big_c + math.sqrt(big_c**2 - 4 * m * k)) / (2 * m)
    y0 = k * x0 / tau
    ratio = slope / s
    assert 1 - 1e-4 <= ratio <= math.atanh(y0) / y0
    # and against the first-order closed form dx/dt = -k x eps/tau, whose gap
    # to s is known: |s/(-k eps/tau) - 1|
    linear = -k * eps / tau
    gap = abs(s / linear - 1)
    assert abs(slope / linear - 1) <= (math.atanh(y0) / y0 - 1) + gap + 1e-4
    # it does move: the DAE would keep x == x0
    assert r.x[-1] < x0 * math.exp(0.9 * s * 3.0)


def test_textbook_force_and_rhs(paper_oscillator):
    model = TextbookModel(paper_oscillator, force=lambda t: 2.0)
    assert model.dashpot_force(0.0) == 0.0  # the convention sgn(0) = 0
    assert model.dashpot_force(0.5) == 1.0 + 0.5
    np.testing.assert_array_equal(model.rhs(0.0, np.array([0.01, 0.0])), [0.0, 2.0 - 1.0])
