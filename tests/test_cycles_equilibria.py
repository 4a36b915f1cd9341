"""Steady sliding on a belt, its eigenvalues and its Hopf points (issue 34, :mod:`lumped.drivers.cycles.equilibria`).

References: the eigenvalues of the linearisation in closed form, ``(-c_eff +- sqrt(c_eff^2 - 4 m k))/(2 m)``
with ``c_eff`` the dashpots' sum plus the slip curve's slope written here by hand; the Hopf speed of the
Veraszto-Stepan parameters, ``V_H = ln((C0 - C) c_v/(b0 + b_s))/c_v``, and the Hopf damping
``b0_H = (C0 - C) c_v exp(-c_v V) - b_s`` at a fixed speed.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from lumped.drivers.cycles import check_autonomous, hopf_points, steady_sliding
from lumped.drivers.cycles.equilibria import HOPF_RTOL
from lumped.laws import Bingham, LinearDashpot, SlipCurve, Spring
from lumped.laws.contract import central_slope
from lumped.laws.slip_elements import Contact
from lumped.laws.stribeck import Friction, StribeckLaw
from lumped.model.forcing import SwitchedSine, Table
from lumped.model.network import Driver, Load, Mass, Network
from lumped.model.system_parameters import system_parameters, with_values

EPS = float(np.finfo(float).eps)
M, K, B0 = 0.538, 6957.0, 5.746
C, C0, CV, BS = 2.0, 6.0, 10.0, 0.2
V_HOPF = math.log((C0 - C) * CV / (B0 + BS)) / CV


def belt(contact, V: float = 0.2, *, k: float = 1.0, m: float = 1.0, extra=(), drivers=None) -> Network:
    """One mass on a spring to the ground and ``contact`` on a belt at ``V``."""
    elements = [Spring("k", ("ground", "m"), k), contact, *extra]
    return Network([Mass("m", m)], elements, drivers=drivers or [Driver("belt", V)])


def stribeck(V: float) -> Network:
    friction = Friction("f", ("belt", "m"), static=C0, kinetic=C, stribeck_velocity=1 / CV, viscous=BS)
    return belt(friction, V, k=K, m=M, extra=[LinearDashpot("b0", ("ground", "m"), B0)])


def stribeck_slope(V: float) -> float:
    return BS - (C0 - C) * CV * math.exp(-CV * V)


def closed_form(m: float, c: float, k: float) -> np.ndarray:
    root = np.sqrt(complex(c * c - 4 * m * k))
    return np.array([(-c + root) / (2 * m), (-c - root) / (2 * m)])


# -- the equilibrium and its eigenvalues -----------------------------------------------------------------------


@pytest.mark.parametrize("V", [0.1, 0.19, 0.25, 0.8])
def test_stribeck_sliding_eigenvalues_are_the_closed_form(V: float):
    """``c_eff = b0 + g'(V)`` with the exact slope: the eigenvalues are rounding away from the closed form, a few
    operations on terms of size ``(C0 - C) c_v`` = 40 N s/m over ``2 m``: ``1e-12`` of the ``|lambda| ~ 114`` 1/s
    (40 * 8 eps / (2 * 0.538) ~ 7e-14, and the square root's ``4 m k`` ~ 1.5e4 to ``eps`` relative)."""
    eq = steady_sliding(stribeck(V))
    ref = closed_form(M, B0 + stribeck_slope(V), K)
    assert np.allclose(np.sort_complex(eq.eigenvalues), np.sort_complex(ref), rtol=0, atol=1e-12)
    assert eq.max_real_part == pytest.approx(-(B0 + stribeck_slope(V)) / (2 * M), abs=1e-12)
    assert eq.stable == (V > V_HOPF)
    g = C + (C0 - C) * math.exp(-CV * V) + BS * V
    assert eq.position == pytest.approx([g / K], rel=4 * EPS)
    assert np.allclose(eq.forces, [g, -g, 0.0], rtol=4 * EPS, atol=0)  # spring, contact, the dashpot at rest


def test_leines_curve_by_central_difference_within_its_bound():
    """Leine's ``g(s) = 1/(1 + 3 s)`` as a callable: the slope is a central difference whose error bound
    (:func:`central_slope`) carries into the eigenvalues over ``2 m``; the exact slope ``-3/(1 + 3 V)^2``."""
    V = 0.2
    law = SlipCurve(1.0, lambda s: 1 / (1 + 3 * s), fall=3.0)
    slope = law.slope(V)
    exact = -3 / (1 + 3 * V) ** 2
    assert abs(slope.value - exact) <= slope.error < 1e-8
    eq = steady_sliding(belt(Contact("c", ("belt", "m"), law), V))
    ref = closed_form(1.0, exact, 1.0)
    assert np.allclose(np.sort_complex(eq.eigenvalues), np.sort_complex(ref), rtol=0, atol=slope.error / 2 + 4 * EPS)
    assert not eq.stable and eq.max_real_part > 0
    assert eq.position == pytest.approx([1 / (1 + 3 * V)], rel=4 * EPS)


def test_an_overdamped_equilibrium_has_two_real_eigenvalues_without_cancellation():
    """``c = 100, m = k = 1``: the small root ``-0.0100010002...`` is ``k/(m big)``, not a difference of two
    near-equal numbers: to a few ulps of the closed form's stable expression ``-2k/(c + sqrt(c^2 - 4mk))``."""
    eq = steady_sliding(belt(Friction("f", ("belt", "m"), static=1.0, kinetic=1.0, viscous=100.0), 0.3))
    big, small = -(100 + math.sqrt(100**2 - 4)) / 2, -2 / (100 + math.sqrt(100**2 - 4))
    assert eq.eigenvalues.imag.tolist() == [0.0, 0.0]
    assert eq.eigenvalues.real == pytest.approx([small, big], rel=8 * EPS)
    assert eq.stable


def test_the_static_kinetic_belt_is_neutral_and_not_labelled_stable():
    """No viscous part: ``c_eff = 0`` exactly, the pair ``+-i``: a centre, within its error bound of 0: not stable."""
    eq = steady_sliding(belt(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5)))
    assert eq.eigenvalues.tolist() == [1j, -1j]
    assert eq.max_real_part == 0.0 and not eq.stable
    assert eq.position.tolist() == [0.5]


