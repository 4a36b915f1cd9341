"""Limit cycles of one mass on a belt by shooting with an unknown period: the fixed point of a return map.

The systems are those of :mod:`lumped.solvers.event_driven_network` with no
load: one mass ``m``, springs of total stiffness ``K > 0`` to points at rest,
linear dashpots (total ``C``), one friction contact (slip curve ``g``, static
force ``static``) on a belt at ``V != 0``.  With ``u = x' - V`` the contact's
rate the motion is autonomous,

    x' = u + V,    m u' = -K x - C u + gamma - T,    T = sgn(u) g(|u|)  (any value in [-static, static] at u = 0),

and steady sliding sits at ``x*`` (the mass at rest, ``u = -V``).

**The section and the return map.**  The section is the line ``x = x*``
crossed upward (``x' = v > 0``), its coordinate the mass's velocity ``v``
(:func:`section_of`); on a belt running backwards (``V < 0``) it is crossed downward (``v < 0``), in the
belt's direction: such a system is computed as its mirror image ``x -> -x``, whose belt runs forwards
(:func:`~lumped.drivers.cycles.equilibria.mirrored`), so that the two directions give mirrored cycles exactly.  The return map ``P(v)`` follows the motion from
``(x*, v)`` by the event-driven method's phases and rule (:class:`March`:
stick, slip, stop, reversal, breakaway) to its next upward crossing; a
limit cycle is a fixed point ``P(v) = v``, its period the return time,
found by Newton's method on ``P(v) - v`` (:func:`find_cycle`).

**The derivative of the map** (:func:`return_map`).  In the plane ``(x, u)``
the flow's Jacobian ``Phi`` maps the field ``f = (x', u')`` at the start to
the field at the end, and ``det Phi`` obeys ``(det Phi)' = div f det Phi``
(the variational equations' trace, Liouville): with the section's normal
component of the field ``x' = v``,

    P'(v0) = (v0 / v1) det Phi,    det Phi = exp(-int (C + g'(|u|)) / m dt) prod_reversals r,

(``v0 / v1`` is the return time's correction: a perturbation ``Phi (0, dv)``
is brought back to the section along the field, by ``dt = -dx / v1``, and in
the basis ``(f, e_v)`` only its ``e_v`` part is left, ``det Phi v0 / v1``),

with the integral over the slip phases (``g'`` the law's
:meth:`~lumped.laws.SlipLaw.slope`, by Gauss-Legendre quadrature on each
step of the phase's dense output), and ``r`` the determinant of each event's
saltation matrix ``S = I + (f+ - f-) n^T / (n . f-)``:

* *reversal* (``u`` through 0, the slip turning from ``s`` to ``-s``, the
  surface ``u = 0``, ``n = (0, 1)``): ``S = diag(1, u'+ / u'-)``, so
  ``r = (H + s g0) / (H - s g0)`` with ``H = -K x + gamma`` the held force and
  ``g0 = g(0+)``: below 1, since a reversal needs ``-s H > static >= g0``;
* *slip to stick* (the stop, ``n = (0, 1)``, ``f+ = (V, 0)``):
  ``S = [[1, 0], [0, 0]]``: rank one, ``det = 0``.  A stuck contact removes
  the direction ``u``: every state reaching the stop leaves it, whatever its
  ``u`` was, along the one line ``u = 0``;
* *stick to slip* (the breakaway, ``H = +-static``, ``n = (-K, -C)``):
  ``S = [[1, 0], [u'+/V, 1 + C u'+/(K V)]]`` on the stick line; after a stop
  it changes nothing more: the stick's motion ``x = x_s + V t`` reaches the
  breakaway point ``x_b`` whatever ``x_s`` was, so a perturbation leaves it
  as a shift in time, along the flow, which the section's return time
  absorbs.

So a cycle with a stick phase has ``P' = 0`` exactly: its nontrivial Floquet
multiplier is 0 (the trivial one, 1, is along the flow) and it is stable, a
superstable cycle that any nearby motion joins at its first stop.  A
cycle without stick has the one nontrivial multiplier ``P'(v)`` (one mass:
the monodromy matrix is 2 x 2, its eigenvalues ``1`` and ``det Phi``).

**Closed forms.**  Where the slip curve is flat (``g = a``, the static/kinetic
belt without a Stribeck velocity or viscous part) and no dashpot damps, a
slip phase is harmonic with its stop in closed form
(:class:`~lumped.solvers.closed_form_belt.HarmonicSlip`), a stick phase is
``x = x_s + V t`` and its breakaway at ``|H| = static`` in closed form: the
cycle of :func:`~lumped.solvers.closed_form_belt.belt_cycle` is met to
round-off.  Otherwise a slip phase is integrated by DOP853 (the event-driven
method's :class:`~lumped.solvers.event_driven_network.ContactSlip`) at
:data:`RTOL`.
"""

