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

A linear system (no friction) with an undamped mode is not continued: its
periodic motion is not unique at ``omega = omega_n/j``, and a continuation
there follows the family of motions instead of the curve.  Its table is the
closed form on the grid of ``points`` values from ``start`` to ``stop``, the
values whose motion is not unique left out and named in the summary, and
``ValueError`` when no value is left (:mod:`~lumped.drivers.response.linear`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from lumped.drivers.response import linear
from lumped.drivers.response.continuation import Branch, ResponsePoint, check_points, continue_orbits
from lumped.drivers.response.shooting import Orbit, find_orbit
from lumped.drivers.response.systems import (
    Family,
    LoadedNetwork,
    check_omega,
    omega_family,
    parameter_family,
    response_system,
)
from lumped.model.network import Network
from lumped.model.oscillator import Oscillator
from lumped.numerics import validate

__all__ = ["COLUMNS", "MAX_POINTS", "MIN_WIDTH", "Curve", "Request", "request", "response_curve"]

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


#: The most rows asked for: 1e4 is five times the width of a printed figure at 600 dpi, and, with a range at
#: least :data:`MIN_WIDTH` wide, keeps a step above ``1e-10`` of the parameter, so that a change located to
#: ``2^-12`` of a step (:data:`~lumped.drivers.response.continuation.BISECTIONS`) stays ~100 ulps apart.
MAX_POINTS = 10_000
#: The narrowest range, relative to its largest value ``max(|START|, |STOP|)`` (see :data:`MAX_POINTS`).
MIN_WIDTH = 1e-6


class Request(NamedTuple):
    """A checked request for a curve: its system, force amplitude, range, rows and family (``None`` in omega)."""

    system: Oscillator | LoadedNetwork
    amplitude: float
    start: float
    stop: float
    points: int
    family: Family | None


def request(
    network: Network,
    mass: str,
    amplitude: float,
    start: float,
    stop: float,
    points: int = 200,
    vary: str | None = None,
    omega: float | None = None,
) -> Request:
    """:func:`response_curve`'s arguments checked before any work, or a one-line ``ValueError`` naming the
    argument and its limit: ``points`` in ``[2, MAX_POINTS]``, a finite range at least :data:`MIN_WIDTH` wide,
    every forcing frequency within :data:`~lumped.drivers.response.systems.OMEGA_RATIO` of the system's time
    scales (:func:`~lumped.drivers.response.systems.check_omega`: in omega at both ends; with ``vary``, the
    fixed ``omega`` for the systems at both ends of the range, between which the time scales are monotone).
    A linear system with an undamped mode skips those bounds: its closed form
    (:mod:`~lumped.drivers.response.linear`) refuses the omegas it cannot vouch for itself."""
    if not isinstance(network, Network):
        raise ValueError(f"network must be a Network (a system file read by load_system), got {type(network).__name__}")
    if not isinstance(mass, str):
        raise ValueError(f"mass must be the name of a mass of the network, got {mass!r:.40}")
    amplitude = validate.positive("force_amplitude", amplitude)
    points = check_points(points)
    if points > MAX_POINTS:
        raise ValueError(f"points: between 2 and {MAX_POINTS} rows, got {points}")
    system = response_system(network, mass)
    axis = "START:STOP" if vary is None else vary
    if vary is None and omega is not None:
        raise ValueError("omega: a fixed omega goes with vary (START:STOP are then the parameter's)")
    if vary == "omega":
        raise ValueError("vary: omega is followed without vary, from START to STOP")
    if vary is not None:
        if omega is None:
            raise ValueError("omega: vary needs the fixed forcing frequency omega")
        omega = validate.positive("force_omega", omega)
    start, stop = _range("omega" if vary is None else "vary", axis, start, stop)
    if vary is None:
        if not _undamped(omega_family(system, amplitude), start, stop):  # the closed form vouches for itself
            for value in (start, stop):
                check_omega(system, value, "omega")
        return Request(system, amplitude, start, stop, points, None)
    family = parameter_family(network, mass, amplitude, omega, vary, start, stop)  # type: ignore[arg-type]
    if _undamped(family, start, stop):
        return Request(system, amplitude, start, stop, points, family)
    for value in (start, stop):
        check_omega(family.member(value)[0], omega, f"vary: at {vary} = {value:g}")  # type: ignore[arg-type]
    return Request(system, amplitude, start, stop, points, family)


def _range(what: str, axis: str, start: float, stop: float) -> tuple[float, float]:
    """``(start, stop)`` of ``axis`` finite, in order (and positive in omega), at least :data:`MIN_WIDTH` wide;
    messages begin with ``what``."""
    try:
        start, stop = float(start), float(stop)
    except (TypeError, ValueError):
        raise ValueError(f"{what}: {axis}: START and STOP must be real numbers, got {start!r}:{stop!r}") from None
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise ValueError(f"{what}: {axis}: START and STOP must be finite, got {start!r}:{stop!r}")
    if what == "omega" and not start > 0:
        raise ValueError(f"{what}: {axis}: START must be > 0, got {start!r}")
    if not start < stop:
        raise ValueError(f"{what}: {axis}: START must be below STOP, got {start!r}:{stop!r}")
    if stop - start < MIN_WIDTH * max(abs(start), abs(stop)):
        raise ValueError(
            f"{what}: {axis} = {start!r}:{stop!r} is narrower than {MIN_WIDTH:g} of its largest value, "
            "the least width the continuation resolves"
        )
    return start, stop


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
        ``0 < start < stop``, at least :data:`MIN_WIDTH` of ``stop`` apart, within
        :data:`~lumped.drivers.response.systems.OMEGA_RATIO` of the system's time scales; with ``vary``, the
        parameter's values, ``start < stop`` (:func:`request` checks them all before any work).
    points : int
        2 to :data:`MAX_POINTS`: about the number of rows of a branch monotone in omega
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
        its column first.  A linear system with an undamped mode: the closed form at ``points`` values evenly
        spaced from ``start`` to ``stop``, without those where the periodic motion is not unique (module
        docstring).

    Raises
    ------
    ValueError
        One line naming the argument; ``force_omega: ...`` where no value of a linear system with an undamped
        mode has a unique periodic motion (``omega = omega_n/j``).
    """
    req = request(network, mass, amplitude, start, stop, points, vary, omega)
    family = req.family or omega_family(req.system, req.amplitude)
    if _undamped(family, req.start, req.stop):
        return _linear_curve(family, req.start, req.stop, req.points, network.mass_names, vary)
    branches = _branches(req.system, req.amplitude, req.start, req.stop, req.points, progress, req.family)
    rows = [p for b in branches for p in b.points]
    return Curve(_table(rows, network.mass_names, vary), _summary(branches, rows, vary or "omega"))


def _undamped(family: Family, start: float, stop: float) -> bool:
    """True when the members at ``start`` and ``stop`` are linear and one has an undamped mode: the closed form
    (:func:`~lumped.drivers.response.linear.linear_rows`) then takes the family."""
    forms = [linear.linear_form(family.member(value)[0]) for value in (start, stop)]
    return None not in forms and any(linear.undamped_frequencies(f).size for f in forms)  # type: ignore[arg-type]


def _linear_curve(family: Family, start: float, stop: float, points: int, masses: list[str], vary: str | None) -> Curve:
    """The closed-form table of a linear family with an undamped mode, its left-out values named; ``ValueError``
    when every value of the grid is left out (the motion not unique at any)."""
    rows = linear.linear_rows(family.member, start, stop, points)
    system, _, omega = family.member(start)
    frequencies = linear.undamped_frequencies(linear.linear_form(system))  # type: ignore[arg-type]
    modes = ", ".join(f"{w:.6g}" for w in frequencies)
    if not rows.points:
        where = f"at omega = {omega:g} rad/s" if vary else f"at every omega of the grid from {start:g} to {stop:g}"
        why = linear.nearest_mode(frequencies, omega) if vary else f"omega_n/j of an undamped mode ({modes} rad/s)"
        raise ValueError(
            f"force_omega: the periodic motion {where} is not unique: it is {why}, where monodromy - I is singular"
        )
    count = len(rows.points)
    table = {
        **({} if vary is None else {vary: np.array(rows.values)}),
        "omega": np.array([p.omega for p in rows.points]),
        **{f"amplitude_{name}": np.array([p.amplitudes[i] for p in rows.points]) for i, name in enumerate(masses)},
        "stops_per_period": np.zeros(count),
        "stable": np.array([p.max_multiplier < 1.0 for p in rows.points]),
        "max_multiplier": np.array([p.max_multiplier for p in rows.points]),
        "kind": np.array(["regular"] * count),
    }
    if vary is None:
        named = linear.non_unique_points(frequencies, start, stop)
        where = f"omega = {named} rad/s" if named else ""
    else:
        where = f"{vary} = {', '.join(f'{v:.6g}' for v in rows.skipped[:4])}{', ...' * (len(rows.skipped) > 4)}"
    left = len(rows.skipped)
    gaps = "is unique throughout"
    if where:
        gaps = f"is not unique at {where}: {f'{left} of the {points}' if left else 'none of the'} grid points left out"
    modes = "" if vary else f", omega_n = {modes} rad/s"
    return Curve(
        table, f"{count} points (closed form: a linear system with an undamped mode{modes}; its periodic motion {gaps})"
    )


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
