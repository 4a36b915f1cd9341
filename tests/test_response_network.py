"""Response curves of networks (issue 23, second part): the network monodromy against central differences of the
exact network period map, the energy of a difference never growing over a period (why no fold appears), the
two-mass example without friction against the linear two-degree-of-freedom response, elements that stick through
the period, the detection of changes on a synthetic branch, and the command."""

from __future__ import annotations

import csv
import math
import subprocess
import tomllib
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_lumped
from scipy.linalg import sqrtm

import lumped as L
from lumped.drivers.response import NEWTON_TOL, find_orbit
from lumped.drivers.response.continuation import change, signature
from lumped.drivers.response.curve import response_curve
from lumped.drivers.response.systems import LoadedNetwork, Scales, omega_derivative, period_map, response_system

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "two_mass_response.toml"
P = 5.0  # N, the example's amplitude

#: Two oscillators (100 and 400 N/m, 1 kg each, light dashpots) joined by a Coulomb pad: when the pad sticks the
#: two masses move as one group (the projection onto a group's velocity).
COUPLED = """
[[mass]]
name = "m1"
mass = 1.0
[[mass]]
name = "m2"
mass = 1.0
[[element]]
name = "k1"
kind = "spring"
between = ["ground", "m1"]
stiffness = 100.0
[[element]]
name = "k2"
kind = "spring"
between = ["ground", "m2"]
stiffness = 400.0
[[element]]
name = "c1"
kind = "dashpot"
between = ["ground", "m1"]
damping = 0.1
[[element]]
name = "c2"
kind = "dashpot"
between = ["ground", "m2"]
damping = 0.1
[[element]]
name = "pad"
kind = "bingham"
between = ["m1", "m2"]
threshold = 1.0
gamma = inf
"""

#: A block on a spring (and a light dashpot) with a light second block on a spring, held to the floor by a Coulomb
#: contact: a spring that slips, so the system softens as the amplitude grows (where a fold would be expected).
SOFTENING = """
[[mass]]
name = "m1"
mass = 1.0
[[mass]]
name = "m2"
mass = 0.05
[[element]]
name = "k1"
kind = "spring"
between = ["ground", "m1"]
stiffness = 100.0
[[element]]
name = "c1"
kind = "dashpot"
between = ["ground", "m1"]
damping = 0.2
[[element]]
name = "k2"
kind = "spring"
between = ["m1", "m2"]
stiffness = 100.0
[[element]]
name = "pad"
kind = "bingham"
between = ["ground", "m2"]
threshold = 1.0
gamma = inf
"""


def example(threshold: float = 1.0) -> L.Network:
    """The two-mass example, with its contacts' thresholds set to ``threshold`` (N)."""
    return L.parse_system(EXAMPLE.read_text().replace("threshold = 1.0", f"threshold = {threshold!r}"))


def scale_vector(system: LoadedNetwork, amplitude: float) -> np.ndarray:
    s = Scales.of(system, amplitude)
    return np.repeat([s.x, s.v], system.parts.m.size)


