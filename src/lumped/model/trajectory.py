"""What every run returns: :class:`Trajectory`, one type for one mass or many, with its events.

A trajectory holds the motion of every mass of its system (a
:class:`~lumped.model.network.Network`) and the force of every element on
the saved grid points.  A run of the paper's system (one mass, springs and
one dashpot) also reads as the paper writes it: ``x``, ``v``, the spring
force ``F_s``, the dashpot force ``F_d`` and the external force ``F``, with
the stick intervals, the final rest and the energy balance; these views
refuse, in one line, a system of several masses.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import NamedTuple

import numpy as np

from lumped.laws import GROUND
from lumped.model.network import Network, listed
from lumped.model.oscillator import Oscillator
from lumped.model.problem import OneMass, one_mass_form, oscillator_network

__all__ = ["COLUMNS", "Trajectory", "EnergyBalance", "Jump", "sign_changes"]

#: The one-mass output columns, in order: time (s), displacement (m), velocity
#: (m/s), spring force (N), dashpot force (N), external force (N).
COLUMNS = ("t", "x", "v", "F_s", "F_d", "F")


class EnergyBalance(NamedTuple):
    """Cumulative energies (J) at the saved grid points.

    ``kinetic + potential + dissipated + numerical - external_work`` is
    constant; ``residual`` is that sum minus its value at ``t = 0``.
    ``numerical`` is the energy backward Euler removes by itself,
    ``sum(m dv^2/2 + dF_s^2/(2k))`` (zero for the exact solution).
    """

    kinetic: np.ndarray
    potential: np.ndarray
    dissipated: np.ndarray
    numerical: np.ndarray
    external_work: np.ndarray
    residual: np.ndarray


class Jump(NamedTuple):
    """An element's jump between the branches of its graph (a ``curve`` at a fold), an event of the trajectory.

    ``time`` (s) is the end of the step that reached the fold (backward Euler:
    the element is on branch ``after`` from the next step on); ``element``
    its name; ``before`` and ``after`` the branches' numbers, from 1 along
    the curve.
    """

    time: float
    element: str
    before: int
    after: int


@dataclass(frozen=True, eq=False)
class Trajectory:
    """The motion of a system on the saved grid points.

    Attributes
    ----------
    t : ndarray, (N,), s
    positions, velocities : ndarray, (N, masses), m and m/s
        In the order of ``network.masses``.
    forces : ndarray, (N, elements), N
        Tensions, in the order of ``network.elements``; at ``t = 0`` the
        consistent initial forces.
    applied : ndarray, (N, masses), N
        The external force on each mass.
    network : Network
        The system that ran (masses with their initial state, elements, loads).
    method : str
        The registered method (``"backward-euler"``, ``"exact"``, ...).
    dt : float, s
        Grid step of the computation.
    save_every : int
        Stride between the computed grid and the saved points.
    states : ndarray, (N, elements), or None
        Each element's internal variable (a spring's force, a string's
        elongation, a Maxwell element's force; 0 for none).
    rigid : ndarray of bool, (N, elements), or None
        Element on a rigid piece in the step ending there (sticking, taut,
        locked); False at ``t = 0``.
    final_rest : (ndarray, ndarray) or None
        Each mass's start time (s) and position (m) of the stick interval that
        lasts to the end of the run, found by the method at its full
        resolution (a grid step for backward Euler, the event time for the
        exact solution), ``nan`` if it moves at the end; ``None`` derives them
        from the saved points.
    solver : str
        The path that ran: ``"algorithm1"``, ``"resolvent"`` (a law's
        resolvent), ``"compiled"`` or ``"python"`` (the network's active-set
        step), ``"one-mass-friction"`` (the compiled loop of one mass with a
        friction contact, :mod:`lumped.solvers.friction_compiled`), or the method's name.
    iterations : int
        Largest number of active-set iterations in a step (0 when none ran).
    events : tuple
        The events the method located (stops, breakaways, reversals, the
        forcing's switch-off), in time order; empty for a method that
        locates none.  Backward Euler records each :class:`Jump` of an
        element between the branches of its graph (:attr:`jumps`).
    force_min, force_max : ndarray, (N, elements), N, or None
        The least and greatest admissible force of each element where rigid
        elements close a loop and their split is not unique (``forces`` then
        holds the split of least norm); equal to ``forces`` where the force is
        unique.  ``None`` when every saved point's forces are unique.
    """

    t: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray
    forces: np.ndarray
    applied: np.ndarray
    network: Network
    method: str
    dt: float
    save_every: int = 1
    states: np.ndarray | None = None
    rigid: np.ndarray | None = None
    final_rest: tuple[np.ndarray, np.ndarray] | None = None
    solver: str = ""
    iterations: int = 0
    events: tuple = field(default=())
    force_min: np.ndarray | None = None
    force_max: np.ndarray | None = None

    @classmethod
    def of_oscillator(
        cls,
        *,
        t: np.ndarray,
        x: np.ndarray,
        v: np.ndarray,
        F_s: np.ndarray,  # noqa: N803 -- the paper's names
        F_d: np.ndarray,  # noqa: N803
        F: np.ndarray,  # noqa: N803
        oscillator: Oscillator,
        method: str,
        dt: float,
        save_every: int = 1,
        final_rest: tuple[float, float] | None = None,
        events: tuple = (),
        solver: str | None = None,
    ) -> Trajectory:
        """A one-mass run of ``oscillator`` from its columns (:data:`COLUMNS`); ``solver`` names
        its path where the method has several (``method`` by default).

        The system is :func:`~lumped.model.problem.oscillator_network`'s (the
        spring's force is ``F_s``, the dashpot's ``F_d``, both unchanged), with
        the run's initial state; a driver that knows the load replaces the
        network by the problem's own.
        """
        net = oscillator_network(oscillator, float(x[0]), float(v[0]))
        rest = None if final_rest is None else (np.array([final_rest[0]]), np.array([final_rest[1]]))
        forces = np.column_stack([F_s, F_d])
        rigid = np.column_stack([np.zeros(t.size, dtype=bool), (v == 0) & (t > 0)])
        states = np.column_stack([F_s, np.zeros_like(F_s)])
        return cls(
            t=t,
            positions=x[:, None],
            velocities=v[:, None],
            forces=forces,
            applied=F[:, None],
            network=net,
            method=method,
            dt=dt,
            save_every=save_every,
            states=states,
            rigid=rigid,
            final_rest=rest,
            solver=method if solver is None else solver,
            events=events,
        )

    @classmethod
    def from_array(cls, data: np.ndarray, oscillator: Oscillator, **meta: object) -> Trajectory:
        """A one-mass run from an array whose columns are :data:`COLUMNS` (see :meth:`of_oscillator`)."""
        cols = {name: np.ascontiguousarray(data[:, i]) for i, name in enumerate(COLUMNS)}
        return cls.of_oscillator(**cols, oscillator=oscillator, **meta)  # type: ignore[arg-type]

    # -- every system -------------------------------------------------------

    @property
    def rest_times(self) -> np.ndarray:
        """Each mass's start of the stick interval that lasts to the end (s), ``nan`` if it moves at the end."""
        if self.final_rest is not None:
            return self.final_rest[0]
        return np.array([_rest_start(self.t, self.velocities[:, i]) for i in range(self.positions.shape[1])])

    @property
    def rest_positions(self) -> np.ndarray:
        """Each mass's position at its final rest (m), ``nan`` if it moves at the end."""
        if self.final_rest is not None:
            return self.final_rest[1]
        return np.where(self.velocities[-1] == 0.0, self.positions[-1], np.nan)

    def system_columns(self, suffix: str) -> dict[str, np.ndarray]:
        """The system's output arrays: ``.npz`` names or ``.csv`` columns (see book/guide/systems.md).

        Where some forces are not unique, ``force_min`` and ``force_max`` too
        (``.npz``), or ``force_min_<element>`` and ``force_max_<element>``
        beside ``F_<element>`` for each element concerned (``.csv``).  With
        driven points, their positions and velocities at the saved times
        (:meth:`driver_motion`): ``driver_x``, ``driver_v`` and
        ``driver_names`` (``.npz``), or ``x_<driver>`` and ``v_<driver>``
        after the masses' (``.csv``).
        """
        net = self.network
        drive_x, drive_v = self.driver_motion()
        if suffix == ".npz":
            out = {
                "t": self.t,
                "x": self.positions,
                "v": self.velocities,
                "force": self.forces,
                "load": self.applied,
                "mass_names": np.array(net.mass_names),
                "element_names": np.array(net.element_names),
            }
            if self.force_min is not None and self.force_max is not None:
                out |= {"force_min": self.force_min, "force_max": self.force_max}
            if net.drivers:
                out |= {"driver_x": drive_x, "driver_v": drive_v, "driver_names": np.array(self.driver_names)}
            return out
        out = {"t": self.t}
        out |= {f"x_{n}": self.positions[:, i] for i, n in enumerate(net.mass_names)}
        out |= {f"v_{n}": self.velocities[:, i] for i, n in enumerate(net.mass_names)}
        out |= {f"x_{n}": drive_x[:, i] for i, n in enumerate(self.driver_names)}
        out |= {f"v_{n}": drive_v[:, i] for i, n in enumerate(self.driver_names)}
        for i, n in enumerate(net.element_names):
            out[f"F_{n}"] = self.forces[:, i]
            if i in self.undetermined:
                out[f"force_min_{n}"] = self.force_min[:, i]  # type: ignore[index]
                out[f"force_max_{n}"] = self.force_max[:, i]  # type: ignore[index]
        out |= {f"load_{n}": self.applied[:, i] for i, n in enumerate(net.mass_names)}
        return out

    @property
    def driver_names(self) -> list[str]:
        """The names of the system's driven points, in order (none without ``[[driver]]`` s)."""
        return [d.name for d in self.network.drivers]

    def driver_motion(self) -> tuple[np.ndarray, np.ndarray]:
        """Each driven point's position (m) and velocity (m/s) at the saved times: two ``(N, drivers)`` arrays.

        The position is the integral of the prescribed velocity from 0
        (:meth:`lumped.model.network.Driver.position`), the displacement a
        backward-Euler step moves the point by, so a contact stuck to it
        keeps its elongation.
        """
        shape = (self.t.size, len(self.network.drivers))
        x, v = np.zeros(shape), np.zeros(shape)
        for i, d in enumerate(self.network.drivers):
            x[:, i] = d.position(self.t)
            v[:, i] = d.velocity_at(self.t)
        return x, v

    @property
    def undetermined(self) -> list[int]:
        """Indices of the elements whose force is not unique at some saved point (see ``force_min``)."""
        if self.force_min is None or self.force_max is None:
            return []
        return np.flatnonzero((self.force_min != self.force_max).any(axis=0)).tolist()

    @property
    def jumps(self) -> tuple[Jump, ...]:
        """The jumps between branches among the :attr:`events`, in time order."""
        return tuple(e for e in self.events if isinstance(e, Jump))

    def summary(self, shown: int = 10) -> str:
        """One line: the masses' motion at the end, then the jumps between branches (each element's count
        and its first three), as clauses joined by ``"; "``.

        Up to ``shown`` masses: each one's rest time and position, or that it still moves.  More: how many
        rest at the end (the last to stop, when and which) and which still move, and the largest
        displacement over the saved points, which mass and when (:meth:`_many_masses`).
        """
        few = len(self.network.mass_names) <= shown
        clauses = self._each_mass() if few else self._many_masses()
        return "; ".join(clauses) + _jumps_line(self.jumps)

    def _each_mass(self) -> list[str]:
        """``m1 at rest from t = 3.1458 s at x = 0.0017 m`` or ``m1 still moving at t = 20 s (x = ...)``."""
        parts, times, places = [], self.rest_times, self.rest_positions
        for i, name in enumerate(self.network.mass_names):
            if math.isnan(times[i]):
                parts.append(f"{name} still moving at t = {self.t[-1]:.6g} s (x = {self.positions[-1, i]:.9g} m)")
            else:
                parts.append(f"{name} at rest from t = {times[i]:.10g} s at x = {places[i]:.10g} m")
        return parts

    def _many_masses(self) -> list[str]:
        """``1000 masses: 998 at rest at the end, the last from t = 1.93 s ('b17')``, ``2 still moving at
        t = 2 s ('b3', 'b4')`` (``all`` when none or every one moves) and ``largest |x| 0.0123 m ('b17' at
        t = 1.2 s)``, the largest displacement over the saved points."""
        names, times, end = self.network.mass_names, self.rest_times, f"{self.t[-1]:.6g}"
        moving = np.flatnonzero(np.isnan(times))
        if moving.size == len(names):
            clauses = [f"{len(names)} masses: all still moving at t = {end} s"]
        else:
            last = int(np.nanargmax(times))
            rest = "all" if moving.size == 0 else str(len(names) - moving.size)
            clauses = [
                f"{len(names)} masses: {rest} at rest at the end, the last from t = {times[last]:.6g} s "
                f"({names[last]!r})"
            ]
            if moving.size:
                still = listed([names[i] for i in moving])
                clauses.append(f"{moving.size} still moving at t = {end} s ({still})")
        at, mass = np.unravel_index(int(np.argmax(np.abs(self.positions))), self.positions.shape)
        clauses.append(f"largest |x| {abs(self.positions[at, mass]):.6g} m ({names[mass]!r} at t = {self.t[at]:.6g} s)")
        return clauses

    # -- the paper's system: one mass ------------------------------------------

    @cached_property
    def one_mass(self) -> OneMass:
        """The system as an oscillator, or a one-line ``ValueError`` saying why it is not one."""
        try:
            return one_mass_form(self.network)
        except ValueError as err:
            raise ValueError(
                f"the one-mass view (x, v, F_s, F_d, F) needs the paper's system; the network {err}"
            ) from None

    @property
    def oscillator(self) -> Oscillator:
        """The system as the paper's oscillator (one mass, springs, one dashpot)."""
        return self.one_mass.oscillator

    @property
    def x(self) -> np.ndarray:
        """Displacement (m) of the one mass."""
        self.one_mass  # noqa: B018 -- refuses a system that is not one mass
        return self.positions[:, 0]

    @property
    def v(self) -> np.ndarray:
        """Velocity (m/s) of the one mass."""
        self.one_mass  # noqa: B018
        return self.velocities[:, 0]

    @property
    def F_s(self) -> np.ndarray:  # noqa: N802 -- the paper's name
        """Spring force (N): the springs' tensions, each oriented from the ground to the mass, summed."""
        springs = [self.network.element_names.index(s.name) for s in self.one_mass.springs]
        oriented = [_orientation(self.network.elements[i]) * self.forces[:, i] for i in springs]
        return oriented[0] if len(oriented) == 1 else np.sum(oriented, axis=0)

    @property
    def F_d(self) -> np.ndarray:  # noqa: N802
        """Dashpot force (N), oriented from the ground to the mass."""
        i = self.network.element_names.index(self.one_mass.dashpot.name)
        return _orientation(self.network.elements[i]) * self.forces[:, i]

    @property
    def F(self) -> np.ndarray:  # noqa: N802
        """External force (N) on the one mass."""
        self.one_mass  # noqa: B018
        return self.applied[:, 0]

    def columns(self) -> dict[str, np.ndarray]:
        """The one-mass arrays by column name, in output order (:data:`COLUMNS`)."""
        return {name: getattr(self, name) for name in COLUMNS}

    def as_array(self) -> np.ndarray:
        """Array of shape ``(n, 6)`` with columns :data:`COLUMNS`."""
        return np.column_stack([getattr(self, name) for name in COLUMNS])

    @property
    def at_rest(self) -> np.ndarray:
        """Boolean mask of saved points with ``v == 0`` exactly (stick)."""
        return self.v == 0.0

    def stick_intervals(self) -> list[tuple[float, float]]:
        """Maximal runs of saved points with ``v == 0``, as ``(t_first, t_last)``.

        Backward Euler and the exact solution both give ``v == 0`` exactly in
        stick, so no tolerance is involved.
        """
        rest = self.at_rest.astype(np.int8)
        edges = np.diff(np.concatenate(([0], rest, [0])))
        starts, stops = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1
        return [(float(self.t[a]), float(self.t[b])) for a, b in zip(starts, stops)]

    @property
    def rest_time(self) -> float:
        """Start of the one mass's stick interval that lasts to the end of the run (s).

        ``nan`` if the mass is moving at the last point.  Taken from
        ``final_rest`` when the method supplied it, so that it does not
        depend on ``save_every``.
        """
        self.one_mass  # noqa: B018
        return float(self.rest_times[0])

    @property
    def rest_position(self) -> float:
        """Displacement of the one mass at its final rest (m); ``nan`` if still moving."""
        self.one_mass  # noqa: B018
        return float(self.rest_positions[0])

    def energy_balance(self) -> EnergyBalance:
        """Energy bookkeeping of the one mass on the saved grid.

        For backward Euler on the full grid (``save_every == 1``) the
        discrete identity, obtained by multiplying eq. (13a) by ``v_{n+1}`` and
        eq. (13b) by ``F_s,n+1 / k``, closes to round-off:
        ``dE + dt F_d v + (m dv^2 + dF_s^2/k)/2 = dt F v`` per step.  For other
        methods the integrals use the trapezoidal rule (error ``O(dt^2)``).
        """
        m, k = self.oscillator.mass, self.oscillator.spring.stiffness
        v, F_s, F_d, F = self.v, self.F_s, self.F_d, self.F  # noqa: N806
        kinetic, potential = 0.5 * m * v**2, 0.5 * F_s**2 / k
        step = np.diff(self.t)
        if self.method == "backward-euler":
            if self.save_every != 1:
                raise ValueError("energy_balance needs save_every == 1 for backward Euler")
            power_d, power_f = (step * F_d[1:] * v[1:], step * F[1:] * v[1:])
            numeric = 0.5 * m * np.diff(v) ** 2 + 0.5 * np.diff(F_s) ** 2 / k
        else:
            power_d = step * 0.5 * (F_d[1:] * v[1:] + F_d[:-1] * v[:-1])
            power_f = step * 0.5 * (F[1:] * v[1:] + F[:-1] * v[:-1])
            numeric = np.zeros_like(power_d)
        cum = [np.concatenate(([0.0], np.cumsum(p))) for p in (power_d, numeric, power_f)]
        total = kinetic + potential + cum[0] + cum[1] - cum[2]
        return EnergyBalance(kinetic, potential, *cum, total - total[0])

    @property
    def dissipated_energy(self) -> float:
        """Energy dissipated in the dashpot over the run (J)."""
        return float(self.energy_balance().dissipated[-1])


