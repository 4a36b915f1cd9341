"""The compiled network step (``_network_kernel.c``) against the Python step, and on its own.

The two paths solve the same one-step problem with the same active-set
iteration (warm start, mode test, scales, bound); they differ only in the
linear solve with the modes fixed: elimination along the forest of links in
C, a band or dense factorisation in Python.  Both are backward stable, so in
a step each velocity differs by a few roundings of the step's velocity scale
per level of elimination.  A step is the minimiser of a strictly convex
function (see ``Network``), a resolvent in the metric ``M/dt``: it is
non-expansive, so differences made in earlier steps are not amplified and
the bound after ``N`` steps is the sum of the per-step ones (the tests
below write it with 8 roundings per element and step, and the factor
``sqrt(max m / min m)`` that turns the ``M``-norm into the largest
component).  Mode decisions agree unless a mode test falls within a
rounding of a kink (where both pieces give the same solution); it does not
on these runs, so the rigid flags are compared exactly.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import EPS
from test_network import PAPER, F, _compare_active_set, chain, check_invariants

import lumped as L
from lumped import (
    Bingham,
    LinearDashpot,
    Load,
    LockingBingham,
    Mass,
    MaxwellBingham,
    Monotone,
    Network,
    Spring,
    SpringString,
    simulate_network,
)
from lumped.solvers import network_compiled as kernel

pytestmark = pytest.mark.skipif(kernel.KERNEL != "compiled", reason="the network kernel was not built")


def tree() -> Network:
    """Branches at ``a``, every kind, elements written in both directions, and a
    component (``e``, ``f``) that does not touch the ground."""
    masses = [Mass("a", 1.0, 0.05), Mass("b", 0.5, 0.0, 1.5), Mass("c", 2.0, -0.1), Mass("d", 0.3)]
    masses += [Mass("e", 1.0, 0.0, 0.5), Mass("f", 0.7)]
    elements = [
        Spring("k_a", ("ground", "a"), 100.0),
        Bingham("b_a", ("a", "ground"), 1.0, 2.0),
        SpringString("s_ab", ("a", "b"), 40.0, 0.08),
        MaxwellBingham("mx_ac", ("c", "a"), 60.0, 0.8, math.inf),
        LockingBingham("lock_cd", ("c", "d"), 0.3, math.inf, 0.4),
        Spring("k_cd", ("d", "c"), 30.0),
        LinearDashpot("d_d", ("d", "c"), 0.2),
        Spring("k_ef", ("e", "f"), 20.0),
        Bingham("c_ef", ("e", "f"), 0.2, math.inf),
    ]
    loads = [Load("a", F), Load("e", L.SwitchedSine(2.0, 3.0, 0.5, 2.0)), Load("a", lambda t: 0.5 * np.cos(7 * t))]
    return Network(masses, elements, loads)


def strings() -> Network:
    """test_network's two strings, the dashpot moved from ``b``-ground to ``b``-``a`` (a forest)."""
    return Network(
        [Mass("a", 1.0, 0.0, 2.0), Mass("b", 2.0)],
        [
            SpringString("s1", ("ground", "a"), 50.0, 0.1),
            SpringString("s2", ("a", "b"), 80.0, 0.05),
            LinearDashpot("d", ("b", "a"), 0.5),
        ],
    )


def maxwell_chain() -> Network:
    return Network(
        [Mass("a", 1.0, 0.2), Mass("b", 1.5, 0.3)],
        [
            Spring("k", ("ground", "a"), 100.0),
            MaxwellBingham("m1", ("ground", "a"), 50.0, 0.5, 2.0),
            MaxwellBingham("m2", ("a", "b"), 80.0, 0.3, math.inf),
        ],
        [Load("b", F)],
    )


def locking() -> Network:
    return Network(
        [Mass("m", 1.0, 0.5), Mass("n", 0.5)],
        [
            Spring("k", ("ground", "m"), 100.0),
            LockingBingham("lock", ("ground", "m"), 1.0, math.inf, 2.0),
            LockingBingham("lock2", ("m", "n"), 0.1, 4.0, 0.5),
        ],
    )


