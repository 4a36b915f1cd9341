"""The friction contract: a law given as a graph in (rate, tension) that need not be monotone.

A friction contact relates its tension ``T`` to its slip rate ``u`` (the
rate of the element, ``w``): off zero rate it slides with
``T = sgn(u) g(|u|)``, where ``g`` is the *slip curve* (the sliding force's
magnitude, viscous part included); at zero rate it holds any tension in the
*stick interval* ``[-static, static]``.  Unlike a dashpot of
:class:`lumped.laws.Dashpot` the graph may fall: ``g(0+)`` may lie below
``static`` (static friction above kinetic) and ``g`` may decrease with speed
(Stribeck friction).  Such a graph is not maximal monotone, so a step's
solution is picked by a rule (the contact's state; see
:class:`lumped.laws.step_graph.SlipGraph`), and backward Euler needs a bound
on ``dt`` for it to be unique (:meth:`SlipLaw.fall`).

This module holds the contract :class:`SlipLaw` and :class:`SlipCurve`, the
law of any slip curve given as a callable (API).  The laws a system file
writes are in their own files (:mod:`lumped.laws.stribeck`); no solver names
any of them.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from lumped.laws.contract import BinghamForm
from lumped.numerics import validate
from lumped.numerics.roots import brentq

__all__ = ["SlipLaw", "SlipCurve", "SlipPiece", "FALL_SAMPLE"]


class SlipPiece(NamedTuple):
    """A linear piece of a slip curve: ``g(s) = a + b s`` for ``lo <= s <= hi`` (speeds, m/s)."""

    lo: float
    hi: float
    a: float
    b: float


#: Speeds at which :class:`SlipCurve` samples a callable for its checks and its steepest fall, as
#: multiples of its speed scale: 0, then 32 per decade from 1e-9 to 1e6.
FALL_SAMPLE = np.concatenate(([0.0], 10.0 ** (np.arange(-9 * 32, 6 * 32 + 1) / 32)))


class SlipLaw(ABC):
    """A friction law: a graph in (rate ``u``, tension ``T``), symmetric (``T(-u) = -T(u)``).

    A new law must provide:

    1. ``static`` (N, > 0): the stick interval at ``u = 0`` is ``[-static, static]``, the largest
       tension a stuck contact holds.
    2. ``slip(speed)``: the slip curve ``g(s)`` (N) at speeds ``s > 0`` (m/s), vectorised over NumPy
       arrays, finite and ``>= 0``; off zero rate ``T(u) = sgn(u) g(|u|)``.  Its limit at ``0+``
       (``slip_limit``, point 3) must not exceed ``static``.
    3. ``slip_limit``: ``g(0+)`` (N), the tension just after breaking away.
    4. ``fall``: the steepest fall of the slip curve, ``sup_s max(0, -g'(s))`` (N s/m): the bound
       that a backward-Euler step needs for uniqueness (one mass: ``m/dt + k dt > fall``;
       :func:`lumped.solvers.uniqueness.check_step`).  ``0`` for a curve that never falls.
    5. ``pieces()``: the slip curve as :class:`SlipPiece` s, in increasing speed, the last reaching
       ``inf``, if it is piecewise linear (so each phase has a closed form); ``None`` otherwise.

    What a solver may ask beyond points 1 to 5 is a method here with a default that any law meeting
    them satisfies; a law overrides one only to be faster or more exact.  No solver asks a law for
    its class.

    6. ``bingham_form()``: the :class:`~lumped.laws.BinghamForm` ``(tau, c)`` if the graph *is* the
       Bingham graph of eq. (6) (``g(s) = static + c s``), else ``None``.  Such a contact is run as
       the Bingham element it equals, bit for bit.
    7. ``slip_speed(z, sigma)``: the speed ``s > 0`` with ``g(s) + sigma s = z``, for ``z >
       slip_limit`` and ``sigma > fall`` (where it is unique): the slip step of a contact whose
       resolvent variable is ``z``.  The default is the linear pieces' closed form, else Brent's
       method on the bracket ``(0, z/sigma]`` (``g >= 0``).
    8. ``kernel_form()``: ``(code, parameters)`` for the compiled one-mass loop, or ``None`` (the
       default: the Python step runs it).
    """

    static: float

    @abstractmethod
    def slip(self, speed: np.ndarray | float) -> np.ndarray | float:
        """The slip curve ``g(s)`` (N) at speeds ``s > 0`` (point 2)."""

    @property
    @abstractmethod
    def slip_limit(self) -> float:
        """``g(0+)`` (N), point 3."""

    @property
    @abstractmethod
    def fall(self) -> float:
        """The steepest fall of the slip curve (N s/m), point 4."""

    def pieces(self) -> tuple[SlipPiece, ...] | None:
        """The slip curve's linear pieces, or ``None`` (point 5)."""
        return None

    def tension(self, rate: np.ndarray | float) -> np.ndarray | float:
        """``T(u) = sgn(u) g(|u|)`` off zero rate, ``0`` at ``u = 0`` (for plots)."""
        u = np.asarray(rate, dtype=float)
        out = np.where(u != 0, np.sign(u) * self.slip(np.where(u != 0, np.abs(u), 1.0)), 0.0)
        return float(out) if np.ndim(rate) == 0 else out

    def force_interval(self, rate: float) -> tuple[float, float]:
        """The tensions compatible with ``rate``: the stick interval at 0, the slip tension elsewhere."""
        if rate == 0:
            return (-self.static, self.static)
        t = float(self.tension(rate))
        return (t, t)

    def bingham_form(self) -> BinghamForm | None:
        """``(tau, c)`` if the graph is the Bingham graph (point 6), else ``None``."""
        pieces = self.pieces()
        if pieces is None or len(pieces) != 1 or pieces[0].a != self.static:
            return None
        c = pieces[0].b
        return BinghamForm(self.static, c)

    def slip_speed(self, z: float, sigma: float) -> float:
        """The speed ``s > 0`` of ``g(s) + sigma s = z`` (point 7); ``z > slip_limit``, ``sigma > 0``."""
        pieces = self.pieces()
        if pieces is not None:
            for p in pieces:
                s = (z - p.a) / (p.b + sigma)
                if s <= p.hi:
                    return max(s, p.lo)
            return s  # the last piece reaches inf
        g = self.slip
        return brentq(lambda s: float(g(s)) + sigma * s - z, 0.0, z / sigma)

    def kernel_form(self) -> tuple[int, tuple[float, ...]] | None:
        """``(code, parameters)`` of the compiled one-mass loop, or ``None`` (point 8)."""
        return None

    @staticmethod
    def check(value: object, name: str) -> SlipLaw:
        """``value`` if it is a friction law, else a ``ValueError`` (the one test of "is this a law?")."""
        if not isinstance(value, SlipLaw):
            raise ValueError(f"{name} must be a lumped.laws.SlipLaw, got {type(value).__name__}")
        return value


class SlipCurve(SlipLaw):
    """Friction with any slip curve, given as a callable of the speed (API).

    Parameters
    ----------
    static : float, N
        The largest tension a stuck contact holds (> 0).
    slip : callable
        ``g(s)``, the sliding force's magnitude (N) at speed ``s >= 0`` (m/s), viscous part included;
        ``g(0) <= static``, finite and ``>= 0``.  Leine's law is ``lambda s: 1 / (1 + 3 * s)``
        with ``static = 1``; the Veraszto-Stepan law ``lambda s: 2 + 4 * math.exp(-10 * s) + 0.2 * s``
        with ``static = 6``.
    fall : float, N s/m, optional
        The steepest fall of ``g``, if known in closed form.  By default it is the largest fall
        between neighbours of :data:`FALL_SAMPLE` (times ``speed_scale``), which is exact for a curve
        whose slope is steepest at 0 or between samples less than 2 % apart, and a lower bound
        otherwise: give it where the curve is known.
    speed_scale : float, m/s
        The speeds of the sample (1 by default).

    Raises
    ------
    ValueError
        If ``g(0) > static``, or ``g`` is negative or not finite on the sample.
    """

    def __init__(
        self,
        static: float,
        slip: Callable[[float], float],
        *,
        fall: float | None = None,
        speed_scale: float = 1.0,
    ) -> None:
        self.static = validate.positive("static", static)
        if not callable(slip):
            raise ValueError("slip must be callable: the sliding force (N) as a function of the speed (m/s)")
        self._g = slip
        scale = validate.positive("speed_scale", speed_scale)
        s = FALL_SAMPLE * scale
        values = np.array([self._value(float(x)) for x in s])
        if values[0] > self.static:
            raise ValueError(f"slip: g(0) = {values[0]:.6g} N is above static = {self.static:.6g} N")
        self._limit = float(values[0])
        if fall is None:
            fall = max(0.0, float(np.max(-np.diff(values) / np.diff(s))))
        self._fall = validate.non_negative("fall", fall)

    def _value(self, s: float) -> float:
        try:
            g = float(self._g(s))
        except (ArithmeticError, ValueError, TypeError) as err:
            raise ValueError(f"slip: g({s:.6g}) raised {type(err).__name__}: {err}") from None
        if not math.isfinite(g) or g < 0:
            raise ValueError(f"slip: g({s:.6g}) = {g!r} is not a finite force >= 0")
        return g

    def slip(self, speed: np.ndarray | float) -> np.ndarray | float:
        if np.ndim(speed) == 0:
            return self._value(float(speed))
        return np.array([self._value(float(s)) for s in np.ravel(speed)]).reshape(np.shape(speed))

    @property
    def slip_limit(self) -> float:
        return self._limit

    @property
    def fall(self) -> float:
        return self._fall
