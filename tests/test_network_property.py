"""Property tests of backward Euler on random networks (issue 9): every step of
random chains and small trees satisfies the scheme's identities.

A network is drawn as a tree over the masses and the ground (each mass hangs
from the ground or an earlier mass), with at most one element that can be
rigid (Bingham, spring-string, locking-bingham) on each tree edge, compliant
elements (spring, Maxwell-Bingham, linear dashpot) beside it, and a few more
compliant elements between random points.  The rigid-capable elements then
form a forest, so the package never refuses these networks (refusal of loops
is tested in test_network.py); loops of compliant elements do occur.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from conftest import EPS
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import lumped as L
from lumped import (
    Bingham,
    LinearDashpot,
    Load,
    LockingBingham,
    Mass,
    MaxwellBingham,
    Network,
    Spring,
    SpringString,
    simulate_network,
)

#: An absolute floor on every round-off tolerance: below about 2.2e-308 numbers
#: are subnormal and rounding is no longer relative (hypothesis draws such
#: thresholds and velocities, e.g. 2.2e-311).
TINY = 1e-290

FAST = settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
MORE = settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])

masses = st.floats(0.1, 10.0)
stiffnesses = st.floats(1.0, 1000.0)
thresholds = st.floats(0.0, 5.0)
positive_thresholds = st.floats(0.05, 5.0)
gammas = st.one_of(st.just(math.inf), st.floats(0.01, 100.0))
lengths = st.floats(0.01, 0.5)
velocities = st.floats(-2.0, 2.0)
forcings = st.one_of(
    st.none(),
    st.builds(
        L.SwitchedSine,
        amplitude=st.floats(-20.0, 20.0),
        omega=st.floats(0.0, 50.0),
        phase=st.floats(-math.pi, math.pi),
        until=st.floats(0.0, 0.3),
    ),
)


def _rigid_capable(draw, name: str, pair: tuple[str, str]):
    """One element that can be rigid (or none), and its admissible elongation range."""
    kind = draw(st.sampled_from(["none", "bingham", "spring-string", "locking-bingham"]))
    if kind == "bingham":
        return Bingham(name, pair, draw(thresholds), draw(gammas)), (-0.2, 0.2)
    if kind == "spring-string":
        el = SpringString(name, pair, draw(stiffnesses), draw(lengths))
        return el, (-0.2, el.length)
    if kind == "locking-bingham":
        return LockingBingham(name, pair, draw(positive_thresholds), draw(gammas), draw(st.floats(0.1, 3.0))), (
            -0.2,
            0.2,
        )
    return None, (-0.2, 0.2)


def _compliant(draw, name: str, pair: tuple[str, str]):
    kind = draw(st.sampled_from(["spring", "maxwell-bingham", "dashpot"]))
    if kind == "spring":
        return Spring(name, pair, draw(stiffnesses))
    if kind == "maxwell-bingham":
        return MaxwellBingham(name, pair, draw(stiffnesses), draw(thresholds), draw(gammas))
    return LinearDashpot(name, pair, draw(st.floats(0.01, 50.0)))


@st.composite
def networks(draw) -> Network:
    """A random chain or tree of 2 to 5 masses (see the module docstring)."""
    n = draw(st.integers(2, 5))
    names = [f"m{i}" for i in range(n)]
    x = {"ground": 0.0}
    elements = []
    for i, child in enumerate(names):
        parent = draw(st.sampled_from(["ground", *names[:i]]))
        flip = draw(st.booleans())
        pair = (child, parent) if flip else (parent, child)
        rigid, (lo, hi) = _rigid_capable(draw, f"r{i}", pair)
        e = draw(st.floats(lo, hi))  # the elongation x_second - x_first on this edge
        x[child] = x[parent] + (-e if flip else e)
        elements += [rigid] if rigid else []
        elements += [_compliant(draw, f"c{i}_{j}", pair) for j in range(draw(st.integers(0 if rigid else 1, 2)))]
    points = ["ground", *names]
    for j in range(draw(st.integers(0, 2))):
        a, b = draw(st.lists(st.sampled_from(points), min_size=2, max_size=2, unique=True))
        elements.append(_compliant(draw, f"x{j}", (a, b)))
    for el in elements:  # the positions' rounding may put a string drawn at its length just past it
        a, b = el.between
        assume(not isinstance(el, SpringString) or x[b] - x[a] <= el.length)
    mass_list = [Mass(nm, draw(masses), x[nm], draw(velocities)) for nm in names]
    force = draw(forcings)
    loads = [Load(draw(st.sampled_from(names)), force)] if force is not None else []
    return Network(mass_list, elements, loads)


class Steps:
    """Every step of a run as arrays: rows ``n`` (start) and ``n + 1`` (end)."""

    def __init__(self, tr) -> None:
        net = tr.network
        self.tr, self.net, self.dt = tr, net, tr.dt
        self.m = np.array([mm.mass for mm in net.masses])
        self.first, self.second = net.incidence()
        vg = np.column_stack([tr.velocities, np.zeros(tr.t.size)])
        xg = np.column_stack([tr.positions, np.zeros(tr.t.size)])
        self.w = (vg[:, self.second] - vg[:, self.first])[1:]  # each step's rates
        self.e = (xg[:, self.second] - xg[:, self.first])[1:]
        self.f = tr.forces[1:]
        self.load = net.load_table(tr.t)[1:]
        self.s0, self.s1 = tr.states[:-1], tr.states[1:]
        self.v0, self.v1 = tr.velocities[:-1], tr.velocities[1:]
        self.rigid = tr.rigid[1:]
        self.vpeak = np.max(np.abs(self.v1), axis=1)  # each step's largest speed (see check_momentum)

    def pushed(self, f: np.ndarray) -> np.ndarray:
        """``B f``: each element's force on each mass, ``(steps, masses)`` (``-f`` on second, ``+f`` on first)."""
        n = self.m.size
        out = np.zeros((f.shape[0], n + 1))
        np.add.at(out.T, self.second, -f.T)
        np.add.at(out.T, self.first, f.T)
        return out[:, :n]