def ring(n: int, tau: float) -> Network:
    """Masses in a ring through the ground (one loop of links, its chord in C), each link a spring
    beside a Coulomb element; with ``tau = 4`` it comes to rest stuck all round (a rigid loop)."""
    points = ["ground", *(f"m{i}" for i in range(n)), "ground"]
    elements = []
    for i, (a, b) in enumerate(zip(points, points[1:])):
        elements += [Spring(f"k{i}", (a, b), 50.0 + 10 * i), Bingham(f"c{i}", (a, b), tau + 0.5 * i, math.inf)]
    masses = [Mass(f"m{i}", 1.0 + 0.25 * i, 0.05 * (i + 1)) for i in range(n)]
    return Network(masses, elements, [Load("m0", L.SwitchedSine(30.0, 7.0, 0.3, 1.2))])


CASES = {
    "chain-bingham": (chain(6, 1.0, F), 2.5),
    "ring-slipping": (ring(3, 2.0), 3.0),
    "ring-stuck": (ring(6, 4.0), 4.0),
    "chain-coulomb": (chain(4, math.inf, F), 2.5),
    "tree": (tree(), 3.0),
    "strings-impacts": (strings(), 2.0),
    "maxwell": (maxwell_chain(), 2.0),
    "locking": (locking(), 2.0),
}


def _bounds(tr) -> tuple[float, float, float]:
    """The bounds of the module docstring on velocities, positions and forces after the run."""
    masses = np.array([m.mass for m in tr.network.masses])
    n, elements = round(tr.t[-1] / tr.dt), len(tr.network.elements)
    step_scale = np.max(np.abs(tr.velocities)) + tr.dt * np.max(np.abs(tr.forces)) / masses.min()
    dv = n * 8 * elements * EPS * step_scale * math.sqrt(masses.max() / masses.min())
    # positions sum dt * v; a force moves with the largest stiffness seen by a step, m/dt
    return dv, tr.t[-1] * dv + n * EPS * np.max(np.abs(tr.positions)), (masses.max() / tr.dt) * 4 * dv


@pytest.mark.parametrize("case", list(CASES))
def test_compiled_step_agrees_with_the_python_step(case: str) -> None:
    net, t_end = CASES[case]
    py = simulate_network(net, t_end, 1e-3, solver="python")
    c = simulate_network(net, t_end, 1e-3, solver="compiled")
    assert (py.solver, c.solver) == ("python", "compiled")
    assert np.array_equal(py.rigid, c.rigid)
    dv, dx, df = _bounds(py)
    assert np.max(np.abs(py.velocities - c.velocities)) <= dv
    assert np.max(np.abs(py.positions - c.positions)) <= dx
    assert np.max(np.abs(py.forces - c.forces)) <= df
    assert np.array_equal(np.isnan(py.rest_times), np.isnan(c.rest_times))


@pytest.mark.parametrize("n", [3, 6])
def test_a_stuck_ring_reports_the_same_intervals_on_both_paths(n: int) -> None:
    """A ring at rest, stuck all round: both paths report the least-norm split and each
    element's interval (to the forces' bound above), on the same rows."""
    net = ring(n, 4.0)
    py = simulate_network(net, 4.0, 1e-3, solver="python")
    c = simulate_network(net, 4.0, 1e-3, solver="compiled")
    assert c.solver == "compiled" and py.undetermined == c.undetermined == list(range(1, 2 * n + 2, 2))
    assert np.array_equal(py.force_min != py.force_max, c.force_min != c.force_max)
    df = _bounds(py)[2]
    assert np.max(np.abs(py.force_min - c.force_min)) <= df and np.max(np.abs(py.force_max - c.force_max)) <= df