def test_a_linear_viscous_contact_has_the_closed_form_equilibrium_and_no_cycle():
    """The dashpot ``c`` to the belt in place of friction: ``x* = c V / k``, eigenvalues of ``m s^2 + c s + k``;
    ``cycles`` refuses it (no falling law) and says so with those eigenvalues."""
    net = belt(LinearDashpot("c", ("belt", "m"), 0.3), 0.2)
    eq = steady_sliding(net)
    assert eq.position == pytest.approx([0.06], rel=2 * EPS)
    assert np.allclose(eq.eigenvalues, closed_form(1.0, 0.3, 1.0), rtol=0, atol=4 * EPS)
    assert eq.stable
    with pytest.raises(
        ValueError,
        match=r"^cycles: no falling law: the dashpot 'c' .*linear.*x = 0\.06 m "
        r"\(eigenvalues -0\.15 \+- 0\.988686i 1/s\).*no cycle$",
    ):
        check_autonomous(net)


# -- Hopf points -----------------------------------------------------------------------------------------------


def test_the_veraszto_stepan_hopf_speed_is_located():
    """The issue asks for 1e-8 relative; Brent's method stops at :data:`HOPF_RTOL`, and ``c_eff`` is exact but
    for rounding (``8 eps`` of 40 N s/m) over its slope ``(C0 - C) c_v^2 exp(-c_v V_H)`` = 59 N s^2/m^2:
    ``5e-15`` m/s more.  So ``2 HOPF_RTOL``."""
    (v_h,) = hopf_points(stribeck(0.3), "belt.velocity", 0.05, 0.5)
    assert v_h == pytest.approx(V_HOPF, rel=2 * HOPF_RTOL)
    assert V_HOPF == pytest.approx(0.190616, abs=1e-6)


