"""The one-step problem with friction contacts: the slip rule at its edge, and steps that must settle (issue 41 A).

Each test fails without its fix: the slip rule's ``>`` at the static bound (a
contact loaded at exactly ``static`` sticks), in the Python step and in the C
twin (the sparse step); the Newton finish of a Stribeck contact's fixed-point
iteration (the three-block example and the Burridge-Knopoff chain at
``bk_dt = 0.1`` did not settle); a slipping contact's force on its law (a cycle of
points reached from a solve off the law was accepted as settled).
"""

from __future__ import annotations

import numpy as np
import pytest

from lumped.drivers.network import run_network
from lumped.model.files import parse_system
from lumped.studies import burridge_knopoff as bk

EPS = float(np.finfo(float).eps)

THREE_BLOCKS = """
[[mass]]
name = "a"
mass = 1.0
v0 = -0.4
[[mass]]
name = "b"
mass = 1.0
[[mass]]
name = "c"
mass = 1.0
v0 = -0.4
[[element]]
name = "ab"
kind = "friction"
between = ["a", "b"]
static = 0.6
kinetic = 0.0
stribeck_velocity = 0.25
[[element]]
name = "ac"
kind = "friction"
between = ["a", "c"]
static = 0.2
kinetic = 0.1
stribeck_velocity = 0.5
"""


def _edge(masses: int) -> str:
    """A contact to the ground under mass ``m0`` loaded by exactly its static force 1 N (no spring, at rest);
    with ``masses = 2`` a second mass hangs on ``m0`` by a stiff spring (so the sparse step runs it)."""
    text = """
[[mass]]
name = "m0"
mass = 1.0
[[element]]
name = "pad"
kind = "friction"
between = ["ground", "m0"]
static = 1.0
kinetic = 0.5
[[force]]
on = "m0"
kind = "constant"
value = 1.0
"""
    if masses == 2:
        text += """
[[mass]]
name = "m1"
mass = 1.0
[[element]]
name = "k"
kind = "spring"
between = ["m0", "m1"]
stiffness = 10.0
"""
    return text


@pytest.mark.parametrize(
    ("masses", "solver", "path"),
    [
        (1, "python", "python"),
        (1, "auto", "one-mass-friction"),
        (2, "python", "python"),
        (2, "auto", "compiled-banded"),
    ],
)
def test_a_contact_loaded_at_exactly_its_static_force_sticks(masses: int, solver: str, path: str) -> None:
    """|F| <= static sticks: the stuck contact's holding force is the load itself, 1 N = static, with no
    rounding (the mass is at rest, ``m/dt v_n = 0``, so ``f = F`` exactly), so the rule's ``>`` alone decides;
    a ``>=`` (the mutant of issue 41) slips it, and the mass then moves."""
    net = parse_system(_edge(masses), "edge")
    run = run_network(net, 0.01, 1e-3, solver=solver)
    assert run.solver == path
    assert np.all(run.velocities[:, 0] == 0.0)
    assert np.all(run.positions[:, 0] == 0.0)


@pytest.mark.parametrize(("solver", "path"), [("python", "python"), ("auto", "one-mass-friction")])
def test_a_slipping_stribeck_contact_that_arrives_at_exactly_its_static_force_sticks(solver: str, path: str) -> None:
    """A slipping contact on a Stribeck branch whose step asks exactly ``static`` of it (``y = static``): no
    slip speed, it sticks.  m = 1 kg at v0 = 1/16 m/s, dt = 1/8 s (m/dt = 8 N s/m, above the fall's steepest
    slope 5 N s/m: the step is unique), a constant 0.5 N: ``y = m/dt v0 + F = 0.5 + 0.5 = 1 = static`` with
    no rounding (powers of two).  The one-mass compiled loop's ``y > static`` turned ``y >= static`` (a
    mutant that survived the suite) slips it at rate ``2.8e-17`` m/s, unflagged as stuck."""
    text = """[[mass]]
name = "m"
mass = 1.0
v0 = 0.0625
[[element]]
name = "f"
kind = "friction"
between = ["ground", "m"]
static = 1.0
kinetic = 0.5
stribeck_velocity = 0.1
[[force]]
on = "m"
kind = "constant"
value = 0.5
"""
    run = run_network(parse_system(text, "arrives"), 0.5, 0.125, solver=solver)
    assert run.solver == path
    assert np.all(run.velocities[1:, 0] == 0.0) and np.all(run.rigid[1:, 0])
    assert run.forces[1, 0] == 1.0 and np.all(run.forces[2:, 0] == 0.5)


