"""Limit cycles by shooting on the return map (issue 34, part Q): :mod:`lumped.drivers.cycles.shooting`.

References: the closed-form stick-slip cycle of static above kinetic on a belt (``belt_cycle``); Leine et al.'s
benchmark against the independent event-located SciPy integration of tests/test_friction_event_driven.py; the
linearised multiplier of steady sliding (a closed form); central differences of the map; simulations started on
the cycles.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq
from test_friction_event_driven import (
    C0,
    CV,
    FS,
    V_HOPF,
    C,
    K,
    M,
    belt_system,
    damping,
    leine_reference,
    leine_system,
    stribeck_system,
)

from lumped.drivers.cycles import cycle_derivative_in, find_cycle, return_map, section_of
from lumped.drivers.cycles.shooting import MULTIPLIER_MARGIN, RTOL
from lumped.laws import LinearDashpot
from lumped.laws.stribeck import Friction
from lumped.model.forcing import Constant
from lumped.model.network import Driver, Load, Mass, Network
from lumped.solvers.closed_form_belt import belt_cycle
from lumped.solvers.event_driven_network import solve_contact

EPS = float(np.finfo(float).eps)

#: Just above the Veraszto-Stepan Hopf speed: steady sliding is stable and the Hopf bifurcation subcritical, so an
#: unstable slip-only cycle surrounds the equilibrium (at v = 0.0554 m/s on the section) inside the stick-slip one.
V_ABOVE = 1.02 * V_HOPF


def started(network: Network, x0: float, v0: float) -> Network:
    """``network`` with its mass started at ``(x0, v0)``."""
    mass = dataclasses.replace(network.masses[0], x0=x0, v0=v0)
    return Network([mass], network.elements, drivers=network.drivers)


def crossings(network: Network, x_star: float, t_end: float, samples: int) -> tuple[np.ndarray, np.ndarray]:
    """Times and velocities of the upward crossings of ``x = x*`` by the event-driven simulation to ``t_end``,
    bracketed on ``samples`` points and refined by SciPy's Brent (independent of the shooting's search)."""
    sol = solve_contact(network, t_end, rtol=1e-13)
    grid = np.linspace(0.0, t_end, samples)
    x = sol.state(grid)[0] - x_star
    up = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    f = lambda t: float(sol.state(np.array([t]))[0][0]) - x_star
    times = np.array([brentq(f, grid[i], grid[i + 1], xtol=1e-15) for i in up])
    return times, np.array([float(sol.state(np.array([t]))[1][0]) for t in times])


# -- the static/kinetic belt: closed form ----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("m", "k", "static", "kinetic", "V"),
    [(1.0, 1.0, 1.0, 0.5, 0.2), (0.5, 4.0, 2.0, 0.3, 0.7), (2.0, 1.5, 1.0, 0.9, 0.05)],
)
def test_the_static_kinetic_cycle_is_the_closed_form(m, k, static, kinetic, V):
    """Every phase in closed form (a harmonic slip whose stop is an arccosine, a stick at the belt's speed with its
    breakaway at ``k x = static``), and the section ``x* = kinetic/k`` crossed while stuck: Newton lands on the
    fixed point ``P(v) = V`` in one step (``P' = 0``).  The period sums a few phase durations, each an arccosine or
    a quotient to a few ulps, the extremes come from Brent's method on the closed form (``4 eps`` in time, a
    quadratic error in place): all to ~1e-15 of their O(1) size, so 1e-10 leaves room and no integrator could."""
    net = belt_system(Friction("f", ("belt", "m"), static=static, kinetic=kinetic), V, k=k, m=m)
    ref = belt_cycle(m, k, static, kinetic, V)
    assert section_of(net) == pytest.approx(kinetic / k, rel=1e-15)
    cycle = find_cycle(net, 2 * V)
    assert cycle.period == pytest.approx(ref.period, abs=1e-10)
    assert cycle.x_max[0] == pytest.approx(ref.x_max, abs=1e-10)
    assert cycle.x_min[0] == pytest.approx(ref.x_min, abs=1e-10)
    assert cycle.stick_time == pytest.approx(ref.stick_time, abs=1e-10)
    assert cycle.section == V and cycle.stick_phases == 1 and cycle.min_slip_speed == 0.0
    assert cycle.max_multiplier == 0.0 and cycle.stable  # a stop collapses the map


@pytest.mark.parametrize("law", [{}, {"stribeck_velocity": 0.1, "viscous": 0.05}], ids=["closed-form", "dop853"])
@pytest.mark.parametrize("offset", [1, 1e-13 / EPS, -1, -1e-13 / EPS], ids=["ulp", "1e-13", "-ulp", "-1e-13"])
def test_a_cycle_started_off_the_belts_speed_by_newtons_error_sticks_once(law: dict, offset: float):
    """The stick-slip cycle crosses the section stuck, at the belt's speed ``V``.  Newton started within its own
    tolerance of ``V`` (1e-12 relative: one ulp, or 1e-13, above or below it) returns at once, and the flight from
    there slips from ``u = v - V`` back to 0 before the stick: a slip of round-off length that is no motion.  One
    stick phase per period, and the period's stick time that of the cycle started at ``V`` exactly (the static/
    kinetic belt's is ``belt_cycle``'s; the merged slip lasts ``|v - V| m / |force|``, 1e-13 s at most here, and
    each flight's own round-off is ~1e-15 of the 5 s stuck, so 1e-12).  Below ``V`` on the static/kinetic belt
    (a centre) the harmonic cycle never reaches the belt: no stick there, whatever the offset."""
    V = 0.2
    net = belt_system(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5, **law), V)
    exact = find_cycle(net, V)
    cycle = find_cycle(net, V * (1 + offset * EPS))
    if not law and offset < 0:
        assert (cycle.stick_phases, cycle.stick_time) == (0, 0.0)
        return
    assert exact.stick_phases == cycle.stick_phases == 1
    assert cycle.stick_time == pytest.approx(exact.stick_time, abs=1e-12)
    if not law:
        assert exact.stick_time == pytest.approx(belt_cycle(1.0, 1.0, 1.0, 0.5, V).stick_time, abs=1e-12)


@pytest.mark.parametrize("V", [2e-7, 1e-3, 1e3, 1e8])
def test_the_static_kinetic_cycle_on_a_very_slow_or_fast_belt_is_the_closed_form(V: float):
    """The edges of the belt's speed, from the belt's speed (the cycle crosses the section stuck, at ``V``).  At 2e-7
    m/s the stick lasts 5e6 s, 8e5 natural periods: the return counts only its slip against its bound.  At 1e8 m/s
    the slip's stop, ``acos(V / (R omega))`` with ``R omega = V (1 + 1.25e-17)``, is taken without the cancellation.
    Period and extremes to 1e-10 relative (the issue's bound; closed forms, a few ulps each).  The stick time is a
    difference of times on the return's clock (the breakaway, the stop, the crossing: a few ulps of the period
    each), so to ``8 eps`` of the period: at 1e8 m/s that is 1e-14 s of a stick of 1e-8 s."""
    net = belt_system(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5), V)
    ref = belt_cycle(1.0, 1.0, 1.0, 0.5, V)
    cycle = find_cycle(net, V)
    scale = max(abs(ref.x_max), abs(ref.x_min))
    assert cycle.period == pytest.approx(ref.period, rel=1e-10)
    assert cycle.x_max[0] == pytest.approx(ref.x_max, abs=1e-10 * scale)
    assert cycle.x_min[0] == pytest.approx(ref.x_min, abs=1e-10 * scale)
    assert cycle.stick_time == pytest.approx(ref.stick_time, abs=8 * EPS * ref.period)
    assert cycle.stick_phases == 1 and cycle.stable


def test_a_belt_too_slow_for_the_returns_clock_is_refused_in_one_line():
    """At 1e-10 m/s the return lasts 1e10 s, past ``sqrt(2e-12) / (omega eps)`` = 6.4e9 s, where the clock's round-off
    of the phases' angles (``omega eps t``) moves the positions by more than 1e-12 of their scale."""
    net = belt_system(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5), 1e-10)
    with pytest.raises(
        ValueError, match=r"^v: the return from the section at v = 1e-10 m/s lasts beyond 6.37e\+09 s"
    ) as err:
        find_cycle(net, 1e-10)
    assert "no cycle is vouched for" in str(err.value) and "\n" not in str(err.value)


