"""Backward Euler for a network: the integrator, returning a :class:`~lumped.model.trajectory.Trajectory`.

Each step takes the states of the step's start (positions, velocities,
element states), asks every element for its step graph, solves the one-step
problem (:func:`lumped.solvers.network_step.solve_step`), and advances
``x_{n+1} = x_n + dt v_{n+1}`` and each element's state.

The paper's system written as a network (one mass, one ``spring`` and one
``bingham`` to the ground, any loads) is handed to Algorithm 1
(:func:`lumped.backward_euler`) itself when ``solver="auto"``: the same
numbers bit for bit, at the compiled kernel's speed.  With a
``herschel-bulkley`` element instead it goes to the same function, whose
step is then the law's resolvent (a root solve).  Every other network takes
the active-set step, in C (:mod:`lumped.solvers.network_compiled`) when its elements
are piecewise linear and its links form a forest or close one loop, else in Python.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from lumped.drivers.methods import NETWORK_SOLVERS
from lumped.drivers.one_mass import network_trajectory
from lumped.model.forcing import check_span, one_force, sine_form
from lumped.model.network import Network, listed
from lumped.model.problem import OneMass, one_mass_form
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate
from lumped.solvers import network_compiled as kernel
from lumped.solvers.network_step import StepError, default_bound, solve_step, unsettled

__all__ = ["simulate_network", "SOLVERS"]

#: Step solvers by name (see :func:`simulate_network`): a view of the registry
#: (:data:`lumped.drivers.methods.NETWORK_SOLVERS`, those of the method that runs any network).
SOLVERS = NETWORK_SOLVERS
#: Steps whose forcing is tabulated at once (at most ``_TABLE_VALUES`` values).
_BLOCK = 1 << 14
_TABLE_VALUES = 1 << 20
#: Estimated cost (s) of a step, a constant and a part per element, by path.
#: Measured on this project's 2-core machine, shared and busy
#: (benchmarks/bench_network.py, chains): Python about 2e-5 + 1e-5 per
#: element; compiled about 1e-6 + 4e-8 to 1e-7 per element; a margin of 2.
_COST = {"python": (4e-5, 2e-5), "compiled": (4e-6, 2e-7)}


def _paper_form(net: Network) -> OneMass | None:
    """The oscillator if ``net`` is the paper's system: one spring and one dashpot that
    :func:`lumped.backward_euler` runs (a Bingham or Herschel-Bulkley element, its
    ``auto_one_mass``) to the ground; several loads are run as their sum."""
    if len(net.masses) != 1 or len(net.elements) != 2:
        return None
    if sum(e.linear_stiffness is not None for e in net.elements) != 1:
        return None
    if sum(e.auto_one_mass for e in net.elements) != 1:
        return None
    try:
        return one_mass_form(net)
    except ValueError:  # an element not to the ground: the active-set step says what is wrong
        return None


def _via_algorithm1(net: Network, form: OneMass, t_end: float, dt: float, save_every: int) -> Trajectory:
    """Backward Euler of :func:`lumped.backward_euler`: Algorithm 1, or the law's resolvent."""
    from lumped.solvers.backward_euler import backward_euler

    m = net.masses[0]
    force = sine_form(one_force([load.force for load in net.loads]))
    tr = backward_euler(form.oscillator, t_end, dt, x0=m.x0, v0=m.v0, force=force, save_every=save_every)
    solver = "algorithm1" if form.oscillator.dashpot.bingham_form() is not None else "resolvent"  # as backward_euler
    return network_trajectory(net, form, tr, solver)


def _sigma(net: Network, inertia: np.ndarray, dt: float) -> np.ndarray:
    """Each element's mode-test scale: the series stiffness its two points see."""
    first, second = net.incidence()
    seen = np.append(inertia, np.inf)
    for e, el in enumerate(net.elements):
        k = el.step_stiffness
        seen[first[e]] += dt * k
        seen[second[e]] += dt * k
    pairs = zip(seen[first], seen[second])
    return np.array(
        [b if math.isinf(a) else a if math.isinf(b) else a * b / (a + b) for a, b in pairs]
    )  # the ground is infinitely stiff


