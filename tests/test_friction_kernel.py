"""The compiled one-mass friction loop (``_friction_kernel.c``) against the Python step.

The loop is backward Euler for one mass with springs, dashpots and one friction contact of
:class:`lumped.StribeckLaw`, to the ground or a belt (:mod:`lumped.solvers.friction_compiled`).  The
reference is the Python step (``solver="python"``): the active-set step of the network with the
contact's rule.  On a linear slip curve (no Stribeck velocity) the loop does the Python step's
operations in its order, so whole runs agree bit for bit.  On a Stribeck curve the slip speed is a
root, found by Newton's method in C and by the resolvent iteration with Brent's method in Python: one
step from the same state then agrees to the root solves' tolerance (derived in :func:`step_tolerance`),
and whole runs take the same active set (stuck or slipping, and which way) at every step.
"""

from __future__ import annotations

import functools
import math
import re

import numpy as np
import pytest
from test_bindings import assert_refused

import lumped
from lumped import Driver, Friction, LinearDashpot, Mass, Network, Spring
from lumped.solvers import friction_compiled as friction

needs_kernel = pytest.mark.skipif(friction.KERNEL != "compiled", reason="the friction kernel was not built")

EPS = np.finfo(float).eps
G = "ground"


def belt_system(*, ground=False, reverse=False, stiffness=4.0, load=None, dashpot=0.0, **law):
    """A 1 kg block on a spring to the ground and a contact to a belt at 0.2 m/s, at rest at x = 0 (or to
    the ground, the block then started at 0.5 m/s from 0.2 m), the contact written ``(belt, m)`` or,
    ``reverse``, ``(m, belt)``."""
    point = G if ground else "belt"
    law = {"static": 1.0, "kinetic": 0.5, **law}
    elements = [
        Spring("spring", (G, "m"), stiffness),
        Friction("contact", ("m", point) if reverse else (point, "m"), **law),
    ]
    if dashpot:
        elements.append(LinearDashpot("damper", ("m", G), dashpot))
    loads = [] if load is None else [lumped.Load("m", load)]
    drivers = [] if ground else [Driver("belt", 0.2)]
    return Network([Mass("m", 1.0, 0.2 if ground else 0.0, 0.5 if ground else 0.0)], elements, loads, drivers)


LINEAR = {  # a linear slip curve: bit for bit
    "belt": {},
    "belt-reversed": dict(reverse=True),
    "belt-viscous-loaded-damped": dict(viscous=0.3, load=lumped.SwitchedSine(0.8, 2.0), dashpot=0.2),
    "ground": dict(ground=True),
    "ground-reversed-viscous": dict(ground=True, reverse=True, viscous=0.5),
    "belt-static-equal-kinetic": dict(kinetic=1.0),
}
STRIBECK = {  # a Stribeck curve: each decay, to a belt and to the ground, either way round
    "exponential": dict(stribeck_velocity=0.1),
    "gaussian": dict(stribeck_velocity=0.1, decay="gaussian"),
    "rational-reversed": dict(stribeck_velocity=0.1, decay="rational", reverse=True),
    "exponential-viscous-damped-loaded": dict(
        stribeck_velocity=0.05, viscous=0.3, dashpot=0.2, load=lumped.SwitchedSine(0.5, 3.0)
    ),
    "gaussian-ground": dict(stribeck_velocity=0.1, decay="gaussian", ground=True),
    "rational-ground-reversed": dict(stribeck_velocity=0.2, decay="rational", ground=True, reverse=True),
}
T_END, DT = 6.0, 5e-3  # a slip, a stick and a slip again (the block's period is pi s)


@functools.cache
def runs(case):
    """The system of ``case`` (in :data:`LINEAR` or :data:`STRIBECK`), run compiled and in Python (once)."""
    net = belt_system(**{**LINEAR, **STRIBECK}[case])
    compiled = lumped.simulate_network(net, T_END, DT)
    python = lumped.simulate_network(net, T_END, DT, solver="python")
    return net, compiled, python


