"""The event-driven method (lumped.solvers.event_driven) against the exact solver and closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest
import references
from scipy.integrate import solve_ivp

import lumped as L
from lumped.cli import main
from lumped.studies import examples

PAPER = examples.paper()


def _hb(n: float, K: float = 1.0, tau: float = 1.0) -> L.Oscillator:
    return L.Oscillator(1.0, L.LinearSpring(100.0), L.HerschelBulkleyDashpot(tau, K, n))


def _bound(sol: L.IntegratedSolution, scale: float) -> float:
    """Global error bound: the local errors of the steps, each at most ``rtol`` times the scale.

    Between events the motion is a non-expansive flow (the spring conserves
    the energy norm, the monotone dashpot only removes from it), so local
    errors add up without growth; stick phases are exact.
    """
    return max(sol.steps, 1) * sol.rtol * scale


def _scale(ex) -> float:  # noqa: ANN001
    """The largest |x| of the exact solution on a fine grid (m)."""
    return float(np.max(np.abs(ex.exact().evaluate(np.linspace(0, ex.t_end, 2001))["x"])))


@pytest.mark.parametrize("coulomb", [False, True], ids=["bingham", "coulomb"])
@pytest.mark.parametrize("name", list(PAPER))
@pytest.mark.parametrize("rtol", [1e-8, 1e-12])
def test_agrees_with_exact_on_every_example_of_section_3(name, rtol, coulomb):
    ex = PAPER[name]
    osc = L.Oscillator(ex.oscillator.mass, ex.oscillator.spring, L.coulomb(1.0)) if coulomb else ex.oscillator
    exact = L.solve_exact(osc, ex.t_end, x0=ex.x0, force=ex.force)
    sol = L.solve_event_driven(osc, ex.t_end, x0=ex.x0, force=ex.force, rtol=rtol)
    # the same sequence of events (an integer count: exact)
    assert [e.kind for e in sol.events] == [e.kind for e in exact.events]
    scale = float(np.max(np.abs(exact.evaluate(np.linspace(0, ex.t_end, 2001))["x"])))
    bound = _bound(sol, scale)
    a, b = sol.sample(1e-3), exact.sample(1e-3)
    assert np.max(np.abs(a.x - b.x)) <= bound
    assert abs(a.rest_position - b.rest_position) <= bound or (
        math.isnan(a.rest_position) and math.isnan(b.rest_position)
    )
    # event times: a position error e at a stop where |v'| >= a_min moves the time by about sqrt(2 e / a_min)
    # at most; on these runs the stops have |m v'| >= 0.1 N, so 10 sqrt(bound) s is safe
    t_a, t_b = np.array([e.time for e in sol.events]), np.array([e.time for e in exact.events])
    assert np.all(np.abs(t_a - t_b) <= 10 * math.sqrt(bound))


def test_paper_free_decay_rest_position_within_the_tolerance_bound():
    """The paper's free decay (Figures 11 to 14) at rtol 1e-12 against the exact solution.

    The bound is derived, not measured: each accepted step's local error is at most
    rtol |y| + atol, with |x| <= x0 and atol = 1e-3 rtol x0, and the free decay does
    not amplify an error between events (its phases are damped linear flows), so the
    global error is at most steps (1 + 1e-3) rtol x0 (in the energy norm, which the
    damped phases do not increase; the spring and mass scales are 1 here).  The error
    measured here is 1.5e-13 m (5.4e-11 relative); the bound, with 232 steps, is
    1.2e-10 m, 800 times more, so a change of the step sequence by round-off on another
    machine cannot break it.  The stop's time moves by the position error over the
    speed just before it, of order 1e-2 m/s here; 1e2 times the bound covers it.
    """
    ex = PAPER["free_large"]
    sol = L.solve_event_driven(ex.oscillator, ex.t_end, x0=ex.x0, rtol=1e-12)
    exact = ex.exact()
    bound = sol.steps * (1 + 1e-3) * 1e-12 * abs(ex.x0)
    assert abs(sol.rest_position - exact.rest_position) <= bound
    assert abs(sol.rest_time - exact.rest_time) <= 1e2 * bound


def test_herschel_bulkley_with_exponent_one_is_bingham_bit_for_bit():
    hb = _hb(1.0, K=1 / 3)  # gamma = 3: K = 1/3 is the float BinghamDashpot(1, 3).viscosity
    bingham = L.Oscillator.bingham(gamma=3.0)
    force = PAPER["forced_large"].force
    a = L.solve_event_driven(hb, 2.5, force=force).sample(1e-3)
    b = L.solve_event_driven(bingham, 2.5, force=force).sample(1e-3)
    assert np.array_equal(a.as_array(), b.as_array())


#: The free-decay cases of references with a viscous part (K = 1/gamma > 0; Coulomb is K = 0,
#: not a Herschel-Bulkley law, and is compared with exact above).
VISCOUS = {name: case for name, case in references.FREE_DECAY.items() if math.isfinite(case[3])}


@pytest.mark.parametrize(("m", "k", "tau", "gamma", "x0"), VISCOUS.values(), ids=list(VISCOUS))
def test_free_decay_turning_points_for_exponent_one_follow_the_closed_form(m, k, tau, gamma, x0):
    ref = references.free_decay(m, k, tau, gamma, x0)
    osc = L.Oscillator(m, L.LinearSpring(k), L.HerschelBulkleyDashpot(tau, 1 / gamma, 1.0))
    sol = L.solve_event_driven(osc, ref.times[-1] + 1.0, x0=x0, rtol=1e-12)
    turning = [e for e in sol.events if e.kind in ("reversal", "stop")]
    assert len(turning) == len(ref.times)
    bound = _bound(sol, abs(x0))
    np.testing.assert_allclose([e.x[0] for e in turning], ref.positions, rtol=0, atol=bound)
    np.testing.assert_allclose([e.time for e in turning], ref.times, rtol=0, atol=10 * math.sqrt(bound))


@pytest.mark.parametrize(
    "n", [0.5, pytest.param(2.0, marks=pytest.mark.slow), pytest.param(3.0, marks=pytest.mark.slow)]
)
def test_first_half_cycle_agrees_with_an_independent_radau_integration(n):
    # Released at rest from x0 = 0.5 > tau/k: slips towards the origin until v = 0.
    sol = L.solve_event_driven(_hb(n), 1.0, x0=0.5, rtol=1e-12)
    first = sol.events[0]

    def rhs(t, y):  # m = 1, k = 100, tau = 1, K = 1, moving with v < 0
        x, v = y
        return [v, -100 * x + 1.0 - math.copysign(abs(v) ** n, v)]

    stop = lambda t, y: y[1]  # noqa: E731
    stop.terminal, stop.direction = True, 1
    ref = solve_ivp(rhs, (0, 1), [0.5, 0.0], method="Radau", rtol=1e-11, atol=1e-13, events=stop)
    # Radau at rtol 1e-11 over ~200 steps: a global error below 1e-8 of the scale
    # (its bound as in _bound); the event-driven run is 100 times tighter
    assert first.time == pytest.approx(ref.t_events[0][0], rel=1e-8)
    assert first.x[0] == pytest.approx(ref.y_events[0][0][0], abs=1e-8 * 0.5)


@pytest.mark.parametrize("n", [0.5, 2.0])
def test_energy_balance_between_turning_points(n):
    # At turning points v = 0: k x_i^2/2 - k x_{i+1}^2/2 = the work of the dashpot, int F_d v dt.
    sol = L.solve_event_driven(_hb(n), 4.0, x0=0.5, rtol=1e-12)
    turning = [e for e in sol.events if e.kind in ("reversal", "stop")]
    nodes, weights = np.polynomial.legendre.leggauss(10)
    for a, b in zip(turning[:-1], turning[1:]):
        # composite 10-point Gauss-Legendre on 400 panels; the integrand F_d v behaves like
        # |t - t_stop|^(1+n) at the ends, so the end panels (width h = T/400) carry an error
        # of order h^(2+n) of the work, below 1e-9 of it here
        edges = np.linspace(a.time, b.time, 401)
        half = 0.5 * np.diff(edges)[:, None]
        t = (0.5 * (edges[:-1] + edges[1:]))[:, None] + half * nodes
        cols = sol.evaluate(t.ravel())
        work = float(np.sum((half * weights).ravel() * cols["F_d"] * cols["v"]))
        assert 50 * (a.x[0] ** 2 - b.x[0] ** 2) == pytest.approx(work, rel=1e-8)


def test_stick_band_is_exact():
    # Released inside the band tau/k = 0.01 m: rests at once; under a force
    # that stays in the band the dashpot force is F(t) (eq. 19) exactly.
    for n in (0.5, 2.0):
        sol = L.solve_event_driven(_hb(n), 2.0, x0=0.0075)
        assert [e.kind for e in sol.events] == ["rest"] and sol.rest_position == 0.0075
        forced = L.solve_event_driven(_hb(n), 2.0, force=PAPER["forced_small"].force)
        cols = forced.evaluate(np.linspace(0, 2, 201))
        assert np.all(cols["v"] == 0) and np.array_equal(cols["F_d"], cols["F"])


def test_thinning_law_creeps_towards_the_band_edge_without_stopping():
    # n = 1/2, K = 20: quasi-static creep K v^n = u with u = k|x| - tau gives
    # u' = -k (u/K)^2, so 1/u grows linearly with slope k/K^2 = 0.25 1/(N s).
    # The neglected inertia m v' is a fraction (m k/(n K^2)) (u/K)^2 <= 1e-3 of u here.
    sol = L.solve_event_driven(_hb(0.5, K=20.0), 10.0, x0=0.5)
    assert sol.events == () and math.isnan(sol.rest_position)
    t = np.linspace(5.0, 10.0, 6)
    cols = sol.evaluate(t)
    u = 100 * np.abs(cols["x"]) - 1.0
    assert np.all(u > 0) and np.all(np.diff(u) < 0) and np.all(cols["v"] != 0)
    assert np.polyfit(t, 1 / u, 1)[0] == pytest.approx(100 / 20.0**2, rel=1e-2)


def test_thickening_law_stops_in_finite_time():
    # n = 2 with the same K: the viscous force vanishes faster than v, the
    # threshold stops the mass after finitely many half-cycles, inside the band.
    sol = L.solve_event_driven(_hb(2.0, K=20.0), 10.0, x0=0.5)
    assert sol.events[-1].kind == "rest" and abs(sol.rest_position) <= 0.01
    assert sol.rest_time < 10.0


def test_driver_and_sample():
    ex = PAPER["free_large"]
    tr = L.simulate(ex.oscillator, 4.0, 1e-3, x0=0.5, method="event-driven", rtol=1e-12, save_every=10)
    assert tr.method == "event-driven" and tr.t.size == 401
    sol = L.solve_event_driven(ex.oscillator, 4.0, x0=0.5, rtol=1e-12)
    assert np.array_equal(tr.as_array(), sol.sample(1e-3, 10).as_array())
    assert tr.rest_position == sol.rest_position


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"rtol": 0.0}, "^rtol must lie in"),
        ({"rtol": -1e-8}, "^rtol must lie in"),
        ({"rtol": 1e-15}, "^rtol must lie in"),
        ({"rtol": 0.5}, "^rtol must lie in"),
        ({"rtol": math.nan}, "^rtol must be a real number"),
        ({"rtol": "1e-8"}, "^rtol must be a real number"),
        ({"force": lambda t: 0 * t}, "^force: the event-driven method needs a SwitchedSine"),
        ({"max_steps": 5}, "^t_end: the event-driven integration needs more than the 5 steps a run may take"),
        ({"max_events": 3}, "^t_end: more than the 3 events a run may have before t_end"),
        ({"t_end": 0.0}, "^t_end must be > 0"),
        ({"x0": math.inf}, "^x0 must be finite"),
        ({"v0": 1e200}, "^v0:"),
    ],
)
def test_bad_inputs_are_refused_with_one_line(kwargs, match):
    args = {"t_end": 4.0, "x0": 0.5} | kwargs
    with pytest.raises(ValueError, match=match) as err:
        L.solve_event_driven(_hb(0.5), **args)
    assert "\n" not in str(err.value)


def test_simulate_refuses_options_a_method_does_not_take():
    with pytest.raises(ValueError, match="^rtol: method 'backward-euler' takes no option 'rtol'"):
        L.simulate(L.Oscillator.bingham(), 1.0, 1e-3, rtol=1e-8)
    with pytest.raises(ValueError, match="^theta: method 'event-driven' takes no option 'theta'"):
        L.simulate(L.Oscillator.bingham(), 1.0, 1e-3, method="event-driven", theta=0.5)


HB_SYSTEM = """\
[[mass]]
name = "m1"
mass = 1.0
x0 = 0.5
[[element]]
name = "spring"
kind = "spring"
between = ["ground", "m1"]
stiffness = 100.0
[[element]]
name = "hb"
kind = "herschel-bulkley"
between = ["m1", "ground"]
threshold = 1.0
consistency = 1.0
exponent = 2.0
"""


def test_command_line_single_mass_matches_the_api(tmp_path, capsys):
    out = tmp_path / "run.npz"
    argv = ["simulate", "--x0", "0.5", "--t-end", "4", "--dt", "1e-3", "--method", "event-driven", "--rtol", "1e-12"]
    assert main([*argv, "--output", str(out)]) == 0
    assert "(event-driven): at rest from t = " in capsys.readouterr().err
    ref = L.solve_event_driven(L.Oscillator.bingham(), 4.0, x0=0.5, rtol=1e-12).sample(1e-3)
    data = np.load(out)
    assert np.array_equal(data["x"], ref.x) and np.array_equal(data["F_d"], ref.F_d)


def test_command_line_one_mass_system_file(tmp_path, capsys):
    system, out = tmp_path / "hb.toml", tmp_path / "run.csv"
    system.write_text(HB_SYSTEM)
    argv = ["simulate", "--system", str(system), "--t-end", "4", "--dt", "1e-3", "--method", "event-driven"]
    assert main([*argv, "--output", str(out)]) == 0
    assert "m1 at rest from t = " in capsys.readouterr().err
    with open(out) as fh:
        assert fh.readline().strip() == "t,x_m1,v_m1,F_spring,F_hb,load_m1"
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    ref = L.solve_event_driven(_hb(2.0), 4.0, x0=0.5).sample(1e-3)
    assert np.array_equal(data[:, 1], ref.x)
    assert np.array_equal(data[:, 4], -ref.F_d)  # between = ["m1", "ground"]: the tension is -F_d


@pytest.mark.parametrize(
    ("extra", "system", "message"),
    [
        (["--rtol", "0"], None, "--rtol must lie in"),
        (["--rtol", "-1e-8"], None, "--rtol must lie in"),
        (["--rtol", "1e-8", "--method=backward-euler"], None, "--rtol: method 'backward-euler' takes no option"),
        (["--method", "event-driven"], HB_SYSTEM.replace("exponent = 2.0", "exponent = 0"), "exponent must be > 0"),
        (["--method", "event-driven"], HB_SYSTEM.replace("consistency = 1.0", "consistency = -1"), "consistency must"),
        (
            ["--method", "event-driven"],
            HB_SYSTEM + '[[mass]]\nname = "m2"\nmass = 1.0\n[[mass]]\nname = "m3"\nmass = 1.0\n',
            "method 'event-driven' needs a one-mass system; the network has 3 masses",
        ),
    ],
)
def test_command_line_bad_inputs_one_line_status_2(tmp_path, capsys, extra, system, message):
    out = tmp_path / "run.csv"
    method = [] if any(a.startswith("--method") for a in extra) else ["--method", "event-driven"]
    argv = ["simulate", "--t-end", "1", "--output", str(out), *method, *extra]
    if system is None:
        argv += ["--x0", "0.5"]
    else:
        (tmp_path / "s.toml").write_text(system)
        argv += ["--system", str(tmp_path / "s.toml")]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and message in err
    assert not out.exists() and not list(tmp_path.glob("*.part"))
    if "masses" in message:
        assert err.endswith("has 3 masses (" + str(tmp_path / "s.toml") + ")")  # the file is named


def test_any_monotone_law_through_its_inverted_graph():
    # MonotoneDashpot gives phi only: its slip force is found by inverting the graph
    # (the Dashpot default, point 5), to a few ulps; the motion then matches the
    # Herschel-Bulkley law written in closed form to the integration's bound.
    n = 1.5
    law = L.MonotoneDashpot(lambda f: math.copysign(max(abs(f) - 1.0, 0.0) ** (1 / n), f), threshold=1.0)
    a = L.solve_event_driven(L.Oscillator(1.0, L.LinearSpring(100.0), law), 1.0, x0=0.5, rtol=1e-8)
    b = L.solve_event_driven(_hb(n), 1.0, x0=0.5, rtol=1e-8)
    assert [e.kind for e in a.events] == [e.kind for e in b.events]
    t = np.linspace(0, 1, 101)
    assert np.max(np.abs(a.evaluate(t)["x"] - b.evaluate(t)["x"])) <= _bound(b, 0.5)
