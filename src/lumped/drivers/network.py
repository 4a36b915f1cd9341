"""Backward Euler for a network: the method ``"backward-euler"`` of :func:`lumped.solve`.

:func:`run_network` is what :func:`lumped.solve` runs for that method (and
:func:`lumped.simulate_network`, a shim over :func:`lumped.solve`, with it).
It checks the arguments once (the grid, the output's size, the
estimated run time), picks the path and hands the run to a solver; the time
loop itself is :func:`lumped.solvers.backward_euler_network.march`.

The paper's system written as a network (one mass, one ``spring`` and one
``bingham`` to the ground, any loads) is handed to Algorithm 1
(:func:`lumped.backward_euler`) itself when ``solver="auto"``: the same
numbers bit for bit, at the compiled kernel's speed.  With a
``herschel-bulkley`` element instead it goes to the same function, whose
step is then the law's resolvent (a root solve).  Every other network takes
the active-set step, in C (:mod:`lumped.solvers.network_compiled`) when its elements
are piecewise linear and its links form a forest or close one loop, else, for one
mass with a friction contact (a block on a belt), in the compiled friction loop
(:mod:`lumped.solvers.friction_compiled`), else in the compiled sparse step
(:mod:`lumped.solvers.network_sparse`: any network of piecewise-linear elements and
friction contacts of a ``kernel_form``, Stribeck falls included, loops through the ground
included), else in Python.
"""

from __future__ import annotations

from lumped.drivers.methods import NETWORK_SOLVERS
from lumped.drivers.one_mass import network_trajectory
from lumped.model.forcing import check_spans, one_force, sine_form
from lumped.model.network import Network
from lumped.model.problem import OneMass, one_mass_form
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate

# The step solvers (the active-set loop, the compiled kernels, the uniqueness check) are imported by the
# functions that run them: the paper's system, which goes to Algorithm 1, loads none of them (start-up).

__all__ = ["SOLVERS", "check_active_set", "paper_form", "run_network"]

#: Step solvers by name (see :func:`run_network`): a view of the registry
#: (:data:`lumped.drivers.methods.NETWORK_SOLVERS`, those of the method that runs any network).
SOLVERS = NETWORK_SOLVERS


def _cost(path: str) -> tuple[float, float]:
    """Estimated cost (s) of a step on ``path``: a constant and a part per element.

    Measured on this project's 2-core machine, shared and busy
    (benchmarks/bench_network.py, chains): Python about 2e-5 + 1e-5 per
    element; compiled about 1e-6 + 4e-8 to 1e-7 per element; a margin of 2.
    The one-mass friction loop: about 3e-8 s a step (benchmarks/bench_belt.py), a margin of 10.
    The sparse step: about 0.04 to 0.12 us per block and step on the floor chain of
    benchmarks/bench_chain.py (three elements a block: 1.5e-8 to 4e-8 s per element, CPU
    time; the wall time on the busy machine up to twice that), a margin of 2 to 3.
    """
    from lumped.solvers import friction_compiled as friction
    from lumped.solvers import network_sparse as sparse

    costs = {"python": (4e-5, 2e-5), "compiled": (4e-6, 2e-7), friction.PATH: (3e-7, 0.0), sparse.PATH: (4e-6, 1e-7)}
    return costs[path]


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
    return network_trajectory(net, form, tr, tr.solver)  # "algorithm1", or "resolvent" for another law


def run_network(network: Network, t_end: float, dt: float, *, save_every: int = 1, solver: str = "auto") -> Trajectory:
    """Integrate a network with backward Euler on the grid ``t_n = n*dt`` (``solve``'s ``"backward-euler"``).

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
        piecewise linear, the link graph a forest or one loop, the kernel built), in
        the compiled one-mass friction loop when
        :func:`lumped.solvers.friction_compiled.ineligible` allows (one mass, linear
        springs and dashpots, one friction contact of a ``kernel_form``, drivers at
        constant velocities; ``Trajectory.solver`` is then ``"one-mass-friction"``), in the
        compiled sparse step when :func:`lumped.solvers.network_sparse.ineligible` allows
        (``"compiled-banded"``; ``"compiled-banded+python (k of n steps)"`` when rigid loops
        left ``k`` steps to the Python step), and in Python otherwise.  ``"compiled"`` and
        ``"python"`` force one path (``"compiled"`` refuses a network no compiled step can run).

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
    t_end, dt, save_every, n_steps = validate.grid(t_end, dt, save_every)
    if solver not in SOLVERS:
        raise ValueError(f"solver must be one of {', '.join(SOLVERS)}; got {solver!r}")
    pair = _paper_form(network) if solver == "auto" else None
    if pair is not None:
        return _via_algorithm1(network, pair, t_end, dt, save_every)
    from lumped.solvers import backward_euler_network

    path, rows, _ = check_active_set(network, dt, n_steps, save_every, solver)
    return backward_euler_network.march(network, dt, n_steps, save_every, rows, path)


def check_active_set(network: Network, dt: float, n_steps: int, save_every: int, solver: str) -> tuple[str, int, float]:
    """The checks of an active-set run before any step: the step's uniqueness bound, the path, the loads'
    span, the output's size and the estimated time; returns ``(path, saved rows, estimated seconds)``.

    :func:`run_network` makes them before its time loop, and a sweep of a system file
    (:mod:`lumped.drivers.sweep.system`) for every row before the first runs.
    """
    from lumped.solvers.uniqueness import check_step

    check_step(network, dt)
    path = _path(network, solver)
    check_spans(network.loads, network.drivers, n_steps * dt)  # a sine's range, to the grid's last time
    width = 1 + 2 * len(network.masses) + 3 * len(network.elements)
    rows = validate.output_size(n_steps, save_every, width)
    fixed, per_element = _cost(path)
    seconds = validate.run_time(n_steps, fixed + per_element * len(network.elements), f"the network step ({path})")
    return path, rows, seconds


def paper_form(network: Network, solver: str = "auto") -> OneMass | None:
    """The oscillator :func:`run_network` hands to Algorithm 1 with ``solver``, or ``None`` (the active-set step)."""
    return _paper_form(network) if solver == "auto" else None


def _path(net: Network, solver: str) -> str:
    """``"compiled"``, :data:`lumped.solvers.friction_compiled.PATH` (one mass with a friction contact
    that the network kernel cannot run), :data:`lumped.solvers.network_sparse.PATH` (any other network
    the sparse step runs) or ``"python"``: the active-set step's path for ``solver``."""
    from lumped.solvers import friction_compiled as friction
    from lumped.solvers import network_compiled as kernel
    from lumped.solvers import network_sparse as sparse

    if solver == "python":
        return "python"
    reason = kernel.ineligible(net)
    if reason is None:
        return "compiled"
    other = friction.ineligible(net)
    if other is None:
        return friction.PATH
    general = sparse.ineligible(net)
    if general is None:
        return sparse.PATH
    if solver == "compiled":
        raise ValueError(f"solver: 'compiled' cannot run this network: {general}")
    return "python"
