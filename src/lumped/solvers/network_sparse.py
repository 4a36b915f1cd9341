"""The compiled step for any network: the merged system as a variable band (``_network_sparse.h``).

Loops through the ground (a chain of blocks each on a friction contact to
the floor), friction between masses, elements joined to driven points: the
one-step problem of :mod:`lumped.solvers.network_step` with its active-set
iteration (warm start, mode test or a contact's rule, scales, cycle
handling, bound: ``_network_active_set.h``'s, one C home for both compiled
steps) and, with the modes fixed, the merged system (rigid clusters merged,
``merged_system.assemble``) factorised as an envelope LDL^T in an ordering
of the masses fixed once per network (:func:`ordering`): file order when the
elements join each mass to its neighbours in the file (a chain:
tridiagonal, so a step is O(N)), else reverse Cuthill-McKee.  The rigid
elements' forces follow leaf to root of the rigid forest.

What it runs (:func:`ineligible`): elements with a ``kernel_form`` (point 9 of
:class:`~lumped.laws.element.Element`) and friction contacts whose law has a
kernel form (``SlipLaw.kernel_form``, :class:`~lumped.laws.StribeckLaw`):
a linear slip curve (code 0: static above kinetic, a viscous part) or a
Stribeck fall (codes 1 to 3: exponential, gaussian, rational decay), whose
slip branches are linearised in each iteration as the Python step's
:class:`~lumped.laws.step_graph.CurveSlipGraph` is (``_network_curve.h``;
its modes carry a point, the marching array ``points``: :func:`python_modes`,
:func:`store_modes` hand them to and from a step left to Python), drivers at any velocity history (the rate shift of
``backward_euler_network._shifts``, tabulated per block), at most one
rigid-capable element between any two points.  A step whose rigid elements
close a loop (two stuck masses joined by a stuck contact: forces not unique)
is left to the Python step, and the march returns to C after it
(:func:`lumped.solvers.backward_euler_network.march` counts those steps).

The numbers are the Python step's up to the rounding of one linear solve
(``tests/test_network_banded.py``).
"""

from __future__ import annotations

from collections import deque
from typing import NamedTuple

import numpy as np

from lumped.laws.step_graph import _CYCLE, SLIP_BACK, SLIP_FORWARD, STICK
from lumped.model.network import Network, listed
from lumped.solvers import network_compiled as forest
from lumped.solvers.network_step import StepError, StepSolution, default_bound, unsettled

__all__ = [
    "PATH",
    "POINT_WIDTH",
    "SparsePlan",
    "ineligible",
    "march_block",
    "ordering",
    "plan",
    "points",
    "python_modes",
    "solve_graphs",
    "store_modes",
]

#: The trajectory's ``solver`` when this step ran it.
PATH = "compiled-banded"
#: The kind code of a friction contact with a linear slip curve (``FRICTION``, ``_network_elements.h``).
_FRICTION = 6
#: A Stribeck contact's kind code is ``_FRICTION`` plus its decay code 1 to 3 (``STRIBECK - 1 + code``).
_STRIBECK = range(_FRICTION + 1, _FRICTION + 4)
#: The values per element of the marching array ``points`` (``_network_curve.h``'s ``POINT_WIDTH``:
#: ``w, f``, the count of earlier points, their ``w`` s and ``f`` s; the binding checks its size).
POINT_WIDTH = 3 + 2 * _CYCLE


class SparsePlan(NamedTuple):
    """The arrays the C step reads (``sparse_block``'s ``topology`` without the inertias, scales, loads).

    ``at_pos``: the mass at each place of the ordering; ``inc_start``,
    ``inc_el``: the elements at each point (masses, then the ground);
    ``driven``, ``driver``, ``sign``: :meth:`~lumped.model.network.Network.driven`, an entry per
    element and driven point it is joined to.
    """

    kind: np.ndarray
    par: np.ndarray
    first: np.ndarray
    second: np.ndarray
    at_pos: np.ndarray
    inc_start: np.ndarray
    inc_el: np.ndarray
    driven: np.ndarray
    driver: np.ndarray
    sign: np.ndarray


def _form(el: object) -> tuple[int, tuple[float, ...], bool] | None:
    """``(code, parameters, rigid_pieces)`` of an element as the C step reads it, or ``None``."""
    form = el.kernel_form()  # type: ignore[attr-defined]
    if form is not None:
        return form.code, tuple(form.parameters), bool(form.rigid_pieces)
    law = el.slip_law()  # type: ignore[attr-defined]
    if law is None or law.kernel_form() is None:
        return None
    code, parameters = law.kernel_form()
    if code != 0:
        return _FRICTION + code, tuple(float(p) for p in parameters), True
    pieces = law.pieces()
    if pieces is None or len(pieces) != 1:
        return None
    return _FRICTION, (float(law.static), float(pieces[0].a), float(pieces[0].b)), True


