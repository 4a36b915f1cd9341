"""The response curve of a system file's mass under ``P sin(omega t)``: the API of ``python -m lumped response``.

:func:`response_curve` takes a :class:`~lumped.model.network.Network` (a
system file read by :func:`lumped.model.files.load_system`): one mass on
linear springs and a Bingham or Coulomb dashpot, all to the ground, or a
network of linear springs, Bingham and Coulomb elements and linear dashpots
whose springs hold every mass to the ground
(:func:`~lumped.drivers.response.systems.response_system`), and returns the
table of ``omega``, ``amplitude_<mass>`` for each mass and :data:`COLUMNS`
along the branch of periodic motions
(:func:`~lumped.drivers.response.continuation.continue_orbits`).  The file's
initial state is not used (each row's is found), and the file may hold no
load of its own: the command's sine is the one load.

With ``vary``, the branch is followed in another parameter at a fixed
``omega``: the force's ``amplitude`` or a numeric parameter of the file
(``dashpot.threshold``, ``spring.stiffness``, ``m.mass``;
:func:`~lumped.drivers.response.systems.parameter_family`), whose column
comes first.

Without viscosity (``gamma = inf``) and below Den Hartog's ``F/P = pi/4`` the
amplitude grows without bound at ``omega = omega_n``: the branch is cut where
it passes :data:`~lumped.drivers.response.continuation.MAX_AMPLITUDE` and
taken up again as far above ``omega_n`` as it stopped below, from the linear
oscillator's motion there (Newton then finds the friction's).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from lumped.drivers.response.continuation import Branch, ResponsePoint, check_points, continue_orbits
from lumped.drivers.response.shooting import Orbit, find_orbit
from lumped.drivers.response.systems import Family, LoadedNetwork, parameter_family, response_system
from lumped.model.network import Network
from lumped.model.oscillator import Oscillator
from lumped.numerics import validate

__all__ = ["COLUMNS", "Curve", "response_curve"]

#: The columns after ``omega`` and ``amplitude_<mass>``.
COLUMNS = ("stops_per_period", "stable", "max_multiplier", "kind")


class Curve(NamedTuple):
    """The table (column name -> array, ``stable`` as bool, ``kind`` as str) and a one-line summary."""

    columns: dict[str, np.ndarray]
    summary: str


def _branches(
    osc: Oscillator | LoadedNetwork,
    amplitude: float,
    start: float,
    stop: float,
    points: int,
    progress: Callable | None,
    family: Family | None = None,
) -> list[Branch]:
    """One branch, or for one mass in omega two around an undamped resonance (module docstring)."""
    first = continue_orbits(osc, amplitude, start, stop, points, progress, family=family)
    if family is not None or not isinstance(osc, Oscillator):
        return [first]
    wn = math.sqrt(osc.stiffness / osc.mass)
    last = first.points[-1].orbit.omega
    if first.end != "amplitude" or osc.dashpot.bingham_form().viscosity != 0 or not last < wn < stop:
        return [first]
    restart = 2 * wn - last
    a = amplitude / (osc.stiffness - osc.mass * restart**2)  # the linear motion a sin(omega t)
    orbit = find_orbit(osc, amplitude, restart, np.array([0.0, a * restart]))
    return [first, continue_orbits(osc, amplitude, orbit.omega, stop, points, progress, start_orbit=orbit)]


def response_curve(
    network: Network,
    mass: str,
    amplitude: float,
    start: float,
    stop: float,
    points: int = 200,
    progress: Callable[[int, int], None] | None = None,
    vary: str | None = None,
    omega: float | None = None,
) -> Curve:
    """The forced response of ``mass`` under ``amplitude sin(omega t)`` for ``omega`` from ``start`` to ``stop``
    (or, with ``vary``, for that parameter from ``start`` to ``stop`` at ``omega``).

    Parameters
    ----------
    network : Network
        One mass on springs and a Bingham or Coulomb dashpot, or a network of linear springs, Bingham and
        Coulomb elements and linear dashpots, no loads (:func:`~lumped.drivers.response.systems.response_system`).
    mass : str
        The mass the force acts on (its name in the file).
    amplitude : float, N
        ``P > 0``.
    start, stop : float, rad/s
        ``0 < start < stop``; with ``vary``, the parameter's values, ``start < stop``.
    points : int
        At least 2: about the number of rows of a branch monotone in omega
        (:func:`~lumped.drivers.response.continuation.continue_orbits`).
    vary : str, optional
        ``amplitude`` or a parameter of the file (``element.key``, ``mass.key``) to follow instead of omega.
    omega : float, rad/s
        The fixed forcing frequency, with ``vary`` (and only then).

    Returns
    -------
    Curve
        Columns ``omega``, ``amplitude_<mass>`` for each mass (half of max x
        minus min x over the period, m), then :data:`COLUMNS`; with ``vary``,
        its column first.
    """
    if not isinstance(network, Network):
        raise ValueError(f"network must be a Network (a system file read by load_system), got {type(network).__name__}")
    if not isinstance(mass, str):
        raise ValueError(f"mass must be the name of a mass of the network, got {mass!r:.40}")
    amplitude = validate.positive("force_amplitude", amplitude)
    points = check_points(points)
    system = response_system(network, mass)
    if vary is None:
        if omega is not None:
            raise ValueError("omega: a fixed omega goes with vary (START:STOP are then the parameter's)")
        start, stop = validate.positive("start", start), validate.positive("stop", stop)
    else:
        if vary == "omega":
            raise ValueError("vary: omega is followed without vary, from START to STOP")
        if omega is None:
            raise ValueError("omega: vary needs the fixed forcing frequency omega")
        omega = validate.positive("force_omega", omega)
        start, stop = validate.finite("start", start), validate.finite("stop", stop)
    if not start < stop:
        raise ValueError(f"{vary or 'omega'}: START must be below STOP, got {start!r}:{stop!r}")
    family = None if vary is None else parameter_family(network, mass, amplitude, omega, vary, start, stop)
    branches = _branches(system, amplitude, start, stop, points, progress, family)
    rows = [p for b in branches for p in b.points]
    return Curve(_table(rows, network.mass_names, vary), _summary(branches, rows, vary or "omega"))


def _table(rows: list[ResponsePoint], masses: list[str], vary: str | None = None) -> dict[str, np.ndarray]:
    orbits: list[Orbit] = [p.orbit for p in rows]
    amplitudes = np.array([o.amplitudes for o in orbits]).reshape(len(orbits), len(masses))
    return {
        **({} if vary is None else {vary: np.array([p.value for p in rows])}),
        "omega": np.array([o.omega for o in orbits]),
        **{f"amplitude_{name}": amplitudes[:, i] for i, name in enumerate(masses)},
        "stops_per_period": np.array([float(o.stops) for o in orbits]),
        "stable": np.array([o.stable for o in orbits]),
        "max_multiplier": np.array([o.max_multiplier for o in orbits]),
        "kind": np.array([p.kind for p in rows]),
    }


_ENDS = {
    "stop": "reached STOP",
    "amplitude": "amplitude beyond {limit:g} P/k near {name} = {value:.6g}{unit}",
    "turned": "turned back below START",
    "step": "no corrector step converged near {name} = {value:.6g}{unit}",
    "steps": "step budget spent near {name} = {value:.6g}{unit}",
}


def _summary(branches: list[Branch], rows: list[ResponsePoint], name: str = "omega") -> str:
    """``N points; ends: ...; changes: k fold, ...``."""
    from lumped.drivers.response.continuation import MAX_AMPLITUDE

    ends = "; ".join(
        _ENDS[b.end].format(
            limit=MAX_AMPLITUDE, name=name, value=b.points[-1].value, unit=" rad/s" if name == "omega" else ""
        )
        for b in branches
    )
    kinds = [p.kind for p in rows if p.kind != "regular"]
    changes = ", ".join(f"{kinds.count(k)} {k}" for k in dict.fromkeys(kinds)) or "none"
    return f"{len(rows)} points ({ends}; changes: {changes})"
