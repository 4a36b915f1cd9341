"""``cycles`` at the edges issue 41 found: belts running backwards, every parameter kind, equilibria that are no
cycles, cycles close to one another, subcritical Hopf points, bounded work and the command line's refusals.

References: the closed-form stick-slip cycle of static above kinetic on a belt (``belt_cycle``), mirrored for a
belt running backwards; the forward belt's own cycles (the mirror ``x -> -x`` maps one system onto the other).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from cli_run import run_lumped

import lumped
from lumped.drivers.cycles import api, continuation, find_cycle, return_map, shooting
from lumped.drivers.cycles.continuation import continue_branches
from lumped.drivers.cycles.equilibria import hopf_points
from lumped.model.files import load_system
from lumped.model.system_parameters import system_parameters, with_values
from lumped.solvers.closed_form_belt import belt_cycle

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
BELT = EXAMPLES / "belt.toml"  # m = k = 1, static 1, kinetic 0.5, belt 0.2 m/s
STRIBECK = EXAMPLES / "stribeck_belt.toml"  # static 6, kinetic 2, v_s 0.1, viscous 0.2, exponential, belt 0.8 m/s
#: The closed form's tolerance: the shooting's phases are closed forms too (harmonic slip, stick, breakaway), so
#: the two differ by the round-off of a few ulps of the O(1) state and of the O(10) s period, far below
#: (tests/test_cycles_continuation.py, test_the_static_kinetic_branch_meets_belt_cycle_at_every_point).
CLOSED_FORM_ABS = 1e-10


def with_text(tmp_path: Path, source: Path, old: str, new: str, extra: str = "") -> Path:
    """``source`` with ``old`` replaced by ``new`` (and ``extra`` appended), written to ``tmp_path``."""
    text = source.read_text()
    assert old in text
    path = tmp_path / source.name
    path.write_text(text.replace(old, new) + extra)
    return path


def cycle_rows(table: api.CyclesTable) -> dict[str, np.ndarray]:
    keep = table.columns["branch"] == "cycle"
    return {name: col[keep] for name, col in table.columns.items()}


def member(path: Path, name: str, value: float):
    net = load_system(path)
    return with_values(net, system_parameters(net, [name]), [value])


# -- 1. a belt running backwards is the mirror image of the forward one ------------------------------------------


@pytest.mark.parametrize("speed", [0.1, 0.3])
def test_a_backward_static_kinetic_belt_gives_the_mirrored_closed_form_cycle(speed):
    """At ``V = -speed`` the stick-slip cycle is ``belt_cycle``'s at ``speed`` mirrored: the same period and stick
    time, ``x_max = -x_min(speed)`` and ``x_min = -x_max(speed)``, crossing ``x*`` downward at ``V``."""
    ref = belt_cycle(mass=1.0, stiffness=1.0, static=1.0, kinetic=0.5, velocity=speed)
    cycle = find_cycle(member(BELT, "belt.velocity", -speed), -speed)
    got = (cycle.period, cycle.x_max[0], cycle.x_min[0], cycle.stick_time)
    assert got == pytest.approx((ref.period, -ref.x_min, -ref.x_max, ref.stick_time), rel=0, abs=CLOSED_FORM_ABS)
    assert cycle.section == -speed and cycle.stick_phases == 1


def test_a_backward_belt_range_has_the_cycles_of_the_forward_one():
    """``vary = belt.velocity`` over -0.5:-0.3 on the Stribeck belt: at both ends the cycles are those of 0.3:0.5
    mirrored.  The mirror is an exact symmetry of the equations and of every step of the method (negation is exact
    in floating point), so the ends, where both ranges take the same speeds, agree to the last bit; before, no
    cycle at all (``find_cycle``'s ``v0 > 0`` refusal swallowed)."""
    net = load_system(STRIBECK)
    back = lumped.cycles(net, vary=("belt.velocity", -0.5, -0.3), points=2)
    ahead = lumped.cycles(net, vary=("belt.velocity", 0.3, 0.5), points=2)
    b, a = cycle_rows(back), cycle_rows(ahead)
    for end in (0.3, 0.5):
        i = np.flatnonzero(b["belt.velocity"] == -end)
        j = np.flatnonzero(a["belt.velocity"] == end)
        assert i.size == j.size >= 1
        for col in ("period", "stick_time", "max_multiplier"):
            assert np.array_equal(np.sort(b[col][i]), np.sort(a[col][j]))
        assert np.array_equal(np.sort(b["max_m"][i]), np.sort(-a["min_m"][j]))
    eq = back.columns["branch"] == "equilibrium"
    assert np.all(back.columns["max_m"][eq] < 0)  # x* = -g(|V|)/K


def test_the_backward_sections_speed_is_refused_in_the_forward_direction():
    """On a belt at ``V < 0`` the section is crossed downward: a ``v > 0`` is refused in one line naming it."""
    net = member(BELT, "belt.velocity", -0.2)
    with pytest.raises(ValueError, match=r"^v0: the belt runs at V < 0, so the section is crossed downward"):
        find_cycle(net, 0.2)
    with pytest.raises(ValueError, match=r"^v: the belt runs at V < 0"):
        return_map(net, 0.2)


def test_a_backward_belt_without_vary_is_the_mirrored_file(tmp_path):
    """The file at -0.2 m/s (no ``vary``): steady sliding at ``-kinetic/K`` and the mirrored closed-form cycle."""
    path = with_text(tmp_path, BELT, "velocity = 0.2 ", "velocity = -0.2 ")
    table = lumped.cycles(load_system(path))
    ref = belt_cycle(mass=1.0, stiffness=1.0, static=1.0, kinetic=0.5, velocity=0.2)
    rows = cycle_rows(table)
    stuck = np.flatnonzero(rows["stick_time"] > 0)
    assert stuck.size == 1
    got = (rows["period"][stuck[0]], rows["max_m"][stuck[0]], rows["min_m"][stuck[0]])
    assert got == pytest.approx((ref.period, -ref.x_min, -ref.x_max), rel=0, abs=CLOSED_FORM_ABS)
    assert table.summary.startswith("steady sliding at x = -0.5 m")


# -- 2. every parameter kind over its valid range ----------------------------------------------------------------


def test_kinetic_varied_gives_the_closed_form_cycle_at_every_point():
    """``vary = fric.kinetic`` over 0.1:0.9 (static 1): every row is ``belt_cycle``'s at its kinetic force.  Before,
    ``dP/dp`` at a stuck return built the member at ``kinetic + 1`` (1.1 > static), refused and swallowed: no
    cycle."""
    table = lumped.cycles(load_system(BELT), vary=("fric.kinetic", 0.1, 0.9), points=5)
    rows = cycle_rows(table)
    assert rows["fric.kinetic"].size >= 5 and rows["fric.kinetic"][0] == 0.1 and rows["fric.kinetic"][-1] == 0.9
    for kinetic, period, hi, lo, stuck in zip(
        *(rows[c] for c in ("fric.kinetic", "period", "max_m", "min_m", "stick_time"))
    ):
        ref = belt_cycle(mass=1.0, stiffness=1.0, static=1.0, kinetic=float(kinetic), velocity=0.2)
        got = (period, hi, lo, stuck)
        assert got == pytest.approx((ref.period, ref.x_max, ref.x_min, ref.stick_time), rel=0, abs=CLOSED_FORM_ABS)


def test_f_p_steps_backwards_at_the_edge_of_the_values_the_system_takes():
    """On the Stribeck belt without its viscous part at ``kinetic = 6 - 1e-6`` (static 6), the end of the range from
    1, ``kinetic + h`` (``h`` = 3.2e-5) is refused (above
    static): ``F_p`` is the backward difference ``(P(p - h) - P(p)) / -h``, the same arithmetic as written here
    (``==``); before, the refusal reached the corrector, which took it for no cycle there."""
    net = member(STRIBECK, "fric.viscous", 0.0)  # no viscous part: the curve falls for every kinetic below static
    fam = continuation._Family(net, "fric.kinetic", 1.0, 6 - 1e-6)
    p, v = 6 - 1e-6, 0.3
    h = continuation._forward_step(p, fam.p_s)
    with pytest.raises(ValueError):
        fam.member(p + h)
    here = return_map(fam.member(p), v)[0]
    got = fam._difference(v, p, here)
    assert got == (return_map(fam.member(p - h), v)[0] - here) / -h
    assert math.isfinite(got)


def test_a_parameter_that_does_not_move_the_belt_has_no_belt_rate():
    """``dV/dp``: 1 for the contact's driver's velocity, 0 for any other parameter (kinetic, stiffness), the sign
    of the mirror for a belt running backwards."""
    net = load_system(BELT)
    rates = [
        continuation._Family(net, name, a, b).belt_rate
        for name, a, b in (
            ("belt.velocity", 0.1, 0.2),
            ("belt.velocity", -0.2, -0.1),
            ("fric.kinetic", 0.1, 0.9),
            ("spring.stiffness", 1, 2),
        )
    ]
    assert rates == [1.0, -1.0, 0.0, 0.0]


# -- 3. an equilibrium is never a cycle --------------------------------------------------------------------------

DAMPER = '\n[[element]]\nname = "damper"\nkind = "dashpot"\nbetween = ["ground", "m"]\ndamping = {c}\n'


def test_an_overdamped_belt_has_no_cycle_of_the_integrators_noise(tmp_path):
    """A 30 N s/m dashpot on the Stribeck belt (``c_eff`` = 30.1 > 2 sqrt(m k): overdamped, stable): no cycle.
    Before, Newton from the belt's speed came to a "stable cycle" of swing 7.4e-14 m, the motion creeping back to
    ``x*`` and crossing it by the integrator's error; the swing is now refused below 1e-9 of the motion's scale
    ``max(static/K, |x*|)`` (6 m here), the returns' error (shooting.SWING_TOL)."""
    path = with_text(tmp_path, STRIBECK, "", "", DAMPER.format(c=30.0))
    table = lumped.cycles(load_system(path))
    assert list(table.columns["branch"]) == ["equilibrium"]
    assert "steady sliding, not a cycle" in table.summary


# -- 4. a short stick is not the grazing orbit ---------------------------------------------------------------------


def test_a_stick_slip_cycle_beside_the_grazing_orbit_is_its_own_row(tmp_path):
    """``static - kinetic = 1e-6 K``: the stick-slip cycle (stuck 2e-6/0.2 = 1e-5 s a period) crosses the section
    at ``V`` and the grazing harmonic orbit of the centre just below: within 1e-8 of each other, so they were one
    row and the stick-slip cycle was dropped.  The stick-slip cycle is a row, ``belt_cycle``'s.  The grazing orbit
    is one member of the centre's family of harmonic orbits (multiplier 1), listed only when a start happens to land
    on it (at ``kinetic = 0.5`` none does), so its row is not asserted; if it is there, it is a row of its own."""
    path = with_text(tmp_path, BELT, "kinetic = 0.5 ", "kinetic = 0.999999 ")
    rows = cycle_rows(lumped.cycles(load_system(path)))
    ref = belt_cycle(mass=1.0, stiffness=1.0, static=1.0, kinetic=0.999999, velocity=0.2)
    stuck = np.flatnonzero(rows["stick_time"] > 0)
    assert stuck.size == 1 and rows["period"].size in (1, 2)
    got = tuple(rows[c][stuck[0]] for c in ("period", "max_m", "min_m", "stick_time"))
    assert got == pytest.approx((ref.period, ref.x_max, ref.x_min, ref.stick_time), rel=0, abs=CLOSED_FORM_ABS)


# -- 5. below a subcritical Hopf point -----------------------------------------------------------------------------


def test_below_a_subcritical_hopf_point_the_hopf_branch_gives_no_start(tmp_path):
    """The Stribeck belt at 0.4 m/s, below its Hopf speed ``0.1 ln(4 / (0.1 0.2)) = 0.530`` m/s: the branch born
    there is subcritical (its cycles above it), so it gives no start at 0.4: the summary reports the stick-slip
    cycle and nothing from the Hopf branch (before: "v0 must be > 0 and finite, got 0.0", the zero amplitude's
    section taken for a start)."""
    path = with_text(tmp_path, STRIBECK, "velocity = 0.8 ", "velocity = 0.4 ")
    table = lumped.cycles(load_system(path))
    assert table.summary == "steady sliding at x = 2.15326 m (not stable); 1 cycle (1 stable)"


# -- 6. bounded work, reported -------------------------------------------------------------------------------------


def test_a_branch_ends_where_its_returns_are_spent_and_says_so():
    """A budget of 30 returns on the Stribeck belt's Hopf branch: no more returns are made than that (counted), the
    rows so far are kept and the notes say where the branch ended."""
    fly, made = shooting._fly, []

    def counted(*args, **kwargs):
        made.append(1)
        return fly(*args, **kwargs)

    notes: list[str] = []
    shooting._fly = counted
    try:
        rows = continue_branches(
            load_system(STRIBECK), "belt.velocity", 0.5, 0.8, 50, start_branch=False, returns=30, notes=notes
        )
    finally:
        shooting._fly = fly
    assert len(made) == 30 + 1  # the 31st raises ReturnsSpent before any work
    assert [r.kind for r in rows if r.branch == "cycle"][:1] == ["hopf"]
    assert (
        len(notes) == 1 and notes[0].startswith("a branch ends at belt.velocity = ") and "30 returns spent" in notes[0]
    )


def test_the_gaussian_belt_answers_within_its_stated_bound_with_progress(tmp_path, monkeypatch):
    """The Stribeck belt with ``decay = "gaussian"`` (its Hopf branch's slip-only cycles grow a multiplier past 900
    and the walk crawls: 180 s before): the walk along it takes at most ``HOPF_RETURNS`` returns (here set to 40,
    to keep the test short), progress is reported as it goes, and the summary says where it ended."""
    path = with_text(tmp_path, STRIBECK, 'decay = "exponential"', 'decay = "gaussian"')
    monkeypatch.setattr(api, "HOPF_RETURNS", 40)
    fly, made, calls = shooting._fly, [], []
    monkeypatch.setattr(shooting, "_fly", lambda *a, **k: made.append(1) or fly(*a, **k))
    table = lumped.cycles(load_system(path), progress=lambda done, total: calls.append((done, total)))
    assert "a branch ends at belt.velocity = " in table.summary and "its 40 returns spent" in table.summary
    assert len(made) <= 40 + 1 + 3 * shooting.MAX_NEWTON  # the walk, then Newton from each start
    assert len(calls) > 4 and calls[-1] == (3000, 3000)
    assert "stable" in table.summary and list(table.columns["branch"]).count("cycle") >= 1  # the stick-slip cycle


# -- 7. the command line and the API's arguments -------------------------------------------------------------------


def test_vary_given_twice_is_refused_in_one_line(tmp_path):
    run = run_lumped(
        "cycles",
        "--system",
        BELT,
        "--vary",
        "belt.velocity=0.1:0.2",
        "--vary",
        "fric.static=1:2",
        "--output",
        tmp_path / "c.csv",
    )
    assert run.returncode == 2
    assert run.stderr == "lumped cycles: error: --vary is given more than once: cycles continues in one parameter\n"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("ends", [("0.1", "0.2"), (0.1, "0.2"), (True, 0.2), (None, 0.2)])
def test_the_api_refuses_ends_that_are_not_numbers(ends):
    with pytest.raises(ValueError, match=r"^vary: START and STOP must be real numbers"):
        lumped.cycles(load_system(BELT), vary=("belt.velocity", *ends))


def test_a_range_one_ulp_long_writes_each_row_once():
    """0.2 to the next double but one: each end's cycle once (before, the last twice: the end's test was made in
    the scaled ``p / span``, 5e15 here, whose ulp is above LOCATE_TOL)."""
    stop = float(np.nextafter(np.nextafter(0.2, 1.0), 1.0))
    rows = cycle_rows(lumped.cycles(load_system(BELT), vary=("belt.velocity", 0.2, stop), points=2))
    assert list(rows["belt.velocity"]) == [0.2, stop]


def test_a_return_that_touches_the_section_at_rest_is_refused_in_one_line():
    """``--vary fric.viscous=0:1 --points 10`` on the Gaussian belt: at viscous 0 (a Hopf point, the equilibrium's
    real part 5e-26/s) a Newton trial from v = 9.3e-16 m/s came back to the section with v = 0 to the last bit,
    and ``P' = v0/v1 ...`` divided by it: ``the cycles run failed: ZeroDivisionError``.  A return at rest is a
    tangency of the section, where the map has no derivative: refused in one line, which Newton's halving (and the
    walk) then takes as any return it cannot use, and the command answers (121 rows, 61 s here)."""
    with pytest.raises(ValueError, match=r"^v: the motion from the section at v = 1 m/s comes back to it at rest"):
        shooting._landed(None, None, 1.0, 2.0, 0.0)


def test_a_range_beside_a_subcritical_hopf_point_reports_the_branch_that_enters_it():
    """The Stribeck belt's slip-only cycles are born at its Hopf speed 0.52983 m/s and grow to faster belts
    (unstable, never stuck).  Over ``belt.velocity = 0.55:0.8``, which leaves the Hopf point out, the branch was
    not reported: only the stick-slip cycles.  The walk now starts at the Hopf point just outside the range
    (within ``HOPF_REACH`` of its end) and reports its cycles inside it.  At 0.8 m/s, the file's own speed, the
    row is the cycle that ``cycles`` without ``vary`` finds there by Newton from its own walk: both are
    fixed points of the return map to its tolerance (1e-12 of the belt's speed in the section's speed), so their
    periods agree far inside 1e-9.  The mirrored range reports the mirrored cycle at -0.8 m/s."""
    net = load_system(STRIBECK)
    table = lumped.cycles(net, vary=("belt.velocity", 0.55, 0.8), points=11).columns
    slip = (table["branch"] == "cycle") & (table["stick_time"] == 0)
    assert slip.sum() >= 5 and not table["stable"][slip].any()
    assert np.all((table["belt.velocity"][slip] >= 0.55) & (table["belt.velocity"][slip] <= 0.8))
    alone = lumped.cycles(net).columns
    unstable = (alone["branch"] == "cycle") & ~alone["stable"]
    at_end = slip & (table["belt.velocity"] == 0.8)
    assert at_end.sum() == 1 and unstable.sum() == 1
    assert table["period"][at_end][0] == pytest.approx(alone["period"][unstable][0], rel=1e-9)
    back = lumped.cycles(net, vary=("belt.velocity", -0.8, -0.55), points=11).columns
    mirrored = (back["branch"] == "cycle") & (back["stick_time"] == 0) & (back["belt.velocity"] == -0.8)
    assert mirrored.sum() == 1 and back["period"][mirrored][0] == pytest.approx(alone["period"][unstable][0], rel=1e-9)
    assert back["max_m"][mirrored][0] == pytest.approx(-alone["min_m"][unstable][0], rel=1e-9)
    # a range that starts on the Hopf point itself (as one search locates it; another puts it some ulps on the
    # range's side, and neither search that ends there sees it) reports the branch too
    (hopf,) = hopf_points(net, "belt.velocity", 0.5, 5.0)  # one search's located value (each lands some ulps apart)
    edge = lumped.cycles(net, vary=("belt.velocity", hopf, 0.7), points=5).columns
    assert ((edge["branch"] == "cycle") & (edge["stick_time"] == 0)).sum() >= 5
