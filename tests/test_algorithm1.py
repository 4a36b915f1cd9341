"""Algorithm 1 (backward Euler, eqs. 13-16): the paper's cases and per-step invariants."""

from __future__ import annotations

import importlib
import math
import types

import numpy as np
import pytest
import references
from conftest import EPS, F17A, F17B, KERNELS, PAPER_DT, assert_same_trajectory, case_table, energy_scale
from references import line3, switched_sine

import lumped as L
from lumped import laws
from lumped.numerics import sine as _sine
from lumped.solvers import backward_euler as timestepping

# Cases for the invariants: (gamma, keyword arguments of backward_euler).
CASES = {
    **case_table(
        "fig5-17a",
        "fig6-17b",
        "fig10-x0-0.005",
        "fig11-x0-0.5",
        "coulomb-x0-0.5",
        "coulomb-17b",
        "overdamped-17b",
        "v0-phase-negative-amp",
    ),
    "callable-force": (1.0, dict(force=lambda t: 3.0 * np.cos(2.0 * t))),
}


def _run(gamma: float, kwargs: dict, t_end: float = 3.0, dt: float = PAPER_DT, **extra):
    osc = L.Oscillator.bingham(mass=1.0, stiffness=100.0, threshold=1.0, gamma=gamma)
    return L.backward_euler(osc, t_end, dt, **kwargs, **extra)


def test_figure5_is_equation_19_exactly(paper_oscillator):
    # Forcing (17a) never exceeds tau = 1, so every predictor is
    # F~ = (m/dt)*0 + F_1(t_{n+1}) - 0 = F_1(t_{n+1}) with |F~| <= 0.5 < 1:
    # line 6 sets v = 0 and F_d = F~ by assignment, and line 11 adds dt*k*0 = 0
    # to F_s = 0.  No rounding enters, so eq. (19) holds with ==, not approx.
    tr = L.backward_euler(paper_oscillator, 2.0, PAPER_DT, force=F17A)
    n = np.arange(len(tr.t))
    assert np.array_equal(tr.t, n * PAPER_DT)
    assert np.all(tr.x == 0.0) and np.all(tr.v == 0.0) and np.all(tr.F_s == 0.0)
    # F_1 is the project's sine (lumped.numerics.sine, the kernels' own) of the double
    # 5*pi*t_n, exactly; recomputed independently with libm's sin it agrees to
    # 1.5 P EPS: ours is within 1 ulp of the true value, a C library's within 2
    # (even one moved by an ulp, as scripts/perturbed_check.py's libm-ulp does),
    # an ulp of |sin| < 1 is at most 2^-53, so the two differ by less than
    # 3 * 2^-53 = 1.5 EPS; the product with P = 2^-1 is exact.
    f1 = np.array([0.5 * _sine.sin(5 * np.pi * t) if t <= 1.0 else 0.0 for t in tr.t])
    libm = np.array([switched_sine(references.F17A, t) for t in tr.t])
    assert np.array_equal(tr.F, f1) and np.any(f1 != 0.0)
    assert np.all(np.abs(tr.F - libm) <= 0.5 * 1.5 * EPS)
    assert np.array_equal(tr.F_d, tr.F)
    assert tr.stick_intervals() == [(0.0, 2.0)]


def test_figure10_mass_never_moves(paper_oscillator):
    # x0 = 0.005 is inside the static band tau/k = 0.01.  First predictor:
    # F~ = 0 + 0 - k x0 = -0.5, |F~| <= 1, so v = 0, F_d = -0.5 exactly and
    # F_s is unchanged; every later step repeats the same arithmetic.
    x0 = 0.005
    tr = L.backward_euler(paper_oscillator, 2.0, PAPER_DT, x0=x0)
    assert np.all(tr.x == x0) and np.all(tr.v == 0.0)
    assert np.all(tr.F_s == 100.0 * x0)
    assert np.all(tr.F_d[1:] == -100.0 * x0)
    assert tr.rest_time == 0.0 and tr.rest_position == x0


