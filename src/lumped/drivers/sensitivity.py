"""Sensitivities of a system's exact motion to its parameters, named as in its file (``dashpot.threshold``).

:func:`system_sensitivities` runs a system by an exact solver and
differentiates it with respect to parameters named as
:mod:`lumped.model.system_parameters` names them:

* a one-mass system (one mass on springs and a Bingham or Coulomb dashpot,
  all to the ground, under a sine or a constant load from ``t = 0``: what
  :func:`~lumped.solvers.exact.solve_exact` takes) by the one-mass solver
  (:func:`lumped.solvers.sensitivities.sensitivities`).  A spring's
  ``stiffness`` moves the total stiffness ``k`` by as much, so every spring
  of the mass has the same derivative; ``force.value`` of a constant load is
  the amplitude of the sine it equals;
* any other network that the exact network solver runs (linear springs,
  Bingham, Coulomb and linear dashpots under sine and constant loads, the
  sticking elements a forest) by it
  (:func:`lumped.solvers.network_sensitivities.network_sensitivities`), with
  respect to every mass's ``mass``, ``x0``, ``v0``, every spring's
  ``stiffness``, every dashpot's ``threshold``, ``gamma`` and ``damping``,
  and a single load's ``amplitude``, ``value``, ``omega``, ``phase`` and
  ``until``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence

import numpy as np

from lumped.model.forcing import SwitchedSine, as_sine, one_force
from lumped.model.network import Network
from lumped.model.problem import one_mass_form
from lumped.model.system_parameters import ONE_MASS_NAMES, SystemParameter, system_parameters, with_values
from lumped.solvers.exact import ExactSolution, solve_exact
from lumped.solvers.network_modes import final_rest
from lumped.solvers.network_phase import linear_parts, parts, refusal
from lumped.solvers.network_sensitivities import (
    NetworkMotion,
    NetworkSensitivities,
    Parameter,
    network_sensitivities,
)
from lumped.solvers.one_sided import STEP, OneSided, one_sided
from lumped.solvers.sensitivities import Sensitivities, sensitivities

__all__ = ["NetworkOneSided", "NetworkPlan", "one_sided_sensitivities", "plan", "prepare", "system_sensitivities"]


def _api_name(network: Network, p: SystemParameter, what: str) -> str:
    """The one-mass API's name of ``p``, or a ``ValueError`` for a parameter the exact one-mass solver lacks."""
    name = ONE_MASS_NAMES.get((p.table, p.key))
    if p.table == "element":
        el = network.elements[p.index]
        spring = el.linear_stiffness is not None
        if (name == "stiffness") != spring:
            name = None
    if name is None:
        raise ValueError(f"{what}: {p.name!r} has no sensitivity: the exact one-mass solver does not take it")
    return name


@dataclasses.dataclass(frozen=True)
class NetworkPlan:
    """The network solver's ``parameters`` for a system's, and the ``factors`` (p,) of the chain rule
    (``-c^2`` for a ``gamma``, ``c = 1/gamma``: 0 for a Coulomb element; 1 for the others)."""

    parameters: tuple[Parameter, ...]
    factors: np.ndarray


def prepare(
    network: Network, parameters: str | Sequence[str], what: str = "parameters"
) -> tuple[tuple[SystemParameter, ...], list[str], SwitchedSine | None]:
    """The parameters called ``parameters``, their one-mass API names and the load as a sine, or a
    ``ValueError`` (one line beginning with ``what``) for a system or a parameter the one-mass sensitivities
    lack (a network among them: :func:`plan` takes it)."""
    params = system_parameters(network, parameters, what)
    return (params, *_one_mass(network, params, what))


def plan(
    network: Network, parameters: str | Sequence[str], what: str = "parameters"
) -> tuple[tuple[SystemParameter, ...], list[str] | NetworkPlan, SwitchedSine | None]:
    """The parameters called ``parameters`` and how to differentiate them, or a ``ValueError`` (one line
    beginning with ``what``) for a system or a parameter the sensitivities lack.

    For a system of the one-mass solver, :func:`prepare`'s answer; else (a network, or one mass that only
    the network solver runs, such as one on a linear dashpot): the parameters, a :class:`NetworkPlan` and
    ``None``.
    """
    params = system_parameters(network, parameters, what)
    try:  # before the one-mass form, which would call a driven point "not the ground"
        network.refuse_drivers("the exact sensitivities")
        network.refuse_non_monotone("the exact sensitivities")
    except ValueError as err:
        raise ValueError(f"{what}: {err}") from None
    try:
        return (params, *_one_mass(network, params, what))
    except ValueError as err:
        one_mass = err
    reason = refusal(network, "exact")
    if reason is not None:
        if len(network.masses) == 1:
            raise one_mass
        raise ValueError(f"{what}: the exact sensitivities cannot run this network: {reason}")
    plan = [_network_parameter(network, p, what) for p in params]
    return params, NetworkPlan(tuple(a for a, _ in plan), np.array([f for _, f in plan])), None