@pytest.mark.parametrize("case", list(CASES))
def test_compiled_step_keeps_the_invariants(case: str) -> None:
    """Sticking elements exactly still, taut strings exactly at length, the energy balance."""
    net, t_end = CASES[case]
    tr = simulate_network(net, t_end, 1e-3, solver="compiled")
    check_invariants(tr)
    first, second = net.incidence()
    vg = np.column_stack([tr.velocities, np.zeros(tr.t.size)])
    w = vg[:, second] - vg[:, first]
    for e, el in enumerate(net.elements):
        if isinstance(el, LockingBingham):
            # Held: sticking (v_second = v_first + 0, exactly) or locked, v_second = v_first + v_lock:
            # that sum and the difference taken here round once each, so |w| is v_lock to 2 eps.
            held, near = tr.rigid[:, e], 2 * EPS * el.v_lock
            assert np.all(np.abs(w[:, e]) <= el.v_lock + near)
            assert np.all((w[held, e] == 0) | (np.abs(np.abs(w[held, e]) - el.v_lock) <= near))
            assert np.any(held & (w[:, e] != 0))  # it does lock


def test_every_rigid_kind_is_exercised() -> None:
    """The cases above do stick, go taut and lock (else the exactness checks are empty)."""
    kinds = set()
    for net, t_end in CASES.values():
        tr = simulate_network(net, t_end, 1e-3, solver="compiled")
        kinds |= {type(el).__name__ for e, el in enumerate(net.elements) if tr.rigid[:, e].any()}
    assert kinds == {"Bingham", "SpringString", "LockingBingham"}


@pytest.mark.parametrize("name", ["forced_large", "free_large"])
def test_compiled_step_reproduces_algorithm1(name: str) -> None:
    """One mass: the elimination is Algorithm 1's line 8/9 in its order (see _compare_active_set)."""
    _compare_active_set(PAPER[name], 1e-3, "compiled")


@pytest.mark.slow
@pytest.mark.parametrize("name", list(PAPER))
def test_compiled_step_reproduces_algorithm1_paper_runs(name: str) -> None:
    _compare_active_set(PAPER[name], PAPER[name].dt, "compiled")


@pytest.mark.slow
def test_long_coulomb_chain_agrees_with_the_python_step() -> None:
    """50 masses (a band of width 1 in Python, 50 levels of elimination in C)."""
    net = chain(50, math.inf, F)
    py = simulate_network(net, 0.5, 1e-3, solver="python")
    c = simulate_network(net, 0.5, 1e-3, solver="compiled")
    assert np.array_equal(py.rigid, c.rigid) and py.rigid.any()
    dv, dx, df = _bounds(py)
    assert np.max(np.abs(py.velocities - c.velocities)) <= dv and np.max(np.abs(py.positions - c.positions)) <= dx
    assert np.max(np.abs(py.forces - c.forces)) <= df
    check_invariants(c)


def test_chain_sticks_exactly_as_one_body() -> None:
    """A Coulomb link that never slips: its two masses have the same velocity, bit for bit."""
    net = Network(
        [Mass("a", 0.4, 0.5), Mass("b", 0.6, 0.5)],
        [
            Spring("k", ("ground", "a"), 100.0),
            Bingham("d", ("ground", "a"), 1.0, 1.0),
            Bingham("glue", ("a", "b"), 1e6, math.inf),
        ],
    )
    tr = simulate_network(net, 4.0, 1e-3, solver="compiled")
    assert tr.rigid[1:, 2].all() and np.array_equal(tr.velocities[:, 0], tr.velocities[:, 1])


# -- which path runs -----------------------------------------------------------------
def test_auto_takes_the_compiled_path_for_a_chain_and_algorithm1_for_the_paper() -> None:
    assert simulate_network(chain(3, 1.0, F), 0.01, 1e-3).solver == "compiled"
    assert simulate_network(chain(1, 1.0, F), 0.01, 1e-3).solver == "algorithm1"
    assert simulate_network(chain(1, 1.0, F), 0.01, 1e-3, solver="active-set").solver == "compiled"