# --- the monodromy matrix of a network ---------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "mass", "amplitude", "omega", "stops"),
    [
        (None, "m1", P, 3.0, 4),  # both contacts stop and break away twice a period
        (None, "m1", P, 5.5, 2),  # m1's contact sticks briefly at each turn
        (None, "m1", P, 8.0, 0),  # reversals only
        (COUPLED, "m1", 1.0, 14.0, 2),  # the pad joins the masses into one group, then lets go
    ],
)
def test_network_monodromy_is_the_derivative_of_the_exact_period_map(text, mass, amplitude, omega, stops):
    # Central differences with step h = 1e-6 of the scales (P/k, omega_n P/k): truncation h^2 |Pi'''| ~ 1e-12;
    # round-off of the map (event times refined to 4 ulps, matrix exponentials good to ~1e-15, states to ~1e-13
    # of the scales) over h: 1e-7.  Ten times that: 1e-6.  The orbits start with every contact slipping, where the
    # map is smooth (a contact stuck at t = 0 makes it only once differentiable across v = 0).
    system = response_system(example() if text is None else L.parse_system(text), mass)
    orbit = find_orbit(system, amplitude, omega)
    assert orbit.stops == stops
    assert np.all(orbit.period.phases[0].mode[system.parts.friction] != 0)
    scale = scale_vector(system, amplitude)
    fd = np.empty((scale.size, scale.size))
    for j, h in enumerate(1e-6 * scale):
        step = h * np.eye(scale.size)[j]
        plus, minus = (period_map(system, amplitude, omega, orbit.state + s).end for s in (step, -step))
        fd[:, j] = (plus - minus) / (2 * h)
    scaled = lambda a: a * scale[None, :] / scale[:, None]
    assert np.max(np.abs(scaled(orbit.period.monodromy) - scaled(fd))) <= 1e-6
    # dPi/domega (the continuation's column, lumped.drivers.response.systems.omega_derivative: the period's phases
    # differentiated in omega, the end moving by -T/omega) against a central difference with h = 1e-6 omega; the
    # same error budget, for omega dPi/domega in units of the state's scales: 1e-6.
    h = 1e-6 * omega
    plus, minus = (period_map(system, amplitude, omega + s, orbit.state).end for s in (h, -h))
    exact = omega_derivative(system, amplitude, orbit)
    assert np.max(np.abs(exact - (plus - minus) / (2 * h)) * omega / scale) <= 1e-6


def energy_factor(system: L.Oscillator | LoadedNetwork) -> np.ndarray:
    """``L`` with ``|L dy|^2 / 2`` the energy of a difference of states: ``dv^T M dv / 2 + dx^T K dx / 2``."""
    if isinstance(system, L.Oscillator):
        k, m = np.array([[system.stiffness]]), np.array([[system.mass]])
    else:
        k, m = system.stiffness, np.diag(system.parts.m)
    zero = np.zeros_like(k)
    return np.block([[sqrtm(k).real, zero], [zero, np.sqrt(m)]])


@pytest.mark.parametrize(
    ("text", "mass", "amplitude", "omegas"),
    [
        (None, "m1", P, (2.0, 5.5, 16.0, 23.0, 30.0)),  # at 30 rad/s m2's contact sticks through the period
        (COUPLED, "m2", 1.0, (14.0, 15.0, 18.8, 19.5)),  # near the steepest part of its curve
        (COUPLED, "m2", 1.3, (19.8, 19.95, 20.05)),
        (SOFTENING, "m1", 1.0, (9.0, 10.1, 10.5, 11.2, 12.0)),  # at 9 rad/s the pad sticks through the period
    ],
)
def test_the_period_map_never_expands_the_energy_of_a_difference(text, mass, amplitude, omegas):
    # Two motions of the same network differ by (dx, dv); the energy of the difference, E = dv^T M dv/2 +
    # dx^T K dx/2, changes at the rate -dv^T C dv - sum_e dw_e df_e <= 0 (dashpots, and each friction element's
    # force a monotone function of its rate w_e, sticking included).  So the monodromy is non-expansive in that
    # norm: |L M L^-1|_2 <= 1, and no multiplier leaves the unit circle, no fold, no unstable motion, no
    # coexisting isolated ones (the fixed points of a non-expansive map in a Euclidean norm form a convex set).
    # The matrices' round-off (products of some ten exponentials and saltations, each good to ~1e-14) is far
    # below the 1e-9 allowed.
    system = response_system(example() if text is None else L.parse_system(text), mass)
    lf = energy_factor(system)
    for omega in omegas:
        orbit = find_orbit(system, amplitude, omega)
        assert np.linalg.norm(lf @ orbit.period.monodromy @ np.linalg.inv(lf), 2) <= 1 + 1e-9
        assert orbit.stable


