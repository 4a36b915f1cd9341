"""Networks (issue 9): the paper's system as a network, each element kind against
an independent reference, observed order 1, invariants and well-posedness."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import EPS
from references import order
from scipy.integrate import solve_ivp

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
from lumped.studies import examples

PAPER = examples.paper()


def paper_network(run: examples.Example) -> Network:
    osc = run.oscillator
    return Network(
        [Mass("m1", osc.mass, run.x0, run.v0)],
        [
            Spring("spring", ("ground", "m1"), osc.stiffness),
            Bingham("dashpot", ("ground", "m1"), osc.threshold, osc.dashpot.gamma),
        ],
        [Load("m1", run.force)] if run.force else [],
    )


# -- the paper's system --------------------------------------------------------
@pytest.mark.parametrize("name", list(PAPER))
def test_paper_network_is_algorithm1_bit_for_bit(name: str) -> None:
    """The default path hands the paper's system to Algorithm 1: identical arrays."""
    run = PAPER[name]
    tr, net = run.algorithm1(), simulate_network(paper_network(run), run.t_end, run.dt)
    assert net.solver == "algorithm1"
    assert np.array_equal(net.positions[:, 0], tr.x) and np.array_equal(net.velocities[:, 0], tr.v)
    assert np.array_equal(net.forces, np.column_stack([tr.F_s, tr.F_d]))
    assert net.rest_times[0] == tr.rest_time or (np.isnan(net.rest_times[0]) and np.isnan(tr.rest_time))


def _compare_active_set(run: examples.Example, dt: float, solver: str = "python") -> None:
    """The active-set step (``solver``: the Python step or the compiled one) against Algorithm 1.

    The merged system of one mass is the scalar ``v = ((m/dt v_n + F - F_s) -
    s tau) / ((m/dt + dt k) + c)``, Algorithm 1's line 8/9 with the same
    operations in the same order, and a sticking step's force is the
    predictor ``F~`` itself; so velocities and spring forces agree bit for bit
    (asserted), unless a mode test falls within an ulp of the threshold (it
    does not on these runs).  Then only two things differ: the position,
    accumulated ``x + dt v`` instead of ``F_s / k``: each step rounds each by
    at most ``eps/2`` of its size and the increments ``dt v`` and ``dt k v / k``
    differ by 2 roundings, so ``|dx_n| <= eps (n max|x| + 2 sum dt|v|)``; and
    the slipping dashpot force, ``s tau + c v`` instead of line 8's quotient:
    both are within 2 roundings of the same number, ``|dF_d| <= 4 eps (|F_d|
    + tau + c eta |v|)``.
    """
    osc = run.oscillator
    tr = run.algorithm1(dt)
    net = simulate_network(paper_network(run), run.t_end, dt, solver=solver)
    assert net.solver == solver
    assert np.array_equal(net.velocities[:, 0], tr.v) and np.array_equal(net.states[:, 0], tr.F_s)
    n = np.arange(tr.t.size)
    bound_x = EPS * (n * np.max(np.abs(tr.x)) + 2 * np.cumsum(dt * np.abs(tr.v)))
    assert np.all(np.abs(net.positions[:, 0] - tr.x) <= bound_x)
    eta, c = osc.mass / dt + osc.stiffness * dt, osc.dashpot.viscosity
    bound_f = 4 * EPS * (np.abs(tr.F_d) + osc.threshold + c * eta * np.abs(tr.v))
    assert np.all(np.abs(net.forces[1:, 1] - tr.F_d[1:]) <= bound_f[1:])
    assert net.forces[0, 1] == tr.F_d[0]  # the consistent initial force, the same rule


@pytest.mark.parametrize("name", ["forced_large", "free_large"])
def test_active_set_step_reproduces_algorithm1_coarse(name: str) -> None:
    _compare_active_set(PAPER[name], 1e-3)


@pytest.mark.slow
@pytest.mark.parametrize("name", list(PAPER))
def test_active_set_step_reproduces_algorithm1_paper_runs(name: str) -> None:
    _compare_active_set(PAPER[name], PAPER[name].dt)


# -- the spring-string against its exact piecewise solution --------------------
def string_motion(t: np.ndarray, k: float, length: float, v0: float) -> np.ndarray:
    """Exact motion of a unit mass on a spring-string to the ground from x = 0, v = v0 > 0.

    Harmonic ``x = (v0/w) sin(w t)`` until it reaches ``L`` at ``t*`` (if
    ``v0/w > L``); the impact stops it (inelastic), and the spring pulls it
    back, ``x = L cos(w (t - t*))``, touching ``L`` again only with zero speed.
    """
    w = math.sqrt(k)
    amp = v0 / w
    if amp <= length:
        return amp * np.sin(w * t)
    hit = math.asin(length / amp) / w
    return np.where(t <= hit, amp * np.sin(w * t), length * np.cos(w * (t - hit)))


