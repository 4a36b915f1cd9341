"""Response curves beyond omega (issue 23): the exact derivative of the period map in omega that the
continuation uses, the branch followed in the force's amplitude or in a parameter of the system file, and a
mass held through the whole period; each against an independent reference (central differences of the exact
map, the textbook curve, Den Hartog's closed form, a Newton solve at the row's parameter)."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_lumped

from lumped.drivers.response import NEWTON_TOL, continue_orbits, find_orbit
from lumped.drivers.response.curve import response_curve
from lumped.model.files import load_system
from lumped.model.oscillator import Oscillator
from lumped.model.system_parameters import system_parameters, with_values
from lumped.solvers.monodromy import period_map
from lumped.studies.den_hartog import closed_form

ROOT = Path(__file__).resolve().parent.parent
FIGURE3 = ROOT / "examples" / "figure3.toml"  # m = 1 kg, k = 100 N/m, tau = 1 N, gamma = 1 m/(N s)
M, K, TAU = 1.0, 100.0, 1.0
WN = 10.0


@pytest.mark.parametrize(
    ("gamma", "tau", "r", "state"),
    [
        (math.inf, 1.0, 1.05, (0.01, 0.0)),  # Coulomb, slip through the period after a breakaway
        (math.inf, 1.0, 0.3, (0.0, 0.05)),  # Coulomb, stops and breakaways
        (1.0, 1.0, 2.5, (0.002, -0.01)),  # Bingham, stops
        (1.0, 1.0, 0.73, (0.03, 0.1)),  # Bingham, a reversal then stops
        (0.2, 0.0, 0.2, (0.0, 0.0)),  # linear viscous, reversals only
    ],
)
def test_omega_derivative_is_the_central_difference_of_the_period_map(gamma, tau, r, state):
    # Central difference with h = 1e-5 omega: truncation h^2 |Pi'''|/6 ~ 1e-10 omega^2 |Pi'''|, round-off of the
    # map (states good to ~1e-14 of the scale P/k, event times to a few ulps) over h: ~1e-9 of the scale per
    # unit of omega.  Relative to the derivative's size, 1e-7 holds with a margin of 10 over the worst seen.
    osc, p, omega = Oscillator.bingham(M, K, tau, gamma), 1.25, r * WN
    exact = period_map(osc, p, omega, *state).omega_derivative
    h = 1e-5 * omega
    fd = (period_map(osc, p, omega + h, *state).end - period_map(osc, p, omega - h, *state).end) / (2 * h)
    assert np.max(np.abs(exact - fd)) <= 1e-7 * np.max(np.abs(fd))


def test_undamped_resonance_has_no_closed_form_derivative_and_the_branch_still_starts_there():
    # At omega = omega_n with c = 0 the particular solution grows secularly: no derivative of that form
    # (None), and the continuation takes a central difference there instead.  Coulomb, F/P = 0.9 > pi/4: the
    # amplitude stays bounded through resonance, and the branch from omega_n is Den Hartog's where it has no stops.
    osc, p = Oscillator.bingham(M, K, TAU, math.inf), TAU / 0.9
    assert period_map(osc, p, WN, 0.0, 0.0).omega_derivative is None
    branch = continue_orbits(osc, p, WN, 1.3 * WN, 10)
    assert branch.end == "stop" and branch.points[0].value == WN
    for point in branch.points[1:]:  # the closed form refuses omega = omega_n itself
        ref = closed_form(M, 0.0, K, TAU, p, point.orbit.omega)
        if point.orbit.stops == 0 and ref.nonstop:
            assert abs(point.orbit.amplitude - ref.amplitude) <= 1e-9 * ref.amplitude


def test_branch_in_the_amplitude_of_a_linear_oscillator_is_the_textbook_line():
    # tau = 0: X = (P/k)/sqrt((1 - r^2)^2 + (2 zeta r)^2) for every P.  Newton's residual (1e-11 of the start's
    # P/k) moves a fixed point by at most |(M - I)^-1| times that (<= 10 here: multipliers <= 0.9): 1e-10 of it.
    network = _with(load_system(FIGURE3), "dashpot.threshold", 0.0)
    omega, zeta = 8.0, 1.0 / (2 * math.sqrt(K * M))  # c = 1/gamma = 1 N s/m
    curve = response_curve(network, "m", 1.0, 0.5, 5.0, points=10, vary="amplitude", omega=omega)
    r = omega / WN
    gain = 1 / (K * math.sqrt((1 - r * r) ** 2 + (2 * zeta * r) ** 2))
    p, x = curve.columns["amplitude"], curve.columns["amplitude_m"]
    assert list(curve.columns)[:3] == ["amplitude", "omega", "amplitude_m"]
    assert p[0] == 0.5 and p[-1] == 5.0 and np.all(np.diff(p) > 0) and np.all(curve.columns["omega"] == omega)
    assert np.max(np.abs(x - gain * p)) <= 10 * 10 * NEWTON_TOL * 0.5 / K + 1e-12 * x.max()


def _with(network, name, value):
    """``network`` with its parameter ``name`` set to ``value``."""
    return with_values(network, system_parameters(network, [name]), [value])


def test_branch_in_the_friction_force_is_den_hartogs_where_it_has_no_stops(tmp_path):
    # Coulomb (gamma = inf) at r = 0.8 under P = 2.5 N, the threshold from 0.2 to 2 N: where the motion has no
    # stops, Den Hartog's closed form at that friction force (bound as in test_response: 1e-9 relative); each
    # row is also the motion Newton finds at its own threshold, from rest (a separate solve).
    coulomb = tmp_path / "coulomb.toml"  # figure3.toml with gamma = inf
    coulomb.write_text(FIGURE3.read_text().replace("gamma = 1.0 ", "gamma = inf "))
    network = load_system(coulomb)
    assert math.isinf(network.elements[1].gamma)
    p, omega = 2.5, 8.0
    curve = response_curve(network, "m", p, 0.2, 2.0, points=20, vary="dashpot.threshold", omega=omega)
    tau, x, stops = curve.columns["dashpot.threshold"], curve.columns["amplitude_m"], curve.columns["stops_per_period"]
    assert tau[0] == 0.2 and tau[-1] == 2.0
    nonstop = [
        (t, a) for t, a, s in zip(tau, x, stops, strict=True) if s == 0 and closed_form(M, 0, K, t, p, omega).nonstop
    ]
    assert len(nonstop) >= 10
    for t, a in nonstop:
        ref = closed_form(M, 0.0, K, t, p, omega).amplitude
        assert abs(a - ref) <= 1e-9 * ref
    i = len(tau) // 2
    orbit = find_orbit(Oscillator.bingham(M, K, float(tau[i]), math.inf), p, omega)
    assert abs(orbit.amplitude - x[i]) <= 1e-9 * p / K


def test_a_mass_held_through_the_period_is_a_neutral_motion_not_an_unstable_one():
    # P = 0.5 N < tau = 1 N from rest: the mass never moves; every position in the band is periodic (the
    # multiplier 1 along x, set apart as for a network's held element) and v is reset to 0 (multiplier 0).
    orbit = find_orbit(Oscillator.bingham(M, K, TAU, 1.0), 0.5, 8.0)
    assert orbit.period.held and orbit.amplitude == 0.0 and orbit.stops == 0
    assert orbit.stable and orbit.max_multiplier == 0.0
    curve = response_curve(load_system(FIGURE3), "m", 0.5, 2.0, 30.0, points=5)
    assert curve.columns["omega"][-1] == 30.0 and np.all(curve.columns["amplitude_m"] == 0.0)
    assert np.all(curve.columns["stable"])


def _vary(tmp_path: Path, omega: str, vary: str, *more: str):
    """``python -m lumped response`` on figure3.toml under 2.5 N at ``--omega omega --vary vary``, in-process."""
    args = ["--system", str(FIGURE3), "--force-on", "m", "--amplitude", "2.5", "--omega", omega, "--vary", vary]
    return run_lumped("response", *args, *more, cwd=tmp_path)


def test_command_follows_a_parameter_of_the_file(tmp_path):
    out = tmp_path / "threshold.csv"
    done = _vary(tmp_path, "8", "dashpot.threshold=0.2:2", "--points", "10", "--output", str(out))
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(out.open()))
    assert list(rows[0])[:2] == ["dashpot.threshold", "omega"]
    assert float(rows[0]["dashpot.threshold"]) == 0.2 and float(rows[-1]["dashpot.threshold"]) == 2.0
    i = len(rows) // 2
    orbit = find_orbit(Oscillator.bingham(M, K, float(rows[i]["dashpot.threshold"]), 1.0), 2.5, 8.0)
    assert abs(float(rows[i]["amplitude_m"]) - orbit.amplitude) <= 1e-9 * 2.5 / K


@pytest.mark.parametrize(
    ("omega", "vary", "words"),
    [
        ("8", "dashpot.thresh=1:2", "unknown parameter 'dashpot.thresh'"),
        ("8", "m.x0=0:1", "initial state"),
        ("8", "dashpot.threshold=-1:2", "threshold must be >= 0"),
        ("8", "dashpot.threshold=2:1", "START < STOP"),
        ("8", "amplitude=0:3", "--vary: amplitude = 0 gives no system the response takes (amplitude must be"),
        ("8", "threshold", "NAME=START:STOP"),
        ("2:8", "amplitude=1:2", "--omega"),
        ("-1", "amplitude=1:2", "--omega"),
    ],
)
def test_command_refuses_a_bad_vary_in_one_line(tmp_path, omega, vary, words):
    done = _vary(tmp_path, omega, vary, "--output", str(tmp_path / "r.csv"))
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1 and words in done.stderr, done.stderr
    assert list(tmp_path.iterdir()) == []
