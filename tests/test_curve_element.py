"""The ``curve`` element (issue 33, part B): a relation between rate and tension invertible neither way.

The S-shaped curve :data:`S_POINTS` has three branches: 1, ``T = u`` for
``u <= 2``; 2, ``T = 4 - u`` for ``1 <= u <= 2`` (falling); 3, ``T = u + 2``
for ``u >= 1``.  A mass ``m`` with no spring, pulled by a constant force ``F``
between 2 and 3, relaxation-oscillates: on branch 1, ``m u' = F - u`` carries
it up to the fold at ``u = 2``, where the tension jumps at constant rate to
branch 3 (``T = 4``); there ``m u' = F - 2 - u`` carries it down to the fold
at ``u = 1``, where it jumps back to branch 1 (``T = 1``).  On each linear
piece ``T = a + b u`` the motion is ``u - u_eq = (u0 - u_eq) exp(-b t/m)``
with ``u_eq = (F - a)/b``, so from fold to fold the time is ``m ln r``: ``r =
F/(F - 2) = 5`` from rest to the first fold (F = 2.5), then ``r = (F - 1)/(F
- 2) = 3`` on branch 1 and ``(4 - F)/(3 - F) = 3`` on branch 3.

Backward Euler's step on a piece is ``u_{n+1} - u_eq = (u_n - u_eq)/(1 + b
h)`` (``h = dt/m``), so its own motion has a closed form too,
``(1 + b h)^-n``; the step that would carry the rate past a fold ends held at
the fold (the branch's wall) and the element is on the branch beyond from
the next step (the delay convention, the jump recorded at that step's end).
So the steps of the jumps are known exactly: from a fold, or from rest, the
first ``n`` with ``(1 + h)^n > r``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import EPS, ROOT

import lumped as L
from lumped.cli import main
from lumped.laws import Piece
from lumped.solvers.network_step import solve_step

S_POINTS = [[0, 0], [2, 2], [1, 3], [3, 5]]


def pulled(points, force: float, v0: float = 0.0, branch: int | None = None, mass: float = 1.0) -> L.Network:
    """One mass (no spring) on a curve to the ground, pulled by a constant force."""
    curve = L.Curve("c", ("ground", "m"), points=points, branch=branch)
    return L.Network([L.Mass("m", mass, 0.0, v0)], [curve], [L.Load("m", L.Constant(force))])


def first_beyond(ratio: float, h: float) -> int:
    """The first ``n`` with ``(1 + h)^n > ratio``, refusing a case within 1e-6 of a tie (where rounding
    could move the step by one)."""
    steps = math.log(ratio) / math.log1p(h)
    assert abs(steps - round(steps)) > 1e-6
    return math.floor(steps) + 1


# -- the branches ---------------------------------------------------------------------


def test_branches_of_an_s_curve() -> None:
    """Three branches, the folds at u = 2 and u = 1, each fold's branch beyond, the falling middle one."""
    c = L.Curve("c", ("ground", "m"), points=S_POINTS)
    got = [(b.number, b.lo, b.hi, b.below, b.above, b.fall) for b in c.branches]
    assert got == [(1, -math.inf, 2.0, 0, 3, 0.0), (2, 1.0, 2.0, 1, 3, 1.0), (3, 1.0, math.inf, 1, 0, 0.0)]
    assert c.steepest_fall == 1.0
    assert c.force_interval(0.0, 1.5) == (1.5, 3.5)  # branches 1, 2 and 3 hold 1.5, 2.5 and 3.5
    assert c.bingham_form() is None and c.one_mass_law() is None and c.kernel_form() is None


def test_fold_stretch_goes_to_the_branch_it_rises_on() -> None:
    """A vertical stretch at a fold is a set-valued stretch of the branch whose tension rises with the rate
    there: at the upper fold of branch 1 (u = 1, T from 1 to 2), at the lower fold of branch 3 (u = 0)."""
    c = L.Curve("c", ("ground", "m"), points=[[0, 1], [1, 1], [1, 2], [0, 3], [0, 4], [2, 5]])
    one, two, three = c.branches
    assert one.pieces[-1] == Piece(True, 1.0, 0.0, 1.0, math.inf) and one.leave_above == 2.0  # holds T in [1, 2]
    assert three.pieces[0] == Piece(True, 0.0, 0.0, -math.inf, 4.0) and three.leave_below == 3.0
    assert (two.lo, two.hi, two.fall, one.above, three.below, two.below, two.above) == (0.0, 1.0, 1.0, 3, 1, 1, 3)


