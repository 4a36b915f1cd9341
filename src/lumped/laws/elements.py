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
general monotone law is the exception: see :class:`LawElement`).  A
piecewise-linear step graph is a list of :class:`Piece` s in increasing order
along the graph: a *free* piece ``f = a + b w`` (``b >= 0``) on ``lo <= w <=
hi``, or a *rigid* piece ``w = a`` with ``lo <= f <= hi``.  The one-step
problem (:mod:`lumped.solvers.network_step`) sees each graph through the graph
contract of :class:`StepGraph` (:class:`Pieces`, or a law's
:class:`LawGraph`); it never asks which kind an element or a graph is.
"""

from __future__ import annotations

import math
import re
from abc import ABC, abstractmethod
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import ClassVar, NamedTuple

from lumped.laws.dashpots import BinghamDashpot, Dashpot, HerschelBulkleyDashpot, sticks
from lumped.numerics import validate

__all__ = [
    "Piece",
    "StepGraph",
    "Pieces",
    "LawGraph",
    "as_step_graph",
    "KernelForm",
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
_EPS = 2.0**-52  # numpy.finfo(float).eps
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


class StepGraph(ABC):
    """The graph contract: what the one-step problem asks of a step graph.

    A *mode* is where on the graph an element is taken to be in one
    iteration of the active-set loop (:mod:`lumped.solvers.network_step`).  A step
    graph must provide:

    1. ``is_piecewise``: True if the graph is made of :class:`Piece` s
       (indexable, its modes their indices), so that the iteration's modes can
       cycle and the dual sweeps can step on it; False for a graph that is
       linearised about a point in each iteration (:class:`LawGraph`).
    2. ``initial_mode()``: the mode of the first iteration with no warm start.
    3. ``piece(mode, sigma)``: the free or rigid :class:`Piece` that the
       linear problem of an iteration uses in ``mode``.
    4. ``mode(z, sigma)``: the new mode from the resolvent variable ``z = f +
       sigma w`` of the iteration's solution.
    5. ``same(old, new)``: True when the mode has settled.
    """

    __slots__ = ()
    is_piecewise: ClassVar[bool] = True

    @abstractmethod
    def initial_mode(self) -> object:
        """The mode of the first iteration (point 2)."""

    @abstractmethod
    def piece(self, mode: object, sigma: float) -> Piece:
        """The piece used in ``mode`` (point 3)."""

    @abstractmethod
    def mode(self, z: float, sigma: float) -> object:
        """The mode holding ``z = f + sigma w`` (point 4)."""

    @abstractmethod
    def same(self, old: object, new: object) -> bool:
        """True if the mode has settled (point 5)."""


class Pieces(tuple, StepGraph):
    """A piecewise-linear step graph: its :class:`Piece` s in order; a mode is a piece's index."""

    __slots__ = ()
    is_piecewise: ClassVar[bool] = True

    def initial_mode(self) -> int:
        """The middle piece (a Bingham element's sticking piece)."""
        return len(self) // 2

    def piece(self, mode: object, sigma: float) -> Piece:
        return self[mode]  # type: ignore[index]

    def mode(self, z: float, sigma: float) -> int:
        """The piece whose range of ``z = f + sigma w`` holds ``z``.

        A rigid piece (``w = a``, ``f`` in ``[lo, hi]``) holds the closed band
        ``[lo + sigma a, hi + sigma a]`` (:func:`lumped.laws.sticks`, Algorithm 1's
        line 5), so at an edge it shares with a free piece, where both give the
        same ``(w, f)``, the rigid piece is chosen: a Bingham element sticks on
        both edges of its band, as in Algorithm 1.  A rigid piece of zero width
        (a threshold 0) is never taken: its one point lies on the free pieces
        beside it, and such an element is not ``rigid_capable``.  ``mode_of`` in
        ``_network_kernel.c`` is the C copy (``tests/test_band_edge.py``).
        """
        for k, p in enumerate(self):
            if p.rigid and p.lo < p.hi and sticks(z, p.lo + sigma * p.a, p.hi + sigma * p.a):
                return k
        last = len(self) - 1
        for k, p in enumerate(self[:last]):
            if not p.rigid and z <= p.a + (p.b + sigma) * p.hi:
                return k
        return last

    def same(self, old: object, new: object) -> bool:
        return old == new


class LawGraph(StepGraph):
    """The step graph of a :class:`LawElement`: its dashpot law, linearised in each iteration.

    A mode is the point ``(w, f)`` of the graph last reached (``0`` before
    the first): the piece is the line of slope ``sigma`` through it, and the
    new point is the law's resolvent point of ``z``.  The mode has settled
    when the force agrees to a relative 8 ulps.
    """

    __slots__ = ("law",)
    is_piecewise: ClassVar[bool] = False

    def __init__(self, law: Dashpot) -> None:
        self.law = law

    def initial_mode(self) -> int:
        return 0

    def piece(self, mode: object, sigma: float) -> Piece:
        w0, f0 = mode if isinstance(mode, tuple) else (0.0, 0.0)
        return Piece(False, f0 - sigma * w0, sigma, -_INF, _INF)

    def mode(self, z: float, sigma: float) -> tuple[float, float]:
        f = self.law._resolvent_impl(z, sigma).force
        return ((z - f) / sigma, f)

    def same(self, old: object, new: object) -> bool:
        if not isinstance(old, tuple):
            return False
        scale = abs(new[1]) + abs(old[1]) + 1e-300  # type: ignore[index]
        return abs(new[1] - old[1]) <= 8 * _EPS * scale  # type: ignore[index]


