"""Rigid elements closing loops (issue 21): solved, not refused.

The velocities of a step are the unique minimiser of a strictly convex
potential; only the split of force among rigid elements in a loop is not
unique.  Checked here: the motion against an independent minimisation of each
step's potential (SciPy's SLSQP) and against the equivalent single pad; each
step's optimality conditions; the intervals of admissible forces against the
hand calculation; the least-norm representative; the one refusal that is left.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import linprog, minimize

import lumped as L
from lumped import (
    Bingham,
    LinearDashpot,
    Load,
    LockingBingham,
    Mass,
    Network,
    Spring,
    SpringString,
    simulate_network,
)
from lumped.laws.step_graph import bingham_band, rigid_piece
from lumped.solvers.loop_forces import core_forces
from lumped.solvers.network_step import StepError, solve_step

EPS = np.finfo(float).eps
FORCE = L.SwitchedSine(30.0, 7.0, 0.3, 1.2)


def pads(tau1: float, tau2: float, reverse: bool = False) -> Network:
    """A mass on a spring with two Coulomb pads to the ground (the second reversed if asked)."""
    second = ("m", "ground") if reverse else ("ground", "m")
    return Network(
        [Mass("m", 1.0, 0.5)],
        [
            Spring("k", ("ground", "m"), 100.0),
            Bingham("c1", ("ground", "m"), tau1, math.inf),
            Bingham("c2", second, tau2, math.inf),
        ],
        [Load("m", FORCE)],
    )


def figure2_bingham() -> Network:
    """The paper's Figure 2 (a spring with a string) beside its Bingham dashpot, both to the ground."""
    return Network(
        [Mass("m", 1.0, -0.5)],
        [SpringString("s", ("ground", "m"), 100.0, 0.2), Bingham("d", ("ground", "m"), 5.0, 1.0)],
    )


def ring(n: int, tau: float = 1.0) -> Network:
    """Masses in a ring through the ground, each link a spring beside a Coulomb element, one
    forced; with ``tau = 8`` it is stuck all round (a rigid loop) on some steps of the first 0.6 s."""
    points = ["ground", *(f"m{i}" for i in range(n)), "ground"]
    elements = []
    for i, (a, b) in enumerate(zip(points, points[1:])):
        elements += [Spring(f"k{i}", (a, b), 50.0 + 10 * i), Bingham(f"c{i}", (a, b), tau + 0.5 * i, math.inf)]
    masses = [Mass(f"m{i}", 1.0 + 0.25 * i, 0.05 * (i + 1)) for i in range(n)]
    return Network(masses, elements, [Load("m0", FORCE)])


def locked_pair() -> Network:
    """A locking dashpot beside a sticking Bingham element and a string: hard and soft rigid pieces in one loop."""
    return Network(
        [Mass("m", 1.0, 0.0, 3.0)],
        [
            LockingBingham("l", ("ground", "m"), 1.0, 2.0, 1.0),
            Bingham("b", ("ground", "m"), 10.0, 1.0),
            SpringString("s", ("m", "ground"), 10.0, 0.3),
            LinearDashpot("d", ("ground", "m"), 0.5),
        ],
        [Load("m", FORCE)],
    )


def hard_pairs() -> Network:
    """Two strings of different lengths and a string beside a lock, in parallel: loops of hard
    rigid pieces (one edge of their band infinite) whose rates may disagree in an iteration."""
    return Network(
        [Mass("m", 1.0, 0.0, 2.0), Mass("n", 1.0, 0.0, 3.0)],
        [
            SpringString("s1", ("ground", "m"), 50.0, 0.1),
            SpringString("s2", ("ground", "m"), 80.0, 0.15),
            Bingham("b", ("ground", "m"), 1.0, math.inf),
            SpringString("s3", ("m", "n"), 50.0, 0.1),
            LockingBingham("l", ("m", "n"), 0.5, math.inf, 1.0),
        ],
        [Load("m", FORCE)],
    )


LOOPS = {
    "pads": pads(4.0, 2.0),
    "figure2": figure2_bingham(),
    "ring": ring(3, 8.0),
    "locked": locked_pair(),
    "hard-pairs": hard_pairs(),
}


