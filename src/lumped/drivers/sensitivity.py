"""Sensitivities of a system's exact motion to its parameters, named as in its file (``dashpot.threshold``).

:func:`system_sensitivities` runs a one-mass system (one mass on springs and
a Bingham or Coulomb dashpot, all to the ground, under a sine or a constant
load from ``t = 0``: what :func:`~lumped.solvers.exact.solve_exact` takes)
by the exact solver and differentiates it
(:func:`lumped.solvers.sensitivities.sensitivities`) with respect to
parameters named as :mod:`lumped.model.system_parameters` names them.  A
spring's ``stiffness`` moves the total stiffness ``k`` by as much, so every
spring of the mass has the same derivative; ``force.value`` of a constant
load is the amplitude of the sine it equals.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from lumped.model.forcing import SwitchedSine, one_force, sine_form
from lumped.model.network import Network
from lumped.model.problem import one_mass_form
from lumped.model.system_parameters import SystemParameter, system_parameters
from lumped.solvers.exact import ExactSolution, solve_exact
from lumped.solvers.sensitivities import Sensitivities, sensitivities

__all__ = ["prepare", "system_sensitivities"]

#: ``(table, key)`` of a system's parameter -> the one-mass API's name (an element's keys: its springs'
#: and its dashpot's, checked by :func:`_api_name`).
_API = {
    ("mass", "mass"): "mass",
    ("mass", "x0"): "x0",
    ("mass", "v0"): "v0",
    ("element", "stiffness"): "stiffness",
    ("element", "threshold"): "threshold",
    ("element", "gamma"): "gamma",
    ("force", "amplitude"): "force_amplitude",
    ("force", "value"): "force_amplitude",
    ("force", "omega"): "force_omega",
    ("force", "phase"): "force_phase",
    ("force", "until"): "force_until",
}


def _api_name(network: Network, p: SystemParameter, what: str) -> str:
    """The one-mass API's name of ``p``, or a ``ValueError`` for a parameter the exact one-mass solver lacks."""
    name = _API.get((p.table, p.key))
    if p.table == "element":
        el = network.elements[p.index]
        spring = el.linear_stiffness is not None
        if (name == "stiffness") != spring:
            name = None
    if name is None:
        raise ValueError(f"{what}: {p.name!r} has no sensitivity: the exact one-mass solver does not take it")
    return name


def prepare(
    network: Network, parameters: str | Sequence[str], what: str = "parameters"
) -> tuple[tuple[SystemParameter, ...], list[str], SwitchedSine | None]:
    """The parameters called ``parameters``, their one-mass API names and the load as a sine, or a
    ``ValueError`` (one line beginning with ``what``) for a system or a parameter the sensitivities lack."""
    params = system_parameters(network, parameters, what)
    try:
        form = one_mass_form(network)
    except ValueError as err:
        raise ValueError(f"{what}: the exact sensitivities need a one-mass system; the network {err}") from None
    names = [_api_name(network, p, what) for p in params]
    force = sine_form(one_force([load.force for load in network.loads]))
    if force is not None and not isinstance(force, SwitchedSine):
        raise ValueError(f"{what}: the exact sensitivities need a sine load or a constant one from t = 0")
    if form.oscillator.dashpot.bingham_form() is None:
        raise ValueError(f"{what}: the exact sensitivities need a Bingham or Coulomb dashpot")
    return params, names, force


def system_sensitivities(
    network: Network, t: np.ndarray | Sequence[float], parameters: str | Sequence[str], what: str = "parameters"
) -> tuple[ExactSolution, Sensitivities]:
    """The exact motion of a one-mass ``network`` over ``[0, t[-1]]`` and its derivatives at the times ``t``.

    Parameters
    ----------
    network : Network
        One mass on springs and a Bingham or Coulomb dashpot, all to the
        ground, with at most one load, a sine or a constant on from ``t = 0``.
    t : array_like, (n,), s
        Increasing times from 0 or later; the motion is solved to the last one (``> 0``).
    parameters : str or sequence of str
        Names as :func:`~lumped.model.system_parameters.system_parameters` reads them.
    what : str
        The argument's name in messages (``--sensitivities`` on the command line).

    Returns
    -------
    (ExactSolution, Sensitivities)
        The solution, and its derivatives with ``parameters`` named as given.

    Raises
    ------
    ValueError
        One line: an unknown parameter, a system the exact one-mass solver does not run, bad times.
    """
    params, names, force = prepare(network, parameters, what)
    t = np.asarray(t, dtype=float).ravel()
    if t.size == 0 or not np.all(np.isfinite(t)) or t[0] < 0 or not t[-1] > 0 or np.any(np.diff(t) < 0):
        raise ValueError("t: the times must be finite, from 0 or later, increasing, and end after 0")
    mass = network.masses[0]
    solution = solve_exact(one_mass_form(network).oscillator, float(t[-1]), x0=mass.x0, v0=mass.v0, force=force)
    sens = sensitivities(solution, t, names)
    return solution, dataclasses.replace(sens, parameters=tuple(p.name for p in params))
