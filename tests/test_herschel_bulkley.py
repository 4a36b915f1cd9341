"""The Herschel-Bulkley dashpot: its graph, its resolvent, its network element and its system-file kind."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import EPS

import lumped as L
from lumped import HerschelBulkley, Mass, Network, Spring, simulate_network
from lumped.laws import bingham_corrector
from lumped.model.files import parse_system

EXPONENTS = [0.3, 0.5, 1.0, 2.0, 3.7]


def _system(exponent: float = 2.0, consistency: float = 1.0, threshold: float = 1.0, masses: int = 1) -> str:
    text = "".join(f'[[mass]]\nname = "m{i}"\nmass = 1.0\nx0 = 0.5\n' for i in range(1, masses + 1))
    text += '[[element]]\nname = "k"\nkind = "spring"\nbetween = ["ground", "m1"]\nstiffness = 100.0\n'
    text += (
        '[[element]]\nname = "hb"\nkind = "herschel-bulkley"\nbetween = ["ground", "m1"]\n'
        f"threshold = {threshold}\nconsistency = {consistency}\nexponent = {exponent}\n"
    )
    for i in range(2, masses + 1):
        text += f'[[element]]\nname = "s{i}"\nkind = "spring"\nbetween = ["m{i - 1}", "m{i}"]\nstiffness = 10.0\n'
    return text


@pytest.mark.parametrize("n", EXPONENTS)
def test_graph_and_its_inverse(n):
    law = L.HerschelBulkleyDashpot(1.0, 2.0, n)
    # the band: no motion for |F| <= tau, and the interval of forces at rest is the band
    assert np.all(law.velocity(np.array([-1.0, -0.3, 0.0, 0.7, 1.0])) == 0.0)
    assert law.force_interval(0.0) == (-1.0, 1.0)
    # beyond it, phi(F) = sgn(F) ((|F| - tau)/K)^(1/n), and slip_force inverts it
    v = np.array([-3.0, -0.2, 1e-3, 0.5, 4.0])
    f = law.slip_force(v)
    np.testing.assert_allclose(f, np.sign(v) * (1.0 + 2.0 * np.abs(v) ** n), rtol=2 * EPS)
    # Inverting subtracts tau from F: its rounding, relative to |F| - tau, is
    # raised to the power 1/n (a factor 1/n on relative errors); 4 roundings.
    tol = 4 * EPS * np.abs(f) / (np.abs(f) - 1.0) / n
    assert np.all(np.abs(law.velocity(f) - v) <= tol * np.abs(v))
    assert law.slip_force(0.0) == 0.0


@pytest.mark.parametrize("n", EXPONENTS)
@pytest.mark.parametrize("eta", [1e-3, 0.7, 1e4])
def test_resolvent_solves_its_equation(n, eta):
    law = L.HerschelBulkleyDashpot(1.0, 2.0, n)
    for predictor in (-50.0, -1.0000001, -0.4, 0.0, 1.0, 1.3, 7.0, 1e3):
        f, v = law.resolvent(predictor, eta)
        if abs(predictor) <= 1.0:  # the stick branch returns the predictor itself
            assert (f, v) == (predictor, 0.0)
            continue
        # F + eta v = F~ and F = sgn(v)(tau + K|v|^n), each to a few roundings of its terms
        assert abs(f + eta * v - predictor) <= 4 * EPS * abs(predictor)
        residual = f - float(law.slip_force(v))
        assert abs(residual) <= 16 * EPS * (abs(f) + eta * abs(v))


def test_exponent_one_is_the_bingham_corrector_bit_for_bit():
    # K = 1/gamma with gamma = 1/3: the same float as BinghamDashpot's viscosity
    gamma = 1 / 3
    hb, bingham = L.HerschelBulkleyDashpot(0.7, 1 / gamma, 1.0), L.BinghamDashpot(0.7, gamma)
    assert hb.consistency == bingham.viscosity
    for predictor in np.linspace(-5, 5, 101):
        for eta in (0.01, 1.0, 100.0):
            assert hb.resolvent(float(predictor), eta) == bingham.resolvent(float(predictor), eta)
            assert hb.resolvent(float(predictor), eta) == bingham_corrector(float(predictor), eta, 0.7, 3.0)
    v = np.linspace(-2, 2, 41)
    assert np.array_equal(hb.slip_force(v), bingham.slip_force(v))


def test_backward_euler_with_exponent_one_is_algorithm_1_bit_for_bit():
    # Free decay: no forcing table, so the generic loop and Algorithm 1's
    # Python loop form the same operations in the same order.
    hb = L.Oscillator(1.0, L.LinearSpring(100.0), L.HerschelBulkleyDashpot(1.0, 1.0, 1.0))
    a = L.backward_euler(hb, 4.0, 1e-3, x0=0.5)
    b = L.backward_euler(L.Oscillator.bingham(), 4.0, 1e-3, x0=0.5, kernel="python")
    assert np.array_equal(a.as_array(), b.as_array())


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"consistency": 0.0}, "consistency"),
        ({"consistency": -1.0}, "consistency"),
        ({"exponent": 0.0}, "exponent"),
        ({"exponent": -2.0}, "exponent"),
        ({"exponent": math.inf}, "exponent"),
        ({"threshold": -1.0}, "threshold"),
        ({"consistency": math.nan}, "consistency"),
        ({"exponent": "2"}, "exponent"),
    ],
)
def test_bad_parameters_are_refused_by_name(kwargs, name):
    with pytest.raises(ValueError, match=f"^{name} must") as err:
        L.HerschelBulkleyDashpot(**kwargs)
    assert "\n" not in str(err.value)


def test_system_file_kind_and_backward_euler_through_the_resolvent():
    net = parse_system(_system(exponent=2.0))
    assert isinstance(net.elements[1], HerschelBulkley) and net.elements[1].law.exponent == 2.0
    tr = simulate_network(net, 1.0, 1e-3)
    assert tr.solver == "resolvent"
    ref = L.backward_euler(L.Oscillator(1.0, L.LinearSpring(100.0), net.elements[1].law), 1.0, 1e-3, x0=0.5)
    assert np.array_equal(tr.positions[:, 0], ref.x) and np.array_equal(tr.forces[:, 1], ref.F_d)


def test_active_set_step_agrees_with_the_resolvent():
    # The network's Monotone-style iteration stops when the force settles to 8 ulps
    # (lumped.solvers.network_step); the resolvent solves the same step to a few ulps.
    # Over 1000 non-expansive steps the difference stays at round-off scale.
    net = parse_system(_system(exponent=0.5))
    a = simulate_network(net, 1.0, 1e-3, solver="active-set")
    b = simulate_network(net, 1.0, 1e-3)
    assert np.max(np.abs(a.x - b.x)) <= 1e-12 * 0.5


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("exponent", "0.0", "exponent must be > 0"),
        ("consistency", "-1.0", "consistency must be > 0"),
        ("threshold", "-0.5", "threshold must be >= 0"),
    ],
)
def test_system_file_bad_parameters_name_file_entry_and_problem(field, value, message):
    text = _system().replace(
        f"{field} = {dict(exponent=2.0, consistency=1.0, threshold=1.0)[field]}", f"{field} = {value}"
    )
    with pytest.raises(ValueError) as err:
        parse_system(text, "system file 'x.toml'")
    assert str(err.value).startswith("system file 'x.toml': [[element]] 2 ('hb'): ") and message in str(err.value)


def test_herschel_bulkley_in_a_network_of_several_masses_is_an_element_like_any_other():
    # rigid when it can stick (a loop of two sticking elements would be refused)
    el = HerschelBulkley("hb", ("ground", "a"), 1.0, 2.0, 0.5)
    assert el.rigid_capable and not HerschelBulkley("z", ("ground", "a"), 0.0, 2.0, 0.5).rigid_capable
    net = Network(
        [Mass("a", 1.0, 0.3), Mass("b", 1.0)], [Spring("k", ("ground", "a"), 50.0), el, Spring("c", ("a", "b"), 5.0)]
    )
    tr = simulate_network(net, 0.5, 1e-3)
    assert tr.solver == "python" and np.isfinite(tr.positions).all()  # not piecewise linear: the Python step


# The step's own magnitudes (the law's contract, point 9).  With m = 1 kg,
# k = 100 N/m, dt = 1e-3 s and v0 = 1e110 m/s the predictor reaches about
# (m/dt) v0 = 1e113 N; with K = 1e200 the products K F~ (n = 1) and 4 K r
# (n = 2) are about 1e313 and overflow.  Before the law had its own bound,
# check_magnitudes read its viscosity as 0: the n = 2 run gave a wrong answer
# without a word (sqrt(inf) made the speed 0 and the force the threshold), the
# n = 1 run overflowed in its first step.
@pytest.mark.parametrize("n", [1.0, 2.0, 0.5, 3.7])
def test_a_run_whose_viscous_term_would_overflow_is_refused_up_front(n):
    osc = L.Oscillator(1.0, L.LinearSpring(100.0), L.HerschelBulkleyDashpot(1.0, 1e200, n))
    # at n = 3.7 the power v^n alone, (1e110)^3.7, overflows whatever K: the exponent is named (issue 31)
    blamed = "exponent" if n == 3.7 else "consistency"
    for run in (L.backward_euler, L.theta_method, L.event_capturing):
        with pytest.raises(ValueError, match=rf"^{blamed}: the run could reach viscous term"):
            run(osc, 0.003, 1e-3, v0=1e110)


@pytest.mark.parametrize("n", EXPONENTS)
def test_the_bound_does_not_refuse_the_run_next_to_it(n):
    # the same law with K = 1 and v0 = 1e90: every product is at most about
    # 2^n 1e93 or K v^n = 1e(90 n) (n <= 3.7 gives 1e333 only for the slip force
    # at n = 3.7, so that one is refused and the others pass)
    osc = L.Oscillator(1.0, L.LinearSpring(100.0), L.HerschelBulkleyDashpot(1.0, 1.0, n))
    if 90 * n > 300:  # K = 1: the power v^n is what overflows, so the exponent is named, not the consistency
        with pytest.raises(ValueError, match=r"^exponent: "):
            L.backward_euler(osc, 0.003, 1e-3, v0=1e90)
        return
    run = L.backward_euler(osc, 0.003, 1e-3, v0=1e90)
    assert np.all(np.isfinite(run.F_d)) and np.all(np.isfinite(run.v))