from __future__ import annotations

import contextvars
import math
from collections.abc import Iterator
from contextlib import contextmanager
from typing import NamedTuple

import numpy as np

from lumped.drivers.cycles.equilibria import belt_sign, check_autonomous, mirrored, steady_sliding
from lumped.model.network import Network
from lumped.model.system_parameters import system_parameters, with_values
from lumped.numerics import validate
from lumped.numerics.roots import brentq
from lumped.solvers.closed_form_belt import HarmonicSlip
from lumped.solvers.event_driven import _ATOL_FACTOR, _Budget, _Settings
from lumped.solvers.event_driven_network import ContactSlip, March, Model, model
from lumped.solvers.events import OFF, STICK, Phase, Piece

__all__ = [
    "MULTIPLIER_MARGIN",
    "RTOL",
    "Cycle",
    "ReturnsSpent",
    "cycle_derivative_in",
    "find_cycle",
    "mirror_cycle",
    "return_map",
    "returns_budget",
    "section_of",
]

#: DOP853's relative tolerance on the slip phases: 1e-13, as the benchmark of Leine et al. is met to 1e-8
#: with it (tests/test_friction_event_driven.py derives that bound), a little above the least DOP853 takes.
RTOL = 1e-13
#: A return must come within this many natural periods ``2 pi sqrt(m/K)`` (else the motion has left).
RETURN_PERIODS = 1000
#: Round-off of the positions that the one clock of a return may cause, relative to the motion's scale: a return
#: longer than ``sqrt(2 CLOCK_TOL) / (omega eps)`` (6.4e9 s at ``omega`` = 1 rad/s) is refused (:func:`_fly`).
CLOCK_TOL = 1e-12
#: Events and integrator steps a return may take.
MAX_EVENTS, MAX_STEPS = 10_000, 1_000_000
#: Newton iterations before :func:`find_cycle` gives up; halvings of one step that leaves ``v > 0``.
MAX_NEWTON, MAX_HALVINGS = 40, 30
#: A multiplier is labelled stable only below ``1 - MULTIPLIER_MARGIN`` (plus the slope's own error bound):
#: the returns' states err by some 1e-9 of their scale at :data:`RTOL` (the derivation of Leine's test:
#: 80 steps of 2e-13, grown 22 times), and ``log P'`` by that times ``int |g''| dt / m`` over a period,
#: below 1e-7 for a curve that changes its slope by O(1) over O(1) of its speeds; 1e-6 keeps a factor 10.
MULTIPLIER_MARGIN = 1e-6
#: A cycle's swing ``x_max - x_min`` must exceed this fraction of the motion's scale (:func:`_off_rest`): the
#: returns' states err by some 1e-9 of their scale at :data:`RTOL` (:data:`MULTIPLIER_MARGIN`'s derivation).
SWING_TOL = 1e-9
#: Gauss-Legendre nodes and weights on ``[-1, 1]`` for ``int g'(|u|) dt`` on each step of a slip phase: exact
#: for polynomials of degree 15, beyond the order-7 dense output they integrate.
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(8)
#: Samples per step of a slip phase's dense output when its crossings and extremes are bracketed.
_SUBSTEPS = 4


class ReturnsSpent(Exception):
    """A return asked for beyond the budget of :func:`returns_budget`.

    Not a ``ValueError``: the continuation takes a ``ValueError`` from a return for "no cycle from there" and
    tries elsewhere, which would turn a spent budget into more work; this one ends the work it bounds."""


#: The returns left to the innermost :func:`returns_budget` (a one-item list), or ``None``: no bound.
_RETURNS_LEFT: contextvars.ContextVar[list[int] | None] = contextvars.ContextVar("returns_left", default=None)