def _three_blocks(x: np.ndarray, v: np.ndarray) -> object:
    """The three blocks started at positions ``x`` and velocities ``v`` (exact: ``repr`` round-trips)."""
    text = THREE_BLOCKS
    for name, xi, vi in zip("abc", x, v):
        text = text.replace(f'name = "{name}"\n', f'name = "{name}"\nx0 = {float(xi)!r}\nv0 = {float(vi)!r}\n', 1)
    return parse_system(text.replace("v0 = -0.4\n[[", "[[").replace("v0 = -0.4\n", ""), "three")


def test_three_blocks_settle_and_the_two_steps_agree() -> None:
    """Issue 41's example did not settle at t = 0.959 s.  No external force acts, so the momentum
    ``sum m v = -0.8`` N s is kept by every step (each contact's force acts on both its masses, equal and
    opposite: only rounding, a few ulps of 0.8 a step, 1000 steps).  From the compiled run's state at
    t = 0.94 s (its contacts' states follow from the rates: ``ab`` slipping, ``ac`` stuck, ``w = 0``
    exactly) the Python step and the compiled one take the next 30 steps, through the step that failed,
    and agree to 1e-12 of the largest position (their root solves differ by a few ulps of a slip speed a
    step, tests/test_network_banded.py, which no step amplifies: m/dt = 1000 against falls of 2.4 N s/m)."""
    net = parse_system(THREE_BLOCKS, "three")
    whole = run_network(net, 1.0, 1e-3)
    assert whole.solver == "compiled-banded"
    assert np.max(np.abs(whole.velocities.sum(axis=1) + 0.8)) <= 1000 * 8 * EPS
    _on_law(net, whole)
    assert whole.rigid[940, 1] and not whole.rigid[940, 0]
    start = _three_blocks(whole.positions[940], whole.velocities[940])
    python = run_network(start, 0.03, 1e-3, solver="python")
    compiled = run_network(start, 0.03, 1e-3)
    scale = np.abs(python.positions).max()
    np.testing.assert_allclose(compiled.positions, python.positions, rtol=1e-12, atol=1e-12 * scale)
    np.testing.assert_array_equal(compiled.rigid, python.rigid)
    _on_law(start, python)


