"""The response command at its edges (issue 31): a parameter followed from the edge of its domain, and the
bounds on omega, on the width of a range and on the rows, checked before any work.

``--vary`` used to take ``dPi/dlambda`` by a central difference of step ``1e-6 max(|START|, |STOP|)``, which
left the parameter's domain from its edge (``dashpot.threshold=0:3`` tried a threshold of -3e-6) and blamed
``simulate``'s ``--threshold``; it is now the exact derivative of the period's own phases, into the domain on
its edge (:func:`~lumped.drivers.response.systems.exact_derivative`).  The rows are checked against closed
forms (the linear oscillator's, Den Hartog's) or a Newton solve of the member at the row's value."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_lumped

from lumped.drivers.response import NEWTON_TOL, Orbit, find_orbit
from lumped.drivers.response.curve import MAX_POINTS, request, response_curve
from lumped.drivers.response.systems import OMEGA_RATIO, exact_derivative, response_system, time_scales
from lumped.drivers.response.systems import period_map as any_map
from lumped.model.files import load_system
from lumped.model.forcing import SwitchedSine
from lumped.model.network import Load, Network
from lumped.model.oscillator import Oscillator
from lumped.model.system_parameters import system_parameters, with_values
from lumped.solvers.monodromy import period_map
from lumped.studies.den_hartog import closed_form

ROOT = Path(__file__).resolve().parent.parent
FIGURE3 = ROOT / "examples" / "figure3.toml"  # m = 1 kg, k = 100 N/m, tau = 1 N, gamma = 1 m/(N s)
TWO_MASS = ROOT / "examples" / "two_mass_response.toml"
M, K, TAU, P, OMEGA = 1.0, 100.0, 1.0, 2.5, 5.0


def _with(network, name, value):
    return with_values(network, system_parameters(network, [name]), [value])


def _loaded(network, mass):
    return Network(list(network.masses), list(network.elements), [Load(mass, SwitchedSine(P, OMEGA))])


def _linear(r: float, zeta: float, p: float = P, k: float = K) -> float:
    """The linear oscillator's steady amplitude, ``(P/k)/sqrt((1 - r^2)^2 + (2 zeta r)^2)``."""
    return p / k / math.sqrt((1 - r * r) ** 2 + (2 * zeta * r) ** 2)


# --- the derivative in a parameter -------------------------------------------------------------------


@pytest.mark.parametrize(
    ("path", "mass", "name", "value"),
    [
        (FIGURE3, "m", "dashpot.threshold", 1.0),
        (FIGURE3, "m", "dashpot.gamma", 0.5),
        (FIGURE3, "m", "m.mass", 0.7),
        (FIGURE3, "m", "spring.stiffness", 80.0),
        (FIGURE3, "m", "force.amplitude", P),
        (TWO_MASS, "m2", "floor1.threshold", 1.0),
        (TWO_MASS, "m2", "floor2.gamma", 0.5),
        (TWO_MASS, "m2", "m1.mass", 0.7),
        (TWO_MASS, "m2", "k12.stiffness", 80.0),
        (TWO_MASS, "m2", "force.amplitude", P),
    ],
)
def test_parameter_derivative_is_the_central_difference_of_the_period_map(path, mass, name, value):
    # Central difference with h = 1e-5 |p|: truncation h^2 |Pi'''|/6 ~ 1e-10 of the derivative's size (p in its
    # own units), round-off of the map (~1e-14 of the state's scale) over h: ~1e-9.  1e-7 of the derivative's
    # size leaves a margin of 100 over both; the state is one off the orbit, so that no event sits on an edge.
    loaded = _with(_loaded(load_system(path), mass), name, value)
    system = response_system(Network(loaded.masses, loaded.elements, []), mass)
    state = find_orbit(system, P, OMEGA).state * 1.1
    orbit = Orbit(OMEGA, state, _map(loaded, mass, state))
    exact = exact_derivative(loaded, name, orbit)
    h = 1e-5 * abs(value)
    ends = [_map(_with(loaded, name, value + d), mass, state).end for d in (h, -h)]
    fd = (ends[0] - ends[1]) / (2 * h)
    assert np.max(np.abs(exact - fd)) <= 1e-7 * np.max(np.abs(fd))


