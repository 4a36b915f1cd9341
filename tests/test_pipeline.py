"""The Snakemake pipeline: every paper figure has a producing job.

The checks run ``snakemake`` in dry-run mode (``--dry-run --forceall
--nolock``), which reads the Snakefile and plans the jobs without running or
writing anything; the override check builds ``results/config.yaml`` alone, in
a copy of the repository.
"""

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import copy_tracked_files

ROOT = Path(__file__).resolve().parent.parent
SNAKEMAKE = shutil.which("snakemake") or str(Path(sys.executable).with_name("snakemake"))
FIGURES = [f"{n:02d}" for n in range(1, 15)]

pytestmark = pytest.mark.skipif(not Path(SNAKEMAKE).exists(), reason="snakemake not installed")


def _snakemake(*args: str, check: bool = True, cwd: Path = ROOT) -> str:
    done = subprocess.run(
        [SNAKEMAKE, "--nolock", *args], cwd=cwd, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0 or not check, done.stdout + done.stderr
    return done.stdout + done.stderr


def _outputs_by_rule(text: str) -> dict[str, str]:
    """Map each planned output file to the rule of its job."""
    producer = {}
    for block in re.split(r"\n(?=\[.*\]\n)|\n(?=(?:local)?rule \w+:)", text):
        rule = re.search(r"^(?:local)?rule (\w+):", block, re.M)
        output = re.search(r"^\s+output: (.*)$", block, re.M)
        if rule and output:
            for path in output.group(1).split(", "):
                producer[path.strip()] = rule.group(1)
    return producer


@pytest.fixture(scope="module")
def dry_run() -> dict[str, str]:
    return _outputs_by_rule(_snakemake("--dry-run", "--forceall"))


@pytest.mark.parametrize("number", FIGURES)
@pytest.mark.parametrize("ext", ["pdf", "png"])
def test_every_paper_figure_has_a_job(dry_run, number, ext):
    made = {p: r for p, r in dry_run.items() if re.fullmatch(rf"figures/fig{number}_\w+\.{ext}", p)}
    assert len(made) == 1, f"figure {number} ({ext}): planned outputs {sorted(made)}"
    (rule,) = made.values()
    assert rule.startswith("notebook_"), f"figure {number} is made by rule {rule}"


def test_every_notebook_is_executed_and_figures_come_from_notebooks(dry_run):
    executed = {p for p in dry_run if p.startswith("results/notebooks/")}
    sources = sorted(Path(ROOT, "notebooks").glob("[0-9][0-9]_*.py"))
    assert executed == {f"results/notebooks/{p.stem}.ipynb" for p in sources}
    figure_jobs = {job for path, job in dry_run.items() if path.startswith("figures/")}
    assert figure_jobs == {"notebook_03", "notebook_04", "notebook_05"}


@pytest.fixture(scope="module")
def configured(tmp_path_factory) -> Path:
    """A copy of the repository in which only ``results/config.yaml`` is built (about 1 s)."""
    repo = copy_tracked_files(tmp_path_factory.mktemp("repo"))
    done = subprocess.run([SNAKEMAKE, "--nolock", "--cores", "1", "results/config.yaml"],
                          cwd=repo, capture_output=True, text=True, timeout=120)  # fmt: skip
    assert done.returncode == 0, done.stdout + done.stderr
    return repo


def _plan(repo: Path, *overrides: str) -> str:
    """The dry-run plan for ``results/config.yaml``, with ``--config`` overrides if any."""
    args = ["--config", *overrides, "--"] if overrides else []
    return _snakemake("--dry-run", *args, "results/config.yaml", cwd=repo)


def test_config_override_reruns_the_effective_config_for_its_params(configured):
    """With results/config.yaml up to date, only an override plans its job, for changed params."""
    assert "Nothing to be done" in _plan(configured)
    text = _plan(configured, "dt=0.001")
    assert _outputs_by_rule(text).get("results/config.yaml") == "effective_config", text[-2000:]
    reason = re.search(r"^\s+reason: (.*)$", text, re.M)
    assert reason and reason.group(1).startswith("Params have changed"), text[-2000:]
    assert "dt: 0.0001" in reason.group(1) and "dt: 0.001\\n" in reason.group(1)


def test_every_notebook_reads_the_effective_config():
    """So the override above reaches every notebook job (and hence every figure)."""
    text = _snakemake("--dry-run", "--forceall")
    jobs = re.findall(r"^(?:local)?rule (notebook_\w+):\n\s+input: (.*)$", text, re.M)
    assert len(jobs) == len(list(Path(ROOT, "notebooks").glob("[0-9][0-9]_*.py")))
    assert all("results/config.yaml" in inputs.split(", ") for _, inputs in jobs), jobs


def test_every_rule_has_a_log():
    """``--lint`` exits 1 on its (waived) conda findings; a rule without log: must not be one."""
    lint = _snakemake("--lint", check=False)
    assert "Lints for rule" in lint or "no lints" in lint.lower() or lint.strip() == "", lint
    assert "log directive" not in lint.lower(), lint
