"""The Snakemake pipeline: every paper figure has a producing job.

The checks run ``snakemake`` in dry-run mode (``--dry-run --forceall
--nolock``), which reads the Snakefile and plans the jobs without running or
writing anything.
"""

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SNAKEMAKE = shutil.which("snakemake") or str(Path(sys.executable).with_name("snakemake"))
FIGURES = [f"{n:02d}" for n in range(1, 15)]

pytestmark = pytest.mark.skipif(not Path(SNAKEMAKE).exists(), reason="snakemake not installed")


def _snakemake(*args: str, check: bool = True) -> str:
    done = subprocess.run(
        [SNAKEMAKE, "--nolock", *args], cwd=ROOT, capture_output=True, text=True, timeout=120
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


def test_config_override_reaches_the_notebooks():
    """``--config dt=...`` changes the effective config, so every notebook job is planned."""
    text = _snakemake("--dry-run", "--config", "dt=0.001")
    producer = _outputs_by_rule(text)
    assert producer.get("results/config.yaml") == "effective_config", text[-2000:]


def test_every_rule_has_a_log():
    """``--lint`` exits 1 on its (waived) conda findings; a rule without log: must not be one."""
    lint = _snakemake("--lint", check=False)
    assert "Lints for rule" in lint or "no lints" in lint.lower() or lint.strip() == "", lint
    assert "log directive" not in lint.lower(), lint
