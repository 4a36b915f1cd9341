"""DOP853 on a few floats: SciPy's ``DOP853`` stepper without numpy in the step.

The event-driven method integrates a 2-state ODE per slip phase
(:mod:`lumped.solvers.event_driven`), a few hundred steps per run.  SciPy's
``DOP853`` spends most of its time there in numpy calls on 2-element arrays;
this module does the same arithmetic with Python floats.  Tableau
(:mod:`lumped.numerics.dop853_tableau`), error estimate, step-size controller and
initial step are SciPy's (``scipy/integrate/_ivp/rk.py`` and ``common.py``,
after Hairer, Norsett and Wanner, Sec. II.4 and II.10), so the accepted steps
agree with SciPy's to round-off (``tests/test_dop853.py``); only the order
of summation inside a dot product can differ.

Notes
-----
One step of size ``h`` from ``(t, y)`` evaluates the stages
``k_s = f(t + c_s h, y + h sum_j a_sj k_j)`` for ``s = 1..11`` (``k_0 = f(t,
y)``), the solution ``y_new = y + h sum_s b_s k_s`` and ``k_12 = f(t + h,
y_new)``.  With ``e5 = sum_s E5_s k_s / sc`` and ``e3 = sum_s E3_s k_s / sc``
(componentwise, ``sc = atol + rtol max(|y|, |y_new|)``), the error norm is

    err = |h| |e5|^2 / sqrt(n (|e5|^2 + 0.01 |e3|^2)),

and the step is accepted when ``err < 1``; either way the next size is
``h min(10, max(0.2, 0.9 err^(-1/8)))``, not above ``h`` after a rejection.
The dense output on ``[t, t + h]`` adds stages 13-15 and is the polynomial
``y(t + theta h) = y + theta (F0 + (1 - theta) (F1 + theta (F2 + ...)))``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from operator import mul
from typing import NamedTuple

import numpy as np
from numpy.polynomial import polynomial as npoly

from lumped.numerics.dop853_tableau import E3, E5, N_STAGES, N_STAGES_EXTENDED, A, C, D

__all__ = ["Dop853", "Piece", "PiecewiseDense", "piece_critical_times", "piece_spread", "piece_value"]

Rhs = Callable[[float, Sequence[float]], Sequence[float]]
SAFETY, MIN_FACTOR, MAX_FACTOR = 0.9, 0.2, 10.0  # SciPy's rk.py
_EXPONENT = -1 / 8  # -1 / (error estimator order + 1)


class Piece(NamedTuple):
    """The dense output of one step: ``t_old`` (s), ``h`` (s), ``y_old`` and the 7 coefficients ``F[c]``."""

    t_old: float
    h: float
    y_old: tuple[float, ...]
    F: tuple[tuple[float, ...], ...]  # F[c][i]: component c, coefficient i


def piece_value(piece: Piece, t: float, c: int) -> float:
    """Component ``c`` of the dense output at time ``t`` (SciPy's ``Dop853DenseOutput`` on one float)."""
    x = (t - piece.t_old) / piece.h
    y, odd = 0.0, False
    for f in reversed(piece.F[c]):
        y = (y + f) * ((1 - x) if odd else x)
        odd = not odd
    return y + piece.y_old[c]


def piece_spread(piece: Piece, c: int) -> float:
    """A bound on how far component ``c`` of the dense output strays below its chord over the step.

    With ``theta = (t - t_old)/h`` in ``[0, 1]`` the dense output is ``y_old + theta F0 + theta (1 - theta) R``,
    ``R = F1 + theta (F2 + (1 - theta) (F3 + ...))`` (module Notes): every factor lies in ``[0, 1]``, so
    ``|R| <= |F1| + ... + |F6|`` and ``theta (1 - theta) <= 1/4``.  The component stays within
    ``(|F1| + ... + |F6|) / 4`` of the chord ``y_old + theta F0``, hence above ``min(y_old, y_old + F0)`` minus it.
    """
    return sum(abs(f) for f in piece.F[c][1:]) / 4


def piece_critical_times(piece: Piece, c: int) -> list[float]:
    """The times inside the step, increasing, where component ``c`` of the dense output has a zero derivative.

    The dense output is a polynomial of degree 7 in ``theta`` (module Notes); its derivative's roots (numpy's
    companion-matrix eigenvalues) with real part in ``(0, 1)`` are mapped to times.  The real part of a complex
    pair is kept too (a near-double root split by rounding): a time that is no extremum only adds a point at
    which the caller evaluates the component.  Every extremum of the polynomial inside the step is in the list.
    """
    poly = np.zeros(1)
    theta, one_minus = np.array([0.0, 1.0]), np.array([1.0, -1.0])
    for i, f in enumerate(reversed(piece.F[c])):  # piece_value's nesting, on coefficient arrays
        poly = npoly.polymul(npoly.polyadd(poly, [f]), one_minus if i % 2 else theta)
    roots = npoly.polyroots(npoly.polyder(poly)) if poly.size > 2 else []
    inside = sorted({float(r.real) for r in np.atleast_1d(roots) if 0 < r.real < 1})
    return [piece.t_old + piece.h * r for r in inside]


def _call(fun: Rhs, t: float, y: list[float]) -> Sequence[float]:
    """``fun(t, y)``, with infinities where a float power overflows (numpy's result, which SciPy sees)."""
    try:
        return fun(t, y)
    except OverflowError:
        return [math.inf] * len(y)


def _stages(fun: Rhs, t: float, y: Sequence[float], h: float, K: list[list[float]], stop: int) -> None:
    """Append stages ``len(K[0])`` to ``stop - 1`` to ``K`` (one list of stage values per component)."""
    for s in range(len(K[0]), stop):
        a = A[s]
        f = _call(fun, t + C[s] * h, [yc + sum(map(mul, a, Kc)) * h for yc, Kc in zip(y, K)])
        for Kc, fc in zip(K, f):
            Kc.append(fc)


def _error_norm(K: list[list[float]], h: float, scale: list[float]) -> float:
    """Hairer's combined 5th/3rd-order error norm of one step (module Notes)."""
    e5 = sum(_sq(sum(map(mul, E5, Kc)) / sc) for Kc, sc in zip(K, scale))
    e3 = sum(_sq(sum(map(mul, E3, Kc)) / sc) for Kc, sc in zip(K, scale))
    if e5 == 0 and e3 == 0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * len(scale))


