"""The "stops per cycle" study (lumped.studies.stops): its counts against an independent integration, its limits,
its chunks and its inputs.

The reference is :func:`references.stick_slip_motion`, an event-driven DOP853 integration written independently of
:mod:`lumped.solvers.exact` (its own stop detection, its own stick/slip decision as a complementarity problem, its own
breakaway events).  A stop of the study is an event of that reference where the friction element's rate reaches zero
and the mode chosen after it is "stick" (mode 0); a reversal chooses a slip mode instead.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import references as R

from lumped import studies
from lumped.drivers.response import shooting
from lumped.drivers.response.shooting import NEWTON_TOL, Scales, find_orbit
from lumped.drivers.sweep import sweep
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.solvers.exact import solve_exact
from lumped.studies import stops, stops_low

CFG = {"mass": 1.0, "stiffness": 100.0, "threshold": 1.0}
OMEGA_N = 10.0  # sqrt(k/m) (rad/s)


def _system(r: float, ratio: float) -> R.StickSlipSystem:
    """The study's Coulomb oscillator from rest under ``(F/ratio) sin(r omega_n t)``, for the reference."""
    tau = CFG["threshold"]
    return R.StickSlipSystem(
        (CFG["mass"],),
        (0.0,),
        (0.0,),
        (R.SpringLink(-1, 0, CFG["stiffness"]),),
        (R.FrictionLink(-1, 0, tau, math.inf),),
        ((0, (tau / ratio, r * OMEGA_N, 0.0, math.inf)),),
    )


def reference_counts(r: float, ratio: float) -> tuple[int, int]:
    """Stops of the reference integration in the study's two windows, from rest under ``P sin(r omega_n t)``."""
    period = 2 * math.pi / (r * OMEGA_N)
    t_end = (stops.TRANSIENT + 2 * stops.PERIODS) * period
    motion = R.stick_slip_motion(_system(r, ratio), t_end, max_events=5000)
    times = np.array([e.time for e in motion.events if e.kind == "stop" and e.mode == (0,)])
    edge = t_end - stops.PERIODS * period
    return int(np.count_nonzero(times > edge)), int(
        np.count_nonzero((times > edge - stops.PERIODS * period) & (times <= edge))
    )


def study_counts(r: float, ratio: float) -> stops.Count:
    return stops.count_stops(stops.run(CFG, r, ratio), 2 * math.pi / (r * OMEGA_N), stops.PERIODS)


# Points of three regions of the default map: nonstop (0), two stops, four stops per period.  The counts are
# integers, so agreement is exact; the reference's event times differ from the exact ones by about rtol = 1e-12 of
# the time scale, far inside the gap between events (milliseconds at least), so no stop moves across a window edge.
@pytest.mark.slow
@pytest.mark.parametrize(("r", "ratio"), [(2.0, 0.3), (0.4, 0.6), (0.16, 0.45)])
def test_counts_agree_with_an_independent_integration(r: float, ratio: float) -> None:
    c = study_counts(r, ratio)
    assert (c.window_stops, c.previous_stops) == reference_counts(r, ratio)


def test_stop_times_agree_with_an_independent_integration_over_two_periods() -> None:
    # A point with four stops per period (its stops last from about 0.01 to 1 s).  DOP853 at rtol = 1e-12 locates
    # each event to about 1e-12 of the time scale; after some twenty events that is still below 1e-9 s, so 1e-8 s
    # bounds the difference while staying far below the shortest gap between events (checked below).
    r, ratio = 0.16, 0.45
    omega = r * OMEGA_N
    t_end = 2 * 2 * math.pi / omega
    sol = solve_exact(Oscillator.bingham(1.0, 100.0, 1.0, math.inf), t_end, force=SwitchedSine(1.0 / ratio, omega))
    ours = sol.event_times("stop")
    ref = R.stick_slip_motion(_system(r, ratio), t_end, max_events=500)
    theirs = np.array([e.time for e in ref.events if e.kind == "stop" and e.mode == (0,)])
    assert ours.size >= 6 and np.diff(ours).min() > 1e-3
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-8)


