"""The steady amplitude of a forced mass and its derivatives, with parameters named as in a system file.

:func:`steady_amplitude_sensitivities` finds the periodic motion under
``P sin(omega t)`` (:func:`~lumped.drivers.response.find_orbit`, the fixed
point of the exact period map) and differentiates its amplitude by the
implicit function theorem (:mod:`lumped.solvers.steady_sensitivities`).
Where a stop appears or vanishes (the period's smallest event margin below
:data:`MARGIN`), it also gives the one-sided derivatives, from the periodic
motions at ``p -+ delta`` (:func:`lumped.solvers.one_sided.moved`).  A
network (what the ``response`` command takes with more than one mass) is
differentiated through its own period map
(:func:`lumped.solvers.steady_sensitivities.network_steady_sensitivities`);
there the margin is reported and no one-sided values are formed.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

from lumped.drivers.response import find_orbit
from lumped.drivers.response.shooting import Orbit
from lumped.drivers.response.systems import response_system
from lumped.drivers.sensitivity import NetworkPlan, plan, prepare
from lumped.model.forcing import SwitchedSine
from lumped.model.network import Load, Network
from lumped.model.oscillator import Oscillator
from lumped.solvers.one_sided import STEP, Problem, moved
from lumped.solvers.steady_sensitivities import (
    NETWORK_STEADY_KINDS,
    STEADY_PARAMETERS,
    SteadySensitivities,
    network_steady_sensitivities,
    steady_sensitivities,
)

__all__ = ["MARGIN", "OneSidedAmplitude", "SteadyAmplitude", "steady_amplitude_sensitivities"]

#: Below this event margin (in units of the threshold) the one-sided derivatives are computed as well.
MARGIN = 1e-6


class OneSidedAmplitude(NamedTuple):
    """``dA/dp`` of the periodic motions at ``p - delta`` (``below``) and ``p + delta`` (``above``), their
    stops per period, and the amplitude's jump ``A(p + delta) - A(p - delta) - delta (below + above)`` (m)."""

    parameter: str
    delta: float
    below: float
    above: float
    stops_below: int
    stops_above: int
    jump: float


@dataclass(frozen=True)
class SteadyAmplitude:
    """The steady amplitude of the loaded mass and its derivatives.

    Attributes
    ----------
    amplitude : float, m
        Half of ``max x - min x`` over a period of the periodic motion.
    derivatives : dict of str to float
        ``dA/dp`` by the parameters' names as given.
    stops : int
        Stops per period.
    margin : float
        The period's smallest event margin: near 0 a stop appears or vanishes nearby.
    one_sided : tuple of OneSidedAmplitude
        Computed when ``margin < MARGIN`` (else empty).
    orbit : Orbit
    """

    amplitude: float
    derivatives: dict[str, float]
    stops: int
    margin: float
    one_sided: tuple[OneSidedAmplitude, ...]
    orbit: Orbit

    @property
    def stops_change(self) -> bool:
        """True where the periodic motions at ``p - delta`` and ``p + delta`` differ in their stops per period
        for some parameter: a stop appears or vanishes here."""
        return any(s.stops_below != s.stops_above for s in self.one_sided)

    @property
    def kink(self) -> float:
        """The largest ``|above - below|`` of :attr:`one_sided` relative to ``max(|below|, |above|)`` (0 without
        one-sided values): of order :data:`~lumped.solvers.one_sided.STEP` where ``A`` is differentiable."""
        gaps = [abs(s.above - s.below) / max(abs(s.above), abs(s.below), math.ulp(0.0)) for s in self.one_sided]
        return max(gaps, default=0.0)

    def summary(self) -> str:
        """One line: the amplitude, the stops, and, where a stop appears or vanishes, how far apart the sides are."""
        line = f"amplitude {self.amplitude:.6g} m, {self.stops} stops per period"
        if self.stops_change:
            line += f"; a stop appears or vanishes here: one-sided derivatives {self.kink:.1e} apart (relative)"
        return line


