"""The pure-Python DOP853 (lumped.numerics.dop853) against SciPy's ``DOP853`` and closed forms.

SciPy's stepper is the reference: the same tableau, error norm, controller and
initial step must give the same steps.  The two differ only in the order of
summation inside dot products (numpy's BLAS against Python's left-to-right
``sum``), so every comparison of one step from the same state is to
round-off, with one subtlety: the error estimate ``sum_s E5_s k_s`` cancels
the stages down to the local error, so its relative round-off is ``eps``
times the cancellation ratio ``kappa = sum |E5_s k_s| / |sum E5_s k_s|``,
and the controller passes ``1/8`` of that to the next step size.  Over a
whole free run those differences grow into different step sequences, so a
whole run is compared with the tolerance's global error, not to round-off.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import EPS
from scipy.integrate import DOP853, OdeSolution, solve_ivp
from scipy.integrate._ivp import dop853_coefficients as ref

from lumped.numerics import dop853
from lumped.numerics import dop853_tableau as tab

W = 3.0  # angular frequency of the harmonic oscillator (rad/s)


def harmonic(t, y):
    return (y[1], -W * W * y[0])


def pendulum(t, y):
    """A damped, forced pendulum: nonlinear, non-autonomous, smooth."""
    return (y[1], -math.sin(y[0]) - 0.1 * y[1] + 0.5 * math.cos(t))


CASES = {  # name -> (rhs, y0, t_end, rtol, atol)
    "harmonic": (harmonic, [1.0, 0.0], 10.0, 1e-10, [1e-12, 1e-12]),
    "pendulum": (pendulum, [1.0, 0.0], 20.0, 1e-9, [1e-12, 1e-12]),
}


def _scipy(case: str) -> DOP853:
    fun, y0, t_end, rtol, atol = CASES[case]
    return DOP853(lambda t, y: np.array(fun(t, y)), 0.0, np.array(y0), t_end, rtol=rtol, atol=np.array(atol))


def _ours(case: str) -> dop853.Dop853:
    fun, y0, t_end, rtol, atol = CASES[case]
    return dop853.Dop853(fun, 0.0, y0, t_end, rtol, atol)


def test_tableau_is_scipys_bit_for_bit():
    for s in range(1, tab.N_STAGES_EXTENDED):
        assert tab.A[s] == tuple(ref.A[s, :s]), s
    assert tab.C == tuple(ref.C)
    assert tab.B == tuple(ref.B)
    assert tab.E5 == tuple(ref.E5) and tab.E3 == tuple(ref.E3)
    assert tab.D == tuple(tuple(r) for r in ref.D)


@pytest.mark.parametrize("case", list(CASES))
def test_initial_step_is_scipys(case):
    # A ratio of root-mean-square norms: a few roundings, all well conditioned.
    assert _ours(case).h_abs == pytest.approx(_scipy(case).h_abs, rel=8 * EPS)


def _kappa(K: list[list[float]]) -> float:
    """The cancellation ratio of the 5th-order error estimate (module docstring)."""
    out = 1.0
    for Kc in K:
        terms = [e * k for e, k in zip(tab.E5, Kc)]
        out = max(out, sum(map(abs, terms)) / max(abs(sum(terms)), 1e-300))
    return out


@pytest.mark.parametrize("case", list(CASES))
def test_each_step_is_scipys_from_the_same_state(case):
    """Lockstep: ours is put in SciPy's state before each of SciPy's steps and takes the same step.

    Without a rejection the new time is the same float (the same trial size);
    after one it agrees to ``1e-7`` of the step: a rejected estimate exceeds 1,
    so it is at least ``rtol`` times the scale while the stages are of the
    scale's size, ``kappa <= ~1/rtol = 1e9``, and ``eps kappa / 8 < 3e-8``.
    The new state agrees to a few roundings of its size (plus ``|f|`` times
    the difference in time), the next step size to ``1/8`` of the error
    estimate's round-off (``16 eps kappa`` for each side, generously), and the
    dense output to round-off at the same times.
    """
    sp, ours = _scipy(case), _ours(case)
    theta = np.linspace(0.0, 1.0, 9)
    rejections = 0
    while sp.status == "running":
        ours.t, ours.y, ours.f, ours.h_abs = sp.t, list(sp.y), list(sp.f), sp.h_abs
        h_try = sp.h_abs
        sp.step()
        assert ours.step()
        h = sp.t - sp.t_old
        rejected = sp.t != min(sp.t_old + h_try, sp.t_bound)
        rejections += rejected
        assert ours.t == sp.t if not rejected else ours.t == pytest.approx(sp.t, abs=1e-7 * h)
        size = np.abs(sp.y).max() + h * np.abs(sp.f).max()
        drift = abs(ours.t - sp.t) * np.abs(sp.f).max()
        assert np.abs(np.array(ours.y) - sp.y).max() <= 16 * EPS * size + drift
        kappa = _kappa(ours._last[2])
        assert ours.h_abs == pytest.approx(sp.h_abs, rel=2 * 16 * EPS * kappa / 8 + 4 * EPS), (h_try, kappa)
        t = sp.t_old + theta * min(h, ours.t - ours.t_old)
        dense, piece = sp.dense_output()(t), ours.dense_output()
        mine = np.array([[dop853.piece_value(piece, ti, c) for ti in t] for c in range(2)])
        assert np.abs(mine - dense).max() <= 64 * EPS * size
    assert case == "harmonic" or rejections > 0  # the pendulum's run does exercise the rejection branch


def _variational(t, z):
    """The pendulum and its variational equation ``P' = J(t, y) P`` (``z = (y, P.ravel())``)."""
    x, v = z[0], z[1]
    jac = np.array([[0.0, 1.0], [-math.cos(x), -0.1]])
    return np.concatenate([pendulum(t, z[:2]), (jac @ z[2:].reshape(2, 2)).ravel()])


