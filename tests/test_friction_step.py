"""Backward Euler with friction laws that fall and with driven points: the step's rule, its dt bound, belts.

References: the Coulomb element itself (a friction contact whose static and
kinetic forces are equal *is* the Bingham graph, so it must run bit for bit
as today's runs), the closed form of the uniqueness bound for one mass
(``m/dt + k dt > fall``), and the motion of a block stuck to a belt.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import lumped
from lumped import Bingham, Driver, Friction, Mass, Network, Spring
from lumped.laws.stribeck import StribeckLaw
from lumped.solvers.uniqueness import check_step, largest_step

G = "ground"


def one_mass(contact, *, x0=0.3, v0=0.0, drivers=(), force=None, stiffness=100.0, mass=1.0):
    """A mass on a spring to the ground and ``contact``, optionally a load and driven points."""
    loads = [] if force is None else [lumped.Load("m", force)]
    return Network([Mass("m", mass, x0, v0)], [Spring("k", (G, "m"), stiffness), contact], loads, drivers)


@pytest.mark.parametrize("solver", ["auto", "python", "compiled"])
@pytest.mark.parametrize("v0", [0.0, 2.0])
def test_static_equal_to_kinetic_is_coulomb_bit_for_bit(solver, v0):
    """``friction`` with ``static == kinetic`` and no Stribeck velocity is the Coulomb element: the same
    numbers bit for bit, by Algorithm 1 (``auto``) and by the active-set step in Python and in C."""
    force = lumped.SwitchedSine(3.0, 7.0)
    friction = one_mass(Friction("d", (G, "m"), static=1.5, kinetic=1.5), v0=v0, force=force)
    coulomb = one_mass(Bingham("d", (G, "m"), threshold=1.5, gamma=math.inf), v0=v0, force=force)
    a = lumped.simulate_network(friction, 2.0, 1e-3, solver=solver)
    b = lumped.simulate_network(coulomb, 2.0, 1e-3, solver=solver)
    assert a.solver == b.solver
    for name in ("positions", "velocities", "forces"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name


def test_static_equal_to_kinetic_is_coulomb_in_a_network():
    """The same in a two-mass chain with a contact between the masses (the active-set step)."""

    def chain(contact):
        masses = [Mass("a", 1.0, 0.2), Mass("b", 2.0, -0.1, 1.0)]
        elements = [Spring("s1", (G, "a"), 50.0), Spring("s2", ("a", "b"), 30.0), contact]
        return Network(masses, elements)

    a = lumped.simulate_network(chain(Friction("c", ("a", "b"), static=0.8, kinetic=0.8, viscous=0.0)), 1.0, 1e-3)
    b = lumped.simulate_network(chain(Bingham("c", ("a", "b"), threshold=0.8, gamma=math.inf)), 1.0, 1e-3)
    assert np.array_equal(a.positions, b.positions) and np.array_equal(a.forces, b.forces)


def test_a_stuck_contact_stays_stuck_between_kinetic_and_static():
    """The rule: a predictor between ``kinetic`` and ``static`` admits two solutions (stuck, and slipping
    against ``kinetic``); the stuck contact stays stuck.  A mass at rest with a constant load of 0.9 N on
    a contact of static 1 N and kinetic 0.5 N (no spring force: x0 = 0) never moves."""
    net = one_mass(Friction("d", (G, "m"), static=1.0, kinetic=0.5), x0=0.0, force=lumped.Constant(0.9), stiffness=1e-9)
    tr = lumped.simulate_network(net, 1.0, 1e-2)
    assert np.all(tr.velocities == 0) and np.all(tr.forces[1:, 1] == 0.9)


def test_a_contact_that_breaks_away_slides_against_kinetic():
    """Above ``static`` it slips, and the force drops to ``kinetic`` at once (no Stribeck velocity): with a
    constant load P > static on a free mass, ``v_n = n dt (P - kinetic)/m`` (the step is exact for a
    constant acceleration's velocity; the tolerance is a few ulps of the largest velocity)."""
    p, kinetic, dt = 1.2, 0.5, 1e-2
    net = one_mass(
        Friction("d", (G, "m"), static=1.0, kinetic=kinetic), x0=0.0, force=lumped.Constant(p), stiffness=1e-300
    )
    tr = lumped.simulate_network(net, 1.0, dt)
    expected = tr.t * (p - kinetic)
    assert np.allclose(tr.velocities[:, 0], expected, rtol=0, atol=16 * np.finfo(float).eps * expected.max())
    assert np.all(tr.forces[1:, 1] == kinetic)


def test_a_curve_given_as_a_function_settles_where_rounding_cycles_its_points():
    """Leine's benchmark (``SlipCurve``, ``1/(1 + 3 s)``) on a belt at 0.2 m/s, from rest, at ``dt = 2e-3``: at
    the step to t = 5.328 s the iteration's slip points cycle through three values of the rate 30 ulps apart
    (the rounding of the belt's shift), which no 8-ulp test and no two-point cycle catches; a rounding cycle
    of any length up to ``_CYCLE`` settles.  The run goes on through the slip, and each slipping step's
    force is on the curve at its rate to the rounding of the step: the force is balanced against the
    momentum terms ``(m/dt) v`` (``m/dt = 500``, ``v = w + V``) and the settling test allows 8 eps of
    ``|f| + |f'| + sigma (|w| + |w'|)`` with ``sigma`` of that size, so within ``16 eps (1 + 500 (|w| + V))``
    (``|f| <= 1``; a cycle's points are 30 ulps of ``w`` apart, inside that)."""
    law = lumped.SlipCurve(1.0, lambda s: 1.0 / (1.0 + 3.0 * s), fall=3.0)
    net = Network(
        [Mass("m", 1.0)],
        [Spring("k", (G, "m"), 1.0), lumped.Contact("c", ("belt", "m"), law)],
        drivers=[Driver("belt", 0.2)],
    )
    tr = lumped.simulate_network(net, 5.4, 2e-3)
    slipping = ~tr.rigid[:, 1]
    assert slipping[tr.t > 5.33].all()
    w = tr.velocities[slipping, 0] - 0.2
    curve = np.sign(w) / (1.0 + 3.0 * np.abs(w))
    assert np.all(np.abs(tr.forces[slipping, 1] - curve) <= 16 * np.finfo(float).eps * (1 + 500 * (np.abs(w) + 0.2)))


def test_a_block_stuck_to_a_belt_moves_with_it():
    """A contact that holds more than the spring can pull: the block rides the belt, ``x = V t`` (to the
    rounding of the sum of ``n`` steps), ``v = V`` exactly, and the contact's force balances the spring."""
    belt = Driver("belt", 0.25)
    net = one_mass(
        Friction("d", ("m", "belt"), static=100.0, kinetic=50.0), x0=0.0, v0=0.25, drivers=[belt], stiffness=10.0
    )
    tr = lumped.simulate_network(net, 2.0, 1e-3)
    assert np.all(tr.velocities[:, 0] == 0.25)
    assert np.allclose(tr.positions[:, 0], 0.25 * tr.t, rtol=0, atol=4e3 * np.finfo(float).eps * 0.5)
    assert np.allclose(tr.forces[:, 1], 10.0 * tr.positions[:, 0], rtol=1e-12, atol=1e-15)


def test_a_belt_given_by_a_table_moves_the_block_by_its_integral():
    """A driver whose velocity is a table: the stuck block's position is the velocity's integral (the
    trapezoids) at every step, to rounding."""
    history = lumped.Table(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 0.0]))
    net = one_mass(Friction("d", ("m", "belt"), static=1e3, kinetic=1.0), x0=0.0, drivers=[Driver("belt", history)])
    tr = lumped.simulate_network(net, 2.0, 1e-2)
    exact = np.where(tr.t <= 1, tr.t**2 / 2, 1 - (2 - tr.t) ** 2 / 2)
    assert np.allclose(tr.positions[:, 0], exact, rtol=0, atol=1e-12)