def _graphs(net: Network, state: list[float], dt: float | None, w0: np.ndarray | None) -> list:
    """Each element's step graph (``dt`` given) or its rate graph at ``t = 0`` (``w0`` given)."""
    if dt is not None:
        return [el.step_graph(s, dt) for el, s in zip(net.elements, state)]
    return [el.rate_graph(s, float(w)) for el, s, w in zip(net.elements, state, w0)]  # type: ignore[arg-type]


def _initial(net: Network, first: np.ndarray, second: np.ndarray, path: str):
    """Initial positions, velocities, element states and consistent forces
    (the problem solved by ``path``'s step)."""
    x, v = net.initial_positions()
    e0, w0 = x[second] - x[first], v[second] - v[first]
    state = []
    for e, el in enumerate(net.elements):
        try:
            state.append(el.initial_state(float(e0[e]), float(w0[e])))
        except ValueError as err:
            raise ValueError(f"element {el.name!r}: {err}") from None
    inertia = np.array([m.mass for m in net.masses])
    f0 = net.load_table(np.zeros(1))[0]
    graphs, sigma = _graphs(net, state, None, w0), _sigma(net, inertia, 1.0)
    if path == "compiled" and not kernel.has_chord(kernel.plan(net)):  # a loop's intervals: the Python step
        sol = kernel.solve_graphs(kernel.plan(net), inertia, sigma, graphs, f0)
    else:
        sol = solve_step(first, second, inertia, f0, graphs, sigma, ranges=True)
    return x[:-1], v[:-1], state, sol


def simulate_network(
    network: Network, t_end: float, dt: float, *, save_every: int = 1, solver: str = "auto"
) -> Trajectory:
    """Integrate a network with backward Euler on the grid ``t_n = n*dt``.

    Parameters
    ----------
    network : Network
    t_end, dt, save_every
        As for :func:`lumped.backward_euler`.
    solver : {"auto", "active-set", "compiled", "python"}
        ``"auto"`` runs the paper's system through Algorithm 1 and every
        other network through the active-set step; ``"active-set"`` always
        takes the active-set step.  Both run it compiled when
        :func:`lumped.solvers.network_compiled.ineligible` allows (every element
        piecewise linear, the link graph a forest or one loop, the kernel built) and in
        Python otherwise.  ``"compiled"`` and ``"python"`` force one path
        (``"compiled"`` refuses a network it cannot run).

    Returns
    -------
    Trajectory

    Raises
    ------
    ValueError
        For a bad argument (named), a run estimated beyond the limits of
        :mod:`lumped.numerics.validate`, a non-finite step or a step whose
        active-set iteration does not settle (the time named).
    """
    if not isinstance(network, Network):
        raise ValueError(f"network must be a Network, got {type(network).__name__}")
    t_end, dt = validate.positive("t_end", t_end), validate.positive("dt", dt)
    save_every = validate.stride("save_every", save_every)
    if solver not in SOLVERS:
        raise ValueError(f"solver must be one of {', '.join(SOLVERS)}; got {solver!r}")
    pair = _paper_form(network) if solver == "auto" else None
    if pair is not None:
        return _via_algorithm1(network, pair, t_end, dt, save_every)
    path = _path(network, solver)
    n_steps = validate.step_count(t_end, dt)
    for load in network.loads:
        check_span(load.force, n_steps * dt)  # a sine's range, to the grid's last time
    width = 1 + 2 * len(network.masses) + 3 * len(network.elements)
    rows = validate.output_size(n_steps, save_every, width)
    fixed, per_element = _COST[path]
    validate.run_time(n_steps, fixed + per_element * len(network.elements), f"the network step ({path})")
    return _march(network, dt, n_steps, save_every, rows, path)


