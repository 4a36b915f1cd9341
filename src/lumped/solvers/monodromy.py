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

The derivative in the forcing frequency, ``dPi/domega`` (what continuation
in omega needs, :func:`omega_derivative`), follows the same rules for the
column ``d(t, x, v)/domega``, which starts at 0, with two sources: a slip
phase's closed form ``z(t) = p(t) + Phi (z_a - p(t_a))`` moves with omega
through its particular solution ``p`` (by ``dp/domega (t_b) - Phi
dp/domega (t_a)``, :meth:`~lumped.solvers.closed_form.SlipMotion.particular_omega_derivative`),
and a breakaway's ``P sin(omega t_c) - k x_b = +-tau`` moves by
``-P t_c cos(omega t_c)/F'(t_c)``.  The period's end moves too:
``dPi/domega = dz(T)/domega + f(T) dT/domega`` with ``dT/domega = -T/omega``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.solvers.exact import ExactSolution, solve_exact

__all__ = ["RESOLUTION", "PeriodMap", "derivatives", "held_slip", "monodromy", "omega_derivative", "period_map"]

#: The resolution of a periodic motion, in units of the static deflection ``P/k`` of the loaded mass: the
#: residual ``|Pi(z) - z|`` to which shooting solves (:data:`lumped.drivers.response.shooting.NEWTON_TOL` is
#: this value), some 1e5 ulps of unit amplitude, above the map's own round-off.  A motion is known to this
#: much, and a slip over the period shorter than it (:func:`held_slip`) is not resolved: the element is held.
RESOLUTION = 1e-11


def held_slip(amplitude: float, stiffness: float) -> float:
    """The longest slip per period (m) of an element counted as held under ``amplitude sin(omega t)`` on a mass of
    diagonal stiffness ``stiffness``: :data:`RESOLUTION` times ``P/k``."""
    return RESOLUTION * amplitude / stiffness


class PeriodMap(NamedTuple):
    """One forcing period of exact motion from ``(x0, v0)`` at ``t = 0``.

    ``end`` is ``(x, v)`` at ``t = T`` (m, m/s); ``monodromy`` its derivative
    with respect to ``(x0, v0)`` (2 x 2); ``omega_derivative`` its derivative in omega, the period moving
    with it (2,; ``None`` at an undamped resonance: :func:`derivatives`); ``solution`` the exact solution over
    ``[0, T]`` (its phases and events).
    """

    end: np.ndarray
    monodromy: np.ndarray
    omega_derivative: np.ndarray | None
    solution: ExactSolution

    @property
    def stops(self) -> int:
        """Stop events in ``(0, T]``: the stops per period of a periodic motion; none when :attr:`held` (a held
        mass's permanent stick is not a stop)."""
        if self.held:
            return 0
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
    def held(self) -> bool:
        """True when the mass sticks through the whole period, or slips less than :func:`held_slip` over it (a
        slip a fixed point does not resolve): any position in the band is then periodic, a neutral direction
        with the multiplier 1 (as a network's held elements)."""
        phases = self.solution.phases
        ends = [p.x_start for p in phases[1:]] + [float(self.end[0])]
        slip = sum(abs(b - p.x_start) for p, b in zip(phases, ends) if p.motion is not None)
        P, k = self.solution.force.canonical()[0], self.solution.oscillator.stiffness
        return slip <= held_slip(P, k)

    @property
    def multipliers(self) -> np.ndarray:
        """The Floquet multipliers (complex): eigenvalues of the monodromy matrix, but the neutral one of a
        mass held through the period (eigenvalues of ``W^T M W``, :attr:`free_basis`)."""
        w = self.free_basis
        return np.linalg.eigvals(w.T @ self.monodromy @ w)

    @property
    def neutral(self) -> np.ndarray:
        """The held position ``[[1, 0]]`` when :attr:`held`, else no row (shape (0, 2))."""
        return np.array([[1.0, 0.0]]) if self.held else np.zeros((0, 2))

    @property
    def free_basis(self) -> np.ndarray:
        """The states that keep a held position (the velocity, ``[[0], [1]]``), else the identity."""
        return np.array([[0.0], [1.0]]) if self.held else np.eye(2)


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
    return PeriodMap(_end_state(solution), *derivatives(solution), solution)


