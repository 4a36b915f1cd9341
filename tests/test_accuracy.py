"""The work-precision study (lumped.studies.accuracy): event matching, observed orders, the references, bad inputs.

The orders are measured against the closed-form event-driven solver
(``solve_exact``), which shares no code with the fixed-step schemes; the
Herschel-Bulkley reference (``event-driven`` at its smallest tolerance) is
checked against ``solve_exact`` on a Bingham law and against a DOP853
integration written here.  The event matching is checked on trajectories
typed by hand, where the answer is known without running a solver.
"""

from __future__ import annotations

import itertools
import json
import math

import numpy as np
import pytest
from references import geometric_steps, order_band
from scipy import stats
from scipy.integrate import solve_ivp

import lumped as L
from lumped.solvers.event_driven import RTOL_RANGE
from lumped.solvers.events import Event
from lumped.drivers.methods import METHODS
from lumped.studies import accuracy as A
from lumped.studies.accuracy import methods as M
from lumped.studies.accuracy.orders import fitted_slope


# ---------------------------------------------------------------- the methods, from the registry


def test_the_study_compares_every_method_of_the_registry_in_one_group():
    """The methods come from lumped.drivers.methods.METHODS (issue 20, item 2), grouped by their capabilities."""
    groups = (M.SCHEMES, M.TOLERANCED, M.CLOSED_FORM)
    assert sorted(name for group in groups for name in group) == sorted(METHODS)
    assert M.STUDY_METHODS == (*M.SCHEMES, *M.TOLERANCED, *M.CLOSED_FORM, "tanh") == A.STUDY_METHODS
    assert all(any(o.name == "rtol" for o in METHODS[name].options) for name in M.TOLERANCED)
    # the order of the rows of results/accuracy/study.json and of its order table
    assert M.SCHEMES == ("backward-euler", "event-locating", "theta", "moreau-jean")
    assert (M.TOLERANCED, M.CLOSED_FORM) == (("event-driven",), ("exact",))


@pytest.mark.parametrize("name", ["exact", "event-driven"])
def test_a_methods_run_samples_its_solution_in_continuous_time(name):
    """``Method.solution`` is what ``run`` samples: the study measures the one the others call (bit for bit)."""
    case = A.cases()["forced-17b"]
    method, dt = METHODS[name], 1e-3
    traj = method(case.oscillator, case.t_end, dt, case.x0, 0.0, case.force, 1)
    sampled = method.solution(case.oscillator, case.t_end, x0=case.x0, v0=0.0, force=case.force).sample(dt)
    assert np.array_equal(traj.x, sampled.x) and np.array_equal(traj.v, sampled.v)
    assert not method.fixed_step and all(METHODS[n].solution is None for n in M.SCHEMES)


# ---------------------------------------------------------------- events of a grid trajectory


def test_direct_sign_change_is_a_reversal_at_the_interpolated_zero():
    t, x, v = np.array([0.0, 1.0, 2.0, 3.0]), np.array([0.0, 1.0, 2.0, 3.0]), np.array([1.0, 3.0, -1.0, -2.0])
    (ev,) = A.grid_events(t, x, v)
    # v goes from 3 to -1 between t = 1 and 2: the line's zero is at 1 + 3/4.
    assert (ev.kind, ev.time, ev.x) == ("reversal", 1.75, (1.75,))


def test_one_zero_between_opposite_signs_is_a_reversal_not_a_stick():
    t, x = np.arange(5.0), np.array([0.0, 0.5, 0.6, 0.5, 0.0])
    v = np.array([1.0, 1.0, 0.0, -3.0, -1.0])
    (ev,) = A.grid_events(t, x, v)
    # the line through (1, 1) and (3, -3) is zero at t = 1.5; x there 0.5 + 0.25 * 0 = 0.5
    assert (ev.kind, ev.time, ev.x) == ("reversal", 1.5, (0.5,))


def test_stick_runs_give_stop_and_breakaway_at_their_ends():
    t = np.arange(9.0)
    v = np.array([0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, -1.0, 0.0])
    x = np.array([0.0, 0.0, 0.1, 0.2, 0.3, 0.3, 0.3, 0.2, 0.1])
    kinds = [(e.kind, e.time) for e in A.grid_events(t, x, v)]
    # a run from t = 0 has no stop; the last run, to the end, has no breakaway;
    # a lone zero between the same sign would be a stick, here 8 is the end.
    assert kinds == [("breakaway", 1.0), ("stop", 4.0), ("breakaway", 6.0), ("stop", 8.0)]


