"""The load contract is the only way to ask a load anything (issue 33, part A, point 3).

Read from the source with :mod:`ast`, as ``test_law_contract.py`` reads the
laws: no module of the package but :mod:`lumped.model.forcing` calls
``isinstance`` or ``issubclass`` on a load class, or keys a table by one.
Then the contract itself: a load kind written outside the package, through
:class:`~lumped.model.forcing.Forcing`'s points alone, runs in the methods that
need a closed form, with the numbers of the load it equals, bit for bit.
"""

from __future__ import annotations

import ast
import math
from dataclasses import dataclass

import numpy as np
import pytest
from test_import_graph import MODULES
from test_law_contract import _class_tests, _tree

import lumped as L
from lumped.model.forcing import Forcing, SineForm, as_sine, closed_form, jumps, kind_of, parameters
from lumped.numerics.sine import sin_array
from lumped.solvers.exact_network import solve_exact_network
from lumped.solvers.network_phase import load_matrix, parts

FORCING = "lumped.model.forcing"

#: Every class the load module defines.
LOAD_CLASSES = {node.name for node in ast.walk(_tree(FORCING)) if isinstance(node, ast.ClassDef)}


def _dict_keys(module: str) -> list[tuple[int, str]]:
    """``(line, class name)`` of each load class used as a key of a dict literal in ``module`` (a table by type)."""
    return [
        (node.lineno, key.id)
        for node in ast.walk(_tree(module))
        if isinstance(node, ast.Dict)
        for key in node.keys
        if isinstance(key, ast.Name) and key.id in LOAD_CLASSES
    ]


def test_the_reader_sees_the_load_classes_and_their_tests():
    """A test that cannot fail is none: the load classes are found, and so are the module's own class tests."""
    assert {"Forcing", "SwitchedSine", "Constant", "Table", "LoadSum", "SineForm"} <= LOAD_CLASSES
    assert "Forcing" in {name for _, name in _class_tests(FORCING)}


def test_no_module_asks_a_load_for_its_class():
    asked = sorted(
        f"{module}:{line} {name}"
        for module in MODULES
        if module != FORCING
        for line, name in _class_tests(module) + _dict_keys(module)
        if name in LOAD_CLASSES
    )
    assert asked == []


@dataclass(frozen=True)
class Cosine(Forcing):
    """``amplitude cos(omega t)``: a load kind the package does not know, given through the contract alone."""

    amplitude: float
    omega: float

    def __call__(self, t):
        out = self.amplitude * sin_array(self.omega * np.asarray(t, dtype=float) + math.pi / 2)
        return float(out) if np.ndim(out) == 0 else out

    def scaled(self, factor: float) -> Cosine:
        return Cosine(factor * self.amplitude, self.omega)

    def closed_form(self) -> SineForm:
        return SineForm(self.amplitude, self.omega, math.pi / 2, 0.0, math.inf)


def test_a_new_load_kind_runs_the_exact_one_mass_solver_as_the_sine_it_equals():
    # The solver asks the load for its sine (point 4, built from point 3): the same floats go in, so the
    # same floats come out, whatever the solver does with them.
    osc = L.Oscillator()
    new, sine = Cosine(2.0, 3.0), L.SwitchedSine(2.0, 3.0, math.pi / 2)
    assert as_sine(new) == sine
    a, b = L.solve_exact(osc, 2.0, force=new), L.solve_exact(osc, 2.0, force=sine)
    assert a.events == b.events  # rest_position is nan for both: a forced motion that never rests
    assert np.array_equal(a.sample(1e-2).states, b.sample(1e-2).states)


