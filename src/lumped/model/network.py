"""A network: masses, elements between two points, forces on masses.

Why every step of a network is well posed, and which forces may not be
unique, is :class:`Network`'s Notes.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from lumped.laws.element import GROUND, NAME_PATTERN, Element, check_name
from lumped.model.forcing import Constant, Forcing, SwitchedSine, evaluate, history, validate_force
from lumped.numerics import validate
from lumped.numerics.union_find import UnionFind

__all__ = [
    "Mass",
    "Load",
    "Driver",
    "Network",
    "NAME_PATTERN",
    "MAX_MASSES",
    "MAX_ELEMENTS",
    "MAX_LOADS",
    "check_count",
    "listed",
]

#: Largest network accepted (masses, elements, loads).  The compiled sparse step
#: (:mod:`lumped.solvers.network_sparse`) runs a chain of blocks, each on a friction
#: contact to the floor with a leaf spring to a moving plate and coupling springs,
#: at about 0.1 us per block and step (benchmarks/bench_chain.py), so 100,000 blocks
#: run a thousand steps in tens of seconds; building such a network in Python takes
#: about a minute, and the output's size and the run time are refused beyond their
#: own limits (:mod:`lumped.numerics.validate`).  Elements: three per mass (a
#: contact, a leaf spring, a coupling spring); forces: two per mass (one, and the
#: ground's ``-m a_g``).
MAX_MASSES = 100_000
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
class Driver:
    """A driven point: a point whose motion is prescribed (a moving belt, a plate pulled at a speed).

    Parameters
    ----------
    name : str
        Its name, which elements give in ``between`` as they give a mass or ``"ground"``.
    velocity : float or Forcing, m/s
        A number (the point sits at ``velocity * t``), or a history of the velocity
        (:class:`~lumped.model.forcing.Table`, :class:`~lumped.model.forcing.SwitchedSine`,
        :class:`~lumped.model.forcing.Constant`); the position is its integral from 0
        (point 9 of :class:`~lumped.model.forcing.Forcing`), so the point starts at 0.
    """

    name: str
    velocity: float | Forcing

    def __post_init__(self) -> None:
        check_name("name", self.name)
        if self.name == GROUND:
            raise ValueError(f"name {GROUND!r} is reserved for the fixed point")
        if history(self.velocity) is not None:
            if self.velocity.integral(0.0) is None or self.velocity.initial_slope() is None:
                raise ValueError(
                    f"velocity: {self.velocity.description} has no closed-form integral to give a position"
                )
        else:
            object.__setattr__(self, "velocity", validate.finite("velocity", self.velocity))

    @property
    def history(self) -> Forcing:
        """The velocity as a function of time (a number as a :class:`~lumped.model.forcing.Constant`)."""
        given = history(self.velocity)
        return given if given is not None else Constant(self.velocity)  # type: ignore[arg-type]

    @property
    def constant_velocity(self) -> float | None:
        """The velocity (m/s) if it is one number at all times, else ``None``."""
        return None if history(self.velocity) is not None else self.velocity  # type: ignore[return-value]

    def position(self, t: np.ndarray | float) -> np.ndarray | float:
        """The point's position (m) at the times ``t``: the integral of its velocity from 0."""
        if self.constant_velocity is not None:
            return self.constant_velocity * np.asarray(t, dtype=float) if np.ndim(t) else self.constant_velocity * t
        return self.history.integral(t)  # type: ignore[return-value]

    def velocity_at(self, t: np.ndarray | float) -> np.ndarray | float:
        """The point's velocity (m/s) at the times ``t``."""
        return (
            evaluate(self.history, np.atleast_1d(np.asarray(t, dtype=float))) if np.ndim(t) else float(self.history(t))
        )

    def mean_velocity(self, t0: np.ndarray, t1: np.ndarray) -> np.ndarray:
        """The mean velocity over each ``[t0, t1]``: its displacement over the time, the one a
        backward-Euler step moves the point by (exactly ``velocity`` for a number)."""
        if self.constant_velocity is not None:
            return np.full(np.shape(t0), self.constant_velocity)
        h = self.history
        return (np.asarray(h.integral(t1)) - np.asarray(h.integral(t0))) / (t1 - t0)

    def check_span(self, t_end: float) -> None:
        """A one-line ``ValueError`` if the point's position leaves double precision by ``t_end`` (s).

        A constant velocity moves the point by ``|velocity| t_end``, its largest excursion; a history is checked
        at ``t_end``, where an overflow on the way would have left ``inf`` or ``nan``.  Past that, every method
        would write ``inf`` for the point and for what it pulls (issue 41: a belt at 1e308 m/s).
        """
        V = self.constant_velocity
        with np.errstate(over="ignore", invalid="ignore"):
            reach = abs(V) * t_end if V is not None else abs(float(self.position(t_end)))
        if not math.isfinite(reach):
            moving = f"at {V:.6g} m/s" if V is not None else "along its history"
            raise ValueError(
                f"driver {self.name!r}: moving {moving}, its position passes the largest double "
                f"({sys.float_info.max:.3g} m) before t_end = {t_end:.6g} s; lower its velocity or t_end"
            )

    @property
    def initial_acceleration(self) -> float:
        """The velocity's rate of change just after ``t = 0`` (m/s^2)."""
        return float(self.history.initial_slope())  # type: ignore[arg-type]

    @staticmethod
    def check(value: object, name: str, message: str = "{name} must be a Driver, got {got}") -> Driver:
        """``value`` if it is a :class:`Driver`, else a ``ValueError`` (as :meth:`Element.check`)."""
        if not isinstance(value, Driver):
            raise ValueError(message.format(name=name, got=type(value).__name__))
        return value


