"""One phase of a piecewise-linear network: its linear ODE, solved by the matrix exponential.

A network of linear springs, Bingham and Coulomb elements and linear
dashpots (:class:`Parts`) under constant and sine loads is linear while its
*mode* is fixed: each friction element either sticks (``mode 0``: its two
points move together, with a force within ``+-threshold``) or slips one way
(``mode +-1``: its force is ``+-threshold + w/gamma``).  So is a friction
contact whose slip curve is one linear piece (:func:`slip_parts`): it sticks
within ``+-static`` and slips with ``+-kinetic + c w``; and a point driven at
a constant velocity ``V`` (its position ``V t``, carried by the ramp
generator ``t - start``; a mass that sticks to it moves with it).  :func:`phase` merges the points joined by
sticking elements into groups, writes the motion of the free groups as

    M_r u'' + C_r u' + K_r u = h + P^T F(t),    x = x_0 + P u,

(``P`` the membership of masses in free groups, ``u`` their displacement
since the phase began) and augments it with the loads' generators (``1``,
``cos omega t``, ``sin omega t``), so that the state ``z`` obeys ``z' = A z``
and ``z(t) = expm(A (t - t_0)) z_0`` exactly (:func:`lumped.numerics.expm.expm`),
whatever the damping, the resonance or the rigid-body modes.  Positions, velocities, accelerations and
every element's force (the sticking ones' reactions from the momentum
balance, unique on a forest of sticking elements) are linear maps of ``z``
(:class:`Phase`).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from lumped.laws.element import Element
from lumped.model.forcing import SineForm, closed_form, kind_of
from lumped.model.network import Network, listed, rigid_loop
from lumped.numerics.expm import expm
from lumped.numerics.union_find import UnionFind

__all__ = [
    "SLIP_TAKES",
    "Parts",
    "Phase",
    "generator_one",
    "groups",
    "load_matrix",
    "parts",
    "phase",
    "refusal",
    "slip_parts",
]

#: What the closed forms of a phase take, for the refusals.
_TAKES = "linear springs, Bingham or Coulomb elements and linear dashpots under sine and constant loads"
#: What ``exact`` takes beyond them (``refusal``'s ``slip``).
SLIP_TAKES = (
    "friction elements with a linear slip curve (no stribeck_velocity) and points driven at a constant velocity"
)


class Parts(NamedTuple):
    """A network as arrays: masses ``m`` (n,), incidence ``b`` (n, E: +1 at ``second``, -1 at ``first``,
    the ground and the driven points have no row), stiffness ``k``, viscosity ``c`` and threshold ``tau``
    (E,: a contact's static force), ``friction`` (E,) the elements that can stick, and the loads as
    ``(mass, form)``, each load's closed form (:class:`~lumped.model.forcing.Forcing`, point 3).

    The driven points (constant velocities only) and the contacts whose sliding force differ from their
    static one add: ``kinetic`` (E,), the tension a slipping element holds at zero rate (``tau`` but for
    such a contact), ``drive`` (E,), the part of each element's rate that its driven points give
    (``+V`` for a driver that is its ``second`` point, ``-V`` for its ``first``), and ``anchor`` (E,), the
    velocity of an element's point that is not a mass (the ground's 0 or a driver's ``V``; ``nan`` for an
    element between two masses).  ``None`` for a network without them (:attr:`slip_force` and
    :attr:`ramp` read them).
    """

    m: np.ndarray
    b: np.ndarray
    k: np.ndarray
    c: np.ndarray
    tau: np.ndarray
    friction: np.ndarray
    loads: tuple[tuple[int, SineForm], ...]
    omegas: tuple[float, ...]
    kinetic: np.ndarray | None = None
    drive: np.ndarray | None = None
    anchor: np.ndarray | None = None

    @property
    def slip_force(self) -> np.ndarray:
        """The tension (N, (E,)) of a slipping element at zero rate: ``kinetic``, else the threshold."""
        return self.tau if self.kinetic is None else self.kinetic

    @property
    def ramp(self) -> bool:
        """True if a phase carries the ramp ``t - start`` among its generators (a point driven at a speed)."""
        return self.drive is not None


def linear_parts(el: Element) -> tuple[float, float, float] | None:
    """``(stiffness, viscosity, threshold)`` of a linear spring, or of a dashpot whose law is Bingham's graph
    (a Bingham, Coulomb or linear dashpot, by the element's contract: ``linear_stiffness``, its
    ``one_mass_law()`` and that law's ``bingham_form()``, a Herschel-Bulkley law of exponent 1 included); else ``None``."""
    if el.linear_stiffness is not None:
        return el.linear_stiffness, 0.0, 0.0
    law = el.one_mass_law()
    if law is None:
        return None
    form = law.bingham_form()
    if form is not None:
        return 0.0, form.viscosity, form.threshold
    return None


def slip_parts(el: Element) -> tuple[float, float, float, float] | None:
    """``(stiffness, viscosity, static, kinetic)`` of an element whose phases are linear: those of
    :func:`linear_parts` (``kinetic`` the threshold), or a friction contact whose slip curve is one
    linear piece ``g(s) = kinetic + viscosity s`` (its law's ``pieces()``, point 5 of
    :class:`~lumped.laws.SlipLaw`, with ``static`` its stick bound); else ``None``."""
    found = linear_parts(el)
    if found is not None:
        return (*found, found[2])
    law = el.slip_law()
    pieces = law.pieces() if law is not None else None
    if pieces is None or len(pieces) != 1:
        return None
    return 0.0, pieces[0].b, law.static, pieces[0].a


def refusal(net: Network, method: str = "exact", *, any_load: bool = False, slip: bool = False) -> str | None:
    """Why ``method`` cannot run ``net`` phase by phase (one line naming the element or load), or ``None``.

    Every phase must be linear (:func:`linear_parts` of each element) and
    the sticking elements must form a forest (their reactions unique); the
    loads must be sines and constants, whose generators the phase carries,
    unless ``any_load`` (a method that steps the loads as functions of time).  With ``slip`` (the
    ``exact`` method), friction contacts whose slip curve is linear (:func:`slip_parts`) and points
    driven at a constant velocity are run too.
    """
    takes = _TAKES if not any_load else _TAKES.split(" under ")[0]
    if slip:
        takes = takes.replace(" under ", f", {SLIP_TAKES} under ")
    if (reason := _driver_refusal(net, method, slip)) is not None:
        return reason
    for el in net.elements:
        if (linear_parts(el) if not slip else slip_parts(el)) is None:
            if slip and (law := el.slip_law()) is not None:
                shape = "it falls with speed" if law.fall > 0 else "it is curved"
                return (
                    f"method {method!r} cannot run element {el.name!r} of kind {el.kind!r}: its slip curve is not "
                    f"linear ({shape}), and the closed forms per phase need a linear one"
                )
            return (
                f"method {method!r} cannot run element {el.name!r} of kind {el.kind!r}: "
                f"its {'closed forms' if not any_load else 'linear steps'} per phase need {takes}"
            )
    for load in net.loads if not any_load else ():
        if closed_form(load.force) is None:
            return f"method {method!r} cannot run the load on {load.on!r}, {kind_of(load.force)}: it runs {_TAKES}"
    index = _anchored_points(net)
    sticking = [((index[el.between[0]], index[el.between[1]]), el) for el in net.elements if el.rigid_capable]
    loop = rigid_loop(index, sticking)
    if loop:
        return (
            f"method {method!r} cannot run elements {listed([el.name for el in loop])}: they close a loop of "
            "elements that can stick together, whose forces are not unique (backward-euler runs it and reports "
            "their admissible intervals)"
        )
    return None


def _driver_refusal(net: Network, method: str, slip: bool) -> str | None:
    """Why ``method`` cannot run the driven points of ``net`` (one line naming them), or ``None``."""
    if net.drivers and not slip:
        return f"method {method!r} cannot run a system with driven points ({listed([d.name for d in net.drivers])})"
    for d in net.drivers:
        if d.constant_velocity is None:
            return (
                f"method {method!r} cannot run driver {d.name!r}: its velocity is {d.history.description}, "
                "and the closed forms per phase need a constant velocity given as a number (m/s)"
            )
    return None


def _anchored_points(net: Network) -> dict[str, int]:
    """Point name -> node, as :meth:`~lumped.model.network.Network.point_index` but with each driven
    point's velocity its own node (the ground's for 0): a contact that sticks to a belt and one that
    sticks to the ground hold a mass to different motions, so they never stick together."""
    index = net.point_index()
    speeds = sorted({d.constant_velocity for d in net.drivers} - {0.0})
    for d in net.drivers:
        if d.constant_velocity:
            index[d.name] = len(net.masses) + 1 + speeds.index(d.constant_velocity)
    return index


def parts(net: Network, with_loads: bool = True) -> Parts:
    """The arrays of ``net`` (which :func:`refusal` accepts), its loads by their closed forms; without them
    (``with_loads=False``: a method that steps the loads as functions of time, ``any_load``)."""
    n, index = len(net.masses), net.point_index()
    b = np.zeros((n, len(net.elements)))
    k, c, tau, kinetic = (np.zeros(len(net.elements)) for _ in range(4))
    for e, el in enumerate(net.elements):
        first, second = index[el.between[0]], index[el.between[1]]
        if second < n:
            b[second, e] += 1.0
        if first < n:
            b[first, e] -= 1.0
        k[e], c[e], tau[e], kinetic[e] = slip_parts(el)  # type: ignore[misc]
    loads = tuple((index[load.on], closed_form(load.force)) for load in net.loads) if with_loads else ()
    omegas = tuple(sorted({abs(f.omega) for _, f in loads if f.omega != 0}))  # type: ignore[union-attr]
    m = np.array([mass.mass for mass in net.masses])
    p = Parts(m, b, k, c, tau, tau > 0, loads, omegas)
    if np.array_equal(kinetic, tau) and not net.drivers:
        return p
    return p._replace(kinetic=kinetic, **(_driven_parts(net, b) if net.drivers else {}))


def _driven_parts(net: Network, b: np.ndarray) -> dict[str, np.ndarray]:
    """``drive`` and ``anchor`` of :class:`Parts` for a network with points driven at constant velocities."""
    drive = np.zeros(b.shape[1])
    anchor = np.where(np.count_nonzero(b, axis=0) == 1, 0.0, math.nan)
    for d in net.driven():
        speed = net.drivers[d.driver].constant_velocity
        drive[d.element] += d.sign * speed
        anchor[d.element] = speed
    return {"drive": drive, "anchor": anchor}


def load_on(force: SineForm, t: float) -> bool:
    """True if the load of closed form ``force`` is on just after ``t`` (a phase beginning at ``t`` feels it)."""
    return force.on_after(t)


def switch_times(p: Parts, t_end: float) -> list[float]:
    """The times in ``(0, t_end)`` at which a load comes on or goes off."""
    times = {t for _, f in p.loads for t in f.switch_times}
    return sorted(t for t in times if 0 < t < t_end)


def groups(p: Parts, mode: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``P`` (n, G), the membership of each mass in a free group, and the grounded masses (n,)."""
    member, carried = _groups(p, mode)
    return member, carried == 0


def _groups(p: Parts, mode: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``P`` (n, G), the membership of each mass in a free group, and the velocity (m/s, (n,)) of each
    mass that sticking elements hold to the ground (0) or to a driven point (its ``V``), ``nan`` for a
    mass of a free group.

    The ground and each driven velocity are nodes of their own (after the masses); a mode that would
    hold a group to two of them is inconsistent (its sticking elements could not all have rate 0)."""
    n = p.m.size
    speeds = [0.0] if p.anchor is None else sorted({0.0} | {float(a) for a in p.anchor[~np.isnan(p.anchor)]})
    sets = UnionFind(n + len(speeds))  # the ground is n
    root = sets.find
    for e in np.flatnonzero(p.friction & (mode == 0)):
        ends = [i for i in range(n) if p.b[i, e] != 0] or [n]
        anchor = n if p.anchor is None or len(ends) != 1 else n + speeds.index(float(p.anchor[e]))
        ends += [anchor] * (2 - len(ends))  # an element to the ground (or a driver) has one mass row
        sets.union(ends[0], ends[1])
    held = {root(n + j): speed for j, speed in enumerate(speeds)}
    if len(held) < len(speeds):
        raise ArithmeticError(f"a mode holds masses to points moving at different speeds ({speeds} m/s)")
    roots = [root(i) for i in range(n)]
    free = sorted({r for r in roots if r not in held})
    member = np.zeros((n, len(free)))
    for i, r in enumerate(roots):
        if r not in held:
            member[i, free.index(r)] = 1.0
    return member, np.array([held.get(r, math.nan) for r in roots])


class Phase(NamedTuple):
    """A phase from ``start``: ``z(t) = expm(a (t - start)) z0``; ``out @ z`` is ``(x, v, acceleration, forces)``.

    A further load ``F`` (n,) on the masses, beyond the parts' own, enters
    linearly: ``z' = a z + gin F`` and ``(x, v, acceleration, forces) = out z
    + feed F`` (the event-locating method steps its loads this way).
    """

    start: float
    z0: np.ndarray
    a: np.ndarray
    out: np.ndarray
    mode: np.ndarray
    grounded: np.ndarray
    n: int
    gin: np.ndarray
    feed: np.ndarray

    def z(self, t: float) -> np.ndarray:
        return expm(self.a * (t - self.start)) @ self.z0

    def values(self, z: np.ndarray, load: np.ndarray | None = None) -> tuple[np.ndarray, ...]:
        """Positions, velocities, accelerations (n,) and element forces (E,) at the state ``z``
        (with the further load ``load`` on the masses, if given)."""
        y, n = self.out @ z, self.n
        if load is not None:
            y = y + self.feed @ load
        return y[:n], y[n : 2 * n], y[2 * n : 3 * n], y[3 * n :]

    def rows(self, what: str) -> np.ndarray:
        """The rows of ``out`` for ``"x"``, ``"v"``, ``"a"`` or ``"f"``."""
        n = self.n
        return {"x": self.out[:n], "v": self.out[n : 2 * n], "a": self.out[2 * n : 3 * n], "f": self.out[3 * n :]}[what]


def load_matrix(p: Parts, t: float, dim: int, base: int) -> np.ndarray:
    """``F(t) = L @ z`` (n, dim) for the loads on just after ``t``; generators from column ``base``."""
    out = np.zeros((p.m.size, dim))
    for i, f in p.loads:
        if not load_on(f, t):
            continue
        if f.omega == 0:  # a constant's form, A sin(pi/2) = A exactly
            out[i, base] += f.amplitude * math.sin(f.phase)
        else:  # A sin(w t + phi) = A sin(phi) cos(w t) + A cos(phi) sin(w t), with w = |omega|
            w, sign = abs(f.omega), math.copysign(1.0, f.omega)
            j = base + 1 + 2 * p.omegas.index(w)
            out[i, j] += f.amplitude * math.sin(f.phase)
            out[i, j + 1] += sign * f.amplitude * math.cos(f.phase)
    return out


def generator_one(p: Parts, dim: int) -> int:
    """The column of the generator ``1`` in a phase's state of size ``dim`` (after ``u`` and ``u'``; the
    sines' pairs, then the ramp, if any, follow it)."""
    return dim - 1 - 2 * len(p.omegas) - int(p.ramp)


def phase(p: Parts, t: float, x: np.ndarray, v: np.ndarray, mode: np.ndarray) -> Phase:
    """The phase of ``mode`` from the state ``(x, v)`` at ``t``.

    The velocity of a group is its masses' momentum over their mass (the
    nearest velocities, in the kinetic metric, on which every sticking
    element's rate is zero).  A mass held to a driven point moves with it,
    ``x(t) = x(start) + V (t - start)``: the ramp ``t - start``, the last
    generator (``ramp' = 1``), carries it, and the elongation of every element
    joined to a driven point (:attr:`Parts.drive`).
    """
    n = p.m.size
    member, held = _groups(p, mode)
    carried = np.nan_to_num(held)  # the velocities of the held masses, 0 for the free ones
    g = member.shape[1]
    dim = 2 * g + 1 + 2 * len(p.omegas) + int(p.ramp)
    base = 2 * g
    slip = p.friction & (mode != 0)
    stick = p.friction & (mode == 0)
    mr = member.T @ (p.m[:, None] * member)
    bu = p.b.T @ member  # the elements' elongations per unit u, (E, G)
    load = load_matrix(p, t, dim, base)
    # the forces of the elements that do not stick, as rows on z: springs, viscous parts, slip forces
    e0 = p.b.T @ x
    free = np.zeros((p.k.size, dim))
    free[:, :g] = p.k[:, None] * bu
    free[:, g : 2 * g] = p.c[:, None] * bu
    free[:, base] = p.k * e0 + np.where(slip, mode * p.slip_force, 0.0)
    if p.ramp:  # the rate that held masses and driven points give each element: (b^T V_held + drive)
        shift = p.b.T @ carried + p.drive
        free[:, base] += p.k * p.drive * t + p.c * shift
        free[:, -1] = p.k * shift
    free[stick] = 0.0
    acc_u = np.linalg.solve(mr, member.T @ (load - p.b @ free)) if g else np.zeros((0, dim))
    a = np.zeros((dim, dim))
    a[:g, g : 2 * g] = np.eye(g)
    a[g : 2 * g] = acc_u
    for j, w in enumerate(p.omegas):  # (cos w t, sin w t)' = w (-sin, cos)
        c, s = base + 1 + 2 * j, base + 2 + 2 * j
        a[c, s], a[s, c] = -w, w
    z0 = np.zeros(dim)
    z0[g : 2 * g] = (member.T @ (p.m * v)) / np.diag(mr) if g else 0.0
    z0[base] = 1.0
    for j, w in enumerate(p.omegas):
        z0[base + 1 + 2 * j], z0[base + 2 + 2 * j] = math.cos(w * t), math.sin(w * t)
    xs = np.zeros((n, dim))
    xs[:, :g], xs[:, base] = member, x
    vs = np.zeros((n, dim))
    vs[:, g : 2 * g] = member
    if p.ramp:  # ramp' = 1 (z0 = 0: the ramp starts at the phase's start)
        a[-1, base] = 1.0
        xs[:, -1] = vs[:, base] = carried
    acc = member @ acc_u
    gin = np.zeros((dim, n))  # a further load F: u'' gains Mr^-1 P^T F
    gin[g : 2 * g] = np.linalg.solve(mr, member.T) if g else 0.0
    acc_in = member @ gin[g : 2 * g]
    forces, f_in = free.copy(), np.zeros((p.k.size, n))
    if stick.any():  # B_S f_S = F - B f_free - M a: consistent, with one solution on a forest
        split = np.linalg.pinv(p.b[:, stick])
        forces[stick] = split @ (load - p.b @ free - p.m[:, None] * acc)
        f_in[stick] = split @ (np.eye(n) - p.m[:, None] * acc_in)
    out = np.vstack([xs, vs, acc, forces])
    feed = np.vstack([np.zeros((2 * n, n)), acc_in, f_in])
    return Phase(t, z0, a, out, mode.copy(), held == 0, n, gin, feed)
