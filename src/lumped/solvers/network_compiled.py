"""The compiled step for networks whose link graph is a forest or has one loop (``_network_kernel.c``).

The *link graph* has the masses and the ground as points and one link per
pair of points joined by at least one element (parallel elements share a
link).  When it is a forest, or a forest and one more link closing one loop
(a ring of masses through the ground: the *chord* of ``_network_loop.h``,
one rank-one update of the forest's solve, and the least-norm split with
its intervals when the loop is rigid all round; every element on the loop
that can be rigid must then be a Bingham element), and every element is piecewise linear with a C
copy of its step graph (a ``kernel_form``, point 9 of
:class:`~lumped.laws.element.Element`: every kind but the law elements,
:class:`~lumped.laws.dashpot_elements.Monotone` and Herschel-Bulkley), the one-step problem
with its modes fixed is solved by elimination along the forest, leaf to
root, and back-substitution: a free link adds its conductance to its parent,
a rigid link merges its child into the parent with a fixed rate offset.
That is Gaussian elimination of the merged system of
:mod:`lumped.solvers.network_step` in an order that creates no fill-in, so a step
costs O(masses + elements); the C loop runs the whole march (step graphs,
active-set iteration, state updates, saving), block by block.

The active-set iteration, its warm start, its mode test, its cycle handling
and its bound are those of :func:`lumped.solvers.network_step.solve_step`, and the
step graphs those of :mod:`lumped.laws.spring_elements` and
:mod:`lumped.laws.dashpot_elements`, repeated in C by kind code.  Only the rounding of the linear solve differs from the Python step
(a band or dense factorisation there); ``tests/test_network_kernel.py``
bounds the difference.  For the paper's one-mass system both reduce to
Algorithm 1's operations in Algorithm 1's order.
"""

from __future__ import annotations

import os
from collections import deque
from typing import NamedTuple

import numpy as np

from lumped.laws.step_graph import Piece
from lumped.model.network import Network, listed, rigid_loop
from lumped.solvers import network_step as step
from lumped.solvers.network_step import StepError, StepSolution, default_bound, unsettled

__all__ = ["KERNEL", "Plan", "ineligible", "plan", "has_chord", "solve_graphs", "march_block", "settings"]

#: ``"compiled"`` when ``_network_kernel.c`` was built (and ``LUMPED_PURE_PYTHON``
#: is unset), else ``"python"``: the Python step then runs every network.
KERNEL = "python"
if os.environ.get("LUMPED_PURE_PYTHON", "") in ("", "0"):
    try:
        from lumped.kernels._network_kernel import network_block as _network_block  # type: ignore[import-not-found]
        from lumped.kernels._network_kernel import network_settings as _network_settings  # type: ignore[import-not-found]
        from lumped.kernels._network_kernel import network_solve as _network_solve  # type: ignore[import-not-found]

        KERNEL = "compiled"
    except ImportError:  # no C compiler at install: the Python step, as before
        pass


def settings() -> None:
    """Hand the iteration's ``SIGMA_SCALES``, ``DUAL_SWEEPS`` and ``BOUND`` (:mod:`lumped.solvers.network_step`)
    to the compiled step: one definition for both (done at import; again after changing them)."""
    if KERNEL == "compiled":
        _network_settings(
            tuple(float(s) for s in step.SIGMA_SCALES),
            tuple(int(n) for n in step.DUAL_SWEEPS),
            tuple(int(n) for n in step.BOUND),
        )


settings()


class Plan(NamedTuple):
    """The arrays the C loop reads: elements by kind code and the spanning forest.

    ``order`` lists the points root first (breadth first from the ground,
    then from each mass not connected to it); ``parent[p]`` is ``-1`` at a
    root; the elements of the link from ``p`` to its parent are
    ``link_el[link_start[p]:link_start[p + 1]]``, each with ``sign`` +1 if
    ``p`` is its ``second`` point.
    """

    kind: np.ndarray
    par: np.ndarray
    first: np.ndarray
    second: np.ndarray
    order: np.ndarray
    parent: np.ndarray
    link_start: np.ndarray
    link_el: np.ndarray
    sign: np.ndarray


