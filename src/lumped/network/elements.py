"""Elements of a lumped network: each a constitutive graph between its force
and its elongation or elongation rate.

An element joins two points, ``first`` and ``second`` (a mass or the ground,
whose position is 0).  Its *elongation* is ``e = x_second - x_first``, its
*rate* ``w = v_second - v_first``, and its *force* ``f`` is a tension: it
pulls ``second`` by ``-f`` and ``first`` by ``+f``.  With one mass and
``between = ("ground", "m1")`` this is the paper's sign convention: the mass
feels ``-F_s - F_d``.

One backward-Euler step fixes every state of the step's start and leaves the
new rates ``w`` unknown; each element then relates ``f`` to ``w`` by a
*step graph*, maximal monotone and piecewise linear for every kind here (a
general monotone law is the exception: see :class:`Monotone`).  A step graph
is a list of :class:`Piece` s in increasing order along the graph: a *free*
piece ``f = a + b w`` (``b >= 0``) on ``lo <= w <= hi``, or a *rigid* piece
``w = a`` with ``lo <= f <= hi``.  The one-step problem
(:mod:`lumped.network.step`) only sees pieces; it never asks which kind an
element is.
"""

from __future__ import annotations

import math
import re
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import ClassVar, NamedTuple

from lumped import _validate
from lumped.laws import BinghamDashpot, Dashpot, HerschelBulkleyDashpot

__all__ = [
    "Piece",
    "Element",
    "Spring",
    "SpringString",
    "Bingham",
    "MaxwellBingham",
    "LinearDashpot",
    "LockingBingham",
    "Monotone",
    "HerschelBulkley",
    "LawElement",
    "KINDS",
    "GROUND",
    "NAME_PATTERN",
    "MAX_NAME_LENGTH",
    "check_name",
]

#: The name of the fixed point at ``x = 0``.
GROUND = "ground"
_INF = math.inf
#: Longest name of a mass or an element (characters).
MAX_NAME_LENGTH = 64
#: Names of masses and elements: a letter or ``_``, then ASCII letters, digits
#: and ``_ . -``, at most :data:`MAX_NAME_LENGTH` characters in all.  They
#: become column names of the output (``x_<mass>``, ``F_<element>`` in a CSV
#: header), so a comma, a newline, a quote or a non-ASCII character, which
#: would break the header or its encoding, is refused.
NAME_PATTERN = re.compile(rf"[A-Za-z_][A-Za-z0-9_.\-]{{0,{MAX_NAME_LENGTH - 1}}}\Z")


def check_name(what: str, value: object) -> str:
    """``value`` if it is a name (:data:`NAME_PATTERN`), else a one-line ``ValueError`` naming ``what``."""
    if not isinstance(value, str) or not NAME_PATTERN.match(value):
        raise ValueError(
            f"{what} must be 1 to {MAX_NAME_LENGTH} ASCII letters, digits, '_', '.', '-' "
            f"starting with a letter or '_', got {ascii(value):.40}"
        )
    return value


class Piece(NamedTuple):
    """One piece of a step graph.

    ``rigid`` False: ``f = a + b*w`` for ``lo <= w <= hi`` (``b >= 0``).
    ``rigid`` True: ``w = a`` and ``lo <= f <= hi`` (``b`` unused, 0).
    """

    rigid: bool
    a: float
    b: float
    lo: float
    hi: float


def _free(a: float, b: float, lo: float = -_INF, hi: float = _INF) -> Piece:
    return Piece(False, a, b, lo, hi)


def _rigid(w: float, lo: float, hi: float) -> Piece:
    return Piece(True, w, 0.0, lo, hi)


def _band(threshold: float, c: float, lo: float = -_INF, hi: float = _INF) -> tuple[Piece, ...]:
    """The Bingham step graph: slip- on ``[lo, 0]``, stick, slip+ on ``[0, hi]``."""
    return (_free(-threshold, c, lo, 0.0), _rigid(0.0, -threshold, threshold), _free(threshold, c, 0.0, hi))


def _checked_pair(between: object) -> tuple[str, str]:
    if (
        not isinstance(between, (tuple, list))
        or len(between) != 2
        or not all(isinstance(p, str) and p for p in between)
    ):
        raise ValueError(f"between must be two point names, got {between!r:.60}")
    for point in between:
        check_name("between", point)
    if between[0] == between[1]:
        raise ValueError(f"between joins {between[0]!r} to itself")
    return (between[0], between[1])