@contextmanager
def returns_budget(limit: int | None) -> Iterator[None]:
    """Bound the returns (:func:`_fly`, the unit of work of every cycle computation) made inside the block to
    ``limit``: the next one raises :class:`ReturnsSpent`.  A return costs about the same at any parameter (a
    natural period or so of DOP853 at :data:`RTOL`, or closed forms), so the bound is one on the block's time.
    ``None``: no bound inside the block (for work bounded by its own construction), the outer one's count kept."""
    token = _RETURNS_LEFT.set(None if limit is None else [limit])
    try:
        yield
    finally:
        _RETURNS_LEFT.reset(token)


def _spend_return() -> None:
    left = _RETURNS_LEFT.get()
    if left is not None:
        left[0] -= 1
        if left[0] < 0:
            raise ReturnsSpent("the returns allowed are spent")


class Cycle(NamedTuple):
    """A limit cycle: ``period`` (s), ``section`` (its velocity ``v`` at the upward crossing of ``x = x*``,
    m/s), ``x_max``, ``x_min`` (``(masses,)`` m), ``stick_time`` (s per period stuck), ``stick_phases`` (per
    period), ``min_slip_speed`` (smallest ``|u|`` over the slip, m/s; 0 where the contact stops),
    ``multipliers`` (the nontrivial Floquet multipliers, complex), ``max_multiplier`` (their largest modulus)
    and ``stable`` (``max_multiplier`` below 1 by more than its error bound)."""

    period: float
    section: float
    x_max: np.ndarray
    x_min: np.ndarray
    stick_time: float
    stick_phases: int
    min_slip_speed: float
    multipliers: np.ndarray
    max_multiplier: float
    stable: bool


def mirror_cycle(cycle: Cycle) -> Cycle:
    """The cycle of the mirrored system (:func:`~lumped.drivers.cycles.equilibria.mirrored`): its extremes swapped
    and negated, its ``section`` the velocity at the crossing of ``x = x*`` in the mirrored belt's direction
    (downward for a belt at ``V < 0``), negated; period, stick and multipliers the same."""
    return cycle._replace(section=-cycle.section, x_max=-cycle.x_min, x_min=-cycle.x_max)


class _Flight(NamedTuple):
    """One return: ``v_next``, ``derivative`` (``P'``), its error bound, ``time``, and the march's record."""

    v_next: float
    derivative: float
    error: float
    time: float
    march: March


class _System(NamedTuple):
    """What a return needs: the model, the section ``x*``, the contact's law, the flat slip force ``a`` (where
    the closed form runs, else ``None``), the contact's name and the number of elements."""

    mdl: Model
    x_star: float
    law: object
    flat: float | None
    name: str
    n_elements: int


def _system(network: Network) -> _System:
    """The checked system of ``network`` (a one-line ``ValueError`` for any other: the boundary of ``cycles``,
    :func:`~lumped.drivers.cycles.equilibria.check_autonomous`), its section at steady sliding's position."""
    check_autonomous(network)
    mdl = model(network)
    el = network.elements[mdl.contact.link.element]
    law = el.slip_law() or el.one_mass_law()
    pieces = law.pieces()
    flat = None
    if pieces is not None and len(pieces) == 1 and pieces[0].b == 0 and mdl.C == 0:
        flat = pieces[0].a
    x_star = float(steady_sliding(network).position[0])
    return _System(mdl, x_star, law, flat, el.name, len(network.elements))


def section_of(network: Network) -> float:
    """The section's place ``x*`` (m): steady sliding's position; the section is ``x = x*`` crossed with ``v > 0``."""
    return _system(network).x_star


class _SectionMarch(March):
    """:class:`March` whose slip phases are :class:`HarmonicSlip` where the slip curve is flat and undamped."""

    flat: float | None = None

    def slip_motion(self, s: int, p: Piece, start: tuple[float, float, float]) -> ContactSlip | HarmonicSlip:
        if self.flat is None:
            return super().slip_motion(s, p, start)
        mdl = self.mdl
        return HarmonicSlip(mdl.m, mdl.K, (mdl.gamma - s * self.flat) / mdl.K, mdl.V, s, start)


