"""Step graphs: how one backward-Euler step of a network sees each element.

One backward-Euler step fixes every state of the step's start and leaves the
new rates ``w`` unknown; each element then relates ``f`` to ``w`` by a
*step graph*, maximal monotone and piecewise linear for every kind here (a
general monotone law is the exception: see :class:`LawGraph`).  A
piecewise-linear step graph is a list of :class:`Piece` s in increasing order
along the graph: a *free* piece ``f = a + b w`` (``b >= 0``) on ``lo <= w <=
hi``, or a *rigid* piece ``w = a`` with ``lo <= f <= hi``.  The one-step
problem (:mod:`lumped.solvers.network_step`) sees each graph through the graph
contract of :class:`StepGraph` (:class:`Pieces`, or a law's
:class:`LawGraph`); it never asks which kind an element or a graph is.

This module holds that contract, its two implementations and the pieces the
element kinds build their graphs from (:func:`free_piece`,
:func:`rigid_piece`, :func:`bingham_band`).
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Sequence
from typing import ClassVar, NamedTuple

from lumped.laws.bingham import sticks
from lumped.laws.contract import Dashpot

__all__ = [
    "CurveSlipGraph",
    "LawGraph",
    "Piece",
    "Pieces",
    "Shifted",
    "SlipGraph",
    "StepGraph",
    "as_step_graph",
    "bingham_band",
    "free_piece",
    "rigid_piece",
    "shifted",
]

_INF = math.inf
_EPS = 2.0**-52  # numpy.finfo(float).eps


class Piece(NamedTuple):
    """One piece of a step graph.

    ``rigid`` False: ``f = a + b*w`` for ``lo <= w <= hi`` (``b >= 0``).
    ``rigid`` True: ``w = a`` and ``lo <= f <= hi`` (``b`` unused, 0).
    """

    rigid: bool
    a: float
    b: float
    lo: float
    hi: float


def free_piece(a: float, b: float, lo: float = -_INF, hi: float = _INF) -> Piece:
    """The free piece ``f = a + b w`` on ``lo <= w <= hi``."""
    return Piece(False, a, b, lo, hi)


def rigid_piece(w: float, lo: float, hi: float) -> Piece:
    """The rigid piece ``w`` fixed, ``lo <= f <= hi``."""
    return Piece(True, w, 0.0, lo, hi)


def bingham_band(threshold: float, c: float, lo: float = -_INF, hi: float = _INF) -> tuple[Piece, ...]:
    """The Bingham step graph: slip- on ``[lo, 0]``, stick, slip+ on ``[0, hi]``."""
    return (
        free_piece(-threshold, c, lo, 0.0),
        rigid_piece(0.0, -threshold, threshold),
        free_piece(threshold, c, 0.0, hi),
    )


class StepGraph(ABC):
    """The graph contract: what the one-step problem asks of a step graph.

    A *mode* is where on the graph an element is taken to be in one
    iteration of the active-set loop (:mod:`lumped.solvers.network_step`).  A step
    graph must provide:

    1. ``is_piecewise``: True if the graph is made of :class:`Piece` s
       (indexable, its modes their indices), so that the iteration's modes can
       cycle and the dual sweeps can step on it; False for a graph that is
       linearised about a point in each iteration (:class:`LawGraph`).
    2. ``initial_mode()``: the mode of the first iteration with no warm start.
    3. ``piece(mode, sigma)``: the free or rigid :class:`Piece` that the
       linear problem of an iteration uses in ``mode``.
    4. ``mode(z, sigma)``: the new mode from the resolvent variable ``z = f +
       sigma w`` of the iteration's solution.
    5. ``same(old, new)``: True when the mode has settled.
    6. ``monotone``: True (the default) if the graph is maximal monotone, so that
       its step is a convex problem and parallel graphs may be summed
       (:mod:`lumped.solvers.parallel_elements`); False for a friction contact
       whose tension falls (:class:`SlipGraph`), whose solution a rule picks.
    7. ``next_mode(old, w, f, sigma, rounding=(0, 0))``: the new mode from the
       iteration's rate and force in mode ``old``; ``rounding = (df, dw)``
       bounds the linear solve's rounding in force and rate
       (:func:`lumped.solvers.network_step.on_pieces`).  The default is :meth:`mode`
       of ``z = f + sigma w``, the resolvent's choice, right for a monotone
       graph; a graph that is not monotone states its rule here.
    8. ``newton()``: the graph the step's finishing iteration uses when the
       iteration at every scale fails to settle (``network_step``): the
       default is the graph itself; a curve linearised by a line of slope
       ``sigma`` returns its tangent (Newton) form (:class:`CurveSlipGraph`).
    9. ``potential(w)``: the step potential ``psi(w)``, the integral from 0 to
       ``w`` of the graph's force (``+inf`` where the graph has no rate ``w``),
       whose sum with the masses' terms is the step's function ``Phi``
       (book/guide/systems.md; the value a failed step reports).  The default
       integrates the free pieces exactly; a curve integrates its law.
    """

    __slots__ = ()
    is_piecewise: ClassVar[bool] = True
    monotone: ClassVar[bool] = True

    def next_mode(self, old: object, w: float, f: float, sigma: float, rounding: tuple = (0.0, 0.0)) -> object:
        """The mode after an iteration that gave ``(w, f)`` in mode ``old`` (point 7)."""
        return self.mode(f + sigma * w, sigma)

    def newton(self) -> StepGraph:
        """The graph of the finishing iteration (point 8): this one."""
        return self

    def potential(self, w: float) -> float:
        """``psi(w)`` (point 9) of a piecewise graph: each free piece's ``a s + b s^2/2`` over its part
        of ``[0, w]`` (a rigid piece is one rate, of no length), ``+inf`` off every piece."""
        pieces = list(self)  # type: ignore[call-overload]
        if not any(p.lo <= w <= p.hi if not p.rigid else w == p.a for p in pieces):
            return _INF
        low, high, sign = (0.0, w, 1.0) if w >= 0 else (w, 0.0, -1.0)
        total = 0.0
        for p in pieces:
            a, b = max(p.lo, low), min(p.hi, high)
            if not p.rigid and a < b:
                total += p.a * (b - a) + p.b * (b * b - a * a) / 2
        return sign * total

    @abstractmethod
    def initial_mode(self) -> object:
        """The mode of the first iteration (point 2)."""

    @abstractmethod
    def piece(self, mode: object, sigma: float) -> Piece:
        """The piece used in ``mode`` (point 3)."""

    @abstractmethod
    def mode(self, z: float, sigma: float) -> object:
        """The mode holding ``z = f + sigma w`` (point 4)."""

    @abstractmethod
    def same(self, old: object, new: object) -> bool:
        """True if the mode has settled (point 5)."""


class Pieces(tuple, StepGraph):
    """A piecewise-linear step graph: its :class:`Piece` s in order; a mode is a piece's index."""

    __slots__ = ()
    is_piecewise: ClassVar[bool] = True

    def initial_mode(self) -> int:
        """The middle piece (a Bingham element's sticking piece)."""
        return len(self) // 2

    def piece(self, mode: object, sigma: float) -> Piece:
        return self[mode]  # type: ignore[index]

    def mode(self, z: float, sigma: float) -> int:
        """The piece whose range of ``z = f + sigma w`` holds ``z``.

        A rigid piece (``w = a``, ``f`` in ``[lo, hi]``) holds the closed band
        ``[lo + sigma a, hi + sigma a]`` (:func:`lumped.laws.sticks`, Algorithm 1's
        line 5), so at an edge it shares with a free piece, where both give the
        same ``(w, f)``, the rigid piece is chosen: a Bingham element sticks on
        both edges of its band, as in Algorithm 1.  A rigid piece of zero width
        (a threshold 0) is never taken: its one point lies on the free pieces
        beside it, and such an element is not ``rigid_capable``.  ``mode_of`` in
        ``_network_elements.h`` is the C copy (``tests/test_band_edge.py``).
        """
        for k, p in enumerate(self):
            if p.rigid and p.lo < p.hi and sticks(z, p.lo + sigma * p.a, p.hi + sigma * p.a):
                return k
        last = len(self) - 1
        for k, p in enumerate(self[:last]):
            if not p.rigid and z <= p.a + (p.b + sigma) * p.hi:
                return k
        return last

    def same(self, old: object, new: object) -> bool:
        return old == new


