"""The ``event-driven`` method for one mass on a friction contact of any slip curve, on the ground or on a belt.

The system is one mass ``m`` with linear springs and linear dashpots, each
to the ground or to a driven point moving at a constant velocity, and one
friction contact (any :class:`lumped.laws.SlipLaw`, or a Bingham or Coulomb
element, whose graph is one) to the ground or to such a point, moving at
``V``, under a sine or a constant load from ``t = 0``.  With ``u = v - V``
(the contact's slip rate, seen from the mass) the equation of motion is

    x' = u + V,    m u' = S(t, x, u) - T,    S = F(t) - K x + A t - C u + gamma,

with ``K``, ``C`` the sums of the stiffnesses and viscosities, ``A = sum
k_i V_i`` and ``gamma = sum c_i (V_i - V)`` (``V_i`` the velocity of the
element's other point), and ``T`` the contact's force on the mass,
resisting the slip: ``T = sgn(u) g(|u|)`` off zero rate, any value in
``[-static, static]`` at ``u = 0``.  The motion is a sequence of phases:

* **stick** (``u = 0``, ``x = x_s + V (t - t_s)``): ``T = S(t, x, 0)``, a sine
  plus a linear function of ``t`` (of slope ``beta = A - K V``), which holds while ``|T| <= static``.  The
  *breakaway* (``|S|`` reaches ``static``) is found between the critical
  points of ``S`` (in closed form), on each of which ``S`` is monotone, by
  Brent's method: no sign change is missed, whatever the length of the stick;
* **slip** with direction ``s = +-1``: ``m u' = S - s g(max(s u, 0))``
  integrated by DOP853 (:class:`lumped.solvers.event_driven.IntegratedSlip`,
  the integrator of the one-mass method) on the mass's motion relative to the
  springs' rest point moving at ``W = A / K``, ``(y, w) = (x - W t, v - W)``
  (:class:`ContactSlip`: never on ``u``, whose constant part ``-V`` a fast belt
  makes huge against the motion, nor on ``x`` when springs pull it along); the clipped
  speed keeps the right-hand side continuous where the step passes the stop,
  whose time is found on the step's dense output by Brent's method (also a
  touch of ``u = 0`` shorter than a step, between two ends of one sign).  At the
  stop the rule of :class:`lumped.laws.step_graph.SlipGraph` decides: the
  contact sticks if the holding force ``S`` lies within ``[-static,
  static]``, else it slips the other way (a *reversal*).

The load's switch-off ends a phase too (a *switch*).  Every event is a
:class:`~lumped.solvers.events.Event` naming the contact, with the mass's
position and the mode after it (the contact's ``0`` or ``+-1`` in its own orientation).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple

import numpy as np

from lumped.laws import sticks
from lumped.model.forcing import as_sine, kind_of, one_force
from lumped.model.network import Network, listed
from lumped.model.trajectory import Trajectory
from lumped.numerics import validate
from lumped.numerics.roots import brentq
from lumped.solvers.event_driven import (
    _ATOL_FACTOR,
    DEFAULT_RTOL,
    IntegratedSlip,
    _Budget,
    _Settings,
    validate_rtol,
)
from lumped.solvers.events import OFF, STICK, Event, Phase, Piece
from lumped.solvers.network_modes import grid_index

__all__ = ["TAKES", "March", "classify", "model", "refusal", "solve_contact", "solve_event_driven_network"]

METHOD = "event-driven"
#: What it runs, in words (the refusals, ``--help``).
TAKES = (
    "one mass, one friction contact of any slip curve, linear springs and linear dashpots (each to the ground "
    "or to a driven point at a constant velocity) under a sine or a constant load from t = 0"
)
#: Bounds of a run: events, and integrator steps over the whole run.
MAX_EVENTS, MAX_STEPS = 100_000, 1_000_000


class Link(NamedTuple):
    """An element seen from the mass: its index, ``k`` or ``c``, the velocity ``V_i`` of its other point (m/s)
    and its orientation (``+1`` if the mass is its ``second`` point: its elongation is ``x - V_i t``; ``-1``)."""

    element: int
    coefficient: float
    velocity: float
    orientation: float


@dataclass(frozen=True)
class Contact:
    """The friction contact: its element (:class:`Link`, coefficient unused), ``static`` (N), its slip curve
    ``g`` (N, of the speed ``> 0``) and ``g(0+)``."""

    link: Link
    static: float
    g: Callable[[float], float]
    slip_limit: float

    def slip_force(self, s: int, u: float) -> float:
        """``s g(max(s u, 0))``: the sliding force of a phase of direction ``s``, continuous through its stop."""
        speed = s * u
        return s * (self.g(speed) if speed > 0 else self.slip_limit)


@dataclass(frozen=True)
class Model:
    """The equation of motion (module docstring): ``m``, ``K``, ``C``, ``A``, ``beta = A - K V``, ``gamma``,
    the contact, its other point's velocity ``V``, and the elements as :class:`Link` s."""

    m: float
    K: float
    C: float
    A: float
    beta: float
    gamma: float
    contact: Contact
    V: float
    springs: tuple[Link, ...]
    dashpots: tuple[Link, ...]

    def smooth(self, t: float, x: float, u: float, p: Piece) -> float:
        """``S(t, x, u)`` (N): every force on the mass but the contact's, with the load's piece ``p``."""
        force = p.amplitude * math.sin(p.omega * t + p.phase) if p.amplitude else 0.0
        return force - self.K * x + self.A * t - self.C * u + self.gamma

    def framed(self, t: float, y: float, w: float, p: Piece) -> float:
        """``S`` (N) from the state relative to the springs' frame (:attr:`frame`, moving at ``W``): the position
        ``y = x - W t`` and the velocity ``w = v - W``: ``F(t) - K y + (A - K W) t - C w + sum c_i (V_i - W)``.

        It equals :meth:`smooth` at ``x = y + W t``, ``u = w + W - V``, without forming either: on a fast belt
        ``u``'s constant part ``-V`` would cancel in ``-C u + gamma``, and with springs to fast points ``-K x``
        would cancel against ``A t`` (``A - K W`` is zero for springs to one point, round-off otherwise)."""
        force = p.amplitude * math.sin(p.omega * t + p.phase) if p.amplitude else 0.0
        W = self.frame
        return force - self.K * y + (self.A - self.K * W) * t - self.C * w + self.dashpot_push

    @cached_property
    def frame(self) -> float:
        """``W = A / K`` (m/s): the velocity of the springs' rest point ``A t / K``, about which the mass moves
        (``0`` without springs, when no force depends on ``x``)."""
        return self.A / self.K if self.K > 0 else 0.0

    @cached_property
    def dashpot_push(self) -> float:
        """``sum c_i (V_i - W)`` (N): the dashpots' force on the mass moving with the frame."""
        return sum(d.coefficient * (d.velocity - self.frame) for d in self.dashpots)

    def held(self, t: float, start: float, x_start: float, p: Piece) -> float:
        """``S`` on the contact stuck since ``start`` at ``x_start``: the force it holds (N)."""
        return self.smooth(t, x_start + self.V * (t - start), 0.0, p)