def _path(net: Network, solver: str) -> str:
    """``"compiled"`` or ``"python"``: the active-set step's path for ``solver``."""
    if solver == "python":
        return "python"
    reason = kernel.ineligible(net)
    if solver == "compiled" and reason is not None:
        raise ValueError(f"solver: 'compiled' cannot run this network: {reason}")
    return "python" if reason is not None else "compiled"


class _Record:
    """Saved rows, filled as the run goes; the intervals of the rows whose forces are not unique."""

    def __init__(self, rows: int, masses: int, elements: int) -> None:
        self.t = np.empty(rows)
        self.x, self.v = np.empty((rows, masses)), np.empty((rows, masses))
        self.force, self.state = np.empty((rows, elements)), np.empty((rows, elements))
        self.rigid = np.zeros((rows, elements), dtype=bool)
        self.ranges: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self.low: np.ndarray | None = None  # the compiled loop's intervals, every row
        self.high: np.ndarray | None = None
        self.row = 0

    def save(self, t: float, x, v, f, state, rigid, low=None, high=None) -> None:  # noqa: ANN001
        r = self.row
        self.t[r], self.x[r], self.v[r], self.force[r] = t, x, v, f
        self.state[r], self.rigid[r] = state, rigid
        if low is not None:
            self.ranges[r] = (low, high)
        self.row += 1

    def intervals(self) -> tuple[np.ndarray | None, np.ndarray | None]:
        """``force_min``, ``force_max`` of the saved rows (the force itself where it is
        unique), or ``None`` if every saved row's forces are unique."""
        if not self.ranges and self.low is None:
            return None, None
        low = self.force.copy() if self.low is None else self.low
        high = self.force.copy() if self.high is None else self.high
        low[0], high[0] = self.force[0], self.force[0]
        for r, (lo, hi) in self.ranges.items():
            low[r], high[r] = lo, hi
        return (low, high) if np.any(low != high) else (None, None)


class _Start(NamedTuple):
    """What both marching loops start from: positions, velocities, element states,
    inertias ``m/dt``, mode-test scales and the rest counters."""

    x: np.ndarray
    v: np.ndarray
    state: list[float]
    inertia: np.ndarray
    sigma: np.ndarray
    rest: np.ndarray


def _march(net: Network, dt: float, n_steps: int, save_every: int, rows: int, path: str) -> Trajectory:
    first, second = net.incidence()
    x, v, state, sol = _initial(net, first, second, path)
    inertia = np.array([m.mass / dt for m in net.masses])
    rec = _Record(rows, len(net.masses), len(net.elements))
    rec.save(0.0, x, v, sol.f, state, False, sol.low, sol.high)
    start = _Start(x, v, state, inertia, _sigma(net, inertia, dt), np.where(v == 0, 0, 1).astype(np.int64))
    run = _run_compiled if path == "compiled" else _run_python
    v, most = run(net, dt, n_steps, save_every, rec, start)
    still = v != 0
    rest_time = np.where(still, np.nan, np.minimum(start.rest, n_steps) * dt)
    rest_position = np.where(still, np.nan, rec.x[rec.row - 1])
    applied = net.load_table(rec.t)  # the loads at the saved times, as the steps evaluated them
    rest = (rest_time, rest_position)
    force_min, force_max = rec.intervals()
    return Trajectory(
        t=rec.t,
        positions=rec.x,
        velocities=rec.v,
        forces=rec.force,
        applied=applied,
        network=net,
        method="backward-euler",
        dt=dt,
        save_every=save_every,
        states=rec.state,
        rigid=rec.rigid,
        final_rest=rest,
        solver=path,
        iterations=most,
        force_min=force_min,
        force_max=force_max,
    )


def _unsettled(n: int, dt: float, elements: int) -> ValueError:
    """The message of a step whose iteration did not settle: the step solver's failure, named as
    such (the step problem has a solution, unique in its velocities, at every ``dt``)."""
    return ValueError(f"the step solver failed at the step to t = {n * dt:.6g} s: {unsettled(default_bound(elements))}")


