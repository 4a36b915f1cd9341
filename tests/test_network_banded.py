"""The compiled sparse step (``_network_sparse.h``, :mod:`lumped.solvers.network_sparse`) against
independent references: the one-block system, the Python step on random networks with loops
through the ground, a chain on a moving belt.

Tolerances.  With its modes fixed, a step solves the merged system (the inertias ``m/dt`` plus a
weighted Laplacian, symmetric positive definite) by an envelope LDL^T in the sparse step and by a
band or dense solver in the Python step; both are backward stable, so each velocity of a step
differs by a few roundings of the step's velocity scale times the condition number, which here is
``1 + O(k dt^2 / m)``, i.e. 1 to a part in 1e3.  We allow 8 roundings per element and step, as
tests/test_network_kernel.py does.  A step is a resolvent in the metric ``M/dt``: non-expansive,
so differences made in earlier steps are not amplified and add up over the steps; a position is
the sum of ``dt v`` over the steps.  Mode decisions agree unless a mode test falls within a
rounding of a kink (where both pieces give the same solution): on these runs it does not, so
active sets are compared exactly.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import lumped
from lumped import Bingham, Driver, Friction, LinearDashpot, Load, Mass, Network, Spring, simulate_network
from lumped.solvers import network_compiled as kernel
from lumped.solvers import network_sparse as sparse

pytestmark = pytest.mark.skipif(kernel.KERNEL != "compiled", reason="the network kernel was not built")

EPS = np.finfo(float).eps


def blocks(n: int, x0: float = 0.01, decay: str | None = None) -> Network:
    """``n`` identical blocks on a static/kinetic floor, each pulled by a leaf spring from a plate moving
    at 0.1 m/s, neighbours joined by coupling springs: every floor contact closes a loop through the ground.
    With ``decay``, the floor falls from static to kinetic with it (Stribeck velocity 0.05 m/s)."""
    masses = [Mass(f"m{i}", 1.0, x0) for i in range(n)]
    elements = []
    fall = {"stribeck_velocity": 0.05, "decay": decay} if decay else {}
    for i in range(n):
        elements.append(Friction(f"c{i}", (f"m{i}", "ground"), static=1.0, kinetic=0.6, **fall))
        elements.append(Spring(f"leaf{i}", ("plate", f"m{i}"), 10.0))
        if i:
            elements.append(Spring(f"k{i}", (f"m{i - 1}", f"m{i}"), 50.0))
    return Network(masses, elements, (), [Driver("plate", 0.1)])


@pytest.mark.parametrize("n", [10, pytest.param(1000, marks=pytest.mark.slow)])
def test_identical_blocks_move_as_one_block(n: int) -> None:
    """Started in one state, the blocks stay in one state: the coupling springs carry no force and every
    block's trajectory is the one-block system's (run by the Python step), to the rounding of the solves.

    Bound: a block's velocity in a step is off by at most 8 eps max|v| per element it has (3) (module
    docstring), these add over the steps and a position sums ``dt v``: ``|dx| <= 3 * 8 eps max|v| t``;
    the chain's solve mixes the ``n`` blocks' errors, which in the step's M-norm grow at most as
    ``sqrt(n)``.  A coupling spring's force is ``k`` times the difference of two such positions."""
    t_end, dt = 3.0, 1e-3
    one = simulate_network(blocks(1), t_end, dt, solver="python")
    chain = simulate_network(blocks(n), t_end, dt, solver="compiled")
    assert chain.solver == sparse.PATH
    vmax = np.abs(one.velocities).max()
    bound = 3 * 8 * EPS * vmax * t_end * math.sqrt(n)
    assert np.abs(chain.positions - one.positions).max() <= bound
    contacts = [e for e, name in enumerate(chain.network.element_names) if name.startswith("c")]
    couplings = [e for e, name in enumerate(chain.network.element_names) if name.startswith("k")]
    assert np.abs(chain.forces[:, couplings]).max() <= 50.0 * 2 * bound
    assert (one.velocities[:, 0] != 0).sum() > 500  # it slips, and sticks (below): stick-slip
    assert np.array_equal(chain.rigid[:, contacts], np.repeat(one.rigid[:, :1], n, axis=1))
    assert one.rigid[:, 0].sum() > 500


# -- random networks with loops through the ground ---------------------------------------------------


