"""``python -m lumped cycles`` and :func:`lumped.cycles` (issue 34, part P): the columns, the empty cells, the
long run's crossing, the refusals (one line, status 2, no output, before any work).

The cycles come from :func:`~lumped.drivers.cycles.shooting.find_cycle` and the branches from
:func:`~lumped.drivers.cycles.continuation.continue_branches` (parts Q and R, tested in their own files); the
wiring is tested with doubles of them built on the static/kinetic belt's closed form
(:func:`~lumped.solvers.closed_form_belt.belt_cycle`), and the command itself against the issue's references:
the static/kinetic belt's closed-form cycle (1e-10) and Leine's benchmark against the independent event-located
integration of tests/test_friction_event_driven.py (1e-8).
"""

from __future__ import annotations

import csv
import math
import re
import sys
import types
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_lumped
from test_friction_event_driven import leine_reference, leine_system

import lumped
from lumped.drivers.cycles import api, steady_sliding
from lumped.drivers.cycles.continuation import BranchPoint
from lumped.drivers.cycles.shooting import Cycle
from lumped.model.files import load_system
from lumped.solvers.closed_form_belt import belt_cycle
from lumped.solvers.event_driven_network import model

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
BELT = EXAMPLES / "belt.toml"
STRIBECK = EXAMPLES / "stribeck_belt.toml"


def closed_form_cycle(network, v0: float) -> Cycle:
    """The double of ``find_cycle``: the static/kinetic belt's closed-form cycle (a stick collapses the map)."""
    mdl = model(network)
    el = network.elements[mdl.contact.link.element]
    c = belt_cycle(mdl.m, mdl.K, el.static, el.kinetic, mdl.V)
    return Cycle(
        c.period, v0, np.array([c.x_max]), np.array([c.x_min]), c.stick_time, 1, 0.0, np.array([0j]), 0.0, True
    )


@pytest.fixture
def doubles(monkeypatch):
    """Parts Q and R as doubles: ``find_cycle`` records its starts; ``continue_branches`` gives an equilibrium, a
    Hopf point and one cycle."""
    starts = []

    def find_cycle(network, v0, *, tol=1e-12):
        starts.append(v0)
        return closed_form_cycle(network, v0)

    def continue_branches(
        network, parameter, start, stop, points=50, progress=None, *, start_branch=True, returns=None, notes=None
    ):
        continuation.calls.append((parameter, start, stop, start_branch))
        eq = steady_sliding(network)
        cycle = closed_form_cycle(network, 0.2)
        stable = eq._replace(max_real_part=-1e-14, stable=True)  # the located Hopf point, a hair on one side
        return [
            BranchPoint(start, "equilibrium", eq, None, "regular"),
            BranchPoint(0.5 * (start + stop), "equilibrium", stable, None, "hopf"),
            BranchPoint(0.5 * (start + stop), "cycle", None, cycle, "hopf"),
            BranchPoint(stop, "cycle", None, cycle, "fold"),
        ]

    monkeypatch.setattr(api, "find_cycle", find_cycle)
    continuation = types.ModuleType("lumped.drivers.cycles.continuation")  # part R, until it is on main
    continuation.continue_branches, continuation.calls = continue_branches, []
    monkeypatch.setitem(sys.modules, "lumped.drivers.cycles.continuation", continuation)
    return starts


def read(path: Path) -> list[dict[str, str]]:
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def test_the_long_run_crosses_the_section_in_the_stick_at_the_belts_speed(doubles, tmp_path):
    """The belt's cycle crosses ``x* = kinetic/k = 0.5`` upward while stuck (it sticks at ``x = 0`` and breaks
    away at ``x = 1``): the long run's settled crossing is the belt's speed, exactly (a stuck phase moves with
    the belt: ``u = 0``, no rounding)."""
    out = tmp_path / "c.csv"
    run = run_lumped("cycles", "--system", BELT, "--output", out)
    assert run.returncode == 0, run.stderr
    assert doubles == [0.2]
    rows = read(out)
    assert list(rows[0]) == [
        "branch",
        "period",
        "max_m",
        "min_m",
        "stick_time",
        "stable",
        "max_multiplier",
        "max_real_part",
        "kind",
    ]
    eq, cyc = rows
    assert eq == {
        "branch": "equilibrium",
        "period": "",
        "max_m": "0.5",
        "min_m": "0.5",
        "stick_time": "",
        "stable": "false",
        "max_multiplier": "",
        "max_real_part": "0",
        "kind": "regular",
    }
    ref = belt_cycle(1.0, 1.0, 1.0, 0.5, 0.2)
    assert cyc["branch"] == "cycle" and float(cyc["period"]) == ref.period and float(cyc["max_m"]) == ref.x_max
    assert (cyc["max_real_part"], cyc["stable"], cyc["max_multiplier"]) == ("", "true", "0")
    assert "steady sliding at x = 0.5 m (not stable); 1 cycle (1 stable)" in run.stderr


