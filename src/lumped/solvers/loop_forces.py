"""The forces of rigid elements that close loops: one representative split and each one's admissible interval.

An element on a rigid piece of its step graph (sticking, taut, locked) fixes
its rate and takes any force in its band ``[lo, hi]`` that balances the
masses.  The step (:mod:`lumped.solvers.network_step`) finds the forces of the
rigid elements that hang in trees by peeling them leaf to root; what is left,
the *core*, is made of closed loops of rigid elements (two or more in
parallel, a ring through masses and the ground) and the paths between them.
Their forces ``f`` satisfy the momentum balance of every mass,

    sum_e B_ei f_e = g_i,     lo_e <= f_e <= hi_e,

(``g_i`` the force that mass ``i`` still needs, ``B_ei = +1`` if ``i`` is the
element's ``second`` point, ``-1`` if its ``first``), which fixes ``f`` only
up to a circulation around each loop: the set of solutions is a polytope.
This module gives

* the *representative*: the split of least Euclidean norm ``sum_e f_e^2``
  among the admissible ones (unique: a strictly convex function on a convex
  set), the one reported as ``F_<element>``.  Without bounds it is the
  current of a network of unit resistors: a load shared equally by two pads
  in parallel, ``R/2`` each, until one reaches its threshold;
* each element's *interval*: the least and the greatest of its force over
  the polytope (``force_min_<element>``, ``force_max_<element>``).

Method.  A spanning forest of the core (the ground a root) gives a particular
solution ``f0`` (the other elements, the *chords*, at 0) and, per chord, its
fundamental cycle (entries +-1); ``f = f0 + N c``.  Chords whose cycles share
an element are solved together.  A single loop (``c`` a scalar: parallel
pairs, rings) is solved in closed form: ``c`` lies in the intersection of
one interval per element and the least-norm ``c`` is the clipped minimiser of
a parabola; an element's interval is its band intersected with what the
*other* elements of the loop leave it, so that two pads under a held force
``R`` get exactly ``[max(-tau1, R - tau2), min(tau1, R + tau2)]``.  Several
coupled loops (three pads in parallel, a ladder) take the dual active-set
method of Goldfarb and Idnani (1983) for the least norm, finished by one
solve of its final active set, and a maximum flow (Edmonds-Karp) in the
residual graph of the representative for each interval.  When no split is
admissible (the modes of that iteration are wrong), the least-norm split of
the loop without bounds is returned and the iteration releases the elements
it overloads.
"""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from lumped.numerics.union_find import UnionFind

__all__ = ["CoreForces", "core_forces"]

_INF = math.inf
_EPS = 2.0**-52


class CoreForces(NamedTuple):
    """Forces of the core's ``elements``: the representative ``force``, and the
    intervals ``low``, ``high`` (``None`` unless asked for); ``feasible`` is
    False when no split lies in every band."""

    elements: list[int]
    force: list[float]
    low: list[float] | None
    high: list[float] | None
    feasible: bool


class _Core(NamedTuple):
    first: Sequence[int]
    second: Sequence[int]
    lo: dict[int, float]
    hi: dict[int, float]


def core_forces(
    elements: list[int],
    first: Sequence[int],
    second: Sequence[int],
    bands: dict[int, tuple[float, float]],
    gap: Sequence[float],
    ground: int,
    ranges: bool = False,
) -> CoreForces:
    """The representative forces of the core ``elements`` (and their intervals if ``ranges``).

    ``first``, ``second`` are the points of every element, ``bands[e]`` the
    band ``(lo, hi)`` of each core element, ``gap[i]`` the force point ``i``
    still needs from the core (the ground's is not used).
    """
    core = _Core(first, second, {e: bands[e][0] for e in elements}, {e: bands[e][1] for e in elements})
    order, parent = _spanning(elements, core, ground)
    f0 = _tree_flows(order, parent, core, {p: gap[p] for p in order if p != ground})
    tree = set(parent.values())
    columns = [_column(h, order, parent, core) for h in elements if h not in tree]
    force = {e: f0.get(e, 0.0) for e in elements}
    low = dict(force) if ranges else None
    high = dict(force) if ranges else None
    looped = _support(columns)
    feasible = all(core.lo[e] <= force[e] <= core.hi[e] for e in elements if e not in looped)
    for group in _groups(columns):
        cols = [columns[k] for k in group]
        solve = _one_loop if len(cols) == 1 else _coupled_loops
        feasible &= solve(cols, core, force, low, high)
    out = [force[e] for e in elements]
    if low is None or high is None:
        return CoreForces(elements, out, None, None, feasible)
    return CoreForces(elements, out, [low[e] for e in elements], [high[e] for e in elements], feasible)