def dissipation(s: Steps, e: int, el) -> np.ndarray:
    """Energy (J) element ``e`` removes in each step, from its own kind's formula.

    A spring: the scheme's ``(f_{n+1} - f_n)^2 / 2k``.  A string: the same in
    its elongation, ``k (de)^2/2``, plus the impact's ``(f - k e_{n+1}) de``
    (0 while slack).  A Maxwell element: ``(df)^2 / 2k`` plus its dashpot's
    ``dt f r`` at the rate ``r = w - df/(dt k)``.  The dashpots: ``dt f w``.
    """
    dt, f, w = s.dt, s.f[:, e], s.w[:, e]
    if isinstance(el, Spring):
        return (s.s1[:, e] - s.s0[:, e]) ** 2 / (2 * el.stiffness)
    if isinstance(el, SpringString):
        de = s.s1[:, e] - s.s0[:, e]
        return 0.5 * el.stiffness * de**2 + (f - el.stiffness * s.s1[:, e]) * de
    if isinstance(el, MaxwellBingham):
        df = s.s1[:, e] - s.s0[:, e]
        return df**2 / (2 * el.stiffness) + dt * f * (w - df / (dt * el.stiffness))
    return dt * f * w


def check_energy_balance(s: Steps) -> None:
    """The discrete energy balance of backward Euler, closed exactly.

    Multiplying the momentum balance ``m (v_{n+1} - v_n) = dt (F_{n+1} - B f)``
    by ``v_{n+1}`` and using ``a (a - b) = (a^2 - b^2)/2 + (a - b)^2/2``:

        K_{n+1} - K_n + sum m (v_{n+1} - v_n)^2/2 = dt F.v_{n+1} - dt sum_e f_e w_e.

    For each element ``dt f w = U_{n+1} - U_n + D``: its stored energy's change
    plus the dissipation of :func:`dissipation` (this holds because the spring
    and string states advance by ``dt k w`` and ``dt w``; each ``D`` is a sum of
    squares and a dashpot's ``f w >= 0``: the implicit step of a convex
    potential loses energy, never gains it).  So

        (K + U)_{n+1} + sum m (dv)^2/2 + sum_e D_e = (K + U)_n + dt F.v_{n+1},

    to round-off: a few roundings of each term, over ``masses + elements``
    terms, and the momentum balance's rounding (see :func:`check_momentum`)
    times ``dt v``.  Every ``D_e`` must also be ``>= 0`` to the same round-off.
    """
    els = s.net.elements
    u0 = np.column_stack([[el.stored_energy(q) for q in s.s0[:, e]] for e, el in enumerate(els)])
    u1 = np.column_stack([[el.stored_energy(q) for q in s.s1[:, e]] for e, el in enumerate(els)])
    d = np.column_stack([dissipation(s, e, el) for e, el in enumerate(els)])
    k0, k1 = 0.5 * s.m * s.v0**2, 0.5 * s.m * s.v1**2
    num = 0.5 * s.m * (s.v1 - s.v0) ** 2
    work = s.dt * np.sum(s.load * s.v1, axis=1)
    residual = (k1.sum(1) + u1.sum(1) + num.sum(1) + d.sum(1)) - (k0.sum(1) + u0.sum(1) + work)
    scale = (k0 + k1).sum(1) + (u0 + u1).sum(1) + np.abs(d).sum(1) + np.abs(work) + s.dt * np.abs(s.f * s.w).sum(1)
    scale = scale + np.sum(s.m * (np.abs(s.v0) + np.abs(s.v1)), axis=1) * s.vpeak  # see check_momentum
    scale = scale + s.dt * s.vpeak * np.sum(np.abs(s.f) + np.abs(s.tr.forces[:-1]), axis=1)  # its residual times dt v
    terms = s.m.size + len(els)
    assert np.all(np.abs(residual) <= 16 * terms * EPS * scale + TINY)
    assert np.all(d >= -16 * EPS * scale[:, None] - TINY)