@pytest.mark.parametrize("kernel", KERNELS)
def test_released_on_the_band_edge_the_mass_sticks(kernel):
    # k = 4 and x0 = tau/4 make k*x0 == tau exactly (powers of two), and with
    # v0 = 0, F = 0 every predictor is F~ = (m/dt)*0 + 0 - k*x0 = -tau exactly:
    # on the closed band, so lines 5-6 stick (v = 0, F_d = F~ by assignment)
    # for ever.  The slip formula of line 8 would give the same force in exact
    # arithmetic; with these values it rounds an ulp off (checked), so a
    # strict |F~| < tau test shows in F_d.
    tau, m, k, dt = 1.1, 1.0, 4.0, 1e-3
    osc = L.Oscillator.bingham(m, k, tau, 1.0)
    eta, c = m / dt + k * dt, 1.0
    assert k * (tau / k) == tau and (eta * -tau + c * -tau) / (eta + c) != -tau
    tr = L.backward_euler(osc, 0.05, dt, x0=tau / k, kernel=kernel)
    assert np.all(tr.v == 0.0) and np.all(tr.x == tau / k)
    assert np.all(tr.F_d[1:] == -tau) and tr.rest_time == 0.0


@pytest.mark.parametrize("case", CASES)
def test_force_in_band_whenever_stuck(case):
    # Lines 5-6: v = 0 only when |F~| <= tau and then F_d = F~.  A slip step
    # gives v = (F~ - s tau)/eta != 0.  So v == 0 implies |F_d| <= tau exactly.
    gamma, kwargs = CASES[case]
    tr = _run(gamma, kwargs)
    stuck = tr.v[1:] == 0.0
    assert np.all(np.abs(tr.F_d[1:][stuck]) <= 1.0)
    # and slipping implies the force is at or beyond the band edge
    assert np.all(np.abs(tr.F_d[1:][~stuck]) >= 1.0)


@pytest.mark.parametrize("case", CASES)
def test_sign_of_dashpot_force_is_sign_of_predictor(case):
    # Eq. (16).  F~ is recomputed here from the stored trajectory with the
    # kernel's expression (m/dt) v_n + F_{n+1} - F_s,n.
    gamma, kwargs = CASES[case]
    tr = _run(gamma, kwargs)
    f_tilde = line3(1.0, PAPER_DT, tr.v[:-1], tr.F[1:], tr.F_s[:-1])
    assert np.array_equal(np.sign(tr.F_d[1:]), np.sign(f_tilde))
    # v has the sign of F_d off the band (eq. 7a)
    moving = tr.v[1:] != 0
    assert np.array_equal(np.sign(tr.v[1:][moving]), np.sign(tr.F_d[1:][moving]))


@pytest.mark.parametrize("case", CASES)
def test_discrete_energy_balance_closes_to_round_off(case):
    # Multiplying (13a) by v_{n+1} and (13b) by F_s,n+1/k gives an identity per
    # step; the residual is only rounding: a few roundings of size eps*E per
    # step, added over N steps, E the energy scale (stored + dissipated +
    # numerical + |work|).  Worst case linear growth: 4 eps E N.  A wrong term
    # (say the numerical dissipation dropped) would be O(dt E) ~ 1e-4 E.
    gamma, kwargs = CASES[case]
    tr = _run(gamma, kwargs)
    eb = tr.energy_balance()
    # (Figures 5 and 10 never move: every energy, and the residual, is 0.)
    assert np.abs(eb.residual).max() <= 4 * EPS * max(energy_scale(eb), 1.0) * len(tr.t)
    # dissipation is non-negative and non-decreasing (F_d v >= 0, eq. 7a)
    assert np.all(np.diff(eb.dissipated) >= 0) and np.all(np.diff(eb.numerical) >= 0)


def test_energy_balance_refuses_thinned_backward_euler(paper_oscillator):
    tr = L.backward_euler(paper_oscillator, 0.1, PAPER_DT, x0=0.5, save_every=10)
    with pytest.raises(ValueError, match="save_every"):
        tr.energy_balance()


