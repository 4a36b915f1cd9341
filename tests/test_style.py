"""The code is formatted by ruff (configured in pyproject.toml), not by hand-kept markers."""

from __future__ import annotations

import shutil
import subprocess

import pytest
from conftest import ROOT

FORMATTED = ("src", "scripts", "tests", "benchmarks")


def test_code_is_ruff_formatted():
    """``ruff format --check`` lists every file whose layout ruff would change."""
    ruff = shutil.which("ruff")
    if ruff is None:
        pytest.skip("ruff is not installed (environment-pip.txt pins it)")
    run = subprocess.run([ruff, "format", "--check", *FORMATTED], cwd=ROOT, capture_output=True, text=True)
    assert run.returncode == 0, run.stdout + run.stderr


def test_no_format_markers_are_left():
    """One formatter configuration replaces the per-line skip markers."""
    marker = "fmt: " + "skip"
    found = [str(p.relative_to(ROOT)) for d in FORMATTED for p in (ROOT / d).rglob("*.py") if marker in p.read_text()]
    assert found == []
