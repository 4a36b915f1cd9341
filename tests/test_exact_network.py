"""``exact`` on networks (issue 21): closed forms per phase against independent solutions.

:func:`lumped.solvers.exact_network.solve_exact_network` is checked against
the independent stick-slip reference of ``tests/references.py`` (DOP853 at
``rtol = 1e-12`` per mode, a KKT system for the sticking forces, modes chosen
by enumeration; no code shared), against the one-mass exact solver, against
closed forms (the modal solution of two masses on springs; a glued pair as
one mass; the Coulomb oscillator under a constant load), and its refusals.
Then backward Euler's order on a network is measured against it.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import references as R
from references import order
from scipy.integrate import solve_ivp
from test_network_references import CHAINS, FORCE, chain, plain, reference

import lumped as L
from lumped import Bingham, Load, Mass, Network, Spring
from lumped.solvers.exact_network import solve_exact_network


def exact(net: Network, t_end: float, dt: float = 1e-3) -> L.Trajectory:
    return L.solve(L.Problem(net, t_end), dt, method="exact")


# -- against the independent reference ------------------------------------------------
@pytest.mark.parametrize("name", list(CHAINS))
def test_chains_and_a_tree_are_the_reference(name: str) -> None:
    """Positions to 1e-9 of their scale (0.1 m to 0.5 m: the reference's rtol 1e-12 over about
    20 events; the two agree to about 1e-12), velocities to 1e-9 of 10 m/s, the same events
    and the same final rest (times to 1e-9 s)."""
    net, t_end = CHAINS[name]
    tr, ref = exact(net, t_end), reference(name)
    x, v = ref.state(tr.t)
    assert np.max(np.abs(tr.positions - x)) <= 1e-9 * 0.1
    assert np.max(np.abs(tr.velocities - v)) <= 1e-9 * 10.0
    friction = [i for i, el in enumerate(net.elements) if isinstance(el, Bingham)]
    assert [(e.kind, tuple(e.mode[i] for i in friction)) for e in tr.events] == [(e.kind, e.mode) for e in ref.events]
    np.testing.assert_allclose(tr.final_rest[0], ref.rest_time, rtol=0, atol=1e-9)
    np.testing.assert_allclose(tr.final_rest[1], ref.rest_position, rtol=0, atol=1e-10)


def test_loads_of_two_frequencies_and_a_negative_omega_are_the_reference() -> None:
    net = chain(2, 3.0, 1.0)
    loads = [Load("m1", L.SwitchedSine(8.0, 5 * math.pi, 0.3, 1.2)), Load("m0", L.SwitchedSine(-6.0, -7.0, 1.1, 0.7))]
    net = Network(net.masses, net.elements, loads)
    tr, ref = exact(net, 2.0), R.stick_slip_motion(plain(net), 2.0)
    x, _ = ref.state(tr.t)
    assert np.max(np.abs(tr.positions - x)) <= 1e-9 * 0.1
    assert len(tr.events) == len(ref.events)


def test_sticking_forces_lie_in_their_bands_and_balance_the_masses() -> None:
    """While an element sticks its force is within its threshold (to round-off)."""
    net, t_end = CHAINS["3-coulomb-forced"]
    tr = exact(net, t_end)
    tau = np.array([getattr(el, "threshold", np.inf) for el in net.elements])
    assert tr.rigid.any()
    assert np.all(np.abs(tr.forces[tr.rigid]) <= np.broadcast_to(tau, tr.forces.shape)[tr.rigid] * (1 + 1e-9))


# -- against the one-mass exact solver -------------------------------------------------
@pytest.mark.parametrize(
    ("gamma", "x0", "force"),
    [(1.0, 0.5, None), (math.inf, 0.3, None), (1.0, 0.0, FORCE), (math.inf, 0.0, FORCE)],
)
def test_one_mass_is_the_one_mass_exact_solver(gamma: float, x0: float, force: L.SwitchedSine | None) -> None:
    """The network path on the paper's system (``solve`` sends it to the one-mass solver, so
    it is called directly): the same motion to 1e-11 of its 0.5 m scale, the same rest."""
    net = Network(
        [Mass("m", 1.0, x0)],
        [Spring("k", ("ground", "m"), 100.0), Bingham("d", ("ground", "m"), 1.0, gamma)],
        [Load("m", force)] if force else [],
    )
    tr = solve_exact_network(net, 3.0, 1e-3)
    one = L.solve(L.Problem(net, 3.0), 1e-3, method="exact")
    assert all(hasattr(e, "x") for e in one.events)  # the one-mass path's events
    assert np.max(np.abs(tr.positions - one.positions)) <= 1e-11 * 0.5
    assert np.max(np.abs(tr.forces - one.forces)) <= 1e-9 * 50.0
    np.testing.assert_allclose(tr.final_rest[1], one.final_rest[1], rtol=0, atol=1e-11)


# -- against closed forms --------------------------------------------------------------
def test_two_masses_on_springs_are_the_modal_solution() -> None:
    """No friction: ``x(t) = M^-1/2 Phi (cos(w t) a + sin(w t) b / w)`` from the eigenpairs
    of ``M^-1/2 K M^-1/2``; to 1e-12 of the amplitude."""
    m, k = np.array([1.0, 2.0]), (100.0, 150.0)
    net = Network(
        [Mass("a", m[0], 0.01, 2.0), Mass("b", m[1], 0.03, -1.0)],
        [Spring("k0", ("ground", "a"), k[0]), Spring("k1", ("a", "b"), k[1])],
    )
    tr = exact(net, 2.0)
    stiff = np.array([[k[0] + k[1], -k[1]], [-k[1], k[1]]])
    root = np.diag(m**-0.5)
    lam, phi = np.linalg.eigh(root @ stiff @ root)
    w = np.sqrt(lam)
    a, b = phi.T @ (m**0.5 * np.array([0.01, 0.03])), phi.T @ (m**0.5 * np.array([2.0, -1.0]))
    modal = (root @ phi @ (np.cos(np.outer(w, tr.t)) * a[:, None] + np.sin(np.outer(w, tr.t)) * (b / w)[:, None])).T
    assert np.max(np.abs(tr.positions - modal)) <= 1e-12 * np.max(np.abs(modal))


def test_a_glued_pair_moves_as_one_mass() -> None:
    """A Coulomb element that never slips joins two masses into one of their sum."""
    net = Network(
        [Mass("a", 0.4, 0.0), Mass("b", 0.6, 0.0)],
        [
            Spring("k", ("ground", "a"), 100.0),
            Bingham("d", ("ground", "a"), 1.0, 1.0),
            Bingham("glue", ("a", "b"), 1e3, math.inf),
        ],
        [Load("b", FORCE)],
    )
    tr = exact(net, 2.5)
    one = L.solve_exact(L.Oscillator.bingham(1.0, 100.0, 1.0, 1.0), 2.5, force=FORCE)
    assert tr.rigid[1:, 2].all()
    assert np.max(np.abs(tr.positions - one.evaluate(tr.t)["x"][:, None])) <= 1e-11 * 0.1
    np.testing.assert_allclose(tr.final_rest[0], one.rest_time, rtol=0, atol=1e-11)


@pytest.mark.parametrize("start", [0.0, 0.25])
def test_a_coulomb_pair_under_a_constant_load_rests_at_the_closed_form(start: float) -> None:
    """A glued pair (M = 1 kg) on a spring k and a Coulomb pad tau, a constant load P with
    tau < P < 3 tau from ``start``: it moves for half a period ``pi sqrt(M/k)`` and stops
    at ``2 (P - tau)/k`` for good (the spring's pull back, ``P - 2(P - tau)``, lies in the band)."""
    k, tau, p = 100.0, 1.0, 2.5
    net = Network(
        [Mass("a", 0.3), Mass("b", 0.7)],
        [
            Spring("k", ("ground", "a"), k),
            Bingham("pad", ("ground", "a"), tau, math.inf),
            Bingham("g", ("a", "b"), 9.0, math.inf),
        ],
        [Load("b", L.Constant(p, start))],
    )
    tr = exact(net, 1.0)
    np.testing.assert_allclose(tr.final_rest[0], start + math.pi * math.sqrt(1.0 / k), rtol=0, atol=1e-12)
    np.testing.assert_allclose(tr.final_rest[1], 2 * (p - tau) / k, rtol=1e-13, atol=0)
    assert [e.kind for e in tr.events] == (["switch"] if start else []) + ["stop"]


def test_a_linear_dashpot_between_masses_is_the_linear_ode() -> None:
    """Springs, a viscous dashpot and a sine: ``M x'' + C x' + K x = F(t)``, by DOP853 at rtol 1e-12."""
    m = np.array([1.0, 1.5])
    net = Network(
        [Mass("a", m[0], 0.05), Mass("b", m[1])],
        [Spring("k0", ("ground", "a"), 100.0), Spring("k1", ("a", "b"), 60.0), L.LinearDashpot("c", ("a", "b"), 2.0)],
        [Load("b", L.SwitchedSine(3.0, 9.0, 0.2, 0.8))],
    )
    stiff, damp = np.array([[160.0, -60.0], [-60.0, 60.0]]), np.array([[2.0, -2.0], [-2.0, 2.0]])

    def rhs(t: float, y: np.ndarray) -> np.ndarray:
        f = np.array([0.0, 3.0 * math.sin(9.0 * t + 0.2) if t <= 0.8 else 0.0])
        return np.concatenate([y[2:], (f - stiff @ y[:2] - damp @ y[2:]) / m])

    tr = exact(net, 0.8)
    y = solve_ivp(rhs, (0.0, 0.8), [0.05, 0.0, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-15, t_eval=tr.t).y
    assert np.max(np.abs(tr.positions - y[:2].T)) <= 1e-10 * 0.05


# -- refusals ---------------------------------------------------------------------------
_BETWEEN = ("a", "b")


@pytest.mark.parametrize(
    ("element", "kind"),
    [
        (L.SpringString("s", _BETWEEN, 10.0, 1.0), "spring-string"),
        (L.MaxwellBingham("s", _BETWEEN, 10.0, 1.0, 1.0), "maxwell-bingham"),
        (L.LockingBingham("s", _BETWEEN, 1.0, 1.0, 1.0), "locking-bingham"),
        (L.HerschelBulkley("s", _BETWEEN, 1.0, 1.0, 2.0), "herschel-bulkley"),
        (L.Monotone("s", _BETWEEN, L.HerschelBulkleyDashpot(1.0, 1.0, 0.5)), "monotone"),
    ],
)
def test_exact_refuses_an_element_without_a_closed_form_in_one_line(element: L.Element, kind: str) -> None:
    net = Network([Mass("a", 1.0, 0.1), Mass("b", 1.0)], [Spring("k", ("ground", "a"), 10.0), element])
    message = f"^method 'exact' cannot run element 's' of kind '{kind}': its closed forms per phase need linear springs"
    with pytest.raises(ValueError, match=message):
        exact(net, 0.1)


def test_exact_refuses_a_table_load_in_one_line() -> None:
    net = chain(2, 1.0, 1.0)
    net = Network(net.masses, net.elements, [Load("m1", L.Table([0.0, 1.0], [0.0, 1.0]))])
    with pytest.raises(
        ValueError, match="^method 'exact' cannot run the load on 'm1', a table: it runs linear springs"
    ):
        exact(net, 0.1)


# -- backward Euler's order on a network, against exact ---------------------------------
def test_backward_euler_is_first_order_on_a_chain_against_exact(capsys: pytest.CaptureFixture[str]) -> None:
    """The 3-mass Coulomb chain under the sine: max |x - x_exact| on the grid, and the slope of
    its logarithm on log(dt).  Band 0.8..1.2 as in test_network_references (first order, its
    constant settled at these steps, room for the kinks where stick phases start a step early or late)."""
    net, t_end = CHAINS["3-coulomb-forced"]
    steps = np.array([2e-3, 1e-3, 5e-4, 2.5e-4])
    errors = []
    for dt in steps:
        be, ex = L.solve(L.Problem(net, t_end), dt), exact(net, t_end, dt)
        errors.append(float(np.max(np.abs(be.positions - ex.positions))))
    with capsys.disabled():
        print("\nbackward Euler on the 3-mass Coulomb chain against exact:")
        for dt, err in zip(steps, errors):
            print(f"  dt = {dt:.2e}  max |x - x_exact| = {err:.3e}  err/dt = {err / dt:.3f}")
        print(f"  fitted order {order(steps, np.array(errors)):.3f}")
    assert 0.8 <= order(steps, np.array(errors)) <= 1.2


def test_exact_refuses_a_loop_of_elements_that_can_stick_together():
    """Two Coulomb pads on one mass: the motion is unique, their split is not; exact says so, backward Euler runs it."""
    pads = L.Network(
        [L.Mass("m", 1.0, 0.5)],
        [
            L.Spring("k", ("ground", "m"), 100.0),
            L.Bingham("p1", ("ground", "m"), 4.0, math.inf),
            L.Bingham("p2", ("ground", "m"), 2.0, math.inf),
        ],
    )
    message = r"^method 'exact' cannot run elements 'p1', 'p2': they close a loop of elements that can stick together"
    with pytest.raises(ValueError, match=message):
        L.solve(L.Problem(pads, 1.0), 1e-3, method="exact")
    assert L.solve(L.Problem(pads, 1.0), 1e-3).force_min is not None  # backward Euler reports the intervals
