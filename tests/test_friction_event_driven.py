"""The ``event-driven`` method on friction contacts of any slip curve (issue 33, part B).

References: the closed-form stick-slip cycle of static above kinetic on a
belt, Leine et al.'s benchmark (Nonlinear Dynamics 16 (1998) 41-54) against an
independent event-located integration with SciPy's ``solve_ivp``, and the
Hopf speed of steady sliding on a Stribeck belt (the Veraszto-Stepan
parameters), with the decay and growth rates of its linearisation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import lumped
from lumped.laws import LinearDashpot, SlipCurve, Spring
from lumped.laws.slip_elements import Contact
from lumped.laws.stribeck import Friction, StribeckLaw
from lumped.model.forcing import SwitchedSine, Table
from lumped.model.network import Driver, Load, Mass, Network
from lumped.model.problem import Problem
from lumped.solvers.event_driven_network import solve_contact

EPS = float(np.finfo(float).eps)


def belt_system(contact, V: float, *, k: float = 1.0, m: float = 1.0, x0: float = 0.0, extra=()) -> Network:
    """One mass on a spring to the ground and ``contact`` (an element between ``belt`` and ``m``) on a belt at ``V``."""
    elements = [Spring("k", ("ground", "m"), k), contact, *extra]
    return Network([Mass("m", m, x0, 0.0)], elements, drivers=[Driver("belt", V)])


def times(tr, kind: str) -> np.ndarray:
    return np.array([e.time for e in tr.events if e.kind == kind])


def extremes(sol, t0: float, t1: float) -> list[tuple[float, float]]:
    """``(t, x)`` where the velocity of the continuous solution ``sol`` changes sign in ``(t0, t1)``."""
    grid = np.linspace(t0, t1, 4001)
    v = sol.state(grid)[1]
    where = np.flatnonzero(np.sign(v[1:]) * np.sign(v[:-1]) < 0)
    roots = [brentq(lambda t: float(sol.state(np.array([t]))[1][0]), grid[i], grid[i + 1], xtol=1e-15) for i in where]
    return [(r, float(sol.state(np.array([r]))[0][0])) for r in roots]


# -- static above kinetic on a belt: the closed-form cycle ------------------------------------------------


def test_static_above_kinetic_on_a_belt_meets_the_closed_form_cycle():
    """After the first breakaway (at ``x = static/k``, moving with the belt) the motion is the cycle: a harmonic
    slip about ``kinetic/k`` of ``pi + 2 atan(V/(omega d))``, ``d = (static - kinetic)/k``, then a stick of
    ``2 d / V`` while the spring loads at the belt's speed; the extremes are ``kinetic/k +- A``,
    ``A = sqrt(d^2 + (V/omega)^2)``."""
    static, kinetic, V, k, m = 1.0, 0.5, 0.2, 1.0, 1.0
    net = belt_system(Friction("f", ("belt", "m"), static=static, kinetic=kinetic), V, k=k, m=m)
    tr = lumped.solve(Problem(net, 30.0), 1e-3, method="event-driven", rtol=1e-12)
    omega, d = math.sqrt(k / m), (static - kinetic) / k
    slip, stick = (math.pi + 2 * math.atan(V / (omega * d))) / omega, 2 * d / V
    breaks, stops = times(tr, "breakaway"), times(tr, "stop")
    # DOP853 at rtol 1e-12 on an O(1) state over ~60 steps of a slip that does not amplify errors (a harmonic
    # oscillation: its flow is an isometry in the energy norm) errs by at most ~60 * 2e-12 ~ 1e-10 in the state;
    # the stop's time then by that over |u'| = d k/m = 0.5 at the stop (Brent's xtol 2e-12 on top): 1e-9.
    n = len(breaks)
    assert n >= 2 and len(stops) >= n
    assert np.allclose(stops[1:n] - breaks[: n - 1], slip, rtol=0, atol=1e-9)
    assert np.allclose(breaks[1:] - stops[1:n], stick, rtol=0, atol=1e-9 / V)  # the stop's place error over V
    sol = solve_contact(net, 30.0, rtol=1e-12)
    (t_hi, x_hi), (t_lo, x_lo) = extremes(sol, breaks[0], stops[1])
    amplitude = math.hypot(d, V / omega)
    assert x_hi == pytest.approx(kinetic / k + amplitude, abs=1e-9)
    assert x_lo == pytest.approx(kinetic / k - amplitude, abs=1e-9)
    stuck = tr.rigid[:, 1]
    assert np.all(tr.velocities[stuck, 0] == V)  # sticking to the belt is exact, not a small rate
    assert np.all(np.abs(tr.forces[stuck, 1]) <= static)


def test_the_tensions_are_the_elements_own():
    """Spring ``k x``, contact ``T``: in stick the contact holds the spring (``T = -k x``, the mass does not
    accelerate); in slip it is ``sgn(w) g(|w|)`` at the element's own rate ``w = v - V``."""
    net = belt_system(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5, stribeck_velocity=0.1), 0.2)
    tr = lumped.solve(Problem(net, 12.0), 1e-2, method="event-driven")
    x, v = tr.positions[:, 0], tr.velocities[:, 0]
    assert np.array_equal(tr.forces[:, 0], 1.0 * x)
    stuck = tr.rigid[:, 1]
    assert stuck.any() and (~stuck[1:]).any()
    assert np.array_equal(tr.forces[stuck, 1], -x[stuck])
    w = v[~stuck] - 0.2
    law = StribeckLaw(1.0, 0.5, 0.1)
    assert np.allclose(tr.forces[~stuck, 1][1:], np.sign(w[1:]) * law.slip(np.abs(w[1:])), rtol=1e-13, atol=0)


