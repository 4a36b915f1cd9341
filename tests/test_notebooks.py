"""The committed notebooks: each jupytext ``.py`` and its ``.ipynb`` twin agree.

nbval (``python -m pytest --nbval ...``) then checks that re-executing the
``.ipynb`` reproduces its stored outputs; these tests make sure the stored
notebook is the one the ``.py`` describes, and that it was executed.
Refresh both with ``python scripts/run_notebook.py --update-committed``.
"""

from pathlib import Path

import jupytext
import pytest

NOTEBOOKS = Path(__file__).resolve().parent.parent / "notebooks"
SOURCES = sorted(NOTEBOOKS.glob("[0-9][0-9]_*.py"))


def _cells(notebook):
    return [(cell.cell_type, cell.source.strip()) for cell in notebook.cells]


def test_there_are_notebooks():
    assert len(SOURCES) >= 3, f"expected the numbered notebooks in {NOTEBOOKS}"


@pytest.mark.parametrize("source", SOURCES, ids=lambda p: p.stem)
def test_py_and_ipynb_have_the_same_cells(source):
    twin = source.with_suffix(".ipynb")
    assert twin.is_file(), f"{source.name} has no committed {twin.name}"
    from_py, from_ipynb = jupytext.read(source), jupytext.read(twin)
    py_cells, nb_cells = _cells(from_py), _cells(from_ipynb)
    assert len(py_cells) == len(nb_cells), f"{source.name}: {len(py_cells)} cells, {twin.name}: {len(nb_cells)}"
    for i, (a, b) in enumerate(zip(py_cells, nb_cells)):
        assert a == b, f"cell {i} differs between {source.name} and {twin.name}"


@pytest.mark.parametrize("source", SOURCES, ids=lambda p: p.stem)
def test_committed_ipynb_was_executed(source):
    notebook = jupytext.read(source.with_suffix(".ipynb"))
    code = [cell for cell in notebook.cells if cell.cell_type == "code"]
    unrun = [i for i, cell in enumerate(code) if cell.get("execution_count") is None]
    assert not unrun, f"{source.stem}.ipynb: code cells {unrun} were not executed"
    errors = [o for cell in code for o in cell.get("outputs", []) if o.output_type == "error"]
    assert not errors, f"{source.stem}.ipynb holds an error output: {errors[0].get('ename')}"


@pytest.mark.parametrize("source", SOURCES, ids=lambda p: p.stem)
def test_pairing_is_declared(source):
    formats = jupytext.read(source).metadata.get("jupytext", {}).get("formats", "")
    assert "ipynb" in formats and "py:percent" in formats, f"{source.name}: formats={formats!r}"


def test_a_changed_cell_is_detected(tmp_path):
    """The comparison above can fail: editing one cell of a copy breaks it."""
    source = SOURCES[-1]
    notebook = jupytext.read(source)
    notebook.cells[-1].source += "\n# edited"
    copy = tmp_path / source.name
    jupytext.write(notebook, copy)
    twin = jupytext.read(source.with_suffix(".ipynb"))
    assert _cells(jupytext.read(copy)) != _cells(twin)