class LawGraph(StepGraph):
    """The step graph of a :class:`LawElement`: its dashpot law, linearised in each iteration.

    A mode is the point ``(w, f)`` of the graph last reached (``0`` before
    the first): the piece is the line of slope ``sigma`` through it, and the
    new point is the law's resolvent point of ``z``.  The mode has settled
    when the force agrees to a relative 8 ulps.
    """

    __slots__ = ("law",)
    is_piecewise: ClassVar[bool] = False

    def __init__(self, law: Dashpot) -> None:
        self.law = law

    def initial_mode(self) -> int:
        return 0

    def piece(self, mode: object, sigma: float) -> Piece:
        w0, f0 = mode if isinstance(mode, tuple) else (0.0, 0.0)
        return Piece(False, f0 - sigma * w0, sigma, -_INF, _INF)

    def mode(self, z: float, sigma: float) -> tuple[float, float]:
        f = self.law._resolvent_impl(z, sigma).force
        return ((z - f) / sigma, f)

    def potential(self, w: float) -> float:
        """``psi(w)`` (point 9): the law's force integrated (:func:`_integral`)."""
        return _integral(self.law, w)

    def same(self, old: object, new: object) -> bool:
        if not isinstance(old, tuple):
            return False
        scale = abs(new[1]) + abs(old[1]) + 1e-300  # type: ignore[index]
        return abs(new[1] - old[1]) <= 8 * _EPS * scale  # type: ignore[index]


