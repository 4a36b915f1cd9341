"""numerics.expm: the matrix exponential in NumPy against closed forms and SciPy's independent implementation."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.linalg

from lumped.numerics.expm import THETA, expm

EPS = np.finfo(float).eps


@pytest.mark.parametrize("t", [1e-3, 0.1, 1.0, 7.0, 40.0])  # every degree of the approximant, and scaling
def test_a_rotation_generator_gives_cos_and_sin(t):
    # exp(t [[0, -w], [w, 0]]) is the rotation by w t; the method's backward error (below the unit roundoff per
    # squaring) grows to about (s + 1) eps over s squarings, s <= log2(w t / theta_13) + 1.
    w = 3.0
    out = expm(t * np.array([[0.0, -w], [w, 0.0]]))
    c, s = math.cos(w * t), math.sin(w * t)
    squarings = max(0, math.ceil(math.log2(w * t / THETA[13])))
    assert np.max(np.abs(out - np.array([[c, -s], [s, c]]))) <= 8 * (squarings + 1) * EPS


def test_a_nilpotent_matrix_gives_its_finite_series():
    # The generators of a network's constant load make A nilpotent in those rows: exp(N) = I + N + N^2/2 exactly
    # for N^3 = 0 (Pade's rational function agrees with the series to the degree of the approximant, and rounds).
    n = np.array([[0.0, 1.0, 0.5], [0.0, 0.0, 2.0], [0.0, 0.0, 0.0]])
    assert np.max(np.abs(expm(n) - (np.eye(3) + n + n @ n / 2))) <= 4 * EPS * 3


@pytest.mark.parametrize("scale", [1e-3, 0.1, 1.0, 10.0])
def test_agrees_with_scipys_expm(scale):
    # Both are backward stable to the unit roundoff; their difference is within the exponential's condition
    # number times eps, below 1e3 eps relative for these norms (|A|_1 <= 10 * 7 * 3).
    rng = np.random.default_rng(23)
    for n in (1, 2, 5, 7):
        a = scale * rng.standard_normal((n, n))
        ref = scipy.linalg.expm(a)
        assert np.max(np.abs(expm(a) - ref)) <= 1e3 * EPS * max(1.0, np.abs(ref).max()) * max(1.0, scale)


def test_a_non_finite_matrix_is_refused_in_one_line():
    with pytest.raises(ValueError, match="non-finite"):
        expm(np.array([[math.nan]]))