def test_branch_beyond_a_fold_on_a_curve_of_four_folds() -> None:
    """A tension rising along the curve (``u = phi(T)``, rates -inf to 2, back to 1, on to 5, back to 0.5, on to
    inf): past a fold the jump lands on the first branch that holds the rates beyond, walking towards the end
    of the jump's sign, where a stiff spring in series would take the tension (up past an upper fold, down past
    a lower one).  From the middle branch 2's lower fold (u = 1) that is branch 1, not branch 4 beyond its
    partner 3, which holds those rates at a higher tension."""
    c = L.Curve("c", ("ground", "m"), points=[[0, 0], [2, 2], [1, 3], [5, 7], [0.5, 8], [3, 10]])
    assert [(b.lo, b.hi) for b in c.branches] == [(-math.inf, 2), (1, 2), (1, 5), (0.5, 5), (0.5, math.inf)]
    assert [(b.below, b.above) for b in c.branches] == [(0, 3), (1, 3), (1, 5), (1, 5), (1, 0)]
    z = L.Curve("c", ("ground", "m"), points=[[1, 2], [-1, 2], [0, 0], [-2, 0]])  # a Z written from u = +inf
    assert [(b.lo, b.hi, b.below, b.above) for b in z.branches] == [
        (-1, math.inf, 3, 0),
        (-1, 0, 3, 1),
        (-math.inf, 0, 0, 1),
    ]


BAD_POINTS = [
    ([[0, 0]], "points: a curve needs at least 2 points, got 1"),
    ([[0, 0], [1]], "points: point 2 must be a pair [u, T] (m/s, N), got [1]"),
    ([[0, 0], [1, math.nan]], "points: point 2's tension T must be a real number, got nan"),
    ([[0, 0], [math.inf, 1]], "points: point 2's rate u must be finite, got inf"),
    ([[0, 0], [0, 0], [1, 1]], "points 1 and 2 are the same point (0, 0): a segment of zero length"),
    ([[0, 0], [0, 1], [1, 2]], "points: the first segment, (0, 0) to (0, 1), is vertical"),
    ([[0, 0], [1, 1], [1, 2]], "points: the last segment, (1, 1) to (1, 2), is vertical"),
    ([[0, 0], [1, 1], [0, 2]], "points: the curve's ends both run towards u = -inf"),
    ([[0, 0], [1, 1], [1, 0], [2, 1]], "points 2 and 3: the vertical segment (1, 1) to (1, 0) lets the tension fall"),
    ([[0, 0], [1, 1], [1, 3], [1, 2], [2, 3]], "points 2 to 4: a vertical stretch folds back on itself at u = 1"),
    ([[0, 0], [1e-300, 1e300], [1, 1e300]], "points 1 and 2: the line through (0, 0) and (1e-300, 1e+300)"),
    ("ab", "points must be a list of [u, T] pairs (m/s, N), got 'ab'"),
    ([[k, k] for k in range(10_001)], "points: 10001 points, more than the 10000 a curve may have"),
]


@pytest.mark.parametrize(("points", "message"), BAD_POINTS)
def test_bad_points_refused_in_one_line(points, message: str) -> None:
    with pytest.raises(ValueError) as err:
        L.Curve("c", ("ground", "m"), points=points)
    assert str(err.value).startswith(message) and "\n" not in str(err.value)


def test_bad_curve_in_a_system_file_names_the_entry(tmp_path) -> None:
    """From a file: the entry and its key, and the branch that does not hold the initial rate."""
    text = '[[mass]]\nname = "m"\nmass = 1.0\n[[element]]\nname = "c"\nkind = "curve"\nbetween = ["ground", "m"]\n'
    with pytest.raises(ValueError, match=r"^s.toml: \[\[element\]\] 1 \('c'\): points: a curve needs at least 2"):
        L.parse_system(text + "points = [[0, 1]]\n", "s.toml")
    with pytest.raises(
        ValueError, match=r"^s.toml: element 'c': branch 3 holds the rates 1 to inf m/s, not the initial"
    ):
        L.parse_system(text + "points = [[0, 0], [2, 2], [1, 3], [3, 5]]\nbranch = 3\n", "s.toml")
    with pytest.raises(ValueError, match=r"branch must be 1 to 3, the curve's branches; got 4$"):
        L.parse_system(text + "points = [[0, 0], [2, 2], [1, 3], [3, 5]]\nbranch = 4\n", "s.toml")


