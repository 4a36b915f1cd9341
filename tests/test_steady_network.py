"""The steady amplitude's derivatives of a network's periodic motion (issue 24), against central differences of
the periodic motions Newton finds, and against the one-mass code on a one-mass system run as a network."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from lumped.drivers.response import find_orbit
from lumped.drivers.response.systems import LoadedNetwork, response_system
from lumped.drivers.steady_sensitivity import steady_amplitude_sensitivities
from lumped.model.files import load_system
from lumped.model.network import Network
from lumped.model.system_parameters import system_parameters, with_values
from lumped.solvers.network_phase import parts
from lumped.solvers.network_sensitivities import Parameter
from lumped.solvers.steady_sensitivities import network_steady_sensitivities

ROOT = Path(__file__).resolve().parent.parent
#: Two blocks on springs (k1 to the wall, k12 between them), each on a Bingham contact to the floor; 5 N on m1.
TWO = load_system(ROOT / "examples" / "two_mass_response.toml")
P = 5.0
NAMES = ["k12.stiffness", "floor1.threshold", "floor2.gamma", "m2.mass", "force.amplitude", "force.omega"]


def _amplitude(name: str, value: float, omega: float, guess: np.ndarray) -> float:
    """The loaded mass's amplitude of the periodic motion with ``name`` set to ``value`` (Newton to 1e-13)."""
    net, p, w = TWO, P, omega
    if name == "force.amplitude":
        p = value
    elif name == "force.omega":
        w = value
    else:
        net = with_values(TWO, system_parameters(TWO, [name]), [value])
    return find_orbit(response_system(net, "m1"), p, w, guess, tol=1e-13).amplitude


@pytest.mark.parametrize(("omega", "stops"), [(3.0, 4), (5.5, 2), (14.0, 0)])
def test_network_amplitude_derivatives_are_the_central_differences(omega, stops):
    # Central differences with h = 1e-5 of each value: they converge as h^2 to the derivatives (checked from
    # h = 1e-3 to 1e-5 in development: 2e-4, 2e-6, 2e-8 relative at the worst case, omega = 5.5 with two stops),
    # so the truncation here is ~2e-8; Newton's 1e-13 residual over h adds ~1e-13 |(I - M)^-1| X_s/(h p) < 1e-7.
    # Asserted: 1e-6 of max(|dA/dp|, 1e-3 A), ten times both.
    res = steady_amplitude_sensitivities(TWO, "m1", P, omega, NAMES)
    assert res.stops == stops and res.margin > 0.05  # away from a change of the event sequence
    values = {
        **{p.name: p.value for p in system_parameters(TWO, NAMES[:4])},
        "force.amplitude": P,
        "force.omega": omega,
    }
    for name in NAMES:
        h = 1e-5 * values[name]
        up, down = (_amplitude(name, values[name] + s * h, omega, res.orbit.state) for s in (1, -1))
        fd = (up - down) / (2 * h)
        assert abs(fd - res.derivatives[name]) <= 1e-6 * max(abs(res.derivatives[name]), 1e-3 * res.amplitude), name


def test_an_element_held_through_the_period_keeps_its_elongation():
    # At 30 rad/s m2's contact sticks through the period: m2 never moves, so its mass does not enter (exactly 0),
    # and the held elongation stays as the others move (the differences start Newton from the same state).
    res = steady_amplitude_sensitivities(TWO, "m1", P, 30.0, ["m2.mass", "k12.stiffness", "force.omega"])
    assert res.orbit.period.held.size == 1 and res.derivatives["m2.mass"] == 0.0
    for name, value in (("k12.stiffness", system_parameters(TWO, ["k12.stiffness"])[0].value), ("force.omega", 30.0)):
        h = 1e-5 * value
        fd = (
            _amplitude(name, value + h, 30.0, res.orbit.state) - _amplitude(name, value - h, 30.0, res.orbit.state)
        ) / (2 * h)
        assert abs(fd - res.derivatives[name]) <= 1e-6 * abs(res.derivatives[name])


@pytest.mark.parametrize("omega", [4.0, 8.0, 17.0])
def test_one_mass_run_as_a_network_gives_the_one_mass_derivatives(omega):
    # Two codes: the one-mass chain (closed-form phases, lumped.solvers.sensitivities) and the network's block
    # exponentials (lumped.solvers.network_sensitivities); they differ by roundings: 1e-12 relative.
    one = load_system(ROOT / "examples" / "figure3.toml")
    one = Network(list(one.masses), list(one.elements), [])
    names = ["spring.stiffness", "dashpot.threshold", "m.mass", "force.amplitude", "force.omega"]
    ref = steady_amplitude_sensitivities(one, "m", 2.5, omega, names)
    net = LoadedNetwork(parts(one), 0, ("m",), tuple(one.element_names))
    orbit = find_orbit(net, 2.5, omega, ref.orbit.state)
    kinds = [Parameter("stiffness", 0), Parameter("threshold", 1), Parameter("mass", 0)]
    amps, d, _, _ = network_steady_sensitivities(
        orbit.period, orbit.state, [*kinds, Parameter("amplitude"), Parameter("omega")], list(one.element_names)
    )
    assert abs(amps[0] - ref.amplitude) <= 1e-12 * ref.amplitude
    expected = np.array([ref.derivatives[n] for n in names])
    assert np.max(np.abs(d[0] - expected) / np.abs(expected)) <= 1e-12


@pytest.mark.parametrize(("name", "words"), [("m1.x0", "does not depend on 'm1.x0'"), ("k99.stiffness", "unknown")])
def test_network_refusals_are_one_line(name, words):
    with pytest.raises(ValueError, match=words) as err:
        steady_amplitude_sensitivities(TWO, "m1", P, 5.5, [name])
    assert "\n" not in str(err.value)
