"""The cluster path (issue 12, part 4): profiles/cluster and scripts/slurm_local.sh.

SLURM itself is not run here: scripts/slurm_local.sh does that on a machine
where it may install and start daemons (book/guide/cluster.md).  These tests
check what can be checked without it: the profile's values and the claims its
comments make, a dry run through the profile with the executor plugin (the
jobs are the study's chunks, with the profile's resources), and the script's
syntax and its refusal of a bad argument.
"""

import os
import re
import shutil
import subprocess

import pytest
import yaml
from conftest import ROOT
from test_pipeline import SNAKEMAKE, _jobs

from lumped.studies import rest

PROFILE = ROOT / "profiles" / "cluster" / "config.yaml"
SCRIPT = ROOT / "scripts" / "slurm_local.sh"


@pytest.fixture(scope="module")
def profile() -> dict:
    return yaml.safe_load(PROFILE.read_text())


def test_the_profile_submits_to_slurm_with_its_account_and_partition_from_the_environment(profile):
    assert profile["executor"] == "slurm"
    assert profile["default-resources"]["slurm_account"] == "$LUMPED_SLURM_ACCOUNT"
    assert profile["default-resources"]["slurm_partition"] == "$LUMPED_SLURM_PARTITION"
    # every job of the pipeline is one single-threaded process
    assert profile["default-resources"]["cpus_per_task"] == 1


def test_the_profiles_comment_on_jobs_is_the_full_studys_chunk_count(profile):
    """The comment says how many chunks studies=full makes; all of them fit in `jobs` at once."""
    (claimed,) = re.findall(r"\((\d+) chunks with studies=full\)", PROFILE.read_text())
    assert int(claimed) == rest.CHUNKS["full"] <= profile["jobs"]


def test_the_profiles_per_rule_resources_name_rules_of_the_workflow(profile):
    rules = set(re.findall(r"^rule (\w+):", "".join(p.read_text() for p in (ROOT / "rules").glob("*.smk")), re.M))
    assert set(profile["set-resources"]) <= rules, set(profile["set-resources"]) - rules