def _march(sys: _System, rtol: float, t_max: float, v: float) -> _SectionMarch:
    mdl = sys.mdl
    x_scale = max(mdl.contact.static / mdl.K, abs(sys.x_star))
    v_scale = max(abs(mdl.V), abs(v), mdl.contact.static / math.sqrt(mdl.K * mdl.m))
    atol = (_ATOL_FACTOR * rtol * x_scale, _ATOL_FACTOR * rtol * v_scale)
    settings = _Settings(None, rtol, atol, _Budget(MAX_STEPS, MAX_STEPS))  # type: ignore[arg-type]
    march = _SectionMarch(mdl, (OFF,), t_max, settings, MAX_EVENTS, (sys.name, "cycles"), sys.n_elements)
    march.flat = sys.flat
    return march


def _fly(sys: _System, v: float, rtol: float = RTOL) -> _Flight:
    """The return from ``(x*, v)`` to the section, with the map's derivative (module docstring).

    The return must come within :data:`RETURN_PERIODS` natural periods of slip; the sticks on the way do not
    count against it.  A stick is closed-form, of any length at no cost, and ends by itself: the held force
    ``-K x + gamma`` moves at ``-K V`` while the mass rides the belt, so it leaves ``[-static, static]`` within
    ``2 static / (K |V|)`` (5e6 s on a belt at 2e-7 m/s: a natural period's count would end the return there).

    But a return's times are carried in one clock from 0, to ``eps t``: a phase starting at ``t0`` evaluates its
    state at ``t - t0``, so its angle ``omega (t - t0)`` errs by ``omega eps t``.  What a cycle reports sits where
    the position is stationary in that angle (the turning points, ``x' = 0``; the stops, where the slip speed is
    0; the breakaways, on a stick whose time is linear), so it errs by ``R (omega eps t)^2 / 2``, ``R`` the slip's
    radius.  Past ``t = sqrt(2 CLOCK_TOL) / (omega eps)`` that passes :data:`CLOCK_TOL` of the motion's scale, and
    the return is refused in one line (a belt slower than about 1.6e-10 m/s for ``examples/belt.toml``).
    """
    _spend_return()
    mdl = sys.mdl
    natural = 2 * math.pi * math.sqrt(mdl.m / mdl.K)
    longest_stick = 2 * mdl.contact.static / (mdl.K * abs(mdl.V))
    clock = math.sqrt(2 * CLOCK_TOL) / (2 * math.pi / natural * float(np.finfo(float).eps))
    slip_left = horizon = RETURN_PERIODS * natural
    march = _march(sys, rtol, slip_left + MAX_EVENTS * longest_stick, v)
    t, x, u, nxt = 0.0, sys.x_star, v - mdl.V, None
    while True:
        nxt = march.mode(t, x, u) if nxt is None else nxt
        if nxt == STICK:
            # it breaks away before t + longest_stick (2: room for round-off); Brent's bracket ends at the horizon
            # where that lies beyond, so that the breakaway's bits do not depend on the stick's bound
            t_next, nxt = march.stick(t, max(horizon, t + 2 * longest_stick), x, OFF)
            x_next, u_next = x + mdl.V * (t_next - t), 0.0
        else:  # a slip in pieces of a natural period, so that no more than one is run past the section
            t_next, x_next, u_next, nxt = march.slip(t, t + min(slip_left, natural), x, u, nxt, OFF)
            slip_left -= t_next - t
        hit = _crossing(march.phases[-1], sys.x_star, mdl.V)
        if (t_next if hit is None else hit[0]) > clock:
            raise ValueError(
                f"v: the return from the section at v = {v:.6g} m/s lasts beyond {clock:.3g} s (a stick on the belt at "
                f"{mdl.V:.3g} m/s lasts up to {longest_stick:.3g} s), where the round-off of its one clock moves the "
                f"positions by more than {CLOCK_TOL:.0e} of their scale: no cycle is vouched for"
            )
        if hit is not None:
            return _landed(sys, march, v, *hit)
        if slip_left <= 0 or (march.phases[-1].kind == "stick" and nxt is None):
            raise ValueError(
                f"v: the motion from the section at v = {v:.6g} m/s does not return to it within "
                f"{RETURN_PERIODS} natural periods of slip; start nearer a cycle"
            )
        t, x, u = t_next, x_next, u_next


