"""The README and the website's guide pages: their examples run as written and print what they say.

* Every ``python`` block of README.md and of the guide pages (``book/guide/``)
  runs, and each number quoted in a ``# ...`` comment after a ``print(`` is in
  what it printed.
* Every ``bash`` block of the README's quick start runs, command by command, in
  a scratch folder holding a copy of ``examples/``; a comment line right under
  a command shows what it prints, and each number written with a decimal point
  in such a line must be in the command's output.  The ``python`` blocks
  between it and the next ``bash`` block then run in that folder (they read
  the files its commands wrote).
* The example system file is the paper's Figure 3: it gives Algorithm 1's
  numbers bit for bit.
* The README stays a front door: at most 200 lines, its two set-up commands,
  every guide page named with its built and source paths, and every relative
  link pointing at a file of the repository.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import NamedTuple

import matplotlib.pyplot as plt
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
GUIDE = sorted((ROOT / "book" / "guide").glob("*.md"))
#: A number with a decimal point, as the README's comments quote them.
NUMBER = re.compile(r"\d+\.\d+")
#: The README's two set-up commands, which .ci/run and a fresh machine rely on, word for word.
SETUP_COMMANDS = (
    "python3 -m venv .venv && . .venv/bin/activate && pip install -r environment-pip.txt && snakemake --cores all",
    "python3 -m venv .venv && . .venv/bin/activate && pip install -r environment-pip.txt && python -m pytest",
)


def python_blocks(path: Path) -> list[str]:
    return re.findall(r"```python\n(.*?)```", path.read_text(encoding="utf-8"), flags=re.DOTALL)


def quick_start() -> str:
    """The README's section ``## Quick start``, up to the next ``##`` heading."""
    text = README.read_text(encoding="utf-8")
    return re.search(r"^## Quick start\n(.*?)(?=^## )", text, flags=re.DOTALL | re.MULTILINE).group(1)


class Command(NamedTuple):
    """A shell command of the quick start and the lines it is said to print."""

    line: str
    printed: list[str]


def commands(block: str) -> list[Command]:
    """The commands of a ``bash`` block, each with the comment lines right under it."""
    found: list[Command] = []
    under_a_command = False  # no blank line since the last command
    for line in block.splitlines():
        if not line.strip():
            under_a_command = False
        elif not line.startswith("#"):
            found.append(Command(line, []))
            under_a_command = True
        elif under_a_command:
            found[-1].printed.append(line.removeprefix("#").strip())
    return found


class Step(NamedTuple):
    """A ``bash`` block of the quick start and the ``python`` blocks that follow it."""

    commands: list[Command]
    python: list[str]


def steps(text: str) -> list[Step]:
    """The quick start's ``bash`` blocks, each with the ``python`` blocks before the next one."""
    found: list[Step] = []
    for language, block in re.findall(r"```(bash|python)\n(.*?)```", text, flags=re.DOTALL):
        if language == "bash":
            found.append(Step(commands(block), []))
        else:
            assert found, "the quick start's first block must be a bash block"
            found[-1].python.append(block)
    return found


def check_printed(source: str, block: str, printed: str) -> None:
    """Every number quoted in a ``# ...`` comment after a ``print(`` of ``block`` is in ``printed``."""
    for line in block.splitlines():
        if line.lstrip().startswith("print(") and "#" in line:
            for number in NUMBER.findall(line.split("#", 1)[1]):
                assert number in printed, f"{source} claims {number}, the code printed {printed}"


#: The README's Python outside the quick start (none today) and the guide pages', run where pytest runs.
EXAMPLES = [(str(README.relative_to(ROOT)), b) for b in python_blocks(README) if b not in quick_start()] + [
    (str(p.relative_to(ROOT)), b) for p in GUIDE for b in python_blocks(p)
]
STEPS = steps(quick_start())
QUICK_START = [command for step in STEPS for command in step.commands]
#: Quick-start commands that take more than a few seconds run with the slow tests (``-m slow``); the response
#: curve's command is also its example's header command, run by tests/test_examples.py.
SLOW = (" response --system examples/",)


