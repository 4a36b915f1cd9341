"""One event type (issue 41, part B): the same problem gives the same events whatever route runs it.

The paper's forced problem (eq. 17b: 10 N at 5 pi rad/s, off after 1 s), Bingham and Coulomb, run as
one mass (the one-mass closed forms and their march, :mod:`lumped.solvers.exact`) and as a network of
that one mass (the network's march, :mod:`lumped.solvers.exact_network`; the event-locating method's
two marches likewise): every event has the same kind, the same element and the same mode after it,
and both routes report the rest.  Times agree to the exact solvers' event accuracy (each phase starts
from the previous event: a few ulps per event over about ten events, 1e-12 s covers it), the
event-locating method's to its own error of order dt**2 (below 1e-5 s at dt = 1e-3 here).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import lumped as L
from lumped.model.problem import oscillator_network
from lumped.solvers.event_capturing_network import solve_capturing_network
from lumped.solvers.events import KINDS, Event
from lumped.solvers.exact_network import solve_exact_network
from lumped.studies import examples

DT = 1e-3


def paper(gamma: float) -> tuple[L.Oscillator, L.SwitchedSine, float]:
    ex = examples.paper()["forced_large"]
    return dataclasses.replace(ex.oscillator, dashpot=L.BinghamDashpot(1.0, gamma)), ex.force, ex.t_end


def same_events(a: tuple, b: tuple, atol: float) -> None:
    assert [(e.kind, e.elements, e.mode) for e in a] == [(e.kind, e.elements, e.mode) for e in b]
    assert all(isinstance(e, Event) and e.kind in KINDS for e in a + b)
    np.testing.assert_allclose([e.time for e in a], [e.time for e in b], rtol=0, atol=atol)
    np.testing.assert_allclose([e.x for e in a], [e.x for e in b], rtol=0, atol=atol)


@pytest.mark.parametrize("gamma", [1.0, math.inf], ids=["bingham", "coulomb"])
def test_exact_gives_the_same_events_as_one_mass_and_as_a_network(gamma: float) -> None:
    osc, force, t_end = paper(gamma)
    one = L.solve_exact(osc, t_end, force=force).sample(DT)
    net = solve_exact_network(oscillator_network(osc, 0.0, 0.0, force), t_end, DT)
    same_events(one.events, net.events, 1e-12)
    kinds = [e.kind for e in one.events]
    assert kinds.count("switch") == 1 and kinds[-1] == "rest" and "reversal" in kinds
    assert one.events[-1].time == one.rest_time and net.events[-1].time == net.rest_times[0]


@pytest.mark.parametrize("gamma", [1.0, math.inf], ids=["bingham", "coulomb"])
def test_event_locating_gives_the_same_events_as_one_mass_and_as_a_network(gamma: float) -> None:
    osc, force, t_end = paper(gamma)
    one = L.event_capturing(osc, t_end, DT, force=force).trajectory
    net = solve_capturing_network(oscillator_network(osc, 0.0, 0.0, force), t_end, DT)
    same_events(one.events, net.events, 1e-5)


def test_a_network_of_one_mass_names_its_own_element() -> None:
    # Solved through the one-mass route (one_mass_form), the events name the user's dashpot, and its mode
    # is its own elongation rate's sign: the element runs from the mass to the ground, so a mass moving
    # up (breakaway under the rising sine) slips it at -1.
    osc, force, t_end = paper(1.0)
    net = L.Network(
        [L.Mass("block", 1.0)],
        [L.Spring("k", ("block", "ground"), 100.0), L.Bingham("pad", ("block", "ground"), 1.0, 1.0)],
        [L.Load("block", force)],
    )
    tr = L.solve(L.Problem(net, t_end), DT, method="exact")
    one = L.solve_exact(osc, t_end, force=force).sample(DT)
    fired = [e for e in one.events if e.kind in ("stop", "reversal", "breakaway")]
    assert [e.elements for e in one.events] == [("dashpot",) if e in fired else () for e in one.events]
    assert [e.elements for e in tr.events] == [("pad",) if e in fired else () for e in one.events]
    assert [e.mode for e in tr.events] == [(0, -e.mode[1]) for e in one.events]
    assert tr.events[0].kind == "breakaway" and tr.events[0].mode == (0, -1)