def test_the_api_gives_the_same_table_with_nan_where_a_value_does_not_apply(doubles):
    with pytest.raises(ValueError, match=r"^progress must be callable"):
        lumped.cycles(load_system(BELT), progress=3)
    with pytest.raises(ValueError, match=r"^vary: expected \(name, start, stop\)"):
        lumped.cycles(load_system(BELT), vary=0.3)
    table = lumped.cycles(load_system(BELT))
    assert table.columns["branch"].tolist() == ["equilibrium", "cycle"]
    assert math.isnan(table.columns["period"][0]) and math.isnan(table.columns["max_real_part"][1])
    assert table.columns["stable"].dtype == bool


def test_without_vary_only_the_hopf_branch_is_followed(doubles):
    """Without ``vary`` the Hopf branch is followed from the nearest Hopf point (the Stribeck example's,
    ``0.5298`` m/s) to the file's belt speed for its cycle there, and not the branch of the cycle found at the
    range's start as well: that one is not wanted (and it took 25 of the command's 33 s)."""
    lumped.cycles(load_system(STRIBECK))
    calls = sys.modules["lumped.drivers.cycles.continuation"].calls
    assert [(name, stop, start_branch) for name, _, stop, start_branch in calls] == [("belt.velocity", 0.8, False)]
    assert calls[0][1] == pytest.approx(0.5298317366548037, rel=1e-12)


def test_with_vary_the_branches_are_rows_with_the_parameter_first(doubles, tmp_path):
    out = tmp_path / "v.csv"
    run = run_lumped("cycles", "--system", BELT, "--vary", "0.1:0.3", "--points", "5", "--output", out)
    assert run.returncode == 0, run.stderr
    rows = read(out)
    assert list(rows[0])[:2] == ["belt.velocity", "branch"]
    assert [r["kind"] for r in rows] == ["regular", "hopf", "hopf", "fold"]
    assert [r["belt.velocity"] for r in rows] == [
        "0.10000000000000001",
        "0.20000000000000001",
        "0.20000000000000001",
        "0.29999999999999999",
    ]
    assert rows[3]["max_real_part"] == "" and rows[3]["period"] != ""
    assert rows[1]["stable"] == "false"  # the pair on the imaginary axis: marginal, whatever side it lies on
    assert "changes: 1 hopf, 1 fold" in run.stderr  # one Hopf point, where both branches meet
    named = run_lumped("cycles", "--system", BELT, "--vary", "belt.velocity=0.1:0.3", "--output", tmp_path / "n.csv")
    assert named.returncode == 0 and (tmp_path / "n.csv").read_text() == out.read_text()  # the default's name


VISCOUS = """
[[mass]]
name = "m"
mass = 1.0
[[driver]]
name = "belt"
velocity = 0.2
[[element]]
name = "k"
kind = "spring"
between = ["ground", "m"]
stiffness = 1.0
[[element]]
name = "c"
kind = "dashpot"
between = ["belt", "m"]
damping = 0.3
"""


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--points", "1"], r"--points: between 2 and 10000 rows, got 1"),
        (["--points", "10001"], r"--points: between 2 and 10000 rows, got 10001"),
        (
            ["--vary", "fric.static=0.5:2"],
            r"--vary: at fric.static = 0.5: no falling law: .*\(eigenvalues 0 \+- 1i 1/s\)",
        ),
        (["--vary", "belt.velocity=-0.1:0.5"], r"--vary: belt.velocity = -0.1:0.5 reaches 0, where the belt stops"),
        (["--vary", "belt.speed=0.1:0.5"], r"--vary: unknown parameter 'belt.speed'; .*'belt.velocity'"),
        (["--vary", "0.5:0.1"], r"--vary: START:STOP must satisfy START < STOP"),
        (
            ["--vary", "belt.velocity=0.2:0.20000000000000004", "--points", "3"],
            r"--vary: 0.2:0.20000000000000004 holds fewer than 3 distinct values",
        ),  # one ulp wide: 50 rows of the same two speeds otherwise
        (["--vary", "fric.kinetic=0.5:2"], r"--vary: at fric.kinetic = 2: kinetic = 2.0 N must not exceed static"),
        (["--vary", "fric.kinetic=0.5:1"], r"--vary: at fric.kinetic = 1: no falling law"),
        (["--vary", "=0.1:0.5"], r"--vary expects NAME=START:STOP or START:STOP"),
        (["--vary", "m.x0=0.1:0.5"], r"--vary: m.x0 is the initial state, on which neither steady sliding nor"),
    ],
)
def test_bad_options_are_refused_in_one_line_before_any_work(doubles, tmp_path, args, message):
    out = tmp_path / "c.csv"
    run = run_lumped("cycles", "--system", BELT, *args, "--output", out)
    assert run.returncode == 2
    assert run.stderr.count("\n") == 1 and run.stderr.startswith("lumped cycles: error: ")
    assert re.search(message, run.stderr), run.stderr
    assert not list(tmp_path.iterdir()) and doubles == []