@needs_kernel
@pytest.mark.parametrize("case", list(LINEAR))
def test_a_linear_slip_curve_runs_as_the_python_step_bit_for_bit(case):
    """Same operations in the same order (the C file's comment): every saved number is equal."""
    _, compiled, python = runs(case)
    assert (compiled.solver, python.solver) == (friction.PATH, "python")
    assert compiled.rigid[:, 1].any() and not compiled.rigid[:, 1].all()  # it sticks and slips
    for name in ("t", "positions", "velocities", "forces", "states", "rigid", "applied"):
        assert np.array_equal(getattr(compiled, name), getattr(python, name)), name
    assert compiled.iterations == python.iterations
    for a, b in zip(compiled.final_rest, python.final_rest):
        assert np.array_equal(a, b, equal_nan=True)


def _one_step(net, plan, tr, n):
    """The compiled loop's step ``n`` from the Python run's row ``n - 1`` (saved every step)."""
    x, v = tr.positions[n - 1].copy(), tr.velocities[n - 1].copy()
    state = tr.states[n - 1].copy()
    counters = np.array([0, 0, 0, 0], dtype=np.int64)
    marching = (x, v, state, np.zeros(1, dtype=np.int64), counters)
    ne = len(net.elements)
    record = (np.empty(1), np.empty(1), np.empty(1), np.empty(ne), np.empty(ne), np.zeros(ne, dtype=np.uint8))
    table = net.load_table(np.array([n * DT]))[:, 0] if net.loads else np.empty(0)
    friction.march_block(plan, 1.0 / DT, marching, record, table, DT, (n, n, n, 1))
    assert counters[2] == 0
    return record


def step_tolerance(net, tr, n):
    """How far the two steps' contact force may lie apart on a slip branch, from their root solves.

    Both solve ``h(s) = g(s) + E s - y = 0`` (``E`` the mass's ``m/dt`` with its springs' ``k dt``
    and dashpots' ``c``, ``y`` the contact's resolvent variable, ``|y| <= |f| + E (|v| + |belt|)``).
    ``h`` is a handful of roundings (the decay, its scaling, three sums), so it is computed to within
    ``6 eps (g + E s + |y|) <= 12 eps |y|``; a root solver stops where the computed ``h`` changes
    sign, within that over ``h' >= E - fall`` of the root, plus its own stopping width (2 ulps of
    ``s`` in C, Brent's 4 ulps in Python).  The Python step adds its settling test, ``|df| + sigma |dw|
    <= 8 eps (2 |f| + 2 sigma |w|)``, and rounds its rates by ``eps sigma (|v| + |belt|)``.  So the
    forces differ by at most ``(24 + 16 + 2) eps |y| E / (E - fall) + 6 eps E s``, which is below
    ``64 eps Y E / (E - fall)`` with ``Y = |f| + E (|v| + |belt|)``.
    """
    law = net.elements[1].slip_law()
    inertia = 1.0 / DT
    e = (
        inertia
        + sum(el.linear_stiffness * DT for el in net.elements if el.linear_stiffness)
        + sum(el.kernel_form().parameters[0] for el in net.elements if el.name == "damper")
    )
    belt = 0.2 if net.drivers else 0.0
    y = abs(tr.forces[n, 1]) + e * (abs(tr.velocities[n, 0]) + belt)
    return 64 * EPS * y * e / (e - law.fall), e


@needs_kernel
@pytest.mark.parametrize("case", list(STRIBECK))
def test_a_stribeck_step_agrees_with_the_python_step_to_the_root_tolerance(case):
    """From each state of the Python run, the compiled step takes the same active set, the same numbers
    where the contact sticks (the same operations) and, where it slips, forces within
    :func:`step_tolerance`, velocities within it over ``E`` (``v = (load - f)/E``), positions within
    ``dt`` times that plus an ulp of the sum."""
    net, _, python = runs(case)
    assert python.rigid[:, 1].any() and not python.rigid[:, 1].all()
    plan = friction.plan(net)
    for n in range(1, python.t.size):
        t, x, v, force, state, rigid = _one_step(net, plan, python, n)
        assert rigid[1] == python.rigid[n, 1] and state[1] == python.states[n, 1], n  # the active set
        if rigid[1]:
            assert (
                x[0] == python.positions[n, 0]
                and v[0] == python.velocities[n, 0]
                and np.array_equal(force, python.forces[n])
            )
            continue
        tol, e = step_tolerance(net, python, n)
        assert abs(force[1] - python.forces[n, 1]) <= tol, n
        assert abs(v[0] - python.velocities[n, 0]) <= tol / e, n
        assert abs(x[0] - python.positions[n, 0]) <= DT * tol / e + 2 * EPS * abs(x[0]), n


