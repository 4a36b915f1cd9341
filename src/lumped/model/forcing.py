"""External forcing ``F(t)``.

:class:`SwitchedSine` is ``P sin(omega t + phi)`` for ``t <= t_off`` and ``0``
afterwards, which covers both forcings of the paper, eqs. (17a) and (17b).  Any
other forcing may be passed to the API as a Python callable of time.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lumped.numerics import validate
from lumped.numerics.sine import sin, sin_array

__all__ = ["SwitchedSine", "evaluate", "validate_force"]


@dataclass(frozen=True)
class SwitchedSine:
    """``F(t) = amplitude * sin(omega*t + phase)`` for ``t <= until``, else 0.

    Parameters
    ----------
    amplitude : float, N
    omega : float, rad/s
    phase : float, rad
        Within ``+-MAX_ARGUMENT = 2e8`` (:mod:`lumped.numerics.sine`); a run also
        needs ``|omega| t + |phase|`` in that range (:meth:`check_span`).
    until : float, s
        Time ``t_off >= 0`` after which the force is zero; ``inf`` for never.
    """

    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0
    until: float = math.inf

    def __post_init__(self) -> None:
        for name, check in (
            ("amplitude", validate.finite),
            ("omega", validate.finite),
            ("phase", validate.sine_phase),
            ("until", validate.time_or_inf),
        ):
            object.__setattr__(self, name, check("force_" + name, getattr(self, name)))

    def __call__(self, t: np.ndarray | float) -> np.ndarray | float:
        """The force at the times ``t`` (N), with the kernels' sine (:func:`lumped.numerics.sine.sin_array`), bit for bit."""
        on = self.amplitude * sin_array(self.omega * np.asarray(t, dtype=float) + self.phase)
        out = np.where(np.asarray(t) <= self.until, on, 0.0)
        return float(out) if np.ndim(out) == 0 else out

    def check_span(self, t_last: float) -> None:
        """Refuse a run to ``t_last`` (s) whose argument ``omega t + phase`` leaves the sine's range.

        See :func:`lumped.numerics.validate.sine_argument`, the one bound every method shares.
        """
        validate.sine_argument(self.omega, self.phase, min(t_last, self.until))

    @property
    def is_zero(self) -> bool:
        """True when the force vanishes at all times."""
        return self.amplitude == 0 or (self.omega == 0 and sin(self.phase) == 0)

    def canonical(self) -> tuple[float, float, float]:
        """``(P, omega, phase)`` with ``P >= 0`` and ``omega >= 0``, same function."""
        p, w, ph = self.amplitude, self.omega, self.phase
        if w < 0:  # sin(-|w| t + ph) = sin(|w| t - ph + pi)
            w, ph = -w, math.pi - ph
        if p < 0:
            p, ph = -p, ph + math.pi
        return p, w, math.remainder(ph, 2 * math.pi)


def validate_force(force: object) -> SwitchedSine | Callable[[np.ndarray], np.ndarray] | None:
    """Return ``force`` if it is ``None``, a :class:`SwitchedSine` or a callable."""
    if force is None or isinstance(force, SwitchedSine) or callable(force):
        return force  # type: ignore[return-value]
    raise ValueError(f"force must be a SwitchedSine, a callable of time or None, got {type(force).__name__}")


def _numbers(raw: object, shape: tuple[int, ...]) -> np.ndarray | None:
    """``raw`` as a float array of ``shape`` (a number is broadcast), else ``None``."""
    try:
        values = np.asarray(raw, dtype=float)
    except (TypeError, ValueError, OverflowError):
        return None
    if values.ndim == 0 and isinstance(raw, (numbers.Real, np.ndarray)) and not isinstance(raw, bool):
        return np.full(shape, float(values))
    return values if values.shape == shape and _real_array(raw) else None


def _real_array(raw: object) -> bool:
    """True for a real numeric array (not strings, booleans or objects)."""
    kind = np.asarray(raw).dtype.kind
    return kind in "iuf"


def _at(force: Callable[[float], object], t: float) -> float:
    """``force(t)`` as a float, or a ``ValueError`` that says what went wrong."""
    try:
        raw = force(t)
    except Exception as err:  # a user's callable: report its failure, named
        raise ValueError(f"force raised {type(err).__name__} at t = {t:.6g} s: {err}") from None
    if isinstance(raw, bool) or not isinstance(raw, (numbers.Real, np.ndarray)):
        raise ValueError(f"force must return a real number, got {_short(raw)} at t = {t:.6g} s")
    values = np.asarray(raw)
    if values.size != 1 or values.dtype.kind not in "iuf":
        raise ValueError(f"force must return one real number per time, got {_short(raw)} at t = {t:.6g} s")
    return float(values.reshape(()))


def _short(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def evaluate(force: Callable[[np.ndarray], np.ndarray] | None, t: np.ndarray) -> np.ndarray:
    """Values of a forcing callable on the times ``t`` (zeros for ``None``).

    A callable that accepts an array and returns an array of the same shape
    (or one number, taken as constant) is called once; any other is called
    point by point.  The values must be real and finite.

    Raises
    ------
    ValueError
        Naming ``force``: not callable, an exception inside it, a value that
        is not a real number, or a non-finite value (with the time).
    """
    if force is None:
        return np.zeros_like(t)
    force = validate_force(force)
    try:
        values = _numbers(force(t), t.shape)
    except Exception:  # a scalar-only callable: call it point by point below
        values = None
    if values is None:
        values = np.array([_at(force, float(s)) for s in t])
    bad = ~np.isfinite(values)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"force must return finite values; got {values[i]} at t = {t[i]:.6g} s")
    return values
