"""Friction and belts from a system file: ``simulate --system`` runs them, everything else refuses them.

* ``python -m lumped simulate --system`` runs ``[[driver]]`` tables and
  ``kind = "friction"`` elements by backward Euler, and writes each driven
  point's position and velocity (``x_<driver>``, ``v_<driver>``); a ``dt``
  above the uniqueness bound of a falling curve, and every bad ``[[driver]]``
  or ``friction`` entry, is one line naming the file, the entry and the
  problem, exit status 2, no file written.
* Every other command and API entry that takes a system refuses driven points
  and friction whose graph is not monotone in one line naming itself and the
  reason, before any work (a driven point was once read as the ground).
* ``examples/belt.toml`` meets the closed-form stick-slip cycle, and
  ``examples/stribeck_belt.toml`` the linearised motion about steady sliding.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_lumped
from conftest import ROOT

import lumped as L
from lumped.model.records import Record

EXAMPLES = ROOT / "examples"
BELT = (EXAMPLES / "belt.toml").read_text(encoding="utf-8")
STRIBECK = (EXAMPLES / "stribeck_belt.toml").read_text(encoding="utf-8")
DRIVER = '[[driver]]\nname = "belt"\nvelocity = 0.2'
FRICTION = (
    "static = 1.0   # N\nkinetic = 0.5  # N, no stribeck_velocity: the force drops to kinetic as soon as it slips"
)
assert DRIVER in BELT and FRICTION in BELT  # the replacements below edit these lines


def _simulate(tmp_path: Path, text: str, *args: str, output: str = "out.csv"):
    (tmp_path / "s.toml").write_text(text, encoding="utf-8")
    return run_lumped(
        "simulate", "--system", "s.toml", "--t-end", "1", "--dt", "0.01", *args, "--output", output, cwd=tmp_path
    )


def _refused(result, tmp_path: Path, *words: str) -> str:
    """The one line of a refusal (status 2, nothing written), checked to hold ``words``."""
    assert result.returncode == 2, result
    assert result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    for w in words:
        assert w in lines[0], (w, lines[0])
    assert not [
        p.name
        for p in tmp_path.iterdir()
        if p.suffix in (".csv", ".npz", ".part", ".json") and p.name not in ("v.csv", "t.csv", "record.csv")
    ]
    return lines[0]


# -- bad [[driver]] and friction entries -----------------------------------------------------------------

BAD_FRICTION = {
    "unknown key": ("static = 1.0\nkinetic = 0.5\nstribek_velocity = 0.1", "unknown parameter 'stribek_velocity'"),
    "missing static": ("kinetic = 0.5", "missing parameter 'static'"),
    "missing kinetic": ("static = 0.5", "missing parameter 'kinetic'"),
    "kinetic above static": ("static = 0.5\nkinetic = 1.0", "kinetic = 1.0 N must not exceed static = 0.5 N"),
    "negative kinetic": ("static = 0.5\nkinetic = -1.0", "kinetic must be >= 0"),
    "zero static": ("static = 0.0\nkinetic = 0.0", "static must be > 0"),
    "negative stribeck velocity": (
        "static = 1.0\nkinetic = 0.5\nstribeck_velocity = -0.1",
        "stribeck_velocity must be > 0",
    ),
    "infinite stribeck velocity": (
        "static = 1.0\nkinetic = 0.5\nstribeck_velocity = inf",
        "stribeck_velocity must be finite",
    ),
    "unknown decay": ("static = 1.0\nkinetic = 0.5\nstribeck_velocity = 0.1\ndecay = 'cubic'", "decay must be one of"),
    "negative viscous": ("static = 1.0\nkinetic = 0.5\nviscous = -1", "viscous must be >= 0"),
    "text static": ("static = '1'\nkinetic = 0.5", "static must be a real number"),
    "nan static": ("static = nan\nkinetic = 0.5", "static must be a real number"),
}


@pytest.mark.parametrize("case", BAD_FRICTION, ids=str)
def test_a_bad_friction_entry_is_one_line_naming_the_file_entry_and_key(tmp_path: Path, case: str) -> None:
    lines, message = BAD_FRICTION[case]
    result = _simulate(tmp_path, BELT.replace(FRICTION, lines))
    _refused(result, tmp_path, "system file 's.toml'", "[[element]] 2 ('fric')", message)


def _driver(text: str) -> str:
    return BELT.replace(DRIVER, text)


SPRING_TO = '[[element]]\nname = "s2"\nkind = "spring"\nbetween = [{}]\nstiffness = 1.0\n'
BAD_DRIVER = {
    "missing velocity": (_driver('[[driver]]\nname = "belt"'), "[[driver]] 1 ('belt'): missing parameter 'velocity'"),
    "missing name": (_driver("[[driver]]\nvelocity = 0.2"), "[[driver]] 1: missing parameter 'name'"),
    "unknown key": (_driver(DRIVER + "\nspeed = 1"), "[[driver]] 1 ('belt'): unknown parameter 'speed'"),
    "text velocity": (_driver('[[driver]]\nname = "belt"\nvelocity = "fast"'), "velocity must be a number (m/s)"),
    "boolean velocity": (_driver('[[driver]]\nname = "belt"\nvelocity = true'), "velocity must be a number (m/s)"),
    "infinite velocity": (_driver('[[driver]]\nname = "belt"\nvelocity = inf'), "velocity must be finite"),
    "velocity table with bad columns": (
        _driver('[[driver]]\nname = "belt"\nvelocity = { kind = "table", file = "t.csv" }'),
        "[[driver]] 1 ('belt'): file 't.csv': line 1: expected the header 't,v', got 't,F'",
    ),
    "velocity table missing": (
        _driver('[[driver]]\nname = "belt"\nvelocity = { kind = "table", file = "none.csv" }'),
        "[[driver]] 1 ('belt'): file 'none.csv': cannot read it",
    ),
    "unknown velocity kind": (
        _driver('[[driver]]\nname = "belt"\nvelocity = { kind = "ramp", slope = 1 }'),
        "[[driver]] 1 ('belt'): unknown kind 'ramp'",
    ),
    "sine without omega": (
        _driver('[[driver]]\nname = "belt"\nvelocity = { kind = "sine", amplitude = 1 }'),
        "[[driver]] 1 ('belt'): missing parameter 'omega'",
    ),
    "named like a mass": (
        _driver('[[driver]]\nname = "m"\nvelocity = 0.2').replace('["belt", "m"]', '["ground", "m"]'),
        "driver 'm': the name is a mass's",
    ),
    "named ground": (_driver('[[driver]]\nname = "ground"\nvelocity = 0.2'), "name 'ground' is reserved"),
    "named twice": (_driver(DRIVER + "\n" + DRIVER), "driver 'belt': the name is used twice"),
    "element between two drivers": (
        _driver(DRIVER + '\n[[driver]]\nname = "b2"\nvelocity = 0.1') + SPRING_TO.format('"belt", "b2"'),
        "element 's2': joins 'belt' and 'b2', neither a mass",
    ),
    "element between a driver and the ground": (
        BELT + SPRING_TO.format('"belt", "ground"'),
        "element 's2': joins 'belt' and 'ground', neither a mass",
    ),
    "force on a driver": (
        BELT + '[[force]]\non = "belt"\namplitude = 1.0\nomega = 1.0\n',
        "force on 'belt': 'belt' is a driven point, whose motion is prescribed; forces act on masses",
    ),
    "written as a table": (BELT.replace("[[driver]]", "[driver]"), "driver must be written as [[driver]] tables"),
}


@pytest.mark.parametrize("case", BAD_DRIVER, ids=str)
def test_a_bad_driver_entry_is_one_line_naming_the_file_and_entry(tmp_path: Path, case: str) -> None:
    text, message = BAD_DRIVER[case]
    (tmp_path / "t.csv").write_text("t,F\n0,0\n1,1\n")
    _refused(_simulate(tmp_path, text), tmp_path, "system file 's.toml'", message)


def test_a_drivers_table_is_an_input_that_output_may_not_overwrite(tmp_path: Path) -> None:
    (tmp_path / "v.csv").write_text("t,v\n0,0\n1,0.2\n")
    text = _driver('[[driver]]\nname = "belt"\nvelocity = { kind = "table", file = "v.csv" }')
    result = _simulate(tmp_path, text, output="v.csv")
    _refused(result, tmp_path, "--output 'v.csv' is the file of [[driver]] 1 velocity")
    assert (tmp_path / "v.csv").read_text() == "t,v\n0,0\n1,0.2\n"


# -- the run and its columns -----------------------------------------------------------------------------


def test_the_output_adds_each_drivers_position_and_velocity(tmp_path: Path) -> None:
    """``x_belt``, ``v_belt`` after the masses' columns; the position is the velocity's integral from 0 (a ramp
    ``0.2 t`` up to t = 1 s, then 0.2: x = 0.1 t^2, then 0.2 t - 0.1, exact at the samples: the integral of a
    straight line between samples is its trapezoid); stuck to the belt, the block keeps the contact's
    elongation, so x_m - x_belt stays constant to rounding while v_m = v_belt."""
    (tmp_path / "v.csv").write_text("t,v\n0,0\n1,0.2\n100,0.2\n")
    text = _driver('[[driver]]\nname = "belt"\nvelocity = { kind = "table", file = "v.csv" }')
    result = _simulate(tmp_path, text)
    assert result.returncode == 0, result.stderr
    run = np.genfromtxt(tmp_path / "out.csv", delimiter=",", names=True)
    assert list(run.dtype.names) == ["t", "x_m", "v_m", "x_belt", "v_belt", "F_spring", "F_fric", "load_m"]
    t = run["t"]
    assert np.allclose(
        run["x_belt"], np.where(t <= 1, 0.1 * t * t, 0.2 * t - 0.1), rtol=0, atol=4 * np.finfo(float).eps
    )
    assert np.allclose(run["v_belt"], np.minimum(0.2 * t, 0.2), rtol=0, atol=1e-16)
    # static 1 N holds the spring's k x <= 0.1 m and the block's m a = 0.2 N: it never slips in this run
    gap = run["x_m"] - run["x_belt"]
    assert np.abs(gap - gap[0]).max() <= 1e-15
    assert (
        result.stderr.strip()
        == "lumped simulate (backward-euler): m still moving at t = 1 s (x = 0.1 m); compiled step (banded); wrote out.csv"
    )
    npz = _simulate(tmp_path, text, output="out.npz")
    assert npz.returncode == 0, npz.stderr
    with np.load(tmp_path / "out.npz") as data:
        assert list(data["driver_names"]) == ["belt"]
        assert np.array_equal(data["driver_x"][:, 0], run["x_belt"])
        assert np.array_equal(data["driver_v"][:, 0], run["v_belt"])


def test_the_uniqueness_bound_is_refused_above_and_runs_at_the_printed_step(tmp_path: Path) -> None:
    """``m/dt + k dt`` must exceed the fall ``(static - kinetic)/v_s - viscous = 39.8`` N s/m: the roots of
    ``dt^2 - 39.8 dt + 1 = 0`` give ``dt < 0.025142``, printed rounded down as 0.0251."""
    fall = (6.0 - 2.0) / 0.1 - 0.2
    bound = (fall - math.sqrt(fall * fall - 4.0)) / 2.0
    assert 0.0251 < bound < 0.0252
    (tmp_path / "s.toml").write_text(STRIBECK, encoding="utf-8")
    args = ("simulate", "--system", "s.toml", "--t-end", "1", "--output", "out.csv")
    line = _refused(run_lumped(*args, "--dt", "0.0252", cwd=tmp_path), tmp_path)
    assert line == (
        "lumped simulate: error: --dt: 0.0252 s is too long for a unique backward-Euler step: the tension of "
        "'fric' falls with its rate by up to 39.8 N s/m, more than the masses' m/dt and the springs' k dt outweigh; "
        "take dt <= 0.0251 s"
    )
    assert run_lumped(*args, "--dt", "0.0251", cwd=tmp_path).returncode == 0


# -- refusals elsewhere ------------------------------------------------------------------------------------

STUCK = BELT.replace(DRIVER + "  # m/s: the belt sits at 0.2 t\n", "").replace(
    '["belt", "m"]', '["ground", "m"]'
)  # static above kinetic
NOT_MONOTONE = "cannot run element 'fric' of kind 'friction': its graph is not monotone"
DRIVEN = "cannot run a system with driven points ('belt'); backward-euler runs it (exact and event-driven too, at a constant velocity)"
SYSTEMS = {"belt": (BELT, DRIVEN), "static above kinetic": (STUCK, NOT_MONOTONE)}
assert "\n[[driver]]" not in STUCK


@pytest.mark.parametrize("system", SYSTEMS, ids=str)
@pytest.mark.parametrize("method", ["theta", "moreau-jean"])  # event-driven runs them (test_friction_event_driven.py)
def test_the_one_mass_methods_refuse_a_belt_and_falling_friction(tmp_path: Path, system: str, method: str) -> None:
    """Not "needs a one-mass system; element 'fric' does not join the mass to the ground": the reason."""
    text, reason = SYSTEMS[system]
    _refused(_simulate(tmp_path, text, "--method", method), tmp_path, f"method {method!r} {reason}", "(s.toml)")
    with pytest.raises(ValueError, match="^" + re.escape(f"method {method!r} {reason}")):
        L.solve(L.Problem(L.parse_system(text), 1.0), 0.01, method=method)


@pytest.mark.parametrize("system", SYSTEMS, ids=str)
def test_response_refuses_a_belt_and_falling_friction(tmp_path: Path, system: str) -> None:
    text, reason = SYSTEMS[system]
    (tmp_path / "s.toml").write_text(text, encoding="utf-8")
    args = ("response", "--system", "s.toml", "--force-on", "m", "--amplitude", "1", "--omega", "0.5:2")
    _refused(run_lumped(*args, "--output", "r.csv", cwd=tmp_path), tmp_path, f"s.toml: the period map {reason}")
    with pytest.raises(ValueError, match="^" + re.escape(f"system: the period map {reason}")):
        L.response_curve(L.parse_system(text), "m", 1.0, 0.5, 2.0)
    with pytest.raises(ValueError, match="^" + re.escape(f"system: the period map {reason}")):
        L.steady_amplitude_sensitivities(L.parse_system(text), "m", 1.0, 1.0, ["spring.stiffness"])


@pytest.mark.parametrize("system", SYSTEMS, ids=str)
def test_fit_and_the_sensitivities_refuse_a_belt_and_falling_friction(tmp_path: Path, system: str) -> None:
    text, reason = SYSTEMS[system]
    text += '[[force]]\non = "m"\namplitude = 1.0\nomega = 1.0\n'
    (tmp_path / "s.toml").write_text(text, encoding="utf-8")
    (tmp_path / "record.csv").write_text("t,x_m\n0,0\n0.1,0.01\n0.2,0.02\n0.3,0.03\n")
    fitted = run_lumped("fit", "--system", "s.toml", "--data", "record.csv", "--free", "spring.stiffness", cwd=tmp_path)
    _refused(fitted, tmp_path, f"system file 's.toml': the exact sensitivities {reason}")
    net = L.parse_system(text)
    record = Record(np.array([0.0, 0.1, 0.2, 0.3]), {"m": np.array([0.0, 0.01, 0.02, 0.03])})
    with pytest.raises(ValueError, match="^" + re.escape(f"system: the exact sensitivities {reason}")):
        L.fit(net, record, "spring.stiffness")
    with pytest.raises(ValueError, match="^" + re.escape(f"parameters: the exact sensitivities {reason}")):
        L.system_sensitivities(net, [0.0, 1.0], "spring.stiffness")
    with pytest.raises(ValueError, match="^" + re.escape(f"parameters: the exact sensitivities {reason}")):
        L.one_sided_sensitivities(net, [0.0, 1.0], "spring.stiffness")


def test_friction_with_static_equal_to_kinetic_is_the_coulomb_graph_that_every_path_runs() -> None:
    """The refusals are of the graph, not of the kind: static = kinetic without a Stribeck velocity is Coulomb's."""
    net = L.parse_system(STUCK.replace("kinetic = 0.5", "kinetic = 1.0"))
    from lumped.drivers.response.systems import response_system

    osc = response_system(net, "m")
    assert osc.dashpot.bingham_form() == (1.0, 0.0)
    assert L.solve(L.Problem(net, 1.0), 0.01, method="theta").method == "theta"


