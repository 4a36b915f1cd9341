"""The compiled sparse step factors its merged system again when a free piece's slope changes.

``_network_sparse.h`` keeps its envelope ``L D L^T`` while the structure and every free piece's slope ``b``
are unchanged; a Maxwell-Bingham element's slope is ``dt k`` while its dashpot holds and
``dt k c / (c + dt k)`` while it flows, so where it starts or stops flowing the structure stays and the slope
changes: factors kept there solve the wrong system (with the factors never renewed, this run drifts 2e-5 m
from the Python step).  The Python step assembles and solves every iteration, an independent reference.
"""

from __future__ import annotations

import numpy as np
import pytest

import lumped
from lumped import Friction, Load, Mass, MaxwellBingham, Network, Spring, simulate_network
from lumped.solvers import network_compiled as kernel
from lumped.solvers import network_sparse as sparse

pytestmark = pytest.mark.skipif(kernel.KERNEL != "compiled", reason="the network kernel was not built")


def two_blocks() -> Network:
    """Two blocks on static/kinetic floors (each contact a loop through the ground: the sparse step's case),
    a coupling spring, Maxwell-Bingham elements to the ground and between them, a sine load on ``a``."""
    return Network(
        [Mass("a", 1.0), Mass("b", 2.0)],
        [
            Friction("fa", ("a", "ground"), static=0.5, kinetic=0.3),
            Friction("fb", ("b", "ground"), static=0.8, kinetic=0.5),
            Spring("k", ("a", "b"), 40.0),
            MaxwellBingham("mx", ("ground", "a"), 30.0, 0.6, 2.0),
            MaxwellBingham("my", ("a", "b"), 20.0, 0.4, 1.0),
        ],
        [Load("a", lumped.SwitchedSine(3.0, 4.0))],
    )


def test_maxwell_dashpots_that_start_and_stop_flowing_agree_with_the_python_step() -> None:
    """Positions to 1e-12 of the run's largest |x| and the same active sets, the tolerance of
    tests/test_network_banded.py (both steps solve the same well-conditioned system backward stably, and a
    step is non-expansive: some 1e-14 here); the run is checked to change the Maxwell slopes mid-run (each
    dashpot's force crosses its threshold both ways)."""
    net = two_blocks()
    assert sparse.ineligible(net) is None
    a = simulate_network(net, 1.0, 1e-3, solver="compiled")
    b = simulate_network(net, 1.0, 1e-3, solver="python")
    assert a.solver == sparse.PATH
    for e, threshold in ((3, 0.6), (4, 0.4)):
        flowing = np.abs(b.states[:, e]) > threshold
        assert np.count_nonzero(np.diff(flowing)) >= 2  # starts and stops flowing
    assert np.abs(a.positions - b.positions).max() <= 1e-12 * np.abs(b.positions).max()
    assert np.array_equal(a.rigid, b.rigid)
