"""The dashpot laws and their resolvents (the corrector of Algorithm 1)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import EPS
from references import bingham_velocity, literal_line8

import lumped as L
from lumped.laws import bingham_corrector


@pytest.mark.parametrize("predictor", [-37.0, -1.0000001, -1.0, -0.3, 0.0, 0.999, 1.5, 250.0])
@pytest.mark.parametrize("gamma", [0.01, 1.0, 40.0])
def test_corrector_matches_the_literal_line_8(predictor, gamma):
    # The package divides line 8 through by gamma; the literal form agrees up to
    # the rounding of a few products and one subtraction: ~8 ulps of the
    # largest term, |F~| + tau for the force.  Line 9's velocity is a
    # difference gamma*(F_d - s tau) of nearly equal numbers in the literal
    # form, so it is compared at gamma*(|F~| + tau) * 8 ulps.
    m, k, tau, dt = 1.0, 100.0, 1.0, 1e-4
    eta = m / dt + k * dt
    f_d, v = bingham_corrector(predictor, eta, tau, 1.0 / gamma)
    ref_f, ref_v = literal_line8(predictor, dt, m, k, tau, gamma)
    scale = abs(predictor) + tau
    assert abs(f_d - ref_f) <= 8 * EPS * scale
    assert abs(v - ref_v) <= 8 * EPS * gamma * scale


@pytest.mark.parametrize(("tau", "eta", "c"), [(1.1, 1000.004, 1.0), (0.3, 1000.004, 0.5)])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_predictor_exactly_on_the_band_edge_sticks(tau, eta, c, sign):
    # Lines 5-6 stick for |F~| <= tau, the closed band.  At |F~| = tau the slip
    # formula of line 8 gives the same force in exact arithmetic, so the branch
    # shows only in rounding: for these values (eta*s*tau + c*F~)/(eta + c)
    # is an ulp off tau (checked first, so that a strict < stick test fails).
    predictor = sign * tau
    slip = (eta * predictor + c * predictor) / (eta + c)
    assert slip != predictor  # the case can tell the two branches apart
    assert bingham_corrector(predictor, eta, tau, c) == (predictor, 0.0)


@pytest.mark.parametrize("predictor", [-5.0, -1.0, 0.4, 1.0, 3.0])
def test_stick_branch_is_exact(predictor):
    # |F~| <= tau: lines 5-6 copy the predictor; no arithmetic, so equality.
    f_d, v = bingham_corrector(predictor, 2.0, 5.0, 0.7)
    assert (f_d, v) == (predictor, 0.0)


@pytest.mark.parametrize("predictor", [-3.0, 1.2, 9.0])
def test_coulomb_corrector_puts_the_force_on_the_band_edge(predictor):
    # c = 0: F_d = s tau exactly and v = (F~ - s tau)/eta, which is eq. (15a).
    f_d, v = bingham_corrector(predictor, 4.0, 1.0, 0.0)
    assert f_d == math.copysign(1.0, predictor)
    assert v == (predictor - f_d) / 4.0


@pytest.mark.parametrize("predictor", np.linspace(-30.0, 30.0, 41).tolist())
@pytest.mark.parametrize("eta", [0.5, 1e4])
def test_resolvent_satisfies_its_equation_and_the_law(predictor, eta):
    # F_d + eta*v = F~ (eq. 15a) and v = phi(F_d) (eq. 6), to round-off of F~.
    law = L.BinghamDashpot(threshold=2.0, gamma=3.0)
    f_d, v = law.resolvent(predictor, eta)
    assert abs(f_d + eta * v - predictor) <= 4 * EPS * (abs(predictor) + 2.0)
    assert abs(v - law.velocity(f_d)) <= 4 * EPS * 3.0 * (abs(predictor) + 2.0)
    assert math.copysign(1.0, f_d) == math.copysign(1.0, predictor) or f_d == 0.0


def _bingham_phi(tau: float, gamma: float):
    """The Bingham graph of references as a law ``phi(F_d)`` for MonotoneDashpot."""
    return lambda force: bingham_velocity(force, tau, gamma)


@pytest.mark.parametrize("predictor", [-50.0, -2.5, -1.0, -0.2, 0.0, 0.7, 1.0 + 1e-9, 4.0, 1e3])
@pytest.mark.parametrize(("tau", "gamma", "eta"), [(1.0, 1.0, 1e4), (0.5, 20.0, 3.0), (0.0, 2.0, 1.0)])
def test_monotone_dashpot_with_bingham_phi_agrees_with_closed_form(predictor, tau, gamma, eta):
    # Brent's method is run with rtol = 4 eps on a bracket inside [0, F~], so
    # the root is within ~4 ulps of |F~| of the true one plus the ulp of the
    # closed form: bound 8 eps |F~| (+ a tiny absolute term for F~ = 0).
    generic = L.MonotoneDashpot(_bingham_phi(tau, gamma), threshold=tau)
    f_g, v_g = generic.resolvent(predictor, eta)
    f_c, v_c = L.BinghamDashpot(tau, gamma).resolvent(predictor, eta)
    bound = 8 * EPS * abs(predictor) + 1e-300
    assert abs(f_g - f_c) <= bound
    # v = (F~ - F_d)/eta in both, so the velocity error is the force error / eta.
    assert abs(v_g - v_c) <= bound / eta + 4 * EPS * abs(v_c)


def test_monotone_dashpot_trajectory_matches_bingham_kernel(paper_oscillator):
    # The generic loop (Brent per step) on the paper's free decay against the
    # closed-form kernel.  Per step the force differs by <= 8 ulps of |F~|
    # (~1e4 * |v| here); backward Euler is non-expansive, so the differences
    # add at most linearly over N steps: N * 8 eps * max|F~| / eta in x.
    phi = _bingham_phi(1.0, 1.0)
    osc_g = L.Oscillator(1.0, L.LinearSpring(100.0), L.MonotoneDashpot(phi, threshold=1.0))
    dt, t_end = 1e-3, 2.0
    a = L.backward_euler(osc_g, t_end, dt, x0=0.5)
    b = L.backward_euler(paper_oscillator, t_end, dt, x0=0.5)
    n = len(a.t)
    f_tilde = (1.0 / dt) * np.abs(b.v).max() + np.abs(b.F_s).max()
    eta = 1.0 / dt + 100.0 * dt
    assert np.abs(a.x - b.x).max() <= n * 8 * EPS * f_tilde / eta
    assert np.array_equal(a.t, b.t)


@pytest.mark.parametrize("velocity", [-40.0, -1.5, -1e-3, 0.0, 2e-3, 0.7, 25.0])
@pytest.mark.parametrize(("tau", "gamma"), [(1.0, 1.0), (0.5, 20.0), (0.0, 2.0)])
@pytest.mark.parametrize("kind", ["monotone", "bingham"])
def test_force_interval_is_the_inverse_of_the_bingham_graph(kind, velocity, tau, gamma):
    # Both laws, the MonotoneDashpot built from the Bingham graph and the
    # Bingham law itself, must return the inverse of eq. (7): (-tau, tau) at
    # v = 0, else the single force s tau + v/gamma with s = sgn(v), which the
    # graph maps back to v.  Brent's root of phi(F) = v is found to rtol
    # 4 eps; phi's own rounding moves it by a few ulps of |F|: bound 8 eps |F|
    # (the closed form of the Bingham law is within an ulp of it).
    law = (
        L.MonotoneDashpot(_bingham_phi(tau, gamma), threshold=tau)
        if kind == "monotone"
        else L.BinghamDashpot(tau, gamma)
    )
    lo, hi = law.force_interval(velocity)
    if velocity == 0.0:
        assert (lo, hi) == (-tau, tau)
    else:
        want = math.copysign(tau, velocity) + velocity / gamma
        assert lo == hi and abs(lo - want) <= 8 * EPS * abs(want)
        assert math.copysign(1.0, lo) == math.copysign(1.0, velocity)
        # and the graph maps it back to v (its slope gamma scales the error)
        back = bingham_velocity(lo, tau, gamma)
        assert abs(back - velocity) <= gamma * 8 * EPS * abs(want) + 4 * EPS * abs(velocity)


@pytest.mark.parametrize("threshold", [0.0, 0.3, 2.0])
def test_force_interval_is_the_inverse_graph(threshold):
    law = L.BinghamDashpot(threshold=threshold, gamma=0.5)
    assert law.force_interval(0.0) == (-threshold, threshold)
    lo, hi = law.force_interval(1.5)
    # F_d = tau + v/gamma (eq. 7): exact arithmetic on these values.
    assert lo == hi == threshold + 3.0
    assert law.velocity(lo) == pytest.approx(1.5, rel=4 * EPS)


def test_coulomb_helper_is_bingham_with_infinite_gamma():
    law = L.coulomb(2.0)
    assert law.gamma == math.inf and law.viscosity == 0.0 and law.threshold == 2.0
    assert law.velocity(1.0) == 0.0
    assert law.velocity(2.5) == math.inf and law.velocity(-2.5) == -math.inf


def test_spring_is_linear():
    spring = L.LinearSpring(100.0)
    assert spring.force(0.005) == 0.5
    assert spring.displacement(50.0) == 0.5
    assert spring.energy(50.0) == 12.5


def test_monotone_dashpot_rejects_a_law_not_vanishing_at_zero():
    with pytest.raises(ValueError, match="velocity_of_force"):
        L.MonotoneDashpot(lambda f: f + 1.0)
