"""Exact sensitivities of the exact network solution (issue 24) against independent references: central
differences of the exact network solver, the one-mass sensitivities (a separate implementation) on one-mass
networks, and the monodromy matrix of the period map."""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np
import pytest

from lumped.drivers.sensitivity import system_sensitivities
from lumped.model.files import parse_system
from lumped.model.system_parameters import system_parameters, with_values
from lumped.solvers.exact_network import march, sample
from lumped.solvers.network_modes import final_rest
from lumped.solvers.network_monodromy import network_period_map
from lumped.solvers.network_phase import parts
from lumped.solvers.network_sensitivities import Parameter, network_sensitivities

ROOT = Path(__file__).resolve().parent.parent
EPS = float(np.finfo(float).eps)

#: Two masses: a spring and a linear dashpot from the ground to a, a spring and a Coulomb element between
#: a and b, a Bingham element from the ground to b, a sine on a that goes off at 1.7 s.  Both slip from
#: t = 0 (b.v0 != 0, so that v0 has two-sided derivatives); 29 stops, 2 breakaways, then both rest.  Its
#: smallest event margin, 0.069, is asserted below (the first stop of dry, 5.4 ms after the start: w_max t
#: with w_max = 12.8 rad/s); that of the nearby b.mass = 2, pad.threshold = 3 is 0.0035, two stops 0.27 ms
#: apart that swap at pad.threshold = 3.0448 (tested below).
TWO = """
[[mass]]
name = "a"
mass = 1.0
x0 = 0.6
v0 = 0.3
[[mass]]
name = "b"
mass = 1.5
x0 = -0.2
v0 = -0.4
[[element]]
name = "k1"
kind = "spring"
between = ["ground", "a"]
stiffness = 100.0
[[element]]
name = "k12"
kind = "spring"
between = ["a", "b"]
stiffness = 50.0
[[element]]
name = "c1"
kind = "dashpot"
between = ["ground", "a"]
damping = 0.5
[[element]]
name = "pad"
kind = "bingham"
between = ["ground", "b"]
threshold = 3.5
gamma = 2.0
[[element]]
name = "dry"
kind = "bingham"
between = ["a", "b"]
threshold = 2.0
gamma = inf
[[force]]
on = "a"
amplitude = 8.0
omega = 6.0
phase = 0.3
until = 1.7
"""
NAMES = (
    "a.mass",
    "b.mass",
    "a.x0",
    "b.x0",
    "a.v0",
    "b.v0",
    "k1.stiffness",
    "k12.stiffness",
    "c1.damping",
    "pad.threshold",
    "pad.gamma",
    "dry.threshold",
    "force.amplitude",
    "force.omega",
    "force.phase",
    "force.until",
)
T_END = 5.0
TIMES = np.linspace(0.0, T_END, 81)


@pytest.fixture(scope="module")
def exact():
    """The derivatives by every parameter at once (the columns do not interact)."""
    return system_sensitivities(parse_system(TWO), TIMES, NAMES)[1]


def _values(net, t: np.ndarray) -> tuple[np.ndarray, list[str]]:
    """Both masses' ``x`` at ``t``, every event's time and positions, each mass's rest time and position (the
    exact network solver alone); and the events' kinds."""
    phases, events = march(parts(net), *(a[:-1] for a in net.initial_positions()), float(t[-1]), net.element_names)
    x = sample(phases, t)[0]
    at_events = [ph.values(ph.z0)[0] for ph in phases[1:]]
    rest = final_rest(phases, x[-1])
    out = [x.ravel(), [e.time for e in events], np.ravel(at_events), rest[0], rest[1]]
    return np.concatenate([np.asarray(a, dtype=float) for a in out]), [f"{e.kind} {e.elements}" for e in events]


