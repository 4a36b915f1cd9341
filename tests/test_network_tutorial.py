"""Claims of the tutorial notebooks 06 to 08 that they do not print, and their plot helpers.

Each test states the notebook sentence it guards.  The references are
independent of the network solver: closed forms, the exact event-driven
solver of the paper's system, and the element's own constitutive graph.
"""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import lumped as L  # noqa: E402
from lumped import (  # noqa: E402
    Bingham,
    Load,
    LockingBingham,
    Mass,
    MaxwellBingham,
    Network,
    Spring,
    SpringString,
    plotting,  # noqa: E402
    simulate_network,
)


@pytest.fixture
def close():
    yield
    plt.close("all")


# -- notebook 06 ---------------------------------------------------------------
def test_string_in_parallel_with_a_sticking_dashpot_runs_with_intervals() -> None:
    """06: 'the velocities are unique, the split is not': the network runs, and on the step
    where the string is taut while the dashpot sticks both forces are reported as intervals."""
    tr = simulate_network(
        Network(
            [Mass("m", 1.0, -0.5)],
            [SpringString("s", ("ground", "m"), 100.0, 0.2), Bingham("d", ("ground", "m"), 5.0, 1.0)],
        ),
        1.5,
        1e-3,
    )
    assert tr.undetermined == [0, 1]


def test_after_the_impact_the_string_is_never_taut_again() -> None:
    """06: 'the string goes slack at once, since kL > mu_s N_f pulls it back', and the
    exact solver's motion from L at rest (the notebook's reference) never returns to L."""
    net = Network(
        [Mass("m", 1.0, -0.5)],
        [SpringString("s", ("ground", "m"), 100.0, 0.2), MaxwellBingham("d", ("ground", "m"), 1e5, 5.0, 1.0)],
    )
    tr = simulate_network(net, 0.8, 2e-4)
    taut = np.flatnonzero(tr.rigid[:, 0])
    assert taut.tolist() == [taut[0], taut[0] + 1]  # one impact: the reaching step and the stopping step
    assert np.all(tr.positions[taut[-1] + 1 :, 0] < 0.2)
    exact = L.solve_exact(L.Oscillator.bingham(1.0, 100.0, 5.0, 1.0), 1.5, x0=0.2)
    assert exact.evaluate(np.linspace(1e-3, 1.5, 3000))["x"].max() < 0.2


# -- notebook 07 ---------------------------------------------------------------
def test_the_lock_is_reached_once_and_held_without_interruption() -> None:
    """07: 'its later swings are slower than the lock and never reach it again': every
    step at |v| = v_lock lies in one run, and afterwards |v| stays below the lock by the
    Coulomb oscillator's bound v_lock - 2 omega mu_s N_f / k (one more half-swing's loss)."""
    k, tau, v_lock = 100.0, 1.0, 2.0
    net = Network(
        [Mass("m", 1.0, 0.5)],
        [Spring("k", ("ground", "m"), k), LockingBingham("lock", ("ground", "m"), tau, math.inf, v_lock)],
    )
    tr = simulate_network(net, 1.0, 2e-4)
    at_lock = np.flatnonzero(np.abs(tr.velocities[:, 0]) == v_lock)
    assert at_lock.size > 0 and np.all(np.diff(at_lock) == 1)
    assert np.all(tr.rigid[at_lock, 1])
    v_after = tr.velocities[at_lock[-1] + 1 :, 0]
    turn = np.argmax(v_after > 0)  # the first reversal after the lock
    assert turn > 0
    after = np.abs(v_after[turn:])
    # the amplitude about x_c after the lock is v_lock/omega; the next half-swing starts at
    # v_lock/omega - 2 tau/k from the new centre, so its speed is at most v_lock - 2 omega tau/k
    assert after.max() <= v_lock - 2 * math.sqrt(k) * tau / k + 1e-3  # + backward Euler's O(dt) excess


@pytest.mark.parametrize("f0", [0.5, 5.0])
def test_maxwell_relaxation_never_goes_below_the_threshold(f0: float) -> None:
    """07: the force relaxes 'down to the threshold, not to zero', monotonically."""
    net = Network(
        [Mass("m", 1.0, 0.05)],
        [Bingham("glue", ("ground", "m"), 1e6, math.inf), MaxwellBingham("mx", ("ground", "m"), 100.0, 1.0, 1.0, f0)],
    )
    f = simulate_network(net, 1.0, 1e-3).forces[:, 1]
    assert np.all(f >= min(f0, 1.0)) and np.all(np.diff(f) <= 0)