def test_a_release_from_rest_is_no_breakaway():
    t, x, v = np.arange(3.0), np.array([0.5, 0.4, 0.3]), np.array([0.0, -1.0, -1.0])
    assert A.grid_events(t, x, v) == ()


def test_a_lone_zero_between_the_same_sign_is_a_momentary_stick():
    t, x, v = np.arange(4.0), np.zeros(4), np.array([1.0, 0.0, 1.0, 1.0])
    assert [(e.kind, e.time) for e in A.grid_events(t, x, v)] == [("stop", 1.0), ("breakaway", 1.0)]


def test_forcing_off_is_interpolated():
    t, x, v = np.array([0.0, 1.0, 2.0]), np.array([0.0, 2.0, 4.0]), np.ones(3)
    assert A.grid_events(t, x, v, t_off=1.5) == (Event(1.5, "switch", (3.0,)),)
    assert A.grid_events(t, x, v, t_off=5.0) == ()


def test_match_events_pairs_in_order_and_refuses_unequal_counts():
    wanted = (Event(1.0, "reversal", (0.1,)), Event(2.0, "reversal", (-0.1,)), Event(2.5, "switch", (0.3,)))
    found = (Event(1.1, "reversal", (0.0,)), Event(1.95, "reversal", (0.0,)), Event(2.5, "switch", (0.25,)))
    got = A.match_events(found, wanted)
    assert got["reversal"] == pytest.approx(0.1, abs=1e-15)  # max(|1.1 - 1|, |1.95 - 2|)
    assert got["switch"] == pytest.approx(0.05, abs=1e-15)  # in x: its time is given
    assert "stop" not in got  # not in the reference
    lost = A.match_events(found[:1] + found[2:], wanted)  # a reversal missing: no kind is paired
    assert math.isnan(lost["reversal"]) and math.isnan(lost["switch"])


# ---------------------------------------------------------------- the references


def test_event_driven_reference_agrees_with_exact_on_bingham():
    # The Herschel-Bulkley reference is event-driven at the smallest rtol; on
    # the paper's free decay the same setting agrees with the closed form.
    # Measured 1e-12 relative in rest position and time; the bound 1e-10 is
    # the target for event-driven against exact.
    case = A.cases()["free-decay"]
    ed = L.solve_event_driven(case.oscillator, case.t_end, x0=case.x0, rtol=RTOL_RANGE[0])
    ex = L.solve_exact(case.oscillator, case.t_end, x0=case.x0)
    assert abs(ed.rest_position - ex.rest_position) <= 1e-10 * abs(ex.rest_position)
    assert abs(ed.rest_time - ex.rest_time) <= 1e-10 * ex.rest_time


@pytest.mark.parametrize("name, n", [("hb-n0.5", 0.5), ("hb-n2", 2.0)])
def test_herschel_bulkley_reference_against_an_independent_integration(name, n):
    # Written here: slip phases m v' = -k x - s (tau + K |v|^n) by SciPy's
    # DOP853 with a terminal event at v = 0; stop if |k x| <= tau, else reverse.
    # Its own error (rtol 1e-13) is ~1e-13 m; the errors the study fits are
    # >= 4e-9 m (event-locating at 6.25e-5), so 1e-10 m leaves them intact.
    case, m, k, tau = A.cases()[name], 1.0, 100.0, 1.0
    ref = A.reference(case)
    t, x, s = 0.0, case.x0, -1
    while True:
        rhs = lambda _, y, s=s: (y[1], (-k * y[0] - s * (tau + abs(y[1]) ** n)) / m)  # noqa: E731
        stop = lambda time, y, t0=t, s=s: y[1] if time > t0 else s  # noqa: E731
        stop.terminal, stop.direction = True, -s
        sol = solve_ivp(rhs, (t, case.t_end), (x, 0.0), method="DOP853", rtol=1e-13, atol=1e-16, events=stop)
        t, x = float(sol.t_events[0][0]), float(sol.y_events[0][0][0])
        if abs(k * x) <= tau:
            break
        s = -s
    rest_time, position = ref.final(case.t_end)
    assert abs(position - x) <= 1e-10
    assert abs(rest_time - t) <= 1e-10


# ---------------------------------------------------------------- observed orders

# Seven steps in the ratio 1.37 from 1e-3 s (down to 1.5e-4 s, ~1.5 s for the four schemes on one case):
# not nested, so each switch falls at another place in its step on every grid (orders.py's Notes), and
# enough points for a standard error (five degrees of freedom).
ORDER_STEPS = geometric_steps(1e-3, 7)


