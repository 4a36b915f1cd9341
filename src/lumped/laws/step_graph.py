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

__all__ = ["Piece", "StepGraph", "Pieces", "LawGraph", "as_step_graph", "free_piece", "rigid_piece", "bingham_band"]

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
    """

    __slots__ = ()
    is_piecewise: ClassVar[bool] = True

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

    def same(self, old: object, new: object) -> bool:
        if not isinstance(old, tuple):
            return False
        scale = abs(new[1]) + abs(old[1]) + 1e-300  # type: ignore[index]
        return abs(new[1] - old[1]) <= 8 * _EPS * scale  # type: ignore[index]


def as_step_graph(graph: StepGraph | Sequence[Piece]) -> StepGraph:
    """``graph`` itself if it is a :class:`StepGraph`, else its pieces as :class:`Pieces`."""
    return graph if isinstance(graph, StepGraph) else Pieces(graph)
