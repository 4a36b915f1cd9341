"""Pseudo-arclength continuation of a periodic motion in the forcing frequency.

The unknowns are ``u = (y, omega)``, ``y`` the state (``(x, v)`` of one
mass, or the positions then the velocities of a network's masses), in the
units of :class:`~lumped.drivers.response.systems.Scales`, and the branch is
the curve ``G(u) = Pi(y; omega) - y = 0``.  From a point with unit tangent
``t`` (the null vector of ``dG/du``: for one mass, 2 x 3, the cross product
of its rows) the predictor steps ``ds`` along ``t``; the corrector is Newton
on ``G = 0`` and ``t . (u - u_pred) = 0``, so a fold (where ``omega`` turns
back) is passed like any other point.  ``dG/dy = M - I`` is the analytic
monodromy; ``dG/domega`` is a central difference of the exact period map
(step :data:`OMEGA_STEP`).

Between two accepted points the branch is tested for
``stops-change`` (the stops per period differ), ``fold`` (``det(M - I)``
changes sign: a multiplier crosses +1) and ``period-doubling``
(``det(M + I)`` changes sign: one crosses -1), in that order: where the stops
change the multipliers jump, and a sign change there is not a smooth
bifurcation.  The point of change is located by bisection along the secant
(:data:`BISECTIONS` halvings) and inserted with its ``kind``.

Notes
-----
A network's friction element that sticks through the whole period
(:attr:`~lumped.solvers.network_monodromy.NetworkPeriodMap.held`) may hold
any elongation within its band: each gives a periodic motion, the monodromy
has the multiplier 1 in that direction, exactly, and the rows of ``G`` along
it vanish.  There the corrector solves ``W^T G = 0`` (``W`` the states that
keep the held elongations, ``free_basis``) with the held elongations pinned
to those of the point it starts from (a slow sweep keeps what sticks where
it is), and the tests for a change use ``W^T M W``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from lumped.drivers.response.shooting import NEWTON_TOL, Orbit, find_orbit
from lumped.drivers.response.systems import LoadedNetwork, Scales, period_map
from lumped.model.oscillator import Oscillator

__all__ = [
    "BISECTIONS",
    "MAX_AMPLITUDE",
    "OMEGA_STEP",
    "Branch",
    "ResponsePoint",
    "change",
    "continue_orbits",
    "signature",
]

#: Step of the central difference ``dPi/domega`` in units of omega_n: its truncation (step^2, 1e-12)
#: and round-off (the map's ~1e-14 over the step, 1e-8) leave the tangent good to 1e-8, which only
#: slows the corrector's last digit, never moves the point (the corrector's ``G = 0`` is exact).
OMEGA_STEP = 1e-6
#: Halvings of the secant that locate a change (to 2^-12 of a step).
BISECTIONS = 12
#: Corrector iterations before a step is halved.
MAX_CORRECTOR = 8
#: Largest relative change of the state ``(x, v)`` in one step (see :func:`_largest_step`).
STATE_STEP = 0.1
#: Largest amplitude (in units of P/k) followed: beyond it the branch is taken to run to infinity
#: (an undamped resonance; Den Hartog's Coulomb oscillator below F/P = pi/4 at omega = omega_n).
MAX_AMPLITUDE = 50.0
#: Smallest step as a fraction of the largest before the continuation gives up.
MIN_STEP = 1e-7


class ResponsePoint(NamedTuple):
    """A point of the branch: an :class:`Orbit` and its ``kind`` (``regular``, ``fold``, ``period-doubling``,
    ``stops-change``)."""

    orbit: Orbit
    kind: str


class Branch(NamedTuple):
    """The points of a branch in order, and why it ended: ``"stop"`` (it reached ``stop``), ``"amplitude"``
    (its amplitude passed the bound), ``"turned"`` (it turned back below ``start``), ``"step"`` (the corrector
    failed down to the smallest step) or ``"steps"`` (``50 points`` steps taken)."""

    points: list[ResponsePoint]
    end: str


class _Point(NamedTuple):
    u: np.ndarray  # (state, omega) scaled
    orbit: Orbit
    jacobian: np.ndarray  # dG/du, d x (d + 1)

    def system(self, g: np.ndarray, u: np.ndarray, pin: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The equations of the corrector at this point, their matrix and residual: ``G`` itself, or with
        elements held through the period (module Notes) ``W^T G`` and the held elongations pinned to ``pin``'s."""
        neutral = self.orbit.period.neutral
        if not neutral.shape[0]:
            return self.jacobian, g
        w = self.orbit.period.free_basis
        matrix = np.vstack([w.T @ self.jacobian, np.hstack([neutral, np.zeros((neutral.shape[0], 1))])])
        return matrix, np.append(w.T @ g, neutral @ (u[:-1] - pin[:-1]))


