"""Friction with any slip curve, given as a callable (API): :class:`SlipCurve`.

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

The contract is :class:`lumped.laws.contract.SlipLaw`; this module holds
:class:`SlipCurve`, the law of any slip curve given as a callable.  The laws
a system file writes are in their own files (:mod:`lumped.laws.stribeck`);
no solver names any of them.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from lumped.laws.contract import SlipLaw
from lumped.numerics import validate

__all__ = ["SlipCurve", "FALL_SAMPLE"]


#: Speeds at which :class:`SlipCurve` samples a callable for its checks and its steepest fall, as
#: multiples of its speed scale: 0, then 32 per decade from 1e-9 to 1e6.
FALL_SAMPLE = np.concatenate(([0.0], 10.0 ** (np.arange(-9 * 32, 6 * 32 + 1) / 32)))


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
        if isinstance(speed, float) or np.ndim(speed) == 0:  # the first test alone for the integrators' floats
            return self._value(float(speed))
        return np.array([self._value(float(s)) for s in np.ravel(speed)]).reshape(np.shape(speed))

    @property
    def slip_limit(self) -> float:
        return self._limit

    @property
    def fall(self) -> float:
        return self._fall
