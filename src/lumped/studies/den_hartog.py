"""Study "Den Hartog (1931)" (notebook 11, ``results/studies/den_hartog.csv``): the steady amplitude of the forced
oscillator with Coulomb friction, and with Coulomb friction plus the viscous part of the paper's Bingham dashpot,
against the closed form for motion without stops.

The system is ``m x'' + c x' + k x = P sin(omega t) - F sgn(x')`` with the
committed ``m``, ``k`` and ``F = tau`` (``threshold``); ``c = 0`` (Coulomb,
``gamma = inf``) or ``c = 1/gamma`` (the paper's ``gamma``: damping ratio
``zeta = c / (2 sqrt(k m)) = 0.05``).  Each row is one long run from rest by
the exact solver, summarised from its events (:func:`steady_state`).

The file's columns (:data:`COLUMNS`):

* ``damping``: ``zeta`` (0 for Coulomb);
* ``friction_ratio``: ``F/P``; ``frequency_ratio``: ``r = omega/omega_n``,
  ``omega_n = sqrt(k/m)``;
* ``amplitude_ratio``: ``X k/P``, ``X`` the largest ``|x|`` over the last
  :data:`PERIODS` forcing periods of the run (m);
* ``amplitude_change``: ``|X - X'|/X``, ``X'`` the same over the
  :data:`PERIODS` periods before (how far from steady the run still is);
* ``stops_per_period``: stop events in the last window over :data:`PERIODS`;
* ``closed_form``: ``X k/P`` of the symmetric one-slip-per-half-period motion
  (:func:`closed_form`), ``nan`` where it has no real solution;
* ``nonstop``: 1.0 where that motion is admissible (:func:`closed_form`'s
  conditions), 0.0 elsewhere.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import NamedTuple

import numpy as np

from lumped.drivers.sweep import chunk_slice
from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.numerics import validate
from lumped.solvers.events import Event
from lumped.solvers.exact import ExactSolution, solve_exact

__all__ = [
    "coulomb_boundary",
    "GRID",
    "CHUNKS",
    "COLUMNS",
    "SteadyMotion",
    "closed_form",
    "half_period_velocity",
    "Curve",
    "curve",
    "SteadyState",
    "steady_state",
    "rows",
    "chunk_table",
]

#: The friction ratios F/P of the study.
FRICTION_RATIOS = (0.2, 0.4, 0.6, 0.8)
#: ``studies`` -> (frequency ratios per F/P and damping, chunks).
GRID = {"default": (6, 2), "full": (120, 16)}
CHUNKS = {resolution: chunks for resolution, (_, chunks) in GRID.items()}
#: The interval of r = omega/omega_n; an even count keeps r = 1 off the grid.
RATIO_RANGE = (0.2, 2.5)
#: K: forcing periods of each window of the summary.
PERIODS = 5
#: Length of the run before the last two windows (s): 15 e-folds of the viscous decay 1/(zeta omega_n) = 2 s
#: at the paper's values; notebook 11 reports the amplitude change it leaves.
TRANSIENT = 30.0
#: Velocity samples per half-period in the check that the velocity keeps its sign.
SAMPLES = 512
COLUMNS = (
    "damping",
    "friction_ratio",
    "frequency_ratio",
    "amplitude_ratio",
    "amplitude_change",
    "stops_per_period",
    "closed_form",
    "nonstop",
)


class SteadyMotion(NamedTuple):
    """The symmetric steady motion with one slip phase per half-period (:func:`closed_form`).

    ``amplitude`` X (m) and ``phase`` psi (rad): ``x(0) = -X``, ``v(0) = 0``
    under the force ``P sin(omega t + psi)``; ``nan`` when no real solution
    exists.  ``nonstop`` is true when the motion is admissible.
    """

    amplitude: float
    phase: float
    nonstop: bool


# The free oscillator is written out here rather than taken from lumped.solvers.exact: the closed form is
# the reference the exact solver's runs are compared with, so the two share no code.
def _flow(m: float, c: float, k: float, t: float) -> np.ndarray:
    """``exp(M t)`` of ``z' = M z``, ``z = (x, v)``, for the underdamped free oscillator (closed form)."""
    h, wn2 = c / (2 * m), k / m
    q = math.sqrt(wn2 - h * h)
    e, s, co = math.exp(-h * t), math.sin(q * t), math.cos(q * t)
    return e * np.array([[co + h / q * s, s / q], [-wn2 / q * s, co - h / q * s]])


