"""The derivative of an exact one-mass solution carried through its phases (:mod:`lumped.solvers.sensitivities`).

:class:`Chain` carries ``D = d(t, x, v)/dq`` (3 x 10) from phase to phase for
the canonical parameters ``q = (m, k, tau, c, x0, v0, P, w, ph, t_off)``
(the rules are in :mod:`lumped.solvers.sensitivities`, Notes), keeps each
slip phase's block matrix and start so that the derivative at any time can
be evaluated (:meth:`Chain.sample`), and records each event's derivative and
its distance from a change of the event sequence (its *margin*).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from lumped.model.forcing import SwitchedSine
from lumped.solvers.events import Phase
from lumped.solvers.exact import ExactSolution

__all__ = ["C_", "K_", "M_", "OFF_", "PH_", "P_", "TAU_", "V0_", "W_", "X0_", "Chain", "Load", "N"]

# The canonical parameters: the columns of D.
M_, K_, TAU_, C_, X0_, V0_, P_, W_, PH_, OFF_ = range(10)
N = 10
_V_ZERO = ("stop", "reversal")
#: Times per slip phase above which a uniform grid is marched by one step's exponential.
_MARCH = 2


@dataclass(frozen=True)
class Load:
    """The canonical forcing ``P sin(w t + ph)``, on for ``t < until``, and the signs of the user's ``P`` and ``w``."""

    P: float
    w: float
    ph: float
    until: float
    sign_p: float
    sign_w: float

    @classmethod
    def of(cls, force: SwitchedSine) -> Load:
        P, w, ph = force.canonical()
        return cls(P, w, ph, force.until, -1.0 if force.amplitude < 0 else 1.0, -1.0 if force.omega < 0 else 1.0)

    def on(self, t: float) -> bool:
        """True if the sine acts just after ``t`` (the piece of :meth:`~lumped.solvers.events.EventMarch.piece`)."""
        return t < self.until

    def generators(self, t: float, on: bool) -> np.ndarray:
        """``(sin theta, cos theta)`` at ``t`` for a phase with the force ``on``, else zeros."""
        if not on:
            return np.zeros(2)
        theta = self.w * t + self.ph
        return np.array([math.sin(theta), math.cos(theta)])

    def force(self, t: float, on: bool) -> float:
        """``F(t)`` (N) of a phase with the force ``on``."""
        return self.P * math.sin(self.w * t + self.ph) if on else 0.0

    def gradient(self, t: float) -> tuple[np.ndarray, float]:
        """``dF/dq`` at a fixed ``t`` (10,) and ``dF/dt``, with the force on."""
        s, c = self.generators(t, True)
        grad = np.zeros(N)
        grad[P_], grad[W_], grad[PH_] = s, self.P * t * c, self.P * c
        return grad, self.P * self.w * c


