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
refuses in one line what neither supports.  A continuation follows a
:class:`Family` of such systems: in the forcing frequency
(:func:`omega_family`), or in the force's amplitude or any numeric parameter
of the system file at a fixed frequency (:func:`parameter_family`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from lumped.model.network import Network
from lumped.model.oscillator import Oscillator
from lumped.model.problem import one_mass_form
from lumped.model.system_parameters import system_parameters, with_values
from lumped.solvers.monodromy import PeriodMap
from lumped.solvers.monodromy import period_map as one_mass_map
from lumped.solvers.network_monodromy import NetworkPeriodMap, network_period_map
from lumped.solvers.network_sensitivities import Parameter, along
from lumped.solvers.network_phase import Parts, parts, refusal

__all__ = [
    "OMEGA_STEP",
    "Family",
    "LoadedNetwork",
    "Scales",
    "omega_derivative",
    "omega_family",
    "parameter_family",
    "period_map",
    "response_system",
]


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
    """One forcing period of exact motion from the state ``z`` at ``t = 0``, with its monodromy matrix;
    ``ValueError`` for a state that is not finite (a diverged iterate), before any phase is computed."""
    if not np.all(np.isfinite(z)):
        raise ValueError(f"force_omega: no periodic motion found at omega = {omega:.6g} rad/s (a state not finite)")
    if isinstance(system, Oscillator):
        return one_mass_map(system, amplitude, omega, *z)
    return network_period_map(system.parts, system.mass, amplitude, omega, z, list(system.elements))


#: Relative step of the central difference ``dPi/domega`` where no exact one is at hand: its truncation
#: (step^2, 1e-12) and round-off (the map's ~1e-14 over the step, 1e-8) leave a derivative good to 1e-8, which
#: only slows a Newton iteration's last digit, never moves the fixed point it converges to.
OMEGA_STEP = 1e-6


def omega_derivative(system: Oscillator | LoadedNetwork, amplitude: float, orbit) -> np.ndarray:
    """``dPi/domega`` (m s/rad, then m/rad) at ``orbit`` (an :class:`~lumped.drivers.response.shooting.Orbit`:
    its ``omega``, its state at ``t = 0`` and its period map): exact for one mass
    (:func:`lumped.solvers.monodromy.omega_derivative`) and for a network (the period's own phases
    differentiated in omega at the fixed end ``T``, :func:`lumped.solvers.network_sensitivities.along`, plus the
    end's move ``f(T) dT/domega``, ``dT/domega = -T/omega``); at an undamped resonance of one mass a central
    difference of relative step :data:`OMEGA_STEP`."""
    period = orbit.period
    if isinstance(period, PeriodMap) and (exact := period.omega_derivative) is not None:
        return exact
    if isinstance(period, NetworkPeriodMap):
        T = period.t_end
        dx, dv = along(period.parts, period.phases, period.events, [T], [Parameter("omega")], list(system.elements))
        last = period.phases[-1]
        _, v_end, a_end, _ = last.values(last.z(T))
        return np.concatenate([dx[0, :, 0], dv[0, :, 0]]) - np.concatenate([v_end, a_end]) * (T / orbit.omega)
    z, h = orbit.state, OMEGA_STEP * orbit.omega
    ends = [period_map(system, amplitude, orbit.omega + d, z).end for d in (h, -h)]
    return (ends[0] - ends[1]) / (2 * h)


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


class Family(NamedTuple):
    """A one-parameter family of forced systems, what a continuation follows: the parameter's ``name``
    (``omega``, ``amplitude``, or a system file's ``element.key``), its ``unit`` (the continuation's scale for
    it), ``member(value)`` giving ``(system, P, omega)`` (``ValueError`` for a value the system refuses) and the
    ``scales`` of the state (those of the member at the start)."""

    name: str
    unit: float
    member: Callable[[float], tuple[Oscillator | LoadedNetwork, float, float]]
    scales: Scales


def omega_family(system: Oscillator | LoadedNetwork, amplitude: float) -> Family:
    """The family in the forcing frequency (rad/s, in units of omega_n) of ``system`` under ``amplitude``."""

    def member(omega: float) -> tuple[Oscillator | LoadedNetwork, float, float]:
        if not (omega > 0 and math.isfinite(omega)):
            raise ValueError(f"force_omega must be finite and > 0, got {omega!r}")
        return system, amplitude, omega

    scales = Scales.of(system, amplitude)
    return Family("omega", scales.omega, member, scales)


def parameter_family(
    network: Network, mass: str, amplitude: float, omega: float, name: str, start: float, stop: float
) -> Family:
    """The family in ``name`` from ``start`` to ``stop`` of ``network`` under ``amplitude sin(omega t)`` on
    ``mass``: ``amplitude`` (the force's, N) or a numeric parameter of the file (``dashpot.threshold``,
    ``m.mass``: :func:`~lumped.model.system_parameters.system_parameters`), not an initial state (unused) nor
    a load (refused).  Its unit is ``max(|start|, |stop|)``.  ``ValueError`` (one line beginning ``vary``)
    for another name, or for a system refused at ``start`` or ``stop``."""
    unit = max(abs(start), abs(stop))
    if name == "amplitude":
        system = response_system(network, mass)

        def member(value: float) -> tuple[Oscillator | LoadedNetwork, float, float]:
            if not (value > 0 and math.isfinite(value)):
                raise ValueError(f"force_amplitude must be finite and > 0, got {value!r}")
            return system, value, omega

    else:
        (param,) = system_parameters(network, [name], "vary")
        if param.key in ("x0", "v0"):
            raise ValueError(f"vary: {name!r} is an initial state, which a periodic motion does not use")

        def member(value: float) -> tuple[Oscillator | LoadedNetwork, float, float]:
            return response_system(with_values(network, [param], [value]), mass), amplitude, omega

    for value in (start, stop):
        try:
            member(value)
        except ValueError as err:
            raise ValueError(f"vary: {name} = {value:g} gives no system the response takes ({err})") from None
    system, p, _ = member(start)
    return Family(name, unit, member, Scales.of(system, p))
