"""Branches of steady sliding and of its limit cycles in a parameter (issue 34, :mod:`lumped.drivers.cycles.continuation`).

References: the closed-form stick-slip cycle of the static/kinetic belt (:func:`belt_cycle`) at every point of
the branch in belt speed; the Hopf speed of a falling law with viscous damping in closed form (Veraszto and
Stepan's ``V_H = ln((C0 - C) c_v/(b0 + b_s))/c_v``; Leine's law ``F_s/(1 + delta s)`` with a dashpot ``c``:
``V_H = (sqrt(F_s delta/c) - 1)/delta``); the stick-slip onset against an independent computation of the
sliding cycle whose largest speed is the belt's (SciPy's event-located DOP853 and Brent's method).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from lumped.drivers.cycles import continuation, shooting
from lumped.drivers.cycles.continuation import BranchPoint, continue_branches
from lumped.drivers.cycles.equilibria import HOPF_RTOL, hopf_points
from lumped.drivers.cycles.shooting import Cycle
from lumped.laws import LinearDashpot, SlipCurve, Spring
from lumped.laws.slip_elements import Contact
from lumped.laws.stribeck import Friction
from lumped.model.network import Driver, Mass, Network
from lumped.solvers.closed_form_belt import belt_cycle
from lumped.solvers.event_driven_network import model

# -- the static/kinetic belt ----------------------------------------------------------------------------------

S_K = {"mass": 1.0, "stiffness": 1.0, "static": 1.0, "kinetic": 0.5}


def static_kinetic_belt(V: float = 0.2) -> Network:
    friction = Friction("f", ("belt", "m"), static=S_K["static"], kinetic=S_K["kinetic"])
    return Network(
        [Mass("m", S_K["mass"])],
        [Spring("k", ("ground", "m"), S_K["stiffness"]), friction],
        drivers=[Driver("belt", V)],
    )


def cycles_of(rows: list[BranchPoint]) -> list[BranchPoint]:
    return [r for r in rows if r.branch == "cycle"]


class ClosedFormShooting:
    """A test double of the shooting (:mod:`lumped.drivers.cycles.shooting`) on the static/kinetic belt, from
    :func:`belt_cycle`: on the section ``x = kinetic/k`` a speed ``v >= V`` sticks (or slips forward and
    sticks) before it returns, so ``P(v) = V``, ``P' = 0`` and ``dP/dV = 1``; a speed ``v < V`` is a harmonic
    slip about the section that never reaches the belt's speed, ``P(v) = v``, ``P' = 1``: sliding is a centre."""

    @staticmethod
    def parts(net: Network) -> tuple[float, float, float]:
        mdl = model(net)
        return mdl.V, math.sqrt(mdl.K / mdl.m), mdl.contact.slip_limit / mdl.K

    def return_map(self, net: Network, v: float) -> tuple[float, float, float]:
        V, omega, _ = self.parts(net)
        if v >= V:
            return V, 0.0, belt_cycle(**S_K, velocity=V).period
        return v, 1.0, 2 * math.pi / omega

    def find_cycle(self, net: Network, v0: float, *, tol: float = 1e-12) -> Cycle:
        V, omega, centre = self.parts(net)
        if v0 >= V:
            c = belt_cycle(**S_K, velocity=V)
            return Cycle(
                c.period, V, np.array([c.x_max]), np.array([c.x_min]), c.stick_time, 1, 0.0, np.array([0.0]), 0.0, True
            )
        a = v0 / omega
        return Cycle(
            2 * math.pi / omega,
            v0,
            np.array([centre + a]),
            np.array([centre - a]),
            0.0,
            0,
            V - v0,
            np.array([1.0]),
            1.0,
            False,
        )


def test_the_static_kinetic_branch_in_belt_speed_is_the_closed_form_cycle_at_every_point(monkeypatch):
    """With the closed form for the shooting (a double), every point of the branch from 0.1 to 0.5 m/s is the
    stick-slip cycle at its own speed (not one of the harmonic cycles below it, which solve ``F = 0`` as well:
    the module's Notes), the first at 0.1 and the last at 0.5 exactly, at most 0.4/(points - 1) apart."""
    double = ClosedFormShooting()
    for name in ("return_map", "find_cycle"):
        monkeypatch.setattr(continuation, name, getattr(double, name))
    # sliding is a centre at every speed (no damping, a flat curve): no pair crosses the axis, no Hopf point
    monkeypatch.setattr(continuation, "hopf_points", lambda *args: [])
    rows = continue_branches(static_kinetic_belt(), "belt.velocity", 0.1, 0.5, points=21)
    cycles = cycles_of(rows)
    values = np.array([r.value for r in cycles])
    assert values[0] == 0.1 and values[-1] == 0.5
    assert np.all(np.diff(values) > 0) and np.all(np.diff(values) <= 0.02 * (1 + 1e-9))
    assert {r.kind for r in cycles} == {"regular"}
    for r in cycles:
        ref = belt_cycle(**S_K, velocity=r.value)
        assert (r.cycle.period, r.cycle.stick_time) == (ref.period, ref.stick_time)
        assert r.cycle.section == r.value


def test_the_static_kinetic_branch_meets_belt_cycle_at_every_point():
    """The same branch by the package's shooting (closed-form phases: the harmonic slip, the stick, the
    breakaway): period, extremes and stick time of every cycle row are belt_cycle's at its speed to 1e-10 (the
    phases' round-off, a few ulps of the O(1) state and the O(10) s period, far below)."""
    rows = continue_branches(static_kinetic_belt(), "belt.velocity", 0.1, 0.5, points=21)
    cycles = cycles_of(rows)
    assert [r.value for r in cycles][:: len(cycles) - 1] == [0.1, 0.5] and len(cycles) >= 21
    for r in cycles:
        ref = belt_cycle(**S_K, velocity=r.value)
        got = (r.cycle.period, r.cycle.x_max[0], r.cycle.x_min[0], r.cycle.stick_time)
        assert got == pytest.approx((ref.period, ref.x_max, ref.x_min, ref.stick_time), rel=0, abs=1e-10)
        assert r.kind == "regular" and r.cycle.stick_phases == 1 and r.cycle.section == r.value


def test_progress_goes_to_the_end_and_a_system_without_a_falling_law_is_refused_before_work():
    calls: list[tuple[int, int]] = []
    continue_branches(static_kinetic_belt(), "belt.velocity", 0.1, 0.5, points=5, progress=lambda *a: calls.append(a))
    assert calls[-1] == (1000, 1000) and all(0 <= done <= total == 1000 for done, total in calls)
    viscous = Network(
        [Mass("m", 1.0)],
        [Spring("k", ("ground", "m"), 1.0), LinearDashpot("d", ("belt", "m"), 0.5)],
        drivers=[Driver("belt", 0.2)],
    )
    with pytest.raises(ValueError, match=r"^cycles: no falling law") as err:
        continue_branches(viscous, "belt.velocity", 0.1, 0.5, progress=lambda *a: calls.append(("late",)))
    assert "\n" not in str(err.value) and calls[-1] == (1000, 1000)


# -- Hopf points and the stick-slip onset -----------------------------------------------------------------------

M, K, B0 = 0.538, 6957.0, 5.746
C, C0, CV, BS = 2.0, 6.0, 10.0, 0.2
#: Veraszto and Stepan's Hopf speed: b0 + b_s - (C0 - C) c_v exp(-c_v V) = 0.
V_HOPF = math.log((C0 - C) * CV / (B0 + BS)) / CV
FS, DELTA, DAMPING = 1.0, 3.0, 0.75
#: Leine's law with a dashpot c: c - F_s delta/(1 + delta V)^2 = 0, V_H = (sqrt(F_s delta/c) - 1)/delta = 1/3.
V_HOPF_LEINE = (math.sqrt(FS * DELTA / DAMPING) - 1) / DELTA


def stribeck_g(s: float) -> float:
    return C + (C0 - C) * math.exp(-CV * s) + BS * s


def stribeck_belt(V: float = 0.2) -> Network:
    friction = Friction("f", ("belt", "m"), static=C0, kinetic=C, stribeck_velocity=1 / CV, viscous=BS)
    elements = [Spring("k", ("ground", "m"), K), friction, LinearDashpot("b0", ("ground", "m"), B0)]
    return Network([Mass("m", M)], elements, drivers=[Driver("belt", V)])


def leine_belt(V: float = 0.2) -> Network:
    law = SlipCurve(FS, lambda s: FS / (1 + DELTA * s), fall=FS * DELTA)
    elements = [
        Spring("k", ("ground", "m"), 1.0),
        Contact("c", ("belt", "m"), law),
        LinearDashpot("c0", ("ground", "m"), DAMPING),
    ]
    return Network([Mass("m", 1.0)], elements, drivers=[Driver("belt", V)])


def bubble_belt(V: float = 0.07) -> Network:
    """A Gaussian Stribeck fall, ``g(s) = 1 + exp(-(s/0.1)^2)`` N, and a dashpot of 8.55 N s/m, just below the
    fall's steepest ``sqrt(2/e)/0.1 = 8.578``: steady sliding is unstable between two Hopf points (0.0667 and
    0.0748 m/s), both supercritical (benchmarks/bench_cycles.py derives it: the third derivative of ``g`` is
    positive below ``s = 0.1 sqrt(3/2)``), and a bubble of stable cycles without a stick joins them."""
    friction = Friction("f", ("belt", "m"), static=2.0, kinetic=1.0, stribeck_velocity=0.1, decay="gaussian")
    elements = [Spring("k", ("ground", "m"), 1.0), friction, LinearDashpot("d", ("ground", "m"), 8.55)]
    return Network([Mass("m", 1.0)], elements, drivers=[Driver("belt", V)])


@pytest.mark.slow
def test_a_branch_that_comes_back_to_a_hopf_point_ends_there_and_is_followed_once():
    """The branch from the first Hopf point crosses the bubble and comes back to zero amplitude at the second: it
    ends there with that point's ``hopf`` row, and the second point starts no walk back along it.  Every other
    cycle row lies strictly between the two, once, in order, stable (multiplier below 1: supercritical) and
    without a stick; no row near steady sliding outside them (Newton's fixed point ``v = 0``)."""
    low, high = hopf_points(bubble_belt(), "belt.velocity", 0.05, 0.09)
    cycles = cycles_of(continue_branches(bubble_belt(), "belt.velocity", 0.999 * low, 1.001 * high, points=11))
    # the Hopf points located again over the continuation's range: each within HOPF_RTOL's xtol + rtol |x|
    assert [r.kind for r in (cycles[0], cycles[-1])] == ["hopf", "hopf"]
    assert [cycles[0].value, cycles[-1].value] == pytest.approx([low, high], rel=4 * HOPF_RTOL)
    inner = cycles[1:-1]
    assert all(r.kind == "regular" for r in inner) and np.all(np.diff([r.value for r in inner]) > 0)
    assert all(low < r.value < high for r in inner)
    assert all(r.cycle.stable and r.cycle.stick_phases == 0 and r.cycle.max_multiplier < 1 for r in inner)


def test_f_p_off_a_stick_is_one_return_and_meets_richardsons_central_difference(monkeypatch):
    """``F_p`` (``dP/dV``) at a cycle of the bubble that slips throughout, at 0.07 m/s on the bubble's range
    (0.0667 to 0.0748 m/s): a one-sided difference from the cycle's own speed, one return (a central difference
    takes two), within the error :func:`continuation._forward_step` derives, ``sqrt(2 (2 rho + CYCLE_TOL)) S / L``
    (``S = V``, ``L`` the range: 5.5e-5 m/s per m/s), of Richardson's extrapolation of central differences at
    ``h = 1e-5`` and ``h/2`` (error ``O(h^4)`` and the returns' noise over ``h``: some 1e-9, far below)."""
    low, high = 0.0667, 0.0748
    fam = continuation._Family(bubble_belt(), "belt.velocity", low, high)
    net = bubble_belt(0.07)
    cycle = continuation.find_cycle(net, 0.03)
    v, slope = cycle.section, float(cycle.multipliers[0].real)
    assert cycle.stick_phases == 0 and 0 < slope < 1
    fly, returns = shooting._fly, []
    monkeypatch.setattr(shooting, "_fly", lambda *a, **k: returns.append(1) or fly(*a, **k))
    d_p = fam.derivative(net, v, 0.07, v, slope)
    assert len(returns) == 1
    monkeypatch.setattr(shooting, "_fly", fly)
    at = lambda V: shooting.return_map(bubble_belt(V), v)[0]
    central = lambda h: (at(0.07 + h) - at(0.07 - h)) / (2 * h)
    reference = (4 * central(5e-6) - central(1e-5)) / 3
    bound = math.sqrt(2 * (2 * 100 * shooting.RTOL + continuation.CYCLE_TOL)) * 0.07 / (high - low)
    assert abs(d_p - reference) <= bound


@pytest.fixture(scope="module")
def hopf_rows() -> list[BranchPoint]:
    return continue_branches(stribeck_belt(), "belt.velocity", 0.185, 0.2, points=3)


@pytest.fixture(scope="module")
def onset_rows() -> list[BranchPoint]:
    """From the stick-slip cycle at 0.26 m/s up to where it meets the unstable sliding cycles, and back down."""
    return continue_branches(stribeck_belt(), "belt.velocity", 0.26, 0.28, points=3)


@pytest.mark.slow
def test_the_cycles_start_at_the_hopf_point_in_closed_form(hopf_rows):
    """The first cycle row is the Hopf point's (its value from :func:`hopf_points`, Brent to 1e-12 relative on
    the exact linearised damping), of zero amplitude and multiplier 1; the small cycle after it lies on the
    side where sliding is stable (a subcritical Hopf point: the falling law's cubic term destabilises), its
    value within ``O(amplitude^2)`` of it: ``HOPF_AMPLITUDE^2`` of the Hopf speed, times the normal form's
    coefficient of order ``(c_v V)^2 ~ 4``, so 1e-4 relative."""
    cycles = cycles_of(hopf_rows)
    hopf = cycles[0]
    assert hopf.kind == "hopf" and hopf.value == pytest.approx(V_HOPF, rel=1e-8)
    assert hopf.cycle.x_max[0] == hopf.cycle.x_min[0] == pytest.approx(stribeck_g(V_HOPF) / K, rel=1e-12)
    assert hopf.cycle.period == pytest.approx(2 * math.pi * math.sqrt(M / K), rel=1e-12)
    assert hopf.cycle.max_multiplier == pytest.approx(1.0, abs=1e-12) and not hopf.cycle.stable
    small = cycles[1]
    assert V_HOPF < small.value < V_HOPF * (1 + 1e-4)
    equilibria = [r for r in hopf_rows if r.branch == "equilibrium" and r.kind == "hopf"]
    assert [r.value for r in equilibria] == [hopf.value]


def test_leines_law_with_a_dashpot_starts_at_its_hopf_speed():
    rows = continue_branches(leine_belt(), "belt.velocity", 0.25, 0.4, points=4)
    hopf = [r for r in cycles_of(rows) if r.kind == "hopf"]
    assert len(hopf) == 1 and hopf[0].value == pytest.approx(V_HOPF_LEINE, rel=1e-8)


def sliding_return(V: float, v: float) -> tuple[float, float]:
    """``(P(v), largest speed)`` of the sliding motion (no stick) of the Stribeck belt from ``x = x*`` at speed
    ``v``, by SciPy's DOP853 with located events, independently of the package: ``M x'' = -K x - b0 x' +
    g(V - x')`` (the contact's rate ``x' - V < 0``) down through ``x*``, then up to it; the largest speed where
    the acceleration changes sign from + to -."""
    x_star = stribeck_g(V) / K

    def rhs(_, y):
        return [y[1], (-K * y[0] - B0 * y[1] + stribeck_g(V - y[1])) / M]

    def down(_, y):
        return y[0] - x_star

    def peak(t, y):
        return rhs(t, y)[1]

    down.terminal, down.direction, peak.direction = True, -1, -1
    tol = {"method": "DOP853", "rtol": 1e-12, "atol": 1e-15}
    first = solve_ivp(rhs, (0, 1), [x_star, v], events=[down, peak], **tol)
    up = lambda t, y: y[0] - x_star
    up.terminal, up.direction = True, 1
    second = solve_ivp(rhs, (first.t[-1], first.t[-1] + 1), first.y[:, -1], events=[up, peak], **tol)
    speeds = [y[1] for sol in (first, second) for y in sol.y_events[1]] + [v]
    return float(second.y_events[0][0][1]), max(speeds)


def grazing_speed() -> float:
    """The belt speed at which the sliding cycle's largest speed is the belt's: Brent's method on the section
    speed ``v`` of ``largest(v) - V(v)``, ``V(v)`` the belt speed at which ``v`` is a fixed point (Brent again: from
    ``V = v``, outside the unstable cycle, where the motion grows, to 0.35 m/s, inside it)."""

    def belt(v: float) -> float:
        return brentq(lambda V: sliding_return(V, v)[0] - v, v, 0.35, xtol=1e-14, rtol=1e-14)

    v = brentq(lambda v: sliding_return(belt(v), v)[1] - belt(v), 0.25, 0.27, xtol=1e-14, rtol=1e-14)
    return belt(v)


@pytest.mark.slow
def test_the_stick_slip_branch_folds_where_it_meets_the_unstable_sliding_cycles(onset_rows):
    """Leine and van Campen's discontinuous fold: the stable stick-slip branch (a stick phase: multiplier 0)
    and the unstable sliding cycles from the Hopf point (multiplier 1.56) meet where the sliding cycle grazes
    the belt's speed; the branch turns back there, its multiplier jumping across +1.  One ``fold`` row (the
    stick-slip piece's end) beside one ``stick-slip-onset`` row (the sliding piece's end), the branch from
    0.26 m/s going up to them and coming back to 0.26 m/s on the sliding cycles."""
    cycles = cycles_of(onset_rows)
    kinds = [r.kind for r in cycles]
    assert kinds.count("fold") == 1 and kinds.count("stick-slip-onset") == 1
    i = kinds.index("fold")
    fold, onset = cycles[i], cycles[i + 1]
    assert onset.kind == "stick-slip-onset"
    assert fold.cycle.stick_phases == 1 and fold.cycle.max_multiplier == 0 and fold.cycle.stable
    assert onset.cycle.stick_phases == 0 and onset.cycle.max_multiplier > 1 and not onset.cycle.stable
    assert all(r.cycle.stick_phases == 1 for r in cycles[:i]) and all(
        r.cycle.stick_phases == 0 for r in cycles[i + 1 :]
    )
    values = [r.value for r in cycles]
    assert values[0] == values[-1] == 0.26 and max(values) == onset.value


@pytest.mark.slow
def test_the_stick_slip_onset_is_where_the_sliding_cycle_reaches_the_belt_speed(onset_rows):
    """The Hopf point's unstable cycles grow until their largest speed is the belt's (0.2717890 m/s), where the
    contact first sticks: the ``stick-slip-onset`` row there, and the stick-slip piece's end (the ``fold`` row)
    too.  Each is located to LOCATE_TOL of the range on the arclength (2e-11 m/s) with each point's F within
    1e-10 v_s (3e-11 m/s over a slope of order 1); the reference's DOP853 at 1e-12 and Brent at 1e-14 err by
    1e-11.  So 1e-9 m/s."""
    cycles = cycles_of(onset_rows)
    onset = next(r for r in cycles if r.kind == "stick-slip-onset")
    fold = next(r for r in cycles if r.kind == "fold")
    assert onset.cycle.min_slip_speed < 1e-8
    reference = grazing_speed()
    assert onset.value == pytest.approx(reference, abs=1e-9)
    assert fold.value == pytest.approx(reference, abs=1e-9)


@pytest.fixture(scope="module")
def grazing() -> float:
    return grazing_speed()


@pytest.mark.slow
@pytest.mark.parametrize("points", [50, 101, 200])
def test_the_fold_is_at_the_grazing_whatever_the_step(points, grazing):
    """``--points`` sets the continuation's largest step, and so where its points fall along the branch; the
    ``fold`` row (the stick-slip piece's end, found by bisection along that piece from the last point before it)
    must not depend on it.  It moved by 2.4e-6 m/s with the range and the step while stops shorter than an
    integrator step were missed (the stick-slip piece seemed to end where the stick first became long enough to
    be seen); now it is the grazing, the reference of the onset test above, to that test's bound: LOCATE_TOL of
    the range on the arclength (2e-11 m/s), each point's F within 1e-10 v_s (3e-11 m/s), the reference's 1e-11;
    so 1e-9 m/s."""
    rows = continue_branches(stribeck_belt(), "belt.velocity", 0.26, 0.28, points=points)
    (fold,) = [r for r in cycles_of(rows) if r.kind == "fold"]
    assert fold.value == pytest.approx(grazing, abs=1e-9)
    assert fold.cycle.stick_phases == 1 and fold.cycle.max_multiplier == 0