#: The modes of a friction contact's step graph (:class:`SlipGraph`): the indices of its pieces.
SLIP_BACK, STICK, SLIP_FORWARD = 0, 1, 2


def _slip_rule(old: int, w: float, f: float, static: float) -> int:
    """The rule that picks a friction contact's step (a graph that is not monotone).

    A stuck contact stays stuck while its tension is within ``[-static, static]``
    and slips the way it is pulled beyond; a slipping contact slips while its
    rate keeps its direction and sticks when the rate would change sign (the
    next iteration then tests the stuck tension against ``static``, so a
    contact may stop and slip back within one step).
    """
    if old == STICK:
        return SLIP_FORWARD if f > static else SLIP_BACK if f < -static else STICK
    if old == SLIP_FORWARD:
        return SLIP_FORWARD if w > 0 else STICK
    return SLIP_BACK if w < 0 else STICK


class SlipGraph(StepGraph):
    """The step graph of a friction contact whose slip curve is linear, ``g(s) = a + b s``.

    Three pieces: slip back (``f = -a + b w``, ``w <= 0``), stick (``w = 0``,
    ``|f| <= static``) and slip forward (``f = a + b w``, ``w >= 0``).  With
    ``a < static`` the graph falls at ``w = 0`` and is not monotone: the mode
    is chosen by the contact's rule (:func:`_slip_rule`), starting from the
    contact's state at the step's start (``start``: the piece it is on).
    """

    __slots__ = ("pieces", "start", "static")
    is_piecewise: ClassVar[bool] = True
    monotone: ClassVar[bool] = False

    def __init__(self, static: float, a: float, b: float, start: int) -> None:
        self.static, self.start = static, start
        self.pieces = (free_piece(-a, b, -_INF, 0.0), rigid_piece(0.0, -static, static), free_piece(a, b, 0.0, _INF))

    def __getitem__(self, k: int) -> Piece:
        return self.pieces[k]

    def __len__(self) -> int:
        return 3

    def __iter__(self):
        return iter(self.pieces)

    def initial_mode(self) -> int:
        return self.start

    def piece(self, mode: object, sigma: float) -> Piece:
        return self.pieces[mode]  # type: ignore[index]

    def mode(self, z: float, sigma: float) -> int:
        """The stuck contact's choice from ``z`` (used by the dual sweeps' first guess)."""
        return Pieces(self.pieces).mode(z, sigma)

    def next_mode(self, old: object, w: float, f: float, sigma: float, rounding: tuple = (0.0, 0.0)) -> int:
        return _slip_rule(old, w, f, self.static)  # type: ignore[arg-type]

    def same(self, old: object, new: object) -> bool:
        return old == new


