"""The period map of a piecewise-linear network under a sine load on one mass, and its monodromy matrix.

Under ``P sin(omega t)`` on one mass, the motion over one forcing period
``T = 2 pi/omega`` from the state ``y0 = (x, v)`` of the masses (2n,) is
the ``exact`` network solution (:func:`lumped.solvers.exact_network.march`:
phases of linear motion, events located, modes chosen by
:mod:`lumped.solvers.network_modes`); its end state is the *period map*
``Pi(y0)``.  :func:`network_period_map` gives ``Pi`` with its derivative
``M = dPi/dy0`` (2n x 2n), computed phase by phase from the same phases.

Notes
-----
The derivative is carried as ``D = d(t, y)/dy0`` ((2n + 1) x 2n) at the start
of each phase, ``D = [0; I]`` at ``t = 0`` (notebook 13 derives each rule):

* **a phase** of mode ``mu`` (which friction elements stick, which slip and
  which way) moves the masses by a linear ODE in their full state,
  ``y' = B y + b(t)`` with ``B = [[0, I], [-G K, -G C]]``
  (:func:`mode_flow`): ``K = A diag(k) A^T`` and ``C = A diag(c) A^T`` the
  stiffness and viscosity of the elements that do not stick (``A`` the
  incidence), ``G = S (S^T m S)^-1 S^T`` with ``S`` the membership of the
  masses in the groups that sticking elements join (a group held to the
  ground has no column).  The phase starts from the projection
  ``Q = diag(I, G m)`` of its initial state (a group moves with its
  momentum's velocity), so at a fixed end ``t_b`` the state varies by
  ``dy_b = expm(B h) Q (dy_a - f+ dt_a)``, ``f+`` the phase's own field at its
  start: a later start is the same motion, shifted.
* **an event** at ``t_b`` where the event function ``g = r . y`` (a slipping
  element's rate, or a sticking element's ``tau -+ force``: linear in ``y``,
  with ``t`` through the load) reaches 0 moves with the state:
  ``dt_b = -r . dy_b / g'`` (``g'`` its rate along the flow before it), and
  the state there varies by ``dy_b + f- dt_b``.  With the next phase's
  ``-f+ dt_b`` this is the saltation matrix ``I + (f+ - f-) r^T / (r^T f-)``
  of the switch (``g`` has no explicit time for a stop; for a breakaway the
  two fields agree, the force being the threshold on both sides); at a
  slip-to-stick the next phase's ``Q`` is the projection onto the stuck
  subspace.
* the end ``t = T`` is fixed: ``M`` is the ``y`` rows of ``D`` there.

Two events at one instant (not generic: a symmetric network, or a tie) take
the rule of the first element the solver names; the map is not
differentiable there in any case.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from lumped.model.forcing import SwitchedSine
from lumped.numerics.expm import expm
from lumped.numerics.roots import brentq
from lumped.solvers.exact_network import march, step_for
from lumped.solvers.monodromy import RESOLUTION, held_slip
from lumped.solvers.events import Event
from lumped.solvers.network_modes import event_rows
from lumped.solvers.network_phase import Parts, Phase, groups

__all__ = ["ModeFlow", "NetworkPeriodMap", "event_gradient", "forced_parts", "mode_flow", "network_period_map"]


def forced_parts(p: Parts, mass: int, amplitude: float, omega: float) -> Parts:
    """``p`` with one load, ``amplitude sin(omega t)`` on the mass of index ``mass`` (its own loads dropped)."""
    return p._replace(loads=((mass, SwitchedSine(amplitude, omega).closed_form()),), omegas=(float(omega),))


@dataclass(frozen=True)
class ModeFlow:
    """A mode's linear flow in the masses' full state: ``y' = B y + b(t)`` from ``Q y`` (module Notes), and the
    derivative of the sticking elements' forces, ``d f_stick / dy`` (rows in the order of the elements).

    Its parts, for the parameters' derivatives (:mod:`lumped.solvers.network_sensitivities`): ``g`` is ``G``
    (n x n), ``stiffness`` and ``viscosity`` are ``K`` and ``C`` (n x n), and ``reach`` is
    ``-pinv(A_S) (I - m G)`` (s x n), so that the accelerations are ``G N`` and the sticking forces
    ``-reach N`` for the net force ``N`` on the masses (loads less the forces of the elements that do not stick).
    """

    b: np.ndarray
    q: np.ndarray
    force: np.ndarray
    sticking: np.ndarray
    g: np.ndarray
    stiffness: np.ndarray
    viscosity: np.ndarray
    reach: np.ndarray


def mode_flow(p: Parts, mode: np.ndarray) -> ModeFlow:
    """``B``, ``Q`` and the sticking forces' gradient of ``mode`` (module Notes)."""
    n = p.m.size
    member, _ = groups(p, mode)
    stick = p.friction & (mode == 0)
    g = member @ np.linalg.solve(member.T @ (p.m[:, None] * member), member.T) if member.size else np.zeros((n, n))
    k = p.b @ np.diag(np.where(stick, 0.0, p.k)) @ p.b.T
    c = p.b @ np.diag(np.where(stick, 0.0, p.c)) @ p.b.T
    b = np.block([[np.zeros((n, n)), np.eye(n)], [-g @ k, -g @ c]])
    q = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), g * p.m[None, :]]])
    force, reach = np.zeros((0, 2 * n)), np.zeros((0, n))
    if stick.any():  # f_S = pinv(A_S) (I - m G) (F - A f_free): the reactions of notebook 8's phases
        reach = -np.linalg.pinv(p.b[:, stick]) @ (np.eye(n) - p.m[:, None] * g)
        force = np.hstack([reach @ k, reach @ c])
    return ModeFlow(b, q, force, np.flatnonzero(stick), g, k, c, reach)


