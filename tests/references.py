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
  :func:`order_fit`, :func:`order_band` and :func:`geometric_steps`: an order with its
  spread, the band it must lie in, and steps that are not nested;
* :func:`sign_changes`: direction changes of a sampled velocity;
* :func:`stick_slip_motion`: event-driven integration of networks of masses,
  linear springs and Bingham/Coulomb elements (chains and trees), from plain
  :class:`StickSlipSystem` numbers.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from typing import NamedTuple

import numpy as np
from scipy import stats
from scipy.integrate import solve_ivp

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


def order_fit(steps: Sequence[float], errors: Sequence[float], next_term: bool = False) -> tuple[float, float, int]:
    """Observed order with its spread: the slope of ``log(error)`` against ``log(step)``, its
    standard error and the fit's degrees of freedom (``scipy.stats.linregress``).

    With ``next_term``, the order is fitted jointly with the next term of the
    error's expansion, ``e = C dt^p (1 + a dt)``, as ``log e = c + p log dt + a dt``
    (ordinary least squares, three parameters): on a smooth error the slope is
    then no longer tilted by ``a dt``.
    """
    h, y = np.log(steps), np.log(errors)
    if not next_term:
        fit = stats.linregress(h, y)
        return float(fit.slope), float(fit.stderr), len(steps) - 2
    design = np.column_stack([np.ones_like(h), h, np.asarray(steps, dtype=float)])
    beta = np.linalg.lstsq(design, y, rcond=None)[0]
    residual, dof = y - design @ beta, len(steps) - 3
    covariance = (residual @ residual / dof) * np.linalg.inv(design.T @ design)
    return float(beta[1]), math.sqrt(covariance[1, 1]), dof


def order_band(stderr: float, dof: int, rate: float, dt_max: float, left_out: int = 1) -> float:
    """How far a fitted order may lie from the method's, derived rather than tuned.

    Two parts: the scatter of the errors about the fit, as the 99 % two-sided
    Student quantile of the slope's standard error (an error dated at a grid
    point is ``O(dt)`` times a factor that jumps with where the switch falls in
    its step); and the first term of the error's expansion that the fit leaves
    out, ``e = C dt^p (1 + a dt + ...)``: it moves the local slope by about
    ``(a dt)^left_out``, with ``|a|`` of the order of the motion's fastest rate
    (1/s), so by at most about ``(rate * dt_max)^left_out`` over the steps
    fitted (``left_out = 2`` when :func:`order_fit` fitted the ``a dt`` term).
    """
    return float(stats.t.ppf(0.995, dof)) * stderr + (rate * dt_max) ** left_out


def geometric_steps(first: float, count: int, ratio: float = 1.37) -> tuple[float, ...]:
    """``first / ratio^j``, ``j < count``: steps that are not nested (no grid holds another's points
    but ``t = 0`` and, for ``ratio = 1.37``, multiples of 137 steps), so a switch falls at another place
    in its step on every grid, unlike halvings, where an error fixed by the grid repeats (issue 32)."""
    return tuple(first / ratio**j for j in range(count))


def sign_changes(v: np.ndarray) -> int:
    """Changes of direction: sign changes between successive nonzero velocities."""
    moving = [value for value in np.asarray(v, dtype=float) if value != 0.0]
    return sum((a > 0) != (b > 0) for a, b in zip(moving, moving[1:]))


# -- stick-slip networks: an event-driven reference (issue 9) ---------------------
class SpringLink(NamedTuple):
    """A linear spring between two points: tension ``f = stiffness (x_second - x_first)`` (N).

    Points are mass indices; ``-1`` is the ground (``x = 0``).  A tension
    pulls ``second`` by ``-f`` and ``first`` by ``+f``.
    """

    first: int
    second: int
    stiffness: float


class FrictionLink(NamedTuple):
    """A Bingham (finite ``gamma``) or Coulomb (``gamma = inf``) element between two points.

    With ``w = v_second - v_first``: ``w = 0`` while ``|f| <= threshold``
    (``threshold > 0``), else ``f = sgn(w) (threshold + |w|/gamma)`` (eq. 6).
    """

    first: int
    second: int
    threshold: float
    gamma: float


