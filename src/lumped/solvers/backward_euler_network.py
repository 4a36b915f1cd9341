"""Backward Euler for a network: the time loop, returning a :class:`~lumped.model.trajectory.Trajectory`.

Each step takes the states of the step's start (positions, velocities,
element states), asks every element for its step graph, solves the one-step
problem (:func:`lumped.solvers.network_step.solve_step`), and advances
``x_{n+1} = x_n + dt v_{n+1}`` and each element's state.  The loop runs in
Python (:func:`_run_python`) or, block by block, in the compiled kernel
(:mod:`lumped.solvers.network_compiled`), or for one mass with a friction
contact in the compiled friction loop (:mod:`lumped.solvers.friction_compiled`),
or in the compiled sparse step (:mod:`lumped.solvers.network_sparse`, any other
network it runs; a step whose rigid elements close a loop runs :func:`_python_step`).

:func:`march` takes arguments already checked at the boundary
(:func:`lumped.drivers.network.run_network`: the grid, the output's size,
the run time, the path); it does not check them again.
"""

from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

from lumped.laws.step_graph import shifted
from lumped.model.network import Network, listed
from lumped.model.trajectory import Jump, Trajectory
from lumped.solvers import friction_compiled as friction
from lumped.solvers import network_compiled as kernel
from lumped.solvers import network_sparse as sparse
from lumped.solvers.network_step import StepError, default_bound, solve_step, unsettled

__all__ = ["march"]

#: Steps whose forcing is tabulated at once (at most ``_TABLE_VALUES`` values).
_BLOCK = 1 << 14
_TABLE_VALUES = 1 << 20


def _sigma(net: Network, inertia: np.ndarray, dt: float) -> np.ndarray:
    """Each element's mode-test scale: the series stiffness its two points see."""
    first, second = net.incidence()
    seen = np.append(inertia, np.inf)
    k = dt * np.array([el.step_stiffness for el in net.elements], dtype=float)
    # each element adds to its first point, then its second, in element order (np.add.at keeps that order)
    np.add.at(seen, np.stack([first, second], axis=1).ravel(), np.repeat(k, 2))
    a, b = seen[first], seen[second]
    with np.errstate(invalid="ignore"):
        series = a * b / (a + b)
    return np.where(np.isinf(a), b, np.where(np.isinf(b), a, series))  # the ground is infinitely stiff


def _graphs(
    net: Network, state: list[float], dt: float | None, w0: np.ndarray | None, delta: np.ndarray | None = None
) -> list:
    """Each element's step graph (``dt`` given) or its rate graph at ``t = 0`` (``w0`` given), seen in the
    problem's rates: an element joined to a driven point shifted by ``delta`` (:func:`_shifts`)."""
    if dt is not None:
        graphs = [el.step_graph(s, dt) for el, s in zip(net.elements, state)]
    else:
        graphs = [el.rate_graph(s, float(w)) for el, s, w in zip(net.elements, state, w0)]  # type: ignore[arg-type]
    if delta is not None:
        for d in net.driven():
            graphs[d.element] = shifted(graphs[d.element], float(delta[d.element]))
    return graphs


def _means(net: Network, times: np.ndarray, dt: float) -> np.ndarray:
    """Each driver's mean velocity over each step ending at ``times``: ``(steps, drivers)``."""
    out = np.empty((times.size, len(net.drivers)))
    for k, d in enumerate(net.drivers):
        out[:, k] = d.mean_velocity(times - dt, times)
    return out


def _shifts(net: Network, times: np.ndarray, dt: float) -> np.ndarray | None:
    """Each element's rate shift at each step ending at ``times`` (``(steps, elements)``): ``+-`` the mean
    velocity over the step of the driven point it is joined to (0 for the others); ``None`` without drivers.

    The problem sees a driven point as the ground; an element's true rate is the
    problem's plus this shift, and the mean velocity moves the point by its exact
    displacement over the step, so a contact stuck to it follows its position.
    """
    if not net.drivers:
        return None
    out = np.zeros((times.size, len(net.elements)))
    means = _means(net, times, dt)
    for d in net.driven():
        out[:, d.element] += d.sign * means[:, d.driver]
    return out


