"""Response curves (issue 23): the monodromy matrix, the periodic motions and the continuation against
independent references (finite differences of the exact map, the textbook curve, Den Hartog's closed form and
its boundary, long runs of the exact solver), and the ``response`` command; networks are in test_response_network."""

from __future__ import annotations

import csv
import math
import subprocess
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_lumped

from lumped.drivers.response import NEWTON_TOL, continue_orbits, find_orbit
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.solvers.exact import solve_exact
from lumped.solvers.monodromy import period_map
from lumped.studies.den_hartog import closed_form, coulomb_boundary

ROOT = Path(__file__).resolve().parent.parent
FIGURE3 = ROOT / "examples" / "figure3.toml"
M, K, TAU = 1.0, 100.0, 1.0
WN = 10.0  # sqrt(K/M)


def _osc(gamma: float) -> Oscillator:
    return Oscillator.bingham(M, K, TAU, gamma)


# --- the monodromy matrix ------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("gamma", "friction_ratio", "r", "stops"),
    [(math.inf, 0.2, 0.7, 0), (math.inf, 0.5, 0.5, 2), (1.0, 0.8, 1.5, 2), (1.0, 0.2, 2.0, 0), (1.0, 0.8, 0.3, 2)],
)
def test_monodromy_is_the_derivative_of_the_exact_period_map(gamma, friction_ratio, r, stops):
    # Central differences with step h (relative 1e-6 of the scales P/k and omega_n P/k): truncation
    # h^2 |Pi'''| ~ 1e-12, round-off of the map (its event times refined to a few ulps of T, states
    # good to ~1e-13 of the scales) over h: 1e-7.  Ten times that: 1e-6 of the scale.
    osc, p = _osc(gamma), TAU / friction_ratio
    orbit = find_orbit(osc, p, r * WN)
    assert orbit.stops == stops  # the cases cover slip only and stick phases
    scale = np.array([p / K, p / K * WN])
    h = 1e-6 * scale
    fd = np.empty((2, 2))
    for j in range(2):
        step = np.eye(2)[j] * h
        plus = period_map(osc, p, r * WN, *(orbit.state + step)).end
        minus = period_map(osc, p, r * WN, *(orbit.state - step)).end
        fd[:, j] = (plus - minus) / (2 * h[j])
    scaled = lambda a: a * scale[None, :] / scale[:, None]
    assert np.max(np.abs(scaled(orbit.period.monodromy) - scaled(fd))) <= 1e-6


def test_a_stick_at_the_start_makes_v0_irrelevant():
    # The stuck state is fixed by the stick: the derivative with respect to v0 vanishes (the projection).
    pm = period_map(_osc(1.0), 1.25, 3.0, 0.0, 0.0)  # |P sin 0 - k 0| = 0 <= tau: it sticks at t = 0
    assert pm.solution.phases[0].kind == "stick"
    assert np.all(pm.monodromy[:, 1] == 0)


# --- the periodic motions along the branch ---------------------------------------------------------


def test_linear_oscillator_gives_the_textbook_curve():
    # tau = 0: X k/P = 1/sqrt((1 - r^2)^2 + (2 zeta r)^2).  Newton stops at a residual of NEWTON_TOL (units
    # P/k); the fixed point's error is at most |(M - I)^-1| times that, <= 1/(1 - 0.9) = 10 here (the largest
    # multiplier is 0.9): 1e-10 of P/k, and the amplitude ratio is >= 0.1 of it over r in [0.2, 3]... within 1e-9.
    osc, zeta = Oscillator.bingham(M, K, 0.0, 1.0), 0.05
    branch = continue_orbits(osc, 1.0, 2.0, 30.0, 30)
    assert branch.end == "stop"
    for point in branch.points:
        r = point.orbit.omega / WN
        ref = 1 / math.sqrt((1 - r * r) ** 2 + (2 * zeta * r) ** 2)
        bound = 10 * NEWTON_TOL / (1 - point.orbit.max_multiplier)
        assert abs(point.orbit.amplitude * K - ref) <= bound
        assert abs(point.orbit.amplitude * K - ref) <= 1e-10 * ref


@pytest.fixture(scope="module")
def coulomb_branch():
    """Coulomb, F/P = 0.4, r from 0.4 to 0.95: it loses its stops at Den Hartog's boundary."""
    return continue_orbits(_osc(math.inf), TAU / 0.4, 4.0, 9.5, 40)


def test_coulomb_branch_without_stops_is_den_hartogs(coulomb_branch):
    # The error of a fixed point is at most |(M - I)^-1| NEWTON_TOL (P/k), and the amplitude is a state of the
    # same motion carried over at most one period by a flow of norm <= 1 in these units (c = 0: a rotation) with
    # a factor of at most 10 for the reversals' saltations; the closed form is good to ~1e-13.
    p = TAU / 0.4
    nonstop = [pt.orbit for pt in coulomb_branch.points if pt.orbit.stops == 0]
    assert len(nonstop) > 20
    for orbit in nonstop:
        ref = closed_form(M, 0.0, K, TAU, p, orbit.omega)
        assert ref.nonstop
        bound = 10 * NEWTON_TOL * p / K / (1 - orbit.max_multiplier) + 1e-12 * ref.amplitude
        assert abs(orbit.amplitude - ref.amplitude) <= bound
        assert abs(orbit.amplitude - ref.amplitude) <= 1e-9 * ref.amplitude


