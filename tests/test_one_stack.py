"""One stack (issue 33, A.1): every registered method runs a problem through :func:`lumped.solve` or refuses it.

For every method of :data:`lumped.METHODS` and six problems (the paper's
system under a sine, a two-mass network, a friction element with static above
kinetic, a block on a belt, a Stribeck contact on the belt, the paper's system
under a table load), ``solve`` either returns a :class:`~lumped.Trajectory` of
the problem's own system or raises a one-line ``ValueError`` that names the
method (``'exact'``) and a reason: never another exception type.  A run is
held to a reference where one exists in closed form, so that a silent wrong
path (a driver treated as the ground, a table dropped, a friction element run
as another law) fails.

:data:`EXPECTED` is the one table of outcomes, each ``RUNS`` or ``REFUSES``,
asserted.  (``EITHER``, either outcome in its form, is for a method being
extended; no pair is marked so today.)

The shims (:func:`lumped.simulate`, :func:`lumped.simulate_network` and the
one-mass solvers users know) give what ``solve`` gives, bit for bit.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from conftest import assert_same_trajectory

import lumped as L
from lumped.cli import main
from lumped.model.files import parse_system

RUNS, REFUSES, EITHER = "runs", "refuses", "either"

#: The grid of every run; the checks below derive their tolerances from it.
DT = 1e-3
#: The time at which runs are compared with their references.
T_CHECK = 1.0

_MASS = '[[mass]]\nname = "m"\nmass = 1.0\nx0 = {x0}\n'
_BELT = '[[driver]]\nname = "belt"\nvelocity = 0.2\n'


def _spring(a: str = "ground", b: str = "m", k: float = 1.0, name: str = "spring") -> str:
    return f'[[element]]\nname = "{name}"\nkind = "spring"\nbetween = ["{a}", "{b}"]\nstiffness = {k}\n'


def _friction(to: str, extra: str = "") -> str:
    return (
        f'[[element]]\nname = "fric"\nkind = "friction"\nbetween = ["{to}", "m"]\nstatic = 1.0\nkinetic = 0.5\n{extra}'
    )


_BINGHAM_N = '[[element]]\nname = "d"\nkind = "bingham"\nbetween = ["ground", "n"]\nthreshold = 0.5\ngamma = 1.0\n'
#: The system files of the network problems (m = k = 1 where not said).
TEXTS = {
    "two-mass": _MASS.format(x0=0.5)
    + '[[mass]]\nname = "n"\nmass = 2.0\n'
    + _spring()
    + _spring("m", "n", 2.0, "s2")
    + _BINGHAM_N,
    # Released at x0 = 3.2 (spring force 3.2 > static 1): it slips at once with the kinetic force.
    "friction": _MASS.format(x0=3.2) + _spring() + _friction("ground"),
    # At rest under a belt at 0.2 m/s: it slips at first, then rides the belt.
    "belt": _MASS.format(x0=0.0) + _BELT + _spring() + _friction("belt"),
    "stribeck": _MASS.format(x0=0.0)
    + _BELT
    + _spring()
    + _friction("belt", "stribeck_velocity = 0.5\nviscous = 0.1\n"),
}
PAPER = L.Oscillator.bingham(1.0, 100.0, 1.0, 1.0)
TABLE = L.Table(np.array([0.0, 1.0, 2.0]), np.array([0.0, 1.0, 0.0]))


def problem(name: str) -> L.Problem:
    """The problem called ``name`` (over 1.5 s: past :data:`T_CHECK`, cheap for every method)."""
    if name == "paper":
        return L.Problem.oscillator(PAPER, 1.5, x0=0.5, force=L.SwitchedSine(2.0, 5.0))
    if name == "table":
        return L.Problem.oscillator(PAPER, 1.5, x0=0.5, force=TABLE)
    return L.Problem(parse_system(TEXTS[name], name), 1.5)


PROBLEMS = ("paper", "two-mass", "friction", "belt", "stribeck", "table")
_ONE_MASS = ("event-driven", "theta", "moreau-jean")  # their solvers run one mass on springs and a dashpot
#: The outcome of every (problem, method); the lead updates it as methods gain laws.
EXPECTED: dict[tuple[str, str], str] = {
    **{("paper", m): RUNS for m in L.METHODS},
    **{("two-mass", m): RUNS for m in ("backward-euler", "exact", "event-locating")},
    **{("two-mass", m): REFUSES for m in _ONE_MASS},
    ("friction", "backward-euler"): RUNS,
    ("friction", "exact"): RUNS,  # static/kinetic without a Stribeck velocity: closed forms per phase
    ("friction", "event-driven"): RUNS,  # any slip curve
    ("belt", "backward-euler"): RUNS,
    ("belt", "exact"): RUNS,  # a driver at constant velocity: closed forms per phase
    ("belt", "event-driven"): RUNS,
    ("stribeck", "backward-euler"): RUNS,
    ("stribeck", "exact"): REFUSES,  # a Stribeck curve has no closed form per phase
    ("stribeck", "event-driven"): RUNS,
    **{(p, m): REFUSES for p in ("friction", "belt", "stribeck") for m in ("event-locating", "theta", "moreau-jean")},
    **{("table", m): RUNS for m in ("backward-euler", "event-locating", "theta", "moreau-jean")},
    **{("table", m): REFUSES for m in ("exact", "event-driven")},  # their closed forms and events need a sine
}


def test_the_table_covers_every_method_and_problem() -> None:
    assert set(EXPECTED) == {(p, m) for p in PROBLEMS for m in L.METHODS}


def _at(tr: L.Trajectory, t: float) -> int:
    """The saved row at time ``t`` (a grid point)."""
    i = int(np.argmin(np.abs(tr.t - t)))
    assert math.isclose(tr.t[i], t, abs_tol=DT / 2)
    return i


def _belt_reference(t: float) -> float:
    """The block on the belt (m = k = 1, kinetic 0.5, belt 0.2 m/s, from rest at 0): it slips, pushed forward by
    the kinetic force, ``x = 0.5 (1 - cos t)``, until its speed ``0.5 sin t`` reaches the belt's at
    ``t1 = asin(0.4)``, then rides the belt (its spring force, below 0.16 N before ``t = 1``, is within
    ``static``): ``x = x(t1) + 0.2 (t - t1)``."""
    t1 = math.asin(0.4)
    return 0.5 * (1 - math.cos(min(t, t1))) + 0.2 * max(t - t1, 0.0)


def check_reference(name: str, method: str, tr: L.Trajectory) -> None:
    """Hold a run of problem ``name`` to its independent reference, where one exists."""
    i = _at(tr, T_CHECK)
    x, v = tr.positions[i, 0], tr.velocities[i, 0]
    if name == "friction":
        # Slipping from x0 = 3.2 with the kinetic force 0.5 against the motion: x = 0.5 + 2.7 cos t until
        # t = pi.  Backward Euler's amplification |1/(1 + i dt)| per step shrinks the amplitude 2.7 by
        # 2.7 t dt / 2 to first order (its phase error is O(dt^2)); a method of higher order does better.
        # The bound is twice that term.  A friction element run with the static force in the slip (1, not
        # 0.5) would be off by 0.5 (1 - cos 1) = 0.23.
        assert abs(x - (0.5 + 2.7 * math.cos(T_CHECK))) <= 2.7 * T_CHECK * DT
    elif name in ("belt", "stribeck"):
        # Stuck to the belt at t = 1 (the mass reached the belt's speed before, its spring force is far
        # inside static): its rate is the belt's to rounding.  A driver treated as the ground would keep the
        # mass at rest (x = 0 is an equilibrium there: spring force 0, inside the static bound).
        assert abs(v - 0.2) <= 1e-12
        if name == "belt":
            # Backward Euler's one slip phase: a local error dt^2 |x''| / 2 <= dt^2 / 4 (|x''| <= 0.5) on each
            # of t1 / dt = 412 steps, grown at most e^t1 = 1.5 times: 0.16 dt; the step in which it catches the
            # belt adds at most 0.2 dt (the speeds differ by at most 0.2 m/s over one step).  The bound dt is
            # more than twice that sum; a method of higher order does better.
            assert abs(x - _belt_reference(T_CHECK)) <= DT
    elif name == "table":
        # The load applied is the table's, interpolated between its points (the ramp t here), to rounding.
        assert np.allclose(tr.applied[:, 0], np.interp(tr.t, TABLE.t, TABLE.values), rtol=0, atol=1e-15)


def check_refusal(method: str, err: ValueError) -> None:
    """A refusal in its form: one line that names the method (quoted) and a reason, not the registry's list."""
    message = str(err)
    name = L.METHODS[method].name
    assert "\n" not in message and message == message.strip(), message
    assert f"'{name}'" in message, f"the refusal does not name the method {name!r}: {message}"
    assert "must be one of" not in message, message
    reason = message.replace(f"'{name}'", "").replace("method", "")
    assert len(re.findall(r"[a-z]{3,}", reason)) >= 4, f"no reason given: {message}"