def _crossing(ph: Phase, x_star: float, V: float) -> tuple[float, float] | None:
    """``(t, v)`` of the first upward crossing of ``x = x*`` in ``(start, end]`` of the phase, or ``None``.

    A stick crosses at ``x_s + V (t - start) = x*``; a slip where ``x - x*`` changes sign from negative to
    non-negative between two samples of its dense output (:data:`_SUBSTEPS` a step: a crossing and its return
    within one sample, a grazing of the section, is missed), refined by Brent's method.
    """
    if ph.motion is None:
        if V <= 0 or not ph.x_start < x_star <= ph.x_start + V * (ph.end - ph.start):
            return None
        return float(min(ph.end, ph.start + (x_star - ph.x_start) / V)), V
    motion = ph.motion
    times = _grid(motion.steps, ph.end)
    f = motion.state(times)[0] - x_star
    up = np.flatnonzero((f[:-1] < 0) & (f[1:] >= 0))
    if not up.size:
        return None
    i = int(up[0])
    position = lambda t: float(motion.state(t)[0]) - x_star
    t_hit = times[i + 1] if f[i + 1] == 0 else brentq(position, float(times[i]), float(times[i + 1]))
    return float(t_hit), float(motion.state(t_hit)[1]) + V


def _grid(steps: np.ndarray, end: float) -> np.ndarray:
    """The step times up to ``end``, each step cut into :data:`_SUBSTEPS` samples."""
    steps = np.append(steps[steps < end], end)
    if steps.size < 2:
        return steps
    frac = np.arange(_SUBSTEPS) / _SUBSTEPS
    inner = (steps[:-1, None] + np.diff(steps)[:, None] * frac).ravel()
    return np.append(inner, end)


def _landed(sys: _System, march: March, v0: float, t_hit: float, v1: float) -> _Flight:
    """The flight cut at the crossing ``t_hit``, with ``P'`` and its error bound; refused in one line where it
    crosses at rest (``v1 = 0``: the orbit touches the section, and ``P' = v0/v1 ...`` has no value)."""
    if v1 == 0:
        raise ValueError(
            f"v: the motion from the section at v = {v0:.6g} m/s comes back to it at rest (it touches the section): "
            "the return map has no derivative there"
        )
    ph = march.phases[-1]
    march.phases[-1] = Phase(ph.start, t_hit, ph.kind, ph.x_start, ph.motion)
    march.events = [e for e in march.events if e.time < t_hit]
    if any(p.kind == "stick" for p in march.phases):
        return _Flight(v1, 0.0, 0.0, t_hit, march)  # a stop collapses the map (module docstring)
    log, error = 0.0, 0.0
    for p in march.phases:
        dlog, derr = _log_det(sys, p)
        log, error = log + dlog, error + derr
    factor = 1.0
    g0, mdl = sys.mdl.contact.slip_limit, sys.mdl
    ends = {p.end: p for p in march.phases}
    for e in march.events:  # every event here is a reversal, at the end of a slip phase
        p = ends[e.time]
        s, x = p.motion.s, float(p.motion.state(p.end)[0])
        held = mdl.smooth(e.time, x, 0.0, OFF)
        factor *= (held + s * g0) / (held - s * g0)
    return _Flight(v1, v0 / v1 * math.exp(log) * factor, error, t_hit, march)


def _log_det(sys: _System, ph: Phase) -> tuple[float, float]:
    """``-int (C + g'(|u|)) / m dt`` over a slip phase (Gauss-Legendre on each step) and the bound on its error
    from the slope's (:class:`~lumped.laws.Slope`)."""
    mdl, law = sys.mdl, sys.law
    if sys.flat is not None:
        return 0.0, 0.0  # g' = 0 and C = 0: an undamped slip keeps its area
    steps = np.append(ph.motion.steps[ph.motion.steps < ph.end], ph.end)
    a, b = steps[:-1, None], steps[1:, None]
    t = ((a + b) / 2 + (b - a) / 2 * _NODES).ravel()
    w = ((b - a) / 2 * _WEIGHTS).ravel()
    slopes = [law.slope(abs(float(u))) for u in ph.motion.state(t)[1]]
    value = sum(wi * (mdl.C + sl.value) for wi, sl in zip(w, slopes))
    error = sum(wi * sl.error for wi, sl in zip(w, slopes))
    return -value / mdl.m, error / mdl.m


