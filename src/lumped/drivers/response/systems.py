"""The forced systems whose periodic motions are followed, and their units.

A response curve is taken of one of two kinds of system under
``P sin(omega t)`` (:func:`period_map` dispatches):

* an :class:`~lumped.model.oscillator.Oscillator` with a Bingham or Coulomb
  dashpot, whose period map is the one-mass exact solver's
  (:func:`lumped.solvers.monodromy.period_map`, state ``(x, v)``);
* a :class:`LoadedNetwork`: a network of linear springs, Bingham and Coulomb
  elements and linear dashpots with the mass the sine acts on, whose period
  map is the exact network solver's
  (:func:`lumped.solvers.network_monodromy.network_period_map`, state
  ``(x_1 .. x_n, v_1 .. v_n)``).

:func:`response_system` reads either from a system file's network, and
refuses in one line what neither supports.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from lumped.model.network import Network
from lumped.model.oscillator import Oscillator
from lumped.model.problem import one_mass_form
from lumped.solvers.monodromy import PeriodMap
from lumped.solvers.monodromy import period_map as one_mass_map
from lumped.solvers.network_monodromy import NetworkPeriodMap, network_period_map
from lumped.solvers.network_phase import Parts, parts, refusal

__all__ = ["LoadedNetwork", "Scales", "period_map", "response_system"]


class LoadedNetwork(NamedTuple):
    """A network as arrays (:class:`~lumped.solvers.network_phase.Parts`), the index of the mass the sine acts
    on, and the names of its masses and elements."""

    parts: Parts
    mass: int
    masses: tuple[str, ...]
    elements: tuple[str, ...]

    @property
    def stiffness(self) -> np.ndarray:
        """The stiffness matrix of the springs (n x n, N/m)."""
        return self.parts.b @ np.diag(self.parts.k) @ self.parts.b.T


class Scales(NamedTuple):
    """The units of the continuation: ``x`` (m), ``v`` (m/s) and ``omega`` (rad/s)."""

    x: float
    v: float
    omega: float

    @classmethod
    def of(cls, system: Oscillator | LoadedNetwork, amplitude: float) -> Scales:
        """``X_s = P/k``, ``X_s omega_n`` and ``omega_n = sqrt(k/m)``; for a network, ``k`` and ``m`` are the
        loaded mass's diagonal stiffness (the springs that meet it) and its mass."""
        if isinstance(system, Oscillator):
            k, m = system.stiffness, system.mass
        else:
            k, m = float(system.stiffness[system.mass, system.mass]), float(system.parts.m[system.mass])
        wn = math.sqrt(k / m)
        xs = amplitude / k
        return cls(xs, xs * wn, wn)

    def state(self, z: np.ndarray) -> np.ndarray:
        """The state (positions, then velocities) in these units."""
        z = np.asarray(z, dtype=float)
        return z / np.repeat([self.x, self.v], z.size // 2)


def period_map(
    system: Oscillator | LoadedNetwork, amplitude: float, omega: float, z: np.ndarray
) -> PeriodMap | NetworkPeriodMap:
    """One forcing period of exact motion from the state ``z`` at ``t = 0``, with its monodromy matrix."""
    if isinstance(system, Oscillator):
        return one_mass_map(system, amplitude, omega, *z)
    return network_period_map(system.parts, system.mass, amplitude, omega, z, list(system.elements))


def response_system(network: Network, mass: str) -> Oscillator | LoadedNetwork:
    """The system of ``network`` with the sine on ``mass``: its oscillator if it is one mass on springs and a
    Bingham or Coulomb dashpot, else the network; ``ValueError`` naming what is not supported."""
    names = [m.name for m in network.masses]
    if mass not in names:
        raise ValueError(f"force_on: no mass named {mass!r} in the system (its masses: {', '.join(names)})")
    if network.loads:
        raise ValueError("system: the file has loads of its own; the response command applies the one sine load")
    try:
        osc = one_mass_form(network).oscillator
    except ValueError:
        osc = None
    if osc is not None and osc.dashpot.bingham_form() is not None:
        return osc
    if (reason := refusal(network)) is not None:
        raise ValueError(f"system: {reason.replace('method ' + repr('exact'), 'the period map')}")
    system = LoadedNetwork(parts(network), names.index(mass), tuple(names), tuple(network.element_names))
    if np.linalg.matrix_rank(system.stiffness) < len(names):
        raise ValueError(
            "system: the springs do not hold every mass to the ground (the stiffness matrix is singular), "
            "so its periodic motions are not isolated"
        )
    return system