def _free_velocity(m: float, c: float, k: float, e0: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Velocity row of :func:`_flow` applied to ``e0``, at the times ``t`` (s) at once (m/s)."""
    h, wn2 = c / (2 * m), k / m
    q = math.sqrt(wn2 - h * h)
    s, co = np.sin(q * t), np.cos(q * t)
    return np.exp(-h * t) * (-wn2 / q * s * e0[0] + (co - h / q * s) * e0[1])


def _homogeneous_start(m: float, c: float, k: float, friction: float, omega: float) -> np.ndarray:
    """``e0`` with ``(Phi(T/2) + I) e0 = (2F/k, 0)``: the free part of the state at ``t = 0``."""
    return np.linalg.solve(_flow(m, c, k, math.pi / omega) + np.eye(2), [2 * friction / k, 0.0])


def _check(m: float, c: float, k: float, friction: float, p: float, omega: float) -> None:
    """Refuse, with one line naming the argument, what :func:`closed_form` does not cover."""
    for name, value in (("mass", m), ("stiffness", k), ("force_amplitude", p), ("force_omega", omega)):
        validate.positive(name, value)
    validate.non_negative("threshold", friction)
    if not 0 <= validate.finite("damping", c) < 2 * math.sqrt(k * m):
        raise ValueError(f"damping: c must lie in [0, 2 sqrt(k m)) = [0, {2 * math.sqrt(k * m)!r}) N s/m, got {c!r}")
    if c == 0 and omega * omega * m == k:
        raise ValueError("force_omega: omega = sqrt(k/m) with c = 0 is the undamped resonance (no steady state)")


def closed_form(m: float, c: float, k: float, friction: float, p: float, omega: float) -> SteadyMotion:
    """Steady motion without stops of ``m x'' + c x' + k x = P sin(omega t + psi) - F sgn(x')`` (notebook 11, eq. 1).

    Parameters
    ----------
    m, c, k : float
        Mass (kg), viscous coefficient (N s/m, ``0 <= c < 2 sqrt(km)``) and stiffness (N/m).
    friction, p : float, N
        Friction force ``F >= 0`` and force amplitude ``P > 0``.
    omega : float, rad/s
        Forcing frequency ``> 0``.

    Notes
    -----
    On the half-period ``0 < t < T/2`` where ``v > 0`` the equation is linear:
    ``x = a sin(omega t + theta) - F/k + e(t)`` with the harmonic response
    ``a = P/sqrt((k - m omega^2)^2 + (c omega)^2)``, ``theta = psi - phi``,
    ``phi = atan2(c omega, k - m omega^2)``, and ``e`` free, ``e(t) = Phi(t) e0``.
    The symmetry ``z(t + T/2) = -z(t)`` gives ``(Phi(T/2) + I) e0 = (2F/k, 0)`` (eq. 2),
    independent of ``psi``; then ``v(0) = 0`` gives
    ``cos theta = -e0_v/(a omega)`` and ``x(0) = -X`` gives
    ``X = F/k - e0_x + sqrt(a^2 - (e0_v/omega)^2)`` (eq. 3).  For ``c = 0`` this is
    Den Hartog's (1931) ``X k/P = sqrt(1/(1 - r^2)^2 - (F/P)^2 (U/r)^2)``,
    ``U = sin(pi/r)/(1 + cos(pi/r))`` (eq. 4).  ``X`` is ``nan`` unless real and
    positive.  The motion is admissible (``nonstop``)
    when the mass leaves the turning point at once, ``P sin psi + k X > F``,
    and ``v > 0`` at :data:`SAMPLES` points inside the half-period.
    """
    _check(m, c, k, friction, p, omega)
    x, theta, phi = _solve(m, c, k, friction, p, omega)
    if math.isnan(x):
        return SteadyMotion(math.nan, math.nan, False)
    psi = theta + phi
    leaves = p * math.sin(psi) + k * x > friction
    return SteadyMotion(x, psi, bool(leaves and np.all(half_period_velocity(m, c, k, friction, p, omega)[1:-1] > 0)))


#: Below this frequency ratio the Coulomb boundary :func:`coulomb_boundary` is not claimed (notebook 11).
BOUNDARY_FROM = 0.5


def coulomb_boundary(r: np.ndarray | float) -> np.ndarray:
    """Largest ``F/P`` of Coulomb motion without stops at frequency ratio ``r`` (notebook 11, eq. 5).

    ``F/P < r^2 / (|1 - r^2| sqrt(1 + r^2 U^2))``, ``U = sin(pi/r)/(1 + cos(pi/r))``:
    the mass leaves each turning point at once, ``m omega^2 X > F``, with ``X``
    from eq. (4).  At ``r = 1`` its limit, ``pi/4``.  Claimed for
    ``r >= BOUNDARY_FROM`` only: below, the velocity's sign over the
    half-period binds too, and motions with several reversals appear.
    """
    r = np.asarray(r, dtype=float)
    if np.any(~np.isfinite(r)) or np.any(r <= 0):
        raise ValueError("r must be finite and > 0")
    with np.errstate(divide="ignore", invalid="ignore"):
        # U = tan(pi / 2r) = 1 / tan(pi (r - 1) / 2r): near r = 1 the form sin/(1 + cos) cancels
        # (1 + cos(pi/r) ~ (pi (r - 1))^2 / 2 carries eps / that of relative error, 4e-5 at
        # r = 1 + 1e-6), where r - 1 is exact (Sterbenz) and the tangent well conditioned.
        u = 1 / np.tan(np.pi * (r - 1) / (2 * r))
        edge = r * r / (np.abs(1 - r * r) * np.sqrt(1 + (r * u) ** 2))
    return np.where(r == 1.0, np.pi / 4, edge)


def _solve(m: float, c: float, k: float, friction: float, p: float, omega: float) -> tuple[float, float, float]:
    """``(X, theta, phi)`` of :func:`closed_form`'s Notes; ``X = nan`` unless real and positive."""
    e0 = _homogeneous_start(m, c, k, friction, omega)
    a, phi = p / math.hypot(k - m * omega**2, c * omega), math.atan2(c * omega, k - m * omega**2)
    disc = a * a - (e0[1] / omega) ** 2
    x = friction / k - e0[0] + math.sqrt(disc) if disc >= 0 else math.nan
    if not x > 0:
        return math.nan, math.nan, phi
    return x, math.atan2(-math.sqrt(disc) / a, -e0[1] / (a * omega)), phi


