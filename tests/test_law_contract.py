"""The law and element contracts are the only way to ask a law or an element anything (issue 20, item 4).

Read from the source with :mod:`ast`, as ``test_import_graph.py`` reads the
imports: no module of the package calls ``isinstance`` or ``issubclass`` on a
class of :mod:`lumped.laws` that another module defines.  The one test of
"is this a law?" is the contract's own ``check``, whose messages are kept
word for word.
"""

from __future__ import annotations

import ast

import pytest
from test_import_graph import GRAPH, MODULES

import lumped as L
from lumped.laws import Dashpot, Element, LinearSpring, Monotone

LAW_MODULES = [m for m in MODULES if m.startswith("lumped.laws.")]


def _tree(module: str) -> ast.AST:
    return ast.parse(MODULES[module].read_text(encoding="utf-8"))


#: Every class a module of lumped.laws defines, with that module.
HOME = {node.name: m for m in LAW_MODULES for node in ast.walk(_tree(m)) if isinstance(node, ast.ClassDef)}


def _class_tests(module: str) -> list[tuple[int, str]]:
    """``(line, class name)`` of each class named in an ``isinstance``/``issubclass`` call of ``module``."""
    found = []
    for node in ast.walk(_tree(module)):
        if isinstance(node, ast.Call) and getattr(node.func, "id", None) in ("isinstance", "issubclass"):
            classes = node.args[1].elts if isinstance(node.args[1], ast.Tuple) else [node.args[1]]
            for c in classes:
                name = c.id if isinstance(c, ast.Name) else getattr(c, "attr", None)
                found.append((node.lineno, name))
    return found


def test_the_reader_sees_the_classes_and_the_calls():
    """A test that cannot fail is none: the laws' classes are found, and so are the contract's own checks."""
    assert HOME["Dashpot"] == "lumped.laws.contract" and HOME["Element"] == "lumped.laws.element"
    assert (HOME["StepGraph"], HOME["LinearSpring"]) == ("lumped.laws.step_graph", "lumped.laws.contract")
    assert "Dashpot" in {name for _, name in _class_tests("lumped.laws.contract")}


def test_no_module_asks_a_law_or_an_element_for_its_class():
    asked = sorted(
        f"{module}:{line} isinstance(..., {name})"
        for module in MODULES
        for line, name in _class_tests(module)
        if name in HOME and HOME[name] != module
    )
    assert asked == []


def test_the_regularised_law_touches_nothing_but_the_contract():
    """Remark 2.3's law was added through the contract alone: it imports no other law and no solver."""
    assert GRAPH["lumped.laws.regularised"] == {"lumped.laws.contract", "lumped.numerics.validate"}


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: L.Oscillator(spring=100.0), "spring must be a LinearSpring"),
        (lambda: L.Oscillator(dashpot=LinearSpring(1.0)), "dashpot must be a Dashpot"),
        (lambda: Monotone("d", ("ground", "m"), law=1.0), "law must be a lumped.laws.Dashpot, got float"),
        (
            lambda: L.Network([L.Mass("m", 1.0)], [LinearSpring(1.0)]),
            "elements must hold Element objects, got LinearSpring",
        ),
        (lambda: L.Network(["m"], []), "masses must hold Mass objects, got str"),
    ],
)
def test_the_checks_keep_their_messages(make, message):
    with pytest.raises(ValueError, match=f"^{message}$"):
        make()


def test_a_check_returns_what_it_accepts():
    law, spring = L.BinghamDashpot(), LinearSpring(3.0)
    assert Dashpot.check(law, "dashpot") is law and LinearSpring.check(spring, "spring") is spring
    element = L.Spring("k", ("ground", "m"), 1.0)
    assert Element.check(element, "element") is element