def test_the_hopf_point_in_a_dashpot_is_its_closed_form():
    """At ``V = 0.2`` the damping ``b0`` that cancels the fall: ``(C0 - C) c_v exp(-c_v V) - b_s`` = 5.213 N s/m."""
    (b_h,) = hopf_points(stribeck(0.2), "b0.damping", 1.0, 10.0)
    assert b_h == pytest.approx((C0 - C) * CV * math.exp(-CV * 0.2) - BS, rel=2 * HOPF_RTOL)


def test_a_gaussian_decay_has_two_hopf_speeds():
    """``g' = b_s - (C0 - C)/v_s 2x exp(-x^2)`` (``x = V/v_s``) falls then rises: with ``b0 = 20`` it is below
    ``-b0`` between two speeds; each is a root of ``b0 + g'`` (checked by the closed-form slope's sign)."""
    friction = Friction("f", ("belt", "m"), static=C0, kinetic=C, stribeck_velocity=0.1, decay="gaussian", viscous=BS)
    net = belt(friction, 0.1, k=K, m=M, extra=[LinearDashpot("b0", ("ground", "m"), 20.0)])
    points = hopf_points(net, "belt.velocity", 0.01, 0.5)
    law = StribeckLaw(C0, C, 0.1, "gaussian", BS)
    assert len(points) == 2
    for v in points:
        assert 20.0 + law.slope(v * (1 - 1e-10)).value != pytest.approx(0.0, abs=0)
        assert np.sign(20.0 + law.slope(v * (1 - 1e-10)).value) == -np.sign(20.0 + law.slope(v * (1 + 1e-10)).value)


def test_no_hopf_point_where_sliding_stays_stable():
    assert hopf_points(stribeck(0.3), "belt.velocity", 0.3, 2.0) == []


# -- parameters ------------------------------------------------------------------------------------------------


def test_a_belts_velocity_is_a_parameter_and_with_values_keeps_the_drivers():
    net = stribeck(0.3)
    (p,) = system_parameters(net, "belt.velocity")
    assert (p.table, p.key, p.value) == ("driver", "velocity", 0.3)
    moved = with_values(net, [p], [0.5])
    assert [d.velocity for d in moved.drivers] == [0.5]
    (b,) = system_parameters(net, "b0.damping")
    assert with_values(net, [b], [1.0]).drivers == net.drivers


def test_a_driver_following_a_history_has_no_velocity_parameter():
    net = belt(Friction("f", ("belt", "m"), static=1.0, kinetic=0.5), drivers=[Driver("belt", Table([0, 1], [0, 1]))])
    with pytest.raises(ValueError, match=r"^vary: 'belt.velocity': driver 'belt' follows a history"):
        system_parameters(net, "belt.velocity", "vary")


@pytest.mark.parametrize(
    ("name", "start", "stop", "message"),
    [
        ("belt.velocity", -0.1, 0.5, r"^vary: belt.velocity = -0.1:0.5 reaches 0, where the belt stops"),
        ("belt.velocity", 0.0, 0.5, r"^vary: at belt.velocity = 0: the friction contact 'f' is on a point at rest"),
        ("k.stiffness", -1.0, 2.0, r"^vary: at k.stiffness = -1: "),
        ("belt.speed", 0.1, 0.5, r"^vary: unknown parameter 'belt.speed'; .*'belt.velocity'"),
        ("belt.velocity", 0.5, 0.1, r"^vary: START:STOP must be finite with START < STOP"),
    ],
)
def test_a_bad_range_is_refused_in_one_line(name, start, stop, message):
    with pytest.raises(ValueError, match=message) as err:
        hopf_points(stribeck(0.3), name, start, stop)
    assert "\n" not in str(err.value)


# -- the boundary ----------------------------------------------------------------------------------------------

FRICTION = Friction("f", ("belt", "m"), static=1.0, kinetic=0.5)
LOOSE = Network([Mass("m", 1.0)], [FRICTION, LinearDashpot("c", ("ground", "m"), 1.0)], drivers=[Driver("belt", 0.2)])


