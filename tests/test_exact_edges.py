"""``exact`` at the edges its twins handle (issue 41, part B), against closed forms.

The stick rule of every method is the closed band of :func:`lumped.laws.sticks`: a contact (or a
Bingham element) whose holding force is exactly its static bound sticks, one a hair above it breaks
away at once.  ``exact`` on networks, the ``event-locating`` method (both choose their modes with
:func:`lumped.solvers.network_modes.select` and fire their events with
:func:`lumped.solvers.network_modes.crossed`), backward Euler and ``event-driven`` must agree there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import lumped as L
from lumped import Bingham, Friction, Load, Mass, Network, Spring
from lumped.model.forcing import Constant
from lumped.solvers.closed_form_belt import belt_cycle
from lumped.solvers.exact_network import solve_exact_network

G = "ground"
#: The issue's contact: static 1 N, kinetic 0.5 N, on m = 1 kg held by k = 1 N/m.
STATIC, KINETIC = 1.0, 0.5


def contact(load: float) -> Network:
    """The mass on its spring and its contact to the ground, under the constant ``load`` from t = 0."""
    elements = [Spring("s", (G, "m"), 1.0), Friction("f", (G, "m"), static=STATIC, kinetic=KINETIC)]
    return Network([Mass("m", 1.0)], elements, [Load("m", Constant(load))])


def test_a_contact_loaded_a_hair_above_static_breaks_away_at_once() -> None:
    """``P = static + 1e-12``: at t = 0 the holding force ``P - k x = P`` exceeds ``static``, so the mass
    slips at once with the kinetic force, ``m x'' + k x = P - kinetic`` from rest:
    ``x = (P - kinetic)/k (1 - cos t)`` until ``v`` returns to zero at ``t = pi``.  ``exact`` takes that
    phase as one matrix exponential (a few ulps of the 0.23 m motion); 1e-12 relative is 4e3 ulps, and
    a breakaway one bracketing sub-step late (the fault) is 3.6 % off."""
    load = STATIC + 1e-12
    tr = L.solve(L.Problem(contact(load), 1.0), 1e-3, method="exact")
    closed = (load - KINETIC) * (1 - np.cos(tr.t))
    np.testing.assert_allclose(tr.positions[:, 0], closed, rtol=1e-12, atol=1e-15)
    assert [e.kind for e in tr.events] == []  # it slips from t = 0 to past t_end: no event


@pytest.mark.parametrize("method", ["exact", "backward-euler", "event-driven"])
def test_a_contact_loaded_exactly_at_static_sticks_in_every_method(method: str) -> None:
    """``P = static``: ``|F| <= static`` sticks (the closed band), so the mass never moves: ``x = 0``
    exactly at every time (no rounding can enter a motion that never starts)."""
    tr = L.solve(L.Problem(contact(STATIC), 2.0), 1e-3, method=method)
    assert np.all(tr.positions == 0.0)
    assert np.all(tr.velocities == 0.0)


def bingham_at_threshold(gamma: float) -> Network:
    """Two masses on springs, the second held to the ground by a Bingham element (threshold 1 N) and
    loaded by exactly 1 N: at rest the element holds the whole load, exactly its threshold."""
    elements = [
        Spring("s", (G, "a"), 1.0),
        Spring("s2", ("a", "b"), 1.0),
        Bingham("d", (G, "b"), threshold=1.0, gamma=gamma),
    ]
    return Network([Mass("a", 1.0), Mass("b", 1.0)], elements, [Load("b", Constant(1.0))])


@pytest.mark.parametrize("gamma", [1.0, math.inf])
def test_a_bingham_element_loaded_exactly_at_its_threshold_sticks_without_events(gamma: float) -> None:
    """The element's reaction is the load, 1 N, exactly its threshold: it sticks for ever, with no event
    (the fault fired a breakaway at every bracketing sub-step and never reached ``t_end``; the bound of 50
    events makes that fault a quick failure).  Both masses stay at 0 exactly and rest from t = 0."""
    tr = solve_exact_network(bingham_at_threshold(gamma), 10.0, 1e-2, max_events=50)
    assert tr.events == ()
    assert np.all(tr.positions == 0.0)
    np.testing.assert_array_equal(tr.final_rest[0], [math.nan, 0.0])  # a, on its spring alone, is not held


@pytest.mark.parametrize("method", ["event-locating", "backward-euler"])
def test_a_bingham_element_at_its_threshold_sticks_in_every_network_method(method: str) -> None:
    """The same network by the other methods that run it (``exact`` above): nothing moves, exactly."""
    tr = L.solve(L.Problem(bingham_at_threshold(1.0), 1.0), 1e-2, method=method)
    assert np.all(tr.positions == 0.0)


def test_a_slow_belt_over_a_long_run_meets_the_closed_form_cycle() -> None:
    """A block on a spring (m = k = 1) riding a belt at V = 1e-6 m/s through the contact (static 1, kinetic
    0.5) for 3e6 s: it rides for 1e6 s between slips of pi s, so the stuck phases are a million seconds long.

    From rest on the moving belt it slips at once and the kinetic force brings it to the belt's speed at
    ``t_s = asin(V/K)`` (``m x'' = K - k x``, ``v = K sin t``), at ``x_s = K (1 - cos t_s)``; it breaks away
    at ``t_1 = t_s + (S - x_s)/V`` and then follows the closed-form cycle (:func:`belt_cycle`): sticks again
    at ``stick_position`` after ``slip_time``, breaks away a period later.  At ``t_end`` (after the second
    slip) it rides at ``stick_position + V (t_end - t_1 - period - slip_time)``: 0.99999372 m.  ``exact``'s
    event times are roots to a few ulps of 3e6 s (5e-10 s each, 5e-16 m at this speed); 1e-12 m is a wide
    margin.  The fault (stuck phases' exponentials scaled by their norm) ended at 1.4e-6 m."""
    v, t_end = 1e-6, 3e6
    elements = [Spring("spring", (G, "m"), 1.0), Friction("fric", ("belt", "m"), static=STATIC, kinetic=KINETIC)]
    net = Network([Mass("m", 1.0)], elements, [], [L.Driver("belt", v)])
    tr = L.solve(L.Problem(net, t_end), 1e4, method="exact")
    cycle = belt_cycle(1.0, 1.0, STATIC, KINETIC, v)
    t_s = math.asin(v / KINETIC)
    t_1 = t_s + (STATIC - KINETIC * (1 - math.cos(t_s))) / v
    expected = cycle.stick_position + v * (t_end - t_1 - cycle.period - cycle.slip_time)
    assert abs(tr.positions[-1, 0] - expected) <= 1e-12
    assert [e.kind for e in tr.events] == ["stop", "breakaway", "stop", "breakaway", "stop"]


def two_masses(*extra: L.Element, loads: tuple = ()) -> Network:
    """Mass ``a`` (released at 0.5 m) on a spring to the ground, ``b`` on a spring to ``a``, and ``extra``."""
    springs = [Spring("s", (G, "a"), 1.0), Spring("s2", ("a", "b"), 1.0)]
    return Network([Mass("a", 1.0, 0.5), Mass("b", 1.0)], [*springs, *extra], list(loads))


def test_a_grid_step_far_past_t_end_gives_the_decayed_motion_exactly() -> None:
    """With a dashpot every mode decays; at the grid's last time ``t_1 = dt = 1e300`` s each is below the
    smallest double, so the exact motion is the equilibrium, 0, to the last bit (no NaN)."""
    net = two_masses(Bingham("d", (G, "b"), threshold=0.0, gamma=1.0))
    tr = L.solve(L.Problem(net, 4.0), 1e300, method="exact")
    assert tr.t[-1] == 1e300
    np.testing.assert_array_equal(tr.positions[-1], [0.0, 0.0])


@pytest.mark.parametrize(
    ("extra", "loads", "match"),
    [
        ((), (), r"^dt: the exact motion at t = 1e\+300 s .* phase of 1\.6\d*e\+300 rad"),  # undamped: no digit left
        ((), (Load("a", Constant(1.0)),), r"^dt: the exact motion is not finite"),  # x = t^2/4 overflows
        (
            (Bingham("d0", (G, "a"), threshold=0.0, gamma=1.0), Bingham("d", (G, "b"), threshold=0.1, gamma=1.0)),
            (),
            r"^t_end: the phase from t = \S+ s has no event in 100 sub-steps",
        ),
    ],
    ids=["undamped", "overflowing", "events to bracket"],
)
def test_a_grid_step_beyond_double_precision_is_refused_in_one_line(extra, loads, match, monkeypatch) -> None:  # noqa: ANN001
    """``dt = 1e300`` past ``t_end = 4`` s: an undamped mode's phase (1.6e300 rad) has no digit left, a free
    pair under a constant load is beyond the largest double, and a damped phase with a sticking element
    would need 1e301 bracketing sub-steps: each a one-line ``ValueError`` (the fault wrote a row of NaN, or ran
    for ever), and no row is written.  The bound on sub-steps is lowered to 100 to keep the test fast
    (it is reached the same way at any bound)."""
    monkeypatch.setattr("lumped.solvers.exact_network.MAX_SUBSTEPS", 100)
    net = two_masses(*extra, loads=loads)
    if loads:  # the free pair: no spring to the ground
        net = Network(net.masses, [Spring("s2", ("a", "b"), 1.0)], list(loads))
    with pytest.raises(ValueError, match=match) as err:
        L.solve(L.Problem(net, 4.0), 1e300, method="exact")
    assert "\n" not in str(err.value)


def test_the_command_line_refuses_a_step_beyond_double_precision(tmp_path) -> None:  # noqa: ANN001
    """The same refusal from ``simulate``: exit status 2, one line, no file."""
    from cli_run import run_lumped

    system = tmp_path / "two.toml"
    system.write_text(
        '[[mass]]\nname = "a"\nmass = 1.0\nx0 = 0.5\n[[mass]]\nname = "b"\nmass = 1.0\n'
        '[[element]]\nname = "s"\nkind = "spring"\nbetween = ["ground", "a"]\nstiffness = 1.0\n'
        '[[element]]\nname = "s2"\nkind = "spring"\nbetween = ["a", "b"]\nstiffness = 1.0\n'
    )
    out = tmp_path / "out.csv"
    done = run_lumped(
        "simulate", "--system", system, "--t-end", "4", "--dt", "1e300", "--method", "exact", "--output", out
    )
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1 and "dt:" in done.stderr
    assert not out.exists()