@dataclass(frozen=True)
class Element(ABC):
    """An element between two points, given by its constitutive graph.

    A new element kind must provide:

    1. ``kind`` (a class attribute): its name in system files, and its
       parameters as dataclass fields after ``name`` and ``between``, each
       validated in ``_check`` (a ``ValueError`` naming the field).
    2. ``initial_state(e0, w0)``: its internal variable at ``t = 0`` from the
       initial elongation (m) and rate (m/s) (a spring's force, a string's
       elongation, a Maxwell element's force; ``0.0`` if it has none).
    3. ``step_graph(state, dt)``: the step graph of backward Euler from
       ``state``, as :class:`Piece` s in increasing order along the graph
       (each piece's ``hi`` is the next one's start; the last reaches
       ``f = +inf`` or ``w = +inf``).  It must be maximal monotone: that
       makes the one-step problem a strictly convex minimisation.
    4. ``rate_graph(state, w0)``: the graph between the force and the rate
       of ``w`` at ``t = 0`` (same form), used once for the consistent
       initial forces: a flat stretch of ``f(w)`` at ``w0`` becomes a rigid
       piece at acceleration 0.
    5. ``next_state(state, dt, w, f, rigid)``: the internal variable at the
       step's end, from the step's rate and force and whether a rigid piece
       was taken.
    6. ``stored_energy(state)`` (J), and ``rigid_capable``: True if some
       state makes a rigid piece available (the force then is not a function
       of the motion; see :func:`lumped.network.model.Network` for why
       that matters).

    The graph itself, for plots and tests, is :meth:`force_interval`.
    """

    kind: ClassVar[str] = ""
    name: str
    between: tuple[str, str]

    def __post_init__(self) -> None:
        check_name("name", self.name)
        object.__setattr__(self, "between", _checked_pair(self.between))
        self._check()

    def _set(self, field_name: str, check: Callable[[str, object], float]) -> None:
        object.__setattr__(self, field_name, check(field_name, getattr(self, field_name)))

    @abstractmethod
    def _check(self) -> None:
        """Validate the parameters (see the class docstring, point 1)."""

    @property
    def rigid_capable(self) -> bool:
        """True if some state gives the step graph a rigid piece."""
        return False

    def initial_state(self, e0: float, w0: float) -> float:
        """Internal variable at ``t = 0`` (point 2); none by default."""
        return 0.0

    @abstractmethod
    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        """Backward-Euler graph between ``f`` and the step's rate ``w`` (point 3)."""

    @abstractmethod
    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        """Graph between the force at ``t = 0`` and the rate of ``w`` (point 4)."""

    def next_state(self, state: float, dt: float, w: float, f: float, rigid: bool) -> float:
        """Internal variable at the step's end (point 5); none by default."""
        return 0.0

    def stored_energy(self, state: float) -> float:
        """Energy stored in the element (J); none by default."""
        return 0.0

    @abstractmethod
    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        """The constitutive graph: forces (N) compatible with ``e`` (m) and ``w`` (m/s).

        ``(lo, hi)`` with ``lo == hi`` where the force is a function of the
        motion; ``(nan, nan)`` if the motion is not admissible.
        """


class _ForceState:
    """Elements whose state is the force ``f`` of a spring of ``stiffness``."""

    stiffness: float

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        return (_free(state, 0.0),)

    def next_state(self, state: float, dt: float, w: float, f: float, rigid: bool) -> float:
        return f

    def stored_energy(self, state: float) -> float:
        return 0.5 * state * state / self.stiffness


@dataclass(frozen=True)
class Spring(_ForceState, Element):
    """Linear spring, ``f = k e``.

    The state is the force, advanced as ``f + dt*k*w`` exactly as line 11 of
    Algorithm 1 advances ``F_s``.
    """

    kind: ClassVar[str] = "spring"
    stiffness: float = 1.0

    def _check(self) -> None:
        self._set("stiffness", _validate.positive)

    def initial_state(self, e0: float, w0: float) -> float:
        return self.stiffness * e0

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        return (_free(state, dt * self.stiffness),)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return (self.stiffness * e, self.stiffness * e)