def string_network(v0: float, k: float = 100.0, length: float = 0.05) -> Network:
    return Network([Mass("m", 1.0, 0.0, v0)], [SpringString("s", ("ground", "m"), k, length)])


@pytest.mark.parametrize("v0", [0.4, 1.0], ids=["no-impact", "impact"])
def test_spring_string_converges_at_order_one(v0: float) -> None:
    """Backward Euler's error at t = 0.5 s (after the impact) falls as dt^1."""
    dts = np.array([1e-3, 5e-4, 2.5e-4, 1.25e-4])
    errors = []
    for dt in dts:
        tr = simulate_network(string_network(v0), 0.5, dt)
        errors.append(np.max(np.abs(tr.positions[:, 0] - string_motion(tr.t, 100.0, 0.05, v0))))
    # the slope of a first-order method whose error constant settles: within 0.1 of 1
    assert 0.9 <= order(dts, np.array(errors)) <= 1.1


def test_spring_string_impact_is_inelastic_and_exactly_taut() -> None:
    tr = simulate_network(string_network(1.0), 0.3, 1e-4)
    taut = tr.rigid[:, 0]
    assert taut.any()
    assert np.all(tr.states[taut, 0] == 0.05)  # exactly at length, not recomputed
    first = int(np.argmax(taut))
    assert tr.velocities[first + 1, 0] <= 0  # no bounce: the relative motion stops
    # energy after the impact: what remains is the spring's k L^2 / 2 (less the scheme's loss)
    assert tr.forces[first, 0] >= 100.0 * 0.05


