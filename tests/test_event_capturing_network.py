"""``event-locating`` on networks (issue 21): order two through events, against independent solutions.

:func:`lumped.solvers.event_capturing_network.solve_capturing_network` is
checked against the independent stick-slip reference of ``tests/references.py``
(DOP853 at ``rtol = 1e-12`` per mode, modes by enumeration; no code shared),
against the one-mass ``event-locating`` solver (a separate implementation:
the dashpot's resolvent in scalar arithmetic), against closed forms (the
Coulomb oscillator under a constant load and under a constant ground
acceleration), and for its refusals and its routing.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import references as R
from cli_run import run_lumped
from test_network_references import CHAINS, FORCE, chain, plain, reference

import lumped as L
from lumped import Bingham, Load, Mass, Network, Spring
from lumped.model.forcing import one_force, sine_form
from lumped.solvers.event_capturing import event_capturing
from lumped.solvers.event_capturing_network import solve_capturing_network


def capture(net: Network, t_end: float, dt: float) -> L.Trajectory:
    return L.solve(L.Problem(net, t_end), dt, method="event-locating")


def slope(errors: list[float], steps: list[float]) -> float:
    return float(np.polyfit(np.log(steps), np.log(errors), 1)[0])


# -- order two against the independent reference -----------------------------------------
@pytest.mark.parametrize(
    "name",
    [n if n == "3-coulomb-forced" else pytest.param(n, marks=pytest.mark.slow) for n in CHAINS],  # one by default
)
def test_order_two_through_stops_and_breakaways_against_the_reference(name: str) -> None:
    """max |x - x_ref| on the grid at dt = 2e-3, 1e-3, 5e-4: the slope of its logarithm lies in
    1.8..2.2 (order two, as measured on this machine: 1.98 to 2.01), the same events as the
    reference (kinds and modes) and the rest times within 1e-4 s (the time error of a located stop
    is that of the phase, about (omega dt)^2/12 of the time elapsed: below 1e-5 s here)."""
    net, t_end = CHAINS[name]
    ref = reference(name)
    friction = [i for i, el in enumerate(net.elements) if isinstance(el, Bingham)]
    steps, errors = [2e-3, 1e-3, 5e-4], []
    for dt in steps:
        tr = capture(net, t_end, dt)
        errors.append(float(np.max(np.abs(tr.positions - ref.state(tr.t)[0]))))
    assert 1.8 <= slope(errors, steps) <= 2.2, errors
    assert [(e.kind, tuple(e.mode[i] for i in friction)) for e in tr.events] == [(e.kind, e.mode) for e in ref.events]
    np.testing.assert_allclose(tr.final_rest[0], ref.rest_time, rtol=0, atol=1e-4)


def test_a_table_load_with_its_end_as_a_jump_keeps_order_two() -> None:
    """The chain's sine written as a table (samples every 1e-4 s up to its switch-off at 1 s, zero
    after: the same jump), against the reference with the sine: slope 1.8..2.2.  The table's
    interpolation error, (1e-4)^2/8 * 10 * (5 pi)^2 < 4e-7 N, moves x by less than 1e-8 m, far
    below the step's errors (1e-6 m and up)."""
    net = chain(3, 1.0, math.inf, FORCE)
    ts = np.linspace(0.0, 1.0, 10_001)
    table = Network(net.masses, net.elements, [Load("m2", L.Table(ts, FORCE(ts)))])
    ref = R.stick_slip_motion(plain(net), 1.6)
    steps, errors = [2e-3, 1e-3, 5e-4], []
    for dt in steps:
        tr = capture(table, 1.6, dt)
        errors.append(float(np.max(np.abs(tr.positions - ref.state(tr.t)[0]))))
    assert 1.8 <= slope(errors, steps) <= 2.2, errors


