"""The one entry point, :func:`solve`: every method of the registry takes a :class:`~lumped.model.problem.Problem`.

``solve(problem, dt, method=...)`` runs any problem by any registered method
(:data:`lumped.drivers.methods.METHODS`, re-exported as ``lumped.METHODS``)
and returns one :class:`~lumped.model.trajectory.Trajectory`, for one mass or
many, or refuses the problem in one line that names the method and the reason.
The fast paths are chosen here, never by the caller: backward Euler runs any
network (:func:`lumped.drivers.network.run_network`, which hands the paper's
system to Algorithm 1's kernel); a method that runs one mass gets a network
of the one-mass form as an oscillator (the exact one-mass solver for
``"exact"``), and another network goes to its solver of piecewise-linear
networks, or is refused.

The other ways to start a run that users know are shims over :func:`solve`
(the same stack, the same numbers): :func:`simulate` (one oscillator) and
:func:`simulate_network` (a network by backward Euler, with its ``solver``).
(The module is not called ``simulate``: ``lumped/__init__.py`` exports the
function under that name.)
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from lumped.drivers import methods
from lumped.drivers.methods import METHODS, Method
from lumped.drivers.network import run_network
from lumped.drivers.one_mass import network_trajectory
from lumped.model.forcing import SwitchedSine, check_spans, sine_form
from lumped.model.network import Network
from lumped.model.oscillator import Oscillator
from lumped.model.problem import OneMass, Problem
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate

__all__ = ["METHODS", "method_options", "simulate", "simulate_network", "solve"]

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


def solve(
    problem: Problem, dt: float, *, method: str = "backward-euler", save_every: int = 1, **options: object
) -> Trajectory:
    """Solve ``problem`` on the grid ``t_n = n*dt`` by ``method``: the one entry point.

    Parameters
    ----------
    problem : Problem
        The system, its loads and initial state, and the span.
    dt : float, s
        The grid step (the methods that locate events still report on this grid).
    method : str
        A key of :data:`METHODS`; ``options`` are its own (``rtol`` for
        ``"event-driven"``, ``theta`` for ``"moreau-jean"``, and ``solver`` for
        ``"backward-euler"``: ``"auto"``, ``"active-set"``, ``"compiled"`` or
        ``"python"``, see :func:`lumped.drivers.network.run_network`).
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
        network that is not the paper's form, or that has driven points or a
        friction contact whose graph is not monotone, ``exact`` and a law with no
        Bingham form, ``exact`` and a network element or load that has no
        closed form per phase).

    Notes
    -----
    The caller never picks a fast path.  ``"backward-euler"`` runs any network
    (:func:`~lumped.drivers.network.run_network`: the paper's system goes to
    Algorithm 1's kernel, bit for bit).  For the other methods a network of
    the one-mass form goes to the method's one-mass solver (the exact one-mass
    solver for ``"exact"``), unchanged bit for bit; any other network goes to
    its solver of piecewise-linear networks
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
    save_every = validate.stride("save_every", save_every)  # before a method solves, then samples
    if run.runs_networks:
        return run_network(problem.system, problem.t_end, dt, save_every=save_every, **options)  # type: ignore[arg-type]
    if run.piecewise_networks is None:  # the one-mass route: no driven point, no falling graph
        problem.system.refuse_drivers(f"method {method!r}")
        problem.system.refuse_non_monotone(f"method {method!r}")
    try:
        form = problem.one_mass()
    except ValueError as err:
        if run.piecewise_networks is not None:  # its phases solved in turn, or a refusal naming the element
            check_spans(problem.system.loads, problem.system.drivers, problem.t_end)  # before any phase
            return run.piecewise_networks(problem.system, problem.t_end, dt, save_every=save_every, **options)
        raise ValueError(f"method {method!r} needs a one-mass system; the network {err}") from None
    if run.by_network(problem.force, problem.system):  # a load its one-mass solver lacks
        check_spans(problem.system.loads, problem.system.drivers, problem.t_end)
        return run.piecewise_networks(problem.system, problem.t_end, dt, save_every=save_every)  # type: ignore[misc]
    return _one_mass(run, method, problem, form, dt, save_every, options)


def _one_mass(
    run: Method, method: str, problem: Problem, form: OneMass, dt: float, save_every: int, options: dict[str, object]
) -> Trajectory:
    """``problem``, a network of the one-mass form ``form``, by ``run``'s one-mass solver, written on the network."""
    if (reason := run.refusal(form.oscillator)) is not None:
        raise ValueError(reason)
    force = sine_form(problem.force)  # a constant on from t = 0 runs as the sine it equals
    if (reason := run.force_refusal(force)) is not None:
        raise ValueError(reason)
    mass = problem.system.masses[0]
    tr = run(form.oscillator, problem.t_end, dt, mass.x0, mass.v0, force, save_every, **options)
    return network_trajectory(problem.system, form, tr, method)


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
    """Solve the DAE (8) of one oscillator on the grid ``t_n = n*dt`` by ``method``.

    A shim: ``solve(Problem.oscillator(oscillator, t_end, x0=x0, v0=v0, force=force), dt,
    method=method, save_every=save_every, **options)``, kept for the paper's
    system written as its parts; it adds nothing, and gives the same numbers.

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
    problem = Problem.oscillator(oscillator, t_end, x0=x0, v0=v0, force=force)
    return solve(problem, dt, method=method, save_every=save_every, **options)


def simulate_network(
    network: Network, t_end: float, dt: float, *, save_every: int = 1, solver: str = "auto"
) -> Trajectory:
    """Integrate a network with backward Euler on the grid ``t_n = n*dt``.

    A shim: ``solve(Problem(network, t_end), dt, method="backward-euler",
    save_every=save_every, solver=solver)``; it adds nothing, and gives the
    same numbers.  ``solver`` is one of ``"auto"``, ``"active-set"``,
    ``"compiled"``, ``"python"`` (:func:`lumped.drivers.network.run_network`
    says what each does).
    """
    if not isinstance(network, Network):
        raise ValueError(f"network must be a Network, got {type(network).__name__}")
    return solve(Problem(network, t_end), dt, method="backward-euler", save_every=save_every, solver=solver)