def test_a_contact_to_the_ground_stops_where_the_closed_form_says():
    """No belt: from ``x0 > static/k`` at rest the mass slips back by half a period about ``kinetic/k`` and
    stops at ``2 kinetic/k - x0``, where the spring's ``k |x|`` is within ``static``: at rest for ever."""
    static, kinetic, k, x0 = 1.0, 0.6, 4.0, 0.5
    net = Network(
        [Mass("m", 1.0, x0)],
        [Spring("k", ("ground", "m"), k), Friction("f", ("ground", "m"), static=static, kinetic=kinetic)],
    )
    tr = lumped.solve(Problem(net, 3.0), 1e-3, method="event-driven", rtol=1e-12)
    assert [e.kind for e in tr.events] == ["stop", "rest"]  # no load: the stop is the rest, as for one mass
    assert tr.events[0].time == pytest.approx(math.pi / 2, abs=1e-9)  # a harmonic slip: see the belt's test
    assert tr.events[1].time == tr.events[0].time and tr.events[1].x == tr.events[0].x
    assert tr.rest_positions[0] == pytest.approx(2 * kinetic / k - x0, abs=1e-10)
    assert tr.rest_times[0] == tr.events[0].time
    assert np.all(tr.velocities[tr.t > tr.rest_times[0], 0] == 0.0)