# -- against the one-mass event-locating solver ----------------------------------------
@pytest.mark.parametrize(("gamma", "force"), [(1.0, None), (math.inf, None), (1.0, FORCE), (math.inf, FORCE)])
def test_one_mass_is_the_one_mass_event_capturing_solver(gamma: float, force: L.SwitchedSine | None) -> None:
    """The paper's system run by the network solver (called directly: ``solve`` sends it to the
    one-mass solver) and by the one-mass solver, two implementations of the same scheme: the
    same motion to 1e-10 of its 0.5 m scale (they differ by round-off, about 1e-13 m), the same rest."""
    net = Network(
        [Mass("m", 1.0, 0.5)],
        [Spring("k", ("ground", "m"), 100.0), Bingham("d", ("ground", "m"), 1.0, gamma)],
        [Load("m", force)] if force else [],
    )
    dt = 1e-3
    tr = solve_capturing_network(net, 2.5, dt)
    form = L.Problem(net, 2.5).one_mass()
    one = event_capturing(form.oscillator, 2.5, dt, x0=0.5, force=sine_form(one_force([ld.force for ld in net.loads])))
    assert np.max(np.abs(tr.positions[:, 0] - one.trajectory.x)) <= 1e-10 * 0.5
    np.testing.assert_allclose(tr.final_rest[0], one.trajectory.rest_time, rtol=0, atol=1e-10)


# -- closed forms ---------------------------------------------------------------------------
def _rest_bound(omega: float, dt: float) -> float:
    """The trapezoidal rule's phase error over half a period, (pi/omega) (omega dt)^2/12, times 1.5."""
    return 1.5 * (math.pi / omega) * (omega * dt) ** 2 / 12


@pytest.mark.parametrize("dt", [2e-3, 5e-4])
def test_coulomb_oscillators_under_a_constant_load_rest_at_the_closed_form(dt: float) -> None:
    """Two unconnected masses on springs k and Coulomb pads tau, pushed by a constant P with
    tau < P < 3 tau, one from t = 0 and one from t = 0.25 s: each moves half a period
    pi sqrt(m/k) and rests at 2 (P - tau)/k.  The trapezoidal rule keeps the energy of the
    undamped oscillator exactly, so the located stop (v = 0) is at the exact amplitude: the
    rest position to 1e-12 m; the rest time carries the phase error of half a period."""
    k, tau, p, m = 100.0, 1.0, 2.5, 1.0
    net = Network(
        [Mass("early", m), Mass("late", m)],
        [
            Spring("k1", ("ground", "early"), k),
            Bingham("pad1", ("ground", "early"), tau, math.inf),
            Spring("k2", ("ground", "late"), k),
            Bingham("pad2", ("ground", "late"), tau, math.inf),
        ],
        [Load("early", L.Constant(p)), Load("late", L.Constant(p, 0.25))],
    )
    tr = capture(net, 1.0, dt)
    omega = math.sqrt(k / m)
    np.testing.assert_allclose(tr.final_rest[1], 2 * (p - tau) / k, rtol=0, atol=1e-12)
    assert np.all(np.abs(tr.final_rest[0] - (np.array([0.0, 0.25]) + math.pi / omega)) <= _rest_bound(omega, dt))
    assert [e.kind for e in tr.events] == ["switch", "stop", "stop"]  # a constant load stays on: no rest


def test_a_constant_ground_acceleration_from_a_system_file_rests_at_the_closed_form(tmp_path) -> None:  # noqa: ANN001
    """The paper's arrangement with a Coulomb pad under a [ground] acceleration a_g = -P/m, a table
    of two equal samples (the constant itself, bit for bit: np.interp's straight line), which the
    one-mass solver does not take: the network solver runs it, and the mass rests, relative to the
    ground, at 2 (P - tau)/k after half a period, as under the load P."""
    k, tau, p = 100.0, 1.0, 2.5
    (tmp_path / "a.csv").write_text(f"t,a\n0,{-p}\n10,{-p}\n")
    (tmp_path / "sys.toml").write_text(
        '[[mass]]\nname = "m"\nmass = 1.0\n'
        f'[[element]]\nname = "k"\nkind = "spring"\nbetween = ["ground", "m"]\nstiffness = {k}\n'
        f'[[element]]\nname = "pad"\nkind = "bingham"\nbetween = ["ground", "m"]\nthreshold = {tau}\ngamma = inf\n'
        '[ground]\nacceleration = { kind = "table", file = "a.csv" }\n'
    )
    dt = 1e-3
    tr = capture(L.load_system(tmp_path / "sys.toml"), 1.0, dt)
    assert tr.solver == "event-locating" and np.all(tr.applied == p)
    np.testing.assert_allclose(tr.final_rest[1], 2 * (p - tau) / k, rtol=0, atol=1e-12)
    assert abs(tr.final_rest[0][0] - math.pi / 10.0) <= _rest_bound(10.0, dt)