def classify(network: Network) -> tuple[list[Link], list[Link], list[Contact], int | None]:
    """Springs, dashpots and friction contacts of a one-mass network as :class:`Link` s and :class:`Contact` s, and
    the index of the first element that is none of them (``None`` if there is none; the lists stop there)."""
    mass = network.masses[0].name
    speeds = {d.name: d.constant_velocity for d in network.drivers}
    springs, dashpots, contacts = [], [], []
    for e, el in enumerate(network.elements):
        other = el.between[0] if el.between[1] == mass else el.between[1]
        link = Link(e, 0.0, speeds.get(other, 0.0), 1.0 if el.between[1] == mass else -1.0)
        law, dashpot = el.slip_law(), el.one_mass_law()
        form = dashpot.bingham_form() if dashpot is not None else None
        if el.linear_stiffness is not None:
            springs.append(link._replace(coefficient=el.linear_stiffness))
        elif law is not None:
            g = lambda s, law=law: float(law.slip(s))
            contacts.append(Contact(link, law.static, g, law.slip_limit))
        elif form is not None and form.threshold == 0:
            dashpots.append(link._replace(coefficient=form.viscosity))
        elif form is not None:  # the Bingham graph: a contact with g(s) = tau + c s
            tau, c = form.threshold, form.viscosity
            contacts.append(Contact(link, tau, lambda s, tau=tau, c=c: tau + c * s, tau))
        else:
            return springs, dashpots, contacts, e
    return springs, dashpots, contacts, None


