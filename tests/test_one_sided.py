"""One-sided derivatives of forced one-mass motion where its event sequence changes (issue 24), against one-sided
differences of the exact solver on each side, the jump of the rest time against the events that make it, and the
free decay's closed-form switch (:class:`~lumped.solvers.sensitivities.RestSwitch`)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.solvers.exact import solve_exact
from lumped.solvers.one_sided import Problem, moved, one_sided
from lumped.solvers.sensitivities import sensitivities

EPS = float(np.finfo(float).eps)
_KEYS = ("mass", "stiffness", "threshold", "gamma", "x0", "v0", "force_amplitude", "force_omega", "force_phase")
STICK_SLIP = dict(zip(_KEYS, (1.0, 1.0, 1.0, 2.0, 0.2, 0.0, 2.0, 1.3, 0.4)))
#: Three changes of the event sequence, each at the parameter ``key`` bisected in ``bracket`` to neighbouring
#: doubles, on the lower one: the stick-slip mass whose force goes off just as it would break away (the rest
#: time jumps by the stick's length); the same mass, whose turn at t ~ 4.7 s, during the forcing, is a reversal on
#: one side and a stop on the band's edge with a breakaway at once on the other; the forced-then-free mass of
#: tests/test_sensitivities.py, which loses its last half-cycle after the force goes off (the rest has a kink).
CASES = {
    "force off at a breakaway": (STICK_SLIP | {"force_until": 2.3, "t_end": 30.0}, "force_until", (2.1, 2.4)),
    "stop on the band's edge": (STICK_SLIP | {"force_until": 9.0, "t_end": 30.0}, "threshold", (1.0, 1.05)),
    "half-cycle lost": (
        dict(zip(_KEYS, (1.0, 100.0, 1.07, 1.0, 0.5, 0.3, 2.0, 3.0, 0.2))) | {"force_until": 2.5, "t_end": 5.0},
        "threshold",
        (1.06, 1.08),
    ),
}
NAMES = ("threshold", "force_amplitude", "x0", "force_until", "stiffness")


def _solve(p: dict):
    osc = Oscillator.bingham(p["mass"], p["stiffness"], p["threshold"], p["gamma"])
    force = SwitchedSine(p["force_amplitude"], p["force_omega"], p["force_phase"], p["force_until"])
    return solve_exact(osc, p["t_end"], x0=p["x0"], v0=p["v0"], force=force)


def _kinds(sol) -> list[str]:
    return [e.kind for e in sol.events]


def _edge(case: str) -> dict:
    """The case's parameters at the lower of the two neighbouring doubles where its event sequence changes."""
    p, key, (lo, hi) = CASES[case]
    below = _kinds(_solve(p | {key: lo}))
    assert below != _kinds(_solve(p | {key: hi}))
    while math.nextafter(lo, hi) < hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _kinds(_solve(p | {key: mid})) == below else (lo, mid)
    return p | {key: lo}


def _turns(sol) -> tuple[int, int]:
    """The counts of breakaways and reversals, which tell the sides of the three changes apart (an instant's
    slip after the force goes off may or may not end in a stop event of its own)."""
    kinds = _kinds(sol)
    return kinds.count("breakaway"), kinds.count("reversal")