def _map(loaded, mass, state):
    """One period of ``loaded`` (its sine on ``mass``) from ``state``."""
    force = loaded.loads[0].force
    system = response_system(Network(loaded.masses, loaded.elements, []), mass)
    return any_map(system, force.amplitude, force.omega, state)


def test_derivative_at_a_threshold_of_zero_is_the_one_into_the_domain():
    # At tau = 0 the derivative is one-sided: the motion with -tau sign(v) added.  Forward difference with
    # h = 1e-6 N: truncation (h/2)|Pi''| ~ 1e-6 of the derivative's size, round-off ~1e-14/h = 1e-8; 1e-5 bounds
    # both with a margin of 10.
    loaded = _with(_loaded(load_system(FIGURE3), "m"), "dashpot.threshold", 0.0)
    osc = Oscillator.bingham(M, K, 0.0, 1.0)
    orbit = find_orbit(osc, P, OMEGA)
    exact = exact_derivative(loaded, "dashpot.threshold", orbit)
    h = 1e-6
    fd = (period_map(Oscillator.bingham(M, K, h, 1.0), P, OMEGA, *orbit.state).end - orbit.period.end) / h
    assert np.max(np.abs(exact - fd)) <= 1e-5 * np.max(np.abs(fd))


# --- ranges that start on the domain's edge ------------------------------------------------------------


@pytest.mark.slow
def test_threshold_from_zero_runs_from_the_linear_oscillator_to_a_held_mass():
    # tau = 0: the linear oscillator (c = 1/gamma = 1 N s/m, zeta = 0.05, r = 0.5); tau = 3 N > P: the mass is held
    # (amplitude exactly 0).  Newton's residual (1e-11 of P/k) moves the fixed point by |(I - M)^-1| <= 10 times
    # that (its multipliers are below 0.6): 1e-10 of P/k.
    curve = response_curve(load_system(FIGURE3), "m", P, 0.0, 3.0, 5, vary="dashpot.threshold", omega=OMEGA)
    tau, x = curve.columns["dashpot.threshold"], curve.columns["amplitude_m"]
    assert tau[0] == 0.0 and tau[-1] == 3.0
    assert abs(x[0] - _linear(OMEGA / 10.0, 0.05)) <= 10 * NEWTON_TOL * P / K
    assert x[-1] == 0.0


@pytest.mark.parametrize(
    ("name", "start", "stop", "omega", "member"),
    [
        ("dashpot.gamma", 1e-7, 1.0, OMEGA, lambda g: Oscillator.bingham(M, K, TAU, g)),
        ("m.mass", 1e-7, 1.0, OMEGA, lambda m: Oscillator.bingham(m, K, TAU, 1.0)),
        # from k = 2e-4 N/m (omega_n = 0.014 rad/s, r = 71, under the bound of 100): the old step, 1e-6 of 250,
        # went below 0
        ("spring.stiffness", 2e-4, 250.0, 1.0, lambda k: Oscillator.bingham(M, k, TAU, 1.0)),
    ],
)
@pytest.mark.slow
def test_range_from_near_the_domains_edge_runs_and_ends_on_the_direct_solves(name, start, stop, omega, member):
    # Each end is the motion Newton finds from rest in the member at that value, a separate solve: both converge
    # to NEWTON_TOL of their own P/k, and |(I - M)^-1| (multipliers below 1 - 1e-5 at gamma = 1e-7, whose slow
    # creep k/c = 1e-5 1/s is what remains) magnifies it to at most 1e5 NEWTON_TOL P/k.
    curve = response_curve(load_system(FIGURE3), "m", P, start, stop, 5, vary=name, omega=omega)
    values, x = curve.columns[name], curve.columns["amplitude_m"]
    assert values[0] == start and values[-1] == stop
    for value, amplitude in ((start, x[0]), (stop, x[-1])):
        osc = member(value)
        ref = find_orbit(osc, P, omega).amplitude
        assert abs(amplitude - ref) <= 1e5 * NEWTON_TOL * P / osc.stiffness + 1e-12 * ref