# -- an independent solution of each step -------------------------------------------
def _terms(net: Network, state: np.ndarray, dt: float):
    """Per element: (kind, parameters) of its step potential in the rate w (see ``potential``)."""
    out = []
    for el, s in zip(net.elements, state):
        if el.kind == "spring":
            out.append(("quad", s, dt * el.stiffness, -math.inf, math.inf, 0.0))
        elif el.kind == "spring-string":
            out.append(("quad", el.stiffness * s, dt * el.stiffness, -math.inf, (el.length - s) / dt, 0.0))
        elif el.kind == "dashpot":
            out.append(("quad", 0.0, el.damping, -math.inf, math.inf, 0.0))
        elif el.kind == "bingham":
            out.append(("quad", 0.0, el.viscosity, -math.inf, math.inf, el.threshold))
        elif el.kind == "locking-bingham":
            c = 0.0 if math.isinf(el.gamma) else 1.0 / el.gamma
            out.append(("quad", 0.0, c, -el.v_lock, el.v_lock, el.threshold))
        else:
            raise AssertionError(el.kind)
    return out


def potential(v, d, r, terms, first, second, walls: float = 0.0) -> float:  # noqa: ANN001
    """``sum d v^2/2 - r v + sum_e (a w + b w^2/2 + tau |w|)`` with ``lo <= w <= hi`` (else inf)."""
    va = np.append(v, 0.0)
    w = va[second] - va[first]
    total = 0.5 * np.dot(d * v, v) - np.dot(r, v)
    for we, (_, a, b, lo, hi, tau) in zip(w, terms):
        if we < lo - walls or we > hi + walls:
            return math.inf
        total += a * we + 0.5 * b * we * we + tau * abs(we)
    return total


def scipy_step(d, r, terms, first, second):  # noqa: ANN001
    """The step's minimiser by SLSQP: variables v and, per element, p, q >= 0 with w = p - q."""
    n, m = d.size, len(terms)
    rate = np.zeros((m, n + 2 * m))  # w = rate[:, :n] @ v, the ground left out
    for e, (i, j) in enumerate(zip(first, second)):
        if j < n:
            rate[e, j] += 1.0
        if i < n:
            rate[e, i] -= 1.0
    link = rate.copy()
    link[:, n : n + m], link[:, n + m :] = -np.eye(m), np.eye(m)  # w - (p - q) = 0
    a, b, tau = (np.array([t[k] for t in terms], dtype=float) for k in (1, 2, 5))

    def f(z):  # noqa: ANN001
        v, p, q = z[:n], z[n : n + m], z[n + m :]
        w = p - q
        return 0.5 * np.dot(d * v, v) - np.dot(r, v) + np.sum(a * w + 0.5 * b * w * w + tau * (p + q))

    def grad(z):  # noqa: ANN001
        v, w = z[:n], z[n : n + m] - z[n + m :]
        return np.concatenate([d * v - r, a + b * w + tau, -(a + b * w) + tau])

    cons = [{"type": "eq", "fun": lambda z: link @ z, "jac": lambda z: link}]
    for e, t in enumerate(terms):
        if math.isfinite(t[4]):
            cons.append(
                {"type": "ineq", "fun": lambda z, e=e, hi=t[4]: hi - rate[e] @ z, "jac": lambda z, e=e: -rate[e]}
            )
        if math.isfinite(t[3]):
            cons.append(
                {"type": "ineq", "fun": lambda z, e=e, lo=t[3]: rate[e] @ z - lo, "jac": lambda z, e=e: rate[e]}
            )
    start = np.concatenate([r / d, np.zeros(2 * m)])
    bounds = [(None, None)] * n + [(0, None)] * (2 * m)
    options = {"ftol": 1e-15, "maxiter": 1000}
    res = minimize(f, start, jac=grad, method="SLSQP", bounds=bounds, constraints=cons, options=options)
    return res.x[:n]


def feasible(v: np.ndarray, terms, first, second) -> np.ndarray:  # noqa: ANN001
    """``v`` scaled towards 0 (which meets every wall, ``lo <= 0 <= hi``) until it meets them all."""
    w = np.append(v, 0.0)[second] - np.append(v, 0.0)[first]
    t = 1.0
    for we, (_, _, _, lo, hi, _) in zip(w, terms):
        t = min(t, hi / we if we > hi else lo / we if we < lo else 1.0)
    return v * t


