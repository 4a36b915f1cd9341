"""Response curves of systems without dissipation (issue 31): a mass on a spring alone, two masses on springs,
and springs with a dashpot that leaves a mode undamped.  Their periodic motion is unique exactly where
``monodromy - I`` is nonsingular (omega other than omega_n/j): there the rows are the closed form, checked against
Cramer's rule and against the exact period map; the points omega_n/j get no row and are named; a fixed omega at
such a point is refused in one line."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from cli_run import run_lumped

import lumped as L
from lumped.drivers.response import NEWTON_TOL, find_orbit
from lumped.drivers.response.curve import response_curve
from lumped.drivers.response.linear import linear_form, undamped_frequencies
from lumped.drivers.response.systems import Scales, period_map, response_system

EPS = np.finfo(float).eps
M, K = 1.0, 100.0  # kg, N/m: omega_n = 10 rad/s

SPRING = """
[[mass]]
name = "m"
mass = 1.0
[[element]]
name = "spring"
kind = "spring"
between = ["ground", "m"]
stiffness = 100.0
"""

#: A chain: a spring from the ground to m1, one from m1 to m2 (omega_n^2 = (k/m)(3 -+ sqrt 5)/2).
CHAIN = """
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
name = "k12"
kind = "spring"
between = ["m1", "m2"]
stiffness = 100.0
"""

#: Two equal oscillators joined by a dashpot: the mode in which they swing together (omega_n = 10) is undamped,
#: the other (omega^2 = 300) damped.
JOINED = """
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
stiffness = 100.0
[[element]]
name = "d12"
kind = "dashpot"
between = ["m1", "m2"]
damping = 2.0
"""


def _network(tmp_path, text: str):
    path = tmp_path / "system.toml"
    path.write_text(text)
    return L.load_system(path)


def _one_mass_bound(omega: float) -> float:
    """The relative error of ``P/(k - m omega^2)`` computed in floats: ``omega^2``, ``m omega^2`` and the
    difference are each rounded (half an ulp of ``k + m omega^2`` at most, amplified by the cancellation
    ``(k + m omega^2)/|k - m omega^2|``), the quotient once more: four roundings with room for either way of
    evaluating it (a solve of the 1 x 1 complex system performs the same operations)."""
    return 4 * EPS * (1 + (K + M * omega**2) / abs(K - M * omega**2))


def test_one_mass_rows_are_the_closed_form_and_skip_omega_n_over_j(tmp_path):
    """``--omega 2:25`` on 24 points lands on 2, 5 and 10 = omega_n/5, /2, /1: those three get no row, the
    other 21 are ``P/|k - m omega^2|``, marginal (multipliers exp(+-i omega_n T) on the unit circle)."""
    curve = response_curve(_network(tmp_path, SPRING), "m", 1.0, 2.0, 25.0, 24)
    grid = np.linspace(2.0, 25.0, 24)
    expected = [w for w in grid if w not in (2.0, 5.0, 10.0)]
    assert curve.columns["omega"].tolist() == expected
    reference = np.array([1.0 / abs(K - M * w**2) for w in expected])
    bound = np.array([_one_mass_bound(w) for w in expected])
    assert np.all(np.abs(curve.columns["amplitude_m"] / reference - 1) <= bound)
    assert np.all(curve.columns["max_multiplier"] == 1.0) and not curve.columns["stable"].any()
    assert set(curve.columns["kind"]) == {"regular"} and np.all(curve.columns["stops_per_period"] == 0)
    assert "10/j for j = 1..5 (10, 5, ..., 2) rad/s: 3 of the 24 grid points left out" in curve.summary


#: The stiffness and damping matrices of CHAIN and JOINED, written from the files by hand (unit masses).
MATRICES = {
    "chain": (np.array([[200.0, -100.0], [-100.0, 100.0]]), np.zeros((2, 2))),
    "joined": (np.array([[100.0, 0.0], [0.0, 100.0]]), np.array([[2.0, -2.0], [-2.0, 2.0]])),
}


def _cramer(name: str, mass: int, omega: float) -> tuple[np.ndarray, float]:
    """``|X|``, ``X = (K - omega^2 M + i omega C)^-1 F`` of a two-mass system by Cramer's rule, and the bound of its
    distance from the package's solve (largest component, m): Cramer's rule on a 2 x 2 system and a solve by LU
    with partial pivoting are both forward stable, each within a few ulps times ``cond(A)`` of ``|X|`` (Higham,
    *Accuracy and Stability*, sections 1.10.1 and 9.4); 8 ulps times ``cond(A)`` holds both.  The matrix ``A`` is
    formed by the same operations on both sides, so that its own rounding cancels."""
    k, c = MATRICES[name]
    a = k - omega**2 * np.eye(2) + 1j * omega * c
    det = a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
    f = np.zeros(2)
    f[mass] = 1.0
    x = np.array([a[1, 1] * f[0] - a[0, 1] * f[1], a[0, 0] * f[1] - a[1, 0] * f[0]]) / det
    return np.abs(x), 8 * EPS * float(np.linalg.cond(a)) * float(np.abs(x).max())


@pytest.mark.parametrize(("name", "mass"), [("chain", 0), ("chain", 1), ("joined", 0)])
def test_two_mass_rows_are_the_closed_form(tmp_path, name, mass):
    """Every row of a two-mass curve against Cramer's rule, to the bound derived in :func:`_cramer` (``|X|`` is
    1-Lipschitz in ``X``)."""
    net = _network(tmp_path, {"chain": CHAIN, "joined": JOINED}[name])
    curve = response_curve(net, net.mass_names[mass], 1.0, 2.0, 25.0, 47)
    assert curve.columns["omega"].size >= 43  # 47 less omega_n/j on the grid (JOINED: 2, 2.5, 5, 10)
    for i, omega in enumerate(curve.columns["omega"]):
        x, bound = _cramer(name, mass, omega)
        got = np.array([curve.columns["amplitude_m1"][i], curve.columns["amplitude_m2"][i]])
        assert np.max(np.abs(got - x)) <= bound, (omega, got, x)
    assert np.all(curve.columns["max_multiplier"] == 1.0)  # an undamped mode: a multiplier on the unit circle


@pytest.mark.parametrize(("text", "omega"), [(SPRING, 3.7), (CHAIN, 7.3), (CHAIN, 20.0), (JOINED, 4.4)])
def test_closed_form_is_a_fixed_point_of_the_exact_period_map(tmp_path, text, omega):
    """The closed form's state at ``t = 0`` (``x = Im X = 0``, ``v = omega Re X``) comes back after a period of
    the exact solver to :data:`NEWTON_TOL` (in units of P/k), the resolution every continued row is solved to:
    an independent check of the closed form and of its sign, which the amplitude column does not show."""
    net = _network(tmp_path, text)
    system = response_system(net, net.mass_names[0])
    ls = linear_form(system)
    force = np.zeros(ls.mass.size)
    force[0] = 1.0
    x = np.linalg.solve(ls.stiffness - omega**2 * np.diag(ls.mass) + 1j * omega * ls.damping, force)
    z = np.concatenate([x.imag, omega * x.real])
    end = period_map(system, 1.0, omega, z).end
    assert np.max(np.abs(Scales.of(system, 1.0).state(end - z))) <= NEWTON_TOL


def test_undamped_frequencies_are_the_modes_without_damping(tmp_path):
    """The chain's two modes (closed form ``(k/m)(3 -+ sqrt 5)/2``), and of the joined pair only the one the dashpot
    does not stretch (to the eigenvalue solver's accuracy, a few ulps of ``|B|``)."""
    chain = undamped_frequencies(linear_form(response_system(_network(tmp_path, CHAIN), "m1")))
    exact = np.sqrt(K / M * np.array([(3 - math.sqrt(5)) / 2, (3 + math.sqrt(5)) / 2]))
    assert np.allclose(chain, exact, rtol=64 * EPS * exact[1] ** 2 / exact[0] ** 2, atol=0)
    joined = undamped_frequencies(linear_form(response_system(_network(tmp_path, JOINED), "m1")))
    assert joined.size == 1 and abs(joined[0] - 10.0) <= 64 * EPS * 300 / 10


def _command(tmp_path, text: str, *args: str):
    (tmp_path / "system.toml").write_text(text)
    return run_lumped(
        "response",
        "--system",
        "system.toml",
        "--force-on",
        "m",
        "--amplitude",
        "1",
        *args,
        "--output",
        "r.csv",
        cwd=tmp_path,
    )


def test_command_from_the_resonance_writes_the_curve(tmp_path):
    """``--omega 10:20`` starts at the resonance: a warning-free run, the resonance left out and named."""
    done = _command(tmp_path, SPRING, "--omega", "10:20", "--points", "11")
    assert done.returncode == 0, done.stderr
    assert "not unique at omega = 10 rad/s: 1 of the 11 grid points left out" in done.stderr
    with open(tmp_path / "r.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [float(r["omega"]) for r in rows] == list(np.linspace(10, 20, 11)[1:])
    for r in rows:
        w = float(r["omega"])
        assert abs(float(r["amplitude_m"]) * abs(K - M * w**2) - 1) <= _one_mass_bound(w)


@pytest.mark.parametrize(("omega", "j"), [("10", 1), ("5", 2)])
def test_command_refuses_a_fixed_omega_where_the_motion_is_not_unique(tmp_path, omega, j):
    """With ``--vary`` at omega = omega_n (no periodic motion) or omega_n/2 (a family of them): one line, status 2,
    no output left."""
    done = _command(tmp_path, SPRING, "--omega", omega, "--vary", "amplitude=1:2")
    assert done.returncode == 2
    line = done.stderr.strip()
    assert "\n" not in line and f"--omega: the periodic motion at omega = {omega} rad/s is not unique" in line
    assert f"omega_n/{j} of the undamped mode omega_n = 10 rad/s" in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["system.toml"]


def test_vary_leaves_out_the_parameter_values_at_omega_n_over_j(tmp_path):
    """At omega = 4, ``spring.stiffness`` from 1 to 100 on 12 points passes k = 64 (omega_n = 8 = 2 omega): that
    value gets no row and is named; the others are ``P/|k - m omega^2|``."""
    net = _network(tmp_path, SPRING)
    curve = response_curve(net, "m", 1.0, 1.0, 100.0, 12, vary="spring.stiffness", omega=4.0)
    ks = curve.columns["spring.stiffness"]
    assert 64.0 not in ks and ks.size == 11
    assert "not unique at spring.stiffness = 64: 1 of the 12 grid points left out" in curve.summary
    assert np.all(np.abs(curve.columns["amplitude_m"] * np.abs(ks - 16.0) - 1) <= 8 * EPS * (ks + 16) / abs(ks - 16))


def test_shooting_refuses_a_singular_monodromy_minus_identity(tmp_path):
    """At the resonance Newton's matrix ``M - I`` is zero within its error: ``find_orbit`` takes least-norm steps,
    which find no periodic motion (there is none), and says so in one line instead of stepping to a non-finite
    state (which reached the matrix exponential)."""
    system = response_system(_network(tmp_path, SPRING), "m")
    with pytest.raises(ValueError, match=r"^force_omega: no isolated periodic motion at omega = 10 rad/s: monodromy"):
        find_orbit(system, 1.0, 10.0, np.array([0.0, 0.1]))
    with pytest.raises(ValueError, match=r"^force_omega: no periodic motion found .* \(a state not finite\)"):
        period_map(system, 1.0, 3.0, np.array([math.nan, 0.0]))


def test_high_omega_is_resolved(tmp_path):
    """Far above omega_n the period is short and ``|B T|`` (6e-17 here) is below an ulp of 1: ``expm(B T) - I``
    subtracted is known only to ulps of 1, more than its own size, and every point would be left out as not
    unique.  As ``B T phi1(B T)`` its error is relative to ``|B T|``, and the rows are ``P/(m omega^2 - k)`` to
    the bound of :func:`_one_mass_bound`."""
    curve = response_curve(_network(tmp_path, SPRING), "m", 1.0, 1e18, 2e18, 5)
    omega = curve.columns["omega"]
    assert omega.tolist() == np.linspace(1e18, 2e18, 5).tolist()
    bound = np.array([_one_mass_bound(w) for w in omega])
    assert np.all(np.abs(curve.columns["amplitude_m"] * (M * omega**2 - K) - 1) <= bound)


@pytest.mark.parametrize(
    ("omega", "words"),
    [
        ("1e-12:2e-12", "--omega: omega = 1e-12 rad/s is too low for this system"),
        ("1e200:1e201", "--omega: omega = 1e+200 rad/s is too high: m omega^2 overflows"),
        ("1e154:1.1e154", "--omega: omega = 1e+154 rad/s is too high: the amplitude underflows"),
    ],
)
def test_command_refuses_an_omega_the_closed_form_cannot_vouch_for(tmp_path, omega, words):
    """Below omega_n by 1e13 the monodromy's error bound passes 1 (nothing known of ``M - I``); above about 1e154
    ``m omega^2`` overflows or the amplitude leaves the normal numbers: one line each, status 2, nothing written."""
    done = _command(tmp_path, SPRING, "--omega", omega)
    assert done.returncode == 2 and "\n" not in done.stderr.strip() and words in done.stderr, done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["system.toml"]
