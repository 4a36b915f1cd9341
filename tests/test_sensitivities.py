"""Exact sensitivities of the one-mass exact solution (issue 24) against independent references: central
differences of the exact solver, the Coulomb oscillator's closed-form rest, the monodromy matrix, and the
one-sided derivatives on the two sides of a change in the number of half-cycles."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lumped.model.forcing import SwitchedSine
from lumped.model.oscillator import Oscillator
from lumped.solvers.exact import solve_exact
from lumped.solvers.monodromy import derivatives
from lumped.solvers.sensitivities import PARAMETER_NAMES, sensitivities

EPS = float(np.finfo(float).eps)

#: Four motions away from any change of their event sequence (their smallest margin is asserted):
#: the paper's free decay from rest (slip from t = 0, reversals, a stop, the rest); a forced Bingham
#: mass whose sine goes off at 2.5 s, during a slip, and then decays; a forced Bingham mass that starts
#: stuck and sticks, breaks away, stops and reverses; a Coulomb mass under a sine with a negative
#: amplitude and frequency that goes off at t = 14.3 s, during a stick, then comes to rest.
_KEYS = ("mass", "stiffness", "threshold", "gamma", "x0", "v0", "t_end")
_FORCE = ("force_amplitude", "force_omega", "force_phase", "force_until")
CASES = {
    name: dict(zip(_KEYS, system)) | dict(zip(_FORCE, force))
    for name, system, force in (
        ("paper's free decay", (1.0, 100.0, 1.0, 1.0, 0.5, 0.0, 4.0), (0.0, 0.0, 0.0, math.inf)),
        ("forced, then free", (1.0, 100.0, 1.0, 1.0, 0.5, 0.3, 5.0), (2.0, 3.0, 0.2, 2.5)),
        ("forced stick-slip", (1.0, 1.0, 1.0, 2.0, 0.2, 0.0, 20.0), (2.0, 1.3, 0.4, math.inf)),
        ("Coulomb, sine off", (1.0, 1.0, 1.0, math.inf, 0.2, -0.5, 20.0), (-2.5, -1.1, 0.4, 14.3)),
    )
}


def _moved(p: dict, name: str, step: float) -> dict:
    """``p`` with the parameter ``name`` moved by ``step``; ``viscosity`` is ``1/gamma``."""
    if name == "viscosity":
        return {**p, "gamma": 1.0 / (1.0 / p["gamma"] + step)}
    return {**p, name: p[name] + step}


def _solve(p: dict):
    osc = Oscillator.bingham(p["mass"], p["stiffness"], p["threshold"], p["gamma"])
    force = SwitchedSine(p["force_amplitude"], p["force_omega"], p["force_phase"], p["force_until"])
    return solve_exact(osc, p["t_end"], x0=p["x0"], v0=p["v0"], force=force)


def _values(sol, t: np.ndarray) -> tuple[np.ndarray, list[str]]:
    """``x`` at the times ``t``, then every event time and position and the rest; the event kinds."""
    events = [e for e in sol.events if e.kind != "rest"]
    out = [sol.evaluate(t)["x"], [e.time for e in events], [e.x[0] for e in events], [sol.rest_time, sol.rest_position]]
    return np.concatenate([np.asarray(a, dtype=float) for a in out]), [e.kind for e in events]


def _differences(p: dict, name: str, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Central differences of :func:`_values` in ``name`` with step ``h``, their error bound, and the
    indices that the stencil's event motion leaves smooth.

    The bound of ``|D_h - f'|`` is ``h^2/6 |f'''| + eps_f/h`` (truncation plus round-off).  ``eps_f =
    (events + 1) eps (max|x| + t_end max|v|)`` is the exact solver's error: each phase's closed form rounds
    ``x`` by about ``eps |x|``, and each event time is found to about an ulp of ``t``, which shifts the
    phases after it by ``eps t`` (``x`` by ``|v| eps t``); the dissipative flow does not amplify them.
    ``|f'''|`` is bounded by twice its five-point difference at ``H = 30 h``, plus that difference's own
    round-off ``3 eps_f/H^3``.  ``h = 1e-4 |p|`` is near the optimum ``(3 eps_f/|f'''|)^(1/3)`` for
    ``eps_f ~ 1e-13 |f|`` and ``|f'''| ~ |f|/p^3``.  Grid times within ``2H |dt_e/dp|`` (plus 1e-9 s) of an
    event are left out: there ``x(t)`` is only C^1 in ``p``, and its differences converge at first order.
    """
    h = 1e-4 * max(abs(p.get(name, 1.0)), 1.0)
    big = 30 * h
    base = _solve(p)
    f = {}
    for step in (-2 * big, -big, -h, h, big, 2 * big):
        f[step], kinds = _values(_solve(_moved(p, name, step)), t)
        assert kinds == _values(base, t)[1], f"the event sequence changes within the stencil of {name}"
    d_h = (f[h] - f[-h]) / (2 * h)
    cols = base.evaluate(np.linspace(0, p["t_end"], 2001))
    n_events = len(base.events)
    eps_f = (n_events + 1) * EPS * (np.abs(cols["x"]).max() + p["t_end"] * np.abs(cols["v"]).max())
    third = (f[2 * big] - 2 * f[big] + 2 * f[-big] - f[-2 * big]) / (2 * big**3)
    bound = h**2 / 6 * (2 * np.abs(third) + 3 * eps_f / big**3) + eps_f / h
    moved = [e for e in base.events if e.kind != "rest"]
    slopes = (f[big][t.size : t.size + len(moved)] - f[-big][t.size : t.size + len(moved)]) / (2 * big)
    near = np.zeros(t.size, dtype=bool)
    for e, slope in zip(moved, slopes):
        near |= np.abs(t - e.time) <= 2 * big * abs(slope) + 1e-9
    smooth = np.concatenate([~near, np.ones(d_h.size - t.size, dtype=bool)])
    return d_h, bound, smooth


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("name", PARAMETER_NAMES)
def test_every_sensitivity_matches_central_differences(case, name):
    p = CASES[case]
    if name in ("gamma", "viscosity") and math.isinf(p["gamma"]):
        pytest.skip("Coulomb: c = 0 is the edge of the range of c, a central difference cannot straddle it")
    if name == "force_until" and math.isinf(p[name]):
        pytest.skip("the force never goes off")
    if name == "v0" and p["v0"] == 0:
        pytest.skip("v0 = 0 with a stick at the start: one-sided (tested below)")
    t = np.linspace(0.0, p["t_end"], 97)
    sol = _solve(p)
    sens = sensitivities(sol, t, [name])
    assert sens.smallest_margin() > 1e-2  # away from every change of the event sequence
    events = [e for e in sens.events]
    exact = np.concatenate(
        [sens.x[:, 0], [e.time[0] for e in events], [e.x[0] for e in events], sens.rest_time, sens.rest_position]
    )
    d_h, bound, smooth = _differences(p, name, t)
    keep = smooth & np.isfinite(d_h)
    assert keep.sum() > 0.8 * t.size
    assert np.all(np.abs(exact[keep] - d_h[keep]) <= bound[keep])
    assert np.array_equal(np.isnan(exact), np.isnan(d_h))  # no rest, no derivative


