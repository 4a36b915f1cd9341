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
from lumped.drivers.sweep import sweep
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.solvers.exact import solve_exact
from lumped.studies import stops

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