def check_momentum(s: Steps) -> None:
    """Each mass: ``m (v_{n+1} - v_n)/dt = F_{n+1} - (B f)``, to round-off.

    The terms are the inertia terms, the load, and each force on the mass with
    the previous step's force (a spring's is an increment of it).  Where rigid
    elements join masses into a cluster, the cluster is solved as one unknown
    and the rigid forces then leaf by leaf, so the rounding of every term in
    the cluster ends in the balance of its last mass; and each velocity is the
    cluster's plus an offset (a lock's ``v_lock``), rounded to eps of the
    cluster's speeds (``vpeak``), not of its own.  So each mass is held to a few
    eps of the terms of the whole network, per step.
    """
    lhs = s.m * (s.v1 - s.v0) / s.dt
    rhs = s.load + s.pushed(s.f)
    terms = s.m * (np.abs(s.v1) + np.abs(s.v0) + s.vpeak[:, None]) / s.dt + np.abs(s.load)
    terms = terms + _abs_pushed(s, np.abs(s.f) + np.abs(s.tr.forces[:-1]))
    scale = np.sum(terms, axis=1, keepdims=True)
    count = 2 + len(s.net.elements)
    assert np.all(np.abs(lhs - rhs) <= 8 * count * EPS * scale + TINY)


def _abs_pushed(s: Steps, a: np.ndarray) -> np.ndarray:
    """``|B| a``: the sum of ``a`` over the elements at each mass."""
    n = s.m.size
    out = np.zeros((a.shape[0], n + 1))
    np.add.at(out.T, s.second, a.T)
    np.add.at(out.T, s.first, a.T)
    return out[:, :n]


def check_rigid(s: Steps) -> None:
    """Sticking elements: rate exactly 0.0 (their masses move as one); locked ones at
    ``+-v_lock`` to round-off (the rate is a difference of two velocities, one
    offset by ``v_lock``); taut strings exactly at their length; no string beyond it."""
    vmax = float(np.max(np.abs(s.tr.velocities)))
    for e, el in enumerate(s.net.elements):
        held, w = s.rigid[:, e], s.w[:, e]
        if isinstance(el, Bingham):
            assert np.all(w[held] == 0.0), el.name
        if isinstance(el, LockingBingham):
            locked = np.abs(np.abs(w[held]) - el.v_lock) <= TINY + 4 * EPS * (el.v_lock + vmax)
            assert np.all((w[held] == 0.0) | locked), el.name
        if isinstance(el, SpringString):
            assert np.all(s.s1[held, e] == el.length), el.name
            assert np.all(s.tr.states[:, e] <= el.length), el.name
        if not el.rigid_capable:
            assert not held.any(), el.name


