"""The Den Hartog study (lumped.studies.den_hartog): closed form, simulations, boundary, chunks, bad inputs.

The references are independent of the package (tests/references.py): Den
Hartog's published formula and his no-stop boundary for Coulomb friction, and
a numerical shooting over a half-period (solve_ivp + fsolve) for combined
Coulomb and viscous damping.
"""

import math

import numpy as np
import pytest
from conftest import EPS
from references import den_hartog_amplitude, den_hartog_boundary, shoot_steady_slip

import lumped.studies.config
from lumped import studies
from lumped.drivers.sweep import sweep
from lumped.model.oscillator import Oscillator
from lumped.studies import den_hartog as dh

CFG = lumped.studies.config.default()
M, K, F = CFG["mass"], CFG["stiffness"], CFG["threshold"]
WN = math.sqrt(K / M)
#: The paper's viscous coefficient c = 1/gamma (damping ratio 0.05).
C = 1.0 / CFG["gamma"]
EPS = np.finfo(float).eps


def _ratio(c: float, fp: float, r: float) -> float:
    """The library's X k/P at (c, F/P, r)."""
    return dh.closed_form(M, c, K, F, F / fp, r * WN).amplitude * K / (F / fp)


@pytest.mark.parametrize("r", [0.6, 0.8, 1.3, 2.0, 2.5])
@pytest.mark.parametrize("fp", [0.1, 0.3, 0.5, 0.7])
def test_coulomb_closed_form_is_den_hartogs_formula(fp, r):
    """Round-off only: both are a few dozen flops; the root sqrt(A^2 - B^2) amplifies a relative error by
    A^2/(A^2 - B^2) (the condition number, computed here), so 100 eps times it bounds the difference."""
    ref = den_hartog_amplitude(r, fp)
    got = _ratio(0.0, fp, r)
    if math.isnan(ref):
        assert math.isnan(got)
        return
    u = math.sin(math.pi / r) / (1 + math.cos(math.pi / r))
    condition = (1 / (1 - r * r) ** 2) / ref**2 + 1 / abs(1 - r * r)
    assert got == pytest.approx(ref, rel=100 * EPS * condition * (1 + abs(u)))


@pytest.mark.parametrize(
    ("fp", "r"),
    [
        (0.2, 0.8),
        (0.4, 1.3),
        pytest.param(0.6, 2.0, marks=pytest.mark.slow),
        pytest.param(0.2, 2.4, marks=pytest.mark.slow),
        (0.4, 0.7),
    ],
)
def test_combined_closed_form_is_the_shooting_solution(fp, r):
    """The half-period boundary-value problem solved numerically (DOP853 at rtol 1e-12 over half a period,
    residual below 1e-12): 1e-9 leaves three orders of magnitude for the integrator's global error."""
    p, w = F / fp, r * WN
    x_amp, psi, residual = shoot_steady_slip(M, C, K, F, p, w)
    assert residual < 1e-12
    got = dh.closed_form(M, C, K, F, p, w)
    assert got.amplitude == pytest.approx(x_amp, rel=1e-9)
    assert math.remainder(got.phase - psi, 2 * math.pi) == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize(
    ("c", "fp", "r"),
    [
        (0.0, 0.4, 0.7),
        (0.0, 0.6, 1.5),
        (C, 0.4, 1.3),
        pytest.param(C, 0.2, 2.2, marks=pytest.mark.slow),
        pytest.param(C, 0.6, 0.8, marks=pytest.mark.slow),
    ],
)
def test_long_runs_reach_the_closed_form_without_stops(c, fp, r):
    """The exact solver from rest: the amplitude has settled (change between the last two windows below
    1e-10); the event times are refined to a few ulps and |x| is stationary at them, so the floor is round-off
    and the error is the transient left.  Measured on the full grid (960 rows): rows settled to 1e-10 were within
    6.2e-11 of the closed form; 1e-9 is ten times the settling asked for."""
    gamma = math.inf if c == 0 else 1 / c
    run = dh.steady_state(Oscillator.bingham(M, K, F, gamma), F / fp, r * WN)
    assert run.stops == 0
    assert abs(run.amplitude - run.previous) < 1e-10 * run.amplitude
    p = F / fp
    ref = den_hartog_amplitude(r, fp) * p / K if c == 0 else shoot_steady_slip(M, c, K, F, p, r * WN)[0]
    assert run.amplitude == pytest.approx(ref, rel=1e-9)