def test_regions_nonstop_at_high_frequency_and_stops_at_low_frequency() -> None:
    high, low = study_counts(2.5, 0.1), study_counts(0.15, 0.5)
    assert (high.window_stops, high.stuck_fraction) == (0, 0.0)
    assert low.window_stops >= 2 * stops.PERIODS and low.settled
    assert 0 < low.stuck_fraction < 1


@pytest.mark.parametrize("ratio", [1.0, 1.5])
def test_friction_at_least_the_force_amplitude_never_moves(ratio: float) -> None:
    # |P sin(omega t) - k*0| <= P <= F for all t: the mass released at rest sticks for ever (eq. 6).
    sol = stops.run(CFG, 0.7, ratio)
    assert [p.kind for p in sol.phases] == ["stick"] and sol.events == ()
    c = stops.count_stops(sol, 2 * math.pi / 7.0, stops.PERIODS)
    assert (c.window_stops, c.previous_stops, c.stuck_fraction) == (0, 0, 1.0)


def test_count_is_the_stop_events_in_each_window() -> None:
    # The windows, recounted here from the event list by a loop (an independent tally of the same definition).
    sol = stops.run(CFG, 0.2, 0.5)
    period = 2 * math.pi / 2.0
    c = stops.count_stops(sol, period, 2)
    last = first = 0
    for e in sol.events:
        if e.kind == "stop" and e.time > sol.t_end - 2 * period:
            last += 1
        elif e.kind == "stop" and e.time > sol.t_end - 4 * period:
            first += 1
    assert (c.window_stops, c.previous_stops) == (last, first)


@pytest.fixture(scope="module")
def whole() -> dict[str, np.ndarray]:
    """The study on a 2 x 2 grid (r = 0.1 and 3, F/P = 1/4 and 3/4)."""
    return stops.rows(CFG, 2, 2)


def test_chunks_concatenate_to_the_whole_grid(whole: dict[str, np.ndarray]) -> None:
    parts = [stops.rows(CFG, 2, 2, (i, 3)) for i in range(3)]
    for column in stops.COLUMNS:
        np.testing.assert_array_equal(np.concatenate([p[column] for p in parts]), whole[column])
    assert whole["window_stops"].dtype == np.int64
    np.testing.assert_array_equal(whole["stops_per_period"], whole["window_stops"] / stops.PERIODS)


def test_the_file_reads_back_bit_for_bit(tmp_path, whole: dict[str, np.ndarray]) -> None:
    table = whole
    studies.write_csv(table, tmp_path / "stops.csv", stops.COLUMNS)
    back = studies.read_csv(tmp_path / "stops.csv", stops.COLUMNS)
    for column in stops.COLUMNS:
        np.testing.assert_array_equal(back[column], table[column])


