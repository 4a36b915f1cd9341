"""Steady sliding of one mass on a belt: the equilibrium, the eigenvalues of its linearisation, its Hopf points.

The systems are those of :mod:`lumped.solvers.event_driven_network` with no
load: one mass ``m`` held by linear springs (of total stiffness ``K > 0``) to
points at rest, linear dashpots to the ground or to driven points at constant
velocities ``V_i``, and one friction contact (any
:class:`lumped.laws.SlipLaw`, slip curve ``g``) on a driven point moving at
``V != 0`` (the *belt*).  In *steady sliding* the mass is at rest and the
contact slips at ``-V``; its force on the mass is ``sgn(V) g(|V|)``, so

    x* = (sum_i c_i V_i + sgn(V) g(|V|)) / K.

About it, ``x = x* + xi`` obeys (the contact's tension ``T(u) = sgn(u) g(|u|)``
is odd, so ``T'(u) = g'(|u|)`` on both sides)

    m xi'' + c_eff xi' + K xi = 0,      c_eff = C + g'(|V|),

``C`` the dashpots' sum: the eigenvalues are ``(-c_eff +- sqrt(c_eff^2 - 4 m
K)) / (2 m)``.  Steady sliding is stable where ``c_eff > 0`` and a pair
crosses the imaginary axis at ``+-i sqrt(K/m)`` where ``c_eff`` changes sign:
a *Hopf point* (Veraszto and Stepan, Int. J. Non-Linear Mech. 2017: with
``g(s) = C + (C0 - C) exp(-c_v s) + b_s s`` and a dashpot ``b0`` to the
ground, ``V_H = ln((C0 - C) c_v / (b0 + b_s)) / c_v``).  The slope ``g'`` is the
law's (:meth:`lumped.laws.SlipLaw.slope`: exact for a Stribeck law or linear
pieces, a central difference with its error bound for a
:class:`~lumped.laws.SlipCurve`), and its error bound decides what is
vouched for: a ``c_eff`` within it of 0 is *not* stable.

A linear dashpot to the belt in place of the contact is steady sliding too,
with ``c_eff = C``: :func:`steady_sliding` gives its equilibrium, and
:func:`check_autonomous`, the boundary of ``cycles``, refuses it (no falling
law: it cannot lose stability, so it has no cycle), quoting its eigenvalues.
"""

from __future__ import annotations

import math
from itertools import pairwise
from typing import NamedTuple

import numpy as np

from lumped.laws.contract import Slope
from lumped.model.forcing import kind_of
from lumped.model.network import Network, listed
from lumped.model.system_parameters import SystemParameter, system_parameters, with_values
from lumped.numerics.roots import brentq
from lumped.solvers.event_driven_network import Contact, Link, classify

__all__ = [
    "HOPF_RTOL",
    "HOPF_SAMPLES",
    "Equilibrium",
    "belt_sign",
    "check_autonomous",
    "hopf_points",
    "mirror_equilibrium",
    "mirrored",
    "steady_sliding",
]

#: What ``cycles`` runs, in words (the refusals).
SCOPE = (
    "one mass on linear springs to points at rest and linear dashpots, sliding on one friction contact "
    "on a driven point at a constant velocity, with no load"
)
#: The relative tolerance to which a Hopf point is located (Brent's method on ``c_eff``).
HOPF_RTOL = 1e-12
#: The samples of ``c_eff`` over a range, evenly spaced, whose sign changes bracket the Hopf points: two
#: crossings closer than ``(stop - start) / (HOPF_SAMPLES - 1)`` may pair up unseen.
HOPF_SAMPLES = 257
_EPS = float(np.finfo(float).eps)


class Equilibrium(NamedTuple):
    """Steady sliding: ``position`` (``(masses,)`` m), the elements' ``forces`` (``(elements,)`` N, as a
    :class:`~lumped.model.trajectory.Trajectory` signs them), the ``eigenvalues`` of the linearisation
    (complex, ``(2 masses,)``, 1/s), ``max_real_part`` (1/s) and ``stable`` (``max_real_part < 0`` by more than
    its error bound, that of the slip curve's slope)."""

    position: np.ndarray
    forces: np.ndarray
    eigenvalues: np.ndarray
    max_real_part: float
    stable: bool