def test_gamma_is_the_chain_rule_of_viscosity_and_does_not_move_a_coulomb_dashpot():
    p = CASES["forced, then free"]
    t = np.linspace(0.0, p["t_end"], 97)
    sens = sensitivities(_solve(p), t, ["viscosity", "gamma"])
    c = 1.0 / p["gamma"]
    assert np.array_equal(sens.x[:, 1], -(c**2) * sens.x[:, 0])  # dc/dgamma = -1/gamma^2, exactly
    coulomb = sensitivities(_solve(CASES["Coulomb, sine off"]), t, ["gamma", "viscosity"])
    assert not coulomb.x[:, 0].any() and coulomb.x[:, 1].any()  # gamma = inf: c = 0 does not move with it


def test_the_coulomb_rest_matches_its_closed_form_to_1e_12():
    # m = k = friction = 1 from x0 = 12, v0 = 6: the first half-cycle about -b (b = tau/k) has the
    # amplitude A = sqrt((x0 + b)^2 + m v0^2/k) = sqrt(205) and turns at A - b; each later one shortens
    # |x| by 2b, and the seventh stops inside the band: rest = 15 b - A = 15 - sqrt(205), at the time
    # (phi + 7 pi)/omega_n, phi = atan2(v0/omega_n, x0 + b).  Both hold while the count of half-cycles
    # does (the margins are asserted); their derivatives are the closed forms below.  The solver's own
    # values are good to a few ulps of 15 per phase: 1e-12 leaves room for the 8 phases.
    m, k, tau, x0, v0 = 1.0, 1.0, 1.0, 12.0, 6.0
    sol = solve_exact(Oscillator.bingham(m, k, tau, math.inf), 40.0, x0=x0, v0=v0)
    assert sol.rest_position == pytest.approx(15 - math.sqrt(205), abs=1e-13)
    names = ["x0", "v0", "threshold", "mass", "stiffness"]
    sens = sensitivities(sol, (), names)
    assert sens.smallest_margin() > 0.1
    b, wn = tau / k, math.sqrt(k / m)
    A = math.hypot(x0 + b, v0 / wn)
    db_dk = -tau / k**2
    position = [
        -(x0 + b) / A,
        -m * v0 / (k * A),
        15 / k - (x0 + b) / (k * A),
        -(v0**2) / (2 * k * A),
        15 * db_dk - ((x0 + b) * db_dk - m * v0**2 / (2 * k**2)) / A,
    ]
    assert np.abs(sens.rest_position - position).max() <= 1e-12
    time = [-(v0 / wn) / A**2 / wn, (x0 + b) / (wn * A**2) / wn]  # d((phi + 7 pi)/omega_n)/d(x0, v0)
    assert np.abs(sens.rest_time[:2] - time).max() <= 1e-12


