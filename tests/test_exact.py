"""The exact, event-driven solver against closed forms computed here."""

from __future__ import annotations

import math

import numpy as np
import pytest
import references
from conftest import EPS, F17A, F17B, case_table

import lumped as L


@pytest.mark.parametrize(
    ("m", "k", "tau", "gamma", "x0"), references.FREE_DECAY.values(), ids=list(references.FREE_DECAY)
)
def test_free_decay_turning_points_follow_the_half_cycle_recurrence(m, k, tau, gamma, x0):
    osc = L.Oscillator.bingham(mass=m, stiffness=k, threshold=tau, gamma=gamma)
    ref = references.free_decay(m, k, tau, gamma, x0)
    ref_t, ref_x = ref.times, ref.positions
    sol = L.solve_exact(osc, ref_t[-1] + 1.0, x0=x0)
    turning = [e for e in sol.events if e.kind in ("reversal", "stop")]
    # the number of half-cycles is an integer: exact
    assert len(turning) == len(ref_t)
    assert [e.kind for e in turning] == ["reversal"] * (len(ref_t) - 1) + ["stop"]
    # Zeros of v are refined by Brent to rtol = 4 eps of the phase time and
    # each phase starts from the previous event, so times carry a few ulps per
    # event: 1e-12 relative covers ~50 events with margin.  Positions are
    # evaluated at those times (v = 0 there, so a time error enters at second
    # order) and compared on the scale |x0|.
    t_ev = np.array([e.time for e in turning])
    x_ev = np.array([e.x[0] for e in turning])
    np.testing.assert_allclose(t_ev, ref_t, rtol=1e-12, atol=0)
    np.testing.assert_allclose(x_ev, ref_x, rtol=0, atol=1e-12 * abs(x0))
    assert sol.rest_time == pytest.approx(ref_t[-1], rel=1e-12)
    assert sol.rest_position == pytest.approx(ref_x[-1], abs=1e-12 * abs(x0))
    assert sol.event_times("rest") == pytest.approx([ref_t[-1]], rel=1e-12)
    # stays there: evaluate after the rest
    after = sol.evaluate(np.array([ref_t[-1] + 0.5]))
    assert after["v"][0] == 0.0 and after["x"][0] == sol.rest_position


@pytest.mark.parametrize("x0", [0.0, 0.005, -0.01, 0.01])
def test_released_inside_the_band_rests_at_once(x0):
    # |x0| <= tau/k at rest: never moves (the stick branch of eq. 6).
    sol = L.solve_exact(L.Oscillator.bingham(), 2.0, x0=x0)
    assert sol.rest_time == 0.0 and sol.rest_position == x0
    assert [e.kind for e in sol.events] == ["rest"]
    cols = sol.evaluate(np.linspace(0, 2, 11))
    assert np.all(cols["x"] == x0) and np.all(cols["v"] == 0.0)
    assert np.all(cols["F_d"] == -100.0 * x0)


def test_figure5_exact_solution_is_equation_19():
    # Forcing (17a) stays in the band: stick throughout, F_d = F_1(t).
    f1 = F17A
    sol = L.solve_exact(L.Oscillator.bingham(), 2.0, force=f1)
    t = np.linspace(0, 2, 201)
    cols = sol.evaluate(t)
    assert np.all(cols["x"] == 0.0) and np.all(cols["v"] == 0.0)
    assert np.array_equal(cols["F_d"], f1(t))
    assert sol.stick_intervals() == [(0.0, 2.0)]
    # it never moves, so it is at rest for ever from t = 0 (as backward Euler says)
    assert sol.rest_time == 0.0 and sol.rest_position == 0.0


CASES = case_table(
    "fig6-17b",
    "v0-phase-negative-amp",
    "overdamped-17b",
    "overdamped-free",
    "coulomb-17b",
    "negative-amplitude-phase",
    "v0-only",
)