#: ``(table, key)`` of a system's parameter -> the network solver's kind (an element's are checked by
#: :func:`_network_parameter`).
_NETWORK = {
    ("mass", "mass"): "mass",
    ("mass", "x0"): "x0",
    ("mass", "v0"): "v0",
    ("force", "amplitude"): "amplitude",
    ("force", "value"): "amplitude",
    ("force", "omega"): "omega",
    ("force", "phase"): "phase",
    ("force", "until"): "until",
}


def _network_parameter(network: Network, p: SystemParameter, what: str) -> tuple[Parameter, float]:
    """The network solver's parameter of ``p`` and its chain-rule factor, or a one-line ``ValueError``."""
    if p.table != "element":
        kind = _NETWORK[(p.table, p.key)]
        if kind == "omega" and network.loads[0].force.omega == 0:  # type: ignore[union-attr]
            raise ValueError(f"{what}: {p.name!r} has no sensitivity at 0 (the load is then the constant A sin(phase))")
        return Parameter(kind, p.index), 1.0
    el = network.elements[p.index]
    _, c, tau = linear_parts(el)  # type: ignore[misc]
    if p.key == "stiffness" and el.linear_stiffness is not None:
        return Parameter("stiffness", p.index), 1.0
    if p.key == "threshold" and tau > 0:
        return Parameter("threshold", p.index), 1.0
    if p.key == "threshold":
        raise ValueError(f"{what}: {p.name!r} is 0, where the force's derivative by it (the rate's sign) is one-sided")
    if p.key == "gamma":
        return Parameter("viscosity", p.index), -c * c  # dc/dgamma = -1/gamma^2: 0 for Coulomb
    if p.key in ("damping", "consistency"):
        return Parameter("viscosity", p.index), 1.0
    raise ValueError(f"{what}: {p.name!r} has no sensitivity: the exact network solver does not take it")


def _one_mass(network: Network, params: tuple[SystemParameter, ...], what: str) -> tuple[list[str], object]:
    """The one-mass API names of ``params`` and the load as a sine, or a ``ValueError``."""
    try:
        form = one_mass_form(network)
    except ValueError as err:
        raise ValueError(f"{what}: the exact sensitivities need a one-mass system; the network {err}") from None
    loads = one_force([load.force for load in network.loads])
    force = as_sine(loads)
    if loads is not None and force is None:
        raise ValueError(f"{what}: the exact sensitivities need a sine load or a constant one from t = 0")
    if form.oscillator.dashpot.bingham_form() is None:
        raise ValueError(f"{what}: the exact sensitivities need a Bingham or Coulomb dashpot")
    return [_api_name(network, p, what) for p in params], force


def system_sensitivities(
    network: Network, t: np.ndarray | Sequence[float], parameters: str | Sequence[str], what: str = "parameters"
) -> tuple[ExactSolution, Sensitivities] | tuple[NetworkMotion, NetworkSensitivities]:
    """The exact motion of ``network`` over ``[0, t[-1]]`` and its derivatives at the times ``t``.

    Parameters
    ----------
    network : Network
        One mass on springs and a Bingham or Coulomb dashpot, all to the
        ground, with at most one load, a sine or a constant on from ``t = 0``;
        or a network that the exact network solver runs (module docstring).
    t : array_like, (n,), s
        Increasing times from 0 or later; the motion is solved to the last one (``> 0``).
    parameters : str or sequence of str
        Names as :func:`~lumped.model.system_parameters.system_parameters` reads them.
    what : str
        The argument's name in messages (``--sensitivities`` on the command line).

    Returns
    -------
    (ExactSolution, Sensitivities) or (NetworkMotion, NetworkSensitivities)
        The solution, and its derivatives with ``parameters`` named as given: for one mass by the
        one-mass solver, else by the network solver (``x`` of shape (T, n, p), masses in the file's order).

    Raises
    ------
    ValueError
        One line: an unknown parameter, a system the exact one-mass solver does not run, bad times.
    """
    params, names, force = plan(network, parameters, what)
    t = np.asarray(t, dtype=float).ravel()
    if t.size == 0 or not np.all(np.isfinite(t)) or t[0] < 0 or not t[-1] > 0 or np.any(np.diff(t) < 0):
        raise ValueError("t: the times must be finite, from 0 or later, increasing, and end after 0")
    with np.errstate(over="ignore", invalid="ignore"):  # a derivative that overflows is refused below
        if isinstance(names, NetworkPlan):
            x0, v0 = (a[:-1] for a in network.initial_positions())
            sens = network_sensitivities(parts(network), x0, v0, t, names.parameters, network.element_names)
            motion, out = sens.motion, _scaled(sens, names.factors, tuple(p.name for p in params))
        else:
            mass = network.masses[0]
            oscillator = one_mass_form(network).oscillator
            motion = solve_exact(oscillator, float(t[-1]), x0=mass.x0, v0=mass.v0, force=force)
            out = dataclasses.replace(sensitivities(motion, t, names), parameters=tuple(p.name for p in params))
    _refuse_non_finite(out, what)
    return motion, out  # type: ignore[return-value]