def refusal(network: Network) -> str | None:
    """Why the method cannot run ``network`` (one line naming the method and what blocks it), or ``None``."""
    if len(network.masses) != 1:
        return f"method {METHOD!r} needs a one-mass system; the network has {len(network.masses)} masses"
    for d in network.drivers:
        if d.constant_velocity is None:
            return f"method {METHOD!r} runs driven points at a constant velocity; driver {d.name!r} has {kind_of(d.velocity)}"
    *_, contacts, bad = classify(network)
    if bad is not None:
        el = network.elements[bad]
        return f"method {METHOD!r} cannot run element {el.name!r} of kind {el.kind!r}: its networks are {TAKES}"
    if len(contacts) != 1:
        names = [network.elements[c.link.element].name for c in contacts]
        found = f"it has {len(contacts)}" + (f" ({listed(names)})" if names else "")
        return f"method {METHOD!r} runs one mass with exactly one friction contact; {found}"
    force = one_force([load.force for load in network.loads])
    if force is not None and as_sine(force) is None:
        return f"method {METHOD!r} cannot run the load on {network.masses[0].name!r}, {kind_of(force)}: its networks are {TAKES}"
    return None


def model(network: Network) -> Model:
    """The :class:`Model` of a network that :func:`refusal` accepts."""
    springs, dashpots, (contact,), _ = classify(network)
    V = contact.link.velocity
    K, C = sum(s.coefficient for s in springs), sum(d.coefficient for d in dashpots)
    A = sum(s.coefficient * s.velocity for s in springs)
    gamma = sum(d.coefficient * (d.velocity - V) for d in dashpots)
    m = network.masses[0].mass
    return Model(m, K, C, A, A - K * V, gamma, contact, V, tuple(springs), tuple(dashpots))