@pytest.mark.parametrize(("gamma", "ratio", "r"), [(math.inf, 0.5, 0.5), (1.0, 0.8, 1.5), (1.0, 0.8, 0.3)])
def test_the_one_mass_period_map_never_expands_the_energy_either(gamma, ratio, r):
    osc = L.Oscillator.bingham(1.0, 100.0, 1.0, gamma)
    orbit = find_orbit(osc, 1.0 / ratio, 10.0 * r)
    lf = energy_factor(osc)
    assert orbit.stops > 0
    assert np.linalg.norm(lf @ orbit.period.monodromy @ np.linalg.inv(lf), 2) <= 1 + 1e-9


# --- the two-mass example -------------------------------------------------------------------------------


def linear_amplitudes(omega: np.ndarray) -> np.ndarray:
    """``|X|`` per mass (rows per omega) of ``(K - omega^2 M + i omega C) X = F``, F = P on m1: the steady motion
    ``Im(X exp(i omega t))`` of the example's chain with its contacts as dashpots of damping ``1/gamma``, the
    matrices assembled here from the file's entries."""
    spec = tomllib.loads(EXAMPLE.read_text())
    names = [m["name"] for m in spec["mass"]]
    n = len(names)
    k, c = np.zeros((n, n)), np.zeros((n, n))
    for el in spec["element"]:
        value, matrix = (el["stiffness"], k) if el["kind"] == "spring" else (1 / el["gamma"], c)
        ends = [names.index(p) for p in el["between"] if p != "ground"]
        for i in ends:
            matrix[i, i] += value
        if len(ends) == 2:
            matrix[ends[0], ends[1]] -= value
            matrix[ends[1], ends[0]] -= value
    m = np.diag([float(mass["mass"]) for mass in spec["mass"]])
    force = np.zeros(n, dtype=complex)
    force[names.index("m1")] = P
    return np.array([np.abs(np.linalg.solve(k - w * w * m + 1j * w * c, force)) for w in omega])


def test_without_friction_the_example_is_the_linear_two_degree_of_freedom_response():
    # Newton stops at a residual of NEWTON_TOL (largest component, scaled units): the fixed point is off by at most
    # |(M - I)^-1|_2 sqrt(2n) NEWTON_TOL in the scaled Euclidean norm, and the motion from it by at most cond(L) times
    # that over the period (the energy of the difference never grows; L the energy factor on scaled states): that
    # bounds each amplitude's error (times P/k, the unit of x); the closed form adds ~1e-13 of the amplitude.
    network = example(threshold=0.0)
    system = response_system(network, "m1")
    assert not system.parts.friction.any()
    curve = response_curve(network, "m1", P, 2.0, 25.0, points=20).columns
    omega = curve["omega"]
    assert omega[0] == 2.0 and omega[-1] == 25.0 and omega.size >= 20
    reference = linear_amplitudes(omega)
    scale = scale_vector(system, P)
    energy = energy_factor(system) * scale[None, :]
    worst = 0.0
    for row, w in enumerate(omega):
        monodromy = period_map(system, P, w, np.zeros(4)).monodromy  # the same for every state: one linear phase
        gap = np.linalg.inv(monodromy - np.eye(4)) * scale[None, :] / scale[:, None]
        bound = np.linalg.cond(energy) * np.linalg.norm(gap, 2) * 2 * NEWTON_TOL * scale[0]
        for i, name in enumerate(system.masses):
            error = abs(curve[f"amplitude_{name}"][row] - reference[row, i])
            assert error <= bound + 1e-13 * reference[row, i]
            worst = max(worst, error / reference[row, i])
    assert worst <= 1e-9


# --- elements that stick through the period; runs of the exact solver on the orbits ------------------------------


def run_from(network: L.Network, mass: str, amplitude: float, omega: float, state: np.ndarray, periods: int):
    """The states (rows) at t = 0, T, 2T, ... of ``solve_exact_network`` from ``state`` under the sine on ``mass``."""
    from lumped.solvers.exact_network import solve_exact_network

    n = len(network.masses)
    masses = tuple(L.Mass(m.name, m.mass, float(state[i]), float(state[n + i])) for i, m in enumerate(network.masses))
    loaded = L.Network(masses, network.elements, (L.Load(mass, L.SwitchedSine(amplitude, omega)),))
    period = 2 * math.pi / omega
    run = solve_exact_network(loaded, periods * period, period)
    return np.hstack([run.positions, run.velocities])