def test_readme_has_an_example() -> None:
    assert python_blocks(README), "README.md lost its Python example"


@pytest.mark.parametrize("source, block", EXAMPLES, ids=[f"{s}-{i}" for i, (s, _) in enumerate(EXAMPLES)])
def test_readme_example_runs_and_matches_its_comments(source: str, block: str, capsys) -> None:
    exec(compile(block, source, "exec"), {})
    check_printed(source, block, capsys.readouterr().out)


def test_the_quick_start_has_its_four_steps() -> None:
    """One mass, one system file, one sweep, one response curve: each a command of the quick start, each shown
    printing."""
    lines = [c.line for c in QUICK_START]
    assert any(" simulate --x0" in c for c in lines)
    assert any(" simulate --system examples/" in c for c in lines)
    assert any(" sweep --vary" in c for c in lines)
    assert any(" response --system examples/" in c for c in lines)
    assert all(c.printed for c in QUICK_START), [c.line for c in QUICK_START if not c.printed]


@pytest.mark.parametrize(
    "step",
    [pytest.param(s, marks=pytest.mark.slow) if any(w in s.commands[0].line for w in SLOW) else s for s in STEPS],
    ids=[step.commands[0].line.split(" --output")[0] for step in STEPS],
)
def test_a_quick_start_block_runs_and_prints_what_the_readme_shows(
    step: Step, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    """The block's commands, in order, in a folder holding a copy of ``examples/``, with this
    interpreter's ``python`` first on the PATH: each succeeds and prints every number shown under it.
    Then the Python that follows the block runs in that folder and prints what its comments say."""
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    for command in step.commands:
        done = subprocess.run(
            ["bash", "-c", command.line],
            check=False,
            cwd=tmp_path,
            env=env,
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert done.returncode == 0, f"`{command.line}`: {done.stderr}"
        output = done.stdout + done.stderr
        for line in command.printed:
            for number in NUMBER.findall(line):
                assert number in output, f"README shows {number} under `{command.line}`; it printed {output!r}"
    monkeypatch.chdir(tmp_path)
    for block in step.python:
        try:
            exec(compile(block, "README.md", "exec"), {})
        finally:
            plt.close("all")
        check_printed("README.md", block, capsys.readouterr().out)


def test_the_example_system_file_is_the_papers_figure_3() -> None:
    """examples/figure3.toml runs through Algorithm 1 and gives its arrays bit for bit (free vibration, x0 = 0.5)."""
    import lumped as L
    from lumped.model.files import load_system

    network = load_system(ROOT / "examples" / "figure3.toml")
    run = L.solve(L.Problem(network, 4.0), 1e-4)
    reference = L.backward_euler(L.Oscillator.bingham(mass=1, stiffness=100, threshold=1, gamma=1), 4.0, 1e-4, x0=0.5)
    assert np.array_equal(run.positions[:, 0], reference.x) and np.array_equal(run.velocities[:, 0], reference.v)
    assert np.array_equal(run.forces[:, 1], reference.F_d) and np.array_equal(run.F_d, reference.F_d)


def test_the_readme_is_at_most_200_lines_and_keeps_its_two_commands() -> None:
    text = README.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= 200
    for command in SETUP_COMMANDS:
        assert f"\n{command}\n" in text, command


@pytest.mark.parametrize("page", GUIDE, ids=lambda p: p.stem)
def test_the_readme_names_every_guide_page(page: Path) -> None:
    """Each page of book/guide/ is in the README with its built path and its source."""
    text = README.read_text(encoding="utf-8")
    assert f"`results/site/guide/{page.stem}.html`" in text
    assert f"[`book/guide/{page.name}`](book/guide/{page.name})" in text


def test_every_relative_link_of_the_readme_exists() -> None:
    links = re.findall(r"\]\(([^)\s]+)\)", README.read_text(encoding="utf-8"))
    relative = [link.split("#")[0] for link in links if ":" not in link and not link.startswith("#")]
    assert relative and [link for link in relative if not (ROOT / link).exists()] == []