#: ``sup_{0 <= s <= t <= t_end} |Phi(t, s)|_2``: how much the flow magnifies an error made at ``s`` by ``t``
#: (``max(W, 1/W)`` for the harmonic oscillator, whose fundamental matrix is a rotation scaled by ``W``; the
#: pendulum's is checked by ``test_flow_amplification_of_the_pendulum``).
AMPLIFICATION = {"harmonic": W, "pendulum": 7.5}


def test_flow_amplification_of_the_pendulum():
    """``AMPLIFICATION["pendulum"]`` bounds ``|Phi(t) Phi(s)^-1|_2`` on a grid of ``(s, t)`` (it is 7.14)."""
    grid = np.linspace(0.0, 20.0, 401)
    sol = solve_ivp(_variational, (0.0, 20.0), [1.0, 0.0, 1.0, 0.0, 0.0, 1.0], "DOP853", grid, rtol=1e-10, atol=1e-12)
    P = sol.y[2:].T.reshape(-1, 2, 2)
    norms = np.linalg.norm(np.einsum("tij,sjk->tsik", P, np.linalg.inv(P)), 2, axis=(2, 3))
    sup = np.tril(norms).max()
    assert 5.0 < sup <= AMPLIFICATION["pendulum"]


def _reference(case: str, grid: np.ndarray) -> np.ndarray:
    """The closed form for the harmonic oscillator, SciPy's DOP853 at ``rtol = 1e-13`` for the pendulum."""
    if case == "harmonic":
        return np.array([np.cos(W * grid), -W * np.sin(W * grid)])
    fun, y0, t_end = CASES[case][:3]
    sol = solve_ivp(
        lambda t, y: np.array(fun(t, y)), (0.0, t_end), y0, "DOP853", rtol=1e-13, atol=1e-15, dense_output=True
    )
    return sol.sol(grid)


@pytest.mark.parametrize("case", list(CASES))
def test_a_whole_run_takes_scipys_steps_and_values(case):
    """Run free: as many steps as SciPy, and both runs within the tolerance's global error of a reference.

    The step sizes of a free run are not compared one by one: they follow
    round-off.  The first step's error estimate is pure round-off (``kappa``
    ~1e16) and the second's nearly so (~1e13), so the third size already
    differs by up to ``eps kappa / 8`` ~1e-3 between two summation orders; the
    grids then differ by a shift in time, and the controller's
    ``h ~ (tol / C(t))^(1/8)`` turns that shift into a relative change of
    ``|d ln C / dt| shift / 8``, large where the local error coefficient ``C``
    passes near zero.  Measured on the pendulum: sin or cos one ulp off moves
    single steps by up to 3.5e-3, reordering the right-hand side's terms by
    2.3e-2.  The lockstep test compares each step from the same state; here:

    * the step count: it changes only if ``t_end`` moves across a breakpoint,
      so it is compared when the grids' shift is below a quarter of ``t_end``'s
      distance to the nearest breakpoint (last step, or last full step's end);
    * the values: each accepted step's local error is at most its tolerance,
      ``sqrt(n) (atol + rtol |y|)`` per component (the error norm is an rms
      below 1), and the flow magnifies an error made at ``s`` by at most
      ``AMPLIFICATION`` at ``t``, so each run is within
      ``AMPLIFICATION sqrt(n) sum_steps (atol + rtol max|y|)`` of the true
      solution, here the reference.
    """
    sp, ours = _scipy(case), _ours(case)
    ts, to, ds, do = [0.0], [0.0], [], []
    while sp.status == "running":
        sp.step()
        ts.append(sp.t)
        ds.append(sp.dense_output())
    while ours.status == "running":
        assert ours.step()
        to.append(ours.t)
        do.append(ours.dense_output())
    n = min(len(ts), len(to)) - 1  # the last breakpoint before t_end of the shorter run
    shift = np.abs(np.subtract(ts[:n], to[:n])).max()
    last, full = ts[-1] - ts[-2], ts[-2] - ts[-3]
    assert shift < min(last, full - last) / 4, (shift, last, full)
    assert len(to) == len(ts) and to[-1] == ts[-1]
    fun, y0, t_end, rtol, atol = CASES[case]
    grid = np.linspace(0.0, t_end, 2001)
    ref = _reference(case, grid)
    for run in (OdeSolution(ts, ds)(grid), dop853.PiecewiseDense(to, do)(grid)):
        scale = np.abs(ref).max(axis=1)  # max |y| of each component
        bound = AMPLIFICATION[case] * math.sqrt(2) * len(ts) * (np.array(atol) + rtol * scale).max()
        assert np.abs(run - ref).max() <= bound