def _sq(v: float) -> float:
    return v * v  # not v ** 2, which raises OverflowError where numpy gives inf


def _rms(values: Sequence[float]) -> float:
    return math.sqrt(sum(v * v for v in values) / len(values))


class Dop853:
    """SciPy's ``DOP853`` stepper, forwards in time, on a state of a few floats.

    ``fun(t, y)`` takes a list of floats and returns a sequence of floats.
    :meth:`step` takes one accepted step (returns ``False``, with
    ``status = "failed"``, if the step size falls below 10 ulps of ``t``);
    ``status`` becomes ``"finished"`` at ``t_bound``; :meth:`dense_output` is
    the last step's :class:`Piece`.  ``rtol`` must be at least ``100 eps``
    (SciPy raises smaller values) and ``atol`` holds one float per component.
    """

    def __init__(
        self, fun: Rhs, t0: float, y0: Sequence[float], t_bound: float, rtol: float, atol: Sequence[float]
    ) -> None:
        self.fun, self.t, self.t_bound, self.rtol, self.atol = fun, t0, t_bound, rtol, tuple(atol)
        self.y = [float(v) for v in y0]
        self.f = list(_call(fun, t0, self.y))
        self.status = "running" if t_bound > t0 else "finished"
        self.h_abs = self._initial_step() if t_bound > t0 else 0.0
        self.t_old: float | None = None
        self._last: tuple[float, list[float], list[list[float]]] | None = None  # h, y_old, K

    def _initial_step(self) -> float:
        """SciPy's ``select_initial_step`` (Hairer, Norsett and Wanner, Sec. II.4) for order 7."""
        t0, y0, f0, span = self.t, self.y, self.f, self.t_bound - self.t
        scale = [a + abs(v) * self.rtol for a, v in zip(self.atol, y0)]
        d0 = _rms([v / s for v, s in zip(y0, scale)])
        d1 = _rms([f / s for f, s in zip(f0, scale)])
        h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
        h0 = min(h0, span)
        f1 = _call(self.fun, t0 + h0, [v + h0 * f for v, f in zip(y0, f0)])
        d2 = _rms([(b - a) / s for a, b, s in zip(f0, f1, scale)]) / h0 if h0 > 0 else math.inf
        if d1 <= 1e-15 and d2 <= 1e-15:
            h1 = max(1e-6, h0 * 1e-3)
        else:
            h1 = (0.01 / max(d1, d2)) ** (1 / 8)
        return min(100 * h0, h1, span)

    def _attempt(self, h: float) -> tuple[list[float], list[list[float]], float]:
        """One trial step of size ``h``: the new state, the 13 stages and the error norm."""
        t, y = self.t, self.y
        K = [[fc] for fc in self.f]
        _stages(self.fun, t, y, h, K, N_STAGES)
        y_new = [yc + h * sum(map(mul, A[N_STAGES], Kc)) for yc, Kc in zip(y, K)]
        for Kc, fc in zip(K, _call(self.fun, t + h, y_new)):
            Kc.append(fc)
        scale = [a + max(abs(u), abs(w)) * self.rtol for a, u, w in zip(self.atol, y, y_new)]
        return y_new, K, _error_norm(K, h, scale)

    def step(self) -> bool:
        """Take one accepted step (SciPy's ``RungeKutta._step_impl``); ``False`` if it fails."""
        t = self.t
        min_step = 10 * abs(math.nextafter(t, math.inf) - t)
        h_abs, rejected = max(self.h_abs, min_step), False
        while True:
            if h_abs < min_step:
                self.status = "failed"
                return False
            t_new = min(t + h_abs, self.t_bound)
            h = t_new - t
            h_abs = abs(h)
            y_new, K, err = self._attempt(h)
            if err < 1:
                factor = MAX_FACTOR if err == 0 else min(MAX_FACTOR, SAFETY * err**_EXPONENT)
                self.h_abs = h_abs * (min(1.0, factor) if rejected else factor)
                break
            h_abs *= max(MIN_FACTOR, SAFETY * err**_EXPONENT)
            rejected = True
        self._last = (h, self.y, K)
        self.t_old, self.t, self.y, self.f = t, t_new, y_new, [Kc[-1] for Kc in K]
        if self.t >= self.t_bound:
            self.status = "finished"
        return True

    def dense_output(self) -> Piece:
        """The order-7 dense output of the last accepted step (SciPy's ``_dense_output_impl``)."""
        assert self._last is not None and self.t_old is not None, "no step taken yet"
        h, y_old, K = self._last
        if len(K[0]) < N_STAGES_EXTENDED:
            _stages(self.fun, self.t_old, y_old, h, K, N_STAGES_EXTENDED)
        F = []
        for Kc, yo, yn, fn in zip(K, y_old, self.y, self.f):
            dy = yn - yo
            head = (dy, h * Kc[0] - dy, 2 * dy - h * (fn + Kc[0]))
            F.append(head + tuple(h * sum(map(mul, d, Kc)) for d in D))
        return Piece(self.t_old, h, tuple(y_old), tuple(F))