@pytest.mark.parametrize("method", list(L.METHODS))
@pytest.mark.parametrize("name", PROBLEMS)
def test_every_method_runs_or_refuses_every_problem(name: str, method: str) -> None:
    p = problem(name)
    expected = EXPECTED[(name, method)]
    try:
        tr = L.solve(p, DT, method=method)
    except ValueError as err:
        assert expected != RUNS, f"{method} refused {name}: {err}"
        check_refusal(method, err)
        return
    assert expected != REFUSES, f"{method} ran {name}, which the table says it refuses"
    assert isinstance(tr, L.Trajectory)
    assert tr.network is p.system  # the problem's own system, its drivers and loads included
    assert tr.positions.shape == (tr.t.size, len(p.system.masses)) and np.isfinite(tr.positions).all()
    check_reference(name, method, tr)


def test_a_driven_point_is_named_in_the_refusal_of_a_one_mass_method() -> None:
    """A contact on a belt is not to the ground: the refusal names the driven point and who runs it."""
    with pytest.raises(
        ValueError,
        match=r"^method 'theta' cannot run a system with driven points \('belt'\); backward-euler runs it \(exact and event-driven too, at a constant velocity\)$",
    ):
        L.solve(problem("belt"), DT, method="theta")
    with pytest.raises(
        ValueError, match="^element 'fric' joins the mass to the driven point 'belt', not to the ground$"
    ):
        L.model.problem.one_mass_form(problem("belt").system)