def test_the_extremes_of_an_orbit_sampled_on_its_turning_point():
    """On a belt at 1e3 m/s an orbit about ``kinetic/k`` with speed 0.5 m/s never reaches the belt (a neutral orbit
    of the centre, ``P' = 1``): its extremes are ``kinetic/k +- 0.5``, though ``u + V`` rounds to exactly 0 on the
    samples at its turning points (``u`` = -1e3 there)."""
    net = belt_system(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5), 1e3)
    cycle = find_cycle(net, 0.5)
    assert cycle.max_multiplier == 1.0 and not cycle.stable and cycle.stick_phases == 0
    assert (cycle.x_max[0], cycle.x_min[0]) == pytest.approx((1.0, 0.0), abs=1e-12)


def test_inside_the_static_kinetic_cycle_every_orbit_is_neutral():
    """Below the belt's speed the slip about ``kinetic/k`` is a harmonic circle that never reaches the belt: the map
    is the identity there, ``P' = 1`` (a centre, not a cycle to label stable), the return time ``2 pi/omega``."""
    net = belt_system(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5), 0.2)
    v_next, derivative, time = return_map(net, 0.1)
    assert v_next == pytest.approx(0.1, rel=1e-14) and derivative == 1.0
    assert time == pytest.approx(2 * math.pi, rel=1e-14)
    assert not find_cycle(net, 0.1).stable


