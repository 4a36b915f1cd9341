"""Friction with static above kinetic and a Stribeck fall: the ``friction`` kind of system files.

Off zero rate ``u`` the tension is

    T(u) = sgn(u) (kinetic + (static - kinetic) d(|u|/v_s)) + viscous u,

with the decay ``d`` one of ``exp(-x)`` (``"exponential"``, the default),
``exp(-x^2)`` (``"gaussian"``) or ``1/(1 + x)`` (``"rational"``) and ``v_s``
the Stribeck velocity; without a Stribeck velocity the tension drops from
``static`` to ``kinetic`` as soon as the contact slips.  At zero rate it is
anything in ``[-static, static]``.  The law (:class:`StribeckLaw`) and its
element (:class:`Friction`) are this one file, by the contracts of
:class:`lumped.laws.SlipLaw` and :class:`lumped.laws.slip_elements.SlipElement`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from lumped.laws.element import Element
from lumped.laws.contract import SlipLaw, SlipPiece, Slope
from lumped.laws.slip_elements import SlipElement
from lumped.numerics import validate

__all__ = ["DECAYS", "StribeckLaw", "Friction"]

#: The decays by name: the function of ``x = |u|/v_s``, its steepest fall ``max(-d'(x))``, its
#: code in the compiled one-mass loop and its derivative ``d'(x)``.
DECAYS = {
    "exponential": (lambda x: np.exp(-x), 1.0, 1, lambda x: -math.exp(-x)),
    # -d' = 2x exp(-x^2), largest at 1/sqrt(2)
    "gaussian": (lambda x: np.exp(-x * x), math.sqrt(2.0 / math.e), 2, lambda x: -2.0 * x * math.exp(-x * x)),
    "rational": (lambda x: 1.0 / (1.0 + x), 1.0, 3, lambda x: -1.0 / ((1.0 + x) * (1.0 + x))),
}


@dataclass(frozen=True)
class StribeckLaw(SlipLaw):
    """Static above kinetic with an optional Stribeck fall and a viscous part (see the module docstring).

    Parameters
    ----------
    static : float, N
        The largest tension a stuck contact holds (> 0).
    kinetic : float, N
        The sliding tension's limit at high speed, ``0 <= kinetic <= static``.
    stribeck_velocity : float or None, m/s
        ``v_s > 0``; ``None`` for a drop to ``kinetic`` as soon as the contact slips.
    decay : str
        ``"exponential"``, ``"gaussian"`` or ``"rational"``.
    viscous : float, N s/m
        ``>= 0``.
    """

    static: float = 1.0
    kinetic: float = 1.0
    stribeck_velocity: float | None = None
    decay: str = "exponential"
    viscous: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "static", validate.positive("static", self.static))
        object.__setattr__(self, "kinetic", validate.non_negative("kinetic", self.kinetic))
        if self.kinetic > self.static:
            raise ValueError(f"kinetic = {self.kinetic!r} N must not exceed static = {self.static!r} N")
        if self.stribeck_velocity is not None:
            object.__setattr__(
                self, "stribeck_velocity", validate.positive("stribeck_velocity", self.stribeck_velocity)
            )
        if not isinstance(self.decay, str) or self.decay not in DECAYS:  # an array is no key: the same message
            raise ValueError(f"decay must be one of {', '.join(map(repr, DECAYS))}; got {self.decay!r:.40}")
        object.__setattr__(self, "viscous", validate.non_negative("viscous", self.viscous))

    @property
    def _falls(self) -> bool:
        """True if the tension falls with speed (a Stribeck velocity and static above kinetic)."""
        return self.stribeck_velocity is not None and self.static > self.kinetic

    def slip(self, speed: np.ndarray | float) -> np.ndarray | float:
        if isinstance(speed, float):  # the event-driven integrators' scalar calls: the same operations, no arrays
            base = self.kinetic + self.viscous * speed
            if self._falls:
                base = base + (self.static - self.kinetic) * DECAYS[self.decay][0](speed / self.stribeck_velocity)
            return float(base)
        base = self.kinetic + self.viscous * np.asarray(speed, dtype=float)
        if self._falls:
            base = base + (self.static - self.kinetic) * DECAYS[self.decay][0](
                np.asarray(speed) / self.stribeck_velocity
            )
        return float(base) if np.ndim(speed) == 0 else base

    @property
    def slip_limit(self) -> float:
        return self.static if self._falls else self.kinetic

    @property
    def fall(self) -> float:
        if not self._falls:
            return 0.0
        return max(0.0, (self.static - self.kinetic) / self.stribeck_velocity * DECAYS[self.decay][1] - self.viscous)

    def pieces(self) -> tuple[SlipPiece, ...] | None:
        return None if self._falls else (SlipPiece(0.0, math.inf, self.kinetic, self.viscous),)

    def slope(self, speed: float) -> Slope:
        """``g'(s) = viscous + (static - kinetic)/v_s d'(s/v_s)`` in closed form (point 9); its error is the
        rounding of a few operations on terms of the size of ``viscous`` and the fall, ``8 eps`` of them taken."""
        if not self._falls:
            return Slope(self.viscous, 0.0)
        v_s = self.stribeck_velocity
        fall = (self.static - self.kinetic) / v_s * DECAYS[self.decay][3](speed / v_s)
        return Slope(self.viscous + fall, 8 * float(np.finfo(float).eps) * (self.viscous - fall))

    def kernel_form(self) -> tuple[int, tuple[float, ...]]:
        """Code 0 (no fall) or the decay's code, with ``(static, kinetic, v_s or 0, viscous)``."""
        code = DECAYS[self.decay][2] if self._falls else 0
        return code, (self.static, self.kinetic, self.stribeck_velocity or 0.0, self.viscous)


@dataclass(frozen=True)
class Friction(SlipElement, Element):
    """A friction contact of :class:`StribeckLaw` (system files: ``kind = "friction"``)."""

    kind: ClassVar[str] = "friction"
    optional: ClassVar[tuple[str, ...]] = ("stribeck_velocity", "decay", "viscous")
    static: float = 1.0
    kinetic: float = 1.0
    stribeck_velocity: float | None = None
    decay: str = "exponential"
    viscous: float = 0.0

    def _check(self) -> None:
        law = StribeckLaw(self.static, self.kinetic, self.stribeck_velocity, self.decay, self.viscous)
        for name in ("static", "kinetic", "stribeck_velocity", "decay", "viscous"):
            object.__setattr__(self, name, getattr(law, name))
        # the law, built and checked once (the step, the plans and the checks ask for it many times per
        # element: for 100,000 contacts, rebuilding it on each ask took most of a network's set-up)
        object.__setattr__(self, "_law", law)

    @property
    def law(self) -> StribeckLaw:  # type: ignore[override]
        """The friction law of this contact."""
        return self._law  # type: ignore[attr-defined]
