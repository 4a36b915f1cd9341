"""A network: masses, elements between two points, forces on masses.

Why every step of a network is well posed, and which forces may not be
unique, is :class:`Network`'s Notes.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import numpy as np

from lumped.laws.element import GROUND, NAME_PATTERN, Element, check_name
from lumped.model.forcing import SwitchedSine, evaluate, validate_force
from lumped.numerics import validate
from lumped.numerics.union_find import UnionFind

__all__ = [
    "Mass",
    "Load",
    "Network",
    "NAME_PATTERN",
    "MAX_MASSES",
    "MAX_ELEMENTS",
    "MAX_LOADS",
    "check_count",
    "listed",
]

#: Largest network accepted (masses, elements, loads).  A backward-Euler step of
#: :func:`~lumped.drivers.network.simulate_network` costs about 14 us per mass
#: for a chain with a spring and a Bingham element on every mass (0.14 s a step
#: at 10,000 masses, measured on one core), so 10,000 masses run a thousand
#: steps in minutes; a million masses (issue 19) took 4 minutes and 4.1 GB
#: before their first message, and would take about 14 s a step.  Elements: three per mass (notebook 08's
#: chain has two, a spring and a friction element); forces: two per mass (one, and the ground's ``-m a_g``).
MAX_MASSES = 10_000
MAX_ELEMENTS = 3 * MAX_MASSES
MAX_LOADS = 2 * MAX_MASSES
_SHOWN = 5  # names listed in a message before "... and N more"


def listed(names: Sequence[str], shown: int = _SHOWN) -> str:
    """``'a', 'b', 'c'``, or the first ``shown`` of them and ``... and N more``: one short line."""
    head = ", ".join(repr(n) for n in names[:shown])
    return head if len(names) <= shown else f"{head} ... and {len(names) - shown} more"


@dataclass(frozen=True)
class Mass:
    """A point mass: ``name``, ``mass`` (kg, > 0), ``x0`` (m), ``v0`` (m/s).

    ``x0`` is measured from the position where every element is unstretched.
    """

    name: str
    mass: float
    x0: float = 0.0
    v0: float = 0.0

    def __post_init__(self) -> None:
        check_name("name", self.name)
        if self.name == GROUND:
            raise ValueError(f"name {GROUND!r} is reserved for the fixed point")
        object.__setattr__(self, "mass", validate.positive("mass", self.mass))
        object.__setattr__(self, "x0", validate.finite("x0", self.x0))
        object.__setattr__(self, "v0", validate.finite("v0", self.v0))

    @staticmethod
    def check(value: object, name: str, message: str = "{name} must be a Mass, got {got}") -> Mass:
        """``value`` if it is a :class:`Mass`, else a ``ValueError`` (as :meth:`Element.check`)."""
        if not isinstance(value, Mass):
            raise ValueError(message.format(name=name, got=type(value).__name__))
        return value


@dataclass(frozen=True)
class Load:
    """An external force (N) on the mass ``on``: a load of :mod:`lumped.model.forcing` or any callable of time."""

    on: str
    force: SwitchedSine | Callable[[np.ndarray], np.ndarray]

    def __post_init__(self) -> None:
        check_name("on", self.on)
        if validate_force(self.force) is None:
            raise ValueError("force must be a SwitchedSine or a callable of time, got None")

    @staticmethod
    def check(value: object, name: str, message: str = "{name} must be a Load, got {got}") -> Load:
        """``value`` if it is a :class:`Load`, else a ``ValueError`` (as :meth:`Element.check`)."""
        if not isinstance(value, Load):
            raise ValueError(message.format(name=name, got=type(value).__name__))
        return value


@dataclass(frozen=True)
class Network:
    """Masses, elements and loads, validated as a whole.

    Parameters
    ----------
    masses : sequence of Mass
    elements : sequence of Element
        Each between two points: mass names or ``"ground"``.
    loads : sequence of Load

    Notes
    -----
    **Which steps are well posed.**  With ``v`` the masses' new velocities,
    one backward-Euler step minimises

        sum_i m_i/(2 dt) (v_i - v_n,i)^2 - F_i v_i + sum_e psi_e(w_e)

    over ``v``, with ``w = v_second - v_first`` and ``psi_e`` the convex
    potential of element ``e``'s step graph (a spring's energy at the new
    position over ``dt``, a dashpot's dissipation potential, the indicator
    of a string's ``e <= L`` or of a lock's ``|w| <= v_lock``).  Every mass
    is positive, so the first sum is strictly convex and the minimiser,
    hence every velocity, is unique; so is the force of every element whose
    step graph is single-valued at its rate.  "Two Coulomb elements in
    series with nothing compliant between them" cannot be written here: any
    two elements in series meet at a point, and every point but the ground
    is a mass, whose ``m/dt`` is the compliance of the step.  What *can* be
    non-unique is the force of elements that are *rigid* at the solution (a
    sticking Bingham or Coulomb element, a taut string, a locked or sticking
    locking dashpot): they fix their rate and take whatever force balances
    the masses, and a closed loop of such elements (two in parallel between
    the same points, or a ring through masses and the ground) carries any
    circulating force on top of a solution.  Such networks are solved, not
    refused: the step reports, for each element of such a loop, the interval
    of its admissible forces and, as its force, the split of least norm
    (:mod:`lumped.solvers.loop_forces`).  No network is refused for its
    loops, because every one has a unique motion: the velocities 0 meet
    every constraint of a step (every string starts within its length and
    stays there to rounding, every lock admits the rate 0), so the strictly convex
    potential has one minimiser.  (A loop of rigid pieces whose fixed rates
    disagree has none; only a step of hand-made graphs can pose one, and
    :func:`~lumped.solvers.network_step.solve_step` names its elements.)
    """

    masses: tuple[Mass, ...]
    elements: tuple[Element, ...]
    loads: tuple[Load, ...] = field(default=())

    def __post_init__(self) -> None:
        for what in ("masses", "elements", "loads"):
            value = getattr(self, what)
            if isinstance(value, (str, bytes)) or not isinstance(value, Sequence):
                raise ValueError(f"{what} must be a sequence, got {type(value).__name__}")
            object.__setattr__(self, what, tuple(value))
        self._check_items()
        self._check_names()

    def _check_items(self) -> None:
        for what, cls in (("masses", Mass), ("elements", Element), ("loads", Load)):
            check_count(what, len(getattr(self, what)))
            for item in getattr(self, what):
                cls.check(item, what, f"{{name}} must hold {cls.__name__} objects, got {{got}}")
        if not self.masses:
            raise ValueError("masses: a network needs at least one mass")

    def _check_names(self) -> None:
        for what, items in (("mass", self.masses), ("element", self.elements)):
            seen: set[str] = set()
            for item in items:
                if item.name in seen:
                    raise ValueError(f"{what} {item.name!r}: the name is used twice")
                seen.add(item.name)
        known = {m.name for m in self.masses} | {GROUND}
        for el in self.elements:
            for point in el.between:
                if point not in known:
                    raise ValueError(
                        f"element {el.name!r}: between names {point!r}, which is neither a mass nor 'ground'"
                    )
        for load in self.loads:
            if load.on not in known - {GROUND}:
                raise ValueError(f"force on {load.on!r}: there is no mass of that name")

    # -- indices ------------------------------------------------------------
    def point_index(self) -> dict[str, int]:
        """Point name -> index: masses in order, then the ground (``len(masses)``)."""
        index = {m.name: i for i, m in enumerate(self.masses)}
        index[GROUND] = len(self.masses)
        return index

    def index_of(self, el: Element) -> tuple[int, int]:
        """``(first, second)`` point indices of an element."""
        index = self.point_index()
        return index[el.between[0]], index[el.between[1]]

    @property
    def mass_names(self) -> list[str]:
        return [m.name for m in self.masses]

    @property
    def element_names(self) -> list[str]:
        return [el.name for el in self.elements]

    def incidence(self) -> tuple[np.ndarray, np.ndarray]:
        """Arrays ``first``, ``second`` of point indices (the ground is ``len(masses)``)."""
        index = self.point_index()
        pairs = np.array([(index[el.between[0]], index[el.between[1]]) for el in self.elements], dtype=np.intp)
        pairs = pairs.reshape(len(self.elements), 2)
        return pairs[:, 0].copy(), pairs[:, 1].copy()

    def initial_positions(self) -> tuple[np.ndarray, np.ndarray]:
        """``x0``, ``v0`` of the masses, with the ground's 0 appended."""
        x = np.array([m.x0 for m in self.masses] + [0.0])
        v = np.array([m.v0 for m in self.masses] + [0.0])
        return x, v

    def load_table(self, t: np.ndarray, columns: Sequence[int] | None = None) -> np.ndarray:
        """External force on each mass at the times ``t``: shape ``(len(t), masses)``.

        With ``columns`` (mass indices), only those masses' columns, in that order.
        """
        index = self.point_index()
        columns = range(len(self.masses)) if columns is None else columns
        where = {int(i): k for k, i in enumerate(columns)}
        out = np.zeros((t.size, len(where)))
        for load in self.loads:
            if index[load.on] in where:
                out[:, where[index[load.on]]] += evaluate(load.force, t)
        return out

    def loaded_masses(self) -> list[int]:
        """Indices of the masses that carry a load, in increasing order."""
        index = self.point_index()
        return sorted({index[load.on] for load in self.loads})