def test_a_linear_viscous_contact_is_refused_with_its_eigenvalues(tmp_path):
    """No falling law: steady sliding at ``x* = c V / k = 0.06`` m, eigenvalues of ``s^2 + 0.3 s + 1``."""
    system = tmp_path / "viscous.toml"
    system.write_text(VISCOUS)
    run = run_lumped("cycles", "--system", system, "--output", tmp_path / "c.csv")
    assert run.returncode == 2
    root = math.sqrt(4 - 0.09) / 2
    assert run.stderr == (
        f"lumped cycles: error: {system}: no falling law: the dashpot 'c' on the moving point is linear, so steady "
        f"sliding at x = 0.06 m (eigenvalues -0.15 +- {root:.6g}i 1/s) cannot lose stability and there is no cycle\n"
    )
    assert [p.name for p in tmp_path.iterdir()] == ["viscous.toml"]


def test_a_file_without_a_driven_point_is_refused(tmp_path):
    system = tmp_path / "ground.toml"
    system.write_text(BELT.read_text().replace('between = ["belt", "m"]', 'between = ["ground", "m"]'))
    run = run_lumped("cycles", "--system", system, "--output", tmp_path / "c.csv")
    assert run.returncode == 2 and "the friction contact 'fric' is on a point at rest" in run.stderr


def test_two_drivers_need_the_parameters_name(tmp_path):
    system = tmp_path / "two.toml"
    system.write_text(BELT.read_text() + '\n[[driver]]\nname = "plate"\nvelocity = 0.0\n')
    run = run_lumped("cycles", "--system", system, "--vary", "0.1:0.3", "--output", tmp_path / "c.csv")
    assert (
        run.returncode == 2 and "--vary: the system has 2 driven points (belt, plate): name the parameter" in run.stderr
    )


def test_only_csv_is_written(tmp_path):
    run = run_lumped("cycles", "--system", BELT, "--output", tmp_path / "c.npz")
    assert run.returncode == 2 and "--output must end in .csv" in run.stderr


def test_the_help_names_the_columns():
    run = run_lumped("cycles", "--help")
    assert run.returncode == 0
    text = " ".join(run.stdout.split())
    for column in ("branch", "period", "max_<mass>", "min_<mass>", "stick_time", "max_multiplier", "max_real_part"):
        assert column in text


def test_a_stable_sliding_run_settles_on_steady_sliding():
    """The Stribeck example above its Hopf speed spirals in at ``0.093``/s: no cycle from its initial state."""
    net = load_system(STRIBECK)
    assert api._settled_crossing(net, steady_sliding(net)) == (
        None,
        "the run from the initial state settles on steady sliding",
    )


# -- the references, through the command and the API -----------------------------------------------------


def test_the_belt_example_from_cycles_is_the_closed_form_cycle(tmp_path):
    """``examples/belt.toml``: the row's period, extremes and stick time are the closed form's to 1e-10 (the
    issue's bound: the harmonic slip and the stick at the belt's speed are closed forms in shooting too, so only
    rounding of a few operations on O(1) numbers and Newton's 1e-12 on the section speed separate them)."""
    out = tmp_path / "c.csv"
    run = run_lumped("cycles", "--system", BELT, "--output", out)
    assert run.returncode == 0, run.stderr
    eq, cyc = read(out)
    ref = belt_cycle(1.0, 1.0, 1.0, 0.5, 0.2)
    assert (eq["branch"], eq["max_m"], eq["stable"], eq["max_real_part"]) == ("equilibrium", "0.5", "false", "0")
    got = [float(cyc[c]) for c in ("period", "max_m", "min_m", "stick_time")]
    assert got == pytest.approx([ref.period, ref.x_max, ref.x_min, ref.stick_time], rel=1e-10, abs=1e-10)
    assert (cyc["stable"], cyc["max_multiplier"], cyc["max_real_part"]) == ("true", "0", "")