def _random_network(seed: int, decay: str | None = None) -> Network:
    """Masses each on a floor contact (static/kinetic friction or Bingham), springs between random pairs,
    sometimes a dashpot, a Bingham or a friction contact between masses, a plate moving at a constant or
    swaying velocity with leaf springs or contacts to it, and a sine load.  With ``decay``, the floor's
    friction contacts fall from static to kinetic with that decay, Stribeck velocities 0.02 to 0.2 m/s
    (the steepest fall, at most 2 N / 0.02 m/s = 100 N s/m, is below every m/dt >= 500 N s/m: each step is
    unique, ``lumped.solvers.uniqueness``)."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 7))
    masses = [
        Mass(f"m{i}", float(rng.uniform(0.5, 2.0)), float(rng.uniform(-0.05, 0.05)), float(rng.uniform(-0.5, 0.5)))
        for i in range(n)
    ]
    elements = []
    plate = rng.random() < 0.6
    for i in range(n):
        static = float(rng.uniform(0.2, 2.0))
        if rng.random() < 0.7:
            elements.append(
                Friction(
                    f"c{i}",
                    (f"m{i}", "ground"),
                    static=static,
                    kinetic=static * float(rng.uniform(0.3, 1.0)),
                    viscous=float(rng.choice([0.0, 0.3])),
                    stribeck_velocity=float(rng.uniform(0.02, 0.2)) if decay else None,
                    decay=decay or "exponential",
                )
            )
        else:
            elements.append(Bingham(f"c{i}", ("ground", f"m{i}"), static, float(rng.uniform(0.5, 5.0))))
    pairs = set()
    for k in range(int(rng.integers(n - 1, 2 * n + 1))):
        i, j = (int(a) for a in rng.choice(n, 2, replace=False))
        if (min(i, j), max(i, j)) in pairs:
            continue
        pairs.add((min(i, j), max(i, j)))
        roll = rng.random()
        if roll < 0.6:
            elements.append(Spring(f"k{k}", (f"m{i}", f"m{j}"), float(rng.uniform(5.0, 100.0))))
        elif roll < 0.75:
            elements.append(LinearDashpot(f"d{k}", (f"m{i}", f"m{j}"), float(rng.uniform(0.1, 2.0))))
        elif roll < 0.9:
            elements.append(
                Bingham(f"b{k}", (f"m{i}", f"m{j}"), float(rng.uniform(0.1, 1.0)), float(rng.uniform(0.5, 5.0)))
            )
        else:
            elements.append(Friction(f"f{k}", (f"m{i}", f"m{j}"), static=0.8, kinetic=0.5))
    drivers = []
    if plate:
        velocity = 0.2 if rng.random() < 0.5 else lumped.SwitchedSine(0.3, float(rng.uniform(2.0, 8.0)))
        drivers.append(Driver("plate", velocity))
        for i in rng.choice(n, int(rng.integers(1, n + 1)), replace=False):
            elements.append(Spring(f"leaf{i}", ("plate", f"m{i}"), float(rng.uniform(10.0, 80.0))))
    loads = [
        Load(
            f"m{int(rng.integers(n))}", lumped.SwitchedSine(float(rng.uniform(0.5, 3.0)), float(rng.uniform(3.0, 15.0)))
        )
    ]
    return Network(masses, elements, loads, drivers)


CASES = 200


@pytest.mark.slow
def test_random_networks_agree_with_the_python_step() -> None:
    """Positions to 1e-12 relative (of the run's largest |x|; the bound of the module docstring is
    some 1e-14 for these sizes and lengths), the same active sets (rigid flags) and the same contact
    directions every step, and the same admissible force intervals where forces are not unique."""
    compiled_steps = sum(_agrees(_random_network(seed), seed) for seed in range(CASES))
    assert compiled_steps > CASES // 2  # most runs never leave C


def _agrees(net: Network, seed: int) -> bool:
    """Assert the compiled and the Python step agree on ``net`` (as the test above says), or fail at the
    same step with the same one-line message; True if the run never left the sparse step."""
    assert sparse.ineligible(net) is None, seed
    try:
        b = simulate_network(net, 0.06, 1e-3, solver="python")
    except ValueError as err:  # the Python step's iteration did not settle: the compiled one fails there too
        with pytest.raises(ValueError, match=f"^{re.escape(str(err))}$"):
            simulate_network(net, 0.06, 1e-3, solver="compiled")
        return False
    a = simulate_network(net, 0.06, 1e-3, solver="compiled")
    assert a.solver.startswith("compiled"), seed  # a forest takes the forest's step
    scale = max(np.abs(b.positions).max(), 1e-300)
    assert np.abs(a.positions - b.positions).max() <= 1e-12 * scale, seed
    assert np.array_equal(a.rigid, b.rigid), seed
    contacts = [e for e, el in enumerate(net.elements) if el.kind == "friction"]
    assert np.array_equal(a.states[:, contacts], b.states[:, contacts]), seed
    assert (a.force_min is None) == (b.force_min is None), seed
    if a.force_min is not None:
        np.testing.assert_allclose(a.force_min, b.force_min, rtol=1e-9, atol=1e-12, err_msg=str(seed))
        np.testing.assert_allclose(a.force_max, b.force_max, rtol=1e-9, atol=1e-12, err_msg=str(seed))
    return a.solver == sparse.PATH


FALL_CASES = 30
DECAYS = ("exponential", "gaussian", "rational")


@pytest.mark.slow
@pytest.mark.parametrize("decay", DECAYS)
def test_random_networks_with_stribeck_falls_agree_with_the_python_step(decay: str) -> None:
    """As above, the floor contacts falling with each decay: on a slip branch both steps linearise the
    curve in each iteration the same way (the line of slope sigma through the last point) and differ
    by their root solves (Newton in C, Brent in Python, each to a few ulps of the slip speed:
    tests/test_friction_kernel.py's ``step_tolerance``, ``64 eps Y E / (E - fall)`` per contact and step,
    ``E >= m/dt``), which a falling curve carries from step to step amplified by at most ``E / (E -
    fall) <= 500 / 400`` per step while it slips; over these 60 steps of 1e-3 s that stays below
    1e-13 of the positions, so positions are held to 1e-12 relative as above, and the active sets and
    contact directions exactly.  A few of these networks (a falling contact between two masses or to the
    plate, each beside a falling floor) make the Python step's iteration circle without settling (its
    linearised branches hold no cycle test): the compiled step then stops at the same step with the same
    message."""
    runs = [_agrees(_random_network(seed, decay), seed) for seed in range(FALL_CASES)]
    assert sum(runs) > FALL_CASES * 3 // 4


def test_a_rigid_loop_is_left_to_the_python_step_and_said() -> None:
    """Two stuck blocks joined by a stuck contact close a loop of rigid elements through the ground:
    their forces are not unique; that step runs in Python (its intervals), and the solver says so."""
    net = Network(
        [Mass("a", 1.0), Mass("b", 1.0)],
        [
            Friction("ca", ("a", "ground"), static=2.0, kinetic=1.0),
            Friction("cb", ("b", "ground"), static=2.0, kinetic=1.0),
            Bingham("ab", ("a", "b"), 1.0, 1.0),
        ],
        [Load("a", lumped.SwitchedSine(0.5, 3.0))],
    )
    a = simulate_network(net, 0.05, 1e-3, solver="compiled")
    b = simulate_network(net, 0.05, 1e-3, solver="python")
    assert a.solver == f"{sparse.PATH}+python (50 of 50 steps)"
    assert np.array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.force_min, b.force_min)


def test_stribeck_contacts_keep_their_points_across_steps_left_to_the_python_step() -> None:
    """Two blocks on falling floors joined by a Bingham element: while all three stick they close a rigid
    loop, whose steps run in Python; the falling contacts' modes (a point on the branch and the points
    before it) pass from C to Python and back (``network_sparse.python_modes``, ``store_modes``), so the
    run is the Python step's: positions to 1e-12 relative (as above), the same active sets."""
    net = Network(
        [Mass("a", 1.0), Mass("b", 1.0)],
        [
            Friction("ca", ("a", "ground"), static=2.0, kinetic=1.0, stribeck_velocity=0.05),
            Friction("cb", ("b", "ground"), static=2.0, kinetic=1.0, stribeck_velocity=0.05, decay="rational"),
            Bingham("ab", ("a", "b"), 1.0, 1.0),
        ],
        [Load("a", lumped.SwitchedSine(4.0, 3.0))],
    )
    a = simulate_network(net, 2.0, 1e-3, solver="compiled")
    b = simulate_network(net, 2.0, 1e-3, solver="python")
    assert a.solver.startswith(f"{sparse.PATH}+python (")
    assert np.abs(a.positions - b.positions).max() <= 1e-12 * np.abs(b.positions).max()
    assert np.array_equal(a.rigid, b.rigid) and np.array_equal(a.states[:, :2], b.states[:, :2])
    slipping = ~a.rigid[1:, 0]
    assert slipping.sum() > 100 and (slipping[1:] & ~slipping[:-1]).sum() >= 2  # slips, sticks, slips again


