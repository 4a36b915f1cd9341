"""Loads (issue 21): constant, table, sums and ground motion, against closed forms and hand sums.

The closed form: a Coulomb oscillator (``gamma = inf``, threshold ``tau``)
released from rest at ``x = 0`` under a constant load ``P`` with
``tau < P < 3 tau`` slides while ``m x'' + k x = P - tau``, that is
``x(t) = A (1 - cos(omega t))`` with ``A = (P - tau)/k`` and
``omega = sqrt(k/m)``; its velocity vanishes after half a period,
``T = pi sqrt(m/k)``, at ``x = 2A``, where the spring's excess over the load,
``k 2A - P = P - 2 tau``, lies inside the band ``[-tau, tau]``: it stays there.
The same motion, in coordinates relative to the ground, under a constant
ground acceleration with ``-m a_g = P``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import EPS

import lumped as L

M, K, TAU = 2.0, 200.0, 2.0  # omega = 10 rad/s, T = pi/10 s; m a power of two: -m (-P/m) == P exactly
RATIOS = [1.5, 2.0, 2.9]  # P / tau, inside (1, 3)


def coulomb(load: str, m: float = M, k: float = K, tau: float = TAU) -> str:
    """A system file: one mass from rest at 0 on a spring and a Coulomb pad, with ``load`` appended."""
    return (
        f'[[mass]]\nname = "m"\nmass = {m!r}\n'
        f'[[element]]\nname = "k"\nkind = "spring"\nbetween = ["ground", "m"]\nstiffness = {k!r}\n'
        f'[[element]]\nname = "c"\nkind = "bingham"\nbetween = ["ground", "m"]\nthreshold = {tau!r}\ngamma = inf\n'
        + load
    )


def loads(how: str, p: float) -> str:
    """The constant load ``p`` written as a force, or as a ground acceleration ``-p/m``."""
    a = -p / M
    return {
        "force": f'[[force]]\non = "m"\nkind = "constant"\nvalue = {p!r}\n',
        "ground-constant": f'[ground]\nacceleration = {{ kind = "constant", value = {a!r} }}\n',
        "ground-sine": f'[ground]\nacceleration = {{ kind = "sine", amplitude = {a!r}, omega = 0.0, '
        f"phase = {math.pi / 2!r} }}\n",
    }[how]


def run(text: str, method: str, dt: float = 1e-3, t_end: float = 0.6, folder: object = ".") -> L.Trajectory:
    return L.solve(L.Problem(L.parse_system(text, folder=folder), t_end), dt, method=method)


@pytest.mark.parametrize("ratio", RATIOS)
@pytest.mark.parametrize("how", ["force", "ground-constant", "ground-sine"])
def test_exact_coulomb_under_a_constant_load_rests_at_twice_the_offset_after_half_a_period(how, ratio):
    # The exact method evaluates the phase's closed form and locates the stop
    # from it: a few correctly rounded operations, far inside 1e-12.
    p = ratio * TAU
    tr = run(coulomb(loads(how, p)), "exact")
    assert tr.rest_time == pytest.approx(math.pi * math.sqrt(M / K), rel=1e-12, abs=0)
    assert tr.rest_position == pytest.approx(2 * (p - TAU) / K, rel=1e-12, abs=0)


@pytest.mark.parametrize("dt", [1e-2, 1e-3])
@pytest.mark.parametrize("ratio", RATIOS)
def test_backward_euler_stops_where_its_recurrence_does_within_its_first_order_bound(ratio, dt):
    # While it slides, backward Euler is the linear recurrence of y = x - A:
    # (y, v/omega) turns by theta = atan(u), u = omega dt, and shrinks by
    # r = 1/sqrt(1 + u^2) each step, so y_j = -A r^j cos(j theta).  The slip
    # trial fails first at n = ceil(pi/theta) (sin(n theta) <= 0); the trial
    # of the other direction fails too (its force P + tau - k x >= 3 tau - P
    # >= 0 pushes forward), so the mass sticks at x_{n-1}.  Rounding: each of
    # the n steps rounds a few operations and the recurrence is a
    # contraction, so the errors add: 8 n eps A.
    p, a, omega = ratio * TAU, (ratio - 1) * TAU / K, math.sqrt(K / M)
    u = omega * dt
    theta, r = math.atan(u), 1 / math.sqrt(1 + u * u)
    n = math.ceil(math.pi / theta)
    recurrence = a * (1 - r ** (n - 1) * math.cos((n - 1) * theta))
    tr = run(coulomb(loads("force", p)), "backward-euler", dt=dt)
    assert tr.rest_time == pytest.approx(n * dt, rel=4 * EPS, abs=0)
    assert abs(tr.rest_position - recurrence) <= 8 * n * EPS * a
    # First order: 2A - x = A (1 - r^(n-1) |cos((n-1) theta)|) <= A (1 - r^n)
    # (cos theta = r) <= A n u^2 / 2, with n <= pi/theta + 1 and
    # theta >= u / (1 + u^2); the stop is at most a step after T (1 + u^2).
    period = math.pi / omega
    assert 0 <= 2 * a - tr.rest_position <= a * (math.pi * u * (1 + u * u) + u * u) / 2
    assert period <= tr.rest_time <= period * (1 + u * u) + dt


@pytest.mark.parametrize("method", list(L.METHODS))
@pytest.mark.parametrize("how", ["ground-constant", "ground-sine"])
def test_ground_acceleration_is_the_load_minus_m_a_on_every_method(how, method):
    # -m a_g = -2 (-P/2) = P exactly: the ground's run is the force's, bit for bit.
    p = 2.0 * TAU
    ground, force = run(coulomb(loads(how, p)), method), run(coulomb(loads("force", p)), method)
    assert np.array_equal(ground.positions, force.positions) and np.array_equal(ground.forces, force.forces)
    assert np.array_equal(ground.applied, force.applied)


@pytest.mark.parametrize("method", ["backward-euler", "theta"])
def test_a_table_equal_to_a_constant_runs_as_the_constant_bit_for_bit(tmp_path, method):
    # np.interp between two equal values returns that value itself.
    p = 2.5
    (tmp_path / "load.csv").write_text(f"t,F\n0,{p!r}\n0.25,{p!r}\n1,{p!r}\n")
    table = run(coulomb('[[force]]\non = "m"\nkind = "table"\nfile = "load.csv"\n'), method, folder=tmp_path)
    constant = run(coulomb(loads("force", p)), method)
    assert np.array_equal(table.positions, constant.positions) and np.array_equal(table.velocities, constant.velocities)
    assert np.array_equal(table.forces, constant.forces) and np.array_equal(table.applied, constant.applied)


def chain(load: str) -> str:
    """Two masses in a chain (spring and Coulomb pad to the ground, spring between): the network step."""
    return (
        '[[mass]]\nname = "a"\nmass = 1.0\n[[mass]]\nname = "b"\nmass = 4.0\n'
        '[[element]]\nname = "k"\nkind = "spring"\nbetween = ["ground", "a"]\nstiffness = 100.0\n'
        '[[element]]\nname = "c"\nkind = "bingham"\nbetween = ["ground", "a"]\nthreshold = 1.0\ngamma = inf\n'
        '[[element]]\nname = "kab"\nkind = "spring"\nbetween = ["a", "b"]\nstiffness = 50.0\n' + load
    )


@pytest.mark.parametrize("solver", ["compiled", "python"])
def test_a_table_equal_to_a_constant_runs_a_network_bit_for_bit(tmp_path, solver):
    (tmp_path / "load.csv").write_text("t,F\n0,3\n2,3\n")
    table = L.parse_system(chain('[[force]]\non = "b"\nkind = "table"\nfile = "load.csv"\n'), folder=tmp_path)
    constant = L.parse_system(chain('[[force]]\non = "b"\nkind = "constant"\nvalue = 3.0\n'))
    if solver == "compiled" and L.simulate_network(constant, 0.01, 1e-3).solver != "compiled":
        pytest.skip("the network kernel is not built")
    one, two = (L.simulate_network(net, 1.0, 1e-3, solver=solver) for net in (table, constant))
    assert np.array_equal(one.positions, two.positions) and np.array_equal(one.forces, two.forces)


def test_the_loads_of_a_network_add_per_mass_in_their_order(tmp_path):
    # Hand sums, written out: a constant on a from 0.1 s to 0.3 s, a ramp
    # table on a, a sine on b, and the ground's sine acceleration on both.
    (tmp_path / "ramp.csv").write_text("# a ramp from 0 to 2 N over 0.4 s, then off\nt,F\n0.1,0\n0.5,2\n")
    text = chain(
        '[[force]]\non = "a"\nkind = "constant"\nvalue = 1.5\nfrom = 0.1\nuntil = 0.3\n'
        '[[force]]\non = "a"\nkind = "table"\nfile = "ramp.csv"\n'
        '[[force]]\non = "b"\namplitude = 2.0\nomega = 7.0\n'
        '[ground]\nacceleration = { kind = "sine", amplitude = 0.5, omega = 3.0, phase = 0.25, until = 0.4 }\n'
    )
    tr = L.simulate_network(L.parse_system(text, folder=tmp_path), 0.6, 1e-2)
    t = tr.t
    constant = np.where((t >= 0.1) & (t <= 0.3), 1.5, 0.0)
    ramp = np.where((t >= 0.1) & (t <= 0.5), 2.0 * (t - 0.1) / 0.4, 0.0)
    ground = np.where(t <= 0.4, 0.5 * np.sin(3.0 * t + 0.25), 0.0)
    want_a = constant + ramp - 1.0 * ground
    want_b = 2.0 * np.sin(7.0 * t) - 4.0 * ground
    # np.interp's slope form and the kernels' sine round differently from
    # these formulas: a few eps of each term's size.
    assert np.all(np.abs(tr.applied[:, 0] - want_a) <= 8 * EPS * 4.0)
    assert np.all(np.abs(tr.applied[:, 1] - want_b) <= 8 * EPS * 4.0)


def sine_and_constant() -> tuple[L.SwitchedSine, L.Constant, str]:
    sine, constant = L.SwitchedSine(1.5, 9.0, 0.2, 0.4), L.Constant(2.5, 0.05)
    text = coulomb(
        '[[force]]\non = "m"\namplitude = 1.5\nomega = 9.0\nphase = 0.2\nuntil = 0.4\n'
        '[[force]]\non = "m"\nkind = "constant"\nvalue = 2.5\nfrom = 0.05\n'
    )
    return sine, constant, text


@pytest.mark.parametrize("method", ["backward-euler", "theta"])
def test_several_forces_on_one_mass_run_as_their_sum(method):
    # The one-mass methods get the sum as one callable: the same numbers as
    # the API given 0 + F1 + F2 written by hand.
    sine, constant, text = sine_and_constant()
    tr = run(text, method)
    osc = L.Oscillator.bingham(M, K, TAU, math.inf)
    ref = L.simulate(osc, 0.6, 1e-3, force=lambda t: 0.0 + sine(t) + constant(t), method=method)
    assert np.array_equal(tr.x, ref.x) and np.array_equal(tr.F_d, ref.F_d) and np.array_equal(tr.F, ref.F)
    assert tr.solver == ("algorithm1" if method == "backward-euler" else method)


def test_the_sum_of_two_constants_is_the_constant_of_their_sum_for_the_exact_method():
    # 1.5 + 2.5 = 4 exactly, and the exact method refuses a sum (it needs one formula):
    # the sum's backward Euler is the single constant's bit for bit.
    two = coulomb(loads("force", 1.5) + loads("force", 2.5))
    one = coulomb(loads("force", 4.0))
    assert np.array_equal(run(two, "backward-euler").x, run(one, "backward-euler").x)
    with pytest.raises(ValueError, match=r"^force: method 'exact' runs a sine .* not a sum of 2 loads;"):
        run(two, "exact")


def test_problem_force_is_the_one_load_or_the_sum():
    sine, constant, text = sine_and_constant()
    problem = L.Problem(L.parse_system(text), 1.0)
    assert isinstance(problem.force, L.LoadSum) and problem.force.forces == (sine, constant)
    single = L.Problem(L.parse_system(coulomb(loads("force", 3.0))), 1.0)
    assert single.force == L.Constant(3.0)


def test_a_constant_from_zero_is_the_sine_of_phase_pi_over_2_value_for_value():
    # sin(pi/2) rounds to 1 exactly in the package's sine (what the kernels use),
    # so the methods that need a sine run a constant as one with the same values.
    from lumped.model.forcing import sine_form

    t = np.linspace(0.0, 5.0, 5001)
    constant = L.Constant(-3.25, until=2.0)
    assert np.array_equal(sine_form(constant)(t), constant(t))
    assert sine_form(L.Constant(1.0, start=0.5)) == L.Constant(1.0, start=0.5)  # switched on later: no sine


def test_table_interpolates_linearly_and_is_zero_outside():
    table = L.Table([0.5, 1.0, 2.0], [1.0, -3.0, 5.0])
    t = np.array([0.0, 0.4999, 0.5, 0.75, 1.0, 1.5, 2.0, 2.0001, 9.0])
    hand = np.array([0.0, 0.0, 1.0, 1.0 + (-4.0) * 0.5, -3.0, -3.0 + 8.0 * 0.5, 5.0, 0.0, 0.0])
    assert np.all(np.abs(table(t) - hand) <= 4 * EPS * 5.0)
    assert table(1.0) == -3.0 and table(3.0) == 0.0


def test_constant_is_on_from_start_to_until_inclusive():
    c = L.Constant(2.0, 0.5, 1.5)
    assert c(np.array([0.0, 0.4999, 0.5, 1.0, 1.5, 1.5001])).tolist() == [0.0, 0.0, 2.0, 2.0, 2.0, 0.0]


def test_outputs_carry_the_applied_force_per_mass(tmp_path):
    from lumped.cli import main

    path = tmp_path / "chain.toml"
    path.write_text(chain('[[force]]\non = "b"\nkind = "constant"\nvalue = 3.0\nfrom = 0.1\n'))
    for suffix in (".csv", ".npz"):
        out = tmp_path / f"run{suffix}"
        assert main(["simulate", "--system", str(path), "--t-end", "0.2", "--dt", "1e-2", "--output", str(out)]) == 0
    data = np.loadtxt(tmp_path / "run.csv", delimiter=",", skiprows=1)
    header = (tmp_path / "run.csv").read_text().splitlines()[0].split(",")
    assert header[-2:] == ["load_a", "load_b"]
    t = data[:, 0]
    assert np.array_equal(data[:, -1], np.where(t >= 0.1, 3.0, 0.0)) and np.all(data[:, -2] == 0)
    with np.load(tmp_path / "run.npz") as z:
        assert z["load"].shape == (t.size, 2) and np.array_equal(z["load"], data[:, -2:])
