"""Independent references shared by the tests: nothing here imports ``lumped``.

Each function is written from the paper or from a textbook closed form, not
from the package, so that a test comparing the package with it can fail.

* :data:`PAPER`: the parameter values stated in section 3 of the paper;
* :data:`CASES`: the motions the tests run (as plain numbers);
* :func:`switched_sine`: the forcing of eq. (17), any amplitude, frequency, phase;
* :data:`FREE_DECAY`: free decays ``(m, k, tau, gamma, x0)`` with no turning
  point within round-off of the band edge;
* :func:`bingham_velocity`: the Bingham law's graph ``v = phi(F_d)`` (eq. 7);
* :func:`line3`, :func:`literal_line8` and :func:`literal_algorithm1`:
  Algorithm 1 typed line by line as printed (line 8 with its factor ``gamma``);
* :func:`free_decay`: the half-cycle recurrence of the viscous + Coulomb
  oscillator released at rest (Den Hartog);
* :func:`slope` and :func:`order`: least-squares slopes (convergence orders);
* :func:`sign_changes`: direction changes of a sampled velocity.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

#: Section 3 of the paper: "gamma = 1, mu_s N_f = 1, m = 1, k = 100 and
#: Delta t = 1e-4"; forcings (17a), (17b): P sin(5 pi t) for 0 <= t <= 1 with
#: P = 0.5 and 10; section 3.2: x(0) = 0.005 and x(0) = 0.5.
PAPER = {
    "m": 1.0,
    "k": 100.0,
    "tau": 1.0,
    "gamma": 1.0,
    "dt": 1e-4,
    "omega_over_pi": 5.0,
    "force_until": 1.0,
    "P_small": 0.5,
    "P_large": 10.0,
    "x0_small": 0.005,
    "x0_large": 0.5,
}


class Case(NamedTuple):
    """A motion of the paper's oscillator (m = 1, k = 100, tau = 1) with slope ``gamma``.

    ``force`` is ``(P, omega, phase, until)`` of ``P sin(omega t + phase)``
    for ``t <= until``, or ``None`` for free vibration.
    """

    gamma: float
    x0: float = 0.0
    v0: float = 0.0
    force: tuple[float, float, float, float] | None = None


#: Forcings (17a) and (17b) of the paper.
F17A = (0.5, 5 * math.pi, 0.0, 1.0)
F17B = (10.0, 5 * math.pi, 0.0, 1.0)
#: The motions several test modules run, by name.
CASES = {
    "fig5-17a": Case(1.0, force=F17A),
    "fig10-x0-0.005": Case(1.0, x0=0.005),
    "fig6-17b": Case(1.0, force=F17B),
    "fig11-x0-0.5": Case(1.0, x0=0.5),
    "coulomb-x0-0.5": Case(math.inf, x0=0.5),
    "coulomb-17b": Case(math.inf, force=F17B),
    "overdamped-17b": Case(0.01, force=F17B),
    "overdamped-free": Case(0.01, x0=0.5),
    "v0-phase-negative-amp": Case(2.0, x0=0.1, v0=-3.0, force=(-4.0, 7.0, 0.3, 1.5)),
    "negative-amplitude-phase": Case(1.0, force=(-10.0, 5 * math.pi, 0.7, 1.0)),
    "v0-only": Case(1.0, v0=4.0),
}

#: Free decays from rest, ``(m, k, tau, gamma, x0)``: the paper's (Figure 11),
#: other x0 and gamma, Coulomb, other m, k, tau.  x0 chosen so that no turning
#: point lies within round-off of the band edge (where the count of
#: half-cycles would be ill-posed).
FREE_DECAY = {
    "fig11": (1.0, 100.0, 1.0, 1.0, 0.5),
    "fig11-negative-x0": (1.0, 100.0, 1.0, 1.0, -0.5),
    "gamma-2": (1.0, 100.0, 1.0, 2.0, 0.3),
    "gamma-10": (1.0, 100.0, 1.0, 10.0, -0.37),
    "gamma-0.2": (1.0, 100.0, 1.0, 0.2, 0.5),
    "coulomb": (1.0, 100.0, 1.0, math.inf, 0.5),
    "coulomb-negative-x0": (1.0, 100.0, 1.0, math.inf, -0.2345),
    "other-m-k-tau": (2.5, 40.0, 0.3, 5.0, 0.41),
    "coulomb-other-m-k-tau": (0.2, 900.0, 3.0, math.inf, 0.0731),
    "gamma-1e12": (1.0, 100.0, 1.0, 1e12, 0.2345),
}


def switched_sine(force: tuple[float, float, float, float], t: float) -> float:
    """``P sin(omega t + phase)`` for ``t <= until``, else 0 (eq. 17), with libm's sin."""
    amplitude, omega, phase, until = force
    return amplitude * math.sin(omega * t + phase) if t <= until else 0.0


def bingham_velocity(force: float, tau: float, gamma: float) -> float:
    """Eq. (7): ``v = gamma (|F_d| - tau) sgn(F_d)`` outside the band, 0 inside."""
    return math.copysign(gamma * max(abs(force) - tau, 0.0), force)


def line3(
    m: float, dt: float, v: np.ndarray | float, force_next: np.ndarray | float, f_s: np.ndarray | float
) -> np.ndarray | float:
    """Algorithm 1, line 3 (eq. 15b): the predictor ``F~ = (m/dt) v_n + F_{n+1} - F_s,n``."""
    return (m / dt) * v + force_next - f_s


