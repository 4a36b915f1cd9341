"""The regularised Bingham dashpot of :mod:`lumped.laws.regularised`: a law added through the contract alone."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import EPS
from scipy.integrate import solve_ivp
from scipy.special import lambertw

import lumped as L

M, K, TAU, X0, T_END = 1.0, 100.0, 1.0, 0.1, 1.0


def _oscillator(eps: float, gamma: float = 1.0) -> L.Oscillator:
    return L.Oscillator(M, L.LinearSpring(K), L.PapanastasiouDashpot(TAU, gamma, eps))


def _reference(eps: float, t: np.ndarray, gamma: float = 1.0) -> np.ndarray:
    """``x(t)`` of the smooth ODE ``m x'' = -k x - F_d(x')`` by SciPy's Radau (implicit: the creep is stiff)."""
    law = L.PapanastasiouDashpot(TAU, gamma, eps)
    viscous = law.viscous_part()
    sol = solve_ivp(
        lambda _, y: (y[1], (-K * y[0] - viscous(y[1])) / M),
        (0.0, float(t[-1])),
        (X0, 0.0),
        method="Radau",
        t_eval=t,
        rtol=1e-12,
        atol=1e-15,
    )
    assert sol.success
    return sol.y[0]


# --------------------------------------------------------------------------- the graph


@pytest.mark.parametrize("gamma", [1.0, 0.01, math.inf])
def test_graph_is_monotone_through_zero_and_dissipates(gamma):
    law = L.PapanastasiouDashpot(TAU, gamma, 1e-2)
    forces = np.linspace(-0.999, 0.999, 2001) * (TAU if math.isinf(gamma) else 5 * TAU)
    v = law.velocity(forces)
    assert law.threshold == 0.0 and law.velocity(0.0) == 0.0 and law.force_interval(0.0) == (0.0, 0.0)
    assert np.all(np.diff(v) > 0)  # strictly increasing: no band, the mass creeps
    assert np.all(forces * v >= 0)
    # the graph and its inverse: F_d(phi(F)) = F to a few ulps of the force scale
    np.testing.assert_allclose(law.slip_force(v), forces, rtol=0, atol=8 * EPS * np.max(np.abs(forces)))


@pytest.mark.parametrize("eta", [1e-3, 1.0, 1e4])
@pytest.mark.parametrize("predictor", [-1e8, -3.0, -1.0, -0.2, 1e-9, 0.5, 0.999, 1.0, 2.0, 1e12])
def test_resolvent_solves_its_equation(predictor, eta):
    law = L.PapanastasiouDashpot(TAU, 1.0, 1e-2)
    force, v = law.resolvent(predictor, eta)
    # F + eta phi(F) = F~ to a few ulps of the terms (Newton stops at no progress)
    assert abs(force + eta * v - predictor) <= 8 * EPS * (abs(predictor) + abs(force))
    assert float(law.slip_force(v)) == force  # the force is the law's at the speed found
    assert np.sign(force) == np.sign(v) == np.sign(predictor)


def test_eps_to_zero_gives_the_bingham_slip_force():
    # |F_eps(v) - F_B(v)| = tau exp(-|v|/eps) for v != 0: the exact gap, to a few ulps
    v = np.array([-2.0, -0.1, 0.05, 1.0])
    bingham = L.BinghamDashpot(TAU, 1.0).slip_force(v)
    for eps in (1e-1, 1e-2, 1e-3):
        gap = np.abs(L.PapanastasiouDashpot(TAU, 1.0, eps).slip_force(v) - bingham)
        np.testing.assert_allclose(gap, TAU * np.exp(-np.abs(v) / eps), rtol=0, atol=4 * EPS * 3)


@pytest.mark.parametrize(
    ("kwargs", "name"), [({"yield_force": -1.0}, "yield_force"), ({"eps": 0.0}, "eps"), ({"gamma": -1.0}, "gamma")]
)
def test_bad_parameters_are_refused_by_name(kwargs, name):
    with pytest.raises(ValueError, match=f"^{name}"):
        L.PapanastasiouDashpot(**kwargs)


# --------------------------------------------------------------------------- the methods, no solver edited


def _slope(dts: list[float], errors: list[float]) -> float:
    return float(np.polyfit(np.log(dts), np.log(errors), 1)[0])


@pytest.mark.slow  # a convergence study: the slow suite (.ci/run runs it)
@pytest.mark.parametrize(("method", "order"), [("backward_euler", 1), ("theta_method", 2)])
def test_time_stepping_converges_at_its_order_to_the_smooth_ode(method, order):
    # eps = 1e-2 keeps the ODE smooth on the scale of the steps; the slope of
    # log(error) against log(dt) must be the method's order within 10 %
    run, dts, errors = getattr(L, method), [4e-4, 2e-4, 1e-4], []
    for dt in dts:
        tr = run(_oscillator(1e-2), T_END, dt, x0=X0)
        errors.append(float(np.max(np.abs(tr.x - _reference(1e-2, tr.t)))))
    assert abs(_slope(dts, errors) - order) <= 0.1 * order
    # and the error constant is that of the method on the undamped oscillator
    # (omega = sqrt(k/m)), which the dashpot only damps: backward Euler's
    # numerical damping |1 + i omega dt|^-n ~ exp(-omega^2 dt t/2) costs at most
    # X0 omega^2 dt T/2; the trapezoidal rule's phase error omega^3 dt^2 t/12
    # costs at most X0 omega^3 dt^2 T/12
    omega, dt = math.sqrt(K / M), dts[-1]
    allowed = X0 * omega**2 * dt * T_END / 2 if order == 1 else X0 * omega**3 * dt**2 * T_END / 12
    assert errors[-1] <= allowed


def test_event_driven_integration_agrees_with_the_smooth_ode():
    # both integrators hold a local error of rtol relative to the motion's scale X0;
    # over the run's steps the damped motion adds them at most: steps * rtol * X0
    sol = L.solve_event_driven(_oscillator(1e-2), T_END, x0=X0, rtol=1e-10)
    tr = sol.sample(1e-3)
    assert np.max(np.abs(tr.x - _reference(1e-2, tr.t))) <= (sol.steps + 1) * 1e-10 * X0


def test_event_capturing_runs_and_the_closed_forms_refuse():
    dt = 1e-4  # trapezoidal steps within the modes: the bound of the θ-method's test
    tr = L.event_capturing(_oscillator(1e-2), T_END, dt, x0=X0).trajectory
    assert np.max(np.abs(tr.x - _reference(1e-2, tr.t))) <= X0 * (K / M) ** 1.5 * dt**2 * T_END / 12
    with pytest.raises(ValueError, match="^dashpot: the exact solver needs a BinghamDashpot"):
        L.solve_exact(_oscillator(1e-2), T_END, x0=X0)


# --------------------------------------------------------------------------- the limit eps -> 0


@pytest.mark.parametrize("eps", [1e-2, 1e-3, 1e-4])
def test_eps_to_zero_approaches_the_exact_bingham_solution_within_the_derived_bound(eps):
    """``|x_eps(t) - x_B(t)| <= 2 sqrt(w1 (tau + c V) T / k)``, ``w1 = eps W(tau/(c eps))``.

    Derivation.  Let ``E = m dv^2/2 + k dx^2/2`` for the differences of the
    regularised and the Bingham motions from the same state.  At each time
    take ``v^`` with ``F_eps(v^) = F_B``, the Bingham dashpot force: then
    ``dE/dt = -(v_eps - v^)(F_eps(v_eps) - F_eps(v^)) - (v^ - v)(F_eps(v_eps) - F_B)``;
    the first term is ``<= 0`` (``F_eps`` increases) and ``|v^ - v| <= w1``:
    in stick ``tau (1 - e^{-w/eps}) + c w = |F_B| <= tau`` gives ``c w <=
    tau e^{-w/eps}``; in slip ``d = |v^| - |v|`` solves ``c d = tau e^{-(|v| +
    d)/eps} <= tau e^{-d/eps}``; both give ``<= w1``, the root of ``c w = tau
    e^{-w/eps}``.  Both motions dissipate, so ``|v| <= V = sqrt(k/m) X0`` and
    each force is at most ``tau + c V``: ``E(T) <= 2 w1 (tau + c V) T`` and
    ``|dx| <= sqrt(2 E/k)``.
    """
    c, V = 1.0, math.sqrt(K / M) * X0
    w1 = eps * float(lambertw(TAU / (c * eps)).real)
    bound = 2 * math.sqrt(w1 * (TAU + c * V) * T_END / K)
    exact = L.solve_exact(L.Oscillator.bingham(M, K, TAU, 1.0 / c), T_END, x0=X0).sample(1e-3)
    gap = np.max(np.abs(_reference(eps, exact.t) - exact.x))
    assert gap <= bound


@pytest.mark.slow  # a convergence study: the slow suite (.ci/run runs it)
def test_the_gap_to_bingham_shrinks_with_eps():
    t = np.linspace(0.0, T_END, 1001)
    exact = L.solve_exact(L.Oscillator.bingham(M, K, TAU, 1.0), T_END, x0=X0).sample(1e-3).x
    gaps = [np.max(np.abs(_reference(eps, t) - exact)) for eps in (1e-2, 1e-3, 1e-4)]
    assert gaps[0] > gaps[1] > gaps[2]
