"""Brent's method on a bracket, in Python floats (the algorithm of SciPy's ``brentq``), and its tolerances.

Brent (1973), *Algorithms for Minimization without Derivatives*, ch. 4, in
the form of SciPy's ``scipy/optimize/Zeros/brentq.c`` (C. Harris): inverse
quadratic extrapolation or secant steps, safeguarded by bisection.  It is the
package's one root finder: the laws' resolvents and inverses and every
solver's events (the stops of ``exact`` and ``event-driven``, the switches of
``event-locating``) use it, with the tolerances below unless they say
otherwise; importing ``scipy.optimize`` for it would cost more than a whole
solve.
"""

from __future__ import annotations

import math
from collections.abc import Callable

__all__ = ["brentq", "NoConvergence", "EPS", "RTOL", "XTOL", "MAXITER"]

#: Machine epsilon of a double, ``2^-52`` (``numpy.finfo(float).eps``).
EPS = 2.0**-52
#: Relative tolerance on the root: ``4 eps``, the least SciPy's ``brentq`` accepts.
RTOL = 4 * EPS
#: Absolute tolerance on the root (m, s, N: the unit of ``x``): tiny, so that
#: :data:`RTOL` decides everywhere but within about ``1e-285`` of zero.
XTOL = 1e-300
#: Iterations allowed before :class:`NoConvergence`.
MAXITER = 200


class NoConvergence(ValueError):
    """Brent's method used up its ``maxiter`` iterations (a ``ValueError``, so callers may name it)."""


def _trial(xcur: float, xpre: float, xblk: float, fcur: float, fpre: float, fblk: float) -> float:
    """The secant step (when the bracket end is the previous point) or inverse quadratic extrapolation.

    A zero denominator (an underflow) gives ``inf``, as the C division
    gives ``+-inf`` or ``nan``: either fails the step test, so the method
    bisects, as SciPy's does.
    """
    if xpre == xblk:
        return -fcur * (xcur - xpre) / (fcur - fpre)  # |fcur| < |fpre|: never 0 / 0
    dpre = (fpre - fcur) / (xpre - xcur)
    dblk = (fblk - fcur) / (xblk - xcur)
    denominator = dblk * dpre * (fblk - fpre)
    return -fcur * (fblk * dblk - fpre * dpre) / denominator if denominator != 0 else math.inf


def _value(f: Callable[[float], float], x: float) -> float:
    """``f(x)`` as a float; a NaN refused, as SciPy refuses it."""
    fx = float(f(x))
    if math.isnan(fx):
        raise ValueError(f"brentq: the function value at x = {x!r} is NaN")
    return fx


def _opposite(u: float, w: float) -> bool:
    """True if ``u`` and ``w`` lie on opposite sides of zero (their sign bits, never their product, which may underflow)."""
    return math.copysign(1.0, u) != math.copysign(1.0, w)


def brentq(
    f: Callable[[float], float],
    a: float,
    b: float,
    xtol: float = XTOL,
    rtol: float = RTOL,
    maxiter: int = MAXITER,
) -> float:
    """A zero of ``f`` in ``[a, b]`` (``f(a)`` and ``f(b)`` of opposite signs, or one zero) to ``xtol + rtol |x|``.

    The iterates are SciPy's, operation for operation (``tests/test_brent.py``
    requires the same root bit for bit); the signs of ``f(a)`` and ``f(b)``
    are compared by their sign bits, as SciPy does, so values whose product
    underflows are still seen to bracket a root.

    Raises
    ------
    ValueError
        If ``f(a)`` and ``f(b)`` have the same sign, ``f`` returns NaN, or a
        tolerance is below what SciPy accepts (``xtol > 0``, ``rtol >=``
        :data:`RTOL`).
    NoConvergence
        If ``maxiter`` iterations pass (a ``ValueError``).
    """
    if not xtol > 0:
        raise ValueError(f"brentq: xtol must be > 0, got {xtol!r}")
    if not rtol >= RTOL:
        raise ValueError(f"brentq: rtol must be >= 4 eps = {RTOL!r}, got {rtol!r}")
    xpre, xcur = float(a), float(b)
    fpre, fcur = _value(f, xpre), _value(f, xcur)
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    if not _opposite(fpre, fcur):
        raise ValueError("brentq: f(a) and f(b) must have opposite signs")
    xblk = fblk = spre = scur = 0.0
    for _ in range(maxiter):
        if fpre != 0 and fcur != 0 and _opposite(fpre, fcur):  # the bracket is [xpre, xcur]
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):  # keep the better end as xcur
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            stry = _trial(xcur, xpre, xblk, fcur, fpre, fblk)
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre, scur = scur, stry  # a good short step
            else:
                spre = scur = sbis
        else:
            spre = scur = sbis
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        fcur = _value(f, xcur)
    raise NoConvergence(f"brentq: no convergence in {maxiter} iterations")