#: How many earlier points a :class:`CurveSlipGraph` mode remembers: rounding cycles up to this long settle.
_CYCLE = 8


class CurveSlipGraph(StepGraph):
    """The step graph of a friction contact with any slip curve (a :class:`lumped.laws.SlipLaw`).

    Its mode is :data:`STICK`, or the point ``(s, w, f, sigma, before)`` of
    the slip branch of direction ``s`` last reached, the scale it was reached
    with and the ``(w, f)`` of the last :data:`_CYCLE` points reached before
    it (``()`` for the first);
    the piece of a slip mode is the line of slope ``sigma`` through that point
    and the next point is the branch's resolvent point of ``z = f + sigma w``
    (``SlipLaw.slip_speed``), as for a :class:`LawGraph`.  Where the branch
    has no point (``|z|`` at most the slip limit), the contact stops: the rule
    of :func:`_slip_rule`.  The mode has settled when the point's ``f + sigma
    w`` agrees to a relative 8 ulps term by term, ``|df| + sigma |dw| <= 8 eps
    (|f| + |f'| + sigma (|w| + |w'|))`` (the step's force lies on the line
    through the old point, ``sigma |dw|`` off the branch, so the force alone
    agreeing is not enough where the branch is flat: a Stribeck curve at
    speeds well above ``v_s``), or when the new point is one reached before,
    a cycle of points that the rounding of the step's rates keeps apart (on
    a belt it is ``eps sigma |belt velocity|`` wide, more than 8 ulps of
    ``f + sigma w`` near a stop; Leine's curve on a belt at ``dt = 2e-3``
    cycles through three points 30 ulps of ``w`` apart).  A cycle is such
    only while each solve's ``(w, f)`` lies on the branch to the solve's
    rounding (:meth:`near`): a point reached from a solve off the branch
    forgets the points before it, so that a true cycle of points (the
    iteration is a fixed-point one, with no convergence proof) is never taken
    for a settled step whose force is off its law.

    ``tangent`` True is the finishing (Newton) form (point 8): the piece of a
    slip mode is the branch's tangent at its point (slope ``g'(|w|)``; the
    line of slope ``sigma`` at ``w = 0``), the next point the branch at the
    solve's rate, and the mode settles when the solve's ``(w, f)`` lies on the
    branch to the solve's rounding.  Given the modes, that is Newton's method
    on a smooth strongly convex function (book/guide/systems.md), so it
    converges quadratically from near the solution.
    """

    __slots__ = ("law", "start", "tangent")
    is_piecewise: ClassVar[bool] = False
    monotone: ClassVar[bool] = False

    def __init__(self, law: object, start: int, tangent: bool = False) -> None:
        self.law, self.start, self.tangent = law, start, tangent

    def newton(self) -> CurveSlipGraph:
        return CurveSlipGraph(self.law, self.start, tangent=True)

    def potential(self, w: float) -> float:
        """``psi(w)`` (point 9): the slip curve integrated (:func:`_integral`), the kinetic graph's."""
        return _integral(self.law, w)

    def _point(self, direction: float, z: float, sigma: float, old: object = None, near: bool = True) -> object:
        """The point of the branch ``direction`` whose ``f + sigma w`` is ``z`` (reached from the point
        ``old``, if any, by a solve on the branch if ``near``), or :data:`STICK`."""
        if direction * z <= self.law.slip_limit:  # type: ignore[attr-defined]
            return STICK
        s = self.law.slip_speed(direction * z, sigma)  # type: ignore[attr-defined]
        before = () if old is None or not near else (old[4] + (old[1:3],))[-_CYCLE:]  # type: ignore[index,operator]
        return (direction, direction * s, direction * float(self.law.slip(s)), sigma, before)  # type: ignore[attr-defined]

    def near(self, direction: float, w: float, f: float, sigma: float, rounding: tuple) -> bool:
        """True if ``(w, f)`` (the true rate, ``direction w > 0``) lies on the branch to the solve's rounding.

        The solve is exact for a problem whose rates and forces are moved by at
        most ``dw`` and ``df`` (``rounding``, :func:`lumped.solvers.network_step.on_pieces`);
        moving the rate by ``dw`` moves the branch's force by ``|g'(|w|)| dw``,
        and ``g`` itself is evaluated to a few ulps (8 taken): so the gap
        ``|f - s g(|w|)|`` of a solution is at most ``df + |g'| dw + 8 eps |g|``.
        """
        df, dw = rounding
        s = direction * w
        g = float(self.law.slip(s))  # type: ignore[attr-defined]
        slope = abs(self.law.slope(s).value)  # type: ignore[attr-defined]
        return abs(f - direction * g) <= df + slope * dw + 8 * _EPS * abs(g)

    def initial_mode(self) -> object:
        if self.start == STICK:
            return STICK
        direction = 1.0 if self.start == SLIP_FORWARD else -1.0
        return (direction, 0.0, direction * self.law.slip_limit, 0.0, ())  # type: ignore[attr-defined]

    def piece(self, mode: object, sigma: float) -> Piece:
        if mode == STICK:
            return rigid_piece(0.0, -self.law.static, self.law.static)  # type: ignore[attr-defined]
        _, w0, f0, _, _ = mode  # type: ignore[misc]
        slope = self.law.slope(abs(w0)).value if self.tangent and w0 else sigma  # type: ignore[attr-defined]
        return Piece(False, f0 - slope * w0, slope, -_INF, _INF)

    def mode(self, z: float, sigma: float) -> object:
        static = self.law.static  # type: ignore[attr-defined]
        return STICK if abs(z) <= static else self._point(math.copysign(1.0, z), z, sigma)

    def next_mode(self, old: object, w: float, f: float, sigma: float, rounding: tuple = (0.0, 0.0)) -> object:
        if old == STICK:
            stays = _slip_rule(STICK, w, f, self.law.static) == STICK  # type: ignore[attr-defined]
            return STICK if stays else self._point(math.copysign(1.0, f), f, sigma)
        if self.tangent and self.law.slip_limit >= self.law.static:  # type: ignore[attr-defined]
            return self._convex_mode(old, w, f, sigma, rounding)
        direction = old[0]  # type: ignore[index]
        if direction * w <= 0:
            return STICK
        near = self.near(direction, w, f, sigma, rounding)
        if not self.tangent:
            return self._point(direction, f + sigma * w, sigma, old, near)
        if near:
            return old  # settled: the solve lies on the branch
        return (direction, w, direction * float(self.law.slip(direction * w)), sigma, ())  # type: ignore[attr-defined]

    def _convex_mode(self, old: object, w: float, f: float, sigma: float, rounding: tuple) -> object:
        """The Newton finish's mode of a contact whose graph is one (``g(0+) = static``, a Stribeck fall).

        With ``lambda`` the steepest fall, ``f + lambda w`` is a monotone graph (the
        contact's potential plus ``lambda w^2/2``, convex: book/guide/systems.md), so
        the mode is its resolvent's choice, the primal-dual active-set test of a
        monotone graph: ``z = f + (lambda + sigma) w``, stuck if ``|z| <= static``,
        else slipping the way of ``z``.  This replaces the contact's rule, which picks
        among several solutions where a step has them; below the uniqueness bound
        it has one, and the rule's stop-then-slip could send two coupled contacts
        round a cycle (one breaking away while the other stops, in turn).
        """
        z = f + (self.law.fall + sigma) * w  # type: ignore[attr-defined]
        if abs(z) <= self.law.static:  # type: ignore[attr-defined]
            return STICK
        direction = math.copysign(1.0, z)
        if old != STICK and old[0] == direction and direction * w > 0:  # type: ignore[index]
            if self.near(direction, w, f, sigma, rounding):
                return old  # settled: the solve lies on the branch
            return (direction, w, direction * float(self.law.slip(direction * w)), sigma, ())  # type: ignore[attr-defined]
        return self._point(direction, z, sigma)

    def same(self, old: object, new: object) -> bool:
        if old == STICK or new == STICK:
            return old == new
        if old[0] != new[0]:  # type: ignore[index]
            return False
        if self.tangent:
            return old is new
        (_, w0, f0, _, _), (_, w1, f1, sigma, before) = old, new  # type: ignore[misc]
        scale = abs(f1) + abs(f0) + sigma * (abs(w1) + abs(w0)) + 1e-300
        return abs(f1 - f0) + sigma * abs(w1 - w0) <= 8 * _EPS * scale or (w1, f1) in before