def _initial(net: Network, first: np.ndarray, second: np.ndarray, path: str, topology: object = None):
    """Initial positions, velocities, element states and consistent forces
    (the problem solved by ``path``'s step; ``topology``: the sparse step's plan, if it is the path)."""
    x, v = net.initial_positions()
    e0, w0 = x[second] - x[first], v[second] - v[first]
    speed, acceleration = np.zeros(len(net.elements)), np.zeros(len(net.elements))
    starts = [(float(d.velocity_at(0.0)), d.initial_acceleration) for d in net.drivers]  # once per driver
    for d in net.driven():  # a driven point starts at 0 with its velocity at t = 0
        speed[d.element] = d.sign * starts[d.driver][0]
        acceleration[d.element] = d.sign * starts[d.driver][1]
    w0 = w0 + speed
    state = []
    for e, el in enumerate(net.elements):
        try:
            state.append(el.initial_state(float(e0[e]), float(w0[e])))
        except ValueError as err:
            raise ValueError(f"element {el.name!r}: {err}") from None
    inertia = np.array([m.mass for m in net.masses])
    f0 = net.load_table(np.zeros(1))[0]
    graphs, sigma = _graphs(net, state, None, w0, acceleration if net.drivers else None), _sigma(net, inertia, 1.0)
    sol = None
    if path == "compiled" and not kernel.has_chord(kernel.plan(net)):  # a loop's intervals: the Python step
        sol = kernel.solve_graphs(kernel.plan(net), inertia, sigma, graphs, f0)
    elif path == sparse.PATH:  # None if its rigid elements close a loop
        sol = sparse.solve_graphs(topology, inertia, sigma, graphs, f0, acceleration)  # type: ignore[arg-type]
    if sol is None:
        sol = solve_step(first, second, inertia, f0, graphs, sigma, ranges=True)
    return x[:-1], v[:-1], state, sol


class _Record:
    """Saved rows, filled as the run goes; the intervals of the rows whose forces are not unique."""

    def __init__(self, rows: int, masses: int, elements: int) -> None:
        self.t = np.empty(rows)
        self.x, self.v = np.empty((rows, masses)), np.empty((rows, masses))
        self.force, self.state = np.empty((rows, elements)), np.empty((rows, elements))
        self.rigid = np.zeros((rows, elements), dtype=bool)
        self.ranges: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        self.jumps: list[Jump] = []  # the elements' jumps between branches, every step's (Element point 12)
        self.low: np.ndarray | None = None  # the compiled loop's intervals, every row
        self.high: np.ndarray | None = None
        self.row = 0
        self.python_steps = 0  # steps the sparse step left to the Python step

    def save(self, t: float, x, v, f, state, rigid, low=None, high=None) -> None:
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


def march(net: Network, dt: float, n_steps: int, save_every: int, rows: int, path: str) -> Trajectory:
    """Backward Euler on ``net`` for ``n_steps`` steps of ``dt``, saving every ``save_every``-th
    (``rows`` rows in all) with the step of ``path`` (``"compiled"``, ``"python"``,
    :data:`lumped.solvers.friction_compiled.PATH` or :data:`lumped.solvers.network_sparse.PATH`)."""
    first, second = net.incidence()
    topology = sparse.plan(net) if path == sparse.PATH else None  # once a run: a loop over the elements
    x, v, state, sol = _initial(net, first, second, path, topology)
    inertia = np.array([m.mass / dt for m in net.masses])
    rec = _Record(rows, len(net.masses), len(net.elements))
    rec.save(0.0, x, v, sol.f, state, False, sol.low, sol.high)
    start = _Start(x, v, state, inertia, _sigma(net, inertia, dt), np.where(v == 0, 0, 1).astype(np.int64))
    run = {"compiled": _run_compiled, friction.PATH: _run_friction}.get(path, _run_python)
    if path == sparse.PATH:
        run = functools.partial(_run_sparse, topology=topology)
    v, most = run(net, dt, n_steps, save_every, rec, start)
    if rec.python_steps:  # the sparse step left some steps (rigid loops) to the Python step
        path = f"{path}+python ({rec.python_steps} of {n_steps} steps)"
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
        events=tuple(rec.jumps),
    )


def _unsettled(n: int, dt: float, elements: int) -> ValueError:
    """The message of a step whose iteration did not settle: the step solver's failure, named as
    such (the step problem has a solution, unique in its velocities, at every ``dt``)."""
    return ValueError(
        f"the step solver failed at the step to t = {n * dt:.6g} s (step {n}): {unsettled(default_bound(elements))}"
    )