def _refuse_non_finite(sens: Sensitivities | NetworkSensitivities, what: str) -> None:
    """A ``ValueError`` naming the first derivative of ``x`` or ``v`` that is not finite, and when."""
    for array in (sens.x, sens.v):
        bad = ~np.isfinite(array.reshape(array.shape[0], -1, array.shape[-1]))
        if bad.any():
            i, _, j = np.argwhere(bad)[0]
            raise ValueError(
                f"{what}: the derivative by {sens.parameters[j]!r} is not finite at t = {sens.t[i]:.6g} s: "
                "the exact sensitivities overflow double precision for this system"
            )


def _scaled(sens: NetworkSensitivities, factors: np.ndarray, names: tuple[str, ...]) -> NetworkSensitivities:
    """``sens`` with each column multiplied by its chain-rule factor and named ``names``."""
    events = tuple(dataclasses.replace(e, time=e.time * factors, x=e.x * factors) for e in sens.events)
    return dataclasses.replace(
        sens,
        parameters=names,  # type: ignore[arg-type]
        x=sens.x * factors,
        v=sens.v * factors,
        events=events,
        rest_time=sens.rest_time * factors,
        rest_position=sens.rest_position * factors,
    )


@dataclasses.dataclass(frozen=True)
class NetworkOneSided:
    """A network's derivatives in one parameter on each side of its value (:func:`one_sided_sensitivities`).

    Attributes
    ----------
    parameter : str
        Its name as in the file.
    delta : float
        The distance of each side from the value, in the parameter's units.
    below, above : NetworkSensitivities
        The derivatives (one column) of the motions at ``p - delta`` and ``p + delta``, each with its own events.
    same_events : bool
        True when both sides have the same events (kinds and elements, in order): differentiable at ``p``.
    x_jump : ndarray, (T, n), m
        Jump of each mass's position at the times ``t``.
    rest_time_jump, rest_position_jump : ndarray, (n,), s and m
        Jumps of each mass's rest (``nan`` for a mass that moves at the end on either side).
    """

    parameter: str
    delta: float
    below: NetworkSensitivities
    above: NetworkSensitivities
    same_events: bool
    x_jump: np.ndarray
    rest_time_jump: np.ndarray
    rest_position_jump: np.ndarray


def one_sided_sensitivities(
    network: Network, t: np.ndarray | Sequence[float], parameters: str | Sequence[str], step: float = STEP
) -> tuple[OneSided | NetworkOneSided, ...]:
    """The one-sided derivatives of a system's exact motion in each of ``parameters``, and the jumps.

    Where the event sequence changes with a parameter (an event's margin near 0:
    :meth:`~lumped.solvers.network_sensitivities.NetworkSensitivities.smallest_margin`), the motion is solved
    again at ``p -+ delta`` (``delta = step |p|``, ``step`` if ``p = 0``) and each side differentiated
    (:mod:`lumped.solvers.one_sided`, whose Notes give the accuracy: each side's derivative is the one-sided
    one to first order in ``delta``; a jump is ``S(p + delta) - S(p - delta) - delta (S'_+ + S'_-)``).  A
    one-mass system is answered by :func:`lumped.solvers.one_sided.one_sided` (its parameters renamed as
    given), a network by its own solver.

    Raises
    ------
    ValueError
        One line: what :func:`system_sensitivities` refuses, a step outside ``(0, 1e-3]``, or a parameter
        that cannot move by ``delta`` (the value refused there).
    """
    if not 0 < step <= 1e-3:
        raise ValueError(f"step must lie in (0, 1e-3], got {step!r}")
    params, how, _ = plan(network, parameters)
    if not isinstance(how, NetworkPlan):
        solution, _ = system_sensitivities(network, t, parameters)
        sides = one_sided(solution, how, t, step)  # type: ignore[arg-type]
        return tuple(dataclasses.replace(side, parameter=p.name) for side, p in zip(sides, params, strict=True))
    return tuple(_network_sides(network, t, p, step * (abs(p.value) or 1.0)) for p in params)


def _network_sides(network: Network, t, p: SystemParameter, delta: float) -> NetworkOneSided:
    """:class:`NetworkOneSided` of ``p`` from the motions at ``p -+ delta``."""
    runs = [system_sensitivities(with_values(network, [p], [p.value + d]), t, [p.name]) for d in (-delta, delta)]
    (lo_motion, below), (hi_motion, above) = runs
    same = [(e.kind, e.elements) for e in lo_motion.events] == [(e.kind, e.elements) for e in hi_motion.events]
    x_jump = above.positions - below.positions - delta * (below.x[:, :, 0] + above.x[:, :, 0])
    rests = [final_rest(list(m.phases), s.positions[-1]) for m, s in ((lo_motion, below), (hi_motion, above))]
    time_jump = rests[1][0] - rests[0][0] - delta * (below.rest_time[:, 0] + above.rest_time[:, 0])
    position_jump = rests[1][1] - rests[0][1] - delta * (below.rest_position[:, 0] + above.rest_position[:, 0])
    return NetworkOneSided(p.name, delta, below, above, same, x_jump, time_jump, position_jump)