def literal_line8(predictor: float, dt: float, m: float, k: float, tau: float, gamma: float) -> tuple[float, float]:
    """Algorithm 1, lines 5 to 9, as printed (finite ``gamma``): ``(F_d, v)``."""
    if abs(predictor) <= tau:  # lines 5-6
        return predictor, 0.0
    a, b, s = 1 + dt**2 * k / m, dt / m, math.copysign(1.0, predictor)
    f_d = (gamma * a * s * tau + b * predictor) / (gamma * a + b)  # line 8
    return f_d, gamma * (f_d - math.copysign(1.0, f_d) * tau)  # line 9


def literal_algorithm1(
    t_end: float, dt: float, x0: float, force: Callable[[float], float], m: float, k: float, tau: float, gamma: float
) -> dict[str, np.ndarray]:
    """Algorithm 1 (lines 3 to 11) from rest at ``x0``; columns ``t, x, v, F_s, F_d``.

    ``F_d(0)`` is the consistent value at rest: the net force, clipped to the band.
    """
    n = int(round(t_end / dt))
    n += n * dt < t_end * (1 - 1e-12)
    out = np.zeros((n + 1, 5))
    f_s, v = k * x0, 0.0
    net0 = force(0.0) - k * x0
    out[0] = (0.0, x0, 0.0, f_s, math.copysign(min(abs(net0), tau), net0))
    for i in range(1, n + 1):
        predictor = line3(m, dt, v, force(i * dt), f_s)
        f_d, v = literal_line8(predictor, dt, m, k, tau, gamma)
        f_s = f_s + dt * k * v  # line 11
        out[i] = (i * dt, f_s / k, v, f_s, f_d)
    return dict(zip(("t", "x", "v", "F_s", "F_d"), out.T))


class FreeDecay(NamedTuple):
    """Free decay from rest: turning points, half-cycle starts and the modal constants."""

    x0: float  #: release position (m)
    times: np.ndarray  #: turning-point times (s); the last is the stop
    positions: np.ndarray  #: turning-point positions (m)
    starts: list[tuple[float, float]]  #: (t, x) at the start of each half-cycle
    half: float  #: duration of a half-cycle, pi/omega_d (s)
    sigma: float  #: decay rate c/(2m) (1/s)
    omega_d: float  #: damped angular frequency (rad/s)

    @property
    def rest(self) -> tuple[float, float]:
        """Rest time and position (``(0, x0)`` released inside the band)."""
        if len(self.times):
            return float(self.times[-1]), float(self.positions[-1])
        return 0.0, self.x0


def free_decay(m: float, k: float, tau: float, gamma: float, x0: float) -> FreeDecay:
    """Turning points of free decay with viscous (c = 1/gamma) plus Coulomb damping.

    During a half-cycle moving with sign ``s`` the motion is a damped
    oscillation about ``x_c = -s tau/k``; it lasts ``pi/omega_d`` and the
    offset from ``x_c`` shrinks by ``exp(-sigma pi/omega_d)`` and flips sign.
    The mass stops at the first turning point with ``|x| <= tau/k``.
    """
    c = 0.0 if math.isinf(gamma) else 1.0 / gamma
    sigma = c / (2 * m)
    omega_d = math.sqrt(k / m - sigma**2)
    half = math.pi / omega_d
    shrink = math.exp(-sigma * half)
    times, xs, starts, x, t = [], [], [], x0, 0.0
    while k * abs(x) > tau:
        starts.append((t, x))
        centre = math.copysign(tau / k, x)  # released at rest, it moves towards the origin
        x = centre - (x - centre) * shrink
        t += half
        times.append(t)
        xs.append(x)
    return FreeDecay(x0, np.array(times), np.array(xs), starts, half, sigma, omega_d)


def free_decay_state(ref: FreeDecay, k: float, m: float, tau: float, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``x(t), v(t)`` of the recurrence solution (closed form within each half-cycle)."""
    x = np.full_like(t, ref.rest[1])
    v = np.zeros_like(t)
    for t0, x0 in ref.starts:
        sel = (t >= t0) & (t < t0 + ref.half)
        s = t[sel] - t0
        centre = math.copysign(tau / k, x0)
        e = np.exp(-ref.sigma * s)
        w = ref.omega_d
        x[sel] = centre + (x0 - centre) * e * (np.cos(w * s) + ref.sigma / w * np.sin(w * s))
        v[sel] = -(x0 - centre) * (k / m) / w * e * np.sin(w * s)
    return x, v


def slope(x: np.ndarray, y: np.ndarray) -> float:
    """Least-squares slope of ``y`` against ``x`` (closed form of the normal equations)."""
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    dx = x - x.mean()
    return float(np.dot(dx, y - y.mean()) / np.dot(dx, dx))


def order(steps: np.ndarray, errors: np.ndarray) -> float:
    """Observed order: the slope of ``log(error)`` against ``log(step)``."""
    return slope(np.log(steps), np.log(errors))


def sign_changes(v: np.ndarray) -> int:
    """Changes of direction: sign changes between successive nonzero velocities."""
    moving = [value for value in np.asarray(v, dtype=float) if value != 0.0]
    return sum((a > 0) != (b > 0) for a, b in zip(moving, moving[1:]))
