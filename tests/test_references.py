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
    imported = {alias.name for node in ast.walk(tree) if isinstance(node, ast.Import)
                for alias in node.names}  # fmt: skip
    imported |= {node.module for node in ast.walk(tree) if isinstance(node, ast.ImportFrom)}
    assert not any(name and name.split(".")[0] == "lumped" for name in imported), imported


def test_coulomb_free_decay_loses_two_band_widths_per_half_cycle():
    # Textbook fact (no viscosity): each half-cycle lasts pi sqrt(m/k) and the
    # offset from the centre x_c = sgn(x) tau/k flips: x -> 2 x_c - x.  From
    # x0 = 0.095, k = 100, tau = 1 (x_c = +-0.01): -0.075, 0.055, -0.035,
    # 0.015, then 0.005, inside the band (on the same side): stop.
    ref = references.free_decay(1.0, 100.0, 1.0, math.inf, 0.095)
    np.testing.assert_allclose(ref.positions, [-0.075, 0.055, -0.035, 0.015, 0.005],
                               rtol=0, atol=1e-15)  # fmt: skip
    np.testing.assert_allclose(ref.times, np.arange(1, 6) * math.pi / 10.0, rtol=1e-15)
    assert ref.rest == (ref.times[-1], ref.positions[-1])


def test_released_inside_the_band_rests_at_once():
    ref = references.free_decay(1.0, 100.0, 1.0, 1.0, 0.005)
    assert ref.times.size == 0 and ref.rest == (0.0, 0.005)


@pytest.mark.parametrize(("v", "changes"), [([1.0, 0.0, -1.0], 1), ([1.0, 0.0, 2.0], 0),
                                            ([0.0, 0.0], 0), ([-1.0, 2.0, -3.0, 0.0, 4.0], 3)])
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