# -- the dt bound ------------------------------------------------------------------------------------------


def stribeck(static=6.0, kinetic=2.0, v_s=0.1, viscous=0.2, decay="exponential"):
    return Friction(
        "f", ("m", "belt"), static=static, kinetic=kinetic, stribeck_velocity=v_s, viscous=viscous, decay=decay
    )


@pytest.mark.parametrize("decay", ["exponential", "gaussian", "rational"])
def test_the_fall_is_the_closed_form(decay):
    """``fall = (static - kinetic)/v_s max(-d') - viscous``, checked against the slopes of the curve
    sampled finely: the largest difference quotient on a grid of h = 1e-6 m/s (1e-5 v_s).  The curves'
    second derivatives are at most 2 (static - kinetic)/v_s^2 = 800 N s^2/m^2, so a quotient is within
    h/2 of that, 4e-4 N s/m, of the slope it brackets: 1e-5 of the fall (39.8 N s/m)."""
    law = StribeckLaw(6.0, 2.0, 0.1, decay, 0.2)
    s = np.linspace(0, 0.1, 100001)
    sampled = np.max(-np.diff(law.slip(s)) / np.diff(s))
    assert law.fall == pytest.approx(sampled, rel=1.1e-5)


@pytest.mark.parametrize("decay", ["exponential", "gaussian", "rational"])
@pytest.mark.parametrize("v_s", [0.1, None])
def test_a_scalar_speed_gives_the_arrays_tension_bit_for_bit(decay, v_s):
    """The event-driven integrators call ``slip`` on one float at a time, through a path without arrays (four
    times faster); it does the same floating-point operations in the same order as the array path, so the two
    agree with ``==``, and it returns a float."""
    law = StribeckLaw(6.0, 2.0, v_s, decay, 0.2)
    s = np.concatenate([[0.0], np.geomspace(1e-9, 10.0, 1001)])
    scalar = [law.slip(float(v)) for v in s]
    assert all(type(g) is float for g in scalar) and scalar == list(law.slip(s))


