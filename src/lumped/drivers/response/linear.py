"""The response curve of a linear system with an undamped mode, in closed form where it is unique (issue 31).

Without friction (no element with a threshold) a system's flow is linear,
``y' = B y + f(t)`` with ``y = (x, v)`` and

    B = [[0, I], [-M^-1 K, -M^-1 C]]

(``M``, ``K``, ``C`` the mass, stiffness and damping matrices), and the
motions of period ``T = 2 pi/omega`` under ``P sin(omega t)`` on a mass are the
fixed points of ``y -> Phi y + c``, ``Phi = expm(B T)`` the monodromy: one,
exactly when ``Phi - I`` is nonsingular.  It is singular when ``B`` has an
eigenvalue ``i omega_n`` (an *undamped mode*) with ``omega_n T`` a multiple of
``2 pi``: at ``omega = omega_n/j``, ``j >= 1``.  At ``j = 1`` (a resonance) the
undamped oscillator has no periodic motion; at ``j >= 2`` the mode's free
oscillation, of period ``T/j``, adds to the forced motion: a family, not one
motion, which a continuation would follow instead of the curve.  So a system
with an undamped mode (:func:`linear_form`, :func:`undamped_frequencies`) is not
continued (:mod:`~lumped.drivers.response.continuation`) but evaluated on the
grid of the values asked for (:func:`linear_rows`): where ``Phi - I`` is
nonsingular by more than its computed error (:func:`periodic_response`, from
the bound of :func:`~lumped.drivers.response.shooting.monodromy_error`), the motion is the
forced harmonic one,

    x(t) = Im(X e^{i omega t}),    X = (K - omega^2 M + i omega C)^-1 F,

``F`` the amplitude on the loaded mass, and ``amplitude_<mass> = |X|``; where it
is not, the point has no row, and the points ``omega_n/j`` of the range are
named (:func:`non_unique_points`).

Notes
-----
A mode counts as undamped when its eigenvalue's real part is within
``MULTIPLIER_ULPS eps`` of its modulus: its multiplier over one natural period,
``exp(2 pi Re(lambda)/|lambda|)``, is then within the monodromy's error bound
for that period (:data:`~lumped.drivers.response.shooting.MULTIPLIER_ULPS` eps
per unit of work, ``2 pi`` of it) of the unit circle, so no computed monodromy
could tell it from a mode without damping.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from lumped.drivers.response.shooting import MULTIPLIER_ULPS, balance, multiplier_margin
from lumped.drivers.response.systems import LoadedNetwork
from lumped.model.oscillator import Oscillator
from lumped.numerics.expm import expm

__all__ = [
    "LinearPoint",
    "LinearRows",
    "LinearSystem",
    "linear_form",
    "linear_rows",
    "non_unique_points",
    "periodic_response",
    "undamped_frequencies",
]


class LinearSystem(NamedTuple):
    """A linear system: masses (n,, kg), stiffness and damping matrices (n x n, N/m and N s/m), the loaded mass."""

    mass: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    load: int

    @property
    def flow(self) -> np.ndarray:
        """``B`` (2n x 2n) of ``y' = B y`` (module docstring)."""
        n = self.mass.size
        inverse = 1.0 / self.mass[:, None]
        return np.block([[np.zeros((n, n)), np.eye(n)], [-inverse * self.stiffness, -inverse * self.damping]])


class LinearPoint(NamedTuple):
    """The periodic motion at ``omega`` (rad/s): each mass's amplitude ``|X|`` (m) and the largest modulus of a
    multiplier (exactly 1 within the monodromy's error bound, as a continuation's rows)."""

    omega: float
    amplitudes: np.ndarray
    max_multiplier: float


class LinearRows(NamedTuple):
    """The points of a grid whose motion is unique, with the values of the parameter followed, and the values
    left out (the motion not unique there)."""

    points: list[LinearPoint]
    values: list[float]
    skipped: list[float]


