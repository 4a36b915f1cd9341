"""Networks that are the paper's system: one mass, linear springs and one dashpot, all to the ground.

Such a network is an :class:`~lumped.model.oscillator.Oscillator` (the springs in
parallel add their stiffnesses) and can be handed to the single-mass
methods of :data:`lumped.drivers.methods.METHODS`; :func:`simulate_one_mass` does
that and writes the result back as the network's
:class:`~lumped.model.network_trajectory.NetworkTrajectory`.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from lumped.laws import LinearSpring
from lumped.laws.elements import GROUND, Element
from lumped.model.network import Network
from lumped.model.network_trajectory import NetworkTrajectory
from lumped.model.oscillator import Oscillator
from lumped.model.trajectory import Trajectory

__all__ = ["OneMass", "one_mass_form", "network_trajectory", "simulate_one_mass"]


class OneMass(NamedTuple):
    """A one-mass network as an oscillator: its ``springs`` and its ``dashpot`` element."""

    oscillator: Oscillator
    springs: tuple[Element, ...]
    dashpot: Element


def one_mass_form(net: Network) -> OneMass:
    """The oscillator of a one-mass network, or a ``ValueError`` saying why it is not one.

    The network must have one mass, at most one load, and elements that all
    join the mass to the ground: one or more ``spring`` s and exactly one
    ``bingham``, ``herschel-bulkley`` or ``dashpot`` (the elements with a
    ``linear_stiffness`` and those with a ``one_mass_law``: point 8 of
    :class:`~lumped.laws.elements.Element`).  The message completes
    "the network ..." (``"has 3 masses"``, ``"element 'x' ..."``).
    """
    if len(net.masses) != 1:
        raise ValueError(f"has {len(net.masses)} masses")
    if len(net.loads) > 1:
        raise ValueError(f"has {len(net.loads)} [[force]] entries; combine them into one")
    for el in net.elements:
        if GROUND not in el.between:
            raise ValueError(f"element {el.name!r} does not join the mass to the ground")
        if el.linear_stiffness is None and el.one_mass_law() is None:
            raise ValueError(f"element {el.name!r} of kind {el.kind!r} is not a spring or a dashpot")
    springs = tuple(el for el in net.elements if el.linear_stiffness is not None)
    dashpots = [el for el in net.elements if el.one_mass_law() is not None]
    if not springs or len(dashpots) != 1:
        raise ValueError(f"has {len(springs)} springs and {len(dashpots)} dashpots; it needs springs and one dashpot")
    stiffness = sum(s.linear_stiffness for s in springs)
    osc = Oscillator(net.masses[0].mass, LinearSpring(stiffness), dashpots[0].one_mass_law())
    return OneMass(osc, springs, dashpots[0])


def _orientation(el: Element) -> float:
    """+1 if the element's elongation is the mass's position, -1 if its negative."""
    return 1.0 if el.between[0] == GROUND else -1.0


def network_trajectory(net: Network, form: OneMass, tr: Trajectory, solver: str) -> NetworkTrajectory:
    """The :class:`~lumped.model.network_trajectory.NetworkTrajectory` of a one-mass trajectory.

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
    return NetworkTrajectory(tr.t, tr.x[:, None], tr.v[:, None], force, state, rigid, *rest, net, tr.dt, solver, 0)


def simulate_one_mass(
    net: Network, t_end: float, dt: float, *, save_every: int = 1, method: str = "event-driven", **options: object
) -> NetworkTrajectory:
    """Run a one-mass network by a single-mass ``method`` of :data:`lumped.drivers.methods.METHODS`.

    ``options`` are the method's (``rtol`` for ``event-driven``).  Raises a
    ``ValueError`` beginning with ``method`` if the network is not of the
    form of :func:`one_mass_form`.
    """
    from lumped.drivers.simulation import simulate

    try:
        form = one_mass_form(net)
    except ValueError as err:
        raise ValueError(f"method {method!r} needs a one-mass system; the network {err}") from None
    m = net.masses[0]
    force = net.loads[0].force if net.loads else None
    tr = simulate(
        form.oscillator, t_end, dt, x0=m.x0, v0=m.v0, force=force, method=method, save_every=save_every, **options
    )
    return network_trajectory(net, form, tr, method)