@dataclass(frozen=True)
class NetworkPeriodMap:
    """One forcing period of exact network motion from ``y0 = (x, v)`` at ``t = 0``.

    ``end`` is ``y`` at ``t = T`` (2n,: m, m/s); ``monodromy`` its derivative
    with respect to ``y0`` (2n x 2n); ``phases`` and ``events`` the exact
    solution over ``[0, T]``; ``parts`` the network with its load.
    """

    end: np.ndarray
    monodromy: np.ndarray
    phases: tuple[Phase, ...]
    events: tuple[Event, ...]
    parts: Parts
    t_end: float

    @property
    def stops(self) -> int:
        """Slip-to-stick switches in ``(0, T]`` of the friction elements that move (not :attr:`held`): the
        stops per period of a periodic motion (a held element's permanent stick is not a stop)."""
        moving = self.parts.friction.copy()
        moving[self.held] = False
        count = 0
        for before, after in zip(self.phases[:-1], self.phases[1:]):
            count += int(np.sum(moving & (before.mode != 0) & (after.mode == 0)))
        return count

    @cached_property
    def slips(self) -> np.ndarray:
        """The length each element slips over the period (E,, m): the sum over its slip phases of
        ``|b_e . (x_end - x_start)|`` (an element's elongation is monotone within a slip phase)."""
        total = np.zeros(self.parts.k.size)
        for ph, end in zip(self.phases, [*(p.start for p in self.phases[1:]), self.t_end]):
            if np.any(ph.mode != 0):
                moved = self.parts.b.T @ (ph.values(ph.z(end))[0] - ph.values(ph.z0)[0])
                total += np.where(ph.mode != 0, np.abs(moved), 0.0)
        return total

    @cached_property
    def held(self) -> np.ndarray:
        """The friction elements held through the period (indices): those that stick throughout, or slip less
        than the fixed point resolves.  That is :func:`~lumped.solvers.monodromy.held_slip` (the residual
        shooting solves to) times ``|(W^T (M - I) W)^-1|`` in the units ``P/k`` and ``omega_n P/k`` of the loaded
        mass, ``W`` the states that keep the elongations of the elements that stick throughout: the error of a
        fixed point is its residual so amplified, which grows without bound where a mass's motion dies out and
        it comes to be held (the multiplier tends to 1).  A smaller slip (a velocity of round-off size left at
        ``t = 0`` by Newton, or a dying motion's last nanometres) is not resolved: the element is held.  Their
        elongations are kept by the map, each a neutral direction with the multiplier 1 (any elongation in
        the band is periodic)."""
        (mass, load), k = self.parts.loads[0], self.parts.b @ np.diag(self.parts.k) @ self.parts.b.T
        kmm = float(k[mass, mass])
        tol = held_slip(abs(load.amplitude), kmm)
        stuck = self.parts.friction & (self.slips == 0)
        n = self.parts.m.size
        scale = np.repeat([1.0, math.sqrt(kmm / self.parts.m[mass])], n)  # the state in units of (P/k, omega_n P/k)
        w = _keeping(self.parts, np.flatnonzero(stuck))
        free = w.T @ ((self.monodromy - np.eye(2 * n)) * scale[None, :] / scale[:, None]) @ w
        with np.errstate(all="ignore"):
            sv = np.linalg.svd(free, compute_uv=False) if np.all(np.isfinite(free)) else np.array([0.0])
        amplify = 1 / sv[-1] if sv.size and sv[-1] > 0 else math.inf
        return np.flatnonzero(self.parts.friction & (self.slips <= tol * max(1.0, amplify)))

    @cached_property
    def free_basis(self) -> np.ndarray:
        """An orthonormal basis ``W`` (2n x (2n - s)) of the states that leave the held elongations unchanged:
        the map keeps it (``r M = r`` for each held elongation ``r``), and ``W^T M W`` carries the multipliers
        other than the neutral ones."""
        return _keeping(self.parts, self.held)

    @property
    def neutral(self) -> np.ndarray:
        """The held elongations as unit rows on ``y`` (s x 2n)."""
        rows = self.parts.b[:, self.held].T
        rows = rows / np.linalg.norm(rows, axis=1, keepdims=True) if rows.size else rows
        return np.hstack([rows, np.zeros_like(rows)])

    @property
    def multipliers(self) -> np.ndarray:
        """The Floquet multipliers but the neutral ones: eigenvalues of ``W^T M W`` (complex)."""
        w = self.free_basis
        return np.linalg.eigvals(w.T @ self.monodromy @ w)

    @cached_property
    def amplitudes(self) -> np.ndarray:
        """Half of ``max x_i - min x_i`` over the period, per mass (m): the extremes are the phases' ends and
        the zeros of ``v_i`` inside them (bracketed on the event sub-grid, refined by Brent's method)."""
        (hi, _), (lo, _) = self.extremes
        return 0.5 * (hi - lo)

    @cached_property
    def extremes(self) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
        """``((max x_i, its time), (min x_i, its time))`` over the period, per mass ((n,) each; the first
        time where there are several): at a phase's start or end (an event's time, ``0`` or ``T`` exactly) or
        at a zero of ``v_i`` inside a phase."""
        n = self.parts.m.size
        lo, hi = np.full(n, math.inf), np.full(n, -math.inf)
        t_lo, t_hi = np.zeros(n), np.zeros(n)
        for ph, end in zip(self.phases, [*(p.start for p in self.phases[1:]), self.t_end]):
            times, xs = _extremes(ph, end)
            i_hi, i_lo = xs.argmax(axis=0), xs.argmin(axis=0)
            up, down = xs.max(axis=0) > hi, xs.min(axis=0) < lo
            t_hi, t_lo = np.where(up, times[i_hi], t_hi), np.where(down, times[i_lo], t_lo)
            lo, hi = np.minimum(lo, xs.min(axis=0)), np.maximum(hi, xs.max(axis=0))
        return (hi, t_hi), (lo, t_lo)

    @property
    def amplitude(self) -> float:
        """The loaded mass's amplitude (m)."""
        return float(self.amplitudes[self.parts.loads[0][0]])