def half_period_velocity(m: float, c: float, k: float, friction: float, p: float, omega: float) -> np.ndarray:
    """Velocity (m/s) of :func:`closed_form`'s motion at ``SAMPLES + 1`` even times over ``[0, T/2]`` (nan if none)."""
    _, theta, _ = _solve(m, c, k, friction, p, omega)
    a = p / math.hypot(k - m * omega**2, c * omega)
    e0 = _homogeneous_start(m, c, k, friction, omega)
    t = np.linspace(0.0, math.pi / omega, SAMPLES + 1)
    return a * omega * np.cos(omega * t + theta) + _free_velocity(m, c, k, e0, t)


class Curve(NamedTuple):
    """:func:`closed_form` along ``r``: ``X k/P`` (``nan`` where no real positive root) and admissibility."""

    frequency_ratio: np.ndarray
    amplitude_ratio: np.ndarray
    nonstop: np.ndarray


def curve(cfg: Mapping[str, float], damping: float, friction_ratio: float, ratios: np.ndarray) -> Curve:
    """:func:`closed_form` with ``m``, ``k``, ``F = threshold`` of ``cfg``, ``c = 2 zeta sqrt(k m)``, ``P = F/(F/P)``.

    ``damping`` is ``zeta``, ``ratios`` the values of ``r = omega/omega_n`` (``r = 1`` refused when ``zeta = 0``).
    """
    m, k, friction = cfg["mass"], cfg["stiffness"], cfg["threshold"]
    c, p, wn = 2 * damping * math.sqrt(k * m), friction / friction_ratio, math.sqrt(k / m)
    forms = [closed_form(m, c, k, friction, p, r * wn) for r in np.asarray(ratios, dtype=float)]
    amplitude = np.array([f.amplitude * k / p for f in forms])
    return Curve(np.asarray(ratios, dtype=float), amplitude, np.array([f.nonstop for f in forms]))


