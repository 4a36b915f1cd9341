"""The switched sine and its canonical form (P >= 0, omega >= 0, same function)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import references
from conftest import EPS, F17A, F17B
from references import switched_sine

import lumped as L

#: (amplitude, omega, phase): every sign of P and omega, phases on both sides of 0.
SIGNS = [(2.0, 3.0, 0.4), (-2.0, 3.0, 0.4), (2.0, -3.0, 0.4), (-2.0, -3.0, -2.9), (1.5, -7.0, 3.0), (-0.5, -0.25, -1.0)]


@pytest.mark.parametrize(("amplitude", "omega", "phase"), SIGNS)
def test_canonical_form_is_non_negative_and_the_same_function(amplitude, omega, phase):
    # The canonical form promises P >= 0, omega >= 0 (the exact solver's
    # step bound pi/omega and its breakaway formula need omega > 0) and
    # phase in [-pi, pi].  Same function as P sin(omega t + phase) written
    # out (references.switched_sine): sin(-w t + ph) = sin(w t + pi - ph) and
    # -P sin(a) = P sin(a + pi).  Rounding: the phase moves by a few roundings
    # of size eps*(|ph| + pi) and w*t by eps*|w t|, so the values differ by at
    # most |P| * 4 eps (|w t| + |ph| + 2 pi) (sin is 1-Lipschitz).
    force = L.SwitchedSine(amplitude, omega, phase)
    p, w, ph = force.canonical()
    assert p == abs(amplitude) and w == abs(omega) and abs(ph) <= math.pi
    t = np.linspace(0.0, 3.0, 301)
    want = np.array([switched_sine((amplitude, omega, phase, math.inf), ti) for ti in t])
    bound = abs(amplitude) * 4 * EPS * (abs(omega) * t + abs(phase) + 2 * math.pi)
    assert np.all(np.abs(p * np.sin(w * t + ph) - want) <= bound)
    assert np.all(np.abs(force(t) - want) <= bound)


@pytest.mark.parametrize(("force", "paper"), [(F17A, references.F17A), (F17B, references.F17B)], ids=["17a", "17b"])
def test_the_examples_forcings_are_equations_17(force, paper):
    # lumped.studies.examples builds them from config/config.yaml (the tests use
    # those); eq. (17): P sin(5 pi t) for 0 <= t <= 1, P = 0.5 and 10.
    # numpy's sin and libm's may differ by an ulp: 2 eps P.
    assert (force.amplitude, force.omega, force.phase, force.until) == paper
    t = np.linspace(0.0, 2.0, 41)
    want = np.array([switched_sine(paper, ti) for ti in t])
    assert np.all(np.abs(force(t) - want) <= 2 * EPS * paper[0])
    assert np.all(want[t > paper[3]] == 0.0) and np.all(force(t)[t > paper[3]] == 0.0)