def test_coulomb_branch_loses_its_stops_at_den_hartogs_boundary(coulomb_branch):
    # The stops-change is located by bisection to 2^-12 of a step (one step moves omega by at most 1.5 times
    # (9.5 - 4)/39 rad/s); at the located r the boundary's F/P is 0.4 to within its slope times that.
    change = [pt.orbit for pt in coulomb_branch.points if pt.kind == "stops-change"]
    assert len(change) == 1
    r = change[0].omega / WN
    dr = 1.5 * (9.5 - 4.0) / 39 / WN / 2**12
    slope = abs(coulomb_boundary(r + 1e-4) - coulomb_boundary(r - 1e-4)) / 2e-4
    assert abs(float(coulomb_boundary(r)) - 0.4) <= slope * dr


@pytest.mark.parametrize(("gamma", "r"), [(1.0, 0.5), (1.0, 1.2), (math.inf, 0.3), (math.inf, 1.5)])
def test_stable_orbit_is_where_a_long_run_from_rest_settles(gamma, r):
    # From rest the distance to a stable orbit shrinks by the largest multiplier each period (or, through a stick,
    # to zero); after N periods with max_multiplier^N < 1e-12 the run's amplitude is the orbit's to 1e-7.
    osc, p = _osc(gamma), TAU / 0.4
    orbit = find_orbit(osc, p, r * WN)
    assert orbit.stable
    periods = 40 + math.ceil(math.log(1e-12) / math.log(max(orbit.max_multiplier, 1e-3)))
    period = 2 * math.pi / orbit.omega
    run = solve_exact(osc, periods * period, force=SwitchedSine(p, orbit.omega))
    end = run.evaluate(np.array([periods * period]))
    assert abs(end["x"][0] - orbit.state[0]) <= 1e-7 * orbit.amplitude
    # and a run started on the orbit, perturbed by 1e-9 of P/k, stays within 1e-8 of it
    start = orbit.state + 1e-9 * p / K
    on = solve_exact(osc, 20 * period, x0=start[0], v0=start[1], force=SwitchedSine(p, orbit.omega))
    assert abs(on.evaluate(np.array([20 * period]))["x"][0] - orbit.state[0]) <= 1e-8 * p / K


# --- the command -----------------------------------------------------------------------------------


def _run(tmp_path: Path, *args: str) -> subprocess.CompletedProcess:
    return run_lumped("response", *args, cwd=tmp_path)


def test_command_writes_the_curve_from_start_to_stop(tmp_path):
    out = tmp_path / "response.csv"
    done = _run(
        tmp_path,
        "--system",
        str(FIGURE3),
        "--force-on",
        "m",
        "--amplitude",
        "2.5",
        "--omega",
        "2:30",
        "--points",
        "30",
        "--output",
        str(out),
    )
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(out.open()))
    assert list(rows[0]) == ["omega", "amplitude_m", "stops_per_period", "stable", "max_multiplier", "kind"]
    assert float(rows[0]["omega"]) == 2.0 and float(rows[-1]["omega"]) == 30.0
    assert {r["stable"] for r in rows} <= {"true", "false"}
    assert {r["kind"] for r in rows} <= {"regular", "fold", "period-doubling", "stops-change"}
    omega = np.array([float(r["omega"]) for r in rows])
    assert np.all(np.diff(omega) > 0)  # no fold on this branch: omega grows along it
    # each row is the motion of find_orbit at its omega, to Newton's tolerance
    k = 100.0
    i = len(rows) // 2
    orbit = find_orbit(Oscillator.bingham(1.0, k, 1.0, 1.0), 2.5, omega[i])
    assert abs(float(rows[i]["amplitude_m"]) - orbit.amplitude) <= 1e-9 * 2.5 / k


@pytest.mark.parametrize(
    ("change", "words"),
    [
        (("--amplitude", "-1"), "--amplitude must be finite and > 0"),
        (("--amplitude", "x"), "--amplitude"),
        (("--omega", "3:2"), "0 < START < STOP"),
        (("--omega", "3"), "START:STOP"),
        (("--omega", "0:3"), "0 < START < STOP"),
        (("--points", "1"), "--points must be at least 2"),
        (("--force-on", "q"), "no mass named 'q'"),
        (("--system", str(ROOT / "examples" / "maxwell_creep.toml")), "loads of its own"),
        (("--system", "missing.toml"), "cannot read it"),
        (("--output", "out.txt"), "--output must end in .csv or .npz"),
    ],
)
def test_command_refuses_bad_input_in_one_line(tmp_path, change, words):
    args = {
        "--system": str(FIGURE3),
        "--force-on": "m",
        "--amplitude": "2.5",
        "--omega": "2:30",
        "--output": str(tmp_path / "r.csv"),
    }
    args[change[0]] = change[1]
    done = _run(tmp_path, *[item for pair in args.items() for item in pair])
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1 and words in done.stderr, done.stderr
    assert list(tmp_path.iterdir()) == []  # nothing written, no temporary file left