def return_map(network: Network, v: float) -> tuple[float, float, float]:
    """The return map on the section: ``(P(v), P'(v), return time)`` (m/s, 1, s).

    Parameters
    ----------
    network : Network
        One mass on a friction contact on a belt, no load (the module docstring).
    v : float, m/s
        ``> 0``: the velocity at which the motion leaves ``x = x*`` (:func:`section_of`).

    Returns
    -------
    tuple
        The velocity at the next upward crossing, the map's exact derivative there (0 if the contact sticks on
        the way: module docstring) and the time taken.

    Raises
    ------
    ValueError
        One line: a network out of scope, ``v <= 0``, or no return within :data:`RETURN_PERIODS`.
    """
    sign = belt_sign(network) if isinstance(network, Network) else 1  # not a Network: _system refuses it
    if sign < 0:  # the mirror's map, conjugated: P(v) = -P_mirror(-v)
        v_next, derivative, time = return_map(mirrored(network), -_along_belt("v", v, sign))
        return -v_next, derivative, time
    flight = _fly(_system(network), validate.positive("v", v))
    return flight.v_next, flight.derivative, flight.time


def _along_belt(name: str, v: object, sign: int) -> float:
    """``v`` checked to cross the section in the belt's direction, ``sign v > 0`` (finite)."""
    out = validate.finite(name, v)
    if sign < 0 and not out < 0:
        raise ValueError(
            f"{name}: the belt runs at V < 0, so the section is crossed downward: {name} must be < 0, got {out}"
        )
    return out


def find_cycle(network: Network, v0: float, *, tol: float = 1e-12) -> Cycle:
    """The limit cycle through the section near ``v0``: Newton's method on ``P(v) - v``, then its data.

    Parameters
    ----------
    network : Network
        As :func:`return_map`'s.
    v0 : float, m/s
        ``> 0``: the first guess of the cycle's velocity at the section.
    tol : float
        Newton stops when ``|P(v) - v| <= tol max(|V|, v)``; a step that would leave ``v > 0`` or the map's
        domain (a motion that does not return) is halved.

    Raises
    ------
    ValueError
        One line: bad arguments, a neutral map (``P' = 1``: no isolated cycle), no convergence in
        :data:`MAX_NEWTON` steps, or convergence to steady sliding (:func:`_off_steady_sliding`).
    """
    sign = belt_sign(network) if isinstance(network, Network) else 1
    if sign < 0:  # the mirror's cycle, mirrored back (equilibria.mirrored)
        return mirror_cycle(find_cycle(mirrored(network), -_along_belt("v0", v0, sign), tol=tol))
    sys = _system(network)
    v = validate.positive("v0", v0)
    tol = validate.positive("tol", tol)
    flight = _fly(sys, v)
    for _ in range(MAX_NEWTON):
        residual = flight.v_next - v
        if abs(residual) <= tol * max(abs(sys.mdl.V), v):
            _off_steady_sliding(v, flight.derivative, tol * max(abs(sys.mdl.V), v))
            return _off_rest(sys, _cycle(sys, v, flight, tol))
        if flight.derivative == 1:
            raise ValueError(f"v0: the return map is neutral at v = {v:.6g} m/s (P' = 1): no isolated cycle there")
        v, flight = _newton_step(sys, v, -residual / (flight.derivative - 1))
    raise ValueError(f"v0: Newton's method found no cycle from v0 = {v0:.6g} m/s in {MAX_NEWTON} steps")


def _off_steady_sliding(v: float, derivative: float, bound: float) -> None:
    """Refuse a converged ``v`` that Newton's error does not tell from 0, steady sliding itself.

    Steady sliding is a fixed point of the map too, ``P(0) = 0`` (the section's point at rest), and near it
    ``P(v) - v = (P'(0) - 1) v``: within a Hopf point's reach (``P'`` near 1) that is below Newton's stopping
    ``bound`` for every small ``v``.  Newton's iterate is within ``bound / |P'(v) - 1|`` of the root, so a ``v``
    within that of 0 may be steady sliding and is no cycle that can be vouched for (a one-line ``ValueError``).
    Where ``P' = 1`` exactly (a centre: the flat, undamped law's harmonic orbits) every ``v`` is a fixed point,
    exactly, and ``v`` is the orbit's own, not an approximation.
    """
    if derivative != 1 and v <= bound / abs(derivative - 1):
        raise ValueError(
            f"v0: Newton's method came to v = {v:.3g} m/s, within its error of 0 (P' = {derivative:.6g}): steady "
            "sliding, not a cycle"
        )


