"""Messages name what the user can change (issue 31): an option or a file's key, never an internal argument.

Before: a Herschel-Bulkley exponent of 1e6 was blamed on ``consistency``;
``simulate --method event-driven --t-end 1e6`` under a sine ran for 47 s and
then said "raise max_steps", an argument no option sets; the exact solver's
refusals named ``max_events``.
"""

from __future__ import annotations

import math

import pytest
from cli_run import run_lumped

import lumped as L

SINE = L.SwitchedSine(10.0, 5 * math.pi)  # eq. (17b) without its end: 2.5 periods a second, P = 10 N > tau = 1 N

HB_SYSTEM = """[[mass]]
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
between = ["ground", "m1"]
threshold = 1.0
consistency = {consistency}
exponent = {exponent}
"""


@pytest.mark.parametrize(
    ("consistency", "exponent", "blamed"),
    [(1.0, 1e6, "exponent"), (1e305, 1.0, "consistency"), (1e305, 3.0, "consistency")],
)
@pytest.mark.parametrize("method", ["backward-euler", "event-driven"])
def test_a_herschel_bulkley_law_too_large_is_blamed_on_the_key_that_makes_it_so(
    tmp_path, method, consistency, exponent, blamed
):
    # 5^(1e6) overflows by the exponent; K = 1e305 by the consistency, whatever the exponent.
    (tmp_path / "hb.toml").write_text(HB_SYSTEM.format(consistency=consistency, exponent=exponent))
    args = ["simulate", "--system", "hb.toml", "--method", method, "--t-end", "1", "--dt", "0.01"]
    run = run_lumped(*args, "--output", "o.csv", cwd=tmp_path)
    assert run.returncode == 2 and run.stderr.count("\n") == 1, run.stderr
    assert f"system file 'hb.toml': [[element]] 'hb' {blamed}: " in run.stderr, run.stderr
    osc = L.Oscillator(1.0, L.LinearSpring(100.0), L.HerschelBulkleyDashpot(1.0, consistency, exponent))
    with pytest.raises(ValueError, match=f"^{blamed}: "):
        L.simulate(osc, 1.0, 0.01, x0=0.5, method=method)


def test_event_driven_takes_at_least_one_step_per_forcing_period():
    # The lower bound that the up-front refusal below rests on (solvers.event_driven._check_steps, Notes).
    sol = L.solve_event_driven(L.Oscillator.bingham(), 10.0, force=SINE)
    assert sol.steps >= math.floor(10.0 * SINE.omega / (2 * math.pi))  # 25 periods


def test_event_driven_refuses_before_any_step_a_run_over_its_step_budget():
    # 25 whole periods in 10 s: more than 20 steps, refused up front naming t_end, not max_steps.
    message = r"^t_end: the event-driven integration would take at least 25 steps \(one per forcing period"
    with pytest.raises(ValueError, match=message):
        L.solve_event_driven(L.Oscillator.bingham(), 10.0, force=SINE, max_steps=20)


def test_simulate_event_driven_with_a_long_t_end_is_refused_at_once_naming_an_option(tmp_path):
    # Was: refused after 47 s with "raise max_steps or rtol".
    args = ["--method", "event-driven", "--t-end", "1e6", "--dt", "10", "--force-amplitude", "10"]
    run = run_lumped("simulate", *args, "--force-omega", "15.707963267948966", "--output", "o.csv", cwd=tmp_path)
    assert run.returncode == 2 and run.stderr.count("\n") == 1, run.stderr
    assert run.stderr.startswith("lumped simulate: error: --t-end: the event-driven integration would take at least")
    assert "max_" not in run.stderr and not list(tmp_path.iterdir())


def test_the_exact_solvers_event_bound_is_not_named_as_an_argument(tmp_path):
    run = run_lumped(
        "simulate", "--method", "exact", "--stiffness", "1e12", "--x0", "0.5", "--output", "o.csv", cwd=tmp_path
    )
    assert run.returncode == 2 and "max_" not in run.stderr, run.stderr
    assert "events before t_end, more than the 100000 a run may have; shorten t_end" in run.stderr
