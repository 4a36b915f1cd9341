"""The exact solver off the grid, at extreme parameters and against independent references.

Issue 7: values sampled past ``t_end`` must be the solution (not an
extrapolated slip phase), extreme input must end quickly in a ``ValueError``
naming the argument (never NaN, inf or another exception), and heavily damped
phases must be solved, not searched for.
"""

from __future__ import annotations

import dataclasses
import math

import mpmath
import numpy as np
import pytest
from conftest import EPS, F17B
from references import FREE_DECAY
from scipy.integrate import solve_ivp

import lumped as L
from lumped.numerics.roots import MAXITER
from lumped.solvers import closed_form, exact
from lumped.solvers.exact import _event_estimate

# (t_end, dt, keyword arguments): grids whose last point t_N = N dt lies past
# t_end (by 5e-5 s, 0.4 s, round-off, 0.2 s).
OFF_GRID = {
    "rest-just-after-t_end": (3.14552, 1e-4, dict(x0=0.5)),
    "coarse-step": (1.0, 0.7, dict(x0=0.5)),
    "round-off": (0.3, 0.1, dict(x0=0.5)),
    "forced-17b": (2.5, 0.3, dict(force=F17B)),
}


@pytest.mark.parametrize("case", OFF_GRID)
def test_sampled_values_are_the_solution_at_their_times(case):
    # The reference is solved independently to a later t_end.  Events do not
    # depend on t_end once it is past them (stops of free phases are closed
    # forms, the bracketing grid starts at the phase start whatever t_end), so
    # the same operations give the same doubles: equality, no tolerance.
    t_end, dt, kwargs = OFF_GRID[case]
    osc = L.Oscillator.bingham()
    tr = L.solve_exact(osc, t_end, **kwargs).sample(dt)
    assert tr.t[-1] > t_end and tr.t[-1] == (len(tr.t) - 1) * dt
    ref = L.solve_exact(osc, tr.t[-1] + 1.0, **kwargs)
    cols = ref.evaluate(tr.t)
    for name in L.COLUMNS:
        np.testing.assert_array_equal(getattr(tr, name), cols[name], err_msg=name)
    at_rest = ref.rest_time <= tr.t[-1]
    assert (tr.v[-1] == 0.0) == at_rest
    if at_rest:
        assert (tr.rest_time, tr.rest_position) == (ref.rest_time, ref.rest_position)
        assert tr.x[-1] == ref.rest_position
    else:
        assert math.isnan(tr.rest_time) and math.isnan(tr.rest_position)


def test_the_issue_examples_report_the_solution():
    # Issue 7: t = 3.1456 was reported moving at v = -9.3e-5; x(1.4) as 0.03115.
    osc = L.Oscillator.bingham()
    tr = L.solve_exact(osc, 3.14552, x0=0.5).sample(1e-4)
    assert tr.v[-1] == 0.0 and tr.rest_time == pytest.approx(3.1455270229, abs=1e-10)
    tr = L.solve_exact(osc, 1.0, x0=0.5).sample(0.7)
    assert tr.x[-1] == pytest.approx(0.04736, abs=5e-6)


@pytest.mark.parametrize("t", [-5.0, 50.0, math.nan, -0.0 - 1e-300, 4.0 + 8 * EPS])
def test_evaluate_refuses_times_outside_the_solved_interval(t):
    sol = L.solve_exact(L.Oscillator.bingham(), 4.0, x0=0.5)
    with pytest.raises(ValueError, match=r"^t: "):
        sol.evaluate(np.array([0.0, t]))


def test_evaluate_accepts_the_end_points():
    sol = L.solve_exact(L.Oscillator.bingham(), 4.0, x0=0.5)
    cols = sol.evaluate(np.array([0.0, 4.0]))
    assert cols["x"][0] == 0.5 and cols["x"][1] == sol.rest_position


