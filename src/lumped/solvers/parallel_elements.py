"""Elements in parallel that can be rigid, stepped as one element: the sum of their step graphs.

Elements between the same two points have one rate ``w`` and add their
forces, so together they are one element whose step graph is the sum of
theirs: at each rate, the sum of their forces (a band where some are rigid
there).  Two Coulomb pads of ``tau1`` and ``tau2`` are one pad of ``tau1 +
tau2``.  The one-step problem (:mod:`lumped.solvers.network_step`) takes a
group of parallel elements that can be rigid and whose graphs break at the
same rates (Bingham pads: rigid at 0, either way round) as that one element.
Left to the iteration one by one, such elements make a loop of rigid pieces
whose split is decided by the rounding of their bands' edges: where the
group's force is exactly at the edge of its band (the group sticking at its
summed threshold) one element's force comes out a few ulps past its own
threshold in every mode, and the modes cycle.  Summed, the group's motion
is that of the one element bit for bit (the same pieces, the same solve).

With the step solved, :func:`expand` gives each element its piece, rate and
force: on a free piece of the sum each its own ``a + b w``; on a rigid piece
the elements free at that rate their own value and the rigid ones the rest,
split as a loop of rigid elements is (:func:`~lumped.solvers.loop_forces.core_forces`:
the least-norm split and each one's interval of admissible forces).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from lumped.laws.step_graph import Piece, Pieces, StepGraph, free_piece, rigid_piece
from lumped.solvers.loop_forces import CoreForces, core_forces

__all__ = ["Expanded", "Group", "Reduced", "expand", "reduce", "summed"]


class Group(NamedTuple):
    """Parallel ``elements`` (the first one's orientation; ``flip[k]`` if element
    ``k`` is reversed) stepped as one whose pieces come from ``parts``: for each
    piece of the sum, each element's piece index."""

    elements: tuple[int, ...]
    flip: tuple[bool, ...]
    parts: tuple[tuple[int, ...], ...]


class Reduced(NamedTuple):
    """The problem with each group one element: points, graphs, scales, warm start,
    and for each reduced element its ``group`` (``None`` for an element alone) and
    original ``index``."""

    first: list[int]
    second: list[int]
    graphs: list[StepGraph]
    sigma: np.ndarray
    modes: list | None
    groups: list[Group | None]
    index: list[int]


def reduce(
    first: Sequence[int], second: Sequence[int], graphs: Sequence[StepGraph], sigma: np.ndarray, modes: Sequence | None
) -> Reduced | None:
    """The problem with each group of parallel rigid-capable elements summed, or ``None`` if there is none.

    Free elements beside a group stay elements of their own, as beside one
    element: the group is then one element of the summed graph bit for bit.
    """
    pairs: dict[tuple[int, int], list[int]] = {}
    for e, g in enumerate(graphs):
        if g.is_piecewise and g.monotone and any(p.rigid for p in g):  # type: ignore[attr-defined]
            pairs.setdefault((min(first[e], second[e]), max(first[e], second[e])), []).append(e)
    sums = {}
    for els in pairs.values():
        if len(els) > 1:
            els.sort()
            flip = tuple(first[k] != first[els[0]] for k in els)
            graph, parts = summed([_reflected(graphs[k]) if f else list(graphs[k]) for k, f in zip(els, flip)])  # type: ignore[arg-type]
            if graph:  # else no rate suits them all: the step's loop check names them
                sizes = [len(graphs[k]) for k in els]  # type: ignore[arg-type]
                parts = tuple(tuple(n - 1 - i if f else i for i, n, f in zip(part, sizes, flip)) for part in parts)
                sums[els[0]] = (graph, Group(tuple(els), flip, parts))
    if not sums:
        return None
    members = {e for _, group in sums.values() for e in group.elements}
    out = Reduced([], [], [], np.empty(0), [] if modes is not None else None, [], [])
    for e in range(len(graphs)):
        if e in members and e not in sums:
            continue
        out.first.append(first[e])
        out.second.append(second[e])
        out.index.append(e)
        if e not in sums:
            out.graphs.append(graphs[e])
            out.groups.append(None)
            if out.modes is not None:
                out.modes.append(modes[e])  # type: ignore[index]
            continue
        graph, group = sums[e]
        out.graphs.append(graph)
        out.groups.append(group)
        if out.modes is not None:
            held = tuple(modes[k] for k in group.elements)  # type: ignore[index]
            out.modes.append(group.parts.index(held) if held in group.parts else graph.initial_mode())
    return out._replace(sigma=sigma[out.index])  # parallel elements see the same stiffness


def _reflected(pieces: Sequence[Piece]) -> list[Piece]:
    """The graph of a reversed element: ``(w, f)`` to ``(-w, -f)``, its pieces in the new order."""
    out = []
    for p in reversed(pieces):
        out.append(rigid_piece(-p.a, -p.hi, -p.lo) if p.rigid else free_piece(-p.a, p.b, -p.hi, -p.lo))
    return out