# -- a chain on a belt -------------------------------------------------------------------------------


def belt_chain(n: int, velocity: float | lumped.SwitchedSine, decay: str | None = None) -> Network:
    """``n`` blocks on a belt (their contacts to the driven point), held by springs to the ground and to
    their neighbours: the chain stick-slips on the belt.  With ``decay``, the contacts fall from static
    to kinetic with it (Stribeck velocity 0.1 m/s)."""
    masses = [Mass(f"m{i}", 1.0 + 0.1 * i, 0.0, 0.3) for i in range(n)]
    elements = []
    fall = {"stribeck_velocity": 0.1, "decay": decay} if decay else {}
    for i in range(n):
        elements.append(Friction(f"c{i}", (f"m{i}", "belt"), static=1.0 + 0.05 * i, kinetic=0.5, viscous=0.1, **fall))
        elements.append(Spring(f"h{i}", ("ground", f"m{i}"), 20.0))
        if i:
            elements.append(Spring(f"k{i}", (f"m{i - 1}", f"m{i}"), 30.0))
    return Network(masses, elements, (), [Driver("belt", velocity)])


@pytest.mark.parametrize("velocity", [0.3, lumped.SwitchedSine(0.3, 2.0)], ids=["constant", "swaying"])
def test_a_chain_on_a_belt_agrees_with_the_python_step(velocity) -> None:
    """Positions to 1e-12 relative, the same active sets and contact directions every step."""
    net = belt_chain(6, velocity)
    a = simulate_network(net, 1.0, 1e-3, solver="compiled")
    b = simulate_network(net, 1.0, 1e-3, solver="python")
    assert a.solver == sparse.PATH
    assert np.abs(a.positions - b.positions).max() <= 1e-12 * np.abs(b.positions).max()
    assert np.array_equal(a.rigid, b.rigid)
    contacts = [e for e, el in enumerate(net.elements) if el.kind == "friction"]
    assert np.array_equal(a.states[:, contacts], b.states[:, contacts])
    assert a.rigid[:, 0].any() and not a.rigid[:, 0].all()  # stick and slip