@dataclass(frozen=True)
class SpringString(Element):
    """A linear spring in parallel with an inextensible string (the paper's Figure 2).

    ``e <= L``; ``f = k e`` while slack (``e < L``), any ``f >= k L`` while
    taut (``e = L``).  The elongation is a function of the force, not the
    reverse: the graph is the spring's line up to ``(L, kL)``, then the
    vertical ray above it.

    Notes
    -----
    The step graph in ``w`` is the spring's line ``f = k e_n + dt k w`` for
    ``w <= (L - e_n)/dt`` and the vertical ray ``f >= kL`` at
    ``w = (L - e_n)/dt`` (the normal cone of ``e <= L``: Moreau's sweeping
    process).  So a string that would pass its length within a step ends the
    step exactly taut (the state is set to ``L``, not recomputed), and the
    relative velocity jumps to ``(L - e_n)/dt`` and, on the next step, to 0:
    an *inelastic impact* of the relative motion, which backward Euler (like
    the sweeping process) resolves with restitution 0.  The kinetic energy of
    the relative motion it removes is the work ``(f - k L)(L - e_n)`` of the
    string's reaction, counted as dissipation in the energy balance.
    """

    kind: ClassVar[str] = "spring-string"
    stiffness: float = 1.0
    length: float = 1.0

    def _check(self) -> None:
        self._set("stiffness", _validate.positive)
        self._set("length", _validate.positive)

    @property
    def rigid_capable(self) -> bool:
        return True

    def initial_state(self, e0: float, w0: float) -> float:
        if e0 > self.length:
            raise ValueError(f"x0: the initial elongation {e0:.6g} m is beyond the string's length {self.length:.6g} m")
        return e0

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        k, length = self.stiffness, self.length
        reach = (length - state) / dt
        return (_free(k * state, dt * k, -_INF, reach), _rigid(reach, k * length, _INF))

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        k = self.stiffness
        if state < self.length or w0 < 0:
            return (_free(k * state, 0.0),)
        return (_free(k * self.length, 0.0, -_INF, 0.0), _rigid(0.0, k * self.length, _INF))

    def next_state(self, state: float, dt: float, w: float, f: float, rigid: bool) -> float:
        return self.length if rigid else state + dt * w

    def stored_energy(self, state: float) -> float:
        return 0.5 * self.stiffness * state * state

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        if e > self.length:
            return (math.nan, math.nan)
        k = self.stiffness
        return (k * e, k * e) if e < self.length else (k * e, _INF)


@dataclass(frozen=True)
class Bingham(Element):
    """Bingham dashpot, eq. (6): ``w = 0`` for ``|f| <= threshold``, else
    ``f = sgn(w) threshold + w/gamma``; ``gamma = inf`` is Coulomb.

    The law is :class:`lumped.laws.BinghamDashpot` (:attr:`law`); the step
    graph is its graph itself (a dashpot has no state).
    """

    kind: ClassVar[str] = "bingham"
    threshold: float = 1.0
    gamma: float = 1.0

    def _check(self) -> None:
        law = BinghamDashpot(self.threshold, self.gamma)  # its checks, its messages
        object.__setattr__(self, "threshold", law.threshold)
        object.__setattr__(self, "gamma", law.gamma)

    @property
    def law(self) -> BinghamDashpot:
        """The dashpot law of :mod:`lumped.laws`."""
        return BinghamDashpot(self.threshold, self.gamma)

    @property
    def viscosity(self) -> float:
        """``c = 1/gamma`` (N s/m), 0 for Coulomb."""
        return self.law.viscosity

    @property
    def rigid_capable(self) -> bool:
        return self.threshold > 0

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        return _band(self.threshold, self.viscosity)

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        if w0 != 0:
            return (_free(float(self.law.slip_force(w0)), 0.0),)
        return _band(self.threshold, 0.0)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return self.law.force_interval(w)


@dataclass(frozen=True)
class LinearDashpot(Element):
    """Linear viscous dashpot, ``f = damping * w``."""

    kind: ClassVar[str] = "dashpot"
    damping: float = 1.0

    def _check(self) -> None:
        self._set("damping", _validate.positive)

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        return (_free(0.0, self.damping),)

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        return (_free(self.damping * w0, 0.0),)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return (self.damping * w, self.damping * w)