def test_grid_axes() -> None:
    r, ratio = stops.grid(5, 4)
    np.testing.assert_allclose(r[[0, -1]], stops.R_RANGE, rtol=1e-15)
    np.testing.assert_allclose(np.diff(np.log(r)), np.log(30) / 4, rtol=1e-12)
    np.testing.assert_array_equal(ratio, [0.125, 0.375, 0.625, 0.875])
    assert "stops" in studies.STUDIES and studies.study("stops") is stops


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: stops.run(CFG, 0.0, 0.5), "frequency_ratio"),
        (lambda: stops.run(CFG, 1.0, -0.5), "friction_ratio"),
        (lambda: stops.run(CFG, math.nan, 0.5), "frequency_ratio"),
        (lambda: stops.grid(0, 3), "r_points"),
        (lambda: stops.rows(CFG, 2, 2, (2, 2)), "index"),
    ],
)
def test_bad_inputs_name_the_argument(call, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        call()


def test_event_count_equals_the_sweeps_sampled_definition_where_stops_are_long() -> None:
    # At r = 0.4, F/P = 0.6 every stop lasts a good part of a period (stuck fraction printed in notebook 12), so
    # sampling the same exact solution every dt = 1 ms misses none: lumped.drivers.sweep's sampled stops_per_period (steps
    # entering v == 0, over the last K periods) must equal the count from events.  t_end is chosen so that the sweep's
    # grid ends exactly at the study's t_end up to round-off; no stop lies within dt of a window edge (asserted).
    r, ratio = 0.4, 0.6
    omega, dt = r * OMEGA_N, 1e-3
    period = 2 * math.pi / omega
    sol = stops.run(CFG, r, ratio)
    n = round(sol.t_end / dt)
    ours = stops.count_stops(sol, period, stops.PERIODS)
    swept = sweep(
        {"force_omega": [omega]},
        t_end=n * dt,
        dt=dt,
        method="exact",
        periods=stops.PERIODS,
        gamma=math.inf,
        threshold=CFG["threshold"],
        force_amplitude=CFG["threshold"] / ratio,
    )
    times = sol.event_times("stop")
    assert np.abs(times - (sol.t_end - stops.PERIODS * period)).min() > 2 * dt
    assert ours.window_stops > 0
    assert swept["stops_per_period"][0] == ours.window_stops / stops.PERIODS


# ---- the periodic motions by shooting (orbit columns, lumped.studies.stops_low) ----


def test_orbit_columns_agree_with_the_runs_where_they_settle(whole: dict[str, np.ndarray]) -> None:
    # Newton from the run's last state converges to the motion of period T that the run approaches; where the run's
    # two windows agree and the multiplier is well below 1 (the run has converged geometrically), the counts agree.
    fast = (whole["settled"] == 1) & (whole["orbit_multiplier"] < 0.9)
    assert fast.sum() >= 3
    np.testing.assert_array_equal(whole["orbit_stops"][fast], whole["stops_per_period"][fast])


@pytest.fixture(scope="module")
def low() -> dict[str, np.ndarray]:
    """The low-frequency study on its default grid (40 shootings, about 0.5 s)."""
    return stops_low.rows(CFG, *stops_low.GRID["default"][:2])


def test_low_frequency_map_holds_the_high_counts(low: dict[str, np.ndarray]) -> None:
    # Hong and Liu's 8, 10, 12 and 14 stops per cycle appear below r = 0.1; every motion found is symmetric
    # (even counts) and reached fast from rest (multipliers far below 1).
    assert {8, 10, 12, 14} <= set(low["orbit_stops"].tolist())
    assert np.all(low["orbit_stops"] % 2 == 0) and low["orbit_multiplier"].max() < 0.5


# Cells of the default low grid (indices of r and F/P) with 8, 10, 12 and 14 stops per period.  The reference is the
# package's event-driven method (slip phases integrated by DOP853, not the exact phases), run from rest over the
# study's TRANSIENT + 2 PERIODS and sampled every 1 ms: every stick and every slip between two sticks of the exact
# run lasts more than two samples (asserted), so each stop holds a sample and no two merge; the counts are integers,
# so agreement is exact.
@pytest.mark.parametrize(("i", "j"), [(3, 2), (3, 3), (2, 3), (1, 2)])
def test_low_frequency_counts_agree_with_runs_from_rest(low: dict[str, np.ndarray], i: int, j: int) -> None:
    r_axis, q_axis = stops_low.grid(*stops_low.GRID["default"][:2])
    r, ratio = r_axis[i], q_axis[j]
    (row,) = np.flatnonzero((low["frequency_ratio"] == r) & (low["friction_ratio"] == ratio))
    period, dt = 2 * math.pi / (r * OMEGA_N), 1e-3
    exact = stops.run(CFG, r, ratio)
    count = stops.count_stops(exact, period, stops.PERIODS)
    assert count.settled and count.window_stops == low["orbit_stops"][row] * stops.PERIODS
    sticks = np.array([(a, b) for a, b in exact.stick_intervals() if b < exact.t_end])
    assert np.diff(sticks, axis=1).min() > 2 * dt and (sticks[1:, 0] - sticks[:-1, 1]).min() > 2 * dt
    n = round(exact.t_end / dt)
    swept = sweep(
        {"force_omega": [r * OMEGA_N]},
        t_end=n * dt,
        dt=dt,
        method="event-driven",
        periods=stops.PERIODS,
        gamma=math.inf,
        threshold=CFG["threshold"],
        force_amplitude=CFG["threshold"] / ratio,
    )
    assert swept["stops_per_period"][0] == low["orbit_stops"][row]


def test_the_full_grids_row_of_three_stops_is_a_transient() -> None:
    # The cell (30, 4) of the full grid: 3 stops per period in both windows of the run from rest, but the motion of
    # period T has 2, with a multiplier just below 1, and a longer run reaches it.  That motion is symmetric: Newton
    # stops at a residual of NEWTON_TOL (in P/k), so the fixed point is within NEWTON_TOL / (1 - multiplier) < 1e-8,
    # and x(t) + x(t + T/2) of a symmetric motion is 0 up to twice that.
    r_axis, q_axis = stops.grid(*stops.GRID["full"][:2])
    r, ratio = r_axis[30], q_axis[4]
    period = 2 * math.pi / (r * OMEGA_N)
    count = stops.count_stops(stops.run(CFG, r, ratio), period, stops.PERIODS)
    assert (count.window_stops, count.previous_stops) == (3 * stops.PERIODS, 3 * stops.PERIODS)
    orbit = stops.orbit_count(CFG, r, ratio)
    assert orbit.stops == 2 and 0.99 < orbit.multiplier < 1
    osc = Oscillator.bingham(1.0, 100.0, 1.0, math.inf)
    longer = solve_exact(osc, 120 * period, force=SwitchedSine(1.0 / ratio, r * OMEGA_N))
    later = stops.count_stops(longer, period, stops.PERIODS)
    assert (later.window_stops, later.previous_stops) == (2 * stops.PERIODS, 2 * stops.PERIODS)
    found = find_orbit(osc, 1.0 / ratio, r * OMEGA_N)
    t = np.linspace(0.0, period / 2, 101)
    x = found.period.solution.evaluate(np.concatenate([t, t + period / 2]))["x"] * 100.0 * ratio  # units P/k
    bound = 2 * NEWTON_TOL / (1 - found.max_multiplier)
    assert bound < 2e-8 and np.abs(x[:101] + x[101:]).max() < bound


def test_one_stop_motion_at_half_the_natural_frequency_is_marginal_and_asymmetric() -> None:
    # At r = 1/2 (Csernak, Stepan and Shaw's Omega = 1/2n, n = 1) the motion found has one stop per period (odd,
    # so not symmetric), a multiplier 1 to within Newton's accuracy, and a run from rest keeps one stop per period.
    orbit = stops.orbit_count(CFG, 0.5, 0.2)
    assert orbit.stops == 1 and abs(orbit.multiplier - 1) < 1e-5
    count = stops.count_stops(stops.run(CFG, 0.5, 0.2), 2 * math.pi / 5.0, stops.PERIODS)
    assert (count.window_stops, count.previous_stops) == (stops.PERIODS, stops.PERIODS)


def test_on_a_continuum_of_periodic_motions_newton_takes_least_norm_steps() -> None:
    # At r = 1/4, F/P = 0.02 the periodic motions form a continuum (Csernak, Stepan and Shaw's Omega = 1/2n,
    # n = 2): M - I is singular within its computed error, so a Newton step is not defined by the map.  The
    # least-norm steps find a member of the family (its defect below Newton's tolerance, its multiplier 1 to
    # the margin of its computation), where a full solve would step by round-off along the family.
    osc = Oscillator.bingham(CFG["mass"], CFG["stiffness"], CFG["threshold"], math.inf)
    found = find_orbit(osc, CFG["threshold"] / 0.02, 0.25 * OMEGA_N)
    assert shooting._singular(found.period)
    defect = found.period.end - found.state
    assert np.max(np.abs(Scales.of(osc, CFG["threshold"] / 0.02).state(defect))) <= NEWTON_TOL
    assert found.max_multiplier == 1.0  # marginal: 1 within the monodromy's error


def test_low_grid_continues_the_step_of_the_map_above() -> None:
    above, ratio_above = stops.grid(12, 8)
    r, ratio = stops_low.grid(12, 8)
    step = above[1] / above[0]
    np.testing.assert_allclose(np.append(r, above[0])[1:] / np.append(r, above[0])[:-1], step, rtol=1e-12)
    assert r[0] >= stops_low.R_LOW > r[0] / step and r[-1] < stops.R_RANGE[0]
    np.testing.assert_array_equal(ratio, ratio_above)
    assert studies.study("stops_low") is stops_low
    assert {k: v[:2] for k, v in stops_low.GRID.items()} == {k: v[:2] for k, v in stops.GRID.items()}


def test_low_chunks_concatenate_and_read_back(tmp_path) -> None:
    whole = stops_low.rows(CFG, 12, 1)
    parts = [stops_low.rows(CFG, 12, 1, (i, 3)) for i in range(3)]
    studies.write_csv(whole, tmp_path / "low.csv", stops_low.COLUMNS)
    back = studies.read_csv(tmp_path / "low.csv", stops_low.COLUMNS)
    for column in stops_low.COLUMNS:
        np.testing.assert_array_equal(np.concatenate([p[column] for p in parts]), whole[column])
        np.testing.assert_array_equal(back[column], whole[column])
    assert whole["orbit_stops"].dtype == np.int64


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: stops_low.grid(1, 3), "r_points"),
        (lambda: stops_low.grid(12, 0), "ratio_points"),
        (lambda: stops.orbit_count(CFG, -1.0, 0.5), "frequency_ratio"),
        (lambda: stops.orbit_count(CFG, 0.5, math.inf), "friction_ratio"),
    ],
)
def test_low_bad_inputs_name_the_argument(call, message: str) -> None:
    with pytest.raises(ValueError, match=message):
        call()


