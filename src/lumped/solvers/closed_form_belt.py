"""The closed-form stick-slip cycle of a block on a moving belt: the one home of its formulas.

A block of mass ``m`` on a spring ``k`` to the ground rides a belt moving at
a constant ``V > 0`` through a friction contact whose static force ``S`` is
at least its kinetic force ``K`` (no viscous part, no Stribeck velocity).
Its limit cycle has a closed form (:func:`belt_cycle`), which the tests of
the ``exact`` and ``backward-euler`` methods and notebook 15 meet; nothing
else derives it.  Its slip phase, a harmonic motion whose stop (the block back
at the belt's speed) has a closed form, is :class:`HarmonicSlip`: the phase the
cycles' return map (:mod:`lumped.drivers.cycles.shooting`) runs where the slip
is undamped and the slip curve flat.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from lumped.numerics import validate

__all__ = ["BeltCycle", "HarmonicSlip", "belt_cycle"]

#: Samples of :attr:`HarmonicSlip.steps` per period ``2 pi/omega``.
HARMONIC_SAMPLES = 64


class BeltCycle(NamedTuple):
    """The stick-slip limit cycle of :func:`belt_cycle` (positions from the spring's unstretched length)."""

    #: The cycle's period (s): ``stick_time + slip_time``.
    period: float
    #: How long the block rides the belt in each cycle (s).
    stick_time: float
    #: How long it slips in each cycle (s).
    slip_time: float
    #: The largest position (m), reached while slipping.
    x_max: float
    #: The smallest position (m), reached while slipping.
    x_min: float
    #: The smallest velocity (m/s), reached while slipping (negative: the block moves back).
    v_min: float
    #: Where the block breaks away from the belt, ``S/k`` (m).
    break_position: float
    #: Where it sticks to the belt again, ``(2K - S)/k`` (m).
    stick_position: float


def belt_cycle(mass: float, stiffness: float, static: float, kinetic: float, velocity: float) -> BeltCycle:
    """The stick-slip limit cycle of a block on a spring, riding a belt through static/kinetic friction.

    Parameters
    ----------
    mass : float, kg
        ``m > 0``.
    stiffness : float, N/m
        ``k > 0``, the spring from the ground to the block.
    static : float, N
        ``S > 0``, the largest force the stuck contact holds.
    kinetic : float, N
        ``K``, the sliding force, ``0 <= K <= S``.
    velocity : float, m/s
        ``V > 0``, the belt's speed.

    Returns
    -------
    BeltCycle

    Raises
    ------
    ValueError
        For a parameter out of its range (named).

    Notes
    -----
    With ``x`` the block's position (the spring's elongation), the contact
    joins the belt to the block, so its rate is ``x' - V`` and the block
    feels ``m x'' = -k x - T`` with ``T`` the contact's tension.

    *Stick.*  The block moves with the belt, ``x' = V``, and the contact
    holds ``T = -k x`` while ``|k x| <= S``: the spring loads at the belt's
    speed until ``x = S/k`` (``break_position``), where the contact breaks
    away.

    *Slip.*  The block is slower than the belt (the rate ``x' - V`` turns
    negative, because ``m x'' = -k x + K < 0`` at ``x = S/k`` when
    ``S > K``), so ``T = -K`` and ``m x'' = -k x + K``: a harmonic motion
    about ``K/k`` at ``omega = sqrt(k/m)``.  With ``y = x - K/k`` it keeps
    ``y^2 + (x'/omega)^2 = R^2``, from ``y_0 = (S - K)/k`` and ``x' = V``:

        R = sqrt(y_0^2 + (V/omega)^2).

    In the plane ``(y, x'/omega)`` the point turns clockwise on that circle
    from the angle ``theta_0 = atan2(V/omega, y_0)`` (in ``(0, pi/2]``).  The
    rate ``x' - V`` is back at zero where ``x' = V`` again, at ``y = -y_0``
    (angle ``pi - theta_0``); on the way the point passes the angles ``0``
    (``x_max = K/k + R``), ``-pi/2`` (``v_min = -omega R``) and ``-pi``
    (``x_min = K/k - R``).  The angle swept is ``pi + 2 theta_0``, so

        slip_time = (pi + 2 theta_0) / omega.

    *Stick again.*  At ``x = (2K - S)/k`` (``stick_position``) the block moves
    with the belt; the holding force ``|k x| = |2K - S|`` is within ``S``, so
    the contact sticks, and the spring loads from there to ``S/k`` in

        stick_time = (S/k - (2K - S)/k) / V = 2 (S - K) / (k V).

    The cycle repeats with ``period = stick_time + slip_time``.  With
    ``S = K`` there is no stick (``stick_time = 0``): the block oscillates
    harmonically about ``K/k`` with amplitude ``V/omega`` and period
    ``2 pi/omega``, touching the belt's speed once a period.
    """
    m = validate.positive("mass", mass)
    k = validate.positive("stiffness", stiffness)
    s = validate.positive("static", static)
    kin = validate.non_negative("kinetic", kinetic)
    if kin > s:
        raise ValueError(f"kinetic = {kin!r} N must not exceed static = {s!r} N")
    v = validate.positive("velocity", velocity)
    omega = math.sqrt(k / m)
    y0 = (s - kin) / k
    radius = math.hypot(y0, v / omega)
    theta0 = math.atan2(v / omega, y0)
    slip_time = (math.pi + 2 * theta0) / omega
    stick_time = 2 * (s - kin) / (k * v)
    centre = kin / k
    return BeltCycle(
        period=stick_time + slip_time,
        stick_time=stick_time,
        slip_time=slip_time,
        x_max=centre + radius,
        x_min=centre - radius,
        v_min=-omega * radius,
        break_position=s / k,
        stick_position=(2 * kin - s) / k,
    )


class HarmonicSlip:
    """A slip phase of direction ``s`` (``+-1``) on a belt at ``V``, undamped under a constant force: closed form.

    With ``x' = u + V`` and ``m u' = -k (x - centre)`` (the contact's force ``s a`` of a flat slip curve and the
    constant forces folded into ``centre``), ``y = x - centre`` turns clockwise on the circle of radius
    ``R = sqrt(y0^2 + (v0/omega)^2)`` in the plane ``(y, x'/omega)``, ``omega = sqrt(k/m)``:

        x' = R omega cos(psi),    y = R sin(psi),    psi = omega (t - t0) + phi,    phi = atan2(y0, v0/omega).

    The contact stops where ``x' = V``, ``cos(psi) = c = V/(R omega)`` (never if ``|c| > 1``): ``u = x' - V``
    falls through zero there when ``sin(psi) > 0`` (``s = +1``, ``psi = acos(c)``) and rises through it when
    ``sin(psi) < 0`` (``s = -1``, ``psi = -acos(c)``), so the stop is the first such ``psi`` after ``phi``.
    The interface is :class:`lumped.solvers.event_driven_network.ContactSlip`'s: ``first_stop``, ``state``
    (``(x, u)``), ``rhs``, ``s``, and ``steps`` (:data:`HARMONIC_SAMPLES` a period, for the scans of the phase).
    """

    def __init__(
        self, mass: float, stiffness: float, centre: float, velocity: float, s: int, start: tuple[float, float, float]
    ) -> None:
        self.m, self.k, self.centre, self.V, self.s = mass, stiffness, centre, velocity, s
        self.omega = math.sqrt(stiffness / mass)
        self.t0, x0, self.u0 = start
        self.y0, self.v0 = x0 - centre, self.u0 + velocity
        self.end = self.t0

    def state(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Position (m) and the contact's rate ``u = x' - V`` (m/s) at times ``t``."""
        tau = self.omega * (np.asarray(t, dtype=float) - self.t0)
        cos, sin = np.cos(tau), np.sin(tau)
        y = self.y0 * cos + self.v0 / self.omega * sin
        return self.centre + y, self.v0 * cos - self.omega * self.y0 * sin - self.V

    def rhs(self, t: float, y: tuple[float, float]) -> tuple[float, float]:
        """``(x', u')``: ``u + V`` and ``-omega^2 (x - centre)``."""
        return y[1] + self.V, -(self.omega**2) * (y[0] - self.centre)

    def first_stop(self, t_lim: float, direction: int) -> float | None:
        """The first time in ``(t0, t_lim]`` at which ``u`` is back at zero (the class docstring), or ``None``."""
        # acos(c) as atan2(sqrt((R omega)^2 - V^2), V), with (R omega)^2 - V^2 = (y0 omega)^2 + u0 (u0 + 2 V) from
        # the start's own u0: acos(V/(R omega)) loses half the digits where c is near 1 (a fast belt: c = 1 - 1e-17
        # rounds to 1 at 1e8 m/s, and the stop moves by 5e-9 s, half a metre)
        gap = (self.y0 * self.omega) ** 2 + self.u0 * (self.u0 + 2 * self.V)
        stop = None
        if gap >= 0 and (self.y0 or self.v0):
            phi = math.atan2(self.y0, self.v0 / self.omega)
            tau = ((direction * math.atan2(math.sqrt(gap), self.V) - phi) % (2 * math.pi)) / self.omega
            stop = self.t0 + tau if self.t0 + tau <= t_lim else None
        self.end = t_lim if stop is None else stop
        return stop

    @property
    def steps(self) -> np.ndarray:
        """Times from ``t0`` to the phase's end, :data:`HARMONIC_SAMPLES` a period (both ends included)."""
        n = max(1, math.ceil((self.end - self.t0) * self.omega / (2 * math.pi) * HARMONIC_SAMPLES))
        return np.linspace(self.t0, self.end, n + 1)
