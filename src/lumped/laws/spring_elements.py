"""Element kinds with a spring, whose state is a force or an elongation.

:class:`Spring` (``f = k e``), :class:`SpringString` (a spring with an
inextensible string beside it) and :class:`MaxwellBingham` (a spring in
series with a Bingham dashpot), each by the contract of
:class:`lumped.laws.element.Element`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from lumped.laws.bingham import BinghamDashpot, sticks
from lumped.laws.element import Element
from lumped.laws.step_graph import Piece, free_piece, rigid_piece
from lumped.numerics import validate

__all__ = ["Spring", "SpringString", "MaxwellBingham"]

_INF = math.inf


class _ForceState:
    """Elements whose state is the force ``f`` of a spring of ``stiffness``."""

    stiffness: float

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        return (free_piece(state, 0.0),)

    def next_state(self, state: float, dt: float, w: float, f: float, rigid: bool) -> float:
        return f

    def stored_energy(self, state: float) -> float:
        return 0.5 * state * state / self.stiffness

    @property
    def step_stiffness(self) -> float:
        return self.stiffness


@dataclass(frozen=True)
class Spring(_ForceState, Element):
    """Linear spring, ``f = k e``.

    The state is the force, advanced as ``f + dt*k*w`` exactly as line 11 of
    Algorithm 1 advances ``F_s``.
    """

    kind: ClassVar[str] = "spring"
    kernel_code: ClassVar[int | None] = 0
    stiffness: float = 1.0

    def _check(self) -> None:
        self._set("stiffness", validate.positive)

    def initial_state(self, e0: float, w0: float) -> float:
        return self.stiffness * e0

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        return (free_piece(state, dt * self.stiffness),)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return (self.stiffness * e, self.stiffness * e)

    @property
    def linear_stiffness(self) -> float:
        return self.stiffness

    def _kernel_form(self) -> tuple[list[float], bool]:
        return [self.stiffness], False


@dataclass(frozen=True)
class SpringString(Element):
    """A linear spring in parallel with an inextensible string (the paper's Figure 2).

    ``e <= L``; ``f = k e`` while slack (``e < L``), any ``f >= k L`` while
    taut (``e = L``).  The elongation is a function of the force, not the
    reverse: the graph is the spring's line up to ``(L, kL)``, then the
    vertical ray above it.

    Notes
    -----
    The step graph in ``w`` is the spring's line ``f = k e_n + dt k w`` for
    ``w <= (L - e_n)/dt`` and the vertical ray ``f >= kL`` at
    ``w = (L - e_n)/dt`` (the normal cone of ``e <= L``: Moreau's sweeping
    process).  So a string that would pass its length within a step ends the
    step exactly taut (the state is set to ``L``, not recomputed), and the
    relative velocity jumps to ``(L - e_n)/dt`` and, on the next step, to 0:
    an *inelastic impact* of the relative motion, which backward Euler (like
    the sweeping process) resolves with restitution 0.  The kinetic energy of
    the relative motion it removes is the work ``(f - k L)(L - e_n)`` of the
    string's reaction, counted as dissipation in the energy balance.
    """

    kind: ClassVar[str] = "spring-string"
    kernel_code: ClassVar[int | None] = 1
    stiffness: float = 1.0
    length: float = 1.0

    def _check(self) -> None:
        self._set("stiffness", validate.positive)
        self._set("length", validate.positive)

    @property
    def rigid_capable(self) -> bool:
        return True

    def initial_state(self, e0: float, w0: float) -> float:
        if e0 > self.length:
            raise ValueError(f"x0: the initial elongation {e0:.6g} m is beyond the string's length {self.length:.6g} m")
        return e0

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        k, length = self.stiffness, self.length
        reach = (length - state) / dt
        return (free_piece(k * state, dt * k, -_INF, reach), rigid_piece(reach, k * length, _INF))

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        k = self.stiffness
        if state < self.length or w0 < 0:
            return (free_piece(k * state, 0.0),)
        return (free_piece(k * self.length, 0.0, -_INF, 0.0), rigid_piece(0.0, k * self.length, _INF))

    def next_state(self, state: float, dt: float, w: float, f: float, rigid: bool) -> float:
        return self.length if rigid else state + dt * w

    def stored_energy(self, state: float) -> float:
        return 0.5 * self.stiffness * state * state

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        if e > self.length:
            return (math.nan, math.nan)
        k = self.stiffness
        return (k * e, k * e) if e < self.length else (k * e, _INF)

    @property
    def step_stiffness(self) -> float:
        return self.stiffness

    def _kernel_form(self) -> tuple[list[float], bool]:
        return [self.stiffness, self.length], True


@dataclass(frozen=True)
class MaxwellBingham(_ForceState, Element):
    """A linear spring (``stiffness``) in series with a Bingham dashpot, massless between.

    The state is the common force ``f`` (the spring's elongation is ``f/k``,
    the dashpot's the rest of ``e``).  Relaxed (``f = 0``) at ``t = 0``
    unless ``force0`` is given.  Inside the dashpot's band, ``|force0| <=
    threshold``, the dashpot holds; beyond it a viscous dashpot (finite
    ``gamma``) creeps from ``t = 0`` and the force relaxes towards the
    threshold (notebook 07).  A Coulomb dashpot (``gamma = inf``) carries no
    force beyond its threshold, so there ``|force0| > threshold`` is not an
    admissible state (backward Euler would drop the force to the threshold in
    the first step, whatever ``dt``) and is refused.

    Notes
    -----
    Backward Euler on ``f' = k (w - phi(f))`` gives ``f + dt k phi(f) = p``
    with the trial force ``p = f_n + dt k w``: the dashpot's resolvent
    (:mod:`lumped.laws`) with ``eta = 1/(dt k)``.  For the Bingham ``phi``
    it is ``f = p`` while ``|p| <= threshold`` (the dashpot holds) and
    ``f = (c p + dt k s threshold)/(c + dt k)``, ``s = sgn(p)``, beyond
    (Coulomb, ``c = 0``: ``f = s threshold``).  Each is affine in ``w``, so
    the element is never rigid: its force is always a function of the motion.
    """

    kind: ClassVar[str] = "maxwell-bingham"
    kernel_code: ClassVar[int | None] = 3
    stiffness: float = 1.0
    threshold: float = 1.0
    gamma: float = 1.0
    force0: float = 0.0
    optional: ClassVar[tuple[str, ...]] = ("force0",)

    def _check(self) -> None:
        self._set("stiffness", validate.positive)
        law = BinghamDashpot(self.threshold, self.gamma)
        object.__setattr__(self, "threshold", law.threshold)
        object.__setattr__(self, "gamma", law.gamma)
        self._set("force0", validate.finite)
        if math.isinf(self.gamma) and not sticks(self.force0, -self.threshold, self.threshold):
            raise ValueError(
                f"force0 = {self.force0:.6g} N lies outside the band |f| <= threshold = {self.threshold:.6g} N, "
                "which a Coulomb dashpot (gamma = inf) cannot leave; lower |force0| or give a finite gamma"
            )

    def initial_state(self, e0: float, w0: float) -> float:
        return self.force0

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        kdt, tau = dt * self.stiffness, self.threshold
        c = BinghamDashpot(tau, self.gamma).viscosity
        lo, hi = (-tau - state) / kdt, (tau - state) / kdt  # |p| <= tau
        slope = c * kdt / (c + kdt)
        return (
            free_piece((c * state - kdt * tau) / (c + kdt), slope, -_INF, lo),
            free_piece(state, kdt, lo, hi),
            free_piece((c * state + kdt * tau) / (c + kdt), slope, hi, _INF),
        )

    def dashpot_rate(self, f: float) -> float:
        """The dashpot's elongation rate (m/s) under force ``f`` (N)."""
        return float(BinghamDashpot(self.threshold, self.gamma).velocity(f))

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return (-_INF, _INF)  # a state variable: the force is not fixed by (e, w)

    def _kernel_form(self) -> tuple[list[float], bool]:
        c = BinghamDashpot(self.threshold, self.gamma).viscosity
        return [self.stiffness, self.threshold, c], False