def _graph_rate(el, w: np.ndarray, held: np.ndarray, vmax: float) -> np.ndarray:
    """The rate to read the graph at: a locked element's ``+-v_lock`` itself (see check_rigid)."""
    if isinstance(el, LockingBingham):
        near = held & (np.abs(np.abs(w) - el.v_lock) <= TINY + 4 * EPS * (el.v_lock + vmax))
        return np.where(near, np.copysign(el.v_lock, w), w)
    return w


def check_graphs(s: Steps) -> None:
    """Each element's ``(rate, force)`` on its graph, :meth:`Element.force_interval`.

    Springs are read at the elongation of the positions, which drifts from
    the spring's own state by the roundings of ``x + dt v`` and ``f + dt k w``:
    ``4 eps`` of ``k|x| + |f|`` per step, over ``N`` steps.  A string is read at
    its own elongation (its state; the positions may pass ``L`` by a rounding).
    Dashpot forces are ``a + b w`` from the step's piece: a few roundings.  A
    Maxwell element's force is its state, so its graph says nothing: its
    dashpot's rate ``w - df/(dt k)`` is checked on the Bingham graph instead.
    """
    vmax, steps = float(np.max(np.abs(s.tr.velocities))), s.w.shape[0]
    xmax = float(np.max(np.abs(s.tr.positions)))
    for e, el in enumerate(s.net.elements):
        f, w = s.f[:, e], _graph_rate(el, s.w[:, e], s.rigid[:, e], vmax)
        if isinstance(el, MaxwellBingham):
            check_maxwell(s, e, el)
            continue
        elong = s.s1[:, e] if isinstance(el, SpringString) else s.e[:, e]
        bounds = np.array([el.force_interval(float(a), float(b)) for a, b in zip(elong, w)])
        assert not np.isnan(bounds).any(), el.name
        slack = TINY + 8 * EPS * (np.abs(f) + _terms(s, e, el))
        if isinstance(el, Spring):
            slack = slack + 4 * EPS * steps * (el.stiffness * xmax + np.max(np.abs(s.tr.forces[:, e])))
        lo, hi = bounds[:, 0], bounds[:, 1]
        assert np.all((f >= lo - slack) & (f <= hi + slack)), el.name


def _terms(s: Steps, e: int, el) -> np.ndarray:
    """The size of the terms an element's force is computed from (N): its
    rounding is a few eps of this, not of the force, when they cancel."""
    w = np.abs(s.w[:, e])
    if isinstance(el, Spring):
        return np.abs(s.s0[:, e]) + s.dt * el.stiffness * w
    if isinstance(el, SpringString):
        return el.stiffness * (np.abs(s.s0[:, e]) + s.dt * w)
    if isinstance(el, LinearDashpot):
        return el.damping * w
    c = 0.0 if math.isinf(el.gamma) else 1.0 / el.gamma
    return el.threshold + c * w


def check_maxwell(s: Steps, e: int, el: MaxwellBingham) -> None:
    """The dashpot of a Maxwell element: rate ``r = w - df/(dt k)`` and force ``f``
    on the Bingham graph.  ``r`` is a difference of terms of size ``|w|`` and
    ``(|f_n| + |f|)/(dt k)``: its rounding ``dr`` is a few eps of those."""
    f, df = s.s1[:, e], s.s1[:, e] - s.s0[:, e]
    kdt = s.dt * el.stiffness
    r = s.w[:, e] - df / kdt
    dr = TINY + 8 * EPS * (np.abs(s.w[:, e]) + (np.abs(s.s0[:, e]) + np.abs(f)) / kdt)
    c = 0.0 if math.isinf(el.gamma) else 1.0 / el.gamma
    df_tol = TINY + 8 * EPS * (np.abs(f) + el.threshold) + c * dr
    still = np.abs(r) <= dr
    assert np.all(np.abs(f[still]) <= el.threshold + df_tol[still]), el.name
    moving = ~still
    expected = np.copysign(el.threshold + c * np.abs(r[moving]), r[moving])
    assert np.all(np.abs(f[moving] - expected) <= df_tol[moving]), el.name