class Chain:
    """The derivative ``D`` carried through the phases of one solution.

    Its columns are independent of one another: only those of ``wanted`` (indices of ``q``) are carried
    through the slip phases' exponentials (the others are left 0 there), so that the block matrix is
    ``5 (len(wanted) + 1)`` square.
    """

    def __init__(self, sol: ExactSolution, wanted: tuple[int, ...] = tuple(range(N))) -> None:
        self.wanted = list(wanted)
        osc = sol.oscillator
        self.m, self.k, self.tau = osc.mass, osc.stiffness, osc.threshold
        self.c = osc.dashpot.bingham_form().viscosity
        self.load, self.t_end = Load.of(sol.force), sol.t_end
        self.ends: dict[float, set[str]] = {}
        for e in sol.events:
            self.ends.setdefault(e.time, set()).add(e.kind)
        #: per phase: ``("slip", B, Y_a)`` or ``("stick", D)``; ``D`` at each phase's start.
        self.pieces: list[tuple] = []
        self.starts: list[np.ndarray] = []
        #: ``(d(t, x)/dq (2 x 10), margin)`` of each event, by ``(time, kind)``.
        self.at_events: dict[tuple[float, str], tuple[np.ndarray, float]] = {}
        D = np.zeros((3, N))
        D[1, X0_], D[2, V0_] = 1.0, 1.0
        for i, phase in enumerate(sol.phases):
            self.starts.append(D)
            if phase.motion is None:
                after = sol.phases[i + 1] if i + 1 < len(sol.phases) else None
                D = self._stick(phase, D, direction(after) if after is not None and after.motion else 0)
            else:
                D = self._slip(phase, D)

    def _matrix(self, s: int, on: bool) -> tuple[np.ndarray, np.ndarray]:
        """``M`` (5 x 5) of a slip phase in direction ``s`` and ``dM/dq`` (10 x 5 x 5)."""
        m, P, w = self.m, self.load.P if on else 0.0, self.load.w if on else 0.0
        M = np.zeros((5, 5))
        M[0, 1] = 1.0
        M[1, :] = np.array([-self.k, -self.c, P, 0.0, -s * self.tau]) / m
        M[2, 3], M[3, 2] = w, -w
        dM = np.zeros((N, 5, 5))
        dM[M_, 1, :] = -M[1, :] / m
        dM[K_, 1, 0], dM[C_, 1, 1], dM[TAU_, 1, 4] = -1 / m, -1 / m, -s / m
        if on:
            dM[P_, 1, 2] = 1 / m
            dM[W_, 2, 3], dM[W_, 3, 2] = 1.0, -1.0
        return M, dM

    def _slip(self, phase: Phase, D: np.ndarray) -> np.ndarray:
        """Record the phase's block matrix and start; return ``D`` after its end."""
        from scipy.linalg import expm  # here: importing the package loads no SciPy solver

        t_a, on, s = phase.start, self.load.on(phase.start), direction(phase)
        x_a, v_a = (float(a) for a in phase.motion.state(t_a))
        M, dM = self._matrix(s, on)
        n = len(self.wanted)
        B = np.kron(np.eye(n + 1), M)  # [[M, 0], [dM/dq, I (x) M]]
        B[5:, :5] = dM[self.wanted].reshape(5 * n, 5)
        y_a = np.array([x_a, v_a, *self.load.generators(t_a, on), 1.0])
        dy = np.zeros((5, N))
        dy[:2] = D[1:]
        if on:  # d(sin, cos)(theta_a)/dq at the moving start, theta_a = w t_a + ph
            dtheta = self.load.w * D[0]
            dtheta[W_] += t_a
            dtheta[PH_] += 1.0
            dy[2], dy[3] = y_a[3] * dtheta, -y_a[2] * dtheta
        u_a = dy - np.outer(M @ y_a, D[0])  # the phase's own field: the saltation of its start
        Y_a = np.concatenate([y_a, u_a[:, self.wanted].T.ravel()])
        self.pieces.append(("slip", B, Y_a))
        if phase.end >= self.t_end:
            return D
        Y_b = expm(B * (phase.end - t_a)) @ Y_a
        x_b, v_b = (float(a) for a in phase.motion.state(phase.end))
        field = M[:2] @ np.array([x_b, v_b, *self.load.generators(phase.end, on), 1.0])
        dz = np.zeros((2, N))
        dz[:, self.wanted] = Y_b[5:].reshape(n, 5)[:, :2].T
        return self._slip_end(phase.end, x_b, on, dz, field)

    def _slip_end(self, t_b: float, x_b: float, on: bool, dz: np.ndarray, field: np.ndarray) -> np.ndarray:
        """``D`` just after a slip phase (with the force ``on`` at its start) ends at ``(t_b, x_b)``, with ``dz``
        (2 x 10) at that fixed time and the field ``(v, a)`` there: at a zero of ``v``, or at the force going off.

        The phase's own force tells the two apart, not the events at ``t_b``: a stop a few ulps of ``t`` after
        the force goes off (a slip just begun, stopped at once) shares ``t_b`` with the switch (the force going off).
        """
        kinds = self.ends.get(t_b, set())
        if not (on and not self.load.on(t_b)):
            dt = -dz[1] / field[1]  # v(t_b) = 0 moves t_b; x gains v_b dt = 0
            out = np.vstack([dt, dz[0], np.zeros(N)])
            kind = next(k for k in _V_ZERO if k in kinds)
            self.at_events[(t_b, kind)] = (out[:2], self._v_zero_margin(kind, t_b, x_b, float(field[1])))
            return out
        dt = np.zeros(N)  # the force goes off at t_b = t_off: the state there gains f(t_b-) dt_b
        dt[OFF_] = 1.0
        out = np.vstack([dt, dz + np.outer(field, dt)])
        self.at_events[(t_b, "switch")] = (out[:2], math.inf)
        return out

    def _v_zero_margin(self, kind: str, t: float, x: float, accel: float) -> float:
        """A zero of ``v``'s distance from the band edge (a stop turning into a reversal) and, for a stop,
        from a zero acceleration, in units of the threshold (of the forces when it is 0)."""
        net = self.load.force(t, self.load.on(t)) - self.k * x
        unit = self.tau if self.tau > 0 else abs(net) + self.k * abs(x) + self.load.P
        if kind == "reversal":
            return (abs(net) - self.tau) / unit if unit > 0 else math.inf
        return min(self.tau - abs(net), self.m * abs(accel)) / unit

    def _stick(self, phase: Phase, D: np.ndarray, s: int) -> np.ndarray:
        """Record the stick; return ``D`` after its end (a breakaway in direction ``s``, or the force going off)."""
        D = np.vstack([D[:2], np.zeros(N)])  # v = 0 whatever the parameters: the projection
        self.pieces.append(("stick", D))
        t_c, kinds = phase.end, self.ends.get(phase.end, set())
        if t_c >= self.t_end or not kinds & {"breakaway", "switch"}:
            return D
        dt, margin, kind = np.zeros(N), math.inf, "switch"
        if "breakaway" in kinds:  # g = F(t_c) - k x - s tau = 0 moves t_c
            grad, slope = self.load.gradient(t_c)
            grad[K_] -= phase.x_start
            grad[TAU_] -= s
            dt = -(grad - self.k * D[1]) / slope
            margin, kind = abs(slope) / (self.load.P * self.load.w), "breakaway"
        else:
            dt[OFF_] = 1.0
        self.at_events[(t_c, kind)] = (np.vstack([dt, D[1]]), margin)
        return np.vstack([dt, D[1], np.zeros(N)])

    def sample(self, sol: ExactSolution, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``dx/dq`` and ``dv/dq`` (n x 10) at the times ``t``, each in the phase that holds there
        (as :meth:`~lumped.solvers.exact.ExactSolution.evaluate` assigns them)."""
        dx, dv = np.zeros((t.size, N)), np.zeros((t.size, N))
        starts = np.array([p.start for p in sol.phases])
        which = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(starts) - 1)
        for i in np.unique(which):
            sel = np.flatnonzero(which == i)
            piece = self.pieces[i]
            if piece[0] == "stick":
                dx[sel] = piece[1][1]
                continue
            u = flow(piece[1], piece[2], t[sel] - starts[i])[:, 5:].reshape(sel.size, len(self.wanted), 5)
            dx[np.ix_(sel, self.wanted)], dv[np.ix_(sel, self.wanted)] = u[:, :, 0], u[:, :, 1]
        return dx, dv


def direction(phase: Phase) -> int:
    """The slip direction ``s`` of a phase: the sign of ``s tau``, or of ``v`` inside it when ``tau = 0``."""
    if phase.motion.s_tau != 0:
        return 1 if phase.motion.s_tau > 0 else -1
    v = float(phase.motion.state(0.5 * (phase.start + phase.end))[1])
    return 1 if v >= 0 else -1


def flow(B: np.ndarray, Y_a: np.ndarray, taus: np.ndarray, expm: Callable | None = None) -> np.ndarray:
    """``expm(B tau) Y_a`` for each ``tau`` (n x len(Y_a)); a uniform grid is marched by one step's exponential.

    Marching adds a rounding of about ``eps`` per step, relative to the state: ``n eps`` at worst over ``n``
    steps, far below what the derivatives are compared with (``tests/test_sensitivities.py``).  ``expm`` is
    SciPy's unless given (the networks' take :func:`lumped.numerics.expm.expm`, as their phases do).
    """
    if expm is None:
        from scipy.linalg import expm

    out = np.empty((taus.size, Y_a.size))
    gaps = np.diff(taus)
    uniform = taus.size > _MARCH and np.ptp(gaps) <= 1e-9 * gaps.mean()
    if not uniform:
        for j, tau in enumerate(taus):
            out[j] = expm(B * tau) @ Y_a
        return out
    step = expm(B * gaps.mean())
    out[0] = expm(B * taus[0]) @ Y_a
    for j in range(1, taus.size):
        out[j] = step @ out[j - 1]
    return out
