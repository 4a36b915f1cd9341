"""The project's own sine: the Python twin of ``_sine.h``, bit for bit.

The compiled kernels do not call the C library's ``sin`` (which differs
between machines and blocks vectorisation): they evaluate ``_sine.h``, one
branch-free implementation for every lane width.  This module takes the same
IEEE operations in the same order, for a Python float (:func:`sin`, the
pure-Python loop's) and for a NumPy array (:func:`sin_array`, the NumPy
twins' and :class:`~lumped.model.forcing.SwitchedSine`'s).  Python's and NumPy's
``+ - *`` on doubles are correctly rounded and never contracted, so all
give the same bits as the C code.

Supported range ``|x| <= MAX_ARGUMENT = 2e8`` rad, with an error below
1 ulp there (``tests/test_sine.py`` measures it against mpmath on 50000
random and adversarial arguments: at most 0.76 ulp, near ``pi/4``); outside
it, and for ``inf`` or ``nan``, the result is ``nan``.

Notes
-----
1. ``k = round(x 2/pi)`` by adding and subtracting ``0x1.8p52``; ``k mod 4``
   is the quadrant.
2. Cody-Waite reduction ``r = x - k pi/2`` with ``pi/2 = P1 + ... + P5``,
   ``P1..P4`` of 26 significant bits so that ``k*Pi`` is exact for
   ``|k| < 2^27``; ``x - k*P1`` is exact (Sterbenz), the next three
   subtractions are two-sums whose errors, with ``k*P5``, form the low part
   ``rr`` of the double-double ``r + rr``.
3. fdlibm's ``__kernel_sin`` and ``__kernel_cos`` (FreeBSD's branch-free
   versions; polynomial errors below ``2^-58`` on ``[-pi/4, pi/4]``) give
   ``sin(r + rr)`` and ``cos(r + rr)``; the quadrant picks one and its sign.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["MAX_ARGUMENT", "sin", "sin_array"]

#: Largest ``|x|`` (rad) of the supported range (``SINE_MAX`` in ``_sine.h``).
MAX_ARGUMENT = 2e8

_h = float.fromhex
SHIFT, INV_PIO2 = _h("0x1.8p52"), _h("0x1.45f306dc9c883p-1")
P1, P2, P3 = _h("0x1.921fb58p+0"), _h("-0x1.dde974p-27"), _h("0x1.1a6263p-54")
P4, P5 = _h("0x1.8a2e038p-81"), _h("-0x1.f1976b7ed8fbcp-110")
S1, S2, S3 = _h("-0x1.5555555555549p-3"), _h("0x1.111111110f8a6p-7"), _h("-0x1.a01a019c161d5p-13")
S4, S5, S6 = _h("0x1.71de357b1fe7dp-19"), _h("-0x1.ae5e68a2b9cebp-26"), _h("0x1.5d93a5acfd57cp-33")
C1, C2, C3 = _h("0x1.555555555554cp-5"), _h("-0x1.6c16c16c15177p-10"), _h("0x1.a01a019cb159p-16")
C4, C5, C6 = _h("-0x1.27e4f809c52adp-22"), _h("0x1.1ee9ebdb4b1c4p-29"), _h("-0x1.8fae9be8838d4p-37")


def _reduce(x):  # a float or an array alike: the same IEEE operations
    """``x = k pi/2 + r + rr``: ``(big, k, r, rr)``, ``big`` holding ``k`` in its low bits."""
    big = x * INV_PIO2 + SHIFT
    k = big - SHIFT
    a = x - k * P1
    c = k * -P2
    hi = a + c
    bb = hi - a
    lo = (a - (hi - bb)) + (c - bb)
    for piece in (P3, P4):  # two more pieces, each added as a two-sum
        h, c = hi, k * -piece
        hi = h + c
        bb = hi - h
        lo = lo + ((h - (hi - bb)) + (c - bb))
    lo = lo - k * P5
    r = hi + lo
    return big, k, r, lo - (r - hi)


def _kernel_sin(r, rr):  # fdlibm's __kernel_sin on [-pi/4, pi/4], with the tail rr
    z = r * r
    w = z * z
    v = z * r
    ps = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6)
    return r - ((z * (0.5 * rr - v * ps) - rr) - v * S1)


def _kernel_cos(r, rr):  # fdlibm's __kernel_cos on [-pi/4, pi/4], with the tail rr
    z = r * r
    w = z * z
    pc = z * (C1 + z * (C2 + z * C3)) + w * w * (C4 + z * (C5 + z * C6))
    hz = 0.5 * z
    one_hz = 1.0 - hz
    return one_hz + (((1.0 - one_hz) - hz) + (z * pc - r * rr))


def sin(x: float) -> float:
    """``sin(x)`` for a float, bit-identical to ``_sine.h`` (see the module's Notes)."""
    if not abs(x) <= MAX_ARGUMENT:
        return math.nan
    _, k, r, rr = _reduce(x)
    quadrant = int(k) & 3
    value = _kernel_cos(r, rr) if quadrant & 1 else _kernel_sin(r, rr)
    return -value if quadrant & 2 else value


def sin_array(x: np.ndarray) -> np.ndarray:
    """``sin(x)`` elementwise for a float array, bit-identical to ``_sine.h``."""
    with np.errstate(invalid="ignore", over="ignore"):  # inf and nan give nan, as in C
        x = np.asarray(x, dtype=float)
        big, _, r, rr = _reduce(x)
        quadrant = big.view(np.int64) & 3
        value = np.where(quadrant & 1, _kernel_cos(r, rr), _kernel_sin(r, rr))
        value = np.where(quadrant & 2, -value, value)
        return np.where(np.abs(x) <= MAX_ARGUMENT, value, np.nan)