def test_leines_benchmark_cycle_from_cycles_meets_the_reference():
    """Leine's law (a callable: the API), the cycle from the long run: its period (between two breakaways) and
    extremes against the SciPy event-located reference at 1e-13, to 1e-8: tests/test_friction_event_driven.py
    derives 1.8e-9 for each method's event times and states over a cycle at that tolerance (shooting integrates
    at the same), twice that between the two.  Steady sliding: ``c_eff = g'(0.2) = -3/1.6^2``, a complex pair
    of real part ``-c_eff/2``."""
    breaks, turns = leine_reference(40.0, 1e-13)
    table = lumped.cycles(leine_system())
    assert table.columns["branch"].tolist() == ["equilibrium", "cycle"]
    turning = [x for t, x in turns if breaks[1] < t < breaks[2]]
    assert table.columns["period"][1] == pytest.approx(breaks[2] - breaks[1], abs=1e-8)
    assert table.columns["max_m"][1] == pytest.approx(max(turning), abs=1e-8)
    assert table.columns["min_m"][1] == pytest.approx(min(turning), abs=1e-8)
    assert table.columns["stable"].tolist() == [False, True]
    assert table.columns["max_real_part"][0] == pytest.approx((3 / (1 + 3 * 0.2) ** 2) / 2, rel=1e-8)


def test_a_block_riding_a_slow_belt_is_not_called_steady_sliding(tmp_path):
    """At a belt speed of 2e-7 m/s the block sticks near x = 0 and creeps with the belt (its stick lasts
    2 (static - kinetic)/(k V) = 5e6 s): its swing over a natural period is tiny, but it is far from x* = 0.5 m,
    so the summary must not say that the run settles on steady sliding."""
    text = BELT.read_text(encoding="utf-8").replace("velocity = 0.2", "velocity = 2e-7")
    assert "velocity = 2e-7" in text
    path = tmp_path / "slow.toml"
    path.write_text(text, encoding="utf-8")
    table = lumped.cycles(load_system(path))
    assert "settles on steady sliding" not in table.summary


def test_a_slow_belt_from_cycles_gives_the_closed_form_cycle(tmp_path):
    """``examples/belt.toml`` at 2e-7 m/s: the long run from rest cannot reach the cycle within its natural periods
    (the block rides the belt for 2.5e6 s before it first breaks away), but the cycle crosses the section stuck, at
    the belt's speed, which is a start of its own: one cycle row, ``belt_cycle``'s period and extremes to 1e-10
    (relative for the period: 5e6 s), its stick time to the clock's ``8 eps`` of the period (the shooting's test)."""
    path = tmp_path / "slow.toml"
    path.write_text(BELT.read_text(encoding="utf-8").replace("velocity = 0.2", "velocity = 2e-7"), encoding="utf-8")
    out = tmp_path / "c.csv"
    run = run_lumped("cycles", "--system", path, "--output", out)
    assert run.returncode == 0, run.stderr
    eq, cyc = read(out)
    ref = belt_cycle(1.0, 1.0, 1.0, 0.5, 2e-7)
    assert float(cyc["period"]) == pytest.approx(ref.period, rel=1e-10)
    assert [float(cyc["max_m"]), float(cyc["min_m"])] == pytest.approx([ref.x_max, ref.x_min], abs=1e-10)
    assert float(cyc["stick_time"]) == pytest.approx(ref.stick_time, abs=8 * np.finfo(float).eps * ref.period)
    assert (cyc["stable"], cyc["max_multiplier"]) == ("true", "0")
    assert "1 cycle (1 stable)" in run.stderr


def test_a_belt_too_slow_to_vouch_for_says_why_without_naming_an_internal_argument(tmp_path):
    """At 1e-12 m/s the stick lasts 1e12 s, beyond the return's clock: no cycle, and the summary says why in the
    user's words.  ``find_cycle``'s messages name its own arguments (``v0: ``, ``v: ``), which the user never gave."""
    path = tmp_path / "slowest.toml"
    path.write_text(BELT.read_text(encoding="utf-8").replace("velocity = 0.2", "velocity = 1e-12"), encoding="utf-8")
    run = run_lumped("cycles", "--system", path, "--output", tmp_path / "c.csv")
    assert run.returncode == 0, run.stderr
    summary = run.stderr.strip().splitlines()[-1]
    assert "0 cycles" in summary and "no cycle is vouched for" in summary
    assert not re.search(r"\bv0?: ", summary), summary