@pytest.mark.parametrize("case", CASES)
def test_slip_phases_satisfy_the_equation_of_motion(case):
    # Independent check of the closed-form slip motion: second differences of
    # x inside each slip phase against m x'' = F - k x - s tau - c v.  Central
    # differences with h = 1e-4 have truncation h^2 |x''''|/12 and rounding
    # 4 eps |x| / h^2; both < 1e-3 of the force scale here.
    gamma, kwargs = CASES[case]
    osc = L.Oscillator.bingham(gamma=gamma)
    sol = L.solve_exact(osc, 3.0, **kwargs)
    h, c = 1e-4, osc.dashpot.viscosity
    checked = 0
    for p in sol.phases:
        if p.motion is None or p.end - p.start < 10 * h:
            continue
        t = np.linspace(p.start + 2 * h, p.end - 2 * h, 50)
        x_m, _ = p.motion.state(t - h)
        x_0, v_0 = p.motion.state(t)
        x_p, _ = p.motion.state(t + h)
        acc = (x_p - 2 * x_0 + x_m) / h**2
        f = np.asarray(sol.force(t), dtype=float)
        rhs = f - 100.0 * x_0 - p.motion.s_tau - c * v_0
        scale = 1.0 + np.abs(f).max() + 100.0 * np.abs(x_0).max() + c * np.abs(v_0).max()
        assert np.abs(acc - rhs).max() <= 1e-3 * scale
        assert np.all(np.sign(v_0) * np.sign(p.motion.s_tau) >= 0)  # slips with sign s
        checked += 1
    assert checked >= 1


@pytest.mark.parametrize("case", CASES)
def test_event_conditions_hold(case):
    # stop: v = 0 and the net force is in the band; reversal: outside it;
    # breakaway: on its edge.  Net force F - k x at the event.
    gamma, kwargs = CASES[case]
    osc = L.Oscillator.bingham(gamma=gamma)
    sol = L.solve_exact(osc, 3.0, **kwargs)
    force = kwargs.get("force") or L.SwitchedSine()
    for e in sol.events:
        net = float(force(e.time)) - 100.0 * e.x[0]
        if e.kind == "stop":
            assert abs(net) <= 1.0 + 1e-12
        elif e.kind == "reversal":
            assert abs(net) >= 1.0 - 1e-12
        elif e.kind == "breakaway":
            # arcsin closed form: on the band edge to round-off of the force
            assert abs(abs(net) - 1.0) <= 1e-12 * (1.0 + abs(force.amplitude))
        if e.kind in ("stop", "reversal"):
            assert abs(sol.evaluate(np.array([e.time]))["v"][0]) <= 1e-12
    cols = sol.evaluate(np.linspace(0, 3.0, 3001))
    stuck = cols["v"] == 0
    # in stick the force is in the closed band (eq. 11c); round-off allowance
    assert np.all(np.abs(cols["F_d"][stuck]) <= 1.0 + 1e-12)


def test_overdamped_free_decay_never_stops():
    # c = 100 > 2 sqrt(km) = 20: the slip motion creeps towards x_c = tau/k
    # without v ever reaching zero, so there is no event and no rest.
    sol = L.solve_exact(L.Oscillator.bingham(gamma=0.01), 3.0, x0=0.5)
    assert sol.events == () and math.isnan(sol.rest_time)
    cols = sol.evaluate(np.linspace(0, 3, 301))
    assert np.all(cols["v"][1:] < 0) and np.all(np.diff(cols["x"]) < 0)
    assert np.all(cols["x"] > 0.01)


