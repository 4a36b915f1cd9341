"""The element contract: what an element of a network is, and what it must provide.

An element joins two points, ``first`` and ``second`` (a mass or the ground,
whose position is 0).  Its *elongation* is ``e = x_second - x_first``, its
*rate* ``w = v_second - v_first``, and its *force* ``f`` is a tension: it
pulls ``second`` by ``-f`` and ``first`` by ``+f``.  With one mass and
``between = ("ground", "m1")`` this is the paper's sign convention: the mass
feels ``-F_s - F_d``.  Each element is a constitutive graph between its force
and its elongation or elongation rate; one step sees it as a step graph
(:mod:`lumped.laws.step_graph`).

This module holds the :class:`Element` base class with its numbered
extension contract, the names of points and elements (:data:`GROUND`,
:func:`check_name`) and :class:`KernelForm`; the kinds are in
:mod:`lumped.laws.spring_elements` and :mod:`lumped.laws.dashpot_elements`,
listed by name in :data:`lumped.laws.kinds.KINDS`.
"""

from __future__ import annotations

import re
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

from lumped.laws.contract import Dashpot, SlipLaw
from lumped.laws.step_graph import Piece

__all__ = ["Element", "KernelForm", "GROUND", "NAME_PATTERN", "MAX_NAME_LENGTH", "check_name"]

#: The name of the fixed point at ``x = 0``.
GROUND = "ground"
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


class KernelForm(NamedTuple):
    """An element as ``_network_kernel.c`` reads it: its kind ``code``, its
    ``parameters`` (at most 4, in the order of ``_network_elements.h``) and whether its step
    graph has a rigid piece, of any width, for some state (``rigid_pieces``)."""

    code: int
    parameters: tuple[float, ...]
    rigid_pieces: bool


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
    10. ``steepest_fall`` (N s/m): how steeply the element's force may fall
        as its rate grows (a friction contact's Stribeck curve), which a
        backward-Euler step must outweigh to be unique
        (:func:`lumped.solvers.uniqueness.check_step`); ``0.0`` by default
        (a monotone graph).
    11. ``optional`` (a class attribute): the parameters a system file may
        leave out, which then take the dataclass field's default (``()`` by
        default: every parameter is written).
    12. ``slip_law()``: the friction law (:class:`lumped.laws.SlipLaw`) of a
        contact, which a method asks through that law's contract (its
        ``static``, ``slip_limit``, ``pieces()``), or ``None`` (the default:
        the element is not a friction contact).
    13. ``monotone``: True (the default) if the element's graph is maximal
        monotone for every state; False for a graph that falls (a friction
        contact with ``static`` above its slip limit, a slip curve falling
        with speed, a curve invertible neither way), whose step a rule picks
        (point 6 of :class:`lumped.laws.step_graph.StepGraph`).  The methods
        written for monotone graphs (the period map, the exact
        sensitivities, the one-mass schemes) refuse such an element
        (:meth:`lumped.model.network.Network.refuse_non_monotone`).
    14. ``jumps`` (a class attribute): True if the state is a branch of the
        element's graph (a number), so that a change of state between steps is
        a jump that backward Euler records in the trajectory
        (:class:`lumped.model.trajectory.Jump`: time, element, branch before,
        branch after); False by default.
    """

    kind: ClassVar[str] = ""
    optional: ClassVar[tuple[str, ...]] = ()
    #: True if a change of the state is a jump between branches (point 12).
    jumps: ClassVar[bool] = False
    #: The kind code of ``_network_elements.h`` (point 9), ``None`` if it has none.
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
    def steepest_fall(self) -> float:
        """How steeply the force may fall with the rate (N s/m, point 10); ``0.0`` by default."""
        return 0.0

    @property
    def monotone(self) -> bool:
        """True if the graph is maximal monotone for every state (point 12); True by default."""
        return True

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

    def slip_law(self) -> SlipLaw | None:
        """The contact's friction law (point 12), or ``None``: not a friction contact."""
        return None

    def kernel_form(self) -> KernelForm | None:
        """The element as ``_network_kernel.c`` reads it, or ``None`` (point 9)."""
        code = type(self).__dict__.get("kernel_code")
        if code is None:
            return None
        parameters, rigid_pieces = self._kernel_form()
        return KernelForm(code, tuple(parameters), rigid_pieces)

    def _kernel_form(self) -> tuple[list[float], bool]:
        """Parameters in the order of ``_network_elements.h`` and ``rigid_pieces`` (point 9)."""
        raise NotImplementedError(f"{type(self).__name__} declares kernel_code but not _kernel_form")

    @staticmethod
    def check(value: object, name: str, message: str = "{name} must be an Element, got {got}") -> Element:
        """``value`` if it is an element, else a ``ValueError``.

        The one test of "is this an element?", so that no other module asks
        for an element's class: ``message`` is formatted with ``name`` and
        ``got``, the name of ``value``'s type.
        """
        if not isinstance(value, Element):
            raise ValueError(message.format(name=name, got=type(value).__name__))
        return value
