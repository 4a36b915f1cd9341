"""One home per concept (issue 33, A.4): read from the source, as tests/test_import_graph.py reads the imports.

Each test names a concept that was once written in several modules, and
asserts that exactly one module now holds it: a second copy, which would have
to change together with the first, fails here.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent / "src" / "lumped"
SOURCES = {str(p.relative_to(PACKAGE)): p.read_text(encoding="utf-8") for p in sorted(PACKAGE.rglob("*.py"))}


def _holding(pattern: str) -> list[str]:
    return [name for name, text in SOURCES.items() if re.search(pattern, text, re.MULTILINE)]


@pytest.mark.parametrize(
    ("concept", "pattern", "home"),
    [
        # a union-find's root walk: ``while parent[i] != i`` (any names)
        ("union-find", r"while \w+\[\w+\] != \w+:", ["numerics/union_find.py"]),
        # the bound on a run's steps
        ("MAX_STEPS", r"^MAX_STEPS\b\s*=", ["numerics/validate.py"]),
        # the grid's check: dt > 0 is checked by validate.grid alone
        ("the grid's check", r"positive\(\s*\"dt\"", ["numerics/validate.py"]),
        # steady sliding's position on a belt, x* = (... + sgn(V) g(|V|)) / K (issue 34)
        ("steady sliding", r"copysign\([\w.]*\.g\(abs\(", ["drivers/cycles/equilibria.py"]),
        # the scope of cycles: a refusal that says what cycles runs (issue 34)
        ("the cycles scope", r"cycles runs \{", ["drivers/cycles/equilibria.py"]),
    ],
)
def test_one_module_holds(concept: str, pattern: str, home: list[str]) -> None:
    assert _holding(pattern) == home, concept


def test_the_network_time_loop_lives_in_solvers() -> None:
    """The driver hands the run to :func:`lumped.solvers.backward_euler_network.march`; it steps nothing itself."""
    driver = SOURCES["drivers/network.py"]
    assert "solve_step" not in driver and "march_block" not in driver
    assert _holding(r"\bsolve_step\(first, second, start\.inertia") == ["solvers/backward_euler_network.py"]
