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
1`` is the return map's exact derivative and ``F_p`` a one-sided difference
in ``p`` from the return already made (:func:`_forward_step`: one return
more per point).  A step moves
``p`` by ``(stop - start)/(points - 1)`` at most and ``v`` by
:data:`SPEED_STEP` of ``v_s`` at most; it is halved where the corrector fails
and grows by half again after a success.  ``F_p`` is a difference: within
its step of a kink of the branch (where the stick phases change) it spans both
sides, so where Newton on the hyperplane fails the corrector tries at the
predicted value of ``p`` (which needs no ``F_p``).

The branch starts from each Hopf point: a row of kind ``hopf`` (the cycle of
zero amplitude, below), then the small cycle whose section speed is
:data:`HOPF_AMPLITUDE` of the belt's (branch switching: ``p`` solved for at
that fixed amplitude, which puts the branch on the side where it exists), and
grows in amplitude from there.  Then, unless a branch from a Hopf point has
come to it, the branch of the cycle found at ``start`` from the belt's speed
(a cycle stuck as it crosses the section crosses it at exactly the belt's
speed, so that this is its fixed point), if there is one: the stick-slip
branch need not be joined to a Hopf point's within the range.  A branch ends
where it leaves the range (its last row is at the range's end), where it
comes back to half the Hopf amplitude (another Hopf point: the row of kind
``hopf`` there ends it, and no second branch is followed from that point,
which would walk the same one back), or where the step
falls below :data:`MIN_STEP` of the largest; before that, where steps fail
below :data:`KINK_STEP` of the largest, the other piece of a fold at a kink is
looked for at the same value (:meth:`_Family.across`).

Between two accepted points the branch is tested for a change and each is
inserted as a row:

* ``stick-slip-onset`` (the number of stick phases per period goes from 0 to
  more: the cycle grazes the stuck state, its smallest slip speed reaching 0)
  or ``stick-change`` (it changes otherwise).  The branch has a kink there
  and may turn back: each side's piece is followed to its end by bisection on
  the step along its own tangent (:func:`_arm_end`, to :data:`LOCATE_TOL`), and
  the row is the end with fewer stick phases (the grazing cycle at an onset).
  Where the stick phases change the multipliers jump (a stuck phase makes
  ``P' = 0``): if the jump takes a multiplier across the unit circle, the other
  end is a row too, of kind ``fold`` (across +1: the discontinuous fold of
  Leine and van Campen, where the stable stick-slip branch meets the unstable
  sliding cycles) or ``period-doubling`` (across -1);
* ``fold``: ``dp/ds`` changes sign on a piece with the same stick phases;
* ``period-doubling``: a multiplier crosses -1 there (the sign of ``P' + 1``);

these two located by bisection on the secant (each point tried the branch's
crossing of the hyperplane normal to it, corrected to :data:`CORRECTOR_TOL`)
until the bracket is shorter than :data:`LOCATE_TOL`.

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

from lumped.drivers.cycles.equilibria import (
    Equilibrium,
    belt_sign,
    check_autonomous,
    hopf_points,
    mirror_equilibrium,
    mirrored,
    steady_sliding,
)
from lumped.drivers.cycles.shooting import (
    RTOL,
    Cycle,
    ReturnsSpent,
    find_cycle,
    mirror_cycle,
    return_map,
    returns_budget,
)
from lumped.drivers.response.continuation import check_points
from lumped.model.network import Network
from lumped.model.system_parameters import SystemParameter, system_parameters, with_values
from lumped.numerics import validate
from lumped.numerics.arclength import predict, unit_tangent
from lumped.numerics.roots import brentq
from lumped.solvers.event_driven_network import model

__all__ = ["HOPF_AMPLITUDE", "RETURNS_PER_POINT", "BranchPoint", "continue_branches"]

#: The corrector's tolerance on ``|F|``, in units of the speed scale ``v_s``: a hundred times the shooting's
#: 1e-12, so that the noise of the return map's integration (and of ``F_p``'s) never stalls it; the row's
#: cycle is then converged to the shooting's own tolerance by :func:`find_cycle` from the corrected speed.
CORRECTOR_TOL = 1e-10
#: :func:`find_cycle`'s tolerance on ``|P(v) - v|`` relative to ``max(|V|, v)`` (its default, passed explicitly).
CYCLE_TOL = 1e-12
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
#: A step this fraction of the largest that fails: look for another piece of the branch at the same value
#: (:meth:`_Family.across`).
KINK_STEP = 1e-4
#: How far back from a failing step's point (scaled units) another piece of the branch is searched for.
ACROSS_GAP = 1e-5
#: The cosine of the largest angle between a point's tangent and the secant to it for the tangent to be used.
TRUSTED = 0.9
#: The returns (:func:`~lumped.drivers.cycles.shooting.returns_budget`) one branch may take, per row asked
#: (``points``), at least :data:`MIN_RETURNS`: a branch that has not ended by then ends there, and the rows
#: say where (:func:`continue_branches`' ``notes``).  Only the walk's returns count: a step costs 3 to 5 (the
#: corrector, the cycle's Newton, ``F_p``), and one halved where the corrector fails costs them again; locating a
#: change (:func:`_changes`) is bounded by its own construction (bisections to :data:`LOCATE_TOL`, some 30 of a
#: few returns each, some 500 for a kink's two pieces) and is not counted.  The Veraszto-Stepan branch of notebook
#: 16 walks 1206 returns for 30 points, 40 a point; the stick-slip branch of tests/test_cycles_continuation.py
#: through its discontinuous fold 1054 for 3 (the steps halved at the kink and the search across it): the budget
#: is some three times each.  A branch whose steps shrink without end (the Gaussian
#: Stribeck belt's slip-only cycles, their multiplier passing 900 as the orbits beside them start to stick) is so
#: bounded in time: a return is a period or so of DOP853 at RTOL, some 0.05 s.
RETURNS_PER_POINT, MIN_RETURNS = 100, 3000
#: The corrector's hyperplane at a fixed parameter.
_FIXED_P = np.array([0.0, 1.0])


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


def _forward_step(value: float, span: float) -> float:
    """The step ``h`` of the one-sided difference ``dP/dp ~ (P(v; p + h) - P(v; p)) / h`` at ``p = value`` on a
    range ``span`` long (the parameter's unit).

    Notes
    -----
    With ``S = max(|V|, v)`` the scale of ``P``, each return errs by ``rho S``, ``rho = 100 RTOL`` (DOP853's
    local errors, not their sum: :func:`~lumped.drivers.cycles.shooting.cycle_derivative_in`), and ``P(v; p)``
    is either a return of its own or the cycle's ``v`` itself, within :data:`CYCLE_TOL` ``S`` of ``P(v)``
    (:func:`find_cycle`'s stop): the numerator's noise is at most ``(2 rho + CYCLE_TOL) S``.  The truncation is
    ``h |P_pp| / 2``, ``|P_pp| ~ S / L^2`` with ``L = min(|p|, span)``: ``P`` varying on the scale of ``p``
    itself or of the range the branch is followed over, whichever is shorter (the bubble of
    ``benchmarks/bench_cycles.py``, 0.008 m/s wide at 0.07 m/s, has ``|P_pp| = 70 s/m``, ``S / span^2``).  The
    sum is least at ``h = sqrt(2 (2 rho + CYCLE_TOL)) L`` (6.5e-6 ``L``), where the error is that times ``S /
    L``: ``F_p`` to some 1e-5 of its scale.  That moves only the tangent (the predictor) and the rate of Newton
    on the hyperplane (linear, at that relative error), never where a point converges (``F = 0`` to
    :data:`CORRECTOR_TOL`), nor the sign of ``dp/ds`` that tells a fold (``F_v``, exact).
    """
    scale = min(abs(value), span) if value != 0 else span
    return math.sqrt(2 * (2 * 100 * RTOL + CYCLE_TOL)) * scale


class _Family:
    """The members of the family, the scales and the residual ``F`` with its Jacobian."""

    def __init__(self, network: Network, parameter: str, start: float, stop: float, budget: int = MIN_RETURNS) -> None:
        (self.parameter,) = system_parameters(network, [parameter], "vary")
        self.network, self.name, self.budget = network, parameter, budget
        self.notes: list[str] = []  # what ended a branch early, in words
        # the belt's sign over the range (a driver's range never reaches 0: parameter_member); V < 0 is computed
        # as its mirror (equilibria.mirrored), whose belt runs forwards, and the rows are mirrored back
        self.sign = belt_sign(with_values(network, (self.parameter,), [start]))
        self.belt_rate = self.sign * _drives_contact(network, self.parameter)  # dV/dp of the members: V is affine
        self.p_s = abs(stop - start)
        self.v_s = max(abs(self.belt(start)), abs(self.belt(stop)))

    def member(self, value: float) -> Network:
        """The system at ``value`` of the parameter, mirrored where its belt runs backwards."""
        net = with_values(self.network, (self.parameter,), [value])
        return mirrored(net) if self.sign < 0 else net

    def belt(self, value: float) -> float:
        """The speed of the contact's other point (m/s) in the member at ``value``."""
        return model(self.member(value)).V

    def point(self, v: float, value: float, tangent: bool = True) -> _Point:
        """The point at section speed ``v`` of the member at ``value``, with the cycle through it (and ``F_p``
        unless ``tangent`` is false: then 0, for a point whose tangent is not wanted)."""
        net = self.member(value)
        cycle = find_cycle(net, v, tol=CYCLE_TOL)
        d_p = (
            self.derivative(net, cycle.section, value, cycle.section, float(cycle.multipliers[0].real))
            if tangent
            else 0.0
        )
        slope = float(cycle.multipliers[0].real)  # the one nontrivial multiplier: P' at the cycle
        jacobian = np.array([[slope - 1.0, d_p * self.p_s / self.v_s]])
        return _Point(np.array([cycle.section / self.v_s, value / self.p_s]), jacobian, cycle, value)

    def correct(self, guess: np.ndarray, normal: np.ndarray, tangent: bool = True) -> _Point | None:
        """The point of the branch at ``guess``'s value of the parameter, else on the hyperplane through ``guess``
        normal to ``normal`` (``None`` if neither converges).

        The first needs no ``F_p``, which is a difference (:func:`_forward_step`): within its step
        of a kink of the branch (a change of the stick phases) it spans both sides and is no derivative, and
        Newton on the hyperplane may then land on the other piece, close by; at a fixed parameter Newton is exact
        and converges to the piece nearest the guess.  The second passes a fold, where the first finds nothing
        (Newton's residual stops decreasing)."""
        return self._newton(guess, _FIXED_P, tangent) or self._newton(guess, normal, tangent)

    def _newton(
        self, guess: np.ndarray, normal: np.ndarray, tangent: bool = True, tol: float = CORRECTOR_TOL
    ) -> _Point | None:
        """Newton on ``F = 0``, ``normal . (u - guess) = 0`` to ``|F| <= tol v_s``, then the point's cycle
        (``None`` where it does not converge or leaves the values the system takes)."""
        u, fixed, last = guess.copy(), normal[0] == 0, math.inf
        if fixed and tangent and tol == CORRECTOR_TOL:  # Newton at a fixed value: find_cycle's, to its tolerance
            try:
                return self.point(*self._snapped(u), tangent)
            except ValueError:
                return None
        try:
            for _ in range(MAX_CORRECTOR):
                v, value = self._snapped(u)
                net = self.member(value)
                v_next, slope, _ = return_map(net, v)
                f = (v_next - v) / self.v_s
                if not abs(f) < last:  # not finite, or Newton does not converge here: no quadratic decrease
                    return None
                if abs(f) <= tol:
                    return self.point(v, value, tangent)
                last = abs(f)
                d_p = 0.0 if fixed else self.derivative(net, v, value, v_next, slope) * self.p_s / self.v_s
                u = u - np.linalg.solve(np.array([[slope - 1.0, d_p], normal]), np.array([f, normal @ (u - guess)]))
        except (ValueError, np.linalg.LinAlgError):
            return None
        return None

    def across(self, p: _Point) -> _Point | None:
        """A cycle at ``p``'s value on another piece of the branch near ``p`` (other stick phases), or ``None``.

        Where two pieces meet in a fold at a kink (the branch turning back where its cycle grazes the stuck
        state) no hyperplane ahead of the last point meets the branch; at ``p``'s value, a little way back from
        the kink (:data:`ACROSS_GAP`), the other piece's cycle is near ``p``'s, and ``F`` (continuous through the
        kink) changes sign between them: the speeds ``v +- 10^-k v_s`` (``k`` = 9 down to 1) are scanned for it
        and Brent's method finds it."""
        net, v0 = self.member(p.value), p.cycle.section
        f = lambda v: (return_map(net, v)[0] - v) / self.v_s
        for sign in (1.0, -1.0):
            steps = [v for v in (v0 + sign * 10.0**-k * self.v_s for k in range(9, 0, -1)) if v > 0]
            values = []
            for v in steps:
                try:
                    values.append(f(v))
                except ValueError:  # no return from there: the scan ends
                    break
            for i in np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0):
                try:
                    q = self.point(brentq(f, steps[i], steps[i + 1]), p.value)
                except ValueError:
                    continue
                if q.cycle.stick_phases != p.cycle.stick_phases:
                    return q
        return None

    def landed(self, u: np.ndarray, along: np.ndarray) -> np.ndarray:
        """The tangent of the piece of the branch that ``u`` lies near, from ``F``'s gradient at ``u``: where
        the branch has a kink (a change of the stick phases) and turns back sharply, the hyperplane normal to
        the incoming tangent does not meet the piece beyond, but the one normal to that piece's own does."""
        try:
            v, value = self._snapped(u)
            net = self.member(value)
            v_next, slope, _ = return_map(net, v)
            row = [slope - 1.0, self._difference(v, value, v_next) * self.p_s / self.v_s]  # no shortcut here
        except ValueError:
            return along
        if not np.all(np.isfinite(row)) or not np.any(row):
            return along
        return unit_tangent(np.array([row]), along)

    def derivative(self, net: Network, v: float, value: float, v_next: float, slope: float) -> float:
        """``dP/dp`` at ``v`` (m/s per unit of the parameter), ``v_next`` being ``P(v)`` at ``value`` (or ``v``
        itself at a cycle that :func:`find_cycle` converged, within its tolerance: :func:`_forward_step`): where
        the motion from ``v`` sticks before it returns and returns stuck (``P = V``, ``P' = 0``), ``P = V(p)``
        near it and ``dP/dp = dV/dp`` exactly, the belt's speed being the parameter itself or not depending on it
        (an affine function of it: its difference over a unit step); else the one-sided difference
        ``(P(v; p + h) - v_next) / h`` with :func:`_forward_step`'s ``h``: one return more, ``v_next`` being known."""
        if slope == 0 and v_next == self.belt(value):
            return self.belt_rate
        return self._difference(v, value, v_next)

    def _difference(self, v: float, value: float, v_next: float) -> float:
        """``(P(v; p + h) - v_next) / h`` at ``p = value``, ``h`` :func:`_forward_step`'s, or the backward one
        (``-h``) where the system refuses ``p + h`` (a range ending at the edge of the values it takes, such as
        ``kinetic`` just below ``static``: the range's ends are checked, not what lies beyond them)."""
        h = _forward_step(value, self.p_s)
        try:
            ahead = self.member(value + h)
        except ValueError:
            h, ahead = -h, self.member(value - h)
        return (return_map(ahead, v)[0] - v_next) / h

    def _snapped(self, u: np.ndarray) -> tuple[float, float]:
        """``(v, p)`` at ``u``, with ``v`` the belt's speed where it is within the tolerance of it (Notes)."""
        v, value = float(u[0] * self.v_s), float(u[1] * self.p_s)
        belt = self.belt(value)
        return (belt if abs(v - belt) <= CORRECTOR_TOL * self.v_s else v), value


def _drives_contact(network: Network, parameter: SystemParameter) -> float:
    """``dV/dp``: 1 if ``parameter`` is the velocity of the driven point the friction contact slides on (the belt's
    speed is that velocity), else 0 (no other parameter moves it)."""
    if parameter.table != "driver":
        return 0.0
    contact = model(network).contact.link.element
    return 1.0 if network.drivers[parameter.index].name in network.elements[contact].between else 0.0


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


def _arm_end(fam: _Family, a: _Point, b: _Point, t: np.ndarray) -> _Point:
    """The end of ``a``'s piece of the branch (its stick phases) on the way to ``b``: bisection on the distance
    ``s`` along ``a``'s tangent ``t`` (oriented towards the kink; the bracket ``|b - a|`` first doubled while the
    piece goes on) to :data:`LOCATE_TOL`.

    The point at ``s`` is the piece's crossing of the hyperplane ``t . (u - u_a) = s``, from the line through the
    last two points found on the piece (the first: ``t``), corrected at that guess's value of the parameter
    (exact ``F_v``, no ``F_p``: the difference spans the kink near it) or else on the hyperplane; it is
    on the piece if it converges with ``a``'s stick phases within ``s`` of that line.  Each piece is followed
    from its own side because the two may meet at an angle, or in a fold: a bisection along the secant from one
    to the other would cross the angle's inside, where the hyperplanes meet the two pieces far from the kink."""
    lo, hi, near, line = 0.0, float(np.linalg.norm(b.u - a.u)), a, t

    def on(step: float) -> _Point | None:
        guess = near.u + line * (step - t @ (near.u - a.u)) / (t @ line)
        p = fam._newton(guess, _FIXED_P, tangent=False) or fam._newton(guess, t, tangent=False)
        if p is None or p.cycle.stick_phases != a.cycle.stick_phases or np.linalg.norm(p.u - guess) > step:
            return None
        return p

    def found(p: _Point) -> np.ndarray:
        d = p.u - near.u
        return d / np.linalg.norm(d) if t @ d > 0 else line

    for _ in range(4):
        p = on(hi)
        if p is None:
            break
        lo, line, near, hi = hi, found(p), p, 2 * hi
    while hi - lo > LOCATE_TOL:
        mid = 0.5 * (lo + hi)
        p = on(mid)
        if p is not None:
            lo, line, near = mid, found(p), p
        else:
            hi = mid
    return near if near is a else fam.point(near.cycle.section, near.value)  # with its tangent


def _changes(fam: _Family, a: _Point, b: _Point, travel: np.ndarray) -> tuple[list[BranchPoint] | None, _Point | None]:
    """The rows of the changes between ``a`` and ``b`` (module docstring), in order along the branch, and where
    ``b``'s piece begins if the stick phases change between them (``None`` if they do not).  ``travel`` is the
    tangent along which the branch left ``a``: ``a``'s piece ends ahead along it, and ``b``'s piece ends towards
    where ``a``'s does (behind ``b`` where the branch turns back at the kink).  ``(None, None)`` if ``a``'s piece
    goes on well past ``b`` (twice as far): near a kink the pieces run close and Newton may land on the other
    one, which is not the branch going on; the step is then refused."""
    if a.cycle.stick_phases == b.cycle.stick_phases:
        return _smooth_changes(fam, a, b), None
    end_a = _arm_end(fam, a, b, travel)
    if np.linalg.norm(end_a.u - a.u) > 2 * np.linalg.norm(b.u - a.u):
        return None, None  # a's piece goes on past b: b is on another piece close by, not across a kink
    end_b = _arm_end(fam, b, end_a, _tangent(b, end_a.u - b.u))
    onset = min(a.cycle.stick_phases, b.cycle.stick_phases) == 0
    kind = "stick-slip-onset" if onset else "stick-change"
    fewer_first = a.cycle.stick_phases < b.cycle.stick_phases
    few, many = (end_a, end_b) if fewer_first else (end_b, end_a)
    jump = _jump(end_a.cycle, end_b.cycle)
    rows = [_row(few, kind)] + ([_row(many, jump)] if jump is not None else [])
    if not fewer_first:
        rows.reverse()
    return _smooth_changes(fam, a, end_a) + rows + _smooth_changes(fam, end_b, b), end_b


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
    p, back, ds, crossed, trail = first, None, walk.largest(tangent), False, [first]
    travel = tangent  # the branch's direction at p: the secant to it from the point before on its piece
    try:
        for _ in range(steps):
            guess = predict(p.u, tangent, ds, back)
            q = fam.correct(guess, tangent) or fam._newton(guess, fam.landed(guess, tangent))
            if q is None and not crossed and ds < KINK_STEP * walk.largest(tangent):
                q, crossed = fam.across(_back_from(trail, p)), True
            if q is None or abs(q.u[1] - p.u[1]) > 1.5 * walk.dp or abs(q.u[0] - p.u[0]) > 1.5 * walk.dv:
                ds *= 0.5
                if ds < MIN_STEP * walk.largest(tangent):
                    break
                continue
            crossed = False
            outside = _at_end(q.value, walk, fam.p_s)
            if outside:
                q = _at_edge(fam, p, q, walk) or q
            with returns_budget(None):  # bounded by construction: bisections to LOCATE_TOL (RETURNS_PER_POINT)
                found, piece = _changes(fam, p, q, travel)
            if found is None:
                ds *= 0.5
                continue
            rows += [*found, _row(q, "regular")]
            # across a kink the branch may turn back: the tangent is oriented from where q's piece begins; it is the
            # secant from there where F_p (a difference: no derivative within its step of a kink) turns it
            begins = p if piece is None or np.array_equal(piece.u, q.u) else piece
            secant = (q.u - begins.u) / np.linalg.norm(q.u - begins.u)
            jacobian = _tangent(q, secant)
            trusted = jacobian @ secant > TRUSTED
            back = (p.u, tangent) if piece is None and trusted else None  # no Hermite cubic through a kink
            tangent, travel = (jacobian if trusted else secant), secant
            progress(q.value)
            if piece is not None:  # a new piece, known from its end to q: the steps grow again from that length
                ds = float(np.linalg.norm(q.u - begins.u))
            p, ds = q, min(1.5 * ds, walk.largest(tangent))
            trail.append(q)
            if outside or q.u[0] < walk.floor:
                break
    except ReturnsSpent:  # the branch's budget (RETURNS_PER_POINT): it ends at its last point, which says so
        fam.notes.append(f"a branch ends at {fam.name} = {p.value:.6g}, its {fam.budget} returns spent")
    return rows


def _at_end(value: float, walk: _Walk, span: float) -> bool:
    """Whether ``value`` is at or past an end of the range, to :data:`LOCATE_TOL` of its length ``span``: then the
    branch's point is the end's own (:func:`_at_edge`), and the branch ends.  In the parameter's unit, not the
    scaled ``p / span``: on a range a few ulps long that is ``1e16`` or more, whose ulp exceeds LOCATE_TOL, and a
    step landing on the end exactly was then not at it (the end's row written twice)."""
    lo, hi = walk.ends
    return value <= lo + LOCATE_TOL * span or value >= hi - LOCATE_TOL * span


def _back_from(trail: list[_Point], p: _Point) -> _Point:
    """The last point of ``trail`` at least :data:`ACROSS_GAP` from ``p``, else the first: where the branch folds
    at a kink the other piece is searched for a little way back from it, where the two are apart (module
    docstring of :meth:`_Family.across`)."""
    for q in reversed(trail):
        if np.linalg.norm(q.u - p.u) >= ACROSS_GAP:
            return q
    return trail[0]


def _at_edge(fam: _Family, p: _Point, q: _Point, walk: _Walk) -> _Point | None:
    """The point of the branch at the end of the range that the step ``p -> q`` passed (``None`` if the
    corrector fails there: ``q`` then ends the branch)."""
    edge, value = (walk.hi, walk.ends[1]) if q.u[1] > p.u[1] else (walk.lo, walk.ends[0])
    guess = p.u + (q.u - p.u) * (edge - p.u[1]) / (q.u[1] - p.u[1])
    guess[1] = edge
    at = fam.correct(guess, _FIXED_P)
    return None if at is None else fam.point(at.cycle.section, value)  # at the end's value exactly


def _hopf_row(fam: _Family, hopf: float) -> BranchPoint:
    """The cycle row of zero amplitude at the Hopf point ``hopf`` (module Notes)."""
    return BranchPoint(hopf, "cycle", None, _hopf_cycle(steady_sliding(fam.member(hopf)), fam.belt(hopf)), "hopf")


def _from_hopf(
    fam: _Family, hopf: float, walk: _Walk, steps: int, progress: Callable[[float], None]
) -> list[BranchPoint]:
    """The branch from the Hopf point at ``hopf``: its cycle of zero amplitude, the small cycle at
    :data:`HOPF_AMPLITUDE` of the belt's speed (``p`` solved for), and on along growing amplitude; the first
    alone where no small cycle is found or the map is neutral there (``F_v = F_p = 0``: a centre, no isolated
    cycle to follow)."""
    rows = [_hopf_row(fam, hopf)]
    belt = fam.belt(hopf)
    guess = np.array([HOPF_AMPLITUDE * abs(belt) / fam.v_s, hopf / fam.p_s])
    # v fixed, p solved for; F = v (P'(0) - 1 + O(v^2)) is that small: the tolerance is relative to v
    first = fam._newton(guess, np.array([1.0, 0.0]), tol=CORRECTOR_TOL * guess[0])
    if first is None:  # said, not silent: the Hopf point's row alone
        fam.notes.append(f"no small cycle found off the Hopf point at {fam.name} = {hopf:.6g}")
        return rows
    if not np.any(first.jacobian):  # a neutral family (a centre): no isolated cycle, no branch to follow
        return rows
    rows.append(_row(first, "regular"))
    tangent = _tangent(first, np.array([1.0, 0.0]))
    return rows + _follow(fam, first, tangent, walk, steps, progress)


def _from_start(
    fam: _Family, start: float, walk: _Walk, steps: int, progress: Callable[[float], None], found: list[BranchPoint]
) -> list[BranchPoint]:
    """The branch through the cycle found at ``start`` from the belt's speed, towards ``stop``: none if Newton
    finds no cycle there (its reason in ``fam.notes``: no failure is silent), or if a branch ``found`` from a Hopf
    point has come to it."""
    try:
        first = fam.point(fam.belt(start), start)
    except ValueError as err:  # find_cycle names its own argument (v0: ...); the user gave none
        fam.notes.append(f"no cycle from the belt's speed at {fam.name} = {start:.6g}: {str(err).split(': ', 1)[-1]}")
        return []
    tol = CORRECTOR_TOL * fam.v_s
    if any(
        r.cycle is not None and r.value == start and abs(r.cycle.section - first.cycle.section) <= tol for r in found
    ):
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
    *,
    start_branch: bool = True,
    returns: int | None = None,
    notes: list[str] | None = None,
) -> list[BranchPoint]:
    """Steady sliding and its limit cycles from ``parameter = start`` to ``stop`` (the module docstring).

    Parameters
    ----------
    network : Network
        One mass on a friction contact on a driven point (:func:`check_autonomous`).
    parameter : str
        A numeric parameter of the system file, ``entry.key`` (``belt.velocity``).
    start, stop : float
        The range, in the parameter's unit: finite, ``start < stop``, values the system takes
        (:func:`hopf_points` checks them).
    points : int
        The equilibria's rows (``>= 2``), and the cycles' steps: ``p`` moves by ``(stop - start)/(points - 1)``
        at most in one.
    progress : callable, optional
        ``progress(done, 1000)``: how far the branches have come through the range.
    start_branch : bool
        Whether to follow the branch of the cycle found at ``start`` too (module docstring); false: the branches
        from the Hopf points alone (``cycles`` without ``vary`` wants the Hopf branch's cycle and no other).
    returns : int, optional
        The returns each branch may take (:func:`~lumped.drivers.cycles.shooting.returns_budget`; default
        :data:`RETURNS_PER_POINT` ``points``, at least :data:`MIN_RETURNS`): a branch ends where they are spent.
    notes : list of str, optional
        Appended with what ended a branch early, in words (its budget spent).

    Returns
    -------
    list of BranchPoint
        The equilibria in order from ``start`` to ``stop`` (Hopf points inserted), then each cycle branch in
        order along it, its changes inserted.

    Raises
    ------
    ValueError
        One line: a system :func:`check_autonomous` refuses, bad ``points``, an unknown parameter, a bad range
        or a value of it that the system refuses (:func:`hopf_points`).
    """
    check_autonomous(network)
    points = check_points(points)
    hopf = hopf_points(network, parameter, start, stop)  # checks the parameter and the range (vary: ...)
    budget = (
        max(MIN_RETURNS, RETURNS_PER_POINT * points) if returns is None else validate.positive_int("returns", returns)
    )
    fam = _Family(network, parameter, start, stop, budget)
    report = _reporter(progress, start, stop)
    rows = _equilibria(fam, start, stop, points, hopf)
    lo, hi = sorted((start / fam.p_s, stop / fam.p_s))
    slowest = min(abs(fam.belt(start)), abs(fam.belt(stop)))
    walk = _Walk(
        lo,
        hi,
        (min(start, stop), max(start, stop)),
        1.0 / (points - 1),
        SPEED_STEP,
        0.5 * HOPF_AMPLITUDE * slowest / fam.v_s,
    )
    reached: list[float] = []  # Hopf points where a branch followed from another one came back to zero amplitude
    for h in hopf:
        if h in reached:
            continue  # its branch is the one that came to it: no second walk along it
        branch = _bounded(fam, lambda h=h: _from_hopf(fam, h, walk, 50 * points, report)) or [_hopf_row(fam, h)]
        rows += branch
        end = branch[-1]
        others = [g for g in hopf if g != h]
        if len(branch) > 1 and end.cycle.section < walk.floor * fam.v_s and others:  # type: ignore[union-attr]
            reached.append(min(others, key=lambda g: abs(g - end.value)))
            rows.append(_hopf_row(fam, reached[-1]))
    if start_branch:
        rows += _bounded(fam, lambda: _from_start(fam, start, walk, 50 * points, report, rows))
    if progress is not None:
        progress(1000, 1000)
    if notes is not None:
        notes += fam.notes
    return rows if fam.sign > 0 else [_mirrored_row(r) for r in rows]


def _bounded(fam: _Family, branch: Callable[[], list[BranchPoint]]) -> list[BranchPoint]:
    """``branch()``'s rows, its returns bounded by ``fam.budget`` (:data:`RETURNS_PER_POINT`); none, and a note,
    where the budget is spent before its first cycle (a walk under way keeps its rows: :func:`_follow`)."""
    with returns_budget(fam.budget):
        try:
            return branch()
        except ReturnsSpent:
            fam.notes.append(f"a branch of {fam.name} found no cycle in its {fam.budget} returns")
            return []


def _mirrored_row(row: BranchPoint) -> BranchPoint:
    """A row of the mirrored family (a belt running backwards, :class:`_Family`) as the system's own."""
    eq = None if row.equilibrium is None else mirror_equilibrium(row.equilibrium)
    cycle = None if row.cycle is None else mirror_cycle(row.cycle)
    return row._replace(equilibrium=eq, cycle=cycle)


def _reporter(progress: Callable[[int, int], None] | None, start: float, stop: float) -> Callable[[float], None]:
    """``progress`` called with how far ``value`` has come from ``start`` towards ``stop``, in thousandths."""
    if progress is None:
        return lambda value: None
    return lambda value: progress(int(1000 * min(max((value - start) / (stop - start), 0.0), 1.0)), 1000)