class Driven(NamedTuple):
    """An element joined to a driven point: its index, the driver's index, and ``+1`` if the driver is the
    element's ``second`` point (its rate is the problem's plus the driver's velocity), ``-1`` if its ``first``."""

    element: int
    driver: int
    sign: float


@dataclass(frozen=True)
class Network:
    """Masses, elements and loads, validated as a whole.

    Parameters
    ----------
    masses : sequence of Mass
    elements : sequence of Element
        Each between two points: mass names or ``"ground"``.
    loads : sequence of Load
    drivers : sequence of Driver
        Points whose motion is prescribed; elements join them as they join the ground.

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
    drivers: tuple[Driver, ...] = field(default=())

    def __post_init__(self) -> None:
        for what in ("masses", "elements", "loads", "drivers"):
            value = getattr(self, what)
            if isinstance(value, (str, bytes)) or not isinstance(value, Sequence):
                raise ValueError(f"{what} must be a sequence, got {type(value).__name__}")
            object.__setattr__(self, what, tuple(value))
        self._check_items()
        self._check_names()

    def _check_items(self) -> None:
        for what, cls in (("masses", Mass), ("elements", Element), ("loads", Load), ("drivers", Driver)):
            check_count(what, len(getattr(self, what)))
            for item in getattr(self, what):
                cls.check(item, what, f"{{name}} must hold {cls.__name__} objects, got {{got}}")
        if not self.masses:
            raise ValueError("masses: a network needs at least one mass")

    def _check_names(self) -> None:
        for what, items in (("mass", self.masses), ("driver", self.drivers), ("element", self.elements)):
            seen: set[str] = set()
            for item in items:
                if item.name in seen:
                    raise ValueError(f"{what} {item.name!r}: the name is used twice")
                seen.add(item.name)
        masses = {m.name for m in self.masses}
        for d in self.drivers:
            if d.name in masses:
                raise ValueError(f"driver {d.name!r}: the name is a mass's; a driven point needs a name of its own")
        known = masses | {GROUND} | {d.name for d in self.drivers}
        for el in self.elements:
            for point in el.between:
                if point not in known:
                    raise ValueError(
                        f"element {el.name!r}: between names {point!r}, which is neither a mass nor 'ground'"
                        + (" nor a driver" if self.drivers else "")
                    )
            if not masses & set(el.between):
                raise ValueError(f"element {el.name!r}: joins {el.between[0]!r} and {el.between[1]!r}, neither a mass")
        for load in self.loads:
            if load.on in known - masses - {GROUND}:
                raise ValueError(
                    f"force on {load.on!r}: {load.on!r} is a driven point, whose motion is prescribed; "
                    "forces act on masses"
                )
            if load.on not in masses:
                raise ValueError(f"force on {load.on!r}: there is no mass of that name")

    # -- indices ------------------------------------------------------------
    def point_index(self) -> dict[str, int]:
        """Point name -> index: masses in order, then the ground (``len(masses)``).

        A driven point has the ground's index: the one-step problem sees it as the
        ground, and shifts the rates of the elements joined to it (:meth:`driven`).
        """
        index = {m.name: i for i, m in enumerate(self.masses)}
        index[GROUND] = len(self.masses)
        for d in self.drivers:
            index[d.name] = len(self.masses)
        return index

    def _memo(self, key: str, build: Callable[[], object]) -> object:
        """``build()``, computed once per network (its fields are immutable tuples of frozen items): the
        indices below are asked for several times per run, each a loop over every element."""
        memo = self.__dict__.setdefault("_computed", {})
        if key not in memo:
            memo[key] = build()
        return memo[key]

    def driven(self) -> list[Driven]:
        """The elements joined to a driven point, in element order (:class:`Driven`)."""
        return list(self._memo("driven", self._driven))  # type: ignore[call-overload]

    def _driven(self) -> tuple[Driven, ...]:
        where = {d.name: k for k, d in enumerate(self.drivers)}
        out = []
        for e, el in enumerate(self.elements):
            for point, sign in zip(el.between, (-1.0, 1.0)):
                if point in where:
                    out.append(Driven(e, where[point], sign))
        return tuple(out)

    def check_span(self, t_end: float) -> None:
        """A one-line ``ValueError`` if a driven point's position leaves double precision by ``t_end``
        (:meth:`Driver.check_span`), or if a linear spring it pulls would carry more than the largest double
        when the point is that far (``k |x_d(t_end)|``: every method forms it, and would write ``inf``)."""
        for d in self.drivers:
            d.check_span(t_end)
        for link in self.driven():
            el, d = self.elements[link.element], self.drivers[link.driver]
            with np.errstate(over="ignore", invalid="ignore"):
                pull = (el.linear_stiffness or 0.0) * abs(float(d.position(t_end)))
            if not math.isfinite(pull):
                raise ValueError(
                    f"element {el.name!r}: its stiffness {el.linear_stiffness:.6g} N/m times the travel of driver "
                    f"{d.name!r} by t_end = {t_end:.6g} s passes the largest double; lower them or t_end"
                )

    def refuse_drivers(self, what: str) -> None:
        """A ``ValueError`` saying that ``what`` cannot run a system with driven points, if it has any."""
        if self.drivers:
            raise ValueError(
                f"{what} cannot run a system with driven points ({listed([d.name for d in self.drivers])}); "
                "backward-euler runs it (exact and event-driven too, at a constant velocity)"
            )

    def refuse_non_monotone(self, what: str) -> None:
        """A ``ValueError`` saying that ``what`` cannot run the first element whose graph is not monotone
        (point 13 of :class:`~lumped.laws.element.Element`: friction with static above kinetic, a falling
        slip curve, a curve that folds), if there is one."""
        for el in self.elements:
            if not el.monotone:
                raise ValueError(
                    f"{what} cannot run element {el.name!r} of kind {el.kind!r}: its graph is not monotone "
                    "(static above kinetic, a slip curve that falls with speed, a curve that folds); "
                    "backward-euler runs it"
                )

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
        first, second = self._memo("incidence", self._incidence)  # type: ignore[misc]
        return first.copy(), second.copy()

    def _incidence(self) -> tuple[np.ndarray, np.ndarray]:
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
    bound = {"masses": MAX_MASSES, "elements": MAX_ELEMENTS, "loads": MAX_LOADS, "drivers": MAX_MASSES}[what]
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