@pytest.mark.parametrize(
    "decay, velocity",
    [("exponential", 0.3), ("gaussian", lumped.SwitchedSine(0.3, 2.0)), ("rational", 0.3)],
    ids=["exponential", "gaussian-swaying", "rational"],
)
def test_a_chain_on_a_belt_with_stribeck_falls_agrees_with_the_python_step(decay, velocity) -> None:
    """Positions to 1e-12 relative (the bound of the random networks' test with falls), the same active
    sets and contact directions every step; it sticks and slips."""
    net = belt_chain(4, velocity, decay)
    a = simulate_network(net, 0.5, 1e-3, solver="compiled")
    b = simulate_network(net, 0.5, 1e-3, solver="python")
    assert a.solver == sparse.PATH
    assert np.abs(a.positions - b.positions).max() <= 1e-12 * np.abs(b.positions).max()
    assert np.array_equal(a.rigid, b.rigid)
    contacts = [e for e, el in enumerate(net.elements) if el.kind == "friction"]
    assert np.array_equal(a.states[:, contacts], b.states[:, contacts])
    assert a.rigid[:, contacts].any() and not a.rigid[:, contacts].all()


@pytest.mark.parametrize("decay", DECAYS)
def test_one_stribeck_block_runs_as_the_one_mass_friction_loop(decay: str) -> None:
    """The one-block chain through the sparse step against the one-mass compiled friction loop (which solves
    each step's slip equation directly, by Newton's method): the same active set every step, and positions
    within what their root solves allow.  Per step the slip speeds differ by at most the two root
    solves' and the sparse step's settling tolerance, ``delta = 64 eps Y / (E - fall)`` in velocity (``Y
    = max|f| + E max|v|``: tests/test_friction_kernel.py's ``step_tolerance``), carried while the block
    slips and amplified by at most ``a = E / (E - fall)`` per step, and reset where it sticks; a slip of
    ``L`` steps so moves the block by at most ``dt L^2 delta a^L`` more; positions add those."""
    from lumped.solvers.backward_euler_network import march

    t_end, dt = 3.0, 1e-3
    net = blocks(1, decay=decay)
    loop = simulate_network(net, t_end, dt, solver="compiled")
    step = march(net, dt, 3000, 1, 3001, sparse.PATH)
    assert (loop.solver, step.solver) == ("one-mass-friction", sparse.PATH)
    assert np.array_equal(loop.rigid, step.rigid) and np.array_equal(loop.states[:, 0], step.states[:, 0])
    law = net.elements[0].slip_law()
    e = 1.0 / dt + 10.0 * dt
    delta = 64 * EPS * (np.abs(loop.forces[:, 0]).max() + e * np.abs(loop.velocities).max()) / (e - law.fall)
    slipping = ~loop.rigid[1:, 0]
    edges = np.flatnonzero(np.diff(np.concatenate([[0], slipping.astype(int), [0]])))
    lengths = edges[1::2] - edges[::2]
    bound = sum(dt * n * n * delta * (e / (e - law.fall)) ** n for n in lengths.tolist())
    assert 100 < slipping.sum() < slipping.size - 100  # it slips and sticks
    assert np.abs(loop.positions - step.positions).max() <= bound