@pytest.mark.parametrize("dt", [4e-4, 2e-4, 1e-4, 5e-5])
@pytest.mark.parametrize("gamma", [1.0, 0.01])
def test_stick_intervals_and_rest_time_match_backward_euler_within_order_dt(dt, gamma):
    # Forcing (17b).  Backward Euler sees a switch on the grid (<= 1 dt late)
    # after slip phases carrying an O(dt) error; observed ~3 dt at every dt.
    # A bound of 5 dt uniform in dt is the statement "O(dt)".  Single-point
    # runs of v == 0 in backward Euler (a grid point landing on a reversal)
    # have zero length and are not stick phases.
    osc = L.Oscillator.bingham(gamma=gamma)
    force = F17B
    sol = L.solve_exact(osc, 3.0, force=force)
    be = L.backward_euler(osc, 3.0, dt, force=force)
    runs = [iv for iv in be.stick_intervals() if iv[1] > iv[0]]
    exact = sol.stick_intervals()
    assert len(runs) == len(exact)
    assert np.abs(np.array(runs) - np.array(exact)).max() <= 5 * dt
    assert abs(be.rest_time - sol.rest_time) <= 5 * dt
    assert abs(be.rest_position - sol.rest_position) <= 5 * dt * np.abs(be.v).max()


def test_exact_energy_balance_is_second_order():
    # Trapezoid on the sampled exact solution: the power F_d v is continuous
    # and piecewise smooth, so the residual is O(dt^2): fitted order in [1.8, 2.2].
    sol = L.solve_exact(L.Oscillator.bingham(), 3.0, force=F17B)
    dts = np.array([4e-4, 2e-4, 1e-4, 5e-5])
    res = [np.abs(sol.sample(dt).energy_balance().residual).max() for dt in dts]
    assert 1.8 <= references.order(dts, res) <= 2.2
    eb = sol.sample(1e-4).energy_balance()
    assert np.all(eb.numerical == 0.0)


def test_sample_is_evaluate_on_the_grid():
    sol = L.solve_exact(L.Oscillator.bingham(), 1.0, x0=0.5)
    tr = sol.sample(1e-3, save_every=7)
    idx = np.append(np.arange(0, 1001, 7), 1000)
    cols = sol.evaluate(idx * 1e-3)
    assert np.array_equal(tr.as_array(), np.column_stack(list(cols.values())))
    assert tr.method == "exact" and tr.t[0] == 0.0 and tr.t[-1] == 1.0
    via = L.simulate(L.Oscillator.bingham(), 1.0, 1e-3, x0=0.5, method="exact", save_every=7)
    assert np.array_equal(via.as_array(), tr.as_array())


def test_exact_solver_refuses_other_laws_and_forcings():
    osc = L.Oscillator(1.0, L.LinearSpring(1.0), L.MonotoneDashpot(lambda f: f))
    with pytest.raises(ValueError, match="dashpot"):
        L.solve_exact(osc, 1.0)
    with pytest.raises(ValueError, match="force"):
        L.solve_exact(L.Oscillator.bingham(), 1.0, force=lambda t: t)


@pytest.mark.parametrize("phase", [0.3, -2.0])
def test_negative_omega_is_solved_as_the_same_forcing_with_positive_omega(phase):
    # 10 sin(-5 pi t + ph) = 10 sin(5 pi t + pi - ph): the same force, so the
    # same motion.  The solver's breakaway times and its step bound pi/omega
    # are written for omega > 0, which the canonical form must supply.  Event
    # times agree to the solver's event accuracy (1e-12 relative, as above);
    # positions and the rest state to 1e-12 of the motion's scale.
    osc = L.Oscillator.bingham(gamma=1.0)
    neg = L.SwitchedSine(10.0, -5 * math.pi, phase, 1.0)
    pos = L.SwitchedSine(10.0, 5 * math.pi, math.pi - phase, 1.0)
    a, b = L.solve_exact(osc, 3.0, force=neg), L.solve_exact(osc, 3.0, force=pos)
    assert [e.kind for e in a.events] == [e.kind for e in b.events]
    np.testing.assert_allclose([e.time for e in a.events], [e.time for e in b.events], rtol=1e-12, atol=0)
    np.testing.assert_allclose([e.x for e in a.events], [e.x for e in b.events], rtol=0, atol=1e-12)
    assert abs(a.rest_position - b.rest_position) <= 1e-12