@pytest.mark.parametrize("depth", [1e-9, -1e-9])
def test_a_slip_speed_that_touches_zero_inside_one_step_stops_there(depth: float):
    """A stop shorter than an integrator step.  Slipping back on the belt (``u = v - V < 0``) the mass oscillates
    harmonically about ``kinetic/k`` (``m = k = 1``): from ``x0 = kinetic/k``, ``v0 = -A`` the speed is
    ``-A cos t`` and the slip speed's largest value, at ``t = pi``, is ``A - V = depth``.  With ``depth = 1e-9``
    the slip speed is at or above 0 for ``2 arccos(V/A) = 2e-4`` s, inside one DOP853 step (about 0.08 s here,
    asserted), and the contact stops at ``t* = pi - arccos(V/A)`` (a holding force ``k x``, about ``kinetic``,
    within ``static``: it sticks); with ``depth = -1e-9`` it never reaches the belt's speed and slips on.

    Tolerance: each step errs in ``u`` by at most ``rtol |u| + atol`` (``|u| <= 2 V``), and the undamped
    oscillator does not grow errors (its flow is a rotation in ``(x, u)``), so ``u`` errs by at most
    ``steps (rtol 2 V + atol)`` at ``t*``: the zero moves by that over the slip speed's slope there,
    ``A sin(arccos(V/A))``, about 2e-5 m/s^2 (Brent's 4 eps on ``t*`` is far below)."""
    V, static, kinetic, rtol = 0.2, 1.0, 0.5, 1e-13
    A = V + depth
    elements = [Spring("k", ("ground", "m"), 1.0), Friction("f", ("belt", "m"), static=static, kinetic=kinetic)]
    net = Network([Mass("m", 1.0, kinetic, -A)], elements, drivers=[Driver("belt", V)])
    sol = solve_contact(net, 4.0, rtol=rtol)
    opening = 2 * math.asin(math.sqrt(abs(depth) / A / 2))  # arccos(V/A), without the cancellation in 1 - V/A
    slip = sol.phases[0].motion
    if depth < 0:
        assert sol.events == [] and [p.kind for p in sol.phases] == ["slip"]
        steps = slip.steps
        # the touch lies inside one step: no step ends within the dip's span (pi -+ opening)
        assert not np.any(np.abs(steps - math.pi) <= opening)
        return
    assert [(e.kind, p.kind) for e, p in zip(sol.events, sol.phases[1:])] == [("stop", "stick")]
    t_star = math.pi - opening
    slope = A * math.sin(opening)
    steps = slip.steps
    bound = len(steps) * (rtol * 2 * V + 1e-3 * rtol * static) / slope  # atol: 1e-3 rtol (static / sqrt(k m))
    assert sol.events[0].time == pytest.approx(t_star, abs=bound)
    assert steps[-2] < t_star - 10 * opening  # the step that holds the stop began well before the touch


# -- Leine et al.'s benchmark --------------------------------------------------------------------------------

V_LEINE, FS, DELTA = 0.2, 1.0, 3.0


def leine_g(s: float) -> float:
    return FS / (1 + DELTA * s)


def leine_reference(t_end: float, tol: float) -> tuple[np.ndarray, list[tuple[float, float]]]:
    """Breakaway times and ``(t, x)`` of the turning points by SciPy's DOP853 with events, stick in closed form.

    Slip with ``s = sgn(v - V)``: ``x'' = -x - s g(s (v - V))`` (the smooth continuation of the phase's
    slip force through its stop), ended by ``v = V``; then stick if ``|x| <= F_s`` (the spring's force within
    the static bound), else the other way.  Stick moves with the belt until ``-x`` reaches ``-F_s``.
    """
    t, x, v = 0.0, 0.0, 0.0
    breaks, turns = [], []
    while t < t_end:
        s = 0 if v == V_LEINE else (1 if v > V_LEINE else -1)
        if s == 0:
            if abs(x) <= FS:
                t, x, s = t + (FS - x) / V_LEINE, FS, -1
                breaks.append(t)
            else:
                s = 1 if -x > 0 else -1

        def rhs(_, y, s=s):
            return [y[1], -y[0] - s * leine_g(s * (y[1] - V_LEINE))]

        def stop(_, y):
            return y[1] - V_LEINE

        def turn(_, y):
            return y[1]

        stop.terminal, stop.direction = True, -s
        sol = solve_ivp(rhs, (t, t_end), [x, v], method="DOP853", rtol=tol, atol=tol, events=[stop, turn])
        turns += [(float(a), float(b[0])) for a, b in zip(sol.t_events[1], sol.y_events[1]) if a > t]
        if sol.status != 1:
            break
        t, x, v = float(sol.t_events[0][0]), float(sol.y_events[0][0][0]), V_LEINE
    return np.array(breaks), turns


def leine_system() -> Network:
    return belt_system(Contact("c", ("belt", "m"), SlipCurve(FS, leine_g, fall=DELTA)), V_LEINE)


