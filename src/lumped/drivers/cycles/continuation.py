"""Steady sliding and its limit cycles followed in a parameter of the system file (issue 34).

The equilibria (:func:`~lumped.drivers.cycles.equilibria.steady_sliding`) are
computed at ``points`` values over the range, with the Hopf points
(:func:`~lumped.drivers.cycles.equilibria.hopf_points`) inserted as rows of
kind ``hopf``.  The cycles are the zeros of

    F(v, p) = P(v; p) - v,

``P`` the return map to the section ``x = x*`` crossed upward
(:func:`~lumped.drivers.cycles.shooting.return_map`), ``v`` the speed there
and ``p`` the parameter, followed by pseudo-arclength in ``u = (v/v_s,
p/p_s)`` (``v_s`` the belt's largest speed over the range, ``p_s = |stop -
start|``): from a point with unit tangent ``t`` (the null vector of ``[F_v,
F_p]``, :func:`~lumped.numerics.arclength.unit_tangent`) the predictor steps
``ds`` along the branch (:func:`~lumped.numerics.arclength.predict`), and
the corrector is Newton on ``F = 0`` and ``t . (u - u_pred) = 0``, so that a
fold (where ``p`` turns back) is passed like any other point.  ``F_v = P' -
1`` is the return map's exact derivative and ``F_p``
:func:`~lumped.drivers.cycles.shooting.cycle_derivative_in`.  A step moves
``p`` by ``(stop - start)/(points - 1)`` at most and ``v`` by
:data:`SPEED_STEP` of ``v_s`` at most; it is halved where the corrector fails
and grows by half again after a success.

The branch starts from each Hopf point: a row of kind ``hopf`` (the cycle of
zero amplitude, below), then the small cycle whose section speed is
:data:`HOPF_AMPLITUDE` of the belt's (branch switching: ``p`` solved for at
that fixed amplitude, which puts the branch on the side where it exists), and
grows in amplitude from there.  Then, unless a branch from a Hopf point has
come to it, the branch of the cycle found at ``start`` from the belt's speed
(a cycle stuck as it crosses the section crosses it at exactly the belt's
speed, so that this is its fixed point), if there is one: the stick-slip
branch need not be joined to a Hopf point's within the range.  A branch ends where it leaves the range
(its last row is at the range's end), where it comes back to the Hopf
amplitude (another Hopf point), or where the step falls below :data:`MIN_STEP`
of the largest.

Between two accepted points the branch is tested for a change, located by
bisection on the arclength (each point tried corrected to :data:`CORRECTOR_TOL`)
until the bracket is shorter than :data:`LOCATE_TOL`, and inserted as a row:

* ``stick-slip-onset`` (the number of stick phases per period goes from 0 to
  more: the cycle grazes the stuck state, its smallest slip speed reaching 0)
  or ``stick-change`` (it changes otherwise): the row is the bracket's end with
  fewer stick phases (the grazing cycle at an onset).  Where the stick phases
  change the multipliers jump (a stuck phase makes ``P' = 0``): if the jump
  takes a multiplier across the unit circle, the bracket's other end is a row
  too, of kind ``fold`` (across +1: the branch turns back at the transition,
  Leine and van Campen's discontinuous fold) or ``period-doubling`` (across -1);
* ``fold``: ``dp/ds`` changes sign on a piece with the same stick phases;
* ``period-doubling``: a multiplier crosses -1 there (the sign of ``P' + 1``).

Notes
-----
The cycle of zero amplitude at a Hopf point ``p_H`` is the limit of the small
cycles: period ``2 pi/omega`` (``+-i omega`` the equilibrium's eigenvalues
there), both extremes at the equilibrium's position, no stick, its smallest
slip speed the belt's, and its multiplier ``exp(T tr J) = exp(2 T Re lambda)
= 1`` (Liouville: the planar flow's one nontrivial multiplier), so it is
labelled not stable.

A cycle stuck at the section crosses it at exactly the belt's speed ``V``,
and nearby starts stick before they return, so ``P = V`` near it: the branch
is ``v = V(p)`` there.  A corrected speed within :data:`CORRECTOR_TOL` of
``V`` is taken as ``V`` itself, so that round-off cannot put the point on the
side of ``V`` where the contact slips (on the static/kinetic belt, whose
sliding is a centre, every speed below ``V`` is a harmonic cycle: ``F = 0``
there too).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from lumped.drivers.cycles.equilibria import Equilibrium, check_autonomous, hopf_points, steady_sliding
from lumped.drivers.cycles.shooting import Cycle, cycle_derivative_in, find_cycle, return_map
from lumped.drivers.response.continuation import check_points
from lumped.model.network import Network
from lumped.model.system_parameters import system_parameters, with_values
from lumped.numerics import validate
from lumped.numerics.arclength import predict, unit_tangent
from lumped.solvers.event_driven_network import model

__all__ = ["HOPF_AMPLITUDE", "BranchPoint", "continue_branches"]

#: The corrector's tolerance on ``|F|``, in units of the speed scale ``v_s``: a hundred times the shooting's
#: 1e-12, so that the noise of the return map's integration (and of ``F_p``'s) never stalls it; the row's
#: cycle is then converged to the shooting's own tolerance by :func:`find_cycle` from the corrected speed.
CORRECTOR_TOL = 1e-10
#: Corrector iterations before a step is halved.
MAX_CORRECTOR = 8
#: The first cycle off a Hopf point: its section speed as a fraction of the belt's speed there.  Its
#: amplitude's relative error in the linearisation is of the order of its square (the Hopf normal form),
#: 1e-5, and ``F`` is still 2e-3 ``v_s`` times ``P' - 1``, far above the corrector's tolerance.
HOPF_AMPLITUDE = 2e-3
#: Largest change of the section speed in one step, in units of ``v_s``.
SPEED_STEP = 0.05
#: A located change's bracket on the arclength (scaled units): its value is known to this fraction of the range.
LOCATE_TOL = 1e-9
#: Smallest step as a fraction of the largest before the continuation gives up.
MIN_STEP = 1e-7


class BranchPoint(NamedTuple):
    """A row of :func:`continue_branches`: the parameter's ``value``, the ``branch`` (``"equilibrium"`` or
    ``"cycle"``), its :class:`Equilibrium` or :class:`Cycle` (the other ``None``) and its ``kind``
    (``regular``, ``hopf``, ``fold``, ``stick-slip-onset``, ``stick-change`` or ``period-doubling``)."""

    value: float
    branch: str
    equilibrium: Equilibrium | None
    cycle: Cycle | None
    kind: str


class _Point(NamedTuple):
    u: np.ndarray  # (v/v_s, p/p_s)
    jacobian: np.ndarray  # [[F_v, F_p]] in the scaled unknowns, 1 x 2
    cycle: Cycle
    value: float  # p


class _Family:
    """The members of the family, the scales and the residual ``F`` with its Jacobian."""

    def __init__(self, network: Network, parameter: str, start: float, stop: float) -> None:
        (self.parameter,) = system_parameters(network, [parameter], "vary")
        self.network, self.name = network, parameter
        self.p_s = abs(stop - start)
        self.v_s = max(abs(self.belt(start)), abs(self.belt(stop)))

    def member(self, value: float) -> Network:
        return with_values(self.network, (self.parameter,), [value])

    def belt(self, value: float) -> float:
        """The speed of the contact's other point (m/s) in the member at ``value``."""
        return model(self.member(value)).V

    def point(self, v: float, value: float) -> _Point:
        """The point at section speed ``v`` of the member at ``value``, with the cycle through it."""
        net = self.member(value)
        cycle = find_cycle(net, v)
        _, slope, _ = return_map(net, cycle.section)
        d_p = cycle_derivative_in(net, cycle.section, self.name)
        jacobian = np.array([[slope - 1.0, d_p * self.p_s / self.v_s]])
        return _Point(np.array([cycle.section / self.v_s, value / self.p_s]), jacobian, cycle, value)

    def correct(self, guess: np.ndarray, normal: np.ndarray) -> _Point | None:
        """Newton on ``F = 0``, ``normal . (u - guess) = 0`` to ``|F| <= CORRECTOR_TOL v_s``, then the point's
        cycle (``None`` where it does not converge or leaves the values the system takes)."""
        u = guess.copy()
        try:
            for _ in range(MAX_CORRECTOR):
                v, value = self._snapped(u)
                net = self.member(value)
                v_next, slope, _ = return_map(net, v)
                f = (v_next - v) / self.v_s
                if not math.isfinite(f):
                    return None
                if abs(f) <= CORRECTOR_TOL:
                    return self.point(v, value)
                row = [slope - 1.0, cycle_derivative_in(net, v, self.name) * self.p_s / self.v_s]
                u = u - np.linalg.solve(np.array([row, normal]), np.array([f, normal @ (u - guess)]))
        except (ValueError, np.linalg.LinAlgError):
            return None
        return None

    def landed(self, u: np.ndarray, along: np.ndarray) -> np.ndarray:
        """The tangent of the piece of the branch that ``u`` lies near, from ``F``'s gradient at ``u``: where
        the branch has a kink (a change of the stick phases) and turns back sharply, the hyperplane normal to
        the incoming tangent does not meet the piece beyond, but the one normal to that piece's own does."""
        try:
            v, value = self._snapped(u)
            net = self.member(value)
            slope = return_map(net, v)[1]
            row = [slope - 1.0, cycle_derivative_in(net, v, self.name) * self.p_s / self.v_s]
        except ValueError:
            return along
        if not np.all(np.isfinite(row)) or not np.any(row):
            return along
        return unit_tangent(np.array([row]), along)

    def _snapped(self, u: np.ndarray) -> tuple[float, float]:
        """``(v, p)`` at ``u``, with ``v`` the belt's speed where it is within the tolerance of it (Notes)."""
        v, value = float(u[0] * self.v_s), float(u[1] * self.p_s)
        belt = self.belt(value)
        return (belt if abs(v - belt) <= CORRECTOR_TOL * self.v_s else v), value