@pytest.mark.parametrize("name", list(LOOPS))
def test_every_step_is_the_minimiser_of_its_potential(name: str) -> None:
    """Each step of a short run against SLSQP on the same potential ``Phi``.

    ``Phi`` is strongly convex with modulus ``mu = min m/dt``: any admissible
    ``v_s`` lies within ``sqrt(2 (Phi(v_s) - Phi(v*)) / mu)`` of the minimiser
    ``v*``.  SLSQP's point, made admissible (:func:`feasible`), must so be no
    better than ours, and within that distance of ours; the slack is the
    rounding of evaluating ``Phi`` (64 eps of its largest term).
    """
    net, dt = LOOPS[name], 2e-3
    tr = simulate_network(net, 0.6, dt)
    first, second = net.incidence()
    d = np.array([m.mass / dt for m in net.masses])
    for n in range(1, tr.t.size):
        r = d * tr.velocities[n - 1] + tr.applied[n]
        terms = _terms(net, tr.states[n - 1], dt)
        ours = tr.velocities[n]
        theirs = feasible(scipy_step(d, r, terms, first, second), terms, first, second)
        phi_ours = potential(ours, d, r, terms, first, second, walls=8 * EPS * np.abs(ours).max())
        phi_theirs = potential(theirs, d, r, terms, first, second, walls=8 * EPS * np.abs(theirs).max())
        size = np.abs(r).max() * (np.abs(ours).max() + np.abs(theirs).max()) + d.max() * np.abs(ours).max() ** 2
        slack = 64 * EPS * (size + abs(phi_ours))
        assert phi_ours <= phi_theirs + slack, n
        assert np.max(np.abs(ours - theirs)) <= math.sqrt(2 * (phi_theirs - phi_ours + slack) / d.min()), n


@pytest.mark.parametrize("name", list(LOOPS))
def test_every_step_meets_its_optimality_conditions(name: str) -> None:
    """Every case has steps whose forces are not unique; on every step, the momentum balance of every mass closes to rounding with the reported
    (least-norm) forces, and every force lies in its element's interval, which
    lies on the element's graph."""
    net, dt = LOOPS[name], 2e-3
    tr = simulate_network(net, 0.6, dt)
    first, second = net.incidence()
    d = np.array([m.mass / dt for m in net.masses])
    low, high = tr.force_min, tr.force_max
    assert np.any(low != high)
    for n in range(1, tr.t.size):
        r = d * tr.velocities[n - 1] + tr.applied[n]
        pushed = np.zeros(len(net.masses) + 1)
        np.add.at(pushed, second, tr.forces[n])
        np.add.at(pushed, first, -tr.forces[n])
        residual = d * tr.velocities[n] + pushed[:-1] - r
        scale = np.abs(d * tr.velocities[n]).max() + np.abs(tr.forces[n]).max() + np.abs(r).max()
        assert np.max(np.abs(residual)) <= 64 * EPS * scale, n
        assert np.all(low[n] <= tr.forces[n]) and np.all(tr.forces[n] <= high[n])
        va = np.append(tr.velocities[n], 0.0)
        for e, el in enumerate(net.elements):
            if tr.rigid[n, e] and el.kind in ("bingham", "locking-bingham"):  # graphs of the rate alone
                lo, hi = el.force_interval(0.0, va[second[e]] - va[first[e]])
                assert lo <= low[n, e] and high[n, e] <= hi, (n, e)


# -- two pads on one mass --------------------------------------------------------------
@pytest.mark.parametrize("reverse", [False, True], ids=["same-way", "reversed"])
@pytest.mark.parametrize("held", [0.3, 1.2, -1.4, 1.5, 0.75, -0.6])
def test_two_sticking_pads_share_the_held_force_as_the_hand_calculation(held: float, reverse: bool) -> None:
    """One mass held by two pads (tau1 = 1, tau2 = 0.5) under a force R: each pad's admissible
    force is what the other's threshold leaves, ``[max(-tau1, R - tau2), min(tau1, R + tau2)]``
    (a reversed pad's tension is the negative), bit for bit; the split is the least-norm one:
    ``R/2`` each until a pad's threshold stops it."""
    tau1, tau2 = 1.0, 0.5
    sign = -1.0 if reverse else 1.0
    second = [0, 1] if reverse else [0, 0]
    first = [1, 0] if reverse else [1, 1]
    sol = solve_step(
        first,
        second,
        np.array([10.0]),
        np.array([held]),
        [bingham_band(tau1, 0.0), bingham_band(tau2, 0.0)],
        np.array([10.0, 10.0]),
        ranges=True,
    )
    assert sol.v[0] == 0.0 and sol.rigid == [True, True]
    one = [max(-tau1, held - tau2), min(tau1, held + tau2)]
    two = [max(-tau2, held - tau1), min(tau2, held + tau1)]
    if one[0] == one[1]:  # R = tau1 + tau2: the split is unique
        assert sol.low is None and sol.high is None
        return
    assert [sol.low[0], sol.high[0]] == one
    assert sorted([sign * sol.low[1], sign * sol.high[1]]) == two
    split = min(max(held / 2, two[0]), two[1])  # both equal, then one at its threshold
    assert sol.f[1] * sign == split and sol.f[0] + sign * sol.f[1] == pytest.approx(held, abs=2 * EPS * held)


