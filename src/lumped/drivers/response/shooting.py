"""Periodic motions by shooting: the fixed point of the exact period map, found by Newton with the monodromy matrix.

A motion of the forcing's period ``T = 2 pi/omega`` is a fixed point of the
period map ``Pi`` (:func:`lumped.solvers.monodromy.period_map`):
``Pi(z) = z`` with ``z = (x, v)`` at ``t = 0``.  Newton's step solves
``(M - I) dz = -(Pi(z) - z)`` with the analytic monodromy matrix ``M``
(stick phases included: their projection makes ``M`` singular, never
``M - I``).  Its eigenvalues are the Floquet multipliers: the motion is
stable when all lie inside the unit circle.

Lengths are measured in the units of the problem: ``X_s = P/k`` (the static
deflection) for ``x``, ``X_s omega_n`` for ``v``, ``omega_n = sqrt(k/m)`` for
``omega`` (:class:`Scales`); :data:`NEWTON_TOL` is a residual in those units.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from lumped.model.oscillator import Oscillator
from lumped.solvers.monodromy import PeriodMap, period_map

__all__ = ["NEWTON_TOL", "Orbit", "Scales", "find_orbit"]

#: Newton stops when ``|Pi(z) - z|`` (largest component, in :class:`Scales` units) is below this:
#: some 1e5 ulps of unit amplitude, above the period map's own round-off (its event times are
#: refined to a few ulps of the period), far below any amplitude a response curve shows.
NEWTON_TOL = 1e-11
#: Newton iterations before a fixed point is declared not found.
MAX_NEWTON = 40
#: Periods of motion from rest (at most) that bring the first guess near the orbit.
SETTLE_PERIODS = 400


class Scales(NamedTuple):
    """The units of the continuation: ``x`` (m), ``v`` (m/s) and ``omega`` (rad/s)."""

    x: float
    v: float
    omega: float

    @classmethod
    def of(cls, osc: Oscillator, amplitude: float) -> Scales:
        """``X_s = P/k``, ``X_s omega_n`` and ``omega_n = sqrt(k/m)``."""
        wn = math.sqrt(osc.stiffness / osc.mass)
        xs = amplitude / osc.stiffness
        return cls(xs, xs * wn, wn)

    def state(self, z: np.ndarray) -> np.ndarray:
        """``(x, v)`` in these units."""
        return np.asarray(z, dtype=float) / np.array([self.x, self.v])


class Orbit(NamedTuple):
    """A periodic motion: its frequency (rad/s), its state ``(x, v)`` at ``t = 0`` and one period of it."""

    omega: float
    state: np.ndarray
    period: PeriodMap

    @property
    def multipliers(self) -> np.ndarray:
        """The Floquet multipliers: eigenvalues of the monodromy matrix (complex, shape (2,))."""
        return np.linalg.eigvals(self.period.monodromy)

    @property
    def max_multiplier(self) -> float:
        """The largest modulus of a multiplier."""
        return float(np.max(np.abs(self.multipliers)))

    @property
    def stable(self) -> bool:
        """True when every multiplier lies inside the unit circle."""
        return self.max_multiplier < 1.0

    @property
    def amplitude(self) -> float:
        """Half of ``max x - min x`` over the period (m)."""
        return self.period.amplitude

    @property
    def stops(self) -> int:
        """Stops per period."""
        return self.period.stops


def _settle(osc: Oscillator, amplitude: float, omega: float, scales: Scales) -> np.ndarray:
    """The state after up to :data:`SETTLE_PERIODS` periods from rest (until two periods agree to 1e-3)."""
    z = np.zeros(2)
    for _ in range(SETTLE_PERIODS):
        nxt = period_map(osc, amplitude, omega, *z).end
        if np.max(np.abs(scales.state(nxt - z))) < 1e-3:
            return nxt
        z = nxt
    return z


def find_orbit(
    osc: Oscillator, amplitude: float, omega: float, guess: np.ndarray | None = None, tol: float = NEWTON_TOL
) -> Orbit:
    """The periodic motion under ``amplitude sin(omega t)`` near ``guess`` (or the one reached from rest).

    Parameters
    ----------
    osc : Oscillator
        A Bingham or Coulomb dashpot.
    amplitude, omega : float
        ``P`` (N) and ``omega`` (rad/s), both ``> 0``.
    guess : array of shape (2,), optional
        ``(x, v)`` at ``t = 0`` to start Newton from; without it, the state
        after a run from rest (:data:`SETTLE_PERIODS` periods at most).
    tol : float
        :data:`NEWTON_TOL` by default.

    Raises
    ------
    ValueError
        ``force_omega: ...`` when Newton does not converge in :data:`MAX_NEWTON` steps.
    """
    scales = Scales.of(osc, amplitude)
    z = _settle(osc, amplitude, omega, scales) if guess is None else np.asarray(guess, dtype=float)
    for _ in range(MAX_NEWTON):
        pm = period_map(osc, amplitude, omega, *z)
        if np.max(np.abs(scales.state(pm.end - z))) <= tol:
            return Orbit(omega, z, pm)
        z = z - np.linalg.solve(pm.monodromy - np.eye(2), pm.end - z)
    raise ValueError(f"force_omega: Newton found no periodic motion at omega = {omega:.6g} rad/s in {MAX_NEWTON} steps")