def test_the_bound_for_one_mass_is_the_root_of_m_over_dt_plus_k_dt():
    """One mass, a spring k and a contact whose curve falls by lambda: the step is unique while
    ``m/dt + k dt > lambda``, i.e. below ``dt_1 = (lambda - sqrt(lambda^2 - 4 m k)) / (2 k)``; the
    bisection of :func:`largest_step` finds it to its 1e-12 relative."""
    m, k = 0.05, 200.0
    contact = stribeck()
    lam = contact.steepest_fall  # 39.8 N s/m
    net = one_mass(contact, mass=m, stiffness=k, drivers=[Driver("belt", 0.2)])
    dt1 = (lam - math.sqrt(lam * lam - 4 * m * k)) / (2 * k)
    assert largest_step(net, 0.01) == pytest.approx(dt1, rel=1e-11)
    check_step(net, dt1 * (1 - 1e-9))  # admitted
    with pytest.raises(ValueError, match=r"^dt: .* take dt <= 0\.00126 s$"):
        check_step(net, dt1 * (1 + 1e-9))
    dt2 = (lam + math.sqrt(lam * lam - 4 * m * k)) / (2 * k)
    check_step(net, dt2 * (1 + 1e-9))  # beyond the second root m/dt + k dt exceeds lambda again


def test_above_the_bound_a_step_has_two_slipping_solutions():
    """Why the bound: with ``eta = m/dt + k dt`` below the fall, ``g(s) + eta s = z`` has two roots s > 0
    for a predictor z just below ``static`` (the slipping contact's step is not unique); above the fall
    ``g(s) + eta s`` increases, so it has at most one."""
    law = StribeckLaw(6.0, 2.0, 0.1, "exponential", 0.2)
    s = np.linspace(1e-9, 2.0, 200001)
    for eta, roots in ((0.9 * law.fall, 2), (1.1 * law.fall, 1)):
        z = law.slip(0.0) - 1e-3 if roots == 2 else law.slip(0.0) + 1e-3
        h = law.slip(s) + eta * s - z
        assert np.count_nonzero(np.diff(np.sign(h))) == roots


def test_a_step_beyond_the_bound_is_refused_by_the_run():
    """``simulate_network`` refuses before any work, naming the largest admissible step."""
    net = one_mass(stribeck(), mass=0.538, stiffness=6957.0, drivers=[Driver("belt", 0.22)])
    lumped.simulate_network(net, 0.01, 1e-2)  # 53.8 + 69.6 kg/s > 39.8 N s/m
    heavy_fall = one_mass(stribeck(v_s=0.01), mass=0.538, stiffness=6957.0, drivers=[Driver("belt", 0.22)])
    with pytest.raises(ValueError, match=r"^dt: 0\.01 s is too long .*'f' falls with its rate by up to 399\.8 N s/m"):
        lumped.simulate_network(heavy_fall, 0.1, 1e-2)


def test_the_bound_in_a_network_is_the_definite_test():
    """Two masses, a falling contact between them: the bound is where ``M/dt + dt K - L`` stops being
    definite; for equal masses m with no springs, ``L = lambda [[1, -1], [-1, 1]]`` has eigenvalue
    ``2 lambda``, so the bound is ``dt < m/(2 lambda)``."""
    contact = Friction("f", ("a", "b"), static=6.0, kinetic=2.0, stribeck_velocity=0.1)
    net = Network([Mass("a", 1.0), Mass("b", 1.0)], [contact])
    assert largest_step(net, 1.0) == pytest.approx(1.0 / (2 * contact.steepest_fall), rel=1e-11)
    # the bisection ends on the admissible side, a hair below 1/80 = 0.0125, printed rounded down
    with pytest.raises(ValueError, match=r"take dt <= 0\.0124 s$"):
        check_step(net, 0.02)