def test_a_dry_run_through_the_profile_plans_the_full_studys_chunks_with_the_profiles_resources():
    """With the executor plugin loaded (an unknown executor or option would stop the run)."""
    pytest.importorskip("snakemake_executor_plugin_slurm", reason="snakemake-executor-plugin-slurm is not installed")
    env = {**os.environ, "LUMPED_SLURM_ACCOUNT": "acct-test", "LUMPED_SLURM_PARTITION": "part-test"}
    args = ["--profile", str(PROFILE.parent), "--dry-run", "--forceall", "--config", "studies=full", "--"]
    done = subprocess.run(
        [SNAKEMAKE, "--nolock", *args, "results/studies/rest.csv"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    jobs = _jobs(done.stdout + done.stderr)
    chunks = sorted(f["output"] for rule, f in jobs if rule == "study_rest_chunk")
    assert chunks == sorted(f"results/studies/rest/chunk-{i}.csv" for i in range(rest.CHUNKS["full"]))
    assert [rule for rule, _ in jobs].count("study_rest") == 1 and len(jobs) == len(chunks) + 1
    for rule, fields in jobs:  # the environment's account and partition, the rule's runtime and memory
        resources = dict(item.split("=", 1) for item in fields["resources"].split(", "))
        assert resources["slurm_account"] == "acct-test" and resources["slurm_partition"] == "part-test"
        per_rule = {k: str(v) for k, v in yaml.safe_load(PROFILE.read_text())["set-resources"][rule].items()}
        assert {k: resources[k] for k in per_rule} == per_rule, rule


def test_the_script_parses_and_builds_what_the_workflow_names():
    """``bash -n`` reads it without a word; what it builds and compares is the rest study's merged output
    (the one output of rule ``study_rest``), the rules whose lines it prints are rules of the workflow, and
    its four daemons listen on four different unprivileged ports."""
    done = subprocess.run(["bash", "-n", str(SCRIPT)], capture_output=True, text=True, timeout=30)
    assert (done.returncode, done.stdout, done.stderr) == (0, "", "")
    text = SCRIPT.read_text()
    (targets,) = re.findall(r"^readonly TARGETS=\((.*)\)$", text, re.M)
    targets = re.findall(r'"([^"]+)"', targets)
    merged = []
    for smk, rule in (("studies", "study_rest"), ("sweeps", "sweep_system")):
        rules = (ROOT / "rules" / f"{smk}.smk").read_text()
        (outputs,) = re.findall(rf"^rule {rule}:.*?\n    output:\n(.*?)\n    log:", rules, re.M | re.S)
        merged += re.findall(r'"([^"]+)"', outputs)
        assert re.search(rf"^rule {rule}_chunk:", rules, re.M)  # the grep's {rule}[a-z_]* lines
        assert f"|{rule}[a-z_]*" in text
    assert targets == merged == ["results/studies/rest.csv", "results/sweeps/two_blocks.csv"]
    (ports,) = re.findall(r"^readonly (PORT_CTLD=.*)$", text, re.M)
    numbers = [int(p.split("=")[1]) for p in ports.split()]
    assert len(numbers) == len(set(numbers)) == 4 and all(1024 <= n < 65536 for n in numbers)


def test_the_script_passes_shellcheck():
    if shutil.which("shellcheck") is None:
        pytest.skip("shellcheck is not installed (Debian package shellcheck)")
    done = subprocess.run(["shellcheck", str(SCRIPT)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stdout


def test_the_script_refuses_an_argument_with_one_line_before_touching_anything():
    done = subprocess.run(["bash", str(SCRIPT), "--bogus"], capture_output=True, text=True, timeout=30)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.splitlines() == [
        "slurm_local: unknown argument '--bogus' (no arguments; --help says what it does)"
    ]


def test_the_scripts_help_is_its_header():
    done = subprocess.run(["bash", str(SCRIPT), "--help"], capture_output=True, text=True, timeout=30)
    assert done.returncode == 0 and "profiles/cluster" in done.stdout and "LUMPED_SLURM_KEEP" in done.stdout
    assert done.stdout.rstrip().endswith("CI does not run it."), "--help stops short of the header's last line"


def test_a_dry_run_through_the_profile_plans_the_system_sweeps_chunks_with_the_profiles_resources():
    """The network sweep of rules/sweeps.smk: one SLURM job per chunk (``sweep --chunk I/N``), then the merge."""
    pytest.importorskip("snakemake_executor_plugin_slurm", reason="snakemake-executor-plugin-slurm is not installed")
    env = {**os.environ, "LUMPED_SLURM_ACCOUNT": "acct-test", "LUMPED_SLURM_PARTITION": "part-test"}
    args = ["--profile", str(PROFILE.parent), "--dry-run", "--forceall", "--"]
    done = subprocess.run(
        [SNAKEMAKE, "--nolock", *args, "results/sweeps/two_blocks.csv"],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    jobs = _jobs(done.stdout + done.stderr)
    chunks = sorted(f["output"] for rule, f in jobs if rule == "sweep_system_chunk")
    assert chunks == sorted(f"results/sweeps/two_blocks/chunk-{i}.csv" for i in range(4))
    assert [rule for rule, _ in jobs].count("sweep_system") == 1 and len(jobs) == len(chunks) + 1
    per_rule = yaml.safe_load(PROFILE.read_text())["set-resources"]
    for rule, fields in jobs:
        resources = dict(item.split("=", 1) for item in fields["resources"].split(", "))
        assert resources["slurm_account"] == "acct-test" and resources["slurm_partition"] == "part-test"
        assert {k: resources[k] for k in per_rule[rule]} == {k: str(v) for k, v in per_rule[rule].items()}, rule
