"""The shared references are independent of the package, and right on hand-checkable cases."""

from __future__ import annotations

import ast
import math
from pathlib import Path

import numpy as np
import pytest
import references


def test_references_import_nothing_from_lumped():
    tree = ast.parse(Path(references.__file__).read_text(encoding="utf-8"))
    imported = {alias.name for node in ast.walk(tree) if isinstance(node, ast.Import) for alias in node.names}
    imported |= {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
    assert not any(name and name.split(".")[0] == "lumped" for name in imported), imported


def test_coulomb_free_decay_loses_two_band_widths_per_half_cycle():
    # Textbook fact (no viscosity): each half-cycle lasts pi sqrt(m/k) and the
    # offset from the centre x_c = sgn(x) tau/k flips: x -> 2 x_c - x.  From
    # x0 = 0.095, k = 100, tau = 1 (x_c = +-0.01): -0.075, 0.055, -0.035,
    # 0.015, then 0.005, inside the band (on the same side): stop.
    ref = references.free_decay(1.0, 100.0, 1.0, math.inf, 0.095)
    np.testing.assert_allclose(ref.positions, [-0.075, 0.055, -0.035, 0.015, 0.005], rtol=0, atol=1e-15)
    np.testing.assert_allclose(ref.times, np.arange(1, 6) * math.pi / 10.0, rtol=1e-15)
    assert ref.rest == (ref.times[-1], ref.positions[-1])


def test_released_inside_the_band_rests_at_once():
    ref = references.free_decay(1.0, 100.0, 1.0, 1.0, 0.005)
    assert ref.times.size == 0 and ref.rest == (0.0, 0.005)


@pytest.mark.parametrize(
    ("v", "changes"), [([1.0, 0.0, -1.0], 1), ([1.0, 0.0, 2.0], 0), ([0.0, 0.0], 0), ([-1.0, 2.0, -3.0, 0.0, 4.0], 3)]
)
def test_sign_changes_skip_zeros(v, changes):
    assert references.sign_changes(np.array(v)) == changes


def test_order_of_a_power_law_is_its_exponent():
    steps = np.array([1e-3, 5e-4, 2.5e-4])
    assert abs(references.order(steps, 7.0 * steps**1.5) - 1.5) <= 1e-12


def test_literal_line8_satisfies_eq_15a():
    # F_d + eta v = F~ with eta = m/dt + k dt, the implicit step's equation.
    m, k, dt, tau, gamma, predictor = 1.0, 100.0, 1e-3, 1.0, 2.0, 7.5
    f_d, v = references.literal_line8(predictor, dt, m, k, tau, gamma)
    assert abs(f_d + (m / dt + k * dt) * v - predictor) <= 1e-12 * predictor
    assert v == pytest.approx(gamma * (f_d - tau), rel=1e-15)


@pytest.mark.parametrize(("force", "velocity"), [(0.0, 0.0), (0.7, 0.0), (-1.0, 0.0), (1.5, 1.0), (-3.0, -4.0)])
def test_bingham_velocity_is_flat_in_the_band_and_of_slope_gamma_outside(force, velocity):
    # tau = 1, gamma = 2: v = 2 (|F| - 1) sgn(F) for |F| > 1 (eq. 7)
    assert references.bingham_velocity(force, 1.0, 2.0) == velocity


def test_switched_sine_is_17b_and_off_after_until():
    # 10 sin(5 pi t): 10 at t = 0.1, -10 at t = 0.3; zero once t > 1
    assert references.switched_sine(references.F17B, 0.1) == pytest.approx(10.0, rel=1e-15)
    assert references.switched_sine(references.F17B, 0.3) == pytest.approx(-10.0, rel=1e-15)
    assert references.switched_sine(references.F17B, 1.0 + 1e-12) == 0.0


def test_line3_is_the_predictor_of_a_step_from_rest():
    # from rest with F_s = k x0, F~ = F_{n+1} - k x0; moving, (m/dt) v is added
    assert references.line3(1.0, 1e-4, 0.0, 2.0, 50.0) == -48.0
    assert references.line3(2.0, 0.5, 3.0, 0.0, 0.0) == 12.0


@pytest.mark.parametrize(
    ("m", "k", "tau", "gamma", "x0"), references.FREE_DECAY.values(), ids=list(references.FREE_DECAY)
)
def test_free_decay_table_keeps_clear_of_the_band_edge(m, k, tau, gamma, x0):
    # As FREE_DECAY promises: the count of half-cycles is well posed.
    ref = references.free_decay(m, k, tau, gamma, x0)
    band = tau / k
    assert len(ref.times) >= 1
    assert abs(abs(x0) - band) > 1e-9 * abs(x0)
    assert np.all(np.abs(np.abs(ref.positions) - band) > 1e-9 * abs(x0))
