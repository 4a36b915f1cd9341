"""Brent's method in Python floats (lumped.numerics.roots) against SciPy's ``brentq``, the same algorithm in C."""

from __future__ import annotations

import math

import pytest
from conftest import EPS
from scipy.optimize import brentq as scipy_brentq

from lumped.numerics.roots import MAXITER, RTOL, XTOL, brentq

CASES = {  # name -> (f, a, b)
    "cubic": (lambda x: x**3 - 2 * x - 5, 2.0, 3.0),
    "cosine": (lambda x: math.cos(x) - x, 0.0, 1.0),
    "steep": (lambda x: math.expm1(50 * (x - 0.3)), 0.0, 1.0),
    "flat": (lambda x: (x - 0.7) ** 5, 0.0, 1.0),
    "root at an end": (lambda x: x - 1.0, 0.0, 1.0),
    # Values near 1e-200: the product of two underflows to -0.0, so a sign
    # test by product loses the bracket (the port returned 0.0 until it
    # compared signs, as SciPy does).
    "tiny values": (lambda x: 1e-200 * (x - 0.3) * (1 + x * x), 0.0, 1.0),
    # Near the triple root the trial step divides by an underflowed product:
    # C gets inf and bisects, Python raises ZeroDivisionError (scipy/scipy#24589),
    # which the port raised until it bisected there too.
    "division by an underflow": (lambda x: 1e-100 * (x - 0.3) ** 3, 0.0, 1.0),
}


@pytest.mark.parametrize("name", list(CASES))
def test_same_root_as_scipy(name):
    """The same iterates in the same float arithmetic (IEEE doubles, no fused operations): the same root, bit for bit."""
    f, a, b = CASES[name]
    ours = brentq(f, a, b)
    theirs = scipy_brentq(f, a, b, xtol=XTOL, rtol=RTOL, maxiter=MAXITER)
    assert ours == theirs


def test_the_default_tolerances_are_the_least_scipy_accepts():
    assert RTOL == 4 * EPS and XTOL > 0


def test_refuses_a_bracket_without_a_sign_change_and_a_budget_passed():
    with pytest.raises(ValueError, match="opposite signs"):
        brentq(lambda x: x * x + 1, -1.0, 1.0, xtol=1e-12, rtol=4 * EPS, maxiter=50)
    with pytest.raises(ValueError, match="no convergence"):
        brentq(lambda x: math.cos(x) - x, 0.0, 1.0, xtol=1e-300, rtol=4 * EPS, maxiter=2)
    with pytest.raises(ValueError, match="is NaN"):
        brentq(lambda x: math.nan if x > 0.5 else x - 0.7, 0.0, 1.0)