# -- the spanning forest and the cycles -------------------------------------------
def _spanning(elements: list[int], core: _Core, ground: int) -> tuple[list[int], dict[int, int]]:
    """Breadth-first order of the core's points (the ground first) and each point's tree element."""
    adjacent: dict[int, list[tuple[int, int]]] = {}
    for e in elements:
        a, b = core.first[e], core.second[e]
        adjacent.setdefault(a, []).append((b, e))
        adjacent.setdefault(b, []).append((a, e))
    starts = ([ground] if ground in adjacent else []) + [p for p in adjacent if p != ground]
    order: list[int] = []
    parent: dict[int, int] = {}
    seen: set[int] = set()
    for start in starts:
        if start in seen:
            continue
        seen.add(start)
        queue = deque([start])
        while queue:
            p = queue.popleft()
            order.append(p)
            for q, e in adjacent[p]:
                if q not in seen:
                    seen.add(q)
                    parent[q] = e
                    queue.append(q)
    return order, parent


def _tree_flows(order: list[int], parent: dict[int, int], core: _Core, balance: dict[int, float]) -> dict[int, float]:
    """Forces of the tree elements that meet ``balance`` at every non-root point, leaf to root."""
    acc = dict(balance)
    out: dict[int, float] = {}
    for c in reversed(order):
        t = parent.get(c)
        if t is None:
            continue
        sign = 1.0 if core.second[t] == c else -1.0
        out[t] = sign * acc.get(c, 0.0)
        p = core.first[t] if sign > 0 else core.second[t]
        acc[p] = acc.get(p, 0.0) - (1.0 if core.second[t] == p else -1.0) * out[t]
    return out


def _column(h: int, order: list[int], parent: dict[int, int], core: _Core) -> dict[int, float]:
    """The fundamental cycle of chord ``h``: a unit force on ``h`` and the tree's +-1 that balance it."""
    unit = {core.second[h]: -1.0, core.first[h]: 1.0}
    column = {e: x for e, x in _tree_flows(order, parent, core, unit).items() if x != 0.0}
    column[h] = 1.0
    return column


def _support(columns: list[dict[int, float]]) -> set[int]:
    return {e for col in columns for e in col}


def _groups(columns: list[dict[int, float]]) -> list[list[int]]:
    """Chords whose cycles share an element, together (union-find)."""
    sets = UnionFind(len(columns))
    find = sets.find
    owner: dict[int, int] = {}
    for k, col in enumerate(columns):
        for e in col:
            if e in owner:
                sets.union(k, owner[e])
            else:
                owner[e] = k
    groups: dict[int, list[int]] = {}
    for k in range(len(columns)):
        groups.setdefault(find(k), []).append(k)
    return list(groups.values())


# -- one loop: closed form ------------------------------------------------------------
def _one_loop(cols: list[dict[int, float]], core: _Core, force: dict, low: dict | None, high: dict | None) -> bool:
    """Add the circulation ``c`` of one loop to ``force`` (in place): True if admissible."""
    col = cols[0]
    f0 = {e: force[e] for e in col}
    bounds = {e: _c_bounds(f0[e], n, core.lo[e], core.hi[e]) for e, n in col.items()}
    c_lo, c_hi = max(b[0] for b in bounds.values()), min(b[1] for b in bounds.values())
    c = -math.fsum(n * f0[e] for e, n in col.items()) / len(col)  # the parabola's vertex
    feasible = c_lo <= c_hi
    if feasible:
        c = min(max(c, c_lo), c_hi)
    for e, n in col.items():
        value = f0[e] + n * c
        force[e] = min(max(value, core.lo[e]), core.hi[e]) if feasible else value  # rounding only
    if low is not None and high is not None:
        for e, n in col.items():
            others_lo = max((b[0] for k, b in bounds.items() if k != e), default=-_INF)
            others_hi = min((b[1] for k, b in bounds.items() if k != e), default=_INF)
            a, b = (f0[e] + others_lo, f0[e] + others_hi) if n > 0 else (f0[e] - others_hi, f0[e] - others_lo)
            low[e], high[e] = max(a, core.lo[e]), min(b, core.hi[e])
    return feasible


def _c_bounds(f0: float, n: float, lo: float, hi: float) -> tuple[float, float]:
    """The circulations ``c`` with ``lo <= f0 + n c <= hi`` (``n`` is +-1)."""
    return (lo - f0, hi - f0) if n > 0 else (f0 - hi, f0 - lo)


# -- coupled loops: least norm by Goldfarb-Idnani, intervals by maximum flow ------------
def _coupled_loops(cols: list[dict[int, float]], core: _Core, force: dict, low: dict | None, high: dict | None) -> bool:
    """As :func:`_one_loop` for several loops that share elements."""
    edges = sorted(_support(cols))
    where = {e: i for i, e in enumerate(edges)}
    n = np.zeros((len(edges), len(cols)))
    for k, col in enumerate(cols):
        for e, x in col.items():
            n[where[e], k] = x
    f0 = np.array([force[e] for e in edges])
    lo = np.array([core.lo[e] for e in edges])
    hi = np.array([core.hi[e] for e in edges])
    c, feasible = least_norm(f0, n, lo, hi)
    values = f0 + n @ c
    for i, e in enumerate(edges):
        force[e] = min(max(float(values[i]), core.lo[e]), core.hi[e]) if feasible else float(values[i])
    if feasible and low is not None and high is not None:
        for e in edges:
            up = _max_flow(edges, core, force, e, core.first[e], core.second[e])
            down = _max_flow(edges, core, force, e, core.second[e], core.first[e])
            low[e], high[e] = max(core.lo[e], force[e] - down), min(core.hi[e], force[e] + up)
    return feasible