def test_leines_benchmark_agrees_with_an_independent_event_located_integration():
    """Every breakaway is at ``x = F_s/k = 1`` moving with the belt, so the cycle is reached at the first one;
    its period and turning points agree with the reference to 1e-8.

    The tolerance: both integrate at 1e-13 (rtol and, relative to the O(1) state, atol), ~80 steps a cycle,
    each with a local error below ~2e-13; the slip's linearisation (``x'' = -x + g'(|u|) u'``, the falling
    curve a negative damping up to 3) grows an error by at most 22 over a slip (its fundamental matrix along
    the cycle, computed when this test was written), so each state is within 80 * 2e-13 * 22 = 3.5e-10.  A
    stop's time errs by that over ``|u'| = 1.5``; the stick that follows moves the error in place into time
    by ``1/V = 5``: 1.8e-9 a method, twice that between two: below 1e-8.
    """
    ref_breaks, ref_turns = leine_reference(40.0, 1e-13)
    ref_breaks = ref_breaks[ref_breaks < 40.0]  # the reference dates the last stick's end past the span
    tr = lumped.solve(Problem(leine_system(), 40.0), 1e-2, method="event-driven", rtol=1e-13)
    breaks = times(tr, "breakaway")
    assert len(breaks) == len(ref_breaks) >= 3
    assert np.allclose(np.diff(breaks), np.diff(ref_breaks), rtol=0, atol=1e-8)
    sol = solve_contact(leine_system(), 40.0, rtol=1e-13)
    ours = extremes(sol, breaks[1], breaks[2])
    ref = [(t, x) for t, x in ref_turns if breaks[1] < t < breaks[2]]
    assert len(ours) == len(ref) == 2
    assert np.allclose(ours, ref, rtol=0, atol=1e-8)
    assert ref[0][1] > FS > 0 > ref[1][1]  # past the breakaway point, then back below the spring's rest


# -- Stribeck stability: the Hopf speed ---------------------------------------------------------------------

M, K, B0 = 0.538, 6957.0, 5.746
C, C0, CV, BS = 2.0, 6.0, 10.0, 0.2
#: b0 + b_s - (C0 - C) c_v exp(-c_v V) = 0: the total damping of the linearised sliding motion vanishes.
V_HOPF = math.log((C0 - C) * CV / (B0 + BS)) / CV


def stribeck_g(s: float) -> float:
    return C + (C0 - C) * math.exp(-CV * s) + BS * s


def damping(V: float) -> float:
    """The linearised sliding motion's damping (N s/m): ``b0 + g'(V)``; the motion ``x* + A e^(-lambda t) cos``
    with ``lambda = damping / (2 m)``."""
    return B0 + BS - (C0 - C) * CV * math.exp(-CV * V)


def stribeck_system(V: float, dx: float) -> Network:
    """Started at rest ``dx`` from the sliding equilibrium ``x* = g(V)/k`` (the mass still, the belt sliding)."""
    friction = Friction("f", ("belt", "m"), static=C0, kinetic=C, stribeck_velocity=1 / CV, viscous=BS)
    return belt_system(
        friction, V, k=K, m=M, x0=stribeck_g(V) / K + dx, extra=[LinearDashpot("b0", ("ground", "m"), B0)]
    )


def peak_rate(t: np.ndarray, x: np.ndarray) -> float:
    """The exponential rate of the oscillation's swings, each maximum of ``x`` less the minimum after it (a
    least-squares line through their logarithms); the swings do not see a slow drift of the centre."""
    inner = x[1:-1]
    top = np.flatnonzero((inner > x[:-2]) & (inner >= x[2:])) + 1
    low = np.flatnonzero((inner < x[:-2]) & (inner <= x[2:])) + 1
    pairs = [(i, low[np.searchsorted(low, i)]) for i in top if np.searchsorted(low, i) < low.size]
    swings = np.array([x[i] - x[j] for i, j in pairs])
    return float(np.polyfit(t[[i for i, _ in pairs]], np.log(swings), 1)[0])


def test_the_hopf_speed_is_where_the_damping_vanishes():
    assert damping(V_HOPF) == pytest.approx(0.0, abs=1e-13)
    assert damping(1.1 * V_HOPF) > 0 > damping(0.9 * V_HOPF)
    assert V_HOPF == pytest.approx(0.190616, abs=1e-6)