def as_step_graph(graph: StepGraph | Sequence[Piece]) -> StepGraph:
    """``graph`` itself if it is a :class:`StepGraph`, else its pieces as :class:`Pieces`."""
    return graph if isinstance(graph, StepGraph) else Pieces(graph)


class KernelForm(NamedTuple):
    """An element as ``_network_kernel.c`` reads it: its kind ``code``, its
    ``parameters`` (at most 4, in the C file's order) and whether its step
    graph has a rigid piece, of any width, for some state (``rigid_pieces``)."""

    code: int
    parameters: tuple[float, ...]
    rigid_pieces: bool


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
       of the motion; see :func:`lumped.model.network.Network` for why
       that matters).

    The graph itself, for plots and tests, is :meth:`force_interval`.

    What an integrator may ask of an element beyond its graph is a property
    or method here, with a generic default that an element meeting points 1
    to 6 satisfies; no solver asks an element for its class.

    7. ``step_stiffness``: the stiffness (N/m) of the spring the element puts
       between its points, which scales the mode test of the one-step problem
       (``0.0`` by default: none).
    8. The one-mass form (:func:`lumped.model.problem.one_mass_form`):
       ``linear_stiffness``, ``k`` if the element is the linear spring ``f =
       k e`` and nothing more (``None`` by default); ``one_mass_law()``, the
       :class:`lumped.laws.Dashpot` a single-mass method runs if the element
       is a dashpot without state (``None`` by default); ``auto_one_mass``,
       True if ``solver="auto"`` hands one mass with one spring and this
       dashpot to :func:`lumped.backward_euler` rather than to the active-set
       step (False by default).
    9. ``kernel_form()``: the element as the compiled step reads it, a
       :class:`KernelForm`, or ``None`` (the default: the Python step runs
       it).  A kind with a C copy of its step graph declares ``kernel_code``
       and implements ``_kernel_form()``; a subclass that does not declare
       its own ``kernel_code`` gets ``None``, since it may have changed the
       graph the C copy repeats.
    """

    kind: ClassVar[str] = ""
    #: The kind code of ``_network_kernel.c`` (point 9), ``None`` if it has none.
    kernel_code: ClassVar[int | None] = None
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

    @property
    def step_stiffness(self) -> float:
        """Stiffness (N/m) of the element's spring for the mode-test scale (point 7); none by default."""
        return 0.0

    @property
    def linear_stiffness(self) -> float | None:
        """``k`` (N/m) if the element is the linear spring ``f = k e`` (point 8), else ``None``."""
        return None

    def one_mass_law(self) -> Dashpot | None:
        """The dashpot law a single-mass method runs for this element (point 8), else ``None``."""
        return None

    @property
    def auto_one_mass(self) -> bool:
        """True if ``solver="auto"`` runs one mass, one spring and this dashpot by
        :func:`lumped.backward_euler` (point 8); False by default."""
        return False

    def kernel_form(self) -> KernelForm | None:
        """The element as ``_network_kernel.c`` reads it, or ``None`` (point 9)."""
        code = type(self).__dict__.get("kernel_code")
        if code is None:
            return None
        parameters, rigid_pieces = self._kernel_form()
        return KernelForm(code, tuple(parameters), rigid_pieces)

    def _kernel_form(self) -> tuple[list[float], bool]:
        """Parameters in the C file's order and ``rigid_pieces`` (point 9)."""
        raise NotImplementedError(f"{type(self).__name__} declares kernel_code but not _kernel_form")


class _ForceState:
    """Elements whose state is the force ``f`` of a spring of ``stiffness``."""

    stiffness: float

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        return (_free(state, 0.0),)

    def next_state(self, state: float, dt: float, w: float, f: float, rigid: bool) -> float:
        return f

    def stored_energy(self, state: float) -> float:
        return 0.5 * state * state / self.stiffness

    @property
    def step_stiffness(self) -> float:
        return self.stiffness


@dataclass(frozen=True)
class Spring(_ForceState, Element):
    """Linear spring, ``f = k e``.

    The state is the force, advanced as ``f + dt*k*w`` exactly as line 11 of
    Algorithm 1 advances ``F_s``.
    """

    kind: ClassVar[str] = "spring"
    kernel_code: ClassVar[int | None] = 0
    stiffness: float = 1.0

    def _check(self) -> None:
        self._set("stiffness", validate.positive)

    def initial_state(self, e0: float, w0: float) -> float:
        return self.stiffness * e0

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        return (_free(state, dt * self.stiffness),)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return (self.stiffness * e, self.stiffness * e)

    @property
    def linear_stiffness(self) -> float:
        return self.stiffness

    def _kernel_form(self) -> tuple[list[float], bool]:
        return [self.stiffness], False


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
    kernel_code: ClassVar[int | None] = 1
    stiffness: float = 1.0
    length: float = 1.0

    def _check(self) -> None:
        self._set("stiffness", validate.positive)
        self._set("length", validate.positive)

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

    @property
    def step_stiffness(self) -> float:
        return self.stiffness

    def _kernel_form(self) -> tuple[list[float], bool]:
        return [self.stiffness, self.length], True