# -- the Maxwell element against a high-accuracy integration -------------------
def maxwell_reference(t_end: float, k_m: float, tau: float, gamma: float, x0: float) -> callable:
    """Unit mass, a spring (k = 100) and a Maxwell-Bingham element to the ground.

    With a finite gamma the dashpot's law w = phi(f) is Lipschitz, so the
    system x' = v, v' = -100 x - f, f' = k_m (v - phi(f)) is an ODE with a
    Lipschitz right-hand side: DOP853 at rtol 1e-12 is an independent reference.
    """

    def rhs(t, y):
        x, v, f = y
        phi = math.copysign(gamma * max(abs(f) - tau, 0.0), f)
        return [v, -100.0 * x - f, k_m * (v - phi)]

    sol = solve_ivp(rhs, (0, t_end), [x0, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    return sol.sol


def test_maxwell_bingham_converges_at_order_one() -> None:
    k_m, tau, gamma, x0, t_end = 50.0, 0.5, 2.0, 0.3, 1.0
    ref = maxwell_reference(t_end, k_m, tau, gamma, x0)
    net = Network(
        [Mass("m", 1.0, x0)],
        [Spring("k", ("ground", "m"), 100.0), MaxwellBingham("mx", ("ground", "m"), k_m, tau, gamma)],
    )
    dts = np.array([2e-3, 1e-3, 5e-4, 2.5e-4])
    errors = []
    for dt in dts:
        tr = simulate_network(net, t_end, dt)
        exact = ref(tr.t)
        errors.append(
            max(np.max(np.abs(tr.positions[:, 0] - exact[0])), np.max(np.abs(tr.forces[:, 1] - exact[2])) / 100.0)
        )
    assert 0.9 <= order(dts, np.array(errors)) <= 1.1
    assert errors[-1] < 1e-2


# -- chains -------------------------------------------------------------------
def chain(n: int, gamma: float, force: L.SwitchedSine | None = None) -> Network:
    masses = [Mass(f"m{i}", 1.0 + 0.5 * i, 0.1 * (i + 1)) for i in range(n)]
    elements = []
    for i in range(n):
        a = "ground" if i == 0 else f"m{i - 1}"
        elements.append(Spring(f"k{i}", (a, f"m{i}"), 100.0 + 20 * i))
        elements.append(Bingham(f"b{i}", (a, f"m{i}"), 1.0, gamma))
    loads = [Load(f"m{n - 1}", force)] if force else []
    return Network(masses, elements, loads)


F = L.SwitchedSine(10.0, 5 * math.pi, 0.0, 1.0)


def test_stuck_pair_moves_as_one_mass() -> None:
    """Two masses joined by a Coulomb element that never slips are one mass m1 + m2:
    Algorithm 1 on the merged mass agrees, to roundings propagated by a
    non-expansive step (N steps of a few eps of the largest state)."""
    net = Network(
        [Mass("a", 0.4, 0.5), Mass("b", 0.6, 0.5)],
        [
            Spring("k", ("ground", "a"), 100.0),
            Bingham("d", ("ground", "a"), 1.0, 1.0),
            Bingham("glue", ("a", "b"), 1e6, math.inf),
        ],
    )
    tr = simulate_network(net, 4.0, 1e-3)
    ref = L.backward_euler(L.Oscillator.bingham(1.0, 100.0, 1.0, 1.0), 4.0, 1e-3, x0=0.5)
    assert np.all(tr.velocities[:, 0] == tr.velocities[:, 1])  # exactly together
    bound = tr.t.size * 8 * EPS * (np.max(np.abs(ref.v)) + 10 * np.max(np.abs(ref.x)))
    assert np.max(np.abs(tr.velocities[:, 0] - ref.v)) <= bound
    assert np.max(np.abs(tr.positions[:, 0] - ref.x)) <= bound


# -- invariants -----------------------------------------------------------------
def energy_residual(tr) -> tuple[np.ndarray, np.ndarray]:
    """Per step: the balance dKE + m(dv)^2/2 + dt sum f w - dt F.v, and each element's
    dissipation dt f w - d(stored) (>= 0: physical, the scheme's and the impacts')."""
    net, dt = tr.network, tr.dt
    m = np.array([mm.mass for mm in net.masses])
    first, second = net.incidence()
    vg = np.column_stack([tr.velocities, np.zeros(tr.t.size)])
    w = vg[:, second] - vg[:, first]
    loads = net.load_table(tr.t)
    dv = np.diff(tr.velocities, axis=0)
    kin = 0.5 * m * (tr.velocities[1:] ** 2 - tr.velocities[:-1] ** 2) + 0.5 * m * dv**2
    work = dt * np.sum(tr.forces[1:] * w[1:], axis=1)
    balance = kin.sum(axis=1) + work - dt * np.sum(loads[1:] * tr.velocities[1:], axis=1)
    stored = np.array([[el.stored_energy(s) for el, s in zip(net.elements, row)] for row in tr.states])
    removed = dt * tr.forces[1:] * w[1:] - np.diff(stored, axis=0)
    return balance, removed


def check_invariants(tr) -> None:
    net = tr.network
    first, second = net.incidence()
    vg = np.column_stack([tr.velocities, np.zeros(tr.t.size)])
    w = vg[:, second] - vg[:, first]
    for e, el in enumerate(net.elements):
        held = tr.rigid[:, e]
        if isinstance(el, Bingham):
            assert np.all(w[held, e] == 0.0), el.name  # sticking: exactly still
            assert np.all(np.abs(tr.forces[held, e]) <= el.threshold * (1 + 4 * EPS))
        if isinstance(el, SpringString):
            assert np.all(tr.states[held, e] == el.length)  # taut: exactly at length
            assert np.all(tr.states[:, e] <= el.length)
    balance, removed = energy_residual(tr)
    scale = np.max(np.abs(tr.forces)) * np.max(np.abs(tr.velocities)) * tr.dt + np.max(
        np.array([mm.mass for mm in net.masses])
    ) * np.max(tr.velocities**2)
    assert np.max(np.abs(balance)) <= 64 * EPS * scale * len(net.elements)
    assert np.min(removed) >= -64 * EPS * scale


@pytest.mark.parametrize("gamma", [1.0, math.inf])
def test_chain_invariants(gamma: float) -> None:
    check_invariants(simulate_network(chain(3, gamma, F), 2.5, 1e-3))


def test_string_invariants() -> None:
    net = Network(
        [Mass("a", 1.0, 0.0, 2.0), Mass("b", 2.0)],
        [
            SpringString("s1", ("ground", "a"), 50.0, 0.1),
            SpringString("s2", ("a", "b"), 80.0, 0.05),
            LinearDashpot("d", ("ground", "b"), 0.5),
        ],
    )
    tr = simulate_network(net, 2.0, 1e-3)
    assert tr.rigid[:, 0].any() and tr.rigid[:, 1].any()
    check_invariants(tr)


# -- other kinds ------------------------------------------------------------------
def test_locking_bingham_never_exceeds_its_lock() -> None:
    net = Network(
        [Mass("m", 1.0, 0.5)],
        [Spring("k", ("ground", "m"), 100.0), LockingBingham("lock", ("ground", "m"), 1.0, math.inf, 2.0)],
    )
    tr = simulate_network(net, 2.0, 1e-3)
    assert np.max(np.abs(tr.velocities)) == 2.0  # reached, exactly, never passed
    locked = tr.rigid[:, 1] & (np.abs(tr.velocities[:, 0]) == 2.0)
    assert locked.any() and np.all(np.abs(tr.forces[locked, 1]) >= 1.0)


def test_linear_dashpot_matches_the_monotone_law() -> None:
    """A linear dashpot and the same law as a Monotone element give the same motion."""
    law = L.MonotoneDashpot(lambda f: 0.5 * f)
    nets = [
        Network([Mass("m", 1.0, 0.5)], [Spring("k", ("ground", "m"), 100.0), d])
        for d in (LinearDashpot("d", ("ground", "m"), 2.0), Monotone("d", ("ground", "m"), law))
    ]
    a, b = (simulate_network(n, 1.0, 1e-3) for n in nets)
    assert np.max(np.abs(a.x - b.x)) <= 1e-12


def test_monotone_element_matches_the_generic_loop() -> None:
    law = L.MonotoneDashpot(lambda f: math.copysign(max(abs(f) - 1.0, 0.0) ** 2, f), threshold=1.0)
    net = Network([Mass("m", 1.0, 0.5)], [Spring("k", ("ground", "m"), 100.0), Monotone("d", ("ground", "m"), law)])
    tr = simulate_network(net, 1.0, 1e-3)
    ref = L.backward_euler(L.Oscillator(1.0, L.LinearSpring(100.0), law), 1.0, 1e-3, x0=0.5)
    assert np.max(np.abs(tr.velocities[:, 0] - ref.v)) <= 1e-10


# -- well-posedness -------------------------------------------------------------------
def test_parallel_rigid_elements_run() -> None:
    """Two Coulomb elements in parallel, once refused (issue 21): the motion is unique."""
    net = Network(
        [Mass("m", 1.0, 0.3)],
        [
            Spring("k", ("ground", "m"), 10.0),
            Bingham("b1", ("ground", "m"), 1.0, math.inf),
            Bingham("b2", ("m", "ground"), 2.0, 1.0),
        ],
    )
    tr = simulate_network(net, 0.5, 1e-3)
    assert tr.solver == "python" and np.isfinite(tr.positions).all()


@pytest.mark.parametrize(
    "law, rigid",
    [(L.BinghamDashpot(5.0, 1.0), True), (L.MonotoneDashpot(lambda f: f), False)],
    ids=["banded-law", "no-band"],
)
def test_a_law_with_a_static_band_is_rigid_capable(law: L.Dashpot, rigid: bool) -> None:
    """A Monotone element whose law holds a range of forces at rest sticks like a Bingham
    element; beside a string it closes a loop that may be rigid, no longer refused.  (Run
    here to 0.15 s, before the string goes taut: the impact step of a string beside a law
    element, banded or not, does not settle within the iteration's bound, as before.)"""
    net = Network(
        [Mass("m", 1.0, -0.5)],
        [SpringString("s", ("ground", "m"), 100.0, 0.2), Monotone("d", ("ground", "m"), law=law)],
    )
    assert net.elements[1].rigid_capable is rigid
    assert np.isfinite(simulate_network(net, 0.15, 1e-3).positions).all()


def test_ring_through_masses_runs() -> None:
    """A ring of rigid-capable elements through two masses and the ground, once refused."""
    net = Network(
        [Mass("a", 1.0, 0.1), Mass("b", 1.0)],
        [
            Bingham("c1", ("ground", "a"), 1.0, math.inf),
            Bingham("c2", ("a", "b"), 1.0, 1.0),
            SpringString("c3", ("b", "ground"), 1.0, 1.0),
            Spring("k", ("ground", "a"), 10.0),
        ],
    )
    tr = simulate_network(net, 1.0, 1e-3)
    assert np.all(tr.velocities[-1] == 0)


def test_series_coulomb_through_a_mass_is_well_posed() -> None:
    net = Network(
        [Mass("a", 1e-3), Mass("b", 1.0, 0.2)],
        [
            Bingham("c1", ("ground", "a"), 1.0, math.inf),
            Bingham("c2", ("a", "b"), 1.0, math.inf),
            Spring("k", ("ground", "b"), 100.0),
        ],
    )
    check_invariants(simulate_network(net, 1.0, 1e-3))