class _Sliding(NamedTuple):
    """The parts of a system in scope: the mass, the springs, the dashpots and the contact (or ``None``)."""

    m: float
    springs: list[Link]
    dashpots: list[Link]
    contact: Contact | None


def _refuse(reason: str) -> ValueError:
    return ValueError(f"cycles: {reason}")


def _sliding(network: Network) -> _Sliding:
    """The parts of ``network`` if steady sliding exists in it (module docstring), else a one-line ``ValueError``."""
    if not isinstance(network, Network):
        got = type(network).__name__
        raise ValueError(f"network must be a Network (a system file read by load_system), got {got}")  # noqa: TRY004 (the API's one error type)
    n = len(network.masses)
    if n != 1:
        raise _refuse(f"the system has {n} masses; cycles runs {SCOPE}")
    if network.loads:
        raise _refuse(f"the system has a load on {network.loads[0].on!r}; cycles runs self-excited motions: {SCOPE}")
    for d in network.drivers:
        if d.constant_velocity is None:
            raise _refuse(
                f"driver {d.name!r} has {kind_of(d.velocity)}; cycles runs driven points at a constant velocity"
            )
    springs, dashpots, contacts, bad = classify(network)
    if bad is not None:
        el = network.elements[bad]
        raise _refuse(f"element {el.name!r} of kind {el.kind!r} is not one cycles runs: {SCOPE}")
    if len(contacts) > 1:
        names = [network.elements[c.link.element].name for c in contacts]
        raise _refuse(f"the system has {len(contacts)} friction contacts ({listed(names)}); cycles runs {SCOPE}")
    moving = [s for s in springs if s.velocity != 0]
    if moving:
        el = network.elements[moving[0].element]
        raise _refuse(f"spring {el.name!r} pulls the mass from a moving point, so the mass has no rest: {SCOPE}")
    if not sum(s.coefficient for s in springs) > 0:
        raise _refuse(f"no spring holds the mass, so steady sliding has no position: cycles runs {SCOPE}")
    if not network.drivers:
        raise _refuse(f"no driven point: the system has no [[driver]] for a contact to slide on; cycles runs {SCOPE}")
    if contacts and contacts[0].link.velocity == 0:
        el = network.elements[contacts[0].link.element]
        raise _refuse(f"the friction contact {el.name!r} is on a point at rest (no driven point slides on it): {SCOPE}")
    if not any(link.velocity != 0 for link in [c.link for c in contacts] + dashpots):
        raise _refuse(f"no driven point: no contact or dashpot of the system is on a moving point; cycles runs {SCOPE}")
    return _Sliding(network.masses[0].mass, springs, dashpots, contacts[0] if contacts else None)


def _slope(network: Network, contact: Contact) -> Slope:
    """The contact's slip curve's slope at the belt's speed ``|V|`` (a Bingham element's: its viscosity, exact)."""
    el = network.elements[contact.link.element]
    law = el.slip_law()
    if law is None:
        return Slope(el.one_mass_law().bingham_form().viscosity, 0.0)  # type: ignore[union-attr]
    return law.slope(abs(contact.link.velocity))


def _damping(network: Network, parts: _Sliding) -> Slope:
    """``c_eff = C + g'(|V|)`` (N s/m) and its error bound: the slope's, and the rounding of the sum."""
    C = sum(d.coefficient for d in parts.dashpots)
    slope = Slope(0.0, 0.0) if parts.contact is None else _slope(network, parts.contact)
    value = C + slope.value
    return Slope(value, slope.error + 4 * _EPS * (C + abs(slope.value)))