def test_harmonic_oscillator_against_its_closed_form():
    """``cos(W t)`` to the global error the tolerance allows: steps times ``rtol`` (the flow is an isometry)."""
    ours = _ours("harmonic")
    ts, pieces = [0.0], []
    while ours.status == "running":
        ours.step()
        ts.append(ours.t)
        pieces.append(ours.dense_output())
    grid = np.linspace(0.0, 10.0, 1001)
    x, v = dop853.PiecewiseDense(ts, pieces)(grid)
    bound = len(pieces) * 1e-10 * W
    assert np.abs(x - np.cos(W * grid)).max() <= bound
    assert np.abs(v + W * np.sin(W * grid)).max() <= bound * W


def test_piecewise_dense_shapes_and_breakpoints():
    """A scalar gives shape ``(n,)``; a breakpoint takes the earlier piece, as SciPy's ``OdeSolution``."""
    ours = _ours("harmonic")
    ts, pieces = [0.0], []
    for _ in range(3):
        ours.step()
        ts.append(ours.t)
        pieces.append(ours.dense_output())
    dense = dop853.PiecewiseDense(ts, pieces)
    assert dense(ts[1]).shape == (2,)
    assert dense(np.array(ts)).shape == (2, 4)
    assert dense(ts[1])[0] == dop853.piece_value(pieces[0], ts[1], 0)


def test_overflow_is_a_rejected_step_then_a_failure():
    """``y' = y^2`` from ``1e150`` blows up at ``t = 1e-150``: its power overflows (an ``OverflowError``
    in Python, an infinity in numpy), every trial step is rejected, and the step fails instead of raising."""
    ours = dop853.Dop853(lambda t, y: (y[0] ** 2.0,), 0.0, [1e150], 1.0, 1e-6, [1e-9])
    steps = 0
    while ours.status == "running" and ours.step():
        steps += 1
    assert ours.status == "failed" and ours.t < 1e-150


def test_the_critical_times_are_the_dense_outputs_extrema_and_the_spread_bounds_it():
    """``x = sin t`` from t = 1 to 10: the steps' critical times of ``x`` are the maxima and minima ``pi/2 + j pi``,
    each found once.  The harmonic flow is a rotation, so the state's error after ``n`` steps is at most ``n``
    local errors (``rtol |y| + atol``, ``|y| = 1``), a shift of the phase by as much; the interpolant's own error
    (order 7, of the same size) moves the extremum by no more: ``4 n rtol``.  On every step the dense output stays
    above ``min(x(a), x(b)) - piece_spread`` (:func:`dop853.piece_spread`'s inequality, on 65 points a step)."""
    rtol = 1e-12
    solver = dop853.Dop853(lambda t, y: (y[1], -y[0]), 1.0, (math.sin(1.0), math.cos(1.0)), 10.0, rtol, (1e-15, 1e-15))
    found, steps = [], 0
    theta = np.linspace(0.0, 1.0, 65)
    while solver.status == "running":
        assert solver.step()
        steps += 1
        piece = solver.dense_output()
        found += [(t, steps) for t in dop853.piece_critical_times(piece, 0)]
        x = [dop853.piece_value(piece, piece.t_old + th * piece.h, 0) for th in theta]
        assert min(x) >= min(x[0], x[-1]) - dop853.piece_spread(piece, 0)
    expected = [math.pi / 2 + j * math.pi for j in range(3)]
    assert len(found) == len(expected)
    for (t, n), ref in zip(found, expected):
        assert t == pytest.approx(ref, abs=4 * n * rtol)