@pytest.mark.parametrize(("gamma", "ratio"), [(math.inf, 0.5), (1.0, 0.3)])
def test_the_x0_v0_columns_at_a_period_are_the_monodromy_matrix(gamma, ratio):
    # The same derivative by two codes: this module's block exponential and the monodromy's flow matrix
    # (lumped.solvers.monodromy); they differ by the roundings of a few matrix products: 1e-12 of |M|.
    osc, p, w = Oscillator.bingham(1.0, 100.0, 1.0, gamma), 1.0 / ratio, 7.0
    sol = solve_exact(osc, 2 * math.pi / w, x0=0.003, v0=-0.01, force=SwitchedSine(p, w))
    assert "stop" in {e.kind for e in sol.events} and "breakaway" in {e.kind for e in sol.events}
    sens = sensitivities(sol, [sol.t_end], ["x0", "v0", "force_omega"])
    M, d_omega = derivatives(sol)
    assert np.abs(np.vstack([sens.x, sens.v])[:, :2] - M).max() <= 1e-12 * np.abs(M).max()
    # and the omega column: the chain's d(x, v)(t)/domega at the fixed t = T, plus the field there times
    # dT/domega = -T/omega, is the closed-form dPi/domega the continuation uses (the particular solution's
    # derivative in omega, lumped.solvers.monodromy.derivatives); they differ by roundings, 1e-10 of its size
    # (the closed form subtracts particular solutions of size P/|k - m w^2|, a few times the motion here).
    end = sol.evaluate(np.array([sol.t_end]))
    field = np.array([end["v"][0], (p * math.sin(w * sol.t_end) - end["F_d"][0] - 100.0 * end["x"][0])])
    chain = np.array([sens.x[0, 2], sens.v[0, 2]]) - field * sol.t_end / w
    assert np.abs(chain - d_omega).max() <= 1e-10 * np.abs(d_omega).max()