@pytest.mark.parametrize("factor", [1.1, 0.9])
def test_event_driven_sliding_decays_above_the_hopf_speed_and_grows_below(factor: float):
    """Started 1e-6 m off the equilibrium the swings decay or grow at ``-damping/(2 m)``, to within: the
    nonlinearity, the Stribeck slope's first-harmonic mean over the oscillation, ``(c_v du)^2/8`` of it
    (``du = omega dx`` at most 6.5e-4 m/s after the growth by 5.7 over the run), relative to the damping it
    nearly cancels (5.8 times smaller): 3e-5; the extrema's sampling every 1e-5 s, ``(omega dt)^2/8 = 2e-6``;
    DOP853 at rtol 1e-12 on ``x ~ 5e-4`` m over ~3000 steps, 1e-6 of the 1e-6 m oscillation.  So 1e-4.
    Below the Hopf speed the growth ends in stick-slip."""
    V = factor * V_HOPF
    net = stribeck_system(V, 1e-6)
    sol = solve_contact(net, 1.5, rtol=1e-12)
    t = np.arange(0, 150_001) * 1e-5
    x = sol.state(t)[0]
    assert peak_rate(t, x) == pytest.approx(-damping(V) / (2 * M), rel=1e-4)
    assert not sol.events  # linear sliding, no stick yet
    if factor < 1:
        tr = lumped.solve(Problem(stribeck_system(V, 1e-5), 6.0), 1e-3, method="event-driven")
        stuck = tr.rigid[:, 1]
        assert len(times(tr, "stop")) > 10 and stuck[tr.t > 5].any()
    else:
        assert np.ptp(sol.state(np.linspace(1.4, 1.5, 1001))[0]) < 0.5 * np.ptp(x[:10_000])


def backward_euler_rate(V: float, dt: float) -> float:
    """The decay rate of backward Euler's linearised step ``(I - dt A)^-1`` at ``V`` (its largest |eigenvalue|)."""
    a = np.array([[0.0, 1.0], [-K / M, -damping(V) / M]])
    mu = np.max(np.abs(np.linalg.eigvals(np.linalg.inv(np.eye(2) - dt * a))))
    return -math.log(mu) / dt


@pytest.mark.slow  # the Python step of a falling curve: about 1.2 ms a step, 37,000 steps
def test_backward_euler_sliding_decays_above_the_hopf_speed_and_grows_into_stick_slip_below():
    """At ``dt = 5e-5`` the step is unique (``m/dt + k dt`` far above the fall 39.8) and its own damping,
    ``k dt = 0.35`` N s/m, is below ``|damping|`` on both sides, so the rate of its linearised step keeps the
    sign of the exact one (asserted).  Started 1e-5 m off, the swings decay or grow at that rate to 1e-3 (the
    nonlinearity ``(c_v omega dx)^2/8`` times 5.8, 1e-4 after the growth; the sampling ``(omega dt)^2/8 =
    4e-6``), and below the Hopf speed, from 5e-4 m, the growth ends in stick-slip."""
    dt = 5e-5
    fall = Friction("f", ("belt", "m"), static=C0, kinetic=C, stribeck_velocity=1 / CV, viscous=BS).steepest_fall
    assert fall == pytest.approx(39.8) and M / dt + K * dt > fall
    for factor in (1.1, 0.9):
        V = factor * V_HOPF
        rate = backward_euler_rate(V, dt)
        assert (rate > 0) == (damping(V) > 0)
        tr = lumped.simulate_network(stribeck_system(V, 1e-5), 0.25, dt)
        assert peak_rate(tr.t, tr.positions[:, 0]) == pytest.approx(-rate, rel=1e-3)
        assert not tr.rigid.any()
    tr = lumped.simulate_network(stribeck_system(0.9 * V_HOPF, 5e-4), 1.35, dt)
    assert tr.rigid[tr.t > 1.0, 1].any()  # stick-slip