def band(fit: A.Fit, rate: float, dt_max: float) -> float:
    """:func:`references.order_band` of a fit (its points less its constants and its slope)."""
    return order_band(fit.stderr, fit.points - fit.series - 1, rate, dt_max)


def fastest_rate(case: A.Case) -> float:
    """The fastest rate of a case's motion (1/s): natural frequency, forcing frequency, viscous rate 1/(m gamma)."""
    osc = case.oscillator
    gamma = getattr(osc.dashpot, "gamma", math.inf)
    omega_f = 0.0 if case.force is None else case.force.omega
    return max(math.sqrt(osc.stiffness / osc.mass), omega_f, 1 / (osc.mass * gamma))


@pytest.fixture(scope="module")
def forced_fits() -> dict[str, dict[str, A.Fit]]:
    """``[scheme][quantity]``: the Fit of each fixed-step scheme on eq. (17b) over ORDER_STEPS."""
    case = A.cases()["forced-17b"]
    ref = A.reference(case)
    out: dict[str, dict[str, A.Fit]] = {}
    for m in A.SCHEMES:
        rs = [A.run(case, m, dt, ref=ref) for dt in ORDER_STEPS]
        quantities = {"max_x": [r.max_x_error for r in rs], "position": [r.position_error for r in rs]}
        quantities |= {k: [r.event_errors.get(k, math.nan) for r in rs] for k in rs[0].event_errors}
        out[m] = {q: A.fit_order(ORDER_STEPS, e) for q, e in quantities.items()}
    return out


FORCED_RATE = fastest_rate(A.cases()["forced-17b"])  # the forcing's 5 pi rad/s


def test_the_study_steps_are_not_nested():
    # The cause of Table 3's slope 0 (issue 32): on steps 1.6e-3 / 2^j every grid holds
    # t = 0.0064 s, 23 us after the (17b) breakaway, so a scheme dating it at a grid point misses
    # it by the same 23 us at every step.  No step of the study is a whole multiple of another.
    for coarse, fine in itertools.combinations(A.STEPS, 2):
        ratio = coarse / fine
        assert abs(ratio - round(ratio)) > 1e-3, (coarse, fine)
    assert max(A.STEPS) / min(A.STEPS) > 10  # a decade at least, for a slope with a spread


def test_pooled_order_is_the_least_squares_slope_with_its_standard_error():
    # Independent reference: scipy.stats.linregress on one series; on two series with their
    # own constants, the same line fitted to the series shifted onto a common constant.
    steps = np.array(ORDER_STEPS)
    wobble = np.array([1.3, 0.7, 1.1, 0.8, 1.25, 0.9, 1.0])  # an irregular factor, as of a grid-dated event
    errors = 0.4 * steps * wobble
    ref = stats.linregress(np.log(steps), np.log(errors))
    fit = A.fit_order(steps, errors)
    assert (fit.slope, fit.stderr, fit.points, fit.series) == (
        pytest.approx(ref.slope, rel=1e-12),
        pytest.approx(ref.stderr, rel=1e-12),
        7,
        1,
    )
    h, e = np.log(steps), np.log(errors)
    pooled = A.pooled_order([(h, e), (h[1:], e[1:] + 3.0)])  # the same errors, a constant 20 times larger
    x, y = np.concatenate([h - h.mean(), h[1:] - h[1:].mean()]), np.concatenate([e - e.mean(), e[1:] - e[1:].mean()])
    slope = (x @ y) / (x @ x)
    stderr = math.sqrt(((y - slope * x) @ (y - slope * x)) / (x.size - 3) / (x @ x))  # 13 points, 2 constants, 1 slope
    assert (pooled.slope, pooled.stderr, pooled.points, pooled.series) == (
        pytest.approx(slope, rel=1e-12),
        pytest.approx(stderr, rel=1e-12),
        13,
        2,
    )


def test_event_locating_is_second_order_per_event_type(forced_fits):
    # Trapezoidal within modes, switches located to O(h^3) locally: O(dt^2)
    # for the state, the rest and every located event (event_capturing's Notes).
    for q in ("position", "max_x", "stop", "reversal", "switch"):
        fit = forced_fits["event-locating"][q]
        width = band(fit, FORCED_RATE, ORDER_STEPS[0])
        assert abs(fit.slope - 2) <= width < 0.5, q  # two, and the band excludes one
    assert math.isnan(forced_fits["event-locating"]["breakaway"].slope)  # closed form on the sine: error 0


