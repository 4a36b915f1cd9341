"""The one-step problem of a network: new velocities and element forces.

Given the inertia ``d_i`` of each mass (``m_i/dt`` in a step; ``m_i`` in the
problem for the initial forces), the right-hand side ``r_i`` (``m_i/dt v_n,i
+ F_i``) and the step graph of every element (:class:`Piece` s), find ``v``
and ``f`` with

    d_i v_i + sum_e B_ei f_e = r_i,      (w_e, f_e) on the graph of e,

``w = B v``, ``B_ei = +1`` if mass ``i`` is the element's ``second`` point,
``-1`` if its ``first``.  These are the optimality conditions of the
strictly convex potential of :class:`~lumped.model.network.Network`.

Method: a primal-dual active set (semismooth Newton) iteration.  Each
element is given a *mode*, one piece of its graph.  With the modes fixed the
problem is linear: a free piece adds ``b`` to the stiffness between its
points and ``a`` to the load; a rigid piece fixes its rate, so the masses it
joins move as one (their velocities differ by the fixed rates, and by
exactly 0 for a sticking element) and are merged into one unknown.  The
merged system is symmetric positive definite (the inertias are positive);
for a chain in file order it is tridiagonal and is solved as a band.  The
rigid elements' forces then follow from the momentum balance of each mass,
leaf to root of the rigid forest (unique, see ``Network``).  Rigid elements
that close loops (two in parallel, a ring) share what is left: their split
is the least-norm admissible one, each with its interval of admissible
forces (:mod:`lumped.solvers.loop_forces`), and a loop whose fixed rates
disagree has one element on a wrong piece, which the next iteration moves
(:mod:`lumped.solvers.rigid_clusters`).  Each element's
new mode is the piece that contains ``z = f + sigma w``, its resolvent with
a scale ``sigma > 0`` of the stiffness its points see; the iteration stops
when no mode changes, and then every ``(w, f)`` lies on its graph: the
problem is solved exactly, up to the rounding of one linear solve.  A mode
vector that comes back is a cycle.  At a *corner* of a graph (a pad sticking
at exactly its threshold, where its sticking piece meets a slipping one)
both pieces give the same solution, and in floating point each one's solve
lands a few ulps on the other's side (a force of ``tau + 2 ulp``, a rate of
``-6e-21``): the modes alternate.  So a cycle is gone round once and its
first iterate on its pieces up to the linear solve's rounding
(:func:`on_pieces`) is the solution, its rigid forces clipped to their
bands.  A cycle without one (the iteration can cycle in exact arithmetic)
is restarted with other scales ``sigma`` (``SIGMA_SCALES``), then from the
modes of Gauss-Seidel sweeps on the dual (``DUAL_SWEEPS``); if none settles,
or the bound on iterations is reached, a ``StepError`` says so.  Parallel
elements that can be rigid and whose graphs break at the same rates (pads)
are stepped as one element of the summed graph
(:mod:`lumped.solvers.parallel_elements`).  (For one mass with a spring and a Bingham dashpot,
``sigma = m/dt + k dt`` makes ``z`` the predictor ``F~`` of eq. 15b and the
mode test Algorithm 1's ``|F~| <= mu_s N_f``.)

A contact that is not monotone (static above kinetic, a falling slip curve)
changes its discrete mode (stick, slip forward, slip back) only on an
iterate where no element's point still moves on its piece
(:func:`_points_first`): its rule (stay stuck while the tension is within
``static``, keep slipping while the rate keeps its sign) acts on the solve
of the pieces chosen, not on an iterate on the way to it, which may pull a
stuck contact past ``static`` or turn a slipping one's rate for a moment
(both happened in ``coupled(12)`` of ``tests/test_step_property.py``: the
two steps broke a held contact away, or stopped a slipping pair, an iterate
early, and the compiled and Python steps, started from different points,
took different active sets).

Where some graph is linearised in each iteration (below) and the first
scale does not settle, the step is finished by Newton's method: each graph's
:meth:`~lumped.laws.step_graph.StepGraph.newton` form (a Stribeck contact's
tangent lines, its mode the resolvent's choice on its convexified graph),
one discrete mode changed at a time once the modes repeat (Murty's
least-index rule, :func:`_least_index`), a slipping contact held at rest by
stuck ones (in parallel, or round a loop) kept slipping while one of them
breaks away (:func:`_pinned_rule`); it settles when every slipping
contact's force lies on its law to the solve's rounding (book/guide/systems.md
derives the step as the minimiser of a strongly convex function ``Phi``
below the uniqueness bound, whose Newton step this is).  Why the answer is
the solution: a settled iterate has every ``(w, f)`` on its graph (on its
law, to the solve's rounding), so it solves the step's equations, and below
the bound they have one solution.  Why the iteration ends has no proof yet:
the rules above end every case the property tests draw (1000 random falling
networks), the bound on iterations ends the rest, and a step that reaches it
raises a ``StepError`` that calls itself a bug and carries ``Phi`` at its
last iterate (:func:`step_function`); a line search on ``Phi``, which would
make it a proof, is not done.  ``_network_active_set.h``'s ``solve`` is the
same in C but for :func:`_pinned_rule`: a contact held at rest by stuck
ones that stops closes a rigid loop, a step both compiled steps hand to
this one (and both refuse parallel elements that can be rigid).

A graph that is not piecewise linear (a
:class:`~lumped.laws.step_graph.LawGraph`, the step graph of a
:class:`~lumped.laws.dashpot_elements.Monotone` or Herschel-Bulkley element) is
given instead the line of slope ``sigma`` through its resolvent point of
``z``; the fixed point of that iteration lies on its graph, reached to a
relative 8 ulps.  The step asks each graph through the graph contract of
:class:`~lumped.laws.step_graph.StepGraph` (its pieces, its modes), never
for its class.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from lumped.laws.step_graph import STICK, Piece, StepGraph, as_step_graph
from lumped.solvers import parallel_elements as parallel
from lumped.solvers.loop_forces import CoreForces, core_forces
from lumped.solvers.merged_system import assemble, solve_merged
from lumped.solvers.rigid_clusters import Clusters, Merged, loop_merge

__all__ = [
    "BOUND",
    "DUAL_SWEEPS",
    "SIGMA_SCALES",
    "StepError",
    "StepSolution",
    "default_bound",
    "on_pieces",
    "solve_step",
    "step_function",
    "unsettled",
]

_EPS = 2.0**-52  # numpy.finfo(float).eps

#: Scales of ``sigma`` tried in turn when the active-set iteration cycles.
SIGMA_SCALES = (1.0, 0.25, 4.0, 1 / 16, 16.0)
#: Gauss-Seidel sweeps on the dual tried in turn when no scale settles (:func:`_dual_sweeps`).
#: Both are handed to the compiled step when it is imported (``network_settings``).
DUAL_SWEEPS = (10, 100, 1000)

Graph = Sequence[Piece] | StepGraph


class StepError(ArithmeticError):
    """The active-set iteration did not settle (``changing``: the elements whose modes still changed
    in its last iteration), or (``elements`` given) the rigid elements ``elements`` close a loop whose
    rates disagree: the step has no solution."""

    def __init__(
        self, message: str, elements: Sequence[int] = (), changing: Sequence[int] = (), phi: float | None = None
    ) -> None:
        super().__init__(message)
        self.elements = tuple(elements)
        self.changing = tuple(changing)
        self.phi = phi  # the step's function at the last iterate (step_function), if it did not settle


class StepSolution(NamedTuple):
    """Velocities ``v`` (masses), rates ``w``, forces ``f``, chosen ``modes`` (elements),
    ``rigid`` (elements on a rigid piece) and the ``iterations`` taken.

    ``low``, ``high`` (elements), when asked for and some forces are not
    unique (rigid elements closing a loop), bound each element's admissible
    force; ``f`` is then the least-norm split.  ``None`` otherwise.
    """

    v: np.ndarray
    w: np.ndarray
    f: np.ndarray
    modes: list[int]
    rigid: list[bool]
    iterations: int
    low: np.ndarray | None = None
    high: np.ndarray | None = None


class _Linear(NamedTuple):
    """One linear solve: velocities, rates, forces, the loops' forces (``None``
    without rigid loops) and the rigid elements whose loops disagree."""

    v: np.ndarray
    w: np.ndarray
    f: np.ndarray
    core: tuple | None
    clash: tuple[int, ...]


class _Topology(NamedTuple):
    first: list[int]
    second: list[int]
    n_mass: int


def solve_step(
    first: Sequence[int],
    second: Sequence[int],
    inertia: np.ndarray,
    rhs: np.ndarray,
    graphs: Sequence[Graph],
    sigma: np.ndarray,
    modes: Sequence[int] | None = None,
    max_iterations: int | None = None,
    ranges: bool = False,
) -> StepSolution:
    """Solve the one-step problem (see the module docstring).

    Parameters
    ----------
    first, second : sequences of int
        Point indices of each element; the ground is ``len(inertia)``.
    inertia : ndarray, (masses,)
        ``d_i > 0``.
    rhs : ndarray, (masses,)
    graphs : sequence
        Each element's step graph: its pieces, or a
        :class:`~lumped.laws.step_graph.StepGraph` (a law's
        :class:`~lumped.laws.step_graph.LawGraph`).
    sigma : ndarray, (elements,)
        Scale of each element's mode test (> 0).
    modes : sequence of int, optional
        Initial guess (the previous step's modes); the middle piece otherwise.
    max_iterations : int, optional
        Bound per scale; ``20 + 2 * elements`` by default.
    ranges : bool
        Also the interval of admissible forces of each element
        (:attr:`StepSolution.low`, ``high``), when some are not unique.

    Raises
    ------
    StepError
        If no scale settles within the bound; with ``elements`` set if the
        last failure was a loop of rigid pieces whose rates disagree.
    """
    graphs = [as_step_graph(g) for g in graphs]
    reduced = parallel.reduce(first, second, graphs, sigma, modes)
    if reduced is not None:
        return _solve_reduced(reduced, first, second, inertia, rhs, graphs, max_iterations, ranges)
    topo = _Topology(list(first), list(second), inertia.size)
    guess = [g.initial_mode() for g in graphs] if modes is None else list(modes)
    bound = default_bound(len(graphs)) if max_iterations is None else max_iterations
    clash: list = [(), (), None]  # a last loop whose rates disagree; the modes still changing; the last v
    finish = None if all(g.is_piecewise for g in graphs) else [g.newton() for g in graphs]
    for k, scale in enumerate(SIGMA_SCALES):
        out = _iterate(topo, inertia, rhs, graphs, sigma * scale, list(guess), bound, clash)
        if out is None and k == 0 and finish is not None:  # a curve's fixed-point iteration failed: Newton
            out = _iterate(topo, inertia, rhs, finish, sigma, list(guess), bound, clash, one_at_a_time=True)
        if out is not None:
            return _with_ranges(out, topo, ranges)
    for sweeps in DUAL_SWEEPS:  # the guaranteed way in, then the exact finish
        guess = _dual_sweeps(topo, inertia, rhs, graphs, sweeps)
        out = _iterate(topo, inertia, rhs, graphs, sigma, guess, bound, clash)
        if out is not None:
            return _with_ranges(out, topo, ranges)
    if clash[0]:
        raise StepError(DISAGREE, clash[0])
    last = clash[2] if clash[2] is not None else np.zeros(inertia.size)
    phi = step_function(first, second, inertia, rhs, graphs, last)
    raise StepError(unsettled(bound), changing=clash[1], phi=phi)


def step_function(
    first: Sequence[int],
    second: Sequence[int],
    inertia: np.ndarray,
    rhs: np.ndarray,
    graphs: Sequence[StepGraph],
    v: np.ndarray,
) -> float:
    """The step's function ``Phi(v) = sum_i d_i v_i^2/2 - r . v + sum_e psi_e(w_e)``, ``w = B v``.

    Below the uniqueness bound, with each contact's graph chosen, it is strongly convex and the step's
    solution is its minimiser (book/guide/systems.md); ``psi_e`` is each graph's potential
    (:meth:`~lumped.laws.step_graph.StepGraph.potential`, 0 at rate 0).  A step that did not settle
    reports its value at the last iterate.
    """
    points = np.r_[v, 0.0]
    n = inertia.size
    value = float(0.5 * (inertia * v * v).sum() - (rhs * v).sum())
    for a, b, g in zip(first, second, graphs):
        value += g.potential(float(points[min(b, n)] - points[min(a, n)]))
    return value


def _solve_reduced(
    red: parallel.Reduced,
    first: Sequence[int],
    second: Sequence[int],
    inertia: np.ndarray,
    rhs: np.ndarray,
    graphs: Sequence[StepGraph],
    max_iterations: int | None,
    ranges: bool,
) -> StepSolution:
    """The step with each group of parallel rigid-capable elements as one
    (:mod:`lumped.solvers.parallel_elements`), then each element's share."""
    try:
        sol = solve_step(red.first, red.second, inertia, rhs, red.graphs, red.sigma, red.modes, max_iterations, ranges)
    except StepError as err:
        names = [k for e in err.elements for k in (red.groups[e].elements if red.groups[e] else (red.index[e],))]
        moved = [k for e in err.changing for k in (red.groups[e].elements if red.groups[e] else (red.index[e],))]
        raise StepError(str(err), sorted(names), sorted(moved), err.phi) from None
    low, high = (sol.low, sol.high) if sol.low is not None else (None, None)
    out = parallel.expand(
        red, len(graphs), graphs, first, second, inertia.size, (sol.modes, sol.w, sol.f, sol.rigid, low, high)
    )
    kept = ranges and not np.array_equal(out.low, out.high)
    return StepSolution(
        sol.v, out.w, out.f, out.modes, out.rigid, sol.iterations, out.low if kept else None, out.high if kept else None
    )


#: Why a step with a loop of rigid pieces whose rates disagree has no solution.
DISAGREE = "close a loop of rigid constraints whose fixed rates disagree, so no velocities meet them all"


def _with_ranges(out: tuple[StepSolution, _Linear], topo: _Topology, ranges: bool) -> StepSolution:
    """The settled solution, with the intervals of the loops' forces if asked for."""
    sol, lin = out
    if not ranges or lin.core is None:
        return sol
    loops: CoreForces = core_forces(*lin.core, topo.n_mass, ranges=True)
    low, high = sol.f.copy(), sol.f.copy()
    low[loops.elements], high[loops.elements] = loops.low, loops.high
    if np.array_equal(low, high):
        return sol
    return sol._replace(low=low, high=high)


def unsettled(bound: int) -> str:
    """The message of a step whose iteration did not settle within ``bound`` per scale: below the
    uniqueness bound (:mod:`lumped.solvers.uniqueness`, checked before every run) the step has one
    solution, so this is a defect of the solver, said as such."""
    return (
        f"the active-set iteration did not settle (tried sigma scales {SIGMA_SCALES}, {bound} iterations each, "
        "and Newton on the curves); the step has one solution below the uniqueness bound, so this is a bug "
        "in the step solver: please report it"
    )


#: The bound on active-set iterations per scale, ``(base, per_element)``: ``base + per_element * elements``
#: (:func:`default_bound`); handed to the compiled step with the scales (``network_settings``).
BOUND = (20, 2)


def default_bound(elements: int) -> int:
    """The bound on active-set iterations per scale: ``20 + 2 * elements`` (:data:`BOUND`)."""
    return BOUND[0] + BOUND[1] * elements


def _iterate(
    topo: _Topology,
    inertia: np.ndarray,
    rhs: np.ndarray,
    graphs: Sequence[StepGraph],
    sigma: np.ndarray,
    modes: list,
    bound: int,
    clash: list[tuple[int, ...]],
    one_at_a_time: bool = False,
) -> tuple[StepSolution, _Linear] | None:
    """The active-set loop at one scale; ``None`` if it cycles or hits the bound
    (``clash[0]``: the elements of a last loop whose rates disagree).

    A cycle is gone round once, and its first iterate whose ``(w, f)`` lies on
    its pieces up to the rounding of the linear solve (:func:`on_pieces`) is
    the solution: a corner, see the module docstring.  With ``one_at_a_time``
    (the Newton finish), once the elements' discrete modes (:func:`_discrete`)
    repeat, each iteration changes the discrete mode of only the first element
    that asks for a change (Murty's least-index rule, which ends for a linear
    complementarity problem with a P-matrix, as the step's positive definite
    matrix makes it), the curves' points moving on meanwhile.
    """
    single, patterns = False, set()
    seen: set[tuple] = set()
    tried: set[tuple] = set()
    piecewise = all(g.is_piecewise for g in graphs)
    for it in range(1, bound + 1):
        pieces = [g.piece(m, s) for g, m, s in zip(graphs, modes, sigma)]
        lin = _linear(topo, inertia, rhs, pieces)
        v, w, f = lin.v, lin.w, lin.f
        clash[0], clash[2] = lin.clash, v
        if lin.clash:
            return None  # rigid pieces whose rates disagree and none can give way
        rounding = None if piecewise else _rounding(v, w, f, inertia, rhs)
        new = [
            g.next_mode(m, we, fe, s) if g.is_piecewise else g.next_mode(m, we, fe, s, rounding)
            for g, m, fe, we, s in zip(graphs, modes, f, w, sigma)
        ]
        moved = tuple(e for e, (a, b, g) in enumerate(zip(modes, new, graphs)) if not g.same(a, b))
        clash[1] = moved
        settled = not moved
        if settled:
            return StepSolution(v, w, f, modes, [p.rigid for p in pieces], it), lin
        new = _points_first(graphs, modes, new)
        if one_at_a_time:
            new = _pinned_rule(topo, graphs, modes, new, pieces)
            pattern = tuple(map(_discrete, new))
            single = single or pattern in patterns
            patterns.add(pattern)
            if single:
                new = _least_index(modes, new)
        key = tuple(m if g.is_piecewise else None for m, g in zip(new, graphs))
        if piecewise and (key in seen or tried):  # a cycle: go round it once
            if on_pieces(pieces, v, w, f, inertia, rhs):
                f = np.array([min(max(fe, p.lo), p.hi) if p.rigid else fe for fe, p in zip(f, pieces)])
                return StepSolution(v, w, f, modes, [p.rigid for p in pieces], it), lin._replace(f=f)
            here = tuple(modes)
            if here in tried:
                return None  # round the cycle and no iterate on its pieces: this scale will never settle
            tried.add(here)
        seen.add(key)
        modes = new
    return None


def _pinned_rule(topo: _Topology, graphs: Sequence[StepGraph], modes: list, new: list, pieces: Sequence[Piece]) -> list:
    """The Newton finish's mode of a slipping contact held at rest by stuck ones: it keeps slipping while
    one of them breaks away.

    A slipping contact whose two points lie in one cluster of rigid pieces (its rate fixed at 0 by the
    contacts stuck around a loop through it) has rate 0 only because they hold it; its rule would stop
    it, and stuck it may carry more than ``static`` and ask to slip again, while a stuck contact of that
    loop asks to break away and the least-index rule lets only one of them change: the modes cycle
    (issue 41, ``coupled(12)`` of ``tests/test_step_property.py`` at step 367).  So while a stuck contact
    of its cluster asks to break away, the held one keeps its mode and the stuck one's change goes first.
    Contacts in parallel are the shortest such loop: a Stribeck contact beside a Coulomb one swapped
    stick and slip for ever (five of the 1000 random falling networks, at their first step).
    """
    root = _clusters(topo, pieces).clusters.root
    breaking = {
        root[topo.first[e]]
        for e, g in enumerate(graphs)
        if not g.monotone and pieces[e].rigid and _discrete(new[e]) != _discrete(modes[e])
    }
    out = list(new)
    for e, g in enumerate(graphs):
        pinned = root[topo.first[e]] == root[topo.second[e]] and not pieces[e].rigid
        if not g.monotone and pinned and new[e] == STICK and root[topo.first[e]] in breaking:
            out[e] = modes[e]
    return out


def _points_first(graphs: Sequence[StepGraph], modes: list, new: list) -> list:
    """``new`` with the discrete changes of the contacts that are not monotone held back while any element's
    point still moves on its piece: the rule that picks a contact's piece acts on the solve of the pieces
    chosen, not on an iterate on the way to it (issue 41: ``coupled(12)`` at step 215)."""
    moving = any(_discrete(a) == _discrete(b) and not g.same(a, b) for a, b, g in zip(modes, new, graphs))
    if not moving:
        return new
    return [a if not g.monotone and _discrete(a) != _discrete(b) else b for a, b, g in zip(modes, new, graphs)]


def _discrete(mode: object) -> object:
    """A mode's discrete part: a piece's index, or a curve's stick or slip direction (``None``: a law's point)."""
    if not isinstance(mode, tuple):
        return mode
    return ("slip", mode[0]) if len(mode) == 5 else None  # a direction +1.0 is not the stick mode 1


def _least_index(old: list, new: list) -> list:
    """``new`` with every discrete change after the first one undone (:func:`_iterate`'s ``one_at_a_time``)."""
    out, changed = [], False
    for a, b in zip(old, new):
        if _discrete(a) != _discrete(b):
            if changed:
                b = a
            changed = True
        out.append(b)
    return out


def on_pieces(
    pieces: Sequence[Piece], v: np.ndarray, w: np.ndarray, f: np.ndarray, inertia: np.ndarray, rhs: np.ndarray
) -> bool:
    """True if every ``(w_e, f_e)`` lies on its piece up to the rounding of the linear solve.

    A rigid piece asks ``lo - df <= f <= hi + df`` and ``|w - a| <= dw``; a
    free one ``lo - dw <= w <= hi + dw``.  Every velocity and force of the
    solve is a sum (the merged system's elimination, the momentum balances
    peeled leaf to root) of at most ``n = masses + elements + 1`` terms, each
    a velocity, a rate, a momentum ``d_i v_i``, a right-hand side or a force
    of this solve; a sum of ``n`` terms is off by at most ``n eps`` times the
    sum of their magnitudes (Higham, *Accuracy and Stability*, eq. 4.4).  So
    ``df = n eps (sum |r_i| + sum d_i |v_i| + sum |f_e|)`` and ``dw = n eps
    (sum |v_i| + sum |w_e|)``.  The solve then is the exact solution of the
    step with each piece's edges moved by at most ``df`` or ``dw``.
    """
    df, dw = _rounding(v, w, f, inertia, rhs)
    for p, we, fe in zip(pieces, w, f):
        if p.rigid and not (p.lo - df <= fe <= p.hi + df and abs(we - p.a) <= dw):
            return False
        if not p.rigid and not p.lo - dw <= we <= p.hi + dw:
            return False
    return True


def _rounding(v: np.ndarray, w: np.ndarray, f: np.ndarray, inertia: np.ndarray, rhs: np.ndarray) -> tuple[float, float]:
    """The bounds ``(df, dw)`` on the rounding of one linear solve's forces and rates (:func:`on_pieces`)."""
    n = inertia.size + f.size + 1
    df = n * _EPS * (np.abs(rhs).sum() + (inertia * np.abs(v)).sum() + np.abs(f).sum())
    dw = n * _EPS * (np.abs(v).sum() + np.abs(w).sum())
    return float(df), float(dw)


def _dual_sweeps(
    topo: _Topology, inertia: np.ndarray, rhs: np.ndarray, graphs: Sequence[StepGraph], sweeps: int
) -> list:
    """Modes from Gauss-Seidel on the dual problem, a fallback when the active set cycles.

    The dual of the step, minimise ``|r - B^T f|^2_{D^-1}/2 + sum_e psi_e*(f_e)``
    over the forces, has a separable nonsmooth part, so exact minimisation
    over one force at a time converges (Tseng, 2001).  For element ``e`` with
    ``q = 1/d_first + 1/d_second``, that minimisation is the resolvent point
    of ``z = f_e + w_e/q`` with scale ``1/q``: the same mode test.  It
    converges only linearly, so it is used to find the modes, which the
    active-set iteration then finishes exactly.
    """
    inv = [1.0 / d for d in inertia] + [0.0]
    v = [r * s for r, s in zip(rhs, inv)] + [0.0]
    f = [0.0] * len(graphs)
    modes: list = [g.initial_mode() for g in graphs]
    for _ in range(sweeps):
        for e, g in enumerate(graphs):
            if not g.is_piecewise:
                continue
            i, j = topo.first[e], topo.second[e]
            sigma = 1.0 / (inv[i] + inv[j])
            z = f[e] + sigma * (v[j] - v[i])
            k = modes[e] = g.mode(z, sigma)
            p = g.piece(k, sigma)
            new = z - sigma * p.a if p.rigid else p.a + p.b * (z - p.a) / (p.b + sigma)
            delta, f[e] = new - f[e], new
            v[j] -= delta * inv[j]
            v[i] += delta * inv[i]
            v[-1] = 0.0
    return modes


def _clusters(topo: _Topology, pieces: list[Piece]) -> Merged:
    """Merge the points joined by rigid pieces: each point's cluster root and
    velocity offset from it (exactly 0 across sticking elements)."""
    n = topo.n_mass + 1
    adjacent: dict[int, list[tuple[int, float]]] = {}
    for e, p in enumerate(pieces):
        if p.rigid:
            a, b = topo.first[e], topo.second[e]
            adjacent.setdefault(a, []).append((b, p.a))
            adjacent.setdefault(b, []).append((a, -p.a))
    root, offset = list(range(n)), [0.0] * n
    done = [False] * n
    ground, merged = topo.n_mass, 0
    for start in [ground] + [i for i in range(topo.n_mass) if i in adjacent]:
        if done[start]:
            continue
        done[start], stack = True, [start]
        while stack:
            node = stack.pop()
            for nxt, rate in adjacent.get(node, ()):
                if not done[nxt]:
                    done[nxt], root[nxt] = True, start
                    offset[nxt] = offset[node] + rate
                    stack.append(nxt)
                    merged += 1
    rigid = [e for e, p in enumerate(pieces) if p.rigid]
    if merged == len(rigid):  # a forest: every rigid element merged two clusters
        return Merged(Clusters(root, offset, {}), {}, ())
    return loop_merge(topo.first, topo.second, topo.n_mass, pieces, rigid)


def _linear(topo: _Topology, inertia: np.ndarray, rhs: np.ndarray, pieces: list[Piece]) -> _Linear:
    """Solve with every mode fixed: velocities, rates and forces."""
    n, ground = topo.n_mass, topo.n_mass
    merged = _clusters(topo, pieces)
    root, offset = merged.clusters.root, merged.clusters.offset
    unknown: dict[int, int] = {}
    for i in range(n):
        if root[i] != root[ground] and root[i] not in unknown:
            unknown[root[i]] = len(unknown)
    col = [unknown.get(root[i], -1) for i in range(n + 1)]
    matrix, load = assemble(topo, inertia, rhs, pieces, col, offset, len(unknown))
    u = solve_merged(matrix, load)
    v_all = [offset[i] if col[i] < 0 else u[col[i]] + offset[i] for i in range(n + 1)]
    v_all[ground] = 0.0
    w, f = _rates_forces(topo, pieces, v_all, merged.released)
    core = _rigid_forces(topo, inertia, rhs, pieces, v_all, f, merged.released)
    return _Linear(np.array(v_all[:n]), np.array(w), np.array(f), core, merged.stuck)


def _rates_forces(
    topo: _Topology, pieces: list[Piece], v_all: list[float], released: dict[int, tuple[float, float]]
) -> tuple[list[float], list[float]]:
    """Each element's rate (the fixed rate on a rigid piece) and free force
    (a released element: the rate its points have, the edge of its band)."""
    w, f = [], []
    for e, p in enumerate(pieces):
        if e in released:
            w.append(released[e][0])
            f.append(released[e][1])
        elif p.rigid:
            w.append(p.a)
            f.append(0.0)
        else:
            rate = v_all[topo.second[e]] - v_all[topo.first[e]]
            w.append(rate)
            f.append(p.a + p.b * rate)
    return w, f


def _rigid_forces(
    topo: _Topology,
    inertia: np.ndarray,
    rhs: np.ndarray,
    pieces: list[Piece],
    v_all: list[float],
    f: list[float],
    released: dict[int, tuple[float, float]],
) -> tuple | None:
    """Forces of the rigid elements, leaf to root of the rigid forest (in place);
    what closes loops is split by :func:`~lumped.solvers.loop_forces.core_forces`,
    whose arguments are returned (``None`` without loops)."""
    rigid = [e for e, p in enumerate(pieces) if p.rigid and e not in released]
    if not rigid:
        return None
    n, ground = topo.n_mass, topo.n_mass
    gap = [rhs[i] - inertia[i] * v_all[i] for i in range(n)] + [0.0]
    pushed = [0.0] * (n + 1)
    for e, p in enumerate(pieces):
        if not p.rigid or e in released:
            pushed[topo.second[e]] += f[e]
            pushed[topo.first[e]] -= f[e]
    gap = [g - q for g, q in zip(gap, pushed)]
    at: dict[int, set[int]] = {}
    for e in rigid:
        at.setdefault(topo.first[e], set()).add(e)
        at.setdefault(topo.second[e], set()).add(e)
    leaves = [i for i, es in at.items() if len(es) == 1 and i != ground]
    while leaves:
        i = leaves.pop()
        if len(at[i]) != 1:
            continue
        e = at[i].pop()
        sign = 1.0 if topo.second[e] == i else -1.0
        f[e] = sign * gap[i]
        j = topo.first[e] if sign > 0 else topo.second[e]
        gap[j] -= (1.0 if topo.second[e] == j else -1.0) * f[e]
        at[j].discard(e)
        if len(at[j]) == 1 and j != ground:
            leaves.append(j)
    left = sorted({e for es in at.values() for e in es})
    if not left:
        return None
    core = (left, topo.first, topo.second, {e: (pieces[e].lo, pieces[e].hi) for e in left}, gap)
    split = core_forces(*core, ground)
    for e, value in zip(split.elements, split.force):
        f[e] = value
    return core