def _differences(name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Central differences of :func:`_values` in ``name``, their error bound and the entries left smooth.

    As in ``tests/test_sensitivities.py``: the bound of ``|D_h - f'|`` is ``h^2/6 |f'''| + eps_f/h``
    (truncation plus round-off), ``eps_f = (events + 1) eps (max|x| + t_end max|v|)`` the exact solver's
    error (each phase rounds ``x`` by about ``eps |x|``, each event time by an ulp of ``t``, which moves the
    later motion by ``|v| eps t``), ``|f'''|`` bounded by twice its five-point difference at ``H = 30 h`` plus
    that difference's round-off ``3 eps_f/H^3``.  ``h = 1e-5 max(|p|, 1)``, a tenth of the one-mass test's:
    two events of this network come within 0.01 s of each other, and the stencil's ``2 H`` must not move
    one past the other (the event sequence is asserted unchanged); ``eps_f/h`` is then about 1e-8.  Times within ``2H |dt_e/dp|``
    (plus 1e-9 s) of an event are left out: there ``x(t)`` is only C^1 in ``p``.
    """
    net = parse_system(TWO)
    (prm,) = system_parameters(net, [name])
    h = 1e-5 * max(abs(prm.value), 1.0)
    big = 30 * h
    base, kinds = _values(net, TIMES)
    f = {}
    for step in (-2 * big, -big, -h, h, big, 2 * big):
        f[step], moved = _values(with_values(net, [prm], [prm.value + step]), TIMES)
        assert moved == kinds, f"the event sequence changes within the stencil of {name}"
    d_h = (f[h] - f[-h]) / (2 * h)
    phases = march(parts(net), *(a[:-1] for a in net.initial_positions()), T_END, net.element_names)[0]
    dense = sample(phases, np.linspace(0.0, T_END, 2001))
    eps_f = (len(kinds) + 1) * EPS * (np.abs(dense[0]).max() + T_END * np.abs(dense[1]).max())
    third = (f[2 * big] - 2 * f[big] + 2 * f[-big] - f[-2 * big]) / (2 * big**3)
    bound = h**2 / 6 * (2 * np.abs(third) + 3 * eps_f / big**3) + eps_f / h
    n, size = 2, TIMES.size * 2
    slopes = (f[big][size : size + len(kinds)] - f[-big][size : size + len(kinds)]) / (2 * big)
    event_times = base[size : size + len(kinds)]
    near = np.zeros(TIMES.size, dtype=bool)
    for t_e, slope in zip(event_times, slopes):
        near |= np.abs(TIMES - t_e) <= 2 * big * abs(slope) + 1e-9
    smooth = np.concatenate([np.repeat(~near, n), np.ones(d_h.size - size, dtype=bool)])
    return d_h, bound, smooth


def test_the_case_is_away_from_every_change_of_its_event_sequence(exact):
    assert exact.smallest_margin() > 0.05
    assert len(exact.events) == 32 and np.all(np.isfinite(exact.rest_time))  # both masses come to rest
    # stop_times: the slip-to-stick events, checked on the phases (4 of the 29 stops: at the others the element does not stick)
    names, phases = parse_system(TWO).element_names, exact.motion.phases
    sticks = [
        (names[e], ph.start)
        for before, ph in itertools.pairwise(phases)
        for e in np.flatnonzero((before.mode != 0) & (ph.mode == 0))
    ]
    assert [(name, time) for name, time, _ in exact.stop_times()] == sticks and len(sticks) == 4


def test_the_margins_vanish_on_both_sides_of_a_change_of_the_event_sequence():
    # b.mass = 2, pad.threshold = 3: dry and pad stop 0.27 ms apart at t = 0.25 s, and swap as the threshold
    # grows (at 3.0448).  The change is bracketed by bisection to 1e-9; there the smallest margin must be
    # within 1e-6 of 0 on both sides (it falls linearly, about 0.1 per unit of threshold, to 0; an event of
    # both elements at once has the margin 0), while 0.045 away it is 0.0035.
    near = with_values(parse_system(TWO), system_parameters(parse_system(TWO), ["b.mass"]), [2.0])
    (tau,) = system_parameters(near, ["pad.threshold"])

    def kinds(value: float) -> list[str]:
        return _values(with_values(near, [tau], [value]), TIMES)[1]

    def margin(value: float) -> float:
        return system_sensitivities(with_values(near, [tau], [value]), TIMES, ["a.x0"])[1].smallest_margin()

    lo, hi, first = 3.0, 3.1, kinds(3.0)
    assert kinds(hi) != first
    while hi - lo > 1e-9:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if kinds(mid) == first else (lo, mid)
    assert margin(lo) < 1e-6 and margin(hi) < 1e-6
    assert margin(3.0) > 1e-3


@pytest.mark.parametrize("name", NAMES)
def test_every_network_sensitivity_matches_central_differences(exact, name):
    j = NAMES.index(name)
    values = [exact.x[:, :, j].ravel(), [e.time[j] for e in exact.events], [e.x[:, j] for e in exact.events]]
    values += [exact.rest_time[:, j], exact.rest_position[:, j]]
    ours = np.concatenate([np.ravel(v) for v in values])
    d_h, bound, smooth = _differences(name)
    assert smooth.sum() > 0.8 * smooth.size
    assert np.all(np.abs(ours[smooth] - d_h[smooth]) <= bound[smooth])


def test_a_coulomb_gamma_does_not_move_the_motion_and_a_gamma_is_the_chain_rule_of_the_viscosity():
    net = parse_system(TWO)
    sens = system_sensitivities(net, TIMES, ["dry.gamma", "pad.gamma"])[1]
    assert not sens.x[:, :, 0].any()  # gamma = inf: c = 0 does not move with it
    pad = net.element_names.index("pad")
    by_c = network_sensitivities(
        parts(net), [0.6, -0.2], [0.3, -0.4], TIMES, [Parameter("viscosity", pad)], net.element_names
    )
    assert np.array_equal(sens.x[:, :, 1], -(0.5**2) * by_c.x[:, :, 0])  # c = 1/gamma = 0.5


# --- one mass, written as a network ----------------------------------------------------------------

FIGURE3 = (ROOT / "examples" / "figure3.toml").read_text()
FORCED = FIGURE3 + '\n[[force]]\non = "m"\namplitude = 30.0\nomega = 7.0\nphase = 0.4\nuntil = 2.2\n'
ONE_MASS = {
    "m.mass": Parameter("mass", 0),
    "m.x0": Parameter("x0", 0),
    "m.v0": Parameter("v0", 0),
    "spring.stiffness": Parameter("stiffness", 0),
    "dashpot.threshold": Parameter("threshold", 1),
    "force.amplitude": Parameter("amplitude"),
    "force.omega": Parameter("omega"),
    "force.phase": Parameter("phase"),
    "force.until": Parameter("until"),
}


@pytest.mark.parametrize("text", [FIGURE3, FORCED], ids=["free decay", "forced, then free"])
def test_a_one_mass_network_agrees_with_the_one_mass_sensitivities(text):
    # Two implementations: the one-mass chain (closed forms of the one-mass phases, its own event rules) and
    # the network's (block exponentials in the masses' full state).  Both are exact to round-off: each
    # phase's derivative carries a few ulps relative, and the dissipative motion does not amplify them, so
    # after the ~10 phases they agree to 1e-10 of the largest derivative of each column; the events' times
    # to 1e-10 of the largest relative derivative p dt/dp of any column (some are 0 but for round-off: a
    # half-cycle's duration does not depend on x0).
    net = parse_system(text)
    names = [n for n in ONE_MASS if n.startswith(("m.", "spring", "dashpot")) or "force" in text]
    t = np.linspace(0.0, 4.0, 161)
    _, one = system_sensitivities(net, t, names)
    ours = network_sensitivities(parts(net), [0.5], [0.0], t, [ONE_MASS[n] for n in names], net.element_names)
    assert one.smallest_margin() > 1e-2
    scale = np.abs(one.x).max(axis=0)
    assert np.all(np.abs(ours.x[:, 0, :] - one.x) <= 1e-10 * scale)
    # the one-mass stops and reversals are the network's, by one vocabulary (:data:`lumped.solvers.events.KINDS`)
    theirs = [e for e in one.events if e.event.kind in ("stop", "reversal")]
    mine = [e for e in ours.events if e.event.kind in ("stop", "reversal")]
    assert np.allclose([e.event.time for e in mine], [e.event.time for e in theirs], rtol=0, atol=1e-12)
    values = np.array([max(abs(p.value), 1.0) for p in system_parameters(net, names)])
    times = np.array([e.time for e in theirs] + [one.rest_time]) * values
    ours_times = np.array([e.time for e in mine] + [ours.rest_time[0]]) * values
    assert np.array_equal(np.isnan(times), np.isnan(ours_times))  # no rest in 4 s under the forced run
    assert np.nanmax(np.abs(ours_times - times)) <= 1e-10 * np.nanmax(np.abs(times))
    rest = np.abs(ours.rest_position[0] - one.rest_position)
    assert np.isnan(one.rest_time[0]) or np.all(rest <= 1e-10 * np.abs(one.x).max(axis=0))


def test_the_initial_state_columns_are_the_monodromy_matrix():
    # The period map's derivative (network_monodromy, in the masses' state without the loads' generators)
    # against the x0 and v0 columns at t = T under the same sine: two carryings of the same rules.
    net = parse_system(TWO)
    p = parts(net)
    omega = 6.0
    period = network_period_map(p, 0, 8.0, omega, np.array([0.6, -0.2, 0.3, -0.4]), net.element_names)
    forced = p._replace(loads=period.parts.loads, omegas=period.parts.omegas)
    cols = [Parameter(kind, i) for kind in ("x0", "v0") for i in range(2)]
    ours = network_sensitivities(forced, [0.6, -0.2], [0.3, -0.4], [2 * math.pi / omega], cols, net.element_names)
    matrix = np.vstack([ours.x[-1], ours.v[-1]])
    assert np.allclose(matrix, period.monodromy, rtol=0, atol=1e-10 * np.abs(period.monodromy).max())


def test_a_mass_on_a_linear_dashpot_goes_by_the_network_solver_and_matches_its_closed_form():
    # One mass on a spring (k = 100) and a linear dashpot (c): the one-mass solver lacks d.damping, the
    # network's takes it.  x(t) = x0 e^(-h t) (cos(w_d t) + h/w_d sin(w_d t)), h = c/2, w_d = sqrt(k - h^2): dx/dx0 is
    # x/x0, and dx/dc is checked against a central difference of the closed form (step 1e-6: truncation
    # about 1e-12 |x'''|, round-off about eps |x|/1e-6 = 1e-10), both to 1e-9.
    text = FIGURE3.split("[[element]]")[0] + (
        '[[element]]\nname = "s"\nkind = "spring"\nbetween = ["ground", "m"]\nstiffness = 100.0\n'
        '[[element]]\nname = "d"\nkind = "dashpot"\nbetween = ["ground", "m"]\ndamping = 2.0\n'
    )
    t = np.linspace(0.0, 1.0, 41)
    _, sens = system_sensitivities(parse_system(text), t, ["m.x0", "d.damping"])

    def closed(c: float) -> np.ndarray:
        h = c / 2
        wd = math.sqrt(100.0 - h * h)
        return 0.5 * np.exp(-h * t) * (np.cos(wd * t) + h / wd * np.sin(wd * t))

    assert np.allclose(sens.x[:, 0, 0], closed(2.0) / 0.5, rtol=0, atol=1e-9)
    assert np.allclose(sens.x[:, 0, 1], (closed(2.0 + 1e-6) - closed(2.0 - 1e-6)) / 2e-6, rtol=0, atol=1e-9)
