"""Event-driven integration for one mass, a linear spring and any monotone dashpot law.

The motion is the same sequence of phases as in :mod:`lumped.solvers.exact`
(slip, stick, and the events stop, reversal, breakaway, switch, rest),
and the same march (:class:`~lumped.solvers.events.PhaseMarch`) decides
between them; only the slip phases differ.
There is no closed form for a general law, so a slip phase with direction
``s = +-1`` integrates

    m x'' = F(t) - k x - s tau - (F_d(x') - sgn(x') tau),

where ``F_d`` is the law's slip force (``sgn(v)(tau + K|v|^n)`` for the
Herschel-Bulkley law), with the explicit Runge-Kutta method of order 8 of
Dormand and Prince (SciPy's ``DOP853``, done in Python floats by
:mod:`lumped.numerics.dop853`, whose steps are SciPy's to round-off) and its dense
output of order 7.
The static part ``s tau`` is held at the phase's sign, so the right-hand
side is smooth in the phase up to the viscous part, which is continuous
through ``v = 0``.  The stop (``v`` returns to zero) is found on each step's
dense output by Brent's method, to a few ulps of the time, also where ``v``
touches zero inside a step and comes back before its end (a stop shorter than
a step: the dense output's extrema, the roots of a polynomial of degree 6, are
all examined; :meth:`IntegratedSlip._dip`).  Stick phases,
breakaways (in closed form, with ``arcsin``) and the stick test are those
of the exact solver.

The final approach to rest
--------------------------
At a stop the net force ``F - k x`` lies strictly inside the band in the
generic case, so ``m v' = F - k x - s tau`` is nonzero and ``v`` vanishes
linearly: the mass stops in finite time, for every exponent.  What the
exponent changes is how the viscous force behaves as ``v -> 0``.  With
``n > 1`` it vanishes faster than ``v``: the last half-cycles are damped by
the threshold alone (Coulomb-like), each shortens the amplitude by about
``2 tau / k``, and the mass comes to rest after finitely many of them at a
well-defined *rest position*.  With ``n < 1`` small velocities meet a large
viscous force (its slope ``n K |v|^(n-1)`` is unbounded): near the band
edge, ``k|x| - tau = u > 0`` small, the mass can *creep*, inertia
negligible, at ``K v^n = u``, so ``u' = -k (u/K)^(1/n)`` and ``u`` decays
like ``t^(-n/(1-n))``, never reaching 0.  Such a mass approaches the band
edge without stopping, and what is well defined at the end of a run is its
*position at the end*, not a rest position.  The creep is stiff (the
velocity's decay rate ``n K v^(n-1)/m`` grows without bound), so the
explicit integrator's steps shrink with ``v^(1-n)``; the step budget
``max_steps`` bounds the work.

Every loop is bounded: the integrator's steps by ``max_steps`` (over the
whole run), the events by ``max_events``, each root search by Brent's
``maxiter``; a run that would pass a bound stops with a ``ValueError``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from lumped.laws import Dashpot
from lumped.model.forcing import SwitchedSine, as_sine
from lumped.model.oscillator import MAGNITUDE_LIMIT, Oscillator
from lumped.numerics import validate
from lumped.numerics.dop853 import Dop853, Piece, PiecewiseDense, piece_critical_times, piece_spread, piece_value
from lumped.numerics.roots import brentq
from lumped.solvers.events import PhaseMarch, SlipFactory
from lumped.solvers.exact import ExactSolution, check_scales

__all__ = [
    "DEFAULT_RTOL",
    "RTOL_RANGE",
    "IntegratedSlip",
    "IntegratedSolution",
    "solve_event_driven",
    "validate_rtol",
    "viscous_part",
]

#: Relative tolerance of the integrator when none is given.
DEFAULT_RTOL = 1e-10
#: Range of ``rtol`` accepted: DOP853 cannot go below ``100 eps`` (SciPy raises
#: smaller values to it with a warning), and above ``1e-2`` no digit is safe.
RTOL_RANGE = (100 * float(np.finfo(float).eps), 1e-2)
#: Factor between ``rtol`` and the absolute tolerance, relative to the motion's scale.
_ATOL_FACTOR = 1e-3
_SAMPLES = 64  # points of the dense output searched for the first motion from rest
#: Largest displacement (m) or speed (m/s) the energy bound may allow: DOP853's
#: error norms square the scaled state and its derivative.
_LARGEST_STATE = 1e100


def validate_rtol(rtol: object) -> float:
    """Return ``rtol`` as a float in :data:`RTOL_RANGE`, else a one-line ``ValueError``."""
    out = validate.finite("rtol", rtol)
    lo, hi = RTOL_RANGE
    if not lo <= out <= hi:
        raise ValueError(f"rtol must lie in [{lo:.3g}, {hi:.0e}] (DOP853's range), got {out:.6g}")
    return out


@dataclass
class _Budget:
    """Integrator steps left for the whole run (a mutable counter shared by the phases)."""

    left: int
    total: int

    def take(self, t: float) -> None:
        self.left -= 1
        if self.left < 0:
            raise ValueError(
                f"t_end: the event-driven integration needs more than the {self.total} steps a run may take "
                f"(reached at t = {t:.6g} s); raise rtol, shorten t_end or use backward Euler"
            )


def viscous_part(law: Dashpot) -> Callable[[float], float]:
    """``F_d(v) - sgn(v) tau`` (N) as a fast scalar function, continuous through ``v = 0`` (the law's contract, point 7)."""
    return law.viscous_part()


@dataclass(frozen=True)
class _Settings:
    """What every slip phase shares: the law's viscous part, tolerances, the budget."""

    viscous: Callable[[float], float]
    rtol: float
    atol: tuple[float, float]
    budget: _Budget


class IntegratedSlip:
    """One slip phase integrated by DOP853 (:mod:`lumped.numerics.dop853`); the interface of :class:`~lumped.solvers.closed_form.SlipMotion`.

    ``first_stop`` integrates (once) from ``t0`` and returns the first zero of
    ``v - surface`` before ``t_lim`` (inside a step too: :meth:`_dip`), or ``None``; ``state`` then evaluates the
    dense output on ``[t0, end]``.

    The state integrated is the mass's own motion (:meth:`flow`): ``(x, v)`` here, the same relative to a moving
    frame in a subclass (:class:`~lumped.solvers.event_driven_network.ContactSlip`), so the error control acts
    on the motion's own scales; the stop is where the velocity meets ``surface`` (m/s), that of the point the
    contact slides on (``0``: the ground; a belt's, relative to the frame, in the subclass).  The slip rate
    ``v - surface`` is formed only where the slip force is evaluated and where the stop is searched, never
    carried: a belt's large constant part then cannot swamp the mass's velocity, whose digits the integrator
    keeps.
    """

    #: Velocity (m/s) of the point the contact slides on: the stop is ``v = surface``.
    surface: float = 0.0

    def __init__(
        self,
        m: float,
        k: float,
        s_tau: float,
        forcing: tuple[float, float, float],
        start: tuple[float, float, float],
        settings: _Settings,
    ) -> None:
        self.m, self.k, self.s_tau = m, k, s_tau
        self.P, self.w, self.ph = forcing
        self.t0, self.x0, self.v0 = start
        self.settings = settings
        self._dense: PiecewiseDense | None = None

    def rhs(self, t: float, y: Sequence[float]) -> tuple[float, float]:
        """``(x', v')`` of the slip equation (module docstring)."""
        x, v = y
        force = self.P * math.sin(self.w * t + self.ph) if self.P else 0.0
        return v, (force - self.k * x - self.s_tau - self.settings.viscous(v)) / self.m

    def flow(self, t: float, y: Sequence[float]) -> Sequence[float]:
        """``(x', v')`` at the mass's state ``y = (x, v)``: what DOP853 integrates (here :meth:`rhs`)."""
        return self.rhs(t, y)

    def state(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Displacement (m) and velocity (m/s) at times ``t`` in the integrated span."""
        t = np.asarray(t, dtype=float)
        if self._dense is None:
            return np.full_like(t, self.x0), np.full_like(t, self.v0)
        y = self._dense(t)
        return y[0], y[1]

    @property
    def steps(self) -> np.ndarray:
        """The integrator's step times over the phase, ``t0`` first (``[t0]`` before :meth:`first_stop`): the dense
        output is one polynomial between two of them."""
        return self._dense.ts if self._dense is not None else np.array([self.t0])

    def first_stop(self, t_lim: float, direction: int) -> float | None:
        """First time in ``(t0, t_lim]`` at which ``v`` returns to ``surface``, or ``None``."""
        if t_lim <= self.t0:
            return None
        st = self.settings
        solver = Dop853(self.flow, self.t0, (self.x0, self.v0), t_lim, st.rtol, st.atol)
        times: list[float] = [self.t0]
        pieces: list[Piece] = []
        while solver.status == "running":
            st.budget.take(solver.t)
            ok = solver.step()
            if not ok or not all(math.isfinite(y) for y in solver.y):
                why = "the step size fell below the spacing of floats" if not ok else "a value left double precision"
                raise ValueError(
                    f"t_end: the event-driven integration failed at t = {solver.t:.6g} s "
                    f"({why}); shorten t_end or lower x0, v0 or the force"
                )
            times.append(solver.t)
            pieces.append(solver.dense_output())
            stop = self._stop_in(
                pieces[-1], times[-2], times[-1], direction, direction * (solver.y[1] - self.surface) <= 0
            )
            if stop is not None:
                times[-1] = stop
                break
        else:
            stop = None
        if times[-1] == times[-2]:  # no motion in the last step
            times.pop()
            pieces.pop()
        self._dense = PiecewiseDense(times, pieces) if pieces else None
        return stop

    def _stop_in(self, piece: Piece, a: float, b: float, direction: int, ends_stopped: bool) -> float | None:
        """The first zero of ``direction * (v - surface)`` in ``(a, b]`` on one step's dense output, or ``None``.

        ``ends_stopped`` says the step ends with ``direction * (v - surface) <= 0``.  Otherwise the speed may still touch
        zero inside the step and come back (a stop shorter than a step): :meth:`_dip` looks for it.
        """
        if ends_stopped:
            dip = self._dip(piece, a, b, direction, last=b)
            return self._root(piece, a, b if dip is None else dip, direction)
        dip = self._dip(piece, a, b, direction, last=None)
        return None if dip is None else self._root(piece, a, dip, direction)

    def _dip(self, piece: Piece, a: float, b: float, direction: int, last: float | None) -> float | None:
        """The first extremum of the dense output in ``(a, b)`` at which ``g = direction * v <= 0`` and after
        which ``g`` is positive again (``g = direction * (v - surface)``) (at a later extremum or at ``b``); ``None`` if there is none.

        The speed's minimum is where its derivative, the acceleration, changes sign from - to +.  On one step
        the dense output is a polynomial of degree 7 (:mod:`lumped.numerics.dop853`), so its extrema are the
        real roots of a polynomial of degree 6, all found at once (:func:`piece_critical_times`): no extremum
        of what the dense output represents is missed, however many a step holds and however short the dip.
        A dip below what the dense output resolves (its error, of order ``rtol`` times the speed's scale) is
        below the integration's tolerance anyway.  Cheap first: ``g`` stays above ``min(g(a), g(b)) -
        piece_spread`` (:func:`piece_spread`'s bound), so a step whose bound is positive has no dip.  With
        ``last = b`` (the step ends stopped) the dip is returned only if ``g`` comes back above 0 after it,
        so that a single crossing keeps the bracket ``(a, b]``.  A step that starts at rest looks only
        where the motion is under way (:meth:`_under_way`).
        """
        v_a, v_b = piece.y_old[1], piece.y_old[1] + piece.F[1][0]  # theta 0, 1
        ends = direction * (v_a - self.surface), direction * (v_b - self.surface)  # g(a), g(b)
        if last is None and ends[0] > 0 and min(ends) > piece_spread(piece, 1):
            return None
        g = self._rate(piece, direction)
        start = self._under_way(g, a, b)
        if start is None:
            return None
        points = [t for t in piece_critical_times(piece, 1) if t > start]
        first = next((i for i, t in enumerate(points) if g(t) <= 0), None)
        if first is None:
            return None
        if last is not None and all(g(t) <= 0 for t in points[first:]):
            return None  # g stays <= 0 from the first dip to b: one crossing, bracketed by (a, b]
        return points[first]

    @staticmethod
    def _under_way(g: Callable[[float], float], a: float, b: float) -> float | None:
        """``a`` if ``g(a) > 0``; for a step that starts at rest, the first of :data:`_SAMPLES` points where ``g > 0``
        (the motion under way), or ``None``."""
        if g(a) > 0:
            return a
        return next((p for p in (a + (b - a) * i / _SAMPLES for i in range(1, _SAMPLES)) if g(p) > 0), None)

    def _rate(self, piece: Piece, direction: int) -> Callable[[float], float]:
        """``g(t) = direction * (v(t) - surface)`` on one step's dense output: the slip rate in the phase's direction."""
        surface = self.surface
        return lambda t: direction * (piece_value(piece, t, 1) - surface)

    def _root(self, piece: Piece, a: float, b: float, direction: int) -> float:
        """The zero of ``g = direction * (v - surface)`` in ``(a, b]`` on one step's dense output, ``g(b) <= 0``."""
        g = self._rate(piece, direction)
        if g(b) == 0:
            return b
        if not g(a) > 0:  # the step started at rest: find where the motion is under way
            first = self._under_way(g, a, b)
            if first is None:
                return a
            a = first
            if not g(b) < 0:
                return b
        return brentq(g, a, b)


def _integrated(osc: Oscillator, settings: _Settings) -> SlipFactory:
    """The event-driven method's slip phases: :class:`IntegratedSlip`."""
    m, k, tau = osc.mass, osc.stiffness, osc.threshold
    return lambda t, x, v, direction, forcing: IntegratedSlip(m, k, direction * tau, forcing, (t, x, v), settings)


@dataclass(frozen=True, eq=False)
class IntegratedSolution(ExactSolution):
    """The event-driven solution: :class:`~lumped.solvers.exact.ExactSolution`'s phases and events.

    Its slip phases hold the dense output of the integrator instead of a closed
    form; ``sample`` gives a :class:`~lumped.model.trajectory.Trajectory` with
    ``method = "event-driven"``.  Additional attributes: ``rtol``, the
    tolerance asked, ``max_steps``, the step bound, and ``steps``, the number of
    integrator steps taken.
    """

    method: ClassVar[str] = "event-driven"
    rtol: float = DEFAULT_RTOL
    max_steps: int = 1_000_000
    steps: int = 0

    def extended(self, t_end: float) -> IntegratedSolution:
        """The same motion solved to a later ``t_end`` (``self`` if not later)."""
        if t_end <= self.t_end:
            return self
        return solve_event_driven(
            self.oscillator,
            t_end,
            x0=self.x0,
            v0=self.v0,
            force=self.force,
            rtol=self.rtol,
            max_events=self.max_events,
            max_steps=self.max_steps,
        )


def _motion_scale(osc: Oscillator, force: SwitchedSine, t_end: float, x0: float, v0: float) -> tuple[float, float]:
    """Displacement (m) and velocity (m/s) scales: the energy bound on the amplitude, or the band.

    The smaller of the amplitude bound ``|x0| + sqrt(m/k)|v0| + 2 P t_on /
    sqrt(m k)`` and the band ``tau/k`` (when positive): the rest position lies
    in the band, so an absolute tolerance relative to it keeps its digits.
    """
    m, k = osc.mass, osc.stiffness
    P = 0.0 if force.is_zero else abs(force.amplitude)
    t_on = min(t_end, force.until) if P else 0.0
    amplitude = (
        abs(x0) + math.sqrt(m / k) * abs(v0) + 2 * P * t_on / (math.sqrt(m) * math.sqrt(k))
    )  # sqrt(m k) underflows at m = 1e-200
    band = osc.threshold / k
    scale = min(amplitude, band) if band > 0 else amplitude
    scale = scale if scale > 0 else 1.0
    return scale, scale * math.sqrt(k / m)


def _check_sizes(osc: Oscillator, force: SwitchedSine, t_end: float, x0: float, v0: float) -> None:
    """Refuse a run whose state or viscous force could leave what the integrator carries.

    The energy bounds the speed by ``sqrt(k/m)|x0| + |v0| + 2 P t_on / m``;
    that speed and the matching amplitude must stay below ``1e100`` (DOP853's
    norms square them) and the dashpot force there below :data:`MAGNITUDE_LIMIT`.
    """
    m, k = osc.mass, osc.stiffness
    P = 0.0 if force.is_zero else abs(force.amplitude)
    t_on = min(t_end, force.until) if P else 0.0
    parts = {"x0": math.sqrt(k / m) * abs(x0), "v0": abs(v0), "force_amplitude": 2 * P * t_on / m}
    v_max = sum(parts.values())
    if max(v_max, v_max * math.sqrt(m / k)) > _LARGEST_STATE:
        name = max(parts, key=parts.get)  # type: ignore[arg-type]
        raise ValueError(
            f"{name}: the run could reach a speed of {v_max:.3g} m/s (bound from the energy); the "
            f"event-driven integrator carries states up to {_LARGEST_STATE:.0e} only"
        )
    with np.errstate(over="ignore"):
        f = abs(float(osc.dashpot.slip_force(v_max))) if v_max > 0 else 0.0
    if not f <= MAGNITUDE_LIMIT:
        # v_max <= 1e100 here, so a force above 1e300 takes a large coefficient or power of the law
        # (contract point 9 names which); the start that gives the speed is named too.
        law = osc.dashpot.step_bound(0.0, v_max, 1.0).parameter
        start = max(parts, key=parts.get)  # type: ignore[arg-type]
        raise ValueError(
            f"{law}: the dashpot force could reach {f:.3g} N at the speed {v_max:.3g} m/s the energy allows "
            f"(from {start}), above {MAGNITUDE_LIMIT:.0e} N; lower {law}, or {start}"
        )


def _check_steps(osc: Oscillator, force: SwitchedSine, t_end: float, max_steps: int) -> None:
    """Refuse, before any step, a run that surely takes more than ``max_steps`` steps.

    Notes
    -----
    While a sine of amplitude ``P`` above the threshold ``tau`` acts, the mass
    cannot stick through a whole forcing period: held at ``x``, the dashpot
    would carry ``P sin(omega t + phase) - k x``, which spans ``2 P > 2 tau``
    over a period.  Nor can one DOP853 step cover a whole period: its local
    error there is of the order of ``(2 pi)^9 / 9! = 4.5`` times the force's
    scale, above every ``rtol`` accepted (:data:`RTOL_RANGE`, at most 1e-2).
    So the run takes at least one step per whole forcing period while the
    force acts: a lower bound, which refuses only runs that cannot finish.
    """
    if force.is_zero:
        return
    P, omega, _ = force.canonical()
    if not P > osc.threshold:
        return
    periods = math.floor(min(t_end, force.until) * omega / (2 * math.pi))
    if periods > max_steps:
        raise ValueError(
            f"t_end: the event-driven integration would take at least {periods:.3g} steps (one per forcing period "
            f"while the force, above the threshold, acts), more than the {max_steps} a run may take; "
            "shorten t_end or use backward Euler"
        )


def solve_event_driven(
    oscillator: Oscillator,
    t_end: float,
    *,
    x0: float = 0.0,
    v0: float = 0.0,
    force: SwitchedSine | None = None,
    rtol: float = DEFAULT_RTOL,
    max_events: int = 100_000,
    max_steps: int = 1_000_000,
) -> IntegratedSolution:
    """Event-driven solution of the DAE (8) for any monotone dashpot law.

    A shim of the one entry point, kept for what it adds:
    ``lumped.solve(Problem.oscillator(oscillator, t_end, x0=x0, v0=v0,
    force=force), dt, method="event-driven", rtol=rtol)`` samples this
    solution on a grid; called directly it returns the solution in continuous
    time (its events, the motion at any time) and takes ``max_events`` and
    ``max_steps``.

    Parameters
    ----------
    oscillator : Oscillator
        One mass, a linear spring and any :class:`~lumped.laws.Dashpot`.
    t_end : float, s
        Final time ``> 0``.
    x0, v0 : float, m and m/s
        Initial state.
    force : SwitchedSine or None
        ``P sin(omega t + phase)`` until ``t_off``, zero afterwards.
    rtol : float
        Relative tolerance of DOP853, in :data:`RTOL_RANGE`; the absolute
        tolerance is ``1e-3 rtol`` times the scale of :func:`_motion_scale`.
    max_events, max_steps : int
        Bounds on the events and on the integrator's steps over the run.

    Returns
    -------
    IntegratedSolution

    Raises
    ------
    ValueError
        One line beginning with the argument to change: a bad input, a
        forcing that is not a :class:`SwitchedSine`, forces that could
        overflow, or a bound on events or steps that would be passed.
    """
    if not isinstance(oscillator, Oscillator):
        raise ValueError(f"oscillator must be an Oscillator, got {type(oscillator).__name__}")
    if force is not None and as_sine(force) is None:
        raise ValueError("force: the event-driven method needs a SwitchedSine or None")
    t_end = validate.positive("t_end", t_end)
    x0, v0 = validate.finite("x0", x0), validate.finite("v0", v0)
    rtol = validate_rtol(rtol)
    max_events = validate.positive_int("max_events", max_events)
    max_steps = validate.positive_int("max_steps", max_steps)
    force = as_sine(force) or SwitchedSine()
    check_scales(oscillator, force, t_end, x0, v0)
    _check_sizes(oscillator, force, t_end, x0, v0)
    _check_steps(oscillator, force, t_end, max_steps)
    x_scale, v_scale = _motion_scale(oscillator, force, t_end, x0, v0)
    atol = (_ATOL_FACTOR * rtol * x_scale, _ATOL_FACTOR * rtol * v_scale)
    settings = _Settings(viscous_part(oscillator.dashpot), rtol, atol, _Budget(max_steps, max_steps))
    build = PhaseMarch(oscillator, force, t_end, max_events, _integrated(oscillator, settings))
    build.run(x0, v0)
    events = tuple(sorted(build.events, key=lambda e: e.time))
    if not all(math.isfinite(p.x_start) for p in build.phases):
        raise ValueError("t_end: the event-driven solution left double precision; shorten t_end")
    return IntegratedSolution(
        oscillator,
        force,
        t_end,
        tuple(build.phases),
        events,
        *build.rest,
        x0=x0,
        v0=v0,
        max_events=max_events,
        rtol=rtol,
        max_steps=max_steps,
        steps=max_steps - settings.budget.left,
    )
