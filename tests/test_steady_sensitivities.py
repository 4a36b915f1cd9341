"""The steady amplitude's derivatives (issue 24) against independent references: central differences of the
amplitude of periodic motions found by Newton, the viscous oscillator's closed form, Den Hartog's nonstop Coulomb
amplitude (differentiated here by hand), and one-sided differences where a stop appears."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import ROOT

from lumped.drivers.response import find_orbit
from lumped.drivers.response.shooting import NEWTON_TOL
from lumped.drivers.steady_sensitivity import steady_amplitude_sensitivities
from lumped.laws import GROUND, Bingham, Spring
from lumped.model.files import load_system
from lumped.model.network import Mass, Network
from lumped.model.oscillator import Oscillator
from lumped.solvers.steady_sensitivities import fixed_point_derivative, steady_sensitivities
from lumped.studies.den_hartog import closed_form

#: The one-mass names of the derivatives, and the systems (m, k, tau, c = 1/gamma, P, omega): the paper's forced
#: oscillator without stops (notebook 14), a Bingham mass with two stops per period, a Coulomb mass with two
#: stops per period, and a viscous one (tau = 0).
NAMES = ("mass", "stiffness", "threshold", "viscosity", "force_amplitude", "force_omega")
CASES = {
    "paper, nonstop": (1.0, 100.0, 1.0, 1.0, 10.0, 5 * math.pi),
    "Bingham, two stops": (1.0, 100.0, 1.0, 1.0, 2.5, 5.0),
    "Coulomb, two stops": (1.0, 100.0, 1.0, 0.0, 2.5, 5.0),
    "viscous": (2.0, 50.0, 0.0, 2.0, 2.0, 4.0),
}
#: Newton's residual in the differences below: 100 times the period map's round-off (:data:`NEWTON_TOL`'s
#: note: its event times are good to a few ulps of the period, ~1e-15 of unit amplitude), so that it is reached
#: from a guess near the orbit, yet 100 times below NEWTON_TOL (which would leave 1e-6 in the differences).
TOL = 1e-13


def _oscillator(m, k, tau, c):
    return Oscillator.bingham(m, k, tau, math.inf if c == 0 else 1.0 / c)


def _amplitude(p: tuple, guess: np.ndarray) -> float:
    m, k, tau, c, P, w = p
    return find_orbit(_oscillator(m, k, tau, c), P, w, guess, tol=TOL).amplitude


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("name", NAMES)
def test_the_amplitude_derivative_matches_central_differences_of_newton_orbits(case, name):
    p = CASES[case]
    j = NAMES.index(name)
    if p[j] == 0:
        pytest.skip("tau = 0 or c = 0 is the edge of its range: no central difference straddles it")
    m, k, tau, c, P, w = p
    orbit = find_orbit(_oscillator(m, k, tau, c), P, w, tol=TOL)
    sens = steady_sensitivities(orbit.period.solution, [name])
    assert sens.margin > 1e-2  # no stop appears or vanishes nearby
    # Central difference D_h with h = 1e-4 |p|: error <= h^2/6 |A'''| + eps_A/h.  |A'''| is bounded by twice the
    # five-point third difference at H = 10 h.  eps_A bounds an amplitude's error: the orbit's state is within
    # |(I - M)^-1| TOL X_s of the fixed point (X_s = P/k, Newton's residual TOL in those units), and that moves
    # x's extremes by as much; the exact solver's own round-off (~1e-15 X_s) is below it.
    h, big = 1e-4 * abs(p[j]), 1e-3 * abs(p[j])
    f = {s: _amplitude(p[:j] + (p[j] + s,) + p[j + 1 :], orbit.state) for s in (-2 * big, -big, -h, h, big, 2 * big)}
    d_h = (f[h] - f[-h]) / (2 * h)
    third = (f[2 * big] - 2 * f[big] + 2 * f[-big] - f[-2 * big]) / (2 * big**3)
    kappa = np.linalg.norm(np.linalg.inv(np.eye(2) - orbit.period.monodromy), np.inf)
    eps_a = 2 * kappa * TOL * max(P / k, P / k * math.sqrt(k / m))
    bound = h**2 / 6 * 2 * abs(third) + eps_a / h
    assert abs(sens.derivatives[0] - d_h) <= bound
    assert bound < 1e-5 * abs(d_h)  # the test can fail: the bound is far below the derivative


def _den_hartog(m: float, k: float, F: float, P: float, w: float) -> tuple[float, dict[str, float]]:
    """Den Hartog's nonstop amplitude X and its derivatives in (F, P, omega, k, m), by hand.

    ``X^2 = G1 - G2`` with ``G1 = P^2/S^2`` (``S = k - m w^2``) and ``G2 = F^2 U^2/(k m w^2)``, ``U = tan th``,
    ``th = pi/(2 r)``, ``r = w sqrt(m/k)``: notebook 11's eq. (4) ``X k/P = sqrt(1/(1 - r^2)^2 - (F/P)^2
    (U/r)^2)`` multiplied out.  ``d ln U/d ln r = -2 th/sin(2 th)``; ``d ln r = d ln w + (d ln m - d ln k)/2``.
    """
    S = k - m * w * w
    th = math.pi * math.sqrt(k / m) / (2 * w)
    G1, G2 = P * P / S**2, F * F * math.tan(th) ** 2 / (k * m * w * w)
    lnu = -2 * th / math.sin(2 * th)
    dG = {
        "threshold": -2 * G2 / F,
        "force_amplitude": 2 * G1 / P,
        "force_omega": 4 * P * P * m * w / S**3 - G2 * (2 * lnu / w - 2 / w),
        "stiffness": -2 * P * P / S**3 - G2 * (-lnu / k - 1 / k),
        "mass": 2 * P * P * w * w / S**3 - G2 * (lnu / m - 1 / m),
    }
    X = math.sqrt(G1 - G2)
    return X, {name: g / (2 * X) for name, g in dG.items()}


def _viscous(m: float, k: float, c: float, P: float, w: float) -> tuple[float, dict[str, float]]:
    """``X = (P/k)/sqrt((1 - r^2)^2 + (2 zeta r)^2) = P/sqrt(D)``, ``D = S^2 + (c w)^2``, ``S = k - m w^2``."""
    S = k - m * w * w
    D = S * S + (c * w) ** 2
    d = {
        "viscosity": -P * c * w * w / D**1.5,
        "force_amplitude": 1 / math.sqrt(D),
        "force_omega": -P * (-2 * m * w * S + c * c * w) / D**1.5,
        "stiffness": -P * S / D**1.5,
        "mass": P * S * w * w / D**1.5,
    }
    return P / math.sqrt(D), d | {"gamma": -c * c * d["viscosity"]}


# The closed forms against the derivatives of find_orbit's orbits: the orbit's state is within ~1e-11 X_s
# (NEWTON_TOL) of the fixed point, which moves the derivatives by ~1e-11 relative; the chain's round-off is
# ~1e-13 (a few matrix exponentials per phase).  1e-9 relative leaves a factor 100.
CLOSED = 1e-9


@pytest.mark.parametrize(("m", "k", "F", "P", "w"), [(1.0, 100.0, 1.0, 2.5, 15.0), (2.0, 50.0, 0.5, 2.0, 8.0)])
def test_den_hartogs_nonstop_amplitude_and_its_derivatives(m, k, F, P, w):
    assert closed_form(m, 0.0, k, F, P, w).nonstop
    X, d = _den_hartog(m, k, F, P, w)
    got = steady_amplitude_sensitivities(Oscillator.bingham(m, k, F, math.inf), None, P, w, list(d))
    assert got.stops == 0 and got.margin > 1
    assert got.amplitude == pytest.approx(X, rel=CLOSED)
    for name, value in d.items():
        assert got.derivatives[name] == pytest.approx(value, rel=CLOSED), name
    assert NEWTON_TOL == 1e-11  # the tolerance CLOSED is derived from


@pytest.mark.parametrize(("m", "k", "c", "P", "w"), [(1.0, 100.0, 0.7, 2.5, 15.0), (2.0, 50.0, 2.0, 2.0, 4.0)])
def test_the_viscous_oscillators_amplitude_and_its_derivatives(m, k, c, P, w):
    X, d = _viscous(m, k, c, P, w)
    got = steady_amplitude_sensitivities(Oscillator.bingham(m, k, 0.0, 1.0 / c), None, P, w, list(d))
    assert got.stops == 0
    assert got.amplitude == pytest.approx(X, rel=CLOSED)
    for name, value in d.items():
        assert got.derivatives[name] == pytest.approx(value, rel=CLOSED), name


def test_the_implicit_function_formula_on_a_linear_map():
    # Pi(z; p) = A z + b p with A fixed: z* = (I - A)^-1 b p, so dz*/dp = (I - A)^-1 b, and with the end moving
    # at the rate f, dPi/dp gains f dT/dp.  The solve is exact to a few ulps.
    A, b, f = np.array([[0.2, 0.5], [-0.3, 0.1]]), np.array([[1.0], [2.0]]), np.array([3.0, -1.0])
    want = np.linalg.inv(np.eye(2) - A) @ (b + np.outer(f, [0.5]))
    assert np.allclose(fixed_point_derivative(A, b, f, np.array([0.5])), want, rtol=1e-14, atol=0)


def _stops_edge() -> tuple[float, float, np.ndarray]:
    """Neighbouring doubles P_lo < P_hi at which the Bingham mass's two stops per period (omega = 5 rad/s)
    vanish, and the orbit's state there (bisection: a stop appears where its net force is on the band's edge)."""
    osc, lo, hi = _oscillator(1.0, 100.0, 1.0, 1.0), 3.45, 3.5
    z = find_orbit(osc, lo, 5.0).state
    assert find_orbit(osc, lo, 5.0, z).stops == 2 and find_orbit(osc, hi, 5.0, z).stops == 0
    while math.nextafter(lo, hi) < hi:
        mid = 0.5 * (lo + hi)
        orbit = find_orbit(osc, mid, 5.0, z)
        lo, hi, z = (mid, hi, orbit.state) if orbit.stops == 2 else (lo, mid, z)
    return lo, hi, z


def test_where_the_stops_vanish_the_one_sided_derivatives_match_one_sided_differences():
    # At the edge the stops' net force lies on the band's edge (margin ~1e-16) and the sides at p -+ delta have 2
    # and 0 stops.  A one-sided difference with step h is off by h/2 |A''| (bounded by 2 |D_h - D_2h|) plus
    # 2 eps_A/h (the orbits' error, as in the central differences above); each side's derivative is the
    # one-sided one to delta |A''| (delta = 1e-9 p, |A''| <= 4 |D_h - D_2h|/h).  Both sides turn out to agree:
    # the new stick starts with the net force on the edge, so with zero acceleration, and moving its start
    # changes the motion at second order only: A is C^1 there, though the stops per period jump from 2 to 0.
    lo, _, z = _stops_edge()
    osc, names = _oscillator(1.0, 100.0, 1.0, 1.0), ["force_amplitude", "threshold", "force_omega"]
    got = steady_amplitude_sensitivities(osc, None, lo, 5.0, names, z)
    assert got.margin < 1e-12 and got.stops_change
    assert "a stop appears or vanishes here" in got.summary()
    kappa = np.linalg.norm(np.linalg.inv(np.eye(2) - got.orbit.period.monodromy), np.inf)
    eps_a = 2 * kappa * TOL * lo / 100.0 * 10.0  # X_s omega_n = (P/k) sqrt(k/m)
    for j, side in enumerate(got.one_sided):
        assert side.parameter == names[j] and {side.stops_below, side.stops_above} == {0, 2}
        base = np.array([lo, 1.0, 5.0])
        h = 1e-5 * base[j]

        def at(s: float) -> float:
            P, tau, w = base + s * np.eye(3)[j]  # noqa: B023 (called within this iteration)
            return _amplitude((1.0, 100.0, tau, 1.0, P, w), z)

        a0 = at(0.0)
        for sign, want in ((1, side.above), (-1, side.below)):
            d_h, d_2h = sign * (at(sign * h) - a0) / h, sign * (at(2 * sign * h) - a0) / (2 * h)
            second = 4 * abs(d_2h - d_h) / h + 4 * eps_a / h**2
            assert abs(want - d_h) <= h / 2 * second + 2 * eps_a / h + side.delta * second
        assert abs(side.above - side.below) <= 2 * side.delta * second + 1e-12 * abs(side.above)  # C^1: no kink
        assert abs(side.jump) <= 1e-12 * got.amplitude  # nor a jump


def _paper_network() -> Network:
    """The paper's mass as ``examples/figure3.toml`` names it, without loads (as the ``response`` command takes it)."""
    between = (GROUND, "m")
    return Network([Mass("m", 1.0, 0.5)], [Spring("spring", between, 100.0), Bingham("dashpot", between, 1.0, 1.0)])


