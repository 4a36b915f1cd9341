"""One phase of a piecewise-linear network: its linear ODE, solved by the matrix exponential.

A network of linear springs, Bingham and Coulomb elements and linear
dashpots (:class:`Parts`) under constant and sine loads is linear while its
*mode* is fixed: each friction element either sticks (``mode 0``: its two
points move together) or slips one way (``mode +-1``: its force is
``+-threshold + w/gamma``).  :func:`phase` merges the points joined by
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

__all__ = ["Parts", "Phase", "groups", "load_matrix", "parts", "phase", "refusal"]

#: What the closed forms of a phase take, for the refusals.
_TAKES = "linear springs, Bingham or Coulomb elements and linear dashpots under sine and constant loads"


class Parts(NamedTuple):
    """A network as arrays: masses ``m`` (n,), incidence ``b`` (n, E: +1 at ``second``, -1 at ``first``,
    the ground has no row), stiffness ``k``, viscosity ``c`` and threshold ``tau`` (E,), ``friction`` (E,)
    the elements that can stick, and the loads as ``(mass, form)``, each load's closed form
    (:class:`~lumped.model.forcing.Forcing`, point 3)."""

    m: np.ndarray
    b: np.ndarray
    k: np.ndarray
    c: np.ndarray
    tau: np.ndarray
    friction: np.ndarray
    loads: tuple[tuple[int, SineForm], ...]
    omegas: tuple[float, ...]


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


def refusal(net: Network, method: str = "exact", *, any_load: bool = False) -> str | None:
    """Why ``method`` cannot run ``net`` phase by phase (one line naming the element or load), or ``None``.

    Every phase must be linear (:func:`linear_parts` of each element) and
    the sticking elements must form a forest (their reactions unique); the
    loads must be sines and constants, whose generators the phase carries,
    unless ``any_load`` (a method that steps the loads as functions of time).
    """
    takes = _TAKES if not any_load else _TAKES.split(" under ")[0]
    if net.drivers:
        return f"method {method!r} cannot run a system with driven points ({listed([d.name for d in net.drivers])})"
    for el in net.elements:
        if linear_parts(el) is None:
            return (
                f"method {method!r} cannot run element {el.name!r} of kind {el.kind!r}: "
                f"its {'closed forms' if not any_load else 'linear steps'} per phase need {takes}"
            )
    for load in net.loads if not any_load else ():
        if closed_form(load.force) is None:
            return f"method {method!r} cannot run the load on {load.on!r}, {kind_of(load.force)}: it runs {_TAKES}"
    index = net.point_index()
    sticking = [((index[el.between[0]], index[el.between[1]]), el) for el in net.elements if el.rigid_capable]
    loop = rigid_loop(index, sticking)
    if loop:
        return (
            f"method {method!r} cannot run elements {listed([el.name for el in loop])}: they close a loop of "
            "elements that can stick together, whose forces are not unique (backward-euler runs it and reports "
            "their admissible intervals)"
        )
    return None


def parts(net: Network, with_loads: bool = True) -> Parts:
    """The arrays of ``net`` (which :func:`refusal` accepts), its loads by their closed forms; without them
    (``with_loads=False``: a method that steps the loads as functions of time, ``any_load``)."""
    n, index = len(net.masses), net.point_index()
    b = np.zeros((n, len(net.elements)))
    k, c, tau = (np.zeros(len(net.elements)) for _ in range(3))
    for e, el in enumerate(net.elements):
        first, second = index[el.between[0]], index[el.between[1]]
        if second < n:
            b[second, e] += 1.0
        if first < n:
            b[first, e] -= 1.0
        k[e], c[e], tau[e] = linear_parts(el)  # type: ignore[misc]
    loads = tuple((index[load.on], closed_form(load.force)) for load in net.loads) if with_loads else ()
    omegas = tuple(sorted({abs(f.omega) for _, f in loads if f.omega != 0}))  # type: ignore[union-attr]
    m = np.array([mass.mass for mass in net.masses])
    return Parts(m, b, k, c, tau, tau > 0, loads, omegas)


def load_on(force: SineForm, t: float) -> bool:
    """True if the load of closed form ``force`` is on just after ``t`` (a phase beginning at ``t`` feels it)."""
    return force.on_after(t)


def switch_times(p: Parts, t_end: float) -> list[float]:
    """The times in ``(0, t_end)`` at which a load comes on or goes off."""
    times = {t for _, f in p.loads for t in f.switch_times}
    return sorted(t for t in times if 0 < t < t_end)


def groups(p: Parts, mode: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``P`` (n, G), the membership of each mass in a free group, and the grounded masses (n,)."""
    n = p.m.size
    sets = UnionFind(n + 1)  # the ground is n
    root = sets.find
    for e in np.flatnonzero(p.friction & (mode == 0)):
        ends = [i for i in range(n) if p.b[i, e] != 0] or [n]
        ends += [n] * (2 - len(ends))  # an element to the ground has one mass row
        sets.union(ends[0], ends[1])
    roots = [root(i) for i in range(n)]
    free = sorted({r for r in roots if r != root(n)})
    member = np.zeros((n, len(free)))
    for i, r in enumerate(roots):
        if r != root(n):
            member[i, free.index(r)] = 1.0
    return member, np.array([r == root(n) for r in roots])


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


def phase(p: Parts, t: float, x: np.ndarray, v: np.ndarray, mode: np.ndarray) -> Phase:
    """The phase of ``mode`` from the state ``(x, v)`` at ``t``.

    The velocity of a group is its masses' momentum over their mass (the
    nearest velocities, in the kinetic metric, on which every sticking
    element's rate is zero).
    """
    n, g = p.m.size, None
    member, grounded = groups(p, mode)
    g = member.shape[1]
    dim = 2 * g + 1 + 2 * len(p.omegas)
    base = 2 * g
    slip = p.friction & (mode != 0)
    stick = p.friction & (mode == 0)
    mr = member.T @ (p.m[:, None] * member)
    bu = p.b.T @ member  # the elements' elongations per unit u, (E, G)
    load = load_matrix(p, t, dim, base)
    # the forces of the elements that do not stick, as rows on z: springs, viscous parts, slip thresholds
    e0 = p.b.T @ x
    free = np.zeros((p.k.size, dim))
    free[:, :g] = p.k[:, None] * bu
    free[:, g : 2 * g] = p.c[:, None] * bu
    free[:, base] = p.k * e0 + np.where(slip, mode * p.tau, 0.0)
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
    return Phase(t, z0, a, out, mode.copy(), grounded, n, gin, feed)