# Each is refused by a ValueError whose message begins with the argument to
# change: (oscillator keywords, solve_exact keywords, argument name).
REFUSED = {
    "huge x0": ({}, dict(x0=1e307), "x0"),
    "huge v0": ({}, dict(v0=1e307), "v0"),
    "huge amplitude": ({}, dict(force=L.SwitchedSine(1e307, 1.0)), "force_amplitude"),
    "huge omega": ({}, dict(force=L.SwitchedSine(1.0, 1e300)), "force_omega"),
    "omega*t_end": ({}, dict(t_end=1e300, force=L.SwitchedSine(1.0, 5 * math.pi)), "force_omega"),
    "viscous v0": (dict(gamma=1e-300), dict(v0=1e10), "v0"),
    "stiff, many events": (dict(stiffness=1e12), dict(x0=0.5), "t_end"),
    "stiffness 1e300": (dict(stiffness=1e300), dict(x0=0.5), "t_end"),
    "no band, t_end 1e300": (dict(threshold=0.0), dict(x0=0.5, t_end=1e300), "t_end"),
    "tiny mass, tiny gamma": (dict(mass=1e-300, gamma=1e-300), dict(x0=0.5), "mass"),
}


@pytest.mark.parametrize("case", REFUSED)
def test_extreme_input_is_refused_at_once_naming_the_argument(case, monkeypatch):
    # "At once" is "before any work": the march through the phases (where a
    # run of 1e12 events or 1e300 s would spend its time) must never start.
    osc_kw, kwargs, name = REFUSED[case]
    kwargs = dict(kwargs)
    t_end = kwargs.pop("t_end", 2.0)
    monkeypatch.setattr(exact, "PhaseMarch", _no_march)
    with pytest.raises(ValueError, match=rf"^{name}\b") as err:
        L.solve_exact(L.Oscillator.bingham(**osc_kw), t_end, **kwargs).sample(t_end / 7)
    assert "\n" not in str(err.value)


def _no_march(*args: object, **kwargs: object) -> None:
    raise AssertionError("the march through the phases started: the input was not refused up front")


def test_many_events_message_states_the_estimate():
    with pytest.raises(ValueError, match=r"about 6\.4e\+05 events .* more than the 100000 a run may have"):
        L.solve_exact(L.Oscillator.bingham(stiffness=1e12), 2.0, x0=0.5)


# Extreme but valid: solved quickly, every value finite.
SOLVED = {
    "gamma 1e-6": (dict(gamma=1e-6), dict(x0=0.5)),
    "mass 1e-12": (dict(mass=1e-12), dict(x0=0.5)),
    "mass 1e-300": (dict(mass=1e-300), dict(x0=0.5)),
    "gamma 1e-300": (dict(gamma=1e-300), dict(x0=0.5)),
    "gamma 1e300": (dict(gamma=1e300), dict(x0=0.5)),
    "threshold 1e300": (dict(threshold=1e300), dict(v0=1.0)),
    "mass 1e-300 forced": (dict(mass=1e-300), dict(force=F17B)),
    "gamma 1e-300 forced": (dict(gamma=1e-300), dict(force=F17B)),
    "gamma 1e-6 forced": (dict(gamma=1e-6), dict(x0=0.5, force=F17B)),
    "t_end 1e300": ({}, dict(x0=0.5, t_end=1e300)),
}