def test_a_contact_stuck_through_the_period_is_a_neutral_direction_left_out_of_the_multipliers():
    # At 30 rad/s m2's contact sticks for good: every elongation in its band is periodic, the monodromy keeps it
    # (r M = r for the elongation r, to round-off), and the other three multipliers decide the stability.
    network = example()
    system = response_system(network, "m1")
    orbit = find_orbit(system, P, 30.0)
    assert [system.elements[e] for e in orbit.period.held] == ["floor2"]
    r = orbit.period.neutral
    assert np.max(np.abs(r @ orbit.period.monodromy - r)) <= 1e-12
    assert orbit.multipliers.size == 3 and orbit.stable
    # a run of the exact network solver from the orbit repeats it, period after period, to Newton's tolerance
    # amplified by at most |(M - I)^-1| on the free directions (about 3 here: 1e-10 of P/k allowed)
    states = run_from(network, "m1", P, 30.0, orbit.state, 10)
    scale = scale_vector(system, P)
    assert np.max(np.abs((states - orbit.state) / scale)) <= 1e-10


@pytest.mark.parametrize("omega", [5.5, 16.0])
def test_a_stable_network_orbit_is_not_left_by_a_perturbed_run(omega):
    # Perturbed by 1e-9 of the scales, a run of the exact solver never gets further from the orbit in the energy
    # norm (the test above; the orbit's own error, ~1e-11 of the scales, allows 1 %), and returns towards it: the
    # largest multiplier is below 0.8, so after 20 periods the gap is within 0.8^20 = 0.012 of the first plus the
    # orbit's error: within a tenth of it.
    network = example()
    system = response_system(network, "m1")
    orbit = find_orbit(system, P, omega)
    assert orbit.max_multiplier < 0.8
    scale = scale_vector(system, P)
    states = run_from(network, "m1", P, omega, orbit.state + 1e-9 * scale, 20)
    gaps = np.linalg.norm((states - orbit.state) @ energy_factor(system).T, axis=1)
    assert np.all(gaps <= 1.01 * gaps[0]) and gaps[-1] <= 0.1 * gaps[0]


def test_a_slip_that_reverses_and_stops_within_one_sub_step_is_located_not_repeated():
    # A state met while following the example's branch (omega = 5.71 rad/s): m1's contact reverses at t = 0.4508 s
    # with its acceleration barely past zero, slips back for about a millisecond and stops.  The exact network
    # solver used to see the new slip's rate below zero at the end of its first sub-step and fire the same stop
    # again at the same instant, without end; it must find the second stop inside the sub-step.
    from lumped.solvers.exact_network import march
    from lumped.solvers.network_monodromy import forced_parts
    from lumped.solvers.network_phase import parts

    network, omega = example(), 5.712672775937431
    p = forced_parts(parts(network), 0, P, omega)
    x, v = np.array([-0.07682843411375934, -0.12365441544477251]), np.array([0.06317649885629395, 0.17586999623326693])
    phases, events = march(p, x, v, 2 * math.pi / omega, network.element_names, max_events=20)
    first, second = events[0], events[1]
    assert first.elements == second.elements == ("floor1",) and (first.kind, second.kind) == ("reversal", "stop")
    assert first.mode[2] == -1 and second.mode[2] == 0  # reversed, then stuck
    sub_step = 2 * math.pi / np.max(np.abs(np.linalg.eigvals(phases[1].a))) / 50
    assert 0 < second.time - first.time < sub_step


# --- the detection of changes, on a synthetic branch ---------------------------------------------------------


def test_fold_and_period_doubling_are_told_by_the_sign_of_det_m_minus_and_plus_i():
    # No motion in the supported class has a multiplier outside the unit disc (the energy test above), so the
    # detection is tested on synthetic monodromies whose multiplier mu crosses +1 or -1 between neighbours.
    along = lambda mu, stops=0: signature(np.diag([mu, 0.3, 0.1 + 0.2j]).real, stops)
    assert change(along(0.9), along(0.95)) is None
    assert change(along(0.97), along(1.02)) == "fold"
    assert change(along(1.05), along(0.99)) == "fold"
    assert change(along(-0.98), along(-1.01)) == "period-doubling"
    assert change(along(0.9, 2), along(1.1, 0)) == "stops-change"  # a jump of the multipliers at a stops change


