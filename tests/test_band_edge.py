"""The edge of the stick band: every path sticks there, as Algorithm 1 does.

Algorithm 1's stick test (line 5) is ``|F~| <= mu_s N_f``, a closed band
(:func:`lumped.laws.sticks`).  A mass released from rest at ``x0 = +-tau/k``
with no force has the predictor exactly on an edge at every step:

* ``m = 1``, ``k = 4``, ``tau = 1``: ``x0 = +-0.25`` and ``F_s,0 = k x0 = +-1``
  are powers of two, so exact;
* ``v0 = 0`` and ``F = 0``, so ``F~ = (m/dt) v0 + F - F_s,0 = -+1 = -+tau``
  exactly (each term is exact, the sum of ``0``, ``0`` and ``-+1`` too);
* if the step sticks, ``v_1 = 0`` and ``F_s,1 = F_s,0 + dt k 0 = F_s,0``
  exactly, so every later step sees the same predictor.

The network's step reaches the same numbers: with its middle (sticking) mode
the mass moves with the ground (``v = 0``, exactly), the spring's force is its
state ``s + dt k 0 = k x0``, the dashpot's force from the momentum balance is
``0 - k x0``, and ``z = f + sigma * 0`` is that force: ``-+tau`` exactly.

So no rounding enters and the checks are exact: ``v == 0`` at every step,
``x == x0``, the dashpot force is the predictor, and every stick flag that a
path exposes is set.  One ulp outside the band (``x0 = nextafter(0.25, 1)``:
``k x0 = 1 + 2^-52``, exact) every path must slip at the first step: the band
is closed, not widened.

The methods that locate events (exact, event-driven, event-locating) follow at
the end: released on the edge, held there by a force that switches off, and
(the exact solution) stopping on the edge after a slip.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import lumped as L
from lumped import Bingham, Mass, Network, Spring, simulate_network
from lumped.kernels import batched
from lumped.solvers import backward_euler
from lumped.solvers import network_compiled as kernel

M, K, TAU, DT, T_END = 1.0, 4.0, 1.0, 1e-3, 0.05
EDGE = TAU / K
assert EDGE == 0.25 and K * EDGE == TAU  # exact (powers of two)
OUTSIDE = math.nextafter(EDGE, 1.0)
assert K * OUTSIDE == TAU + 2.0**-52  # exact: one ulp of tau beyond the edge
#: Released on the upper and the lower edge of the band.
STARTS = {"upper-edge": EDGE, "lower-edge": -EDGE}
LAWS = {"bingham": 1.0, "coulomb": math.inf}

SINGLE = ["python"] + (["compiled"] if backward_euler.KERNEL == "compiled" else [])
BATCHED = ["python"] + (["compiled"] if batched.BATCH_KERNEL == "compiled" else [])
NETWORK = ["python", "auto"] + (["compiled"] if kernel.KERNEL == "compiled" else [])


def oscillator(gamma: float) -> L.Oscillator:
    return L.Oscillator(M, L.LinearSpring(K), L.BinghamDashpot(TAU, gamma))


def single(x0: float, gamma: float, loop: str) -> L.Trajectory:
    return backward_euler.backward_euler(oscillator(gamma), T_END, DT, x0=x0, kernel=loop)


def batch(x0: float, gamma: float, loop: str) -> batched.BatchSummary:
    c = oscillator(gamma).dashpot.viscosity
    values = (M, K, TAU, c, x0, 0.0, 0.0, 0.0, 0.0, math.inf)
    params = batched.BatchParameters(*(np.array([v]) for v in values))
    return batched.batch_backward_euler(params, T_END, DT, save_every=1, kernel=loop)


def network(x0: float, gamma: float, solver: str):  # noqa: ANN201 (a Trajectory)
    """The same system as a network; ``auto`` runs it through Algorithm 1, the others through the step."""
    net = Network([Mass("m", M, x0)], [Spring("k", ("ground", "m"), K), Bingham("d", ("ground", "m"), TAU, gamma)])
    tr = simulate_network(net, T_END, DT, solver=solver)
    assert tr.solver == ("algorithm1" if solver == "auto" else solver)
    return tr


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("start", STARTS)
@pytest.mark.parametrize("loop", SINGLE)
def test_the_single_run_sticks_on_the_edge(loop: str, start: str, law: str) -> None:
    x0 = STARTS[start]
    tr = single(x0, LAWS[law], loop)
    assert np.all(tr.v == 0) and np.all(tr.x == x0) and tr.at_rest.all()
    assert np.all(tr.F_d[1:] == -K * x0)  # stuck: F_d is the predictor, on the edge
    assert tr.rest_time == 0.0 and tr.rest_position == x0


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("start", STARTS)
@pytest.mark.parametrize("loop", BATCHED)
def test_the_batched_run_sticks_on_the_edge(loop: str, start: str, law: str) -> None:
    x0 = STARTS[start]
    out = batch(x0, LAWS[law], loop)
    assert out.v_end[0] == 0 and out.x_end[0] == x0 and np.all(out.x == x0)
    assert (out.rest_step[0], out.stops[0]) == (0, 0)  # v == 0 from step 0 on: stuck throughout


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("start", STARTS)
@pytest.mark.parametrize("solver", NETWORK)
def test_the_network_sticks_on_the_edge(solver: str, start: str, law: str) -> None:
    x0 = STARTS[start]
    tr = network(x0, LAWS[law], solver)
    assert np.all(tr.v == 0) and np.all(tr.x == x0)
    assert tr.rigid[1:, 1].all()  # the dashpot on its sticking piece at every step
    assert np.all(tr.forces[1:, 1] == -K * x0)
    assert tr.rest_times[0] == 0.0


@pytest.mark.parametrize("law", LAWS)
def test_one_ulp_outside_the_band_every_path_slips(law: str) -> None:
    """The band is closed, not widened: ``|F~| = tau + 2^-52`` slips at the first step everywhere."""
    gamma = LAWS[law]
    for loop in SINGLE:
        tr = single(OUTSIDE, gamma, loop)
        assert tr.v[1] < 0 and not tr.at_rest[1], loop
    for loop in BATCHED:
        assert batch(OUTSIDE, gamma, loop).rest_step[0] >= 2, loop  # v_1 != 0
    for solver in NETWORK:
        tr = network(OUTSIDE, gamma, solver)
        assert tr.v[1] < 0, solver
        if solver != "auto":  # the step's own flag (Algorithm 1's path derives it from v)
            assert not tr.rigid[1, 1], solver


def test_the_stick_test_is_closed() -> None:
    """:func:`lumped.laws.sticks` itself: both edges in, the next floats out, NaN out."""
    from lumped.laws import sticks

    assert sticks(-TAU, -TAU, TAU) and sticks(TAU, -TAU, TAU)
    assert not sticks(math.nextafter(TAU, 2.0), -TAU, TAU) and not sticks(-math.nextafter(TAU, 2.0), -TAU, TAU)
    assert not sticks(math.nan, -TAU, TAU) and sticks(-math.inf, -math.inf, 0.0)


@pytest.mark.parametrize("law", LAWS)
@pytest.mark.parametrize("solver", [s for s in NETWORK if s != "auto"])
def test_a_band_of_zero_width_is_never_rigid(solver: str, law: str) -> None:
    """Threshold 0: no band (the element is not ``rigid_capable``).  At rest, ``z = 0`` is the
    one point of its zero-width rigid piece, which the free pieces beside it hold: not rigid."""
    net = Network([Mass("m", M, 0.0)], [Spring("k", ("ground", "m"), K), Bingham("d", ("ground", "m"), 0.0, LAWS[law])])
    tr = simulate_network(net, T_END, DT, solver=solver)
    assert not net.elements[1].rigid_capable
    assert np.all(tr.v == 0) and not tr.rigid.any()


# ---- the methods that locate events: exact, event-driven, event-locating ----------------------------
#
# Their stick test at a release, a breakaway check and a forcing switch-off is the same closed band
# (:meth:`EventMarch.mode`, :func:`lumped.laws.sticks`), and at a zero of ``v`` after a slip in direction
# ``s`` the rule is strict: the mass reverses only if ``-s (F - k x) > tau`` (:meth:`EventMarch.stop_or_reverse`);
# on the edge it stops.  Released on the edge with no force, or held there by a force that switches off
# (``F = +-0.5 sin(pi t)`` until ``t_off = 0.5``: ``F - k x0`` stays in ``[-1, -0.5]`` (or ``[0.5, 1]``) and
# is ``-+tau`` again, exactly, once the force is off), the mass never moves: no event but the forcing's
# switch-off and the rest, dated at ``t = 0``.

EVENT_METHODS = ("exact", "event-driven", "event-locating")
T_OFF = 0.5
HOLDING = {"unforced": None, "forcing-off": T_OFF}


def located(method: str, osc: L.Oscillator, x0: float, force: L.SwitchedSine | None):  # noqa: ANN201
    """``(events, trajectory)`` of an event-locating method on the grid ``DT`` to ``t = 2`` (past the stop at ``pi/2``)."""
    kw = dict(x0=x0, force=force)
    if method == "event-locating":
        run = L.event_capturing(osc, 2.0, DT, **kw)
        return run.events, run.trajectory
    sol = L.METHODS[method].solution(osc, 2.0, **kw)
    return sol.events, sol.sample(DT)


@pytest.mark.parametrize("holding", HOLDING)
@pytest.mark.parametrize("start", STARTS)
@pytest.mark.parametrize("method", EVENT_METHODS)
def test_an_event_method_holds_the_mass_released_on_the_edge(method: str, start: str, holding: str) -> None:
    x0 = STARTS[start]
    force = None if HOLDING[holding] is None else L.SwitchedSine(-math.copysign(0.5, -x0), math.pi, 0.0, T_OFF)
    assert force is None or force.amplitude * x0 > 0  # pushes inwards, so |F - k x0| <= tau while on
    events, tr = located(method, oscillator(math.inf), x0, force)
    expected = [("rest", 0.0, (x0,))] + ([] if force is None else [("switch", T_OFF, (x0,))])
    assert [(e.kind, e.time, e.x) for e in events] == expected
    assert np.all(tr.x == x0) and np.all(tr.v == 0) and tr.rest_time == 0.0 and tr.rest_position == x0


#: Released from ``x0 = +-3 tau/k = +-0.75`` (Coulomb, no force), the mass slips about the centre
#: ``+-tau/k`` with amplitude ``tau/k * 2 = 0.5`` and stops half a period later at ``-+tau/k``: on the edge.
STOPS = {"from-above": 3 * EDGE, "from-below": -3 * EDGE}


@pytest.mark.parametrize("start", STOPS)
def test_a_stop_exactly_on_the_edge_is_a_stop(start: str) -> None:
    """The exact solution stops on the edge in exact arithmetic here, and so in floating point.

    Its free slip phase is ``x = c + cos(q (t - t0)) (x0 - c)`` with the centre ``c = +-0.25`` (exact), ``q =
    sqrt(k/m) = 2`` and the stop at ``q (t - t0) = pi``: :func:`closed_form._first_zero` returns
    ``math.pi``, halved (exact) and doubled back (exact), and ``cos(math.pi)`` is ``-1`` in every libm (the
    true value is ``-1 + 7.5e-33``; ``scripts/perturb`` leaves ``+-1`` alone for that reason).  So ``x_stop
    = c - (x0 - c) = -+0.25`` and the net force ``-k x_stop = +-tau`` exactly: the strict rule stops it.
    (The event-driven and event-locating methods reach the stop with their integration error, ``2e-11``
    and ``1e-14`` m off the edge, so only the exact method meets the edge itself after a slip.)
    """
    x0 = STOPS[start]
    assert np.cos(math.pi) == -1.0 and math.sqrt(K / M) == 2.0
    events, tr = located("exact", oscillator(math.inf), x0, None)
    edge = -math.copysign(EDGE, x0)
    assert [(e.kind, e.x) for e in events] == [("stop", (edge,)), ("rest", (edge,))]
    assert events[0].time == events[1].time == math.pi / 2
    assert tr.x[-1] == edge and tr.v[-1] == 0 and tr.rest_position == edge


@pytest.mark.parametrize("start", STOPS)
def test_a_stop_one_ulp_beyond_the_edge_reverses(start: str) -> None:
    """The rule is strict, not widened: from ``x0`` one ulp further out the stop lies an ulp past the edge
    (``x0 - c = 0.5 + 2^-53`` and ``x_stop = c - (x0 - c) = -+(0.25 + 2^-53)``, exact), where ``|k x| = tau +
    2^-51 > tau``: the mass reverses."""
    x0 = math.nextafter(STOPS[start], math.copysign(math.inf, STOPS[start]))
    events, _ = located("exact", oscillator(math.inf), x0, None)
    assert events[0].kind == "reversal" and K * abs(events[0].x[0]) == TAU + 2.0**-51
