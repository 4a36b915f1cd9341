"""The masses that rigid elements merge when those elements close loops.

With the modes of an iteration fixed, every element on a rigid piece fixes
the rate between its points, ``v_second = v_first + a``, so the points it
joins move as one unknown (:mod:`lumped.solvers.network_step`).  When the rigid
elements form a forest each point's offset from its cluster's root is the sum
of the rates along the one path to it.  When they close a loop, the loop's
rates must also agree: the rates of sticking elements (0) always do, but an
iteration may take a string taut (rate ``(L - e)/dt > 0``) beside a sticking
dashpot, or a dashpot locked at ``v_lock`` beside one that sticks, and no
velocities meet both.  Some element of such a loop is on the wrong piece.

:func:`loop_clusters` merges the points by union-find, taking first the
elements in ``priority``, then the *hard* rigid pieces (one edge of their
band infinite: a taut string, a locked dashpot), then the sticking ones, and
reports each rigid element whose loop disagrees (a *clash*) with the rate its
points would then have.  The step releases a clashing element whose band is
finite on the side of that rate (its force set to that edge of the band, so
that its mode test moves it onto the free piece beside it); a clashing
element whose band is infinite on that side is tried again with priority, so
that another element of the loop clashes instead.  A loop of rigid pieces
whose rates disagree and none of which can give way has no velocities at
all: the step then reports those elements (:class:`~lumped.solvers.network_step.StepError`).
No network of this package's elements reaches that (every string starts
within its length and every lock within its rate, so the velocities 0 meet
every constraint); a step of hand-made graphs can.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

from lumped.laws.step_graph import Piece
from lumped.numerics.union_find import UnionFind

__all__ = ["Clusters", "Merged", "loop_clusters", "loop_merge", "agrees"]

_EPS = 2.0**-52


class Clusters(NamedTuple):
    """Each point's cluster ``root`` and velocity ``offset`` from it; the ``clashes``
    as ``{element: rate its points have}``."""

    root: list[int]
    offset: list[float]
    clashes: dict[int, float]


def agrees(actual: float, rate: float, scale: float) -> bool:
    """True if a loop's ``actual`` rate is ``rate`` up to the rounding of sums of size ``scale``."""
    return abs(actual - rate) <= 8 * _EPS * scale


def loop_clusters(
    n_points: int,
    ground: int,
    rigid: Sequence[tuple[int, int, int, float, bool]],
    priority: Sequence[int] = (),
) -> Clusters:
    """Merge the points joined by ``rigid`` elements ``(e, first, second, rate, hard)``.

    The ground stays its cluster's root (offset 0).  Elements in ``priority``
    are merged first, then the hard ones, then the rest, each in the given order.
    """
    sets = UnionFind(n_points)
    find = sets.locate
    first = [r for e in priority for r in rigid if r[0] == e]
    ordered = first + [r for r in rigid if r[4] and r[0] not in priority]
    ordered += [r for r in rigid if not r[4] and r[0] not in priority]
    clashes: dict[int, float] = {}
    for e, a, b, rate, _ in ordered:
        (ra, oa), (rb, ob) = find(a), find(b)
        if ra == rb:
            if not agrees(ob - oa, rate, abs(oa) + abs(ob) + abs(rate)):
                clashes[e] = ob - oa
            continue
        if rb == ground:  # v_ra = v_ground + ob - rate - oa
            sets.attach(ra, rb, ob - rate - oa)
        else:  # v_rb = v_ra + oa + rate - ob
            sets.attach(rb, ra, oa + rate - ob)
    roots = [find(i) for i in range(n_points)]
    return Clusters([r for r, _ in roots], [o for _, o in roots], clashes)


class Merged(NamedTuple):
    """The clusters, the rigid elements released for this solve (``{e: (rate, force)}``)
    and the elements of a loop whose rates disagree and cannot give way."""

    clusters: Clusters
    released: dict[int, tuple[float, float]]
    stuck: tuple[int, ...]


def loop_merge(
    first: Sequence[int], second: Sequence[int], n_mass: int, pieces: Sequence[Piece], rigid: list[int]
) -> Merged:
    """The clusters of the ``rigid`` elements (on these ``pieces``), which close loops:
    a clash is released when it can give way, else tried again with priority."""
    edges = [(e, first[e], second[e], pieces[e].a, math.isinf(pieces[e].lo) or math.isinf(pieces[e].hi)) for e in rigid]
    priority: list[int] = []
    stuck_ever: list[int] = []
    for _ in range(len(rigid) + 1):
        found = loop_clusters(n_mass + 1, n_mass, edges, priority)
        released, stuck = {}, []
        for e, actual in found.clashes.items():
            edge = pieces[e].lo if actual < pieces[e].a else pieces[e].hi
            if math.isinf(edge):
                stuck.append(e)
            else:
                released[e] = (actual, edge)
        stuck_ever += [e for e in stuck if e not in stuck_ever]
        fresh = [e for e in stuck if e not in priority]
        if not stuck or not fresh:
            return Merged(found, released, tuple(sorted(stuck_ever)) if stuck else ())
        priority.append(fresh[0])
    return Merged(found, released, tuple(sorted(stuck_ever)))