# -- the examples -----------------------------------------------------------------------------------------


def test_the_belt_example_meets_the_closed_form_cycle() -> None:
    """examples/belt.toml's cycle against its closed form (the file's header derives it).

    Stuck, the block moves with the belt (v = 0.2 exactly: the belt's step displacement is exact) and holds
    |F| <= static.  Slipping, it is the harmonic ``kinetic/k + A cos(omega t + phi)``; backward Euler's step
    multiplies a harmonic's amplitude by ``1/sqrt(1 + (omega dt)^2)`` exactly, and its breakaway comes at the
    first step past ``k x = static``, up to one step's travel ``0.2 dt`` late.  So each extreme lies within
    ``0.2 dt`` of the closed form damped by that factor over the steps from breakaway to the extreme (grid
    sampling of the extreme adds at most ``A (omega dt)^2/8 = 3e-7``).
    """
    net = L.load_system(EXAMPLES / "belt.toml")
    m, (spring, fric), v_belt = net.masses[0].mass, net.elements, net.drivers[0].velocity
    k, static, kinetic, dt = spring.stiffness, fric.static, fric.kinetic, 2e-3
    omega = math.sqrt(k / m)
    amplitude = math.hypot((static - kinetic) / k, v_belt / omega)
    phi = -math.atan(k * v_belt / (omega * (static - kinetic)))  # x - kinetic/k = A cos(omega s + phi) from breakaway
    tr = L.solve(L.Problem(net, 20.0), dt)
    t, x, v, force = tr.t, tr.positions[:, 0], tr.velocities[:, 0], tr.forces[:, 1]
    stuck = v == v_belt
    assert stuck.sum() > 0.5 * t.size and np.abs(force[stuck]).max() <= static
    breakaway = t[1:][stuck[:-1] & ~stuck[1:]]
    assert breakaway.size == 2  # the first stick ends at 5.2 s, the cycle's at 14.1 s
    cycle = (t > breakaway[0]) & (t < breakaway[1])
    for phase, extreme, sign in ((-phi, x[cycle].max(), 1.0), (math.pi - phi, x[cycle].min(), -1.0)):
        steps = phase / omega / dt
        damped = kinetic / k + sign * amplitude * (1.0 + (omega * dt) ** 2) ** (-steps / 2)
        assert abs(extreme - damped) <= v_belt * dt + amplitude * (omega * dt) ** 2 / 8
    # the closed form's own numbers, as the header states them
    assert (round(kinetic / k + amplitude, 4), round(kinetic / k - amplitude, 4)) == (1.0385, -0.0385)