@pytest.mark.parametrize("case", ["fig11-x0-0.5", "fig6-17b", "v0-phase-negative-amp"])
def test_coulomb_and_huge_gamma_agree(case):
    # With c = 1e-12 the slip step differs from c = 0 by a relative c/eta
    # (~1e-16 at eta ~ 1e4) in v, plus a different rounding (<= 2 eps).  The
    # step map is non-expansive (resolvent of a monotone graph, dissipative
    # linear part), so these per-step perturbations add at most linearly:
    # |dv|, |dF_s|/k bounded by N (c/eta + 2 eps) times the scale of v, x.
    # F_d = F~ - eta v_{n+1} with F~ = (m/dt) v_n + F - F_s,n, so
    # |dF_d| <= (m/dt + eta) |dv| + |dF_s|.
    _, kwargs = CASES[case]
    dt, t_end = PAPER_DT, 3.0
    a, b = _run(math.inf, kwargs, t_end, dt), _run(1e12, kwargs, t_end, dt)
    n, eta = len(a.t), 1.0 / dt + 100.0 * dt
    rel = n * (1e-12 / eta + 2 * EPS)
    tol_v = rel * np.abs(a.v).max()
    tol_x = rel * np.abs(a.x).max()
    assert np.abs(a.v - b.v).max() <= tol_v
    assert np.abs(a.x - b.x).max() <= tol_x
    assert np.abs(a.F_d - b.F_d).max() <= (1.0 / dt + eta) * tol_v + 100.0 * tol_x


@pytest.mark.skipif(timestepping.KERNEL != "compiled", reason="C kernel not built")
@pytest.mark.parametrize("save_every", [1, 10**9], ids=["every-step", "huge-save-every"])
@pytest.mark.parametrize("case", CASES)
def test_compiled_and_python_kernels_are_bit_identical(case, save_every):
    # Same operations in the same order, no FP contraction: identical bits.
    # With test_python_loop_corrects_through_bingham_corrector this ties the
    # C copy of the corrector to laws.bingham_corrector (Coulomb, forced,
    # callable forcing; a huge save_every keeps only the first and last rows).
    # The whole trajectory: the rest step each loop counts is in final_rest,
    # not in the saved rows (with a huge save_every, nowhere else).
    gamma, kwargs = CASES[case]
    a = _run(gamma, kwargs, t_end=2.0, kernel="compiled", save_every=save_every)
    b = _run(gamma, kwargs, t_end=2.0, kernel="python", save_every=save_every)
    assert_same_trajectory(a, b)


@pytest.mark.parametrize("case", ["coulomb-17b", "callable-force", "fig11-x0-0.5"])
def test_python_loop_corrects_through_bingham_corrector(case, monkeypatch):
    # The Python loop must call laws.bingham_corrector once per step and use
    # what it returns: a spy that counts the calls and records the results
    # must see every stored (F_d, v) of the run.
    seen = []

    def spy(predictor, eta, tau, c):
        out = laws.bingham_corrector(predictor, eta, tau, c)
        seen.append(out)
        return out

    monkeypatch.setattr(timestepping, "bingham_corrector", spy)
    gamma, kwargs = CASES[case]
    tr = _run(gamma, kwargs, t_end=0.5, dt=1e-3, kernel="python")
    assert len(seen) == len(tr.t) - 1
    assert np.array_equal(np.array(seen), np.column_stack([tr.F_d[1:], tr.v[1:]]))


@pytest.mark.skipif(timestepping.KERNEL != "compiled", reason="C kernel not built")
def test_kernels_identical_with_thinning_and_ragged_end(paper_oscillator):
    kw = dict(x0=0.3, force=F17B, save_every=7)
    a = L.backward_euler(paper_oscillator, 1.2345, 1e-3, kernel="compiled", **kw)
    b = L.backward_euler(paper_oscillator, 1.2345, 1e-3, kernel="python", **kw)
    assert_same_trajectory(a, b)


@pytest.mark.parametrize("save_every", [1, 3, 7, 1000])
def test_save_every_keeps_first_last_and_every_kth(paper_oscillator, save_every):
    # The thinned run must be the full run's rows 0, K, 2K, ... and the last.
    dt, t_end = 1e-3, 1.0  # N = 1000 steps
    full = L.backward_euler(paper_oscillator, t_end, dt, force=F17B)
    thin = L.backward_euler(paper_oscillator, t_end, dt, force=F17B, save_every=save_every)
    idx = np.arange(0, 1001, save_every)
    if idx[-1] != 1000:
        idx = np.append(idx, 1000)
    assert np.array_equal(thin.as_array(), full.as_array()[idx])


def test_grid_overshoots_a_ragged_end_by_less_than_a_step(paper_oscillator):
    tr = L.backward_euler(paper_oscillator, 0.00105, 1e-4)
    assert len(tr.t) == 12 and tr.t[-1] == 11 * 1e-4