@needs_kernel
@pytest.mark.parametrize("case", list(STRIBECK))
def test_a_stribeck_run_takes_the_python_steps_active_set(case):
    """Whole runs: stuck or slipping, and which way, at every step.  The runs' numbers differ by round-off
    carried from step to step (below 1e-10 m/s; a stick resets the velocity to the belt's), and every
    decision lies far beyond that from its threshold (asserted: a stuck force at least 1e-4 N inside
    ``static``, a slipping rate at least 1e-6 m/s from 0), so the comparison hangs on no last bit."""
    net, compiled, python = runs(case)
    assert compiled.solver == friction.PATH
    assert np.array_equal(compiled.rigid, python.rigid)
    assert np.array_equal(compiled.states[:, 1], python.states[:, 1])
    stuck, force = python.rigid[1:, 1], python.forces[1:, 1]
    rate = python.velocities[1:, 0] - (0.2 if net.drivers else 0.0)
    assert np.min(net.elements[1].slip_law().static - np.abs(force[stuck])) > 1e-4
    assert np.min(np.abs(rate[~stuck])) > 1e-6 and np.max(np.abs(compiled.velocities - python.velocities)) < 1e-10


def test_the_python_step_lies_on_a_flat_stribeck_branch():
    """A step sliding fast on a Gaussian branch (``|u| = 7 v_s``, where ``g`` is flat to 1e-20): its
    force is the curve's at its rate.  Settling on the force alone (which hardly changes there) stopped
    the resolvent iteration on the line through the previous point, ``sigma |dw|`` (0.5 N) off the
    curve.  Tolerance: the step's rounding in the resolvent variable's scale, ``64 eps sigma |u|``."""
    net = Network(
        [Mass("m", 1.0, 0.0, -0.5)],
        [Spring("spring", (G, "m"), 1.0), Friction("contact", ("belt", "m"), 1.0, 0.5, 0.1, "gaussian")],
        drivers=[Driver("belt", 0.2)],
    )
    tr = lumped.simulate_network(net, 3 * 1e-3, 1e-3, solver="python")
    u = tr.velocities[1:, 0] - 0.2
    curve = -net.elements[1].slip_law().slip(np.abs(u))
    assert np.all(np.abs(tr.forces[1:, 1] - curve) <= 64 * EPS * 1e3 * np.abs(u))


# -- which networks the loop runs -------------------------------------------------------------------


@needs_kernel
def test_auto_and_compiled_choose_the_loop_and_python_does_not():
    net = belt_system(stribeck_velocity=0.1)
    for solver in ("auto", "active-set", "compiled"):
        assert lumped.simulate_network(net, 0.1, DT, solver=solver).solver == friction.PATH
    assert lumped.simulate_network(net, 0.1, DT, solver="python").solver == "python"


