"""Friction contacts as network elements: any :class:`lumped.laws.SlipLaw` between two points.

:class:`SlipElement` turns a friction law into the element contract of
:class:`lumped.laws.element.Element`: its state is the contact's direction
at the step's start (``-1`` slipping back, ``0`` stuck, ``+1`` slipping
forward), its step graph the law's three branches with the rule that picks
one (:class:`lumped.laws.step_graph.SlipGraph`), and a law that *is* the
Bingham graph (static equal to kinetic, no fall) is run as the Bingham
element it equals.  :class:`Contact` holds any law (API); the kinds a system
file writes hold their law's parameters (:mod:`lumped.laws.stribeck`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

from lumped.laws.bingham import BinghamDashpot
from lumped.laws.element import Element, KernelForm
from lumped.laws.contract import SlipLaw
from lumped.laws.step_graph import (
    SLIP_BACK,
    SLIP_FORWARD,
    STICK,
    CurveSlipGraph,
    Piece,
    SlipGraph,
    StepGraph,
    bingham_band,
    free_piece,
)

__all__ = ["SlipElement", "Contact"]

_BINGHAM_CODE = 2  # the Bingham element's kind code in ``_network_elements.h``


def _start(state: float) -> int:
    """The piece a contact in ``state`` (-1, 0, +1) starts its step on."""
    return SLIP_FORWARD if state > 0 else SLIP_BACK if state < 0 else STICK


class SlipElement:
    """A friction contact given by its law (``law``, a :class:`lumped.laws.SlipLaw`).

    The state is the contact's direction: ``0`` stuck, ``+1`` or ``-1``
    slipping, from the sign of the initial rate and then from each step's
    end (a step ending on the stick piece is stuck).
    """

    law: SlipLaw

    @property
    def rigid_capable(self) -> bool:
        return True

    def initial_state(self, e0: float, w0: float) -> float:
        return 0.0 if w0 == 0 else math.copysign(1.0, w0)

    def step_graph(self, state: float, dt: float) -> StepGraph | tuple[Piece, ...]:
        form = self.law.bingham_form()
        if form is not None:  # the Bingham graph itself: the Bingham element's pieces
            return bingham_band(form.threshold, form.viscosity)
        pieces = self.law.pieces()
        if pieces is not None and len(pieces) == 1:
            return SlipGraph(self.law.static, pieces[0].a, pieces[0].b, _start(state))
        return CurveSlipGraph(self.law, _start(state))

    def rate_graph(self, state: float, w0: float) -> StepGraph | tuple[Piece, ...]:
        if w0 != 0:
            return (free_piece(float(self.law.tension(w0)), 0.0),)
        if self.law.slip_limit == self.law.static:
            return bingham_band(self.law.static, 0.0)
        return SlipGraph(self.law.static, self.law.slip_limit, 0.0, STICK)

    def next_state(self, state: float, dt: float, w: float, f: float, rigid: bool) -> float:
        return 0.0 if rigid or w == 0 else math.copysign(1.0, w)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return self.law.force_interval(w)

    @property
    def steepest_fall(self) -> float:
        return self.law.fall

    def slip_law(self) -> SlipLaw:
        """The contact's law (point 12 of the element contract)."""
        return self.law

    @property
    def monotone(self) -> bool:
        """True if the slip curve starts at ``static`` and never falls (the Bingham graph among them)."""
        return self.law.slip_limit >= self.law.static and self.law.fall == 0

    def one_mass_law(self) -> BinghamDashpot | None:
        """The Bingham law this contact equals, if it is one (the paper's methods run it), else ``None``."""
        form = self.law.bingham_form()
        if form is None:
            return None
        return BinghamDashpot(form.threshold, math.inf if form.viscosity == 0 else 1.0 / form.viscosity)

    @property
    def auto_one_mass(self) -> bool:
        """True when the contact is the Bingham graph: Algorithm 1 itself runs it."""
        return self.law.bingham_form() is not None

    def kernel_form(self) -> KernelForm | None:
        """The Bingham element's form when the contact is the Bingham graph; ``None`` otherwise."""
        form = self.law.bingham_form()
        if form is None:
            return None
        return KernelForm(_BINGHAM_CODE, (form.threshold, form.viscosity), True)


@dataclass(frozen=True)
class Contact(SlipElement, Element):
    """A friction contact with any :class:`lumped.laws.SlipLaw` (API), e.g. a :class:`lumped.laws.SlipCurve`."""

    kind: ClassVar[str] = "contact"
    law: SlipLaw = field(default=None)  # type: ignore[assignment]

    def _check(self) -> None:
        SlipLaw.check(self.law, "law")