def _keeping(p: Parts, held: np.ndarray) -> np.ndarray:
    """An orthonormal basis (2n x (2n - s)) of the states that leave the elongations of the elements ``held``
    unchanged."""
    n = p.m.size
    if not held.size:
        return np.eye(2 * n)
    _, sv, vt = np.linalg.svd(p.b[:, held].T)
    wx = vt[int(np.sum(sv > 1e-12 * sv[0])) :].T  # the forest's columns are independent: rank s
    return np.block([[wx, np.zeros((n, n))], [np.zeros((n, wx.shape[1])), np.eye(n)]])


def _extremes(ph: Phase, end: float) -> tuple[np.ndarray, np.ndarray]:
    """Times (k,) and positions (rows, (k, n)) at the phase's sub-grid, its ends and each mass's zeros of
    ``v`` inside it."""
    rx, rv = ph.rows("x"), ph.rows("v")
    if not end > ph.start:  # a phase of no duration (a stop at its start): its one state
        return np.array([ph.start]), (ph.z0 @ rx.T)[None, :]
    h = step_for(ph, end - ph.start)
    times = np.append(np.arange(ph.start, end, h), end)
    step = expm(ph.a * h)
    zs = [ph.z0]
    for t0, t1 in itertools.pairwise(times):
        zs.append(step @ zs[-1] if t1 == t0 + h else expm(ph.a * (t1 - t0)) @ zs[-1])
    z = np.array(zs)
    out, when = [z @ rx.T], [times]
    v = z @ rv.T
    for i, j in zip(*np.nonzero(np.sign(v[:-1]) * np.sign(v[1:]) < 0)):
        vj = lambda s, i=i, j=j: float(rv[j] @ (expm(ph.a * (s - times[i])) @ z[i]))
        if np.sign(vj(times[i])) * np.sign(vj(times[i + 1])) < 0:  # as Brent's method will see them
            at = brentq(vj, times[i], times[i + 1])
            out.append((rx @ (expm(ph.a * (at - times[i])) @ z[i]))[None, :])
            when.append(np.array([at]))
    return np.concatenate(when), np.vstack(out)