def test_algorithm1_is_first_order(forced_fits):
    # Backward Euler: O(dt) for the state, and each switch is seen at the next grid
    # point, an error between 0 and dt whose factor jumps with where the switch falls:
    # the spread of those slopes is in their standard errors, and so in the band.
    for q in ("max_x", "stop", "reversal", "switch"):
        fit = forced_fits["backward-euler"][q]
        width = band(fit, FORCED_RATE, ORDER_STEPS[0])
        assert abs(fit.slope - 1) <= width < 0.5, q  # one, and the band excludes two and zero


def test_theta_method_is_not_second_order_through_switches(forced_fits):
    # theta.theta_method's Notes: a step across a switch averages G over the jump
    # of F_d, an O(dt) momentum error whose factor depends on where the switch
    # falls in its step.  Its order without switches, two, lies outside the band.
    fit = forced_fits["theta"]["max_x"]
    width = band(fit, FORCED_RATE, ORDER_STEPS[0])
    assert abs(fit.slope - 1) <= width and abs(fit.slope - 2) > width


def test_moreau_jean_events_pair_at_every_step(forced_fits):
    # Unlike the theta method it makes no one-step stops (the band is implicit at the new
    # level), so every event pairs with the reference's at every step, and an order is fitted
    # for each kind over all of them.  (Its events are read on the grid, as Algorithm 1's, next
    # to the scheme's own switches: errors of 0.1 to 1.5 steps here, not below one step as the
    # nested steps of the old table suggested.)
    o = forced_fits["moreau-jean"]
    assert all(o[q].points == len(ORDER_STEPS) for q in ("breakaway", "stop", "reversal", "switch"))


def test_moreau_jean_breakaway_order_is_not_the_artefact_of_nested_grids():
    # Table 3 printed slope 0.00 for Moreau-Jean's breakaway on both (17b) cases: on nested
    # steps its error was 23 us at every step.  On the study's steps (A.STEPS) the error is
    # O(dt) and irregular: the slope is one within its band, and zero lies outside it.
    case = A.cases()["forced-17b"]
    ref = A.reference(case)
    errors = [A.run(case, "moreau-jean", dt, ref=ref).event_errors["breakaway"] for dt in A.STEPS]
    fit = A.fit_order(A.STEPS, errors)
    width = band(fit, fastest_rate(case), A.STEPS[0])
    assert abs(fit.slope - 1) <= width and fit.slope > width
    # O(dt): its stick is exact and the load enters a step at its theta-average, so the breakaway
    # is dated at a grid point within one step of the exact one.
    assert all(e < dt for e, dt in zip(errors, A.STEPS))


def test_moreau_jean_runs_on_the_bingham_and_coulomb_cases_only():
    study = A.study(["coulomb-17b", "hb-n2"], steps=(1e-3, 5e-4), rtols=(1e-6,), tanh=[], original_step=None)
    assert {r.case for r in study.results if r.method == "moreau-jean"} == {"coulomb-17b"}
    assert {r.case for r in study.results if r.method == "theta"} == {"coulomb-17b", "hb-n2"}


def test_friction_oscillator_rests_where_the_half_cycles_say():
    # Coulomb, k = m = 1, bound 1: each half-cycle's amplitude about the friction's centre falls
    # by 2; from (12, 6) the first is sqrt(13^2 + 6^2) = sqrt(205) about -1, the eighth ends
    # inside the band at 15 - sqrt(205) (closed form, independent of the exact solver).
    fo = A.study(["forced-17b"], steps=(1e-3, 5e-4), rtols=(1e-6,), tanh=[], original_step=None).friction_oscillator
    assert fo["exact"] == pytest.approx(15 - math.sqrt(205), abs=1e-12)
    s = fo["schemes"]
    # Siconos rests at 0.6820441351954105 m (tests/data/siconos, its last row), to the peer test's 1e-10.
    assert s["moreau-jean"]["position"] == pytest.approx(0.6820441351954105, abs=1e-10)
    # In stick: settled on the reaction (exactly, moreau_jean_step's Notes) but for the theta method.
    assert s["moreau-jean"]["stick_swing"] == 0.0 == s["backward-euler"]["stick_swing"]
    assert s["theta"]["stick_swing"] > 1e-2