@pytest.mark.parametrize("case", SOLVED)
def test_extreme_valid_input_is_solved_quickly_and_finite(case, monkeypatch):
    """Solved, not searched for: few events, and no slip phase sampled beyond its bracketing grid's design.

    The work of the exact solver is its events and, in a forced slip phase, the samples of ``v`` that
    bracket its stop (:meth:`SlipMotion._grid`, then Brent).  Events: at most the up-front estimate
    (:func:`_event_estimate`, an upper bound by its derivation).  Samples of a phase: a geometric run from
    the fast to the slow spacing, at most ``log(1/(1e-12 (GRADE - 1)))/log(GRADE)`` (the fast spacing is at
    least ``1e-12`` times the slow one), then blocks of ``BLOCK`` at the slow spacing over the phase's
    length plus one, then the root's refinement: Brent at most ``MAXITER`` evaluations for the zero and
    as many for each dip (at most two brackets are tried), and 60 halvings leaving rest.  A phase whose
    stop were searched on a too fine grid, or on one reaching ``t_end = 1e300``, would exceed this by far.
    """
    osc_kw, kwargs = SOLVED[case]
    kwargs = dict(kwargs)
    t_end = kwargs.pop("t_end", 2.0)
    samples: dict[int, int] = {}
    state = closed_form.SlipMotion.state

    def counted(motion: closed_form.SlipMotion, t: object) -> tuple[np.ndarray, np.ndarray]:
        samples[id(motion)] = samples.get(id(motion), 0) + np.size(t)
        return state(motion, t)

    monkeypatch.setattr(closed_form.SlipMotion, "state", counted)
    osc = L.Oscillator.bingham(**osc_kw)
    sol = L.solve_exact(osc, t_end, **kwargs)
    force = kwargs.get("force", L.SwitchedSine())
    assert len(sol.events) <= _event_estimate(osc, force, t_end, kwargs.get("x0", 0.0), kwargs.get("v0", 0.0))
    geometric = math.ceil(math.log(1 / (1e-12 * (closed_form._GRADE - 1))) / math.log(closed_form._GRADE))
    refine = 3 * MAXITER + 60
    for phase in (p for p in sol.phases if p.kind == "slip"):
        slow = phase.motion.time_scales()[1] / closed_form._PER_SCALE
        blocks = math.ceil((phase.end - phase.start) / (slow * closed_form._BLOCK)) + 1
        assert samples.pop(id(phase.motion), 0) <= geometric + blocks * closed_form._BLOCK + refine
    monkeypatch.undo()
    tr = sol.sample(t_end / 1000)
    assert np.all(np.isfinite(tr.as_array()))


def _overdamped_free(m, c, k, tau, x0, v0, t):
    """x(t) of the slip ODE m x'' + c x' + k x = -s tau at 50 digits (mpmath roots)."""
    mpmath.mp.dps = 50
    m, c, k, tau, x0, v0 = (mpmath.mpf(a) for a in (m, c, k, tau, x0, v0))
    s = 1 if v0 > 0 or (v0 == 0 and -k * x0 > 0) else -1
    disc = mpmath.sqrt(c * c - 4 * m * k)
    l1, l2 = (-c + disc) / (2 * m), (-c - disc) / (2 * m)
    y0 = x0 + s * tau / k
    a = (v0 - l2 * y0) / (l1 - l2)
    b = y0 - a
    xs = [-s * tau / k + a * mpmath.exp(l1 * ti) + b * mpmath.exp(l2 * ti) for ti in t]
    return np.array([float(v) for v in xs]), (l1, l2, a, b, s)


@pytest.mark.parametrize(
    ("osc_kw", "t_end"), [(dict(gamma=1e-6), 2.0), (dict(mass=1e-12), 2.0), (dict(gamma=1e-3), 50.0)]
)
def test_heavily_overdamped_free_creep_matches_the_closed_form(osc_kw, t_end):
    # From rest v is a sum of two exponentials vanishing only at t = 0: no
    # event, and x creeps towards the band edge tau/k.  Each term is a root
    # (a few ulps) times an exponential (error |l t| ulps): 16 eps |x0| covers
    # the sum of the two terms and the centre.
    osc = L.Oscillator.bingham(**osc_kw)
    sol = L.solve_exact(osc, t_end, x0=0.5)
    assert sol.events == () and math.isnan(sol.rest_time)
    t = np.linspace(0.0, t_end, 41)
    ref, _ = _overdamped_free(osc.mass, osc.dashpot.viscosity, 100.0, 1.0, 0.5, 0.0, t)
    np.testing.assert_allclose(sol.evaluate(t)["x"], ref, rtol=0, atol=16 * EPS * 0.5)


def test_heavily_overdamped_free_stop_time_matches_the_closed_form():
    # Thrown at v0 = 1 with gamma = 1e-6 the mass is stopped within microseconds
    # and then creeps back: v vanishes once, at log(-l2 B/(l1 A))/(l1 - l2).
    # The reference is that formula at 50 digits; the solver's value is a few
    # ulps of the time after Brent's polish: 1e-12 relative.
    osc = L.Oscillator.bingham(gamma=1e-6)
    sol = L.solve_exact(osc, 1.0, v0=1.0)
    _, (l1, l2, a, b, _) = _overdamped_free(1.0, 1e6, 100.0, 1.0, 0.0, 1.0, [0.0])
    t_ref = float(mpmath.log(-l2 * b / (l1 * a)) / (l1 - l2))
    first = sol.events[0]
    assert first.kind == "stop"
    assert first.time == pytest.approx(t_ref, rel=1e-12)