def ineligible(net: Network) -> str | None:
    """Why the sparse step cannot run ``net``, or ``None`` if it can."""
    if forest.KERNEL != "compiled":
        return "the compiled network kernel was not built"
    forms = [_form(el) for el in net.elements]
    odd = [el for el, form in zip(net.elements, forms) if form is None]
    if odd:
        law = odd[0].slip_law()
        what = "has a slip curve the compiled step does not know" if law is not None else "is not piecewise linear"
        return f"element {odd[0].name!r} {what}"
    first, second = net.incidence()
    pairs: dict[tuple[int, int], list[int]] = {}
    for e, form in enumerate(forms):
        if form[2]:  # type: ignore[index]
            pairs.setdefault((min(first[e], second[e]), max(first[e], second[e])), []).append(e)
    for els in pairs.values():
        if len(els) > 1:
            return f"elements {listed([net.elements[e].name for e in els])} are in parallel and can be rigid"
    return None


def _neighbours(n_mass: int, first: np.ndarray, second: np.ndarray) -> list[set[int]]:
    out: list[set[int]] = [set() for _ in range(n_mass)]
    for a, b in zip(first.tolist(), second.tolist()):
        if a < n_mass and b < n_mass and a != b:
            out[a].add(b)
            out[b].add(a)
    return out


def ordering(n_mass: int, first: np.ndarray, second: np.ndarray) -> np.ndarray:
    """The masses in the order of the merged system's unknowns: file order if no element joins
    masses more than one apart in the file (a chain: tridiagonal), else reverse Cuthill-McKee
    (each component breadth first from a mass of least degree, neighbours by degree, reversed)."""
    joined = (first < n_mass) & (second < n_mass)
    if not joined.any() or int(np.abs(first[joined] - second[joined]).max()) <= 1:
        return np.arange(n_mass, dtype=np.int64)
    adjacent = _neighbours(n_mass, first, second)
    degree = [len(a) for a in adjacent]
    done = [False] * n_mass
    order: list[int] = []
    for start in sorted(range(n_mass), key=degree.__getitem__):
        if done[start]:
            continue
        done[start], queue = True, deque([start])
        while queue:
            p = queue.popleft()
            order.append(p)
            for q in sorted(adjacent[p], key=degree.__getitem__):
                if not done[q]:
                    done[q] = True
                    queue.append(q)
    return np.array(order[::-1], dtype=np.int64)


def plan(net: Network) -> SparsePlan:
    """The C step's arrays for ``net`` (which :func:`ineligible` accepts)."""
    first, second = net.incidence()
    n_mass, n_el = len(net.masses), len(net.elements)
    forms = [_form(el) for el in net.elements]
    par = np.zeros((n_el, 4))
    for e, form in enumerate(forms):
        par[e, : len(form[1])] = form[1]  # type: ignore[index]
    points = np.concatenate([first, second])
    by_point = np.argsort(points, kind="stable")
    inc_start = np.searchsorted(points[by_point], np.arange(n_mass + 2))
    driven = net.driven()
    as64 = forest._int64
    return SparsePlan(
        as64([form[0] for form in forms]),  # type: ignore[index]
        par,
        as64(first),
        as64(second),
        ordering(n_mass, first, second),
        as64(inc_start),
        as64(by_point % max(n_el, 1)),
        as64([d.element for d in driven]),
        as64([d.driver for d in driven]),
        np.array([d.sign for d in driven], dtype=float),
    )


def _topology(topology: SparsePlan, inertia: np.ndarray, sigma: np.ndarray, loaded: np.ndarray) -> tuple:
    t = topology
    return (
        t.kind,
        t.par,
        t.first,
        t.second,
        t.at_pos,
        t.inc_start,
        t.inc_el,
        inertia,
        sigma,
        loaded,
        t.driven,
        t.driver,
        t.sign,
    )


