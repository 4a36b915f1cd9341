"""Backward Euler on friction between masses (issue 31): steps whose solution sits on a corner of a graph.

Two masses ``a`` (``x0 = 0.1`` m) and ``b``, each on a spring of 100 N/m to
the ground, joined by a Coulomb pad of 5 N: sticking, the pad holds
``k (x_a - x_b)/2 = 5`` N, exactly its threshold, for the whole run (the
centre of mass swings, the gap stays 0.1 m).  Each step's solution is then
the corner of the pad's graph where the sticking piece meets the slipping
one, and in floating point each of the two pieces' linear solves lands a few
ulps on the other's side (sticking: a force of ``5 + 2 ulp``; slipping: a
rate of ``-6e-21``): the active-set iteration went round that cycle until it
gave up, at every ``dt``, on both paths.  A cycle is now gone round once and
its iterate on its pieces up to the linear solve's rounding
(:func:`lumped.solvers.network_step.on_pieces`) is the solution.  Two pads
in parallel are stepped as one pad of the summed threshold
(:mod:`lumped.solvers.parallel_elements`).

Checked: the runs that failed now run; backward Euler converges to the exact
method at order one on them (the exact method on the equivalent system where
it refuses a loop that can stick); two pads move as one pad bit for bit and
report the split's interval; the compiled and Python steps agree; the
``sigma`` scales of the iteration settle a step that cycles at scale 1; a
step that does not settle is not blamed on ``--dt``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_lumped
from references import order

import lumped as L
from lumped import Bingham, Mass, Network, Spring, SpringString, simulate_network
from lumped.laws.element import Element
from lumped.solvers import network_compiled as kernel
from lumped.solvers import network_step

EPS = float(np.finfo(float).eps)


def two_masses(
    pads: tuple[float, ...], x0: float = 0.1, gamma: float = math.inf, beside: Element | None = None
) -> Network:
    """``a`` and ``b`` on springs of 100 N/m to the ground, joined by Bingham pads of thresholds
    ``pads`` (the second one reversed, ``b`` to ``a``) and the element ``beside`` if given."""
    elements = [Spring("sa", ("ground", "a"), 100.0), Spring("sb", ("ground", "b"), 100.0)]
    elements += [] if beside is None else [beside]
    elements += [Bingham(f"p{i}", ("a", "b") if i != 1 else ("b", "a"), tau, gamma) for i, tau in enumerate(pads)]
    return Network([Mass("a", 1.0, x0), Mass("b", 1.0)], elements)


def chain(n: int) -> Network:
    """The issue's chain: unit blocks, each joined to the previous point (the first to the ground)
    by a spring of 100 N/m and a Coulomb element of 1 N in parallel, released from
    ``x0_i = 0.5 ((7919 i mod 1000)/1000 - 0.5)`` m, ``i = 1..n``."""
    masses = [Mass(f"m{i}", 1.0, 0.5 * ((7919 * i % 1000) / 1000 - 0.5)) for i in range(1, n + 1)]
    elements = []
    for i in range(1, n + 1):
        points = ("ground" if i == 1 else f"m{i - 1}", f"m{i}")
        elements += [Spring(f"k{i}", points, 100.0), Bingham(f"c{i}", points, 1.0, math.inf)]
    return Network(masses, elements)


# -- the runs that failed ---------------------------------------------------------------
@pytest.mark.parametrize("solver", ["python", "compiled"])
@pytest.mark.parametrize("gamma", [math.inf, 1.0], ids=["coulomb", "bingham"])
@pytest.mark.parametrize("dt", [1e-2, 1e-3, 1e-4])
def test_a_pad_held_at_its_threshold_steps_at_every_dt(dt: float, gamma: float, solver: str) -> None:
    """The pad sticks at exactly its threshold: 100 steps run (before: the iteration did not settle
    by step 20 at any of these ``dt``), the gap ``x_a - x_b`` stays 0.1 m and the pad's force
    ``|F| = 5`` N.  Bounds: an accepted corner iterate is on its pieces to ``on_pieces``' rounding,
    so a slipping step moves the gap by at most ``dt dw``, ``dw = n eps (sum|v| + sum|w|)`` with
    ``n = 5`` and ``|v| <= 0.1 omega = 1`` m/s (the swing's amplitude and frequency): over 100
    steps below ``100 dt 5 eps 4`` plus the rounding of ``x`` (``eps``).  A slipping pad's force
    is ``5 + c w`` with ``c = 1/(gamma dt)`` and ``|w| <= dw``; a sticking one's is its masses'
    momentum balance, 4 roundings of its largest term ``m |v|/dt + k |x| + 5``."""
    tr = simulate_network(two_masses((5.0,), gamma=gamma), 100 * dt, dt, solver=solver)
    assert tr.solver == solver and tr.t.size == 101
    gap = tr.positions[:, 0] - tr.positions[:, 1]
    dw = 5 * EPS * 4.0
    assert np.max(np.abs(gap - 0.1)) <= 100 * dt * dw + 2 * EPS
    c = 0.0 if math.isinf(gamma) else 1.0 / (gamma * dt)
    balance = np.max(np.abs(tr.velocities)) / dt + 100.0 * np.max(np.abs(tr.positions)) + 5.0
    assert np.max(np.abs(np.abs(tr.forces[1:, 2]) - 5.0)) <= c * dw + 4 * EPS * balance


def test_two_pads_and_a_string_beside_a_pad_held_at_their_threshold_run() -> None:
    """The issue's other two cases at the corner: pads of 3 N and 2 N (5 N together), and a
    ``spring-string`` of 25 N/m (never taut: ``L = 1`` m) beside a pad of ``(100/2 + 25) 0.1 = 7.5``
    N, the force it holds sticking.  Both ran into the same cycle; the pads split as ``3, 2``."""
    pads = simulate_network(two_masses((3.0, 2.0)), 0.2, 1e-3)
    assert pads.solver == "python" and pads.t.size == 201
    assert np.all(np.abs(pads.forces[1:, 2]) == 3.0) and np.all(np.abs(pads.forces[1:, 3]) == 2.0)
    string = SpringString("s", ("a", "b"), 25.0, 1.0)
    beside = simulate_network(two_masses((7.5,), beside=string), 0.2, 1e-3)
    assert beside.solver == "python" and beside.t.size == 201


@pytest.mark.slow
def test_the_thousand_block_chain_runs_as_its_blocks_come_to_rest() -> None:
    """The issue's chain of 1000 blocks at ``dt = 1e-3`` (before: the compiled step did not settle at
    t = 3.162 s as the blocks came to rest, four Coulomb elements sticking at exactly 1 N): it runs
    to 4 s, blocks coming to rest from 2.9 s on, no Coulomb force beyond its threshold (the
    accepted corner's forces are clipped to the band)."""
    tr = simulate_network(chain(1000), 4.0, 1e-3)
    assert tr.solver == "compiled" and tr.t[-1] == 4.0
    assert np.nanmin(tr.rest_times) < 3.162 and np.max(np.abs(tr.forces[:, 1::2])) <= 1.0


# -- at order against the exact method --------------------------------------------------
#: name -> (the network backward Euler runs, the exact method's equivalent one, t_end)
ORDER = {
    "one-pad": (two_masses((5.0,)), two_masses((5.0,)), 1.0),
    "one-pad-slipping": (two_masses((5.0,), x0=0.2), two_masses((5.0,), x0=0.2), 1.0),
    "two-pads": (two_masses((3.0, 2.0)), two_masses((5.0,)), 0.3),
    "string-beside": (
        two_masses((7.5,), beside=SpringString("s", ("a", "b"), 25.0, 1.0)),
        two_masses((7.5,), beside=Spring("s", ("a", "b"), 25.0)),
        0.3,
    ),
    "chain-3": (chain(3), chain(3), 1.0),
}


@pytest.mark.parametrize("name", list(ORDER))
def test_backward_euler_is_first_order_against_exact(name: str) -> None:
    """max |x - x_exact| on the grid over halving steps: its fitted slope is backward Euler's order 1
    within 0.1 (the band of ``tests/test_convergence.py``: the error constant has settled at these
    steps).  Exact refuses two pads or a string beside a pad (a loop that can stick); it runs the
    equivalent system: one pad of the summed threshold, and the spring alone (the string is never
    taut: its gap stays below 0.3 m < L)."""
    net, ref, t_end = ORDER[name]
    steps = np.array([2e-3, 1e-3, 5e-4, 2.5e-4])
    errors = []
    for dt in steps:
        be = L.solve(L.Problem(net, t_end), dt)
        ex = L.solve(L.Problem(ref, t_end), dt, method="exact")
        errors.append(float(np.max(np.abs(be.positions - ex.positions))))
    assert 0.9 <= order(steps, np.array(errors)) <= 1.1


# -- parallel pads are one pad ------------------------------------------------------------
@pytest.mark.parametrize("x0", [0.1, 0.2, 0.05], ids=["at-threshold", "slipping", "held-below"])
def test_two_pads_move_as_one_pad_of_the_summed_threshold_bit_for_bit(x0: float) -> None:
    """Pads of 3 N and 2 N (the second reversed) step as one pad of ``3 + 2 = 5`` N: the same pieces
    (each sum exact), the same solve, so the same velocities bit for bit; both run the Python step."""
    pads = simulate_network(two_masses((3.0, 2.0), x0=x0), 1.0, 1e-3)
    one = simulate_network(two_masses((5.0,), x0=x0), 1.0, 1e-3, solver="python")
    assert np.array_equal(pads.velocities, one.velocities)
    assert np.array_equal(pads.rigid[:, 2], one.rigid[:, 2]) and np.array_equal(pads.rigid[:, 3], one.rigid[:, 2])
    assert np.array_equal(pads.forces[:, 2] - pads.forces[:, 3], one.forces[:, 2])  # the second one reversed


def test_held_pads_report_the_interval_of_each_ones_force() -> None:
    """Released from ``x0 = 0.05`` the pair sticks from the start, holding ``R = k (x_a - x_b)/2 =
    2.5`` N: pad 1 may carry any force in ``[max(-3, R - 2), min(3, R + 2)] = [0.5, 3]``, pad 2
    (reversed: its tension is ``-f``) any in ``[max(-2, R - 3), min(2, R + 3)] = [-0.5, 2]``, and
    the split reported is the least-norm one, ``R/2`` each.  ``R`` is the step's held force, to
    the rounding of its momentum balance: 4 roundings of its largest term ``m |v|/dt + k |x|``."""
    tr = simulate_network(two_masses((3.0, 2.0), x0=0.05), 1.0, 1e-3)
    assert tr.undetermined == [2, 3] and tr.rigid[1:, 2].all()
    held = tr.forces[1:, 2] - tr.forces[1:, 3]
    bound = 4 * EPS * (np.max(np.abs(tr.velocities)) / 1e-3 + 100.0 * np.max(np.abs(tr.positions)))
    assert np.max(np.abs(held - 2.5)) <= bound
    assert np.array_equal(tr.forces[1:, 2], -tr.forces[1:, 3]) and np.max(np.abs(tr.forces[1:, 2] - 1.25)) <= bound
    assert np.max(np.abs(tr.force_min[1:, 2] - (held - 2.0))) <= bound
    assert np.max(np.abs(tr.force_max[1:, 2] - 3.0)) <= bound
    assert np.max(np.abs(-tr.force_max[1:, 3] - (held - 3.0))) <= bound
    assert np.max(np.abs(-tr.force_min[1:, 3] - 2.0)) <= bound


# -- the compiled step, the scales, the message -----------------------------------------
@pytest.mark.parametrize("gamma", [math.inf, 1.0], ids=["coulomb", "bingham"])
def test_compiled_and_python_steps_agree_at_the_corner(gamma: float) -> None:
    """Both paths run the corner (each accepts the cycle's first iterate on its pieces, which may be
    the sticking or the slipping one: the rigid flags are not compared).  The velocities agree to
    the bound of ``tests/test_network_kernel.py``: 8 roundings per element and step of the step's
    velocity scale, summed over the steps (a step is non-expansive)."""
    net = two_masses((5.0,), gamma=gamma)
    py = simulate_network(net, 1.0, 1e-3, solver="python")
    c = simulate_network(net, 1.0, 1e-3, solver="compiled")
    scale = np.max(np.abs(py.velocities)) + 1e-3 * np.max(np.abs(py.forces))
    assert np.max(np.abs(py.velocities - c.velocities)) <= 1000 * 8 * 3 * EPS * scale


def scaled_step():
    """One step that the iteration cycles on at the scale ``sigma`` (a Bingham element of 1 N,
    ``gamma = 0.1``, to the ground on ``m1`` flips between slipping either way: a genuine cycle,
    rates of 0.02 m/s, no corner) and settles on at ``sigma / 4``: masses of 4 kg at
    ``x0 = 0.4, 0.5`` m moving at 0.4 and 0.3 m/s, two springs between them, a Coulomb pad of
    5 N from ``m0`` to the ground, ``dt = 0.2`` s."""
    net = Network(
        [Mass("m0", 4.0, 0.4), Mass("m1", 4.0, 0.5)],
        [
            Spring("k0", ("m0", "m1"), 270.0),
            Bingham("c1", ("ground", "m1"), 1.0, 0.1),
            Bingham("c2", ("ground", "m0"), 5.0, math.inf),
            Spring("k3", ("m0", "m1"), 290.0),
        ],
    )
    dt = 0.2
    inertia = np.array([m.mass / dt for m in net.masses])
    first, second = net.incidence()
    graphs = [el.step_graph(el.initial_state(0.1 if el.name.startswith("k") else 0.0, 0.0), dt) for el in net.elements]
    seen = 20.0 + dt * (270.0 + 290.0)  # the driver's scale: the stiffness each mass sees, m/dt + dt sum k
    sigma = np.array([seen / 2, seen, seen, seen / 2])  # in series between the masses; the ground is rigid
    return net, first, second, inertia, inertia * np.array([0.4, 0.3]), graphs, sigma


def test_the_sigma_scales_settle_a_step_that_cycles_at_scale_one(monkeypatch: pytest.MonkeyPatch) -> None:
    """The scales (``SIGMA_SCALES``) settle the step without the dual sweeps, and the result meets the
    step's optimality conditions: every ``(w, f)`` on its graph, each mass's momentum balance to
    the rounding of its terms.  The compiled step settles at the same scale, in as many iterations."""

    def no_sweeps(*args: object) -> None:
        raise AssertionError("the sigma scales should settle this step")

    net, first, second, inertia, rhs, graphs, sigma = scaled_step()
    monkeypatch.setattr(network_step, "_dual_sweeps", no_sweeps)
    sol = network_step.solve_step(first, second, inertia, rhs, graphs, sigma)
    assert sol.modes == [0, 1, 2, 0] and sol.v[1] == 0.0  # m1 held by c1, m0 slipping on c2
    pieces = [g[m] for g, m in zip(graphs, sol.modes)]
    assert network_step.on_pieces(pieces, sol.v, sol.w, sol.f, inertia, rhs)
    pushed = np.zeros(3)
    np.add.at(pushed, second, sol.f)
    np.add.at(pushed, first, -sol.f)
    residual = inertia * sol.v + pushed[:2] - rhs
    assert np.max(np.abs(residual)) <= 8 * EPS * (np.abs(rhs).max() + np.abs(sol.f).max())
    if kernel.KERNEL == "compiled":
        compiled = kernel.solve_graphs(kernel.plan(net), inertia, sigma, graphs, rhs)
        assert compiled.modes == sol.modes and compiled.iterations == sol.iterations


def test_a_step_that_does_not_settle_is_not_blamed_on_dt(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    """If the iteration ever fails, the command says the step solver failed, in one line, status 2,
    naming no option: ``--dt`` is not the cause (every step problem has a solution)."""
    system = tmp_path / "pads.toml"
    system.write_text(
        '[[mass]]\nname = "a"\nmass = 1.0\nx0 = 0.1\n[[mass]]\nname = "b"\nmass = 1.0\n'
        '[[element]]\nname = "pad"\nkind = "bingham"\nbetween = ["a", "b"]\nthreshold = 5.0\ngamma = 1.0\n'
    )

    solve = network_step.solve_step

    def fails(*args: object, **kwargs: object) -> network_step.StepSolution:
        if kwargs.get("modes", args[6] if len(args) > 6 else None) is None and not calls:  # the initial forces
            calls.append(1)
            return solve(*args, **kwargs)
        raise network_step.StepError(network_step.unsettled(24))

    calls: list[int] = []
    monkeypatch.setattr(kernel, "KERNEL", "python")  # the Python step, whose solve is replaced
    monkeypatch.setattr("lumped.solvers.backward_euler_network.solve_step", fails)
    out = run_lumped("simulate", "--system", system, "--method", "backward-euler", "--output", tmp_path / "o.csv")
    assert out.returncode == 2 and len(out.stderr.strip().splitlines()) == 1
    assert "the step solver failed at the step to t = 0.0001 s" in out.stderr and "--dt" not in out.stderr
    assert not (tmp_path / "o.csv").exists()


@pytest.mark.skipif(kernel.KERNEL != "compiled", reason="the compiled network kernel was not built")
def test_the_compiled_step_reads_the_scales_from_the_python_step() -> None:
    """``SIGMA_SCALES`` and ``DUAL_SWEEPS`` are written once, in :mod:`lumped.solvers.network_step`:
    with the scales cut to ``(1.0,)`` the compiled step no longer settles the scaled step by its
    scales (it reaches the sweeps' modes, settled in one iteration), and with no sweeps at all it
    fails, as the Python step does."""
    net, first, second, inertia, rhs, graphs, sigma = scaled_step()
    kept = network_step.SIGMA_SCALES, network_step.DUAL_SWEEPS
    try:
        network_step.SIGMA_SCALES = (1.0,)
        kernel.settings()
        assert kernel.solve_graphs(kernel.plan(net), inertia, sigma, graphs, rhs).iterations == 1
        network_step.DUAL_SWEEPS = ()
        kernel.settings()
        with pytest.raises(network_step.StepError):
            kernel.solve_graphs(kernel.plan(net), inertia, sigma, graphs, rhs)
        with pytest.raises(network_step.StepError):
            network_step.solve_step(first, second, inertia, rhs, graphs, sigma)
    finally:
        network_step.SIGMA_SCALES, network_step.DUAL_SWEEPS = kept
        kernel.settings()
    assert kernel.solve_graphs(kernel.plan(net), inertia, sigma, graphs, rhs).iterations == 3