def check_every_step(tr) -> None:
    s = Steps(tr)
    check_energy_balance(s)
    check_momentum(s)
    check_rigid(s)
    check_graphs(s)


def run(net: Network, dt: float, t_end: float = 0.2):
    return simulate_network(net, t_end, dt, solver="active-set")


@FAST
@given(networks(), st.sampled_from([1e-3, 4e-4]))
def test_every_step_of_a_random_network(net: Network, dt: float) -> None:
    check_every_step(run(net, dt))


@pytest.mark.slow
@MORE
@given(networks(), st.sampled_from([1e-3, 4e-4, 1e-4]))
def test_every_step_of_a_random_network_more_examples(net: Network, dt: float) -> None:
    check_every_step(run(net, dt, 0.5))


def _mixed() -> Network:
    """One network with every kind: a Coulomb element that sticks, a string, a
    Maxwell element, a lock that locks, a dashpot, a load."""
    return Network(
        [Mass("a", 1.0, 0.05, 1.0), Mass("b", 2.0, 0.0, -0.5), Mass("c", 0.5, 0.1)],
        [
            Spring("k0", ("ground", "a"), 100.0),
            Bingham("b0", ("ground", "a"), 2.0, math.inf),
            SpringString("s1", ("a", "b"), 80.0, 0.1),
            MaxwellBingham("mx", ("b", "c"), 50.0, 0.5, 2.0),
            LockingBingham("l2", ("a", "c"), 0.3, 1.0, 0.4),
            LinearDashpot("d", ("ground", "c"), 0.5),
        ],
        [Load("b", L.SwitchedSine(5.0, 10.0, 0.0, 0.1))],
    )


#: Perturbations of one saved number, far below any physical tolerance: (array, row, column, change).
PERTURBATIONS = {
    "spring force 1e-9": ("forces", 100, 0, lambda q: q * (1 + 1e-9)),
    "dashpot force 1e-9": ("forces", 100, 5, lambda q: q * (1 + 1e-9)),
    "Maxwell force 1e-9": ("forces", 100, 3, lambda q: q * (1 + 1e-9)),
    "spring state 1e-9": ("states", 100, 0, lambda q: q * (1 + 1e-9)),
    "velocity 1e-12": ("velocities", 100, 1, lambda q: q + 1e-12),
}


def test_the_checks_pass_on_a_mixed_network_and_its_lock_engages() -> None:
    tr = run(_mixed(), 1e-3, 0.5)
    assert tr.rigid[:, 4].any()  # the lock engages (locked or sticking)
    check_every_step(tr)


@pytest.mark.parametrize("name", list(PERTURBATIONS))
def test_the_checks_catch_a_perturbed_step(name: str) -> None:
    """The checks can fail: one number off by far less than any physical tolerance is caught."""
    tr = run(_mixed(), 1e-3, 0.5)
    field, row, col, change = PERTURBATIONS[name]
    values = getattr(tr, field).copy()
    values[row, col] = change(values[row, col])
    with pytest.raises(AssertionError):
        check_every_step(dataclasses.replace(tr, **{field: values}))


def test_the_checks_catch_a_sticking_element_that_creeps() -> None:
    """A sticking element's rate must be exactly 0.0: the smallest creep is caught."""
    tr = run(
        Network([Mass("a", 1.0, 0.01)], [Spring("k", ("ground", "a"), 100.0), Bingham("b", ("ground", "a"), 2.0, 1.0)]),
        1e-3,
        0.1,
    )
    assert tr.rigid[1:, 1].all()
    v = tr.velocities.copy()
    v[5, 0] = 5e-324
    with pytest.raises(AssertionError):
        check_every_step(dataclasses.replace(tr, velocities=v))