def ineligible(net: Network) -> str | None:
    """Why the compiled step cannot run ``net``, or ``None`` if it can."""
    if KERNEL != "compiled":
        return "the compiled network kernel was not built"
    if net.drivers:
        return "the network has driven points"
    forms = [el.kernel_form() for el in net.elements]  # the element contract, point 9
    odd = [el.name for el, form in zip(net.elements, forms) if form is None]
    if odd:
        return f"element {odd[0]!r} is not piecewise linear"
    links = _links(net)
    for els in links.values():
        if sum(forms[e].rigid_pieces for e in els) > 1:  # type: ignore[union-attr]
            return f"elements {listed([net.elements[e].name for e in els])} are in parallel and more than one has rigid pieces"
    chord = _chord(net, links)
    if chord is None:
        return None
    index = net.point_index()
    pairs = [(pair, net.elements[els[0]]) for pair, els in links.items() if pair != chord]
    second = rigid_loop(index, pairs)
    if second:
        return f"the links of {listed([el.name for el in second])} close a second loop"
    looped = [e for pair in _cycle(net, links, chord) for e in links[pair]]
    odd = [net.elements[e].name for e in looped if forms[e].rigid_pieces and forms[e].code != _BINGHAM]  # type: ignore[union-attr]
    if odd:
        return f"element {odd[0]!r} on the loop of links can be rigid at a rate other than 0"
    return None


#: The kind code of a Bingham element (``_network_elements.h``): rigid only at the rate 0.
_BINGHAM = 2


def _chord(net: Network, links: dict[tuple[int, int], list[int]]) -> tuple[int, int] | None:
    """The link that closes the link graph's first loop (in link order), or ``None`` for a forest."""
    loop = rigid_loop(net.point_index(), [(pair, net.elements[els[0]]) for pair, els in links.items()])
    if not loop:
        return None
    first, second = net.incidence()
    e = net.elements.index(loop[-1])
    return (min(first[e], second[e]), max(first[e], second[e]))


def _cycle(net: Network, links: dict[tuple[int, int], list[int]], chord: tuple[int, int]) -> list[tuple[int, int]]:
    """The links of the loop that ``chord`` closes in the spanning forest of :func:`plan`."""
    order, parent, via = _forest(len(net.masses) + 1, {k: v for k, v in links.items() if k != chord})
    up = {}
    for p in chord:
        path, node = [], p
        while parent[node] >= 0:
            path.append(node)
            node = parent[node]
        up[p] = path + [node]
    shared = set(up[chord[0]]) & set(up[chord[1]])
    out = [chord]
    for p in chord:
        for node in up[p]:
            if node in shared:
                break
            out.append((min(node, parent[node]), max(node, parent[node])))
    return out


def _links(net: Network) -> dict[tuple[int, int], list[int]]:
    """Element indices by unordered pair of points, in element order."""
    first, second = net.incidence()
    links: dict[tuple[int, int], list[int]] = {}
    for e, (a, b) in enumerate(zip(first.tolist(), second.tolist())):
        links.setdefault((min(a, b), max(a, b)), []).append(e)
    return links


def _forest(n_points: int, links: dict[tuple[int, int], list[int]]) -> tuple[list[int], list[int], list[list[int]]]:
    """Breadth-first order, parent and link elements of each point (ground first)."""
    adjacent: list[list[tuple[int, list[int]]]] = [[] for _ in range(n_points)]
    for (a, b), els in links.items():
        adjacent[a].append((b, els))
        adjacent[b].append((a, els))
    order, parent, via = [], [-1] * n_points, [[] for _ in range(n_points)]
    done = [False] * n_points
    for root in [n_points - 1, *range(n_points - 1)]:
        if done[root]:
            continue
        done[root], queue = True, deque([root])
        while queue:
            p = queue.popleft()
            order.append(p)
            for q, els in adjacent[p]:
                if not done[q]:
                    done[q], parent[q], via[q] = True, p, els
                    queue.append(q)
    return order, parent, via