def _signature(p: _Point, tangent: np.ndarray) -> tuple[int, float, float]:
    """``(stick phases, sign dp/ds, sign (P' + 1))`` of a point: what a change is told by."""
    slope = float(p.jacobian[0, 0]) + 1.0
    return p.cycle.stick_phases, float(np.sign(tangent[1])), float(np.sign(slope + 1.0))


def _tangent(p: _Point, along: np.ndarray) -> np.ndarray:
    return unit_tangent(p.jacobian, along)


def _locate(fam: _Family, a: _Point, b: _Point, index: int) -> tuple[_Point, _Point]:
    """The bracket ``(lo, hi)`` of the change of :func:`_signature`'s ``index`` between ``a`` and ``b``, by
    bisection on the secant (each point the branch's crossing of the hyperplane normal to it) to
    :data:`LOCATE_TOL`: ``lo`` has ``a``'s value, ``hi`` the other."""
    secant = b.u - a.u
    length = float(np.linalg.norm(secant))
    normal = secant / length
    lo, hi, near, far = 0.0, 1.0, a, b
    while (hi - lo) * length > LOCATE_TOL:
        mid = 0.5 * (lo + hi)
        p = fam.correct(a.u + mid * secant, normal)
        if p is None:
            break
        if _signature(p, _tangent(p, secant))[index] == _signature(a, _tangent(a, secant))[index]:
            lo, near = mid, p
        else:
            hi, far = mid, p
    return near, far