def _off_rest(sys: _System, cycle: Cycle) -> Cycle:
    """``cycle``, or a one-line ``ValueError`` where its swing ``x_max - x_min`` is within the positions' error
    of 0: a fixed point of the map that is steady sliding seen through the integrator's noise.

    The returns' states err by some :data:`SWING_TOL` of the motion's scale ``max(static/K, |x*|)`` (the
    integrator's absolute tolerance on ``x`` is set on that scale: :func:`_march`; the derivation of
    :data:`MULTIPLIER_MARGIN`), so a swing below that is no motion that can be told from rest: an overdamped
    belt's motion from ``(x*, v)`` creeps back to ``x*`` and "crosses" it by its error (``x_max - x_min`` of
    7e-14 m at ``x* = 2.16`` m, its multiplier 2e-35), which is no cycle.
    """
    mdl = sys.mdl
    scale = max(mdl.contact.static / mdl.K, abs(sys.x_star))
    swing = float(cycle.x_max[0] - cycle.x_min[0])
    if swing <= SWING_TOL * scale:
        raise ValueError(
            f"v0: Newton's method came to a motion of swing {swing:.3g} m, within the positions' error "
            f"({SWING_TOL:.0e} of {scale:.3g} m) of rest: steady sliding, not a cycle"
        )
    return cycle


def _newton_step(sys: _System, v: float, step: float) -> tuple[float, _Flight]:
    """``v + lambda step`` with the largest ``lambda = 2^-j`` that keeps ``v > 0`` and returns to the section."""
    for _ in range(MAX_HALVINGS):
        trial = v + step
        if trial > 0:
            try:
                return trial, _fly(sys, trial)
            except ValueError:
                pass
        step /= 2
    raise ValueError(f"v0: no Newton step from v = {v:.6g} m/s stays on the section (v > 0) and returns to it")


def _cycle(sys: _System, v: float, flight: _Flight, tol: float) -> Cycle:
    """The :class:`Cycle` of a flight converged to ``tol`` (:func:`find_cycle`'s)."""
    phases = flight.march.phases
    stuck = [p for p in phases if p.kind == "stick"]
    stick_phases, stick_time = _stick_runs(phases, 2 * tol * max(abs(sys.mdl.V), v))
    highs, lows = zip(*(_extremes(sys.mdl, p) for p in phases))
    multiplier = flight.derivative
    modulus = abs(multiplier)
    slip_min = 0.0 if stuck or flight.march.events else _min_slip_speed(phases[0])
    return Cycle(
        period=flight.time,
        section=v,
        x_max=np.array([max(highs)]),
        x_min=np.array([min(lows)]),
        stick_time=stick_time,
        stick_phases=stick_phases,
        min_slip_speed=slip_min,
        multipliers=np.array([multiplier], dtype=complex),
        max_multiplier=modulus,
        stable=bool(modulus < 1 - MULTIPLIER_MARGIN - flight.error),
    )


def _stick_runs(phases: list[Phase], negligible: float) -> tuple[int, float]:
    """The stick phases per period, counted around the cycle, and the time stuck (s).

    The period's phases are a loop (the last joins the first at the section).  A slip phase whose slip speed
    stays within ``negligible`` (m/s) is no motion of the cycle but Newton's error: a cycle stuck as it crosses
    the section crosses it at the belt's speed ``V`` exactly and ``P = V`` near it (``P' = 0``), so Newton's
    stop ``|P(v) - v| <= tol max(|V|, v)`` leaves ``v`` within that of ``V``, and the flight from it slips from
    ``u = v - V`` back to ``u = 0`` (a stop, then the stick) without exceeding ``|v - V|`` by more than the
    integrator's absolute tolerance (``1e-3 RTOL`` of the speed scale); :func:`_cycle` takes twice
    Newton's bound.  Such a slip between two stuck phases joins them into one, and its time counts as stuck;
    elsewhere (beside a slip that is a motion) it is left out of both.
    """
    kinds = ["S" if p.kind == "stick" else "n" if _largest_slip_speed(p) <= negligible else "s" for p in phases]
    core = [k for k in kinds if k != "n"]
    if "S" not in core:
        return 0, 0.0
    runs = max(1, sum(k == "S" and core[i - 1] != "S" for i, k in enumerate(core)))
    n = len(kinds)

    def stuck(i: int) -> bool:
        if kinds[i] != "n":
            return kinds[i] == "S"
        ahead = next(kinds[(i + j) % n] for j in range(1, n) if kinds[(i + j) % n] != "n")
        behind = next(kinds[(i - j) % n] for j in range(1, n) if kinds[(i - j) % n] != "n")
        return ahead == behind == "S"

    return runs, float(sum(p.end - p.start for i, p in enumerate(phases) if stuck(i)))