def test_two_pads_move_as_one_pad_of_the_summed_threshold() -> None:
    """Two Coulomb pads (4 N and 2 N) against Algorithm 1 with one pad of 6 N: the same
    stops (identical stick rows) and the same motion to the rounding of each step, summed
    over the steps (a step is non-expansive), ``8 eps`` of the largest force per step; while
    they stick the intervals are the hand calculation's with the held force ``R = F1 + F2``."""
    dt, t_end = 1e-3, 3.0
    tr = simulate_network(pads(4.0, 2.0), t_end, dt)
    osc = L.Oscillator.bingham(1.0, 100.0, 6.0, math.inf)
    ref = L.backward_euler(osc, t_end, dt, x0=0.5, force=FORCE)
    assert tr.solver == "python" and ref.x.size == tr.t.size
    assert np.array_equal(tr.velocities[:, 0] == 0, ref.v == 0)
    scale = np.abs(ref.F_s).max() + 30.0
    assert np.max(np.abs(tr.velocities[:, 0] - ref.v)) <= tr.t.size * 8 * EPS * scale
    stuck = (tr.velocities[:, 0] == 0) & (tr.t > 0)
    held = tr.forces[stuck, 1] + tr.forces[stuck, 2]
    assert stuck.sum() > 10
    bound = 4 * EPS * (np.abs(held) + 6.0)  # R = F1 + F2 is the step's held force to its rounding
    assert np.all(np.abs(tr.force_min[stuck, 1] - np.maximum(-4.0, held - 2.0)) <= bound)
    assert np.all(np.abs(tr.force_max[stuck, 1] - np.minimum(4.0, held + 2.0)) <= bound)
    assert tr.undetermined == [1, 2]


def test_three_pads_coupled_loops_against_the_hand_calculation() -> None:
    """Three pads in parallel (two coupled loops, the general path): intervals
    ``[max(-tau_j, R - sum of the others' tau), min(tau_j, R + ...)]`` and the least-norm
    split by water-filling (equal shares, the smallest threshold saturating first)."""
    taus, held = (0.25, 1.0, 2.0), 2.5
    sol = solve_step(
        [1, 1, 1],
        [0, 0, 0],
        np.array([10.0]),
        np.array([held]),
        [bingham_band(t, 0.0) for t in taus],
        np.array([10.0] * 3),
        ranges=True,
    )
    for j, tau in enumerate(taus):
        others = sum(taus) - tau
        assert sol.low[j] == pytest.approx(max(-tau, held - others), abs=8 * EPS * held)
        assert sol.high[j] == pytest.approx(min(tau, held + others), abs=8 * EPS * held)
    assert sol.f == pytest.approx([0.25, 1.0, 1.25], abs=8 * EPS * held)


@pytest.mark.parametrize("seed", range(4))
def test_coupled_loops_against_linear_programming(seed: int) -> None:
    """Two masses joined to each other and to the ground by five rigid elements (three coupled
    loops): each interval against linear programming (HiGHS) over the same polytope, and the
    least-norm split against SLSQP (to its 1e-7) and no larger in norm than SLSQP's."""
    rng = np.random.default_rng(seed)
    first, second = [2, 2, 0, 0, 2], [0, 0, 1, 1, 1]
    bands = {e: (-t, t) for e, t in enumerate(rng.uniform(0.5, 2.0, 5))}
    gap = [rng.uniform(-2, 2), rng.uniform(-2, 2), 0.0]
    out = core_forces(list(range(5)), first, second, bands, gap, 2, ranges=True)
    a_eq = np.zeros((2, 5))
    for e in range(5):
        for p, sign in ((second[e], 1.0), (first[e], -1.0)):
            if p < 2:
                a_eq[p, e] += sign
    box = [bands[e] for e in range(5)]
    assert out.feasible
    for e in range(5):
        unit = np.eye(5)[e]
        low = linprog(unit, A_eq=a_eq, b_eq=gap[:2], bounds=box)
        high = linprog(-unit, A_eq=a_eq, b_eq=gap[:2], bounds=box)
        assert out.low[e] == pytest.approx(low.fun, abs=1e-9) and out.high[e] == pytest.approx(-high.fun, abs=1e-9)
    cons = [{"type": "eq", "fun": lambda f: a_eq @ f - gap[:2]}]
    ref = minimize(lambda f: f @ f, np.zeros(5), method="SLSQP", bounds=box, constraints=cons, options={"ftol": 1e-15})
    f = np.array(out.force)
    assert np.max(np.abs(f - ref.x)) <= 1e-7 and f @ f <= ref.x @ ref.x + 1e-12
    assert np.max(np.abs(a_eq @ f - gap[:2])) <= 16 * EPS * 4


