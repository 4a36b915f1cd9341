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


@pytest.mark.parametrize("t", [1e3, 3e5, 9e7, 1e9])
def test_a_stuck_phase_of_any_length_is_its_exact_integral(t):
    # A mass stuck to a driven point: z = (1, ramp), z' = (0, 1), so exp(t [[0, 0], [1, 0]]) = [[1, 0], [t, 1]]
    # exactly.  The generator is nilpotent: |A^p|^(1/p) = 0, no squaring, and r_3(A) = (I - A/2)^-1 (I + A/2) is
    # I + A to the rounding of one pivoted 2 x 2 solve, a few ulps of each entry (of 1 where it is 0).  Scaled by
    # its 1-norm instead, 2^s ~ t squarings multiplied that rounding by t (6e-2 absolute at t = 3e5, 1e-9
    # relative at 9e7).
    out = expm(np.array([[0.0, 0.0], [t, 0.0]]))
    exact = np.array([[1.0, 0.0], [t, 1.0]])
    assert np.all(np.abs(out - exact) <= 4 * EPS * np.maximum(np.abs(exact), 1.0))


@pytest.mark.parametrize("t", [1.0, 1e6, 1e9])
def test_a_free_mass_under_a_constant_load_is_its_exact_integral(t):
    # z = (u, u', 1) with u'' = a: exp = [[1, t, a t^2/2], [0, 1, a t], [0, 0, 1]] (A^3 = 0, so r_3, exact to
    # degree 6, is the series; its rounding is a few ulps of each entry, of 1 where it is 0).
    a = 0.3
    out = expm(np.array([[0.0, t, 0.0], [0.0, 0.0, a * t], [0.0, 0.0, 0.0]]))
    exact = np.array([[1.0, t, a * t * t / 2], [0.0, 1.0, a * t], [0.0, 0.0, 1.0]])
    assert np.all(np.abs(out - exact) <= 4 * EPS * np.maximum(np.abs(exact), 1.0))