def _changes(fam: _Family, a: _Point, b: _Point) -> tuple[list[BranchPoint], _Point | None]:
    """The rows of the changes between ``a`` and ``b`` (module docstring), in order along the branch, and where
    ``b``'s piece begins if the stick phases change between them (``None`` if they do not)."""
    if a.cycle.stick_phases == b.cycle.stick_phases:
        return _smooth_changes(fam, a, b), None
    lo, hi = _locate(fam, a, b, 0)
    onset = min(lo.cycle.stick_phases, hi.cycle.stick_phases) == 0
    kind = "stick-slip-onset" if onset else "stick-change"
    few, many = (lo, hi) if lo.cycle.stick_phases < hi.cycle.stick_phases else (hi, lo)
    rows = [_row(few, kind)]
    jump = _jump(lo.cycle, hi.cycle)
    if jump is not None:
        rows.append(_row(many, jump))
    if few is hi:
        rows.reverse()
    return _smooth_changes(fam, a, lo) + rows + _smooth_changes(fam, hi, b), hi


def _jump(a: Cycle, b: Cycle) -> str | None:
    """The kind of a multiplier's jump across the unit circle between ``a`` and ``b``, or ``None``."""
    for kind, shift in (("fold", -1.0), ("period-doubling", 1.0)):
        if np.sign(np.prod(a.multipliers + shift).real) != np.sign(np.prod(b.multipliers + shift).real):
            return kind
    return None