@pytest.mark.slow
def test_amplitude_from_near_zero_runs_across_decades_of_p_over_k():
    # P = 1e-7 N < tau: the mass is held, amplitude exactly 0.  P = 5 N: each row is converged in its own P/k
    # (not the start's 1e-9 m), and the last is the Newton solve at P = 5 N to 10 NEWTON_TOL of its P/k.
    curve = response_curve(load_system(FIGURE3), "m", P, 1e-7, 5.0, 10, vary="amplitude", omega=OMEGA)
    p, x = curve.columns["amplitude"], curve.columns["amplitude_m"]
    assert p[0] == 1e-7 and p[-1] == 5.0 and x[0] == 0.0
    ref = find_orbit(Oscillator.bingham(M, K, TAU, 1.0), 5.0, OMEGA).amplitude
    assert abs(x[-1] - ref) <= 10 * NEWTON_TOL * 5.0 / K


def test_a_refused_end_names_vary_and_the_files_key_not_simulates_options(tmp_path):
    done = _run(tmp_path, "--omega", "5", "--vary", "dashpot.threshold=-1:2")
    assert done.returncode == 2 and len(done.stderr.strip().splitlines()) == 1
    assert "--vary: dashpot.threshold = -1" in done.stderr and "--threshold" not in done.stderr
    assert list(tmp_path.iterdir()) == []


# --- bounds before work -------------------------------------------------------------------------------


def _run(tmp_path: Path, *more: str):
    args = ["--system", str(FIGURE3), "--force-on", "m", "--amplitude", str(P), *more]
    return run_lumped("response", *args, "--output", str(tmp_path / "r.csv"), cwd=tmp_path)


@pytest.mark.parametrize(
    ("more", "words"),
    [
        (("--omega", "2:20", "--points", "1000000000"), ("--points", f"{MAX_POINTS}")),
        (("--omega", "5:5.000000000000001"), ("--omega", "narrower than 1e-06")),
        (("--omega", "1e10:2e10"), ("--omega", "above 100 times", "1000 rad/s")),
        (("--omega", "1e15:2e15"), ("--omega", "above 100 times")),
        (("--omega", "1e300:1e301"), ("--omega", "above 100 times")),
        (("--omega", "1e30:2e30"), ("--omega", "above 100 times")),
        (("--omega", "1e-300:1e-299"), ("--omega", "below 0.001", "0.00998749 rad/s")),
        (("--omega", "2:inf"), ("--omega", "finite")),
        (
            ("--omega", "5", "--vary", "spring.stiffness=100:1e12"),
            ("--vary", "spring.stiffness = 1e+12", "below 0.001"),
        ),
        (("--omega", "5", "--vary", "m.mass=1e-300:1"), ("--vary", "m.mass = 1e-300", "1e+11")),
        (("--omega", "5", "--vary", "dashpot.threshold=1:1.0000000001"), ("--vary", "dashpot.threshold", "narrower")),
    ],
)
def test_out_of_bounds_is_one_line_naming_the_option_and_its_limit_before_any_work(tmp_path, more, words):
    done = _run(tmp_path, *more)
    assert done.returncode == 2, done.stderr
    assert len(done.stderr.strip().splitlines()) == 1, done.stderr
    assert all(w in done.stderr for w in words), done.stderr
    assert list(tmp_path.iterdir()) == []