def steady_amplitude_sensitivities(
    system: Network | Oscillator,
    mass: str | None,
    amplitude: float,
    omega: float,
    parameters: str | Sequence[str],
    guess: Sequence[float] | None = None,
) -> SteadyAmplitude:
    """The periodic motion under ``amplitude sin(omega t)`` on ``mass`` and its amplitude's derivatives.

    Parameters
    ----------
    system : Network or Oscillator
        A system without loads of its own, as the ``response`` command takes it (one mass on springs and a
        Bingham or Coulomb dashpot, or a network of linear springs, Bingham and Coulomb elements and linear
        dashpots), or an oscillator.
    mass : str or None
        The mass the sine acts on (``None`` for an oscillator).
    amplitude, omega : float
        ``P`` (N) and ``omega`` (rad/s), both ``> 0``.
    parameters : str or sequence of str
        For a network, names as in its file (``dashpot.threshold``, ``spring.stiffness``, ``m.mass``) and
        ``force.amplitude``, ``force.omega`` for the sine's; for an oscillator, names of
        :data:`~lumped.solvers.steady_sensitivities.STEADY_PARAMETERS`.
    guess : (x, v) at ``t = 0``, optional
        Where Newton starts (:func:`~lumped.drivers.response.find_orbit`).

    Raises
    ------
    ValueError
        One line: a system with more than one mass, a parameter the steady amplitude does not depend on (an
        initial state, the sine's phase or end), or Newton without a periodic motion.
    """
    if isinstance(system, Network) and not isinstance(response_system(system, mass), Oscillator):
        return _network(system, mass, amplitude, omega, parameters, guess)
    osc, force, names, shown = _resolve(system, mass, amplitude, omega, parameters)
    orbit = find_orbit(osc, force.amplitude, force.omega, guess)
    sens = steady_sensitivities(orbit.period.solution, names)
    sides = ()
    if sens.margin < MARGIN:
        sides = tuple(_sides(Problem(osc, force, 0.0, 0.0), name, shown[j], orbit) for j, name in enumerate(names))
    by_name = dict(zip(shown, (float(d) for d in sens.derivatives), strict=True))
    return SteadyAmplitude(sens.amplitude, by_name, sens.stops, sens.margin, sides, orbit)


def _network(
    system: Network, mass: str, amplitude: float, omega: float, parameters, guess: Sequence[float] | None
) -> SteadyAmplitude:
    """The network's case: its period map and sensitivities (:func:`network_steady_sensitivities`); the
    derivatives of the loaded mass's amplitude, no one-sided values (the margin says where they would differ)."""
    loaded = Network(list(system.masses), list(system.elements), [Load(mass, SwitchedSine(amplitude, omega))])
    params, how, _ = plan(loaded, parameters)
    if not isinstance(how, NetworkPlan):  # a one-mass system is answered above
        raise ValueError("system: expected a network")  # noqa: TRY004 (the API's one error type)
    for prm, sp in zip(how.parameters, params, strict=True):
        if prm.kind not in NETWORK_STEADY_KINDS:
            raise ValueError(f"parameters: the steady amplitude does not depend on {sp.name!r}")
    net = response_system(system, mass)
    orbit = find_orbit(net, amplitude, omega, guess)
    amps, derivatives, _, margin = network_steady_sensitivities(
        orbit.period, orbit.state, how.parameters, list(net.elements)
    )
    d = derivatives[net.mass] * how.factors
    by_name = {sp.name: float(v) for sp, v in zip(params, d, strict=True)}
    return SteadyAmplitude(float(amps[net.mass]), by_name, orbit.stops, margin, (), orbit)


def _resolve(system, mass, amplitude: float, omega: float, parameters) -> tuple:
    """``(oscillator, sine, one-mass names, names as given)``, or a one-line ``ValueError``."""
    if isinstance(system, Oscillator):
        names = [n.strip() for n in parameters.split(",")] if isinstance(parameters, str) else list(parameters)
        return system, SwitchedSine(amplitude, omega), tuple(names), tuple(names)
    if not isinstance(system, Network):
        raise ValueError(f"system must be a Network or an Oscillator, got {type(system).__name__}")  # noqa: TRY004 (the API's one error type)
    osc = response_system(system, mass)  # an Oscillator: a network is answered by _network
    loaded = Network(list(system.masses), list(system.elements), [Load(mass, SwitchedSine(amplitude, omega))])
    params, names, force = prepare(loaded, parameters)
    for p, name in zip(params, names):
        if name not in STEADY_PARAMETERS:
            raise ValueError(f"parameters: the steady amplitude does not depend on {p.name!r}")
    return osc, force, tuple(names), tuple(p.name for p in params)


def _sides(problem: Problem, name: str, shown: str, orbit: Orbit) -> OneSidedAmplitude:
    """The periodic motions at ``p -+ delta`` in ``name`` and their amplitudes' derivatives."""
    delta = STEP * problem.scale(name)
    out: list[SteadySensitivities] = []
    for d in (-delta, delta):
        side = moved(problem, name, d)
        found = find_orbit(side.oscillator, side.force.amplitude, side.force.omega, orbit.state)
        out.append(steady_sensitivities(found.period.solution, [name]))
    below, above = (float(s.derivatives[0]) for s in out)
    jump = out[1].amplitude - out[0].amplitude - delta * (below + above)
    return OneSidedAmplitude(shown, delta, below, above, out[0].stops, out[1].stops, jump)
