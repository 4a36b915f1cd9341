"""The driver: one entry point for every method, ``simulate(...) -> Trajectory``.

The methods are those of the one registry, :data:`lumped.drivers.methods.METHODS`
(re-exported here and as ``lumped.METHODS``); :func:`simulate` looks the
method up there, checks its options and refuses what it cannot run.  (The
module is not called ``simulate``: ``lumped/__init__.py`` exports the
function under that name, so ``import lumped.simulate`` would hand back the
function, not a module.)
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np

from lumped.drivers import methods
from lumped.drivers.methods import METHODS
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate

__all__ = ["METHODS", "simulate", "method_options"]

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
    option ``rtol``; ``"event-capturing"`` and ``"theta"`` are the schemes of
    :mod:`lumped.solvers.event_capturing` and :mod:`lumped.solvers.theta` (the latter at ``theta = 1/2``).  ``method`` is a
    key of :data:`METHODS`; ``options`` are the method's own
    (:func:`method_options` checks them and refuses any other).  A method
    that cannot run ``oscillator`` (``exact`` with a law that has no Bingham
    form) is refused in one line naming it and the reason.  The other parameters are
    those of :func:`~lumped.solvers.backward_euler.backward_euler`.
    """
    options = method_options(method, options)
    save_every = validate.stride("save_every", save_every)  # before a method solves, then samples
    run = METHODS[method]
    if isinstance(oscillator, Oscillator) and (reason := run.refusal(oscillator)) is not None:
        raise ValueError(reason)
    return run(oscillator, t_end, dt, x0, v0, force, save_every, **options)