@pytest.mark.parametrize(
    ("network", "message"),
    [
        (
            Network(
                [Mass("m", 1.0), Mass("n", 1.0)],
                [Spring("k", ("ground", "m"), 1.0), FRICTION, Spring("j", ("m", "n"), 1.0)],
                drivers=[Driver("belt", 0.2)],
            ),
            r"the system has 2 masses; cycles runs one mass",
        ),
        (
            Network(
                [Mass("m", 1.0)],
                [Spring("k", ("ground", "m"), 1.0), FRICTION],
                [Load("m", SwitchedSine(1.0, 1.0))],
                drivers=[Driver("belt", 0.2)],
            ),
            r"the system has a load on 'm'; cycles runs self-excited motions",
        ),
        (
            Network(
                [Mass("m", 1.0)],
                [Spring("k", ("ground", "m"), 1.0), Friction("f", ("ground", "m"), static=1.0, kinetic=0.5)],
            ),
            r"no driven point",
        ),
        (
            belt(
                Friction("f", ("ground", "m"), static=1.0, kinetic=0.5), extra=[LinearDashpot("c", ("belt", "m"), 1.0)]
            ),
            r"the friction contact 'f' is on a point at rest",
        ),
        (belt(FRICTION, drivers=[Driver("belt", Table([0, 1], [0, 1]))]), r"driver 'belt' has .*constant velocity"),
        (belt(FRICTION, extra=[Spring("p", ("belt", "m"), 1.0)]), r"spring 'p' pulls the mass from a moving point"),
        (LOOSE, r"no spring holds the mass"),
        (
            belt(FRICTION, extra=[Friction("g", ("belt", "m"), static=1.0, kinetic=0.5)]),
            r"the system has 2 friction contacts \('f', 'g'\)",
        ),
        (
            belt(Friction("f", ("belt", "m"), static=1.0, kinetic=1.0, viscous=0.1)),
            r"no falling law: the friction contact 'f' starts at static and never falls.*eigenvalues -0.05 \+- ",
        ),
        (belt(Bingham("f", ("belt", "m"), threshold=1.0)), r"no falling law: the friction contact 'f'"),
    ],
)
def test_what_cycles_cannot_run_is_refused_with_the_reason(network, message):
    with pytest.raises(ValueError, match=r"^cycles: .*" + message) as err:
        check_autonomous(network)
    assert "\n" not in str(err.value) and "event-driven" not in str(err.value)


def test_a_falling_law_is_accepted():
    check_autonomous(stribeck(0.3))
    check_autonomous(belt(FRICTION))  # static above kinetic: a jump, no fall


# -- the slope of a slip curve (contract point 9) --------------------------------------------------------------


@pytest.mark.parametrize("decay", ["exponential", "gaussian", "rational"])
@pytest.mark.parametrize("speed", [0.01, 0.07, 0.3])
def test_the_central_slope_brackets_the_exact_one(decay: str, speed: float):
    """The closed-form slope of a Stribeck law lies within the central difference's own bound of it."""
    law = StribeckLaw(C0, C, 0.1, decay, BS)
    exact, central = law.slope(speed), central_slope(law.slip, speed)
    assert abs(central.value - exact.value) <= central.error + exact.error
    assert central.error < 1e-6 * max(1.0, abs(exact.value))


def test_a_flat_curve_in_rounding_noise_has_no_hopf_point_and_is_not_stable():
    """``g = 0.5 + 0.3 (sin^2 + cos^2 - 1)``: flat, but its central differences are rounding noise of both signs
    (about half each over the samples).  Within the slope's error bound of 0 a sign is unknown: no crossing, and
    steady sliding is not labelled stable."""
    law = SlipCurve(1.0, lambda s: 0.5 + 0.3 * math.sin(s) ** 2 + 0.3 * math.cos(s) ** 2 - 0.3)
    net = belt(Contact("c", ("belt", "m"), law), 0.3)
    signs = {np.sign(law.slope(v).value) for v in np.linspace(0.05, 1.0, 20)}
    assert signs >= {-1.0, 1.0}  # the noise this test is about
    assert hopf_points(net, "belt.velocity", 0.05, 1.0) == []
    assert not steady_sliding(net).stable