def least_norm(f0: np.ndarray, n: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, bool]:
    """``c`` minimising ``|f0 + n c|^2`` subject to ``lo <= f0 + n c <= hi``, and whether that is feasible.

    The dual active-set method of Goldfarb and Idnani (1983) for the strictly
    convex QP ``min c^T G c / 2 + a^T c``, ``G = n^T n``, ``a = n^T f0``
    (``n`` has full column rank: independent cycles), with the constraints
    ``C^T c >= b`` (one per finite bound): from the unconstrained minimum it
    adds the most violated constraint, dropping others as its multipliers
    require, until none is violated (feasible) or a violated one cannot be
    met (infeasible: the last iterate is returned).  The result is finished
    by one solve of the final active set's optimality conditions.
    """
    g_inv = np.linalg.inv(n.T @ n)
    rows, rhs = [], []
    for j in range(f0.size):
        if lo[j] > -_INF:
            rows.append(n[j]), rhs.append(lo[j] - f0[j])
        if hi[j] < _INF:
            rows.append(-n[j]), rhs.append(f0[j] - hi[j])
    x = -g_inv @ (n.T @ f0)
    if not rows:
        return x, True
    cons, b = np.array(rows).T, np.array(rhs)
    tol = 64 * _EPS * (np.abs(f0).max() + np.abs(b[np.isfinite(b)]).max(initial=0.0) + 1e-300)
    active: list[int] = []
    u = np.zeros(0)
    for _ in range(4 * cons.shape[1] + 10):
        slack = cons.T @ x - b
        slack[active] = _INF
        p = int(np.argmin(slack))
        if slack[p] >= -tol:
            return _finish(g_inv, n.T @ f0, cons, b, active, x), True
        x, u, added = _add(g_inv, cons, b, active, u, x, p)
        if not added:
            return x, False
    return x, False


def _add(g_inv, cons, b, active, u, x, p):  # noqa: ANN001, ANN202 -- the steps of least_norm
    """Goldfarb-Idnani's step 2: make constraint ``p`` active (dropping others as needed)."""
    n_p, u_plus = cons[:, p], np.append(u, 0.0)
    while True:
        if active:
            na = cons[:, active]
            n_star = np.linalg.solve(na.T @ g_inv @ na, na.T @ g_inv)
            z, r = (g_inv - g_inv @ na @ n_star) @ n_p, n_star @ n_p
        else:
            z, r = g_inv @ n_p, np.zeros(0)
        ratios = [(u_plus[j] / r[j], j) for j in range(len(active)) if r[j] > 0]
        t1, drop = min(ratios) if ratios else (_INF, -1)
        zn = float(z @ n_p)
        full = zn > 1e-12 * float(n_p @ g_inv @ n_p)
        t2 = -(float(n_p @ x) - b[p]) / zn if full else _INF
        t = min(t1, t2)
        if math.isinf(t):
            return x, u, False
        if full:
            x = x + t * z
        u_plus[:-1] -= t * r
        u_plus[-1] += t
        if full and t == t2:
            active.append(p)
            return x, u_plus, True
        del active[drop]
        u_plus = np.delete(u_plus, drop)


def _finish(g_inv, a, cons, b, active, x):  # noqa: ANN001, ANN202
    """The minimiser with the final active constraints held as equalities (one solve)."""
    if not active:
        return -g_inv @ a
    na = cons[:, active]
    lam = np.linalg.solve(na.T @ g_inv @ na, b[active] + na.T @ g_inv @ a)
    return g_inv @ (na @ lam - a)


def _max_flow(edges: list[int], core: _Core, force: dict, skip: int, source: int, sink: int) -> float:
    """How far the force of ``skip`` can rise (source = its first point) or fall (its second)
    with the others staying in their bands: a maximum flow from ``source`` to ``sink`` in the
    residual graph of ``force`` without ``skip`` (Edmonds-Karp)."""
    head, cap, out = [], [], {}
    for e in edges:
        if e == skip:
            continue
        for a, b, room in (
            (core.second[e], core.first[e], core.hi[e] - force[e]),
            (core.first[e], core.second[e], force[e] - core.lo[e]),
        ):
            out.setdefault(a, []).append(len(head))
            head.append(b)
            cap.append(max(room, 0.0))
    total = 0.0
    while True:
        came = {source: -1}
        queue = deque([source])
        while queue and sink not in came:
            p = queue.popleft()
            for arc in out.get(p, ()):
                if cap[arc] > 0 and head[arc] not in came:
                    came[head[arc]] = arc
                    queue.append(head[arc])
        if sink not in came:
            return total
        path, p = [], sink
        while came[p] >= 0:
            path.append(came[p])
            p = head[came[p] ^ 1]
        push = min(cap[arc] for arc in path)
        if math.isinf(push):
            return _INF
        for arc in path:
            cap[arc] -= push
            cap[arc ^ 1] += push
        total += push
