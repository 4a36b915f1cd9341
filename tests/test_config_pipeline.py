"""The pipeline's configuration, end to end: checked before any job, canonical, buildable.

The check itself (every key, every kind of bad value) is tested in-process in
tests/test_config.py. Here a few cases show that the pipeline runs it: a bad
value stops the workflow before the DAG is built, with exit status 2, the one
line ``config: <key> ...``, no traceback and nothing written. (That a valid
override is accepted, and plans what it changes, is in tests/test_pipeline.py.)

Each case runs ``snakemake`` in a copy of the repository's tracked files, so
that it neither reads nor writes this checkout's ``results/`` and ``figures/``.
The tests marked ``slow`` build the whole pipeline (about 25 s each); the
default ``pytest`` skips them, ``pytest -m slow`` (run by .ci/run) runs them.
"""

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT, copy_tracked_files

SNAKEMAKE = shutil.which("snakemake") or str(Path(sys.executable).with_name("snakemake"))
#: What Snakemake itself prints whenever --config is given (not ours to change).
NOTICE = "Config file config/config.yaml is extended by additional config specified via the command line."
FIGURE_COUNT = 14

pytestmark = pytest.mark.skipif(not Path(SNAKEMAKE).exists(), reason="snakemake not installed")


def _snakemake(repo: Path, *args: str, timeout: int = 300) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k != "LUMPED_CONFIG"}
    return subprocess.run([SNAKEMAKE, *args], cwd=repo, capture_output=True, text=True, timeout=timeout, env=env)


def _made(repo: Path) -> list[str]:
    """Files in results/ and figures/ besides the tracked figures/README.md."""
    found = [p for d in ("results", "figures") for p in (repo / d).rglob("*") if p.is_file()]
    return sorted(str(p.relative_to(repo)) for p in found if p.name != "README.md")


@pytest.fixture(scope="module")
def repo(tmp_path_factory) -> Path:
    return copy_tracked_files(tmp_path_factory.mktemp("repo"))


def _assert_one_clean_line(done: subprocess.CompletedProcess, expected: str, notice: bool = True) -> None:
    output = done.stdout + done.stderr
    lines = [line for line in output.splitlines() if line.strip()]
    assert done.returncode == 2, output
    assert "Traceback" not in output and 'File "' not in output, output
    assert [line for line in lines if line.startswith("config:")] == [expected], output
    assert lines == ([NOTICE] if notice else []) + [expected], output


BAD = [
    (["dt=abc"], "config: dt must be a finite number > 0 (s); got 'abc'"),
    (["dtt=1e-3"], "config: unknown key dtt; did you mean dt?"),
    # Snakemake reads 1e400 as inf: without the --config texts this became Coulomb friction silently
    (["gamma=1e400"], "config: gamma=1e400 is beyond double precision (about 1.8e308); write .inf for infinity"),
    # accepted by the schema, refused by the run (its own check, before any job)
    (
        ["x0_large=1e300"],
        "config: x0_large: the run could reach spring force |F_s| = 1e+302 (bound from the energy), above the "
        "1e+300 that double precision carries through a step (the free_large run)",
    ),
]


@pytest.mark.parametrize(("overrides", "expected"), BAD, ids=[" ".join(c) for c, _ in BAD])
def test_bad_override_stops_before_any_job(repo, overrides, expected):
    done = _snakemake(repo, "--cores", "1", "--config", *overrides)
    _assert_one_clean_line(done, expected)
    assert _made(repo) == []
    assert not (repo / "logs").exists() and not (repo / "paper" / "build").exists()


def test_missing_key_in_the_config_file_is_named(tmp_path):
    repo = copy_tracked_files(tmp_path)
    config = repo / "config" / "config.yaml"
    text = config.read_text(encoding="utf-8")
    assert re.search(r"^dt:", text, flags=re.M)
    config.write_text(re.sub(r"^dt:.*\n", "", text, flags=re.M), encoding="utf-8")
    done = _snakemake(repo, "--cores", "1")
    _assert_one_clean_line(done, "config: dt is missing; it must be a finite number > 0 (s)", notice=False)
    assert _made(repo) == []


def _build(tmp_path: Path, *overrides: str) -> Path:
    repo = copy_tracked_files(tmp_path)
    args = ["--cores", "all"] + (["--config", *overrides] if overrides else [])
    done = _snakemake(repo, *args, timeout=600)
    assert done.returncode == 0, (done.stdout + done.stderr)[-3000:]
    _check_built(repo)
    return repo


def _check_built(repo: Path) -> None:
    figures = sorted((repo / "figures").glob("fig[0-9][0-9]_*.p*"))
    assert len(figures) == 2 * FIGURE_COUNT, figures
    assert (repo / "paper" / "paper.pdf").stat().st_size > 0


def _plans_nothing(repo: Path, *overrides: str) -> None:
    done = _snakemake(repo, "--dry-run", "--nolock", "--config", *overrides)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Nothing to be done" in done.stdout + done.stderr, done.stdout + done.stderr


def _built_default(tmp_path: Path) -> Path:
    """A tree after the default build: this checkout itself when its whole pipeline is up to date (as in
    .ci/run, whose main job has just built it), else a copy built here."""
    done = _snakemake(ROOT, "--dry-run", "--nolock")
    if done.returncode == 0 and "Nothing to be done" in done.stdout + done.stderr:
        _check_built(ROOT)
        return ROOT
    return _build(tmp_path)


@pytest.mark.slow
def test_default_build_then_override_equal_to_default_reruns_nothing(tmp_path):
    repo = _built_default(tmp_path)
    _plans_nothing(repo, "dt=0.0001")
    _plans_nothing(repo, "dt=1e-4", "mass=1")
    logs = sorted((repo / "logs" / "notebooks").glob("*.log"))
    # one log per notebook of the tutorial (was 5, a number that went stale when 06 to 08 came)
    assert [log.stem for log in logs] == sorted(p.stem for p in (ROOT / "notebooks").glob("[0-9][0-9]_*.py"))
    for log in logs:
        text = log.read_text(encoding="utf-8")
        assert "\x1b[" not in text and "without encryption" not in text, f"{log.name}: {text[:500]}"


@pytest.mark.slow
def test_executed_notebook_is_the_same_bytes_twice(tmp_path):
    """Cell ids are numbered and split streams joined, so two runs write the same file."""
    runner = ROOT / "scripts" / "run_notebook.py"
    notebook = ROOT / "notebooks" / "01_governing_equations.py"
    written = []
    for name in ("a.ipynb", "b.ipynb"):
        done = subprocess.run(
            [sys.executable, str(runner), str(notebook), "--output", str(tmp_path / name)],
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert done.returncode == 0 and done.stdout + done.stderr == "", done.stdout + done.stderr
        written.append((tmp_path / name).read_bytes())
    assert written[0] == written[1]
    cells = json.loads(written[0])["cells"]
    assert [c["id"] for c in cells] == [f"cell-{i}" for i in range(len(cells))]