# -- driven points ---------------------------------------------------------------------------------------


def test_drivers_are_checked_at_the_boundary():
    with pytest.raises(ValueError, match="velocity must be a real number, got nan"):
        Driver("belt", math.nan)
    with pytest.raises(ValueError, match="reserved"):
        Driver("ground", 1.0)
    with pytest.raises(ValueError, match="neither a mass"):
        Network([Mass("m", 1.0)], [Spring("s", ("belt", G), 1.0)], drivers=[Driver("belt", 1.0)])
    with pytest.raises(ValueError, match="the name is a mass's"):
        Network([Mass("m", 1.0)], [Spring("s", ("m", G), 1.0)], drivers=[Driver("m", 1.0)])


def test_a_swaying_belt_runs_the_compiled_sparse_step():
    """The one-mass friction loop runs only constant velocities (tests/test_friction_kernel.py); a belt
    whose velocity is a history takes the compiled sparse step (tests/test_network_banded.py), which
    agrees with the Python step."""
    swaying = Driver("belt", lumped.SwitchedSine(0.2, 1.0))
    net = one_mass(Friction("d", ("m", "belt"), static=1.0, kinetic=1.0), drivers=[swaying])
    compiled = lumped.simulate_network(net, 1.0, 1e-3, solver="compiled")
    python = lumped.simulate_network(net, 1.0, 1e-3, solver="python")
    assert compiled.solver == "compiled-banded"
    assert np.array_equal(compiled.rigid, python.rigid)
    np.testing.assert_allclose(compiled.positions, python.positions, rtol=0, atol=1e-12)


# -- one law contract ------------------------------------------------------------------------------------

LAWS = {
    "bingham": lambda: lumped.BinghamDashpot(1.0, 2.0),
    "coulomb": lambda: lumped.coulomb(1.5),
    "herschel-bulkley": lambda: lumped.HerschelBulkleyDashpot(1.0, 2.0, 0.5),
    "papanastasiou": lambda: lumped.PapanastasiouDashpot(1.0, 2.0, 100.0),
    "stribeck": lambda: StribeckLaw(6.0, 2.0, 0.1, "gaussian", 0.2),
    "static-kinetic": lambda: StribeckLaw(1.0, 0.5),
    "leine": lambda: lumped.SlipCurve(1.0, lambda s: 1.0 / (1.0 + 3.0 * s), fall=3.0),
}


@pytest.mark.parametrize("name", list(LAWS))
def test_every_law_answers_the_one_contract(name):
    """Every law, the dashpots included, is a graph in (rate, tension) by :class:`SlipLaw`'s points: the
    slip limit within the stick interval, the curve >= 0 and odd, no sample falling faster than ``fall``
    (difference quotients on a grid of 1e-4 m/s bracket slopes no steeper than the fall), the linear
    pieces equal to the curve where given, the Bingham form only where the curve is ``static + c s``."""
    law = LAWS[name]()
    assert isinstance(law, lumped.SlipLaw)
    assert 0 <= law.slip_limit <= law.static
    s = np.linspace(1e-4, 2.0, 20000)
    g = law.slip(s)
    assert np.all(g >= 0)
    assert np.all(-np.diff(g) / np.diff(s) <= law.fall * (1 + 1e-9) + 1e-9)
    assert np.array_equal(law.tension(-s), -law.tension(s))
    pieces = law.pieces()
    if pieces is not None:
        (p,) = pieces
        assert np.allclose(g, p.a + p.b * s, rtol=1e-14, atol=0)
    form = law.bingham_form()
    assert (form is not None) == (pieces is not None and pieces[0].a == law.static)


def test_a_contact_holds_any_law_a_dashpot_included():
    """A :class:`Contact` with a Herschel-Bulkley law runs as the Herschel-Bulkley element does: both
    iterate to a fixed point on the same graph to a relative 8 ulps of the force, so the runs agree to
    a few hundred ulps over 1000 steps."""
    law = lumped.HerschelBulkleyDashpot(1.0, 2.0, 0.5)
    a = one_mass(lumped.Contact("d", (G, "m"), law), v0=1.0, force=lumped.SwitchedSine(3.0, 5.0))
    b = one_mass(lumped.HerschelBulkley("d", (G, "m"), 1.0, 2.0, 0.5), v0=1.0, force=lumped.SwitchedSine(3.0, 5.0))
    ta = lumped.simulate_network(a, 1.0, 1e-3, solver="python")
    tb = lumped.simulate_network(b, 1.0, 1e-3, solver="python")
    assert np.allclose(ta.positions, tb.positions, rtol=0, atol=1e-12)
