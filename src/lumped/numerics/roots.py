"""Brent's method on a bracket, in Python floats (the algorithm of SciPy's ``brentq``).

Brent (1973), *Algorithms for Minimization without Derivatives*, ch. 4, in
the form of SciPy's ``scipy/optimize/Zeros/brentq.c`` (C. Harris): inverse
quadratic extrapolation or secant steps, safeguarded by bisection.  The
event-driven method finds its stops with it on a polynomial; importing
``scipy.optimize`` for that would cost more than the whole solve.
"""

from __future__ import annotations

from collections.abc import Callable

__all__ = ["brentq"]


def _trial(xcur: float, xpre: float, xblk: float, fcur: float, fpre: float, fblk: float) -> float:
    """The secant step (when the bracket end is the previous point) or inverse quadratic extrapolation."""
    if xpre == xblk:
        return -fcur * (xcur - xpre) / (fcur - fpre)
    dpre = (fpre - fcur) / (xpre - xcur)
    dblk = (fblk - fcur) / (xblk - xcur)
    return -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))


def brentq(f: Callable[[float], float], a: float, b: float, xtol: float, rtol: float, maxiter: int) -> float:
    """A zero of ``f`` in ``[a, b]`` (``f(a) f(b) <= 0``) to ``xtol + rtol |x|``.

    Raises
    ------
    ValueError
        If ``f(a)`` and ``f(b)`` have the same sign, or ``maxiter`` passes.
    """
    xpre, xcur = a, b
    fpre, fcur = f(xpre), f(xcur)
    if fpre * fcur > 0:
        raise ValueError("brentq: f(a) and f(b) must have opposite signs")
    if fpre == 0:
        return xpre
    if fcur == 0:
        return xcur
    xblk = fblk = spre = scur = 0.0
    for _ in range(maxiter):
        if fpre * fcur < 0:  # the bracket is [xpre, xcur]
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
        fcur = f(xcur)
    raise ValueError(f"brentq: no convergence in {maxiter} iterations")