@dataclass(frozen=True)
class Bingham(Element):
    """Bingham dashpot, eq. (6): ``w = 0`` for ``|f| <= threshold``, else
    ``f = sgn(w) threshold + w/gamma``; ``gamma = inf`` is Coulomb.

    The law is :class:`lumped.laws.BinghamDashpot` (:attr:`law`); the step
    graph is its graph itself (a dashpot has no state).
    """

    kind: ClassVar[str] = "bingham"
    kernel_code: ClassVar[int | None] = 2
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

    def one_mass_law(self) -> BinghamDashpot:
        return self.law

    @property
    def auto_one_mass(self) -> bool:
        """True: Algorithm 1 itself, the same numbers bit for bit at the compiled kernel's speed."""
        return True

    def _kernel_form(self) -> tuple[list[float], bool]:
        c = BinghamDashpot(self.threshold, self.gamma).viscosity
        return [self.threshold, c], True  # a threshold 0 included: the graph keeps its rigid piece


@dataclass(frozen=True)
class LinearDashpot(Element):
    """Linear viscous dashpot, ``f = damping * w``."""

    kind: ClassVar[str] = "dashpot"
    kernel_code: ClassVar[int | None] = 4
    damping: float = 1.0

    def _check(self) -> None:
        self._set("damping", validate.positive)

    def step_graph(self, state: float, dt: float) -> tuple[Piece, ...]:
        return (_free(0.0, self.damping),)

    def rate_graph(self, state: float, w0: float) -> tuple[Piece, ...]:
        return (_free(self.damping * w0, 0.0),)

    def force_interval(self, e: float, w: float) -> tuple[float, float]:
        return (self.damping * w, self.damping * w)

    def one_mass_law(self) -> HerschelBulkleyDashpot:
        """``f = damping * w`` as the Herschel-Bulkley law with no threshold and exponent 1."""
        return HerschelBulkleyDashpot(0.0, self.damping, 1.0)

    def _kernel_form(self) -> tuple[list[float], bool]:
        return [self.damping], False


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
    kernel_code: ClassVar[int | None] = 3
    stiffness: float = 1.0
    threshold: float = 1.0
    gamma: float = 1.0
    force0: float = 0.0

    def _check(self) -> None:
        self._set("stiffness", validate.positive)
        law = BinghamDashpot(self.threshold, self.gamma)
        object.__setattr__(self, "threshold", law.threshold)
        object.__setattr__(self, "gamma", law.gamma)
        self._set("force0", validate.finite)
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

    def _kernel_form(self) -> tuple[list[float], bool]:
        c = BinghamDashpot(self.threshold, self.gamma).viscosity
        return [self.stiffness, self.threshold, c], False


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
    kernel_code: ClassVar[int | None] = 5
    threshold: float = 1.0
    gamma: float = 1.0
    v_lock: float = 1.0

    def _check(self) -> None:
        law = BinghamDashpot(self.threshold, self.gamma)
        object.__setattr__(self, "threshold", law.threshold)
        object.__setattr__(self, "gamma", law.gamma)
        self._set("v_lock", validate.positive)

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

    def _kernel_form(self) -> tuple[list[float], bool]:
        c = BinghamDashpot(self.threshold, self.gamma).viscosity
        return [self.threshold, c, self.v_lock], True


class LawElement:
    """A dashpot element given by a :class:`lumped.laws.Dashpot` law (its ``law``).

    Its step graph, the law's :class:`LawGraph`, is not piecewise linear:
    each iteration of the step linearises it about the point last reached (a
    free piece through that point, of slope ``sigma``), so the step problem
    is solved to within the iteration's tolerance, not exactly; see
    :mod:`lumped.solvers.network_step`.
    """

    law: Dashpot

    def step_graph(self, state: float, dt: float) -> LawGraph:  # type: ignore[override]
        return LawGraph(self.law)

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

    def one_mass_law(self) -> Dashpot:
        """The law itself: a single-mass method runs it as it runs any :class:`lumped.laws.Dashpot`."""
        return self.law

    @property
    def auto_one_mass(self) -> bool:
        """True: the law's resolvent solves the one-mass step, which the active-set step only linearises."""
        return True


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

    def one_mass_law(self) -> HerschelBulkleyDashpot:
        return self.law

    @property
    def auto_one_mass(self) -> bool:
        """True: the law's resolvent solves the one-mass step, which the active-set step only linearises."""
        return True


#: Element kinds by their name in system files.
KINDS: dict[str, type[Element]] = {
    cls.kind: cls
    for cls in (Spring, SpringString, Bingham, MaxwellBingham, LinearDashpot, LockingBingham, HerschelBulkley)
}