def _largest_slip_speed(ph: Phase) -> float:
    """The largest ``|u|`` (m/s) over a slip phase, on its dense output's samples (:func:`_grid`)."""
    motion = ph.motion
    return float(np.max(np.abs(motion.state(_grid(motion.steps, ph.end))[1])))


def _extremes(mdl: Model, ph: Phase) -> tuple[float, float]:
    """The largest and smallest position over a phase: its ends, and where ``x' = u + V`` vanishes in a slip."""
    if ph.motion is None:
        ends = (ph.x_start, ph.x_start + mdl.V * (ph.end - ph.start))
        return max(ends), min(ends)
    motion = ph.motion
    times = _grid(motion.steps, ph.end)
    x, u = motion.state(times)
    speed = u + mdl.V
    found = [*x[[0, -1]], *x[speed == 0]]  # a sample on a turning point (a fast belt rounds u + V there to 0)
    for i in np.flatnonzero(np.sign(speed[:-1]) * np.sign(speed[1:]) < 0):
        t = brentq(lambda s: float(motion.state(s)[1]) + mdl.V, float(times[i]), float(times[i + 1]))
        found.append(float(motion.state(t)[0]))
    return max(found), min(found)


def _min_slip_speed(ph: Phase) -> float:
    """The smallest ``|u|`` over a slip phase that never stops: the sampled least, refined where ``u'`` changes
    sign beside it."""
    motion = ph.motion
    times = _grid(motion.steps, ph.end)
    u = motion.state(times)[1]
    i = int(np.argmin(np.abs(u)))
    accel = lambda t: float(motion.rhs(t, [float(a) for a in motion.state(t)])[1])
    best = abs(float(u[i]))
    for a, b in ((i - 1, i), (i, i + 1)):
        if 0 <= a and b < times.size and accel(float(times[a])) * accel(float(times[b])) < 0:
            t = brentq(accel, float(times[a]), float(times[b]))
            best = min(best, abs(float(motion.state(t)[1])))
    return best


def cycle_derivative_in(network: Network, v: float, parameter: str) -> float:
    """``dP/dp`` at a fixed ``v`` for a parameter of the system file (``entry.key``), by central differences.

    The section moves with ``p`` (``x*(p)``): ``P(v; p)`` is the map on the section at ``p``.

    Notes
    -----
    ``D(h) = (P(p + h) - P(p - h)) / (2h)`` errs by ``h^2 |P'''| / 6`` and by ``rho |P| / h``, ``rho`` the
    relative error with which ``P`` is computed (its changes with ``p`` are not smooth below it: the
    integrator's steps change).  Taking ``P`` to vary on the scale of ``p`` itself (``|P'''| ~ |P| / p^3``)
    the two balance at ``h = (3 rho)^(1/3) |p|`` (``|p|`` = 1 in the parameter's unit at ``p = 0``, where
    the one-sided three-point formula is used), with an error of ``rho^(2/3)`` relative: ``rho`` is
    ``100 eps`` for the closed-form phases and ``100 RTOL`` for DOP853's (its local errors, not their sum:
    a change of ``p`` moves every step alike), 5e-8 at most.
    """
    sys = _system(network)
    v = validate.positive("v", v)
    (param,) = system_parameters(network, [parameter], "parameter")
    rho = 100 * (float(np.finfo(float).eps) if sys.flat is not None else RTOL)
    p = param.value
    h = (3 * rho) ** (1 / 3) * (abs(p) if p != 0 else 1.0)
    at = lambda value: _fly(_system(with_values(network, [param], [value])), v).v_next
    if p != 0:
        return (at(p + h) - at(p - h)) / (2 * h)
    return (-3 * at(p) + 4 * at(p + h) - at(p + 2 * h)) / (2 * h)