class PiecewiseDense:
    """The dense outputs of consecutive steps, evaluated on many times at once (SciPy's ``OdeSolution``).

    ``ts`` are the breakpoints (one more than ``pieces``, increasing); a time
    on a breakpoint takes the earlier piece, a time outside ``[ts[0],
    ts[-1]]`` the nearest piece.  Numpy is used here across the times, never
    per step.
    """

    def __init__(self, ts: Sequence[float], pieces: Sequence[Piece]) -> None:
        self.ts = np.asarray(ts, dtype=float)
        self.t_old = np.array([p.t_old for p in pieces])
        self.h = np.array([p.h for p in pieces])
        self.y_old = np.array([p.y_old for p in pieces])  # (pieces, n)
        self.F = np.array([p.F for p in pieces])  # (pieces, n, 7)

    def __call__(self, t: np.ndarray) -> np.ndarray:
        """The state at times ``t`` (any shape ``S``), as an array of shape ``(n, *S)``."""
        t = np.asarray(t, dtype=float)
        flat = t.reshape(-1)
        seg = np.clip(np.searchsorted(self.ts, flat, side="left") - 1, 0, len(self.h) - 1)
        x = ((flat - self.t_old[seg]) / self.h[seg])[:, None]
        F = self.F[seg]
        y = np.zeros((flat.size, F.shape[1]))
        for i in range(F.shape[2] - 1, -1, -1):
            y += F[:, :, i]
            y *= x if (F.shape[2] - 1 - i) % 2 == 0 else 1 - x
        y += self.y_old[seg]
        return y.T.reshape((F.shape[1], *t.shape))