# -- the shims: the same stack, the same numbers ------------------------------------------------------


@pytest.mark.parametrize("method", list(L.METHODS))
def test_simulate_is_solve_of_the_oscillator_problem(method: str) -> None:
    force = L.SwitchedSine(2.0, 5.0)
    shim = L.simulate(PAPER, 0.5, DT, x0=0.5, force=force, method=method)
    stack = L.solve(L.Problem.oscillator(PAPER, 0.5, x0=0.5, force=force), DT, method=method)
    assert_same_trajectory(shim, stack)


@pytest.mark.parametrize("solver", ["auto", "active-set", "compiled", "python"])
def test_simulate_network_is_backward_euler_with_its_solver(solver: str) -> None:
    net = problem("two-mass").system
    shim = L.simulate_network(net, 0.5, DT, solver=solver)
    stack = L.solve(L.Problem(net, 0.5), DT, method="backward-euler", solver=solver)
    for field in dataclasses.fields(shim):  # every field, bit for bit (two masses: no one-mass view to compare)
        a, b = getattr(shim, field.name), getattr(stack, field.name)
        same = np.array_equal(a, b, equal_nan=True) if isinstance(a, np.ndarray) else repr(a) == repr(b)
        assert same, field.name


def test_the_solver_option_is_backward_eulers_alone() -> None:
    p = problem("paper")
    assert L.solve(p, DT, method="backward-euler").solver == "algorithm1"  # the fast path, chosen inside
    assert L.solve(p, DT, method="backward-euler", solver="python").solver == "python"  # the caller may insist
    with pytest.raises(ValueError, match="^solver must be one of auto, active-set, compiled, python; got 'fast'$"):
        L.solve(p, DT, solver="fast")
    with pytest.raises(ValueError, match=r"^solver: method 'exact' takes no option 'solver' \(it takes none\)$"):
        L.solve(p, DT, method="exact", solver="python")


@pytest.mark.parametrize(
    ("name", "call"),
    [
        ("backward-euler", lambda: L.backward_euler(PAPER, 0.5, DT, x0=0.5)),
        ("backward-euler", lambda: L.algorithm1(PAPER, 0.5, DT, x0=0.5)),
        ("exact", lambda: L.solve_exact(PAPER, 0.5, x0=0.5).sample(DT)),
        ("event-driven", lambda: L.solve_event_driven(PAPER, 0.5, x0=0.5).sample(DT)),
        ("event-locating", lambda: L.event_capturing(PAPER, 0.5, DT, x0=0.5).trajectory),
        ("theta", lambda: L.theta_method(PAPER, 0.5, DT, x0=0.5)),
    ],
)
def test_the_one_mass_solvers_users_know_give_what_solve_gives(name: str, call: Callable[[], L.Trajectory]) -> None:
    """Each is the method's one-mass solver, the path ``solve`` takes for the paper's system: the same
    numbers bit for bit (``solve`` adds the network's columns: each element's force)."""
    own = call()
    stack = L.solve(L.Problem.oscillator(PAPER, 0.5, x0=0.5), DT, method=name)
    for field in ("t", "positions", "velocities", "applied", "forces"):
        assert np.array_equal(getattr(own, field), getattr(stack, field)), field


def test_the_command_line_does_not_offer_the_api_option_solver(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """``solver`` is the API's option of backward Euler; a refusal on the command line lists only its flags."""
    out = tmp_path / "run.csv"
    argv = ["simulate", "--t-end", "1", "--dt", "1e-3", "--rtol", "1e-8", "--output", str(out)]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.endswith("--rtol: method 'backward-euler' takes no option 'rtol' (it takes none)"), err
    with pytest.raises(
        ValueError, match=r"^rtol: method 'backward-euler' takes no option 'rtol' \(its options are solver\)$"
    ):
        L.solve(problem("paper"), DT, rtol=1e-8)