def test_the_api_refuses_the_same_bounds_naming_its_arguments():
    network = load_system(FIGURE3)
    with pytest.raises(ValueError, match="^points: "):
        request(network, "m", P, 2.0, 20.0, MAX_POINTS + 1)
    with pytest.raises(ValueError, match="^omega: omega = 1e\\+10 rad/s is above"):
        request(network, "m", P, 1e10, 2e10)
    with pytest.raises(ValueError, match="^vary: at spring.stiffness = 1e\\+12"):
        request(network, "m", P, 100.0, 1e12, vary="spring.stiffness", omega=OMEGA)


def test_the_bounds_are_the_systems_time_scales():
    # One mass: the damped frequency sqrt(k/m - (c/2m)^2) and sqrt(k/m); overdamped (m = 1e-7 kg, c = 1 N s/m):
    # the roots of 1e-7 s^2 + s + 100, -(k/c)(1 + mk/c^2 + ...) = -100.001 and -1e7 1/s, the slower the scale;
    # a network: the eigenfrequencies of (K, M).
    fast, slow, rate = time_scales(response_system(load_system(FIGURE3), "m"))
    assert math.isclose(fast, math.sqrt(100 - 0.25), rel_tol=1e-14) and math.isclose(slow, 10.0, rel_tol=1e-14)
    fast, _, rate = time_scales(response_system(_with(load_system(FIGURE3), "m.mass", 1e-7), "m"))
    assert math.isclose(fast, 100.001, rel_tol=1e-7) and math.isclose(rate, 1e7, rel_tol=1e-4)
    _, slow, _ = time_scales(response_system(load_system(TWO_MASS), "m2"))
    assert math.isclose(slow, math.sqrt(150 - math.sqrt(12500)), rel_tol=1e-12)


def test_at_the_upper_bound_the_amplitude_is_den_hartogs(tmp_path):
    # Coulomb (gamma = inf), r = 100 (the bound): the motion slips through the period, and Den Hartog's closed
    # form holds.  The amplitude is ~1e-4 of P/k while the fixed point is found to NEWTON_TOL of P/k and the map
    # adds terms of size P/k: NEWTON_TOL r^2 = 1e-7 of it (the bound's argument, systems.check_omega).
    coulomb = tmp_path / "coulomb.toml"  # figure3.toml with gamma = inf
    coulomb.write_text(FIGURE3.read_text().replace("gamma = 1.0 ", "gamma = inf "))
    network = load_system(coulomb)
    hi = OMEGA_RATIO[1] * 10.0
    curve = response_curve(network, "m", P, hi * (1 - 1e-3), hi, 2)
    for omega, x in zip(curve.columns["omega"], curve.columns["amplitude_m"], strict=True):
        ref = closed_form(M, 0.0, K, TAU, P, omega)
        assert ref.nonstop and abs(x - ref.amplitude) <= NEWTON_TOL * (omega / 10.0) ** 2 * ref.amplitude


def test_at_the_lower_bound_the_amplitude_is_the_linear_oscillators():
    # tau = 0, zeta = 0.05: omega = 1e-3 of the damped frequency (the bound), the quasi-static X_s/(1 - r^2);
    # Newton's residual (1e-11 of P/k) with multipliers ~0: 1e-11 of P/k, plus round-off.
    network = _with(load_system(FIGURE3), "dashpot.threshold", 0.0)
    lo = OMEGA_RATIO[0] * math.sqrt(100 - 0.25)
    curve = response_curve(network, "m", P, lo, lo * (1 + 1e-3), 2)
    for omega, x in zip(curve.columns["omega"], curve.columns["amplitude_m"], strict=True):
        assert abs(x - _linear(omega / 10.0, 0.05)) <= 2 * NEWTON_TOL * P / K


def test_command_at_the_bounds_writes_its_rows(tmp_path):
    done = _run(tmp_path, "--omega", "0.0099875:1000", "--points", "2")
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader((tmp_path / "r.csv").open()))
    assert float(rows[0]["omega"]) == 0.0099875 and float(rows[-1]["omega"]) == 1000
