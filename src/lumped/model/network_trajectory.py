"""A network's motion: :class:`NetworkTrajectory`, the one result of every network run.

It lives apart from the integrator (:mod:`lumped.drivers.network`) so that
every path that runs a network returns it without importing another path: the
active-set step, Algorithm 1 for the paper's system, and the single-mass
methods of :mod:`lumped.drivers.one_mass`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lumped.model.network import Network

__all__ = ["NetworkTrajectory"]


@dataclass(frozen=True)
class NetworkTrajectory:
    """A network's motion on the saved grid points.

    Attributes
    ----------
    t : ndarray, (N,), s
    x, v : ndarray, (N, masses), m and m/s
    force : ndarray, (N, elements), N
        Tensions; at ``t = 0`` the consistent initial forces.
    state : ndarray, (N, elements)
        Each element's internal variable (a spring's force, a string's
        elongation, a Maxwell element's force; 0 for none).
    rigid : ndarray of bool, (N, elements)
        Element on a rigid piece in the step ending there (sticking, taut,
        locked); False at ``t = 0``.
    rest_time, rest_position : ndarray, (masses,)
        First time of each mass's final run of ``v == 0`` on the full grid
        and its position there; ``nan`` if it still moves at the end.
    network : Network
    dt : float
    solver : str
        The path that ran: ``"algorithm1"`` (the paper's system),
        ``"resolvent"`` (one mass, a spring and a Herschel-Bulkley element:
        backward Euler through the law's resolvent), ``"compiled"`` (the
        active-set step in C, :mod:`lumped.solvers.network_compiled`), ``"python"``
        (the active-set step of :mod:`lumped.solvers.network_step`), or the
        single-mass method that :func:`lumped.solve` ran.
    iterations : int
        Largest number of active-set iterations in a step (0 for Algorithm 1).
    """

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    force: np.ndarray
    state: np.ndarray
    rigid: np.ndarray
    rest_time: np.ndarray
    rest_position: np.ndarray
    network: Network
    dt: float
    solver: str
    iterations: int

    def columns(self, suffix: str) -> dict[str, np.ndarray]:
        """The output arrays: ``.npz`` names or ``.csv`` columns (see book/guide/systems.md)."""
        net = self.network
        if suffix == ".npz":
            return {
                "t": self.t,
                "x": self.x,
                "v": self.v,
                "force": self.force,
                "mass_names": np.array(net.mass_names),
                "element_names": np.array(net.element_names),
            }
        out = {"t": self.t}
        out |= {f"x_{n}": self.x[:, i] for i, n in enumerate(net.mass_names)}
        out |= {f"v_{n}": self.v[:, i] for i, n in enumerate(net.mass_names)}
        out |= {f"F_{n}": self.force[:, i] for i, n in enumerate(net.element_names)}
        return out

    def summary(self, shown: int = 10) -> str:
        """Each mass's rest time and position, or that it still moves (the first ``shown`` masses)."""
        parts, names = [], self.network.mass_names
        for i, name in enumerate(names[:shown]):
            if math.isnan(self.rest_time[i]):
                parts.append(f"{name} still moving at t = {self.t[-1]:.6g} s (x = {self.x[-1, i]:.9g} m)")
            else:
                parts.append(
                    f"{name} at rest from t = {self.rest_time[i]:.10g} s at x = {self.rest_position[i]:.10g} m"
                )
        more = f"; ... and {len(names) - shown} more masses" if len(names) > shown else ""
        return "; ".join(parts) + more