def test_overdamped_forced_first_stop_matches_dop853():
    # gamma = 1e-3: c = 1000, time constants 1e-3 s and 10 s, with the forcing
    # (17b).  From the breakaway arcsin(0.1)/(5 pi) the slip ODE is integrated
    # by DOP853 (rtol 1e-12) to its first zero of v.  Its global error is at
    # most about rtol times the number of steps, asserted below 1000: 1e-9
    # relative on x; v (at most 9e-3 m/s) crosses zero with |dv/dt| = 0.16
    # m/s^2, so a velocity error of 1e-9 * 9e-3 moves the stop by 6e-11 s:
    # 1e-9 s on its time.
    osc = L.Oscillator.bingham(gamma=1e-3)
    sol = L.solve_exact(osc, 1.0, force=F17B)
    breakaway, stop = sol.events[0], sol.events[1]
    assert breakaway.kind == "breakaway" and stop.kind in ("stop", "reversal")
    assert breakaway.time == pytest.approx(math.asin(0.1) / (5 * math.pi), rel=4 * EPS)

    def rhs(t, y):
        return [y[1], F17B(t) - 100.0 * y[0] - 1.0 - 1000.0 * y[1]]

    def v_zero(t, y):
        return y[1]

    v_zero.terminal, v_zero.direction = True, -1
    ref = solve_ivp(
        rhs, (breakaway.time, 1.0), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-15, events=v_zero, first_step=1e-6
    )
    assert ref.status == 1
    assert len(ref.t) < 1000
    assert stop.time == pytest.approx(ref.t_events[0][0], abs=1e-9)
    assert stop.x[0] == pytest.approx(ref.y_events[0][0][0], rel=1e-9)


# Free decays of references.FREE_DECAY, and stiff ones with many half-cycles.
FREE = {
    **{name: FREE_DECAY[name] for name in ("fig11", "other-m-k-tau")},
    "stiff": (1.0, 1e4, 1.0, 1.0, 0.5),
    "stiff-coulomb": (1.0, 1e4, 1.0, math.inf, 0.3),
}


@pytest.mark.parametrize(("m", "k", "tau", "gamma", "x0"), FREE.values(), ids=list(FREE))
def test_event_estimate_is_not_below_the_count(m, k, tau, gamma, x0):
    # The refusal relies on the estimate; it must not undercount free decay.
    osc = L.Oscillator.bingham(mass=m, stiffness=k, threshold=tau, gamma=gamma)
    sol = L.solve_exact(osc, 100.0, x0=x0)
    estimate = _event_estimate(osc, L.SwitchedSine(), 100.0, x0, 0.0)
    assert len(sol.events) <= estimate <= 2 * len(sol.events) + 4


def test_max_events_below_the_count_is_refused_naming_t_end():
    osc = L.Oscillator.bingham(stiffness=1e4)
    n = len(L.solve_exact(osc, 100.0, x0=0.5).events)
    with pytest.raises(ValueError, match=rf"^t_end: .*more than the {n - 1}( events)? a run may have"):
        L.solve_exact(osc, 100.0, x0=0.5, max_events=n - 1)


@pytest.mark.parametrize("amplitude", [0.0, 0.5, 10.0])
def test_paper_examples_are_solved_instantly_with_the_default_bound(amplitude):
    osc = L.Oscillator.bingham()
    kwargs = dict(x0=0.5) if amplitude == 0 else dict(force=dataclasses.replace(F17B, amplitude=amplitude))
    sol = L.solve_exact(osc, 5.0, **kwargs)
    # "Instantly": a handful of events, within the up-front estimate, far below the default bound
    force = kwargs.get("force", L.SwitchedSine())
    assert len(sol.events) <= _event_estimate(osc, force, 5.0, kwargs.get("x0", 0.0), 0.0) < 1000
    if amplitude == 0:  # the free vibration of the paper (Figure 11)
        assert sol.rest_time == pytest.approx(3.1455270229, abs=1e-10)
        assert sol.rest_position == pytest.approx(0.0027461553, abs=1e-10)