@pytest.mark.parametrize(
    "r",
    [
        0.6,
        1.2,
        pytest.param(0.9, marks=pytest.mark.slow),
        pytest.param(2.0, marks=pytest.mark.slow),
        pytest.param(2.5, marks=pytest.mark.slow),
    ],
)
@pytest.mark.parametrize("side", [0.85, 1.15])
def test_coulomb_runs_stop_exactly_beyond_den_hartogs_boundary(r, side):
    """15 % off the boundary each way: the closed form's admissibility and the simulation's stop events agree
    with Den Hartog's boundary (reference), for r >= 0.6 where the turning-point condition is the binding one."""
    fp = side * den_hartog_boundary(r)
    nonstop = side < 1
    assert dh.closed_form(M, 0.0, K, F, F / fp, r * WN).nonstop == nonstop
    run = dh.steady_state(Oscillator.bingham(M, K, F, math.inf), F / fp, r * WN)
    assert (run.stops == 0) == nonstop


def test_event_summary_is_the_sweeps_sampled_definition():
    """sweep(method='exact') samples the same run on t_n = n dt: its steady_amplitude lies below the event
    summary by at most max|x''| dt^2/2 (|x''| <= (k X + P + F)/m), and counts the same stops per period."""
    p, w, dt = F / 0.8, 0.6 * WN, 1e-3
    run = dh.steady_state(Oscillator.bingham(M, K, F, math.inf), p, w)
    t_end = dh.TRANSIENT + 2 * dh.PERIODS * 2 * math.pi / w
    fixed = {"mass": M, "stiffness": K, "threshold": F, "gamma": math.inf, "force_amplitude": p}
    s = sweep({"force_omega": [w]}, t_end=t_end, dt=dt, method="exact", periods=dh.PERIODS, **fixed)
    bound = (K * run.amplitude + p + F) / M * dt**2 / 2
    assert 0 <= run.amplitude - s["steady_amplitude"][0] <= bound
    assert run.stops > 0 and s["stops_per_period"][0] == run.stops / dh.PERIODS


@pytest.fixture
def small(monkeypatch):
    """One F/P and a short transient: a grid of 2 x 1 x 3 rows in well under a second."""
    monkeypatch.setattr(dh, "FRICTION_RATIOS", (0.4,))
    monkeypatch.setattr(dh, "TRANSIENT", 3.0)
    return dh.rows(CFG, 3)


def test_chunks_merged_equal_the_unchunked_rows(small, tmp_path):
    parts = [tmp_path / f"chunk-{i}.csv" for i in range(4)]
    for i, part in enumerate(parts):
        studies.write_csv(dh.rows(CFG, 3, (i, 4)), part, dh.COLUMNS)
    studies.merge_csv(parts, tmp_path / "den_hartog.csv", dh.COLUMNS)
    merged = studies.read_csv(tmp_path / "den_hartog.csv", dh.COLUMNS)
    for name in dh.COLUMNS:  # bit for bit: floats are written by repr
        assert np.array_equal(merged[name], small[name], equal_nan=True), name
    assert merged["damping"].tolist() == [0.0] * 3 + [C / (2 * math.sqrt(K * M))] * 3