def test_a_system_files_names_give_the_oscillators_derivatives():
    names = ["dashpot.threshold", "dashpot.gamma", "spring.stiffness", "m.mass", "force.amplitude", "force.omega"]
    got = steady_amplitude_sensitivities(_paper_network(), "m", 10.0, 5 * math.pi, names)
    same = steady_amplitude_sensitivities(
        Oscillator.bingham(), None, 10.0, 5 * math.pi, ["threshold", "gamma", "stiffness", "mass"]
    )
    assert list(got.derivatives) == names and got.amplitude == same.amplitude and not got.one_sided
    assert [got.derivatives[n] for n in names[:4]] == list(same.derivatives.values())  # the same computation


@pytest.mark.parametrize(
    ("system", "mass", "names", "message"),
    [
        ("net", "m", "m.x0", r"^parameters: the steady amplitude does not depend on 'm.x0'$"),
        ("net", "m", "force.phase", r"^parameters: the steady amplitude does not depend on 'force.phase'$"),
        ("net", "m", "dashpot.tau", r"^parameters: unknown parameter 'dashpot.tau'; this system's are "),
        ("net", "q", "m.mass", r"^force_on: no mass named 'q' in the system \(its masses: m\)$"),
        ("osc", None, ["x0"], r"^parameters: the steady amplitude has no derivative in 'x0'; expected some of mass,"),
        ("dict", None, ["mass"], r"^system must be a Network or an Oscillator, got dict$"),
        ("two", "m1", "force.phase", r"^parameters: the steady amplitude does not depend on 'force.phase'$"),
    ],
)
def test_bad_arguments_are_refused_in_one_line(system, mass, names, message):
    two = load_system(ROOT / "examples" / "two_mass_response.toml")
    system = {"net": _paper_network(), "osc": Oscillator.bingham(), "dict": {}, "two": two}[system]
    with pytest.raises(ValueError, match=message):
        steady_amplitude_sensitivities(system, mass, 10.0, 5 * math.pi, names)