# -- Leine et al.'s benchmark -----------------------------------------------------------------------------------


def test_leines_cycle_agrees_with_the_independent_event_located_integration():
    """Period and extremes against the reference of tests/test_friction_event_driven.py (SciPy's DOP853 with
    events at 1e-13), to 1e-8: that test derives 1.8e-9 for either method's state and event times in a cycle at
    these tolerances (the slip's fundamental matrix grows an error 22 times, a stick turns a place error into a
    time error over ``V``), so both together stay below 1e-8.  The cycle sticks (multiplier 0)."""
    breaks, turns = leine_reference(40.0, 1e-13)
    cycle = find_cycle(leine_system(), 0.3)
    turning = [x for t, x in turns if breaks[1] < t < breaks[2]]
    assert len(turning) == 2
    assert cycle.period == pytest.approx(breaks[2] - breaks[1], abs=1e-8)
    assert cycle.x_max[0] == pytest.approx(max(turning), abs=1e-8)
    assert cycle.x_min[0] == pytest.approx(min(turning), abs=1e-8)
    assert cycle.x_max[0] > FS  # it breaks away at x = F_s/k = 1 and overshoots
    assert cycle.stick_phases == 1 and 0 < cycle.stick_time < cycle.period
    assert cycle.max_multiplier == 0.0 and cycle.stable