def check_count(what: str, count: int) -> int:
    """``count`` if at most the bound on ``what`` (``masses``, ``elements``, ``loads``), else a ``ValueError``."""
    bound = {"masses": MAX_MASSES, "elements": MAX_ELEMENTS, "loads": MAX_LOADS}[what]
    if count > bound:
        raise ValueError(
            f"{what}: {count} given, more than the {bound} a network may have "
            f"(at most {MAX_MASSES} masses, {MAX_ELEMENTS} elements, {MAX_LOADS} forces)"
        )
    return count


def rigid_loop(points: dict[str, int], edges: list[tuple[tuple[int, int], Element]]) -> list[Element]:
    """The elements of a closed loop in the graph ``edges``, or ``[]`` if it is a forest."""
    sets = UnionFind(len(points))
    for k, ((a, b), el) in enumerate(edges):
        if sets.union(a, b):
            continue
        return _path(edges[:k], a, b) + [el]
    return []


def _path(edges: list[tuple[tuple[int, int], Element]], start: int, goal: int) -> list[Element]:
    """Elements on the path from ``start`` to ``goal`` in a forest (breadth first)."""
    adjacent: dict[int, list[tuple[int, Element]]] = {}
    for (a, b), el in edges:
        adjacent.setdefault(a, []).append((b, el))
        adjacent.setdefault(b, []).append((a, el))
    came: dict[int, tuple[int, Element] | None] = {start: None}
    queue = [start]
    while queue:
        node = queue.pop(0)
        for nxt, el in adjacent.get(node, []):
            if nxt not in came:
                came[nxt] = (node, el)
                queue.append(nxt)
    out, node = [], goal
    while came.get(node) is not None:
        node, el = came[node]  # type: ignore[misc]
        out.append(el)
    return out[::-1]