def summed(graphs: Sequence[Sequence[Piece]]) -> tuple[Pieces, tuple[tuple[int, ...], ...]]:
    """The sum of step graphs with the same pieces' breakpoints (one rate, forces added)
    and, for each of its pieces, the piece of each graph it is made of; empty if their
    breakpoints differ.

    Piece ``k`` of the sum adds the graphs' pieces ``k``: a free piece their
    ``a`` and ``b`` on the common range, a rigid one their bands at the
    common rate (each sum correctly rounded, :func:`math.fsum`).  Graphs whose
    breakpoints differ (a string's reach beside a Bingham dashpot's 0) are
    left to the step as elements of their own, a loop of rigid elements where
    both are rigid.
    """
    shapes = {tuple((p.rigid, p.a) if p.rigid else (p.rigid, p.lo, p.hi) for p in g) for g in graphs}
    if len(shapes) != 1:
        return Pieces(()), ()
    pieces = []
    for column in zip(*graphs):
        p = column[0]
        if p.rigid:
            pieces.append(rigid_piece(p.a, math.fsum(q.lo for q in column), math.fsum(q.hi for q in column)))
        else:
            pieces.append(free_piece(math.fsum(q.a for q in column), math.fsum(q.b for q in column), p.lo, p.hi))
    return Pieces(pieces), tuple((k,) * len(graphs) for k in range(len(pieces)))


class Expanded(NamedTuple):
    """Each original element's mode, rate, force, rigidity and interval of admissible forces."""

    modes: list
    w: np.ndarray
    f: np.ndarray
    rigid: list[bool]
    low: np.ndarray
    high: np.ndarray


def expand(
    red: Reduced,
    n_el: int,
    graphs: Sequence[StepGraph],
    first: Sequence[int],
    second: Sequence[int],
    ground: int,
    sol: tuple,
) -> Expanded:
    """Each element's share of the reduced solution ``sol`` (``modes, w, f, rigid, low, high``:
    ``low``, ``high`` the reduced elements' intervals, or ``None``)."""
    modes_r, w_r, f_r, rigid_r, low_r, high_r = sol
    modes: list = [None] * n_el
    w, f = np.zeros(n_el), np.zeros(n_el)
    low, high = np.zeros(n_el), np.zeros(n_el)
    rigid = [False] * n_el
    for r, e in enumerate(red.index):
        group = red.groups[r]
        span = (f_r[r], f_r[r]) if low_r is None else (low_r[r], high_r[r])
        if group is None:
            modes[e], w[e], f[e], rigid[e] = modes_r[r], w_r[r], f_r[r], rigid_r[r]
            low[e], high[e] = span
            continue
        part = group.parts[modes_r[r]]
        held: list[int] = []
        carried = f_r[r]
        for k, i, flip in zip(group.elements, part, group.flip):
            p = graphs[k][i]  # type: ignore[index]
            modes[k], w[k], rigid[k] = i, -w_r[r] if flip else w_r[r], p.rigid
            if p.rigid:
                held.append(k)
                continue
            f[k] = low[k] = high[k] = p.a + p.b * w[k]
            carried -= -f[k] if flip else f[k]
        if held:  # the group's interval, less what its free elements carry
            bounds = (carried, span[0] - f_r[r] + carried, span[1] - f_r[r] + carried)
            _share(
                held,
                graphs,
                dict(zip(group.elements, part)),
                group.elements[0],
                (first, second, ground),
                bounds,
                (f, low, high),
            )
    return Expanded(modes, w, f, rigid, low, high)


def _share(
    held: list[int],
    graphs: Sequence[StepGraph],
    pick: dict[int, int],
    lead: int,
    points: tuple[Sequence[int], Sequence[int], int],
    carried: tuple[float, float, float],
    out: tuple[np.ndarray, np.ndarray, np.ndarray],
) -> None:
    """Split what the group's rigid elements ``held`` (on pieces ``pick``) carry along the
    element ``lead`` (``carried``: the force, and its least and greatest admissible values) as a
    loop of rigid elements: the least-norm split and each one's interval, into ``out = (f, low,
    high)``."""
    first, second, ground = points
    f, low, high = out
    bands = {k: (graphs[k][pick[k]].lo, graphs[k][pick[k]].hi) for k in held}  # type: ignore[index]
    size = max(max(first), max(second), ground) + 1

    def split(force: float) -> CoreForces:
        gap = [0.0] * size
        gap[second[lead]] += force
        gap[first[lead]] -= force
        return core_forces(held, first, second, bands, gap, ground, ranges=True)

    one = split(carried[0])
    for k, value, lo, hi in zip(one.elements, one.force, one.low, one.high):  # type: ignore[arg-type]
        f[k], low[k], high[k] = min(max(value, bands[k][0]), bands[k][1]), lo, hi
    if carried[1] != carried[0] or carried[2] != carried[0]:  # the group's own force is not unique
        least, most = split(carried[1]), split(carried[2])
        for k, a, b, c, d in zip(held, least.low, least.high, most.low, most.high):  # type: ignore[arg-type]
            low[k], high[k] = min(a, c, low[k]), max(b, d, high[k])
