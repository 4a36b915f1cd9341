"""Dashpot element kinds: no state, the step graph is the law's graph.

:class:`Bingham` (eq. 6, Coulomb at ``gamma = inf``), :class:`LinearDashpot`,
:class:`LockingBingham` (a Bingham dashpot that also locks at a rate), and
the elements given by a dashpot law of :mod:`lumped.laws`
(:class:`LawElement`: :class:`Monotone`, :class:`HerschelBulkley`), each by
the contract of :class:`lumped.laws.element.Element`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

from lumped.laws.bingham import BinghamDashpot
from lumped.laws.contract import Dashpot
from lumped.laws.element import Element
from lumped.laws.monotone import HerschelBulkleyDashpot
from lumped.laws.step_graph import LawGraph, Piece, bingham_band, free_piece, rigid_piece
from lumped.numerics import validate

__all__ = ["Bingham", "LinearDashpot", "LockingBingham", "LawElement", "Monotone", "HerschelBulkley"]

_INF = math.inf


@dataclass(frozen=True)
class Bingham(Element):
    """Bingham dashpot, eq. (6): ``w = 0`` for ``|f| <= threshold``, else
    ``f = sgn(w) threshold + w/gamma``; ``gamma = inf`` is Coulomb.

    The law is :class:`lumped.laws.BinghamDashpot` (:attr:`law`); the step
    graph is its graph itself (a dashpot has no state).
    """

    kind: ClassVar[str] = "bingham"
    kernel_code: ClassVar[int | None] = 2
    threshold: float = 1.0
    gamma: float = 1.0

    def _check(self) -> None:
        law = BinghamDashpot(self.threshold, self.gamma)  # its checks, its messages
        object.__setattr__(self, "threshold", law.threshold)
        object.__setattr__(self, "gamma", law.gamma)

    @property
    def law(self) -> BinghamDashpot:
        """The dashpot law of :mod:`lumped.laws`."""
        return BinghamDashpot(self.threshold, self.gamma)

    @property
    def viscosity(self) -> float:
        """``c = 1/gamma`` (N s/m), 0 for Coulomb."""
        return self.law.viscosity

    @property
    def rigid_capable(self) -> bool:
        return self.threshold > 0

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        return bingham_band(self.threshold, self.viscosity)

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        if w0 != 0:
            return (free_piece(float(self.law.slip_force(w0)), 0.0),)
        return bingham_band(self.threshold, 0.0)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return self.law.force_interval(w)

    def one_mass_law(self) -> BinghamDashpot:
        return self.law

    @property
    def auto_one_mass(self) -> bool:
        """True: Algorithm 1 itself, the same numbers bit for bit at the compiled kernel's speed."""
        return True

    def _kernel_form(self) -> tuple[list[float], bool]:
        c = BinghamDashpot(self.threshold, self.gamma).viscosity
        return [self.threshold, c], True  # a threshold 0 included: the graph keeps its rigid piece


@dataclass(frozen=True)
class LinearDashpot(Element):
    """Linear viscous dashpot, ``f = damping * w``."""

    kind: ClassVar[str] = "dashpot"
    kernel_code: ClassVar[int | None] = 4
    damping: float = 1.0

    def _check(self) -> None:
        self._set("damping", validate.positive)

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        return (free_piece(0.0, self.damping),)

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        return (free_piece(self.damping * w0, 0.0),)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return (self.damping * w, self.damping * w)

    def one_mass_law(self) -> HerschelBulkleyDashpot:
        """``f = damping * w`` as the Herschel-Bulkley law with no threshold and exponent 1."""
        return HerschelBulkleyDashpot(0.0, self.damping, 1.0)

    def _kernel_form(self) -> tuple[list[float], bool]:
        return [self.damping], False