def linear_form(system: Oscillator | LoadedNetwork) -> LinearSystem | None:
    """The matrices of ``system`` when it has no friction (no element with a threshold), else ``None``."""
    if isinstance(system, Oscillator):
        form = system.dashpot.bingham_form()
        if form is None or form.threshold > 0:
            return None
        return LinearSystem(np.array([system.mass]), np.array([[system.stiffness]]), np.array([[form.viscosity]]), 0)
    p = system.parts
    if p.friction.any():
        return None
    return LinearSystem(p.m, system.stiffness, p.b @ np.diag(p.c) @ p.b.T, system.mass)


def undamped_frequencies(ls: LinearSystem) -> np.ndarray:
    """The distinct natural frequencies (rad/s, ascending) of the undamped modes of ``ls`` (module Notes)."""
    lam = np.linalg.eigvals(ls.flow)
    tol = MULTIPLIER_ULPS * np.finfo(float).eps
    wn = np.sort(lam.imag[(np.abs(lam.real) <= tol * np.abs(lam)) & (lam.imag > 0)])
    return wn[np.append(True, np.diff(wn) > tol * wn[1:])] if wn.size else wn


def nearest_mode(frequencies: np.ndarray, omega: float) -> str:
    """The ``omega_n/j`` nearest ``omega`` among the undamped ``frequencies``, in words."""
    j = np.maximum(np.rint(frequencies / omega), 1.0)
    i = int(np.argmin(np.abs(frequencies / j - omega)))
    return f"omega_n/{int(j[i])} of the undamped mode omega_n = {frequencies[i]:.6g} rad/s"


def has_undamped_mode(system: Oscillator | LoadedNetwork) -> bool:
    """True when ``system`` is linear (:func:`linear_form`) and has an undamped mode."""
    ls = linear_form(system)
    return ls is not None and undamped_frequencies(ls).size > 0


def periodic_response(ls: LinearSystem, amplitude: float, omega: float) -> LinearPoint | None:
    """The periodic motion under ``amplitude sin(omega t)`` on the loaded mass, or ``None`` where it is not
    unique: where the smallest singular value of the balanced ``Phi - I`` (:func:`_monodromy`) is within its
    computed error's bound (that of :func:`~lumped.drivers.response.shooting.monodromy_error`, times ``|B T|``;
    Weyl: no singular value moves by more), so that no computation could vouch that it is nonzero.

    ``ValueError`` (``force_omega``) where that error bound, ``MULTIPLIER_ULPS eps rho(B) T``, reaches 1 (``B T``
    not finite included: before ``expm``), where ``m omega^2`` overflows, or where the amplitude falls below the
    normal numbers: numbers no computation here can vouch for."""
    if not omega < math.sqrt(np.finfo(float).max / float(ls.mass.max())):
        raise ValueError(f"force_omega: omega = {omega:g} rad/s is too high: m omega^2 overflows")
    bt = ls.flow * (2 * math.pi / omega)
    work = max(1.0, float(np.max(np.abs(np.linalg.eigvals(bt))))) if np.all(np.isfinite(bt)) else math.inf
    if not MULTIPLIER_ULPS * np.finfo(float).eps * work < 1:  # the monodromy's error bound: not one digit known
        raise ValueError(
            f"force_omega: omega = {omega:g} rad/s is too low for this system: over one period (rho(B) T = "
            f"{work:.3g}) the monodromy's computed error exceeds its size, so no periodic motion can be vouched for"
        )
    a = balance(bt)
    monodromy, minus, size = _monodromy(a)
    error = MULTIPLIER_ULPS * np.finfo(float).eps * work * size * float(np.linalg.norm(a, 2))
    if np.linalg.svd(minus, compute_uv=False)[-1] <= error:
        return None
    force = np.zeros(ls.mass.size, dtype=complex)
    force[ls.load] = amplitude
    x = np.linalg.solve(ls.stiffness - omega**2 * np.diag(ls.mass) + 1j * omega * ls.damping, force)
    if not np.abs(x).max() >= np.finfo(float).tiny:  # P/(m omega^2) below the normal numbers: not a number to print
        raise ValueError(f"force_omega: omega = {omega:g} rad/s is too high: the amplitude underflows")
    mu = float(np.max(np.abs(np.linalg.eigvals(monodromy))))
    return LinearPoint(omega, np.abs(x), 1.0 if abs(mu - 1.0) <= multiplier_margin(monodromy, work) else mu)