def test_slope_uses_the_finest_finite_run():
    steps, errors = [8.0, 4.0, 2.0, 1.0], [math.nan, 4.0, 2.0, 1.0]
    assert fitted_slope(steps, errors) == pytest.approx(1.0, abs=1e-12)
    assert math.isnan(fitted_slope(steps, [1.0, 1.0, math.nan, 1.0]))  # one point left: no fit
    assert str(fitted_slope(steps, [3e-5] * 4)) == "0.0"  # constant errors: exactly 0, never -0.0 or 1e-17
    assert A.fit_order(steps, [3e-5] * 4).stderr == 0.0


def test_the_original_step_runs_but_is_not_fitted():
    # The headline quotes the schemes at the original's 1e-4 s, a grid through t = 0.0064 s: it runs,
    # and the orders are fitted over the study's steps alone.
    study = A.study(["forced-17b"], steps=ORDER_STEPS[:3], rtols=(1e-6,), tanh=[])
    assert {r.resolution for r in study.results if r.method == "backward-euler"} == {*ORDER_STEPS[:3], 1e-4}
    assert study.steps == ORDER_STEPS[:3]
    fits = study.orders["forced-17b"]["backward-euler"]
    assert fits["max_x"]["points"] == 3


@pytest.mark.slow
def test_full_study_order_table():
    # The pipeline's study (~20 s): every case, every scheme; per scheme and event kind one slope
    # pooled over the cases, with its standard error.  The band's rate is the fastest of every case.
    study = A.study()
    table = A.order_table(study.results, study.steps)
    rate = max(fastest_rate(c) for c in A.cases().values())

    def fit(row: dict) -> A.Fit:
        return A.Fit(row["slope"], row["stderr"], row["points"], row["cases"])

    for k in ("stop", "reversal", "switch"):
        f = fit(table["event-locating"][k])
        assert abs(f.slope - 2) <= band(f, rate, A.STEPS[0]) < 0.5, k
    for method in ("backward-euler", "moreau-jean"):
        for k in A.KINDS:
            f = fit(table[method][k])
            assert abs(f.slope - 1) <= band(f, rate, A.STEPS[0]), (method, k)
    assert math.isnan(table["event-locating"]["breakaway"]["slope"])
    json.dumps(A.to_json(study), allow_nan=False)


# ---------------------------------------------------------------- runs and outputs


def test_event_driven_run_meets_the_target_on_the_free_decay():
    # Within the bound derived in tests/test_event_integration.py (steps (1 + 1e-3) rtol x0,
    # about 800 times the error measured, 1.5e-13 m): relative to the rest position here.
    r = A.run("free-decay", "event-driven", 1e-12)
    bound = r.work * (1 + 1e-3) * 1e-12 * 0.5
    assert r.relative_position_error * abs(r.reference_position) <= bound and r.rest_time_error <= 1e2 * bound
    assert r.work > 0


def test_to_json_is_strict_and_without_wall_time():
    study = A.study(["forced-17b"], steps=(1e-3, 5e-4, 2.5e-4), rtols=(1e-6,), tanh=[], original_step=None)
    text = json.dumps(A.to_json(study), allow_nan=False)
    assert "wall_time" not in text
    assert "wall_time" in json.dumps(A.to_json(study, wall_time=True))
    assert json.loads(text)["references"]["forced-17b"]["method"] == "exact"