# -- the derivative of the map ----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "v", "kinds"),
    [
        ("stribeck", 0.03, []),
        ("stribeck", 0.05, []),
        ("stribeck", 0.09, []),
        ("stribeck", 1.0, ["reversal", "reversal"]),
        ("leine", 3.0, ["reversal", "reversal"]),
    ],
)
def test_the_maps_derivative_is_its_central_difference(name: str, v: float, kinds: list[str]):
    """Returns that never stick: slip-only ones just above the Veraszto-Stepan Hopf speed, and large swings that
    pass the belt's speed near their turning points, where the spring's force is beyond ``static``, so the contact
    reverses (twice: the saltation factors ``(H + s g0)/(H - s g0)`` enter).  ``P'`` from the Liouville formula
    against ``D(h) = (P(v+h) - P(v-h))/(2h)``, which errs by its truncation, ``h^2 |P'''|/6 = |D(2h) - D(h)|/3``
    (measured, with a factor 3 for the ``h^4`` rest), and by the map's non-smooth error, at most ``rho = 100
    RTOL`` of ``P`` (DOP853's local errors; a change of ``v`` changes its steps) over ``h``, twice;
    ``h = (3 rho)^(1/3) v`` balances the two.  The events of the return are checked on a simulation."""
    net = stribeck_system(V_ABOVE, 0.0) if name == "stribeck" else leine_system()
    p, derivative, time = return_map(net, v)
    assert [e.kind for e in solve_contact(started(net, section_of(net), v), time, rtol=1e-13).events] == kinds
    rho = 100 * RTOL
    h = (3 * rho) ** (1 / 3) * v
    D = lambda h: (return_map(net, v + h)[0] - return_map(net, v - h)[0]) / (2 * h)
    d1, d2 = D(h), D(2 * h)
    assert derivative == pytest.approx(d1, abs=abs(d2 - d1) + 2 * rho * p / h)


def test_a_small_return_has_the_linearised_multiplier():
    """Near steady sliding the motion is the linearisation's damped oscillation (damping ``c = b0 + g'(V)``,
    frequency ``omega_d``), whose return multiplies ``v`` by ``exp(-c pi / (m omega_d))`` over ``T = 2 pi/omega_d``.
    At ``v = 1e-5`` m/s the slope's mean over the swing differs from ``g'(V)`` by ``g'''(V) v^2/4`` (the cubic
    term; ``|g'''| = (C0 - C) c_v^3 exp(-c_v V)``), which moves ``log P'`` by that times ``T/m``: 1.5e-9;
    DOP853 at 1e-13 relative to ``x ~ x* = 4e-4`` m over ~60 steps errs by up to 2e-8 of the 9e-8 m swing."""
    net = stribeck_system(V_ABOVE, 0.0)
    c = damping(V_ABOVE)
    omega_d = math.sqrt(K / M - (c / (2 * M)) ** 2)
    linear = math.exp(-c * math.pi / (M * omega_d))
    v = 1e-5
    _, derivative, time = return_map(net, v)
    cubic = (C0 - C) * CV**3 * math.exp(-CV * V_ABOVE) * v**2 / 4 * time / M
    assert derivative == pytest.approx(linear, rel=cubic + 2e-8)
    assert time == pytest.approx(2 * math.pi / omega_d, rel=2e-8)
    assert linear < 1  # steady sliding is stable above the Hopf speed


# -- stability against simulations -----------------------------------------------------------------------------


@pytest.mark.parametrize("network", [leine_system(), stribeck_system(V_ABOVE, 0.0)], ids=["leine", "stribeck"])
def test_a_cycle_labelled_stable_is_kept(network: Network):
    """Started on the stick-slip cycle ``1e-9`` m/s off it, the simulation's next stop removes the perturbation
    (multiplier 0): every later crossing of the section is stuck, at exactly the belt's speed, a period apart
    (to the 1e-8 of Leine's test)."""
    cycle = find_cycle(network, 0.3)
    assert cycle.stable and cycle.stick_phases >= 1
    x_star, V = section_of(network), network.drivers[0].velocity
    for dv in (1e-9, -1e-9):
        times, speeds = crossings(started(network, x_star, cycle.section + dv), x_star, 10 * cycle.period, 4000)
        assert len(times) >= 9
        assert np.all(speeds == V)
        assert np.allclose(np.diff(times), cycle.period, rtol=0, atol=1e-8)