def _monodromy(a: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """``expm(a)``, ``expm(a) - I`` and the 2-norm of the exponential computed, from ``expm([[a, I], [0, 0]]) =
    [[expm(a), phi1(a)], [0, I]]`` (``phi1(a) = sum a^k/(k + 1)!``, Higham, *Functions of Matrices*, 10.7.4):
    ``expm(a) - I = a phi1(a)`` keeps its digits however small ``a`` (a high omega), where ``expm(a) - I``
    subtracted keeps none once ``|a|`` is below an ulp of 1.  Its error is ``|a|`` times ``phi1``'s, which is
    within the monodromy's bound (``MULTIPLIER_ULPS eps`` per unit of work, times the exponential's norm)."""
    n = a.shape[0]
    augmented = np.zeros((2 * n, 2 * n))
    augmented[:n, :n], augmented[:n, n:] = a, np.eye(n)
    e = expm(augmented)
    return e[:n, :n], a @ e[:n, n:], float(np.linalg.norm(e, 2))


def linear_rows(members, start: float, stop: float, points: int) -> LinearRows:
    """:func:`periodic_response` at ``points`` values evenly spaced from ``start`` to ``stop`` of a family's
    ``member(value) -> (system, P, omega)`` (:class:`~lumped.drivers.response.systems.Family`), each member
    linear; the values whose motion is not unique are left out and listed."""
    rows = LinearRows([], [], [])
    for value in np.linspace(start, stop, points):
        system, amplitude, omega = members(float(value))
        point = periodic_response(linear_form(system), amplitude, omega)  # type: ignore[arg-type]
        if point is None:
            rows.skipped.append(float(value))
        else:
            rows.points.append(point)
            rows.values.append(float(value))
    return rows


def non_unique_points(frequencies: np.ndarray, start: float, stop: float) -> str:
    """The points ``omega_n/j`` (``j >= 1``) in ``[start, stop]`` of each undamped ``omega_n``, in words: each
    one (up to four of an ``omega_n``), else the first two and the last with the range of ``j``; ``""`` if none.
    The ends count within ``MULTIPLIER_ULPS eps`` relative: :func:`periodic_response` leaves out a point that
    near ``omega_n/j`` (``|omega_n T - 2 pi j|`` within the monodromy's error, ``MULTIPLIER_ULPS eps omega_n T``)."""
    tol = MULTIPLIER_ULPS * np.finfo(float).eps  # as near as periodic_response leaves a point out
    start, stop, parts = start * (1 - tol), stop * (1 + tol), []
    for wn in frequencies:
        first = max(1, math.ceil(wn / stop))
        while first > 1 and wn / (first - 1) <= stop:  # round-off in wn/stop, either way
            first -= 1
        while wn / first > stop:
            first += 1
        if wn / first < start:
            continue
        if wn / start >= 2**53:  # too many to count: j from first on, as far as the range's bottom
            parts.append(f"{wn:.6g}/j for j >= {first} ({wn / first:.6g}, {wn / (first + 1):.6g}, ...)")
            continue
        last = math.floor(wn / start)
        while wn / (last + 1) >= start:
            last += 1
        while wn / last < start:
            last -= 1
        if last == first:
            parts.append(f"{wn / first:.6g}")
            continue
        if last - first < 4:
            shown = ", ".join(f"{wn / j:.6g}" for j in range(first, last + 1))
        else:
            shown = f"{wn / first:.6g}, {wn / (first + 1):.6g}, ..., {wn / last:.6g}"
        parts.append(f"{wn:.6g}/j for j = {first}..{last} ({shown})")
    return "; ".join(parts)