def _failed(net: Network, n: int, dt: float, err: StepError) -> ValueError:
    """The message of a Python step that failed: unsettled, or a loop of rigid pieces whose rates disagree."""
    if not err.elements:
        base = str(_unsettled(n, dt, len(net.elements)))
        if err.changing:
            base += f"; elements still changing: {listed([net.elements[e].name for e in err.changing])}"
        if err.phi is not None:
            base += f"; the step's function Phi = {err.phi:.9g} W at the last iterate"
        return ValueError(base)
    names = listed([net.elements[e].name for e in err.elements])
    return ValueError(f"elements {names} {err} at the step to t = {n * dt:.6g} s")


def _compiled_failed(
    net: Network, dt: float, steps: tuple[int, int, int], rec: _Record, start: _Start, marching: tuple, kind: int
) -> ValueError:
    """The message of a compiled step that failed (``kind`` 1: it did not settle; 2: not finite) at step
    ``steps[0]``, the state before it in ``marching``.  An unsettled one is taken again by the Python step
    from that state: the message then names what the Python step's failure names (the elements still
    changing, ``Phi`` at the last iterate), or says that the Python step settles it, where the compiled
    twin parts from it (both a defect, said as such)."""
    n = steps[0]
    if kind != 1:
        return _overflowed(n, dt)
    time = np.array([n * dt])
    delta = _shifts(net, time, dt)
    now = (marching[0].copy(), marching[1].copy(), [float(s) for s in marching[2]], None)
    try:
        _python_step(net, dt, steps, rec, start, now, net.load_table(time)[0], None if delta is None else delta[0])
    except ValueError as err:
        return err
    return ValueError(
        f"{_unsettled(n, dt, len(net.elements))}; the Python step settles this step from the same state, so the "
        "compiled step parts from its twin there"
    )


def _overflowed(n: int, dt: float) -> ValueError:
    return ValueError(f"the run overflowed at t = {n * dt:.6g} s (step {n}): a velocity or force is not finite")


def _run_python(
    net: Network, dt: float, n_steps: int, save_every: int, rec: _Record, start: _Start
) -> tuple[np.ndarray, int]:
    """The Python step, one step at a time; returns the last velocities and the most iterations."""
    v, x, state, rest = start.v, start.x, start.state, start.rest
    modes, most = None, 0
    for begin in range(1, n_steps + 1, _BLOCK):
        stop = min(begin + _BLOCK - 1, n_steps)
        times = np.arange(begin, stop + 1) * dt
        table, shifts = net.load_table(times), _shifts(net, times, dt)
        for n in range(begin, stop + 1):
            delta = None if shifts is None else shifts[n - begin]
            sol, x, state = _python_step(
                net, dt, (n, n_steps, save_every), rec, start, (x, v, state, modes), table[n - begin], delta
            )
            v, modes, most = sol.v, sol.modes, max(most, sol.iterations)
            rest[v != 0] = n + 1
    return v, most


def _python_step(
    net: Network,
    dt: float,
    steps: tuple[int, int, int],
    rec: _Record,
    start: _Start,
    now: tuple,
    load: np.ndarray,
    delta: np.ndarray | None,
) -> tuple:
    """The Python step to ``t = n dt`` (``steps = (n, n_steps, save_every)``) from ``now = (x, v, state,
    modes)``, the step's loads and rate shifts; saves the row if it is one; returns ``(sol, x, state)``."""
    n, n_steps, save_every = steps
    x, v, state, modes = now
    first, second = net.incidence()
    rhs = start.inertia * v + load
    graphs = _graphs(net, state, dt, None, delta)
    saved = n % save_every == 0 or n == n_steps
    try:
        sol = solve_step(first, second, start.inertia, rhs, graphs, start.sigma, modes, ranges=saved)
    except StepError as err:
        raise _failed(net, n, dt, err) from None
    x = x + dt * sol.v
    w = sol.w if delta is None else sol.w + delta  # the true rates of elements joined to drivers
    before = state
    state = [
        el.next_state(s, dt, float(we), float(fe), r)
        for el, s, we, fe, r in zip(net.elements, before, w, sol.f, sol.rigid)
    ]
    for e, el in enumerate(net.elements):
        if el.jumps and state[e] != before[e]:
            rec.jumps.append(Jump(n * dt, el.name, int(before[e]), int(state[e])))
    if not (np.isfinite(sol.v).all() and np.isfinite(sol.f).all()):
        raise _overflowed(n, dt)
    if saved:
        rec.save(n * dt, x, sol.v, sol.f, state, sol.rigid, sol.low, sol.high)
    return sol, x, state


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
            raise _compiled_failed(net, dt, (int(counters[1]), n_steps, save_every), rec, start, marching, counters[2])
    return marching[1], int(counters[3])