def march_block(
    topology: SparsePlan,
    inertia: np.ndarray,
    sigma: np.ndarray,
    loaded: np.ndarray,
    marching: tuple[np.ndarray, ...],
    record: tuple[np.ndarray, ...],
    table: np.ndarray,
    means: np.ndarray,
    dt: float,
    steps: tuple[int, int, int, int],
) -> None:
    """Advance steps ``n_first..n_last`` in C (``steps = (n_first, n_last, n_steps, save_every)``).

    As :func:`lumped.solvers.network_compiled.march_block`, with ``marching = (x, v, state, modes, rest,
    counters, points)`` (``points``: :func:`points`, the Stribeck contacts' warm start), ``record = (t, x,
    v, force, state, rigid)`` and ``means`` (steps, drivers) each driver's mean velocity over each step (a driven element's
    rate shift is the sum of ``sign * mean`` over its entries, as ``backward_euler_network._shifts``);
    ``counters[2] = 3`` stops the block at step ``counters[1]``, whose rigid elements close a loop (the
    caller runs that step in Python and calls again from the next).
    """
    _sparse_block(
        _topology(topology, inertia, sigma, loaded),
        marching,
        record,
        np.ascontiguousarray(table, dtype=float),
        np.ascontiguousarray(means, dtype=float),
        dt,
        *steps,
        means.shape[1],
    )


def points(net: Network) -> np.ndarray:
    """The marching array of the Stribeck contacts' points, ``(elements, POINT_WIDTH)``, zero (none set)."""
    return np.zeros((len(net.elements), POINT_WIDTH))


def python_modes(topology: SparsePlan, modes: np.ndarray, points: np.ndarray) -> list | None:
    """The C step's modes as the Python step's warm start (``None`` before the first step): a Stribeck
    contact's slip mode is :class:`~lumped.laws.step_graph.CurveSlipGraph`'s point ``(direction, w, f,
    sigma, before)`` (``sigma`` is not read from an old mode: 0)."""
    if (modes < 0).any():
        return None
    out: list = modes.tolist()
    for e in np.flatnonzero(np.isin(topology.kind, _STRIBECK) & (modes != STICK)).tolist():
        row, count = points[e], int(points[e, 2])
        before = tuple(zip(row[3 : 3 + count].tolist(), row[3 + _CYCLE : 3 + _CYCLE + count].tolist()))
        out[e] = (1.0 if modes[e] == SLIP_FORWARD else -1.0, float(row[0]), float(row[1]), 0.0, before)
    return out


def store_modes(python: list, modes: np.ndarray, points: np.ndarray) -> None:
    """The Python step's settled modes into the C step's ``modes`` and ``points`` (in place)."""
    for e, mode in enumerate(python):
        if not isinstance(mode, tuple):
            modes[e] = mode
            continue
        direction, w, f, _, before = mode
        modes[e] = SLIP_FORWARD if direction > 0 else SLIP_BACK
        points[e] = 0.0
        points[e, :3] = w, f, len(before)
        for j, (bw, bf) in enumerate(before):
            points[e, 3 + j], points[e, 3 + _CYCLE + j] = bw, bf


def solve_graphs(
    topology: SparsePlan,
    inertia: np.ndarray,
    sigma: np.ndarray,
    graphs: list,
    rhs: np.ndarray,
    delta: np.ndarray,
) -> StepSolution | None:
    """One step problem with the given graphs (each shifted by ``delta``), in C: the initial forces'
    problem.  ``None`` if its rigid elements close a loop (the Python step then solves it).

    Raises
    ------
    StepError
        If the iteration does not settle.
    """
    n_el = len(graphs)
    counts = np.fromiter(map(len, graphs), dtype=np.int64, count=n_el)
    pieces = np.zeros((n_el, 5, 5))  # every graph's pieces in one array op (a loop over 1e5 elements took 1 s)
    rows = np.repeat(np.arange(n_el), counts), np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    pieces[rows] = np.array([tuple(p) for graph in graphs for p in graph], dtype=float).reshape(-1, 5)
    v, w, f = np.empty(inertia.size), np.empty(n_el), np.empty(n_el)
    modes, rigid = np.full(n_el, -1, dtype=np.int64), np.zeros(n_el, dtype=bool)
    topo = _topology(topology, inertia, sigma, np.empty(0, dtype=np.int64))
    iterations = _sparse_solve(
        topo,
        pieces,
        counts,
        np.ascontiguousarray(rhs, dtype=float),
        np.ascontiguousarray(delta, dtype=float),
        (v, w, f, modes, rigid.view(np.uint8)),
    )
    if iterations < 0:
        return None
    if iterations == 0:
        raise StepError(unsettled(default_bound(n_el)))
    return StepSolution(v, w, f, modes.tolist(), rigid.tolist(), iterations)


if forest.KERNEL == "compiled":
    from lumped.kernels._network_kernel import sparse_block as _sparse_block  # type: ignore[import-not-found]
    from lumped.kernels._network_kernel import sparse_solve as _sparse_solve  # type: ignore[import-not-found]