def test_a_stuck_start_has_zero_v0_derivative_and_a_sliding_one_the_derivative_of_its_side():
    # A stick at t = 0 (|F(0) - k x0| < tau): v0 = +-h slips for a time O(h) and stops again O(h^2)
    # away, so the derivative is 0 on both sides, the differences O(h).  A slip from rest at t = 0
    # (the paper's x0 = 0.5): v0 of the slip's sign continues the same motion, so the derivative is the
    # one-sided one from that side, with a difference error O(h); from the other side a short
    # reversal first makes it differ by O(1).
    t, h = np.linspace(0.0, 4.0, 41), 1e-6
    stuck = CASES["forced stick-slip"]
    base = _solve(stuck)
    assert sensitivities(base, t, ["v0"]).x.max() == 0.0 == np.abs(sensitivities(base, t, ["v0"]).x).max()
    for step in (h, -h):
        moved = _solve({**stuck, "v0": step}).evaluate(t)["x"]
        assert np.abs(moved - base.evaluate(t)["x"]).max() / h <= 1e-3
    paper = CASES["paper's free decay"]
    base, sens = _solve(paper), sensitivities(_solve(paper), t, ["v0"])
    left = (base.evaluate(t)["x"] - _solve({**paper, "v0": -h}).evaluate(t)["x"]) / h
    right = (_solve({**paper, "v0": h}).evaluate(t)["x"] - base.evaluate(t)["x"]) / h
    assert np.abs(left - sens.x[:, 0]).max() <= 1e-7  # O(h): |x''| h ~ 2e-9 with |x''| ~ 1e-3
    assert np.abs(right - sens.x[:, 0]).max() > 1e-3


def _count(tau: float) -> int:
    sol = solve_exact(Oscillator.bingham(1.0, 100.0, tau, 1.0), 20.0, x0=0.5)
    return len(sol.event_times("reversal"))


def test_across_a_lost_half_cycle_the_rest_is_continuous_and_its_derivatives_are_the_switches():
    # Bisect tau to the last double below which the paper's free decay has one more half-cycle;
    # there the stop (or the last reversal) lies on the band edge to round-off (margin ~1e-15).  The
    # rest position is continuous (it differs by |dx/dtau| ulp(tau)), its derivative jumps: the
    # derivative of each side must be the other side's RestSwitch, and the rest time's jump the
    # switch's, to the first order in the margin (1e-15 of the scales) plus round-off: 1e-9.
    lo, hi = 0.93, 0.94
    assert _count(lo) == _count(hi) + 1
    while math.nextafter(lo, hi) < hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _count(mid) == _count(lo) else (lo, mid)
    names = ["threshold", "stiffness", "gamma", "x0", "mass"]
    more, fewer = (solve_exact(Oscillator.bingham(1.0, 100.0, tau, 1.0), 20.0, x0=0.5) for tau in (lo, hi))
    s_more, s_fewer = sensitivities(more, (), names), sensitivities(fewer, (), names)
    assert abs(more.rest_position - fewer.rest_position) <= 1e-15
    lose = next(w for w in s_more.switches if w.kind == "lose")
    gain = next(w for w in s_fewer.switches if w.kind == "gain")
    assert lose.margin < 1e-12 and gain.margin < 1e-12
    assert np.abs(s_more.rest_position - s_fewer.rest_position).max() > 0.01  # a kink, not a smooth point
    assert np.abs(lose.rest_position - s_fewer.rest_position).max() <= 1e-9
    assert np.abs(gain.rest_position - s_more.rest_position).max() <= 1e-9
    assert lose.rest_time_jump == pytest.approx(fewer.rest_time - more.rest_time, abs=1e-9)
    assert gain.rest_time_jump == pytest.approx(more.rest_time - fewer.rest_time, abs=1e-9)


def test_bad_arguments_are_refused_in_one_line():
    sol = _solve(CASES["paper's free decay"])
    with pytest.raises(ValueError, match=r"^parameters: unknown parameter 'tau'; expected some of mass, "):
        sensitivities(sol, (), ["tau"])
    with pytest.raises(ValueError, match=r"^t: times must lie in \[0, t_end\] = \[0, 4.0\] s, got 5.0$"):
        sensitivities(sol, [1.0, 5.0], ["x0"])
    with pytest.raises(ValueError, match="^solution must be an ExactSolution, got dict$"):
        sensitivities({}, (), ["x0"])