def _jumps_line(jumps: tuple[Jump, ...], shown: int = 3, elements: int = 5) -> str:
    """``; 'c' jumped 4 times between branches (t = 1.611 s 1 -> 3, ...)`` for each of the first ``elements``
    elements that jumped, their first ``shown`` jumps each."""
    by: dict[str, list[Jump]] = {}
    for j in jumps:
        by.setdefault(j.element, []).append(j)
    out = []
    for name, own in list(by.items())[:elements]:
        first = ", ".join(f"t = {j.time:.6g} s {j.before} -> {j.after}" for j in own[:shown])
        times = "once" if len(own) == 1 else f"{len(own)} times"
        out.append(f"; {name!r} jumped {times} between branches ({first}{', ...' if len(own) > shown else ''})")
    if len(by) > elements:
        out.append(f"; ... and {len(by) - elements} more elements jumped")
    return "".join(out)


def _orientation(el: object) -> float:
    """+1 if the element's elongation is the mass's position (it starts at the ground), -1 if its negative."""
    return 1.0 if el.between[0] == GROUND else -1.0  # type: ignore[attr-defined]


def _rest_start(t: np.ndarray, v: np.ndarray) -> float:
    """Start of the final run of ``v == 0`` on the saved points, ``nan`` if ``v[-1] != 0``."""
    if v[-1] != 0.0:
        return math.nan
    moving = np.flatnonzero(v != 0.0)
    return float(t[moving[-1] + 1]) if moving.size else float(t[0])


def sign_changes(v: np.ndarray) -> int:
    """Changes of direction: sign changes between successive nonzero velocities.

    A velocity exactly ``0`` (a stick step, or a grid point on a reversal) is
    skipped, so ``+, 0, -`` counts one change and ``+, 0, +`` none.
    """
    s = np.sign(v[v != 0])
    return int(np.count_nonzero(s[1:] != s[:-1]))
