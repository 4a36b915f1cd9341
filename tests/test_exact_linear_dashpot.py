"""``exact`` on a mass, a spring and a linear dashpot: the damped oscillator's closed form (issue 31).

A linear dashpot is the Herschel-Bulkley law with exponent 1 and no threshold,
which is Bingham's graph with ``tau = 0`` and ``c = K`` (``bingham_form()``);
the exact method and its sensitivities run it as they run a Bingham dashpot.
The reference is the damped oscillator's closed form, written here with
complex square roots so that one expression covers under- and overdamping,
and differentiated by the complex step (exact to rounding: no difference of
near-equal numbers is formed).
"""

from __future__ import annotations

import csv

import numpy as np
import pytest
from cli_run import run_lumped
from conftest import EPS

import lumped as L

SYSTEM = """[[mass]]
name = "m1"
mass = {m}
x0 = {x0}
v0 = {v0}

[[element]]
name = "spring"
kind = "spring"
between = ["ground", "m1"]
stiffness = {k}

[[element]]
name = "dashpot"
kind = "dashpot"
between = ["ground", "m1"]
damping = {c}
"""


def closed_form(t: np.ndarray, m: complex, k: complex, c: complex, x0: complex, v0: complex) -> np.ndarray:
    """``x(t)`` of ``m x'' + c x' + k x = 0``: ``e^(-h t) (x0 cos(w t) + (v0 + h x0)/w sin(w t))``, ``h = c/2m``,
    ``w = sqrt(k/m - h^2)`` (imaginary when overdamped: cos and sin/w become cosh and sinh/|w|)."""
    h = c / (2 * m)
    w = np.sqrt(k / m - h * h + 0j)
    t = np.asarray(t, dtype=complex)
    return np.exp(-h * t) * (x0 * np.cos(w * t) + (v0 + h * x0) / w * np.sin(w * t))


def exact_error(events: int, x: np.ndarray, v: np.ndarray, t_end: float) -> float:
    """The exact solver's error, as in ``test_network_sensitivities``: each phase rounds ``x`` by about
    ``eps |x|`` and each event time by an ulp of ``t``, which moves the later motion by ``|v| eps t``; the
    damped motion does not amplify either, so they add over the ``events + 1`` phases."""
    return (events + 1) * EPS * (np.abs(x).max() + t_end * np.abs(v).max())


#: (m, k, c, x0, v0): underdamped (15 reversals in 5 s), with a v0, and overdamped (c > 2 sqrt(k m)).
CASES = {
    "underdamped": (1.0, 100.0, 2.0, 0.5, 0.0),
    "underdamped-v0": (2.0, 50.0, 1.5, -0.2, 3.0),
    "overdamped": (1.0, 100.0, 50.0, 0.5, 0.0),
    "overdamped-v0": (1.0, 100.0, 50.0, 0.5, -30.0),
}


@pytest.mark.parametrize(("m", "k", "c", "x0", "v0"), CASES.values(), ids=list(CASES))
def test_exact_runs_a_linear_dashpot_as_the_closed_form(m, k, c, x0, v0):
    osc = L.Oscillator(m, L.LinearSpring(k), L.LinearDashpot("d", ("ground", "m"), c).one_mass_law())
    t = np.linspace(0.0, 5.0, 2001)
    sol = L.solve_exact(osc, 5.0, x0=x0, v0=v0)
    got = sol.evaluate(t)
    ref = closed_form(t, m, k, c, x0, v0)
    v_ref = np.gradient(ref.real, t)  # only the scale of v enters the bound
    assert np.isnan(sol.rest_time)  # no threshold: it never rests
    assert all(e.kind == "reversal" for e in sol.events)  # v = 0 with a net force: turns, never sticks
    bound = exact_error(len(sol.events), ref.real, v_ref, 5.0)
    assert np.abs(got["x"] - ref.real).max() <= bound


def _rows(path) -> dict[str, np.ndarray]:
    with open(path) as fh:
        rows = list(csv.DictReader(fh))
    return {key: np.array([float(r[key]) for r in rows]) for key in rows[0]}


def test_simulate_exact_and_its_sensitivities_run_a_linear_dashpot(tmp_path):
    # Was: "--method: 'exact' cannot run a HerschelBulkleyDashpot", with or without --sensitivities.
    m, k, c, x0, v0 = CASES["underdamped"]
    (tmp_path / "lin.toml").write_text(SYSTEM.format(m=m, k=k, c=c, x0=x0, v0=v0))
    names = "spring.stiffness,dashpot.damping,m1.mass,m1.x0,m1.v0"
    args = ["simulate", "--system", "lin.toml", "--method", "exact", "--t-end", "5", "--dt", "0.01"]
    run = run_lumped(*args, "--sensitivities", names, "--output", "out.csv", cwd=tmp_path)
    assert run.returncode == 0, run.stderr
    cols = _rows(tmp_path / "out.csv")
    t = cols["t"]
    x = closed_form(t, m, k, c, x0, v0).real
    events = int(np.sum(np.diff(np.sign(np.diff(x))) != 0))  # the reversals: sign changes of v
    assert np.abs(cols["x_m1"] - x).max() <= exact_error(events, x, cols["v_m1"], 5.0)
    # Each derivative by the complex step, Im x(p + i h)/h with h = 1e-30: exact to the rounding of x.
    # The solver's derivative columns carry the exact solver's error of their own motion (the
    # variational equations of the same phases), bounded as x's is, from the columns' own scales.
    base = {"k": k, "c": c, "m": m, "x0": x0, "v0": v0}
    for name, p in zip(names.split(","), ("k", "c", "m", "x0", "v0")):
        args = dict(base, **{p: base[p] + 1e-30j})
        ref = closed_form(t, args["m"], args["k"], args["c"], args["x0"], args["v0"]).imag / 1e-30
        got = cols[f"dx_m1/d{name}"]
        assert np.abs(got - ref).max() <= exact_error(events, ref, np.gradient(ref, t), 5.0), name