class SteadyState(NamedTuple):
    """A long run's last two windows of :data:`PERIODS` periods: largest ``|x|`` (m) in each, stops in the last."""

    amplitude: float
    previous: float
    stops: int


def _window_max(solution: ExactSolution, events: list[Event], start: float, end: float) -> float:
    """Largest ``|x|`` over ``[start, end]``: at a zero of ``v`` (an event) or at an end of the window."""
    ends = solution.evaluate(np.array([start, end]))["x"]
    inside = [abs(e.x[0]) for e in events if start <= e.time <= end and e.kind in ("stop", "reversal")]
    return float(max([*np.abs(ends), *inside]))


def steady_state(oscillator: Oscillator, p: float, omega: float, periods: int = PERIODS) -> SteadyState:
    """Run from rest under ``P sin(omega t)`` for :data:`TRANSIENT` s plus two windows of ``periods`` periods.

    The window summary equals :mod:`lumped.drivers.sweep`'s ``steady_amplitude`` and
    ``stops_per_period`` without sampling: ``|x|`` is largest where ``v = 0``
    (a stop or a reversal event) or at an end of the window.
    """
    window = periods * 2 * math.pi / omega
    t_end = TRANSIENT + 2 * window
    solution = solve_exact(oscillator, t_end, force=SwitchedSine(p, omega, 0.0, math.inf))
    events = list(solution.events)
    stops = sum(1 for e in events if e.kind == "stop" and e.time >= t_end - window)
    last = _window_max(solution, events, t_end - window, t_end)
    return SteadyState(last, _window_max(solution, events, t_end - 2 * window, t_end - window), stops)


def _row(cfg: Mapping[str, float], gamma: float, ratio: float, r: float) -> tuple[float, ...]:
    m, k, friction = cfg["mass"], cfg["stiffness"], cfg["threshold"]
    c = 0.0 if math.isinf(gamma) else 1.0 / gamma
    p, omega = friction / ratio, r * math.sqrt(k / m)
    run = steady_state(Oscillator.bingham(m, k, friction, gamma), p, omega)
    form = closed_form(m, c, k, friction, p, omega)
    change = abs(run.amplitude - run.previous) / run.amplitude
    zeta = c / (2 * math.sqrt(k * m))
    return (zeta, ratio, r, run.amplitude * k / p, change, run.stops / PERIODS, form.amplitude * k / p, form.nonstop)


def grid(points: int) -> list[tuple[float, float, float]]:
    """The study's rows ``(gamma, F/P, r)`` in order: Coulomb first, then the paper's gamma; F/P; r."""
    ratios = np.linspace(*RATIO_RANGE, points)
    return [(g, fp, float(r)) for g in (math.inf, None) for fp in FRICTION_RATIOS for r in ratios]


def rows(cfg: Mapping[str, float], points: int, chunk: tuple[int, int] | None = None) -> dict[str, np.ndarray]:
    """The study's columns (:data:`COLUMNS`) for the rows of ``chunk`` of the grid (all without it).

    Parameters
    ----------
    cfg : mapping
        ``mass`` (kg), ``stiffness`` (N/m), ``threshold`` (N) and ``gamma``
        (m/(N s), finite: the combined damping), as :func:`lumped.studies.config.load` gives them.
    points : int
        Number of frequency ratios over :data:`RATIO_RANGE`.
    chunk : (int, int), optional
        ``(index, count)``: contiguous near-equal chunks, as :meth:`lumped.drivers.sweep.SweepSpec.chunk`.
    """
    if not math.isfinite(cfg["gamma"]):
        raise ValueError("gamma: the study's combined damping needs a finite gamma (c = 1/gamma)")
    validate.positive_int("points", points)
    cells = grid(points)
    if chunk is not None:
        cells = cells[chunk_slice(len(cells), *chunk)]
    table = [_row(cfg, cfg["gamma"] if g is None else g, fp, r) for g, fp, r in cells]
    data = np.array(table, dtype=float).reshape(-1, len(COLUMNS))
    return {name: data[:, i] for i, name in enumerate(COLUMNS)}


def chunk_table(cfg: Mapping[str, float], resolution: str, chunk: tuple[int, int]) -> dict[str, np.ndarray]:
    """:func:`rows` of ``chunk`` on the grid of ``resolution`` (a key of :data:`GRID`)."""
    return rows(cfg, GRID[resolution][0], chunk)
