"""The driver: every method of the registry takes a :class:`~lumped.model.problem.Problem`.

:func:`solve` is the one entry point: ``solve(problem, dt, method=...)``
runs any problem by any registered method (:data:`lumped.drivers.methods.METHODS`,
re-exported as ``lumped.METHODS``) and returns the network's
:class:`~lumped.model.trajectory.Trajectory`.  A method that
runs any network (backward Euler) gets the whole system, and the paper's
system goes to Algorithm 1's kernel by itself; a method that runs one mass
gets the system as an oscillator, or refuses it in one line.
:func:`simulate` is the paper's system seen directly: one oscillator, its
initial state and force, and the one-mass :class:`~lumped.model.trajectory.Trajectory`
with the dashpot's force and the energy balance.  (The module is not called
``simulate``: ``lumped/__init__.py`` exports the function under that name.)
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import replace

import numpy as np

from lumped.drivers import methods
from lumped.drivers.methods import METHODS
from lumped.drivers.network import simulate_network
from lumped.drivers.one_mass import network_trajectory
from lumped.model.forcing import SwitchedSine, sine_form
from lumped.model.problem import Problem, oscillator_network
from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate

__all__ = ["METHODS", "method_options", "simulate", "solve"]

Force = SwitchedSine | Callable[[np.ndarray], np.ndarray] | None


def method_options(method: str, options: Mapping[str, object]) -> dict[str, object]:
    """Check that ``method`` is registered and takes every option in ``options``; the options, checked.

    Raises
    ------
    ValueError
        ``method must be one of ...``, ``<option>: method ... takes no option ...``
        or the option's own check.
    """
    return methods.get(method).check_options(options)


def simulate(
    oscillator: Oscillator,
    t_end: float,
    dt: float,
    *,
    x0: float = 0.0,
    v0: float = 0.0,
    force: Force = None,
    method: str = "backward-euler",
    save_every: int = 1,
    **options: object,
) -> Trajectory:
    """Solve the DAE (8) on the grid ``t_n = n*dt`` by ``method``.

    ``"backward-euler"`` is Algorithm 1 (:func:`~lumped.solvers.backward_euler.backward_euler`);
    ``"exact"`` samples the event-driven solution
    (:func:`~lumped.solvers.exact.solve_exact`) on the same grid;
    ``"event-driven"`` integrates the slip phases of any dashpot law
    (:func:`~lumped.solvers.event_driven.solve_event_driven`) and takes the
    option ``rtol``; ``"event-locating"`` and ``"theta"`` are the schemes of
    :mod:`lumped.solvers.event_capturing` and :mod:`lumped.solvers.theta` (the latter at ``theta = 1/2``).  ``method`` is a
    key of :data:`METHODS`; ``options`` are the method's own
    (:func:`method_options` checks them and refuses any other).  A method
    that cannot run ``oscillator`` (``exact`` with a law that has no Bingham
    form) is refused in one line naming it and the reason, as is a forcing
    that is not a sine for a method that needs its formula
    (:attr:`~lumped.drivers.methods.Method.sine_forcing`); a
    :class:`~lumped.model.forcing.Constant` on from ``t = 0`` is run as the
    sine it equals (:func:`~lumped.model.forcing.sine_form`).  The other parameters are
    those of :func:`~lumped.solvers.backward_euler.backward_euler`.
    """
    options = method_options(method, options)
    save_every = validate.stride("save_every", save_every)  # before a method solves, then samples
    run = METHODS[method]
    if isinstance(oscillator, Oscillator) and (reason := run.refusal(oscillator)) is not None:
        raise ValueError(reason)
    given, force = force, sine_form(force)
    if (reason := run.force_refusal(force)) is not None:
        net = oscillator_network(oscillator, x0, v0, given) if isinstance(oscillator, Oscillator) else None
        if net is not None and run.by_network(force, net):  # its solver of networks takes any load
            return run.piecewise_networks(net, t_end, dt, save_every=save_every)  # type: ignore[misc]
        raise ValueError(reason)
    tr = run(oscillator, t_end, dt, x0, v0, force, save_every, **options)
    if force is None:
        return tr
    return replace(tr, network=oscillator_network(oscillator, x0, v0, given))  # the system with its load


def solve(
    problem: Problem, dt: float, *, method: str = "backward-euler", save_every: int = 1, **options: object
) -> Trajectory:
    """Solve ``problem`` on the grid ``t_n = n*dt`` by ``method``.

    Parameters
    ----------
    problem : Problem
        The system, its loads and initial state, and the span.
    dt : float, s
        The grid step (the methods that locate events still report on this grid).
    method : str
        A key of :data:`METHODS`; ``options`` are its own (``rtol`` for
        ``"event-driven"``).
    save_every : int
        Stride between the computed grid and the saved points.

    Returns
    -------
    Trajectory
        Positions and velocities of every mass, the force of every element, the events.

    Raises
    ------
    ValueError
        For a bad argument (named), or a method that cannot run the problem:
        one line naming the method and the reason (a single-mass method and a
        network that is not the paper's form, ``exact`` and a law with no
        Bingham form, ``exact`` and a network element or load that has no
        closed form per phase).

    Notes
    -----
    A network of the one-mass form goes to the method's one-mass solver
    (the paper's system to Algorithm 1's kernel), unchanged bit for bit; any
    other network goes to a method that runs any network
    (:attr:`~lumped.drivers.methods.Method.network_solvers`) or to its
    solver of piecewise-linear networks
    (:attr:`~lumped.drivers.methods.Method.piecewise_networks`:
    ``exact``'s :func:`~lumped.solvers.exact_network.solve_exact_network`,
    ``event-locating``'s
    :func:`~lumped.solvers.event_capturing_network.solve_capturing_network`),
    which also runs a one-mass system whose load the one-mass solver does
    not take (a table, ground motion) when it takes any load.
    """
    run = methods.get(method)
    options = run.check_options(options)
    if not isinstance(problem, Problem):
        raise ValueError(f"problem must be a Problem, got {type(problem).__name__}")
    if run.runs_networks:
        return simulate_network(problem.system, problem.t_end, dt, save_every=save_every)
    try:
        form = problem.one_mass()
    except ValueError as err:
        if run.piecewise_networks is not None:  # its phases solved in turn, or a refusal naming the element
            return run.piecewise_networks(problem.system, problem.t_end, dt, save_every=save_every, **options)
        raise ValueError(f"method {method!r} needs a one-mass system; the network {err}") from None
    if run.by_network(problem.force, problem.system):  # a load its one-mass solver lacks
        return run.piecewise_networks(problem.system, problem.t_end, dt, save_every=save_every)  # type: ignore[misc]
    mass = problem.system.masses[0]
    tr = simulate(
        form.oscillator,
        problem.t_end,
        dt,
        x0=mass.x0,
        v0=mass.v0,
        force=problem.force,
        method=method,
        save_every=save_every,
        **options,
    )
    return network_trajectory(problem.system, form, tr, method)