@dataclass(frozen=True)
class MaxwellBingham(_ForceState, Element):
    """A linear spring (``stiffness``) in series with a Bingham dashpot, massless between.

    The state is the common force ``f`` (the spring's elongation is ``f/k``,
    the dashpot's the rest of ``e``).  Relaxed (``f = 0``) at ``t = 0``
    unless ``force0`` is given.  Inside the dashpot's band, ``|force0| <=
    threshold``, the dashpot holds; beyond it a viscous dashpot (finite
    ``gamma``) creeps from ``t = 0`` and the force relaxes towards the
    threshold (notebook 07).  A Coulomb dashpot (``gamma = inf``) carries no
    force beyond its threshold, so there ``|force0| > threshold`` is not an
    admissible state (backward Euler would drop the force to the threshold in
    the first step, whatever ``dt``) and is refused.

    Notes
    -----
    Backward Euler on ``f' = k (w - phi(f))`` gives ``f + dt k phi(f) = p``
    with the trial force ``p = f_n + dt k w``: the dashpot's resolvent
    (:mod:`lumped.laws`) with ``eta = 1/(dt k)``.  For the Bingham ``phi``
    it is ``f = p`` while ``|p| <= threshold`` (the dashpot holds) and
    ``f = (c p + dt k s threshold)/(c + dt k)``, ``s = sgn(p)``, beyond
    (Coulomb, ``c = 0``: ``f = s threshold``).  Each is affine in ``w``, so
    the element is never rigid: its force is always a function of the motion.
    """

    kind: ClassVar[str] = "maxwell-bingham"
    stiffness: float = 1.0
    threshold: float = 1.0
    gamma: float = 1.0
    force0: float = 0.0

    def _check(self) -> None:
        self._set("stiffness", _validate.positive)
        law = BinghamDashpot(self.threshold, self.gamma)
        object.__setattr__(self, "threshold", law.threshold)
        object.__setattr__(self, "gamma", law.gamma)
        self._set("force0", _validate.finite)
        if math.isinf(self.gamma) and abs(self.force0) > self.threshold:
            raise ValueError(
                f"force0 = {self.force0:.6g} N lies outside the band |f| <= threshold = {self.threshold:.6g} N, "
                "which a Coulomb dashpot (gamma = inf) cannot leave; lower |force0| or give a finite gamma"
            )

    def initial_state(self, e0: float, w0: float) -> float:
        return self.force0

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        kdt, tau = dt * self.stiffness, self.threshold
        c = BinghamDashpot(tau, self.gamma).viscosity
        lo, hi = (-tau - state) / kdt, (tau - state) / kdt  # |p| <= tau
        slope = c * kdt / (c + kdt)
        return (
            _free((c * state - kdt * tau) / (c + kdt), slope, -_INF, lo),
            _free(state, kdt, lo, hi),
            _free((c * state + kdt * tau) / (c + kdt), slope, hi, _INF),
        )

    def dashpot_rate(self, f: float) -> float:
        """The dashpot's elongation rate (m/s) under force ``f`` (N)."""
        return float(BinghamDashpot(self.threshold, self.gamma).velocity(f))

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return (-_INF, _INF)  # a state variable: the force is not fixed by (e, w)