# -- the paper's Figure 2 beside the Bingham dashpot --------------------------------------
def test_figure2_beside_the_bingham_dashpot_runs_and_reports_the_split() -> None:
    """The string stops the mass at its length; on the step where it is taut while the
    dashpot sticks, the held force ``R`` is shared: the dashpot any force in its band, the
    string the rest, ``>= kL``; reported as intervals, the least-norm split in ``forces``."""
    tr = simulate_network(figure2_bingham(), 1.5, 1e-3)
    assert tr.undetermined == [0, 1]
    rows = np.flatnonzero((tr.force_min != tr.force_max).any(axis=1))
    assert rows.size > 0
    for r in rows:
        held = tr.forces[r].sum()  # the step's held force, to its rounding
        assert tr.rigid[r].all() and tr.velocities[r, 0] == 0.0 and held > 25.0
        assert tr.force_min[r, 1] == -5.0 and tr.force_max[r, 1] == pytest.approx(min(5.0, held - 20.0), rel=4 * EPS)
        assert [tr.force_min[r, 0], tr.force_max[r, 0]] == pytest.approx([held - 5.0, held + 5.0], rel=4 * EPS)
        assert tr.forces[r, 1] == pytest.approx(min(held / 2, 5.0), rel=4 * EPS)
    columns = tr.system_columns(".csv")
    assert list(columns)[3:] == ["F_s", "force_min_s", "force_max_s", "F_d", "force_min_d", "force_max_d", "load_m"]
    assert set(tr.system_columns(".npz")) >= {"force_min", "force_max"}


def test_unique_runs_have_no_interval_columns() -> None:
    """A ring that never sticks all round has unique forces: no interval columns."""
    tr = simulate_network(ring(3), 0.2, 1e-3)
    assert tr.force_min is None and "force_min" not in tr.system_columns(".npz")
    assert not any(name.startswith("force_") for name in tr.system_columns(".csv"))


def test_a_long_ring_of_coulomb_elements_runs() -> None:
    """Twelve Coulomb elements in a ring through eleven masses, at rest: every mass stays
    at rest (no load), every force 0, and each one's interval is the band left by the others."""
    n = 11
    points = ["ground", *(f"m{i}" for i in range(n)), "ground"]
    net = Network(
        [Mass(f"m{i}", 1.0) for i in range(n)],
        [Bingham(f"b{i}", (a, b), 1.0 + i, math.inf) for i, (a, b) in enumerate(zip(points, points[1:]))],
    )
    tr = simulate_network(net, 0.01, 1e-3)
    assert np.all(tr.velocities == 0) and np.all(tr.forces == 0)
    assert np.all(tr.force_min[1:] == -1.0) and np.all(tr.force_max[1:] == 1.0)  # the weakest element binds all


# -- what is still refused -------------------------------------------------------------
def test_rigid_pieces_whose_rates_disagree_are_refused_naming_them() -> None:
    """Two graphs each holding only a rigid piece, at rates 0 and 1, between the same points:
    no velocities meet both (no element of the package has such a graph: its domain always
    holds the rate 0)."""
    with pytest.raises(StepError, match="close a loop of rigid constraints whose fixed rates disagree") as err:
        solve_step(
            [1, 1],
            [0, 0],
            np.array([1.0]),
            np.array([0.0]),
            [(rigid_piece(0.0, -math.inf, math.inf),), (rigid_piece(1.0, -math.inf, math.inf),)],
            np.ones(2),
        )
    assert err.value.elements == (0, 1)