def _linearised(net: L.Network, dt: float, steps: int) -> tuple[np.ndarray, float, float]:
    """The backward-Euler recurrence of the block linearised about steady sliding: its positions (m), the
    steady position g(V)/k and the curve's |g''| bound used by the remainder (over speeds V -+ 0.1)."""
    m, (spring, fric), V = net.masses[0].mass, net.elements, net.drivers[0].velocity
    k, law = spring.stiffness, fric.law
    vs, drop = law.stribeck_velocity, law.static - law.kinetic
    slope = -drop / vs * math.exp(-V / vs) + law.viscous  # g'(V)
    curvature = drop / vs**2 * math.exp(-(V - 0.1) / vs)  # |g''| is largest at the lowest speed
    x_eq = float(law.slip(V)) / k
    e, u, out = net.masses[0].x0 - x_eq, net.masses[0].v0, [net.masses[0].x0]
    for _ in range(steps):  # m (u1 - u0)/dt = -k (e0 + dt u1) - g'(V) u1
        u = (m * u / dt - k * e) / (m / dt + k * dt + slope)
        e += dt * u
        out.append(x_eq + e)
    return np.array(out), x_eq, curvature


@pytest.mark.parametrize("belt", [0.8, 0.3])
def test_the_stribeck_example_is_the_linearised_motion(belt: float) -> None:
    """Steady sliding is stable above s* = 0.530 m/s (the belt at 0.8: the block spirals in) and unstable below
    (at 0.3, started as near its own steady position: it grows into stick-slip).

    At 0.8 the run is the backward-Euler recurrence of the linearised law to within the remainder's effect:
    the step is a contraction in the energy norm ``sqrt(k e^2 + m u^2)`` (it dissipates, ``g'(V) > 0``), and the
    remainder ``|g(V - u) - g(V) + g'(V) u| <= |g''| u^2/2`` adds at most ``dt |g''| u^2/2 / sqrt(m)`` to that
    norm a step, so ``|x - x_lin| <= sum dt |g''| u^2 / (2 sqrt(m k))`` (u from the run, |u| < 0.1 checked).
    """
    text = (
        STRIBECK
        if belt == 0.8
        else STRIBECK.replace("velocity = 0.8", "velocity = 0.3").replace(
            "x0 = 2.21",
            "x0 = 2.31",  # g(0.3)/k = 2.259 m, 0.05 m beside it
        )
    )
    net = L.parse_system(text)
    dt, t_end = 1e-2, 40.0
    tr = L.solve(L.Problem(net, t_end), dt)
    x, u = tr.positions[:, 0], tr.velocities[:, 0]
    linear, x_eq, curvature = _linearised(net, dt, tr.t.size - 1)
    if belt == 0.8:
        assert np.abs(u).max() < 0.1
        bound = np.cumsum(np.append(0.0, dt * curvature * u[1:] ** 2 / 2)) / math.sqrt(
            net.masses[0].mass * net.elements[0].stiffness
        )
        assert np.all(np.abs(x - linear) <= bound + 1e-12)
        assert abs(x[-1] - x_eq) < 0.05 * abs(x[0] - x_eq)  # spiralled in: e^(-0.093 40) = 0.024
    else:
        assert abs(linear[-1] - x_eq) > 10 * abs(x[0] - x_eq)  # the linearised motion grows
        assert np.any(u == belt)  # the run grows until the block sticks to the belt


@pytest.mark.parametrize("entry", ["find_orbit", "continue_orbits"])
def test_the_orbit_functions_refuse_a_network_in_one_line(entry: str) -> None:
    """They take the period map's system, which ``response_system`` makes of a network (and which refuses a
    belt); given the network itself, ``continue_orbits`` once failed with an AttributeError."""
    net = L.load_system(EXAMPLES / "belt.toml")
    call = {
        "find_orbit": lambda: L.find_orbit(net, 1.0, 1.0),
        "continue_orbits": lambda: L.continue_orbits(net, 1.0, 1.0, 2.0),
    }
    with pytest.raises(ValueError, match=r"^system must be an Oscillator or a LoadedNetwork \(a network made one by "):
        call[entry]()