def _grazing_cell() -> tuple[float, float]:
    """The cell (17, 16) of the full low-frequency grid, at the edge where a pair of short stops appears."""
    r_axis, q_axis = stops_low.grid(*stops_low.GRID["full"][:2])
    return r_axis[17], q_axis[16]


def _against_the_slip(solution, spacing: float) -> bool:
    """Whether ``s v < 0`` at any interior time of a slip phase sampled every ``spacing`` s or less (brute force)."""
    for phase in solution.phases:
        if phase.motion is not None:
            t = np.linspace(phase.start, phase.end, 2 + math.ceil((phase.end - phase.start) / spacing))[1:-1]
            if np.any(math.copysign(1.0, phase.motion.s_tau) * phase.motion.state(t)[1] < 0):
                return True
    return False


def test_steps_over_a_stop_agrees_with_dense_sampling() -> None:
    # At the grazing cell the periodic motion has a slip phase whose velocity dips against its direction (by
    # about 4e-6 P omega_n/k for about a millisecond), shorter than the spacing of the grid the exact solver
    # brackets zeros of v on; the solver locates such a dip by the acceleration's sign change
    # (lumped.solvers.closed_form.SlipMotion._scan) and stops there.  The detector (minima of s v bracketed at
    # pi/(64 omega_n), refined by Brent) and sampling every phase every 1e-4 s, a tenth of the dip, must agree
    # that no stop is stepped over, for the periodic motion and for a run from rest (8 periods).
    r, ratio = _grazing_cell()
    osc = Oscillator.bingham(1.0, 100.0, 1.0, math.inf)
    orbit = find_orbit(osc, 1.0 / ratio, r * OMEGA_N)
    run = solve_exact(osc, 8 * 2 * math.pi / (r * OMEGA_N), force=SwitchedSine(1.0 / ratio, r * OMEGA_N))
    for solution in (orbit.period.solution, run):
        assert not stops.steps_over_a_stop(solution)
        assert not _against_the_slip(solution, 1e-4)


def test_the_dip_is_a_stop_and_the_count_is_the_runs() -> None:
    # The dip is a stop: the periodic motion there has 10 stops per period, as the run from rest settles to
    # (its last two periods), not the 9 a solver stepping over the dip would give.
    r, ratio = _grazing_cell()
    assert stops.orbit_count(CFG, r, ratio).stops == 10
    osc, period = Oscillator.bingham(1.0, 100.0, 1.0, math.inf), 2 * math.pi / (r * OMEGA_N)
    run = solve_exact(osc, 8 * period, force=SwitchedSine(1.0 / ratio, r * OMEGA_N))
    last = [e for e in run.events if e.kind == "stop" and e.time > 7 * period]
    assert len(last) == 10