class StickSlipSystem(NamedTuple):
    """Masses (kg) with initial states, springs, friction elements, and loads.

    ``loads`` holds ``(mass index, (P, omega, phase, until))``: ``P sin(omega t
    + phase)`` (N) for ``t <= until``, 0 after.  The friction elements must
    form a forest with the ground (else their sticking forces are not unique).
    """

    masses: tuple[float, ...]
    x0: tuple[float, ...]
    v0: tuple[float, ...]
    springs: tuple[SpringLink, ...]
    frictions: tuple[FrictionLink, ...]
    loads: tuple[tuple[int, tuple[float, float, float, float]], ...] = ()


class StickSlipEvent(NamedTuple):
    """A mode change: ``kind`` is ``"stop"`` (a slipping element's rate reached 0 and it sticks),
    ``"reversal"`` (... and it slips back at once), ``"breakaway"`` (a sticking element's force
    reached its threshold), ``"switch"`` (a load switched off) or ``"rest"`` (every mass held to the
    ground with every load off: from the latest of the masses' rest times on, nothing moves);
    ``mode`` is the mode chosen after it (the package's :data:`lumped.solvers.events.KINDS`)."""

    time: float
    kind: str
    elements: tuple[int, ...]
    mode: tuple[int, ...]


class StickSlipMotion(NamedTuple):
    """The motion as segments of fixed mode, each with DOP853's dense output.

    ``rest_time[i]`` is the start of mass ``i``'s final run of segments in which
    sticking elements join it to the ground (``nan`` if it moves at the end),
    ``rest_position[i]`` its position then.
    """

    starts: np.ndarray
    ends: np.ndarray
    dense: tuple
    modes: tuple[tuple[int, ...], ...]
    events: tuple[StickSlipEvent, ...]
    rest_time: np.ndarray
    rest_position: np.ndarray

    def state(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Positions and velocities at times ``t``: two arrays ``(len(t), masses)``."""
        t = np.asarray(t, dtype=float)
        which = np.clip(np.searchsorted(self.starts, t, side="right") - 1, 0, len(self.starts) - 1)
        y = np.empty((t.size, self.dense[0](self.starts[0]).size))
        for s in np.unique(which):
            y[which == s] = self.dense[s](t[which == s]).T
        n = y.shape[1] // 2
        return y[:, :n], y[:, n:]


def _incidence(n: int, links: Sequence[SpringLink | FrictionLink]) -> np.ndarray:
    """``(n, len(links))``: +1 at a link's second mass, -1 at its first (the ground has no row)."""
    b = np.zeros((n, len(links)))
    for e, link in enumerate(links):
        if link.second >= 0:
            b[link.second, e] += 1.0
        if link.first >= 0:
            b[link.first, e] -= 1.0
    return b


class _StickSlip:
    """The equations of one mode: ``mode[e]`` is 0 (stick) or the slip direction +-1.

    Masses joined by sticking elements share their acceleration; the sticking
    forces are the multipliers of that constraint:

        M a + B_S f_S = F(t) - B_K K B_K^T x - B_D (s tau + c w)_D,   B_S^T a = 0,

    with ``B`` the incidence of each element (+1 at ``second``, -1 at ``first``).
    The system is nonsingular: ``M`` is positive and ``B_S`` has full column
    rank when the friction elements form a forest with the ground.
    """

    def __init__(self, system: StickSlipSystem) -> None:
        self.m = np.array(system.masses, dtype=float)
        n = self.m.size
        self.bk = _incidence(n, system.springs)
        self.k = np.array([s.stiffness for s in system.springs], dtype=float)
        self.bf = _incidence(n, system.frictions)
        self.tau = np.array([f.threshold for f in system.frictions], dtype=float)
        self.c = np.array([0.0 if math.isinf(f.gamma) else 1.0 / f.gamma for f in system.frictions])
        self.links = system.frictions
        self.loads = system.loads

    def load(self, t: float, on: tuple[bool, ...]) -> np.ndarray:
        out = np.zeros(self.m.size)
        for (i, (p, omega, phase, _)), active in zip(self.loads, on):
            out[i] += p * math.sin(omega * t + phase) if active else 0.0
        return out

    def solve(self, t: float, y: np.ndarray, mode: np.ndarray, on: tuple[bool, ...]) -> tuple[np.ndarray, np.ndarray]:
        """Accelerations (m/s^2) and friction forces (N) of the mode at state ``y = (x, v)``."""
        n = self.m.size
        x, v = y[:n], y[n:]
        stick = mode == 0
        f = np.where(stick, 0.0, mode * self.tau + self.c * (self.bf.T @ v))
        rhs = self.load(t, on) - self.bk @ (self.k * (self.bk.T @ x)) - self.bf @ f
        bs = self.bf[:, stick]
        kkt = np.block([[np.diag(self.m), bs], [bs.T, np.zeros((bs.shape[1],) * 2)]])
        sol = np.linalg.solve(kkt, np.concatenate([rhs, np.zeros(bs.shape[1])]))
        f[stick] = sol[n:]
        return sol[:n], f

    def grounded(self, mode: np.ndarray) -> np.ndarray:
        """Masses joined to the ground by sticking elements."""
        reached, changed = {-1}, True
        while changed:
            changed = False
            for link, md in zip(self.links, mode):
                ends = {link.first, link.second}
                if md == 0 and len(ends & reached) == 1:
                    reached |= ends
                    changed = True
        return np.array([i in reached for i in range(self.m.size)])

    def project(self, v: np.ndarray, zero: list[int]) -> np.ndarray:
        """The nearest velocities (kinetic metric) with ``w_e = 0`` for ``e`` in ``zero``.

        The impulse it takes is of the size of the event location's error.
        """
        if not zero:
            return v
        b = self.bf[:, zero]
        lam = np.linalg.solve(b.T @ (b / self.m[:, None]), b.T @ v)
        return v - (b @ lam) / self.m

    def consistent(self, t: float, y: np.ndarray, mode: np.ndarray, zero: list[int], on: tuple[bool, ...]) -> bool:
        """Sticking forces within their bands, and every element of ``zero`` that is
        assumed to slip accelerating in its direction (by a margin of 1e-9 of
        ``tau/m``, so that the degenerate point where both hold is refused)."""
        a, f = self.solve(t, y, mode, on)
        stick = mode == 0
        if np.any(np.abs(f[stick]) > self.tau[stick] * (1 + 1e-9)):
            return False
        margin = 1e-9 * np.max(self.tau) / np.min(self.m)
        rel = self.bf.T @ a
        return all(rel[e] * mode[e] > margin for e in zero if mode[e] != 0)

    def select(self, t: float, y: np.ndarray, mode: np.ndarray, zero: list[int], on: tuple[bool, ...]) -> np.ndarray:
        """The one consistent mode among the ``3^len(zero)`` choices for the elements at ``w = 0``."""
        found = []
        for choice in itertools.product((0, 1, -1), repeat=len(zero)):
            trial = mode.copy()
            trial[zero] = choice
            if self.consistent(t, y, trial, zero, on):
                found.append(trial)
        if len(found) != 1:
            raise ArithmeticError(
                f"t = {t!r}: {len(found)} consistent modes for the elements {zero} at rest (expected exactly 1)"
            )
        return found[0]

    def events(self, mode: np.ndarray, on: tuple[bool, ...]) -> list[Callable]:
        """Terminal events: a slipping element's rate reaching 0, a sticking one's force its threshold."""
        n, out = self.m.size, []
        for e, md in enumerate(mode):
            if md == 0:

                def event(t, y, e=e):
                    return self.tau[e] - abs(self.solve(t, y, mode, on)[1][e])

                event.direction = -1.0
            else:

                def event(t, y, e=e):
                    return self.bf[:, e] @ y[n:]

                event.direction = -float(md)
            event.terminal = True
            out.append(event)
        return out


def _zero_set(net: _StickSlip, v: np.ndarray, mode: np.ndarray, fired: Sequence[int]) -> list[int]:
    """Elements sticking, just stopped, or slipping at a rate within 1e-9 of the speeds."""
    w = net.bf.T @ v
    tol = 1e-9 * float(np.max(np.abs(v), initial=0.0))
    return [e for e in range(mode.size) if mode[e] == 0 or e in fired or abs(w[e]) <= tol]


def _rest(starts: list[float], grounded: list[np.ndarray], x_end: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start of each mass's final run of grounded segments, and its position at the end."""
    rest = np.full(x_end.size, math.nan)
    for i in range(x_end.size):
        for start, g in zip(reversed(starts), reversed(grounded)):
            if not g[i]:
                break
            rest[i] = start
    return rest, np.where(np.isnan(rest), math.nan, x_end)


def stick_slip_motion(
    system: StickSlipSystem, t_end: float, *, rtol: float = 1e-12, atol: float = 1e-14, max_events: int = 2000
) -> StickSlipMotion:
    """Event-driven integration of a network of masses, springs and Bingham/Coulomb elements.

    Between events the mode (each friction element sticking or slipping one
    way) is fixed and the motion is a smooth ODE, integrated by DOP853 at
    ``rtol``, ``atol`` with terminal events; a load switching off ends a
    segment too.  At a stop, or at a switch, the elements at ``w = 0`` are
    given the one consistent mode of the ``3^m`` choices (unique for
    positive masses: the conditions are a linear complementarity problem with
    a positive definite matrix; more than one or none raises).  At a
    breakaway the element slips in the direction of its force: there the slip
    force equals the sticking force, so nothing else changes at that instant.

    Raises
    ------
    ArithmeticError
        If a mode is not unique or more than ``max_events`` segments are needed.
    """
    net, n = _StickSlip(system), len(system.masses)
    breaks = sorted({u for _, (_, _, _, u) in system.loads if 0 < u < t_end} | {t_end})
    t, y = 0.0, np.array(system.x0 + system.v0, dtype=float)
    on = tuple(t < u for _, (_, _, _, u) in system.loads)
    w0 = net.bf.T @ y[n:]
    mode = np.sign(w0).astype(int)
    mode = net.select(t, y, mode, [e for e in range(mode.size) if w0[e] == 0], on)
    starts, ends, dense, modes, grounded, events = [], [], [], [], [], []
    for _ in range(max_events):
        stop = next(b for b in breaks if b > t)
        sol = solve_ivp(
            lambda s, q, mode=mode, on=on: np.concatenate([q[n:], net.solve(s, q, mode, on)[0]]),
            (t, stop),
            y,
            method="DOP853",
            rtol=rtol,
            atol=atol,
            events=net.events(mode, on),
            dense_output=True,
        )
        if sol.t[-1] > t:
            starts.append(t)
            ends.append(sol.t[-1])
            dense.append(sol.sol)
            modes.append(tuple(int(m) for m in mode))
            grounded.append(net.grounded(mode))
        t, y = float(sol.t[-1]), sol.y[:, -1].copy()
        if sol.status == 0 and t >= t_end:
            rest_time, rest_x = _rest(starts, grounded, y[:n])
            if all(grounded[-1]) and not any(o and load[1][0] != 0 for o, load in zip(on, system.loads)):
                events = sorted(
                    [*events, StickSlipEvent(float(np.max(rest_time)), "rest", (), modes[-1])], key=lambda e: e.time
                )
            return StickSlipMotion(
                np.array(starts), np.array(ends), tuple(dense), tuple(modes), tuple(events), rest_time, rest_x
            )
        fired = [e for e, te in enumerate(sol.t_events) if te.size and te[-1] == t] if sol.status == 1 else []
        mode, kind = _next_mode(net, t, y, mode, fired, on)
        if kind == "switch":
            on = tuple(t < u for _, (_, _, _, u) in system.loads)
            y[n:] = net.project(y[n:], _zero_set(net, y[n:], mode, []))
            mode = net.select(t, y, mode, _zero_set(net, y[n:], mode, []), on)
        if kind == "stop" and mode[fired[0]] != 0:
            kind = "reversal"
        events.append(StickSlipEvent(t, kind, tuple(fired), tuple(int(m) for m in mode)))
    raise ArithmeticError(f"more than max_events = {max_events} segments before t_end = {t_end}")


def _next_mode(
    net: _StickSlip, t: float, y: np.ndarray, mode: np.ndarray, fired: list[int], on: tuple[bool, ...]
) -> tuple[np.ndarray, str]:
    """The mode after the event(s) ``fired`` (none: a load switch, handled by the caller)."""
    n = net.m.size
    if not fired:
        return mode, "switch"
    if all(mode[e] == 0 for e in fired):  # breakaway: slip in the direction of the force
        f = net.solve(t, y, mode, on)[1]
        new = mode.copy()
        new[fired] = np.sign(f[fired]).astype(int)
        return new, "breakaway"
    if any(mode[e] == 0 for e in fired):
        raise ArithmeticError(f"t = {t!r}: a stop and a breakaway at once ({fired})")
    zero = _zero_set(net, y[n:], mode, fired)
    y[n:] = net.project(y[n:], zero)
    return net.select(t, y, mode, zero, on), "stop"


def den_hartog_amplitude(r: float, friction_ratio: float) -> float:
    """Den Hartog's (1931) steady amplitude ``X k/P`` of the Coulomb oscillator without stops, as published.

    ``X k/P = sqrt(1/(1 - r^2)^2 - (F/P)^2 (U/r)^2)``, ``U = sin(pi/r)/(1 + cos(pi/r))``,
    ``r = omega/omega_n`` (Den Hartog, Trans. ASME 53, APM-53-9, 1931; his
    textbook *Mechanical Vibrations*, section on Coulomb damping); ``nan``
    where the root is imaginary.
    """
    u = math.sin(math.pi / r) / (1 + math.cos(math.pi / r))
    square = 1 / (1 - r * r) ** 2 - (friction_ratio * u / r) ** 2
    return math.sqrt(square) if square >= 0 else math.nan


def den_hartog_boundary(r: float) -> float:
    """The largest ``F/P`` of Coulomb motion without stops at ``r`` (valid for ``r`` above about 0.5).

    The mass leaves a turning point at once when the net force there exceeds
    ``F``; on Den Hartog's motion ``x(0) = -X``, ``P sin psi = -P X/a`` with
    ``a = (P/k)/(1 - r^2)``, so the condition is ``m omega^2 X > F``, i.e.
    ``r^2 X k/P > F/P``; with :func:`den_hartog_amplitude` squared it is
    ``F/P < r^2 / (|1 - r^2| sqrt(1 + r^2 U^2))``.
    """
    u = math.sin(math.pi / r) / (1 + math.cos(math.pi / r))
    return r * r / (abs(1 - r * r) * math.sqrt(1 + (r * u) ** 2))


def shoot_steady_slip(
    m: float, c: float, k: float, friction: float, p: float, omega: float
) -> tuple[float, float, float]:
    """``(X, psi, residual)`` of the symmetric steady motion by shooting over a half-period (numerical).

    From ``x(0) = -X``, ``v(0) = 0``, integrate ``m x'' + c x' + k x = P sin(omega t + psi) - F``
    over ``[0, pi/omega]`` (``solve_ivp``, DOP853, rtol 1e-12) and solve
    ``x(T/2) = X``, ``v(T/2) = 0`` for ``(X, psi)`` with ``scipy.optimize.fsolve``, started from the
    viscous response (``X = a``, ``psi = phi - pi/2``).  ``residual`` is the final ``max |x(T/2) - X|/X, |v(T/2)|/(omega X)``.
    """
    from scipy.optimize import fsolve

    half = math.pi / omega

    def end(unknowns: np.ndarray) -> np.ndarray:
        x_amp, psi = unknowns
        rhs = lambda t, z: [z[1], (p * math.sin(omega * t + psi) - friction - c * z[1] - k * z[0]) / m]  # noqa: E731
        sol = solve_ivp(rhs, (0.0, half), [-x_amp, 0.0], method="DOP853", rtol=1e-12, atol=1e-14 * abs(x_amp))
        return np.array([sol.y[0, -1] - x_amp, sol.y[1, -1] / omega])

    a = p / math.hypot(k - m * omega**2, c * omega)
    phi = math.atan2(c * omega, k - m * omega**2)
    x_amp, psi = fsolve(end, [a, phi - math.pi / 2], xtol=1e-13)
    residual = float(np.max(np.abs(end(np.array([x_amp, psi])))) / abs(x_amp))
    return float(x_amp), float(psi), residual
