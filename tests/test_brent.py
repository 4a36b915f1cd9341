"""Brent's method in Python floats (lumped.numerics.roots) against SciPy's ``brentq``, the same algorithm in C."""

from __future__ import annotations

import math

import pytest
from conftest import EPS
from scipy.optimize import brentq as scipy_brentq

from lumped.numerics.roots import MAXITER, RTOL, XTOL, NoConvergence, brentq

CASES = {  # name -> (f, a, b)
    "cubic": (lambda x: x**3 - 2 * x - 5, 2.0, 3.0),
    "cosine": (lambda x: math.cos(x) - x, 0.0, 1.0),
    "steep": (lambda x: math.expm1(50 * (x - 0.3)), 0.0, 1.0),
    "flat": (lambda x: (x - 0.7) ** 5, 0.0, 1.0),
    "root at an end": (lambda x: x - 1.0, 0.0, 1.0),
    "reversed bracket": (lambda x: math.cos(x) - x, 1.0, 0.0),
    # f(a) f(b) underflows to -0.0: the sign bits, not the product, show the bracket.
    "values whose product underflows": (lambda x: 1e-200 * (x - 0.3), 0.0, 1.0),
    "tiny cubic": (lambda x: 1e-160 * (x - 0.3) ** 3, 0.0, 1.0),
}


@pytest.mark.parametrize("name", list(CASES))
def test_same_root_as_scipy_bit_for_bit(name):
    """The same iterates in the same float arithmetic: the same root, bit for bit."""
    f, a, b = CASES[name]
    ours = brentq(f, a, b)  # the package's tolerances
    theirs = scipy_brentq(f, a, b, xtol=1e-300, rtol=4 * EPS, maxiter=200)
    assert ours == theirs


def test_the_tolerances_are_the_least_scipy_accepts_and_named_once():
    assert (RTOL, XTOL, MAXITER) == (4 * EPS, 1e-300, 200)
    with pytest.raises(ValueError, match="rtol too small"):
        scipy_brentq(math.cos, 0.0, 3.0, rtol=RTOL * (1 - EPS))


def test_refuses_a_bracket_without_a_sign_change_and_a_budget_passed():
    with pytest.raises(ValueError, match="opposite signs"):
        brentq(lambda x: x * x + 1, -1.0, 1.0, xtol=1e-12, rtol=4 * EPS, maxiter=50)
    with pytest.raises(ValueError, match="opposite signs"):  # both positive, their product underflows to 0
        brentq(lambda x: 1e-200 * (x + 0.3), 0.0, 1.0)
    with pytest.raises(NoConvergence, match="no convergence in 2 iterations"):
        brentq(lambda x: math.cos(x) - x, 0.0, 1.0, xtol=1e-300, rtol=4 * EPS, maxiter=2)


@pytest.mark.parametrize(
    ("kwargs", "words"), [({"xtol": 0.0}, "xtol must be > 0"), ({"rtol": 2 * EPS}, "rtol must be >= 4 eps")]
)
def test_refuses_what_scipy_refuses(kwargs, words):
    with pytest.raises(ValueError, match=words):
        brentq(math.cos, 0.0, 3.0, **kwargs)
    with pytest.raises(ValueError, match="too small"):
        scipy_brentq(math.cos, 0.0, 3.0, **kwargs)


def test_a_nan_stops_the_search():
    with pytest.raises(ValueError, match="NaN"):
        brentq(lambda x: math.nan if x > 0.5 else x - 0.7, 0.0, 1.0)