def _summaries(sol, t: np.ndarray) -> np.ndarray:
    return np.concatenate([sol.evaluate(t)["x"], [sol.rest_time, sol.rest_position]])


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("name", NAMES)
def test_each_side_matches_one_sided_differences(case, name):
    # On side sigma, D1 = (S(p + 2 sigma h) - S(p + sigma h))/(sigma h) and D2 = (S(p + 4 sigma h) -
    # S(p + 2 sigma h))/(2 sigma h) use that side's solutions only (whichever side p itself is on): D1 is off the
    # one-sided derivative by 3h/2 |S''|, which |D1 - D2| estimates (bound: twice it), plus 4 eps_f/h of the
    # solver's round-off (eps_f as in tests/test_sensitivities.py: an ulp per event of the scales, here taken
    # at 4 ulps of max|x| + t_end max|v| per event).  The side's own derivative, taken at p -+ delta, is off by
    # delta |S''|, negligible.  Sample times where an event passes within the stencil are left out (x is only
    # C^1 in p there).
    p = _edge(case)
    t = np.linspace(0.0, p["t_end"], 31)
    base = _solve(p)
    (got,) = one_sided(base, [name], t)
    problem = Problem.of(base)
    h = 1e-6 * problem.scale(name)
    cols = base.evaluate(np.linspace(0.0, p["t_end"], 2001))
    eps_f = 4 * (len(base.events) + 1) * EPS * (np.abs(cols["x"]).max() + p["t_end"] * max(np.abs(cols["v"]).max(), 1))
    checked = 0
    for sigma, side in ((1, got.above), (-1, got.below)):
        runs = {n: _solve_problem(moved(problem, name, sigma * n * h), p["t_end"]) for n in (1, 2, 4)}
        assert len({_turns(r) for r in runs.values()}) == 1  # the stencil stays on its side
        f = {n: _summaries(r, t) for n, r in runs.items()}
        d1, d2 = (f[2] - f[1]) / (sigma * h), (f[4] - f[2]) / (2 * sigma * h)
        exact = np.concatenate([side.x[:, 0], side.rest_time, side.rest_position])
        near = np.zeros(t.size, dtype=bool)
        for e1, e4 in zip(runs[1].events, runs[4].events):
            near |= (t >= min(e1.time, e4.time) - 1e-9) & (t <= max(e1.time, e4.time) + 1e-9)
        keep = np.concatenate([~near, np.isfinite(exact[-2:])])
        assert keep.sum() > 0.8 * t.size
        assert np.all(np.abs(exact[keep] - d1[keep]) <= 2 * np.abs(d1 - d2)[keep] + 4 * eps_f / h)
        checked += _event_times(side, runs, sigma * h, 4 * (len(base.events) + 1) * EPS * p["t_end"])
    assert checked > 0 or case == "force off at a breakaway"


def _event_times(side, runs: dict, h: float, eps_t: float) -> int:
    """Check the side's event times against one-sided differences as for the summaries (their round-off
    ``eps_t``: an ulp of ``t_end`` per event) where the stencil has the side's events; return how many.

    An event with a margin below 1e-3 is left out: a stop reached with an acceleration ``a`` near 0 (the end of
    a half-cycle of vanishing amplitude) has its time found to ``eps |v|/|a|``, not to an ulp of ``t``.
    """
    want = [e.event.kind for e in side.events]
    times = {n: [e.time for e in r.events if e.kind != "rest"] for n, r in runs.items()}
    if any([e.kind for e in r.events if e.kind != "rest"] != want for r in runs.values()):
        return 0
    d1 = (np.array(times[2]) - times[1]) / h
    d2 = (np.array(times[4]) - times[2]) / (2 * h)
    exact = np.array([e.time[0] for e in side.events])
    keep = np.array([e.margin >= 1e-3 for e in side.events])
    assert np.all(np.abs(exact - d1)[keep] <= (2 * np.abs(d1 - d2) + 4 * eps_t / abs(h))[keep])
    return int(keep.sum())


def _solve_problem(problem: Problem, t_end: float):
    osc, force, x0, v0 = problem
    return solve_exact(osc, t_end, x0=x0, v0=v0, force=force)


@pytest.mark.parametrize("name", NAMES)
def test_the_rest_time_jumps_by_the_stick_the_force_going_off_cuts_short(name):
    # At the edge the force goes off at the instant the mass would break away.  On the side without the
    # breakaway the rest begins at the stop that began the stick; on the other the mass slips for an instant
    # and rests at t_off.  So the rest time jumps by t_off - t_stop, up (+) where the side above breaks away;
    # the rest position is continuous.  Both sides are at p -+ delta: the jump is good to delta^2 |S''| plus
    # the solver's round-off (an ulp of t per event), below 1e-12 s.
    p = _edge("force off at a breakaway")
    base = _solve(p)
    t_stop = max(e.time for e in base.events if e.kind == "stop")
    (got,) = one_sided(base, [name], ())
    assert not got.same_events
    sign = 1 if "breakaway" in _kinds(_solve_problem(moved(Problem.of(base), name, got.delta), 30.0))[2:] else -1
    assert got.rest_time_jump == pytest.approx(sign * (p["force_until"] - t_stop), abs=1e-12)
    assert abs(got.rest_position_jump) <= 1e-12


