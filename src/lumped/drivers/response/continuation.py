"""Pseudo-arclength continuation of a periodic motion in the forcing frequency, or in another parameter.

The unknowns are ``u = (y, lambda)``, ``lambda`` the parameter followed (the
forcing frequency ``omega`` by default, or a :class:`~lumped.drivers.response.systems.Family`'s: the
force's amplitude, a parameter of the system file), ``y`` the state (``(x, v)`` of one
mass, or the positions then the velocities of a network's masses), in the
units of :class:`~lumped.drivers.response.systems.Scales` (``lambda`` in its
family's unit), and the branch is the curve ``G(u) = Pi(y; lambda) - y = 0``.  From a point with unit tangent
``t`` (the null vector of ``dG/du``: for one mass, 2 x 3, the cross product
of its rows) the predictor steps ``ds`` along ``t``; the corrector is Newton
on ``G = 0`` and ``t . (u - u_pred) = 0``, so a fold (where ``omega`` turns
back) is passed like any other point.  ``dG/dy = M - I`` is the analytic
monodromy and ``dG/domega`` the derivative of the period map in omega
(:func:`~lumped.drivers.response.systems.omega_derivative`: exact, for one
mass and for a network, so that a corrector iterate costs one period map); in another
parameter ``dG/dlambda`` is exact too, and into the parameter's domain on its edge
(:func:`~lumped.drivers.response.systems.exact_derivative`): the family's ``derivative``.

Between two accepted points the branch is tested for
``stops-change`` (the stops per period of the friction elements that move differ: a held element's
permanent stick is no stop), ``fold`` (``det(M - I)``
changes sign: a multiplier crosses +1) and ``period-doubling``
(``det(M + I)`` changes sign: one crosses -1), in that order: where the stops
change the multipliers jump, and a sign change there is not a smooth
bifurcation.  The point of change is located by bisection along the secant
(:data:`BISECTIONS` halvings, each point corrected to :data:`NEWTON_TOL`) and inserted with its ``kind``; a
second change between it and the next point is located the same way, so each change is one row.

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

from lumped.drivers.response.shooting import NEWTON_TOL, Orbit, Scales, check_system, find_orbit
from lumped.drivers.response.systems import Family, LoadedNetwork, omega_family, period_map
from lumped.model.oscillator import Oscillator
from lumped.numerics import validate
from lumped.numerics.arclength import predict, unit_tangent

__all__ = [
    "BISECTIONS",
    "MAX_AMPLITUDE",
    "Branch",
    "ResponsePoint",
    "change",
    "continue_orbits",
    "signature",
]

#: Halvings of the secant that locate a change (to 2^-12 of a step).
BISECTIONS = 12
#: Further changes located within one step after the first (the rest are left to the next step's row).
MAX_CHANGES = 3
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
    """A point of the branch: an :class:`Orbit`, its ``kind`` (``regular``, ``fold``, ``period-doubling``,
    ``stops-change``) and the ``value`` of the parameter followed (omega itself by default)."""

    orbit: Orbit
    kind: str
    value: float


class Branch(NamedTuple):
    """The points of a branch in order, and why it ended: ``"stop"`` (it reached ``stop``), ``"amplitude"``
    (its amplitude passed the bound), ``"turned"`` (it turned back below ``start``), ``"step"`` (the corrector
    failed down to the smallest step) or ``"steps"`` (``50 points`` steps taken)."""

    points: list[ResponsePoint]
    end: str


class _Point(NamedTuple):
    u: np.ndarray  # (state, lambda) scaled
    orbit: Orbit
    jacobian: np.ndarray  # dG/du, d x (d + 1)
    value: float  # lambda

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

    def __init__(self, family: Family) -> None:
        self.family, self.s = family, family.scales

    def value(self, u: np.ndarray) -> float:
        """The parameter's value at ``u``."""
        return float(u[-1] * self.family.unit)

    def orbit_at(self, u: np.ndarray) -> Orbit:
        """The period map from ``u``'s state, of the member at ``u``'s parameter (``ValueError`` for a value the
        system refuses)."""
        z = u[:-1] * np.repeat([self.s.x, self.s.v], u.size // 2)
        system, amplitude, omega = self.family.member(self.value(u))
        return Orbit(omega, z, period_map(system, amplitude, omega, z))

    def point(self, orbit: Orbit, value: float) -> _Point:
        """The point of ``orbit`` (of the member at ``value``) with its Jacobian ``[S^-1 (M - I) S | dPi/dlambda]``."""
        unit = self.family.unit
        u = np.append(self.s.state(orbit.state), value / unit)
        scale = np.repeat([self.s.x, self.s.v], u.size // 2)
        jz = (orbit.period.monodromy - np.eye(scale.size)) * scale[None, :] / scale[:, None]
        jw = self.s.state(self.family.derivative(orbit, value)) * unit
        return _Point(u, orbit, np.column_stack([jz, jw]), value)

    def found(self, u: np.ndarray) -> _Point:
        """The point at ``u``."""
        return self.point(self.orbit_at(u), self.value(u))

    def residual(self, orbit: Orbit) -> np.ndarray:
        return self.s.state(orbit.period.end - orbit.state)

    def own(self, value: float) -> Scales:
        """The :class:`Scales` of the member at ``value``: what its residual and amplitude are measured in (a
        family in the amplitude or a mass spans decades of ``P/k``; the unknowns keep the start's)."""
        system, p, _ = self.family.member(value)
        return Scales.of(system, p)

    def correct(self, guess: np.ndarray, normal: np.ndarray, start: _Point, tol: float = NEWTON_TOL) -> _Point | None:
        """Newton on ``G(u) = 0``, ``normal . (u - guess) = 0`` to ``|G| <= tol``, each iterate with its own
        Jacobian (the held elongations of elements that stick through the period pinned to ``start``'s);
        ``None`` if it does not converge or leaves the values the system takes."""
        u = guess.copy()
        try:
            at = self.found(u)
            for _ in range(MAX_CORRECTOR):
                if not np.all(np.isfinite(at.jacobian)):  # an event met at a tangency: no derivative there
                    return None
                g = self.residual(at.orbit)
                if np.max(np.abs(self.own(at.value).state(at.orbit.period.end - at.orbit.state))) <= tol:
                    return at
                matrix, rhs = at.system(g, u, start.u)
                u = u - np.linalg.solve(np.vstack([matrix, normal]), np.append(rhs, normal @ (u - guess)))
                at = self.found(u)
        except (ValueError, np.linalg.LinAlgError):
            return None
        return None


def _tangent(p: _Point, previous: np.ndarray | None) -> np.ndarray:
    """The unit null vector of the equations' matrix at ``p`` (:func:`~lumped.numerics.arclength.unit_tangent`),
    oriented along ``previous`` (or towards larger values of the parameter)."""
    matrix, _ = p.system(np.zeros(p.u.size - 1), p.u, p.u)
    return unit_tangent(matrix, previous)


def _predict(p: _Point, tangent: np.ndarray, ds: float, back: tuple[np.ndarray, np.ndarray] | None) -> np.ndarray:
    """The predictor ``ds`` along ``tangent`` from ``p`` (:func:`~lumped.numerics.arclength.predict`: Hermite
    through the previous point ``back``, the tangent line where there is none)."""
    return predict(p.u, tangent, ds, back)


def _largest_step(u: np.ndarray, tangent: np.ndarray, d_value: float) -> float:
    """The largest step along ``tangent`` from ``u``: the parameter moves by ``d_value`` at most, the state by
    :data:`STATE_STEP` of ``1 + |(x, v)|`` at most (a large resonant motion is crossed in relative steps)."""
    along_omega = d_value / max(abs(tangent[-1]), 1e-12)
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
    """Bisect the secant ``a -> b`` for the change ``kind``: the point nearest ``a`` found whose
    :func:`signature` differs from ``a``'s (``b`` itself if none), corrected to :data:`NEWTON_TOL`.

    The point at a fraction ``mid`` of the secant is the branch's crossing of the hyperplane through
    ``a + mid (b - a)`` normal to the secant; the corrector starts from where the tangent line of the last point
    found on ``a``'s side crosses that hyperplane, which comes closer at each halving (fewer iterates).  Each
    point tried is corrected to :data:`NEWTON_TOL`, the accuracy of every row, so the located point is on the
    side the bisection put it (a point corrected further after the bisection could cross back)."""
    index = {"stops-change": 0, "fold": 1, "period-doubling": 2}[kind]
    secant = b.u - a.u
    normal = secant / np.linalg.norm(secant)
    lo, hi, best, near, tangent = 0.0, 1.0, b, a, _tangent(a, secant)
    for _ in range(BISECTIONS):
        mid = 0.5 * (lo + hi)
        on_plane = a.u + mid * secant
        guess = near.u + tangent * (normal @ (on_plane - near.u)) / (normal @ tangent)
        p = branch.correct(guess, normal, a)
        if p is None:
            break
        if _signature(p)[index] == _signature(a)[index]:
            lo, near = mid, p
            tangent = _tangent(p, tangent)
        else:
            hi, best = mid, p
    return best


def check_points(points: object) -> int:
    """``points`` as an int >= 2 (a branch's rows: its two ends at least), or a ``ValueError`` naming it."""
    points = validate.positive_int("points", points)
    if points < 2:
        raise ValueError(f"points must be at least 2, got {points}")
    return points


def continue_orbits(
    system: Oscillator | LoadedNetwork,
    amplitude: float,
    start: float,
    stop: float,
    points: int = 200,
    progress: Callable[[int, int], None] | None = None,
    max_amplitude: float = MAX_AMPLITUDE,
    start_orbit: Orbit | None = None,
    family: Family | None = None,
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
    With ``family`` (:func:`~lumped.drivers.response.systems.parameter_family`),
    the parameter followed from ``start`` to ``stop`` is that family's, the same
    way (``system`` and ``amplitude`` are then not used).
    """
    points = check_points(points)
    start, stop = validate.finite("start", start), validate.finite("stop", stop)
    family = family or omega_family(check_system(system), amplitude)
    branch = _Branch(family)
    w0, w1 = start / family.unit, stop / family.unit
    first = branch.point(start_orbit or find_orbit(*family.member(start)), start)
    out, ds_max = [ResponsePoint(first.orbit, "regular", start)], (w1 - w0) / (points - 1)
    p, tangent, end, back = first, _tangent(first, None), "steps", None
    ds = _largest_step(p.u, tangent, ds_max)
    for _ in range(50 * points):
        q = branch.correct(_predict(p, tangent, ds, back), tangent, p)
        if q is None or q.u[-1] > w1 + ds_max or abs(q.u[-1] - p.u[-1]) > 1.5 * ds_max:
            ds *= 0.5
            if ds < MIN_STEP * ds_max:
                end = "step"
                break
            continue
        if q.u[-1] >= w1:  # passed stop: the motion at stop itself, from the secant's guess
            guess = p.u + (q.u - p.u) * (w1 - p.u[-1]) / (q.u[-1] - p.u[-1])
            scale = np.repeat([branch.s.x, branch.s.v], guess.size // 2)
            last = find_orbit(*family.member(stop), guess[:-1] * scale)
            _append(branch, out, p, branch.point(last, stop))
            end = "stop"
            break
        _append(branch, out, p, q)
        back = (p.u, tangent) if p.orbit.stops == q.orbit.stops else None
        p, tangent = q, _tangent(q, tangent)
        ds = min(1.5 * ds, _largest_step(p.u, tangent, ds_max))
        if progress is not None:
            progress(int(1000 * min(max((q.u[-1] - w0) / (w1 - w0), 0.0), 1.0)), 1000)
        if q.orbit.amplitude > max_amplitude * branch.own(q.value).x:
            end = "amplitude"
            break
        if q.u[-1] < w0 - 10 * ds_max:
            end = "turned"
            break
    return Branch(out, end)


def _append(branch: _Branch, out: list[ResponsePoint], a: _Point, b: _Point, depth: int = 0) -> None:
    """Append ``b``, preceded by the located changes between ``a`` and ``b``: the first change from ``a``
    (:func:`_locate`), then those between it and ``b`` the same way (two in one step: a count of stops held
    over a short interval), each once."""
    kind = change(_signature(a), _signature(b))
    if kind is None:
        out.append(ResponsePoint(b.orbit, "regular", b.value))
        return
    at = _locate(branch, a, b, kind)
    out.append(ResponsePoint(at.orbit, kind, at.value))
    if at is not b:
        if depth < MAX_CHANGES:
            _append(branch, out, at, b, depth + 1)
        else:
            out.append(ResponsePoint(b.orbit, "regular", b.value))