# -- notebook 08 ---------------------------------------------------------------
def chain(n: int, push: float) -> Network:
    names = [f"m{i}" for i in range(n)]
    elements = [Spring(f"k{i}", (a, b), 100.0) for i, (a, b) in enumerate(zip(names, names[1:]))]
    elements += [Bingham(f"f{i}", ("ground", name), 1.0, math.inf) for i, name in enumerate(names)]
    load = Load(names[0], L.SwitchedSine(amplitude=push, omega=0.0, phase=math.pi / 2))
    return Network([Mass(name, 1.0) for name in names], elements, [load])


def first_moves(tr) -> np.ndarray:
    moving = tr.velocities != 0
    return np.where(moving.any(axis=0), tr.t[np.argmax(moving, axis=0)], np.nan)


def test_first_move_times_converge_as_the_step_is_halved() -> None:
    """08: 'checks that they converge as dt is halved'.  Against a run at dt = 2.5e-4 s,
    each mass's first-move time at dt = 2e-3 and 1e-3 s is off by at most 2 dt: backward
    Euler's first-order error plus the reading of the time on a grid of spacing dt (one
    step).  A front that did not converge (or a lost mass) would exceed a bound that
    halves with dt.  Mass 0 moves in the first step at every dt and is left out."""
    net, t_end = chain(5, 6.0), 0.8
    fine = first_moves(simulate_network(net, t_end, 2.5e-4))[1:]
    for dt in (2e-3, 1e-3):
        first = first_moves(simulate_network(net, t_end, dt))[1:]
        assert np.all(np.isfinite(first)) and np.all(np.isfinite(fine))  # every mass is reached
        assert np.max(np.abs(first - fine)) <= 2 * dt


def test_masses_ahead_of_the_front_are_exactly_still_and_the_linear_chain_is_not() -> None:
    """08: 'ahead of it the masses are exactly still'; without friction every mass has
    moved by t = 0.1 s (the discrete chain answers at once, if weakly)."""
    tr = simulate_network(chain(6, 6.0), 0.1, 1e-3)
    first = first_moves(tr)
    for i in range(6):
        before = tr.t < first[i] if np.isfinite(first[i]) else np.ones(tr.t.size, bool)
        assert np.all(tr.positions[before, i] == 0.0)
    assert np.isnan(first[-1])
    names = [f"m{i}" for i in range(6)]
    springs = [Spring(f"k{i}", (a, b), 100.0) for i, (a, b) in enumerate(zip(names, names[1:]))]
    load = Load("m0", L.SwitchedSine(amplitude=6.0, omega=0.0, phase=math.pi / 2))
    linear = simulate_network(Network([Mass(n, 1.0) for n in names], springs, [load]), 0.1, 1e-3)
    assert np.all(linear.positions[-1] > 0)


# -- the plot helpers --------------------------------------------------------------
def test_locking_graph_vertices_lie_on_the_elements_graph(close) -> None:
    """Every corner drawn is a (w, f) the element admits (its force_interval)."""
    law = LockingBingham("lock", ("ground", "m"), 1.0, 2.0, 2.0)  # finite gamma: a sloped middle
    fig = plotting.locking_graph(law, f_max=3.0)
    corners = [(w, f) for line in fig.axes[0].lines[:2] for w, f in zip(*line.get_data())]
    assert len(corners) == 7
    for w, f in corners:
        lo, hi = law.force_interval(0.0, w)
        assert lo - 1e-12 <= f <= hi + 1e-12, (w, f)


def test_stick_map_draws_exactly_the_moving_masses(close) -> None:
    tr = simulate_network(chain(4, 6.0), 0.3, 1e-3)
    fig = plotting.stick_map(tr)
    image = fig.axes[0].get_images()[0].get_array()
    np.testing.assert_array_equal(np.asarray(image), (tr.velocities != 0).T.astype(float))


def test_network_history_draws_the_run_and_the_reference(close) -> None:
    net = Network([Mass("m", 1.0, 0.5)], [Spring("k", ("ground", "m"), 100.0)])
    tr = simulate_network(net, 0.2, 1e-3)
    t = np.linspace(0, 0.2, 50)
    fig = plotting.network_history({"run": tr}, "x", "m", references={"cos": (t, 0.5 * np.cos(10 * t))})
    run, ref = fig.axes[0].lines[:2]
    np.testing.assert_array_equal(run.get_ydata(), tr.positions[:, 0])
    np.testing.assert_array_equal(ref.get_xdata(), t)
    with pytest.raises(ValueError, match="no column 'q'"):
        plotting.network_history({"run": tr}, "x", "q")