# -- routing and refusals ---------------------------------------------------------------
def test_a_one_mass_table_load_runs_through_the_network_solver() -> None:
    """The one-mass solver takes sines only; a table on the paper's system goes to the network
    solver, which agrees with the one-mass solver run with the sine that the table samples
    (to the table's interpolation error, below 1e-8 m as above)."""
    ts = np.linspace(0.0, 1.0, 10_001)
    base = [Spring("k", ("ground", "m"), 100.0), Bingham("d", ("ground", "m"), 1.0, 1.0)]
    table = Network([Mass("m", 1.0)], base, [Load("m", L.Table(ts, FORCE(ts)))])
    sine = Network([Mass("m", 1.0)], base, [Load("m", FORCE)])
    a, b = capture(table, 1.5, 1e-3), capture(sine, 1.5, 1e-3)
    assert a.solver == "event-locating" and a.events
    assert np.max(np.abs(a.positions - b.positions)) <= 1e-8


@pytest.mark.parametrize(
    ("element", "kind"),
    [
        (L.SpringString("s", ("a", "b"), 10.0, 1.0), "spring-string"),
        (L.MaxwellBingham("s", ("a", "b"), 10.0, 1.0, 1.0), "maxwell-bingham"),
        (L.HerschelBulkley("s", ("a", "b"), 1.0, 1.0, 2.0), "herschel-bulkley"),
    ],
)
def test_refuses_an_element_without_linear_phases_in_one_line(element: L.Element, kind: str) -> None:
    net = Network([Mass("a", 1.0, 0.1), Mass("b", 1.0)], [Spring("k", ("ground", "a"), 10.0), element])
    message = f"^method 'event-locating' cannot run element 's' of kind '{kind}': its linear steps per phase need"
    with pytest.raises(ValueError, match=message):
        capture(net, 0.1, 1e-3)


def test_refuses_a_loop_of_friction_elements_in_one_line() -> None:
    net = Network(
        [Mass("m", 1.0, 0.1)],
        [
            Spring("k", ("ground", "m"), 10.0),
            Bingham("p1", ("ground", "m"), 1.0, math.inf),
            Bingham("p2", ("ground", "m"), 1.0, math.inf),
        ],
    )
    with pytest.raises(ValueError, match="^method 'event-locating' cannot run elements 'p1', 'p2': they close a loop"):
        capture(net, 0.1, 1e-3)


def test_the_command_line_runs_a_chain_file_and_refuses_a_maxwell_element(tmp_path) -> None:  # noqa: ANN001
    out = tmp_path / "chain.csv"
    run = ["simulate", "--method", "event-locating", "--t-end", "2.5"]
    ok = run_lumped(*run, "--system", "examples/chain.toml", "--output", out)
    assert ok.returncode == 0, ok.stderr
    header = out.read_text().splitlines()[0].split(",")
    assert header[:2] == ["t", "x_m1"] and "load_m1" in header
    bad = run_lumped(*run, "--system", "examples/maxwell_creep.toml", "--output", out)
    assert bad.returncode == 2 and len(bad.stderr.strip().splitlines()) == 1
    assert "cannot run element 'creep' of kind 'maxwell-bingham'" in bad.stderr
    (tmp_path / "pull.csv").write_text("t,F\n0,0\n1,3\n2,0\n")
    table = run_lumped(*run, "--x0", "0.1", "--force-table", tmp_path / "pull.csv", "--output", out)
    assert table.returncode == 0, table.stderr
    assert out.read_text().splitlines()[0] == "t,x,v,F_s,F_d,F"


def test_the_oscillator_api_runs_a_table_load_as_the_network_solver_does() -> None:
    osc = L.Oscillator.bingham(1.0, 100.0, 1.0, 1.0)
    pull = L.Table([0.0, 1.0, 2.0], [0.0, 3.0, 0.0])
    tr = L.simulate(osc, 2.0, 1e-3, x0=0.1, force=pull, method="event-locating")
    net = L.Problem.oscillator(osc, 2.0, x0=0.1, force=pull).system
    same = solve_capturing_network(net, 2.0, 1e-3)
    assert np.array_equal(tr.x, same.positions[:, 0]) and np.array_equal(tr.F, pull(tr.t))