@needs_kernel
def test_networks_it_cannot_run_go_to_the_python_step():
    """A slip curve without a kernel form: the Python step (and ``"compiled"`` refuses in one line naming
    why); two masses, a belt whose speed varies: not this loop (the sparse step runs them)."""
    curve = lumped.Contact("contact", ("belt", "m"), lumped.SlipCurve(1.0, lambda s: 1 / (1 + 3 * s), fall=3.0))
    leine = Network([Mass("m", 1.0)], [Spring("spring", (G, "m"), 1.0), curve], drivers=[Driver("belt", 0.2)])
    assert friction.ineligible(leine) == "the slip curve of 'contact' has no kernel form"
    assert lumped.simulate_network(leine, 0.1, DT).solver == "python"
    message = (
        "solver: 'compiled' cannot run this network: element 'contact' has a slip curve the compiled step does not know"
    )
    with pytest.raises(ValueError, match=f"^{re.escape(message)}$"):
        lumped.simulate_network(leine, 0.1, DT, solver="compiled")
    two = Network(
        [Mass("a", 1.0), Mass("b", 1.0)],
        [Spring("s", (G, "a"), 1.0), Spring("ab", ("a", "b"), 1.0), Friction("c", (G, "b"), 1.0, 0.5, 0.1)],
    )
    assert friction.ineligible(two) == "the network has 2 masses"
    assert lumped.simulate_network(two, 0.1, DT).solver == "compiled-banded"
    swaying = Network(
        [Mass("m", 1.0)],
        [Spring("spring", (G, "m"), 1.0), Friction("c", ("belt", "m"), 1.0, 0.5)],
        drivers=[Driver("belt", lumped.SwitchedSine(0.2, 1.0))],
    )
    assert "constant velocity" in friction.ineligible(swaying)


@needs_kernel
def test_the_network_kernel_keeps_what_it_ran():
    """A contact that is the Bingham graph with no driven point stays with Algorithm 1 / the network kernel."""
    net = belt_system(ground=True, kinetic=1.0)
    assert lumped.simulate_network(net, 0.1, DT).solver == "algorithm1"
    assert lumped.simulate_network(net, 0.1, DT, solver="active-set").solver == "compiled"


# -- the binding refuses bad arguments ---------------------------------------------------------------


def _args(**change):
    net = belt_system(stribeck_velocity=0.1)
    plan = friction.plan(net)
    ne = len(net.elements)
    args = dict(
        plan=(plan.role, plan.par, plan.sign, plan.delta),
        law=plan.law,
        marching=(np.zeros(1), np.zeros(1), np.zeros(ne), np.zeros(1, dtype=np.int64), np.zeros(4, dtype=np.int64)),
        record=(
            np.empty(10),
            np.empty(10),
            np.empty(10),
            np.empty(10 * ne),
            np.empty(10 * ne),
            np.zeros(10 * ne, np.uint8),
        ),
        table=np.empty(0),
        dt=DT,
        inertia=1 / DT,
        n_first=1,
        n_last=10,
        n_steps=10,
        save_every=1,
    )
    args.update(change)
    return args


BAD = {
    "dt": dict(dt=0.0),
    "inertia": dict(inertia=-1.0),
    "n_last": dict(n_last=0),
    "plan[0] (role)": dict(plan=(np.array([0, 0], dtype=np.int64), *_args()["plan"][1:])),
    "plan[2] (sign)": dict(plan=(*_args()["plan"][:2], np.array([1.0, 0.5]), _args()["plan"][3])),
    "plan[3] (delta)": dict(plan=(*_args()["plan"][:3], np.array([0.0, math.nan]))),
    "code": dict(law=(7, 1.0, 0.5, 0.1, 0.0)),
    "static - kinetic": dict(law=(1, 1.0, 2.0, 0.1, 0.0)),
    "stribeck_velocity": dict(law=(1, 1.0, 0.5, 0.0, 0.0)),
    "table": dict(table=np.ones(3)),
    "marching[2] (state)": dict(marching=(np.zeros(1), np.zeros(1), np.zeros(5), *_args()["marching"][3:])),
    "record[0] (t)": dict(
        record=(np.empty(3), np.empty(3), np.empty(3), np.empty(6), np.empty(6), np.zeros(6, np.uint8))
    ),
}


@needs_kernel
@pytest.mark.parametrize("name", list(BAD))
def test_the_binding_refuses_each_bad_argument(name):
    from lumped.kernels._friction_kernel import friction_block

    good = _args()
    friction_block(*good.values())  # the starting point runs
    assert good["marching"][4][0] == 10
    args = _args(**BAD[name])
    assert_refused(lambda: friction_block(*args.values()), name)