MONOTONE = Network(
    [Mass("m", 1.0, 0.5)],
    [Spring("k", ("ground", "m"), 100.0), Monotone("d", ("ground", "m"), L.MonotoneDashpot(lambda f: 0.5 * f))],
)
TWO_LOOPS = Network(
    [Mass("a", 1.0, 0.1), Mass("b", 1.0), Mass("c", 1.0)],
    [
        Spring("k1", ("ground", "a"), 10.0),
        Bingham("b1", ("a", "b"), 1.0, 1.0),
        Spring("k2", ("b", "ground"), 10.0),
        Spring("k3", ("a", "c"), 10.0),
        Spring("k4", ("c", "ground"), 5.0),
    ],
)
STRING_RING = Network(
    [Mass("a", 1.0, 0.1), Mass("b", 1.0)],
    [
        Spring("k1", ("ground", "a"), 10.0),
        SpringString("s", ("a", "b"), 10.0, 0.5),
        Bingham("b2", ("b", "ground"), 1.0, 1.0),
    ],
)
PARALLEL = Network(
    [Mass("a", 1.0, 0.1)],
    [
        Spring("k", ("ground", "a"), 10.0),
        Bingham("b0", ("ground", "a"), 0.0, 1.0),
        Bingham("b1", ("a", "ground"), 0.0, 2.0),
    ],
)


@pytest.mark.parametrize(
    "net, reason",
    [
        (MONOTONE, "'d' is not piecewise linear"),
        (PARALLEL, "'b0', 'b1' are in parallel and can be rigid"),
    ],
    ids=["monotone", "parallel-rigid-pieces"],
)
def test_ineligible_networks_take_the_python_step(net: Network, reason: str) -> None:
    """The active-set step (``auto`` hands MONOTONE, the paper's form, to the law's resolvent instead); the
    reason is the sparse step's (the most general compiled step: test_network_banded.py)."""
    assert simulate_network(net, 0.01, 1e-3, solver="active-set").solver == "python"
    with pytest.raises(ValueError, match=f"solver: 'compiled' cannot run this network: .*{reason}"):
        simulate_network(net, 0.01, 1e-3, solver="compiled")


def test_without_the_kernel_every_network_takes_the_python_step(monkeypatch) -> None:
    """No compiler at install (or LUMPED_PURE_PYTHON=1): the Python step, and 'compiled' refused."""
    monkeypatch.setattr(kernel, "KERNEL", "python")
    assert simulate_network(chain(3, 1.0, F), 0.01, 1e-3).solver == "python"
    with pytest.raises(ValueError, match="the compiled network kernel was not built"):
        simulate_network(chain(3, 1.0, F), 0.01, 1e-3, solver="compiled")


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning", "ignore:invalid value:RuntimeWarning")
def test_an_overflow_is_reported_alike_by_both_paths() -> None:
    net = Network(
        [Mass("m", 1e-300)], [LinearDashpot("d", ("ground", "m"), 1e-300)], [Load("m", lambda t: 1e300 + 0 * t)]
    )
    messages = []
    for solver in ("python", "compiled"):
        with pytest.raises(ValueError, match="overflowed") as err:
            simulate_network(net, 0.01, 1e-3, solver=solver)
        messages.append(str(err.value))
    assert messages[0] == messages[1]


def test_a_long_compiled_run_is_not_refused(monkeypatch) -> None:
    """The run-time estimate is the path's: 1e6 steps of a 100-mass chain (about
    16 s compiled, measured by benchmarks/bench_network.py; about an hour in
    Python) are accepted compiled and refused in Python."""
    from lumped.solvers import backward_euler_network

    monkeypatch.setattr(backward_euler_network, "march", lambda *args: args[-1])  # the path, without running
    assert simulate_network(chain(100, 1.0, F), 1000.0, 1e-3, save_every=100) == "compiled"
    with pytest.raises(ValueError, match=r"steps of the network step \(python\) would take about"):
        simulate_network(chain(100, 1.0, F), 1000.0, 1e-3, save_every=100, solver="python")
