"""One problem value for every method (issue 20, item 1): :class:`lumped.Problem` and :func:`lumped.solve`.

The paper's oscillator is the one-mass network of ``Problem.oscillator``;
``solve`` hands it to each method by itself (Algorithm 1's kernel for backward
Euler, the oscillator form for the single-mass methods).  The references are
the single-mass runs of the same oscillator (``lumped.simulate``): the path
through the network adds no arithmetic, so every saved value agrees bit for
bit.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import lumped as L

PAPER = L.Oscillator.bingham()
FORCE = L.SwitchedSine(amplitude=10.0, omega=5 * math.pi, until=1.0)  # eq. (17b)
#: Laws of every kind of the contract: Bingham, Coulomb, Herschel-Bulkley, a regularised law.
LAWS = {
    "bingham": L.BinghamDashpot(1.0, 1.0),
    "coulomb": L.coulomb(1.0),
    "herschel-bulkley": L.HerschelBulkleyDashpot(1.0, 1.0, 0.5),
    "papanastasiou": L.PapanastasiouDashpot(1.0, 1.0, 1e-3),
}


def _oscillator(law: str) -> L.Oscillator:
    return L.Oscillator(1.0, L.LinearSpring(100.0), LAWS[law])


def _runnable(method: str, law: str) -> bool:
    return L.METHODS[method].refusal(_oscillator(law)) is None


CASES = [(m, law) for m in L.METHODS for law in LAWS if _runnable(m, law)]


@pytest.mark.parametrize(("method", "law"), CASES)
def test_every_method_runs_the_oscillator_as_a_problem_bit_for_bit(method, law):
    osc = _oscillator(law)
    problem = L.Problem.oscillator(osc, 0.5, x0=0.05, force=FORCE)
    tr = L.solve(problem, 1e-3, method=method, save_every=7)
    ref = L.simulate(osc, 0.5, 1e-3, x0=0.05, force=FORCE, method=method, save_every=7)
    assert np.array_equal(tr.t, ref.t)
    assert np.array_equal(tr.x, ref.x) and np.array_equal(tr.v, ref.v)
    spring, dashpot = tr.network.element_names.index("spring"), tr.network.element_names.index("dashpot")
    assert np.array_equal(tr.forces[:, spring], ref.F_s) and np.array_equal(tr.forces[:, dashpot], ref.F_d)
    assert np.array_equal(tr.F, ref.F) and tr.network.loads[0].force is FORCE and tr.method == method


@pytest.mark.parametrize(
    ("law", "path"),
    [
        ("bingham", "algorithm1"),
        ("coulomb", "algorithm1"),
        ("herschel-bulkley", "resolvent"),
        ("papanastasiou", "resolvent"),
    ],
)
def test_backward_euler_chooses_the_one_mass_path_itself(law, path):
    """The fast path is chosen inside: Algorithm 1's kernel for a law with a Bingham form, else the law's resolvent."""
    tr = L.solve(L.Problem.oscillator(_oscillator(law), 0.2, x0=0.05), 1e-3)
    assert tr.solver == path


def test_the_oscillator_comes_back_with_its_own_law():
    osc = _oscillator("papanastasiou")
    form = L.Problem.oscillator(osc, 1.0, x0=0.1, v0=-2.0).one_mass()
    assert form.oscillator == osc and form.oscillator.dashpot is osc.dashpot


def test_a_network_problem_runs_by_backward_euler_as_simulate_network_runs_it():
    masses = [L.Mass("a", 1.0, 0.3), L.Mass("b", 2.0)]
    elements = [
        L.Spring("k1", ("ground", "a"), 100.0),
        L.Spring("k2", ("a", "b"), 50.0),
        L.Bingham("d", ("ground", "b"), 1.0, 1.0),
    ]
    net = L.Network(masses, elements)
    tr, ref = L.solve(L.Problem(net, 0.5), 1e-3), L.simulate_network(net, 0.5, 1e-3)
    assert np.array_equal(tr.positions, ref.positions) and np.array_equal(tr.forces, ref.forces)


def test_a_single_mass_method_refuses_several_masses_in_one_line():
    net = L.Network([L.Mass("a", 1.0, 0.3), L.Mass("b", 1.0)], [L.Spring("k", ("a", "b"), 1.0)])
    with pytest.raises(ValueError, match="^method 'theta' needs a one-mass system; the network has 2 masses$"):
        L.solve(L.Problem(net, 1.0), 1e-3, method="theta")


def test_exact_refuses_a_law_without_a_bingham_form_as_simulate_does():
    problem = L.Problem.oscillator(_oscillator("herschel-bulkley"), 1.0, x0=0.1)
    with pytest.raises(ValueError, match="^method: 'exact' cannot run a HerschelBulkleyDashpot: "):
        L.solve(problem, 1e-3, method="exact")


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: L.Problem("system.toml", 1.0), "^system must be a Network, got str$"),
        (lambda: L.Problem.oscillator(PAPER, 0.0), "^t_end must be"),
        (lambda: L.Problem.oscillator(PAPER, math.nan), "^t_end must be"),
        (lambda: L.Problem.oscillator("paper", 1.0), "^oscillator must be an Oscillator, got str$"),
        (lambda: L.solve(L.Problem.oscillator(PAPER, 1.0), 1e-3, method="rk4"), "^method must be one of "),
        (
            lambda: L.solve(L.Problem.oscillator(PAPER, 1.0), 1e-3, rtol=1e-6),
            "^rtol: method 'backward-euler' takes no option",
        ),
        (lambda: L.solve(PAPER, 1e-3), "^problem must be a Problem, got Oscillator$"),
    ],
)
def test_bad_problems_are_refused_in_one_line(make, message):
    with pytest.raises(ValueError, match=message) as info:
        make()
    assert "\n" not in str(info.value)