# --- the command -------------------------------------------------------------------------------------------


def _run(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    return run_lumped("response", *args, cwd=tmp_path)


def test_command_writes_an_amplitude_column_for_each_mass(tmp_path):
    out = tmp_path / "two.csv"
    args = ("--system", str(EXAMPLE), "--force-on", "m1", "--amplitude", "5", "--omega", "15:17", "--points", "4")
    done = _run(tmp_path, *args, "--output", str(out))
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(out.open()))
    amplitudes = ["amplitude_m1", "amplitude_m2"]
    assert list(rows[0]) == ["omega", *amplitudes, "stops_per_period", "stable", "max_multiplier", "kind"]
    assert float(rows[0]["omega"]) == 15.0 and float(rows[-1]["omega"]) == 17.0
    # the row at 17 rad/s is the motion find_orbit finds there, to Newton's tolerance over the period (as above)
    orbit = find_orbit(response_system(example(), "m1"), P, 17.0)
    for i, name in enumerate(("m1", "m2")):
        assert abs(float(rows[-1][f"amplitude_{name}"]) - orbit.amplitudes[i]) <= 1e-9 * P / 200.0


STRING = """
[[mass]]
name = "m1"
mass = 1.0
[[element]]
name = "string"
kind = "spring-string"
between = ["ground", "m1"]
stiffness = 100.0
length = 0.1
"""

#: COUPLED without the spring of m2: nothing elastic holds m2 (only the dashpot and the pad).
LOOSE = COUPLED.replace(
    'kind = "spring"\nbetween = ["ground", "m2"]\nstiffness = 400.0',
    'kind = "dashpot"\nbetween = ["ground", "m2"]\ndamping = 0.5',
)


@pytest.mark.parametrize(
    ("text", "mass", "words"),
    [
        (STRING, "m1", "cannot run element 'string' of kind 'spring-string'"),
        (LOOSE, "m1", "the stiffness matrix is singular"),
        (COUPLED, "m3", "no mass named 'm3'"),
        (COUPLED + '[[force]]\non = "m1"\nkind = "constant"\nvalue = 1.0\n', "m1", "loads of its own"),
    ],
)
def test_systems_the_period_map_cannot_follow_are_refused_in_one_line(text, mass, words):
    with pytest.raises(ValueError, match=words) as err:
        response_system(L.parse_system(text), mass)
    assert "\n" not in str(err.value)


def test_command_refuses_a_network_it_cannot_follow_in_one_line(tmp_path_factory):
    folder = tmp_path_factory.mktemp("system")
    (folder / "string.toml").write_text(STRING)
    work = tmp_path_factory.mktemp("work")
    done = _run(
        work,
        "--system",
        str(folder / "string.toml"),
        "--force-on",
        "m1",
        "--amplitude",
        "1",
        "--omega",
        "1:2",
        "--output",
        "r.csv",
    )
    assert done.returncode == 2 and "spring-string" in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1
    assert list(work.iterdir()) == []


# --- issue 31: a mass that comes to be held, its stops and the change reported once --------------------------------


def _m2_curve(start: float, stop: float, points: int) -> dict[str, np.ndarray]:
    """The example with the sine (3 N) on ``m2``: above about 18.72 rad/s the force ``m2`` passes through the
    spring ``k12`` no longer reaches ``floor1``'s threshold and ``m1`` is held."""
    return response_curve(L.load_system(EXAMPLE), "m2", 3.0, start, stop, points).columns