class ContactSlip(IntegratedSlip):
    """A slip phase of direction ``s`` from ``start = (t, x, u)``: :class:`IntegratedSlip` with this system's
    right-hand side, its stop the zero of ``u = v - V``.

    DOP853 integrates the mass's own motion (:meth:`flow`) relative to the springs' rest point moving at ``W``
    (:attr:`Model.frame`, ``0`` for springs to the ground): ``y = x - W t`` and ``w = v - W``, never ``u = v - V``
    or ``x``.  With a belt fast against the mass, ``u`` is ``-V`` plus the motion, and carrying it would put the
    error control on the belt's scale (``rtol |V|``, not the mass's velocity) and lose the motion's digits in
    ``x' = u + V``; with springs to fast points, ``x`` and ``v`` grow as ``W t`` and ``W``, and errors ``rtol |x|``,
    ``rtol |v|`` would swamp the springs' elongations.  The stop is ``w = V - W`` (:attr:`surface`).
    :meth:`state` and :meth:`rhs` keep the interface in ``(x, u)``; :meth:`mass_state` gives ``(x, v)``.
    """

    def __init__(
        self,
        mdl: Model,
        s: int,
        p: Piece,
        start: tuple[float, float, float],
        settings: _Settings,
        velocity: float | None = None,
    ):
        t0, x0, u0 = start
        v0 = u0 + mdl.V if velocity is None else velocity  # the mass's velocity, if known, with all its digits
        W = mdl.frame
        start_ = (t0, x0 - W * t0, v0 - W)
        super().__init__(mdl.m, mdl.K, s * mdl.contact.static, (p.amplitude, p.omega, p.phase), start_, settings)
        self.model, self.s, self.piece, self.surface = mdl, s, p, mdl.V - W

    def flow(self, t: float, y: list[float]) -> tuple[float, float]:
        """``(y', w')`` at ``(y, w)``: ``w`` and ``(S - s g(max(s u, 0)))/m``, ``u = w - surface`` (:meth:`Model.framed`)."""
        y_, w = y
        mdl = self.model
        return w, (mdl.framed(t, y_, w, self.piece) - mdl.contact.slip_force(self.s, w - self.surface)) / mdl.m

    def rhs(self, t: float, y: list[float]) -> tuple[float, float]:
        """``(x', u')``: ``u + V`` and ``(S - s g(max(s u, 0)))/m`` (:meth:`flow` in the contact's rate)."""
        x, u = y
        mdl = self.model
        return u + mdl.V, self.flow(t, [x - mdl.frame * t, u + self.surface])[1]

    def state(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Displacement (m) and slip rate ``u = v - V = w - surface`` (m/s) at times ``t`` in the integrated span."""
        y, w = super().state(t)
        return y + self.model.frame * np.asarray(t, dtype=float), w - self.surface

    def mass_state(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Displacement ``x = y + W t`` (m) and velocity ``v`` (m/s) at times ``t``, from the integrated state."""
        y, w = super().state(t)
        W = self.model.frame
        return y + W * np.asarray(t, dtype=float), w + W


def breakaway(mdl: Model, t0: float, t_lim: float, x0: float, p: Piece) -> tuple[float, int]:
    """First time in ``[t0, t_lim]`` at which the holding force of a stick from ``(t0, x0)`` leaves ``[-static, static]``
    and its sign, or ``(t_lim, 0)``.

    ``S = P sin(w t + ph) + beta t + c0`` is monotone between its critical points,
    where ``P w cos(w t + ph) = -beta``; the first knot outside the band brackets the crossing.
    """
    P, w, ph, band = p.amplitude, p.omega, p.phase, mdl.contact.static
    knots = [t0, t_lim]
    if P * w > abs(mdl.beta):
        theta = math.acos(-mdl.beta / (P * w))
        lo, hi = math.floor((w * t0 + ph - theta) / (2 * math.pi)), math.ceil((w * t_lim + ph + theta) / (2 * math.pi))
        turns = 2 * math.pi * np.arange(lo, hi + 1)
        crit = (np.concatenate((turns + theta, turns - theta)) - ph) / w
        knots = [t0, *np.sort(crit[(crit > t0) & (crit < t_lim)]).tolist(), t_lim]
    held = lambda t: mdl.held(t, t0, x0, p)
    values = np.array([held(t) for t in knots])
    out = np.flatnonzero(np.abs(values[1:]) > band)
    if not out.size:
        return t_lim, 0
    i = int(out[0]) + 1
    sign = 1 if values[i] > 0 else -1
    edge = lambda t: held(t) - sign * band
    if sign * edge(knots[i - 1]) > 0:  # already beyond the band (round-off at a stop): break away at once
        return knots[i - 1], sign
    return brentq(edge, knots[i - 1], knots[i]), sign


@dataclass
class March:
    """The march from phase to phase (the module docstring's rule), recording phases and events."""

    mdl: Model
    pieces: tuple[Piece, ...]
    t_end: float
    settings: _Settings
    max_events: int
    names: tuple[str, str]  # the contact's name, the method's
    n_elements: int

    def __post_init__(self) -> None:
        self.phases: list[Phase] = []
        self.events: list[Event] = []
        self._carried: tuple[tuple[float, float, float], float] | None = None  # a slip's end (t, x, u) and its v

    def state(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The mass's position (m) and velocity (m/s) at the times ``t`` (in ``[0, t_end]``)."""
        t = np.asarray(t, dtype=float)
        x, v, _, _ = _sample(self, t)
        return x, v

    def piece(self, t: float) -> Piece:
        return next(p for p in self.pieces if t < p.end)

    def event(self, t: float, kind: str, x: float, mode: int) -> None:
        link = self.mdl.contact.link
        modes = [0] * self.n_elements
        modes[link.element] = int(mode * link.orientation)
        self.events.append(Event(t, kind, (x,), (self.names[0],) if kind != "switch" else (), tuple(modes)))
        if len(self.events) > self.max_events:
            raise ValueError(
                f"t_end: more than the {self.max_events} events a run may have before t_end = {self.t_end:g} s; "
                "shorten t_end or use backward Euler"
            )

    def mode(self, t: float, x: float, u: float) -> int:
        """STICK or the slip direction at ``(t, x, u)``: the sign of ``u``, else the stick test on ``S``."""
        if u != 0:
            return 1 if u > 0 else -1
        net = self.mdl.smooth(t, x, 0.0, self.piece(t))
        if sticks(net, -self.mdl.contact.static, self.mdl.contact.static):
            return STICK
        return 1 if net > 0 else -1

    def run(self, x: float, u: float, velocity: float | None = None) -> None:
        """March from ``(x, u)`` at ``t = 0`` to ``t_end``; ``velocity``, the mass's ``v`` if given, starts a slip
        with its digits (``u + V`` loses them to a fast belt's)."""
        t, nxt, stalled = 0.0, None, 0
        self._carried = None if velocity is None else ((0.0, x, u), velocity)
        while t < self.t_end:
            p = self.piece(t)
            t_lim = min(p.end, self.t_end)
            nxt = self.mode(t, x, u) if nxt is None else nxt
            t_before = t
            if nxt == STICK:
                t, nxt = self.stick(t, t_lim, x, p)
                x = x + self.mdl.V * (t - t_before)
            else:
                t, x, u, nxt = self.slip(t, t_lim, x, u, nxt, p)
            if t < self.t_end and t == p.end:  # the load goes off: the mode after it, from the state
                nxt = self.mode(t, x, u) if nxt is None else nxt
                self.event(t, "switch", x, nxt)
            stalled = stalled + 1 if t == t_before else 0
            if stalled > 8:
                raise ValueError(
                    f"x0: the {METHOD} method makes no progress at t = {t!r} s: the contact's holding force stays "
                    "on the edge of its static bound to round-off; perturb x0 or the load"
                )

    def stick(self, t: float, t_lim: float, x: float, p: Piece) -> tuple[float, int | None]:
        t_b, direction = breakaway(self.mdl, t, t_lim, x, p)
        self.phases.append(Phase(t, t_b, "stick", x))
        if direction:
            self.event(t_b, "breakaway", x + self.mdl.V * (t_b - t), direction)
        return t_b, direction or None

    def slip_motion(self, s: int, p: Piece, start: tuple[float, float, float]) -> ContactSlip:
        """The slip phase of direction ``s`` from ``start = (t, x, u)``: DOP853 (:class:`ContactSlip`).  A
        subclass may return a closed form with the same interface (``first_stop``, ``state``, ``rhs``, ``s``).

        A start where the last slip ended without a stop (the load's switch-off) takes that slip's ``v`` itself:
        ``u + V`` would lose the mass's velocity to the belt's digits."""
        carried = self._carried
        v = carried[1] if carried is not None and carried[0] == start else None
        return ContactSlip(self.mdl, s, p, start, self.settings, velocity=v)

    def slip(
        self, t: float, t_lim: float, x: float, u: float, s: int, p: Piece
    ) -> tuple[float, float, float, int | None]:
        motion = self.slip_motion(s, p, (t, x, u))
        t_stop = motion.first_stop(t_lim, s)
        if t_stop is None:
            x_end, v_end = (float(a) for a in _mass_state(motion, np.array(t_lim), self.mdl.V))
            u_end = v_end - self.mdl.V
            self._carried = ((t_lim, x_end, u_end), v_end)
            self.phases.append(Phase(t, t_lim, "slip", x, motion))
            return t_lim, x_end, u_end, None
        x_stop = float(motion.state(t_stop)[0])
        self.phases.append(Phase(t, t_stop, "slip", x, motion))
        net = self.mdl.smooth(t_stop, x_stop, 0.0, p)
        reverses = -s * net > self.mdl.contact.static
        self.event(t_stop, "reversal" if reverses else "stop", x_stop, -s if reverses else 0)
        return t_stop, x_stop, 0.0, -s if reverses else STICK


def _forcing(network: Network) -> tuple[Piece, ...]:
    """The load as pieces: ``P sin(w t + ph)`` (canonical) until ``t_off``, then nothing."""
    sine = as_sine(one_force([load.force for load in network.loads]))
    if sine is None or sine.is_zero:
        return (OFF,)
    on = Piece(*sine.canonical(), sine.until)
    return (on, OFF) if math.isfinite(sine.until) else (on,)


def _scales(mdl: Model, pieces: tuple[Piece, ...], t_end: float, x0: float, v0: float) -> tuple[float, float]:
    """Displacement (m) and velocity (m/s) scales of the mass's motion, for the absolute tolerance: the band of
    the forces ``static + P`` over the stiffness (velocities: over ``sqrt(k m)``), or without a spring the
    motion those forces give over ``t_end``; at least the initial state.

    The belt's speed is not a scale of the mass's motion: a mass that never reaches it (pure slip on a fast
    belt) moves on the forces' scale, and one that rides it has ``|v| = |V|``, which the relative tolerance
    ``rtol |v|`` already covers.  An absolute tolerance of the belt's size would let the error control ignore the
    motion of a mass slower than the belt (issue 41: ``x = 0`` at every saved time on a belt at 1e12 m/s)."""
    force = mdl.contact.static + max(p.amplitude for p in pieces)
    if mdl.K > 0:
        x, v = force / mdl.K, force / math.sqrt(mdl.K * mdl.m)
    else:
        v = force * t_end / mdl.m
        x = v * t_end
    return max(x, abs(x0)), max(v, abs(v0))


def _options(options: dict[str, object]) -> tuple[float, int, int]:
    """``rtol``, ``max_events`` and ``max_steps`` from ``options``, checked; any other refused in one line."""
    known = {"rtol", "max_events", "max_steps"}
    for name in options:
        if name not in known:
            raise ValueError(f"{name}: method {METHOD!r} takes no option {name!r} (its options are rtol)")
    rtol = validate_rtol(options.get("rtol", DEFAULT_RTOL))
    max_events = validate.positive_int("max_events", options.get("max_events", MAX_EVENTS))
    max_steps = validate.positive_int("max_steps", options.get("max_steps", MAX_STEPS))
    return rtol, max_events, max_steps


def solve_event_driven_network(
    network: Network, t_end: float, dt: float, *, save_every: int = 1, **options: object
) -> Trajectory:
    """The motion of one mass on a friction contact (the module docstring), sampled on ``t_n = n*dt``.

    Parameters
    ----------
    network : Network
        One mass, one friction contact, linear springs and dashpots (:data:`TAKES`).
    t_end, dt : float, s
        The span and the grid step (the phases and events do not depend on ``dt``).
    save_every : int
        Stride between the grid and the saved points.
    **options
        ``rtol`` (DOP853's relative tolerance, :data:`~lumped.solvers.event_driven.RTOL_RANGE`),
        ``max_events`` and ``max_steps`` (bounds on the run).

    Raises
    ------
    ValueError
        One line: a bad argument (named), a network the method does not run
        (:func:`refusal`), or a bound on events or steps that would be passed.
    """
    if not isinstance(network, Network):
        raise ValueError(f"network must be a Network, got {type(network).__name__}")  # noqa: TRY004 (the API's one error type)
    if (reason := refusal(network)) is not None:
        raise ValueError(reason)
    rtol, max_events, max_steps = _options(options)
    index, dt, save_every = grid_index(t_end, dt, save_every)
    march = _march(network, float(index[-1] * dt), rtol, max_events, max_steps)
    return _trajectory(network, march, index, dt, save_every)


def solve_contact(network: Network, t_end: float, **options: object) -> March:
    """The motion to ``t_end`` in continuous time: its phases, its events and :meth:`March.state` at any time.

    Takes what :func:`solve_event_driven_network` takes but the grid, and raises as it does.
    """
    if not isinstance(network, Network):
        raise ValueError(f"network must be a Network, got {type(network).__name__}")  # noqa: TRY004 (the API's one error type)
    if (reason := refusal(network)) is not None:
        raise ValueError(reason)
    rtol, max_events, max_steps = _options(options)
    return _march(network, validate.positive("t_end", t_end), rtol, max_events, max_steps)


def _march(network: Network, t_end: float, rtol: float, max_events: int, max_steps: int) -> March:
    """The :class:`March` of an accepted network from its initial state to ``t_end``."""
    network.check_span(t_end)
    mdl, pieces = model(network), _forcing(network)
    mass = network.masses[0]
    x0, u0 = mass.x0, mass.v0 - mdl.V
    x_scale, v_scale = _scales(mdl, pieces, t_end, x0, mass.v0)
    atol = (_ATOL_FACTOR * rtol * x_scale, _ATOL_FACTOR * rtol * v_scale)
    settings = _Settings(None, rtol, atol, _Budget(max_steps, max_steps))  # type: ignore[arg-type]
    name = network.elements[mdl.contact.link.element].name
    march = March(mdl, pieces, t_end, settings, max_events, (name, METHOD), len(network.elements))
    march.run(x0, u0, mass.v0)
    return march


def _sample(march: March, times: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """``x``, ``v``, the contact's force on the mass ``T`` and the stick flags at ``times``."""
    mdl, phases = march.mdl, march.phases
    which = np.searchsorted([ph.start for ph in phases], times, side="right") - 1
    x, v, T = (np.empty(times.size) for _ in range(3))
    stuck = np.zeros(times.size, dtype=bool)
    for i, ph in enumerate(phases):
        at = np.flatnonzero(which == i)
        if not at.size:
            continue
        if ph.motion is None:
            x[at], v[at], stuck[at] = ph.x_start + mdl.V * (times[at] - ph.start), mdl.V, True
            T[at] = [mdl.held(float(t), ph.start, ph.x_start, march.piece(float(t))) for t in times[at]]
            continue
        x[at], v[at] = _mass_state(ph.motion, times[at], mdl.V)
        T[at] = [mdl.contact.slip_force(ph.motion.s, float(w) - mdl.V) for w in v[at]]
    return x, v, T, stuck


def _mass_state(motion: ContactSlip, times: np.ndarray, V: float) -> tuple[np.ndarray, np.ndarray]:
    """A slip phase's ``(x, v)`` at ``times``: its :meth:`~ContactSlip.mass_state`, or ``u + V`` from a closed form
    (a subclass's motion, :meth:`March.slip_motion`) that has only ``state``."""
    if hasattr(motion, "mass_state"):
        return motion.mass_state(times)
    x, u = motion.state(times)
    return x, u + V


def _trajectory(network: Network, march: March, index: np.ndarray, dt: float, save_every: int) -> Trajectory:
    """The :class:`Trajectory`: positions, velocities, every element's tension, the events and the rest."""
    mdl, times = march.mdl, index * dt
    x, v, T, stuck = _sample(march, times)
    forces = np.zeros((times.size, len(network.elements)))
    for s in mdl.springs:
        forces[:, s.element] = s.coefficient * s.orientation * (x - s.velocity * times)
    for d in mdl.dashpots:
        forces[:, d.element] = d.coefficient * d.orientation * (v - d.velocity)
    link = mdl.contact.link
    forces[:, link.element] = link.orientation * T
    rest = _final_rest(march, float(x[-1]))
    rigid = np.zeros_like(forces, dtype=bool)
    rigid[:, link.element] = stuck
    rigid[0] = False
    states = np.zeros_like(forces)
    for s in mdl.springs:
        states[:, s.element] = forces[:, s.element]
    return Trajectory(
        t=times,
        positions=x[:, None],
        velocities=v[:, None],
        forces=forces,
        applied=network.load_table(times),
        network=network,
        method=METHOD,
        dt=dt,
        save_every=save_every,
        states=states,
        rigid=rigid,
        final_rest=rest,
        solver=METHOD,
        events=_with_rest(march, rest),
    )


def _with_rest(march: March, rest: tuple[np.ndarray, np.ndarray]) -> tuple[Event, ...]:
    """The events and the *rest* (:data:`~lumped.solvers.events.KINDS`, the one-mass march's rule): a last stick
    on a contact at rest with no spring or dashpot driven, once the load is off for ever."""
    mdl, start = march.mdl, float(rest[0][0])
    if math.isnan(start) or mdl.A != 0 or mdl.gamma != 0 or not march.piece(march.phases[-1].start).zero_for_ever:
        return tuple(march.events)
    modes = (0,) * march.n_elements
    event = Event(start, "rest", (float(march.phases[-1].x_start),), (), modes)
    return tuple(sorted([*march.events, event], key=lambda e: e.time))


def _final_rest(march: March, x_end: float) -> tuple[np.ndarray, np.ndarray]:
    """The start and place of the last stick, if it lasts to the end on a contact at rest (``nan`` otherwise)."""
    start = math.nan
    if march.mdl.V == 0:
        for ph in reversed(march.phases):
            if ph.kind != "stick":
                break
            start = ph.start
    return np.array([start]), np.array([math.nan if math.isnan(start) else x_end])