def test_a_new_load_kind_runs_the_exact_network_solver_as_the_sine_it_equals():
    def net(force):
        masses = [L.Mass("a", 1.0), L.Mass("b", 2.0)]
        elements = [L.Spring("k", ("ground", "a"), 50.0), L.Bingham("d", ("a", "b"), 1.0, 0.5)]
        return L.Network(masses, elements, [L.Load("b", force)])

    a = solve_exact_network(net(Cosine(5.0, 4.0)), 2.0, 1e-2)
    b = solve_exact_network(net(L.SwitchedSine(5.0, 4.0, math.pi / 2)), 2.0, 1e-2)
    assert np.array_equal(a.states, b.states) and np.array_equal(a.forces, b.forces)


def test_a_load_without_a_closed_form_is_refused_by_the_exact_solvers_in_its_own_words():
    table = L.Table([0.0, 1.0], [0.0, 1.0])
    with pytest.raises(ValueError, match="^force: the exact solver needs a SwitchedSine or None$"):
        L.solve_exact(L.Oscillator(), 1.0, force=table)
    assert closed_form(table) is None and closed_form(lambda t: t) is None
    assert (kind_of(table), kind_of(lambda t: t)) == ("a table", "a callable of time")


def test_the_defaults_say_nothing_more():
    """Points 5 to 8 default to a continuous load with no parameters, evaluable over any span."""
    new = Cosine(1.0, 1.0)
    new.check_span(1e300)
    assert (jumps(new), parameters(new), new.description) == ((), (), "a load")
    assert parameters(L.SwitchedSine()) == ("amplitude", "omega", "phase", "until")
    assert parameters(L.Constant(1.0)) == ("value", "until") and parameters(L.Table([0, 1], [1, 1])) == ()


@pytest.mark.parametrize("start", [0.0, 0.5])
def test_a_constant_s_closed_form_gives_its_values_bit_for_bit(start):
    # sin(pi/2) is 1.0 exactly, in the package's sine and in math.sin (the network solvers' load matrix),
    # so value * sin(0 t + pi/2) is value itself: no rounding enters, hence ==.
    constant = L.Constant(-3.25, start=start, until=2.0)
    form = closed_form(constant)
    t = np.linspace(0.0, 3.0, 3001)
    on = (t >= form.start) & (t <= form.until)
    assert np.array_equal(np.where(on, form.amplitude * sin_array(form.omega * t + form.phase), 0.0), constant(t))
    net = L.Network([L.Mass("m", 1.0)], [L.Spring("k", ("ground", "m"), 1.0)], [L.Load("m", constant)])
    assert load_matrix(parts(net), 1.0, 1, 0)[0, 0] == -3.25


def test_a_constant_from_zero_runs_the_one_mass_methods_as_its_sine_bit_for_bit():
    """Asked through the contract, a constant on from t = 0 is a sine (point 4) to every one-mass solver,
    called directly as through ``simulate``; it was refused by the exact solver when called directly."""
    osc, sine = L.Oscillator(), L.SwitchedSine(1.5, 0.0, math.pi / 2, 1.0)
    constant = L.Constant(1.5, until=1.0)
    a, b = L.solve_exact(osc, 2.0, force=constant), L.solve_exact(osc, 2.0, force=sine)
    assert np.array_equal(a.sample(1e-3).states, b.sample(1e-3).states)
    a, b = L.backward_euler(osc, 2.0, 1e-3, force=constant), L.backward_euler(osc, 2.0, 1e-3, force=sine)
    assert np.array_equal(a.states, b.states) and np.array_equal(a.F, b.F)


def test_a_sum_of_loads_checks_the_span_of_each_before_any_step():
    """A sine beyond its argument's range inside a sum is refused up front in the sine's own words
    (it used to run until the sine gave NaN at t = 0.201 s)."""
    force = L.LoadSum((L.SwitchedSine(1.0, 1e9), L.Constant(1.0)))
    with pytest.raises(ValueError, match=r"^force_omega: .* exceeds 2e\+08 rad, the range of the forcing's sine"):
        L.backward_euler(L.Oscillator(), 1.0, 1e-3, force=force)
    assert jumps(L.LoadSum((L.SwitchedSine(until=2.0), L.Constant(1.0, 0.5, 3.0)))) == (0.5, 2.0, 3.0)