def _smooth_changes(fam: _Family, a: _Point, b: _Point) -> list[BranchPoint]:
    """A fold or a period doubling between ``a`` and ``b`` (the same stick phases), located."""
    if a is b or np.array_equal(a.u, b.u):
        return []
    secant = b.u - a.u
    sa, sb = _signature(a, _tangent(a, secant)), _signature(b, _tangent(b, secant))
    for kind, index in (("fold", 1), ("period-doubling", 2)):
        if sa[index] != sb[index]:
            return [_row(_locate(fam, a, b, index)[1], kind)]
    return []


def _row(p: _Point, kind: str) -> BranchPoint:
    return BranchPoint(p.value, "cycle", None, p.cycle, kind)


def _equilibria(fam: _Family, start: float, stop: float, points: int, hopf: list[float]) -> list[BranchPoint]:
    """The equilibrium at ``points`` values from ``start`` to ``stop``, and at each Hopf point (kind ``hopf``)."""
    values = [(float(p), "regular") for p in np.linspace(start, stop, points)] + [(h, "hopf") for h in hopf]
    values.sort(key=lambda item: (item[0] - start) / (stop - start))
    return [BranchPoint(p, "equilibrium", steady_sliding(fam.member(p)), None, kind) for p, kind in values]


def _hopf_cycle(eq: Equilibrium, belt: float) -> Cycle:
    """The cycle of zero amplitude at a Hopf point (module Notes)."""
    omega = float(np.max(np.abs(eq.eigenvalues.imag)))
    period = 2 * math.pi / omega
    multiplier = float(np.exp(period * np.sum(eq.eigenvalues.real)))
    x = np.asarray(eq.position, dtype=float)
    return Cycle(period, 0.0, x, x, 0.0, 0, abs(belt), np.array([multiplier]), abs(multiplier), False)


class _Walk(NamedTuple):
    """What ends a branch: the range in scaled ``p``, the largest steps, and the smallest section speed."""

    lo: float
    hi: float
    ends: tuple[float, float]  # the range's ends in the parameter's unit, lo's then hi's
    dp: float
    dv: float
    floor: float  # scaled v: a branch from a Hopf point ends when it comes back below it

    def largest(self, tangent: np.ndarray) -> float:
        return min(self.dp / max(abs(tangent[1]), 1e-12), self.dv / max(abs(tangent[0]), 1e-12))


def _follow(
    fam: _Family, first: _Point, tangent: np.ndarray, walk: _Walk, steps: int, progress: Callable[[float], None]
) -> list[BranchPoint]:
    """The rows of the branch from ``first`` along ``tangent`` until it ends (module docstring)."""
    rows: list[BranchPoint] = []
    p, back, ds = first, None, walk.largest(tangent)
    for _ in range(steps):
        guess = predict(p.u, tangent, ds, back)
        q = fam.correct(guess, tangent) or fam.correct(guess, fam.landed(guess, tangent))
        if q is None or abs(q.u[1] - p.u[1]) > 1.5 * walk.dp or abs(q.u[0] - p.u[0]) > 1.5 * walk.dv:
            ds *= 0.5
            if ds < MIN_STEP * walk.largest(tangent):
                break
            continue
        outside = q.u[1] < walk.lo or q.u[1] > walk.hi
        if outside:
            q = _at_edge(fam, p, q, walk) or q
        found, piece = _changes(fam, p, q)
        rows += [*found, _row(q, "regular")]
        back = (p.u, tangent) if piece is None else None  # no Hermite cubic through a kink
        # across a kink the branch may turn back: the tangent is oriented from where q's piece begins
        begins = p if piece is None or np.array_equal(piece.u, q.u) else piece
        tangent = _tangent(q, q.u - begins.u)
        progress(q.value)
        p, ds = q, min(1.5 * ds, walk.largest(tangent))
        if outside or q.u[0] < walk.floor:
            break
    return rows


def _at_edge(fam: _Family, p: _Point, q: _Point, walk: _Walk) -> _Point | None:
    """The point of the branch at the end of the range that the step ``p -> q`` passed (``None`` if the
    corrector fails there: ``q`` then ends the branch)."""
    edge, value = (walk.hi, walk.ends[1]) if q.u[1] > walk.hi else (walk.lo, walk.ends[0])
    guess = p.u + (q.u - p.u) * (edge - p.u[1]) / (q.u[1] - p.u[1])
    guess[1] = edge
    at = fam.correct(guess, np.array([0.0, 1.0]))
    return None if at is None else fam.point(at.cycle.section, value)  # at the end's value exactly