def test_from_json_gives_back_the_study_that_to_json_wrote():
    """Notebook 09 reads results/accuracy/study.json through from_json: the same study, NaN and inf included."""
    study = A.study(["free-decay"], steps=(1.6e-3, 8e-4, 4e-4), rtols=(1e-6,), tanh=[(1e-2, 1e-6)], original_step=None)
    data = json.loads(json.dumps(A.to_json(study), allow_nan=False))
    back = A.from_json(data)
    assert A.to_json(back) == data
    assert [r.case for r in back.results] == [r.case for r in study.results]
    for a, b in zip(back.results, study.results):  # field by field, NaN equal to NaN
        for name in ("resolution", "eps", "position_error", "rest_time_error", "max_x_error", "reference_position"):
            assert getattr(a, name) == getattr(b, name) or (
                math.isnan(getattr(a, name)) and math.isnan(getattr(b, name))
            ), name
        assert a.work == b.work and a.event_errors.keys() == b.event_errors.keys()
    assert any(math.isnan(r.eps) for r in back.results)  # the non-tanh rows: None in the file


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: A.run("nope", "theta", 1e-3), "case must be one of"),
        (lambda: A.run("free-decay", "rk4", 1e-3), "method must be one of"),
        (lambda: A.run("hb-n2", "exact", 1e-3), "method: 'exact' needs a Bingham"),
        (lambda: A.run("free-decay", "theta", 1e-3, eps=1e-3), "eps: give it"),
        (lambda: A.run("free-decay", "tanh", 1e-6), "eps: give it"),
        (lambda: A.run("free-decay", "theta", -1e-3), "resolution"),
        (lambda: A.run("free-decay", "theta", 1e-3, repeats=-1), "repeats"),
        (lambda: A.study(["free-decay"], steps=(1e-4, 1e-3)), "steps must be"),
        (lambda: A.study(["nope"]), "names must be"),
    ],
)
def test_bad_inputs_are_named(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_the_cases_ignore_configuration_overrides(tmp_path, monkeypatch):
    """The study's cases come from the committed parameter file even where the
    pipeline points $LUMPED_CONFIG at an override (here gamma = inf, x0 = 0.9)."""
    import yaml

    import lumped.studies.config

    cfg = lumped.studies.config.default()
    override = tmp_path / "config.yaml"
    override.write_text(yaml.safe_dump({**cfg, "gamma": float("inf"), "x0_large": 0.9}), encoding="utf-8")
    monkeypatch.setenv("LUMPED_CONFIG", str(override))
    assert lumped.studies.config.load()["gamma"] == float("inf")  # the override is what load() sees
    free = A.cases()["free-decay"]
    assert free.oscillator.dashpot.gamma == cfg["gamma"] and free.x0 == cfg["x0_large"]


# ------------------------------------------------- what notebook 09 prints of adaptive runs
# An adaptive run's step sizes follow round-off (tests/test_dop853.py: one ulp of sin moves
# DOP853's by 3.5e-3, a reordered sum by 2.3e-2), so its step count and the last digits of
# its error differ between machines; notebook 09 prints bounds and one-digit errors instead.


@pytest.mark.slow
@pytest.mark.parametrize("rtol", [1e-10, 1e-12])
def test_event_driven_free_decay_within_the_printed_bounds(rtol):
    # Each accepted step's local error is at most rtol of the state and the decay does not
    # magnify it, so the rest position is within steps x rtol (145 and 232 steps here); the
    # notebook prints 1000 rtol, and the rest time within rtol seconds.
    r = A.run("free-decay", "event-driven", rtol)
    assert r.relative_position_error < r.work * rtol < 1000 * rtol
    assert r.rest_time_error < rtol


@pytest.mark.slow
@pytest.mark.parametrize("case, rtol", [("hb-n0.5", 1e-8), ("hb-n2", 1e-10)])
def test_herschel_bulkley_reaches_1e8_in_the_printed_steps(case, rtol):
    # The notebook prints the first rtol whose error is below 1e-8: it must be so with the
    # margin a round-off change of the steps leaves (a tenth of the error, see the tanh test),
    # and the coarser rtol must miss it by as much.
    coarser = A.run(case, "event-driven", rtol * 100)
    r = A.run(case, "event-driven", rtol)
    assert r.relative_position_error * 1.1 < 1e-8 < coarser.relative_position_error * 0.9
    assert r.work < 1000


def _digit_is_stable(value: float, spread: float) -> bool:
    """Whether every number within ``spread`` of ``value`` prints as ``value`` does with ``.0e``."""
    return f"{value - spread:.0e}" == f"{value:.0e}" == f"{value + spread:.0e}"


def test_digit_is_stable_sees_a_rounding_boundary():
    assert _digit_is_stable(1.22e-3, 1e-5) and not _digit_is_stable(1.22e-3, 3e-4)


@pytest.mark.slow
@pytest.mark.parametrize("eps", A.TANH_EPS)
def test_tanh_errors_print_the_same_digit_whatever_the_round_off(eps):
    # LSODA's own error at rtol 1e-6 is the difference from the run at 1e-9 (whose error is
    # ~1e-3 of that: errors scale with rtol).  Round-off changes LSODA's step sizes by a few
    # parts in 1e2 (as DOP853's), and the error, of order ~5 in h, by a tenth of itself
    # at most: the digit notebook 09 prints must hold over that spread.
    coarse, fine = (A.run("free-decay", "tanh", rtol, eps=eps) for rtol in A.TANH_RTOLS)
    solver_error = abs(coarse.relative_position_error - fine.relative_position_error)
    assert _digit_is_stable(coarse.relative_position_error, 0.1 * solver_error)
    assert _digit_is_stable(fine.relative_position_error, 0.1 * solver_error * 1e-3)