def test_a_stop_on_the_band_edge_under_the_force_leaves_the_motion_c1():
    # A turn that is a reversal on one side and a stop with an immediate breakaway on the other: the event
    # sequences differ, yet x(t) and the rest have no kink and no jump: the new stick starts with the net force
    # on the band's edge, so the motion after it starts with zero acceleration and moving its start time changes
    # it at second order only.  The sides' derivatives, taken at p -+ delta, differ by delta times the jump of
    # S'' (not by a fixed amount, as at a kink): ten times delta, ten times the gap (to 1e-3: the chain's
    # round-off, 1e-13, against gaps of 1e-9).  The time of the turn has a kink: the reversal's time and the
    # breakaway's time move differently.
    p = _edge("stop on the band's edge")
    t = np.linspace(0.0, 30.0, 31)
    small, large = (one_sided(_solve(p), ["threshold"], t, step=step)[0] for step in (1e-9, 1e-8))
    for got in (small, large):
        assert not got.same_events
        assert np.abs(got.x_jump).max() <= 1e-12 and abs(got.rest_position_jump) <= 1e-12
    gap = lambda got: np.append(
        np.abs(got.below.x - got.above.x), abs(got.below.rest_position - got.above.rest_position)
    )
    assert gap(small).max() > 1e-10
    assert np.allclose(gap(large), 10 * gap(small), rtol=1e-3, atol=1e-12)
    turns = [next(e for e in side.events if 4.0 < e.event.time < 5.0) for side in (small.below, small.above)]
    assert sorted(e.event.kind for e in turns) == ["reversal", "stop"]
    stuck = small.below if turns[0].event.kind == "stop" else small.above
    breakaway = next(e for e in stuck.events if e.event.kind == "breakaway" and 4.0 < e.event.time < 5.0)
    reversal = next(e for e in turns if e.event.kind == "reversal")
    assert abs(breakaway.time[0] - reversal.time[0]) > 0.1 * abs(reversal.time[0])  # a kink in the turn's time


def test_across_a_lost_half_cycle_after_the_force_the_sides_are_the_closed_form_switches():
    # After the force goes off the motion is the free decay, and the RestSwitch of each side (closed form) is the
    # other side's derivative: the chain's derivatives at p -+ delta must agree with it to delta |S''| (1e-9).
    p = _edge("half-cycle lost")
    names = ["threshold", "stiffness", "x0"]
    for got in one_sided(_solve(p), names, ()):
        more, fewer = sorted((got.below, got.above), key=lambda s: -len(s.events))
        lose = next(w for w in more.switches if w.kind == "lose")
        gain = next(w for w in fewer.switches if w.kind == "gain")
        assert lose.rest_position[0] == pytest.approx(fewer.rest_position[0], rel=1e-7)
        assert gain.rest_position[0] == pytest.approx(more.rest_position[0], rel=1e-7)
        assert abs(more.rest_position[0] - fewer.rest_position[0]) > 0.01 * abs(more.rest_position[0])  # a kink
        jump = got.rest_time_jump * (1 if got.above is more else -1)
        assert jump == pytest.approx(gain.rest_time_jump, abs=1e-9)  # half a damped period