# -- the motion on a linear piece -------------------------------------------------------


@pytest.mark.parametrize(
    ("branch", "v0", "a", "b"),
    [(1, 0.0, 0.0, 1.0), (2, 1.6, 4.0, -1.0)],  # branch 1 rises (T = u), branch 2 falls (T = 4 - u)
    ids=["rising", "falling"],
)
def test_motion_on_a_piece_is_its_closed_form(branch: int, v0: float, a: float, b: float) -> None:
    """Up to t = 1.5 s (before either reaches its fold at t = ln 5): backward Euler's own closed form to
    rounding, and the exact motion at order 1 with the leading term of the error.

    Rounding: each step forms ``(m u_n/dt + F - a)/(m/dt + b)``, a few (< 8) roundings of ``|u| + h (|F| +
    |a|)``, and carries the earlier ones by ``1/(1 + b h)`` (< 1 rising, ``1/(1 - h)`` per step falling):
    at most ``n 8 eps max(|u| + |F| + |a|) (1 + |b| h)^n``.  Order: ``(1 + b h)^-n = exp(-b t/m) exp(t b^2
    h/(2 m) + O(h^2))``, so the error is ``(u(t) - u_eq) t b^2 dt/(2 m^2)`` to a relative ``O(|b| h + t b^2
    h)``, below 1 % at ``dt = 1e-3``.
    """
    m, force, dt, t_end = 1.0, 2.5, 1e-3, 1.5
    tr = L.simulate_network(pulled(S_POINTS, force, v0, branch), t_end, dt)
    u, n = tr.velocities[:, 0], np.arange(tr.t.size)
    assert not tr.jumps and np.all(tr.states[:, 0] == branch)
    u_eq, h = (force - a) / b, dt / m
    discrete = u_eq + (v0 - u_eq) * (1.0 + b * h) ** -n.astype(float)
    bound = n[-1] * 8 * EPS * (np.max(np.abs(u)) + abs(force) + abs(a)) * (1 + abs(b) * h) ** n[-1]
    assert np.max(np.abs(u - discrete)) <= bound
    exact = u_eq + (v0 - u_eq) * np.exp(-b * tr.t / m)
    leading = (exact[-1] - u_eq) * t_end * b**2 * dt / (2 * m**2)
    assert (u[-1] - exact[-1]) / leading == pytest.approx(1.0, abs=0.01)
    assert np.all(tr.forces[1:, 0] == pytest.approx(a + b * u[1:], abs=8 * EPS * 4))  # on the piece


@pytest.mark.parametrize("sigma", [1e-3, 0.25, 1.0, 4.0, 1e3])
def test_step_on_a_falling_branch_whatever_the_mode_scale(sigma: float) -> None:
    """The one-step problem on branch 2 (``T = 4 - u``, walls at u = 1 and 2): the mass's ``1000 (v - 1.6) = -f
    + 2.5`` (``m/dt = 1000``, from ``u = 1.6``, F = 2.5) is solved on the falling piece, ``v = (1600 + 2.5 - 4)/999``,
    whatever the scale of the mode test; choosing the piece by ``z = f + sigma w`` would take a wall for
    ``sigma`` below the fall (``z`` is then not ordered along the branch)."""
    graph = L.Curve("c", ("ground", "m"), points=S_POINTS).step_graph(2.0, 1e-3)
    sol = solve_step([1], [0], np.array([1000.0]), np.array([1600.0 + 2.5]), [graph], np.array([sigma]))
    assert sol.v[0] == pytest.approx((1600.0 + 2.5 - 4.0) / 999.0, rel=4 * EPS) and not sol.rigid[0]
    assert sol.f[0] == pytest.approx(4.0 - sol.v[0], rel=4 * EPS)