def _on_law(net: object, run: object, sigma: float = 500.0) -> None:
    """Every slipping contact's force lies on its law to the step's settling test.

    A slip mode settles when its point's ``z = f + sigma w`` agrees to 8 ulps
    of ``scale = |f| + |f'| + sigma (|w| + |w'|)`` (``CurveSlipGraph.same``); the solve's force
    lies on the line of slope ``sigma`` through the old point, and ``z - z_old = 2 sigma (w - w_old)``,
    so ``sigma |w - w_old| <= 4 eps scale`` and the force is off the branch by at most ``(1 + |g'|/sigma)
    4 eps scale``, ``scale <= 2 (|f| + sigma |w|)`` (the Newton finish settles tighter, on the branch to
    the solve's rounding).  So ``|f - sgn(w) g(|w|)| <= 8 eps (1 + |g'|/sigma) (|f| + sigma |w|)``, and 8 eps
    of ``|g|`` more for the evaluations of ``g``: at ``sigma |w| = 200`` N, 4e-13 N, far below the 1.2e-3 N of
    a point accepted off its law.  The solve itself rounds the forces by up to ``df = n eps (sum |r_i| +
    sum d_i |v_i| + sum |f_e|)`` (``network_step.on_pieces``: ``n = 6`` terms, ``r = m/dt v_n`` without
    loads, ``d = m/dt``), which a cycle of points reached by solves on the branch to that rounding may
    leave (``CurveSlipGraph.near``): added.  ``sigma`` is each contact's mode-test scale, ``m/dt`` in
    series for two masses of 1 kg at ``dt = 1e-3`` (500 N s/m)."""
    d = 1.0 / 1e-3
    momenta = d * np.abs(run.velocities).sum(axis=1)  # type: ignore[attr-defined]
    df = 6 * EPS * (np.r_[0.0, momenta[:-1]] + momenta + np.abs(run.forces).sum(axis=1))  # type: ignore[attr-defined]
    first, second = net.incidence()  # type: ignore[attr-defined]
    for e, el in enumerate(net.elements):  # type: ignore[attr-defined]
        w = run.velocities[:, second[e]] - run.velocities[:, first[e]]  # type: ignore[attr-defined]
        slipping = np.flatnonzero((w != 0) & ~run.rigid[:, e])  # type: ignore[attr-defined]
        s, f = np.abs(w[slipping]), run.forces[slipping, e]  # type: ignore[attr-defined]
        g = el.law.slip(s)
        slope = np.array([abs(el.law.slope(float(x)).value) for x in s])
        bound = 8 * EPS * ((1 + slope / sigma) * (np.abs(f) + sigma * s) + np.abs(g)) + df[slipping]
        assert np.all(np.abs(f - np.sign(w[slipping]) * g) <= bound), el.name


def test_the_burridge_knopoff_chain_settles_at_bk_dt_0_1() -> None:
    """``--config bk_blocks=3 bk_travel=2 bk_dt=0.1`` (a step the study's schema admits) did not settle at
    t = 100.1; it runs its 2000 steps, and the compiled step agrees with the Python step."""
    p = bk.Parameters(blocks=3)
    result = bk.run(p, 2.0, 0.1)
    assert result.steps == 2000
    x0 = bk.initial_positions(p)
    net = bk.chain(p, x0)
    python = run_network(net, 100.2, 0.1, solver="python")
    compiled = run_network(net, 100.2, 0.1)
    assert compiled.solver == "compiled-banded"
    np.testing.assert_allclose(compiled.positions, python.positions, rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(compiled.rigid, python.rigid)


@pytest.fixture
def compiled_bound():
    """Set the compiled step's bound on iterations per scale (``network_step.BOUND``, handed to C by
    ``network_compiled.settings``) for one test, and put the definition back after it."""
    from lumped.solvers import network_compiled, network_step

    if network_compiled.KERNEL != "compiled":
        pytest.skip("the compiled step is not built")
    kept = network_step.BOUND

    def set_bound(bound: tuple[int, int]) -> None:
        network_step.BOUND = bound
        network_compiled.settings()

    yield set_bound
    network_step.BOUND = kept
    network_compiled.settings()


def test_an_unsettled_compiled_step_names_the_elements_and_phi_from_the_python_step(compiled_bound) -> None:
    """With one iteration per scale in both steps the three blocks' compiled step does not settle at its first
    step: the Python step takes that step again from the same state, and the message is its own (a bug, the
    step, the elements still changing, the step's function)."""
    compiled_bound((1, 0))
    with pytest.raises(ValueError) as err:
        run_network(parse_system(THREE_BLOCKS, "three"), 0.01, 1e-3)
    message = str(err.value)
    assert "this is a bug" in message and "(step 1)" in message
    assert "elements still changing:" in message and "Phi = " in message


def test_a_compiled_step_that_fails_where_the_python_step_settles_says_so(compiled_bound) -> None:
    """One iteration per scale in C only: the compiled step fails, the Python step settles the same step, and
    the message says that the compiled step parts from its twin there."""
    from lumped.solvers import network_step

    compiled_bound((1, 0))
    network_step.BOUND = (20, 2)  # the Python step's own bound again; C keeps the one it was handed
    with pytest.raises(ValueError, match=r"the Python step settles this step from the same state, so the compiled"):
        run_network(parse_system(THREE_BLOCKS, "three"), 0.01, 1e-3)