def steady_sliding(network: Network) -> Equilibrium:
    """Steady sliding of ``network`` and the eigenvalues of its linearisation (the module docstring).

    Raises
    ------
    ValueError
        One line beginning ``cycles:``: a system outside the scope (more masses, a load, a driven point that is
        not at a constant velocity, an element other than a linear spring, a linear dashpot or one friction
        contact, a spring to a moving point, no spring, no driven point, a contact on a point at rest).
    """
    parts = _sliding(network)
    K = sum(s.coefficient for s in parts.springs)
    push = sum(d.coefficient * d.velocity for d in parts.dashpots)  # the dashpots' force on the mass at rest
    contact = parts.contact
    pull = 0.0 if contact is None else math.copysign(contact.g(abs(contact.link.velocity)), contact.link.velocity)
    x = (push + pull) / K
    forces = np.zeros(len(network.elements))
    for s in parts.springs:
        forces[s.element] = s.coefficient * s.orientation * x
    for d in parts.dashpots:
        forces[d.element] = d.coefficient * d.orientation * (0.0 - d.velocity)
    if contact is not None:
        forces[contact.link.element] = contact.link.orientation * -pull
    c = _damping(network, parts)
    eigenvalues = _eigenvalues(parts.m, c.value, K)
    return Equilibrium(np.array([x]), forces, eigenvalues, float(eigenvalues.real.max()) + 0.0, c.value > c.error)


def _eigenvalues(m: float, c: float, k: float) -> np.ndarray:
    """The roots of ``m s^2 + c s + k`` (``k > 0``), the larger real part first; a real pair without cancellation
    (the larger in modulus by the quadratic formula, the other as ``k / (m root)``)."""
    disc = c * c - 4 * m * k
    if disc < 0:
        re, im = -c / (2 * m), math.sqrt(-disc) / (2 * m)
        return np.array([complex(re, im), complex(re, -im)])
    big = -(c + math.copysign(math.sqrt(disc), c)) / (2 * m)
    small = k / (m * big)
    return np.array(sorted((big, small), reverse=True), dtype=complex)


def check_autonomous(network: Network) -> None:
    """The boundary of ``cycles``: ``network`` is in scope and its steady sliding can lose stability.

    Raises
    ------
    ValueError
        One line beginning ``cycles:``: what :func:`steady_sliding` refuses; no friction contact; or no falling
        law (a slip curve that starts at ``static`` and never falls, or a linear dashpot for a contact): steady
        sliding is then stable or neutral at every speed and has no cycle, and the message gives its
        eigenvalues.
    """
    parts = _sliding(network)
    contact = parts.contact
    if contact is not None:
        law = network.elements[contact.link.element].slip_law()
        if law is not None and (law.fall > 0 or law.static > law.slip_limit):
            return
        what = f"the friction contact {network.elements[contact.link.element].name!r} starts at static and never falls"
    else:
        moving = next(d for d in parts.dashpots if d.velocity != 0)  # _sliding found one
        what = f"the dashpot {network.elements[moving.element].name!r} on the moving point is linear"
    eq = steady_sliding(network)
    top = eq.eigenvalues[0]
    roots = " and ".join(f"{z + 0.0:.6g}" for z in eq.eigenvalues.real)  # + 0.0: no "-0"
    if top.imag:
        roots = f"{top.real + 0.0:.6g} +- {top.imag:.6g}i"
    raise _refuse(
        f"no falling law: {what}, so steady sliding at x = {eq.position[0]:.6g} m (eigenvalues {roots} 1/s) "
        "cannot lose stability and there is no cycle"
    )


def belt_sign(network: Network) -> int:
    """``+1`` or ``-1``: the sign of the belt's speed ``V`` (the velocity of the contact's other point) in a
    system in scope (:func:`check_autonomous`)."""
    contact = _sliding(network).contact
    speed = contact.link.velocity if contact is not None else 1.0
    return 1 if speed > 0 else -1