@pytest.mark.parametrize("dt", [1e-2, 1e-3])
def test_falling_branch_reaches_its_fold(dt: float) -> None:
    """From ``u = 1.6`` on branch 2 (F = 2.5, ``u_eq = 1.5``) the rate grows as ``0.1 exp(t/m)`` and reaches the
    fold at ``u = 2`` after ``m ln 5``; backward Euler's ``0.1 (1 - h)^-n`` passes 0.5 at the first ``n`` with
    ``(1 - h)^-n > 5``, and the tension jumps to branch 3 there.  ``h/(-ln(1 - h)) - 1`` lies in ``(-h/2 - h^2,
    -h/2)`` (``1/(1 + h/2 + h^2/3 + ...)``), so the jump's error is in ``(m ln 5 (-h/2 - h^2), -m ln 5 h/2 +
    dt]``: order 1."""
    m = 1.0
    tr = L.simulate_network(pulled(S_POINTS, 2.5, 1.6, 2), 2.0, dt)
    h = dt / m
    steps = math.log(5.0) / -math.log1p(-h)
    assert abs(steps - round(steps)) > 1e-6
    assert [(j.before, j.after, round(j.time / dt)) for j in tr.jumps][0] == (2, 3, math.floor(steps) + 1)
    error = tr.jumps[0].time - m * math.log(5.0)
    assert m * math.log(5.0) * (-h / 2 - h * h) < error <= -m * math.log(5.0) * h / 2 + dt


def test_falling_branch_dt_bound_both_sides() -> None:
    """The falling branch (slope -1) needs ``m/dt > 1``: ``dt = 1`` (m = 1) is refused naming the largest
    admissible step, 0.999 runs."""
    net = pulled(S_POINTS, 2.5, 1.6, 2)
    with pytest.raises(ValueError, match=r"^dt: 1 s is too long .* the tension of 'c' falls .* 1 N s/m.*dt <= 0\.999"):
        L.simulate_network(net, 2.0, 1.0)
    assert L.simulate_network(net, 2.0, 0.999).jumps  # it reaches its fold


# -- the jumps ----------------------------------------------------------------------------


@pytest.mark.parametrize("dt", [1e-2, 2e-3, 5e-4])
def test_relaxation_oscillation_jump_times(dt: float) -> None:
    """The jumps 1 -> 3 -> 1 -> 3, at the steps of backward Euler's closed form exactly, and at the exact
    times ``m (ln 5 + (k - 1) ln 3)`` to order 1.

    Each stretch of ratio ``r`` takes ``j = floor(L) + 1`` steps, ``L = ln r/ln(1 + h)``, so ``j dt - m ln
    r`` lies in ``(m ln r (h/ln(1 + h) - 1), that + dt]``, and ``h/ln(1 + h) - 1`` in ``(h/2 - h^2/12,
    h/2)`` (the alternating series ``h/2 - h^2/12 + h^3/24 ...``): the k-th jump's error is the sum over its
    stretches, between ``dt (S/2)(1 - h/6)`` and ``dt (S/2 + k)`` with ``S`` the sum of their ``ln r``.
    """
    m, force = 1.0, 2.5
    tr = L.simulate_network(pulled(S_POINTS, force), 4.0, dt)
    h = dt / m
    first, then = first_beyond(5.0, h), first_beyond(3.0, h)
    steps = [first, first + then, first + 2 * then]
    assert [(j.element, j.before, j.after) for j in tr.jumps] == [("c", 1, 3), ("c", 3, 1), ("c", 1, 3)]
    assert [round(j.time / dt) for j in tr.jumps] == steps
    assert [j.time for j in tr.jumps] == [tr.t[k] for k in steps]  # recorded at the end of the step
    logs = np.cumsum([math.log(5.0), math.log(3.0), math.log(3.0)])
    error = np.array([j.time for j in tr.jumps]) - m * logs
    k = np.arange(1, 4)
    assert np.all(error > dt * logs / 2 * (1 - h / 6)) and np.all(error <= dt * (logs / 2 + k))
    # the step of a jump holds the rate at the fold, its tension on the vertical line between the branches
    assert tr.velocities[steps[0], 0] == 2.0 and 2.0 < tr.forces[steps[0], 0] <= 4.0
    assert tr.velocities[steps[1], 0] == 1.0 and 1.0 <= tr.forces[steps[1], 0] < 3.0
    assert tr.states[steps[0], 0] == 3.0 and tr.states[steps[0] - 1, 0] == 1.0