def test_held_mass_stops_reported_once():
    """From 18 to 24 rad/s the stops per period change once, from 2 (both contacts stick at the turns) to 0 (``m1``
    held, ``m2`` reversing without sticking), and that change is the one ``stops-change`` row: a held mass's
    permanent stick is no stop, and a velocity of round-off size that Newton leaves on it (a slip of 1e-22 m
    at ``t = 0``) does not make one.  Before issue 31 the held rows said 0, 1, 0 ... with 7 ``stops-change``."""
    c = _m2_curve(18.0, 24.0, 30)
    stops, kind, omega = c["stops_per_period"], c["kind"], c["omega"]
    changes = int(np.sum(stops[1:] != stops[:-1]))
    assert changes == 1 and stops[0] == 2 and stops[-1] == 0
    assert list(kind).count("stops-change") == 1
    at = int(np.flatnonzero(kind == "stops-change")[0])
    assert stops[at] == 0 and stops[at - 1] == 2  # the located row shows what the rows after it show
    assert np.all(np.diff(omega) > 0)  # no step back around the change
    held = omega >= omega[at]
    # held: m1 moves by less than the resolution of the fixed point (NEWTON_TOL P/k, amplified near the change)
    assert np.all(c["amplitude_m1"][held] < NEWTON_TOL * 3.0 / 200.0)
    assert np.all(c["amplitude_m1"][~held] > 0)


def test_round_off_slip_is_held():
    """The cause of the flicker: at 22 rad/s ``m1`` is held (its contact ``floor1`` sticks through the period);
    a velocity of 1e-22 m/s on it at ``t = 0`` makes the exact map slip it for no time and stop it at once.
    That element is still held (its slip, 1e-24 m, is far below the fixed point's resolution) and the stop is
    no stop per period; the neutral multiplier stays out of ``max_multiplier``."""
    system = response_system(L.load_system(EXAMPLE), "m2")
    orbit = find_orbit(system, 3.0, 22.0)
    assert list(orbit.period.held) == [2] and orbit.stops == 0
    y = orbit.state.copy()
    y[2] = 1e-22  # v of m1
    pm = period_map(system, 3.0, 22.0, y)
    assert any(e.kind == "stop" and e.elements == ("floor1",) for e in pm.events)
    assert list(pm.held) == [2] and pm.stops == 0
    assert np.max(np.abs(pm.multipliers)) < 0.6


@pytest.mark.slow
def test_two_changes_in_one_step_each_located():
    """The example (5 N on ``m1``) goes from 4 stops to 2 near 3.94 rad/s and from 2 to 0 near 4.14 rad/s, both
    within one step of a 30-point curve: each is located and reported once (before issue 31 the second was not)."""
    c = response_curve(L.load_system(EXAMPLE), "m1", P, 2.0, 25.0, 30).columns
    stops, kind = c["stops_per_period"], c["kind"]
    assert int(np.sum(stops[1:] != stops[:-1])) == list(kind).count("stops-change") == 5
    rows = np.flatnonzero(kind == "stops-change")
    assert np.all(stops[rows] != stops[rows - 1])


SPRING_ONLY = """
[[mass]]
name = "m"
mass = 1.0
[[element]]
name = "spring"
kind = "spring"
between = ["ground", "m"]
stiffness = 100.0
"""


@pytest.mark.parametrize("omega", [0.37, 2.3, 3.0, 4.1, 7.7, 13.0])
def test_undamped_multipliers_are_marginal(tmp_path, omega):
    """A mass on a spring alone: its multipliers are ``exp(+-i omega_n T)``, on the unit circle exactly; the
    computed moduli miss 1 by a few ulps either way (2e-15 to 4e-15 here, their sign a matter of round-off).
    Within the monodromy's error bound (:attr:`Orbit.margin`) ``max_multiplier`` is exactly 1 and ``stable``
    false, whichever way the last bits fall; the bound stays far below any modulus a damped motion shows."""
    path = tmp_path / "spring.toml"
    path.write_text(SPRING_ONLY)
    orbit = find_orbit(response_system(L.load_system(path), "m"), 1.0, omega, np.zeros(2))
    assert orbit.max_multiplier == 1.0 and orbit.stable is False
    assert np.all(np.abs(np.abs(orbit.multipliers) - 1) <= orbit.margin) and orbit.margin < 1e-9
