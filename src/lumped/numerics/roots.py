"""Brent's method on a bracket, in Python floats (the algorithm of SciPy's ``brentq``).

Brent (1973), *Algorithms for Minimization without Derivatives*, ch. 4, in
the form of SciPy's ``scipy/optimize/Zeros/brentq.c`` (C. Harris): inverse
quadratic extrapolation or secant steps, safeguarded by bisection.  The
solvers find their events with it (the stops of ``exact`` and
``event-driven``, the switches of ``event-capturing``), with the tolerances
:data:`XTOL`, :data:`RTOL` and :data:`MAXITER` unless a method needs its own;
importing ``scipy.optimize`` for a stop on a polynomial would cost more than
the whole solve.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable

__all__ = ["MAXITER", "RTOL", "XTOL", "brentq"]

#: Absolute tolerance on the root: below every scale of the package, so that ``RTOL`` decides.
XTOL = 1e-300
#: Relative tolerance on the root: ``4 eps``, the least SciPy's ``brentq`` accepts.
RTOL = 4 * sys.float_info.epsilon
#: Bound on the iterations.
MAXITER = 200


def _trial(xcur: float, xpre: float, xblk: float, fcur: float, fpre: float, fblk: float) -> float:
    """The secant step (when the bracket end is the previous point) or inverse quadratic extrapolation.

    A division by zero (a difference or a product of tiny values that
    underflows) gives ``+-inf`` or NaN in C, which the caller refuses for a
    bisection; Python raises instead, so the step is ``inf`` then.
    """
    try:
        if xpre == xblk:
            return -fcur * (xcur - xpre) / (fcur - fpre)
        dpre = (fpre - fcur) / (xpre - xcur)
        dblk = (fblk - fcur) / (xblk - xcur)
        return -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
    except ZeroDivisionError:
        return math.inf


def _value(f: Callable[[float], float], x: float) -> float:
    """``f(x)``, refused if NaN (as SciPy's ``brentq`` refuses it: no sign, no bracket)."""
    fx = f(x)
    if fx != fx:
        raise ValueError(f"brentq: f({x!r}) is NaN")
    return fx


def brentq(
    f: Callable[[float], float], a: float, b: float, xtol: float = XTOL, rtol: float = RTOL, maxiter: int = MAXITER
) -> float:
    """A zero of ``f`` in ``[a, b]`` (``f(a) f(b) <= 0``) to ``xtol + rtol |x|``.

    The iterates are those of SciPy's C code, bit for bit: signs are
    compared, not multiplied (a product of two values below about 1e-162
    underflows to zero; SciPy compares sign bits since scipy/scipy#17664),
    and a division by zero in a trial step leads to bisection, as C's
    ``inf`` does (:func:`_trial`).

    Raises
    ------
    ValueError
        If ``f(a)`` and ``f(b)`` have the same sign, ``f`` is NaN, or ``maxiter`` passes.
    """
    xpre, xcur = a, b
    fpre, fcur = _value(f, xpre), _value(f, xcur)
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    if (fpre < 0) == (fcur < 0):
        raise ValueError("brentq: f(a) and f(b) must have opposite signs")
    xblk = fblk = spre = scur = 0.0
    for _ in range(maxiter):
        if fpre != 0 and fcur != 0 and (fpre < 0) != (fcur < 0):  # the bracket is [xpre, xcur]
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
    raise ValueError(f"brentq: no convergence in {maxiter} iterations")
