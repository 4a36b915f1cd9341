"""A relation between rate and tension invertible neither way: the ``curve`` element of system files.

The element's rate ``u`` (its ``w``, m/s) and tension ``T`` (N) lie on a
curve given by points ``[[u, T], ...]``, ordered along it.  The curve may
fold back in both coordinates (an S or a Z): neither ``T(u)`` nor ``u(T)``
need be a function.  Its first and last segments extend to infinity along
their lines, so the curve holds every rate from ``-inf`` to ``+inf``; a
vertical segment (``u`` constant) is a set-valued stretch, as a stick band
is: at that rate the tension is anything between its ends.

**Branches.**  The curve is split where the direction of ``u`` reverses (a
*fold*; vertical segments between two runs of opposite direction are the
fold's stretch) into *branches*, numbered from 1 along the curve.  On a
branch ``T`` is a piecewise-linear graph of ``u`` (it may fall); a vertical
stretch at a fold belongs to the branch on which the tension rises with the
rate there.  The element's state is the number of the branch it is on.

**Jumps: the delay convention.**  The motion follows the branch it is on as
long as the branch holds it; when the rate reaches a fold and would go on
past it, the tension jumps at constant rate to the *branch beyond the
fold*: the first branch that holds the rates just past it, walking along the
curve from the branch left towards the curve's end at ``u = +inf`` for a jump
up in rate, at ``u = -inf`` for a jump down (the curve runs on to that end, so
there is one).  This is the jump rule of Sastry and Desoer (IEEE Trans.
Circuits Syst. 28 (1981) 1109) for a state that cannot jump (the rate, a
mass's velocity) and one that can (the tension): an S whose tension rises
along it, ``u = phi(T)``, regularised by a stiff spring in series, ``T' =
kappa (u - phi(T))``, leaves the fold along the vertical line ``u`` fixed,
its tension rising past an upper fold and falling past a lower one, and
lands on that branch; a Z (tension falling along it) jumps by the same walk.
In catastrophe theory's words this is the *delay* convention (the state stays
on its branch until the branch ends, so the jumps up and down happen at
different rates: hysteresis).  The other, the *Maxwell* convention, would put the element
always on one branch chosen by the rate alone and jump both ways at the one
rate where the areas cut off between the vertical line and the curve are
equal (Maxwell's construction): no hysteresis, and a jump before the fold.

**Backward Euler.**  A step sees the branch it starts on, with a *wall* at
each fold: a rigid piece at the fold's rate whose band reaches ``-inf`` or
``+inf``, so that every step has a solution on it.  A step that ends on a
wall beyond the branch's tension there (the rate held at the fold, the
tension on the vertical line of the jump) has reached the fold; the element
is on the branch beyond from the next step on (:meth:`Curve.next_state`),
and the run records the jump (:class:`lumped.model.trajectory.Jump`).  The
step held at the fold adds at most a step to backward Euler's own lag in
reaching it: the jump times converge at order 1, as backward Euler does.  A branch whose tension never falls is a maximal monotone step graph (a
convex step); one that falls is walked piece by piece by the rule of
:class:`FallingBranch`, unique when ``dt`` meets the bound of
:mod:`lumped.solvers.uniqueness` for the curve's steepest fall.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

from lumped.laws.bingham import BinghamDashpot
from lumped.laws.contract import BinghamForm
from lumped.laws.element import Element, KernelForm
from lumped.laws.step_graph import Piece, Pieces, bingham_band, free_piece, rigid_piece
from lumped.numerics import validate

__all__ = ["MAX_POINTS", "Branch", "Curve", "FallingBranch", "RisingBranch", "branches"]

_INF = math.inf
#: Most points of a curve: finding the branch beyond each fold walks along the curve, at worst from every
#: fold to an end (a measured S-shaped relation has hundreds).
MAX_POINTS = 10_000
_BINGHAM_CODE = 2  # the Bingham element's kind code in ``_network_elements.h``


class Branch(NamedTuple):
    """One branch of a curve: a stretch of it along which the rate runs one way.

    ``number`` counts from 1 along the curve; ``lo``, ``hi`` (m/s) are the
    rates it holds (``-inf``, ``+inf`` at the curve's ends); ``pieces`` its
    step graph in increasing rate, a wall (a rigid piece reaching ``-inf`` or
    ``+inf``) at each finite end; ``leave_below`` and ``leave_above`` (N) the
    tensions beyond which a step ending on a wall has passed the fold
    (``-inf``, ``+inf`` at an open end); ``below`` and ``above`` the numbers of
    the branches beyond the folds at ``lo`` and ``hi`` (0 at an open end);
    ``fall`` (N s/m) the steepest fall of its tension with the rate.
    """

    number: int
    lo: float
    hi: float
    pieces: tuple[Piece, ...]
    leave_below: float
    leave_above: float
    below: int
    above: int
    fall: float

    def holds(self, rate: float) -> bool:
        """True if the branch holds ``rate`` (its ends included)."""
        return self.lo <= rate <= self.hi


# -- the points and their branches ----------------------------------------------------


def _point(k: int, value: object) -> tuple[float, float]:
    """Point ``k`` (counted from 1) as ``(u, T)``, finite."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 2:  # type: ignore[arg-type]
        raise ValueError(f"points: point {k} must be a pair [u, T] (m/s, N), got {value!r:.40}")
    u, t = value  # type: ignore[misc]
    return validate.finite(f"points: point {k}'s rate u", u), validate.finite(f"points: point {k}'s tension T", t)


def check_points(points: object) -> tuple[tuple[float, float], ...]:
    """``points`` as a tuple of ``(u, T)`` pairs, or a one-line ``ValueError`` saying what is wrong."""
    if isinstance(points, (str, bytes, dict)) or not hasattr(points, "__len__"):
        raise ValueError(f"points must be a list of [u, T] pairs (m/s, N), got {points!r:.40}")
    if len(points) > MAX_POINTS:  # type: ignore[arg-type]
        raise ValueError(f"points: {len(points)} points, more than the {MAX_POINTS} a curve may have")  # type: ignore[arg-type]
    out = tuple(_point(k, p) for k, p in enumerate(points, 1))  # type: ignore[arg-type]
    if len(out) < 2:
        raise ValueError(f"points: a curve needs at least 2 points, got {len(out)}")
    for k, (p, q) in enumerate(zip(out, out[1:]), 1):
        if p == q:
            raise ValueError(f"points {k} and {k + 1} are the same point {_show(p)}: a segment of zero length")
        if p[0] != q[0]:
            slope = (q[1] - p[1]) / (q[0] - p[0])
            if not (math.isfinite(slope) and math.isfinite(p[1] - slope * p[0])):
                raise ValueError(
                    f"points {k} and {k + 1}: the line through {_show(p)} and {_show(q)} (T = a + b u) is beyond "
                    "double precision"
                )
    for end, (p, q) in (("first", out[:2]), ("last", out[-2:])):
        if p[0] == q[0]:
            raise ValueError(
                f"points: the {end} segment, {_show(p)} to {_show(q)}, is vertical: the ends extend to infinity "
                "along their lines, so they must reach every rate"
            )
    return out


def _show(p: tuple[float, float]) -> str:
    return f"({p[0]:.6g}, {p[1]:.6g})"


def _sign(x: float) -> int:
    return (x > 0) - (x < 0)


class _Run(NamedTuple):
    """A run of segments (indices) along which ``u`` moves one way (``sign``), vertical ones inside it included."""

    sign: int
    segments: list[int]


def _runs(points: tuple[tuple[float, float], ...]) -> list[_Run]:
    """The branches' segments, each fold's vertical stretch given to the branch on which it rises."""
    du = [_sign(q[0] - p[0]) for p, q in zip(points, points[1:])]
    dt = [_sign(q[1] - p[1]) for p, q in zip(points, points[1:])]
    for k in range(len(du) - 1):
        if du[k] == du[k + 1] == 0 and dt[k] != dt[k + 1]:
            raise ValueError(
                f"points {k + 1} to {k + 3}: a vertical stretch folds back on itself at u = {points[k][0]:.6g}"
            )
    runs: list[_Run] = []
    stretch: list[int] = []
    for k, s in enumerate(du):
        if s == 0:
            stretch.append(k)
            continue
        if runs and runs[-1].sign == s:
            runs[-1].segments.extend(stretch + [k])
        elif runs:  # a fold: its stretch rises with the rate on the run before it if it runs T the same way as u
            owner = runs[-1] if stretch and dt[stretch[0]] == runs[-1].sign else None
            if owner is not None:
                owner.segments.extend(stretch)
            runs.append(_Run(s, ([] if owner is not None else stretch) + [k]))
        else:
            runs.append(_Run(s, [k]))
        stretch = []
    for run in runs:
        for k in run.segments:
            if du[k] == 0 and dt[k] != run.sign:
                p, q = points[k], points[k + 1]
                raise ValueError(
                    f"points {k + 1} and {k + 2}: the vertical segment {_show(p)} to {_show(q)} lets the tension "
                    "fall as the rate grows, so no step on it is unique"
                )
    if runs[0].sign != runs[-1].sign:
        raise ValueError(
            "points: the curve's ends both run towards u = "
            f"{'+inf' if runs[0].sign < 0 else '-inf'}: a curve that holds every rate begins and ends running the "
            "same way in u"
        )
    return runs


def _branch_pieces(path: list[tuple[float, float]], open_lo: bool, open_hi: bool) -> tuple[list[Piece], float, float]:
    """The pieces of a branch's points ``path`` (in increasing rate) with walls at its closed ends, and the
    tensions beyond which a step leaves it there (see :class:`Branch`)."""
    pieces: list[Piece] = []
    k, last = 0, len(path) - 1
    leave_below, leave_above = -_INF, _INF
    if not open_lo:
        while path[k + 1][0] == path[k][0]:  # the fold's stretch, merged into the wall
            k += 1
        leave_below = path[0][1]
        pieces.append(rigid_piece(path[0][0], -_INF, path[k][1]))
    end = last
    if not open_hi:
        while path[end - 1][0] == path[end][0]:
            end -= 1
        leave_above = path[last][1]
    while k < end:
        p, q = path[k], path[k + 1]
        if p[0] == q[0]:
            j = k + 1
            while path[j + 1][0] == p[0]:
                j += 1
            pieces.append(rigid_piece(p[0], p[1], path[j][1]))
            k = j
            continue
        b = (q[1] - p[1]) / (q[0] - p[0])
        lo = -_INF if open_lo and k == 0 else p[0]
        hi = _INF if open_hi and k + 1 == last else q[0]
        pieces.append(free_piece(p[1] - b * p[0], b, lo, hi))
        k += 1
    if not open_hi:
        pieces.append(rigid_piece(path[end][0], path[end][1], _INF))
    return pieces, leave_below, leave_above


def _beyond(spans: list[tuple[float, float]], j: int, rate: float, up: bool, step: int) -> int:
    """The branch (index) beyond the fold at ``rate`` of branch ``j``: the first after ``j`` in the direction
    ``step`` (towards the curve's end at ``u = +inf`` for a jump ``up``, at ``-inf`` otherwise) that holds the
    rates just past ``rate``.  The curve runs on from the fold to that end, so one does."""
    k = j + step
    while 0 <= k < len(spans):
        lo, hi = spans[k]
        if (lo <= rate < hi) if up else (lo < rate <= hi):
            return k
        k += step
    raise AssertionError("a curve from u = -inf to u = +inf holds every rate")  # pragma: no cover


def branches(points: object) -> tuple[Branch, ...]:
    """The branches of the curve through ``points`` (see the module docstring); a one-line ``ValueError`` for
    points that are not such a curve."""
    pts = check_points(points)
    runs = _runs(pts)
    built, spans = [], []
    for j, run in enumerate(runs):
        path = [pts[run.segments[0]]] + [pts[k + 1] for k in run.segments]
        if run.sign < 0:
            path.reverse()
        open_lo = (j == 0 and run.sign > 0) or (j == len(runs) - 1 and run.sign < 0)
        open_hi = (j == 0 and run.sign < 0) or (j == len(runs) - 1 and run.sign > 0)
        pieces, leave_below, leave_above = _branch_pieces(path, open_lo, open_hi)
        spans.append((-_INF if open_lo else path[0][0], _INF if open_hi else path[-1][0]))
        fall = max([0.0] + [-p.b for p in pieces if not p.rigid])
        built.append((pieces, leave_below, leave_above, fall))
    out, plus = [], runs[-1].sign  # the step along the curve towards its end at u = +inf
    for j, (pieces, leave_below, leave_above, fall) in enumerate(built):
        lo, hi = spans[j]
        below = 0 if lo == -_INF else 1 + _beyond(spans, j, lo, False, -plus)
        above = 0 if hi == _INF else 1 + _beyond(spans, j, hi, True, plus)
        out.append(Branch(j + 1, lo, hi, tuple(pieces), leave_below, leave_above, below, above, fall))
    return tuple(out)


# -- the step graphs of a branch -----------------------------------------------------


class RisingBranch(Pieces):
    """The step graph of a branch whose tension never falls: maximal monotone, its modes its pieces' indices.

    As :class:`~lumped.laws.step_graph.Pieces`, except that a mode that is not
    one of its pieces (the warm start of a step after a jump, from another
    branch) is taken as the first guess.
    """

    __slots__ = ()

    def piece(self, mode: object, sigma: float) -> Piece:
        return self[mode if _own(self, mode) else self.initial_mode()]  # type: ignore[index]


def _own(graph: tuple, mode: object) -> bool:
    return isinstance(mode, int) and 0 <= mode < len(graph)


class FallingBranch(RisingBranch):
    """The step graph of a branch whose tension falls somewhere: its pieces, walked by a rule.

    The one-step problem is unique on the branch when ``dt`` meets the bound
    of :mod:`lumped.solvers.uniqueness`, but the resolvent's choice of a
    piece (``z = f + sigma w``) orders the pieces only where ``sigma`` exceeds
    the fall, which a scale of the iteration need not.  So the mode walks (point
    7 of :class:`~lumped.laws.step_graph.StepGraph`): from a free piece to the
    next one up or down when the rate leaves its range, from a rigid piece when
    the force leaves its band.  Where the step is unique the walk moves towards
    the solution and never back.
    """

    __slots__ = ()
    monotone: ClassVar[bool] = False

    def next_mode(self, old: object, w: float, f: float, sigma: float) -> int:
        k = old if _own(self, old) else self.initial_mode()
        p = self[k]  # type: ignore[index]
        if p.rigid:
            return k + 1 if f > p.hi else k - 1 if f < p.lo else k  # type: ignore[operator]
        return k + 1 if w > p.hi else k - 1 if w < p.lo else k  # type: ignore[operator]


# -- the element ------------------------------------------------------------------------


@dataclass(frozen=True)
class Curve(Element):
    """A relation between rate and tension given by points (system files: ``kind = "curve"``).

    Parameters
    ----------
    points : sequence of (u, T) pairs, m/s and N
        The curve, in order along it (see the module docstring): finite, at
        least 2, no two consecutive equal, the first and last segments not
        vertical and running the same way in ``u`` (so that, extended, the
        curve holds every rate).
    branch : int, optional
        The branch the element starts on (from 1, along the curve); by default
        the first that holds the initial rate.
    """

    kind: ClassVar[str] = "curve"
    optional: ClassVar[tuple[str, ...]] = ("branch",)
    #: The state is the branch: its changes are jumps, which backward Euler records (Element point 12).
    jumps: ClassVar[bool] = True
    points: tuple[tuple[float, float], ...] = ()
    branch: int | None = None

    def _check(self) -> None:
        shape = branches(self.points)
        object.__setattr__(self, "points", check_points(self.points))
        if self.branch is not None:
            number = validate.positive_int("branch", self.branch)
            if number > len(shape):
                raise ValueError(f"branch must be 1 to {len(shape)}, the curve's branches; got {number}")
            object.__setattr__(self, "branch", number)
        object.__setattr__(self, "_branches", shape)

    @property
    def branches(self) -> tuple[Branch, ...]:
        """The curve's branches, numbered from 1 along it."""
        return self._branches  # type: ignore[attr-defined]

    def _on(self, state: float) -> Branch:
        return self.branches[int(state) - 1]

    @property
    def rigid_capable(self) -> bool:
        return any(p.rigid for b in self.branches for p in b.pieces)

    def initial_state(self, e0: float, w0: float) -> float:
        """The branch at ``t = 0``: ``branch`` if given (it must hold ``w0``), else the first that holds ``w0``."""
        if self.branch is not None:
            b = self.branches[self.branch - 1]
            if not b.holds(w0):
                raise ValueError(
                    f"branch {b.number} holds the rates {b.lo:.6g} to {b.hi:.6g} m/s, not the initial rate {w0:.6g} m/s"
                )
            return float(b.number)
        return float(next(b.number for b in self.branches if b.holds(w0)))

    def step_graph(self, state: float, dt: float) -> RisingBranch:
        form = self.bingham_form()
        if form is not None:
            return RisingBranch(bingham_band(form.threshold, form.viscosity))
        b = self._on(state)
        return (FallingBranch if b.fall > 0 else RisingBranch)(b.pieces)

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        """The band of a rigid piece at ``w0`` (the tension then follows the acceleration's sign), else the
        tension at ``w0``."""
        pieces = self._on(state).pieces
        band = next((p for p in pieces if p.rigid and p.a == w0), None)
        if band is None:
            p = next(p for p in pieces if not p.rigid and p.lo <= w0 <= p.hi)
            return (free_piece(p.a + p.b * w0, 0.0),)
        below = (free_piece(band.lo, 0.0, -_INF, 0.0),) if band.lo > -_INF else ()
        above = (free_piece(band.hi, 0.0, 0.0, _INF),) if band.hi < _INF else ()
        return (*below, rigid_piece(0.0, band.lo, band.hi), *above)

    def next_state(self, state: float, dt: float, w: float, f: float, rigid: bool) -> float:
        """The branch beyond a fold if the step ended on that fold's wall past the branch's tension there,
        else the same branch (the delay convention; see the module docstring)."""
        b = self._on(state)
        if not rigid or (b.below == 0 and b.above == 0):
            return state
        walls = [p for p in b.pieces if p.rigid]
        nearest = min(walls, key=lambda p: abs(w - p.a))
        if b.below and nearest is b.pieces[0] and f < b.leave_below:
            return float(b.below)
        if b.above and nearest is b.pieces[-1] and f > b.leave_above:
            return float(b.above)
        return state

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        """The least and greatest tension the curve holds at the rate ``w`` (its branches may hold several)."""
        values = []
        for b in self.branches:
            for p in b.pieces:
                if p.rigid and p.a == w:
                    values += [v for v in (p.lo, p.hi) if math.isfinite(v)]
                elif not p.rigid and p.lo <= w <= p.hi:
                    values.append(p.a + p.b * w)
        return (min(values), max(values))

    @property
    def monotone(self) -> bool:
        """True only for a curve that is the Bingham graph (one branch, never falling; Element point 13)."""
        return self.bingham_form() is not None

    @property
    def steepest_fall(self) -> float:
        """The steepest fall of any branch (N s/m): a backward-Euler step must outweigh it on every branch the
        element may reach."""
        return max(b.fall for b in self.branches)

    def bingham_form(self) -> BinghamForm | None:
        """``(tau, c)`` if the curve is the Bingham graph of eq. (6) (one branch: slope ``c`` through
        ``(0, -tau)``, the band ``[-tau, tau]`` at rate 0, slope ``c`` from ``(0, tau)``), else ``None``."""
        if len(self.branches) != 1 or len(self.branches[0].pieces) != 3:
            return None
        pieces = self.branches[0].pieces
        tau, c = pieces[1].hi, pieces[0].b
        if tau > 0 and c >= 0 and pieces == bingham_band(tau, c):
            return BinghamForm(tau, c)
        return None

    def one_mass_law(self) -> BinghamDashpot | None:
        """The Bingham law the curve is, if it is one (the paper's methods run it), else ``None``."""
        form = self.bingham_form()
        if form is None:
            return None
        return BinghamDashpot(form.threshold, _INF if form.viscosity == 0 else 1.0 / form.viscosity)

    @property
    def auto_one_mass(self) -> bool:
        """True when the curve is the Bingham graph: Algorithm 1 itself runs it."""
        return self.bingham_form() is not None

    def kernel_form(self) -> KernelForm | None:
        """The Bingham element's form when the curve is the Bingham graph; ``None`` otherwise."""
        form = self.bingham_form()
        return None if form is None else KernelForm(_BINGHAM_CODE, (form.threshold, form.viscosity), True)
