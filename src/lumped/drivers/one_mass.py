"""A one-mass run written back on the network it came from (:func:`network_trajectory`).

A network of the paper's form (one mass, linear springs and one dashpot, all
to the ground: :func:`lumped.model.problem.one_mass_form`) is run as an
:class:`~lumped.model.oscillator.Oscillator` by a single-mass method, or by
Algorithm 1's kernel; :func:`network_trajectory` gives each element its force.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from lumped.laws.element import GROUND, Element
from lumped.model.network import Network
from lumped.model.problem import OneMass
from lumped.model.trajectory import Trajectory
from lumped.solvers.events import Event

__all__ = ["network_trajectory"]


def _orientation(el: Element) -> float:
    """+1 if the element's elongation is the mass's position, -1 if its negative."""
    return 1.0 if el.between[0] == GROUND else -1.0


def network_trajectory(net: Network, form: OneMass, tr: Trajectory, solver: str) -> Trajectory:
    """The trajectory of a one-mass run ``tr`` written on the network ``net`` it came from.

    Each spring carries the share ``k_i / k`` of ``F_s`` (all of it, exactly,
    for one spring); tensions take the sign of each element's orientation.
    """
    k = form.oscillator.stiffness
    zeros = np.zeros_like(tr.t)
    forces = {s.name: _orientation(s) * (s.linear_stiffness / k) * tr.F_s for s in form.springs}
    forces[form.dashpot.name] = _orientation(form.dashpot) * tr.F_d
    stick = (tr.v == 0) & (tr.t > 0)
    springs = {s.name for s in form.springs}
    columns = [
        (forces[e.name], forces[e.name] if e.name in springs else zeros, stick if e is form.dashpot else zeros > 0)
        for e in net.elements
    ]
    force, state, rigid = (np.column_stack([c[i] for c in columns]) for i in range(3))
    rest = (np.array([tr.rest_time]), np.array([tr.rest_position]))
    events = tuple(_on_network(e, net, form) for e in tr.events)
    return replace(
        tr, forces=force, network=net, states=state, rigid=rigid, final_rest=rest, solver=solver, events=events
    )


def _on_network(event: object, net: Network, form: OneMass) -> object:
    """An :class:`~lumped.solvers.events.Event` of the one-mass run named on ``net``: its dashpot's name and
    mode (the dashpot's slip direction in that element's own orientation); a ``Jump`` as it is."""
    if not isinstance(event, Event):
        return event
    mode = tuple(int(_orientation(e) * event.mode[-1]) if e is form.dashpot else 0 for e in net.elements)
    return replace(event, elements=tuple(form.dashpot.name for _ in event.elements), mode=mode)