def _end_state(solution: ExactSolution) -> np.ndarray:
    """``(x, v)`` at ``t_end`` from the last phase."""
    last = solution.phases[-1]
    if last.motion is None:
        return np.array([last.x_start, 0.0])
    return np.array([float(a) for a in last.motion.state(solution.t_end)])


def monodromy(solution: ExactSolution) -> np.ndarray:
    """``d(x, v)(t_end) / d(x0, v0)`` of an exact solution under a sine that never stops (module Notes)."""
    return derivatives(solution)[0]


def omega_derivative(solution: ExactSolution) -> np.ndarray | None:
    """``d(x, v)(T)/domega`` of one forcing period ``T = 2 pi/omega`` of an exact solution under a sine that never
    stops, the period moving with omega (module Notes); ``None`` when a slip phase is at an undamped resonance
    (``c = 0``, ``omega^2 = k/m``), whose particular solution has no derivative of this form."""
    return derivatives(solution)[1]


def derivatives(solution: ExactSolution) -> tuple[np.ndarray, np.ndarray | None]:
    """The monodromy matrix and ``dPi/domega`` of one forcing period (``None`` at an undamped resonance), in one
    pass over the phases: the rows ``dt, dx, dv`` of ``D = d(t, x, v)/d(x0, v0, omega)`` carried by the rules of
    the module Notes (in floats: a continuation evaluates this at every corrector iterate)."""
    P, w, ph = solution.force.canonical()
    k, t_end, phases = solution.oscillator.stiffness, solution.t_end, solution.phases
    dt, dx, dv, resonant = [0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], False
    for i, phase in enumerate(phases):
        if phase.motion is None:  # v = 0 whatever the start; a breakaway moves with x_b and with omega
            dt, dv = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
            if phase.end < t_end:
                cos = math.cos(w * phase.end + ph)
                slope = P * w * cos
                dt = [k * dx[0] / slope, k * dx[1] / slope, (k * dx[2] - P * phase.end * cos) / slope]
            continue
        m = phase.motion
        shift_a, shift_b = m.particular_omega_derivative(phase.start), m.particular_omega_derivative(phase.end)
        resonant = resonant or shift_a is None or shift_b is None
        v_a, a_a = m.v0, m.acceleration(m.t0, m.x0, m.v0)  # the phase's own field: the saltation of its start
        rx, rv = [dx[j] - v_a * dt[j] for j in range(3)], [dv[j] - a_a * dt[j] for j in range(3)]
        if not resonant:  # z(t) = p(t) + Phi (z_a - p(t_a)) moves with omega through p
            rx[2], rv[2] = rx[2] - shift_a[0], rv[2] - shift_a[1]
        (f00, f01), (f10, f11) = m.flow_matrix(phase.end - phase.start).tolist()
        dx, dv = [f00 * rx[j] + f01 * rv[j] for j in range(3)], [f10 * rx[j] + f11 * rv[j] for j in range(3)]
        if not resonant:
            dx[2], dv[2] = dx[2] + shift_b[0], dv[2] + shift_b[1]
        if phase.end >= t_end:  # the fixed end of the period
            break
        accel = m.acceleration(phase.end, phases[i + 1].x_start, 0.0)
        dt, dv = [-dv[j] / accel for j in range(3)], [0.0, 0.0, 0.0]  # v(t_b) = 0 moves t_b
    monodromy = np.array([dx[:2], dv[:2]])
    if resonant:
        return monodromy, None
    last, end = phases[-1], _end_state(solution)
    field = (0.0, 0.0) if last.motion is None else (end[1], last.motion.acceleration(t_end, *end))
    return monodromy, np.array([dx[2] - field[0] * t_end / w, dv[2] - field[1] * t_end / w])  # dT/domega = -T/omega