def _failed(net: Network, n: int, dt: float, err: StepError) -> ValueError:
    """The message of a Python step that failed: unsettled, or a loop of rigid pieces whose rates disagree."""
    if not err.elements:
        return _unsettled(n, dt, len(net.elements))
    names = listed([net.elements[e].name for e in err.elements])
    return ValueError(f"elements {names} {err} at the step to t = {n * dt:.6g} s")


def _overflowed(n: int, dt: float) -> ValueError:
    return ValueError(f"the run overflowed at t = {n * dt:.6g} s (step {n}): a velocity or force is not finite")


def _run_python(
    net: Network, dt: float, n_steps: int, save_every: int, rec: _Record, start: _Start
) -> tuple[np.ndarray, int]:
    """The Python step, one step at a time; returns the last velocities and the most iterations."""
    first, second = net.incidence()
    v, x, state, rest = start.v, start.x, start.state, start.rest
    modes, most = None, 0
    for begin in range(1, n_steps + 1, _BLOCK):
        stop = min(begin + _BLOCK - 1, n_steps)
        table = net.load_table(np.arange(begin, stop + 1) * dt)
        for n in range(begin, stop + 1):
            rhs = start.inertia * v + table[n - begin]
            graphs = _graphs(net, state, dt, None)
            saved = n % save_every == 0 or n == n_steps
            try:
                sol = solve_step(first, second, start.inertia, rhs, graphs, start.sigma, modes, ranges=saved)
            except StepError as err:
                raise _failed(net, n, dt, err) from None
            v, modes, most = sol.v, sol.modes, max(most, sol.iterations)
            x = x + dt * v
            state = [
                el.next_state(s, dt, float(we), float(fe), r)
                for el, s, we, fe, r in zip(net.elements, state, sol.w, sol.f, sol.rigid)
            ]
            if not (np.isfinite(v).all() and np.isfinite(sol.f).all()):
                raise _overflowed(n, dt)
            rest[v != 0] = n + 1
            if saved:
                rec.save(n * dt, x, v, sol.f, state, sol.rigid, sol.low, sol.high)
    return v, most


def _run_compiled(
    net: Network, dt: float, n_steps: int, save_every: int, rec: _Record, start: _Start
) -> tuple[np.ndarray, int]:
    """The compiled loop (:mod:`lumped.solvers.network_compiled`), block by block; same contract."""
    topology, loaded = kernel.plan(net), np.array(net.loaded_masses(), dtype=np.int64)
    counters = np.array([rec.row, 0, 0, 0], dtype=np.int64)
    modes = np.full(len(net.elements), -1, dtype=np.int64)
    marching = (start.x.copy(), start.v.copy(), np.array(start.state, dtype=float), modes, start.rest, counters)
    if kernel.has_chord(topology):
        rec.low, rec.high = np.empty_like(rec.force), np.empty_like(rec.force)
    kept = (rec.low, rec.high) if rec.low is not None else (np.empty(0), np.empty(0))
    record = (rec.t, rec.x, rec.v, rec.force, rec.state, rec.rigid.view(np.uint8), *kept)
    block = max(1, min(_BLOCK, _TABLE_VALUES // max(1, loaded.size)))
    for begin in range(1, n_steps + 1, block):
        stop = min(begin + block - 1, n_steps)
        table = net.load_table(np.arange(begin, stop + 1) * dt, loaded)
        steps = (begin, stop, n_steps, save_every)
        kernel.march_block(topology, start.inertia, start.sigma, loaded, marching, record, table, dt, steps)
        rec.row = int(counters[0])
        if counters[2]:
            n = int(counters[1])
            raise _unsettled(n, dt, len(net.elements)) if counters[2] == 1 else _overflowed(n, dt)
    return marching[1], int(counters[3])
