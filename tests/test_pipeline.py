"""The Snakemake pipeline: every paper figure has a producing job.

The checks run ``snakemake`` in dry-run mode (``--dry-run --forceall
--nolock``), which reads the Snakefile and plans the jobs without running or
writing anything; the override checks start from a copy of the repository in
which everything is up to date (``results/config.yaml`` built, the other
outputs empty files newer than it) and show what an override plans.
"""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import ROOT, copy_tracked_files

SNAKEMAKE = shutil.which("snakemake") or str(Path(sys.executable).with_name("snakemake"))
FIGURES = [f"{n:02d}" for n in range(1, 15)]
#: The tutorial's figures (notebooks 06 to 08), after the paper's fourteen.
EXTENSIONS = [f"{n:02d}" for n in range(1, 7)]

pytestmark = pytest.mark.skipif(not Path(SNAKEMAKE).exists(), reason="snakemake not installed")


def _snakemake(*args: str, check: bool = True, cwd: Path = ROOT) -> str:
    done = subprocess.run([SNAKEMAKE, "--nolock", *args], cwd=cwd, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 or not check, done.stdout + done.stderr
    return done.stdout + done.stderr


def _jobs(text: str) -> list[tuple[str, dict[str, str]]]:
    """The planned jobs of a dry run: (rule, its fields such as output and reason)."""
    jobs = []
    for block in re.split(r"\n(?=\[.*\]\n)|\n(?=(?:local)?rule \w+:)", text):
        rule = re.search(r"^(?:local)?rule (\w+):", block, re.M)
        if rule:
            jobs.append((rule.group(1), dict(re.findall(r"^[ \t]+(\w+): (.*)$", block, re.M))))
    return jobs


def _outputs_by_rule(text: str) -> dict[str, str]:
    """Map each planned output file to the rule of its job."""
    return {
        path.strip(): rule
        for rule, fields in _jobs(text)
        for path in fields.get("output", "").split(", ")
        if path.strip()
    }


def _reasons_by_rule(text: str) -> dict[str, str]:
    """Map each planned rule to the reason Snakemake gives for its job."""
    return {rule: fields["reason"] for rule, fields in _jobs(text) if "reason" in fields}


@pytest.fixture(scope="module")
def dry_run() -> dict[str, str]:
    return _outputs_by_rule(_snakemake("--dry-run", "--forceall"))


@pytest.mark.slow  # a snakemake or convergence run: the slow suite (.ci/run runs it)
@pytest.mark.parametrize("number", FIGURES)
@pytest.mark.parametrize("ext", ["pdf", "png"])
def test_every_paper_figure_has_a_job(dry_run, number, ext):
    made = {p: r for p, r in dry_run.items() if re.fullmatch(rf"figures/fig{number}_\w+\.{ext}", p)}
    assert len(made) == 1, f"figure {number} ({ext}): planned outputs {sorted(made)}"
    (rule,) = made.values()
    assert rule.startswith("notebook_"), f"figure {number} is made by rule {rule}"


@pytest.mark.slow  # a snakemake or convergence run: the slow suite (.ci/run runs it)
@pytest.mark.parametrize("number", EXTENSIONS)
@pytest.mark.parametrize("ext", ["pdf", "png"])
def test_every_tutorial_figure_has_a_job_and_stays_out_of_the_article(dry_run, number, ext):
    made = {p: r for p, r in dry_run.items() if re.fullmatch(rf"figures/ext{number}_\w+\.{ext}", p)}
    assert len(made) == 1, f"tutorial figure ext{number} ({ext}): planned outputs {sorted(made)}"
    (rule,) = made.values()
    assert rule in {"notebook_06", "notebook_07", "notebook_08"}, rule
    assert Path(ROOT, "report", f"ext{number}.rst").is_file()
    listed = Path(ROOT, "figures", "README.md").read_text(encoding="utf-8")
    assert f"`{Path(next(iter(made))).stem}`" in listed


@pytest.mark.slow  # a snakemake or convergence run: the slow suite (.ci/run runs it)
def test_the_article_embeds_only_the_paper_figures():
    text = _snakemake("--dry-run", "--forceall", "paper/paper.pdf")
    (inputs,) = [fields["input"] for rule, fields in _jobs(text) if rule == "paper"]
    figures = [p for p in inputs.split(", ") if p.startswith("figures/")]
    assert len(figures) == 14 and all(re.fullmatch(r"figures/fig\d\d_\w+\.pdf", p) for p in figures), figures


@pytest.mark.slow  # a snakemake or convergence run: the slow suite (.ci/run runs it)
def test_every_notebook_is_executed_and_figures_come_from_notebooks(dry_run):
    executed = {p for p in dry_run if p.startswith("results/notebooks/")}
    sources = sorted(Path(ROOT, "notebooks").glob("[0-9][0-9]_*.py"))
    assert executed == {f"results/notebooks/{p.stem}.ipynb" for p in sources}
    figure_jobs = {job for path, job in dry_run.items() if path.startswith("figures/")}
    # notebooks 01 and 02 derive and demonstrate; every later one draws figures
    assert figure_jobs == {f"notebook_{p.stem[:2]}" for p in sources if p.stem[:2] >= "03"}


@pytest.fixture(scope="module")
def up_to_date(tmp_path_factory, dry_run) -> Path:
    """A copy of the repository in which every output is up to date (no build).

    ``results/config.yaml`` is built for real (so Snakemake records the params
    it was made with); every other output of the plan is an empty file a
    second newer than it (outputs without provenance are judged by times).
    """
    repo = copy_tracked_files(tmp_path_factory.mktemp("repo"))
    _snakemake("--cores", "1", "results/config.yaml", cwd=repo)
    later = (repo / "results" / "config.yaml").stat().st_mtime + 1.0
    for path in dry_run:
        if path != "results/config.yaml":
            (repo / path).parent.mkdir(parents=True, exist_ok=True)
            (repo / path).touch()
            os.utime(repo / path, (later, later))
    return repo


#: Overrides that change the configuration: (--config arguments, line before, line after)
#: in the effective configuration.  gamma=.inf is YAML's infinity (Coulomb friction).
CHANGES = [(("dt=0.001",), "dt: 0.0001", "dt: 0.001"), (("gamma=.inf", "mass=1"), "gamma: 1.0", "gamma: .inf")]
#: --config overrides whose plans are checked: none, one equal to the default, the changes.
OVERRIDES = [(), ("dt=1e-4",), *(overrides for overrides, _, _ in CHANGES)]


@pytest.fixture(scope="module")
def plans(up_to_date) -> dict[tuple[str, ...], str]:
    """The dry-run plan of the whole workflow in ``up_to_date`` for each of OVERRIDES.

    The dry runs only read the tree, so they run side by side.
    """
    started = {}
    for overrides in OVERRIDES:
        args = ["--config", *overrides, "--"] if overrides else []
        started[overrides] = subprocess.Popen(
            [SNAKEMAKE, "--nolock", "--dry-run", *args],
            cwd=up_to_date,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
    texts = {}
    for overrides, run in started.items():
        out, err = run.communicate(timeout=120)
        assert run.returncode == 0, out + err
        texts[overrides] = out + err
    return texts


@pytest.mark.slow  # a snakemake or convergence run: the slow suite (.ci/run runs it)
@pytest.mark.parametrize("overrides", OVERRIDES[:2], ids=["none", "dt=1e-4"])
def test_nothing_is_planned_when_up_to_date_or_overridden_with_the_default(plans, overrides):
    """The baseline of the next test: an override equal to the default changes nothing."""
    text = plans[overrides]
    assert "Nothing to be done" in text and _reasons_by_rule(text) == {}, text[-2000:]


@pytest.mark.slow  # a snakemake or convergence run: the slow suite (.ci/run runs it)
@pytest.mark.parametrize(("overrides", "before", "after"), CHANGES, ids=[" ".join(c[0]) for c in CHANGES])
def test_config_override_reruns_the_config_and_every_notebook(plans, overrides, before, after):
    """From an up-to-date tree, an override that changes a value plans effective_config
    (its params changed) and every job downstream of results/config.yaml: each notebook
    (hence every figure), the article's numbers, the convergence figure drawn from
    them, and the article; not the work-precision study nor the studies (rest,
    Den Hartog), which run on the committed parameter file whatever the overrides."""
    reasons = _reasons_by_rule(plans[overrides])
    config = reasons.pop("effective_config", "")
    assert config.startswith("Params have changed"), reasons
    old, new = config.split(" now: ")
    assert f"{before}\\n" in old and f"{after}\\n" in new and f"{before}\\n" not in new, config
    notebooks = {f"notebook_{p.stem[:2]}" for p in Path(ROOT, "notebooks").glob("[0-9][0-9]_*.py")}
    downstream = {"paper_numbers", "paper_figures", "paper", "all"}
    assert set(reasons) == notebooks | downstream, sorted(reasons)
    for rule in sorted(notebooks | {"paper_numbers"}):
        assert reasons[rule] == "Input files updated by another job: results/config.yaml", rule


def test_every_rule_has_a_log():
    """``--lint`` exits 1 on its (waived) conda findings; a rule without log: must not be one."""
    lint = _snakemake("--lint", check=False)
    assert "Lints for rule" in lint or "no lints" in lint.lower() or lint.strip() == "", lint
    assert "log directive" not in lint.lower(), lint


#: Each study: its notebook, and its chunk counts (default, full) as the issue's pipeline should plan them.
STUDY_JOBS = {
    "rest": ("10_where_it_rests", 4, 16),
    "den_hartog": ("11_den_hartog", 2, 16),
    "stops": ("12_stops_per_cycle", 2, 16),
    "stops_low": ("12_stops_per_cycle", 2, 16),
}


@pytest.mark.slow  # a snakemake or convergence run: the slow suite (.ci/run runs it)
@pytest.mark.parametrize("studies", [None, "full"])
def test_every_study_is_chunk_jobs_merged_by_one_rule_and_read_by_its_notebook(studies):
    """One study_<name>_chunk job per chunk of the study module's CHUNKS, merged in order by study_<name>."""
    from lumped import studies as registry

    assert set(registry.STUDIES) == set(STUDY_JOBS)
    args = ["--config", f"studies={studies}", "--"] if studies else []
    targets = [f"results/notebooks/{notebook}.ipynb" for notebook, *_ in STUDY_JOBS.values()]
    jobs = _jobs(_snakemake("--dry-run", "--forceall", *args, *targets))
    for name, (notebook, default, full) in STUDY_JOBS.items():
        chunks = full if studies else default
        assert registry.study(name).CHUNKS[studies or "default"] == chunks
        parts = [f"results/studies/{name}/chunk-{i}.csv" for i in range(chunks)]
        assert sorted(f["output"] for rule, f in jobs if rule == f"study_{name}_chunk") == sorted(parts)
        (merge,) = [f for rule, f in jobs if rule == f"study_{name}"]
        assert merge["output"] == f"results/studies/{name}.csv"
        assert merge["input"].split(", ")[1:] == parts
        (reader,) = [f for rule, f in jobs if rule == f"notebook_{notebook[:2]}"]
        assert f"results/studies/{name}.csv" in reader["input"].split(", ")


def test_a_studies_value_other_than_default_or_full_stops_with_one_line():
    done = subprocess.run(
        [SNAKEMAKE, "--nolock", "--dry-run", "--config", "studies=fast"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 2, done.stdout + done.stderr
    lines = [ln for ln in done.stderr.splitlines() if ln.startswith("config:")]
    assert lines == [
        "config: studies must be default or full (the resolution of the studies in results/studies/); got 'fast'"
    ]
