"""The command line run in this process, for the tests of its outputs and refusals.

``run_lumped(*args, cwd=...)`` calls :func:`lumped.cli.main` as
``python -m lumped`` would, with stdout and stderr captured, and returns a
:class:`subprocess.CompletedProcess` (``returncode``, ``stdout``, ``stderr``).
It saves the start-up of a Python process per call (about 0.2 s); the
commands' own tests of ``python -m lumped`` as a process (the entry point,
signals, the README's commands) keep running it as one.
"""

from __future__ import annotations

import contextlib
import io
import os
import subprocess
from pathlib import Path

from lumped.cli import main

__all__ = ["run_lumped"]


def run_lumped(*args: str, cwd: Path | str | None = None) -> subprocess.CompletedProcess:
    """``python -m lumped ARGS`` in this process, from ``cwd`` (the current folder if none)."""
    out, err, here = io.StringIO(), io.StringIO(), os.getcwd()
    try:
        if cwd is not None:
            os.chdir(cwd)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main([str(a) for a in args])
    finally:
        os.chdir(here)
    return subprocess.CompletedProcess(["lumped", *args], code, out.getvalue(), err.getvalue())