@dataclass(frozen=True)
class LockingBingham(Element):
    """A Bingham dashpot that also locks at the rate ``v_lock``: invertible neither way.

    The graph: no motion while ``|f| <= threshold``; ``f = sgn(w) threshold
    + w/gamma`` for ``0 < |w| < v_lock``; and ``|w| = v_lock`` for every
    ``|f| >= threshold + v_lock/gamma``: no speed above ``v_lock`` whatever
    the force.  The force is not a function of the rate (vertical at 0 and at
    ``+-v_lock``); with ``gamma = inf`` the rate is not a function of the force
    either (horizontal at ``+-threshold``), the case the name is meant for.
    (With a finite ``gamma`` the rate is a function of the force, clipped at
    ``v_lock``, but not an invertible one.)  The potential of its step is
    ``threshold |w| + w^2/(2 gamma)`` plus the indicator of ``|w| <= v_lock``.

    A rate beyond ``v_lock`` at ``t = 0`` is brought to ``v_lock`` in the
    first step, an impact like a string's.
    """

    kind: ClassVar[str] = "locking-bingham"
    threshold: float = 1.0
    gamma: float = 1.0
    v_lock: float = 1.0

    def _check(self) -> None:
        law = BinghamDashpot(self.threshold, self.gamma)
        object.__setattr__(self, "threshold", law.threshold)
        object.__setattr__(self, "gamma", law.gamma)
        self._set("v_lock", _validate.positive)

    @property
    def rigid_capable(self) -> bool:
        return True

    def _edge(self) -> float:
        return self.threshold + BinghamDashpot(self.threshold, self.gamma).viscosity * self.v_lock

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        lock, edge = self.v_lock, self._edge()
        c = BinghamDashpot(self.threshold, self.gamma).viscosity
        return (_rigid(-lock, -_INF, -edge), *_band(self.threshold, c, -lock, lock), _rigid(lock, edge, _INF))

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        edge = self._edge()
        if w0 == 0:
            return _band(self.threshold, 0.0)
        if abs(w0) >= self.v_lock:
            s = math.copysign(1.0, w0)
            if s > 0:
                return (_free(edge, 0.0, -_INF, 0.0), _rigid(0.0, edge, _INF))
            return (_rigid(0.0, -_INF, -edge), _free(-edge, 0.0, 0.0, _INF))
        c = BinghamDashpot(self.threshold, self.gamma).viscosity
        return (_free(math.copysign(self.threshold, w0) + c * w0, 0.0),)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        if abs(w) > self.v_lock:
            return (math.nan, math.nan)
        lo, hi = BinghamDashpot(self.threshold, self.gamma).force_interval(w)
        if w == self.v_lock:
            return (lo, _INF)
        if w == -self.v_lock:
            return (-_INF, hi)
        return (lo, hi)


class LawElement:
    """A dashpot element given by a :class:`lumped.laws.Dashpot` law (its ``law``).

    Its step graph is not piecewise linear: each step linearises it about
    the previous step's force (a free piece through that point, with the
    secant slope), so the step problem is solved to within the iteration's
    tolerance, not exactly; see :mod:`lumped.network.step`.
    """

    law: Dashpot

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        raise NotImplementedError  # handled by the step's outer loop (see step.py)

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        lo, hi = self.law.force_interval(w0)
        return (_free(lo, 0.0),) if lo == hi else _band(hi, 0.0)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return self.law.force_interval(w)

    @property
    def rigid_capable(self) -> bool:
        """True when the law holds a range of forces at rest (a static band)."""
        lo, hi = self.law.force_interval(0.0)
        return lo < hi


@dataclass(frozen=True)
class Monotone(LawElement, Element):
    """Any monotone dashpot law ``w = phi(f)`` (API only), as :class:`lumped.laws.MonotoneDashpot`."""

    kind: ClassVar[str] = "monotone"
    law: Dashpot = field(default=None)  # type: ignore[assignment]

    def _check(self) -> None:
        if not isinstance(self.law, Dashpot):
            raise ValueError(f"law must be a lumped.laws.Dashpot, got {type(self.law).__name__}")


@dataclass(frozen=True)
class HerschelBulkley(LawElement, Element):
    """Herschel-Bulkley dashpot, :class:`lumped.laws.HerschelBulkleyDashpot`: ``w = 0`` for
    ``|f| <= threshold``, else ``f = sgn(w) (threshold + consistency |w|^exponent)``.
    """

    kind: ClassVar[str] = "herschel-bulkley"
    threshold: float = 1.0
    consistency: float = 1.0
    exponent: float = 1.0

    def _check(self) -> None:
        law = HerschelBulkleyDashpot(self.threshold, self.consistency, self.exponent)  # its checks, its messages
        for name in ("threshold", "consistency", "exponent"):
            object.__setattr__(self, name, getattr(law, name))

    @property
    def law(self) -> HerschelBulkleyDashpot:  # type: ignore[override]
        """The dashpot law of :mod:`lumped.laws`."""
        return HerschelBulkleyDashpot(self.threshold, self.consistency, self.exponent)


#: Element kinds by their name in system files.
KINDS: dict[str, type[Element]] = {
    cls.kind: cls
    for cls in (Spring, SpringString, Bingham, MaxwellBingham, LinearDashpot, LockingBingham, HerschelBulkley)
}