def _from_hopf(fam: _Family, hopf: float, walk: _Walk, steps: int, progress: Callable[[float], None]) -> list[BranchPoint]:
    """The branch from the Hopf point at ``hopf``: its cycle of zero amplitude, the small cycle at
    :data:`HOPF_AMPLITUDE` of the belt's speed (``p`` solved for), and on along growing amplitude."""
    net = fam.member(hopf)
    belt = model(net).V
    rows = [BranchPoint(hopf, "cycle", None, _hopf_cycle(steady_sliding(net), belt), "hopf")]
    guess = np.array([HOPF_AMPLITUDE * abs(belt) / fam.v_s, hopf / fam.p_s])
    first = fam.correct(guess, np.array([1.0, 0.0]))
    if first is None:
        raise ValueError(f"vary: no small cycle found off the Hopf point at {fam.name} = {hopf:.12g}")
    rows.append(_row(first, "regular"))
    tangent = _tangent(first, np.array([1.0, 0.0]))
    return rows + _follow(fam, first, tangent, walk, steps, progress)


def _from_start(
    fam: _Family, start: float, walk: _Walk, steps: int, progress: Callable[[float], None], found: list[BranchPoint]
) -> list[BranchPoint]:
    """The branch through the cycle found at ``start`` from the belt's speed, towards ``stop``: none if Newton
    finds no cycle there, or if a branch ``found`` from a Hopf point has come to it."""
    try:
        first = fam.point(fam.belt(start), start)
    except ValueError:
        return []
    tol = CORRECTOR_TOL * fam.v_s
    if any(r.cycle is not None and r.value == start and abs(r.cycle.section - first.cycle.section) <= tol for r in found):
        return []
    toward = np.array([0.0, 1.0 if walk.hi > first.u[1] else -1.0])
    return [_row(first, "regular"), *_follow(fam, first, _tangent(first, toward), walk, steps, progress)]


def continue_branches(
    network: Network,
    parameter: str,
    start: float,
    stop: float,
    points: int = 50,
    progress: Callable[[int, int], None] | None = None,
) -> list[BranchPoint]:
    """Steady sliding and its limit cycles from ``parameter = start`` to ``stop`` (the module docstring).

    Parameters
    ----------
    network : Network
        One mass on a friction contact on a driven point (:func:`check_autonomous`).
    parameter : str
        A numeric parameter of the system file, ``entry.key`` (``belt.velocity``).
    start, stop : float
        The range, in the parameter's unit; ``start != stop``.
    points : int
        The equilibria's rows (``>= 2``), and the cycles' steps: ``p`` moves by ``(stop - start)/(points - 1)``
        at most in one.
    progress : callable, optional
        ``progress(done, 1000)``: how far the branches have come through the range.

    Returns
    -------
    list of BranchPoint
        The equilibria in order from ``start`` to ``stop`` (Hopf points inserted), then each cycle branch in
        order along it, its changes inserted.

    Raises
    ------
    ValueError
        One line: a system :func:`check_autonomous` refuses, an unknown parameter, a bad range or ``points``,
        a value of the range the system refuses.
    """
    check_autonomous(network)
    points = check_points(points)
    start, stop = validate.finite("start", start), validate.finite("stop", stop)
    if start == stop:
        raise ValueError(f"vary: the range {parameter}={start!r}:{stop!r} is empty; give two different values")
    fam = _Family(network, parameter, start, stop)
    report = _reporter(progress, start, stop)
    hopf = hopf_points(network, parameter, start, stop)
    rows = _equilibria(fam, start, stop, points, hopf)
    lo, hi = sorted((start / fam.p_s, stop / fam.p_s))
    slowest = min(abs(fam.belt(start)), abs(fam.belt(stop)))
    walk = _Walk(lo, hi, (min(start, stop), max(start, stop)), 1.0 / (points - 1), SPEED_STEP, 0.5 * HOPF_AMPLITUDE * slowest / fam.v_s)
    for h in hopf:
        rows += _from_hopf(fam, h, walk, 50 * points, report)
    rows += _from_start(fam, start, walk, 50 * points, report, rows)
    if progress is not None:
        progress(1000, 1000)
    return rows


def _reporter(progress: Callable[[int, int], None] | None, start: float, stop: float) -> Callable[[float], None]:
    """``progress`` called with how far ``value`` has come from ``start`` towards ``stop``, in thousandths."""
    if progress is None:
        return lambda value: None
    return lambda value: progress(int(1000 * min(max((value - start) / (stop - start), 0.0), 1.0)), 1000)