def _run_sparse(
    net: Network, dt: float, n_steps: int, save_every: int, rec: _Record, start: _Start, topology: sparse.SparsePlan
) -> tuple[np.ndarray, int]:
    """The compiled sparse step (:mod:`lumped.solvers.network_sparse`), block by block; a step it leaves to
    Python (a rigid loop) runs :func:`_python_step`, and C resumes after it.  Same contract."""
    loaded = np.array(net.loaded_masses(), dtype=np.int64)
    counters = np.array([rec.row, 0, 0, 0], dtype=np.int64)
    modes = np.full(len(net.elements), -1, dtype=np.int64)
    x, v, state = start.x.copy(), start.v.copy(), np.array(start.state, dtype=float)
    points = sparse.points(net)
    marching = (x, v, state, modes, start.rest, counters, points)
    record = (rec.t, rec.x, rec.v, rec.force, rec.state, rec.rigid.view(np.uint8))
    block = max(1, min(_BLOCK, _TABLE_VALUES // max(1, loaded.size + len(net.drivers))))
    most = 0
    for begin in range(1, n_steps + 1, block):
        stop = min(begin + block - 1, n_steps)
        times = np.arange(begin, stop + 1) * dt
        table = net.load_table(times, loaded)
        means = _means(net, times, dt)
        n = begin
        while n <= stop:
            steps = (n, stop, n_steps, save_every)
            sparse.march_block(
                topology,
                start.inertia,
                start.sigma,
                loaded,
                marching,
                record,
                table[n - begin :],
                means[n - begin :],
                dt,
                steps,
            )
            rec.row = int(counters[0])
            if counters[2] != 3:
                break
            n = int(counters[1])  # its rigid elements close a loop: this step in Python
            counters[2] = 0
            delta = _shifts(net, times[n - begin : n - begin + 1], dt)
            full = net.load_table(times[n - begin : n - begin + 1])[0]
            now = (x.copy(), v.copy(), state.tolist(), sparse.python_modes(topology, modes, points))
            sol, new_x, new_state = _python_step(
                net, dt, (n, n_steps, save_every), rec, start, now, full, None if delta is None else delta[0]
            )
            counters[0] = rec.row
            x[:], v[:], state[:] = new_x, sol.v, new_state
            sparse.store_modes(sol.modes, modes, points)
            start.rest[v != 0] = n + 1
            most, n = max(most, sol.iterations), n + 1
            rec.python_steps += 1
        if counters[2]:
            raise _compiled_failed(net, dt, (int(counters[1]), n_steps, save_every), rec, start, marching, counters[2])
    return v, max(most, int(counters[3]))


def _run_friction(
    net: Network, dt: float, n_steps: int, save_every: int, rec: _Record, start: _Start
) -> tuple[np.ndarray, int]:
    """The compiled one-mass friction loop (:mod:`lumped.solvers.friction_compiled`), block by block; same contract."""
    topology, loaded = friction.plan(net), bool(net.loaded_masses())
    counters = np.array([rec.row, 0, 0, 0], dtype=np.int64)
    marching = (start.x.copy(), start.v.copy(), np.array(start.state, dtype=float), start.rest, counters)
    record = (rec.t, rec.x, rec.v, rec.force, rec.state, rec.rigid.view(np.uint8))
    for begin in range(1, n_steps + 1, _BLOCK):
        stop = min(begin + _BLOCK - 1, n_steps)
        table = net.load_table(np.arange(begin, stop + 1) * dt)[:, 0] if loaded else np.empty(0)
        steps = (begin, stop, n_steps, save_every)
        friction.march_block(topology, float(start.inertia[0]), marching, record, table, dt, steps)
        rec.row = int(counters[0])
        if counters[2]:
            raise _compiled_failed(net, dt, (int(counters[1]), n_steps, save_every), rec, start, marching, counters[2])
    return marching[1], int(counters[3])