def _int64(values: object) -> np.ndarray:
    return np.ascontiguousarray(values, dtype=np.int64)


def plan(net: Network) -> Plan:
    """The compiled loop's arrays for ``net`` (which :func:`ineligible` accepts).

    A chord (the link that closes the one loop of links, ``_network_loop.h``)
    has its elements after the forest's in ``link_el``, each with ``sign`` +1
    if its ``second`` point is the chord's first element's ``second``.
    """
    first, second = net.incidence()
    links = _links(net)
    chord = _chord(net, links)
    forest = links if chord is None else {k: v for k, v in links.items() if k != chord}
    order, parent, via = _forest(len(net.masses) + 1, forest)
    link_start = np.cumsum([0] + [len(els) for els in via])
    sign = np.zeros(len(net.elements))
    for p, els in enumerate(via):
        for e in els:
            sign[e] = 1.0 if second[e] == p else -1.0
    tail = [] if chord is None else links[chord]
    for e in tail:
        sign[e] = 1.0 if second[e] == second[tail[0]] else -1.0
    forms = [el.kernel_form() for el in net.elements]
    par = np.zeros((len(net.elements), 4))
    for e, form in enumerate(forms):
        par[e, : len(form.parameters)] = form.parameters  # type: ignore[union-attr]
    return Plan(
        _int64([form.code for form in forms]),  # type: ignore[union-attr]
        par,
        _int64(first),
        _int64(second),
        _int64(order),
        _int64(parent),
        _int64(link_start),
        _int64([e for els in via for e in els] + tail),
        sign,
    )


def has_chord(topology: Plan) -> bool:
    """True if the plan closes one loop of links (its elements follow the forest's)."""
    return int(topology.link_start[-1]) < topology.link_el.size


def march_block(
    topology: Plan,
    inertia: np.ndarray,
    sigma: np.ndarray,
    loaded: np.ndarray,
    marching: tuple[np.ndarray, ...],
    record: tuple[np.ndarray, ...],
    table: np.ndarray,
    dt: float,
    steps: tuple[int, int, int, int],
) -> None:
    """Advance steps ``n_first..n_last`` in C (``steps = (n_first, n_last, n_steps, save_every)``).

    ``marching = (x, v, state, modes, rest, counters)`` is updated in place
    (``modes`` -1 for the middle piece; ``counters = (row, bad_step,
    bad_kind, most_iterations)``); saved rows go to ``record = (t, x, v,
    force, state, rigid, low, high)`` (``low``, ``high``: the admissible
    forces, empty arrays unless the plan has a chord); ``table`` holds the
    loads on the masses ``loaded`` for each step of the block.
    """
    _network_block((*topology, inertia, sigma, loaded), marching, record, np.ascontiguousarray(table), dt, *steps)


def solve_graphs(
    topology: Plan, inertia: np.ndarray, sigma: np.ndarray, graphs: list[tuple[Piece, ...]], rhs: np.ndarray
) -> StepSolution:
    """One step problem with the given graphs, in C (the initial forces' problem).

    The same problem, iteration and result as :func:`lumped.solvers.network_step.solve_step`
    from the middle pieces.

    Raises
    ------
    StepError
        If the iteration does not settle.
    """
    pieces = np.zeros((len(graphs), 5, 5))
    for e, graph in enumerate(graphs):
        pieces[e, : len(graph)] = graph
    counts = np.array([len(g) for g in graphs], dtype=np.int64)
    n_el = len(graphs)
    v, w, f = np.empty(inertia.size), np.empty(n_el), np.empty(n_el)
    modes, rigid = np.full(n_el, -1, dtype=np.int64), np.zeros(n_el, dtype=bool)
    topo = (*topology, inertia, sigma, np.empty(0, dtype=np.int64))
    iterations = _network_solve(
        topo, pieces, counts, np.ascontiguousarray(rhs, dtype=float), (v, w, f, modes, rigid.view(np.uint8))
    )
    if iterations == 0:
        raise StepError(unsettled(default_bound(n_el)))
    return StepSolution(v, w, f, modes.tolist(), rigid.tolist(), iterations)