def network_period_map(
    p: Parts, mass: int, amplitude: float, omega: float, y0: np.ndarray, names: list[str] | None = None
) -> NetworkPeriodMap:
    """The exact motion of ``p`` over ``T = 2 pi/omega`` under ``amplitude sin(omega t)`` on ``mass`` from ``y0``.

    Parameters
    ----------
    p : Parts
        A network that :func:`~lumped.solvers.network_phase.refusal` accepts (its own loads are dropped).
    mass : int
        The index of the loaded mass.
    amplitude, omega : float
        ``P > 0`` (N) and ``omega > 0`` (rad/s).
    y0 : array of shape (2n,)
        Positions then velocities of the masses at ``t = 0`` (m, m/s).
    names : list of str, optional
        The elements' names, for the events (``e0, e1, ...`` without them).
    """
    if not (amplitude > 0 and math.isfinite(amplitude)):
        raise ValueError(f"force_amplitude must be finite and > 0, got {amplitude!r}")
    if not (omega > 0 and math.isfinite(omega)):
        raise ValueError(f"force_omega must be finite and > 0, got {omega!r}")
    p, n, t_end = forced_parts(p, mass, amplitude, omega), p.m.size, 2 * math.pi / omega
    y0 = np.asarray(y0, dtype=float)
    names = names if names is not None else [f"e{e}" for e in range(p.k.size)]
    phases, events = march(p, y0[:n], y0[n:], t_end, names)
    last = phases[-1].values(phases[-1].z(t_end))
    end = np.concatenate([last[0], last[1]])
    d = np.vstack([np.zeros(2 * n), np.eye(2 * n)])
    for ph, event in zip(phases, [*events, None]):
        d = _through(p, ph, d, event, names, t_end)
    return NetworkPeriodMap(end, d[1:], tuple(phases), tuple(events), p, t_end)


def _field(ph: Phase, z: np.ndarray) -> np.ndarray:
    """``f = (v, acceleration)`` of the masses at the phase's state ``z``."""
    _, v, acc, _ = ph.values(z)
    return np.concatenate([v, acc])


def _through(p: Parts, ph: Phase, d: np.ndarray, event: Event | None, names: list[str], t_end: float) -> np.ndarray:
    """``D`` at the end of the phase ``ph`` (at its event, or at ``t_end``) from ``D`` at its start (module Notes)."""
    flow = mode_flow(p, ph.mode)
    end = t_end if event is None else event.time
    dy = expm(flow.b * (end - ph.start)) @ flow.q @ (d[1:] - np.outer(_field(ph, ph.z0), d[0]))
    if event is None:
        return np.vstack([np.zeros(dy.shape[1]), dy])
    z = ph.z(end)
    _, _, r, rate = event_gradient(p, ph, flow, event, names, z)
    dt = -(r @ dy) / rate
    return np.vstack([dt, dy + np.outer(_field(ph, z), dt)])


def event_gradient(
    p: Parts, ph: Phase, flow: ModeFlow, event: Event, names: list[str], z: np.ndarray
) -> tuple[int, float, np.ndarray, float]:
    """The element ``e`` of ``event`` (its first), the sign ``s``, the event function's gradient ``r`` on the
    masses' state ``y`` (2n,) and its rate ``g'`` along the flow of ``ph`` at its state ``z`` (module Notes):
    a stop's ``g = s w_e`` (``s`` the slip direction), a breakaway's ``g = tau_e - s f_e`` (``s`` the force's sign)."""
    e = names.index(event.elements[0])
    rows, _, what = event_rows(p, ph)
    n = p.m.size
    if event.kind in ("stop", "reversal"):  # the slip's rate reached zero: a stop row
        s = float(ph.mode[e])
        r = np.concatenate([np.zeros(n), ph.mode[e] * p.b[:, e]])
        row = rows[what.index((e, "stop"))]
    else:  # a breakaway: tau - s f_e reached 0, s the force's sign
        s = 1.0 if ph.values(z)[3][e] > 0 else -1.0
        r = -s * flow.force[int(np.flatnonzero(flow.sticking == e)[0])]
        row = rows[what.index((e, "breakaway")) + (0 if s > 0 else 1)]
    return e, s, r, float(row @ (ph.a @ z))
