"""Invalid arguments raise ValueError whose message names the argument."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import lumped as L
from lumped.solvers.textbook import TextbookModel, integrate_adaptive, integrate_fixed

SETTINGS = settings(max_examples=40, deadline=None)

non_positive = st.one_of(
    st.floats(max_value=0.0, allow_nan=False), st.just(-math.inf), st.just(math.nan), st.just(math.inf)
)
negative_or_bad = st.one_of(st.floats(max_value=-1e-300, allow_nan=False), st.just(math.nan), st.just(math.inf))
gamma_bad = st.one_of(st.floats(max_value=0.0, allow_nan=False), st.just(math.nan))
not_finite = st.sampled_from([math.nan, math.inf, -math.inf])


@SETTINGS
@given(non_positive)
def test_mass_must_be_positive_and_finite(value):
    with pytest.raises(ValueError, match="mass"):
        L.Oscillator.bingham(mass=value)


@SETTINGS
@given(non_positive)
def test_stiffness_must_be_positive_and_finite(value):
    with pytest.raises(ValueError, match="stiffness"):
        L.Oscillator.bingham(stiffness=value)


@SETTINGS
@given(negative_or_bad)
def test_threshold_must_be_non_negative_and_finite(value):
    with pytest.raises(ValueError, match="threshold"):
        L.Oscillator.bingham(threshold=value)


@SETTINGS
@given(gamma_bad)
def test_gamma_must_be_positive(value):
    with pytest.raises(ValueError, match="gamma"):
        L.BinghamDashpot(threshold=1.0, gamma=value)


@SETTINGS
@given(non_positive, st.sampled_from(["t_end", "dt"]))
def test_time_arguments_must_be_positive_and_finite(value, name):
    args = {"t_end": 1.0, "dt": 1e-3, name: value}
    with pytest.raises(ValueError, match=name):
        L.backward_euler(L.Oscillator.bingham(), args["t_end"], args["dt"])
    if name == "t_end":
        with pytest.raises(ValueError, match=name):
            L.solve_exact(L.Oscillator.bingham(), value)


@SETTINGS
@given(not_finite, st.sampled_from(["x0", "v0"]))
def test_initial_state_must_be_finite(value, name):
    with pytest.raises(ValueError, match=name):
        L.backward_euler(L.Oscillator.bingham(), 1.0, 1e-3, **{name: value})
    with pytest.raises(ValueError, match=name):
        L.solve_exact(L.Oscillator.bingham(), 1.0, **{name: value})


@SETTINGS
@given(not_finite, st.sampled_from(["amplitude", "omega", "phase"]))
def test_forcing_parameters_must_be_finite(value, name):
    with pytest.raises(ValueError, match="force_" + name):
        L.SwitchedSine(**{name: value})


@SETTINGS
@given(st.one_of(st.floats(max_value=-1e-300, allow_nan=False), st.just(math.nan)))
def test_forcing_end_must_be_a_time(value):
    with pytest.raises(ValueError, match="force_until"):
        L.SwitchedSine(amplitude=1.0, omega=1.0, until=value)


@pytest.mark.parametrize("value", [0, -1, 1.5, "two", None, True])
def test_save_every_must_be_a_positive_integer(value):
    with pytest.raises(ValueError, match="save_every"):
        L.backward_euler(L.Oscillator.bingham(), 1.0, 1e-3, save_every=value)


@pytest.mark.parametrize("value", ["abc", None, [1.0]])
def test_non_numbers_are_refused_by_name(value):
    with pytest.raises(ValueError, match="mass must be a real number"):
        L.Oscillator.bingham(mass=value)


def test_gamma_inf_and_threshold_zero_are_valid():
    osc = L.Oscillator.bingham(threshold=0.0, gamma=math.inf)
    assert osc.static_band == 0.0 and osc.dashpot.viscosity == 0.0
    assert L.SwitchedSine(until=math.inf).until == math.inf


def test_huge_run_refused_up_front():
    # 1e18 steps: refused by the step count before any allocation or loop.
    with pytest.raises(ValueError, match="t_end/dt"):
        L.backward_euler(L.Oscillator.bingham(), 1e9, 1e-9)
    with pytest.raises(ValueError, match="save_every"):  # 1e9 rows x 6 doubles > 4 GiB
        L.backward_euler(L.Oscillator.bingham(), 1e5, 1e-4)


def test_unknown_kernel_and_method():
    osc = L.Oscillator.bingham()
    with pytest.raises(ValueError, match="kernel"):
        L.backward_euler(osc, 1.0, 1e-3, kernel="fortran")
    with pytest.raises(ValueError, match="method"):
        L.simulate(osc, 1.0, 1e-3, method="rk4")


def test_force_callable_must_be_finite():
    with pytest.raises(ValueError, match="force"):
        L.backward_euler(L.Oscillator.bingham(), 0.01, 1e-3, force=lambda t: np.full_like(t, math.inf))


def test_resolvent_arguments_checked():
    law = L.BinghamDashpot()
    with pytest.raises(ValueError, match="predictor"):
        law.resolvent(math.nan, 1.0)
    with pytest.raises(ValueError, match="eta"):
        law.resolvent(1.0, 0.0)


def test_textbook_arguments_checked():
    osc = L.Oscillator.bingham()
    with pytest.raises(ValueError, match="eps"):
        TextbookModel(osc, eps=0.0)
    with pytest.raises(ValueError, match="scheme"):
        integrate_fixed(TextbookModel(osc), 1.0, 1e-3, scheme="heun")
    with pytest.raises(ValueError, match="method"):
        integrate_adaptive(TextbookModel(osc), 1.0, method="Euler")
    with pytest.raises(ValueError, match="max_nfev"):
        integrate_adaptive(TextbookModel(osc), 1.0, max_nfev=0)
    with pytest.raises(ValueError, match="dashpot"):
        TextbookModel(L.Oscillator(1.0, L.LinearSpring(1.0), L.MonotoneDashpot(lambda f: f)))


def test_the_grid_is_checked_in_one_place_with_one_wording():
    """validate.grid checks t_end, dt, save_every and the step count in that order; every entry
    that takes a grid refuses a bad one with its words (tests/test_one_home.py: no other copy)."""
    from lumped.numerics import validate
    from lumped.kernels.batched import batch_backward_euler

    assert validate.grid(1.0, 0.25, 3) == (1.0, 0.25, 3, 4)
    net = L.Network([L.Mass("m", 1.0, 0.5, 0.0)], [L.Spring("s", ("ground", "m"), 1.0)], [])
    runs = {
        "backward_euler": lambda t, dt, s: L.backward_euler(L.Oscillator.bingham(), t, dt, save_every=s),
        "simulate_network": lambda t, dt, s: L.simulate_network(net, t, dt, save_every=s),
        "theta": lambda t, dt, s: L.simulate(L.Oscillator.bingham(), t, dt, method="theta", save_every=s),
        "sample": lambda t, dt, s: L.solve_exact(L.Oscillator.bingham(), t).sample(dt, s),
    }
    for bad, words in [
        ((-1.0, 0.1, 1), "t_end must be > 0"),
        ((1.0, 0.0, 1), "dt must be > 0"),
        ((1.0, 0.1, 0), "save_every must be an integer >= 1"),
        ((1e9, 1e-9, 1), "t_end/dt must be at most"),
    ]:
        with pytest.raises(ValueError, match="^" + words) as expected:
            validate.grid(*bad)
        for name, run in runs.items():
            with pytest.raises(ValueError) as err:
                run(*bad)
            assert str(err.value) == str(expected.value), name
    with pytest.raises(ValueError, match="^dt must be > 0"):
        batch_backward_euler({}, 1.0, -1.0)
