"""One-sided derivatives of a network's exact motion where its event sequence changes (issue 24): a free decay
of two blocks on Coulomb friction, released from a.x0, gains an event at a value of a.x0 that bisection finds.
Each side is checked against one-sided differences from that side, and the jump against the difference of
the two motions a little way off."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from lumped.drivers.sensitivity import NetworkOneSided, one_sided_sensitivities, system_sensitivities
from lumped.model.files import load_system
from lumped.model.system_parameters import system_parameters, with_values
from lumped.solvers.network_modes import final_rest

CHAIN = load_system(Path(__file__).resolve().parent / "data" / "two_coulomb_chain.toml")
(X0,) = system_parameters(CHAIN, ["a.x0"])
T = np.array([0.0, 1.0, 2.0, 5.0])


def _run(x0: float):
    return system_sensitivities(with_values(CHAIN, [X0], [x0]), T, ["a.x0"])


def _rest(x0: float) -> np.ndarray:
    """Rest times and positions of both blocks (2, 2)."""
    motion, sens = _run(x0)
    return np.array(final_rest(list(motion.phases), sens.positions[-1]))


@pytest.fixture(scope="module")
def change() -> float:
    """The a.x0 in [0.1, 0.105] where the decay gains events (7 -> 9), bisected to 1e-14 m."""
    lo, hi = 0.1, 0.105
    events = lambda x0: len(_run(x0)[0].events)
    assert (events(lo), events(hi)) == (7, 9)
    while hi - lo > 1e-14:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if events(mid) == 7 else (lo, mid)
    return 0.5 * (lo + hi)


def test_at_the_change_the_sides_differ_and_the_rest_time_jumps(change):
    (side,) = one_sided_sensitivities(with_values(CHAIN, [X0], [change]), T, ["a.x0"])
    assert isinstance(side, NetworkOneSided) and not side.same_events
    assert side.delta == pytest.approx(1e-9 * change)
    # Below the change the derivatives are those of its event sequence: one-sided differences from below with
    # h = 1e-6 m agree to h |S''|/|S'| (measured 2e-5 at worst): 1e-4 of each.
    h, below = 1e-6, change - side.delta
    fd = (_rest(below) - _rest(below - h)) / h
    analytic = np.array([side.below.rest_time[:, 0], side.below.rest_position[:, 0]])
    assert np.all(np.abs(fd - analytic) <= 1e-4 * np.abs(analytic))
    # b's rest time jumps (an extra stick-slip of b); the positions do not.  The jump is the difference of the
    # two motions at change -+ eps as eps -> 0.  From above the rest time grows like C sqrt(eps) (a grazing
    # event: its slope at delta, C/(2 sqrt(delta)), is side.above's large derivative), so at eps = 1e-9 the
    # difference is the jump to C sqrt(eps) + eps |S'_-|; twice that is asserted.
    assert side.rest_time_jump[1] > 0.05 and abs(side.rest_time_jump[0]) < 1e-9
    assert np.all(np.abs(side.rest_position_jump) < 1e-9)
    assert side.above.rest_time[1, 0] > 100 * abs(side.below.rest_time[1, 0])
    eps = 1e-9
    gap = _rest(change + eps) - _rest(change - eps)
    grazing = 2 * side.above.rest_time[1, 0] * np.sqrt(side.delta)
    bound = 2 * (grazing * np.sqrt(eps) + eps * abs(side.below.rest_time[1, 0]))
    assert abs(gap[0, 1] - side.rest_time_jump[1]) <= bound


def test_away_from_a_change_both_sides_are_the_derivative():
    # a.x0 = 0.3 lies 0.005 m from the nearest change: both sides have the same events, and each side's
    # derivative is the two-sided one to delta |S''| ~ 1e-10 of it.
    (side,) = one_sided_sensitivities(CHAIN, T, ["a.x0"])
    _, sens = system_sensitivities(CHAIN, T, ["a.x0"])
    assert side.same_events
    for s in (side.below, side.above):
        assert np.allclose(s.x[:, :, 0], sens.x[:, :, 0], rtol=1e-7, atol=1e-9)
        assert np.allclose(s.rest_time[:, 0], sens.rest_time[:, 0], rtol=1e-7)
    assert np.all(np.abs(side.x_jump) < 1e-12)


def test_a_one_mass_system_is_answered_by_the_one_mass_code():
    one = load_system(Path(__file__).resolve().parent.parent / "examples" / "figure3.toml")
    (side,) = one_sided_sensitivities(one, [0.0, 1.0], ["dashpot.threshold"])
    assert side.parameter == "dashpot.threshold" and side.same_events
