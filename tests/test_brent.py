"""Brent's method in Python floats (lumped.numerics.roots) against SciPy's ``brentq``, the same algorithm in C."""

from __future__ import annotations

import math

import pytest
from conftest import EPS
from scipy.optimize import brentq as scipy_brentq

from lumped.numerics.roots import brentq

CASES = {  # name -> (f, a, b)
    "cubic": (lambda x: x**3 - 2 * x - 5, 2.0, 3.0),
    "cosine": (lambda x: math.cos(x) - x, 0.0, 1.0),
    "steep": (lambda x: math.expm1(50 * (x - 0.3)), 0.0, 1.0),
    "flat": (lambda x: (x - 0.7) ** 5, 0.0, 1.0),
    "root at an end": (lambda x: x - 1.0, 0.0, 1.0),
}


@pytest.mark.parametrize("name", list(CASES))
def test_same_root_as_scipy(name):
    """The same iterates in the same float arithmetic: the same root, to the tolerance asked of both."""
    f, a, b = CASES[name]
    rtol = 4 * EPS
    ours = brentq(f, a, b, xtol=1e-300, rtol=rtol, maxiter=200)
    theirs = scipy_brentq(f, a, b, xtol=1e-300, rtol=rtol, maxiter=200)
    assert abs(ours - theirs) <= 2 * rtol * abs(theirs)  # both within rtol |x| of the zero


def test_refuses_a_bracket_without_a_sign_change_and_a_budget_passed():
    with pytest.raises(ValueError, match="opposite signs"):
        brentq(lambda x: x * x + 1, -1.0, 1.0, xtol=1e-12, rtol=4 * EPS, maxiter=50)
    with pytest.raises(ValueError, match="no convergence"):
        brentq(lambda x: math.cos(x) - x, 0.0, 1.0, xtol=1e-300, rtol=4 * EPS, maxiter=2)
