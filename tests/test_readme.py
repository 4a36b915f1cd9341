"""The README's Python example runs as written and prints what its comments say."""

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"


def python_blocks() -> list[str]:
    return re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)


def test_readme_has_an_example() -> None:
    assert python_blocks(), "README.md lost its Python example"


@pytest.mark.parametrize("block", python_blocks())
def test_readme_example_runs_and_matches_its_comments(block: str, capsys) -> None:
    exec(compile(block, str(README), "exec"), {})
    printed = capsys.readouterr().out
    # every number quoted in a "# ..." comment after a print( must appear in the output
    for line in block.splitlines():
        if line.lstrip().startswith("print(") and "#" in line:
            for number in re.findall(r"\d+\.\d+", line.split("#", 1)[1]):
                assert number in printed, f"README claims {number}, the code printed {printed}"
