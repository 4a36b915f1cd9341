"""The closed-form slip phases of the ``exact`` method (:mod:`lumped.solvers.exact`).

In slip with direction ``s = +-1`` the dashpot force is ``F_d = s mu_s N_f +
c v`` (eq. 7, with ``c = 1/gamma``), so ``m x'' + c x' + k x = F(t) - s mu_s
N_f``, a linear ODE with constant coefficients solved in closed form
(particular solution of the sine plus the free oscillator, written with its
characteristic roots): :class:`SlipMotion`.

Zeros of ``v`` are found in closed form when the force is constant over the
phase (the velocity is then a damped sine, or a sum of two exponentials that
vanishes at most once); under a sinusoidal force they are bracketed on a grid
graded from the fastest time scale of the phase to the slowest relevant one and
refined with Brent's method (:func:`lumped.numerics.roots.brentq`) to a few
ulps of the phase time.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from lumped.numerics.roots import brentq

__all__ = ["SlipMotion"]

_BLOCK = 256  # samples per block when bracketing a zero of v
_MAX_BLOCKS = 100_000  # bound on the search for one zero of v (2.6e7 samples)
_PER_SCALE = 32  # samples per time scale of the bracketing grid
_GRADE = 1.25  # growth factor of the grid from the fast to the slow time scale


@dataclass(frozen=True)
class _Modes:
    """Free motion of ``m x'' + c x' + k x = 0``, from the roots of ``m l^2 + c l + k``.

    ``kind`` is ``"under"`` (roots ``-h +- i q``), ``"critical"`` (double root
    ``slow = fast = -h``) or ``"over"`` (real roots ``fast < slow < 0``).
    ``h = c/(2m)`` (1/s) and ``omega2 = k/m`` (1/s^2).
    """

    kind: str
    h: float
    omega2: float
    q: float = 0.0
    slow: float = 0.0
    fast: float = 0.0


def _modes(m: float, c: float, k: float) -> _Modes:
    """Characteristic roots, computed without forming ``c^2`` or ``4 m k``.

    Notes
    -----
    With ``zeta = c / (2 sqrt(m k))``, the roots are ``-h (1 +- sqrt(1 - 1/zeta^2))``.
    The slow one is written ``-2 k / (c (1 + r))`` (their product is ``k/m``),
    which keeps its digits when ``zeta`` is large.
    """
    h, omega_n = c / (2 * m), math.sqrt(k) / math.sqrt(m)
    modes = _Modes("under", h, k / m)
    zeta = h / omega_n
    if zeta < 1:
        modes = dataclasses.replace(modes, q=omega_n * math.sqrt((1 - zeta) * (1 + zeta)))
    elif zeta == 1:
        modes = dataclasses.replace(modes, kind="critical", slow=-h, fast=-h)
    else:
        r = math.sqrt((1 - 1 / zeta) * (1 + 1 / zeta))
        slow, fast = -2 * k / (c * (1 + r)), -h * (1 + r)
        modes = dataclasses.replace(modes, kind="over", slow=slow, fast=fast)
    rates = (modes.h, modes.omega2, modes.q, modes.fast)
    if not all(math.isfinite(r) for r in rates):
        raise ValueError(
            f"mass: the rates c/m = {h:.3g} 1/s and k/m = {k / m:.3g} 1/s^2 of the oscillator "
            "exceed double precision; raise mass (or lower stiffness or 1/gamma)"
        )
    return modes


def _first_zero(a: float, b: float) -> float:
    """Smallest ``theta > 0`` with ``a cos(theta) + b sin(theta) = 0`` (0 if immediate).

    ``tan(theta) = -a/b``; the arctangent of the ratio keeps its digits when the
    zero is close to 0 or to ``pi`` (a mass stopped at once by a huge band).
    """
    if b == 0:
        return 0.0 if a == 0 else math.pi / 2
    ratio = -a / b
    if ratio == 0 and a != 0:  # underflow: the zero is at 0+ or just before pi
        return 0.0 if a * b < 0 else math.pi
    theta = math.atan(ratio)
    return theta if theta > 0 else theta + math.pi


@dataclass(frozen=True)
class SlipMotion:
    """Closed-form motion ``m x'' + c x' + k x = P sin(w t + ph) - s tau``.

    ``t0, x0, v0`` is the state at the start of the phase; ``P, w, ph`` are the
    canonical forcing parameters (``P = 0`` when the force is off).
    """

    m: float
    c: float
    k: float
    s_tau: float
    P: float
    w: float
    ph: float
    t0: float
    x0: float
    v0: float

    @cached_property
    def modes(self) -> _Modes:
        """Roots of the free oscillator (see :func:`_modes`)."""
        return _modes(self.m, self.c, self.k)

    @property
    def is_free(self) -> bool:
        """True when the force is constant over the phase (no sine)."""
        return self.P == 0 or self.w == 0

    def _particular(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        m, c, k, P, w = self.m, self.c, self.k, self.P, self.w
        xc = -self.s_tau / k
        if P == 0:
            return np.full_like(t, xc), np.zeros_like(t)
        theta = w * t + self.ph
        stiff, drag = k - m * w * w, c * w
        if stiff == 0 and drag == 0:  # undamped resonance: secular growth t cos(theta)
            a = -P / (2 * m * w)
            return xc + a * t * np.cos(theta), a * np.cos(theta) - a * w * t * np.sin(theta)
        norm = math.hypot(stiff, drag)  # the amplitudes without squaring k (k = 1e300)
        A, B = P * (stiff / norm) / norm, -P * (drag / norm) / norm
        sin, cos = np.sin(theta), np.cos(theta)
        return xc + A * sin + B * cos, w * (A * cos - B * sin)

    def particular_omega_derivative(self, t: float) -> tuple[float, float] | None:
        """``d(x_p, v_p)/dw`` at a fixed ``t``: the particular solution's derivative in the forcing frequency,
        ``None`` at an undamped resonance (``k = m w^2``, ``c = 0``: secular growth, no such form).

        With ``x_p = x_c + A sin(theta) + B cos(theta)``, ``theta = w t + ph``, ``A = P s/n``, ``B = -P d/n``,
        ``s = k - m w^2``, ``d = c w``, ``n = s^2 + d^2``: ``dA/dw = P (s' n - s n')/n^2``, ``dB/dw = -P (d' n -
        d n')/n^2`` with ``s' = -2 m w``, ``d' = c``, ``n' = 2 (s s' + d d')``, and ``theta`` moves by ``t``.
        """
        m, c, k, P, w = self.m, self.c, self.k, self.P, self.w
        if P == 0:
            return 0.0, 0.0
        stiff, drag = k - m * w * w, c * w
        if stiff == 0 and drag == 0:
            return None
        norm = math.hypot(stiff, drag)
        A, B = P * (stiff / norm) / norm, -P * (drag / norm) / norm
        d_stiff, d_drag = -2 * m * w, c
        d_norm2 = 2 * (stiff * d_stiff + drag * d_drag) / norm**2  # n'/n
        dA = P * (d_stiff - stiff * d_norm2) / norm**2
        dB = -P * (d_drag - drag * d_norm2) / norm**2
        theta = w * t + self.ph
        sin, cos = math.sin(theta), math.cos(theta)
        dx = dA * sin + dB * cos + t * (A * cos - B * sin)
        dv = (A * cos - B * sin) + w * (dA * cos - dB * sin) - w * t * (A * sin + B * cos)
        return dx, dv

    def _free(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``exp(sigma tau) C(tau)`` and ``exp(sigma tau) S(tau)`` of the free oscillator.

        ``C`` and ``S`` solve the free equation with ``C(0) = 1, C'(0) = -h`` and
        ``S(0) = 0, S'(0) = 1`` shifted by ``exp(-h tau)``: the displacement is
        ``ec y0 + es (h y0 + y0')``.  For real roots ``ec = (e_s + e_f)/2`` and
        ``es = (e_s - e_f)/(slow - fast)``, the difference taken with ``expm1``
        where the two exponentials are close.
        """
        md = self.modes
        with np.errstate(over="ignore", under="ignore"):  # exp(-huge) = 0 is the decay
            return self._free_impl(md, tau)

    @staticmethod
    def _free_impl(md: _Modes, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        if md.kind == "under":
            e = np.exp(-md.h * tau)
            return e * np.cos(md.q * tau), e * np.sin(md.q * tau) / md.q
        if md.kind == "critical":
            e = np.exp(-md.h * tau)
            return e, tau * e
        gap = md.slow - md.fast
        e_slow, e_fast = np.exp(md.slow * tau), np.exp(md.fast * tau)
        close = gap * tau < 1.0
        diff = np.where(close, e_fast * np.expm1(np.minimum(gap * tau, 1.0)), e_slow - e_fast)
        return 0.5 * (e_slow + e_fast), diff / gap

    @cached_property
    def _offsets(self) -> tuple[float, float]:
        """Initial displacement and velocity relative to the particular solution (computed once per phase:
        :meth:`state` is called at every sample of a scan)."""
        xp0, vp0 = self._particular(np.asarray(self.t0))
        return float(self.x0 - xp0), float(self.v0 - vp0)

    def state(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Displacement and velocity at times ``t >= t0``."""
        t = np.asarray(t, dtype=float)
        y0, dy0 = self._offsets
        ec, es = self._free(t - self.t0)
        h, omega2 = self.modes.h, self.modes.omega2
        y = ec * y0 + es * (h * y0 + dy0)
        dy = ec * dy0 - es * (omega2 * y0 + h * dy0)
        xp, vp = self._particular(t)
        return xp + y, vp + dy

    def flow_matrix(self, duration: float) -> np.ndarray:
        """``exp(A duration)``, ``A = [[0, 1], [-k/m, -c/m]]``: the derivative of ``(x, v)`` at
        ``t0 + duration`` with respect to ``(x0, v0)`` at a fixed ``t0`` (2 x 2, from :meth:`_free`)."""
        ec, es = (float(a) for a in self._free(np.asarray(float(duration))))
        h, omega2 = self.modes.h, self.modes.omega2
        return np.array([[ec + h * es, es], [-omega2 * es, ec - h * es]])

    def acceleration(self, t: float, x: float, v: float) -> float:
        """``(P sin(w t + ph) - s tau - c v - k x)/m`` (m/s^2): the slip phase's equation at ``(t, x, v)``."""
        force = self.P * math.sin(self.w * t + self.ph) if self.P else 0.0
        return (force - self.s_tau - self.c * v - self.k * x) / self.m

    def velocity(self, t: float) -> float:
        """``v(t)`` as a float (m/s)."""
        return float(self.state(t)[1])

    def time_scales(self) -> tuple[float, float]:
        """Fastest time scale of the phase and the slowest one a zero of ``v`` can hide in (s).

        The fast one is ``1/omega_n`` (or the fast decay time); the slow one is
        the shortest interval between two sign changes of ``v`` once the fast
        transient is gone: half a damped period, the slow decay time, half a
        forcing period.
        """
        md = self.modes
        if md.kind == "under":
            fast, slow = 1 / math.sqrt(md.omega2), math.pi / md.q
        else:
            fast, slow = -1 / md.fast, -1 / md.slow
        if self.P != 0 and self.w > 0:
            slow = min(slow, math.pi / self.w)
        return min(fast, slow), slow

    def first_stop(self, t_lim: float, direction: int) -> float | None:
        """First time in ``(t0, t_lim]`` at which ``v`` returns to zero, or ``None``.

        The result does not depend on ``t_lim`` beyond whether it is reached,
        so a solution extended to a later ``t_end`` keeps its events.
        """
        if not self.is_free:
            return self._scan(t_lim, direction)
        tau = self._free_stop()
        if tau is None or self.t0 + tau > t_lim:
            return None
        if self.modes.kind != "under" and tau > 0:
            return self._polish(self.t0 + tau, direction)
        return self.t0 + tau

    def _free_stop(self) -> float | None:
        """Closed-form first zero ``tau > 0`` of the free velocity, or ``None``.

        Notes
        -----
        Underdamped: ``v = exp(-h tau) (a cos q tau + b sin q tau)`` with
        ``a = y0'`` and ``b = -(omega2 y0 + h y0')/q`` (:func:`_first_zero`).  Real roots:
        ``v = l_s A e^{l_s tau} + l_f B e^{l_f tau}`` vanishes at most once, at
        ``tau = log(-l_f B / (l_s A)) / (l_s - l_f)``, taken through logarithms
        so that no ratio overflows.
        """
        y0, dy0 = self._offsets
        if y0 == 0 and dy0 == 0:
            return 0.0  # at rest on the centre: it stops at once
        md = self.modes
        if md.kind == "under":
            return _first_zero(dy0, -(md.omega2 * y0 + md.h * dy0) / md.q) / md.q
        if dy0 == 0:
            return None  # from rest a sum of two exponentials has no further zero
        if md.kind == "critical":
            tau = -dy0 / (md.slow * (dy0 - md.slow * y0))
            return tau if tau > 0 else None
        num, den = md.slow * y0 - dy0, md.fast * y0 - dy0  # l_s y0 - y0', l_f y0 - y0'
        if num == 0 or den == 0 or (num > 0) != (den > 0):
            return None  # one exponential only, or both of the sign of v: no zero
        log_rates = math.log(-md.fast) - math.log(-md.slow)
        tau = (log_rates + math.log(abs(num)) - math.log(abs(den))) / (md.slow - md.fast)
        return tau if tau > 0 else None

    def _polish(self, t: float, direction: int) -> float:
        """Brent's method on ``t +- 1e-6 (t - t0)`` when that brackets the zero, else ``t``."""
        a, b = self.t0 + (t - self.t0) * (1 - 1e-6), self.t0 + (t - self.t0) * (1 + 1e-6)
        if not direction * self.velocity(a) > 0 >= direction * self.velocity(b):
            return t
        return brentq(self.velocity, a, b)

    def _grid(self, t_lim: float):  # noqa: ANN202 (a generator of arrays)
        """Blocks of sample times ``t0 + tau``: geometric from the fast scale, then uniform.

        The grid does not depend on ``t_lim`` (only where it stops), so the
        brackets found before ``t_lim`` are those of any later ``t_lim``.
        """
        fast, slow = (s / _PER_SCALE for s in self.time_scales())
        # Below 1e-12 of the slow spacing (or a few ulps of t0) v is rounding
        # noise at the start of a slip from rest: start the grid there.
        fast = max(fast, 1e-12 * slow, 4 * math.ulp(self.t0))
        geo = np.zeros(0)
        if fast * (_GRADE - 1) < slow:
            n_geo = math.ceil(math.log(slow / (fast * (_GRADE - 1))) / math.log(_GRADE))
            geo = fast * _GRADE ** np.arange(n_geo)
            yield from np.array_split(self.t0 + geo, -(-n_geo // _BLOCK))
        start = geo[-1] if geo.size else 0.0
        blocks = (t_lim - self.t0 - start) / (slow * _BLOCK) + 1
        if blocks > _MAX_BLOCKS:
            raise ValueError(
                f"t_end: a slip phase would need {blocks * _BLOCK:.3g} samples to bracket its "
                f"stop, more than {_MAX_BLOCKS * _BLOCK:.3g}; shorten t_end or use backward Euler"
            )
        for j in range(math.ceil(blocks)):
            yield self.t0 + (start + slow * (j * _BLOCK + np.arange(1, _BLOCK + 1)))

    def _scan(self, t_lim: float, direction: int) -> float | None:
        """First zero of ``v`` after ``t0``, bracketed on :meth:`_grid`, refined by Brent.

        A zero is bracketed where ``v`` changes sign between two samples, or, before that, where ``v`` dips
        to zero and back between two samples that both have the slip's sign: there ``s v`` has a local
        minimum, so ``s a`` (``a = v'``) goes from negative to positive; the minimum is located by Brent's
        method on ``a`` and, if ``s v <= 0`` there, the zero is bracketed before it.  The samples alone would
        step over a dip shorter than their spacing (a stop that only just happens, near a grazing).
        """
        # From rest (v0 = 0) the acceleration at t0 is the band's edge to round-off: no dip before the first sample
        lo, turning = self.t0, math.inf if self.v0 == 0 else direction * self.acceleration(self.t0, self.x0, self.v0)
        for grid in self._grid(t_lim):
            if lo >= t_lim:
                return None
            x, v = self.state(grid)
            ahead = direction * v <= 0
            first = int(np.argmax(ahead)) if ahead.any() else grid.size
            times = np.concatenate([[lo], grid])
            rate = np.concatenate([[turning], direction * self._accelerations(grid, x, v)])
            for j in np.flatnonzero((rate[:-1] < 0) & (rate[1:] > 0)):
                if j > first or times[j] >= t_lim:
                    break
                t_min = brentq(self._acceleration_at, float(times[j]), float(times[j + 1]))
                if direction * self.velocity(t_min) <= 0:
                    return self._refine(float(times[j]), t_min, t_lim, direction)
            if ahead.any():
                a = lo if first == 0 else float(grid[first - 1])
                return self._refine(a, float(grid[first]), t_lim, direction)
            lo, turning = float(grid[-1]), float(rate[-1])
        return None

    def _accelerations(self, t: np.ndarray, x: np.ndarray, v: np.ndarray) -> np.ndarray:
        """:meth:`acceleration` at the times ``t`` with the states ``(x, v)`` there (arrays)."""
        force = self.P * np.sin(self.w * t + self.ph) if self.P else 0.0
        return (force - self.s_tau - self.c * v - self.k * x) / self.m

    def _acceleration_at(self, t: float) -> float:
        """``a(t)`` of the motion (m/s^2)."""
        x, v = (float(a) for a in self.state(t))
        return self.acceleration(t, x, v)

    def _refine(self, a: float, b: float, t_lim: float, direction: int) -> float | None:
        """The zero of ``v`` in the bracket ``(a, b]``, if it lies before ``t_lim``."""
        if a >= t_lim or (b > t_lim and direction * self.velocity(t_lim) > 0):
            return None
        if a == self.t0 and self.v0 == 0:
            a = self._leave_rest(b, direction)
            if a is None:
                return self.t0
        if self.velocity(b) == 0:
            return min(b, t_lim)
        root = brentq(self.velocity, a, b)
        return min(root, t_lim)

    def _leave_rest(self, b: float, direction: int) -> float | None:
        """A time in ``(t0, b)`` where the motion from rest has the sign ``direction``."""
        tau = b - self.t0
        for _ in range(60):
            tau *= 0.5
            if direction * self.velocity(self.t0 + tau) > 0:
                return self.t0 + tau
        return None