@pytest.mark.parametrize("dv", [1e-9, -1e-9])
def test_a_cycle_labelled_unstable_is_left(dv: float):
    """The small slip-only cycle about steady sliding above the Hopf speed (subcritical) has the multiplier
    ``mu = P' > 1``: a simulation started ``dv`` off it at the section leaves it, its ``k``-th crossing ``mu^k dv``
    off.  Checked over 100 periods (a growth by 10): the simulation's and the shooting's flows differ by DOP853's
    errors, some 1e-13 of the 0.05 m/s speed a step over ~100 steps a period, 5e-13 m/s a period, which grow as the
    deviation does: ``k`` of them beside ``dv`` is 5e-5 a period, 5e-3 at the last; 1e-2 taken."""
    network = stribeck_system(V_ABOVE, 0.0)
    cycle = find_cycle(network, 0.06)
    mu = cycle.max_multiplier
    assert not cycle.stable and cycle.stick_phases == 0 and cycle.min_slip_speed > 0
    assert mu > 1 + MULTIPLIER_MARGIN and cycle.multipliers[0].imag == 0
    periods = 100
    times, speeds = crossings(
        started(network, section_of(network), cycle.section + dv),
        section_of(network),
        (periods + 0.5) * cycle.period,
        200 * periods,
    )
    deviation = speeds[:periods] - cycle.section
    expected = dv * mu ** np.arange(1, periods + 1)
    assert np.allclose(deviation, expected, rtol=1e-2, atol=0)
    assert abs(deviation[-1]) > 9 * abs(dv)  # left, not kept


# -- the parameter derivative and the refusals ------------------------------------------------------------------


def test_the_derivative_in_a_parameter():
    """A stick-slip cycle crosses the section stuck, at ``v = V`` whatever ``v`` it left at: ``dP/dV = 1`` and
    ``dP/d(static) = 0`` (a difference of equal numbers: exact); a slip-only return's ``dP/dV`` against a
    central difference taken here with a tenth of the step (its truncation 100 times smaller, its noise 10 times
    larger: the two agree to the function's derived error, 5e-8, times 10)."""
    net = belt_system(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5), 0.2)
    assert cycle_derivative_in(net, 0.4, "belt.velocity") == pytest.approx(1.0, abs=1e-12)
    assert cycle_derivative_in(net, 0.4, "f.static") == 0.0
    net = stribeck_system(V_ABOVE, 0.0)
    dp = cycle_derivative_in(net, 0.05, "belt.velocity")
    h = (3 * 100 * RTOL) ** (1 / 3) * V_ABOVE / 10
    P = lambda V: return_map(stribeck_system(V, 0.0), 0.05)[0]
    assert dp == pytest.approx((P(V_ABOVE + h) - P(V_ABOVE - h)) / (2 * h), abs=5e-7)
    with pytest.raises(ValueError, match="unknown parameter 'belt.speed'"):
        cycle_derivative_in(net, 0.05, "belt.speed")


def two_masses() -> Network:
    f = Friction("f", ("belt", "a"), static=1.0, kinetic=0.5)
    return Network(
        [Mass("a", 1.0), Mass("b", 1.0)],
        [LinearDashpot("d", ("a", "b"), 1.0), f],
        drivers=[Driver("belt", 0.2)],
    )


@pytest.mark.parametrize(
    ("network", "v", "message"),
    [
        (two_masses(), 0.1, "the system has 2 masses"),
        (
            Network(
                [Mass("m", 1.0)],
                [*belt_system(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5), 0.2).elements],
                [Load("m", Constant(1.0))],
                drivers=[Driver("belt", 0.2)],
            ),
            0.1,
            "the system has a load on 'm'",
        ),
        (belt_system(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5), 0.0), 0.1, "'f' is on a point at rest"),
        (leine_system(), 0.0, "v must be"),
        (leine_system(), -1.0, "v must be"),
    ],
)
def test_refusals_are_one_line(network, v, message):
    with pytest.raises(ValueError, match=message) as err:
        return_map(network, v)
    assert "\n" not in str(err.value)
