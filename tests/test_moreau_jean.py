"""The ``moreau-jean`` method (issue 25): Algorithm 1 at theta = 1, its order, its stick, its refusals.

Its agreement with Siconos itself is ``tests/test_moreau_jean_siconos.py``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import KERNELS, case_table
from references import PAPER, order
from test_methods import BINGHAM, HERSCHEL_BULKLEY, ONE_MASS, TWO_MASSES, load_system_text

import lumped as L
from lumped.cli import main
from lumped.drivers.methods import METHODS
from lumped.solvers.moreau_jean import moreau_jean

# name of references.CASES -> t_end: the paper's free decay (at rest from 3.15 s), eq. (17b) with the
# paper's law and with Coulomb friction (breakaway, reversals, stops, forcing off).
T_END = {"fig11-x0-0.5": 5.0, "fig6-17b": 3.0, "coulomb-17b": 3.0}
CASES = {name: (*case, T_END[name]) for name, case in case_table(*T_END).items()}


def _oscillator(gamma: float) -> L.Oscillator:
    return L.Oscillator.bingham(PAPER["m"], PAPER["k"], PAPER["tau"], gamma)


@pytest.mark.parametrize("kernel", KERNELS)
@pytest.mark.parametrize("case", list(CASES))
def test_theta_one_is_algorithm1_bit_for_bit(case, kernel):
    # At theta = 1 every (1 - theta) term is (0 * finite) = +-0, added to or subtracted from a
    # finite value, and every other operation is Algorithm 1's in the same order
    # (moreau_jean_step's Notes): no rounding differs, so equality, not a tolerance.
    gamma, kwargs, t_end = CASES[case]
    osc = _oscillator(gamma)
    be = L.backward_euler(osc, t_end, 1e-3, kernel=kernel, **kwargs)
    mj = moreau_jean(osc, t_end, 1e-3, theta=1.0, **kwargs)
    for name in L.COLUMNS:
        assert np.array_equal(getattr(mj, name), getattr(be, name)), name
    assert mj.rest_time == be.rest_time or (math.isnan(be.rest_time) and math.isnan(mj.rest_time))


def test_theta_half_is_second_order_without_a_band():
    # With no band (threshold 0) the law is the linear dashpot and the scheme the midpoint
    # (trapezoidal) rule on a linear ODE: order 2 against the closed form.
    osc = L.Oscillator.bingham(PAPER["m"], PAPER["k"], 0.0, 1.0)
    force = L.SwitchedSine(2.0, 7.0, 0.0, 10.0)
    sol = L.solve_exact(osc, 1.0, x0=0.5, force=force)
    steps = [1e-3, 5e-4, 2.5e-4, 1.25e-4]
    errors = [np.abs(moreau_jean(osc, 1.0, dt, x0=0.5, force=force).x - sol.sample(dt).x).max() for dt in steps]
    assert 1.95 <= order(steps, errors) <= 2.05


@pytest.mark.parametrize("theta", [0.5, 0.7])
def test_in_stick_the_dashpot_force_is_the_reaction_and_settles(theta):
    # In stick v_n = v_{n+1} = 0, so the relay's predictor is theta F_{n+1} + (1-theta) F_n - F_s
    # and the band takes all of it: free vibration (F = 0) gives F_d = -F_s exactly, every step
    # (no alternation about the reaction, unlike the theta method's F_d,n+1 + F_d,n = -2 F_s).
    # The step that ends at rest_time still starts moving (its band force also stops the mass).
    mj = moreau_jean(_oscillator(1.0), 5.0, 1e-3, theta=theta, x0=0.5)
    stick = mj.t > mj.rest_time
    assert stick.sum() > 1000 and np.all(mj.v[stick] == 0.0)
    assert np.array_equal(mj.F_d[stick], -mj.F_s[stick])


def test_the_registry_command_line_and_api_run_the_same_scheme(tmp_path):
    gamma, kwargs, t_end = CASES["fig6-17b"]
    osc = _oscillator(gamma)
    direct = moreau_jean(osc, t_end, 1e-3, theta=0.7, **kwargs)
    via = L.simulate(osc, t_end, 1e-3, method="moreau-jean", theta=0.7, **kwargs)
    assert via.method == "moreau-jean" and all(np.array_equal(getattr(via, c), getattr(direct, c)) for c in L.COLUMNS)
    assert METHODS["moreau-jean"].fixed_step and METHODS["moreau-jean"].bingham_only
    out = tmp_path / "run.csv"
    args = ["simulate", "--x0", "0.5", "--t-end", "1", "--dt", "1e-3", "--method", "moreau-jean", "--theta", "0.7"]
    assert main([*args, "--output", str(out)]) == 0
    rows = np.genfromtxt(out, delimiter=",", names=True)
    assert np.array_equal(rows["x"], moreau_jean(_oscillator(1.0), 1.0, 1e-3, theta=0.7, x0=0.5).x)


def test_a_one_mass_network_runs_as_the_oscillator():
    # The registry sends a network of the one-mass form to the one-mass solver, unchanged.
    net = load_system_text(ONE_MASS.format(dashpot=BINGHAM))
    tr = L.solve(L.Problem(net, 1.0), 1e-3, method="moreau-jean")
    assert np.array_equal(tr.positions[:, 0], moreau_jean(_oscillator(1.0), 1.0, 1e-3, x0=0.5).x)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda o: moreau_jean(o, 1.0, 1e-3, theta=0.0), r"^theta must lie in \(0, 1\], got 0.0$"),
        (lambda o: moreau_jean(o, 1.0, 1e-3, theta=1.5), r"^theta must lie in \(0, 1\], got 1.5$"),
        (lambda o: moreau_jean(o, 1.0, 1e-3, theta=math.nan), "^theta"),
        (lambda o: L.simulate(o, 1.0, 1e-3, method="moreau-jean", theta=-1), "^theta must lie in"),
        (lambda o: L.simulate(o, 1.0, 1e-3, method="moreau-jean", rtol=1e-8), "^rtol: method 'moreau-jean' takes no"),
        (
            lambda o: L.simulate(
                L.Oscillator(1.0, L.LinearSpring(100.0), L.HerschelBulkleyDashpot(1.0, 1.0, 2.0)),
                1.0,
                1e-3,
                x0=0.5,
                method="moreau-jean",
            ),
            "^method: 'moreau-jean' cannot run a HerschelBulkleyDashpot: its relay needs a Bingham or Coulomb law",
        ),
        (
            lambda o: L.solve(L.Problem(load_system_text(TWO_MASSES), 0.1), 1e-3, method="moreau-jean"),
            "^method 'moreau-jean' needs a one-mass system; the network has 2 masses$",
        ),
        (
            lambda o: L.solve(
                L.Problem(load_system_text(ONE_MASS.format(dashpot=HERSCHEL_BULKLEY)), 0.1), 1e-3, method="moreau-jean"
            ),
            "^method: 'moreau-jean' cannot run a HerschelBulkleyDashpot",
        ),
    ],
)
def test_bad_arguments_are_refused_in_one_line_naming_them(call, message):
    with pytest.raises(ValueError, match=message) as err:
        call(_oscillator(1.0))
    assert "\n" not in str(err.value)