def test_curve_between_two_masses_jumps_as_their_relative_motion() -> None:
    """The curve between two masses of 1 kg pulled apart by 2.5 N each: their rate ``w = v2 - v1`` moves as one
    mass of ``m = 1/2`` pulled by 2.5 N (``w' = 2 (2.5 - T)``), so the jumps come at the closed form's steps
    with ``h = dt/m = 2 dt``; the centre of mass stays at rest."""
    dt = 1e-3
    curve = L.Curve("c", ("a", "b"), points=S_POINTS)
    loads = [L.Load("a", L.Constant(-2.5)), L.Load("b", L.Constant(2.5))]
    tr = L.simulate_network(L.Network([L.Mass("a", 1.0), L.Mass("b", 1.0)], [curve], loads), 2.4, dt)
    first, then = first_beyond(5.0, 2 * dt), first_beyond(3.0, 2 * dt)
    steps = [first, first + then, first + 2 * then]
    assert [(j.before, j.after, round(j.time / dt)) for j in tr.jumps] == list(zip([1, 3, 1], [3, 1, 3], steps))
    assert np.max(np.abs(tr.velocities.sum(axis=1))) <= tr.t.size * 4 * EPS * np.max(np.abs(tr.velocities))


def test_jump_to_a_lower_tension() -> None:
    """A Z-shaped curve (branch 1 ``T = 2`` up to ``u = 1``, branch 3 ``T = 0`` from ``u = 0``): a mass pulled
    by 3.3 N accelerates at 1.3 m/s^2 (backward Euler is exact for a constant acceleration) up to the fold,
    where the tension drops to 0 and it accelerates at 3.3 m/s^2.  The fold is crossed at the step ``n`` with
    ``1.3 n dt > 1`` first (n = 770, t = 0.77 s; exactly 1/1.3 s)."""
    dt = 1e-3
    tr = L.simulate_network(pulled([[-1, 2], [1, 2], [0, 0], [2, 0]], 3.3), 1.0, dt)
    assert [(j.before, j.after, round(j.time / dt)) for j in tr.jumps] == [(1, 3, 770)]
    u = tr.velocities[:, 0]
    assert u[770] == 1.0 and tr.forces[770, 0] > 2.0  # held at the fold, beyond branch 1's tension
    after = 1.0 + 3.3 * dt * np.arange(1, u.size - 770)
    before = 1.3 * dt * np.arange(770)
    bound = u.size * 8 * EPS * np.max(np.abs(u))  # a sum of equal increments, a rounding each
    assert np.max(np.abs(u[:770] - before)) <= bound and np.max(np.abs(u[771:] - after)) <= bound
    assert np.all(tr.forces[771:, 0] == 0.0) and np.all(tr.forces[1:770, 0] == 2.0)


def test_jumps_on_a_belt_are_those_on_the_ground() -> None:
    """The curve between a belt at 0.7 m/s and the mass: in the belt's frame the same motion (the mass's
    velocity less the belt's, to rounding of the shift), the same jumps at the same steps."""
    dt, belt = 1e-3, 0.7
    ground = L.simulate_network(pulled(S_POINTS, 2.5), 3.0, dt)
    curve = L.Curve("c", ("belt", "m"), points=S_POINTS)
    net = L.Network([L.Mass("m", 1.0, 0.0, belt)], [curve], [L.Load("m", L.Constant(2.5))], [L.Driver("belt", belt)])
    tr = L.simulate_network(net, 3.0, dt)
    assert tr.jumps == ground.jumps
    # the shift adds and removes 0.7 once a step (a rounding each), carried without growth on branches 1, 3
    bound = tr.t.size * 4 * EPS * (belt + np.max(np.abs(tr.velocities)))
    assert np.max(np.abs(tr.velocities[:, 0] - belt - ground.velocities[:, 0])) <= bound