def mirrored(network: Network) -> Network:
    """``network`` seen in the mirror ``x -> -x``: every driven point's velocity and each mass's ``x0`` and ``v0``
    negated.

    The systems in scope are symmetric under it: the springs pull towards points at rest at 0, a dashpot's force
    ``-c (x' - V_i)`` and the contact's odd tension ``sgn(u) g(|u|)`` change sign with every velocity, so a motion
    ``x(t)`` of ``network`` is ``-x(t)`` of its mirror, steady sliding at ``x*`` is at ``-x*`` with the same
    eigenvalues, and a cycle keeps its period, stick time and multipliers with its extremes swapped and negated.
    ``cycles`` computes a belt running backwards (``V < 0``) as its mirror, whose belt runs forwards, where the
    section's crossing and a stuck cycle's speed there (``V``) are those of :mod:`~lumped.drivers.cycles.shooting`.
    """
    names = [f"{d.name}.velocity" for d in network.drivers if d.constant_velocity is not None]
    names += [f"{m.name}.{key}" for m in network.masses for key in ("x0", "v0")]
    params = system_parameters(network, names)
    return with_values(network, params, [-p.value for p in params])


def mirror_equilibrium(eq: Equilibrium) -> Equilibrium:
    """The equilibrium of the mirrored system (:func:`mirrored`): position and forces negated."""
    return eq._replace(position=-eq.position, forces=-eq.forces)


def parameter_member(network: Network, parameter: str, start: float, stop: float) -> tuple[SystemParameter, list]:
    """The parameter called ``parameter`` and the systems at ``start`` and ``stop``, checked (``vary: ...``): a
    driven point's velocity whose range reaches 0 (where its contact stops sliding) is refused."""
    (param,) = system_parameters(network, [parameter], "vary")
    ends = []
    for value in (start, stop):
        try:
            member = with_values(network, [param], [value])
            _sliding(member)
        except ValueError as err:
            raise ValueError(f"vary: at {parameter} = {value:g}: {str(err).removeprefix('cycles: ')}") from None
        ends.append(member)
    if param.table == "driver" and start <= 0 <= stop:
        raise ValueError(f"vary: {parameter} = {start:g}:{stop:g} reaches 0, where the belt stops; keep it to one side")
    return param, ends


def hopf_points(network: Network, parameter: str, start: float, stop: float) -> list[float]:
    """The values of ``parameter`` in ``[start, stop]`` where a pair of eigenvalues of steady sliding crosses the
    imaginary axis: the sign changes of ``c_eff`` over :data:`HOPF_SAMPLES` samples, each located by Brent's
    method to :data:`HOPF_RTOL` relative (and to a few ulps where ``c_eff`` is exact).  A sample where ``c_eff``
    is within its error bound of 0 has no sign: a change across such samples is one crossing, an end within it
    next to a sample of known sign is one, and a ``c_eff`` within it of 0 throughout (a neutral centre, the
    static/kinetic belt without viscous parts) has none.

    Raises
    ------
    ValueError
        One line: ``start < stop`` not finite, a parameter the file lacks or a value it refuses at either end
        (``vary: ...``), a system out of scope (``cycles: ...``).
    """
    start, stop = float(start), float(stop)
    if not (math.isfinite(start) and math.isfinite(stop) and start < stop):
        raise ValueError(f"vary: START:STOP must be finite with START < STOP, got {start!r}:{stop!r}")
    param, _ = parameter_member(network, parameter, start, stop)

    def damping(value: float) -> Slope:
        member = with_values(network, [param], [value])
        return _damping(member, _sliding(member))

    grid = [float(p) for p in np.linspace(start, stop, HOPF_SAMPLES)]
    values = []
    for p in grid:  # c_eff, or 0 where it is within its error bound of 0 (its sign unknown)
        c = damping(p)
        values.append(c.value if abs(c.value) > c.error else 0.0)
    known = [(p, v) for p, v in zip(grid, values) if v != 0]
    points = [
        brentq(lambda p: damping(p).value, a, b, xtol=HOPF_RTOL * max(abs(a), abs(b)), rtol=HOPF_RTOL)
        for (a, fa), (b, fb) in pairwise(known)  # the samples between them: within the error of 0
        if fa * fb < 0
    ]
    points += [grid[i] for i, j in ((0, 1), (-1, -2)) if values[i] == 0 and values[j] != 0]  # on an end
    return sorted(points)
