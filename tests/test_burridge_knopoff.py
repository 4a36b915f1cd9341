"""The Burridge-Knopoff study (lumped.studies.burridge_knopoff): the law's mapping onto Carlson and Langer's,
the event catalogue against hand-built trajectories (exact counts and sums), the catalogue across the run's
cuts against one uncut run, one block against the event-driven solution, and the power-law fit against
Hill's closed form and a sample of known exponent."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from lumped.solvers.event_driven_network import solve_contact
from lumped.studies import burridge_knopoff as bk


def test_the_floor_is_carlson_and_langers_law_with_no_drop():
    """phi(y) = sign(y)/(1 + |y|), y = 2 alpha v in CL's velocity unit D_0 omega_p (the 1989 law, both ways, as
    the teaching code read for notebook 17 has it; sigma = 0): to a few ulps."""
    p = bk.Parameters(blocks=2, alpha=2.5, mass=2.0, leaf=8.0, static=3.0)
    law = next(el for el in bk.chain(p, np.zeros(2)).elements if el.name == "floor0").law
    unit = p.length * p.omega  # D_0 omega_p = (3/8 m)(2 /s)
    for v in (1e-3, 0.1, 1.0, 7.0):
        assert law.slip(v * unit) / p.static == pytest.approx(1 / (1 + 2 * p.alpha * v), rel=4e-16)
        for u in (v, -v):  # the law acts both ways: the friction on a block sliding backwards is forward
            expected = math.copysign(1.0, u) / (1 + 2 * p.alpha * abs(u))
            assert law.tension(u * unit) / p.static == pytest.approx(expected, rel=4e-16)
    assert law.slip_limit == p.static
    assert p.coupling == 100 * p.leaf and p.plate_speed == p.nu * unit


def _trajectory(cells, steps, blocks, dt=0.5):
    """t, x, v with velocity 0.25 (m/s) in each (step, block) of ``cells`` (step >= 1), x by backward Euler."""
    v = np.zeros((steps + 1, blocks))
    for n, j in cells:
        v[n, j] = 0.25
    t = dt * np.arange(steps + 1)
    return t, np.cumsum(v * dt, axis=0), v


def test_catalogue_counts_connected_bursts():
    # event A: block 2 alone, steps 2-3; event B: blocks 5-7 (7 joins at step 5 through 6), steps 4-5;
    # event C: block 0 at step 5, separate from B (not adjacent); event D: block 2 again at steps 7-9,
    # touching block 3 at step 8.
    cells = [(2, 2), (3, 2), (4, 5), (4, 6), (5, 6), (5, 7), (5, 0), (7, 2), (8, 2), (8, 3), (9, 2)]
    t, x, v = _trajectory(cells, 10, 8)
    c = bk.catalogue(t, x, v)
    assert list(c.start_time) == [0.5, 1.5, 2.0, 3.0]
    assert list(c.first_block) == [2, 5, 0, 2]
    assert list(c.blocks) == [1, 3, 1, 2]
    assert list(c.moment) == [0.25, 0.5, 0.125, 0.5]  # 0.125 per cell: exact in binary
    assert list(c.duration) == [1.0, 1.0, 0.5, 1.5]
    assert (c.unfinished, c.back_steps, c.slip_steps) == (0, 0, len(cells))


def test_catalogue_leaves_out_bursts_cut_by_the_data_and_counts_back_steps():
    cells = [(0, 1), (1, 1), (3, 4), (6, 0), (6, 1)]
    t, x, v = _trajectory(cells, 6, 5)
    v[3, 4] = -0.25
    x = np.cumsum(v * 0.5, axis=0)
    c = bk.catalogue(t, x, v)
    assert list(c.blocks) == [1] and list(c.moment) == [-0.125]
    assert (c.unfinished, c.back_steps, c.slip_steps) == (2, 1, 4)


@pytest.mark.parametrize(("periodic", "events"), [(False, 2), (True, 1)])
def test_a_periodic_chain_joins_its_ends(periodic, events):
    t, x, v = _trajectory([(2, 0), (2, 5), (3, 5)], 5, 6)
    assert len(bk.catalogue(t, x, v, periodic=periodic)) == events


@pytest.mark.parametrize("piece", [1, 2, 3, 4])
def test_a_trajectory_given_in_pieces_has_the_catalogue_of_the_whole(piece):
    """Bursts overlapping in time (one opens before another ends, and ends after it): no event lost or twice."""
    cells = [(2, 0), (3, 0), (4, 0), (5, 0), (6, 0), (7, 0), (3, 4), (4, 4), (5, 4), (5, 3), (8, 6), (9, 6), (2, 2)]
    t, x, v = _trajectory(cells, 10, 7)
    whole = bk.catalogue(t, x, v)
    pieces = bk.Cataloguer(t[0], x[0], v[0])
    for i in range(1, len(t), piece):
        pieces.add(t[i : i + piece], x[i : i + piece], v[i : i + piece])
    for name in ("start_time", "first_block", "blocks", "moment", "duration"):
        assert list(getattr(pieces.catalogue(), name)) == list(getattr(whole, name)), name
    assert len(whole) == 4 and whole.unfinished == 0


def test_the_catalogue_does_not_see_the_cuts_of_a_run():
    """Events in pieces of 11 steps (every one crosses a cut) against one piece: the same events, moments to rounding.

    The restart subtracts the plate's position (a multiple of V dt up to 0.08 m here) and adds it back: each
    position then carries rounding of order 1e-16 of 1 m, and a moment sums at most a few hundred of them.
    """
    p = bk.Parameters(blocks=5, nu=0.1)
    x0 = bk.initial_positions(p, seed=3, roughness=4e-3) - 0.6 * p.length  # loaded: the first slip comes soon
    whole = bk.run(p, 0.8, 0.01, x0=x0, segment=10**6)
    cut = bk.run(p, 0.8, 0.01, x0=x0, segment=11)
    assert len(whole.catalogue) == 6 and whole.catalogue.blocks.max() == 5  # the last slips every block
    for name in ("start_time", "first_block", "blocks", "duration"):
        assert np.array_equal(getattr(whole.catalogue, name), getattr(cut.catalogue, name)), name
    assert np.abs(whole.catalogue.moment - cut.catalogue.moment).max() <= 1e-12
    for name in ("unfinished", "back_steps", "slip_steps"):
        assert getattr(whole.catalogue, name) == getattr(cut.catalogue, name), name


def test_one_block_against_the_event_driven_solution():
    """One block on the plate: each event's slip and duration against the event-driven motion (rtol 1e-12).

    Backward Euler is first order, so each error over dt tends to a constant.  Across the three steps it may
    vary by the grid's quantisation (the breakaway and the stop each fall on a grid point: one step in time,
    so 2 in the duration's error over dt and 2 nu (plate travel in a step, times the slip's sensitivity 2 to
    the force at breakaway) in the moment's) plus the first-order part's own O(dt) change, at most
    rho = omega dt t_slip times its size at the largest dt (as in notebook 15).
    """
    p = bk.Parameters(blocks=1, nu=0.1)
    motion = solve_contact(bk.chain(p, np.zeros(1)), 35.0, rtol=1e-12)
    b0 = next(e.time for e in motion.events if e.kind == "breakaway")
    s0 = next(e.time for e in motion.events if e.kind == "stop")
    exact_duration = s0 - b0
    exact_moment = float(np.diff(motion.state(np.array([b0, s0]))[0])[0])
    errors = []
    for dt in (0.02, 0.01, 0.005):
        events = bk.run(p, 3.5, dt, x0=np.zeros(1)).catalogue
        assert len(events) == 2 and list(events.blocks) == [1, 1]
        errors.append([(events.duration[0] - exact_duration) / dt, (events.moment[0] - exact_moment) / dt])
    errors = np.array(errors)
    rho = p.omega * 0.02 * exact_duration
    band = np.array([2.0, 2 * p.nu]) + rho * np.abs(errors).max(axis=0)
    assert np.all(np.ptp(errors, axis=0) <= band), (errors, band)


def test_hill_estimator_without_an_upper_end():
    s = np.array([1.0, 1.5, 2.0, 4.0, 9.0, 0.5])
    fit = bk.fit_power_law(s, 1.0)
    y = np.log(s[s >= 1.0])
    assert fit.exponent == pytest.approx(1 + y.size / y.sum(), rel=1e-15)
    assert fit.stderr == pytest.approx((fit.exponent - 1) / math.sqrt(y.size), rel=1e-15)
    assert fit.count == 5


@pytest.mark.parametrize("exponent", [1.5, 2.0, 2.7])
def test_truncated_power_law_fit_recovers_a_known_exponent(exponent):
    """20,000 sizes drawn on [1, 100] by the inverse CDF: the estimate within 4 standard errors (its own).

    The estimator is asymptotically normal with the Fisher-information error it reports, so a draw falls
    outside 4 of them with probability 6e-5; the seed is fixed, so the test is deterministic.
    """
    rng = np.random.default_rng(11)
    u = rng.random(20_000)
    a, lo, hi = 1 - exponent, 1.0, 100.0
    s = (lo**a + u * (hi**a - lo**a)) ** (1 / a)
    fit = bk.fit_power_law(s, lo, hi)
    assert abs(fit.exponent - exponent) <= 4 * fit.stderr
    assert 0.005 < fit.stderr < 0.05


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: bk.Parameters(blocks=0), "blocks"),
        (lambda: bk.Parameters(ends="open"), "ends must be one of free, periodic"),
        (lambda: bk.Parameters(alpha=-1.0), "alpha"),
        (lambda: bk.initial_positions(bk.Parameters(), roughness=0.01), "roughness must be below"),
        (lambda: bk.fit_power_law([1.0, 2.0], 3.0), "fewer than 2"),
        (lambda: bk.fit_power_law([1.0, 2.0], 2.0, 1.0), "must exceed"),
        (lambda: bk.run(bk.Parameters(blocks=2), -1.0, 0.01), "travel"),
    ],
)
def test_bad_inputs_are_refused_in_one_line(call, message):
    with pytest.raises(ValueError, match=message) as err:
        call()
    assert "\n" not in str(err.value)


def test_the_pipeline_script_writes_a_catalogue_that_reads_back(tmp_path):
    import subprocess
    import sys
    from pathlib import Path

    script = Path(__file__).resolve().parents[1] / "scripts" / "burridge_knopoff.py"
    out = tmp_path / "bk.csv"
    done = subprocess.run([sys.executable, str(script), "1", "1.1", "0.02", str(out)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    table = bk.read_catalogue(out)
    facts = json.loads(out.with_suffix(".json").read_text())
    assert table["blocks"].dtype == np.int64 and len(table["moment"]) == facts["events"] >= 1
    assert facts["steps"] == 5500 and facts["blocks"] == 1
    bad = subprocess.run([sys.executable, str(script), "3", "1", "0.5", str(out)], capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "dt" in bad.stderr


@pytest.mark.parametrize(("key", "value"), [("bk_blocks", 0), ("bk_blocks", 2.5), ("bk_travel", -1.0), ("bk_dt", 0.2)])
def test_the_configuration_refuses_bad_chain_keys(key, value):
    import lumped.studies.config

    raw = {**lumped.studies.config.default(), key: value}
    (line,) = lumped.studies.config.problems(raw)
    assert line.startswith(f"config: {key}")