# -- SlipCurve's sampled fall ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("g", "fall", "curvature"),
    [
        (leine_g, FS * DELTA, 2 * FS * DELTA**2),  # -g' = 3/(1+3s)^2, steepest at 0; |g''| <= 18
        (stribeck_g, (C0 - C) * CV - BS, (C0 - C) * CV**2),  # -g' = 40 exp(-10 s) - 0.2; |g''| <= 400
    ],
)
def test_the_sampled_fall_is_the_closed_form_fall(g, fall, curvature):
    """Both curves fall steepest at 0, so the sample's first secant, over ``[0, h]`` with ``h = 1e-9`` m/s,
    misses ``-g'(0)`` by at most ``|g''| h/2`` (Taylor), and no secant exceeds ``-g'(0)`` by more than the
    rounding of ``g(s_i) - g(s_i+1)`` (a few half-ulps of ``g(0)``, ``2 eps g(0)``) over the shortest interval
    of the sample, ``h_min = 1e-9 (10^(1/32) - 1) = 7.5e-11``: 3.6e-5 N s/m for the Stribeck curve."""
    static = g(0.0)
    sampled = SlipCurve(static, g).fall
    h, h_min = 1e-9, 1e-9 * (10 ** (1 / 32) - 1)
    assert -curvature * h / 2 <= sampled - fall <= 2 * EPS * static / h_min
    if g is stribeck_g:
        assert StribeckLaw(C0, C, 1 / CV, viscous=BS).fall == pytest.approx(fall, rel=4 * EPS)


# -- what it refuses -------------------------------------------------------------------------------------------


def _two_masses() -> Network:
    return Network(
        [Mass("a", 1.0, 0.1), Mass("b", 1.0)],
        [
            Spring("k", ("ground", "a"), 1.0),
            Spring("ab", ("a", "b"), 1.0),
            Friction("f", ("belt", "b"), static=1.0, kinetic=0.5),
        ],
        drivers=[Driver("belt", 0.2)],
    )


@pytest.mark.parametrize(
    ("network", "message"),
    [
        (_two_masses, "method 'event-driven' needs a one-mass system; the network has 2 masses"),
        (
            lambda: Network(
                [Mass("m", 1.0)],
                [Spring("k", ("ground", "m"), 1.0), Friction("f", ("belt", "m"), static=1.0, kinetic=0.5)],
                drivers=[Driver("belt", Table(np.array([0.0, 1.0]), np.array([0.0, 1.0])))],
            ),
            "method 'event-driven' runs driven points at a constant velocity; driver 'belt' has a table",
        ),
        (
            lambda: belt_system(
                Friction("f", ("belt", "m"), static=1.0, kinetic=0.5),
                0.2,
                extra=[Friction("g", ("ground", "m"), static=1.0, kinetic=1.0)],
            ),
            "method 'event-driven' runs one mass with exactly one friction contact; it has 2 ('f', 'g')",
        ),
        (
            lambda: Network(
                [Mass("m", 1.0)],
                [Spring("k", ("ground", "m"), 1.0), Friction("f", ("belt", "m"), static=1.0, kinetic=0.5)],
                [Load("m", SwitchedSine(1.0, 1.0)), Load("m", SwitchedSine(1.0, 2.0))],
                [Driver("belt", 0.2)],
            ),
            "method 'event-driven' cannot run the load on 'm', a sum of 2 loads",
        ),
    ],
)
def test_what_it_cannot_run_is_refused_in_one_line_naming_the_method(network, message):
    with pytest.raises(ValueError, match="^" + message.replace("(", r"\(").replace(")", r"\)")) as err:
        lumped.solve(Problem(network(), 1.0), 1e-2, method="event-driven")
    assert "\n" not in str(err.value)


def test_its_options_are_checked_and_no_other_is_taken():
    net = leine_system()
    with pytest.raises(ValueError, match="^rtol must lie in"):
        lumped.solve(Problem(net, 1.0), 1e-2, method="event-driven", rtol=1.0)
    with pytest.raises(ValueError, match="^theta: method 'event-driven' takes no option 'theta'"):
        lumped.solve(Problem(net, 1.0), 1e-2, method="event-driven", theta=0.5)