def test_initial_row_is_consistent(paper_oscillator):
    # At rest outside the band the dashpot force starts at the band edge it is
    # pushed towards; moving, it is the slip force of eq. (7).
    tr = L.backward_euler(paper_oscillator, 0.01, 1e-3, x0=0.5)
    assert tuple(tr.as_array()[0]) == (0.0, 0.5, 0.0, 50.0, -1.0, 0.0)
    tr = L.backward_euler(paper_oscillator, 0.01, 1e-3, x0=0.0, v0=2.0)
    assert tr.F_d[0] == 1.0 + 2.0


def test_generic_force_callable_equals_switched_sine(paper_oscillator):
    # A callable is tabulated (SwitchedSine.__call__, NumPy), the SwitchedSine is
    # evaluated inside the loop (the compiled or Python kernel): both use the
    # project's sine (lumped.numerics.sine), so the forcing has one definition and the
    # two runs agree bit for bit.
    sine = F17B
    a = L.backward_euler(paper_oscillator, 2.0, 1e-3, force=sine)
    b = L.backward_euler(paper_oscillator, 2.0, 1e-3, force=lambda t: sine(t))
    assert np.array_equal(a.as_array(), b.as_array())


def test_stick_intervals_and_rest_semantics(paper_oscillator):
    # Hand-built trajectory: runs of exact zeros in v.
    t = np.arange(8) * 0.5
    v = np.array([0.0, 0.0, 1.0, -1.0, 0.0, 0.0, 0.0, 0.0])
    x = np.array([0.0, 0.0, 0.1, 0.2, 0.3, 0.3, 0.3, 0.3])
    z = np.zeros_like(t)

    def hand_built(v: np.ndarray, method: str) -> L.Trajectory:
        return L.Trajectory.of_oscillator(
            t=t, x=x, v=v, F_s=100 * x, F_d=z, F=z, oscillator=paper_oscillator, method=method, dt=0.5
        )

    tr = hand_built(v, "backward-euler")
    assert tr.stick_intervals() == [(0.0, 0.5), (2.0, 3.5)]
    assert tr.rest_time == 2.0 and tr.rest_position == 0.3
    v2 = np.array([0.0, 0.0, 1.0, 0.0, 0.0, 1.0, -1.0, 2.0])
    moving = hand_built(v2, "x")
    assert math.isnan(moving.rest_time) and math.isnan(moving.rest_position)
    assert moving.stick_intervals() == [(0.0, 0.5), (1.5, 2.0)]
    # a single zero is a (degenerate) interval of its own
    v3 = np.array([1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0])
    single = hand_built(v3, "x")
    assert single.stick_intervals() == [(0.5, 0.5), (3.5, 3.5)] and single.rest_time == 3.5


def test_columns_and_array_agree(paper_oscillator):
    tr = L.backward_euler(paper_oscillator, 0.05, 1e-3, x0=0.5)
    cols = tr.columns()
    assert tuple(cols) == L.COLUMNS == ("t", "x", "v", "F_s", "F_d", "F")
    assert np.array_equal(np.column_stack(list(cols.values())), tr.as_array())
    # x = F_s / k (line 11) exactly as stored
    assert np.array_equal(tr.x[1:], tr.F_s[1:] / 100.0)


def test_algorithm1_alias_and_simulate_dispatch(paper_oscillator):
    a = L.algorithm1(paper_oscillator, 0.5, 1e-3, x0=0.5)
    b = L.simulate(paper_oscillator, 0.5, 1e-3, x0=0.5)
    assert_same_trajectory(a, b)
    with pytest.raises(ValueError, match="method"):
        L.simulate(paper_oscillator, 0.5, 1e-3, method="rk4")


def test_the_driver_is_a_module_and_simulate_a_function():
    # lumped.simulate is the function (exported by __init__); the module that
    # holds it and the method registry is lumped.drivers.simulation, so importing it by
    # name gives a module whose simulate is that same function.
    driver = importlib.import_module("lumped.drivers.simulation")
    assert driver.simulate is L.simulate and driver.METHODS is L.METHODS
    assert callable(L.simulate) and not isinstance(L.simulate, types.ModuleType)
    with pytest.raises(ModuleNotFoundError):
        importlib.import_module("lumped.simulate")


@pytest.mark.parametrize("method", list(L.METHODS))
def test_every_registered_method_runs_through_simulate(paper_oscillator, method):
    tr = L.simulate(paper_oscillator, 0.5, 1e-3, x0=0.5, method=method)
    assert tr.method == method and len(tr.t) == 501