# -- the binding refuses bad arguments (tests/test_bindings.py's harness: each call in a child) -------


def _sparse_args(**change: object) -> list:
    """``sparse_block``'s arguments for the first 10 steps of a 3-block chain on a belt; ``change`` replaces
    items of the topology by index (``t<i>``), ``n_drivers`` or the marching ``points``."""
    from lumped.solvers.backward_euler_network import _means, _sigma

    net, dt, steps = belt_chain(3, 0.3), 1e-3, 10
    plan = sparse.plan(net)
    inertia = np.array([m.mass / dt for m in net.masses])
    n_mass, n_el, rows = len(net.masses), len(net.elements), steps + 1
    topology = [*plan[:7], inertia, _sigma(net, inertia, dt), np.empty(0, dtype=np.int64), *plan[7:]]
    for key, value in change.items():
        if key.startswith("t"):
            topology[int(key[1:])] = value
    marching = (
        np.zeros(n_mass),
        np.full(n_mass, 0.3),
        np.zeros(n_el),
        np.full(n_el, -1, dtype=np.int64),
        np.zeros(n_mass, dtype=np.int64),
        np.array([1, 0, 0, 0]),
        change.get("points", np.zeros(n_el * sparse.POINT_WIDTH)),
    )
    record = (
        np.zeros(rows),
        np.zeros((rows, n_mass)),
        np.zeros((rows, n_mass)),
        np.zeros((rows, n_el)),
        np.zeros((rows, n_el)),
        np.zeros((rows, n_el), dtype=np.uint8),
    )
    means = _means(net, np.arange(1, steps + 1) * dt, dt)
    return [tuple(topology), marching, record, np.empty(0), means, dt, 1, steps, steps, 1, change.get("n_drivers", 1)]


def test_the_valid_sparse_block_runs() -> None:
    from test_bindings import outcome

    from lumped.kernels import _network_kernel

    assert outcome(lambda: _network_kernel.sparse_block(*_sparse_args())) == ("ok", "")


@pytest.mark.parametrize(
    "change, name",
    [
        ({"t0": np.full(8, 10, dtype=np.int64)}, "topology[0] (kind)"),
        # Stribeck contacts (kind 7) whose v_s (par[2]) is 0
        (
            {"t0": np.array([7, 0, 7, 0, 0, 7, 0, 0]), "t1": np.tile([1.0, 0.5, 0.0, 0.0], (8, 1))},
            "topology[1] (par) stribeck_velocity",
        ),
        ({"points": np.zeros(8)}, "marching[6] (points)"),
        ({"t4": np.zeros(3, dtype=np.int64)}, "topology[4] (at_pos)"),
        ({"t6": np.zeros(16, dtype=np.int64)}, "topology[6] (inc_el)"),
        ({"t11": np.full(3, 1, dtype=np.int64)}, "topology[11] (driven_driver)"),
        ({"n_drivers": -1}, "n_drivers"),
        ({"n_drivers": 2}, "means"),
    ],
    ids=["kind", "stribeck-law", "points", "at_pos", "inc_el", "driver", "negative-drivers", "means"],
)
def test_sparse_block_refuses(change: dict, name: str) -> None:
    from test_bindings import assert_refused

    from lumped.kernels import _network_kernel

    assert_refused(lambda: _network_kernel.sparse_block(*_sparse_args(**change)), name)
