"""The period map of the forced oscillator and its derivative (the monodromy matrix), from the exact phases.

Under ``P sin(omega t)`` the motion over one forcing period ``T = 2 pi/omega``
from ``(x0, v0)`` is the ``exact`` solution (:func:`lumped.solvers.exact.solve_exact`);
its end state is the *period map* ``Pi(x0, v0)``, and its periodic motions are
the fixed points of ``Pi`` (:mod:`lumped.drivers.response`).  This module gives
``Pi`` with its derivative ``M = dPi/d(x0, v0)``, computed from the same
phases, phase by phase (:func:`period_map`).

Notes
-----
The derivative is carried as ``D = d(t, x, v)/d(x0, v0)`` (3 x 2) at the
start of each phase: an event time moves with the initial state, so it is a
row of ``D``.  At ``t = 0``, ``D = [[0, 0], [1, 0], [0, 1]]``.  Then, phase by
phase (notebook 13 derives each rule):

* **slip** from ``(t_a, z_a)`` with the linear flow ``z' = A z + b(t)``
  (:meth:`~lumped.solvers.closed_form.SlipMotion.flow_matrix`, ``Phi = exp(A
  (t_b - t_a))``): at a fixed end ``t_b`` the end state varies by ``dz_b =
  Phi (dz_a - f(t_a, z_a) dt_a)``, ``f`` the slip phase's vector field.  A
  phase ended by ``v = 0`` (a stop or a reversal) ends at ``t_b`` with
  ``v(t_b) = 0``, so ``dt_b = -dv_b / a_b`` with ``a_b = v'(t_b-)``; then
  ``dx_b`` is unchanged (``v_b = 0``) and ``dv_b = 0``.  The next phase's own
  field in ``f(t_a, z_a) dt_a`` is the saltation of the switch: no separate
  matrix is needed.
* **stick** at ``x_b`` from a stop: ``v = 0`` whatever the initial state, so
  its row of ``D`` is zero (the projection; the stop's time no longer
  matters), and the breakaway at ``t_c`` where ``P sin(omega t_c) - k x_b``
  reaches ``+-tau`` moves by ``dt_c = k dx_b / F'(t_c)``.  A stick at ``t = 0``
  has the same rule: ``v0`` does not enter.
* the end ``t = T`` is fixed: ``M`` is the ``(x, v)`` rows of ``D`` there.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.solvers.events import Phase
from lumped.solvers.exact import ExactSolution, solve_exact

__all__ = ["PeriodMap", "monodromy", "period_map"]


class PeriodMap(NamedTuple):
    """One forcing period of exact motion from ``(x0, v0)`` at ``t = 0``.

    ``end`` is ``(x, v)`` at ``t = T`` (m, m/s); ``monodromy`` its derivative
    with respect to ``(x0, v0)`` (2 x 2); ``solution`` the exact solution over
    ``[0, T]`` (its phases and events).
    """

    end: np.ndarray
    monodromy: np.ndarray
    solution: ExactSolution

    @property
    def stops(self) -> int:
        """Stop events in ``(0, T]``: the stops per period of a periodic motion."""
        return sum(1 for e in self.solution.events if e.kind == "stop" and e.time > 0)

    @property
    def amplitude(self) -> float:
        """Half of ``max x - min x`` over the period (m): ``x`` is monotone within a phase, so its
        extremes are among the phases' starts and the end."""
        xs = [p.x_start for p in self.solution.phases] + [float(self.end[0])]
        return 0.5 * (max(xs) - min(xs))

    @property
    def amplitudes(self) -> np.ndarray:
        """``[amplitude]``: the amplitude of each mass, as for a network."""
        return np.array([self.amplitude])

    @property
    def multipliers(self) -> np.ndarray:
        """The Floquet multipliers: eigenvalues of the monodromy matrix (complex, shape (2,))."""
        return np.linalg.eigvals(self.monodromy)

    @property
    def neutral(self) -> np.ndarray:
        """No neutral direction is set apart for one mass (shape (0, 2); see the network's period map)."""
        return np.zeros((0, 2))

    @property
    def free_basis(self) -> np.ndarray:
        """The whole state space (the identity)."""
        return np.eye(2)


def period_map(osc: Oscillator, amplitude: float, omega: float, x0: float, v0: float) -> PeriodMap:
    """The exact motion over ``T = 2 pi/omega`` under ``amplitude sin(omega t)`` from ``(x0, v0)``, with its derivative.

    Parameters
    ----------
    osc : Oscillator
        Its dashpot a Bingham or Coulomb law (as :func:`~lumped.solvers.exact.solve_exact`).
    amplitude : float, N
        ``P > 0``.
    omega : float, rad/s
        ``omega > 0``.
    x0, v0 : float, m and m/s
        The state at ``t = 0``.
    """
    if not (amplitude > 0 and math.isfinite(amplitude)):
        raise ValueError(f"force_amplitude must be finite and > 0, got {amplitude!r}")
    if not (omega > 0 and math.isfinite(omega)):
        raise ValueError(f"force_omega must be finite and > 0, got {omega!r}")
    force = SwitchedSine(amplitude, omega)
    solution = solve_exact(osc, 2 * math.pi / omega, x0=x0, v0=v0, force=force)
    return PeriodMap(_end_state(solution), monodromy(solution), solution)


def _end_state(solution: ExactSolution) -> np.ndarray:
    """``(x, v)`` at ``t_end`` from the last phase."""
    last = solution.phases[-1]
    if last.motion is None:
        return np.array([last.x_start, 0.0])
    return np.array([float(a) for a in last.motion.state(solution.t_end)])


def monodromy(solution: ExactSolution) -> np.ndarray:
    """``d(x, v)(t_end) / d(x0, v0)`` of an exact solution under a sine that never stops (module Notes)."""
    P, w, ph = solution.force.canonical()
    slope = lambda t: P * w * math.cos(w * t + ph)
    k, t_end = solution.oscillator.stiffness, solution.t_end
    D = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    for phase in solution.phases:
        D = _stick(phase, D, k, slope, t_end) if phase.motion is None else _slip(phase, D, t_end)
    return D[1:]


def _slip(phase: Phase, D: np.ndarray, t_end: float) -> np.ndarray:
    """``D`` at the end of a slip phase from ``D`` at its start (module Notes)."""
    m = phase.motion
    field = np.array([m.v0, m.acceleration(m.t0, m.x0, m.v0)])
    dz = m.flow_matrix(phase.end - phase.start) @ (D[1:] - np.outer(field, D[0]))
    if phase.end >= t_end:  # the fixed end of the period
        return np.vstack([np.zeros(2), dz])
    x_end = float(m.state(phase.end)[0])
    dt = -dz[1] / m.acceleration(phase.end, x_end, 0.0)  # v(t_b) = 0 moves t_b
    return np.vstack([dt, dz[0], np.zeros(2)])


def _stick(phase: Phase, D: np.ndarray, k: float, slope, t_end: float) -> np.ndarray:
    """``D`` at the end of a stick phase: ``x`` held, ``v = 0``, the breakaway moved by ``x`` (module Notes)."""
    dt = np.zeros(2) if phase.end >= t_end else k * D[1] / slope(phase.end)
    return np.vstack([dt, D[1], np.zeros(2)])
