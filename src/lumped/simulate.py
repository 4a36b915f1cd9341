"""One entry point for every method: ``simulate(...) -> Trajectory``."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from lumped.event_driven import solve_exact
from lumped.forcing import SwitchedSine
from lumped.results import Trajectory
from lumped.system import Oscillator
from lumped.timestepping import backward_euler

__all__ = ["METHODS", "simulate"]

#: Methods accepted by :func:`simulate` and ``--method``.
METHODS = ("backward-euler", "exact")


def simulate(
    oscillator: Oscillator,
    t_end: float,
    dt: float,
    *,
    x0: float = 0.0,
    v0: float = 0.0,
    force: SwitchedSine | Callable[[np.ndarray], np.ndarray] | None = None,
    method: str = "backward-euler",
    save_every: int = 1,
) -> Trajectory:
    """Solve the DAE (8) on the grid ``t_n = n*dt`` by ``method``.

    ``"backward-euler"`` is Algorithm 1 (:func:`~lumped.timestepping.backward_euler`);
    ``"exact"`` samples the event-driven solution
    (:func:`~lumped.event_driven.solve_exact`) on the same grid.  The other
    parameters are those of :func:`~lumped.timestepping.backward_euler`.
    """
    if method == "backward-euler":
        return backward_euler(oscillator, t_end, dt, x0=x0, v0=v0, force=force,
                              save_every=save_every)  # fmt: skip
    if method == "exact":
        sol = solve_exact(oscillator, t_end, x0=x0, v0=v0, force=force)  # type: ignore[arg-type]
        return sol.sample(dt, save_every)
    raise ValueError(f"method must be one of {', '.join(METHODS)}; got {method!r}")
