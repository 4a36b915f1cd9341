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
from typing import Any, NamedTuple

import numpy as np

from lumped.drivers.sensitivity import plan
from lumped.model.forcing import SwitchedSine
from lumped.model.network import Load, Network
from lumped.model.oscillator import Oscillator
from lumped.model.problem import one_mass_form
from lumped.model.system_parameters import LOAD, system_parameters, with_values
from lumped.solvers.monodromy import PeriodMap
from lumped.solvers.monodromy import period_map as one_mass_map
from lumped.solvers.network_monodromy import NetworkPeriodMap, network_period_map
from lumped.solvers.network_phase import Parts, parts, refusal
from lumped.solvers.network_sensitivities import Parameter, along
from lumped.solvers.sensitivities import sensitivities

__all__ = [
    "FASTEST_RATE",
    "OMEGA_RATIO",
    "OMEGA_STEP",
    "PARAMETER_STEP",
    "Family",
    "LoadedNetwork",
    "Scales",
    "check_omega",
    "exact_derivative",
    "omega_derivative",
    "omega_family",
    "parameter_family",
    "period_map",
    "response_system",
    "time_scales",
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
    try:  # before the forms below, which would see a driven point as the ground
        network.refuse_drivers("the period map")
        network.refuse_non_monotone("the period map")
    except ValueError as err:
        raise ValueError(f"system: {err}") from None
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


#: The admissible ``omega`` relative to the system's time scales (:func:`check_omega`): from ``1e-3`` of its
#: fastest free oscillation to ``100`` times its slowest natural frequency.
OMEGA_RATIO = (1e-3, 1e2)
#: The fastest decay rate a period resolves, in units of ``omega`` (:func:`check_omega`).
FASTEST_RATE = 1e11


def time_scales(system: Oscillator | LoadedNetwork) -> tuple[float, float, float]:
    """``(fast, slow, rate)`` (rad/s, 1/s) of the system slipping everywhere (its springs, masses and
    viscosities): ``fast`` the largest imaginary part of ``M s^2 + C s + K = 0``'s roots (the fastest free
    oscillation), or, where none oscillates, the smallest ``|s|``; ``slow`` the smallest undamped natural
    frequency (``K v = w^2 M v``); ``rate`` the largest ``|s|``.  ``nan`` where the arithmetic overflows."""
    if isinstance(system, Oscillator):
        m, k = np.array([[system.mass]]), np.array([[system.stiffness]])
        c = np.array([[system.dashpot.bingham_form().viscosity]])
    else:
        b = system.parts.b
        m, k, c = np.diag(system.parts.m), system.stiffness, b @ np.diag(system.parts.c) @ b.T
    n = m.shape[0]
    with np.errstate(all="ignore"):
        inv = np.diag(1.0 / np.diag(m))
        companion = np.block([[np.zeros((n, n)), np.eye(n)], [-inv @ k, -inv @ c]])
        if not np.all(np.isfinite(companion)):
            return math.nan, math.nan, math.nan
        roots = np.linalg.eigvals(companion)
        natural = np.linalg.eigvals(inv @ k).real
    fast = float(np.max(np.abs(roots.imag)))
    if fast == 0.0:
        fast = float(np.min(np.abs(roots)))
    return fast, float(np.sqrt(np.min(natural))), float(np.max(np.abs(roots)))


def check_omega(system: Oscillator | LoadedNetwork, omega: float, what: str) -> None:
    """``ValueError`` (one line beginning ``what``) for a forcing frequency outside :data:`OMEGA_RATIO` of the
    system's :func:`time_scales`.

    Notes
    -----
    Below: a period holds ``fast/omega`` free oscillations, each a phase (or a stop and a breakaway) of the
    exact period map, so that its cost grows as ``1/omega`` (about 0.8 phases per ``omega/fast`` = 1 measured:
    some 800 phases, 0.2 s, a period at the bound) and its round-off as the number of phases (``1e3 eps``).
    Above: the motion's amplitude falls as ``X_s r^-2`` (``r = omega/omega_n``, ``X_s = P/k``) while the fixed
    point is found to :data:`~lumped.drivers.response.shooting.NEWTON_TOL` of ``X_s`` and the period map adds
    and subtracts terms of that static size (the spring's and the friction's offsets): the amplitude's relative
    error grows as ``NEWTON_TOL r^2`` (``1e-7`` at the bound) and its round-off as ``eps r^2``.  Measured on a
    Coulomb oscillator against Den Hartog's closed form: 4e-13 at ``r = 100``, 2e-9 at ``r = 1e3`` where
    Newton stops at its tolerance, 5e-9 at ``r = 1e4``; beyond ``r ~ 1e5`` no digit survives (``omega = 1e10``
    on figure3.toml gave ``2^-62`` m for ``4.75e-20``).  And the fastest decay (an overdamped mass's ``c/m``) must last some 1e4
    ulps of the period's time, ``rate <= FASTEST_RATE omega`` (``1e4 eps 2 pi ~ 1e-11``), so that the event
    times within it are resolved (a mass of 1e-300 kg on figure3.toml divides by an acceleration that
    underflows).
    """
    fast, slow, rate = time_scales(system)
    lo, hi = OMEGA_RATIO
    if not (math.isfinite(rate) and slow > 0):
        raise ValueError(f"{what}: the system's time scales overflow (its masses, springs or viscosities are extreme)")
    if not omega >= lo * fast:
        raise ValueError(
            f"{what}: omega = {omega:.6g} rad/s is below {lo:g} of the system's fastest free oscillation "
            f"({fast:.6g} rad/s), the least the period map resolves: {lo * fast:.6g} rad/s"
        )
    if not omega <= hi * slow:
        raise ValueError(
            f"{what}: omega = {omega:.6g} rad/s is above {hi:g} times the system's slowest natural frequency "
            f"({slow:.6g} rad/s), the most the period map resolves: {hi * slow:.6g} rad/s"
        )
    if not rate <= FASTEST_RATE * omega:
        raise ValueError(
            f"{what}: the system's fastest decay rate ({rate:.6g} 1/s) is above {FASTEST_RATE:g} times "
            f"omega = {omega:.6g} rad/s, the most a period resolves"
        )


class Family(NamedTuple):
    """A one-parameter family of forced systems, what a continuation follows: the parameter's ``name``
    (``omega``, ``amplitude``, or a system file's ``element.key``), its ``unit`` (the continuation's scale for
    it), ``member(value)`` giving ``(system, P, omega)`` (``ValueError`` for a value the system refuses), the
    ``scales`` of the state (those of the member at the start) and ``derivative(orbit, value)``, ``dPi/dlambda``
    at an :class:`~lumped.drivers.response.shooting.Orbit` of the member at ``value`` (its state held; m and m/s
    per unit of the parameter)."""

    name: str
    unit: float
    member: Callable[[float], tuple[Oscillator | LoadedNetwork, float, float]]
    scales: Scales
    derivative: Callable[[Any, float], np.ndarray]


def omega_family(system: Oscillator | LoadedNetwork, amplitude: float) -> Family:
    """The family in the forcing frequency (rad/s, in units of omega_n) of ``system`` under ``amplitude``."""

    def member(omega: float) -> tuple[Oscillator | LoadedNetwork, float, float]:
        if not (omega > 0 and math.isfinite(omega)):
            raise ValueError(f"force_omega must be finite and > 0, got {omega!r}")
        return system, amplitude, omega

    scales = Scales.of(system, amplitude)
    return Family("omega", scales.omega, member, scales, lambda orbit, _: omega_derivative(system, amplitude, orbit))


def parameter_family(
    network: Network, mass: str, amplitude: float, omega: float, name: str, start: float, stop: float
) -> Family:
    """The family in ``name`` from ``start`` to ``stop`` of ``network`` under ``amplitude sin(omega t)`` on
    ``mass``: ``amplitude`` (the force's, N) or a numeric parameter of the file (``dashpot.threshold``,
    ``m.mass``: :func:`~lumped.model.system_parameters.system_parameters`), not an initial state (unused) nor
    a load (refused).  Its unit is ``max(|start|, |stop|)``; its derivative is exact
    (:func:`parameter_derivative`).  ``ValueError`` (one line beginning ``vary``) for another name, or for a
    system refused at ``start`` or ``stop``."""
    unit = max(abs(start), abs(stop))
    if name == "amplitude":
        system = response_system(network, mass)

        def member(value: float) -> tuple[Oscillator | LoadedNetwork, float, float]:
            if not (value > 0 and math.isfinite(value)):
                raise ValueError(f"amplitude must be finite and > 0, got {value!r}")
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
    loaded = Network(list(network.masses), list(network.elements), [Load(mass, SwitchedSine(amplitude, omega))])
    key = f"{LOAD}.amplitude" if name == "amplitude" else name
    (param,) = system_parameters(loaded, [key], "vary")

    def derivative(orbit: Any, value: float) -> np.ndarray:
        exact = exact_derivative(with_values(loaded, [param], [value]), key, orbit)
        return _one_sided(member, orbit, value, PARAMETER_STEP * unit) if exact is None else exact

    return Family(name, unit, member, Scales.of(system, p), derivative)


#: Step of the one-sided difference ``dPi/dlambda`` where the exact derivative is one-sided and the solver
#: lacks it (a network's threshold at 0), in the family's unit: truncation ``step`` (1e-6 relative) and
#: round-off (the map's ~1e-14 over the step, 1e-8) only slow the corrector's last digit, never move the point.
PARAMETER_STEP = 1e-6


def exact_derivative(loaded: Network, name: str, orbit: Any) -> np.ndarray | None:
    """``dPi/dp`` (m and m/s per unit of ``p``) in the parameter ``name`` of ``loaded`` (the system with its
    sine) at ``orbit`` (an :class:`~lumped.drivers.response.shooting.Orbit` of it), its state held, or ``None``
    where the exact sensitivities lack it.

    The sensitivities of the period's own phases at its end ``T = 2 pi/omega`` (fixed: omega is), by
    :func:`~lumped.drivers.sensitivity.plan`'s parameter: for one mass by
    :func:`lumped.solvers.sensitivities.sensitivities`, for a network by
    :func:`~lumped.solvers.network_sensitivities.along` times the chain-rule factor.  On the edge of the
    parameter's domain this is the derivative into it (at a threshold of 0, the motion's with ``-tau sign(v)``
    added), which the one-mass solver gives; a network's threshold at 0 it refuses (``None``)."""
    try:
        _, how, _ = plan(loaded, [name], "vary")
    except ValueError:
        return None
    period = orbit.period
    if isinstance(period, PeriodMap):
        sens = sensitivities(period.solution, [period.solution.t_end], list(how))  # type: ignore[arg-type]
        return np.array([sens.x[0, 0], sens.v[0, 0]])
    dx, dv = along(period.parts, period.phases, period.events, [period.t_end], how.parameters, loaded.element_names)  # type: ignore[union-attr]
    return np.concatenate([dx[0, :, 0], dv[0, :, 0]]) * how.factors[0]  # type: ignore[union-attr]


def _one_sided(member: Callable, orbit: Any, value: float, step: float) -> np.ndarray:
    """``(Pi(lambda + h) - Pi(lambda))/h`` at ``orbit``'s state, towards the side the family takes
    (``h = +-step``): no value outside the parameter's domain is tried."""
    try:
        member(value + step)
    except ValueError:
        step = -step
    system, p, w = member(value + step)
    return (period_map(system, p, w, orbit.state).end - orbit.period.end) / step