class _Branch:
    """The problem in scaled unknowns: residual, Jacobian and the corrector."""

    def __init__(self, system: Oscillator | LoadedNetwork, amplitude: float) -> None:
        self.system, self.amplitude, self.s = system, amplitude, Scales.of(system, amplitude)

    def orbit_at(self, u: np.ndarray) -> Orbit:
        z, omega = u[:-1] * np.repeat([self.s.x, self.s.v], u.size // 2), u[-1] * self.s.omega
        return Orbit(omega, z, period_map(self.system, self.amplitude, omega, z))

    def point(self, orbit: Orbit) -> _Point:
        """The point of ``orbit`` with its Jacobian ``[S^-1 (M - I) S | dPi/domega]``."""
        u = np.append(self.s.state(orbit.state), orbit.omega / self.s.omega)
        scale = np.repeat([self.s.x, self.s.v], u.size // 2)
        jz = (orbit.period.monodromy - np.eye(scale.size)) * scale[None, :] / scale[:, None]
        step = np.eye(u.size)[-1]
        ends = [self.orbit_at(u + d * step).period.end for d in (OMEGA_STEP, -OMEGA_STEP)]
        jw = self.s.state(ends[0] - ends[1]) / (2 * OMEGA_STEP)
        return _Point(u, orbit, np.column_stack([jz, jw]))

    def residual(self, orbit: Orbit) -> np.ndarray:
        return self.s.state(orbit.period.end - orbit.state)

    def correct(self, guess: np.ndarray, normal: np.ndarray, start: _Point) -> _Point | None:
        """Newton on ``G(u) = 0``, ``normal . (u - guess) = 0`` from the Jacobian of ``start`` (whose held
        elongations stay pinned); ``None`` if it does not converge."""
        u, at = guess.copy(), start
        if not u[-1] > 0:
            return None
        orbit = self.orbit_at(u)
        for _ in range(MAX_CORRECTOR):
            g = self.residual(orbit)
            if np.max(np.abs(g)) <= NEWTON_TOL:
                return at if at.orbit is orbit else self.point(orbit)
            matrix, rhs = at.system(g, u, start.u)
            try:
                u = u - np.linalg.solve(np.vstack([matrix, normal]), np.append(rhs, normal @ (u - guess)))
            except np.linalg.LinAlgError:
                return None
            if not u[-1] > 0:
                return None
            at = self.point(self.orbit_at(u))
            orbit = at.orbit
        return None


def _tangent(p: _Point, previous: np.ndarray | None) -> np.ndarray:
    """The unit null vector of the equations' matrix at ``p`` (the cross product of the rows of the 2 x 3
    Jacobian of one mass, else the last right singular vector), oriented along ``previous`` (or towards
    larger omega)."""
    matrix, _ = p.system(np.zeros(p.u.size - 1), p.u, p.u)
    if matrix.shape == (2, 3):
        t = np.cross(matrix[0], matrix[1])
    else:
        t = np.linalg.svd(matrix)[2][-1]
    t /= np.linalg.norm(t)
    ref = t[-1] if previous is None else t @ previous
    return -t if ref < 0 else t


def _largest_step(u: np.ndarray, tangent: np.ndarray, d_omega: float) -> float:
    """The largest step along ``tangent`` from ``u``: omega moves by ``d_omega`` at most, the state by
    :data:`STATE_STEP` of ``1 + |(x, v)|`` at most (a large resonant motion is crossed in relative steps)."""
    along_omega = d_omega / max(abs(tangent[-1]), 1e-12)
    along_state = STATE_STEP * (1 + np.linalg.norm(u[:-1])) / max(np.linalg.norm(tangent[:-1]), 1e-12)
    return min(along_omega, along_state)


def signature(monodromy: np.ndarray, stops: int) -> tuple[int, float, float]:
    """``(stops, sign det(M - I), sign det(M + I))`` of a point with monodromy matrix ``M``: what :func:`change`
    compares between neighbours."""
    eye = np.eye(monodromy.shape[0])
    return stops, np.sign(np.linalg.det(monodromy - eye)), np.sign(np.linalg.det(monodromy + eye))


def change(a: tuple[int, float, float], b: tuple[int, float, float]) -> str | None:
    """The kind of change between two neighbours' :func:`signature` s, or ``None``: ``stops-change`` first
    (where the stops change the multipliers jump), then ``fold`` (a multiplier crossed +1), then
    ``period-doubling`` (one crossed -1)."""
    for kind, i in (("stops-change", 0), ("fold", 1), ("period-doubling", 2)):
        if a[i] != b[i]:
            return kind
    return None


def _signature(p: _Point) -> tuple[int, float, float]:
    """The :func:`signature` of ``p``, without the neutral directions of held elements (``W^T M W``)."""
    period = p.orbit.period
    m = period.monodromy
    if period.neutral.shape[0]:
        m = period.free_basis.T @ m @ period.free_basis
    return signature(m, p.orbit.stops)


def _locate(branch: _Branch, a: _Point, b: _Point, kind: str) -> _Point:
    """Bisect the secant ``a -> b`` for the change ``kind``; the corrected point on ``b``'s side of it."""
    index = {"stops-change": 0, "fold": 1, "period-doubling": 2}[kind]
    secant = b.u - a.u
    normal = secant / np.linalg.norm(secant)
    lo, hi, best = 0.0, 1.0, b
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        p = branch.correct(a.u + mid * secant, normal, a)
        if p is None:
            break
        if _signature(p)[index] == _signature(a)[index]:
            lo = mid
        else:
            hi, best = mid, p
    return best


def continue_orbits(
    system: Oscillator | LoadedNetwork,
    amplitude: float,
    start: float,
    stop: float,
    points: int = 200,
    progress: Callable[[int, int], None] | None = None,
    max_amplitude: float = MAX_AMPLITUDE,
    start_orbit: Orbit | None = None,
) -> Branch:
    """The branch of periodic motions from ``omega = start`` to ``stop`` (rad/s), in order along it.

    The first point is ``start_orbit`` if given (at ``start``), else the motion
    at ``start`` reached from rest (then Newton);
    the last is at ``stop`` exactly when the branch gets there.  A step moves
    omega by ``(stop - start)/(points - 1)`` at most and the state by
    :data:`STATE_STEP` of its size at most, so a branch monotone in omega
    has at least ``points`` points, more where it bends or grows fast.
    ``progress(done, 1000)`` reports how far omega has come.  The branch ends
    early (``Branch.end`` says why) where its amplitude passes ``max_amplitude``
    (in units of ``P/k``: an undamped resonance), where it turns back below
    ``start``, or where the step falls below :data:`MIN_STEP` of the largest.
    """
    branch = _Branch(system, amplitude)
    w0, w1 = start / branch.s.omega, stop / branch.s.omega
    first = branch.point(start_orbit or find_orbit(system, amplitude, start))
    out, ds_max = [ResponsePoint(first.orbit, "regular")], (w1 - w0) / (points - 1)
    p, tangent, end = first, _tangent(first, None), "steps"
    ds = _largest_step(p.u, tangent, ds_max)
    for _ in range(50 * points):
        q = branch.correct(p.u + ds * tangent, tangent, p)
        if q is None or q.u[-1] > w1 + ds_max or abs(q.u[-1] - p.u[-1]) > 1.5 * ds_max:
            ds *= 0.5
            if ds < MIN_STEP * ds_max:
                end = "step"
                break
            continue
        if q.u[-1] >= w1:  # passed stop: the motion at stop itself, from the secant's guess
            guess = p.u + (q.u - p.u) * (w1 - p.u[-1]) / (q.u[-1] - p.u[-1])
            scale = np.repeat([branch.s.x, branch.s.v], guess.size // 2)
            last = find_orbit(system, amplitude, stop, guess[:-1] * scale)
            _append(branch, out, p, branch.point(last))
            end = "stop"
            break
        _append(branch, out, p, q)
        p, tangent = q, _tangent(q, tangent)
        ds = min(1.5 * ds, _largest_step(p.u, tangent, ds_max))
        if progress is not None:
            progress(int(1000 * min(max((q.u[-1] - w0) / (w1 - w0), 0.0), 1.0)), 1000)
        if q.orbit.amplitude > max_amplitude * branch.s.x:
            end = "amplitude"
            break
        if q.u[-1] < w0 - 10 * ds_max:
            end = "turned"
            break
    return Branch(out, end)


def _append(branch: _Branch, out: list[ResponsePoint], a: _Point, b: _Point) -> None:
    """Append ``b``, preceded by the located change between ``a`` and ``b`` if there is one."""
    kind = change(_signature(a), _signature(b))
    if kind is not None:
        at = _locate(branch, a, b, kind)
        if at is not b:
            out.append(ResponsePoint(at.orbit, kind))
        else:
            out.append(ResponsePoint(b.orbit, kind))
            return
    out.append(ResponsePoint(b.orbit, "regular"))