def test_a_force_that_only_touches_the_band_gives_event_times_of_unbounded_slope():
    # A mass stuck at x = 0 under P sin(w t) with P = tau: the force touches the band's edge at its peaks and
    # never leaves it.  Below, the mass never moves (no events); above, it breaks away at t_c = asin(tau/P)/w,
    # whose slope dt_c/dP = -tau/(P^2 w sqrt(1 - tau^2/P^2)) grows as delta^(-1/2).  The chain at P = tau + delta
    # is exact there: it must equal that closed form, to the closed form's own cancellation (1 - tau^2/P^2 =
    # 2 delta carries eps/delta relatively: 1e-7, halved by the root).  The slip lasts ~delta^(1/2) with a force
    # excess ~delta: x moves by ~delta^2, so its slope is ~delta on that side, 0 on the other: C^1.
    w = 1.3
    sol = solve_exact(Oscillator.bingham(1.0, 1.0, 1.0, 2.0), 10.0, force=SwitchedSine(1.0, w))
    assert sol.events == ()
    t = np.linspace(0.0, 10.0, 11)
    slopes, x = [], []
    for step in (1e-9, 1e-8):
        (got,) = one_sided(sol, ["force_amplitude"], t, step=step)
        assert not got.same_events and got.below.events == () and not got.below.x.any()
        P = 1.0 + got.delta
        first = got.above.events[0]
        assert first.event.kind == "breakaway"
        assert first.time[0] == pytest.approx(-1.0 / (P * P * w * math.sqrt(1.0 - 1.0 / P**2)), rel=1e-7)
        slopes.append(first.time[0])
        x.append(np.abs(got.above.x).max())
        # The jump x(P + delta) - x(P) - delta (s_below + s_above), s_below = 0, is at most 2 delta max|s_above|
        # (x(P + delta) is the integral of s over [P, P + delta], s growing with delta), plus the rounding of the
        # two positions: each a closed form of a few terms no larger than the forced amplitude P/|k - m w^2|, so
        # 16 eps of it bounds both (the rounding alone, 5 eps, exceeds the truncation at delta = 1e-9).
        scale = 1.0 / abs(1.0 - w * w)
        assert np.abs(got.x_jump).max() <= 2 * got.delta * np.abs(got.above.x).max() + 16 * np.finfo(float).eps * scale
    assert slopes[0] / slopes[1] == pytest.approx(math.sqrt(10.0), rel=1e-6)  # delta^(-1/2)
    assert x[1] / x[0] == pytest.approx(10.0, rel=1e-3) and x[0] < 1e-8  # delta^1: C^1, the slope 0 at the edge


def test_bad_arguments_are_refused_in_one_line():
    sol = _solve(CASES["force off at a breakaway"][0] | {"force_until": math.inf})
    coulomb = solve_exact(Oscillator.bingham(1.0, 1.0, 1.0, math.inf), 5.0, x0=2.0)
    for args, message in (
        ((sol, ["tau"]), r"^parameters: unknown parameter 'tau'; expected some of mass, "),
        ((sol, ["force_until"]), r"^force_until: inf has no neighbouring values; it cannot move$"),
        ((coulomb, ["gamma"]), r"^gamma: inf has no neighbouring values; it cannot move$"),
        ((coulomb, ["viscosity"]), r"^viscosity: c = 0 is the edge of its range; it has no side below$"),
        (({}, ["x0"]), r"^solution must be an ExactSolution, got dict$"),
    ):
        with pytest.raises(ValueError, match=message):
            one_sided(*args)
    with pytest.raises(ValueError, match=r"^step must lie in \(0, 1e-3\], got 0.1$"):
        one_sided(sol, ["x0"], (), step=0.1)


def test_away_from_a_change_both_sides_are_the_derivative():
    # The paper's free decay far from any change (margins > 0.1): both sides have its event sequence and agree
    # with the two-sided derivative to delta |S''| + round-off: 1e-7 of it.
    p = STICK_SLIP | {"force_until": math.inf, "t_end": 20.0}
    sol = solve_exact(Oscillator.bingham(1.0, 100.0, 1.0, 1.0), 4.0, x0=0.5)
    assert p and sensitivities(sol, (), ["x0"]).smallest_margin() > 0.1
    t = np.linspace(0.0, 4.0, 41)
    both = sensitivities(sol, t, ["threshold", "x0"])
    for j, got in enumerate(one_sided(sol, ["threshold", "x0"], t)):
        assert got.same_events
        for side in (got.below, got.above):
            assert np.abs(side.x[:, 0] - both.x[:, j]).max() <= 1e-7 * np.abs(both.x[:, j]).max()
