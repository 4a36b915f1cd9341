"""Named results: a trajectory on a time grid and the quantities derived from it."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

if TYPE_CHECKING:
    from lumped.model.oscillator import Oscillator

__all__ = ["COLUMNS", "Trajectory", "EnergyBalance", "sign_changes"]

#: Output columns, in order: time (s), displacement (m), velocity (m/s),
#: spring force (N), dashpot force (N), external force (N).
COLUMNS = ("t", "x", "v", "F_s", "F_d", "F")


class EnergyBalance(NamedTuple):
    """Cumulative energies (J) at the saved grid points.

    ``kinetic + potential + dissipated + numerical - external_work`` is
    constant; ``residual`` is that sum minus its value at ``t = 0``.
    ``numerical`` is the energy backward Euler removes by itself,
    ``sum(m dv^2/2 + dF_s^2/(2k))`` (zero for the exact solution).
    """

    kinetic: np.ndarray
    potential: np.ndarray
    dissipated: np.ndarray
    numerical: np.ndarray
    external_work: np.ndarray
    residual: np.ndarray


@dataclass(frozen=True, eq=False)
class Trajectory:
    """Time histories on a grid.

    Attributes
    ----------
    t, x, v, F_s, F_d, F : ndarray, shape (n,)
        See :data:`COLUMNS` for units.
    oscillator : Oscillator
        The system that produced them.
    method : str
        ``"backward-euler"``, ``"exact"``, ...
    dt : float
        Grid step of the computation (s).
    save_every : int
        Stride between the computed grid and the saved points.
    final_rest : (float, float) or None
        Start time (s) and position (m) of the stick interval that lasts to
        the end of the run, found by the method at its full resolution (a
        grid step for backward Euler, the event time for the exact
        solution), ``(nan, nan)`` if the mass moves at the end; ``None``
        derives them from the saved points.
    """

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    F_s: np.ndarray
    F_d: np.ndarray
    F: np.ndarray
    oscillator: Oscillator
    method: str
    dt: float
    save_every: int = 1
    final_rest: tuple[float, float] | None = None

    @classmethod
    def from_array(cls, data: np.ndarray, oscillator: Oscillator, **meta: object) -> Trajectory:
        """Build from an array whose columns are :data:`COLUMNS`."""
        cols = {name: np.ascontiguousarray(data[:, i]) for i, name in enumerate(COLUMNS)}
        return cls(**cols, oscillator=oscillator, **meta)  # type: ignore[arg-type]

    def columns(self) -> dict[str, np.ndarray]:
        """The arrays by column name, in output order."""
        return {name: getattr(self, name) for name in COLUMNS}

    def as_array(self) -> np.ndarray:
        """Array of shape ``(n, 6)`` with columns :data:`COLUMNS`."""
        return np.column_stack([getattr(self, name) for name in COLUMNS])

    @property
    def at_rest(self) -> np.ndarray:
        """Boolean mask of saved points with ``v == 0`` exactly (stick)."""
        return self.v == 0.0

    def stick_intervals(self) -> list[tuple[float, float]]:
        """Maximal runs of saved points with ``v == 0``, as ``(t_first, t_last)``.

        Backward Euler and the exact solution both give ``v == 0`` exactly in
        stick, so no tolerance is involved.
        """
        rest = self.at_rest.astype(np.int8)
        edges = np.diff(np.concatenate(([0], rest, [0])))
        starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1
        return [(float(self.t[a]), float(self.t[b])) for a, b in zip(starts, stops)]

    @property
    def rest_time(self) -> float:
        """Start of the stick interval that lasts to the end of the run (s).

        ``nan`` if the mass is moving at the last point.  Taken from
        ``final_rest`` when the method supplied it, so that it does not
        depend on ``save_every``.
        """
        if self.final_rest is not None:
            return self.final_rest[0]
        runs = self.stick_intervals()
        if not runs or runs[-1][1] != self.t[-1]:
            return math.nan
        return runs[-1][0]

    @property
    def rest_position(self) -> float:
        """Displacement at the final rest (m); ``nan`` if still moving."""
        if self.final_rest is not None:
            return self.final_rest[1]
        return float(self.x[-1]) if self.v[-1] == 0.0 else math.nan

    def energy_balance(self) -> EnergyBalance:
        """Energy bookkeeping on the saved grid.

        For backward Euler on the full grid (``save_every == 1``) the
        discrete identity, obtained by multiplying eq. (13a) by ``v_{n+1}`` and
        eq. (13b) by ``F_s,n+1 / k``, closes to round-off:
        ``dE + dt F_d v + (m dv^2 + dF_s^2/k)/2 = dt F v`` per step.  For other
        methods the integrals use the trapezoidal rule (error ``O(dt^2)``).
        """
        m, k = self.oscillator.mass, self.oscillator.spring.stiffness
        kinetic, potential = 0.5 * m * self.v**2, 0.5 * self.F_s**2 / k
        if self.method == "backward-euler":
            if self.save_every != 1:
                raise ValueError("energy_balance needs save_every == 1 for backward Euler")
            step = np.diff(self.t)
            power_d, power_f = (step * self.F_d[1:] * self.v[1:], step * self.F[1:] * self.v[1:])
            numeric = 0.5 * m * np.diff(self.v) ** 2 + 0.5 * np.diff(self.F_s) ** 2 / k
        else:
            step = np.diff(self.t)
            power_d = step * 0.5 * (self.F_d[1:] * self.v[1:] + self.F_d[:-1] * self.v[:-1])
            power_f = step * 0.5 * (self.F[1:] * self.v[1:] + self.F[:-1] * self.v[:-1])
            numeric = np.zeros_like(power_d)
        cum = [np.concatenate(([0.0], np.cumsum(p))) for p in (power_d, numeric, power_f)]
        total = kinetic + potential + cum[0] + cum[1] - cum[2]
        return EnergyBalance(kinetic, potential, *cum, total - total[0])

    @property
    def dissipated_energy(self) -> float:
        """Energy dissipated in the dashpot over the run (J)."""
        return float(self.energy_balance().dissipated[-1])


def sign_changes(v: np.ndarray) -> int:
    """Changes of direction: sign changes between successive nonzero velocities.

    A velocity exactly ``0`` (a stick step, or a grid point on a reversal) is
    skipped, so ``+, 0, -`` counts one change and ``+, 0, +`` none.
    """
    s = np.sign(v[v != 0])
    return int(np.count_nonzero(s[1:] != s[:-1]))
