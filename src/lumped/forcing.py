"""External forcing ``F(t)``.

:class:`SwitchedSine` is ``P sin(omega t + phi)`` for ``t <= t_off`` and ``0``
afterwards, which covers both forcings of the paper, eqs. (17a) and (17b).  Any
other forcing may be passed to the API as a Python callable of time.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lumped import _validate

__all__ = ["SwitchedSine", "paper_forcing", "evaluate"]


@dataclass(frozen=True)
class SwitchedSine:
    """``F(t) = amplitude * sin(omega*t + phase)`` for ``t <= until``, else 0.

    Parameters
    ----------
    amplitude : float, N
    omega : float, rad/s
    phase : float, rad
    until : float, s
        Time ``t_off >= 0`` after which the force is zero; ``inf`` for never.
    """

    amplitude: float = 0.0
    omega: float = 0.0
    phase: float = 0.0
    until: float = math.inf

    def __post_init__(self) -> None:
        for name, check in (
            ("amplitude", _validate.finite),
            ("omega", _validate.finite),
            ("phase", _validate.finite),
            ("until", _validate.time_or_inf),
        ):
            object.__setattr__(self, name, check("force_" + name, getattr(self, name)))

    def __call__(self, t: np.ndarray | float) -> np.ndarray | float:
        on = self.amplitude * np.sin(self.omega * np.asarray(t) + self.phase)
        out = np.where(np.asarray(t) <= self.until, on, 0.0)
        return float(out) if np.ndim(out) == 0 else out

    @property
    def is_zero(self) -> bool:
        """True when the force vanishes at all times."""
        return self.amplitude == 0 or (self.omega == 0 and math.sin(self.phase) == 0)

    def canonical(self) -> tuple[float, float, float]:
        """``(P, omega, phase)`` with ``P >= 0`` and ``omega >= 0``, same function."""
        p, w, ph = self.amplitude, self.omega, self.phase
        if w < 0:  # sin(-|w| t + ph) = sin(|w| t - ph + pi)
            w, ph = -w, math.pi - ph
        if p < 0:
            p, ph = -p, ph + math.pi
        return p, w, math.remainder(ph, 2 * math.pi)


def paper_forcing(amplitude: float) -> SwitchedSine:
    """Forcing of eq. (17a) (``amplitude = 0.5``) or (17b) (``10``): ``5 pi`` rad/s until 1 s."""
    return SwitchedSine(amplitude=amplitude, omega=5 * math.pi, phase=0.0, until=1.0)


def evaluate(force: Callable[[np.ndarray], np.ndarray] | None, t: np.ndarray) -> np.ndarray:
    """Values of a forcing callable on the time grid ``t`` (zeros for ``None``).

    A callable that accepts arrays is called once; one that works only on
    floats is called point by point.
    """
    if force is None:
        return np.zeros_like(t)
    try:
        values = np.asarray(force(t), dtype=float)
    except Exception:  # a scalar-only callable: fall back to point-wise calls
        values = np.array([float(force(float(s))) for s in t])
    if values.shape != t.shape:
        values = np.array([float(force(float(s))) for s in t])
    if not np.all(np.isfinite(values)):
        raise ValueError("force must return finite values on the time grid")
    return values