class Shifted(StepGraph):
    """A step graph seen with one point driven: the element's rate is ``w + delta``.

    A driven point (:class:`lumped.model.network.Driver`) enters the one-step
    problem as the ground does, at velocity 0; an element joined to it has the
    true rate ``w + delta``, with ``delta`` the driver's mean velocity over the
    step (``+`` if the driver is the element's ``second`` point, ``-`` if its
    ``first``).  This wrapper shows the element's graph in the problem's rate
    ``w``; :func:`shifted` gives piecewise graphs as shifted :class:`Pieces`.
    """

    __slots__ = ("delta", "inner")

    def __init__(self, inner: StepGraph, delta: float) -> None:
        self.inner, self.delta = inner, delta

    @property
    def is_piecewise(self) -> bool:  # type: ignore[override]
        return self.inner.is_piecewise

    @property
    def monotone(self) -> bool:  # type: ignore[override]
        return self.inner.monotone

    def __getitem__(self, k: int) -> Piece:
        return _shift_piece(self.inner[k], self.delta)  # type: ignore[index]

    def __len__(self) -> int:
        return len(self.inner)  # type: ignore[arg-type]

    def __iter__(self):
        return (_shift_piece(p, self.delta) for p in self.inner)  # type: ignore[attr-defined]

    def initial_mode(self) -> object:
        return self.inner.initial_mode()

    def piece(self, mode: object, sigma: float) -> Piece:
        return _shift_piece(self.inner.piece(mode, sigma), self.delta)

    def mode(self, z: float, sigma: float) -> object:
        return self.inner.mode(z + sigma * self.delta, sigma)

    def next_mode(self, old: object, w: float, f: float, sigma: float, rounding: tuple = (0.0, 0.0)) -> object:
        df, dw = rounding  # the true rate w + delta rounds once more
        return self.inner.next_mode(old, w + self.delta, f, sigma, (df, dw + _EPS * abs(w + self.delta)))

    def newton(self) -> StepGraph:
        return Shifted(self.inner.newton(), self.delta)

    def potential(self, w: float) -> float:
        return self.inner.potential(w + self.delta) - self.inner.potential(self.delta)

    def same(self, old: object, new: object) -> bool:
        return self.inner.same(old, new)