@pytest.mark.parametrize(
    ("args", "start"),
    [
        ((M, 2 * math.sqrt(K * M), K, F, 1.0, 5.0), "damping: c must lie in [0, 2 sqrt(k m))"),
        ((M, -1.0, K, F, 1.0, 5.0), "damping: c must lie in"),
        ((M, 0.0, K, -1.0, 1.0, 5.0), "threshold"),
        ((M, 0.0, K, F, 0.0, 5.0), "force_amplitude"),
        ((M, 0.0, K, F, 1.0, -5.0), "force_omega"),
        ((M, 0.0, K, F, 1.0, WN), "force_omega: omega = sqrt(k/m) with c = 0"),
        ((0.0, 0.0, K, F, 1.0, 5.0), "mass"),
        ((M, math.nan, K, F, 1.0, 5.0), "damping"),
    ],
)
def test_bad_inputs_are_one_line_errors(args, start):
    with pytest.raises(ValueError) as err:
        dh.closed_form(*args)
    assert str(err.value).startswith(start) and "\n" not in str(err.value)


def test_the_study_needs_a_finite_gamma_and_a_valid_chunk():
    with pytest.raises(ValueError, match=r"^gamma: the study's combined damping needs a finite gamma"):
        dh.rows(CFG | {"gamma": math.inf}, 3)
    with pytest.raises(ValueError, match=r"^index must be an integer in \[0, 1\]"):
        dh.rows(CFG, 3, (2, 2))


def test_the_figure_draws_stopped_rows_hollow_and_the_curve_dotted_where_it_stops():
    """dh01's marking of the boundary: filled points are the rows without stops, hollow the others; the solid
    curve is the closed form where admissible, the dotted one where not (nan elsewhere)."""
    import matplotlib.pyplot as plt

    from lumped.plotting import den_hartog_amplitudes

    table = {
        "damping": np.zeros(4),
        "friction_ratio": np.full(4, 0.4),
        "frequency_ratio": np.array([0.5, 1.5, 2.0, 2.5]),
        "amplitude_ratio": np.array([1.0, 0.5, 0.3, 0.2]),
        "stops_per_period": np.array([2.0, 0.0, 0.0, 2.0]),
    }
    r = np.array([0.5, 1.5, 2.0])
    fig = den_hartog_amplitudes(table, {(0.0, 0.4): (r, np.array([1.0, 0.5, 0.3]), np.array([False, True, True]))})
    solid, dotted, filled, hollow = fig.axes[0].lines
    np.testing.assert_array_equal(solid.get_ydata(), [np.nan, 0.5, 0.3])
    np.testing.assert_array_equal(dotted.get_ydata(), [1.0, np.nan, np.nan])
    np.testing.assert_array_equal(filled.get_xdata(), [1.5, 2.0])
    np.testing.assert_array_equal(hollow.get_xdata(), [0.5, 2.5])
    assert hollow.get_markerfacecolor() == "none" and solid.get_linestyle() == "-" and dotted.get_linestyle() == ":"
    plt.close(fig)


def test_the_library_boundary_is_the_reference_boundary():
    """dh.coulomb_boundary (drawn over notebook 12's map) against the test's own eq. (5), and its limit pi/4 at r = 1."""
    r = np.geomspace(dh.BOUNDARY_FROM, 3.0, 41)
    r = r[np.abs(r - 1) > 1e-3]
    ours = dh.coulomb_boundary(r)
    ref = np.array([den_hartog_boundary(float(x)) for x in r])
    # The reference's U = sin(x) / (1 + cos(x)), x = pi/r, carries a relative round-off of a few
    # eps / |1 + cos x| (the sum cancels near r = 1) plus eps x / |sin x| (the argument's rounding,
    # near x = pi), and the boundary at most that of U; the library's form is well conditioned.
    x = np.pi / r
    condition = 1 / np.abs(1 + np.cos(x)) + x / np.abs(np.sin(x))
    assert np.all(np.abs(ours - ref) <= 8 * EPS * condition * ref)
    assert dh.coulomb_boundary(1.0) == math.pi / 4
    assert abs(dh.coulomb_boundary(1.0 + 1e-6) - math.pi / 4) < 1e-5  # continuous through r = 1
    with pytest.raises(ValueError, match="^r must be finite and > 0$"):
        dh.coulomb_boundary(np.array([1.0, 0.0]))
