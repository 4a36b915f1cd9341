"""What to solve: :class:`Problem`, a system with its loads and initial state, over a time span.

Every method of the registry (:data:`lumped.drivers.methods.METHODS`) takes a
:class:`Problem` through :func:`lumped.solve`.  The system is always a
:class:`~lumped.model.network.Network`: its masses carry their initial
positions and velocities, its loads the forcing.  The paper's oscillator is
the one-mass network of :meth:`Problem.oscillator`; whether a network is of
that form (one mass, springs and one dashpot, all to the ground) is asked of
the problem (:meth:`Problem.one_mass`), and the drivers use the answer to
hand it to Algorithm 1's kernel or to the single-mass methods, so the caller
never chooses the fast path.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from lumped.laws import GROUND, Element, LinearSpring, Monotone, Spring
from lumped.model.forcing import SwitchedSine, one_force
from lumped.model.network import Load, Mass, Network
from lumped.model.oscillator import Oscillator
from lumped.numerics import validate

__all__ = ["OneMass", "Problem", "one_mass_form", "oscillator_network"]

#: The names :meth:`Problem.oscillator` gives the paper's system's parts.
MASS, SPRING, DASHPOT = "m", "spring", "dashpot"


class OneMass(NamedTuple):
    """A one-mass network as an oscillator: its ``springs`` and its ``dashpot`` element."""

    oscillator: Oscillator
    springs: tuple[Element, ...]
    dashpot: Element


def one_mass_form(net: Network) -> OneMass:
    """The oscillator of a one-mass network, or a ``ValueError`` saying why it is not one.

    The network must have one mass and elements that all
    join the mass to the ground: one or more ``spring`` s and exactly one
    element with a ``one_mass_law`` (point 8 of
    :class:`~lumped.laws.element.Element`).  The message completes "the
    network ..." (``"has 3 masses"``, ``"element 'x' ..."``).
    """
    if len(net.masses) != 1:
        raise ValueError(f"has {len(net.masses)} masses")
    for el in net.elements:
        if GROUND not in el.between:
            driven = [d.name for d in net.drivers if d.name in el.between]
            joins = f"joins the mass to the driven point {driven[0]!r}, not" if driven else "does not join the mass"
            raise ValueError(f"element {el.name!r} {joins} to the ground")
        if el.linear_stiffness is None and el.one_mass_law() is None:
            raise ValueError(f"element {el.name!r} of kind {el.kind!r} is not a spring or a dashpot")
    springs = tuple(el for el in net.elements if el.linear_stiffness is not None)
    dashpots = [el for el in net.elements if el.one_mass_law() is not None]
    if not springs or len(dashpots) != 1:
        raise ValueError(f"has {len(springs)} springs and {len(dashpots)} dashpots; it needs springs and one dashpot")
    stiffness = sum(s.linear_stiffness for s in springs)
    osc = Oscillator(net.masses[0].mass, LinearSpring(stiffness), dashpots[0].one_mass_law())
    return OneMass(osc, springs, dashpots[0])


def oscillator_network(
    oscillator: Oscillator,
    x0: float = 0.0,
    v0: float = 0.0,
    force: SwitchedSine | Callable[[np.ndarray], np.ndarray] | None = None,
) -> Network:
    """The paper's system (Figure 3) as a network: the mass ``"m"`` starting at ``x0`` with ``v0``,
    the spring ``"spring"`` and the dashpot ``"dashpot"`` from the ground, ``force`` (if any) on the mass.

    The dashpot is a :class:`~lumped.laws.Monotone` element holding
    ``oscillator.dashpot`` itself (any law), so :func:`one_mass_form` gives
    back an oscillator equal to ``oscillator``, with the same law object.
    """
    if not isinstance(oscillator, Oscillator):
        raise ValueError(f"oscillator must be an Oscillator, got {type(oscillator).__name__}")
    between = (GROUND, MASS)
    elements = [Spring(SPRING, between, oscillator.stiffness), Monotone(DASHPOT, between, oscillator.dashpot)]
    loads = [] if force is None else [Load(MASS, force)]
    return Network([Mass(MASS, oscillator.mass, x0, v0)], elements, loads)


@dataclass(frozen=True)
class Problem:
    """A system over the span ``[0, t_end]``.

    Parameters
    ----------
    system : Network
        Masses (each with its ``x0`` and ``v0``), elements and loads.
    t_end : float, s
        End of the span, ``> 0``.
    """

    system: Network
    t_end: float

    def __post_init__(self) -> None:
        if not isinstance(self.system, Network):
            raise ValueError(f"system must be a Network, got {type(self.system).__name__}")
        object.__setattr__(self, "t_end", validate.positive("t_end", self.t_end))
        self.system.check_span(self.t_end)  # no driven point beyond double precision: no inf in any method's output

    @classmethod
    def oscillator(
        cls,
        oscillator: Oscillator,
        t_end: float,
        *,
        x0: float = 0.0,
        v0: float = 0.0,
        force: SwitchedSine | Callable[[np.ndarray], np.ndarray] | None = None,
    ) -> Problem:
        """The paper's system as the one-mass network of :func:`oscillator_network`.

        :meth:`one_mass` gives back an oscillator equal to ``oscillator``, with
        the same law object, so a method runs it exactly as it runs ``oscillator``.
        """
        return cls(oscillator_network(oscillator, x0, v0, force), t_end)

    def one_mass(self) -> OneMass:
        """The system as an oscillator (:func:`one_mass_form`), or a ``ValueError`` saying why it is not one."""
        return one_mass_form(self.system)

    @property
    def force(self) -> SwitchedSine | Callable[[np.ndarray], np.ndarray] | None:
        """The load of a one-mass system: ``None`` if it has none, the load itself if one,
        else their sum as one callable (:func:`~lumped.model.forcing.one_force`)."""
        return one_force([load.force for load in self.system.loads])
