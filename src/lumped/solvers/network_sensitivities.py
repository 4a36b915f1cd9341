"""Exact derivatives of the ``exact`` network solution with respect to its parameters (forward sensitivities).

:func:`network_sensitivities` runs a network by the exact method
(:func:`lumped.solvers.exact_network.march`: phases of linear motion, events
located, modes chosen) and differentiates it, phase by phase, with respect
to its numeric parameters (:data:`KINDS`): every mass, initial position and
velocity, spring stiffness, viscosity and threshold, and the amplitude,
frequency, phase and end of its first load.  It extends the monodromy of
:mod:`lumped.solvers.network_monodromy` (the derivative with respect to the
initial state, whose mode flows ``B``, projections ``Q`` and event gradients
it reuses) to the parameters, as :mod:`lumped.solvers.sensitivities` does
for one mass.

Notes
-----
In a phase of mode ``mu`` the masses' state ``y = (x, v)`` with the loads'
generators ``(1, cos w t, sin w t)`` is ``Y`` (``2n + 1 + 2 n_w``), and
``Y' = A Y`` with ``x' = v``, ``v' = G N Y``: ``N Y = F(t) - K x - C v -
A_slip (mu tau)`` is the net force on the masses of the loads and the
elements that do not stick, ``G = S (S^T m S)^-1 S^T`` (module Notes of
:mod:`~lumped.solvers.network_monodromy`).  The sticking elements' forces are
``split N Y`` with ``split = pinv(A_S) (I - m G)``.

* A parameter ``p``'s derivative at a fixed time, ``u = dY/dp``, obeys ``u' = A
  u + (dA/dp) Y``: both are solved at once by the exponential of the block
  matrix ``[[A, 0], [dA/dp, A]]`` (Van Loan, IEEE Trans. Automat. Control 23
  (1978) 395-404), one such block per parameter.  ``dN/dp`` is
  ``-a_e a_e^T`` on ``x`` for a spring's stiffness, on ``v`` for a
  viscosity (``a_e`` the element's column of the incidence; 0 while it
  sticks), ``-mu_e a_e`` on the generator 1 for a slipping threshold, and
  the load's coefficients' derivatives; a mass enters through ``G``:
  ``dG/dm_i = -G e_i e_i^T G``, so ``d(G N)/dm_i = -G e_i a_i`` and
  ``d(split N)/dm_i = -split e_i a_i`` (``a_i`` the mass's acceleration); the
  frequency rotates the generators.
* The phase starts at ``t_a(p)`` from the projection ``Q`` of its state (its
  groups move with their momentum's velocity), so ``u(t_a) = Q (dY_a - f+
  dt_a)``, ``f+ = A Y_a`` its own field.  ``Q`` depends on the masses, but
  ``(dQ/dm) Y_a = 0``: every phase starts with the sticking elements at zero
  rate (a stop reaches zero rate; at ``t = 0`` the elements at zero rate are
  those that may stick), where ``Q Y = Y`` for every mass.
* An event at ``t_b`` where ``g(Y, p) = 0`` (a stop: a slipping element's
  rate ``mu_e a_e^T v``; a breakaway: ``tau_e - s f_e``, ``s`` the force's
  sign) moves by ``dt_b = -(dg/dp + dg/dY u_b)/g'`` (``g'`` its rate along
  the flow); the state there varies by ``u_b + f- dt_b`` (``f- = A Y_b`` the
  ending phase's field).  A load switching at its ``until`` moves with it:
  ``dt_b = d(until)/dp``.
* The rest of a mass is the start of its last run of phases held to the
  ground (:func:`~lumped.solvers.network_modes.final_rest`): its time and
  position move as that phase's start.

Where the sequence of events changes with a parameter the solution is not
differentiable there; each event carries its distance from such a change
(:attr:`NetworkEventSensitivity.margin`, dimensionless), the smallest of:
the event function's rate ``|g'|`` (``m_e |g'|/tau_e`` for a stop, ``m_e``
the smaller mass at the element's ends; ``|g'|/(tau_e w_max)`` for a
breakaway, ``w_max`` the fastest rate of the phase it ends); the time since
the event before, ``w_max (t_b - t_a)`` (two events at one instant, which
may swap; 0 for an event of two elements at once); for each element that sticks after it ``(tau_e - |f_e|)/tau_e``,
for each that stopped or stuck and slips after it ``(|f_e| - tau_e)/tau_e``
(``f_e`` its reaction were it to stick).  A switch has only the last two.
Near 0 the derivatives are one-sided.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from lumped.model.forcing import SineForm
from lumped.numerics.expm import expm
from lumped.solvers.exact_network import march, sample
from lumped.solvers.events import Event
from lumped.solvers.network_monodromy import ModeFlow, event_gradient, mode_flow
from lumped.solvers.network_phase import Parts, Phase, load_matrix, load_on, phase
from lumped.solvers.sensitivity_chain import flow

__all__ = [
    "KINDS",
    "NetworkEventSensitivity",
    "NetworkMotion",
    "NetworkSensitivities",
    "Parameter",
    "along",
    "network_sensitivities",
]

#: The kinds of parameters: ``index`` names the mass (the first three) or the element (the next three);
#: the last four are those of the first load (``amplitude`` is a constant load's value).
KINDS = ("mass", "x0", "v0", "stiffness", "viscosity", "threshold", "amplitude", "omega", "phase", "until")


class Parameter(NamedTuple):
    """A parameter of :data:`KINDS`, of the mass or element of index ``index`` (0 for the load's)."""

    kind: str
    index: int = 0


@dataclass(frozen=True)
class NetworkEventSensitivity:
    """An event with the derivatives of its ``time`` (p,) and of the masses' positions ``x`` there (n, p), its
    ``margin`` from a change of the event sequence (module Notes) and the index of its (first) ``element``
    (-1 for a switch)."""

    event: Event
    time: np.ndarray
    x: np.ndarray
    margin: float
    element: int


@dataclass(frozen=True)
class NetworkMotion:
    """The exact motion of a network: its ``phases`` and ``events`` (:func:`~lumped.solvers.exact_network.march`)."""

    phases: tuple[Phase, ...]
    events: tuple[Event, ...]

    def evaluate(self, t: np.ndarray | Sequence[float]) -> dict[str, np.ndarray]:
        """Positions ``"x"`` and velocities ``"v"`` (T, n) at the increasing times ``t`` (s) of the run."""
        x, v = sample(list(self.phases), np.asarray(t, dtype=float))[:2]
        return {"x": x, "v": v}


@dataclass(frozen=True)
class NetworkSensitivities:
    """The exact network motion at the times ``t`` and its derivatives, one column per parameter.

    Attributes
    ----------
    parameters : tuple of Parameter
    t : ndarray, (T,), s
    positions, velocities : ndarray, (T, n)
        The motion itself (m, m/s), as the exact solver samples it.
    x, v : ndarray, (T, n, p)
        ``dx/dp`` and ``dv/dp`` at the times ``t`` (held fixed).
    events : tuple of NetworkEventSensitivity
        Every stop, breakaway and switch, in time order.
    rest_time, rest_position : ndarray, (n, p)
        Derivatives of each mass's final rest (``nan`` for a mass moving at the end).
    motion : NetworkMotion
    """

    parameters: tuple[Parameter, ...]
    t: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray
    x: np.ndarray
    v: np.ndarray
    events: tuple[NetworkEventSensitivity, ...]
    rest_time: np.ndarray
    rest_position: np.ndarray
    motion: NetworkMotion

    def stop_times(self) -> tuple[tuple[str, float, np.ndarray], ...]:
        """Each slip-to-stick: ``(element, time, d(time)/dp)``, in time order."""
        return tuple(
            (e.event.elements[0], e.event.time, e.time)
            for e in self.events
            if e.event.kind == "stop" and e.event.mode[e.element] == 0
        )

    def smallest_margin(self) -> float:
        """The smallest event margin (``inf`` without events): near 0, the derivatives are one-sided."""
        return min((e.margin for e in self.events), default=math.inf)


def network_sensitivities(
    p: Parts,
    x0: np.ndarray,
    v0: np.ndarray,
    t: np.ndarray | Sequence[float],
    parameters: Sequence[Parameter],
    names: list[str],
) -> NetworkSensitivities:
    """The exact motion of ``p`` from ``(x0, v0)`` (m, m/s; (n,)) over ``[0, t[-1]]`` and its derivatives.

    Parameters
    ----------
    p : Parts
        A network that :func:`~lumped.solvers.network_phase.refusal` accepts.
    t : array_like, (T,), s
        Increasing times in ``[0, t[-1]]``, ``t[-1] > 0``.
    parameters : sequence of Parameter
        The derivatives wanted (module Notes; the caller checks that each applies).
    names : list of str
        The elements' names, for the events.
    """
    t = np.asarray(t, dtype=float)
    params = tuple(parameters)
    phases, events = march(p, np.asarray(x0, float), np.asarray(v0, float), float(t[-1]), names)
    carried = _Carry(p, phases, events, params, names)
    x, v = carried.sample(t)
    motion = NetworkMotion(tuple(phases), tuple(events))
    now = motion.evaluate(t)
    rest = _rest(phases, carried.starts, now["x"][-1])
    return NetworkSensitivities(params, t, now["x"], now["v"], x, v, tuple(carried.events), rest[0], rest[1], motion)


def along(
    p: Parts,
    phases: Sequence[Phase],
    events: Sequence[Event],
    t: np.ndarray | Sequence[float],
    parameters: Sequence[Parameter],
    names: list[str],
) -> tuple[np.ndarray, np.ndarray]:
    """``dx/dp`` and ``dv/dp`` (T, n, p) at the times ``t`` of a motion already marched (its ``phases`` and
    ``events``, as :func:`~lumped.solvers.exact_network.march` or a period map gives them), without marching
    again: what a period map's derivative in a parameter needs."""
    carried = _Carry(p, list(phases), list(events), tuple(parameters), names)
    return carried.sample(np.asarray(t, dtype=float))


def _rest(phases: list[Phase], starts: list[np.ndarray], x_end: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``d(rest time)/dp`` and ``d(rest position)/dp`` (n, p) of each mass: those of the start of its last run
    of grounded phases."""
    n, width = x_end.size, starts[0].shape[1]
    time, position = np.full((n, width), math.nan), np.full((n, width), math.nan)
    for i in range(n):  # as final_rest: the first phase of the last grounded run, if the last is grounded
        k = len(phases)
        while k > 0 and phases[k - 1].grounded[i]:
            k -= 1
        if k < len(phases):
            time[i], position[i] = starts[k][0], starts[k][1 + i]
    return time, position


class _Carry:
    """``D = d(t, Y)/dp`` carried through the phases (module Notes): its value at each phase's start, each
    phase's block matrix and initial vector (for :meth:`sample`), and each event's derivatives."""

    def __init__(self, p: Parts, phases: list[Phase], events: list[Event], params: tuple, names: list) -> None:
        self.p, self.params, self.names = p, params, names
        n, width = p.m.size, len(params)
        self.gens = 1 + 2 * len(p.omegas)
        self.dim = 2 * n + self.gens
        D = np.zeros((1 + self.dim, width))
        for j, prm in enumerate(params):
            if prm.kind in ("x0", "v0"):
                D[1 + prm.index + (n if prm.kind == "v0" else 0), j] = 1.0
        self.starts: list[np.ndarray] = []
        #: per phase: its start, each parameter's block matrix and initial vector ``(Y_a, u_a)``.
        self.pieces: list[tuple[float, list[np.ndarray], list[np.ndarray]]] = []
        self.events: list[NetworkEventSensitivity] = []
        for k, ph in enumerate(phases):  # phase k + 1 begins at event k; the last runs to the end
            self.starts.append(D)
            last = k == len(events)
            D = self._phase(ph, D, None if last else events[k], None if last else phases[k + 1])

    def _state(self, ph: Phase, z: np.ndarray) -> np.ndarray:
        """``Y = (x, v, generators)`` of the phase's state ``z``."""
        x, v = ph.values(z)[:2]
        return np.concatenate([x, v, z[-self.gens :]])

    def _phase(self, ph: Phase, D: np.ndarray, event: Event | None, after: Phase | None) -> np.ndarray:
        """Record the phase's block matrix; return ``D`` just after its event (module Notes)."""
        fl = mode_flow(self.p, ph.mode)
        a, da, frow, dfrow = _matrices(self.p, ph, fl, self.params, self.gens)
        n, dim, width = self.p.m.size, self.dim, len(self.params)
        q = np.eye(dim)
        q[: 2 * n, : 2 * n] = fl.q
        y_a = self._state(ph, ph.z0)
        u_a = q @ (D[1:] - np.outer(a @ y_a, D[0]))
        blocks = [np.block([[a, np.zeros_like(a)], [da[j], a]]) for j in range(width)]
        w_a = [np.concatenate([y_a, u_a[:, j]]) for j in range(width)]
        self.pieces.append((ph.start, blocks, w_a))
        if event is None:
            return D
        h = event.time - ph.start
        u_b = np.zeros((dim, width))
        for j in range(width):  # a block of 2 dim per parameter: cheaper than one of (p + 1) dim for all
            u_b[:, j] = (expm(blocks[j] * h) @ w_a[j])[dim:]
        z_b = ph.z(event.time)
        y_b = self._state(ph, z_b)
        dt, margin, e = self._event(ph, fl, event, after, y_b, u_b, z_b, frow, dfrow)
        D = np.vstack([dt, u_b + np.outer(a @ y_b, dt)])
        self.events.append(NetworkEventSensitivity(event, dt, D[1 : 1 + n], float(margin), e))
        return D

    def _event(self, ph, fl, event, after, y_b, u_b, z_b, frow, dfrow) -> tuple[np.ndarray, float, int]:
        """``dt_b/dp`` (p,) of ``event``, its margin (module Notes) and its element (-1 for a switch)."""
        p, n = self.p, self.p.m.size
        if event.kind == "switch":
            off = p.loads[0][1].until if p.loads else math.inf
            dt = np.array([1.0 if prm.kind == "until" and event.time == off else 0.0 for prm in self.params])
            return dt, _band(p, ph, after, ()), -1
        e, s, r, rate = event_gradient(p, ph, fl, event, self.names, z_b)
        dg = r @ u_b[: 2 * n]
        fastest = float(np.max(np.abs(np.linalg.eigvals(ph.a)), initial=0.0))
        apart = (event.time - ph.start) * fastest if fastest > 0 else math.inf  # from the event before
        if len(set(event.elements)) > 1:  # two elements at one instant (to the events' precision)
            apart = 0.0
        if event.kind == "breakaway":
            row = int(np.flatnonzero(fl.sticking == e)[0])
            dg = dg - s * (frow[row, 2 * n :] @ u_b[2 * n :]) - s * (dfrow[:, row] @ y_b)
            dg += np.array([1.0 if prm == Parameter("threshold", e) else 0.0 for prm in self.params])
            steep = abs(rate) / (p.tau[e] * fastest) if fastest > 0 else math.inf
            return -dg / rate, min(steep, apart, _band(p, ph, after, (), skip=e)), e
        ends = [i for i in range(n) if p.b[i, e] != 0]
        steep = float(np.min(p.m[ends])) * abs(rate) / p.tau[e]
        return -dg / rate, min(steep, apart, _band(p, ph, after, (e,))), e

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``dx/dp`` and ``dv/dp`` (T, n, p) at the times ``t``, each in the phase that holds it."""
        n, dim, width = self.p.m.size, self.dim, len(self.params)
        dx, dv = np.zeros((t.size, n, width)), np.zeros((t.size, n, width))
        starts = np.array([start for start, _, _ in self.pieces])
        which = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(starts) - 1)
        for k in np.unique(which):
            sel = np.flatnonzero(which == k)
            start, blocks, w_a = self.pieces[k]
            for j in range(width):
                u = flow(blocks[j], w_a[j], t[sel] - start, expm)[:, dim:]
                dx[sel, :, j], dv[sel, :, j] = u[:, :n], u[:, n : 2 * n]
        return dx, dv


def _band(p: Parts, before: Phase, after: Phase, stopped: tuple[int, ...], skip: int = -1) -> float:
    """The smallest distance, in thresholds, of a friction element's force from its band's edge just after an
    event: ``(tau - |f|)/tau`` for one that sticks, ``(|f| - tau)/tau`` for one that stuck or ``stopped`` and
    now slips (``f`` its reaction were it to stick), but ``skip`` (a breakaway's own); ``inf`` for none."""
    f = after.values(after.z0)[3]
    out = [(p.tau[e] - abs(f[e])) / p.tau[e] for e in np.flatnonzero(p.friction & (after.mode == 0))]
    was = before.mode == 0
    was[list(stopped)] = True
    x, v = after.values(after.z0)[:2]
    for e in np.flatnonzero(p.friction & (after.mode != 0) & was):
        if e == skip:
            continue
        trial = after.mode.copy()
        trial[e] = 0
        held = phase(p, after.start, x, v, trial)
        out.append((abs(held.values(held.z0)[3][e]) - p.tau[e]) / p.tau[e])
    return min(out, default=math.inf)


def _matrices(p: Parts, ph: Phase, fl: ModeFlow, params: tuple, gens: int) -> tuple[np.ndarray, ...]:
    """``A`` (dim, dim), ``dA/dp`` (p, dim, dim), the sticking forces' rows ``split N`` (s, dim) and their
    derivatives (p, s, dim) of the phase ``ph`` (module Notes)."""
    n = p.m.size
    dim = 2 * n + gens
    net = np.zeros((n, dim))
    net[:, :n], net[:, n : 2 * n] = -fl.stiffness, -fl.viscosity
    net[:, 2 * n :] = load_matrix(p, ph.start, gens, 0)
    net[:, 2 * n] -= p.b @ np.where(p.friction & (ph.mode != 0), ph.mode * p.tau, 0.0)
    acc, split = fl.g @ net, -fl.reach
    a = np.zeros((dim, dim))
    a[:n, n : 2 * n] = np.eye(n)
    a[n : 2 * n] = acc
    a[2 * n :, 2 * n :] = ph.a[-gens:, -gens:]
    da, dfrow = np.zeros((len(params), dim, dim)), np.zeros((len(params), split.shape[0], dim))
    for j, prm in enumerate(params):
        dnet = _net_derivative(p, ph, prm, dim)
        da[j, n : 2 * n], dfrow[j] = fl.g @ dnet, split @ dnet
        if prm.kind == "mass":
            i = prm.index
            da[j, n : 2 * n] -= np.outer(fl.g[:, i], acc[i])
            dfrow[j] -= np.outer(split[:, i], acc[i])
        elif prm.kind == "omega":  # the generators' block is w times a constant matrix; w = |omega|
            force = p.loads[0][1]
            da[j, 2 * n :, 2 * n :] = math.copysign(1.0, force.omega) * a[2 * n :, 2 * n :] / abs(force.omega)
    return a, da, split @ net, dfrow


def _net_derivative(p: Parts, ph: Phase, prm: Parameter, dim: int) -> np.ndarray:
    """``dN/dp`` (n, dim) at fixed ``Y`` in the phase ``ph`` (module Notes); 0 for the masses, the initial
    state, the frequency and the load's end."""
    n, e = p.m.size, prm.index
    out = np.zeros((n, dim))
    sticks = bool(p.friction[e] and ph.mode[e] == 0) if prm.kind in ("viscosity", "threshold") else False
    if prm.kind == "stiffness":
        out[:, :n] = -np.outer(p.b[:, e], p.b[:, e])
    elif prm.kind == "viscosity" and not sticks:
        out[:, n : 2 * n] = -np.outer(p.b[:, e], p.b[:, e])
    elif prm.kind == "threshold" and p.friction[e] and not sticks:
        out[:, 2 * n] = -ph.mode[e] * p.b[:, e]
    elif prm.kind in ("amplitude", "phase") and load_on(p.loads[0][1], ph.start):
        i, force = p.loads[0]
        out[i, 2 * n :] = _load_derivative(p, force, prm.kind, dim - 2 * n)
    return out


def _load_derivative(p: Parts, force: SineForm, kind: str, gens: int) -> np.ndarray:
    """The derivative of the load's coefficients on the generators (gens,) by its amplitude or phase.

    ``force`` is the load's closed form: a constant's is ``value sin(pi/2)``, whose derivative by its
    ``value`` (the kind ``amplitude``) is ``sin(pi/2) = 1`` exactly."""
    out = np.zeros(gens)
    a, ph = force.amplitude, force.phase
    sin, cos = (math.sin(ph), math.cos(ph)) if kind == "amplitude" else (a * math.cos(ph), -a * math.sin(ph))
    if force.omega == 0:
        out[0] = sin
        return out
    j = 1 + 2 * p.omegas.index(abs(force.omega))
    out[j], out[j + 1] = sin, math.copysign(1.0, force.omega) * cos
    return out