@dataclass(frozen=True)
class LockingBingham(Element):
    """A Bingham dashpot that also locks at the rate ``v_lock``: invertible neither way.

    The graph: no motion while ``|f| <= threshold``; ``f = sgn(w) threshold
    + w/gamma`` for ``0 < |w| < v_lock``; and ``|w| = v_lock`` for every
    ``|f| >= threshold + v_lock/gamma``: no speed above ``v_lock`` whatever
    the force.  The force is not a function of the rate (vertical at 0 and at
    ``+-v_lock``); with ``gamma = inf`` the rate is not a function of the force
    either (horizontal at ``+-threshold``), the case the name is meant for.
    (With a finite ``gamma`` the rate is a function of the force, clipped at
    ``v_lock``, but not an invertible one.)  The potential of its step is
    ``threshold |w| + w^2/(2 gamma)`` plus the indicator of ``|w| <= v_lock``.

    A rate beyond ``v_lock`` at ``t = 0`` is brought to ``v_lock`` in the
    first step, an impact like a string's.
    """

    kind: ClassVar[str] = "locking-bingham"
    kernel_code: ClassVar[int | None] = 5
    threshold: float = 1.0
    gamma: float = 1.0
    v_lock: float = 1.0

    def _check(self) -> None:
        law = BinghamDashpot(self.threshold, self.gamma)
        object.__setattr__(self, "threshold", law.threshold)
        object.__setattr__(self, "gamma", law.gamma)
        self._set("v_lock", validate.positive)

    @property
    def rigid_capable(self) -> bool:
        return True

    def _edge(self) -> float:
        return self.threshold + BinghamDashpot(self.threshold, self.gamma).viscosity * self.v_lock

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        lock, edge = self.v_lock, self._edge()
        c = BinghamDashpot(self.threshold, self.gamma).viscosity
        return (
            rigid_piece(-lock, -_INF, -edge),
            *bingham_band(self.threshold, c, -lock, lock),
            rigid_piece(lock, edge, _INF),
        )

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        edge = self._edge()
        if w0 == 0:
            return bingham_band(self.threshold, 0.0)
        if abs(w0) >= self.v_lock:
            s = math.copysign(1.0, w0)
            if s > 0:
                return (free_piece(edge, 0.0, -_INF, 0.0), rigid_piece(0.0, edge, _INF))
            return (rigid_piece(0.0, -_INF, -edge), free_piece(-edge, 0.0, 0.0, _INF))
        c = BinghamDashpot(self.threshold, self.gamma).viscosity
        return (free_piece(math.copysign(self.threshold, w0) + c * w0, 0.0),)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        if abs(w) > self.v_lock:
            return (math.nan, math.nan)
        lo, hi = BinghamDashpot(self.threshold, self.gamma).force_interval(w)
        if w == self.v_lock:
            return (lo, _INF)
        if w == -self.v_lock:
            return (-_INF, hi)
        return (lo, hi)

    def _kernel_form(self) -> tuple[list[float], bool]:
        c = BinghamDashpot(self.threshold, self.gamma).viscosity
        return [self.threshold, c, self.v_lock], True


class LawElement:
    """A dashpot element given by a :class:`lumped.laws.Dashpot` law (its ``law``).

    Its step graph, the law's :class:`LawGraph`, is not piecewise linear:
    each iteration of the step linearises it about the point last reached (a
    free piece through that point, of slope ``sigma``), so the step problem
    is solved to within the iteration's tolerance, not exactly; see
    :mod:`lumped.solvers.network_step`.
    """

    law: Dashpot

    def step_graph(self, state: float, dt: float) -> LawGraph:  # type: ignore[override]
        return LawGraph(self.law)

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        lo, hi = self.law.force_interval(w0)
        return (free_piece(lo, 0.0),) if lo == hi else bingham_band(hi, 0.0)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return self.law.force_interval(w)

    @property
    def rigid_capable(self) -> bool:
        """True when the law holds a range of forces at rest (a static band)."""
        lo, hi = self.law.force_interval(0.0)
        return lo < hi


@dataclass(frozen=True)
class Monotone(LawElement, Element):
    """Any monotone dashpot law ``w = phi(f)`` (API only), as :class:`lumped.laws.MonotoneDashpot`."""

    kind: ClassVar[str] = "monotone"
    law: Dashpot = field(default=None)  # type: ignore[assignment]

    def _check(self) -> None:
        Dashpot.check(self.law, "law", "{name} must be a lumped.laws.Dashpot, got {got}")

    def one_mass_law(self) -> Dashpot:
        """The law itself: a single-mass method runs it as it runs any :class:`lumped.laws.Dashpot`."""
        return self.law

    @property
    def auto_one_mass(self) -> bool:
        """True: the law's resolvent solves the one-mass step, which the active-set step only linearises."""
        return True


@dataclass(frozen=True)
class HerschelBulkley(LawElement, Element):
    """Herschel-Bulkley dashpot, :class:`lumped.laws.HerschelBulkleyDashpot`: ``w = 0`` for
    ``|f| <= threshold``, else ``f = sgn(w) (threshold + consistency |w|^exponent)``.
    """

    kind: ClassVar[str] = "herschel-bulkley"
    threshold: float = 1.0
    consistency: float = 1.0
    exponent: float = 1.0

    def _check(self) -> None:
        law = HerschelBulkleyDashpot(self.threshold, self.consistency, self.exponent)  # its checks, its messages
        for name in ("threshold", "consistency", "exponent"):
            object.__setattr__(self, name, getattr(law, name))

    @property
    def law(self) -> HerschelBulkleyDashpot:  # type: ignore[override]
        """The dashpot law of :mod:`lumped.laws`."""
        return HerschelBulkleyDashpot(self.threshold, self.consistency, self.exponent)

    def one_mass_law(self) -> HerschelBulkleyDashpot:
        return self.law

    @property
    def auto_one_mass(self) -> bool:
        """True: the law's resolvent solves the one-mass step, which the active-set step only linearises."""
        return True