def _integral(law: object, w: float) -> float:
    """The integral from 0 to ``|w|`` of a law's slip force ``g`` (odd in the rate: an even potential),
    by adaptive quadrature (SciPy's ``quad``, to its default 1.5e-8 relative): only a failed step's
    message reports it."""
    from scipy.integrate import quad

    return float(quad(lambda s: float(law.slip(s)), 0.0, abs(w))[0]) if w else 0.0  # type: ignore[attr-defined]


def _shift_piece(p: Piece, delta: float) -> Piece:
    """``p`` in the rate ``w`` of an element whose true rate is ``w + delta``."""
    if p.rigid:
        return Piece(True, p.a - delta, 0.0, p.lo, p.hi)
    return Piece(False, p.a + p.b * delta, p.b, p.lo - delta, p.hi - delta)


def shifted(graph: StepGraph | Sequence[Piece], delta: float) -> StepGraph | Sequence[Piece]:
    """``graph`` seen in the rate ``w`` of an element whose true rate is ``w + delta`` (:class:`Shifted`)."""
    if delta == 0:
        return graph
    if isinstance(graph, StepGraph):
        return Shifted(graph, delta)
    return Pieces(_shift_piece(p, delta) for p in graph)


def as_step_graph(graph: StepGraph | Sequence[Piece]) -> StepGraph:
    """``graph`` itself if it is a :class:`StepGraph`, else its pieces as :class:`Pieces`."""
    return graph if isinstance(graph, StepGraph) else Pieces(graph)