def test_the_s_curve_example_prints_its_jumps(tmp_path, capsys) -> None:
    """``examples/s_curve.toml`` is the relaxation oscillation above; its command's one line lists the jumps at
    the steps of backward Euler's closed form (the first three of four)."""
    net = L.load_system(ROOT / "examples" / "s_curve.toml")
    (curve,), (load,) = net.elements, net.loads
    assert curve.points == tuple((float(u), float(t)) for u, t in S_POINTS) and load.force(1.0) == 2.5
    out = tmp_path / "s_curve.csv"
    argv = ["simulate", "--system", str(ROOT / "examples" / "s_curve.toml"), "--t-end", "6", "--dt", "1e-3"]
    assert main([*argv, "--output", str(out)]) == 0
    err = capsys.readouterr().err
    first, then = first_beyond(5.0, 1e-3), first_beyond(3.0, 1e-3)
    steps = [first, first + then, first + 2 * then]
    shown = ", ".join(f"t = {k * 1e-3:.6g} s {a} -> {b}" for k, (a, b) in zip(steps, [(1, 3), (3, 1), (1, 3)]))
    assert (
        f"; 'c' jumped 4 times between branches ({shown}, ...); Python step; wrote" in err
        and len(err.splitlines()) == 1
    )
    assert shown == "t = 1.611 s 1 -> 3, t = 2.711 s 3 -> 1, t = 3.811 s 1 -> 3"  # as the example and the guide say


# -- the Bingham graph ----------------------------------------------------------------------


def bingham_oscillator_with(points) -> L.Network:
    return L.Network(
        [L.Mass("m", 1.0, 0.5)], [L.Spring("k", ("ground", "m"), 100.0), L.Curve("c", ("ground", "m"), points=points)]
    )


def test_curve_of_the_bingham_graph_is_algorithm1_bit_for_bit() -> None:
    """The curve through (-1, -1.5), (0, -1), (0, 1), (1, 1.5) is the Bingham graph (tau = 1, c = 0.5 exactly):
    it is run as the Bingham element it equals, by Algorithm 1 itself, the same arithmetic."""
    net = bingham_oscillator_with([[-1, -1.5], [0, -1], [0, 1], [1, 1.5]])
    assert net.elements[1].bingham_form() == (1.0, 0.5)
    tr = L.simulate_network(net, 3.0, 1e-3)
    ref = L.backward_euler(L.Oscillator.bingham(1.0, 100.0, 1.0, 2.0), 3.0, 1e-3, x0=0.5)
    assert tr.solver == "algorithm1"
    assert np.array_equal(tr.positions[:, 0], ref.x) and np.array_equal(tr.velocities[:, 0], ref.v)
    assert np.array_equal(tr.forces[:, 1], ref.F_d)


def test_curve_of_the_bingham_graph_in_more_points_agrees_with_algorithm1() -> None:
    """With collinear points added the curve is not recognised, and runs by its own branch (the network's
    active-set step with the curve's pieces); the same backward Euler to rounding: a step is
    non-expansive in the ``M/dt`` metric (``tests/test_network_kernel.py``), so the per-step roundings (8 eps
    of the step's velocity and force scales) add up over the steps."""
    net = bingham_oscillator_with([[-2, -2], [-1, -1.5], [0, -1], [0, 1], [1, 1.5], [2, 2]])
    assert net.elements[1].bingham_form() is None
    tr = L.simulate_network(net, 3.0, 1e-3)
    ref = L.backward_euler(L.Oscillator.bingham(1.0, 100.0, 1.0, 2.0), 3.0, 1e-3, x0=0.5)
    assert tr.solver == "python"
    bound = tr.t.size * 8 * EPS * (np.max(np.abs(ref.v)) + 100.0 * np.max(np.abs(ref.x)))
    assert np.max(np.abs(tr.velocities[:, 0] - ref.v)) <= bound
    assert np.max(np.abs(tr.positions[:, 0] - ref.x)) <= bound
    assert np.array_equal(tr.rigid[1:, 1], ref.v[1:] == 0)  # sticks at the same steps


def test_a_curve_is_refused_by_the_methods_written_for_monotone_graphs(tmp_path):
    """The period map and the exact sensitivities refuse a curve that folds (element point 13), in one line;
    the Bingham graph's points are monotone and not refused for that."""
    net = L.load_system(ROOT / "examples" / "s_curve.toml")
    assert not any(el.monotone for el in net.elements if el.kind == "curve")
    with pytest.raises(ValueError, match="its graph is not monotone"):
        net.refuse_non_monotone("the period map")
